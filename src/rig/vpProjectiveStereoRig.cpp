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

#include "rig/vpStereoRigGeometry.h"
#include "core/vpProjection.h"
#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveNumerics.h"

using namespace vpProjectiveInternal;

namespace vpProjectiveInternal
{

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
} // namespace vpProjectiveInternal

vpProjectiveStereoRig::vpProjectiveStereoRig()
    : m_F(Eigen::Matrix3d::Zero()), m_P(Projection::Zero()), m_Pp(Projection::Zero()), m_bound2P(0.0), m_bound2Pp(0.0),
      m_e(Eigen::Vector3d::Zero()), m_ep(Eigen::Vector3d::Zero()), m_inliers(), m_residual(0.0), m_initialized(false),
      m_canonical(true)
{
}

void vpProjectiveStereoRig::updateFocalPlaneBounds()
{
  m_bound2P = focalPlaneBound2(m_P);
  m_bound2Pp = focalPlaneBound2(m_Pp);
}

void vpProjectiveStereoRig::checkInitialized(const char *where) const
{
  if (!m_initialized) {
    fail(vpProjectiveException::notInitializedError, stereoRigAt("") + where,
         "the rig has no fundamental matrix yet; call estimate() with >= 8 matches or setFundamentalMatrix() first");
  }
}

void vpProjectiveStereoRig::setFundamentalMatrix(const vpMatrix &F)
{
  const std::string where = stereoRigAt("setFundamentalMatrix()");
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
  updateFocalPlaneBounds();
  m_initialized = true;
  m_canonical = true;
}

void vpProjectiveStereoRig::setProjections(const vpMatrix &P, const vpMatrix &Pp)
{
  const std::string where = stereoRigAt("setProjections()");
  setProjections(Projection(toEigen<3, 4>(P, where, "P")), Projection(toEigen<3, 4>(Pp, where, "P'")));
}

void vpProjectiveStereoRig::setProjections(const Projection &P, const Projection &Pp)
{
  const std::string where = stereoRigAt("setProjections()");
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
  updateFocalPlaneBounds();
  m_initialized = true;
  m_canonical = false;
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
  const std::string where = stereoRigAt("triangulate()");
  checkInitialized("triangulate()");
  const Eigen::Vector2d l = toEigen(ipLeft, where, "the left image point");
  const Eigen::Vector2d r = toEigen(ipRight, where, "the right image point");
  return toVispVector(triangulate(l, r));
}

std::vector<vpColVector> vpProjectiveStereoRig::triangulate(const std::vector<vpImagePoint> &ipLeft,
                                                            const std::vector<vpImagePoint> &ipRight) const
{
  const std::string where = stereoRigAt("triangulate()");
  checkInitialized("triangulate()");
  const std::vector<Eigen::Vector4d> s = stackStereoImages(ipLeft, ipRight, where); // same sizes, finite
  std::vector<vpColVector> M;
  M.reserve(s.size());
  for (const Eigen::Vector4d &sj : s) {
    M.push_back(toVispVector(triangulate(Eigen::Vector2d(sj.head<2>()), Eigen::Vector2d(sj.tail<2>()))));
  }
  return M;
}

bool vpProjectiveStereoRig::project(const Eigen::Vector4d &M, Eigen::Vector4d &s, Eigen::Matrix4d *L) const
{
  // projectStereo(m_P, m_Pp, M, s, L) (the same arithmetic, hence the same bits) on the bounds computed with P, P'.
  if (L == nullptr) { // the predictions of the servo's checks: written out, no Jacobian
    const double M2 = M.squaredNorm();
    const Eigen::Vector3d m = m_P * M;
    if (!(m(2) * m(2) > m_bound2P * M2)) {
      return false;
    }
    const Eigen::Vector3d mp = m_Pp * M;
    if (!(mp(2) * mp(2) > m_bound2Pp * M2)) {
      return false;
    }
    const double iw = 1.0 / m(2), iwp = 1.0 / mp(2);
    s(0) = m(0) * iw;
    s(1) = m(1) * iw;
    s(2) = mp(0) * iwp;
    s(3) = mp(1) * iwp;
    return s.allFinite();
  }
  Eigen::Vector2d uv, uvp;
  Eigen::Matrix<double, 2, 4> J, Jp;
  if (!projectPointBounded(m_P, m_bound2P, M, uv, L != nullptr ? &J : nullptr) ||
      !projectPointBounded(m_Pp, m_bound2Pp, M, uvp, L != nullptr ? &Jp : nullptr)) {
    return false;
  }
  s << uv, uvp;
  if (L != nullptr) {
    L->topRows<2>() = J;
    L->bottomRows<2>() = Jp;
  }
  return s.allFinite();
}

void vpProjectiveStereoRig::project(const vpColVector &M, vpImagePoint &ipLeft, vpImagePoint &ipRight) const
{
  const std::string where = stereoRigAt("project()");
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
