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

/*!
  \file rig-errors.cpp
  \brief Errors of a calibrated rig against the truth.
*/

#include "rig-errors.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
RigErrors compare(const Eigen::Matrix3d &Kl, const Eigen::Matrix3d &Kr, const Eigen::Matrix4d &lMr,
                  const SkewedRig &truth, bool metric, const vpProjectiveSelfCalibration::vpUncertainty *uncertainty)
{
  RigErrors e;
  auto within = [&](double error, double sigma, Parameter p) {
    const double ratio = std::abs(error) / sigma;
    e.sigmaRatio = std::max(e.sigmaRatio, ratio);
    e.covered[p] = e.covered[p] && ratio <= 3.0;
  };
  const Eigen::Matrix3d K[2] = {Kl, Kr}, Ktrue[2] = {truth.Kl, truth.Kr};
  for (int c = 0; c < 2; ++c) {
    // (fx, fy, skew, u0, v0) at K's (0, 0), (1, 1), (0, 1), (0, 2), (1, 2)
    const int rows[5] = {0, 1, 0, 0, 1}, cols[5] = {0, 1, 1, 2, 2};
    const Parameter kind[5] = {FOCAL, FOCAL, SKEW, PRINCIPAL, PRINCIPAL};
    for (int k = 0; k < 5; ++k) {
      const double error = K[c](rows[k], cols[k]) - Ktrue[c](rows[k], cols[k]);
      const double relative = kind[k] == FOCAL ? error / Ktrue[c](rows[k], cols[k]) : error;
      e.error[kind[k]] = std::max(e.error[kind[k]], std::abs(relative));
      if (uncertainty != nullptr) {
        within(error, (c == 0 ? uncertainty->left : uncertainty->right)(k), kind[k]);
      }
    }
  }
  Eigen::Matrix4d lMrTrue;
  for (unsigned int i = 0; i < 4; ++i) {
    for (unsigned int j = 0; j < 4; ++j) {
      lMrTrue(i, j) = truth.lMr()[i][j];
    }
  }
  // The rotation error as a rotation vector in the left camera's axes: lRr = exp(e) lRr_true.
  const Eigen::AngleAxisd aa(Eigen::Matrix3d(lMr.topLeftCorner<3, 3>() * lMrTrue.topLeftCorner<3, 3>().transpose()));
  e.error[ROTATION] = aa.angle() * 180.0 / M_PI;
  const Eigen::Vector3d b = lMr.topRightCorner<3, 1>(), bTrue = lMrTrue.topRightCorner<3, 1>();
  const double direction = std::atan2(b.cross(bTrue).norm(), b.dot(bTrue));
  e.error[DIRECTION] = direction * 180.0 / M_PI;
  e.error[LENGTH] = metric ? std::abs(b.norm() / bTrue.norm() - 1.0) : 0.0;
  if (uncertainty != nullptr) {
    const Eigen::Vector3d rotation = aa.angle() * aa.axis();
    for (int k = 0; k < 3; ++k) {
      within(rotation(k), uncertainty->rotation(k), ROTATION);
    }
    within(direction, uncertainty->baselineDirection, DIRECTION);
    if (metric) {
      within(b.norm() - bTrue.norm(), uncertainty->baselineLength, LENGTH);
    }
  }
  return e;
}

const char *nameOf(Parameter p)
{
  const char *const names[PARAMETERS] = {"focal length", "principal point",    "skew",
                                         "rig rotation", "baseline direction", "baseline length"};
  return names[p];
}

const char *unitOf(Parameter p)
{
  const char *const units[PARAMETERS] = {"%", "px", "px", "deg", "deg", "%"};
  return units[p];
}

double scaleOf(Parameter p)
{
  return p == FOCAL || p == LENGTH ? 100.0 : 1.0;
}
} // namespace selfcal
