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
  The refinement of a re-registered rig with a vpServoProjective task's own frames (setRigRefinement()): the features'
  zero-reference points taken from the model-mismatch memories at the re-registration, the frames recorded at the
  calls that move the arm, and vpProjectiveRobot::refineRig() every period.
*/

#include <visp3/projective/vpServoProjective.h>

#include <Eigen/Dense>

#include "core/vpProjectiveErrors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
//! Most frames (calls times refinements) that setRigRefinement() accepts: the memory reserved per feature.
const unsigned long kMaxRefinementCalls = 100000;
} // namespace

void vpServoProjective::setRigRefinement(bool refine, unsigned int period, unsigned int refinements)
{
  const char *const where = "vpServoProjective::setRigRefinement()";
  if (period == 0 || refinements == 0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the period (calls between two refinements) and the number of refinements must be positive, e.g. 40 and 3; "
         "pass refine = false to turn the refinement off");
  }
  if (static_cast<unsigned long>(period) * refinements > kMaxRefinementCalls) {
    fail(vpProjectiveException::invalidValueError, where,
         "period times refinements exceeds 100000 recorded calls, whose frames the task keeps in memory; refine "
         "less often or fewer times (e.g. 40 and 3)");
  }
  m_refinement.enabled = refine;
  m_refinement.period = period;
  m_refinement.count = refinements;
  if (!refine) {
    m_refinement.active = false;
  }
}

void vpServoProjective::startRigRefinement()
{
  // Called by refreshTargets() when the robot's rig was re-registered, before the mismatch memories are forgotten:
  // they are the features' points at the zero reference as seen through the rig of before the move.
  vpRefinement &r = m_refinement;
  r.active = false;
  r.calls = r.done = r.failed = 0;
  r.X.clear();
  r.s.clear();
  if (!r.enabled || m_link.modifiable == nullptr || m_link.modifiable != m_link.robot) {
    return;
  }
  const unsigned int N = static_cast<unsigned int>(m_features.size());
  r.zero.resize(N, Eigen::Vector4d::Zero());
  r.hasZero.resize(N, 0);
  unsigned int known = 0;
  for (unsigned int i = 0; i < N && i < m_mismatch.getNumberOfFeatures(); ++i) {
    Eigen::Vector4d M;
    if (m_mismatch.getMemory(i, M)) { // else the point of an earlier re-registration, if any (same model)
      r.zero[i] = M;
      r.hasZero[i] = 1;
    }
    known += r.hasZero[i] != 0 ? 1 : 0;
  }
  if (known == 0) {
    return; // nothing to refine with (the mismatch check off, or no feature ever agreed)
  }
  const size_t capacity = static_cast<size_t>(r.period) * r.count * known;
  r.X.reserve(capacity); // the recording then allocates nothing
  r.s.reserve(capacity);
  r.active = true;
}

void vpServoProjective::refineRigIfDue()
{
  vpRefinement &r = m_refinement;
  const vpIteration &it = last();
  if (m_link.modifiable == nullptr || m_link.modifiable != m_link.robot || r.hasZero.size() != m_features.size()) {
    r.active = false;
    return;
  }
  if (it.status != SERVO_RUNNING && it.status != SERVO_REDUCED) {
    return; // a call that does not move the arm: neither a frame nor a step of the schedule
  }
  const vpServoProjectiveData &d = it.data;
  for (unsigned int i = 0; i < m_features.size(); ++i) {
    if (r.hasZero[i] == 0 || m_health.getFeatureState(i) != FEATURE_ACTIVE || !d.getFeature(i).allFinite()) {
      continue; // outliers and features set aside never enter the refinement
    }
    if (r.X.size() < r.X.capacity()) {
      r.X.push_back((d.getDisplacement() * r.zero[i]).normalized());
      r.s.push_back(d.getFeature(i));
    }
  }
  ++r.calls;
  if (r.calls % r.period != 0) {
    return;
  }
  try {
    m_link.modifiable->refineRig(r.X, r.s); // tells the task: the next call re-expresses s* in the refined rig
    ++r.done;
  } catch (const vpException &) {
    ++r.failed; // the robot, its rig and the targets are as they were
  }
  if (r.done + r.failed >= r.count) {
    r.active = false; // done: no more frames
    r.X.clear();
    r.s.clear();
  }
}
