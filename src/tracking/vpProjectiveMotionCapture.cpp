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

#include <visp3/projective/vpProjectiveMotionCapture.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/projective/vpProjectiveInverseKinematics.h>

#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveNumerics.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpProjectiveMotionCapture");

vpProjectiveMotionCapture::vpProjectiveMotionCapture(const vpProjectiveArmModel &model,
                                                     const std::vector<unsigned int> &indices)
    : m_model(model), m_indices(indices), m_q(), m_history(), m_times(), m_window(4), m_residual(0.0), m_visible(),
      m_visibleIndices()
{
  const std::string where = at("vpProjectiveMotionCapture()");
  if (model.getNumberOfJoints() == 0) {
    fail(vpProjectiveException::notInitializedError, where, "the model is empty; acquire or load one first");
  }
  const unsigned int K = static_cast<unsigned int>(model.markers().size());
  if (m_indices.empty()) {
    for (unsigned int j = 0; j < K; ++j) {
      m_indices.push_back(j);
    }
  }
  for (unsigned int j : m_indices) {
    if (j >= K) {
      std::ostringstream os;
      os << "marker index " << j << " is out of range; the model has " << K << " markers";
      fail(vpProjectiveException::dimensionError, where, os.str());
    }
  }
  m_q = model.zeroReferenceJoints();
  m_visible.reserve(m_indices.size());
  m_visibleIndices.reserve(m_indices.size());
}

void vpProjectiveMotionCapture::setInitialJoints(const vpColVector &q0)
{
  m_q =
      toEigenVector<vpProjectiveArmModel::JointVector>(q0, m_model.getNumberOfJoints(), at("setInitialJoints()"), "q0");
  m_history.clear();
  m_times.clear();
}

void vpProjectiveMotionCapture::setVelocityWindow(unsigned int frames)
{
  m_window = atLeastOne(frames, at("setVelocityWindow()"), "the velocity is fitted over at least 1 past frame");
}

const vpProjectiveArmModel::JointVector &vpProjectiveMotionCapture::capture(double t,
                                                                            const std::vector<Eigen::Vector4d> &s)
{
  const std::string where = at("capture()");
  if (s.size() != m_indices.size()) {
    std::ostringstream os;
    os << "got the images of " << s.size() << " markers but the capture observes " << m_indices.size()
       << "; pass every observed marker in order, flagging the lost ones";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!std::isfinite(t) || (!m_times.empty() && !(t > m_times.back()))) {
    std::ostringstream os;
    os << "the frame time " << t << " must be finite and after the previous frame's";
    fail(vpProjectiveException::invalidValueError, where, os.str());
  }
  m_visible.clear();
  m_visibleIndices.clear();
  for (size_t k = 0; k < s.size(); ++k) {
    if (s[k].allFinite()) {
      m_visible.push_back(s[k]);
      m_visibleIndices.push_back(m_indices[k]);
    }
  }
  if (2 * m_visible.size() < m_model.getNumberOfJoints()) {
    std::ostringstream os;
    os << "only " << m_visible.size() << " markers are visible for " << m_model.getNumberOfJoints()
       << " joints; each constrains at most 2 to 3 of them";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  double residual = 0.0;
  const vpProjectiveArmModel::JointVector q =
      vpProjectiveInverseKinematics::solve(m_model, m_visible, m_visibleIndices, m_q, &residual);
  m_q = q;
  m_residual = residual;
  if (m_history.size() > m_window) {
    m_history.erase(m_history.begin());
    m_times.erase(m_times.begin());
  }
  m_history.push_back(q);
  m_times.push_back(t);
  return m_q;
}

void vpProjectiveMotionCapture::capture(double t, const std::vector<vpImagePoint> &left,
                                        const std::vector<vpImagePoint> &right, const std::vector<bool> &visible)
{
  if (left.size() != right.size() || (!visible.empty() && visible.size() != left.size())) {
    std::ostringstream os;
    os << "got " << left.size() << " left, " << right.size() << " right images and " << visible.size()
       << " visibility flags; pass one of each per observed marker";
    fail(vpProjectiveException::dimensionError, at("capture()"), os.str());
  }
  std::vector<Eigen::Vector4d> s(left.size());
  for (size_t k = 0; k < s.size(); ++k) {
    s[k] << left[k].get_u(), left[k].get_v(), right[k].get_u(), right[k].get_v();
    if (!visible.empty() && !visible[k]) {
      s[k].setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
  capture(t, s);
}

vpColVector vpProjectiveMotionCapture::getJoints() const
{
  return toVispVector(m_q);
}

vpColVector vpProjectiveMotionCapture::getJointVelocities() const
{
  if (m_history.size() < 2) {
    fail(vpProjectiveException::notInitializedError, at("getJointVelocities()"),
         "a velocity needs two frames; call capture() on another frame first");
  }
  const size_t k = m_history.size() - 1;
  vpProjectiveArmModel::JointVector qdot = vpProjectiveArmModel::JointVector::Zero(m_q.size());
  for (const std::pair<size_t, double> &w : slopeWeights(m_times, k, m_window, at("getJointVelocities()"))) {
    qdot += w.second * (m_history[w.first] - m_history[k]);
  }
  return toVispVector(qdot);
}
