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
  Private: what the arm simulator (vpSimulatorArm.cpp) and the simulated robot (vpSimulatorRobotArm.cpp) share: one
  Denavit-Hartenberg link. Not installed.
*/

#ifndef _vpSimulatorArmInternal_h_
#define _vpSimulatorArmInternal_h_

#include <Eigen/Core>

#include <visp3/projective/vpSimulatorArm.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
//! One Denavit-Hartenberg row at joint value q: \f$ R_z(\theta) T_z(d) T_x(a) R_x(\alpha) \f$, q added to theta
//! (revolute) or d (prismatic).
Eigen::Matrix4d linkTransform(const vpSimulatorArm::vpDHRow &row, double q);
} // namespace vpProjectiveInternal

#endif
