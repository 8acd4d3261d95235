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
  vpProjectivePathPlanner: its constructor and settings (each checked, the planner unchanged on an error).
*/

#include <visp3/projective/vpProjectivePathPlanner.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveInverseKinematics.h>

#include "core/vpProjectiveErrors.h"
#include "servo/vpProjectivePathPlannerInternal.h"

using namespace vpProjectiveInternal;

vpProjectivePathPlanner::vpProjectivePathPlanner()
    : m_groups(), m_minGroupArea(0.3), m_groupArea(), m_groupsOn(true), m_hasLimits(false), m_qmin(), m_qmax(),
      m_width(0), m_height(0), m_border(0.0), m_maxStep(M_PI / 36.0), m_maxExcursion(-1.0), m_starts(24),
      m_maxResidual(5.0), m_followGain(1.0), m_maxOpenLoopTime(2.0), m_refused(), m_refusedRadius(0.0),
      m_limitMargin(0.0), m_front(), m_points(), m_sStar(), m_hasLaw(false), m_law(), m_rehearsalBudget(50),
      m_rehearsalOk(false), m_rehearsalIterations(0), m_rehearsalResidual(-1.0), m_rehearsalSlow(false),
      m_status(PLAN_NONE), m_branches(), m_residuals(), m_branch(0), m_target(), m_path(), m_features(),
      m_kind(PATH_JOINT_LINE), m_description("no plan yet")
{
}

void vpProjectivePathPlanner::setJointLimits(const JointVector &qmin, const JointVector &qmax)
{
  const std::string where = plannerAt("setJointLimits()");
  if (qmin.size() != qmax.size()) {
    fail(vpProjectiveException::dimensionError, where, "qmin and qmax must have the same size");
  }
  if (!qmin.allFinite() || !qmax.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, where, "a joint limit is not finite");
  }
  for (Eigen::Index i = 0; i < qmin.size(); ++i) {
    if (!(qmin(i) < qmax(i))) {
      std::ostringstream os;
      os << "joint " << i << ": qmin (" << qmin(i) << ") must be below qmax (" << qmax(i) << ")";
      fail(vpProjectiveException::invalidValueError, where, os.str());
    }
  }
  m_hasLimits = qmin.size() > 0;
  m_qmin = qmin;
  m_qmax = qmax;
}

void vpProjectivePathPlanner::setImageSize(unsigned int width, unsigned int height, double border)
{
  const std::string where = plannerAt("setImageSize()");
  requireFinite(border, where, "the border");
  if ((width == 0) != (height == 0) || border < 0.0 ||
      (width > 0 && (2.0 * border > width - 1.0 || 2.0 * border > height - 1.0))) {
    std::ostringstream os;
    os << "the image " << width << " x " << height << " with a border of " << border
       << " px has no pixel; give both sides (0 x 0 disables the check) and a border that leaves some";
    fail(vpProjectiveException::invalidValueError, where, os.str());
  }
  m_width = width;
  m_height = height;
  m_border = border;
}

void vpProjectivePathPlanner::setMaxJointStep(double step)
{
  if (!std::isfinite(step) || !(step > 0.0)) {
    fail(vpProjectiveException::invalidValueError, plannerAt("setMaxJointStep()"),
         "the largest joint step between samples must be positive and finite");
  }
  m_maxStep = step;
}

void vpProjectivePathPlanner::setMaxExcursion(double excursion)
{
  if (!std::isfinite(excursion) || excursion < 0.0) {
    fail(vpProjectiveException::invalidValueError, plannerAt("setMaxExcursion()"),
         "the largest motion of a joint beyond its start and target values must be non-negative and finite");
  }
  m_maxExcursion = excursion;
}

double vpProjectivePathPlanner::getMaxJointStep() const
{
  const double saturation = m_hasLaw ? m_law.getDampedLeastSquares().getMaxJointVelocity() : 0.0;
  return saturation > 0.0 ? std::min(m_maxStep, 2.0 / 3.0 * saturation) : m_maxStep;
}

double vpProjectivePathPlanner::getMaxExcursion() const
{
  return m_maxExcursion < 0.0 ? 2.0 * m_maxStep : m_maxExcursion;
}

void vpProjectivePathPlanner::setMaxResidual(double pixels)
{
  if (!std::isfinite(pixels) || !(pixels > 0.0)) {
    fail(vpProjectiveException::invalidValueError, plannerAt("setMaxResidual()"),
         "the largest RMS pixel residual of a target must be positive and finite");
  }
  m_maxResidual = pixels;
}

void vpProjectivePathPlanner::setPlanarGroups(const std::vector<std::vector<unsigned int>> &groups)
{
  for (size_t g = 0; g < groups.size(); ++g) {
    std::vector<unsigned int> sorted = groups[g];
    std::sort(sorted.begin(), sorted.end());
    if (sorted.size() < 3 || std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      std::ostringstream os;
      os << "planar group " << g << " has " << groups[g].size() << " points"
         << (sorted.size() < 3 ? "" : ", one of them twice")
         << "; a group lists 3 or more distinct point indices in order around its marker (a tag's 4 corners)";
      fail(vpProjectiveException::invalidValueError, plannerAt("setPlanarGroups()"), os.str());
    }
  }
  m_groups = groups;
}

void vpProjectivePathPlanner::setMinGroupArea(double fraction)
{
  const std::string where = plannerAt("setMinGroupArea()");
  requireFinite(fraction, where, "the smallest group area");
  if (fraction < 0.0 || fraction > 1.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the smallest group area is a fraction of the group's image area at the ends of the motion: in [0, 1]");
  }
  m_minGroupArea = fraction;
}

void vpProjectivePathPlanner::setJointLimitMargin(double fraction)
{
  if (!std::isfinite(fraction) || fraction < 0.0 || fraction > 0.5) {
    fail(vpProjectiveException::invalidValueError, plannerAt("setJointLimitMargin()"),
         "the margin is a fraction of each joint's range kept from both limits: in [0, 1/2]");
  }
  m_limitMargin = fraction;
}

void vpProjectivePathPlanner::setNumberOfStarts(unsigned int starts)
{
  m_starts = atLeastOne(starts, plannerAt("setNumberOfStarts()"),
                        "the inverse kinematics needs at least one random start to look for other branches");
}

void vpProjectivePathPlanner::setPathFollowingGain(double gain)
{
  if (!std::isfinite(gain) || !(gain > 0.0) || gain > 1.0) {
    fail(vpProjectiveException::invalidValueError, plannerAt("setPathFollowingGain()"),
         "the path-following gain is the fraction of the way to the next sample covered per call: in (0, 1]");
  }
  m_followGain = gain;
}

void vpProjectivePathPlanner::setMaxOpenLoopTime(double seconds)
{
  m_maxOpenLoopTime = nonNegative(seconds, plannerAt("setMaxOpenLoopTime()"), "the longest open loop on the model",
                                  "seconds of consecutive calls; 0 stops the task as soon as the features are too few");
}
