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
  vpProjectiveSelfCalibration: the largest uncertainty, the configurations that would shrink it most, the report.
*/

#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include <algorithm>
#include <cmath>
#include <iomanip>

#include <Eigen/Dense>

#include <visp3/core/vpUniRand.h>

#include "selfcalibration/vpMetricAdjustment.h"
#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveSelfCalibration");

/*!
  The dimensionless deviations of the rig (see getLargestUncertainty()) from the covariance \e S of the layout and
  the estimate; \e names, if not null, receives their names.
*/
std::vector<double> rigDeviations(const Eigen::MatrixXd &S, const Eigen::Matrix<double, 5, 1> &left,
                                  const Eigen::Matrix<double, 5, 1> &right, const Eigen::Vector3d &b,
                                  bool lengthIsScale, std::vector<std::string> *names)
{
  std::vector<double> x;
  const char *const camera[2] = {"left ", "right "};
  const char *const what[5] = {"fx", "fy", "skew", "u0", "v0"};
  const int focal[5] = {0, 1, 0, 0, 1}; // the focal length each deviation is relative to
  for (int c = 0; c < 2; ++c) {
    const Eigen::Matrix<double, 5, 1> &k = c == 0 ? left : right;
    const int offset = c == 0 ? MetricLayout::kLeft : MetricLayout::kRight;
    for (int e = 0; e < 5; ++e) {
      x.push_back(std::sqrt(S(offset + e, offset + e)) / k(focal[e]));
      if (names != nullptr) {
        names->push_back(std::string(camera[c]) + what[e]);
      }
    }
  }
  x.push_back(largestDeviation(S.block<3, 3>(MetricLayout::kRotation, MetricLayout::kRotation)));
  const Eigen::Matrix3d Sb = S.block<3, 3>(MetricLayout::kBaseline, MetricLayout::kBaseline);
  x.push_back(directionDeviation(b.normalized(), Sb, b.norm()));
  if (names != nullptr) {
    names->push_back("rig rotation");
    names->push_back("baseline direction");
  }
  if (!lengthIsScale) {
    x.push_back(std::sqrt(std::max(0.0, double(b.normalized().transpose() * Sb * b.normalized()))) / b.norm());
    if (names != nullptr) {
      names->push_back("baseline length");
    }
  }
  return x;
}
} // namespace

double vpProjectiveSelfCalibration::getLargestUncertainty(std::string *what) const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at("getLargestUncertainty()"),
         "no calibration; construct it from a model first");
  }
  std::vector<std::string> names;
  const bool unitBaseline = !MetricChain{m_types, m_mounting, m_qRef}.hasPrismatic();
  const std::vector<double> x = rigDeviations(m_covariance, m_left, m_right, m_b, unitBaseline, &names);
  size_t k = 0;
  for (size_t e = 1; e < x.size(); ++e) {
    k = x[e] > x[k] ? e : k;
  }
  if (what != nullptr) {
    *what = names[k];
  }
  return x[k];
}

