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

#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/projective/vpMetricTwist.h>

#include "selfcalibration/vpMetricAdjustment.h"
#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveSelfCalibration");

//! A camera \f$ \lambda K [R | t] \f$ of the metric frame, decomposed.
struct MetricCamera {
  Eigen::Matrix3d K; // K(2, 2) = 1
  Eigen::Matrix3d R;
  Eigen::Vector3d t;
};

/*!
  RQ decomposition of the camera \e C (3x4, metric frame) whose sign puts the points \e X (homogeneous, metric frame)
  in front of it: \f$ C \simeq K [R | t] \f$, K upper triangular with a positive diagonal. False if C's left block is
  singular. \e R is improper when the metric frame is mirrored.
*/
bool decompose(Eigen::Matrix<double, 3, 4> C, const std::vector<Eigen::Vector4d> &X, MetricCamera &camera)
{
  double depth = 0.0;
  for (const Eigen::Vector4d &Xj : X) {
    depth += (C.row(2).dot(Xj)) / Xj(3);
  }
  if (depth < 0.0) {
    C = -C;
  }
  const Eigen::Matrix3d A = C.leftCols<3>();
  if (!(std::abs(A.determinant()) > 1e-12 * std::pow(A.norm(), 3))) {
    return false;
  }
  // A = K R from the QR decomposition of (E A)^T, E the exchange matrix: (E A)^T = Q U gives A = (E U^T E)(E Q^T).
  Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
  E(0, 2) = E(1, 1) = E(2, 0) = 1.0;
  const Eigen::HouseholderQR<Eigen::Matrix3d> qr((E * A).transpose());
  const Eigen::Matrix3d U = qr.matrixQR().triangularView<Eigen::Upper>();
  const Eigen::Matrix3d Q = qr.householderQ();
  Eigen::Matrix3d K = E * U.transpose() * E;
  Eigen::Matrix3d R = E * Q.transpose();
  const Eigen::Vector3d signs = K.diagonal().cwiseSign();
  K = K * signs.asDiagonal();
  R = signs.asDiagonal() * R;
  camera.t = K.inverse() * C.col(3);
  camera.K = K / K(2, 2);
  camera.R = R;
  return camera.K.allFinite() && camera.R.allFinite() && camera.t.allFinite();
}

/*!
  The metric frame of the left camera: the rigid map \e lMe from the model's metric frame E' (of G, made
  right-handed) to the left camera's, the scale \e s from E' lengths to the output unit, and both cameras.
*/
struct MetricRig {
  MetricCamera left, right;
  Eigen::Matrix4d lMe; // left camera frame from the model's metric frame E', E' units
  double s;
};

MetricRig metricRig(const vpProjectiveArmModel &model, vpProjectiveSelfCalibration::vpScale scale, unsigned int markerA,
                    unsigned int markerB, double distance, const std::string &where)
{
  if (model.getNumberOfJoints() == 0) {
    fail(vpProjectiveException::notInitializedError, where, "the model is empty; acquire or load one first");
  }
  Eigen::Matrix4d G = model.projectiveToMetric();
  vpProjectiveStereoRig::Projection P, Pp;
  model.getStereoRig().getLeftProjection(P);
  model.getStereoRig().getRightProjection(Pp);
  MetricRig m;
  double mirror = 1.0;
  for (int pass = 0; pass < 2; ++pass) {
    const Eigen::Matrix4d Ginv = G.inverse();
    std::vector<Eigen::Vector4d> X;
    for (const Eigen::Vector4d &M : model.markers()) {
      X.push_back(G * M);
    }
    if (!decompose(P * Ginv, X, m.left) || !decompose(Pp * Ginv, X, m.right)) {
      fail(vpProjectiveException::degenerateConfigurationError, where,
           "a camera matrix is singular in the model's metric frame: the acquisition gave no metric upgrade");
    }
    if (m.left.R.determinant() > 0.0) {
      break;
    }
    // A mirrored metric frame (the similarity G contains a reflection): the same frame with z negated.
    G = Eigen::Vector4d(1.0, 1.0, -1.0, 1.0).asDiagonal() * G;
    mirror = -1.0;
  }
  if (m.left.R.determinant() < 0.0 || m.right.R.determinant() < 0.0) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the two cameras disagree on the handedness of the metric frame: the model's metric upgrade is inconsistent");
  }
  m.lMe.setIdentity();
  m.lMe.topLeftCorner<3, 3>() = m.left.R;
  m.lMe.topRightCorner<3, 1>() = m.left.t;
  m.lMe = m.lMe * Eigen::Vector4d(1.0, 1.0, mirror, 1.0).asDiagonal(); // from the model's own metric frame
  const Eigen::Vector3d baseline = m.right.R.transpose() * m.right.t - m.left.R.transpose() * m.left.t; // centres
  double unitLength = 0.0; // length in E' of one output unit
  if (scale == vpProjectiveSelfCalibration::SCALE_FROM_PRISMATIC_JOINTS) {
    unsigned int prismatic = 0;
    for (unsigned int i = 0; i < model.getNumberOfJoints(); ++i) {
      if (model.jointType(i) == vpProjectiveJoint::PRISMATIC) {
        unitLength += model.axis(i).norm();
        ++prismatic;
      }
    }
    unitLength = prismatic > 0 ? unitLength / prismatic : baseline.norm();
  } else if (scale == vpProjectiveSelfCalibration::SCALE_UNIT_BASELINE) {
    unitLength = baseline.norm();
  } else {
    checkMarkerDistance(markerA, markerB, distance, model.markers().size(), where);
    const Eigen::Vector4d A = G * model.markers()[markerA], B = G * model.markers()[markerB];
    unitLength = (A.head<3>() / A(3) - B.head<3>() / B(3)).norm() / distance;
  }
  if (!(unitLength > 0.0) || !std::isfinite(unitLength)) {
    fail(vpProjectiveException::degenerateConfigurationError, where, "the metric scale is zero or not finite");
  }
  m.s = 1.0 / unitLength;
  return m;
}

