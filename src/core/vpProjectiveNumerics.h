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
  Private: the small numerical pieces several jobs share: a canonical sign, Hartley's normalisation of pixels, the
  whitening of projective points, the weights of a derivative filter, a basis of the sphere's tangent space. Not
  installed.
*/

#ifndef _vpProjectiveNumerics_h_
#define _vpProjectiveNumerics_h_

#include <cmath>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpConfig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
//! Flips the sign of \e x so that its entry of largest magnitude is positive: a canonical sign for a direction.
template <typename Derived> void canonicalSign(Eigen::MatrixBase<Derived> &x)
{
  Eigen::Index r = 0, c = 0;
  x.cwiseAbs().maxCoeff(&r, &c);
  if (x(r, c) < 0) {
    x = -x;
  }
}

//! Hartley's isotropic normalisation of pixels: centroid to 0, mean distance to sqrt(2). Returns the 3x3 similarity.
inline Eigen::Matrix3d hartleyNormalization(const std::vector<Eigen::Vector2d> &points)
{
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d &p : points) {
    c += p;
  }
  c /= static_cast<double>(points.size());
  double meanDistance = 0.0;
  for (const Eigen::Vector2d &p : points) {
    meanDistance += (p - c).norm();
  }
  meanDistance /= static_cast<double>(points.size());
  const double s = meanDistance > 0.0 ? std::sqrt(2.0) / meanDistance : 1.0;
  Eigen::Matrix3d T;
  T << s, 0, -s * c(0), 0, s, -s * c(1), 0, 0, 1;
  return T;
}

/*!
  Whitening of homogeneous 4-vectors without dividing by any coordinate: with each point scaled to unit norm and
  signed canonically, T = (sum M M^T / n)^(-1/2), so that the points T M are spread isotropically over the sphere.
*/
Eigen::Matrix4d whitening(const std::vector<Eigen::Vector4d> &points);

/*!
  The weights of the derivative at sample \e k of a sequence sampled at times \e t: over the samples
  \f$ |j - k| \le \f$ \e halfWindow (clipped at the ends), the least-squares fit
  \f$ x_j - x_k \approx a (t_j - t_k) + b (t_j - t_k)^2 \f$ (a line when the window holds one other sample) gives
  \f$ \dot x_k = a = \sum_j w_j (x_j - x_k) \f$, \f$ x_j - x_k \f$ being a difference in the group (joint values, or
  \f$ \log(H_j H_k^{-1}) \f$). The quadratic term removes the lag that a straight line has at the end of a window
  (the real-time case, k the newest sample), at the price of more noise. Returns the pairs (j, w_j), j != k. Throws
  (dimensionError, invalidValueError, naming \e where) if \e k is out of range, \e halfWindow is 0, the window has
  one sample or its times are not finite and strictly increasing.
*/
std::vector<std::pair<size_t, double>> slopeWeights(const std::vector<double> &t, size_t k, size_t halfWindow,
                                                    const std::string &where);

//! Orthonormal basis (4x3) of the tangent space of the unit sphere at the unit vector M.
Eigen::Matrix<double, 4, 3> sphereTangentBasis(const Eigen::Vector4d &M);

} // namespace vpProjectiveInternal

#endif