std::vector<vpColVector> vpProjectiveSelfCalibration::suggestConfigurations(
    unsigned int count, const vpColVector &qmin, const vpColVector &qmax, unsigned int width, unsigned int height,
    std::vector<double> *largest, unsigned int candidates, unsigned int seed) const
{
  const std::string where = at("suggestConfigurations()");
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, where, "no calibration; construct it from a model first");
  }
  const size_t n = m_types.size();
  const vpProjectiveArmModel::JointVector lower =
      toEigenVector<vpProjectiveArmModel::JointVector>(qmin, n, where, "the lower bounds");
  const vpProjectiveArmModel::JointVector upper =
      toEigenVector<vpProjectiveArmModel::JointVector>(qmax, n, where, "the upper bounds");
  if ((upper - lower).minCoeff() < 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "a lower bound exceeds its upper bound; swap them");
  }
  if (!m_observable) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the frames do not determine every parameter (no covariance): add frames where every joint has moved");
  }
  // The covariance again, in the tangent space of a problem at the estimate (the candidates' Jacobians are in it).
  const MetricChain chain{m_types, m_mounting, m_qRef};
  const MetricArm arm{m_left, m_right, m_lRr, m_b, m_axis, m_point, m_markers};
  MetricProblem problem(chain, arm);
  for (const vpProjectiveArmAcquisition::vpFrame &f : m_frames) {
    problem.addFrame(MetricFrame{f.q, f.s, f.seen});
  }
  const double margin = 10.0;
  const Eigen::Vector4d lowest = Eigen::Vector4d::Constant(margin);
  const Eigen::Vector4d highest(width - 1.0 - margin, height - 1.0 - margin, width - 1.0 - margin,
                                height - 1.0 - margin);
  Eigen::MatrixXd T, L;
  if (!problem.covariance(T, L)) {
    fail(vpProjectiveException::degenerateConfigurationError, where, "the covariance could not be computed again");
  }
  T *= m_noise * m_noise;
  const Eigen::MatrixXd Lrig = L.topRows(MetricLayout::kJoints);
  const bool unitBaseline = !chain.hasPrismatic();
  vpUniRand rng(seed);
  std::vector<vpProjectiveArmModel::JointVector> pool;
  std::vector<Eigen::MatrixXd> jacobians;
  for (unsigned int c = 0; c < candidates; ++c) {
    vpProjectiveArmModel::JointVector q(n);
    for (size_t i = 0; i < n; ++i) {
      q(i) = rng.uniform(lower(i), upper(i));
    }
    std::vector<Eigen::Vector4d> s;
    bool inside = predictFrame(chain, arm, q, s);
    for (size_t j = 0; inside && j < s.size(); ++j) {
      inside = (s[j] - lowest).minCoeff() >= 0.0 && (highest - s[j]).minCoeff() >= 0.0;
    }
    const Eigen::MatrixXd J = inside ? problem.frameJacobian(q) : Eigen::MatrixXd();
    if (J.size() > 0) {
      pool.push_back(q);
      jacobians.push_back(J);
    }
  }
  if (pool.empty()) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "no random configuration within the bounds keeps the markers in both images; check the image size, widen "
         "the bounds or give more candidates");
  }
  std::vector<vpColVector> chosen;
  if (largest != nullptr) {
    largest->clear();
  }
  for (unsigned int r = 0; r < count && !pool.empty(); ++r) {
    double best = kInfinity;
    size_t bestIndex = 0;
    const Eigen::MatrixXd LT = Lrig.lazyProduct(T), S0 = LT.lazyProduct(Lrig.transpose());
    for (size_t c = 0; c < pool.size(); ++c) {
      // Woodbury: the covariance after the candidate's images is T - T J^T (sigma^2 I + J T J^T)^-1 J T; of the rig's
      // parameters, Lrig T Lrig^T - A (sigma^2 I + J T J^T)^-1 A^T with A = Lrig T J^T.
      const Eigen::MatrixXd &J = jacobians[c];
      const Eigen::MatrixXd JT = J.lazyProduct(T);
      Eigen::MatrixXd M = JT.lazyProduct(J.transpose());
      M.diagonal().array() += m_noise * m_noise;
      const Eigen::MatrixXd A = LT.lazyProduct(J.transpose());
      const Eigen::MatrixXd S = S0 - A * M.ldlt().solve(A.transpose());
      const std::vector<double> x = rigDeviations(S, m_left, m_right, m_b, unitBaseline, nullptr);
      const double worst = *std::max_element(x.begin(), x.end());
      if (worst < best) {
        best = worst;
        bestIndex = c;
      }
    }
    const Eigen::MatrixXd &J = jacobians[bestIndex];
    const Eigen::MatrixXd TJt = T.lazyProduct(J.transpose());
    Eigen::MatrixXd M = J.lazyProduct(TJt);
    M.diagonal().array() += m_noise * m_noise;
    T -= TJt.lazyProduct(M.ldlt().solve(TJt.transpose()));
    chosen.push_back(toVispVector(pool[bestIndex]));
    if (largest != nullptr) {
      largest->push_back(best);
    }
    pool.erase(pool.begin() + static_cast<long>(bestIndex));
    jacobians.erase(jacobians.begin() + static_cast<long>(bestIndex));
  }
  return chosen;
}

