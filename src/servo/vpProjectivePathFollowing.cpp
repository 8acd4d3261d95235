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

#include <visp3/projective/vpProjectivePathFollowing.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoProjective"); // the task's computeControlLaw() raises the path following's errors

namespace
{
//! Plans again from an off-path configuration per target, before the task gives the path up for law (47).
const unsigned int kMaxReplans = 2;
//! Calls of the window of the stall test, and the ratio of the error's mean to its spread that says "stalled".
const unsigned int kStallWindow = 10;
const double kStallRatio = 3.0;
} // namespace

vpProjectivePathFollowing::vpProjectivePathFollowing()
    : m_planning(false), m_planner(), m_plannedFor(), m_pathSample(0), m_following(false), m_replans(0),
      m_lawLeftRehearsal(false), m_sincePlan(0), m_replanFailed(false), m_stallSum(),
      m_stallSumSq(), m_stallHalves{0.0, 0.0}, m_stallCount(0), m_openLoopCalls(0), m_seen()
{
}

void vpProjectivePathFollowing::restart()
{
  m_plannedFor.clear(); // plan anew
  m_following = false;
}

void vpProjectivePathFollowing::setPlanning(bool planning)
{
  m_planning = planning;
  restart();
}

void vpProjectivePathFollowing::addFeature()
{
  m_seen.push_back(0);
  restart(); // another task
}

void vpProjectivePathFollowing::clearFeatures()
{
  m_seen.clear();
  m_openLoopCalls = 0;
  restart();
}

void vpProjectivePathFollowing::forgetPoints()
{
  std::fill(m_seen.begin(), m_seen.end(), 0);
}

bool vpProjectivePathFollowing::plan(const vpProjectiveArmModel &model, const JointVector &q,
                                     const vpServoProjectiveData &data, const std::vector<Eigen::Vector4d> &targets,
                                     const vpServoControlLaw &control, const vpServoFeatureHealth &health,
                                     const Eigen::VectorXd &lastError, double lastErrorNorm)
{
  const bool planned = !m_planning || planIfNeeded(model, q, data, targets, control, health, lastError, lastErrorNorm);
  m_following = m_planning && planned && m_pathSample < m_planner.getPath().size() &&
                m_planner.getPathKind() != vpProjectivePathPlanner::PATH_LAW;
  return planned;
}

bool vpProjectivePathFollowing::lawStalled(const Eigen::VectorXd &e)
{
  // Law (47) that has converged leaves the measurement noise: the error's mean over a window of calls is as large as
  // its spread about that mean (the noise of s* against that of s). Stalled at a minimum of the image error that is not
  // the solution, the mean is several times the spread; and a law still converging has a mean that falls from the
  // window's first half to its second. Unit-free: no noise level to set.
  if (e.size() != m_stallSum.size()) {
    return false;
  }
  m_stallSum += e;
  m_stallSumSq += e.cwiseAbs2();
  m_stallHalves[2 * m_stallCount < kStallWindow ? 0 : 1] += e.squaredNorm();
  if (++m_stallCount < kStallWindow) {
    return false;
  }
  const double w = static_cast<double>(kStallWindow);
  const double mean2 = (m_stallSum / w).squaredNorm();
  const double spread2 = std::max(0.0, m_stallSumSq.sum() / w - mean2);
  const bool stalled = mean2 > kStallRatio * kStallRatio * spread2 && m_stallHalves[1] >= 0.64 * m_stallHalves[0];
  m_stallSum.setZero();
  m_stallSumSq.setZero();
  m_stallHalves[0] = m_stallHalves[1] = 0.0;
  m_stallCount = 0;
  return stalled;
}

