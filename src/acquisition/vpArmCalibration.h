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
  Private: the steps of vpProjectiveArmAcquisition::calibrate(), one file each: the algebraic generators and the
  affine and metric upgrade (vpArmUpgrade.cpp), the bundle adjustment (vpArmBundleAdjustment.cpp, Ceres cost
  functors in vpMarkerObservationError.h). Not installed.
*/

#ifndef _vpArmCalibration_h_
#define _vpArmCalibration_h_

#include <cstddef>
#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  One trial motion: joint \e joint alone moved by \e amount; the pixels (u, v, u', v') of every marker after it,
  NaN where \e seen is false (a marker the trial does not show: identified markers).
*/
struct ArmTrial {
  unsigned int joint;
  double amount;
  std::vector<Eigen::Vector4d> s;
  std::vector<bool> seen;
};

/*!
  What the calibration works on: the acquisition's data, and which trial observations it uses (inlier[k][j]: marker
  j of trial k; always false where the trial does not show the marker).
*/
struct ArmCalibrationData {
  std::vector<vpProjectiveJoint::vpJointType> types;
  vpProjectiveArmModel::vpRigMounting mounting;
  vpProjectiveStereoRig rig;
  std::vector<Eigen::Vector4d> zeroImages; // (u, v, u', v') of each marker at the zero reference
  std::vector<ArmTrial> trials;
  double outlierThreshold;               // pixels, 0: every observation is used
  std::vector<std::vector<bool>> inlier; // [trial][marker]
};

//! A metric model: G (projective to metric), and per joint its axis and a point of it (see vpProjectiveArmModel).
struct MetricModel {
  Eigen::Matrix4d G;
  std::vector<Eigen::Vector3d> axis, point;
};

/*!
  Adds the squared pixel errors of joint \e i's inlier trial observations predicted by the generator \e Hhat from the
  zero-reference points \e M0, and their number of coordinates. With an outlier threshold t an error counts at most
  as 3 t (RMS over the two images); a prediction on a camera's focal plane counts as 1e6 px per coordinate.
*/
void accumulateTrialError(const ArmCalibrationData &data, unsigned int i, const Eigen::Matrix4d &Hhat,
                          const std::vector<Eigen::Vector4d> &M0, double &sum, size_t &count);

//! RMS pixel error of all trials predicted by the generators \e Hhat from the zero-reference points \e M0.
double predictionResidual(const ArmCalibrationData &data, const std::vector<Eigen::Matrix4d> &Hhat,
                          const std::vector<Eigen::Vector4d> &M0);

/*!
  The displacement of each trial (4x4, normalised) from the zero reference's images to its own, by maximum likelihood
  (vpProjectiveDisplacement::estimateFromImages()) or, with an outlier threshold, by the 5-point consensus of
  estimateRobust(), whose mismatched markers are flagged in data.inlier; NaN for a trial without a usable estimate.
  Throws (degenerateConfigurationError) if a trial did not move the markers. The displacements do not depend on the
  joint types: the hypotheses of the joint-type check share them.
*/
std::vector<Eigen::Matrix4d> trialDisplacements(ArmCalibrationData &data);

/*!
  The generator of each joint of type data.types[i] from its trials' \e displacements (the candidate that best
  predicts the joint's trials), \e M0 the triangulated zero reference; 0 for a joint none of whose trials gave a
  logarithm. Throws (notInitializedError) if a joint has no trial.
*/
void algebraicGenerators(const ArmCalibrationData &data, const std::vector<Eigen::Vector4d> &M0,
                         const std::vector<Eigen::Matrix4d> &displacements, std::vector<Eigen::Matrix4d> &Hhat);

/*!
  The affine and metric upgrade G (projective to metric frame, 4x4) of the generators \e Hhat of the joints flagged in
  \e use, on the frame whitened by the zero-reference points \e M0 (the paper's section 6: the plane at infinity, then
  the absolute conic that the revolute generators leave fixed), scaled so that the markers spread over a unit sphere.
  False if the upgrade does not give a finite, invertible G.
*/
bool metricUpgrade(const ArmCalibrationData &data, const std::vector<Eigen::Matrix4d> &Hhat,
                   const std::vector<bool> &use, const std::vector<Eigen::Vector4d> &M0, Eigen::Matrix4d &G);

