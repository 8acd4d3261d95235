/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 * Copyright (C) 2026 The visp_projective authors.
 *
 * This software is free software; you can redistribute it and/or modify it under the terms of the GNU General Public
 * License as published by the Free Software Foundation; either version 2 of the License, or (at your option) any
 * later version. See the file LICENSE at the root directory of this source distribution.
 *
 * This software is distributed in the hope that it will be useful, but WITHOUT ANY WARRANTY; without even the
 * implied warranty of MERCHANTABILITY or FITNESS FOR A PARTICULAR PURPOSE. See the GNU General Public License for
 * more details.
 */

#include <visp3/projective/vpProjectiveDisplacement.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveStereoRig.h>

#include "vpProjectiveCeres.h"
#include "vpProjectiveInternal.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
const char *const kClass = "vpProjectiveDisplacement";
// Largest rigidity statistic (DisplacementAdjustment::rigidityStatistic()) of a robust estimate.
const double kRigidityBound = 8.0;

// Pixel reprojection error of a rigid point M0 (unit 4-vector) seen before (M0) and after (H M0) the motion.
struct DisplacementReprojectionError {
  DisplacementReprojectionError(const vpProjectiveStereoRig::Projection &P, const vpProjectiveStereoRig::Projection &Pp,
                                const Eigen::Vector4d &s0, const Eigen::Vector4d &s1)
      : m_P(P), m_Pp(Pp), m_s0(s0), m_s1(s1)
  {
  }

  template <typename T> static void project(const Eigen::Matrix<double, 3, 4> &P, const T *X, T *uv)
  {
    T m[3];
    for (int r = 0; r < 3; ++r) {
      m[r] = T(P(r, 0)) * X[0] + T(P(r, 1)) * X[1] + T(P(r, 2)) * X[2] + T(P(r, 3)) * X[3];
    }
    uv[0] = m[0] / m[2];
    uv[1] = m[1] / m[2];
  }

  template <typename T> bool operator()(const T *const H, const T *const M0, T *residual) const
  {
    T M1[4];
    for (int r = 0; r < 4; ++r) {
      M1[r] = H[4 * r] * M0[0] + H[4 * r + 1] * M0[1] + H[4 * r + 2] * M0[2] + H[4 * r + 3] * M0[3];
    }
    T uv[2];
    const Eigen::Vector4d *obs[2] = {&m_s0, &m_s1};
    const T *points[2] = {M0, M1};
    for (int k = 0; k < 2; ++k) {
      project(m_P, points[k], uv);
      residual[4 * k] = uv[0] - T((*obs[k])(0));
      residual[4 * k + 1] = uv[1] - T((*obs[k])(1));
      project(m_Pp, points[k], uv);
      residual[4 * k + 2] = uv[0] - T((*obs[k])(2));
      residual[4 * k + 3] = uv[1] - T((*obs[k])(3));
    }
    return true;
  }

  Eigen::Matrix<double, 3, 4> m_P, m_Pp;
  Eigen::Vector4d m_s0, m_s1;
};

// Rejects point sets that cannot determine a homography of P^3: all coplanar, or 4 coplanar among a minimal 5.
void checkGeneralPosition(const std::vector<Eigen::Vector4d> &M, const std::string &where, const char *which)
{
  const size_t n = M.size();
  Eigen::Matrix<double, 4, Eigen::Dynamic> U(4, n);
  for (size_t j = 0; j < n; ++j) {
    const double norm = M[j].norm();
    if (norm == 0.0) {
      fail(vpProjectiveException::invalidValueError, where,
           std::string("a point of ") + which + " is the zero vector, which is no projective point");
    }
    U.col(static_cast<Eigen::Index>(j)) = M[j] / norm;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(U);
  if (svd.singularValues()(3) < 1e-10 * svd.singularValues()(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         std::string("the points of ") + which + " are coplanar; a 3D homography needs points spanning 3D space");
  }
  if (n == 5) {
    // Whitened first: the points of a small object are nearly parallel 4-vectors in the rig's frame, so an absolute
    // threshold on raw determinants would reject valid sets. Whitening preserves coplanarity.
    const Eigen::Matrix4d T = whitening(M);
    for (size_t skip = 0; skip < 5; ++skip) {
      Eigen::Matrix4d S;
      for (size_t j = 0, c = 0; j < 5; ++j) {
        if (j != skip) {
          S.col(static_cast<Eigen::Index>(c++)) = (T * U.col(static_cast<Eigen::Index>(j))).normalized();
        }
      }
      if (std::abs(S.determinant()) < 1e-9) {
        fail(vpProjectiveException::degenerateConfigurationError, where,
             std::string("4 of the 5 points of ") + which +
                 " are coplanar (or repeated); 5 points determine a 3D homography only if no 4 are coplanar");
      }
    }
  }
}

/*
  Maximum-likelihood refinement of H on the points \e index (Ceres): H on the unit sphere of R^16 (a gauge for its
  scale), the points M0 on the unit sphere of R^4, the pixel reprojection error of the four images. \e M0 holds the
  starting points of all n points (only those of \e index are used). Returns the normalised refined H, or the
  normalised start if the refinement fails or does not lower the cost.
*/
Eigen::Matrix4d refineFromImages(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                                 const std::vector<Eigen::Vector4d> &s1, const std::vector<size_t> &index,
                                 std::vector<Eigen::Vector4d> M0, const Eigen::Matrix4d &Hstart, int maxIterations)
{
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> H = Hstart / Hstart.norm();
  ceres::Problem problem;
  for (size_t j : index) {
    auto *cost = new ceres::AutoDiffCostFunction<DisplacementReprojectionError, 8, 16, 4>(
        new DisplacementReprojectionError(rig.leftProjection(), rig.rightProjection(), s0[j], s1[j]));
    problem.AddResidualBlock(cost, nullptr, H.data(), M0[j].data());
    problem.SetManifold(M0[j].data(), new ceres::SphereManifold<4>());
  }
  problem.SetManifold(H.data(), new ceres::SphereManifold<16>());
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_SCHUR, maxIterations);
  const Eigen::Matrix4d Hrefined = H;
  if (!Hrefined.allFinite() || summary.final_cost > summary.initial_cost) {
    return vpProjectiveDisplacement::normalize(Hstart);
  }
  return vpProjectiveDisplacement::normalize(Hrefined);
}

/*
  The homography of P^3 that maps 5 points X (unit, whitened) onto 5 points Y, in closed form: with
  X[0..3] diag(a) = A, a = [X0 X1 X2 X3]^-1 X4, A maps the standard frame (e_1..e_4, e_1 + .. + e_4) onto the X's, and
  likewise B onto the Y's, so Hw = B A^-1. Degenerate when 4 of the 5 points of either set are coplanar (or repeated):
  the determinant of the 4 others, a_i det[X0..X3] for the set without X_i, vanishes. Reversed when Hw reverses
  orientation: no displacement does (det H = det T > 0, eq. (11); the whitenings have positive determinants).
*/
enum MinimalResult { MinimalValid, MinimalDegenerate, MinimalReversed };

