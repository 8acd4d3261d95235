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
  Private: the model check of vpProjectiveArmAcquisition::calibrate() (vpProjectiveModelCheck): the image noise, the
  hypotheses of joint types (vpArmJointTypes.cpp), the gate and the diagnosis of a refused model (vpArmDiagnosis.cpp).
  Not installed.
*/

#ifndef _vpArmModelCheck_h_
#define _vpArmModelCheck_h_

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveModelCheck.h>

#include "acquisition/vpArmCalibration.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
//! One calibrated hypothesis: the model of data.types, the data it was fitted to, and its errors.
struct ArmFit {
  bool ok = false;            // a model was fitted
  std::string failure;        // why not, if not
  int failureCode = 0;        // the vpProjectiveException code of the failure
  ArmCalibrationData data;    // its types, and the inlier flags and rig of the fit
  vpProjectiveArmModel model; // the model
  double residual = 0.0;      // RMS px per coordinate of the adjustment
  double algebraicResidual = 0.0;
  ObservationErrors errors;  // of every observation
  double squaredError = 0.0; // S: the sum of the squared errors (px^2), infinite if not ok
  size_t coordinates = 0;    // the number of coordinates (4 per observation)
  bool quick = false;        // from a quick adjustment (see bundleAdjust())

  //! RMS (px per coordinate) of joint \e i's trial observations (NaN if none).
  double jointResidual(unsigned int i) const;
  //! RMS of trial \e k's observations (NaN if none).
  double trialResidual(size_t k) const;
  //! RMS of every trial observation of the joints other than \e i (NaN if none).
  double otherJointsResidual(unsigned int i) const;
};

//! What the check starts from: the acquisition's data ready to be fitted, and the settings.
struct ArmCheckInput {
  ArmCalibrationData data;                    // types declared, or placeholders when identifying
  std::vector<Eigen::Vector4d> M0;            // the triangulated zero reference
  std::vector<Eigen::Matrix4d> displacements; // of each trial (trialDisplacements())
  vpProjectiveArmModel::JointVector qRef;
  bool identify = false;   // the types are unknown: identify them
  double givenNoise = 0.0; // setImageNoise()
  double tolerance = 3.0;  // setResidualTolerance(); 0: no gate
};

//! The check's outcome: the fit kept (its types are the model's) and what vpProjectiveModelCheck reports.
struct ArmCheck {
  ArmFit fit;
  bool accepted = false;
  double noise = 0.0, epipolarNoise = 0.0, limit = 0.0;
  std::vector<vpProjectiveModelCheck::vpJointTypeFit> joints;
  std::vector<vpProjectiveModelCheck::vpDiagnosis> causes;
  std::string message;
  // For the diagnosis: the joints whose declared type the trials contradict, and the fit with them changed.
  std::vector<unsigned int> contradicted;
  ArmFit typesFixed;
  bool exchanged = false; // refused before any fit: the images meet the rig only with left and right exchanged
};

//! The fit of \e data's types from scratch (fitArmModel()); a failure of the estimation is reported, not thrown.
ArmFit fitHypothesis(const ArmCheckInput &in, const ArmCalibrationData &data);
//! The fit of the types \e types started from \e from (refitArmModel()), or from scratch if \e from is not ok.
ArmFit refitHypothesis(const ArmCheckInput &in, const ArmFit &from,
                       const std::vector<vpProjectiveJoint::vpJointType> &types);
//! The fit of \e data (the data of \e from changed: types, trials) started from \e from, which must be ok; a quick
//! adjustment (bundleAdjust()) unless \e quick is false.
ArmFit refitData(const ArmFit &from, const ArmCalibrationData &data, bool quick = true);

/*!
  The image noise (px per coordinate) of the acquisition's images against the rig's epipolar geometry: each
  observation's optimal-triangulation reprojection error (squared, summed over its 4 coordinates: sigma^2 chi^2_1),
  the mean of the smallest 90 % divided by 0.6233. 0 with fewer than 5 observations. \e exchanged: the same with
  every observation's left and right images exchanged, (u', v', u, v).
*/
double epipolarNoise(const ArmCalibrationData &data, bool exchanged = false);

//! Squared epipolar gap (px^2) of one observation (u, v, u', v') in \e rig: infinite if it cannot be projected.
double epipolarGap(const vpProjectiveStereoRig &rig, const Eigen::Vector4d &s);

//! Rotation angle (rad, in [0, pi]) of a displacement: the largest argument of its eigenvalues; NaN if not finite.
double turnAngle(const Eigen::Matrix4d &H);

//! The other joint type.
inline vpProjectiveJoint::vpJointType otherType(vpProjectiveJoint::vpJointType type)
{
  return type == vpProjectiveJoint::REVOLUTE ? vpProjectiveJoint::PRISMATIC : vpProjectiveJoint::REVOLUTE;
}

/*!
  The joint types (vpArmJointTypes.cpp): identifies them (in.identify) or checks the declared ones, filling
  check.fit (the model kept), check.joints, check.contradicted and check.typesFixed. Needs check.noise.
*/
void settleJointTypes(const ArmCheckInput &in, ArmCheck &check);

//! A cause of a refused model, not yet tested: unlikely, nothing fixed, no joint, trial or marker named.
vpProjectiveModelCheck::vpDiagnosis diagnosis(vpProjectiveModelCheck::vpCause cause);
/*!
  Left and right images exchanged against the rig (a rig given with its F, the images right first): true, and
  check refused with that one cause and its message, when the acquisition's epipolar noise with every observation's
  images exchanged is below half of it as given. With the images in the rig's order the epipolar gaps are the noise
  alone and exchanging them can only add a gap; a rig whose F is nearly skew-symmetric (parallel cameras) cannot tell
  the order, and the servo tells it then (vpServoModelMismatch). Needs check.epipolarNoise.
*/
bool refuseExchangedImages(const ArmCheckInput &in, ArmCheck &check);
//! The ranked causes of a refused model and the message (vpArmDiagnosis.cpp).
void diagnoseRefusal(const ArmCheckInput &in, ArmCheck &check);

//! The whole check: noise, joint types, gate, and the causes of a refusal (vpArmModelCheck.cpp).
ArmCheck checkArmModel(const ArmCheckInput &in);

//! "12.3 px": 3 significant digits.
std::string pixelsText(double px);
} // namespace vpProjectiveInternal

#endif
