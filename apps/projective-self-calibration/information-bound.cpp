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

/*!
  \file information-bound.cpp
  \brief The Cramer-Rao bound of the metric self-calibration at a world's true parameters.
*/

#include "information-bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include <visp3/core/vpGaussRand.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
namespace
{
//! Two unit vectors normal to \e w and to each other.
void normals(const Eigen::Vector3d &w, Eigen::Vector3d &e1, Eigen::Vector3d &e2)
{
  e1 = w.cross(std::abs(w(0)) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY()).normalized();
  e2 = w.cross(e1).normalized();
}

double largestDeviation(const Eigen::MatrixXd &S)
{
  return std::sqrt(std::max(0.0, Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(S).eigenvalues().maxCoeff()));
}
} // namespace

MetricModel trueModel(const StudyArm &arm, const SkewedRig &rig)
{
  MetricModel m;
  m.k << rig.Kl(0, 0), rig.Kl(1, 1), rig.Kl(0, 1), rig.Kl(0, 2), rig.Kl(1, 2), rig.Kr(0, 0), rig.Kr(1, 1), rig.Kr(0, 1),
      rig.Kr(0, 2), rig.Kr(1, 2);
  const Eigen::Matrix4d lMr = eigenOf(rig.lMr()), lMw = eigenOf(rig.wMl.inverse());
  m.lRr = lMr.topLeftCorner<3, 3>();
  m.b = lMr.topRightCorner<3, 1>();
  const unsigned int n = arm.arm.getNumberOfJoints();
  m.qRef = Eigen::VectorXd(n);
  // The simulator's twists are at q = 0, world frame; at the zero reference joint i's is moved by the joints before
  // it: A T_i A^-1, A = exp(qref_0 T_0) ... exp(qref_{i-1} T_{i-1}); then carried to the left camera's frame.
  Eigen::Matrix4d A = Eigen::Matrix4d::Identity();
  for (unsigned int i = 0; i < n; ++i) {
    const vpMatrix T0 = arm.arm.getTwist(i);
    Eigen::Matrix4d T;
    for (unsigned int r = 0; r < 4; ++r) {
      for (unsigned int c = 0; c < 4; ++c) {
        T(r, c) = T0[r][c];
      }
    }
    const vpProjectiveJoint::vpJointType type = arm.arm.getJointType(i);
    m.qRef(i) = arm.qRef[i];
    const Eigen::Matrix4d Tl = lMw * A * T * A.inverse() * lMw.inverse();
    A = A * vpProjectiveJoint::exp(type, T, arm.qRef[i]);
    const Eigen::Vector3d w(Tl(2, 1), Tl(0, 2), Tl(1, 0)), v = Tl.topRightCorner<3, 1>();
    m.types.push_back(type);
    m.axis.push_back(type == vpProjectiveJoint::REVOLUTE ? w : v);
    m.point.push_back(type == vpProjectiveJoint::REVOLUTE ? Eigen::Vector3d(w.cross(v) / w.squaredNorm())
                                                          : Eigen::Vector3d::Zero());
  }
  for (const vpColVector &wX : arm.arm.getMarkers(arm.qRef)) {
    m.X.push_back((lMw * Eigen::Vector4d(wX[0], wX[1], wX[2], 1.0)).head<3>());
  }
  return m;
}

