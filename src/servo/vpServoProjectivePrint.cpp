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
  vpServoProjective::print(): the task as vpServo::print(vpServo::ALL) shows it, with what only this task has.
*/

#include <visp3/projective/vpServoProjective.h>

#include <ostream>
#include <string>

#include <visp3/projective/vpProjectiveNotices.h>

#include "servo/vpServoProjectiveNotices.h"
#include <Eigen/Core>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
const char *stateName(vpServoFeatureHealth::vpFeatureState state)
{
  switch (state) {
  case vpServoFeatureHealth::FEATURE_ACTIVE:
    return "active";
  case vpServoFeatureHealth::FEATURE_NOT_TRACKED:
    return "not tracked";
  case vpServoFeatureHealth::FEATURE_OUT_OF_IMAGE:
    return "out of image";
  case vpServoFeatureHealth::FEATURE_NOT_FINITE:
    return "not finite";
  case vpServoFeatureHealth::FEATURE_OUTLIER:
    return "outlier";
  }
  return "?";
}

//! What the model-mismatch check's finding of exchanged images means, and the fix.
const char *const kImagesExchanged =
    "the left and right images are exchanged: the acquired markers are where the model predicts them only with the "
    "left image taken for the right one and the converse; give the left camera's image first, as in the "
    "acquisition, to vpFeatureStereoPoint::buildFrom(ipLeft, ipRight); qdot = 0";

const char *statusName(vpServoProjective::vpServoStatus status)
{
  switch (status) {
  case vpServoProjective::SERVO_RUNNING:
    return "SERVO_RUNNING (every feature used)";
  case vpServoProjective::SERVO_REDUCED:
    return "SERVO_REDUCED (some features set aside, every joint still constrained)";
  case vpServoProjective::SERVO_STOPPED:
    return "SERVO_STOPPED (the active features no longer constrain every joint: qdot = 0)";
  case vpServoProjective::SERVO_NO_PLAN:
    return "SERVO_NO_PLAN (path planning found no plan for the target: qdot = 0)";
  case vpServoProjective::SERVO_MODEL_MISMATCH:
    return "SERVO_MODEL_MISMATCH (most features disagree with the model's prediction at the joint readings: "
           "re-register a moved rig, or check the rig mounting, that the readings are the model's joints (their "
           "order, signs and units) and that the left and right images are not swapped; qdot = 0)";
  case vpServoProjective::SERVO_OPEN_LOOP:
    return "SERVO_OPEN_LOOP (too few features seen: the missing ones predicted by the model, the plan followed for at "
           "most setMaxOpenLoopTime())";
  case vpServoProjective::SERVO_ARM_NOT_FOLLOWING:
    return "SERVO_ARM_NOT_FOLLOWING (the arm does not make the commanded joint motion: qdot = 0 until "
           "getArmFollowing().reset(); getReport().getArmFollowing().getDiagnosis() says why)";
  }
  return "?";
}

template <typename Vector> void printVector(std::ostream &os, const Vector &v)
{
  os << "(";
  for (Eigen::Index k = 0; k < static_cast<Eigen::Index>(v.size()); ++k) {
    os << (k > 0 ? ", " : "") << v[k];
  }
  os << ")";
}
} // namespace

