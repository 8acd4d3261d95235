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

#include <visp3/projective/vpProjectiveRigRegistration.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include "core/vpProjectiveCeres.h"
#include "core/vpProjectiveErrors.h"
#include "core/vpProjectiveNumerics.h"

using namespace vpProjectiveInternal;

namespace
{
const char *const kResect = "vpProjectiveRigRegistration::resect()";
const char *const kRegister = "vpProjectiveRigRegistration::registerRig()";

typedef vpProjectiveStereoRig::Projection Projection;

/*
  Pixel error of a camera A T(omega, t) (A = P0 G^-1, 3x4) at the metric point N = G X (4x1, homogeneous, never
  divided): T acts on N as (R N_xyz + t N_w, N_w).
*/
struct RigidCameraError {
  RigidCameraError(const Projection &A, const Eigen::Vector4d &N, const Eigen::Vector2d &uv) : m_A(A), m_N(N), m_uv(uv)
  {
  }

  template <typename T> bool operator()(const T *const pose, T *residual) const
  {
    const T p[3] = {T(m_N(0)), T(m_N(1)), T(m_N(2))};
    T Rp[3];
    ceres::AngleAxisRotatePoint(pose, p, Rp);
    Eigen::Matrix<T, 4, 1> TN;
    TN << Rp[0] + pose[3] * T(m_N(3)), Rp[1] + pose[4] * T(m_N(3)), Rp[2] + pose[5] * T(m_N(3)), T(m_N(3));
    const Eigen::Matrix<T, 3, 1> m = m_A.cast<T>() * TN;
    residual[0] = m(0) / m(2) - T(m_uv(0));
    residual[1] = m(1) / m(2) - T(m_uv(1));
    return true;
  }

  Projection m_A;
  Eigen::Vector4d m_N;
  Eigen::Vector2d m_uv;
};

//! Pixel error of a general camera P (12 entries, row-major) at the projective point X.
struct GeneralCameraError {
  GeneralCameraError(const Eigen::Vector4d &X, const Eigen::Vector2d &uv) : m_X(X), m_uv(uv) {}

  template <typename T> bool operator()(const T *const P, T *residual) const
  {
    T m[3];
    for (int r = 0; r < 3; ++r) {
      m[r] = P[4 * r] * T(m_X(0)) + P[4 * r + 1] * T(m_X(1)) + P[4 * r + 2] * T(m_X(2)) + P[4 * r + 3] * T(m_X(3));
    }
    residual[0] = m[0] / m[2] - T(m_uv(0));
    residual[1] = m[1] / m[2] - T(m_uv(1));
    return true;
  }

