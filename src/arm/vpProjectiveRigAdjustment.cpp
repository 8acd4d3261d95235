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
  vpProjectiveRigRegistration::adjustRig(): the bundle adjustment of a re-registered rig with the points of a servo
  task's features (the registration itself: vpProjectiveRigRegistration.cpp).
*/

#include <visp3/projective/vpProjectiveRigRegistration.h>

#include <cmath>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include "core/vpProjectiveCeres.h"
#include "core/vpProjectiveErrors.h"
#include "vpProjectiveRigidCamera.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
const char *const kAdjust = "vpProjectiveRigRegistration::adjustRig()";

//! Pixel error of the camera A T(pose) at the tracked point M (zero reference) moved by H: N = G H M, never divided.
struct TrackedPointError {
  TrackedPointError(const CameraMatrix &A, const Eigen::Matrix4d &GH, const Eigen::Vector2d &uv)
      : m_A(A), m_GH(GH), m_uv(uv)
  {
  }

  template <typename T> bool operator()(const T *const pose, const T *const M, T *residual) const
  {
    const Eigen::Matrix<T, 4, 1> N = m_GH.cast<T>() * Eigen::Map<const Eigen::Matrix<T, 4, 1>>(M);
    rigidCameraResidual(m_A, pose, N, m_uv, residual);
    return true;
  }

  CameraMatrix m_A;
  Eigen::Matrix4d m_GH;
  Eigen::Vector2d m_uv;
};

/*
  The images before the move, summed up by their mean point: sqrt(w) times the stereo image of H0 M through the rig
  before the move minus that of H0 Mbar (4 residuals, pixels).
*/
struct PriorError {
  PriorError(const CameraMatrix &P, const CameraMatrix &Pp, const Eigen::Matrix4d &H0, const Eigen::Vector4d &Mbar,
             double weight)
      : m_P(P * H0), m_Pp(Pp * H0), m_sqrtWeight(std::sqrt(weight))
  {
    const Eigen::Vector3d m = m_P * Mbar, mp = m_Pp * Mbar;
    m_s << m.head<2>() / m(2), mp.head<2>() / mp(2);
  }

  template <typename T> bool operator()(const T *const M, T *residual) const
  {
    const Eigen::Map<const Eigen::Matrix<T, 4, 1>> X(M);
    const Eigen::Matrix<T, 3, 1> m = m_P.cast<T>() * X, mp = m_Pp.cast<T>() * X;
    residual[0] = T(m_sqrtWeight) * (m(0) / m(2) - T(m_s(0)));
    residual[1] = T(m_sqrtWeight) * (m(1) / m(2) - T(m_s(1)));
    residual[2] = T(m_sqrtWeight) * (mp(0) / mp(2) - T(m_s(2)));
    residual[3] = T(m_sqrtWeight) * (mp(1) / mp(2) - T(m_s(3)));
    return true;
  }

  CameraMatrix m_P, m_Pp; // the cameras before the move, times H0
  double m_sqrtWeight;
  Eigen::Vector4d m_s;
};

//! True if the cameras P and Q are the same up to scale (a camera registerRig() kept).
bool sameCamera(const CameraMatrix &P, const CameraMatrix &Q)
{
  const CameraMatrix p = P / P.norm(), q = Q / Q.norm();
  return std::min((p - q).norm(), (p + q).norm()) < 1e-12;
}

void checkInput(const Eigen::Matrix4d &G, const std::vector<Eigen::Vector4d> &fixedPoints,
                const std::vector<Eigen::Vector4d> &fixedImages, const Eigen::Matrix4d &H0,
                const std::vector<double> &weights, const std::vector<Eigen::Matrix4d> &frames,
                const std::vector<vpProjectiveRigRegistration::vpTrackedImage> &images,
                const std::vector<Eigen::Vector4d> &points)
{
  if (fixedPoints.size() != fixedImages.size() || weights.size() != points.size()) {
    std::ostringstream os;
    os << "got " << fixedPoints.size() << " known points for " << fixedImages.size() << " images and " << points.size()
       << " tracked points for " << weights.size() << " weights; pass one per point";
    fail(vpProjectiveException::dimensionError, kAdjust, os.str());
  }
  bool finite = G.allFinite() && H0.allFinite();
  for (size_t k = 0; k < fixedPoints.size(); ++k) {
    finite = finite && fixedPoints[k].allFinite() && fixedImages[k].allFinite() && fixedPoints[k].norm() > 0.0;
  }
  for (size_t i = 0; i < points.size(); ++i) {
    finite = finite && points[i].allFinite() && points[i].norm() > 0.0 && std::isfinite(weights[i]) && weights[i] > 0.0;
  }
  for (const Eigen::Matrix4d &H : frames) {
    finite = finite && H.allFinite();
  }
  for (const vpProjectiveRigRegistration::vpTrackedImage &image : images) {
    if (image.point >= points.size() || image.frame >= frames.size()) {
      fail(vpProjectiveException::dimensionError, kAdjust,
           "a tracked image names a point or a frame that was not given; pass its point's and frame's index");
    }
    finite = finite && image.s.allFinite();
  }
  if (!finite) {
    fail(vpProjectiveException::nonFiniteValueError, kAdjust,
         "an input is not finite, a point is zero or a weight is not positive; pass the images of tracked points and "
         "the number of stereo pairs behind each point's prior");
  }
}
} // namespace