/*!
  Each joint's metric twist in the frame of \e G: the axis (unit for a revolute joint, the motion per unit for a
  prismatic one) and a point of a revolute axis, the better of the one read off \f$ G \hat H_i G^{-1} \f$ and the
  rigid motion of the trial points \e trialPoints (per trial, the markers seen) from \e M0. False if a joint has none.
*/
bool initialTwists(const ArmCalibrationData &data, const Eigen::Matrix4d &G, const std::vector<Eigen::Matrix4d> &Hhat,
                   const std::vector<Eigen::Vector4d> &M0, const std::vector<std::vector<Eigen::Vector4d>> &trialPoints,
                   std::vector<Eigen::Vector3d> &axis, std::vector<Eigen::Vector3d> &point);

/*!
  The starts of the bundle adjustment: the affine and metric upgrade of the generators (with every joint, and with
  one or two left out in turn) and the metric twists, the candidate that best predicts all the trials first, then the
  others in the order of their prediction. Throws (estimationFailedError) if no upgrade gives a finite, invertible G.
*/
std::vector<MetricModel> initialMetricModels(const ArmCalibrationData &data, const std::vector<Eigen::Matrix4d> &Hhat,
                                             const std::vector<Eigen::Vector4d> &M0);

/*!
  Bundle adjustment over \f$ G^{-1} \f$ (unit sphere of R^16), the twists (revolute axes on the unit sphere) and the
  marker points (unit sphere of R^4), on the pixel error of the zero reference and of the inlier trial observations,
  or, with \e robustLoss, of every trial observation under a Cauchy loss at the outlier threshold. Returns the model
  (its markers of unit norm, its zero-reference joints \e qRef) and the RMS residual per pixel coordinate; \e quick
  stops earlier (50 iterations, 1e-8 relative changes instead of 200 and 1e-12: to compare hypotheses). Throws
  (estimationFailedError) if Ceres gives no usable solution.
*/
vpProjectiveArmModel bundleAdjust(const ArmCalibrationData &data, const std::vector<Eigen::Vector4d> &M0,
                                  const MetricModel &start, bool robustLoss,
                                  const vpProjectiveArmModel::JointVector &qRef, double &residual, bool quick = false);

//! The metric model (G, axes, points) of \e model: the start of another adjustment.
MetricModel metricModelOf(const vpProjectiveArmModel &model);

/*!
  The whole calibration of \e data with its joint types data.types, from the trials' \e displacements: the algebraic
  generators, the metric start, the bundle adjustment and, with an outlier threshold, its rounds of outlier
  classification. An adjustment ending above 1.3 times the images' epipolar noise (epipolarNoise(), at least 0.05 px)
  tries the other metric starts (initialMetricModels()) and keeps the model of the lowest residual. \e data receives the
  inlier flags and the rig of the last adjustment; \e residual and \e algebraicResidual the RMS pixel residuals of the
  adjustment and of the algebraic generators. Throws (estimationFailedError) if the upgrade or the adjustment fails.
*/
vpProjectiveArmModel fitArmModel(ArmCalibrationData &data, const std::vector<Eigen::Vector4d> &M0,
                                 const std::vector<Eigen::Matrix4d> &displacements,
                                 const vpProjectiveArmModel::JointVector &qRef, double &residual,
                                 double &algebraicResidual);

/*!
  The bundle adjustment of \e data (its inlier flags and rig those of the fit of \e from) with the joint types
  data.types, started from \e from: a joint whose type differs from the model's starts from the motion of the other
  type that moves the markers' centroid alike (a revolute axis at the distance that turns the reading into the
  prismatic joint's motion, perpendicular to it and to the line of sight; a prismatic direction along the revolute
  motion of the centroid). \e quick: see bundleAdjust(). Throws (estimationFailedError) if the adjustment fails.
*/
vpProjectiveArmModel refitArmModel(const ArmCalibrationData &data, const vpProjectiveArmModel &from, double &residual,
                                   bool quick);

/*!
  Squared pixel error (summed over u, v, u', v') of each observation of \e data predicted by \e model: zero[j] at the
  zero reference, trial[k][j] of marker j in trial k; NaN for an observation that is not used (not seen, or an
  outlier), infinity for a prediction on a camera's focal plane.
*/
struct ObservationErrors {
  std::vector<double> zero;
  std::vector<std::vector<double>> trial;
};
ObservationErrors observationErrors(const vpProjectiveArmModel &model, const ArmCalibrationData &data);
} // namespace vpProjectiveInternal

#endif