void vpProjectiveSelfCalibration::print(std::ostream &os) const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at("print()"), "no calibration; construct it from a model first");
  }
  const bool prismatic = MetricChain{m_types, m_mounting, m_qRef}.hasPrismatic();
  const char *unit = m_scale == SCALE_MARKER_DISTANCE ? "the marker distance's unit"
                     : m_scale == SCALE_UNIT_BASELINE || !prismatic
                         ? "unit baseline: no prismatic joint fixes the scale"
                         : "prismatic joints' unit";
  const std::ios::fmtflags flags = os.flags();
  const std::streamsize precision = os.precision();
  os << "metric self-calibration (axes and t in the left camera's frame, lengths in the " << unit << "; +- one "
     << "standard deviation):" << std::endl;
  os << std::fixed << std::setprecision(3) << "  bundle adjustment over " << m_frameCount << " frames, "
     << m_observations << " marker observations: noise " << m_noise << " px, RMS residual " << m_residual << " px"
     << std::endl;
  if (!m_observable) {
    os << "  no uncertainty: "
       << (m_observations == 0 ? "no frames (the read-out of the model's upgrade)"
                               : "the frames do not determine every parameter (add frames where every joint moved)")
       << std::endl;
  }
  const char *const names[5] = {"fx", "fy", "skew", "u0", "v0"};
  for (int c = 0; c < 2; ++c) {
    const Eigen::Matrix<double, 5, 1> &k = c == 0 ? m_left : m_right;
    const Eigen::Matrix<double, 5, 1> &sigma = c == 0 ? m_uncertainty.left : m_uncertainty.right;
    os << std::setprecision(2) << (c == 0 ? "  left K: " : "  right K:");
    for (int e = 0; e < 5; ++e) {
      os << (e == 0 ? " " : ", ") << names[e] << " " << k(e) << " +- " << sigma(e);
    }
    os << std::endl;
  }
  const Eigen::AngleAxisd aa(m_lRr);
  const Eigen::Vector3d tu = aa.angle() * aa.axis() * 180.0 / M_PI, t = m_unit * m_b;
  const Eigen::Vector3d sr = m_uncertainty.rotation * 180.0 / M_PI, st = m_uncertainty.translation;
  os << std::setprecision(3) << "  right camera in the left one: R (theta-u, deg) (" << tu(0) << ", " << tu(1) << ", "
     << tu(2) << ") +- (" << sr(0) << ", " << sr(1) << ", " << sr(2) << ")" << std::endl;
  os << std::setprecision(4) << "  t (" << t(0) << ", " << t(1) << ", " << t(2) << ") +- (" << st(0) << ", " << st(1)
     << ", " << st(2) << "), baseline " << t.norm() << " +- " << m_uncertainty.baselineLength << ", direction +- "
     << std::setprecision(3) << m_uncertainty.baselineDirection * 180.0 / M_PI << " deg" << std::endl;
  for (size_t i = 0; i < m_axis.size(); ++i) {
    const Eigen::Vector3d p = m_unit * m_point[i];
    os << std::setprecision(4) << "  joint " << i << ": direction (" << m_axis[i](0) << ", " << m_axis[i](1) << ", "
       << m_axis[i](2) << ") +- " << std::setprecision(3) << m_uncertainty.jointDirection[i] * 180.0 / M_PI << " deg";
    if (m_types[i] == vpProjectiveJoint::REVOLUTE) {
      os << std::setprecision(4) << ", through (" << p(0) << ", " << p(1) << ", " << p(2) << ") +- "
         << m_uncertainty.jointPoint[i];
    }
    os << std::endl;
  }
  std::string what;
  const double worst = getLargestUncertainty(&what);
  os << std::setprecision(3) << "  largest uncertainty: " << what << ", " << worst * 180.0 / M_PI << " deg ("
     << 100.0 * worst << " % of a focal length)" << std::endl;
  os.flags(flags);
  os.precision(precision);
}