vpProjectiveStereoRig vpProjectiveRigRegistration::adjustRig(
    const vpProjectiveStereoRig &before, const vpProjectiveStereoRig &rig, const Eigen::Matrix4d &G,
    const std::vector<Eigen::Vector4d> &fixedPoints, const std::vector<Eigen::Vector4d> &fixedImages,
    const Eigen::Matrix4d &H0, const std::vector<double> &weights, const std::vector<Eigen::Matrix4d> &frames,
    const std::vector<vpTrackedImage> &images, std::vector<Eigen::Vector4d> &points, double *rms)
{
  checkInput(G, fixedPoints, fixedImages, H0, weights, frames, images, points);
  const Eigen::Matrix4d Ginv = G.inverse();
  const CameraMatrix Al = before.leftProjection() * Ginv, Ar = before.rightProjection() * Ginv;
  // The cameras' motions as registerRig() chose them: a camera it kept stays, a whole rig keeps one motion.
  double poseL[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0}, poseR[6] = {0.0, 0.0, 0.0, 0.0, 0.0, 0.0};
  const bool leftMoved = !sameCamera(rig.leftProjection(), before.leftProjection());
  const bool rightMoved = !sameCamera(rig.rightProjection(), before.rightProjection());
  if (leftMoved) {
    closestRigidMotion(Al, rig.leftProjection() * Ginv, poseL);
  }
  if (rightMoved) {
    closestRigidMotion(Ar, rig.rightProjection() * Ginv, poseR);
  }
  const bool shared =
      leftMoved && rightMoved &&
      (Eigen::Map<const Eigen::Matrix<double, 6, 1>>(poseL) - Eigen::Map<const Eigen::Matrix<double, 6, 1>>(poseR))
              .norm() < 1e-9;
  double *const blockL = poseL, *const blockR = shared ? poseL : poseR;

  std::vector<Eigen::Vector4d> M(points.size());
  ceres::Problem problem;
  for (size_t i = 0; i < points.size(); ++i) {
    M[i] = points[i].normalized();
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PriorError, 4, 4>(new PriorError(
                                 before.leftProjection(), before.rightProjection(), H0, M[i], weights[i])),
                             nullptr, M[i].data());
    problem.SetManifold(M[i].data(), new ceres::SphereManifold<4>());
  }
  for (size_t k = 0; k < fixedPoints.size(); ++k) {
    const Eigen::Vector4d N = G * fixedPoints[k].normalized();
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<RigidCameraError, 2, 6>(new RigidCameraError(Al, N, fixedImages[k].head<2>())),
        nullptr, blockL);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<RigidCameraError, 2, 6>(new RigidCameraError(Ar, N, fixedImages[k].tail<2>())),
        nullptr, blockR);
  }
  for (const vpTrackedImage &image : images) {
    const Eigen::Matrix4d GH = G * frames[image.frame];
    double *const point = M[image.point].data();
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<TrackedPointError, 2, 6, 4>(new TrackedPointError(Al, GH, image.s.head<2>())),
        nullptr, blockL, point);
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<TrackedPointError, 2, 6, 4>(new TrackedPointError(Ar, GH, image.s.tail<2>())),
        nullptr, blockR, point);
  }
  for (double *block : {blockL, blockR}) {
    if (problem.HasParameterBlock(block) && ((block == poseL && !leftMoved) || (block == poseR && !rightMoved))) {
      problem.SetParameterBlockConstant(block);
    }
  }
  solveLeastSquares(problem, ceres::DENSE_QR, 50, 1e-10);

  vpProjectiveStereoRig adjusted;
  const CameraMatrix P = leftMoved ? rigidCamera(Al, blockL, G) : before.leftProjection();
  const CameraMatrix Pp = rightMoved ? rigidCamera(Ar, blockR, G) : before.rightProjection();
  bool finite = P.allFinite() && Pp.allFinite();
  double sum = 0.0;
  for (const vpTrackedImage &image : images) {
    const Eigen::Vector4d X = frames[image.frame] * M[image.point];
    const Eigen::Vector3d m = P * X, mp = Pp * X;
    sum += (m.head<2>() / m(2) - image.s.head<2>()).squaredNorm() +
           (mp.head<2>() / mp(2) - image.s.tail<2>()).squaredNorm();
  }
  for (const Eigen::Vector4d &Mi : M) {
    finite = finite && Mi.allFinite();
  }
  const double error = images.empty() ? 0.0 : std::sqrt(sum / (4.0 * static_cast<double>(images.size())));
  if (!finite || !std::isfinite(error)) {
    fail(vpProjectiveException::estimationFailedError, kAdjust,
         "the adjustment gave no usable rig; check that the images are those of the tracked points");
  }
  adjusted.setProjections(P, Pp);
  for (size_t i = 0; i < M.size(); ++i) {
    points[i] = M[i].normalized();
  }
  if (rms != nullptr) {
    *rms = error;
  }
  return adjusted;
}