//! The joints' axes of \e model in the left camera's frame of \e m, lengths in its output unit.
void axesOf(const vpProjectiveArmModel &model, const MetricRig &m, std::vector<Eigen::Vector3d> &direction,
            std::vector<Eigen::Vector3d> &point)
{
  // Twists of E' carried to the left camera's frame, lengths scaled to the output unit: C That C^-1.
  Eigen::Matrix4d C = m.lMe;
  C.topRows<3>() *= m.s;
  const Eigen::Matrix4d Cinv = C.inverse();
  direction.assign(model.getNumberOfJoints(), Eigen::Vector3d::Zero());
  point.assign(model.getNumberOfJoints(), Eigen::Vector3d::Zero());
  for (unsigned int i = 0; i < model.getNumberOfJoints(); ++i) {
    const Eigen::Matrix<double, 6, 1> xi = vpMetricTwist::vee(Eigen::Matrix4d(C * model.twist(i) * Cinv));
    const Eigen::Vector3d v = xi.head<3>(), w = xi.tail<3>();
    if (model.jointType(i) == vpProjectiveJoint::REVOLUTE) {
      direction[i] = w.normalized();
      point[i] = w.cross(v) / w.squaredNorm(); // the axis' point nearest to the camera centre
    } else {
      direction[i] = v.normalized();
    }
  }
}

//! (fx, fy, skew, u0, v0) of K.
Eigen::Matrix<double, 5, 1> intrinsicsOf(const Eigen::Matrix3d &K)
{
  Eigen::Matrix<double, 5, 1> k;
  k << K(0, 0), K(1, 1), K(0, 1), K(0, 2), K(1, 2);
  return k;
}
} // namespace

namespace vpProjectiveInternal
{
MetricArm metricStart(const vpProjectiveArmModel &model)
{
  const MetricRig m = metricRig(model, vpProjectiveSelfCalibration::SCALE_FROM_PRISMATIC_JOINTS, 0, 1, 0.0,
                                at("vpProjectiveSelfCalibration()"));
  MetricArm arm;
  arm.left = intrinsicsOf(m.left.K);
  arm.right = intrinsicsOf(m.right.K);
  arm.lRr = m.left.R * m.right.R.transpose();
  arm.b = m.s * (m.left.t - arm.lRr * m.right.t);
  axesOf(model, m, arm.axis, arm.point);
  const Eigen::Matrix4d lNe = m.lMe * model.projectiveToMetric(); // projective frame to the left camera's, E' units
  for (const Eigen::Vector4d &M : model.markers()) {
    const Eigen::Vector4d N = lNe * M;
    arm.X.push_back(m.s * N.head<3>() / N(3));
  }
  return arm;
}
} // namespace vpProjectiveInternal

double vpProjectiveSelfCalibration::metricStereoRig(const vpProjectiveArmModel &model, Eigen::Matrix3d &Kl,
                                                    Eigen::Matrix3d &Kr, Eigen::Matrix4d &lMr, vpScale scale,
                                                    unsigned int markerA, unsigned int markerB, double distance)
{
  const MetricRig m = metricRig(model, scale, markerA, markerB, distance, at("metricStereoRig()"));
  Kl = m.left.K;
  Kr = m.right.K;
  const Eigen::Matrix3d R = m.left.R * m.right.R.transpose();
  lMr.setIdentity();
  lMr.topLeftCorner<3, 3>() = R;
  lMr.topRightCorner<3, 1>() = m.s * (m.left.t - R * m.right.t);
  return m.s;
}

void vpProjectiveSelfCalibration::jointAxes(const vpProjectiveArmModel &model, std::vector<Eigen::Vector3d> &direction,
                                            std::vector<Eigen::Vector3d> &point, vpScale scale, unsigned int markerA,
                                            unsigned int markerB, double distance)
{
  axesOf(model, metricRig(model, scale, markerA, markerB, distance, at("jointAxes()")), direction, point);
}
