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
  Private: what the rig's estimation and its triangulation share: the two-view geometry and the error site (and the
  epipolar distance, which the check of a session uses too). Not installed.
*/

#ifndef _vpStereoRigGeometry_h_
#define _vpStereoRigGeometry_h_

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpProjectiveErrors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
//! The error site of vpProjectiveStereoRig, whose sources are vpProjectiveStereoRig.cpp and
//! vpProjectiveStereoRigEstimation.cpp.
const vpErrorSite stereoRigAt("vpProjectiveStereoRig");

//! The canonical right camera of a unit, canonically signed F with right epipole e': P' = [[e']_x F + e' e'^T | e'].
vpProjectiveStereoRig::Projection canonicalRightProjection(const Eigen::Matrix3d &F, const Eigen::Vector3d &ep);

//! Larger of the distances (pixels) of \e mp to the epipolar line F m and of \e m to F^T mp (the estimation's inlier
//! test; vpProjectiveSessionCalibration::check() tells swapped images by it).
double epipolarDistance(const Eigen::Matrix3d &F, const Eigen::Vector2d &m, const Eigen::Vector2d &mp);

//! The unit right singular vector of the smallest singular value of \e As (false if not finite).
bool smallestSingularVector(const Eigen::Matrix4d &As, Eigen::Vector4d &x);

//! Linear triangulation of pixels \e m, \e mp seen by P, P' on column-equilibrated equations (no coordinate of M is
//! divided by).
Eigen::Vector4d linearTriangulation(const vpProjectiveStereoRig::Projection &P,
                                    const vpProjectiveStereoRig::Projection &Pp, const Eigen::Vector2d &m,
                                    const Eigen::Vector2d &mp);
} // namespace vpProjectiveInternal

#endif
