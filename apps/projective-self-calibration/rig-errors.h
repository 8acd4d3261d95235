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
  \file rig-errors.h
  \brief The errors of a calibrated stereo rig against the truth, and whether the stated standard deviations cover
  them.
*/

#ifndef _selfcal_rig_errors_h_
#define _selfcal_rig_errors_h_

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "calibration-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
//! The parameters a calibration is judged on (columns of the study's table).
enum Parameter { FOCAL, PRINCIPAL, SKEW, ROTATION, DIRECTION, LENGTH, PARAMETERS };

//! Errors of one calibration, the worst of both cameras for the intrinsics.
struct RigErrors {
  double error[PARAMETERS] = {0, 0, 0, 0, 0, 0};                   //!< relative (focal, length), px, deg
  bool covered[PARAMETERS] = {true, true, true, true, true, true}; //!< every error within 3 standard deviations
  double sigmaRatio = 0; //!< the largest error in standard deviations (how far the stated uncertainty is off)
};

/*!
  The errors of \e Kl, \e Kr (3x3) and \e lMr (4x4) against \e truth; the baseline length when \e metric (its unit
  the truth's). With \e uncertainty, whether each error is within 3 of its standard deviations (per component).
*/
RigErrors compare(const Eigen::Matrix3d &Kl, const Eigen::Matrix3d &Kr, const Eigen::Matrix4d &lMr,
                  const SkewedRig &truth, bool metric,
                  const vpProjectiveSelfCalibration::vpUncertainty *uncertainty = nullptr);

//! The name of a parameter and its unit in the table.
const char *nameOf(Parameter p);
const char *unitOf(Parameter p);
//! The table's scale of a parameter (100 for a relative error in %).
double scaleOf(Parameter p);
} // namespace selfcal

#endif