Eigen::VectorXd predict(const MetricModel &model, const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames)
{
  std::vector<double> s;
  Eigen::Matrix3d K[2];
  for (int c = 0; c < 2; ++c) {
    const Eigen::Matrix<double, 5, 1> k = model.k.segment<5>(5 * c);
    K[c] << k(0), k(2), k(3), 0.0, k(1), k(4), 0.0, 0.0, 1.0;
  }
  for (const vpProjectiveArmAcquisition::vpFrame &f : frames) {
    Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
    for (size_t i = 0; i < model.types.size(); ++i) {
      const Eigen::Index e = static_cast<Eigen::Index>(i);
      T = T * vpProjectiveJoint::exp(model.types[i],
                                     vpProjectiveJoint::twist(model.types[i], model.axis[i], model.point[i]),
                                     f.q(e) - model.qRef(e));
    }
    for (size_t j = 0; j < model.X.size(); ++j) {
      if (f.seen[j]) {
        const Eigen::Vector3d Xl = (T * model.X[j].homogeneous()).head<3>();
        const Eigen::Vector3d ml = K[0] * Xl, mr = K[1] * (model.lRr.transpose() * (Xl - model.b));
        s.insert(s.end(), {ml(0) / ml(2), ml(1) / ml(2), mr(0) / mr(2), mr(1) / mr(2)});
      }
    }
  }
  return Eigen::Map<const Eigen::VectorXd>(s.data(), static_cast<Eigen::Index>(s.size()));
}

MetricParameters::MetricParameters(const MetricModel &model, bool unitBaseline)
    : m_model(model), m_unitBaseline(unitBaseline), m_e1(), m_e2(), m_joint(), m_marker(0), m_size(0)
{
  int o = kBaseline + baselineSize();
  for (size_t i = 0; i < model.types.size(); ++i) {
    Eigen::Vector3d e1, e2;
    normals(model.axis[i].normalized(), e1, e2);
    m_e1.push_back(e1);
    m_e2.push_back(e2);
    m_joint.push_back(o);
    o += model.types[i] == vpProjectiveJoint::REVOLUTE ? 4 : 2;
  }
  Eigen::Vector3d e1, e2;
  normals(model.b.normalized(), e1, e2);
  m_e1.push_back(e1);
  m_e2.push_back(e2);
  m_marker = o;
  m_size = o + 3 * static_cast<int>(model.X.size());
}

MetricModel MetricParameters::moved(const Eigen::VectorXd &x) const
{
  MetricModel m = m_model;
  m.k += x.head<10>();
  const Eigen::Vector3d phi = x.segment<3>(kRotation);
  m.lRr = Eigen::AngleAxisd(phi.norm(), phi.norm() > 0.0 ? phi.normalized() : Eigen::Vector3d::UnitX().eval()) * m.lRr;
  const size_t n = m.types.size();
  m.b += m_unitBaseline ? Eigen::Vector3d(x(kBaseline) * m_e1[n] + x(kBaseline + 1) * m_e2[n])
                        : Eigen::Vector3d(x.segment<3>(kBaseline));
  for (size_t i = 0; i < n; ++i) {
    const int o = m_joint[i];
    m.axis[i] = (m.axis[i] + x(o) * m_e1[i] + x(o + 1) * m_e2[i]).normalized();
    if (m.types[i] == vpProjectiveJoint::REVOLUTE) {
      m.point[i] += x(o + 2) * m_e1[i] + x(o + 3) * m_e2[i];
    }
  }
  for (size_t j = 0; j < m.X.size(); ++j) {
    m.X[j] += x.segment<3>(marker(j));
  }
  return m;
}

Eigen::MatrixXd pixelJacobian(const MetricParameters &p, const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames)
{
  const Eigen::Index rows = predict(p.model(), frames).size();
  Eigen::MatrixXd J(rows, p.size());
  for (int c = 0; c < p.size(); ++c) {
    const double h = c < MetricParameters::kRotation ? 1e-3 : 1e-6; // px; rad and m
    Eigen::VectorXd dx = Eigen::VectorXd::Zero(p.size());
    dx(c) = h;
    J.col(c) = (predict(p.moved(dx), frames) - predict(p.moved(-dx), frames)) / (2.0 * h);
  }
  return J;
}

