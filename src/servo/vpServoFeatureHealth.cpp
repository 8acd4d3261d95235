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

#include <visp3/projective/vpServoFeatureHealth.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include "core/vpImageWindow.h"
#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoFeatureHealth");

namespace
{
//! Throws the message of a feature index out of range.
[[noreturn]] void badIndex(unsigned int i, size_t size, const char *method)
{
  std::ostringstream os;
  os << "feature index " << i << " is out of range; the task has " << size
     << " features (indices in addFeature() order, from 0)";
  fail(vpProjectiveException::dimensionError, at(method), os.str());
}

/*!
  Distance (pixels) of a point to the line \e l of an image, from the epipolar residual \f$ r = |m'^T F m| \f$ that
  every such distance shares. A line with a null normal is the epipolar line of an epipole: the distance is 0 if the
  residual is, infinite otherwise.
*/
double lineDistance(double residual, const Eigen::Vector3d &l)
{
  const double normal = l.head<2>().norm();
  if (normal > 0.0) {
    return residual / normal;
  }
  return residual == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

/*!
  The larger distance of a point to the lines \e l and \e lp: max(lineDistance(residual, l), lineDistance(residual,
  lp)), to the bit. With both normals non-null it is \f$ r / \sqrt{\min(\|n\|^2, \|n'\|^2)} \f$: the square root and
  the division are correctly rounded, hence monotone, so that one of each gives the larger of both quotients.
*/
double largerLineDistance(double residual, const Eigen::Vector3d &l, const Eigen::Vector3d &lp)
{
  const double n2 = l.head<2>().squaredNorm(), np2 = lp.head<2>().squaredNorm();
  if (n2 > 0.0 && np2 > 0.0) {
    return residual / std::sqrt(std::min(n2, np2));
  }
  return std::max(lineDistance(residual, l), lineDistance(residual, lp));
}
} // namespace

vpServoFeatureHealth::vpServoFeatureHealth()
    : m_tracked(), m_records(), m_work(), m_nbActive(0), m_width(0), m_height(0), m_border(0.0),
      m_outlierThreshold(0.0), m_rankTolerance(1e-6), m_iteration(0), m_classified(0), m_workActive(0),
      m_inIteration(false), m_predict(false), m_F(Eigen::Matrix3d::Zero()), m_data(nullptr)
{
}

void vpServoFeatureHealth::addFeature()
{
  const vpRecord fresh = {FEATURE_ACTIVE, -1.0, -1.0, Eigen::Vector4d::Zero(), false, false, false, 0};
  m_tracked.push_back(1);
  m_records.push_back(fresh);
  m_work.push_back(fresh);
}

void vpServoFeatureHealth::clearFeatures()
{
  m_tracked.clear();
  m_records.clear();
  m_work.clear();
  m_nbActive = 0;
  m_inIteration = false;
}

// The checks run in the control loop: inline, their messages built out of line, only when throwing.
inline void vpServoFeatureHealth::checkIndex(unsigned int i, const char *method) const
{
  if (i >= m_tracked.size()) {
    badIndex(i, m_tracked.size(), method);
  }
}

inline void vpServoFeatureHealth::checkIteration(const char *method) const
{
  if (!m_inIteration) {
    fail(vpProjectiveException::notInitializedError, at(method),
         "no iteration in progress; call startIteration() first");
  }
}

void vpServoFeatureHealth::setFeatureTracked(unsigned int i, bool tracked)
{
  checkIndex(i, "setFeatureTracked()");
  m_tracked[i] = tracked ? 1 : 0;
}

bool vpServoFeatureHealth::isFeatureTracked(unsigned int i) const
{
  checkIndex(i, "isFeatureTracked()");
  return m_tracked[i] != 0;
}

void vpServoFeatureHealth::setImageSize(unsigned int width, unsigned int height, double border)
{
  const std::string where = at("setImageSize()");
  requireFinite(border, where, "the border");
  if ((width == 0) != (height == 0)) {
    std::ostringstream os;
    os << "the image size " << width << " x " << height << " has one zero side; give both sides, or 0 x 0 to "
       << "disable the image check";
    fail(vpProjectiveException::invalidValueError, where, os.str());
  }
  if (border < 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "the border must be non-negative (pixels)");
  }
  if (width > 0 && (2.0 * border > width - 1.0 || 2.0 * border > height - 1.0)) {
    std::ostringstream os;
    os << "a border of " << border << " px leaves no pixel of a " << width << " x " << height << " image";
    fail(vpProjectiveException::invalidValueError, where, os.str());
  }
  m_width = width;
  m_height = height;
  m_border = border;
}

void vpServoFeatureHealth::setOutlierThreshold(double pixels)
{
  m_outlierThreshold =
      nonNegative(pixels, at("setOutlierThreshold()"), "the outlier threshold", "pixels; 0 disables the rejection");
}

void vpServoFeatureHealth::setRankTolerance(double tolerance)
{
  const std::string where = at("setRankTolerance()");
  requireFinite(tolerance, where, "the rank tolerance");
  if (!(tolerance > 0.0) || !(tolerance < 1.0)) {
    fail(vpProjectiveException::invalidValueError, where,
         "the rank tolerance is a ratio of singular values and must be in (0, 1), e.g. 1e-6");
  }
  m_rankTolerance = tolerance;
}

