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
  vpProjectiveSelfCalibration's metric bundle adjustment: the estimate and its standard deviations in the getters'
  unit.
*/

#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpUniRand.h>

#include "selfcalibration/vpMetricAdjustment.h"
#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveSelfCalibration");
Eigen::Matrix3d intrinsicMatrix(const Eigen::Matrix<double, 5, 1> &k)
{
  Eigen::Matrix3d K;
  K << k(0), k(2), k(3), 0.0, k(1), k(4), 0.0, 0.0, 1.0;
  return K;
}
} // namespace

vpProjectiveSelfCalibration::vpProjectiveSelfCalibration()
    : m_calibrated(false), m_types(), m_mounting(vpProjectiveArmModel::EYE_TO_HAND), m_qRef(), m_frames(), m_left(),
      m_right(), m_lRr(), m_b(), m_axis(), m_point(), m_markers(), m_covariance(), m_observable(false), m_noise(0.0),
      m_residual(0.0), m_frameCount(0), m_observations(0), m_scale(SCALE_FROM_PRISMATIC_JOINTS), m_markerA(0),
      m_markerB(1), m_distance(0.0), m_unit(1.0), m_uncertainty()
{
}

vpProjectiveSelfCalibration::vpProjectiveSelfCalibration(const vpProjectiveArmModel &model,
                                                         const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames)
    : vpProjectiveSelfCalibration()
{
  const std::string where = at("vpProjectiveSelfCalibration()");
  if (model.getNumberOfJoints() == 0) {
    fail(vpProjectiveException::notInitializedError, where, "the model is empty; acquire or load one first");
  }
  const size_t n = model.getNumberOfJoints(), K = model.markers().size();
  for (const vpProjectiveArmAcquisition::vpFrame &f : frames) {
    if (static_cast<size_t>(f.q.size()) != n || f.s.size() != K || f.seen.size() != K) {
      std::ostringstream os;
      os << "a frame has " << f.q.size() << " joint readings and " << f.s.size() << " marker images, the model " << n
         << " joints and " << K << " markers; give every frame the model's joints and markers";
      fail(vpProjectiveException::dimensionError, where, os.str());
    }
  }
  const MetricChain chain{model.jointTypes(), model.getRigMounting(), model.zeroReferenceJoints()};
  const MetricArm start = metricStart(model);
  MetricArm arm = start;
  MetricProblem problem(chain, start);
  for (const vpProjectiveArmAcquisition::vpFrame &f : frames) {
    MetricFrame frame{f.q, f.s, f.seen};
    problem.addFrame(frame);
    unsigned int observed = 0;
    for (size_t j = 0; j < K; ++j) {
      observed += f.seen[j] ? 1u : 0u;
    }
    m_observations += observed;
    m_frameCount += observed > 0 ? 1u : 0u;
  }
  const unsigned int unknowns = MetricLayout::size(static_cast<unsigned int>(n), static_cast<unsigned int>(K));
  m_covariance = Eigen::MatrixXd::Zero(unknowns, unknowns);
  if (m_observations > 0) {
    if (!problem.solve()) {
      fail(vpProjectiveException::estimationFailedError, where,
           "the metric bundle adjustment failed; check that every frame's markers are in the model's order and its "
           "readings the encoders' (the zero reference's unit)");
    }
    arm = problem.estimate();
    double sum = 0.0;
    unsigned int residuals = 0, parameters = 0;
    problem.cost(sum, residuals, parameters);
    m_residual = std::sqrt(sum / residuals);
    Eigen::MatrixXd tangent, L;
    m_observable = residuals > parameters && problem.covariance(tangent, L);
    if (m_observable) {
      m_noise = std::sqrt(sum / (residuals - parameters));
      const Eigen::MatrixXd LT = L.lazyProduct(tangent);
      m_covariance = m_noise * m_noise * LT.lazyProduct(L.transpose());
    }
  }
  if (!m_observable) {
    m_covariance.diagonal().setConstant(kInfinity);
  }
  m_calibrated = true;
  m_types = model.jointTypes();
  m_mounting = model.getRigMounting();
  m_qRef = model.zeroReferenceJoints();
  m_frames = frames;
  m_left = arm.left;
  m_right = arm.right;
  m_lRr = arm.lRr;
  m_b = arm.b;
  m_axis = arm.axis;
  m_point = arm.point;
  m_markers = arm.X;
  derive();
}

void vpProjectiveSelfCalibration::setScale(vpScale scale, unsigned int markerA, unsigned int markerB, double distance)
{
  const std::string where = at("setScale()");
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, where, "no calibration; construct it from a model first");
  }
  if (scale == SCALE_MARKER_DISTANCE) {
    checkMarkerDistance(markerA, markerB, distance, m_markers.size(), where);
  }
  m_scale = scale;
  m_markerA = markerA;
  m_markerB = markerB;
  m_distance = distance;
  derive();
}