  Eigen::Vector4d m_X;
  Eigen::Vector2d m_uv;
};

//! RMS per coordinate (pixels) of camera P on the points; infinite if a point is on its focal plane.
double rmsError(const Projection &P, const std::vector<Eigen::Vector4d> &X, const std::vector<Eigen::Vector2d> &uv)
{
  double sum = 0.0;
  for (size_t k = 0; k < X.size(); ++k) {
    const Eigen::Vector3d m = P * X[k];
    if (!(std::abs(m(2)) > 1e-12 * P.norm() * X[k].norm())) {
      return std::numeric_limits<double>::infinity();
    }
    sum += (m.head<2>() / m(2) - uv[k]).squaredNorm();
  }
  const double rms = std::sqrt(sum / (2.0 * static_cast<double>(X.size())));
  return std::isfinite(rms) ? rms : std::numeric_limits<double>::infinity();
}

//! Linear resection (DLT) on Hartley-normalised pixels and whitened points; throws if undetermined.
Projection linearResection(const std::vector<Eigen::Vector4d> &X, const std::vector<Eigen::Vector2d> &uv)
{
  const Eigen::Matrix3d Tn = hartleyNormalization(uv);
  const Eigen::Matrix4d W = whitening(X);
  const Eigen::Index n = static_cast<Eigen::Index>(X.size());
  Eigen::MatrixXd A(2 * n, 12);
  Eigen::MatrixXd Xw(n, 4);
  for (Eigen::Index k = 0; k < n; ++k) {
    const Eigen::Vector4d Xk = (W * X[static_cast<size_t>(k)]).normalized();
    Xw.row(k) = Xk.transpose();
    const Eigen::Vector3d m = Tn * uv[static_cast<size_t>(k)].homogeneous();
    const Eigen::Vector2d x = m.head<2>() / m(2);
    A.row(2 * k) << Xk.transpose(), Eigen::RowVector4d::Zero(), -x(0) * Xk.transpose();
    A.row(2 * k + 1) << Eigen::RowVector4d::Zero(), Xk.transpose(), -x(1) * Xk.transpose();
  }
  // Coplanar (or collinear) points leave a camera undetermined whatever the noise: their whitened 4-vectors span
  // fewer than 4 dimensions.
  const Eigen::VectorXd spread = Eigen::JacobiSVD<Eigen::MatrixXd>(Xw).singularValues();
  if (!(spread(3) > 1e-3 * spread(0))) {
    fail(vpProjectiveException::degenerateConfigurationError, kResect,
         "the observed points are (nearly) coplanar or collinear, which leaves the camera undetermined; observe the "
         "markers at configurations that spread them in depth");
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  if (!(sigma(10) > 1e-9 * sigma(0))) {
    fail(vpProjectiveException::degenerateConfigurationError, kResect,
         "the linear resection is undetermined (repeated points?); observe the markers at other configurations");
  }
  Projection Pn;
  for (int r = 0; r < 3; ++r) {
    Pn.row(r) = svd.matrixV().col(11).segment<4>(4 * r).transpose();
  }
  Projection P = Tn.inverse() * Pn * W;
  return P / P.norm();
}

//! The rigid motion T (angle-axis, t) with A T closest to s B (A, B: 3x4; A's left block invertible).
void closestRigidMotion(const Projection &A, const Projection &B, double pose[6])
{
  const Eigen::Matrix3d Ainv = A.leftCols<3>().inverse();
  Eigen::Matrix3d M = Ainv * B.leftCols<3>();
  if (M.determinant() < 0.0) {
    M = -M;
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(M, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d R = svd.matrixU() * svd.matrixV().transpose();
  const double s = svd.singularValues().mean();
  const double sign = (Ainv * B.leftCols<3>()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Vector3d t = Ainv * (sign * B.col(3) / s) - Ainv * A.col(3);
  ceres::RotationMatrixToAngleAxis(ceres::ColumnMajorAdapter3x3(R.data()), pose);
  for (int i = 0; i < 3; ++i) {
    pose[3 + i] = t(i);
  }
}

Projection rigidCamera(const Projection &A, const double pose[6], const Eigen::Matrix4d &G)
{
  double Rd[9];
  ceres::AngleAxisToRotationMatrix(pose, ceres::ColumnMajorAdapter3x3(Rd));
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::Map<const Eigen::Matrix3d>(Rd);
  T.block<3, 1>(0, 3) << pose[3], pose[4], pose[5];
  const Projection P = A * T * G;
  return P / P.norm();
}

//! Ceres on the 6 pose parameters from \e pose; returns the final cost.
double refineRigid(const Projection &A, const std::vector<Eigen::Vector4d> &N, const std::vector<Eigen::Vector2d> &uv,
                   double pose[6])
{
  ceres::Problem problem;
  for (size_t k = 0; k < N.size(); ++k) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<RigidCameraError, 2, 6>(new RigidCameraError(A, N[k], uv[k])), nullptr, pose);
  }
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_QR, 50, 1e-10);
  return summary.final_cost;
}

//! Sum of squared pixel errors of the camera A T(pose) on the metric points N.
double squaredError(const Projection &A, const double pose[6], const std::vector<Eigen::Vector4d> &N,
                    const std::vector<Eigen::Vector2d> &uv)
{
  double sum = 0.0;
  for (size_t k = 0; k < N.size(); ++k) {
    double r[2];
    RigidCameraError(A, N[k], uv[k])(pose, r);
    sum += r[0] * r[0] + r[1] * r[1];
  }
  return std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
}

//! Ceres on one rigid motion shared by both cameras (the whole rig moved) from \e pose; returns the squared error.
double refineShared(const Projection &Al, const Projection &Ar, const std::vector<Eigen::Vector4d> &N,
                    const std::vector<Eigen::Vector2d> &left, const std::vector<Eigen::Vector2d> &right, double pose[6])
{
  ceres::Problem problem;
  for (size_t k = 0; k < N.size(); ++k) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<RigidCameraError, 2, 6>(new RigidCameraError(Al, N[k], left[k])), nullptr,
        pose);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<RigidCameraError, 2, 6>(new RigidCameraError(Ar, N[k], right[k])), nullptr,
        pose);
  }
  solveLeastSquares(problem, ceres::DENSE_QR, 50, 1e-10);
  return squaredError(Al, pose, N, left) + squaredError(Ar, pose, N, right);
}