void vpServoFeatureHealth::startIteration(const vpProjectiveArmModel &model, const vpServoProjectiveData &data)
{
  ++m_iteration;
  m_classified = 0;
  m_workActive = 0;
  model.getStereoRig().getFundamentalMatrix(m_F); // once per iteration: outlierTest() reads it for every feature
  m_data = &data; // H(q), its LU and the features' points: computed once for the whole servo
  m_predict = m_outlierThreshold > 0.0;
  m_inIteration = true;
}

//! The epipolar and prediction tests of an otherwise active feature; \e record receives the distances.
inline vpServoFeatureHealth::vpFeatureState vpServoFeatureHealth::outlierTest(const Eigen::Vector4d &s,
                                                                              vpRecord &record) const
{
  const Eigen::Matrix3d &F = m_F;
  const Eigen::Vector3d m(s(0), s(1), 1.0);
  const Eigen::Vector3d mp(s(2), s(3), 1.0);
  const Eigen::Vector3d lp = F * m;             // epipolar line of m in the right image
  const Eigen::Vector3d l = F.transpose() * mp; // epipolar line of m' in the left image
  const double residual = std::abs(mp.dot(lp));
  const double dF = largerLineDistance(residual, l, lp);
  record.epipolarDistance = dF;
  if (!(dF <= m_outlierThreshold)) {
    return FEATURE_OUTLIER;
  }
  if (m_predict && record.predicts) {
    Eigen::Vector4d sHat;
    if (m_data->predict(record.M0, sHat)) {
      // The larger of both images' distances, one square root: sqrt is monotone, max(sqrt a, sqrt b) = sqrt(max(a, b)).
      const double dP = std::sqrt(
          std::max((sHat.head<2>() - s.head<2>()).squaredNorm(), (sHat.tail<2>() - s.tail<2>()).squaredNorm()));
      record.predictionDistance = dP;
      if (!(dP <= m_outlierThreshold)) {
        return FEATURE_OUTLIER;
      }
    }
  }
  return FEATURE_ACTIVE;
}

vpServoFeatureHealth::vpFeatureState vpServoFeatureHealth::classify(unsigned int i, const Eigen::Vector4d &sStar)
{
  checkIteration("classify()");
  checkIndex(i, "classify()");
  const Eigen::Vector4d &s = m_data->getFeature(i);
  vpRecord &record = m_work[i];
  if (record.iteration != m_iteration) {
    record.iteration = m_iteration;
    ++m_classified;
  } else if (record.state == FEATURE_ACTIVE) {
    --m_workActive; // classified again: the second outcome counts
  }
  const vpRecord &last = m_records[i];
  record.M0 = last.M0; // the memory of the last completed iteration
  record.hasM0 = last.hasM0;
  record.predicts = last.predicts;
  record.epipolarDistance = -1.0;
  record.predictionDistance = -1.0;
  // The checks of the class documentation, in their order; the window whatever s* (isInView()).
  const bool finite = s.allFinite();
  record.inView = m_tracked[i] && finite && vpImageWindow(m_width, m_height, m_border).containsStereo(s);
  record.state = FEATURE_ACTIVE;
  if (!m_tracked[i]) {
    record.state = FEATURE_NOT_TRACKED;
  } else if (!finite || !sStar.allFinite()) {
    record.state = FEATURE_NOT_FINITE;
  } else if (!record.inView) {
    record.state = FEATURE_OUT_OF_IMAGE;
  }
  if (record.state == FEATURE_ACTIVE && m_outlierThreshold > 0.0) {
    record.state = outlierTest(s, record);
  }
  if (record.state == FEATURE_ACTIVE) {
    ++m_workActive;
    record.M0 = m_data->getZeroPoint(i); // H(q_l)^-1 M_l, for the next predictions (and the task's open loop)
    record.hasM0 = true;
    record.predicts = record.predicts || m_predict;
  }
  return record.state;
}

void vpServoFeatureHealth::endIteration()
{
  checkIteration("endIteration()");
  if (m_classified != m_work.size()) {
    std::ostringstream os;
    os << "only " << m_classified << " of the " << m_work.size()
       << " features were classified in this iteration; classify() every feature before endIteration()";
    fail(vpProjectiveException::notInitializedError, at("endIteration()"), os.str());
  }
  m_records.swap(m_work); // no allocation
  m_nbActive = m_workActive;
  m_inIteration = false;
  m_data = nullptr;
}

bool vpServoFeatureHealth::isInView(unsigned int i) const
{
  checkIndex(i, "isInView()");
  const bool classifiedNow = m_inIteration && m_work[i].iteration == m_iteration;
  return (classifiedNow ? m_work[i] : m_records[i]).inView;
}

const vpServoFeatureHealth::vpRecord &vpServoFeatureHealth::outcome(unsigned int i, const char *method) const
{
  checkIndex(i, method);
  return m_records[i];
}