bool vpProjectivePathFollowing::planIfNeeded(const vpProjectiveArmModel &model, const JointVector &q,
                                             const vpServoProjectiveData &data,
                                             const std::vector<Eigen::Vector4d> &targets,
                                             const vpServoControlLaw &control, const vpServoFeatureHealth &health,
                                             const Eigen::VectorXd &lastError, double lastErrorNorm)
{
  // Plan once per target: again only when a desired feature changed.
  bool changed = m_plannedFor.size() != targets.size();
  for (size_t i = 0; i < targets.size() && !changed; ++i) {
    changed = !(targets[i] == m_plannedFor[i]);
  }
  // Off the plan. Following a path, the arm should be near the sample before the one the call aims at (the
  // feedforward brought it there and the feedback keeps it within the noise): two steps away, it does not move as the
  // model predicted. Running law (47) as rehearsed, its course may differ (near a singular configuration it depends on
  // the noise) as long as it converges: only a law still far from its rehearsed residual after twice the rehearsed
  // iterations and 10 more has stalled. Either way: plan again from here (a path: a law that left its rehearsal is
  // not rehearsed again), or give the path up for law (47) once the re-plans are spent.
  bool replan = false;
  const std::vector<JointVector> &path = m_planner.getPath();
  const bool lawPlan = m_planner.getPathKind() == vpProjectivePathPlanner::PATH_LAW;
  ++m_sincePlan;
  if (changed) {
    m_replans = 0;
    m_lawLeftRehearsal = false;
    m_planner.setRefusedTarget(JointVector());
  } else if (m_planner.getStatus() == vpProjectivePathPlanner::PLAN_FOUND && m_replans <= kMaxReplans &&
             m_openLoopCalls == 0) { // in open loop the features are not all seen: no plan from them
    const double rms = lastError.size() > 0 ? lastErrorNorm / std::sqrt(static_cast<double>(lastError.size())) : 0.0;
    const bool settled = lawPlan && m_sincePlan > 2 * (path.size() - 1) + 10;
    const bool stalled = settled && lawStalled(lastError);
    const bool off = lawPlan
                         ? (settled && rms > 2.0 * m_planner.getRehearsalResidual() + 2.0) || stalled
                         : m_pathSample > 0 && m_pathSample < path.size() &&
                               (q - path[m_pathSample - 1]).cwiseAbs().maxCoeff() > 2.0 * m_planner.getMaxJointStep();
    if (off && m_replans < kMaxReplans) {
      ++m_replans;
      replan = true;
      m_lawLeftRehearsal = m_lawLeftRehearsal || lawPlan;
      if (stalled) {
        m_planner.setRefusedTarget(q); // the images refuse this minimum: another branch, along a path
      }
    } else if (off) {
      ++m_replans;                // spent: law (47) from here, no more checks
      m_pathSample = path.size(); // not following
    }
  }
  if (changed || replan) {
    // The features' points, triangulated at q and carried to the zero reference by H(q)^-1.
    const Eigen::PartialPivLU<Eigen::Matrix4d> H(data.getDisplacement()); // this iteration's H(q), once per plan
    std::vector<Eigen::Vector4d> points, sStar;
    for (unsigned int i = 0; i < data.getNumberOfFeatures(); ++i) {
      const Eigen::Vector4d &s = data.getFeature(i);
      if (!s.allFinite()) {
        return false; // a feature lost at planning time: plan at the next call
      }
      points.push_back(H.solve(model.getStereoRig().triangulate(s.head<2>(), s.tail<2>())).normalized());
      sStar.push_back(targets[i]);
    }
    vpProjectivePathPlanner::JointVector qmin, qmax;
    const vpServoJointLimitAvoidance &limits = control.getJointLimitAvoidance();
    if (limits.hasJointLimits()) {
      qmin = toEigenVector<JointVector>(limits.getLowerLimits(), q.size(), at("computeControlLaw()"), "qmin");
      qmax = toEigenVector<JointVector>(limits.getUpperLimits(), q.size(), at("computeControlLaw()"), "qmax");
    }
    m_planner.setJointLimits(qmin, qmax);
    m_planner.setImageSize(health.getImageWidth(), health.getImageHeight(), health.getImageBorder());
    if (m_lawLeftRehearsal) {
      m_planner.clearControlLaw();
    } else {
      m_planner.setControlLaw(control); // rehearsed per call, as the task runs it
    }
    m_planner.plan(model, q, points, sStar);
    m_plannedFor = sStar;
    m_pathSample = 1; // sample 0 is q
    m_sincePlan = 0;
    m_stallSum.setZero(data.getNumberOfFeatures() * 4);
    m_stallSumSq.setZero(data.getNumberOfFeatures() * 4);
    m_stallHalves[0] = m_stallHalves[1] = 0.0;
    m_stallCount = 0;
    m_replanFailed = replan && m_planner.getStatus() != vpProjectivePathPlanner::PLAN_FOUND;
  }
  // A re-plan that finds nothing leaves law (47) running where the first plan had brought the arm.
  return m_planner.getStatus() == vpProjectivePathPlanner::PLAN_FOUND || m_replanFailed;
}

