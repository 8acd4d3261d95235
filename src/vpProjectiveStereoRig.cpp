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

#include <visp3/projective/vpProjectiveStereoRig.h>

#include <visp3/projective/vpMetricTwist.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "vpCostFunctors.h"
#include "vpProjectiveCeres.h"
#include "vpProjection.h"
#include "vpProjectiveInternal.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveStereoRig");

Eigen::Vector2d dehomogenize(const Eigen::Vector3d &m)
{
  return m.head<2>() / m(2);
}

// Normalised 8-point estimate on the rows \e inliers of the design matrix A, with rank 2 enforced.
Eigen::Matrix3d linearFundamental(const Eigen::MatrixXd &A, const std::vector<size_t> &inliers)
{
  Eigen::MatrixXd Ain(inliers.size(), 9);
  for (size_t k = 0; k < inliers.size(); ++k) {
    Ain.row(static_cast<Eigen::Index>(k)) = A.row(static_cast<Eigen::Index>(inliers[k]));
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Ain, Eigen::ComputeFullV);
  Eigen::Matrix3d F;
  for (int a = 0; a < 3; ++a) {
    F.row(a) = svd.matrixV().col(8).segment<3>(3 * a).transpose();
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svdF(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svdF.matrixU() * Eigen::Vector3d(svdF.singularValues()(0), svdF.singularValues()(1), 0.0).asDiagonal() *
         svdF.matrixV().transpose();
}

// Larger of the distances (pixels) of m' to the epipolar line F m and of m to F^T m'.
double epipolarDistance(const Eigen::Matrix3d &F, const Eigen::Vector2d &m, const Eigen::Vector2d &mp)
{
  const Eigen::Vector3d lp = F * m.homogeneous();
  const Eigen::Vector3d l = F.transpose() * mp.homogeneous();
  const double algebraic = std::abs(mp.homogeneous().dot(lp));
  return std::max(algebraic / lp.head<2>().norm(), algebraic / l.head<2>().norm());
}

/*
  The matches within \e threshold pixels of their epipolar lines under the pixel F (epipolarDistance()), and the
  truncated quadratic cost sum_i min(d_i^2, t^2) over all matches (MSAC).
*/
double consensus(const Eigen::Matrix3d &F, const std::vector<Eigen::Vector2d> &l, const std::vector<Eigen::Vector2d> &r,
                 double threshold, std::vector<size_t> &inliers)
{
  inliers.clear();
  double cost = 0.0;
  for (size_t i = 0; i < l.size(); ++i) {
    const double d = epipolarDistance(F, l[i], r[i]);
    if (d <= threshold) {
      inliers.push_back(i);
      cost += d * d;
    } else {
      cost += threshold * threshold;
    }
  }
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

// Canonical camera pair of a unit, canonically signed F: P' = [[e']_x F + e' e'^T | e'].
vpProjectiveStereoRig::Projection canonicalRightProjection(const Eigen::Matrix3d &F, const Eigen::Vector3d &ep)
{
  vpProjectiveStereoRig::Projection Pp;
  Pp.leftCols<3>() = vpMetricTwist::skew(ep) * F + ep * ep.transpose();
  Pp.col(3) = ep;
  return Pp;
}

/*
  The right singular vector v4 of As for its smallest singular value, without an SVD (the control loop triangulates at
  every iteration): v4 is the dominant eigenvector of W = (As^T As)^-1 = V diag(1 / sigma_i^2) V^T, separated from the
  next one by (sigma_4 / sigma_3)^2, which is tiny for a stereo pair (sigma_4 measures its epipolar error), so power
  iteration from W's largest column reaches machine precision in one to three steps. False (the caller then takes
  the SVD) if As is singular to working precision or the iteration does not settle, which happens only when
  sigma_3 ~ sigma_4, i.e. when the pair does not determine a point.
*/
bool smallestSingularVector(const Eigen::Matrix4d &As, Eigen::Vector4d &x)
{
  const Eigen::Matrix4d Asinv = As.inverse();
  if (!Asinv.allFinite()) {
    return false;
  }
  const Eigen::Matrix4d W = Asinv * Asinv.transpose();
  Eigen::Index k = 0;
  W.diagonal().maxCoeff(&k);
  x = W.col(k);
  const double xNorm = x.norm();
  if (!(xNorm > 0.0) || !std::isfinite(xNorm)) {
    return false;
  }
  x /= xNorm;
  for (int iteration = 0; iteration < 8; ++iteration) {
    Eigen::Vector4d y = W * x;
    y /= y.norm();
    const double change = (y - x).squaredNorm();
    x = y;
    if (change <= 1e-28) { // |y - x| <= 1e-14: the remaining error is (sigma_4 / sigma_3)^2 times smaller
      return x.allFinite();
    }
  }
  return false;
}

// Linear triangulation on column-equilibrated equations (no coordinate of M is divided by).
Eigen::Vector4d linearTriangulation(const vpProjectiveStereoRig::Projection &P,
                                    const vpProjectiveStereoRig::Projection &Pp, const Eigen::Vector2d &m,
                                    const Eigen::Vector2d &mp)
{
  Eigen::Matrix4d A;
  A.row(0) = m(0) * P.row(2) - P.row(0);
  A.row(1) = m(1) * P.row(2) - P.row(1);
  A.row(2) = mp(0) * Pp.row(2) - Pp.row(0);
  A.row(3) = mp(1) * Pp.row(2) - Pp.row(1);
  for (int i = 0; i < 4; ++i) {
    const double n = A.row(i).norm();
    if (n > 0.0) {
      A.row(i) /= n;
    }
  }
  Eigen::Vector4d colScale;
  for (int j = 0; j < 4; ++j) {
    const double n = A.col(j).norm();
    colScale(j) = n > 0.0 ? 1.0 / n : 1.0;
  }
  const Eigen::Matrix4d As = A * colScale.asDiagonal();
  Eigen::Vector4d x;
  if (!smallestSingularVector(As, x)) {
    Eigen::JacobiSVD<Eigen::Matrix4d> svd(As, Eigen::ComputeFullV);
    x = svd.matrixV().col(3);
  }
  const Eigen::Vector4d M = colScale.asDiagonal() * x;
  return M.normalized();
}

/*
  Gold-standard F of the matches \e index: in Hartley-normalised coordinates (T, Tp), P = [I|0] fixed, P' (scale
  fixed on the unit sphere; the remaining 3-dof gauge P' + e' a^T is left to Levenberg-Marquardt's damping) and the
  points free, from the normalised rank-2 \e Fn0; Ceres minimises the reprojection error of the matches, weighted back
  to pixels. Returns the pixel F, or that of Fn0 if the refinement fails.
*/
Eigen::Matrix3d goldStandardFundamental(const std::vector<Eigen::Vector2d> &l, const std::vector<Eigen::Vector2d> &r,
                                        const Eigen::Matrix3d &T, const Eigen::Matrix3d &Tp,
                                        const std::vector<size_t> &index, const Eigen::Matrix3d &Fn0)
{
  Eigen::JacobiSVD<Eigen::Matrix3d> svdF(Fn0, Eigen::ComputeFullU);
  const Eigen::Vector3d epn = svdF.matrixU().col(2);
  const vpProjectiveStereoRig::Projection Ppn = canonicalRightProjection(Fn0 / Fn0.norm(), epn);
  vpProjectiveStereoRig::Projection Pn = vpProjectiveStereoRig::Projection::Zero();
  Pn.leftCols<3>().setIdentity();

  Eigen::Matrix<double, 3, 4, Eigen::RowMajor> PpRowMajor = Ppn / Ppn.norm();
  std::vector<Eigen::Vector4d> points(index.size());
  ceres::Problem problem;
  for (size_t k = 0; k < index.size(); ++k) {
    const size_t i = index[k];
    const Eigen::Vector2d mn = dehomogenize(T * l[i].homogeneous());
    const Eigen::Vector2d mpn = dehomogenize(Tp * r[i].homogeneous());
    points[k] = linearTriangulation(Pn, Ppn, mn, mpn);
    auto *cost = new ceres::AutoDiffCostFunction<StereoReprojectionError, 4, 12, 4>(
        new StereoReprojectionError(mn, mpn, T(0, 0), Tp(0, 0)));
    problem.AddResidualBlock(cost, nullptr, PpRowMajor.data(), points[k].data());
    problem.SetManifold(points[k].data(), new ceres::SphereManifold<4>());
  }
  problem.SetManifold(PpRowMajor.data(), new ceres::SphereManifold<12>());
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_SCHUR, 100);

  const vpProjectiveStereoRig::Projection PpRefined = PpRowMajor;
  const Eigen::Vector3d epRefined = PpRefined.col(3);
  const Eigen::Matrix3d Fn = vpMetricTwist::skew(epRefined) * PpRefined.leftCols<3>();
  const Eigen::Matrix3d F = Tp.transpose() * Fn * T;
  if (!F.allFinite() || F.norm() == 0.0 || summary.final_cost > summary.initial_cost) {
    return Tp.transpose() * Fn0 * T; // the refinement failed: keep the start
  }
  return F;
}
} // namespace

vpProjectiveStereoRig::vpProjectiveStereoRig()
    : m_F(Eigen::Matrix3d::Zero()), m_P(Projection::Zero()), m_Pp(Projection::Zero()), m_e(Eigen::Vector3d::Zero()),
      m_ep(Eigen::Vector3d::Zero()), m_inliers(), m_residual(0.0), m_initialized(false), m_canonical(true)
{
}

void vpProjectiveStereoRig::checkInitialized(const char *where) const
{
  if (!m_initialized) {
    fail(vpProjectiveException::notInitializedError, at("") + where,
         "the rig has no fundamental matrix yet; call estimate() with >= 8 matches or setFundamentalMatrix() first");
  }
}

void vpProjectiveStereoRig::setFundamentalMatrix(const vpMatrix &F)
{
  const std::string where = at("setFundamentalMatrix()");
  const Eigen::Matrix3d Fin = toEigen<3, 3>(F, where, "F");
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(Fin, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector3d sigma = svd.singularValues();
  if (!(sigma(0) > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where, "F is the zero matrix");
  }
  if (sigma(1) < 1e-12 * sigma(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "F has rank 1; a fundamental matrix has rank 2 (check the matches it was computed from)");
  }
  // Closest rank-2 matrix, then unit Frobenius norm and a canonical sign: proportional inputs give the same frame.
  Eigen::Matrix3d F2 =
      svd.matrixU() * Eigen::Vector3d(sigma(0), sigma(1), 0.0).asDiagonal() * svd.matrixV().transpose();
  F2 /= F2.norm();
  canonicalSign(F2);
  Eigen::Vector3d e = svd.matrixV().col(2);
  Eigen::Vector3d ep = svd.matrixU().col(2);
  canonicalSign(e);
  canonicalSign(ep);

  m_F = F2;
  m_e = e.normalized();
  m_ep = ep.normalized();
  m_P.setZero();
  m_P.leftCols<3>().setIdentity();
  m_Pp = canonicalRightProjection(m_F, m_ep);
  m_initialized = true;
  m_canonical = true;
}

void vpProjectiveStereoRig::setProjections(const vpMatrix &P, const vpMatrix &Pp)
{
  const std::string where = at("setProjections()");
  setProjections(Projection(toEigen<3, 4>(P, where, "P")), Projection(toEigen<3, 4>(Pp, where, "P'")));
}

void vpProjectiveStereoRig::setProjections(const Projection &P, const Projection &Pp)
{
  const std::string where = at("setProjections()");
  if (!P.allFinite() || !Pp.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, where, "a camera matrix has a NaN or infinite entry");
  }
  Eigen::Vector4d centre[2];
  const Projection *cameras[2] = {&P, &Pp};
  for (int c = 0; c < 2; ++c) {
    Eigen::JacobiSVD<Eigen::Matrix4d> svd(
        Eigen::Matrix4d((Eigen::Matrix4d() << *cameras[c], Eigen::RowVector4d::Zero()).finished()),
        Eigen::ComputeFullV);
    const Eigen::Vector4d sigma = svd.singularValues();
    if (!(sigma(0) > 0.0) || sigma(2) < 1e-12 * sigma(0)) {
      fail(vpProjectiveException::degenerateConfigurationError, where,
           std::string(c == 0 ? "P" : "P'") + " has rank below 3, which is no camera; pass a 3x4 camera matrix");
    }
    centre[c] = svd.matrixV().col(3);
  }
  const Projection Pn = P / P.norm(), Ppn = Pp / Pp.norm();
  Eigen::Vector3d ep = Ppn * centre[0];
  Eigen::Vector3d e = Pn * centre[1];
  if (!(ep.norm() > 1e-9) || !(e.norm() > 1e-9)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the two cameras have the same centre (no baseline): they give no epipolar geometry");
  }
  const Eigen::Matrix<double, 4, 3> Pplus = Pn.transpose() * (Pn * Pn.transpose()).inverse();
  Eigen::Matrix3d F = vpMetricTwist::skew(ep) * Ppn * Pplus;
  if (!F.allFinite() || !(F.norm() > 0.0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where, "the camera pair gives no fundamental matrix");
  }
  F /= F.norm();
  canonicalSign(F);
  e.normalize();
  ep.normalize();
  canonicalSign(e);
  canonicalSign(ep);
  m_F = F;
  m_e = e;
  m_ep = ep;
  m_P = Pn;
  m_Pp = Ppn;
  m_initialized = true;
  m_canonical = false;
}

void vpProjectiveStereoRig::estimate(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                     double inlierThreshold)
{
  const std::string where = at("estimate()");
  if (left.size() != right.size()) {
    std::ostringstream os;
    os << "got " << left.size() << " left points but " << right.size() << " right points; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (left.size() < 8) {
    std::ostringstream os;
    os << "needs at least 8 matches to estimate the fundamental matrix, got " << left.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  requireFinite(inlierThreshold, where, "the inlier threshold");
  if (!(inlierThreshold > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where, "the inlier threshold must be positive (pixels)");
  }
  const size_t n = left.size();
  std::vector<Eigen::Vector2d> l(n), r(n);
  std::vector<cv::Point2d> cvl(n), cvr(n);
  for (size_t i = 0; i < n; ++i) {
    l[i] = toEigen(left[i], where, "a left image point");
    r[i] = toEigen(right[i], where, "a right image point");
    cvl[i] = cv::Point2d(l[i](0), l[i](1));
    cvr[i] = cv::Point2d(r[i](0), r[i](1));
  }

  // Degeneracy: the normalised 8-point system must have a one-dimensional null space.
  const Eigen::Matrix3d T = hartleyNormalization(l);
  const Eigen::Matrix3d Tp = hartleyNormalization(r);
  Eigen::MatrixXd A(n, 9);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d m = T * l[i].homogeneous();
    const Eigen::Vector3d mp = Tp * r[i].homogeneous();
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        A(static_cast<Eigen::Index>(i), 3 * a + b) = mp(a) * m(b);
      }
    }
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svdA(A);
  const Eigen::VectorXd sA = svdA.singularValues();
  if (sA(7) < 1e-8 * sA(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the matches do not determine the epipolar geometry (points collinear, coincident, or all on one plane "
         "seen without parallax); use matches spread over a 3D scene");
  }

  // Robust selection of the inliers: OpenCV's RANSAC needs 15 matches (it silently switches to LMedS below that),
  // so fewer matches are all kept and screened by the consensus loop below (which is then not robust: see the
  // header).
  const Eigen::Matrix3d Tinv = T.inverse(), Tpinv = Tp.inverse();
  std::vector<size_t> inliers;
  Eigen::Matrix3d Fn0 = Eigen::Matrix3d::Zero();
  double cost = std::numeric_limits<double>::infinity();
  if (n >= 15) {
    std::vector<uchar> mask;
    // RANSAC draws from OpenCV's global generator: reseed it so that the same matches give the same estimate,
    // whatever was computed before in the process.
    cv::theRNG() = cv::RNG(0x5eedULL);
    cv::Mat Fcv = cv::findFundamentalMat(cvl, cvr, cv::FM_RANSAC, inlierThreshold, 0.999, mask);
    if (Fcv.empty() || Fcv.rows != 3 || Fcv.cols != 3 || mask.size() != n) {
      fail(vpProjectiveException::estimationFailedError, where,
           "OpenCV's robust estimator found no fundamental matrix; check that the matches are correct");
    }
    Eigen::Matrix3d Fransac;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        Fransac(a, b) = Fcv.at<double>(a, b);
      }
    }
    if (Fransac.allFinite() && Fransac.norm() > 0.0) {
      Fn0 = Tpinv.transpose() * Fransac * Tinv;
      Fn0 /= Fn0.norm();
      cost = consensus(Tp.transpose() * Fn0 * T, l, r, inlierThreshold, inliers);
    }
    std::vector<size_t> masked;
    for (size_t i = 0; i < n; ++i) {
      if (mask[i]) {
        masked.push_back(i);
      }
    }
    if (masked.size() >= 8) {
      std::vector<size_t> set;
      const Eigen::Matrix3d Fn = linearFundamental(A, masked);
      const double c = consensus(Tp.transpose() * Fn * T, l, r, inlierThreshold, set);
      if (c < cost) {
        Fn0 = Fn;
        cost = c;
        inliers = set;
      }
    }
  } else {
    std::vector<size_t> all(n);
    for (size_t i = 0; i < n; ++i) {
      all[i] = i;
    }
    Fn0 = linearFundamental(A, all);
    inliers = all;
  }

  // Consensus loop: refit linearly on all inliers (RANSAC's F comes from a minimal sample), reclassify every match by
  // its distance to the epipolar lines of that fit, and keep the refit while it lowers the truncated quadratic cost
  // sum_i min(d_i^2, t^2) over all matches (MSAC): a refit on a poor set, which would lose matches, is refused.
  for (int round = 0; round < 10 && n >= 15 && inliers.size() >= 8; ++round) {
    std::vector<size_t> set;
    const Eigen::Matrix3d Fn = linearFundamental(A, inliers);
    const double c = consensus(Tp.transpose() * Fn * T, l, r, inlierThreshold, set);
    if (!(c < cost)) {
      break;
    }
    Fn0 = Fn;
    cost = c;
    const bool stable = set == inliers;
    inliers = set;
    if (stable) {
      break;
    }
  }
  if (inliers.size() < 8) {
    std::ostringstream os;
    os << "only " << inliers.size() << " of " << n
       << " matches agree with one epipolar geometry (8 needed); check the matches or raise the inlier threshold";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }

  // Gold-standard refinement on the inliers, repeated on the inliers of the refined geometry until they are the
  // matches it was fitted to.
  Eigen::Matrix3d F = goldStandardFundamental(l, r, T, Tp, inliers, Fn0);
  for (int round = 0; round < 4; ++round) {
    std::vector<size_t> set;
    consensus(F, l, r, inlierThreshold, set);
    if (set == inliers) {
      break;
    }
    if (set.size() < 8) {
      std::ostringstream os;
      os << "only " << set.size() << " of " << n << " matches agree with one epipolar geometry (8 needed); check "
         << "the matches or raise the inlier threshold";
      fail(vpProjectiveException::estimationFailedError, where, os.str());
    }
    inliers = set;
    Eigen::Matrix3d Fn = Tpinv.transpose() * F * Tinv;
    F = goldStandardFundamental(l, r, T, Tp, inliers, Fn / Fn.norm());
  }
  setFundamentalMatrix(toVisp(F));

  // Inliers of the refined geometry, and their residual in pixels.
  inliers.clear();
  for (size_t i = 0; i < n; ++i) {
    if (epipolarDistance(m_F, l[i], r[i]) <= inlierThreshold) {
      inliers.push_back(i);
    }
  }
  double sum = 0.0;
  m_inliers.assign(n, false);
  for (size_t i : inliers) {
    m_inliers[i] = true;
    const Eigen::Vector4d M = triangulate(l[i], r[i]);
    Eigen::Vector4d s;
    if (project(M, s)) {
      sum += (s.head<2>() - l[i]).squaredNorm() + (s.tail<2>() - r[i]).squaredNorm();
    }
  }
  m_residual = inliers.empty() ? 0.0 : std::sqrt(sum / (2.0 * static_cast<double>(inliers.size())));
}

