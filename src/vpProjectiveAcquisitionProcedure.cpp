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

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
std::string at(const char *method)
{
  return std::string("vpProjectiveAcquisitionProcedure::") + method;
}

void checkPerJoint(const vpColVector &v, bool allowZero, const char *method, const char *name)
{
  for (unsigned int i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                  at(method) + ": " + name + " has a non-finite value: give finite values.");
    }
    if (v[i] < 0.0 || (!allowZero && v[i] == 0.0)) {
      throw vpProjectiveException(
          vpProjectiveException::invalidValueError,
          at(method) + ": " + name + "[" + std::to_string(i) + "] = " + std::to_string(v[i]) +
              (allowZero ? " is negative: give values >= 0." : " is not positive: give values > 0."));
    }
  }
}

void checkScalar(double x, const char *method, const char *name)
{
  if (!std::isfinite(x) || x < 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at(method) + ": " + name + " must be finite and >= 0.");
  }
}
} // namespace

vpProjectiveAcquisitionProcedure::vpProjectiveAcquisitionProcedure(const vpImageSource &source, unsigned int width,
                                                                   unsigned int height)
    : m_source(source), m_width(width), m_height(height), m_maxAmounts(), m_steps(), m_minAmounts(), m_qmin(), m_qmax(),
      m_limitMargin(0.0), m_imageMargin(10.0), m_rotationSpeed(0.0), m_translationSpeed(0.0), m_epipolarThreshold(2.0),
      m_os(nullptr), m_callback(), m_motion(), m_reports(), m_residual(0.0)
{
  if (!m_source) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("constructor") +
                                    ": the image source is empty: give a function returning the images.");
  }
  setImageSize(width, height);
}

void vpProjectiveAcquisitionProcedure::setMaxAmounts(const vpColVector &amounts)
{
  checkPerJoint(amounts, false, "setMaxAmounts", "amounts");
  m_maxAmounts = amounts;
}

void vpProjectiveAcquisitionProcedure::setSteps(const vpColVector &steps)
{
  checkPerJoint(steps, false, "setSteps", "steps");
  m_steps = steps;
}

void vpProjectiveAcquisitionProcedure::setMinAmounts(const vpColVector &amounts)
{
  checkPerJoint(amounts, true, "setMinAmounts", "amounts");
  m_minAmounts = amounts;
}

void vpProjectiveAcquisitionProcedure::setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double margin)
{
  if (qmin.size() != qmax.size()) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                at("setJointLimits") +
                                    ": qmin and qmax have different sizes: give one value per joint.");
  }
  checkScalar(margin, "setJointLimits", "margin");
  for (unsigned int i = 0; i < qmin.size(); ++i) {
    if (!std::isfinite(qmin[i]) || !std::isfinite(qmax[i])) {
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                  at("setJointLimits") + ": a limit is not finite: give finite limits.");
    }
    if (qmin[i] + 2.0 * margin >= qmax[i]) {
      throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                  at("setJointLimits") + ": joint " + std::to_string(i) +
                                      " has qmin + 2 margin >= qmax: give qmin < qmax and a smaller margin.");
    }
  }
  m_qmin = qmin;
  m_qmax = qmax;
  m_limitMargin = margin;
}

void vpProjectiveAcquisitionProcedure::setImageMargin(double pixels)
{
  checkScalar(pixels, "setImageMargin", "the margin");
  m_imageMargin = pixels;
}

void vpProjectiveAcquisitionProcedure::setImageSize(unsigned int width, unsigned int height)
{
  if (width == 0 || height == 0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("setImageSize") + ": an image size is 0: give the cameras' size in pixels.");
  }
  m_width = width;
  m_height = height;
}

void vpProjectiveAcquisitionProcedure::setSpeed(double rotation, double translation)
{
  checkScalar(rotation, "setSpeed", "the rotation speed");
  checkScalar(translation, "setSpeed", "the translation speed");
  m_rotationSpeed = rotation;
  m_translationSpeed = translation;
}

void vpProjectiveAcquisitionProcedure::setEpipolarThreshold(double pixels)
{
  if (!std::isfinite(pixels) || pixels <= 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("setEpipolarThreshold") + ": the threshold must be finite and > 0 (pixels).");
  }
  m_epipolarThreshold = pixels;
}

