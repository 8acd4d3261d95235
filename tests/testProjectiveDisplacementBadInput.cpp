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
  Tests of vpProjectiveDisplacement's bad inputs: every degenerate or invalid input of the estimation from points or
  from images and every invalid matrix throws a vpProjectiveException with a meaningful code and message.
*/

#include <gtest/gtest.h>

#include "vpProjectiveDisplacementTestTools.h"

using namespace vpProjectiveTest;

TEST(vpProjectiveDisplacement, EstimateFromPointsInvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(13);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
  const std::vector<vpColVector> M0 = projectivePoints(scene, body);
  const std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));

  const std::vector<vpColVector> M0four(M0.begin(), M0.begin() + 4), M1four(M1.begin(), M1.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0four, M1four); },
                               vpProjectiveException::notEnoughPointsError, "at least 5"));
  const std::vector<vpColVector> M1short(M1.begin(), M1.begin() + 7);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0, M1short); },
                               vpProjectiveException::dimensionError, "matched pairs"));

  std::vector<vpColVector> bad = M0;
  bad[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  bad = M1;
  bad[4][3] = -std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0, bad); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  bad = M0;
  bad[1] = point3(1.0, 2.0, 3.0);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::dimensionError, "must have 4 entries"));
  bad = M0;
  bad[0] = vpColVector(4, 0.0);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::invalidValueError, "zero vector"));

  // 5 points, 4 of them on one world plane (hence on one projective plane).
  const vpColVector c = Scene::fixation();
  std::vector<vpColVector> five = {c + point3(0.05, 0.0, 0.01), c + point3(-0.04, 0.03, -0.02),
                                   c + point3(0.01, -0.05, 0.03), c + point3(-0.03, -0.02, -0.01),
                                   c + point3(0.0, 0.0, 0.0)};
  // Put the 4th on the plane of the first three.
  {
    const Eigen::Vector3d a = toEigen<3, 1>(five[0]), b = toEigen<3, 1>(five[1]), d = toEigen<3, 1>(five[2]);
    five[3] = toVispVector(Eigen::Vector3d(a + 0.3 * (b - a) + 0.4 * (d - a)));
  }
  const vpHomogeneousMatrix T5 = randomMotion(scene, rng, five, Rotation, 0.5);
  const std::vector<vpColVector> P0 = projectivePoints(scene, five);
  const std::vector<vpColVector> P1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T5, five));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(P0, P1); },
                               vpProjectiveException::degenerateConfigurationError, "4 of the 5"));
  // A repeated point among 5.
  std::vector<vpColVector> R0 = projectivePoints(scene, std::vector<vpColVector>(body.begin(), body.begin() + 5));
  std::vector<vpColVector> R1 = std::vector<vpColVector>(M1.begin(), M1.begin() + 5);
  R0[4] = R0[1];
  R1[4] = R1[1];
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(R0, R1); },
                               vpProjectiveException::degenerateConfigurationError, "4 of the 5"));

  // All 8 points on one plane.
  std::vector<vpColVector> planar;
  while (planar.size() < 8) {
    const double x = rng.uniform(-0.08, 0.08), y = rng.uniform(-0.08, 0.08);
    planar.push_back(c + point3(x, y, 0.5 * x + 0.2 * y));
  }
  const std::vector<vpColVector> Q0 = projectivePoints(scene, planar);
  const std::vector<vpColVector> Q1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, planar));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(Q0, Q1); },
                               vpProjectiveException::degenerateConfigurationError, "are coplanar"));
}

TEST(vpProjectiveDisplacement, EstimateFromImagesInvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(17);
  vpGaussRand noise(1.0, 0.0, 17);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
  const Observation o = observe(scene, body, T, 0.0, noise);

  const vpProjectiveStereoRig empty;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(empty, o.left0, o.right0, o.left1, o.right1); },
                               vpProjectiveException::notInitializedError, "no fundamental matrix"));
  const std::vector<vpImagePoint> short1(o.right1.begin(), o.right1.begin() + 5);
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, short1); },
                       vpProjectiveException::dimensionError, "same size"));
  const std::vector<vpImagePoint> l0(o.left0.begin(), o.left0.begin() + 4), r0(o.right0.begin(), o.right0.begin() + 4),
      l1(o.left1.begin(), o.left1.begin() + 4), r1(o.right1.begin(), o.right1.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, l0, r0, l1, r1); },
                               vpProjectiveException::notEnoughPointsError, "at least 5"));
  std::vector<vpImagePoint> bad = o.left1;
  bad[3].set_i(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, bad, o.right1); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
}

TEST(vpProjectiveDisplacement, InvalidMatricesThrow)
{
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(H); },
                               vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveDisplacement D(H); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(toVisp(H)); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(vpMatrix(3, 3, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(vpMatrix(4, 3, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(Eigen::Matrix4d::Zero()); },
                               vpProjectiveException::invalidValueError, "zero matrix"));
  Eigen::Matrix4d singular = Eigen::Matrix4d::Identity();
  singular(3, 3) = 0.0;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(singular); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(singular); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
}
