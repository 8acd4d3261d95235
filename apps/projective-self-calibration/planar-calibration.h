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
  \file planar-calibration.h
  \brief What the self-calibration is compared with: ViSP's own calibration of a stereo rig from views of a planar
  grid (vpCalibration).
*/

#ifndef _selfcal_planar_calibration_h_
#define _selfcal_planar_calibration_h_

#include <Eigen/Core>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpUniRand.h>

#include "calibration-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
/*!
  ViSP's calibration of both cameras of \e rig from \e views views of a planar grid of \e points x \e points points
  \e width metres wide, seen with noise \e sigma: the grid held as a user holds it in front of the rig, at its
  vergence point (where both views overlap most), tilted by up to 30 deg about its axes, turned by up to 15 deg and
  moved across the view, every point 5 px inside both images; a grid too large for both views (wider than 60 % of
  the view's height there, or than any pose fits) replaced by a smaller one, whose width goes to \e usedWidth. Each
  camera calibrated by vpCalibration::computeCalibrationMulti() (virtual visual servoing, no distortion; its model
  has no skew) from a rough guess (focal length 15 % off, the image centre 20 px off), the rig's pose averaged over
  the two cameras' poses of the grid. \e Kl, \e Kr are 3x3 (skew 0), \e lMr 4x4.
*/
void planarCalibration(const SkewedRig &rig, unsigned int views, unsigned int points, double width, double sigma,
                       vpGaussRand &noise, vpUniRand &rng, Eigen::Matrix3d &Kl, Eigen::Matrix3d &Kr,
                       Eigen::Matrix4d &lMr, double &usedWidth);
} // namespace selfcal

#endif