vpMatrix vpProjectiveStereoRig::getFundamentalMatrix() const
{
  checkInitialized("getFundamentalMatrix()");
  return toVisp(m_F);
}

vpMatrix vpProjectiveStereoRig::getLeftProjection() const
{
  checkInitialized("getLeftProjection()");
  return toVisp(m_P);
}

vpMatrix vpProjectiveStereoRig::getRightProjection() const
{
  checkInitialized("getRightProjection()");
  return toVisp(m_Pp);
}

vpColVector vpProjectiveStereoRig::getLeftEpipole() const
{
  checkInitialized("getLeftEpipole()");
  return toVispVector(m_e);
}

vpColVector vpProjectiveStereoRig::getRightEpipole() const
{
  checkInitialized("getRightEpipole()");
  return toVispVector(m_ep);
}

Eigen::Vector4d vpProjectiveStereoRig::triangulateLinear(const Eigen::Vector2d &left,
                                                         const Eigen::Vector2d &right) const
{
  return linearTriangulation(m_P, m_Pp, left, right);
}

Eigen::Vector4d vpProjectiveStereoRig::triangulate(const Eigen::Vector2d &left, const Eigen::Vector2d &right) const
{
  Eigen::Vector4d M = linearTriangulation(m_P, m_Pp, left, right);
  Eigen::Vector4d obs;
  obs << left, right;
  // Gauss-Newton on the unit sphere, minimising the pixel reprojection error in both images.
  Eigen::Vector4d s;
  Eigen::Matrix4d J;
  if (!project(M, s, &J)) {
    return M;
  }
  double cost = (s - obs).squaredNorm();
  for (int iter = 0; iter < 10 && cost > 0.0; ++iter) {
    const Eigen::Matrix<double, 4, 3> B = sphereTangentBasis(M);
    const Eigen::Matrix<double, 4, 3> JB = J * B;
    const Eigen::Vector3d delta = (JB.transpose() * JB).ldlt().solve(-JB.transpose() * (s - obs));
    if (!delta.allFinite()) {
      break;
    }
    const Eigen::Vector4d Mnew = (M + B * delta).normalized();
    Eigen::Vector4d sNew;
    Eigen::Matrix4d Jnew;
    if (!project(Mnew, sNew, &Jnew)) {
      break;
    }
    const double costNew = (sNew - obs).squaredNorm();
    if (!(costNew < cost)) {
      break;
    }
    const bool converged = cost - costNew < 1e-14 * (1.0 + cost);
    M = Mnew;
    s = sNew;
    J = Jnew;
    cost = costNew;
    if (converged) {
      break;
    }
  }
  return M;
}

