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
  The settings of a vpServoProjective task (gain, error unit, law, checks, joint limits, settling) and its link to the
  robot (setRobot(): the robot tells the task of a new model or rig).
*/

#include <visp3/projective/vpServoProjective.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "core/vpJointUnits.h"
#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoProjective"); // const: internal linkage, as in vpServoProjective.cpp

namespace
{
//! The mean focal length sqrt(px py) (pixels) of the two cameras of the model's metric self-calibration.
double estimatedFocalLength(const vpProjectiveRobot &robot, const std::string &where)
{
  vpMatrix Kl, Kr;
  vpHomogeneousMatrix lMr;
  try {
    robot.getMetricStereoRig(Kl, Kr, lMr);
  } catch (const vpException &e) {
    fail(vpProjectiveException::estimationFailedError, where,
         std::string("the model's metric self-calibration gives no focal length (") + e.getStringMessage() +
             "); give it: setErrorUnit(ERROR_NORMALIZED, f) with f in pixels");
  }
  const double fl = std::sqrt(std::abs(Kl[0][0] * Kl[1][1])), fr = std::sqrt(std::abs(Kr[0][0] * Kr[1][1]));
  const double f = 0.5 * (fl + fr);
  if (!std::isfinite(f) || !(f > 0.0)) {
    fail(vpProjectiveException::estimationFailedError, where,
         "the model's metric self-calibration gives no finite focal length; give it: setErrorUnit(ERROR_NORMALIZED, "
         "f) with f in pixels");
  }
  return f;
}
} // namespace

void vpServoProjective::setErrorUnit(vpErrorUnit unit, double focalLength)
{
  const std::string where = at("setErrorUnit()");
  requireFinite(focalLength, where, "the focal length");
  if (focalLength < 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the focal length must be positive (pixels), or 0 to estimate it from the model");
  }
  if (unit != ERROR_PIXELS && unit != ERROR_NORMALIZED) {
    fail(vpProjectiveException::invalidValueError, where, "unknown unit; use ERROR_PIXELS or ERROR_NORMALIZED");
  }
  double scale = 1.0;
  if (unit == ERROR_NORMALIZED) {
    scale = focalLength;
    if (focalLength == 0.0 && m_link.robot != nullptr) {
      scale = estimatedFocalLength(*m_link.robot, where);
    }
  }
  m_errorUnit = unit;
  m_focalLength = focalLength;
  m_control.setErrorScale(scale);                     // 0 until setRobot() estimates it
  m_iterations[m_lastIteration].m_errorScale = scale; // the report's getters follow the unit
}

void vpServoProjective::setRobot(const vpProjectiveRobot &robot)
{
  if (!robot.isCalibrated()) {
    fail(vpProjectiveException::notInitializedError, at("setRobot()"),
         "the robot model is not acquired; call calibrate() or loadModel() on it first");
  }
  if (m_errorUnit == ERROR_NORMALIZED && m_focalLength == 0.0) {
    const double scale = estimatedFocalLength(robot, at("setRobot()")); // before anything changes
    m_control.setErrorScale(scale);
    m_iterations[m_lastIteration].m_errorScale = scale;
  }
  if (m_link.robot != &robot) {
    m_mismatch.reset(); // memories of another robot's model
  }
  m_follow.reset();   // another arm (or the same, set again after the user fixed it)
  m_link.set(&robot); // the robot now tells this task of a new model or rig
  m_link.modifiable = nullptr;
  for (vpTarget &t : m_targets) {
    t.valid = false; // another robot's frame: take the user's s* anew
  }
  m_refinement.stop(); // only a re-registration from now on starts a refinement
  m_rigUpdatesSeen = robot.getRigUpdate().getUpdateCount();
}

void vpServoProjective::setRobot(vpProjectiveRobot &robot)
{
  setRobot(static_cast<const vpProjectiveRobot &>(robot));
  m_link.modifiable = &robot;
}

