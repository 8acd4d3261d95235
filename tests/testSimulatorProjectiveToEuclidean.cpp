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
  Tests of vpSimulatorStereoRig's projective-to-Euclidean transformation H_PE (helpers in vpSimulatorTestTools.h):
  for the true and for an estimated fundamental matrix, and its refusal of foreign frames.
*/

#include <gtest/gtest.h>

#include "vpSimulatorTestTools.h"

using namespace vpProjectiveTest;

TEST(SimulatorStereoRig, ProjectiveToEuclideanOfTrueFundamentalMatrix)
{
  const vpSimulatorStereoRig sim = paperRig();
  vpProjectiveStereoRig rig;
  rig.setFundamentalMatrix(sim.getFundamentalMatrix());
  double residual = 1.0;
  const Eigen::Matrix4d H = toEigen<4, 4>(sim.getProjectiveToEuclidean(rig, residual));
  EXPECT_LT(residual, 1e-8); // pixels
  EXPECT_NEAR(std::fabs(H.determinant()), 1.0, 1e-9);
  const Eigen::Matrix<double, 3, 4> P = toEigen<3, 4>(rig.getLeftProjection());
  const Eigen::Matrix<double, 3, 4> Pp = toEigen<3, 4>(rig.getRightProjection());
  const Eigen::Matrix4d Hinv = H.inverse();

  vpUniRand rng(11);
  for (int k = 0; k < 100; ++k) {
    const vpColVector X = visiblePoint(sim, rng);
    vpImagePoint l, r;
    ASSERT_TRUE(sim.project(X, l, r));
    const Eigen::Vector4d M = Hinv * leftCameraPoint(sim, X);
    const Eigen::Vector3d m = P * M;
    const Eigen::Vector3d mp = Pp * M;
    EXPECT_GT(m(2), 0.0); // sign convention: K[I|0] H = s P with s > 0
    EXPECT_LT((m.head<2>() / m(2) - pixel(l).head<2>()).norm(), 1e-9 * pixel(l).norm());
    EXPECT_LT((mp.head<2>() / mp(2) - pixel(r).head<2>()).norm(), 1e-9 * pixel(r).norm());
  }
  // Any scale of F gives the same frame, hence the same H.
  vpProjectiveStereoRig rig2;
  rig2.setFundamentalMatrix(-3.0 * sim.getFundamentalMatrix());
  const Eigen::Matrix4d H2 = toEigen<4, 4>(sim.getProjectiveToEuclidean(rig2));
  EXPECT_LT((H2 - H).norm(), 1e-9 * H.norm());
}

TEST(SimulatorStereoRig, ProjectiveToEuclideanOfEstimatedFundamentalMatrix)
{
  // F estimated from noisy matches: no homography maps the frame exactly onto the metric cameras; the best one
  // reproduces the true images to about the noise level, and the residual reports the (small) mismatch.
  const vpSimulatorStereoRig sim = paperRig();
  vpUniRand rng(3);
  vpGaussRand noise(1.0, 0.0, 4);
  std::vector<vpColVector> points;
  std::vector<vpImagePoint> left, right;
  for (int k = 0; k < 60; ++k) {
    points.push_back(visiblePoint(sim, rng));
  }
  const double sigma = 0.5;
  ASSERT_TRUE(sim.project(points, left, right, sigma, noise));
  vpProjectiveStereoRig rig;
  rig.estimate(left, right);
  double residual = 0.0;
  const Eigen::Matrix4d H = toEigen<4, 4>(sim.getProjectiveToEuclidean(rig, residual));
  EXPECT_GT(residual, 1e-6);
  EXPECT_LT(residual, sim.getMaxProjectiveToEuclideanResidual());
  EXPECT_NEAR(sim.getMaxProjectiveToEuclideanResidual(), 16.0, 1e-12);
  const Eigen::Matrix<double, 3, 4> P = toEigen<3, 4>(rig.getLeftProjection());
  const Eigen::Matrix<double, 3, 4> Pp = toEigen<3, 4>(rig.getRightProjection());
  const Eigen::Matrix4d Hinv = H.inverse();
  double sumLeft2 = 0.0, sumRight2 = 0.0;
  for (size_t k = 0; k < points.size(); ++k) {
    vpImagePoint l, r;
    ASSERT_TRUE(sim.project(points[k], l, r));
    const Eigen::Vector4d M = Hinv * leftCameraPoint(sim, points[k]);
    const Eigen::Vector3d m = P * M;
    const Eigen::Vector3d mp = Pp * M;
    sumLeft2 += (m.head<2>() / m(2) - pixel(l).head<2>()).squaredNorm();
    sumRight2 += (mp.head<2>() / mp(2) - pixel(r).head<2>()).squaredNorm();
  }
  // The left cameras are matched exactly; the right images of the true points are off by about the noise.
  EXPECT_LT(std::sqrt(sumLeft2 / points.size()), 1e-9);
  EXPECT_LT(std::sqrt(sumRight2 / points.size()), 4.0 * sigma);
}

TEST(SimulatorStereoRig, ProjectiveToEuclideanRejectsForeignFrames)
{
  const vpSimulatorStereoRig sim = paperRig();
  vpProjectiveStereoRig rig;
  expectThrowsCode([&]() { sim.getProjectiveToEuclidean(rig); }, vpProjectiveException::notInitializedError);

  // The fundamental matrix of another rig: a vertical baseline (epipolar lines across those of the paper's rig).
  vpHomogeneousMatrix rMl(0.0, -0.2, 0.0, vpMath::rad(8.0), 0.0, 0.0);
  const vpSimulatorStereoRig other(sim.getLeftCameraParameters(), sim.getRightCameraParameters(), rMl,
                                   vpHomogeneousMatrix(), 640, 480);
  rig.setFundamentalMatrix(other.getFundamentalMatrix());
  expectThrowsCode([&]() { sim.getProjectiveToEuclidean(rig); }, vpProjectiveException::invalidValueError);
  // The other rig itself accepts its frame.
  double residual = 1.0;
  other.getProjectiveToEuclidean(rig, residual);
  EXPECT_LT(residual, 1e-8);
  // A random rank-2 matrix.
  Eigen::Matrix3d F;
  F << 0.3, -0.1, 0.2, 0.5, 0.4, -0.7, 0.8, 0.3, -0.5;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d s = svd.singularValues();
  s(2) = 0.0;
  F = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
  vpMatrix Fv(3, 3);
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      Fv[i][j] = F(i, j);
    }
  }
  rig.setFundamentalMatrix(Fv);
  expectThrowsCode([&]() { sim.getProjectiveToEuclidean(rig); }, vpProjectiveException::invalidValueError);
}
