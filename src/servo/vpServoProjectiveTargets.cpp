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
  re-registration) and the model-mismatch check of the measured features against the model (the planned path:
  vpProjectivePathFollowing).
*/

#include <visp3/projective/vpServoProjective.h>

#include <algorithm>
#include <cmath>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoProjective"); // const: internal linkage, as in vpServoProjective.cpp

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
    m_path.forgetPoints(); // the open loop's points: of the old frame
  }
  const vpProjectiveStereoRig &rig = m_link.robot->getModel().getStereoRig();
  for (size_t i = 0; i < m_targets.size(); ++i) {
    vpTarget &t = m_targets[i];
    Eigen::Vector4d &effective = m_effective[i];
    const Eigen::Vector4d before = effective;
    const bool wasValid = t.valid;
    const Eigen::Vector4d user = m_desired[i]->getFeature();
    if (!t.valid || modelChanged || !(user == t.user)) {
      t.user = user;
      effective = user;
      t.hasPoint = user.allFinite();
      if (t.hasPoint) {
        t.point = rig.triangulate(user.head<2>(), user.tail<2>());
      }
      t.valid = true;
    } else if (rigChanged) {
      Eigen::Vector4d s;
      if (t.hasPoint && rig.project(t.point, s)) {
        effective = s;
      } else {
        effective = user; // no point: the user's value, which the health then judges
      }
    }
    if (!wasValid || !(effective == before)) {
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
  m_mismatch.startIteration(m_link.robot->getModel(), data);
  for (unsigned int i = 0; i < m_features.size(); ++i) {
    m_mismatch.observe(i, m_health.isInView(i)); // tracked, finite, in the window: the health's verdict of this call
  }
  return m_mismatch.endIteration();
}

vpColVector vpServoProjective::getDesiredFeature(unsigned int i) const
{
  checkFeatureIndex(i, "getDesiredFeature()");
  return toVispVector(m_targets[i].valid ? m_effective[i] : m_desired[i]->getFeature());
}

void vpServoProjective::setPathPlanning(bool planning)
{
  m_path.setPlanning(planning); // plan anew
}

vpColVector vpServoProjective::getPlannedTarget() const
{
  const vpProjectivePathPlanner &planner = m_path.getPlanner();
  if (!m_path.isPlanning() || planner.getStatus() != vpProjectivePathPlanner::PLAN_FOUND) {
    fail(vpProjectiveException::notInitializedError, at("getPlannedTarget()"),
         "no plan: call setPathPlanning(true) and computeControlLaw(), and check getStatus() != SERVO_NO_PLAN (" +
             planner.getDescription() + ")");
  }
  return toVispVector(planner.getTarget());
}