std::string vpProjectiveAcquisitionProcedure::toString(vpStopReason reason)
{
  switch (reason) {
  case AMOUNT_REACHED:
    return "amount";
  case IMAGE_BORDER:
    return "image border";
  case MARKER_LOST:
    return "marker lost";
  default:
    return "joint limit";
  }
}

bool vpProjectiveAcquisitionProcedure::inside(const std::vector<vpImagePoint> &left,
                                              const std::vector<vpImagePoint> &right) const
{
  for (const std::vector<vpImagePoint> *image : {&left, &right}) {
    for (const vpImagePoint &p : *image) {
      if (!std::isfinite(p.get_u()) || !std::isfinite(p.get_v()) || p.get_u() < m_imageMargin ||
          p.get_v() < m_imageMargin || p.get_u() > m_width - 1.0 - m_imageMargin ||
          p.get_v() > m_height - 1.0 - m_imageMargin) {
        return false;
      }
    }
  }
  return true;
}

double vpProjectiveAcquisitionProcedure::amountOf(const vpColVector &v, unsigned int i, double fallback) const
{
  return v.size() == 0 ? fallback : v[i];
}

void vpProjectiveAcquisitionProcedure::moveTo(vpRobot &robot, const vpColVector &q) const
{
  if (m_motion) {
    m_motion(robot, q);
  } else {
    robot.setPosition(vpRobot::ARTICULAR_FRAME, q);
  }
}

void vpProjectiveAcquisitionProcedure::moveJoint(vpRobot &robot, const vpColVector &qRef, unsigned int i, int sign,
                                                 double &amount, vpStopReason &reason, vpColVector &qReached,
                                                 std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right,
                                                 std::vector<vpImagePoint> &allLeft,
                                                 std::vector<vpImagePoint> &allRight)
{
  const double maxAmount = amountOf(m_maxAmounts, i, vpMath::rad(30.0));
  const double step = amountOf(m_steps, i, vpMath::rad(1.0));
  amount = 0.0;
  reason = AMOUNT_REACHED;
  std::vector<vpImagePoint> l, r;
  while (amount < maxAmount) {
    const double next = std::min(maxAmount, amount + step);
    vpColVector q = qRef;
    q[i] = qRef[i] + sign * next;
    if (m_qmin.size() != 0 && (q[i] < m_qmin[i] + m_limitMargin || q[i] > m_qmax[i] - m_limitMargin)) {
      reason = JOINT_LIMIT;
      break;
    }
    moveTo(robot, q);
    vpColVector reading;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, reading);
    if (!m_source(l, r)) {
      reason = MARKER_LOST;
      break;
    }
    if (m_callback) {
      m_callback(i, q, l, r);
    }
    if (!inside(l, r)) {
      reason = IMAGE_BORDER;
      break;
    }
    amount = next;
    qReached = reading;
    left = l;
    right = r;
    allLeft.insert(allLeft.end(), l.begin(), l.end());
    allRight.insert(allRight.end(), r.begin(), r.end());
  }
}