const vpProjectivePathFollowing::JointVector *vpProjectivePathFollowing::getPathTarget() const
{
  const bool path = m_planning && m_planner.getStatus() == vpProjectivePathPlanner::PLAN_FOUND &&
                    m_planner.getPathKind() != vpProjectivePathPlanner::PATH_LAW;
  return path ? &m_planner.getTarget() : nullptr;
}

void vpProjectivePathFollowing::shapeStep(const vpProjectiveArmModel &model, const JointVector &q,
                                          const vpServoDampedLeastSquares &law, JointVector &qdot) const
{
  if (m_following) {
    // The feedback corrects the model's error, a few pixels: bounded by half a path step, so that near a singular
    // configuration (where its least-squares step is large) it cannot throw the arm off its path.
    const double largest = qdot.cwiseAbs().maxCoeff(), bound = 0.5 * m_planner.getMaxJointStep();
    if (largest > bound) {
      qdot *= bound / largest;
    }
    qdot += m_planner.getPath()[m_pathSample] - m_planner.getPath()[m_pathSample - 1];
    law.saturate(qdot);
  } else if (m_planning) {
    m_planner.guardStep(model, q, qdot); // law (47) toward a planned task: no overshoot
  }
}

bool vpProjectivePathFollowing::mayOpenLoop(double period) const
{
  // Only while a plan is under way (a path followed, or law (47) within its rehearsed iterations: checked inside the
  // limits with the features in view), within the time allowed. At rest, a lost feature stops the task as before.
  const bool underWay = m_planning && m_planner.getStatus() == vpProjectivePathPlanner::PLAN_FOUND &&
                        m_pathSample < m_planner.getPath().size();
  const double maxOpenLoopTime = m_planner.getMaxOpenLoopTime();
  return underWay && maxOpenLoopTime > 0.0 && (m_openLoopCalls + 1) * period <= maxOpenLoopTime * (1.0 + 1e-9);
}

bool vpProjectivePathFollowing::predict(unsigned int i, const vpServoFeatureHealth &health,
                                        const vpServoProjectiveData &data, Eigen::Vector4d &sHat) const
{
  Eigen::Vector4d M0;
  return m_seen[i] && health.getMemory(i, M0) && data.predict(M0, sHat);
}

void vpProjectivePathFollowing::commit(vpServoProjectiveReport::vpServoStatus status,
                                       const vpServoFeatureHealth &health, const vpServoProjectiveData &data)
{
  // The features the open loop may predict (the health remembers their points), and the count of consecutive
  // open-loop calls, which only the features seen again (a running task) restart.
  for (unsigned int i = 0; i < m_seen.size(); ++i) {
    if (health.getFeatureState(i) == vpServoFeatureHealth::FEATURE_ACTIVE && data.hasPoint(i)) {
      m_seen[i] = 1;
    }
  }
  if (status == vpServoProjectiveReport::SERVO_OPEN_LOOP) {
    ++m_openLoopCalls;
  } else if (status == vpServoProjectiveReport::SERVO_RUNNING || status == vpServoProjectiveReport::SERVO_REDUCED) {
    m_openLoopCalls = 0;
  }
  if (m_planning && m_pathSample < m_planner.getPath().size() &&
      (status == vpServoProjectiveReport::SERVO_RUNNING || status == vpServoProjectiveReport::SERVO_REDUCED ||
       status == vpServoProjectiveReport::SERVO_OPEN_LOOP)) {
    ++m_pathSample; // the next call aims at the next sample (of the path, or of law (47)'s rehearsal)
  }
}
