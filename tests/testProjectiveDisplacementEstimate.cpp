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
  Tests of vpProjectiveDisplacement's estimation against the metric simulator:
  - estimate() from projective points and from images equals H_PE^-1 T_l H_PE normalised by (12), for rotations about
    a general axis, general screw motions, pure translations and no motion; getRotationAngle() is the metric angle and
    classify() tells the kind of motion;
  - with 0.5 px noise on 7 markers, the angle and matrix errors stay within bounds derived at the test, and the Ceres
    (maximum-likelihood) estimate from images is on average no worse than the linear one from triangulated points.
*/

#include <gtest/gtest.h>

#include "vpProjectiveDisplacementTestTools.h"

using namespace vpProjectiveTest;

TEST(vpProjectiveDisplacement, EstimateNoiseFreeEqualsTruth)
{
  const Scene scene;
  const vpProjectiveDisplacement::vpMotionType expected[] = {
      vpProjectiveDisplacement::ROTATION, vpProjectiveDisplacement::GENERAL, vpProjectiveDisplacement::TRANSLATION,
      vpProjectiveDisplacement::IDENTITY};
  for (int k = Rotation; k <= NoMotion; ++k) {
    const MotionKind kind = static_cast<MotionKind>(k);
    for (unsigned int seed = 1; seed <= 5; ++seed) {
      SCOPED_TRACE(::testing::Message() << kindName(kind) << ", seed " << seed);
      vpUniRand rng(1000 * (k + 1) + seed);
      vpGaussRand noise(1.0, 0.0, 1);
      // 5 (the minimum) to 9 points.
      const std::vector<vpColVector> body = rigidBody(scene, rng, 4 + seed, 0.08, 0.03);
      const double theta = rng.uniform(0.2, 1.0);
      const vpHomogeneousMatrix T = randomMotion(scene, rng, body, kind, theta);
      const Observation o = observe(scene, body, T, 0.0, noise);
      const Eigen::Matrix4d Htrue = truth(scene, T);

      const vpProjectiveDisplacement D = vpProjectiveDisplacement::estimate(o.M0, o.M1);
      EXPECT_LT(relativeError(D.matrix(), Htrue), 1e-8);
      const vpProjectiveDisplacement Di =
          vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, o.right1);
      EXPECT_LT(relativeError(Di.matrix(), Htrue), 1e-8);

      // The angle of (21) is the metric one; translations and the identity have angle 0 (acos near 1 loses half
      // the digits: 1e-6).
      const double metricAngle = rotationAngle(T);
      const double angleTolerance = (kind == Rotation || kind == Screw) ? 1e-8 : 1e-6;
      EXPECT_NEAR(D.getRotationAngle(), metricAngle, angleTolerance);
      EXPECT_NEAR(Di.getRotationAngle(), metricAngle, angleTolerance);

      EXPECT_EQ(D.classify(), expected[k]);
      EXPECT_EQ(Di.classify(), expected[k]);
      EXPECT_EQ(vpProjectiveDisplacement(Htrue).classify(), expected[k]);
    }
  }
}

TEST(vpProjectiveDisplacement, EstimateFromExactProjectivePoints)
{
  // The true projective points H_PE^-1 N, not triangulated, and with arbitrary scales and signs: M ~ H M0 is a
  // relation between projective points, so the scale of each M must not matter.
  const Scene scene;
  vpUniRand rng(77);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Screw, 0.6);
  std::vector<vpColVector> M0 = projectivePoints(scene, body);
  std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));
  for (size_t j = 0; j < M0.size(); ++j) {
    M0[j] *= rng.uniform(-3.0, 3.0);
    M1[j] *= rng.uniform(-3.0, 3.0);
  }
  const vpProjectiveDisplacement D = vpProjectiveDisplacement::estimate(M0, M1);
  EXPECT_LT(relativeError(D.matrix(), truth(scene, T)), 1e-8);
}