/*
  Which cameras moved, with fixed intrinsics (something did: the caller re-registers): the left one, the right one,
  the whole rig rigidly (one motion), or each its own. Each hypothesis is fitted (rigid motions T of the metric
  frame; T = I for a camera that did not move) and the one with the lowest Bayesian information criterion
  N ln(SSE / N) + p ln N wins (N pixel coordinates, p = 6, 6, 6 or 12 parameters). A camera that did not move then keeps
  its acquired projection exactly instead of a re-estimate from a few noisy observations: the disparities, hence the
  depths the servo's target depends on, keep the acquisition's accuracy. Replaces P and Pp by the winning pair.
*/
void selectRigMotion(const Projection &Pold, const Projection &Ppold, const Eigen::Matrix4d &G,
                     const std::vector<Eigen::Vector4d> &X, const std::vector<Eigen::Vector2d> &left,
                     const std::vector<Eigen::Vector2d> &right, Projection &P, Projection &Pp)
{
  const Eigen::Matrix4d Ginv = G.inverse();
  const Projection Al = Pold * Ginv, Ar = Ppold * Ginv;
  std::vector<Eigen::Vector4d> N(X.size());
  for (size_t k = 0; k < X.size(); ++k) {
    N[k] = G * X[k].normalized();
  }
  // The independent fits of resect(), as rigid motions; a camera that did not move has the zero motion.
  const double zero[6] = {0, 0, 0, 0, 0, 0};
  double poseL[6], poseR[6];
  closestRigidMotion(Al, P * Ginv, poseL);
  closestRigidMotion(Ar, Pp * Ginv, poseR);
  const double leftMoved = squaredError(Al, poseL, N, left), leftStill = squaredError(Al, zero, N, left);
  const double rightMoved = squaredError(Ar, poseR, N, right), rightStill = squaredError(Ar, zero, N, right);
  // The whole rig: one motion for both cameras, from either camera's as a start.
  double poseRig[6], fromRight[6];
  std::copy(poseL, poseL + 6, poseRig);
  std::copy(poseR, poseR + 6, fromRight);
  double sseRig = refineShared(Al, Ar, N, left, right, poseRig);
  const double sseFromRight = refineShared(Al, Ar, N, left, right, fromRight);
  if (sseFromRight < sseRig) {
    std::copy(fromRight, fromRight + 6, poseRig);
    sseRig = sseFromRight;
  }

  struct Hypothesis {
    const double *poseL, *poseR;
    double sse;
    int parameters;
  };
  const Hypothesis hypotheses[] = {{poseL, zero, leftMoved + rightStill, 6},
                                   {zero, poseR, leftStill + rightMoved, 6},
                                   {poseRig, poseRig, sseRig, 6},
                                   {poseL, poseR, leftMoved + rightMoved, 12}};
  const double coordinates = 4.0 * static_cast<double>(X.size());
  const double floor = 1e-12 * coordinates; // (1e-6 px)^2 per coordinate: round-off must not pick the hypothesis
  const Hypothesis *best = nullptr;
  double bestScore = std::numeric_limits<double>::infinity(); // a non-finite SSE never wins
  for (const Hypothesis &h : hypotheses) {
    const double score =
        coordinates * std::log(std::max(h.sse, floor) / coordinates) + h.parameters * std::log(coordinates);
    if (score < bestScore) {
      bestScore = score;
      best = &h;
    }
  }
  if (best != nullptr) {
    P = rigidCamera(Al, best->poseL, G);
    Pp = rigidCamera(Ar, best->poseR, G);
  }
}
} // namespace

