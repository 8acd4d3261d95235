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
  Private: the closed-form pair exp(+dq Hhat), exp(-dq Hhat) of one p-joint, which
  vpProjectiveKinematics::forwardKinematics() chains. Not installed.
*/

#ifndef _vpJointExponentialPair_h_
#define _vpJointExponentialPair_h_

#include <cmath>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveJoint.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  E = exp(dq Hhat) and Einv = exp(-dq Hhat) sharing their terms: I +- sin(dq) Hhat + (1 - cos(dq)) Hhat^2 for a
  revolute joint (26), I +- dq Hhat for a prismatic one (31). \e Hhat2 is Hhat * Hhat (unused for a prismatic joint).
*/
inline void jointExponentialPair(vpProjectiveJoint::vpJointType type, double dq, const Eigen::Matrix4d &Hhat,
                                 const Eigen::Matrix4d &Hhat2, Eigen::Matrix4d &E, Eigen::Matrix4d &Einv)
{
  if (type == vpProjectiveJoint::REVOLUTE) {
    const double s = std::sin(dq);
    const double c = 1.0 - std::cos(dq);
    E = Eigen::Matrix4d::Identity() + s * Hhat + c * Hhat2;
    Einv = Eigen::Matrix4d::Identity() - s * Hhat + c * Hhat2;
  } else {
    E = Eigen::Matrix4d::Identity() + dq * Hhat;
    Einv = Eigen::Matrix4d::Identity() - dq * Hhat;
  }
}

/*!
  Chains one joint's pair onto the product of the joints before it along the chain: A = A E, Ainv = Einv Ainv; the
  first joint (\e first) starts them (A = E, Ainv = Einv, no product with the identity).
*/
inline void chainExponentialPair(bool first, const Eigen::Matrix4d &E, const Eigen::Matrix4d &Einv, Eigen::Matrix4d &A,
                                 Eigen::Matrix4d &Ainv)
{
  if (first) {
    A = E;
    Ainv = Einv;
  } else {
    A = A * E;
    Ainv = Einv * Ainv;
  }
}
} // namespace vpProjectiveInternal

#endif