void vpProjectiveSelfCalibration::derive()
{
  const unsigned int n = static_cast<unsigned int>(m_axis.size());
  // The translation of lMr in the getters' unit as a function of b and the two scale markers, and its Jacobian.
  const int iA = MetricLayout::marker(n, m_markerA), iB = MetricLayout::marker(n, m_markerB);
  auto translation = [&](const Eigen::Vector3d &b, const Eigen::Vector3d &A, const Eigen::Vector3d &B) {
    if (m_scale == SCALE_UNIT_BASELINE) {
      return Eigen::Vector3d(b / b.norm());
    }
    return m_scale == SCALE_MARKER_DISTANCE ? Eigen::Vector3d(m_distance * b / (A - B).norm()) : b;
  };
  const Eigen::Vector3d &A = m_markers[m_markerA], &B = m_markers[m_markerB]; // a model has 5 markers or more
  const Eigen::Vector3d t = translation(m_b, A, B);
  m_unit = t.norm() / m_b.norm();
  Eigen::Matrix<double, 3, 9> J; // central differences: a smooth map of 9 variables
  Eigen::Matrix<double, 9, 1> x;
  x << m_b, A, B;
  for (int c = 0; c < 9; ++c) {
    const double h = 1e-6 * std::max(1.0, std::abs(x(c)));
    Eigen::Matrix<double, 9, 1> up = x, down = x;
    up(c) += h;
    down(c) -= h;
    J.col(c) = (translation(up.head<3>(), up.segment<3>(3), up.tail<3>()) -
                translation(down.head<3>(), down.segment<3>(3), down.tail<3>())) /
               (2.0 * h);
  }
  const int index[3] = {MetricLayout::kBaseline, iA, iB};
  Eigen::Matrix<double, 9, 9> S9;
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) {
      S9.block<3, 3>(3 * r, 3 * c) = m_covariance.block<3, 3>(index[r], index[c]);
    }
  }
  const Eigen::Matrix3d St = m_observable ? Eigen::Matrix3d(J * S9 * J.transpose())
                                          : Eigen::Matrix3d(Eigen::Vector3d::Constant(kInfinity).asDiagonal());
  vpUncertainty &u = m_uncertainty;
  u.left = m_covariance.diagonal().segment<5>(MetricLayout::kLeft).cwiseSqrt();
  u.right = m_covariance.diagonal().segment<5>(MetricLayout::kRight).cwiseSqrt();
  u.rotation = m_covariance.diagonal().segment<3>(MetricLayout::kRotation).cwiseSqrt();
  u.translation = St.diagonal().cwiseMax(0.0).cwiseSqrt();
  u.baselineDirection = m_observable ? directionDeviation(t.normalized(), St, t.norm()) : kInfinity;
  u.baselineLength =
      m_observable ? std::sqrt(std::max(0.0, double(t.normalized().transpose() * St * t.normalized()))) : kInfinity;
  u.jointDirection.assign(n, kInfinity);
  u.jointPoint.assign(n, kInfinity);
  for (unsigned int i = 0; m_observable && i < n; ++i) {
    const int o = MetricLayout::joint(i);
    u.jointDirection[i] = directionDeviation(m_axis[i], m_covariance.block<3, 3>(o, o), 1.0);
    u.jointPoint[i] = m_unit * largestDeviation(m_covariance.block<3, 3>(o + 3, o + 3));
  }
}

void vpProjectiveSelfCalibration::getMetricStereoRig(Eigen::Matrix3d &Kl, Eigen::Matrix3d &Kr,
                                                     Eigen::Matrix4d &lMr) const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at("getMetricStereoRig()"),
         "no calibration; construct it from a model first");
  }
  Kl = intrinsicMatrix(m_left);
  Kr = intrinsicMatrix(m_right);
  lMr.setIdentity();
  lMr.topLeftCorner<3, 3>() = m_lRr;
  lMr.topRightCorner<3, 1>() = m_unit * m_b;
}

void vpProjectiveSelfCalibration::getJointAxes(std::vector<Eigen::Vector3d> &direction,
                                               std::vector<Eigen::Vector3d> &point) const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at("getJointAxes()"),
         "no calibration; construct it from a model first");
  }
  direction = m_axis;
  point.clear();
  for (const Eigen::Vector3d &p : m_point) {
    point.push_back(m_unit * p);
  }
}

std::vector<Eigen::Vector3d> vpProjectiveSelfCalibration::getMarkers() const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at("getMarkers()"),
         "no calibration; construct it from a model first");
  }
  std::vector<Eigen::Vector3d> X;
  for (const Eigen::Vector3d &Xj : m_markers) {
    X.push_back(m_unit * Xj);
  }
  return X;
}

const vpProjectiveSelfCalibration::vpUncertainty &vpProjectiveSelfCalibration::getUncertainty() const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at("getUncertainty()"),
         "no calibration; construct it from a model first");
  }
  return m_uncertainty;
}