void vpServoProjective::print(std::ostream &os) const
{
  // The sections of vpServo::print(vpServo::ALL), in its order and with its titles, then what only this task has.
  const bool computed =
      last().m_data.m_J.rows() == static_cast<Eigen::Index>(4 * m_features.size()) && last().m_data.m_J.rows() > 0;
  const char *const unit = m_errorUnit == ERROR_PIXELS ? "pixels" : "normalised: pixels / f";
  os << "Visual servoing task: non-metric stereo (vpServoProjective)\n";
  os << "Type of control law\n";
  if (m_link.robot == nullptr) {
    os << "Robot: none (setRobot())\n";
  } else {
    os << (m_link.robot->getRigMounting() == vpProjectiveRobot::EYE_IN_HAND ? "Eye-in-hand" : "Eye-to-hand")
       << " configuration\n";
    os << "Control in the articular frame: qdot = -lambda J^+ (s - s*), " << m_link.robot->getNumberOfJoints()
       << " joints, J from the projective model\n";
  }
  os << "List of visual features : s (" << m_features.size() << " stereo points s = (u, v, u', v') (pixels), task "
     << "dimension " << 4 * m_features.size();
  if (computed) {
    os << ", " << m_health.getNumberOfActiveFeatures() << " active at the last computeControlLaw()";
  }
  os << ")\n";
  for (unsigned int i = 0; i < m_features.size(); ++i) {
    os << "  " << i << ": s = ";
    printVector(os, m_features[i]->getFeature());
    os << (m_health.isFeatureTracked(i) ? "" : ", not tracked");
    if (computed) {
      os << "; last state " << stateName(m_health.getFeatureState(i));
      if (m_health.getEpipolarDistance(i) >= 0.0) {
        os << ", epipolar distance " << m_health.getEpipolarDistance(i) << " px";
      }
      if (m_health.getPredictionDistance(i) >= 0.0) {
        os << ", prediction distance " << m_health.getPredictionDistance(i) << " px";
      }
    }
    os << "\n";
  }
  os << "List of desired visual features : s*\n";
  for (unsigned int i = 0; i < m_desired.size(); ++i) {
    os << "  " << i << ": s* = ";
    printVector(os, m_desired[i]->getFeature());
    os << "\n";
  }
  os << "Task Jacobian J (" << unit << " per joint unit; vpServo's interaction matrix Ls)\n";
  if (computed) {
    os << toVisp(last().m_data.m_J / m_control.getErrorScale()) << "\n";
  } else {
    os << "not yet computed\n";
  }
  os << "Error vector (s-s*) (" << unit << ", rows of the features set aside zero)\n";
  if (computed) {
    os << toVispVector(last().m_data.m_e / m_control.getErrorScale()).t() << "\n";
    os << "|e| = " << last().m_data.m_errorNorm << "\n";
  } else {
    os << "not yet computed (No computeControlLaw() yet)\n";
  }
  os << "Gain : " << m_control.getLambda() << " (of "
     << (m_control.getAdaptiveGainInput() == vpServoControlLaw::GAIN_INPUT_ERROR ? "||e||_inf"
                                                                                 : "||J^+ e||_inf, as vpServo");
  if (m_errorUnit == ERROR_NORMALIZED) {
    os << "; f = " << m_control.getErrorScale() << " px" << (m_focalLength > 0.0 ? " given" : " estimated");
  }
  os << ")\n";
  os << "Status and settings\n";
  if (computed) {
    os << "  Status: " << statusName(last().m_status) << "\n";
    if (last().m_status == SERVO_MODEL_MISMATCH && m_mismatch.isImagesExchanged()) {
      os << "  The images: " << kImagesExchanged << "\n";
    } else if (last().m_status == SERVO_MODEL_MISMATCH && m_link.robot != nullptr &&
               m_link.robot->getRigUpdate().getGeneration() == 0) {
      // No re-registration since the acquisition: the model may never have fit, whatever moved.
      os << "  Model never re-registered since its acquisition: if it never fit, check the rig mounting ("
         << (m_link.robot->getRigMounting() == vpProjectiveRobot::EYE_IN_HAND ? "EYE_IN_HAND" : "EYE_TO_HAND")
         << " now; EYE_IN_HAND when the cameras ride on the arm, vpProjectiveAcquisitionProcedure tells it) and the "
            "markers' order; if the rig moved, re-register it\n";
    }
    if (last().m_status == SERVO_ARM_NOT_FOLLOWING) {
      os << "  The arm: " << last().getArmFollowing().getDiagnosis() << "\n";
    }
    os << "  Last step: gain " << last().m_lambda << ", damping " << last().m_damping << ", "
       << (last().m_saturated ? "saturated" : "not saturated") << "\n";
  }
  os << "  Settling: ";
  if (!m_control.getSettling().isEnabled()) {
    os << "off (law (47) with the task's gain)\n";
  } else if (m_control.getSettling().isSettled()) {
    os << "settled for " << m_control.getSettling().getSettledIterations()
       << " calls (gain lambda / (1 + lambda k)), noise " << m_control.getSettling().getNoiseEstimate()
       << " px per row\n";
  } else {
    os << "on, not settled (full gain until the error a joint motion explains is within the noise)\n";
  }
  os << "  Damped least squares: sigma_0 " << m_control.getDampedLeastSquares().getSigmaThreshold() << ", mu_max "
     << m_control.getDampedLeastSquares().getMaxDamping() << " (pixels per joint unit); saturation ";
  if (m_control.getMaxJointVelocity() > 0.0) {
    os << m_control.getMaxJointVelocity() << " joint units per second";
  } else {
    os << "off";
  }
  os << "; pseudo-inverse threshold " << m_control.getDampedLeastSquares().getPseudoInverseThreshold()
     << "; rank tolerance " << m_health.getRankTolerance() << "\n";
  os << "  Feature checks: image window ";
  if (m_health.getImageWidth() > 0) {
    os << m_health.getImageWidth() << " x " << m_health.getImageHeight() << ", border " << m_health.getImageBorder()
       << " px";
  } else {
    os << "off";
  }
  os << "; outlier threshold ";
  if (m_health.getOutlierThreshold() > 0.0) {
    os << m_health.getOutlierThreshold() << " px";
  } else {
    os << "off";
  }
  os << "; model-mismatch threshold ";
  if (m_mismatch.getThreshold() > 0.0) {
    os << m_mismatch.getThreshold() << " px over " << m_mismatch.getConsecutiveIterations()
       << " calls, or the features together beyond their noise (";
    if (m_mismatch.getNoise() > 0.0) {
      os << "learned: " << m_mismatch.getNoise() << " px)";
    } else {
      os << "not learned yet)";
    }
  } else {
    os << "off";
  }
  os << "; arm-following check ";
  if (m_follow.isEnabled()) {
    os << "on (" << m_follow.getConsecutiveCalls() << " calls, period ";
    if (m_follow.getControlPeriod() > 0.0) {
      os << m_follow.getControlPeriod() << " s)";
    } else {
      os << "learned: " << m_follow.getReferenceDuration() << " s)";
    }
  } else {
    os << "off";
  }
  os << "\n";
  os << "  Rig refinement: ";
  if (!m_refinement.isEnabled()) {
    os << "off\n";
  } else {
    os << "on, every " << m_refinement.getPeriod() << " calls, " << m_refinement.getCount()
       << " times after a re-registration";
    if (m_link.modifiable == nullptr) {
      os << " (not with this robot: give it to setRobot() as modifiable)";
    } else if (m_refinement.isActive()) {
      os << "; refining: " << m_refinement.getNumberOfRefinements() << " done, " << m_refinement.getNumberOfFailures()
         << " failed, " << m_refinement.getNumberOfPoints() << " points recorded";
    }
    os << "\n";
  }
  double e0 = 0.0, e1 = 0.0;
  m_control.getJointLimitAvoidance().getLargeProjectionThresholds(e0, e1);
  os << "  Joint limits: ";
  if (m_control.getJointLimitAvoidance().hasJointLimits()) {
    const vpColVector qmin = m_control.getJointLimitAvoidance().getLowerLimits(),
                      qmax = m_control.getJointLimitAvoidance().getUpperLimits();
    os << "qmin ";
    printVector(os, qmin);
    os << ", qmax ";
    printVector(os, qmax);
    os << ", rho " << m_control.getJointLimitAvoidance().getRho() << ", rho1 "
       << m_control.getJointLimitAvoidance().getRho1() << ", lambda_t "
       << m_control.getJointLimitAvoidance().getLambdaTune() << "; large projection thresholds e0 " << e0 << ", e1 "
       << e1 << (m_errorUnit == ERROR_PIXELS ? " px" : " (normalised)");
  } else {
    os << "none";
  }
  os << std::endl;
}

