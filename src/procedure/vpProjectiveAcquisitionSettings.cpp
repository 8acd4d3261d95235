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
  vpProjectiveAcquisitionProcedure: its constructors, settings (each checked, the object unchanged on an error) and
  the names of its stop reasons.
*/

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>

#include <visp3/projective/vpProjectiveException.h>

#include "acquisition/vpProjectiveAcquisitionInternal.h"
#include "core/vpJointUnits.h"

using namespace vpProjectiveAcquisitionInternal;

namespace
{
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
  // Beyond 10: neither radians nor metres; run() refuses a revolute joint's above 2 pi once it knows the types.
  vpProjectiveInternal::requireJointUnits(v, std::vector<bool>(), at(method), name);
}

void checkScalar(double x, const char *method, const char *name)
{
  if (!std::isfinite(x) || x < 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at(method) + ": " + name + " must be finite and >= 0.");
  }
}

void checkPositive(double x, const char *method, const char *name)
{
  if (!std::isfinite(x) || x <= 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at(method) + ": " + name + " must be finite and > 0.");
  }
}
} // namespace

vpProjectiveAcquisitionProcedure::vpProjectiveAcquisitionProcedure(const vpImageSource &source, unsigned int width,
                                                                   unsigned int height)
    : m_source(source), m_idSource(), m_identified(false), m_minVisibility(0.5), m_refIds(), m_modelIds(), m_dropped(),
      m_width(width), m_height(height), m_maxAmounts(), m_steps(), m_minAmounts(), m_qmin(), m_qmax(),
      m_limitMargin(0.0), m_imageMargin(10.0), m_rotationSpeed(0.0), m_translationSpeed(0.0), m_epipolarThreshold(2.0),
      m_control(VELOCITY_CONTROL), m_moveTimeout(0.0), m_minTolerance(1e-5), m_tolerance(1e-5), m_coplanarity(2.0),
      m_detectMounting(true), m_os(&std::cout), m_callback(), m_motion(), m_reports(), m_mountingReport(),
      m_residual(0.0), m_parallax(-1.0), m_commandPeriod(0.0), m_wallPeriod(0.0), m_types(), m_lower(), m_upper(),
      m_encoderNoise()
{
  if (!m_source) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("constructor") +
                                    ": the image source is empty: give a function returning the images.");
  }
  setImageSize(width, height);
  m_mountingReport.checked = false;
  m_mountingReport.set = m_mountingReport.kept = vpProjectiveArmModel::EYE_TO_HAND;
  m_mountingReport.residual = m_mountingReport.otherResidual = -1.0;
  m_mountingReport.separation = 0.0;
}

vpProjectiveAcquisitionProcedure::vpProjectiveAcquisitionProcedure(const vpIdentifiedImageSource &source,
                                                                   unsigned int width, unsigned int height, bool)
    : vpProjectiveAcquisitionProcedure(
          source ? vpImageSource([](std::vector<vpImagePoint> &, std::vector<vpImagePoint> &) { return false; })
                 : vpImageSource(),
          width, height)
{
  m_idSource = source;
  m_identified = true;
}

void vpProjectiveAcquisitionProcedure::setMinMarkerVisibility(double fraction)
{
  if (!(fraction >= 0.0 && fraction <= 1.0)) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("setMinMarkerVisibility") + ": the fraction must be in [0, 1].");
  }
  m_minVisibility = fraction;
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
  // Beyond 10: neither radians nor metres; run() refuses a revolute joint's beyond 2 pi once it knows the types.
  vpProjectiveInternal::requireJointUnits(qmin, std::vector<bool>(), at("setJointLimits"), "lower limit");
  vpProjectiveInternal::requireJointUnits(qmax, std::vector<bool>(), at("setJointLimits"), "upper limit");
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

void vpProjectiveAcquisitionProcedure::setMotionControl(vpMotionControl control)
{
  if (control != VELOCITY_CONTROL && control != POSITION_CONTROL) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("setMotionControl") + ": give VELOCITY_CONTROL or POSITION_CONTROL.");
  }
  m_control = control;
}

void vpProjectiveAcquisitionProcedure::setMoveTimeout(double secondsAllowed)
{
  checkScalar(secondsAllowed, "setMoveTimeout", "the timeout (0: automatic)");
  m_moveTimeout = secondsAllowed;
}

void vpProjectiveAcquisitionProcedure::setArrivalTolerance(double tolerance)
{
  checkPositive(tolerance, "setArrivalTolerance", "the tolerance (rad or m)");
  m_minTolerance = tolerance;
}

void vpProjectiveAcquisitionProcedure::setCoplanarityThreshold(double pixels)
{
  checkPositive(pixels, "setCoplanarityThreshold", "the threshold (pixels)");
  m_coplanarity = pixels;
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

double vpProjectiveAcquisitionProcedure::byType(unsigned int i, double revolute, double prismatic, double unknown) const
{
  if (!m_typesKnown) {
    return unknown;
  }
  return m_types[i] == vpProjectiveJoint::REVOLUTE ? revolute : prismatic;
}

std::string vpProjectiveAcquisitionProcedure::valueText(double v, unsigned int i) const
{
  if (m_typesKnown) {
    return jointValue(v, m_types[i] == vpProjectiveJoint::REVOLUTE);
  }
  std::ostringstream os;
  os << std::setprecision(6) << v << " (rad or m)";
  return os.str();
}

void vpProjectiveAcquisitionProcedure::checkUnits() const
{
  std::vector<bool> revolute;
  for (unsigned int i = 0; m_typesKnown && i < m_types.size(); ++i) {
    revolute.push_back(m_types[i] == vpProjectiveJoint::REVOLUTE);
  }
  using vpProjectiveInternal::requireJointUnits;
  requireJointUnits(m_qmin, revolute, at("run") + " (setJointLimits())", "lower limit");
  requireJointUnits(m_qmax, revolute, at("run") + " (setJointLimits())", "upper limit");
  requireJointUnits(m_maxAmounts, revolute, at("run") + " (setMaxAmounts())", "largest amount");
  requireJointUnits(m_steps, revolute, at("run") + " (setSteps())", "step");
  requireJointUnits(m_minAmounts, revolute, at("run") + " (setMinAmounts())", "smallest amount");
}