Projection vpProjectiveRigRegistration::resect(const Projection &Pold, const Eigen::Matrix4d &G,
                                               const std::vector<Eigen::Vector4d> &X,
                                               const std::vector<Eigen::Vector2d> &uv, vpRegistrationMode mode,
                                               double *rms)
{
  if (X.size() != uv.size()) {
    std::ostringstream os;
    os << "got " << X.size() << " points but " << uv.size() << " pixels; pass one pixel per point";
    fail(vpProjectiveException::dimensionError, kResect, os.str());
  }
  if (X.size() < 6) {
    std::ostringstream os;
    os << "a camera needs at least 6 points, got " << X.size() << "; observe more markers or configurations";
    fail(vpProjectiveException::notEnoughPointsError, kResect, os.str());
  }
  for (size_t k = 0; k < X.size(); ++k) {
    if (!X[k].allFinite() || !uv[k].allFinite() || !(X[k].norm() > 0.0)) {
      fail(vpProjectiveException::nonFiniteValueError, kResect,
           "a point or a pixel is not finite (or a point is zero); pass the images of tracked markers only");
    }
  }
  const Projection Plinear = linearResection(X, uv);
  Projection P = Plinear;
  if (mode == FIXED_INTRINSICS) {
    const Eigen::Matrix4d Ginv = G.inverse();
    const Projection A = Pold * Ginv;
    std::vector<Eigen::Vector4d> N(X.size());
    for (size_t k = 0; k < X.size(); ++k) {
      N[k] = G * X[k].normalized();
    }
    // Two starts: the camera before the move, and the rigid motion closest to the linear resection.
    double poseOld[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
    double poseLinear[6];
    closestRigidMotion(A, Plinear * Ginv, poseLinear);
    const double costOld = refineRigid(A, N, uv, poseOld);
    const double costLinear = refineRigid(A, N, uv, poseLinear);
    P = rigidCamera(A, costLinear < costOld ? poseLinear : poseOld, G);
  } else {
    Eigen::Matrix<double, 3, 4, Eigen::RowMajor> Prow = Plinear;
    ceres::Problem problem;
    for (size_t k = 0; k < X.size(); ++k) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<GeneralCameraError, 2, 12>(new GeneralCameraError(X[k].normalized(), uv[k])),
          nullptr, Prow.data());
    }
    problem.SetManifold(Prow.data(), new ceres::SphereManifold<12>());
    solveLeastSquares(problem, ceres::DENSE_QR, 50, 1e-10);
    P = Prow;
    P /= P.norm();
  }
  double error = rmsError(P, X, uv);
  if (!P.allFinite() || !std::isfinite(error)) {
    fail(vpProjectiveException::estimationFailedError, kResect,
         "the resection gave no usable camera; check that the pixels are the images of the given points");
  }
  if (rms != nullptr) {
    *rms = error;
  }
  return P;
}