MinimalResult minimalHomography(const Eigen::Vector4d *const X[5], const Eigen::Vector4d *const Y[5],
                                Eigen::Matrix4d &Hw)
{
  const double eps = 1e-9; // as checkGeneralPosition(): |det| of 4 unit whitened points
  Eigen::Matrix4d A, B;
  for (int c = 0; c < 4; ++c) {
    A.col(c) = *X[c];
    B.col(c) = *Y[c];
  }
  const double detA = A.determinant(), detB = B.determinant();
  if (!(std::abs(detA) > eps) || !(std::abs(detB) > eps)) {
    return MinimalDegenerate;
  }
  const Eigen::Matrix4d Ainv = A.inverse();
  const Eigen::Vector4d a = Ainv * *X[4];
  const Eigen::Vector4d b = B.inverse() * *Y[4];
  for (int c = 0; c < 4; ++c) {
    if (!(std::abs(a(c) * detA) > eps) || !(std::abs(b(c) * detB) > eps)) {
      return MinimalDegenerate;
    }
  }
  // Hw = B diag(b) (A diag(a))^-1 = B diag(b ./ a) A^-1.
  Hw = B * b.cwiseQuotient(a).asDiagonal() * Ainv;
  if (!Hw.allFinite()) {
    return MinimalDegenerate;
  }
  return Hw.determinant() > 0.0 ? MinimalValid : MinimalReversed;
}

/*
  The gold-standard error of one rigid point under a candidate H (any scale): the four cameras P, P', P H, P' H
  stacked in Q (12x4) and their observations s = (s0, s1) (8 pixels). Writes the 8 residuals of M (unit) and their
  Jacobian (8x4); false if M is on a camera's focal plane.
*/
struct GoldStandardPoint {
  Eigen::Matrix<double, 12, 4> Q;
  Eigen::Vector4d rowScale; // |third row| of each camera, for the focal-plane test

  void setDisplacement(const vpProjectiveStereoRig::Projection &P, const vpProjectiveStereoRig::Projection &Pp,
                       const Eigen::Matrix4d &H)
  {
    const Eigen::Matrix4d Hs = H / H.norm();
    Q.block<3, 4>(0, 0) = P;
    Q.block<3, 4>(3, 0) = Pp;
    Q.block<3, 4>(6, 0) = P * Hs;
    Q.block<3, 4>(9, 0) = Pp * Hs;
    for (int k = 0; k < 4; ++k) {
      rowScale(k) = Q.row(3 * k + 2).norm();
    }
  }

  bool residuals(const Eigen::Matrix<double, 8, 1> &s, const Eigen::Vector4d &M, Eigen::Matrix<double, 8, 1> &r,
                 Eigen::Matrix<double, 8, 4> &J) const
  {
    const Eigen::Matrix<double, 12, 1> m = Q * M;
    for (int k = 0; k < 4; ++k) {
      const double w = m(3 * k + 2);
      if (!(std::abs(w) > 1e-12 * rowScale(k))) {
        return false;
      }
      const double iw = 1.0 / w, u = m(3 * k) * iw, v = m(3 * k + 1) * iw;
      r(2 * k) = u - s(2 * k);
      r(2 * k + 1) = v - s(2 * k + 1);
      J.row(2 * k) = iw * (Q.row(3 * k) - u * Q.row(3 * k + 2));
      J.row(2 * k + 1) = iw * (Q.row(3 * k + 1) - v * Q.row(3 * k + 2));
    }
    return r.allFinite();
  }

  /*
    min over M of the squared residual, by at most two Gauss-Newton steps on the unit sphere from \e M (updated): an
    upper bound of the minimum, reached to first order for a correct point. Infinity if M has no image.
  */
  double squaredError(const Eigen::Matrix<double, 8, 1> &s, Eigen::Vector4d &M) const
  {
    Eigen::Matrix<double, 8, 1> r;
    Eigen::Matrix<double, 8, 4> J;
    if (!residuals(s, M, r, J)) {
      return std::numeric_limits<double>::infinity();
    }
    double cost = r.squaredNorm();
    for (int iteration = 0; iteration < 2; ++iteration) {
      // J M = 0 (a projection ignores the scale of M): the term M M^T fixes the step orthogonal to M.
      Eigen::Matrix4d N = J.transpose() * J;
      const double scale = N.trace();
      if (!(scale > 0.0)) {
        break;
      }
      N += (0.25 * scale) * M * M.transpose();
      const Eigen::Vector4d delta = N.llt().solve(-J.transpose() * r);
      const Eigen::Vector4d Mnew = (M + delta).normalized();
      Eigen::Matrix<double, 8, 1> rNew;
      Eigen::Matrix<double, 8, 4> JNew;
      if (!Mnew.allFinite() || !residuals(s, Mnew, rNew, JNew)) {
        break;
      }
      const double costNew = rNew.squaredNorm();
      if (!(costNew < cost)) {
        break;
      }
      const bool converged = cost - costNew <= 1e-6 * cost;
      M = Mnew;
      r = rNew;
      J = JNew;
      cost = costNew;
      if (converged) {
        break;
      }
    }
    return cost;
  }

  /*
    Cheirality of a point M under H: a point in front of both cameras stays so after a rigid motion, and with H = lambda
    H_PE^-1 T H_PE the depths (P M)_3 and (P H M)_3 (likewise with P') have the sign of lambda for every point, whatever
    the scale and sign of M. Returns that sign (+1 or -1), or 0 if the two cameras disagree.
  */
  int cheirality(const Eigen::Vector4d &M) const
  {
    const double left = Q.row(2).dot(M) * Q.row(8).dot(M), right = Q.row(5).dot(M) * Q.row(11).dot(M);
    if (left > 0.0 && right > 0.0) {
      return 1;
    }
    return left < 0.0 && right < 0.0 ? -1 : 0;
  }
};

/*
  The robust estimator's view of the data: the stacked pixels s_j = (s0_j, s1_j), the triangulated points M0_j, M1_j
  and their whitened unit versions X_j = T0 M0_j, Y_j = T1 M1_j (T0, T1 the whitenings of all the points).
*/
struct RobustData {
  const vpProjectiveStereoRig *rig;
  std::vector<Eigen::Matrix<double, 8, 1>> s;
  std::vector<Eigen::Vector4d> M0, M1, X, Y;
  Eigen::Matrix4d T0, T0inv, T1, T1inv;

  size_t size() const { return s.size(); }
  //! H in the rig's frame of a homography Hw between the whitened points.
  Eigen::Matrix4d unwhiten(const Eigen::Matrix4d &Hw) const { return T1inv * Hw * T0; }
};

//! The squared errors d_j^2 of every point under H (mean over the four images, see the header) and, optionally, the
//! best-fitting points.
void pointErrors(const RobustData &data, const Eigen::Matrix4d &H, std::vector<double> &d2,
                 std::vector<Eigen::Vector4d> *points = nullptr)
{
  GoldStandardPoint gold;
  gold.setDisplacement(data.rig->leftProjection(), data.rig->rightProjection(), H);
  d2.resize(data.size());
  std::vector<int> side(data.size());
  int votes = 0;
  for (size_t j = 0; j < data.size(); ++j) {
    Eigen::Vector4d M = data.M0[j];
    d2[j] = 0.25 * gold.squaredError(data.s[j], M);
    side[j] = gold.cheirality(M);
    votes += std::isfinite(d2[j]) ? side[j] : 0;
    if (points) {
      (*points)[j] = M;
    }
  }
  // A point on the other side of the cameras than most (it reached its images through infinity) does not move with H.
  const int sign = votes < 0 ? -1 : 1;
  for (size_t j = 0; j < data.size(); ++j) {
    if (side[j] != sign) {
      d2[j] = std::numeric_limits<double>::infinity();
    }
  }
}

