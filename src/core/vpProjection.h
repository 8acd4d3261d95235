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

/*
  Private: the one home of the pinhole projection of a projective point and of its Jacobian, eq. (45). The rig, the
  robot's image Jacobian, the feature's interaction matrix, the displacement refinements and the Ceres cost functors
  all call it, with one focal-plane tolerance. Templated on the scalar so that Ceres' automatic differentiation uses the
  very same formula. Not installed.
*/

#ifndef _vpProjection_h_
#define _vpProjection_h_

#include <cmath>

#include <Eigen/Core>

namespace vpProjectiveInternal
{
/*!
  A point \f$ M \f$ whose depth \f$ |P_3 M| \f$ in a camera \f$ P \f$ (3x4) is at most kFocalPlaneTolerance
  \f$ \|P\|_F \|M\| \f$ lies on that camera's focal plane: it has no finite image. The bound is relative, so that
  neither the scale of \f$ M \f$ nor that of \f$ P \f$ matters.
*/
constexpr double kFocalPlaneTolerance = 1e-12;

/*!
  Pixel \f$ (u, v) = (m_1 / m_3, m_2 / m_3) \f$ of \f$ m = P M \f$ and, if \e J is not null, its Jacobian with
  respect to \f$ M \f$ (2x4), \f$ J_C(m) P \f$ with \f$ J_C(m) = [[1/m_3, 0, -m_1/m_3^2], [0, 1/m_3, -m_2/m_3^2]] \f$
  (45). \f$ M \f$ is never divided by its last coordinate; the result does not depend on its scale or sign. Returns
  false, leaving \e uv and \e J unspecified, when \f$ M \f$ is on the focal plane of \f$ P \f$ (see
  kFocalPlaneTolerance). \e T is double or a Ceres Jet (the test then compares the values); \e P has scalar double
  or \e T.
*/
template <typename T, typename DerivedP>
bool projectPoint(const Eigen::MatrixBase<DerivedP> &P, const Eigen::Matrix<T, 4, 1> &M, Eigen::Matrix<T, 2, 1> &uv,
                  Eigen::Matrix<T, 2, 4> *J = nullptr);

/*!
  The focal-plane bound of \e P squared, \f$ (10^{-12} \|P\|_F)^2 \f$: a constant of the camera, which a loop that
  projects many points computes once (projectPointBounded()).
*/
template <typename DerivedP> double focalPlaneBound2(const Eigen::MatrixBase<DerivedP> &P)
{
  return (kFocalPlaneTolerance * kFocalPlaneTolerance) * double(P.squaredNorm());
}

/*!
  projectPoint() with the focal-plane bound of \e P given (\e tolerance2: focalPlaneBound2(P)): the same arithmetic,
  hence the same bits, without recomputing \f$ \|P\|_F^2 \f$ at every point.
*/
template <typename T, typename DerivedP>
bool projectPointBounded(const Eigen::MatrixBase<DerivedP> &P, const T &tolerance2, const Eigen::Matrix<T, 4, 1> &M,
                         Eigen::Matrix<T, 2, 1> &uv, Eigen::Matrix<T, 2, 4> *J = nullptr)
{
  const Eigen::Matrix<T, 3, 1> m = P.template cast<T>() * M;
  if (!(m(2) * m(2) > tolerance2 * M.squaredNorm())) {
    return false;
  }
  const T iw = T(1.0) / m(2);
  uv(0) = m(0) * iw;
  uv(1) = m(1) * iw;
  if (J != nullptr) {
    for (int c = 0; c < 4; ++c) {
      (*J)(0, c) = iw * (T(P(0, c)) - uv(0) * T(P(2, c)));
      (*J)(1, c) = iw * (T(P(1, c)) - uv(1) * T(P(2, c)));
    }
  }
  return true;
}

template <typename T, typename DerivedP>
bool projectPoint(const Eigen::MatrixBase<DerivedP> &P, const Eigen::Matrix<T, 4, 1> &M, Eigen::Matrix<T, 2, 1> &uv,
                  Eigen::Matrix<T, 2, 4> *J)
{
  const T tolerance2 = T(kFocalPlaneTolerance * kFocalPlaneTolerance) * T(P.squaredNorm());
  return projectPointBounded(P, tolerance2, M, uv, J);
}

/*!
  Both images \f$ s = (u, v, u', v') \f$ of \f$ M \f$ by the camera pair \f$ P, P' \f$ and, if \e L is not null,
  \f$ L = \partial s / \partial M \f$ (4x4): the rows \f$ J_C(P M) P \f$ and \f$ J_C(P' M) P' \f$ of eq. (45). False
  when \f$ M \f$ is on a focal plane of either camera.
*/
template <typename T, typename DerivedP, typename DerivedPp>
bool projectStereo(const Eigen::MatrixBase<DerivedP> &P, const Eigen::MatrixBase<DerivedPp> &Pp,
                   const Eigen::Matrix<T, 4, 1> &M, Eigen::Matrix<T, 4, 1> &s, Eigen::Matrix<T, 4, 4> *L = nullptr)
{
  Eigen::Matrix<T, 2, 1> uv, uvp;
  Eigen::Matrix<T, 2, 4> J, Jp;
  if (!projectPoint(P, M, uv, L != nullptr ? &J : nullptr) || !projectPoint(Pp, M, uvp, L != nullptr ? &Jp : nullptr)) {
    return false;
  }
  s << uv, uvp;
  if (L != nullptr) {
    L->template topRows<2>() = J;
    L->template bottomRows<2>() = Jp;
  }
  return true;
}
} // namespace vpProjectiveInternal

#endif