vpColVector vpProjectiveStereoRig::triangulate(const vpImagePoint &ipLeft, const vpImagePoint &ipRight) const
{
  const std::string where = at("triangulate()");
  checkInitialized("triangulate()");
  const Eigen::Vector2d l = toEigen(ipLeft, where, "the left image point");
  const Eigen::Vector2d r = toEigen(ipRight, where, "the right image point");
  return toVispVector(triangulate(l, r));
}

bool vpProjectiveStereoRig::project(const Eigen::Vector4d &M, Eigen::Vector4d &s, Eigen::Matrix4d *L) const
{
  return projectStereo(m_P, m_Pp, M, s, L) && s.allFinite();
}

void vpProjectiveStereoRig::project(const vpColVector &M, vpImagePoint &ipLeft, vpImagePoint &ipRight) const
{
  const std::string where = at("project()");
  checkInitialized("project()");
  const Eigen::Vector4d Me = toEigen<4>(M, where, "the projective point M");
  if (Me.norm() == 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "M is the zero vector, which is no projective point");
  }
  Eigen::Vector4d s;
  if (!project(Me, s)) {
    fail(vpProjectiveException::pointAtInfinityError, where,
         "M lies on the focal plane of a camera and has no finite image");
  }
  ipLeft.set_uv(s(0), s(1));
  ipRight.set_uv(s(2), s(3));
}