//! Truncated quadratic cost sum_j min(d_j^2, t^2) (MSAC) and the support #{d_j <= t}.
struct RobustScore {
  double cost = std::numeric_limits<double>::infinity();
  size_t support = 0;
};

RobustScore msac(const std::vector<double> &d2, double threshold)
{
  const double t2 = threshold * threshold;
  RobustScore score;
  score.cost = 0.0;
  for (double e : d2) {
    score.cost += std::min(e, t2);
    score.support += e <= t2 ? 1 : 0;
  }
  return score;
}

std::vector<bool> within(const std::vector<double> &d2, double threshold)
{
  std::vector<bool> flags(d2.size());
  for (size_t j = 0; j < d2.size(); ++j) {
    flags[j] = d2[j] <= threshold * threshold;
  }
  return flags;
}

/*
  Rigidity residual of a homography G: the characteristic polynomial of a rigid displacement normalised by (12) is
  (x - 1)^2 (x^2 - 2 cos(theta) x + 1) for every rotation, screw or translation, so its coefficients e_k (elementary
  symmetric functions of the eigenvalues, by Newton's identities from the traces of G, G^2, G^3) satisfy e3 = e1 and
  e2 = 2 e1 - 2. Returns (e1 - e3, e2 - 2 e1 + 2), a smooth function of G, invariant to its scale and to conjugation;
  false if det G <= 0 (no displacement of P^3 reverses orientation).
*/
bool rigidityResidual(const Eigen::Matrix4d &G, Eigen::Vector2d &c)
{
  const Eigen::Matrix4d Gs = G / G.norm();
  const double det = Gs.determinant();
  if (!(det > 0.0)) {
    return false;
  }
  const Eigen::Matrix4d H = Gs / ((Gs.trace() < 0.0 ? -1.0 : 1.0) * std::pow(det, 0.25));
  const Eigen::Matrix4d H2 = H * H;
  const double p1 = H.trace(), p2 = H2.trace(), p3 = (H2 * H).trace();
  const double e1 = p1, e2 = 0.5 * (e1 * p1 - p2), e3 = (e2 * p1 - e1 * p2 + p3) / 3.0;
  c << e1 - e3, e2 - 2.0 * e1 + 2.0;
  return c.allFinite();
}

/*
  The maximum-likelihood refit of estimateFromImages() (the same cost: the pixel error of the four images over H and
  the points), solved by a dedicated Levenberg-Marquardt with the points eliminated by the Schur complement: the
  robust estimator refits a few times per call and the robot's acquisition calls it a dozen times, where a generic
  solver's set-up costs more than the solve. It works in the whitened frames (view 0: X = T0 M, view 1: T1 H M, so
  Hw = T1 H T0^-1), where H and the points are well conditioned; each of Hw (16 entries) and the points X (4) lives on
  its unit sphere, the scale gauge being removed by a term along the current value (the residuals do not depend on
  it: J h = 0, J X = 0).
*/
class DisplacementAdjustment
{
public:
  typedef Eigen::Matrix<double, 4, 4, Eigen::RowMajor> RowMajor4;

  explicit DisplacementAdjustment(const RobustData &data) : m_data(data)
  {
    const vpProjectiveStereoRig &rig = *data.rig;
    m_Q0.topRows<3>() = rig.leftProjection() * data.T0inv;
    m_Q0.bottomRows<3>() = rig.rightProjection() * data.T0inv;
    m_Q1.topRows<3>() = rig.leftProjection() * data.T1inv;
    m_Q1.bottomRows<3>() = rig.rightProjection() * data.T1inv;
  }

  /*
    Refines H (rig frame, any scale; returned normalised by (12)) and points[j] (rig frame, unit) on the flagged
    points, until an accepted step lowers the cost by less than \e tolerance times it, or after \e maxIterations.
    Returns false, leaving H and the points unchanged, if no step lowered the cost, a point left the image, or the
    result is singular or reverses orientation (no displacement).
  */
  bool refine(const std::vector<bool> &flags, Eigen::Matrix4d &H, std::vector<Eigen::Vector4d> &points,
              int maxIterations, double tolerance = 1e-12) const
  {
    std::vector<size_t> index;
    RowMajor4 Hw;
    std::vector<Eigen::Vector4d> X;
    whiten(flags, H, points, index, Hw, X);
    const size_t m = index.size();
    std::vector<Eigen::Vector4d> Xnew(m);
    std::vector<Eigen::Matrix<double, 8, 1>> r(m);
    std::vector<Eigen::Matrix<double, 4, 16>> A(m);
    std::vector<Eigen::Matrix<double, 8, 4>> B(m);
    double cost = 0.0;
    if (!evaluate(index, Hw, X, r, &A, &B, cost)) {
      return false;
    }
    const double initialCost = cost;
    std::vector<Eigen::Matrix4d> V(m), Vinv(m);
    std::vector<Eigen::Matrix<double, 16, 4>> W(m), WVinv(m);
    std::vector<Eigen::Vector4d> gX(m);
    std::vector<Eigen::Matrix<double, 8, 1>> rNew(m);
    double lambda = 1e-4;
    bool improved = false;
    for (int iteration = 0; iteration < maxIterations; ++iteration) {
      // Normal equations [U W; W^T V] [dh; dX] = -[gh; gX], V block diagonal.
      Eigen::Matrix<double, 16, 16> U = Eigen::Matrix<double, 16, 16>::Zero();
      Eigen::Matrix<double, 16, 1> gh = Eigen::Matrix<double, 16, 1>::Zero();
      for (size_t k = 0; k < m; ++k) {
        U.noalias() += A[k].transpose().lazyProduct(A[k]);
        gh.noalias() += A[k].transpose() * r[k].tail<4>();
        V[k].noalias() = B[k].transpose() * B[k];
        W[k].noalias() = A[k].transpose().lazyProduct(B[k].bottomRows<4>());
        gX[k].noalias() = B[k].transpose() * r[k];
      }
      const Eigen::Map<const Eigen::Matrix<double, 16, 1>> h(Hw.data());
      const double gaugeH = std::max(U.trace() / 16.0, 1e-300);
      bool accepted = false;
      // A step that does not lower the cost is retried with 10 times more damping, at most 6 times: at the minimum,
      // further tries only spend time.
      for (int attempt = 0; attempt < 6 && !accepted; ++attempt) {
        Eigen::Matrix<double, 16, 16> S = U;
        S.diagonal() *= 1.0 + lambda;
        S.noalias() += gaugeH * h * h.transpose();
        Eigen::Matrix<double, 16, 1> rhs = -gh;
        for (size_t k = 0; k < m; ++k) {
          Eigen::Matrix4d Vd = V[k];
          const double gaugeX = std::max(Vd.trace() / 4.0, 1e-300);
          Vd.diagonal() *= 1.0 + lambda;
          Vd.noalias() += gaugeX * X[k] * X[k].transpose();
          Vinv[k] = Vd.inverse();
          WVinv[k].noalias() = W[k].lazyProduct(Vinv[k]);
          S.noalias() -= WVinv[k].lazyProduct(W[k].transpose());
          rhs.noalias() += WVinv[k] * gX[k];
        }
        const Eigen::Matrix<double, 16, 1> dh = S.ldlt().solve(rhs);
        RowMajor4 HwNew = Hw;
        Eigen::Map<Eigen::Matrix<double, 16, 1>>(HwNew.data()) += dh;
        HwNew /= HwNew.norm();
        for (size_t k = 0; k < m; ++k) {
          const Eigen::Vector4d dX = -Vinv[k] * (gX[k] + W[k].transpose() * dh);
          Xnew[k] = (X[k] + dX).normalized();
        }
        double costNew = 0.0;
        if (dh.allFinite() && HwNew.allFinite() && evaluate(index, HwNew, Xnew, rNew, nullptr, nullptr, costNew) &&
            costNew < cost) {
          const bool converged = cost - costNew <= tolerance * cost;
          Hw = HwNew;
          X.swap(Xnew);
          cost = costNew;
          evaluate(index, Hw, X, r, &A, &B, cost);
          lambda = std::max(lambda / 10.0, 1e-12);
          accepted = true;
          improved = true;
          if (converged) {
            iteration = maxIterations;
          }
        } else {
          lambda *= 10.0;
        }
      }
      if (!accepted) {
        break; // no step lowers the cost: at the minimum to working precision
      }
    }
    const Eigen::Matrix4d Hrefined = m_data.T1inv * Hw * m_data.T0;
    // A mismatched set can drive H towards a singular matrix (the points squeezed onto a plane): no displacement.
    // Tested in the whitened frame, where a displacement's singular values are all of order 1.
    const Eigen::Vector4d sigma = Eigen::JacobiSVD<Eigen::Matrix4d>(Eigen::Matrix4d(Hw)).singularValues();
    if (!improved || !(cost <= initialCost) || !Hrefined.allFinite() || !(sigma(3) > 1e-8 * sigma(0)) ||
        !(Hw.determinant() > 0.0)) {
      return false;
    }
    H = vpProjectiveDisplacement::normalize(Hrefined);
    for (size_t k = 0; k < m; ++k) {
      points[index[k]] = (m_data.T0inv * X[k]).normalized();
    }
    return true;
  }