vpProjectiveStereoRig vpProjectiveRigRegistration::registerRig(const vpProjectiveArmModel &model,
                                                               const std::vector<vpProjectiveArmModel::JointVector> &q,
                                                               const std::vector<std::vector<Eigen::Vector4d>> &images,
                                                               vpRegistrationMode mode, double *rms)
{
  if (q.size() != images.size()) {
    fail(vpProjectiveException::dimensionError, kRegister, "there must be one set of images per joint vector");
  }
  if (q.size() < 3) {
    std::ostringstream os;
    os << "re-registering the rig needs at least 3 observations, got " << q.size()
       << "; add observations of the markers at other joint configurations";
    fail(vpProjectiveException::notEnoughPointsError, kRegister, os.str());
  }
  const size_t K = model.markers().size();
  std::vector<Eigen::Vector4d> X, s;
  X.reserve(q.size() * K);
  s.reserve(q.size() * K);
  for (size_t k = 0; k < q.size(); ++k) {
    if (q[k].size() != static_cast<Eigen::Index>(model.getNumberOfJoints()) || images[k].size() != K) {
      fail(vpProjectiveException::dimensionError, kRegister,
           "an observation has the wrong number of joints or markers; pass every marker of the model, in order");
    }
    const Eigen::Matrix4d H = model.displacement(q[k]);
    for (size_t j = 0; j < K; ++j) {
      X.push_back((H * model.markers()[j]).normalized());
      s.push_back(images[k][j]);
    }
  }
  return registerRig(model.getStereoRig(), model.projectiveToMetric(), X, s, mode, rms);
}

vpProjectiveStereoRig vpProjectiveRigRegistration::registerRig(const vpProjectiveStereoRig &old,
                                                               const Eigen::Matrix4d &G,
                                                               const std::vector<Eigen::Vector4d> &points,
                                                               const std::vector<Eigen::Vector4d> &images,
                                                               vpRegistrationMode mode, double *rms)
{
  if (points.size() != images.size()) {
    std::ostringstream os;
    os << "got " << points.size() << " points but " << images.size() << " stereo images; pass one per point";
    fail(vpProjectiveException::dimensionError, kRegister, os.str());
  }
  if (!G.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, kRegister,
         "the projective-to-metric matrix is not finite; pass the model's projectiveToMetric()");
  }
  std::vector<Eigen::Vector4d> X;
  std::vector<Eigen::Vector2d> left, right;
  X.reserve(points.size());
  left.reserve(points.size());
  right.reserve(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    if (!points[k].allFinite() || !images[k].allFinite() || !(points[k].norm() > 0.0)) {
      fail(vpProjectiveException::nonFiniteValueError, kRegister,
           "a point or a pixel is not finite (or a point is zero); pass the images of tracked points only");
    }
    X.push_back(points[k].normalized());
    left.push_back(images[k].head<2>());
    right.push_back(images[k].tail<2>());
  }
  double rmsLeft = 0.0, rmsRight = 0.0;
  Projection oldP, oldPp;
  old.getLeftProjection(oldP);
  old.getRightProjection(oldPp);
  Projection P = resect(oldP, G, X, left, mode, &rmsLeft);
  Projection Pp = resect(oldPp, G, X, right, mode, &rmsRight);
  if (mode == FIXED_INTRINSICS) {
    selectRigMotion(oldP, oldPp, G, X, left, right, P, Pp);
    rmsLeft = rmsError(P, X, left);
    rmsRight = rmsError(Pp, X, right);
  }
  if (rmsLeft > maxResidual || rmsRight > maxResidual) {
    std::ostringstream os;
    os << "the model does not explain the observations (RMS " << rmsLeft << " px left, " << rmsRight
       << " px right, at most " << maxResidual
       << " accepted): check the marker order and that the markers did not slip on the arm; else acquire the arm "
          "model again";
    fail(vpProjectiveException::estimationFailedError, kRegister, os.str());
  }
  vpProjectiveStereoRig rig;
  rig.setProjections(P, Pp);
  if (rms != nullptr) {
    *rms = std::sqrt(0.5 * (rmsLeft * rmsLeft + rmsRight * rmsRight));
  }
  return rig;
}
