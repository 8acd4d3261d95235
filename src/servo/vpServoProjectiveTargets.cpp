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
  Where a vpServoProjective task is going: its desired features (the user's s*, re-expressed through the rig after a
  re-registration), the model-mismatch check of the measured features against the model, and the planned path that
  the task follows before law (47) finishes.
*/

#include <visp3/projective/vpServoProjective.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/vpImageWindow.h"
#include "core/vpProjectiveConversions.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoProjective"); // const: internal linkage, as in vpServoProjective.cpp

Eigen::Vector4d vpServoProjective::desired(unsigned int i) const
{
  // Following, the arm should be at the sample before the one it moves to: its predicted features are the reference
  // of the image feedback.
  return m_following ? m_planner.getPredictedFeatures()[m_pathSample - 1][i] : m_targets[i].effective;
}

void vpServoProjective::refreshTargets()
{
  // The task's copy of s*: the user's value, triangulated once through the rig it was given with; after the robot
  // told of a re-registered rig (vpRobotLink), that point's image in the new rig; after it told of a new model, the
  // user's value anew. The features' point memories of the mismatch check belong to one rig of one model.
  const bool modelChanged = m_link.modelChanged, rigChanged = m_link.rigChanged && !modelChanged;
  if (modelChanged) {
    m_refinement.stop(); // the frames and points belong to the old model
    m_rigUpdatesSeen = m_link.robot->getRigUpdate().getUpdateCount();
  } else if (rigChanged && m_link.robot->getRigUpdate().getUpdateCount() != m_rigUpdatesSeen) {
    m_rigUpdatesSeen = m_link.robot->getRigUpdate().getUpdateCount();
    if (m_link.modifiable != nullptr && m_link.modifiable == m_link.robot) {
      m_refinement.start(m_mismatch, static_cast<unsigned int>(m_features.size())); // from the memories before it
    } else {
      m_refinement.stop();
    }
  }
  if (modelChanged || rigChanged) {
    m_mismatch.reset();
    std::fill(m_hasSeenPoint.begin(), m_hasSeenPoint.end(), 0); // the open loop's points: of the old frame
  }
  const vpProjectiveStereoRig &rig = m_link.robot->getModel().getStereoRig();
  for (size_t i = 0; i < m_targets.size(); ++i) {
    vpTarget &t = m_targets[i];
    const Eigen::Vector4d before = t.effective;
    const bool wasValid = t.valid;
    const Eigen::Vector4d user = m_desired[i]->getFeature();
    if (!t.valid || modelChanged || !(user == t.user)) {
      t.user = user;
      t.effective = user;
      t.hasPoint = user.allFinite();
      if (t.hasPoint) {
        t.point = rig.triangulate(user.head<2>(), user.tail<2>());
      }
      t.valid = true;
    } else if (rigChanged) {
      Eigen::Vector4d s;
      if (t.hasPoint && rig.project(t.point, s)) {
        t.effective = s;
      } else {
        t.effective = user; // no point: the user's value, which the health then judges
      }
    }
    if (!wasValid || !(t.effective == before)) {
      ++m_targetGeneration; // another target: the settling gain converges anew
    }
  }
  m_link.modelChanged = m_link.rigChanged = false;
}

bool vpServoProjective::detectMismatch(const vpServoProjectiveData &data)
{
  if (m_mismatch.getThreshold() == 0.0) {
    return false; // detection off: no memory to keep
  }
  const vpImageWindow window(m_health.getImageWidth(), m_health.getImageHeight(), m_health.getImageBorder());
  m_mismatch.startIteration(m_link.robot->getModel(), data);
  for (unsigned int i = 0; i < m_features.size(); ++i) {
    const Eigen::Vector4d &s = data.getFeature(i);
    bool usable = m_health.isFeatureTracked(i) && data.hasPoint(i);
    usable = usable && window.containsStereo(s);
    m_mismatch.observe(i, usable);
  }
  return m_mismatch.endIteration();
}

vpColVector vpServoProjective::getDesiredFeature(unsigned int i) const
{
  checkFeatureIndex(i, "getDesiredFeature()");
  return toVispVector(m_targets[i].valid ? m_targets[i].effective : m_desired[i]->getFeature());
}

namespace
{
//! Plans again from an off-path configuration per target, before the task gives the path up for law (47).
const unsigned int kMaxReplans = 2;
//! Calls of the window of the stall test, and the ratio of the error's mean to its spread that says "stalled".
const unsigned int kStallWindow = 10;
const double kStallRatio = 3.0;
} // namespace

bool vpServoProjective::lawStalled(const Eigen::VectorXd &e)
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

bool vpServoProjective::planIfNeeded(const JointVector &q, const vpServoProjectiveData &data)
{
  // Plan once per target: again only when a desired feature changed.
  bool changed = m_plannedFor.size() != m_desired.size();
  for (size_t i = 0; i < m_desired.size() && !changed; ++i) {
    changed = !(m_targets[i].effective == m_plannedFor[i]);
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
    const vpIteration &it = last();
    const double rms =
        it.m_data.m_e.size() > 0 ? it.m_data.m_errorNorm / std::sqrt(static_cast<double>(it.m_data.m_e.size())) : 0.0;
    const bool settled = lawPlan && m_sincePlan > 2 * (path.size() - 1) + 10;
    const bool stalled = settled && lawStalled(it.m_data.m_e);
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
    const vpProjectiveArmModel &model = m_link.robot->getModel();
    const Eigen::PartialPivLU<Eigen::Matrix4d> H(data.getDisplacement()); // this iteration's H(q), once per plan
    std::vector<Eigen::Vector4d> points, sStar;
    for (unsigned int i = 0; i < data.getNumberOfFeatures(); ++i) {
      const Eigen::Vector4d &s = data.getFeature(i);
      if (!s.allFinite()) {
        return false; // a feature lost at planning time: plan at the next call
      }
      points.push_back(H.solve(model.getStereoRig().triangulate(s.head<2>(), s.tail<2>())).normalized());
      sStar.push_back(m_targets[i].effective);
    }
    vpProjectivePathPlanner::JointVector qmin, qmax;
    const vpServoJointLimitAvoidance &limits = m_control.getJointLimitAvoidance();
    if (limits.hasJointLimits()) {
      qmin = toEigenVector<JointVector>(limits.getLowerLimits(), q.size(), at("computeControlLaw()"), "qmin");
      qmax = toEigenVector<JointVector>(limits.getUpperLimits(), q.size(), at("computeControlLaw()"), "qmax");
    }
    m_planner.setJointLimits(qmin, qmax);
    m_planner.setImageSize(m_health.getImageWidth(), m_health.getImageHeight(), m_health.getImageBorder());
    if (m_lawLeftRehearsal) {
      m_planner.clearControlLaw();
    } else {
      m_planner.setControlLaw(m_control); // rehearsed per call, as the task runs it
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

void vpServoProjective::setPathPlanning(bool planning)
{
  m_planning = planning;
  m_plannedFor.clear(); // plan anew
  m_following = false;
}

vpColVector vpServoProjective::getPlannedTarget() const
{
  if (!m_planning || m_planner.getStatus() != vpProjectivePathPlanner::PLAN_FOUND) {
    fail(vpProjectiveException::notInitializedError, at("getPlannedTarget()"),
         "no plan: call setPathPlanning(true) and computeControlLaw(), and check getStatus() != SERVO_NO_PLAN (" +
             m_planner.getDescription() + ")");
  }
  return toVispVector(m_planner.getTarget());
}