  /*
    Rigidity statistic of H fitted to the flagged points at their fitted positions \e points: max_k |c_k| / s_k, c
    the rigidity residual of H (rigidityResidual()) and s_k the RMS change of c_k over draws of H from its covariance
    sigma^2 S^-1 (S the Schur complement of the normal equations at the fit, in the whitened frame; sigma the RMS
    residual per coordinate over 5 m - 15 degrees of freedom for m points, at least \e sigmaFloor). Measured on the
    correct data of the tests (275 fits of 7 to 30 points): median 0.6, largest 3.3, and no rejection at the bound 8
    over 1600 correct 7-marker motions of every kind; homographies that absorbed mismatches: 16 and more, or det H <= 0
    (infinity). 0 when the noise alone leaves H undetermined (no rejection).
  */
  double rigidityStatistic(const std::vector<bool> &flags, const Eigen::Matrix4d &H,
                           const std::vector<Eigen::Vector4d> &points, double sigmaFloor) const
  {
    std::vector<size_t> index;
    RowMajor4 Hw;
    std::vector<Eigen::Vector4d> X;
    whiten(flags, H, points, index, Hw, X);
    const size_t m = index.size();
    std::vector<Eigen::Matrix<double, 8, 1>> r(m);
    std::vector<Eigen::Matrix<double, 4, 16>> A(m);
    std::vector<Eigen::Matrix<double, 8, 4>> B(m);
    double cost = 0.0;
    // c is computed on T0 H T0^-1 = (T0 T1^-1) Hw: conjugate to H (same characteristic polynomial), well scaled.
    const Eigen::Matrix4d K = m_data.T0 * m_data.T1inv;
    Eigen::Vector2d c;
    if (m < 5 || !evaluate(index, Hw, X, r, &A, &B, cost) || !rigidityResidual(K * Hw, c)) {
      return std::numeric_limits<double>::infinity();
    }
    const double sigma2 = std::max(cost / std::max(1.0, 5.0 * static_cast<double>(m) - 15.0), sigmaFloor * sigmaFloor);
    // Schur complement of the undamped normal equations, with the scale gauges.
    Eigen::Matrix<double, 16, 16> S = Eigen::Matrix<double, 16, 16>::Zero();
    for (size_t k = 0; k < m; ++k) {
      S.noalias() += A[k].transpose() * A[k];
    }
    const Eigen::Map<const Eigen::Matrix<double, 16, 1>> h(Hw.data());
    S.noalias() += std::max(S.trace() / 16.0, 1e-300) * h * h.transpose();
    for (size_t k = 0; k < m; ++k) {
      Eigen::Matrix4d V = B[k].transpose() * B[k];
      V.noalias() += std::max(V.trace() / 4.0, 1e-300) * X[k] * X[k].transpose();
      const Eigen::Matrix<double, 16, 4> W = A[k].transpose() * B[k].bottomRows<4>();
      S.noalias() -= W * V.inverse() * W.transpose();
    }
    // The spread of c under the noise: c is smooth but its gradient vanishes at some motions (c is of second order
    // in the noise at a translation, and one combination of its two entries is at a rotation), so it is sampled, not
    // linearised: 32 draws Hw + dHw, dHw ~ N(0, sigma^2 S^-1), from a fixed seed.
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix<double, 16, 16>> eig(S);
    if (eig.info() != Eigen::Success || !(eig.eigenvalues()(0) > 0.0)) {
      return 0.0; // no covariance: undecided
    }
    const Eigen::Matrix<double, 16, 16> L =
        eig.eigenvectors() * (std::sqrt(sigma2) * eig.eigenvalues().cwiseSqrt().cwiseInverse()).asDiagonal();
    vpGaussRand normal(1.0, 0.0, 0x5eed);
    Eigen::Vector2d spread = Eigen::Vector2d::Zero();
    int draws = 0;
    for (int draw = 0; draw < 32; ++draw) {
      Eigen::Matrix<double, 16, 1> z;
      for (int k = 0; k < 16; ++k) {
        z(k) = normal();
      }
      RowMajor4 Hd = Hw;
      Eigen::Map<Eigen::Matrix<double, 16, 1>>(Hd.data()) += L * z;
      Eigen::Vector2d cd;
      if (rigidityResidual(K * Hd, cd)) {
        spread += (cd - c).cwiseAbs2();
        ++draws;
      }
    }
    if (draws < 16) {
      return 0.0; // the noise alone may make H no displacement: the data cannot tell, nothing is rejected
    }
    spread = (spread / draws).cwiseSqrt();
    double z = 0.0;
    for (int k = 0; k < 2; ++k) {
      z = std::max(z, spread(k) > 0.0 ? std::abs(c(k)) / spread(k)
                                      : (c(k) == 0.0 ? 0.0 : std::numeric_limits<double>::infinity()));
    }
    return z;
  }

private:
  /*
    The flagged points' indices, and H (rig frame) and their points in the whitened frames, each on its unit sphere:
    Hw = T1 H T0^-1, X = T0 M.
  */
  void whiten(const std::vector<bool> &flags, const Eigen::Matrix4d &H, const std::vector<Eigen::Vector4d> &points,
              std::vector<size_t> &index, RowMajor4 &Hw, std::vector<Eigen::Vector4d> &X) const
  {
    index.clear();
    for (size_t j = 0; j < flags.size(); ++j) {
      if (flags[j]) {
        index.push_back(j);
      }
    }
    Hw = m_data.T1 * H * m_data.T0inv;
    Hw /= Hw.norm();
    X.resize(index.size());
    for (size_t k = 0; k < index.size(); ++k) {
      X[k] = (m_data.T0 * points[index[k]]).normalized();
    }
  }

