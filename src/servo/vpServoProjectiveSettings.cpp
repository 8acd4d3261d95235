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

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

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

void vpServoProjective::setAdaptiveGainInput(vpGainInput input)
{
  if (input != GAIN_INPUT_ERROR && input != GAIN_INPUT_JOINT_VELOCITY) {
    fail(vpProjectiveException::invalidValueError, at("setAdaptiveGainInput()"),
         "unknown input; use GAIN_INPUT_ERROR or GAIN_INPUT_JOINT_VELOCITY");
  }
  m_gainInput = input;
}

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
  m_errorScale = scale;                               // 0 until setRobot() estimates it
  m_iterations[m_lastIteration].m_errorScale = scale; // the report's getters follow the unit
}

void vpServoProjective::setRobot(const vpProjectiveRobot &robot)
{
  if (!robot.isCalibrated()) {
    fail(vpProjectiveException::notInitializedError, at("setRobot()"),
         "the robot model is not acquired; call calibrate() or loadModel() on it first");
  }
  if (m_errorUnit == ERROR_NORMALIZED && m_focalLength == 0.0) {
    m_errorScale = estimatedFocalLength(robot, at("setRobot()")); // before anything changes
    m_iterations[m_lastIteration].m_errorScale = m_errorScale;
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
  const std::string where = at("setLambda()");
  requireFinite(lambda, where, "the gain");
  if (!(lambda > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where, "the gain must be positive");
  }
  m_lambda.initFromConstant(lambda);
}

void vpServoProjective::setLambda(const vpAdaptiveGain &lambda)
{
  m_lambda = lambda;
}

void vpServoProjective::setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero)
{
  const std::string where = at("setLambda()");
  requireFinite(gainAtZero, where, "the gain at zero");
  requireFinite(gainAtInfinity, where, "the gain at infinity");
  requireFinite(slopeAtZero, where, "the slope at zero");
  if (!(gainAtZero > 0.0) || !(gainAtInfinity > 0.0) || !(gainAtZero >= gainAtInfinity) || slopeAtZero < 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "an adaptive gain needs gainAtZero >= gainAtInfinity > 0 and a non-negative slope");
  }
  m_lambda.initStandard(gainAtZero, gainAtInfinity, slopeAtZero);
}

void vpServoProjective::setDamping(double sigmaThreshold, double maxDamping)
{
  m_law.setDamping(sigmaThreshold, maxDamping);
}

void vpServoProjective::setMaxJointVelocity(double qdotMax)
{
  m_law.setMaxJointVelocity(qdotMax * m_period); // throws on a bad value, before anything changes
  m_qdotMax = qdotMax;
}

void vpServoProjective::setControlPeriod(double seconds)
{
  if (!std::isfinite(seconds) || !(seconds > 0.0)) {
    fail(vpProjectiveException::invalidValueError, at("setControlPeriod()"),
         "the control period is the time between two calls of computeControlLaw(), in seconds: positive and finite");
  }
  // Inside, the law works per call (a joint step, as the planner's paths and rehearsals do); the user's gain and
  // saturation are per second.
  m_law.setMaxJointVelocity(m_qdotMax * seconds);
  m_follow.setControlPeriod(seconds); // the arm's motion per call is judged against it
  m_period = seconds;
}

void vpServoProjective::setMaxOpenLoopTime(double seconds)
{
  m_maxOpenLoopTime = nonNegative(seconds, at("setMaxOpenLoopTime()"), "the longest open loop on the model",
                                  "seconds of consecutive calls; 0 stops the task as soon as the features are too few");
}

void vpServoProjective::setPseudoInverseThreshold(double threshold)
{
  m_law.setPseudoInverseThreshold(threshold);
}

void vpServoProjective::setRankTolerance(double tolerance)
{
  const std::string where = at("setRankTolerance()");
  requireFinite(tolerance, where, "the rank tolerance");
  if (!(tolerance > 0.0) || !(tolerance < 1.0)) {
    fail(vpProjectiveException::invalidValueError, where,
         "the rank tolerance is a ratio of singular values and must be in (0, 1), e.g. 1e-6");
  }
  m_rankTolerance = tolerance;
  m_iterations[m_lastIteration].m_rankTolerance = tolerance;
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

void vpServoProjective::setOutlierThreshold(double pixels)
{
  m_health.setOutlierThreshold(pixels);
}

void vpServoProjective::setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double rho, double rho1,
                                       double lambdaTune)
{
  vpServoJointLimitAvoidance limits = m_jointLimits; // validated aside: a failed call changes nothing
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
  m_jointLimits = limits;
}

void vpServoProjective::clearJointLimits()
{
  m_jointLimits.clearJointLimits();
}

void vpServoProjective::setSettling(bool settling)
{
  m_settling.setEnabled(settling, m_settling.getHorizon());
}

void vpServoProjective::setRigRefinement(bool refine, unsigned int period, unsigned int refinements)
{
  m_refinement.setRefinement(refine, period, refinements);
}

double vpServoProjective::taskGain(const vpAdaptiveGain &lambda, vpGainInput input, double errorScale,
                                   const JointMatrix &JtJ, const JointVector &Jte, double errorInf)
{
  if (input == GAIN_INPUT_ERROR) {
    return lambda.value_const(errorInf / errorScale);
  }
  // vpServo's e1 = J^+ e (full column rank here: J^T J is invertible unless the task is singular, then the gain at
  // infinity); fixed-size storage, no allocation.
  const Eigen::LDLT<JointMatrix> ldlt(JtJ);
  const JointVector e1 = ldlt.solve(Jte);
  const double x = e1.allFinite() && ldlt.info() == Eigen::Success ? e1.cwiseAbs().maxCoeff()
                                                                   : std::numeric_limits<double>::infinity();
  return lambda.value_const(x);
}
