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
  Private: a camera that moved rigidly, A T(omega, t) G (A = P0 G^-1, 3x4; T a rigid motion of the metric frame of
  the model's upgrade G), shared by the rig's registration and its adjustment with tracked points. Not installed.
*/

#ifndef _vpProjectiveRigidCamera_h_
#define _vpProjectiveRigidCamera_h_

#include <Eigen/Dense>
#include <ceres/rotation.h>

namespace vpProjectiveInternal
{
//! A camera matrix (3x4), as vpProjectiveStereoRig::Projection.
typedef Eigen::Matrix<double, 3, 4> CameraMatrix;

/*!
  Pixel error of the camera A T(pose) at the metric point N (4x1, homogeneous, never divided): T acts on N as
  (R N_xyz + t N_w, N_w); pose = (angle-axis, t).
*/
template <typename T>
void rigidCameraResidual(const CameraMatrix &A, const T *pose, const Eigen::Matrix<T, 4, 1> &N,
                         const Eigen::Vector2d &uv, T *residual)
{
  const T p[3] = {N(0), N(1), N(2)};
  T Rp[3];
  ceres::AngleAxisRotatePoint(pose, p, Rp);
  Eigen::Matrix<T, 4, 1> TN;
  TN << Rp[0] + pose[3] * N(3), Rp[1] + pose[4] * N(3), Rp[2] + pose[5] * N(3), N(3);
  const Eigen::Matrix<T, 3, 1> m = A.cast<T>() * TN;
  residual[0] = m(0) / m(2) - T(uv(0));
  residual[1] = m(1) / m(2) - T(uv(1));
}

//! Pixel error of the camera A T(pose) at a fixed metric point N = G X (4x1): a Ceres cost on the pose.
struct RigidCameraError {
  RigidCameraError(const CameraMatrix &A, const Eigen::Vector4d &N, const Eigen::Vector2d &uv)
      : m_A(A), m_N(N), m_uv(uv)
  {
  }

  template <typename T> bool operator()(const T *const pose, T *residual) const
  {
    rigidCameraResidual(m_A, pose, Eigen::Matrix<T, 4, 1>(m_N.cast<T>()), m_uv, residual);
    return true;
  }

  CameraMatrix m_A;
  Eigen::Vector4d m_N;
  Eigen::Vector2d m_uv;
};

//! The rigid motion T (angle-axis, t) with A T closest to s B (A, B: 3x4; A's left block invertible).
inline void closestRigidMotion(const CameraMatrix &A, const CameraMatrix &B, double pose[6])
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

//! The camera A T(pose) G (unit Frobenius norm).
inline CameraMatrix rigidCamera(const CameraMatrix &A, const double pose[6], const Eigen::Matrix4d &G)
{
  double Rd[9];
  ceres::AngleAxisToRotationMatrix(pose, ceres::ColumnMajorAdapter3x3(Rd));
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::Map<const Eigen::Matrix3d>(Rd);
  T.block<3, 1>(0, 3) << pose[3], pose[4], pose[5];
  const CameraMatrix P = A * T * G;
  return P / P.norm();
}
} // namespace vpProjectiveInternal

#endif