  /*
    Residuals r (8 pixels) of the flagged points and, if asked, their Jacobians: A (4x16, view-1 rows, with respect to
    the row-major entries of Hw) and B (8x4, with respect to X). False if a point is on a camera's focal plane.
  */
  bool evaluate(const std::vector<size_t> &index, const RowMajor4 &Hw, const std::vector<Eigen::Vector4d> &X,
                std::vector<Eigen::Matrix<double, 8, 1>> &r, std::vector<Eigen::Matrix<double, 4, 16>> *A,
                std::vector<Eigen::Matrix<double, 8, 4>> *B, double &cost) const
  {
    cost = 0.0;
    for (size_t k = 0; k < index.size(); ++k) {
      const Eigen::Matrix<double, 8, 1> &s = m_data.s[index[k]];
      const Eigen::Vector4d Z = Hw * X[k];
      const Eigen::Matrix<double, 6, 1> m0 = m_Q0 * X[k], m1 = m_Q1 * Z;
      for (int c = 0; c < 4; ++c) { // cameras: left 0, right 0, left 1, right 1
        const Eigen::Matrix<double, 6, 4> &Q = c < 2 ? m_Q0 : m_Q1;
        const Eigen::Matrix<double, 6, 1> &mc = c < 2 ? m0 : m1;
        const int o = 3 * (c % 2);
        const double w = mc(o + 2);
        if (!(std::abs(w) > 1e-12 * Q.row(o + 2).norm() * (c < 2 ? 1.0 : Hw.norm()))) {
          return false;
        }
        const double u = mc(o) / w, v = mc(o + 1) / w;
        r[k](2 * c) = u - s(2 * c);
        r[k](2 * c + 1) = v - s(2 * c + 1);
        if (A && B) {
          Eigen::Matrix<double, 2, 4> G; // d(u, v) / d(camera input)
          G.row(0) = (Q.row(o) - u * Q.row(o + 2)) / w;
          G.row(1) = (Q.row(o + 1) - v * Q.row(o + 2)) / w;
          if (c < 2) {
            (*B)[k].block<2, 4>(2 * c, 0) = G;
          } else {
            (*B)[k].block<2, 4>(2 * c, 0) = G * Hw;
            for (int i = 0; i < 2; ++i) {
              for (int row = 0; row < 4; ++row) { // d(Hw X)_row / dHw(row, col) = X(col)
                (*A)[k].block<1, 4>(2 * (c - 2) + i, 4 * row) = G(i, row) * X[k].transpose();
              }
            }
          }
        }
      }
      cost += r[k].squaredNorm();
    }
    return std::isfinite(cost);
  }

  const RobustData &m_data;
  Eigen::Matrix<double, 6, 4> m_Q0, m_Q1;
};

/*
  Local optimisation of a hypothesis (LO-RANSAC, Chum, Matas and Kittler 2003): a 5-point hypothesis predicts the
  other points far less accurately than a fit on all of its inliers (an exact fit amplifies the noise), so it is
  refitted by maximum likelihood on the points \e rough, then on those within \e threshold of that fit, until the
  inliers are stable; a fit that is no rigid displacement (rigidityStatistic()) ends it. Returns the best fit by the
  MSAC cost at \e threshold (or the hypothesis itself) with its errors and best-fitting points, and in \e fitted the
  points it was fitted to (empty for the hypothesis itself).
*/
RobustScore localOptimisation(const RobustData &data, const DisplacementAdjustment &adjustment, double threshold,
                              const std::vector<bool> &rough, Eigen::Matrix4d &H, std::vector<double> &d2,
                              std::vector<Eigen::Vector4d> &points, std::vector<bool> &fitted)
{
  RobustScore best = msac(d2, threshold);
  fitted.clear();
  std::vector<bool> flags = rough;
  Eigen::Matrix4d Hcurrent = H;
  std::vector<Eigen::Vector4d> current = points;
  for (int round = 0; round < 3 && std::count(flags.begin(), flags.end(), true) >= 5; ++round) {
    if (!adjustment.refine(flags, Hcurrent, current, 15, 1e-6)) {
      break;
    }
    std::vector<double> e2;
    pointErrors(data, Hcurrent, e2, &current);
    const RobustScore score = msac(e2, threshold);
    if (score.cost < best.cost) {
      if (!(adjustment.rigidityStatistic(flags, Hcurrent, current, 0.1 * threshold) <= kRigidityBound)) {
        break; // a homography that absorbed mismatches, not a displacement
      }
      best = score;
      H = Hcurrent;
      d2 = e2;
      points = current;
      fitted = flags;
    }
    const std::vector<bool> next = within(e2, threshold);
    if (next == flags) {
      break;
    }
    flags = next;
  }
  return best;
}

//! Adds to \e flags the points of smallest finite error until at least \e count are flagged.
void nearestFirst(const std::vector<double> &d2, size_t count, std::vector<bool> &flags)
{
  std::vector<size_t> order(d2.size());
  for (size_t j = 0; j < order.size(); ++j) {
    order[j] = j;
  }
  std::sort(order.begin(), order.end(), [&d2](size_t a, size_t b) { return d2[a] < d2[b]; });
  size_t flagged = static_cast<size_t>(std::count(flags.begin(), flags.end(), true));
  for (size_t k = 0; k < order.size() && flagged < count && std::isfinite(d2[order[k]]); ++k) {
    if (!flags[order[k]]) {
      flags[order[k]] = true;
      ++flagged;
    }
  }
}

// C(n, k), saturated at cap + 1.
size_t binomialCapped(size_t n, size_t k, size_t cap)
{
  double c = 1.0;
  for (size_t i = 0; i < k; ++i) {
    c = c * static_cast<double>(n - i) / static_cast<double>(i + 1);
  }
  return c > static_cast<double>(cap) ? cap + 1 : static_cast<size_t>(std::llround(c));
}

std::vector<Eigen::Vector4d> toEigenPoints(const std::vector<vpColVector> &M, const std::string &where,
                                           const char *which)
{
  std::vector<Eigen::Vector4d> E(M.size());
  for (size_t j = 0; j < M.size(); ++j) {
    E[j] = toEigen<4>(M[j], where, std::string("a point of ") + which);
  }
  return E;
}
} // namespace