/*
  The minimal case, 5 points, on a small object: 5 random points in a 4 cm cube 1 m away are in general position
  (no 4 coplanar, with probability 1), so the estimate must succeed and be exact. In the rig's frame the unit
  projective points of a small object are nearly parallel, which is a matter of conditioning (the estimator whitens
  its points), not a degeneracy.
*/
TEST(vpProjectiveDisplacement, EstimateMinimalFivePointsOnSmallObject)
{
  const Scene scene;
  for (unsigned int seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(500 + seed);
    const std::vector<vpColVector> body = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.02, 5);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Screw, 0.5);
    const std::vector<vpColVector> M0 = projectivePoints(scene, body);
    const std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));
    try {
      EXPECT_LT(relativeError(vpProjectiveDisplacement::estimate(M0, M1).matrix(), truth(scene, T)), 1e-6);
    } catch (const vpException &e) {
      ADD_FAILURE() << "estimate() rejected 5 points in general position: " << e.getStringMessage();
    }
  }
}

/*
  7 markers pairwise >= 8 cm apart in a 20 cm cube 1 m in front of the paper's rig, a 30 deg rotation about a random
  axis through their centroid (+- 3 cm), 0.5 px noise on all four images, the true F (so that the truth is exact),
  20 seeds. Two estimates: linear (DLT on the triangulated points) and maximum likelihood (Ceres, from the images).

  First-order sizes. A marker's stereo depth has std sigma_Z = Z^2 sqrt(2) sigma / (f b) = 0.71 / (1667 * 0.2) =
  2.1 mm (lateral: Z sigma / f = 0.3 mm). Measured over 400 seeds offline (20-seed blocks: worst block mean):
  - angle: a rotation read off 7 points at a lever of ~7 cm has sigma_theta ~ sigma_Z / (7 cm sqrt(7)) = 0.011 rad,
    i.e. a mean |error| of ~0.8 sigma_theta = 0.009 rad. Measured ML: RMS 0.0100, mean 0.0075 (worst block 0.0096),
    max 0.042 rad; linear: mean 0.0098 (worst block 0.0158), max 0.121 rad (the algebraic estimator has a heavy
    tail). Bounds: ML mean 1.3 sigma_theta = 0.015, max 4.5 sigma_theta = 0.051; linear mean 0.025, max 0.15.
  - transfer error: RMS distance (mm) between the true markers moved by H_PE H H_PE^-1 and by the true motion. Both
    point sets are noisy (sqrt(2) sigma_Z) and 15 parameters are fitted on 21 coordinates, so ~ sqrt(2 * 15/21)
    sigma_Z = 2.5 mm. Measured ML mean 2.24 (worst block 2.52), max 5.0 mm; linear mean 2.90 (worst block 3.23), max
    7.1 mm. Bounds: ML mean 1.5 sigma_Z, max 3.5 sigma_Z; linear mean 2 sigma_Z, max 5 sigma_Z.
  - relative matrix error in the markers' whitened frame (W H W^-1, W the whitening of the true points M0, the frame
    the estimator itself works in): ~ sigma_Z / (10 cm spread) = 0.02. Measured ML mean 0.022 (worst block 0.027),
    max 0.079; linear mean 0.030 (worst block 0.035), max 0.117. Bounds: ML mean 0.04, max 0.12; linear mean 0.05,
    max 0.18.
  - relative matrix error in the rig's frame, |H - Htrue|_F / |Htrue|_F: dominated by the entries that the pixel-based
    frame scales up, it has a heavy tail (max over 400 seeds 1.34 ML, 1.93 linear) and only its mean is bounded:
    measured ML mean 0.084 (worst block 0.146), linear 0.224 (worst block 0.31); bounds 0.3 and 0.6.
  The ML estimate must be no worse than the linear one on average, for every measure (it was better in every one of
  the 20 offline blocks for the transfer and whitened errors).
*/
TEST(vpProjectiveDisplacement, EstimateNoisyWithinBounds)
{
  const Scene scene;
  const double theta = vpMath::rad(30.0);
  const double sigmaZ = std::sqrt(2.0) * kSigma / (scene.sim.getLeftCameraParameters().get_px() * 0.20); // Z = 1 m
  const double sigmaTheta = sigmaZ / (0.07 * std::sqrt(7.0));
  const int seeds = 20;
  enum { Angle, Transfer, Whitened, Raw, Measures };
  const char *names[Measures] = {"angle (rad)", "transfer (mm)", "whitened relative", "rig-frame relative"};
  double mean[2][Measures] = {{0.0}}, worst[2][Measures] = {{0.0}};
  for (int seed = 1; seed <= seeds; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(static_cast<uint64_t>(300 + seed));
    vpGaussRand noise(1.0, 0.0, 300 + seed);
    const std::vector<vpColVector> body = rigidBody(scene, rng, 7, 0.10, 0.08);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, theta);
    const Observation o = observe(scene, body, T, kSigma, noise);
    const Eigen::Matrix4d Htrue = truth(scene, T);
    const Eigen::Matrix4d Tl = scene.cameraDisplacement(T);
    // Whitening of the true points: W = (sum u u^T / n)^(-1/2), u the unit projective points.
    Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
    for (const vpColVector &X : body) {
      const Eigen::Vector4d u = scene.projectivePoint(X);
      C += u * u.transpose() / static_cast<double>(body.size());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(C);
    const Eigen::Matrix4d W =
        eig.eigenvectors() * eig.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();

    const vpProjectiveDisplacement estimates[2] = {
        vpProjectiveDisplacement::estimate(o.M0, o.M1),
        vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, o.right1)};
    for (int k = 0; k < 2; ++k) {
      const Eigen::Matrix4d &H = estimates[k].matrix();
      const Eigen::Matrix4d Tm = scene.Hpe * H * scene.HpeInv;
      double transfer = 0.0;
      for (const vpColVector &X : body) {
        const Eigen::Vector4d N0 = scene.cameraPoint(X);
        const Eigen::Vector4d a = Tm * N0, b = Tl * N0;
        transfer += (a.head<3>() / a(3) - b.head<3>()).squaredNorm() / static_cast<double>(body.size());
      }
      const double e[Measures] = {
          std::abs(estimates[k].getRotationAngle() - theta), 1000.0 * std::sqrt(transfer),
          relativeError(Eigen::Matrix4d(W * H * W.inverse()), Eigen::Matrix4d(W * Htrue * W.inverse())),
          relativeError(H, Htrue)};
      for (int m = 0; m < Measures; ++m) {
        mean[k][m] += e[m] / seeds;
        worst[k][m] = std::max(worst[k][m], e[m]);
      }
    }
  }
  for (int k = 0; k < 2; ++k) {
    testLog() << "[ stats    ] displacement, 7 markers, 30 deg, sigma " << kSigma << " px, " << seeds << " seeds, "
              << (k == 0 ? "linear" : "ML") << ":";
    for (int m = 0; m < Measures; ++m) {
      testLog() << " " << names[m] << " mean " << mean[k][m] << " max " << worst[k][m] << ";";
    }
    testLog() << std::endl;
  }
  const double sigmaZmm = 1000.0 * sigmaZ;
  // Linear estimate.
  EXPECT_LT(mean[0][Angle], 0.025);
  EXPECT_LT(worst[0][Angle], 0.15);
  EXPECT_LT(mean[0][Transfer], 2.0 * sigmaZmm);
  EXPECT_LT(worst[0][Transfer], 5.0 * sigmaZmm);
  EXPECT_LT(mean[0][Whitened], 0.05);
  EXPECT_LT(worst[0][Whitened], 0.18);
  EXPECT_LT(mean[0][Raw], 0.6);
  // Maximum likelihood.
  EXPECT_LT(mean[1][Angle], 1.3 * sigmaTheta);
  EXPECT_LT(worst[1][Angle], 4.5 * sigmaTheta);
  EXPECT_LT(mean[1][Transfer], 1.5 * sigmaZmm);
  EXPECT_LT(worst[1][Transfer], 3.5 * sigmaZmm);
  EXPECT_LT(mean[1][Whitened], 0.04);
  EXPECT_LT(worst[1][Whitened], 0.12);
  EXPECT_LT(mean[1][Raw], 0.3);
  // The ML estimate is on average no worse than the linear one.
  for (int m = 0; m < Measures; ++m) {
    EXPECT_LE(mean[1][m], mean[0][m]) << names[m];
  }
}