vpServoProjective::vpRobotLink::vpRobotLink(const vpRobotLink &other)
    : vpProjectiveRobot::vpListener(), robot(nullptr), modifiable(nullptr), modelChanged(other.modelChanged),
      rigChanged(other.rigChanged)
{
  set(other.robot); // a copied task is attached too
  modifiable = other.modifiable;
}

vpServoProjective::vpRobotLink &vpServoProjective::vpRobotLink::operator=(const vpRobotLink &other)
{
  if (this != &other) {
    set(other.robot);
    modifiable = other.modifiable;
    modelChanged = other.modelChanged;
    rigChanged = other.rigChanged;
  }
  return *this;
}

vpServoProjective::vpRobotLink::~vpRobotLink()
{
  set(nullptr);
}

void vpServoProjective::vpRobotLink::set(const vpProjectiveRobot *r)
{
  if (robot != r && robot != nullptr) {
    detachFrom(*robot);
  }
  if (r != nullptr) {
    attachTo(*r);
  }
  robot = r;
}

void vpServoProjective::vpRobotLink::robotModelChanged(bool rigOnly)
{
  (rigOnly ? rigChanged : modelChanged) = true;
}

void vpServoProjective::setLambda(double lambda)
{
  m_control.setLambda(lambda);
}

void vpServoProjective::setLambda(const vpAdaptiveGain &lambda)
{
  m_control.setLambda(lambda);
}

void vpServoProjective::setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero)
{
  m_control.setLambda(gainAtZero, gainAtInfinity, slopeAtZero);
}

void vpServoProjective::setControlPeriod(double seconds)
{
  m_control.setControlPeriod(seconds); // throws on a bad value, before anything changes
  m_follow.setControlPeriod(seconds);  // the arm's motion per call is judged against it
}

void vpServoProjective::setImageSize(unsigned int width, unsigned int height, double border)
{
  m_health.setImageSize(width, height, border);
}

void vpServoProjective::checkFeatureIndex(unsigned int i, const char *method) const
{
  if (i >= m_features.size()) {
    std::ostringstream os;
    os << "feature index " << i << " is out of range; the task has " << m_features.size()
       << " features (indices in addFeature() order, from 0)";
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
}

void vpServoProjective::setFeatureTracked(unsigned int i, bool tracked)
{
  checkFeatureIndex(i, "setFeatureTracked()");
  m_health.setFeatureTracked(i, tracked);
}

void vpServoProjective::setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double rho, double rho1,
                                       double lambdaTune)
{
  vpServoJointLimitAvoidance limits =
      m_control.getJointLimitAvoidance(); // validated aside: a failed call changes nothing
  limits.setJointLimits(qmin, qmax, rho, rho1, lambdaTune);
  if (m_link.robot != nullptr && limits.getNumberOfJoints() != m_link.robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << "qmin and qmax have " << limits.getNumberOfJoints() << " entries but the robot has "
       << m_link.robot->getNumberOfJoints() << " joints";
    fail(vpProjectiveException::dimensionError, at("setJointLimits()"), os.str());
  }
  // Radians and metres: a revolute joint's limit beyond 2 pi, or any beyond 10, is probably in degrees or millimetres.
  std::vector<bool> revolute;
  for (unsigned int i = 0; m_link.robot != nullptr && i < m_link.robot->getNumberOfJoints(); ++i) {
    if (m_link.robot->isCalibrated() || m_link.robot->getAcquisition().hasDeclaredJointTypes()) {
      revolute.push_back(m_link.robot->getJointType(i) == vpProjectiveRobot::REVOLUTE);
    }
  }
  requireJointUnits(qmin, revolute, at("setJointLimits()"), "qmin");
  requireJointUnits(qmax, revolute, at("setJointLimits()"), "qmax");
  m_control.getJointLimitAvoidance() = limits;
}

void vpServoProjective::setSettling(bool settling)
{
  vpServoSettling &settling_ = m_control.getSettling();
  settling_.setEnabled(settling, settling_.getHorizon());
}