std::string vpServoProjectiveReport::toString(vpServoStatus status)
{
  return statusName(status);
}

void vpProjectiveInternal::noticeServoStatus(const vpServoProjectiveReport &report,
                                             const vpProjectivePathPlanner &planner,
                                             const vpServoModelMismatch &mismatch)
{
  // Once per status kind and process (vpProjectiveNotices): the line is built only when it is printed.
  const vpServoProjectiveReport::vpServoStatus status = report.getStatus();
  if (status == vpServoProjectiveReport::SERVO_RUNNING || !vpProjectiveNotices::isPending(status)) {
    return;
  }
  std::string line = std::string("vpServoProjective: ") + statusName(status);
  if (status == vpServoProjectiveReport::SERVO_MODEL_MISMATCH && mismatch.isImagesExchanged()) {
    line = std::string("vpServoProjective: SERVO_MODEL_MISMATCH (") + kImagesExchanged + ")";
  } else if (status == vpServoProjectiveReport::SERVO_ARM_NOT_FOLLOWING) {
    line += ": " + report.getArmFollowing().getDiagnosis();
  } else if (status == vpServoProjectiveReport::SERVO_NO_PLAN) {
    line += ": " + planner.getDescription();
  }
  vpProjectiveNotices::tell(status, line);
}
