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

#include <visp3/projective/vpServoRigRefinement.h>

#include <Eigen/Dense>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
//! Most frames (calls times refinements) that setRefinement() accepts: the memory reserved per feature.
const unsigned long kMaxRefinementCalls = 100000;
} // namespace

vpServoRigRefinement::vpServoRigRefinement()
    : m_enabled(true), m_period(40), m_count(3), m_active(false), m_calls(0), m_done(0), m_failed(0), m_zero(),
      m_hasZero(), m_X(), m_s()
{
}

void vpServoRigRefinement::setRefinement(bool refine, unsigned int period, unsigned int count)
{
  const char *const where = "vpServoRigRefinement::setRefinement()";
  if (period == 0 || count == 0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the period (calls between two refinements) and the number of refinements must be positive, e.g. 40 and 3; "
         "pass refine = false to turn the refinement off");
  }
  if (static_cast<unsigned long>(period) * count > kMaxRefinementCalls) {
    fail(vpProjectiveException::invalidValueError, where,
         "period times refinements exceeds 100000 recorded calls, whose frames the task keeps in memory; refine "
         "less often or fewer times (e.g. 40 and 3)");
  }
  m_enabled = refine;
  m_period = period;
  m_count = count;
  if (!refine) {
    m_active = false;
  }
}

void vpServoRigRefinement::stop()
{
  m_active = false;
  m_calls = m_done = m_failed = 0;
  m_zero.clear();
  m_hasZero.clear();
  m_X.clear();
  m_s.clear();
}

void vpServoRigRefinement::start(const vpServoModelMismatch &mismatch, unsigned int nbFeatures)
{
  // The features' points at the zero reference as the rig of before the move triangulated them (the mismatch check's
  // mean of the iterations that agreed), not the acquired markers' points: the task re-expresses s* from its point
  // triangulated through that rig, so the refined rig must map that rig's points, not the arm model's, to the new
  // images. The model's points differ from them by its own error (0.2 px RMS at a target), which a rig fitted to them
  // near the target carried into s* (a median 0.3 mm of tool pose, issue 18). But the triangulations are those of the
  // few calls before the move, whose noise the refined rig takes in as an error common to the features (issue 30: with
  // those calls noise-free, 96-98 % of the bumped tasks reached their target instead of 93-94 %). For a feature that
  // is an acquired marker, the mean of both points: errors of similar size (a few tenths of a pixel) and independent,
  // the model's and the triangulations' noise. A feature without a memory keeps its point of an earlier
  // re-registration, if any (the same model and features: stop() forgets them otherwise).
  m_active = false;
  m_calls = m_done = m_failed = 0;
  m_X.clear();
  m_s.clear();
  if (!m_enabled) {
    return;
  }
  m_zero.resize(nbFeatures, Eigen::Vector4d::Zero());
  m_hasZero.resize(nbFeatures, 0);
  unsigned int known = 0;
  for (unsigned int i = 0; i < nbFeatures; ++i) {
    Eigen::Vector4d M;
    if (i < mismatch.getNumberOfFeatures() && mismatch.getTriangulatedMemory(i, M)) {
      Eigen::Vector4d A;
      if (mismatch.isMemoryExact(i) && mismatch.getMemory(i, A)) {
        M = (M + (M.dot(A) < 0.0 ? Eigen::Vector4d(-A) : A)).normalized();
      }
      m_zero[i] = M;
      m_hasZero[i] = 1;
    }
    known += m_hasZero[i] != 0 ? 1 : 0;
  }
  if (known == 0) {
    return; // nothing to refine with (the mismatch check off, or no feature ever agreed)
  }
  const size_t capacity = static_cast<size_t>(m_period) * m_count * known;
  m_X.reserve(capacity); // the recording then allocates nothing
  m_s.reserve(capacity);
  m_active = true;
}

bool vpServoRigRefinement::record(const vpServoProjectiveData &data, const vpServoFeatureHealth &health)
{
  if (!m_active) {
    return false;
  }
  if (m_hasZero.size() != data.getNumberOfFeatures()) {
    stop(); // another set of features
    return false;
  }
  for (unsigned int i = 0; i < data.getNumberOfFeatures(); ++i) {
    if (m_hasZero[i] == 0 || health.getFeatureState(i) != vpServoFeatureHealth::FEATURE_ACTIVE ||
        !data.getFeature(i).allFinite()) {
      continue; // outliers and features set aside never enter the refinement
    }
    if (m_X.size() < m_X.capacity()) {
      m_X.push_back((data.getDisplacement() * m_zero[i]).normalized());
      m_s.push_back(data.getFeature(i));
    }
  }
  ++m_calls;
  return m_calls % m_period == 0;
}

void vpServoRigRefinement::refine(vpProjectiveRobot &robot)
{
  try {
    robot.refineRig(m_X, m_s); // tells the tasks: their next call re-expresses s* in the refined rig
    ++m_done;
  } catch (const vpException &) {
    ++m_failed; // the robot, its rig and the targets are as they were
  }
  if (m_done + m_failed >= m_count) {
    m_active = false; // done: no more frames
    m_X.clear();
    m_s.clear();
  }
}