vpProjectiveDisplacement::vpProjectiveDisplacement() : m_H(Eigen::Matrix4d::Identity()) {}

vpProjectiveDisplacement::vpProjectiveDisplacement(const vpMatrix &H)
    : m_H(normalize(toEigen<4, 4>(H, std::string(kClass) + "()", "H")))
{
}

vpProjectiveDisplacement::vpProjectiveDisplacement(const Eigen::Matrix4d &H) : m_H(normalize(H)) {}

Eigen::Matrix4d vpProjectiveDisplacement::normalize(const Eigen::Matrix4d &H)
{
  const std::string where = std::string(kClass) + "::normalize()";
  if (!H.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, where, "H has a NaN or infinite entry");
  }
  const double scale = H.norm();
  if (scale == 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "H is the zero matrix");
  }
  const Eigen::Matrix4d Hs = H / scale; // avoids overflow of det for large entries
  // Singular when the condition number is beyond working precision. Not a threshold on det(H / |H|): in the rig's
  // pixel-scaled frame a valid H = H_PE^-1 T H_PE has singular values spread over 5 orders of magnitude or more, so
  // that det(H / |H|), the product of three small ratios, may be 1e-15 for a matrix that is far from singular.
  const Eigen::Vector4d sigma = Eigen::JacobiSVD<Eigen::Matrix4d>(Hs).singularValues();
  const double det = Hs.determinant();
  if (!(sigma(3) > 1e-13 * sigma(0)) || det == 0.0) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "H is singular; a projective displacement is an invertible 4x4 homography");
  }
  const double trace = Hs.trace();
  const double gamma = (trace < 0.0 ? -1.0 : 1.0) * std::pow(std::abs(det), 0.25);
  return Hs / gamma;
}

Eigen::Matrix4d vpProjectiveDisplacement::estimateLinear(const std::vector<Eigen::Vector4d> &M0,
                                                         const std::vector<Eigen::Vector4d> &M1)
{
  const std::string where = std::string(kClass) + "::estimate()";
  if (M0.size() != M1.size()) {
    std::ostringstream os;
    os << "got " << M0.size() << " points before the motion but " << M1.size() << " after; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (M0.size() < 5) {
    std::ostringstream os;
    os << "needs at least 5 point pairs to estimate a 3D homography (15 degrees of freedom), got " << M0.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  for (size_t j = 0; j < M0.size(); ++j) {
    if (!M0[j].allFinite() || !M1[j].allFinite()) {
      fail(vpProjectiveException::nonFiniteValueError, where, "a point has a NaN or infinite coordinate");
    }
  }
  checkGeneralPosition(M0, where, "the first set");
  checkGeneralPosition(M1, where, "the second set");

  // DLT on whitened points: Y ~ H' X with X = T0 M0, Y = T1 M1, then H = T1^-1 H' T0.
  const Eigen::Matrix4d T0 = whitening(M0);
  const Eigen::Matrix4d T1 = whitening(M1);
  const size_t n = M0.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * static_cast<Eigen::Index>(n), 16);
  static const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (size_t j = 0; j < n; ++j) {
    const Eigen::Vector4d X = (T0 * M0[j]).normalized();
    const Eigen::Vector4d Y = (T1 * M1[j]).normalized();
    for (int p = 0; p < 6; ++p) {
      const int a = pairs[p][0], b = pairs[p][1];
      const Eigen::Index row = 6 * static_cast<Eigen::Index>(j) + p;
      // Y_a (H X)_b - Y_b (H X)_a = 0
      for (int c = 0; c < 4; ++c) {
        A(row, 4 * b + c) += Y(a) * X(c);
        A(row, 4 * a + c) -= Y(b) * X(c);
      }
    }
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  if (sigma(14) < 1e-9 * sigma(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the point pairs do not determine a unique 3D homography (critical configuration); add points in general "
         "position");
  }
  const Eigen::VectorXd h = svd.matrixV().col(15);
  Eigen::Matrix4d Hw;
  for (int r = 0; r < 4; ++r) {
    Hw.row(r) = h.segment<4>(4 * r).transpose();
  }
  return normalize(T1.inverse() * Hw * T0);
}

vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const std::vector<vpColVector> &M0,
                                                            const std::vector<vpColVector> &M1)
{
  const std::string where = std::string(kClass) + "::estimate()";
  return vpProjectiveDisplacement(
      estimateLinear(toEigenPoints(M0, where, "the first set"), toEigenPoints(M1, where, "the second set")));
}

vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const vpProjectiveStereoRig &rig,
                                                            const std::vector<vpImagePoint> &left0,
                                                            const std::vector<vpImagePoint> &right0,
                                                            const std::vector<vpImagePoint> &left1,
                                                            const std::vector<vpImagePoint> &right1)
{
  const std::string where = std::string(kClass) + "::estimate()";
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where,
         "the stereo rig has no fundamental matrix; estimate it or set it before estimating displacements");
  }
  const size_t n = left0.size();
  if (right0.size() != n || left1.size() != n || right1.size() != n) {
    std::ostringstream os;
    os << "the four image point lists must have the same size, got " << left0.size() << ", " << right0.size() << ", "
       << left1.size() << ", " << right1.size();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (n < 5) {
    std::ostringstream os;
    os << "needs at least 5 points seen before and after the motion, got " << n;
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  std::vector<Eigen::Vector4d> s0(n), s1(n);
  for (size_t j = 0; j < n; ++j) {
    s0[j] << toEigen(left0[j], where, "a left image point before the motion"),
        toEigen(right0[j], where, "a right image point before the motion");
    s1[j] << toEigen(left1[j], where, "a left image point after the motion"),
        toEigen(right1[j], where, "a right image point after the motion");
  }
  return vpProjectiveDisplacement(estimateFromImages(rig, s0, s1));
}

Eigen::Matrix4d vpProjectiveDisplacement::estimateFromImages(const vpProjectiveStereoRig &rig,
                                                             const std::vector<Eigen::Vector4d> &s0,
                                                             const std::vector<Eigen::Vector4d> &s1, int maxIterations)
{
  const size_t n = s0.size();
  std::vector<Eigen::Vector4d> M0(n), M1(n);
  for (size_t j = 0; j < n; ++j) {
    M0[j] = rig.triangulate(Eigen::Vector2d(s0[j].head<2>()), Eigen::Vector2d(s0[j].tail<2>()));
    M1[j] = rig.triangulate(Eigen::Vector2d(s1[j].head<2>()), Eigen::Vector2d(s1[j].tail<2>()));
  }
  const Eigen::Matrix4d Hlin = estimateLinear(M0, M1);
  std::vector<size_t> all(n);
  for (size_t j = 0; j < n; ++j) {
    all[j] = j;
  }
  return refineFromImages(rig, s0, s1, all, M0, Hlin, maxIterations);
}

vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const vpProjectiveStereoRig &rig,
                                                            const std::vector<vpImagePoint> &left0,
                                                            const std::vector<vpImagePoint> &right0,
                                                            const std::vector<vpImagePoint> &left1,
                                                            const std::vector<vpImagePoint> &right1,
                                                            double inlierThreshold, std::vector<bool> &inliers)
{
  const std::string where = std::string(kClass) + "::estimate()";
  const size_t n = left0.size();
  if (right0.size() != n || left1.size() != n || right1.size() != n) {
    std::ostringstream os;
    os << "the four image point lists must have the same size, got " << left0.size() << ", " << right0.size() << ", "
       << left1.size() << ", " << right1.size();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  std::vector<Eigen::Vector4d> s0(n), s1(n);
  for (size_t j = 0; j < n; ++j) {
    s0[j] << toEigen(left0[j], where, "a left image point before the motion"),
        toEigen(right0[j], where, "a right image point before the motion");
    s1[j] << toEigen(left1[j], where, "a left image point after the motion"),
        toEigen(right1[j], where, "a right image point after the motion");
  }
  return vpProjectiveDisplacement(estimateRobust(rig, s0, s1, inlierThreshold, inliers));
}

Eigen::Matrix4d vpProjectiveDisplacement::estimateRobust(const vpProjectiveStereoRig &rig,
                                                         const std::vector<Eigen::Vector4d> &s0,
                                                         const std::vector<Eigen::Vector4d> &s1, double inlierThreshold,
                                                         std::vector<bool> &inliers, int maxIterations)
{
  const std::string where = std::string(kClass) + "::estimateRobust()";
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where,
         "the stereo rig has no fundamental matrix; estimate it or set it before estimating displacements");
  }
  const size_t n = s0.size();
  if (s1.size() != n) {
    std::ostringstream os;
    os << "got " << n << " points before the motion but " << s1.size() << " after; pass the same points in the same "
       << "order";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (n < 5) {
    std::ostringstream os;
    os << "needs at least 5 points seen before and after the motion, got " << n;
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  for (size_t j = 0; j < n; ++j) {
    if (!s0[j].allFinite() || !s1[j].allFinite()) {
      fail(vpProjectiveException::nonFiniteValueError, where, "an image point is not finite (NaN or infinity)");
    }
  }
  requireFinite(inlierThreshold, where, "the inlier threshold");
  if (!(inlierThreshold > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where,
         "the inlier threshold must be positive (pixels, e.g. 3 times the image noise)");
  }
  if (maxIterations < 1) {
    fail(vpProjectiveException::invalidValueError, where, "maxIterations (the number of 5-point sets) must be >= 1");
  }

  // Projective points, and the whitened unit points the minimal solver works on.
  RobustData data;
  data.rig = &rig;
  data.s.resize(n);
  data.M0.resize(n);
  data.M1.resize(n);
  data.X.resize(n);
  data.Y.resize(n);
  for (size_t j = 0; j < n; ++j) {
    data.M0[j] = rig.triangulate(Eigen::Vector2d(s0[j].head<2>()), Eigen::Vector2d(s0[j].tail<2>()));
    data.M1[j] = rig.triangulate(Eigen::Vector2d(s1[j].head<2>()), Eigen::Vector2d(s1[j].tail<2>()));
    data.s[j] << s0[j], s1[j];
  }
  data.T0 = whitening(data.M0);
  data.T0inv = data.T0.inverse();
  data.T1 = whitening(data.M1);
  data.T1inv = data.T1.inverse();
  for (size_t j = 0; j < n; ++j) {
    data.X[j] = (data.T0 * data.M0[j]).normalized();
    data.Y[j] = (data.T1 * data.M1[j]).normalized();
  }
  const DisplacementAdjustment adjustment(data);

  // Hypotheses from minimal sets: all of them in lexicographic order when they are few, else seeded random draws
  // with adaptive stopping. A hypothesis that more points roughly agree with (within the loose threshold) than the
  // best so far agree with precisely is locally optimised.
  const double loose = 4.0 * inlierThreshold;
  const size_t budget = static_cast<size_t>(maxIterations);
  const bool enumerate = binomialCapped(n, 5, budget) <= budget;
  vpUniRand rng(0x5eedULL);
  size_t subset[5] = {0, 1, 2, 3, 4};
  size_t needed = budget;
  Eigen::Matrix4d best = Eigen::Matrix4d::Zero();
  std::vector<double> bestErrors;
  std::vector<Eigen::Vector4d> bestPoints, points(n);
  std::vector<bool> bestFitted, fitted;
  std::vector<std::vector<bool>> tried; // the rough inlier sets already locally optimised
  struct Rival {
    std::vector<bool> inliers;
    double cost; // MSAC cost
  };
  std::vector<Rival> rivals; // the rigid fits found by the local optimisation
  const size_t required = n >= 6 ? 6 : 5;
  RobustScore bestScore;
  bool found = false, reversed = false;
  for (size_t iteration = 0; iteration < needed; ++iteration) {
    if (enumerate) {
      if (iteration > 0) { // next 5-combination of {0..n-1}
        int k = 4;
        while (k >= 0 && subset[k] == n - 5 + static_cast<size_t>(k)) {
          --k;
        }
        if (k < 0) {
          break;
        }
        ++subset[k];
        for (int l = k + 1; l < 5; ++l) {
          subset[l] = subset[l - 1] + 1;
        }
      }
    } else {
      for (int k = 0; k < 5; ++k) {
        do {
          subset[k] = static_cast<size_t>(rng.uniform(0, static_cast<int>(n)));
        } while (std::find(subset, subset + k, subset[k]) != subset + k);
      }
    }
    const Eigen::Vector4d *x[5], *y[5];
    for (int k = 0; k < 5; ++k) {
      x[k] = &data.X[subset[k]];
      y[k] = &data.Y[subset[k]];
    }
    Eigen::Matrix4d Hw;
    const MinimalResult minimal = minimalHomography(x, y, Hw);
    if (minimal != MinimalValid) {
      reversed = reversed || minimal == MinimalReversed;
      continue; // 4 coplanar (or repeated) points among the 5 in one view, or no displacement
    }
    Eigen::Matrix4d H = data.unwhiten(Hw);
    std::vector<double> d2;
    pointErrors(data, H, d2, &points);
    RobustScore score = msac(d2, inlierThreshold);
    fitted.clear();
    // The points to refit on: those within the loose threshold, and at least the `required` best predicted (with few
    // points a 5-point fit may predict every other one far beyond it).
    std::vector<bool> rough = within(d2, loose);
    nearestFirst(d2, required, rough);
    const size_t roughSupport = static_cast<size_t>(std::count(rough.begin(), rough.end(), true));
    if (n > 5 && roughSupport >= bestScore.support) {
      // Skip rough sets already optimised, and those within the inliers of the best fit (nothing to gain).
      bool news = !found;
      for (size_t j = 0; j < n && !news; ++j) {
        news = rough[j] && !(bestErrors[j] <= inlierThreshold * inlierThreshold);
      }
      if (news && std::find(tried.begin(), tried.end(), rough) == tried.end()) {
        tried.push_back(rough);
        score = localOptimisation(data, adjustment, inlierThreshold, rough, H, d2, points, fitted);
        if (!fitted.empty()) {
          rivals.push_back(Rival{within(d2, inlierThreshold), score.cost});
        }
      }
    }
    if (score.cost < bestScore.cost) {
      bestScore = score;
      best = H;
      bestErrors = d2;
      bestPoints = points;
      bestFitted = fitted;
      found = true;
      if (!enumerate) {
        // Draws needed to pick a set of inliers only with probability 0.9999, at the best inlier ratio so far.
        const double clean = std::pow(static_cast<double>(score.support) / static_cast<double>(n), 5.0);
        if (clean >= 1.0) {
          needed = iteration + 1;
        } else if (clean > 0.0) {
          const double draws = std::ceil(std::log(1e-4) / std::log1p(-clean));
          needed = std::min(budget, std::max(iteration + 1, static_cast<size_t>(std::min(draws, 1e9))));
        }
      }
    }
  }
  if (!found && reversed) {
    std::ostringstream os;
    os << "no 5 of the " << n << " points move by one rigid displacement (the homography of every 5 of them reverses "
       << "orientation): too many correspondences are mismatched; check the point tracking or add points";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }
  if (!found) {
    std::ostringstream os;
    os << "no 5 of the " << n << " points are in general position (every set of 5 has 4 coplanar or repeated points "
       << "in one view); a 3D homography needs points spanning 3D space";
    fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
  }

  // Too few points agree with every hypothesis: one more local optimisation, from all the points.
  if (bestScore.support < required) {
    const RobustScore score = localOptimisation(data, adjustment, inlierThreshold, std::vector<bool>(n, true), best,
                                                bestErrors, bestPoints, fitted);
    if (!fitted.empty()) {
      bestScore = score;
      bestFitted = fitted;
    }
  }

  // Another rigid fit supported by as many points, but other ones: both sets cannot be right. If their union is
  // consistent, it is the answer (two correct points near the threshold). Otherwise the better fit wins if it is
  // 1000 times more likely (its MSAC cost, in squared pixels per image point, is lower by 2 ln(1000) sigma^2 / 4,
  // sigma = t / 3 the noise the threshold is meant for); else the data are ambiguous.
  std::vector<bool> bestFlags = within(bestErrors, inlierThreshold);
  const double sigma2 = inlierThreshold * inlierThreshold / 9.0;
  for (const Rival &rival : rivals) {
    if (std::count(rival.inliers.begin(), rival.inliers.end(), true) <
            static_cast<long>(std::max(bestScore.support, required)) ||
        rival.inliers == bestFlags || 4.0 * (rival.cost - bestScore.cost) >= 2.0 * std::log(1000.0) * sigma2) {
      continue;
    }
    std::vector<bool> both(n);
    for (size_t j = 0; j < n; ++j) {
      both[j] = rival.inliers[j] || bestFlags[j];
    }
    Eigen::Matrix4d H = best;
    std::vector<double> d2 = bestErrors;
    std::vector<Eigen::Vector4d> fittedPoints = bestPoints;
    const RobustScore score = localOptimisation(data, adjustment, inlierThreshold, both, H, d2, fittedPoints, fitted);
    const std::vector<bool> flagsBoth = within(d2, inlierThreshold);
    bool covers = !fitted.empty();
    for (size_t j = 0; j < n && covers; ++j) {
      covers = !both[j] || flagsBoth[j];
    }
    if (!covers) {
      std::ostringstream os;
      os << "two different sets of " << bestScore.support << " of the " << n << " points each agree with a rigid "
         << "displacement within " << inlierThreshold << " px, and not with one another: the mismatched points "
         << "cannot be told from the others; check the point tracking or add points";
      fail(vpProjectiveException::estimationFailedError, where, os.str());
    }
    bestScore = score;
    best = H;
    bestErrors = d2;
    bestPoints = fittedPoints;
    bestFitted = fitted;
    bestFlags = flagsBoth;
  }

  // Maximum-likelihood refit on the inliers, from their best-fitting points, until the inliers are stable (the
  // local optimisation has usually done it, with a capped number of iterations: this converges it).
  Eigen::Matrix4d H = best;
  std::vector<bool> flags = within(bestErrors, inlierThreshold);
  points = bestPoints;
  for (int round = 0; round < 3 && (round == 0 || flags != bestFitted) && bestScore.support >= 5; ++round) {
    if (!adjustment.refine(flags, H, points, 100)) {
      break;
    }
    bestFitted = flags;
    std::vector<double> d2;
    pointErrors(data, H, d2, &points);
    flags = within(d2, inlierThreshold);
  }

  // Any 5 points fit a homography: a sixth must confirm it (when there is one).
  const size_t support = static_cast<size_t>(std::count(flags.begin(), flags.end(), true));
  if (support < required) {
    std::ostringstream os;
    os << "only " << support << " of the " << n << " points agree with one rigid displacement within "
       << inlierThreshold << " px (" << required << " needed: any 5 points are fitted exactly by a 3D homography, so a "
       << "sixth must confirm it); too many correspondences are mismatched: check the point tracking, add points, or "
       << "raise the threshold in proportion to the image noise";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }
  // A homography may fit a mismatched set within the threshold by distorting space (few points leave it the freedom):
  // then it is no rigid displacement.
  const double rigidity = adjustment.rigidityStatistic(bestFitted, H, points, 0.1 * inlierThreshold);
  if (!(rigidity <= kRigidityBound)) {
    std::ostringstream os;
    os << "the " << support << " of " << n << " points that agree within " << inlierThreshold << " px are fitted by a "
       << "homography that is no rigid displacement (its characteristic polynomial differs from that of a rotation, "
       << "(x - 1)^2 (x^2 - 2 x cos(theta) + 1), by " << rigidity << " times its noise, more than " << kRigidityBound
       << "), so some of them are mismatched; check the point tracking or add points";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }
  inliers = flags;
  return normalize(H);
}

vpMatrix vpProjectiveDisplacement::getMatrix() const
{
  return toVisp(m_H);
}

double vpProjectiveDisplacement::getRotationAngle() const
{
  const double c = 0.5 * (m_H.trace() - 2.0);
  return std::acos(std::max(-1.0, std::min(1.0, c)));
}

vpProjectiveDisplacement::vpMotionType vpProjectiveDisplacement::classify(double tolerance) const
{
  const Eigen::Matrix4d D = m_H - Eigen::Matrix4d::Identity();
  if (D.norm() <= tolerance * m_H.norm()) {
    return IDENTITY;
  }
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(D);
  const Eigen::Vector4d sigma = svd.singularValues();
  int rank = 0;
  for (int k = 0; k < 4; ++k) {
    rank += sigma(k) > tolerance * sigma(0) ? 1 : 0;
  }
  if (rank == 1) {
    return TRANSLATION;
  }
  if (rank == 2) {
    return ROTATION;
  }
  return GENERAL;
}

vpProjectiveDisplacement vpProjectiveDisplacement::operator*(const vpProjectiveDisplacement &other) const
{
  return vpProjectiveDisplacement(Eigen::Matrix4d(m_H * other.m_H));
}

vpProjectiveDisplacement vpProjectiveDisplacement::inverse() const
{
  return vpProjectiveDisplacement(Eigen::Matrix4d(m_H.inverse()));
}