namespace
{
/*!
  \e A (parameters x free parameters) with \f$ A A^T = \sigma^2 (J_f^T J_f)^{-1} \f$, J_f the columns of the
  parameters not \e known (the rows of the known ones zero); false if J_f lacks rank.
*/
bool covarianceFactor(const MetricParameters &p, const Eigen::MatrixXd &J, double sigma, unsigned int known,
                      Eigen::MatrixXd &A)
{
  std::vector<int> free;
  for (int c = 0; c < p.size(); ++c) {
    const bool skew = c == 2 || c == 7;
    const bool joint = c >= p.joint(0) && c < p.marker(0), marker = c >= p.marker(0);
    if (!((known & SKEW_KNOWN) && skew) && !((known & AXES_KNOWN) && joint) && !((known & MARKERS_KNOWN) && marker)) {
      free.push_back(c);
    }
  }
  Eigen::MatrixXd Jf(J.rows(), static_cast<Eigen::Index>(free.size()));
  for (size_t c = 0; c < free.size(); ++c) {
    Jf.col(static_cast<Eigen::Index>(c)) = J.col(free[c]);
  }
  // (J^T J)^-1 with the columns scaled to unit norm (pixels per px of intrinsics, per rad and per metre).
  const Eigen::VectorXd scale = Jf.colwise().norm().cwiseInverse().transpose();
  const Eigen::MatrixXd Js = Jf * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(Js.transpose() * Js);
  const Eigen::VectorXd lambda = eigen.eigenvalues();
  if (!(lambda.minCoeff() > 1e-14 * lambda.maxCoeff())) {
    return false;
  }
  const Eigen::MatrixXd Af =
      sigma * scale.asDiagonal() * eigen.eigenvectors() * lambda.cwiseSqrt().cwiseInverse().asDiagonal();
  A = Eigen::MatrixXd::Zero(p.size(), Af.cols());
  for (size_t r = 0; r < free.size(); ++r) {
    A.row(free[r]) = Af.row(static_cast<Eigen::Index>(r));
  }
  return true;
}

/*!
  The study's errors (as compare() measures them, in the deviations' units) of a parameters' error \e x: the worst
  relative focal length, the worst principal point and skew, the rotation's angle, the baseline's direction and its
  relative length (unit baseline: the ruler's markers 0 and 1 set the length).
*/
void errorsOf(const MetricParameters &p, const Eigen::VectorXd &x, double (&error)[PARAMETERS])
{
  const MetricModel &m = p.model();
  const double deg = 180.0 / M_PI, length = m.b.norm();
  const Eigen::Vector3d d = m.b / length;
  error[FOCAL] =
      std::max({std::abs(x(0)) / m.k(0), std::abs(x(1)) / m.k(1), std::abs(x(5)) / m.k(5), std::abs(x(6)) / m.k(6)});
  error[PRINCIPAL] = std::max({std::abs(x(3)), std::abs(x(4)), std::abs(x(8)), std::abs(x(9))});
  error[SKEW] = std::max(std::abs(x(2)), std::abs(x(7)));
  error[ROTATION] = deg * x.segment<3>(MetricParameters::kRotation).norm();
  if (p.unitBaseline()) {
    const Eigen::Vector3d D = m.X[0] - m.X[1];
    error[DIRECTION] = deg * x.segment<2>(MetricParameters::kBaseline).norm() / length;
    error[LENGTH] = std::abs(D.dot(x.segment<3>(p.marker(0)) - x.segment<3>(p.marker(1)))) / D.squaredNorm();
  } else {
    const Eigen::Vector3d db = x.segment<3>(MetricParameters::kBaseline);
    error[DIRECTION] = deg * (db - d * d.dot(db)).norm() / length;
    error[LENGTH] = std::abs(d.dot(db)) / length;
  }
}
} // namespace

