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

#include <visp3/projective/vpProjectiveArmAcquisition.h>

#include <algorithm>
#include <functional>
#include <cmath>
#include <limits>
#include <sstream>

#include "acquisition/vpArmCalibration.h"
#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpProjectiveArmAcquisition");

vpProjectiveArmAcquisition::vpProjectiveArmAcquisition()
    : m_types(), m_mounting(vpProjectiveArmModel::EYE_TO_HAND), m_rig(), m_zeroImages(), m_qRef(), m_trials(), m_ids(),
      m_frames(), m_outlierThreshold(0.0), m_inlier(), m_residual(0.0), m_algebraicResidual(0.0)
{
}

vpProjectiveArmAcquisition::vpProjectiveArmAcquisition(const std::vector<vpProjectiveJoint::vpJointType> &types)
    : vpProjectiveArmAcquisition()
{
  const std::string where = at("vpProjectiveArmAcquisition()");
  if (types.empty() || types.size() > vpProjectiveArmModel::maxJoints) {
    std::ostringstream os;
    os << "a chain needs between 1 and " << vpProjectiveArmModel::maxJoints << " joints, got " << types.size();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  for (vpProjectiveJoint::vpJointType t : types) {
    if (t != vpProjectiveJoint::REVOLUTE && t != vpProjectiveJoint::PRISMATIC) {
      fail(vpProjectiveException::invalidValueError, where, "a joint type is neither REVOLUTE nor PRISMATIC");
    }
  }
  m_types = types;
  m_qRef = vpProjectiveArmModel::JointVector::Zero(static_cast<Eigen::Index>(types.size()));
}

void vpProjectiveArmAcquisition::setStereoRig(const vpProjectiveStereoRig &rig)
{
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, at("setStereoRig()"),
         "the rig has no fundamental matrix; estimate or set it first");
  }
  m_rig = rig;
  m_zeroImages.clear();
  m_ids.clear();
  m_trials.clear();
  m_inlier.clear(); // the last calibrate()'s flags were of those trials
  m_frames.clear();
}

void vpProjectiveArmAcquisition::setZeroReference(const std::vector<vpImagePoint> &left0,
                                                  const std::vector<vpImagePoint> &right0)
{
  setZeroReference(vpColVector(static_cast<unsigned int>(m_types.size()), 0.0), left0, right0);
}

void vpProjectiveArmAcquisition::setZeroReference(const vpColVector &qRef, const std::vector<vpImagePoint> &left0,
                                                  const std::vector<vpImagePoint> &right0)
{
  const std::string where = at("setZeroReference()");
  if (!m_rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where, "call setStereoRig() with a weakly calibrated rig first");
  }
  const vpProjectiveArmModel::JointVector q =
      toEigenVector<vpProjectiveArmModel::JointVector>(qRef, m_types.size(), where, "the zero-reference joints");
  std::vector<Eigen::Vector4d> s = stackStereoImages(left0, right0, where);
  if (s.size() < 5) {
    std::ostringstream os;
    os << "needs the images of at least 5 markers, 5 of them with no 4 coplanar (on the tool eye-to-hand, static "
          "in the scene eye-in-hand), got "
       << s.size() << "; add markers off the plane of the others";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  m_zeroImages = s;
  m_ids.resize(s.size());
  for (size_t j = 0; j < s.size(); ++j) {
    m_ids[j] = static_cast<int>(j);
  }
  m_qRef = q;
  m_trials.clear();
  m_inlier.clear(); // the last calibrate()'s flags were of those trials
  m_frames.clear();
}

