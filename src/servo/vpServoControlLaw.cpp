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

#include <visp3/projective/vpServoControlLaw.h>

#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoControlLaw");

vpServoControlLaw::vpServoControlLaw()
    : m_lambda(0.5), m_gainInput(GAIN_INPUT_ERROR), m_period(1.0), m_qdotMax(0.0), m_errorScale(1.0), m_dls(),
      m_limits(), m_settling()
{
}

void vpServoControlLaw::setLambda(double lambda)
{
  m_lambda.initFromConstant(positive(lambda, at("setLambda()"), "the gain", "per second, law (47)'s lambda"));
}

void vpServoControlLaw::setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero)
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

void vpServoControlLaw::setAdaptiveGainInput(vpGainInput input)
{
  if (input != GAIN_INPUT_ERROR && input != GAIN_INPUT_JOINT_VELOCITY) {
    fail(vpProjectiveException::invalidValueError, at("setAdaptiveGainInput()"),
         "unknown input; use GAIN_INPUT_ERROR or GAIN_INPUT_JOINT_VELOCITY");
  }
  m_gainInput = input;
}

void vpServoControlLaw::setControlPeriod(double seconds)
{
  if (!std::isfinite(seconds) || !(seconds > 0.0)) {
    fail(vpProjectiveException::invalidValueError, at("setControlPeriod()"),
         "the control period is the time between two calls of computeControlLaw(), in seconds: positive and finite");
  }
  // Inside, the law works per step (a joint step, as the planner's paths and rehearsals do); the user's gain and
  // saturation are per second.
  m_dls.setMaxJointVelocity(m_qdotMax * seconds);
  m_period = seconds;
}

void vpServoControlLaw::setMaxJointVelocity(double qdotMax)
{
  m_dls.setMaxJointVelocity(qdotMax * m_period); // throws on a bad value, before anything changes
  m_qdotMax = qdotMax;
}

void vpServoControlLaw::setErrorScale(double pixelsPerUnit)
{
  m_errorScale = nonNegative(pixelsPerUnit, at("setErrorScale()"), "the error scale",
                             "pixels per unit of the error (1 for pixels; 0 while unknown)");
}

double vpServoControlLaw::gain(const vpServoNormalEquations &ne, double errorInf) const
{
  if (m_gainInput == GAIN_INPUT_ERROR) {
    return m_period * m_lambda.value_const(errorInf / m_errorScale);
  }
  // vpServo's e1 = J^+ e: the Gauss-Newton step (full column rank here: J^T J is invertible unless the task is
  // singular, then the gain at infinity).
  const JointVector &e1 = ne.getGaussNewtonStep();
  const double x = e1.allFinite() ? e1.cwiseAbs().maxCoeff() : std::numeric_limits<double>::infinity();
  return m_period * m_lambda.value_const(x);
}

bool vpServoControlLaw::addJointLimitAvoidance(const JointVector &q, const vpServoNormalEquations &ne, double errorNorm,
                                               JointVector &qdot, JointVector &qdot2, const JointVector *target) const
{
  qdot2.setZero(q.size());
  if (!m_limits.hasJointLimits()) {
    return false;
  }
  m_limits.computeVelocity(q, qdot, ne, errorNorm, m_dls, qdot2, target);
  qdot += qdot2;
  return m_dls.saturate(qdot);
}

double vpServoControlLaw::computeStep(const JointVector &q, const vpServoNormalEquations &ne, double errorInf,
                                      double errorNorm, JointVector &qdot, JointVector &qdot2)
{
  const double lambda = gain(ne, errorInf);
  computePrimaryStep(ne, lambda, qdot);
  addJointLimitAvoidance(q, ne, errorNorm, qdot, qdot2);
  return lambda;
}

void vpServoControlLaw::keepInside(const JointVector &q, const vpServoNormalEquations &ne, double lambda,
                                   JointVector &qdot) const
{
  // Scaling the whole step down to land a joint on its limit stops every joint once one is there and the law still
  // pushes it outward (a target near a limit, the law's course bending to it): the task stalls, pixels from its goal,
  // with every other joint free. Instead, each joint that would cross is held (its column out of the task: the law
  // solved again with the others), until no joint crosses; the scaling is left for the rest (a joint already beyond
  // its limit).
  JointMatrix JtJ = ne.getJtJ();
  JointVector Jte = ne.getJte(), alone;
  vpServoNormalEquations held;
  vpServoDampedLeastSquares law = m_dls; // computeVelocity() writes its report: the step's stays the first law's
  const Eigen::Index n = q.size();
  for (Eigen::Index pass = 0; pass < n && m_limits.stepInside(q, qdot) < 1.0; ++pass) {
    const double scale = JtJ.diagonal().cwiseAbs().maxCoeff();
    bool holding = false;
    for (Eigen::Index i = 0; i < n; ++i) {
      alone.setZero(n);
      alone(i) = qdot(i);
      if (m_limits.stepInside(q, alone) < 1.0) {
        JtJ.row(i).setZero();
        JtJ.col(i).setZero();
        JtJ(i, i) = scale > 0.0 ? scale : 1.0;
        Jte(i) = 0.0;
        holding = true;
      }
    }
    if (!holding) {
      break;
    }
    held.set(JtJ, Jte);
    law.computeVelocity(held, lambda, qdot);
    law.saturate(qdot);
  }
  qdot *= m_limits.stepInside(q, qdot);
}