void informationBound(const MetricParameters &p, const Eigen::MatrixXd &J, double sigma, unsigned int known,
                      double (&deviation)[PARAMETERS])
{
  Eigen::MatrixXd A;
  if (!covarianceFactor(p, J, sigma, known, A)) {
    std::fill(std::begin(deviation), std::end(deviation), std::numeric_limits<double>::infinity());
    return;
  }
  const Eigen::MatrixXd S = A * A.transpose();
  const MetricModel &m = p.model();
  auto sd = [&](int c) { return std::sqrt(S(c, c)); };
  deviation[FOCAL] = std::max({sd(0) / m.k(0), sd(1) / m.k(1), sd(5) / m.k(5), sd(6) / m.k(6)});
  deviation[PRINCIPAL] = std::max({sd(3), sd(4), sd(8), sd(9)});
  deviation[SKEW] = std::max(sd(2), sd(7));
  const double deg = 180.0 / M_PI;
  deviation[ROTATION] =
      deg * std::sqrt(S.block<3, 3>(MetricParameters::kRotation, MetricParameters::kRotation).trace());
  const double length = m.b.norm();
  const Eigen::Vector3d d = m.b / length;
  if (p.unitBaseline()) {
    // Across the baseline only; its length is fixed (the gauge), so its relative error is that of the distance of
    // markers 0 and 1 (the ruler's, which then sets every length).
    deviation[DIRECTION] =
        deg * largestDeviation(S.block<2, 2>(MetricParameters::kBaseline, MetricParameters::kBaseline)) / length;
    const Eigen::Vector3d D = m.X[0] - m.X[1];
    Eigen::VectorXd g = Eigen::VectorXd::Zero(p.size());
    g.segment<3>(p.marker(0)) = D / D.squaredNorm();
    g.segment<3>(p.marker(1)) = -D / D.squaredNorm();
    deviation[LENGTH] = std::sqrt(std::max(0.0, double(g.transpose() * S * g)));
  } else {
    const Eigen::Matrix3d Sb = S.block<3, 3>(MetricParameters::kBaseline, MetricParameters::kBaseline);
    const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
    deviation[DIRECTION] = deg * largestDeviation(P * Sb * P) / length;
    deviation[LENGTH] = std::sqrt(std::max(0.0, double(d.transpose() * Sb * d))) / length;
  }
}

void withinBounds(const MetricParameters &p, const Eigen::MatrixXd &J, double sigma, const double (&bounds)[PARAMETERS],
                  double (&probability)[PARAMETERS])
{
  Eigen::MatrixXd A;
  std::fill(std::begin(probability), std::end(probability), 0.0);
  if (!covarianceFactor(p, J, sigma, NOTHING_KNOWN, A)) {
    return;
  }
  const int kDraws = 4000;
  vpGaussRand normal(1.0, 0.0, 1234);
  Eigen::VectorXd z(A.cols());
  for (int k = 0; k < kDraws; ++k) {
    for (Eigen::Index i = 0; i < z.size(); ++i) {
      z(i) = normal();
    }
    double error[PARAMETERS];
    errorsOf(p, A * z, error);
    for (int e = 0; e < PARAMETERS; ++e) {
      probability[e] += error[e] <= bounds[e] ? 1.0 / kDraws : 0.0;
    }
  }
}

void statedDeviations(const vpProjectiveSelfCalibration::vpUncertainty &u, const Eigen::Matrix3d &Kl,
                      const Eigen::Matrix3d &Kr, const Eigen::Vector3d &t, double (&deviation)[PARAMETERS])
{
  deviation[FOCAL] =
      std::max({u.left(0) / Kl(0, 0), u.left(1) / Kl(1, 1), u.right(0) / Kr(0, 0), u.right(1) / Kr(1, 1)});
  deviation[PRINCIPAL] = std::max({u.left(3), u.left(4), u.right(3), u.right(4)});
  deviation[SKEW] = std::max(u.left(2), u.right(2));
  deviation[ROTATION] = u.rotation.norm() * 180.0 / M_PI;
  deviation[DIRECTION] = u.baselineDirection * 180.0 / M_PI;
  deviation[LENGTH] = u.baselineLength / t.norm();
}
} // namespace selfcal