namespace
{
//! The order that sorts \e ids ascending; throws if \e ids has not \e count entries or repeats one.
std::vector<size_t> ascendingIds(const std::vector<int> &ids, size_t count, const std::string &where)
{
  if (ids.size() != count) {
    std::ostringstream os;
    os << "got " << ids.size() << " ids for " << count << " marker images; give one id per marker";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  std::vector<size_t> order(ids.size());
  for (size_t j = 0; j < order.size(); ++j) {
    order[j] = j;
  }
  std::sort(order.begin(), order.end(), [&ids](size_t a, size_t b) { return ids[a] < ids[b]; });
  for (size_t k = 1; k < order.size(); ++k) {
    if (ids[order[k]] == ids[order[k - 1]]) {
      std::ostringstream os;
      os << "marker id " << ids[order[k]] << " is given twice; each marker needs its own id";
      fail(vpProjectiveException::invalidValueError, where, os.str());
    }
  }
  return order;
}
} // namespace

void vpProjectiveArmAcquisition::setZeroReference(const vpColVector &qRef, const std::vector<int> &ids,
                                                  const std::vector<vpImagePoint> &left0,
                                                  const std::vector<vpImagePoint> &right0)
{
  const std::string where = at("setZeroReference()");
  if (left0.size() != right0.size()) {
    std::ostringstream os;
    os << "got " << left0.size() << " left and " << right0.size() << " right marker images; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const std::vector<size_t> order = ascendingIds(ids, left0.size(), where);
  std::vector<vpImagePoint> left(order.size()), right(order.size());
  std::vector<int> sorted(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    left[k] = left0[order[k]];
    right[k] = right0[order[k]];
    sorted[k] = ids[order[k]];
  }
  setZeroReference(qRef, left, right);
  m_ids = sorted;
}

std::vector<Eigen::Vector4d> vpProjectiveArmAcquisition::matchByIds(const std::vector<int> &ids,
                                                                    const std::vector<vpImagePoint> &left,
                                                                    const std::vector<vpImagePoint> &right,
                                                                    const std::string &where, std::vector<bool> &seen,
                                                                    unsigned int &shown) const
{
  const std::vector<Eigen::Vector4d> t = stackStereoImages(left, right, where);
  ascendingIds(ids, t.size(), where); // the checks
  std::vector<Eigen::Vector4d> s(m_ids.size(), Eigen::Vector4d::Constant(std::numeric_limits<double>::quiet_NaN()));
  seen.assign(m_ids.size(), false);
  shown = 0;
  for (size_t k = 0; k < ids.size(); ++k) {
    const std::vector<int>::const_iterator it = std::lower_bound(m_ids.begin(), m_ids.end(), ids[k]);
    if (it != m_ids.end() && *it == ids[k]) { // others: not a zero-reference marker, ignored
      const size_t j = static_cast<size_t>(it - m_ids.begin());
      s[j] = t[k];
      seen[j] = true;
      ++shown;
    }
  }
  return s;
}

vpColVector vpProjectiveArmAcquisition::getZeroReferenceJoints() const
{
  return toVispVector(m_qRef);
}

void vpProjectiveArmAcquisition::addTrialMotion(unsigned int i, double amount, const std::vector<vpImagePoint> &left,
                                                const std::vector<vpImagePoint> &right)
{
  const std::string where = at("addTrialMotion()");
  if (i >= m_types.size()) {
    std::ostringstream os;
    os << "joint index " << i << " is out of range; the chain has " << m_types.size() << " joints";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  requireFinite(amount, where, "the trial amount");
  if (amount == 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the trial amount is zero; move the joint (e.g. 20 to 60 deg) so that its motion can be observed");
  }
  if (m_declared && m_types[i] == vpProjectiveJoint::REVOLUTE && std::abs(std::remainder(amount, 2.0 * M_PI)) < 1e-3) {
    fail(vpProjectiveException::invalidValueError, where,
         "a revolute trial by a multiple of 2 pi leaves the markers where they were; use another amount");
  }
  if (m_zeroImages.empty()) {
    fail(vpProjectiveException::notInitializedError, where, "call setZeroReference() before adding trial motions");
  }
  vpTrial trial;
  trial.joint = i;
  trial.amount = amount;
  trial.s = stackStereoImages(left, right, where);
  if (trial.s.size() != m_zeroImages.size()) {
    std::ostringstream os;
    os << "the trial shows " << trial.s.size() << " markers but the zero reference " << m_zeroImages.size()
       << "; pass the same markers in the same order";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  trial.seen.assign(trial.s.size(), true);
  m_trials.push_back(trial);
}

void vpProjectiveArmAcquisition::addIdentifiedTrial(
    const std::vector<int> &ids, const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
    const std::function<void(const std::vector<vpImagePoint> &, const std::vector<vpImagePoint> &)> &addPlainTrial)
{
  const std::string where = at("addTrialMotion()");
  if (m_zeroImages.empty()) {
    fail(vpProjectiveException::notInitializedError, where, "call setZeroReference() before adding trial motions");
  }
  std::vector<bool> seen;
  unsigned int shown = 0;
  const std::vector<Eigen::Vector4d> s = matchByIds(ids, left, right, where, seen, shown);
  if (shown < 5) {
    std::ostringstream os;
    os << "the trial shows " << shown << " of the zero reference's " << m_ids.size()
       << " markers (matched by id); a trial's displacement needs at least 5 of them: leave it out, or move the "
          "joint less so that more markers stay in view";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  // The checks of the joint and the amount, on the zero reference's images; then this trial's.
  std::vector<vpImagePoint> l0(m_zeroImages.size()), r0(m_zeroImages.size());
  for (size_t j = 0; j < m_zeroImages.size(); ++j) {
    l0[j].set_uv(m_zeroImages[j](0), m_zeroImages[j](1));
    r0[j].set_uv(m_zeroImages[j](2), m_zeroImages[j](3));
  }
  addPlainTrial(l0, r0);
  m_trials.back().s = s;
  m_trials.back().seen = seen;
}

void vpProjectiveArmAcquisition::addTrialMotion(unsigned int i, double amount, const std::vector<int> &ids,
                                                const std::vector<vpImagePoint> &left,
                                                const std::vector<vpImagePoint> &right)
{
  addIdentifiedTrial(ids, left, right, [&](const std::vector<vpImagePoint> &l0, const std::vector<vpImagePoint> &r0) {
    addTrialMotion(i, amount, l0, r0);
  });
}

void vpProjectiveArmAcquisition::addTrialMotion(const vpColVector &q, const std::vector<int> &ids,
                                                const std::vector<vpImagePoint> &left,
                                                const std::vector<vpImagePoint> &right)
{
  addIdentifiedTrial(ids, left, right, [&](const std::vector<vpImagePoint> &l0, const std::vector<vpImagePoint> &r0) {
    addTrialMotion(q, l0, r0);
  });
}

bool vpProjectiveArmAcquisition::isObserved(unsigned int trial, unsigned int marker) const
{
  if (trial >= m_trials.size() || marker >= m_zeroImages.size()) {
    std::ostringstream os;
    os << "no marker " << marker << " in trial " << trial << " (the acquisition has " << m_trials.size()
       << " trials of " << m_zeroImages.size() << " markers)";
    fail(vpProjectiveException::dimensionError, at("isObserved()"), os.str());
  }
  return m_trials[trial].seen[marker];
}

void vpProjectiveArmAcquisition::addTrialMotion(const vpColVector &q, const std::vector<vpImagePoint> &left,
                                                const std::vector<vpImagePoint> &right)
{
  const std::string where = at("addTrialMotion()");
  const vpProjectiveArmModel::JointVector dq =
      toEigenVector<vpProjectiveArmModel::JointVector>(q, m_types.size(), where, "the joint readings") - m_qRef;
  Eigen::Index moved = 0;
  const double amount = dq.size() > 0 ? dq.cwiseAbs().maxCoeff(&moved) : 0.0;
  if (!(amount > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where,
         "no joint moved from the zero reference's readings; move one joint alone (e.g. 20 to 60 deg)");
  }
  for (Eigen::Index k = 0; k < dq.size(); ++k) {
    if (k != moved && std::abs(dq(k)) > 0.01 * amount) {
      std::ostringstream os;
      os << "joints " << moved << " and " << k << " both moved from the zero reference's readings (by " << dq(moved)
         << " and " << dq(k) << "); a trial moves one joint alone";
      fail(vpProjectiveException::invalidValueError, where, os.str());
    }
  }
  addTrialMotion(static_cast<unsigned int>(moved), dq(moved), left, right);
}

void vpProjectiveArmAcquisition::setOutlierThreshold(double pixels)
{
  if (!std::isfinite(pixels) || pixels < 0.0) {
    std::ostringstream os;
    os << "the outlier threshold must be a finite number of pixels >= 0 (0 disables the rejection), got " << pixels;
    fail(vpProjectiveException::invalidValueError, at("setOutlierThreshold()"), os.str());
  }
  m_outlierThreshold = pixels;
}

unsigned int vpProjectiveArmAcquisition::getNumberOfOutliers() const
{
  unsigned int outliers = 0;
  for (size_t k = 0; k < m_inlier.size() && k < m_trials.size(); ++k) {
    for (size_t j = 0; j < m_inlier[k].size(); ++j) {
      outliers += m_trials[k].seen[j] && !m_inlier[k][j] ? 1u : 0u;
    }
  }
  return outliers;
}

bool vpProjectiveArmAcquisition::isOutlier(unsigned int trial, unsigned int marker) const
{
  if (trial >= m_inlier.size() || marker >= m_inlier[trial].size()) {
    std::ostringstream os;
    os << "no observation of marker " << marker << " in trial " << trial << " (calibrate() saw " << m_inlier.size()
       << " trials of " << m_zeroImages.size() << " markers)";
    fail(vpProjectiveException::dimensionError, at("isOutlier()"), os.str());
  }
  return !m_inlier[trial][marker] && (trial >= m_trials.size() || m_trials[trial].seen[marker]);
}
