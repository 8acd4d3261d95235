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
  Private: the epipolar distance of a stereo feature, shared by the feature health's outlier test and the model
  mismatch's stereo test. Not installed.
*/

#ifndef _vpEpipolarDistance_h_
#define _vpEpipolarDistance_h_

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Core>

namespace vpProjectiveInternal
{
/*!
  Distance (pixels) of a point to the line \e l of an image, from the epipolar residual \f$ r = |m'^T F m| \f$ that
  every such distance shares. A line with a null normal is the epipolar line of an epipole: the distance is 0 if the
  residual is, infinite otherwise.
*/
inline double lineDistance(double residual, const Eigen::Vector3d &l)
{
  const double normal = l.head<2>().norm();
  if (normal > 0.0) {
    return residual / normal;
  }
  return residual == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

/*!
  The epipolar distance \f$ d_F \f$ (pixels) of the feature \e s = (u, v, u', v') (left image first) under the
  fundamental matrix \e F (\f$ m'^T F m = 0 \f$): the larger of the distances of \f$ m \f$ to the epipolar line of
  \f$ m' \f$ and of \f$ m' \f$ to that of \f$ m \f$, to the bit. With both normals non-null it is
  \f$ r / \sqrt{\min(\|n\|^2, \|n'\|^2)} \f$: the square root and the division are correctly rounded, hence
  monotone, so that one of each gives the larger of both quotients.
*/
inline double epipolarDistance(const Eigen::Matrix3d &F, const Eigen::Vector4d &s)
{
  const Eigen::Vector3d m(s(0), s(1), 1.0);
  const Eigen::Vector3d mp(s(2), s(3), 1.0);
  const Eigen::Vector3d lp = F * m;             // epipolar line of m in the right image
  const Eigen::Vector3d l = F.transpose() * mp; // epipolar line of m' in the left image
  const double residual = std::abs(mp.dot(lp));
  const double n2 = l.head<2>().squaredNorm(), np2 = lp.head<2>().squaredNorm();
  if (n2 > 0.0 && np2 > 0.0) {
    return residual / std::sqrt(std::min(n2, np2));
  }
  return std::max(lineDistance(residual, l), lineDistance(residual, lp));
}
} // namespace vpProjectiveInternal

#endif
