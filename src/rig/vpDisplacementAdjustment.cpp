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

#include "rig/vpDisplacementAdjustment.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpGaussRand.h>
#include <visp3/projective/vpProjectiveDisplacement.h>

#include "core/vpProjection.h"
#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveNumerics.h"

namespace vpProjectiveInternal
{
namespace
{
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
} // namespace

void stackImagePairs(const std::vector<vpImagePoint> &left0, const std::vector<vpImagePoint> &right0,
                     const std::vector<vpImagePoint> &left1, const std::vector<vpImagePoint> &right1,
                     const std::string &where, std::vector<Eigen::Vector4d> &s0, std::vector<Eigen::Vector4d> &s1)
{
  const size_t n = left0.size();
  if (right0.size() != n || left1.size() != n || right1.size() != n) {
    std::ostringstream os;
    os << "the four image point lists must have the same size, got " << left0.size() << ", " << right0.size() << ", "
       << left1.size() << ", " << right1.size();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  s0.resize(n);
  s1.resize(n);
  for (size_t j = 0; j < n; ++j) {
    // Every pixel converted (and checked) before a comma initialiser starts, as in stackStereoImages().
    const Eigen::Vector2d l0 = toEigen(left0[j], where, "a left image point before the motion");
    const Eigen::Vector2d r0 = toEigen(right0[j], where, "a right image point before the motion");
    const Eigen::Vector2d l1 = toEigen(left1[j], where, "a left image point after the motion");
    const Eigen::Vector2d r1 = toEigen(right1[j], where, "a right image point after the motion");
    s0[j] << l0, r0;
    s1[j] << l1, r1;
  }
}

DisplacementData::DisplacementData(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                                   const std::vector<Eigen::Vector4d> &s1)
    : rig(&rig), s(s0.size()), M0(s0.size()), M1(s0.size()), X(s0.size()), Y(s0.size())
{
  for (size_t j = 0; j < s0.size(); ++j) {
    M0[j] = rig.triangulate(Eigen::Vector2d(s0[j].head<2>()), Eigen::Vector2d(s0[j].tail<2>()));
    M1[j] = rig.triangulate(Eigen::Vector2d(s1[j].head<2>()), Eigen::Vector2d(s1[j].tail<2>()));
    s[j] << s0[j], s1[j];
  }
  T0 = whitening(M0);
  T0inv = T0.inverse();
  T1 = whitening(M1);
  T1inv = T1.inverse();
  for (size_t j = 0; j < s0.size(); ++j) {
    X[j] = (T0 * M0[j]).normalized();
    Y[j] = (T1 * M1[j]).normalized();
  }
}

DisplacementAdjustment::DisplacementAdjustment(const DisplacementData &data) : m_data(data)
{
  vpProjectiveStereoRig::Projection P, Pp;
  data.rig->getLeftProjection(P);
  data.rig->getRightProjection(Pp);
  m_P0 = P * data.T0inv;
  m_Pp0 = Pp * data.T0inv;
  m_P1 = P * data.T1inv;
  m_Pp1 = Pp * data.T1inv;
}

bool DisplacementAdjustment::refine(const std::vector<bool> &flags, Eigen::Matrix4d &H,
                                    std::vector<Eigen::Vector4d> &points, int maxIterations, double tolerance) const
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

double DisplacementAdjustment::rigidityStatistic(const std::vector<bool> &flags, const Eigen::Matrix4d &H,
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

void DisplacementAdjustment::whiten(const std::vector<bool> &flags, const Eigen::Matrix4d &H,
                                    const std::vector<Eigen::Vector4d> &points, std::vector<size_t> &index,
                                    RowMajor4 &Hw, std::vector<Eigen::Vector4d> &X) const
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

bool DisplacementAdjustment::evaluate(const std::vector<size_t> &index, const RowMajor4 &Hw,
                                      const std::vector<Eigen::Vector4d> &X,
                                      std::vector<Eigen::Matrix<double, 8, 1>> &r,
                                      std::vector<Eigen::Matrix<double, 4, 16>> *A,
                                      std::vector<Eigen::Matrix<double, 8, 4>> *B, double &cost) const
{
  cost = 0.0;
  Eigen::Matrix<double, 2, 4> G; // d(u, v) / d(camera input)
  Eigen::Vector2d uv;
  for (size_t k = 0; k < index.size(); ++k) {
    const Eigen::Matrix<double, 8, 1> &s = m_data.s[index[k]];
    const Eigen::Vector4d Z = Hw * X[k];
    const vpProjectiveStereoRig::Projection *cameras[4] = {&m_P0, &m_Pp0, &m_P1, &m_Pp1};
    for (int c = 0; c < 4; ++c) { // cameras: left 0, right 0, left 1, right 1
      if (!projectPoint(*cameras[c], c < 2 ? X[k] : Z, uv, A && B ? &G : nullptr)) {
        return false;
      }
      r[k].segment<2>(2 * c) = uv - s.segment<2>(2 * c);
      if (A && B) {
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
} // namespace vpProjectiveInternal
