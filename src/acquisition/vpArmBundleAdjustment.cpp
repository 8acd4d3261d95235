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
  The bundle adjustment of vpProjectiveArmAcquisition::calibrate(): G^-1, the metric twists and the marker points,
  shared by every acquisition image.
*/

#include "acquisition/vpArmCalibration.h"

#include <cmath>

#include <ceres/ceres.h>

#include <visp3/projective/vpMetricTwist.h>

#include "acquisition/vpMarkerObservationError.h"
#include "core/vpProjectiveCeres.h"
#include "core/vpProjectiveConversions.h"

namespace vpProjectiveInternal
{
vpProjectiveArmModel bundleAdjust(const ArmCalibrationData &data, const std::vector<Eigen::Vector4d> &M0,
                                  const MetricModel &start, bool robustLoss,
                                  const vpProjectiveArmModel::JointVector &qRef, double &residual, bool quick)
{
  const size_t n = data.types.size();
  const size_t K = data.zeroImages.size();
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> Ginv = start.G.inverse();
  std::vector<Eigen::Vector3d> axis = start.axis, point = start.point;
  std::vector<Eigen::Vector4d> N(K);
  for (size_t j = 0; j < K; ++j) {
    N[j] = (start.G * M0[j]).normalized();
  }
  // The right camera is adjusted too (the left one, [I | 0], fixes the frame): the acquisition's images determine the
  // epipolar geometry better than the matches it was first estimated from.
  vpProjectiveStereoRig::Projection P, Pp0;
  data.rig.getLeftProjection(P);
  data.rig.getRightProjection(Pp0);
  Eigen::Matrix<double, 3, 4, Eigen::RowMajor> Pp = Pp0 / Pp0.norm();
  ceres::Problem problem;
  for (size_t j = 0; j < K; ++j) {
    problem.AddResidualBlock(new ceres::AutoDiffCostFunction<MarkerObservationError, 4, 16, 12, 4>(
                                 new MarkerObservationError(P, data.zeroImages[j])),
                             nullptr, Ginv.data(), Pp.data(), N[j].data());
  }
  size_t observations = K;
  for (size_t k = 0; k < data.trials.size(); ++k) {
    const ArmTrial &trial = data.trials[k];
    const unsigned int i = trial.joint;
    for (size_t j = 0; j < K; ++j) {
      if (!trial.seen[j] || (!data.inlier[k][j] && !robustLoss)) {
        continue;
      }
      ++observations;
      // Cauchy loss at the outlier threshold (on the squared 4-vector error, 2 d^2): a mismatch pulls with a force
      // that fades with its error instead of growing with it.
      ceres::LossFunction *loss = robustLoss ? new ceres::CauchyLoss(std::sqrt(2.0) * data.outlierThreshold) : nullptr;
      MarkerObservationError *error = new MarkerObservationError(P, trial.s[j], data.types[i], trial.amount);
      if (data.types[i] == vpProjectiveJoint::REVOLUTE) {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<MarkerObservationError, 4, 16, 12, 4, 3, 3>(error),
                                 loss, Ginv.data(), Pp.data(), N[j].data(), axis[i].data(), point[i].data());
      } else {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<MarkerObservationError, 4, 16, 12, 4, 3>(error), loss,
                                 Ginv.data(), Pp.data(), N[j].data(), axis[i].data());
      }
    }
  }
  for (size_t j = 0; j < K; ++j) {
    problem.SetManifold(N[j].data(), new ceres::SphereManifold<4>());
  }
  problem.SetManifold(Ginv.data(), new ceres::SphereManifold<16>());
  problem.SetManifold(Pp.data(), new ceres::SphereManifold<12>());
  for (size_t i = 0; i < n; ++i) {
    // A joint whose trials are all left out of this adjustment keeps its initial axis.
    if (data.types[i] == vpProjectiveJoint::REVOLUTE && problem.HasParameterBlock(axis[i].data())) {
      problem.SetManifold(axis[i].data(), new ceres::SphereManifold<3>());
    }
  }
  // A quick adjustment compares hypotheses: 1e-8 relative changes tell a model at the noise level from one pixels off.
  const ceres::Solver::Summary summary = quick ? solveLeastSquares(problem, ceres::DENSE_SCHUR, 50, 1e-8)
                                               : solveLeastSquares(problem, ceres::DENSE_SCHUR, 200);

  const Eigen::Matrix4d GinvFinal = Ginv;
  if (!GinvFinal.allFinite() || !summary.IsSolutionUsable()) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveArmAcquisition::calibrate()",
         "the bundle adjustment of the generators failed; check that the trial motions are large enough and that "
         "the markers are matched in the same order in every image");
  }
  for (size_t i = 0; i < n; ++i) {
    if (data.types[i] == vpProjectiveJoint::REVOLUTE) {
      axis[i].normalize();
    }
  }
  // The refined epipolar geometry's canonical frame (vpProjectiveStereoRig) differs from the adjusted P' by a
  // homography H = [I 0; v^T s] that keeps P = [I | 0]: P' = lambda P'' H. The model moves to that frame:
  // G^-1 <- H G^-1, markers <- H M.
  const vpProjectiveStereoRig::Projection PpFinal = Pp;
  const Eigen::Vector3d ep = PpFinal.col(3);
  vpProjectiveStereoRig rig;
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  try {
    rig.setFundamentalMatrix(toVisp(Eigen::Matrix3d(vpMetricTwist::skew(ep) * PpFinal.leftCols<3>())));
    vpProjectiveStereoRig::Projection Pc;
    rig.getRightProjection(Pc);
    const Eigen::Vector3d ec = Pc.col(3);
    const Eigen::Matrix3d away = Eigen::Matrix3d::Identity() - ec * ec.transpose() / ec.squaredNorm();
    const Eigen::Matrix3d A = away * PpFinal.leftCols<3>(), Ac = away * Pc.leftCols<3>();
    const double lambda = (A.cwiseProduct(Ac)).sum() / Ac.squaredNorm();
    H.row(3).head<3>() = ec.transpose() * (PpFinal.leftCols<3>() / lambda - Pc.leftCols<3>()) / ec.squaredNorm();
    H(3, 3) = ec.dot(ep) / (lambda * ec.squaredNorm());
  } catch (const vpException &) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveArmAcquisition::calibrate()",
         "the bundle adjustment gave a degenerate epipolar geometry; check the acquisition images");
  }
  // G is the model: the model computes G^-1 from it, as it does for a model read from a file, so that a saved and
  // reloaded model gives bit-identical generators and Jacobians.
  const Eigen::Matrix4d G = (H * GinvFinal).inverse();
  const Eigen::Matrix4d Ginv2 = G.inverse();
  std::vector<Eigen::Vector4d> markers(K);
  for (size_t j = 0; j < K; ++j) {
    markers[j] = (Ginv2 * N[j]).normalized();
  }
  residual = std::sqrt(2.0 * summary.final_cost / static_cast<double>(4 * observations));
  return vpProjectiveArmModel(data.types, data.mounting, rig, G, axis, point, markers, qRef);
}
} // namespace vpProjectiveInternal