vpProjectiveArmModel vpProjectiveAcquisitionProcedure::run(vpRobot &robot, vpProjectiveArmAcquisition &acquisition)
{
  if (!m_motion) {
    robot.setRobotState(vpRobot::STATE_POSITION_CONTROL);
  }
  if (m_rotationSpeed > 0.0) {
    robot.setMaxRotationVelocity(m_rotationSpeed);
  }
  if (m_translationSpeed > 0.0) {
    robot.setMaxTranslationVelocity(m_translationSpeed);
  }
  vpColVector qRef;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, qRef);
  const unsigned int n = qRef.size();
  for (const vpColVector *v : {&m_maxAmounts, &m_steps, &m_minAmounts, &m_qmin}) {
    if (v->size() != 0 && v->size() != n) {
      throw vpProjectiveException(vpProjectiveException::dimensionError,
                                  at("run") + ": a per-joint setting has " + std::to_string(v->size()) +
                                      " values, the robot has " + std::to_string(n) + " joints: give one per joint.");
    }
  }
  if (acquisition.getNumberOfJoints() != n) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                at("run") + ": the acquisition has " + std::to_string(acquisition.getNumberOfJoints()) +
                                    " joints, the robot " + std::to_string(n) + ": give the robot's joint types.");
  }
  std::vector<vpImagePoint> left, right;
  if (!m_source(left, right) || left.size() != right.size() || !inside(left, right)) {
    throw vpProjectiveException(vpProjectiveException::notEnoughPointsError,
                                at("run") + ": the markers are not all tracked inside the images at the zero "
                                            "reference: place the arm so that they are, then run again.");
  }
  // With a known rig the zero reference is checked before the arm moves; without one, once the rig is estimated.
  const bool rigKnown = acquisition.getStereoRig().isInitialized();
  vpProjectiveArmAcquisition work = acquisition;
  if (rigKnown) {
    work.setZeroReference(qRef, left, right);
  }
  struct Trial {
    vpColVector q;
    std::vector<vpImagePoint> left, right;
  };
  std::vector<Trial> trials;
  std::vector<vpImagePoint> allLeft = left, allRight = right; // every pair seen inside the margins, for the rig
  std::vector<vpJointReport> reports(n);
  try {
    for (unsigned int i = 0; i < n; ++i) {
      vpJointReport &report = reports[i];
      report.trials = 0;
      for (int sign = -1; sign <= 1; sign += 2) {
        double amount = 0.0;
        vpStopReason reason = AMOUNT_REACHED;
        Trial trial;
        moveJoint(robot, qRef, i, sign, amount, reason, trial.q, trial.left, trial.right, allLeft, allRight);
        (sign < 0 ? report.amountNegative : report.amountPositive) = amount;
        (sign < 0 ? report.stopNegative : report.stopPositive) = reason;
        if (amount > 0.0) {
          trials.push_back(trial); // the encoders' readings, as the model will take them
          ++report.trials;
        }
      }
      moveTo(robot, qRef);
      const double minAmount = amountOf(m_minAmounts, i, vpMath::rad(5.0));
      const bool revolute = acquisition.getJointTypes()[i] == vpProjectiveJoint::REVOLUTE;
      const double unit = revolute ? vpMath::deg(1.0) : 1.0;
      if (m_os) {
        *m_os << "joint " << i << ": -" << report.amountNegative * unit << " (" << toString(report.stopNegative)
              << "), +" << report.amountPositive * unit << " (" << toString(report.stopPositive) << ") "
              << (revolute ? "deg" : "m") << ", " << report.trials << " trials" << std::endl;
      }
      if (std::max(report.amountNegative, report.amountPositive) < minAmount) {
        std::ostringstream os;
        os << at("run") << ": joint " << i << " moved only -" << report.amountNegative * unit << " ("
           << toString(report.stopNegative) << ") and +" << report.amountPositive * unit << " ("
           << toString(report.stopPositive) << ") " << (revolute ? "deg" : "m") << ", less than the minimum "
           << minAmount * unit << ": move the arm so that the markers are nearer the image centre and the joint "
           << "away from its limits, or lower the image margin or the minimum amount.";
        throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
      }
    }
    if (!rigKnown) {
      vpProjectiveStereoRig rig;
      rig.estimate(allLeft, allRight, m_epipolarThreshold);
      work.setStereoRig(rig);
      work.setZeroReference(qRef, left, right);
    }
    for (const Trial &trial : trials) {
      work.addTrialMotion(trial.q, trial.left, trial.right);
    }
    vpProjectiveArmModel model = work.calibrate();
    acquisition = work;
    m_reports = reports;
    m_residual = work.getCalibrationResidual();
    return model;
  } catch (...) {
    moveTo(robot, qRef);
    throw;
  }
}

void vpProjectiveAcquisitionProcedure::run(vpRobot &robot, vpProjectiveRobot &projectiveRobot)
{
  vpProjectiveArmAcquisition acquisition = projectiveRobot.m_acquisition;
  const vpProjectiveStereoRig &rig = projectiveRobot.getStereoRig(); // once calibrated, the model's (updateRig())
  if (rig.isInitialized()) {
    acquisition.setStereoRig(rig);
  }
  const vpProjectiveArmModel model = run(robot, acquisition);
  projectiveRobot.adopt(acquisition, model, m_residual, acquisition.getAlgebraicResidual());
}
