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
  Tests of vpProjectiveDisplacement's group operations: the normalisation (12) removes any scale and sign and gives
  det H = 1; composition and inverse follow the metric ones.
*/

#include <gtest/gtest.h>

#include "vpProjectiveDisplacementTestTools.h"

using namespace vpProjectiveTest;

TEST(vpProjectiveDisplacement, NormalisationRemovesScaleAndSign)
{
  const Scene scene;
  vpUniRand rng(5);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  for (int k = Rotation; k <= Translation; ++k) {
    SCOPED_TRACE(kindName(static_cast<MotionKind>(k)));
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, static_cast<MotionKind>(k), 0.7);
    // H_PE with an arbitrary scale: the conjugate does not depend on it, and with det H_PE = +-1 from the simulator
    // it is exactly the normalised displacement (det 1, positive trace).
    const Eigen::Matrix4d Hpe = 3.7 * scene.Hpe;
    const Eigen::Matrix4d H = Hpe.inverse() * scene.cameraDisplacement(T) * Hpe;
    const Eigen::Matrix4d Hn = vpProjectiveDisplacement::normalize(H);
    EXPECT_NEAR(Hn.determinant(), 1.0, 1e-12);
    EXPECT_GT(Hn.trace(), 0.0);
    EXPECT_LT(relativeError(Hn, H), 1e-12);
    for (double s : {-5.0, 1e-3, -1e4, 7.5, -1.0}) {
      SCOPED_TRACE(::testing::Message() << "scale " << s);
      const Eigen::Matrix4d Hs = vpProjectiveDisplacement::normalize(Eigen::Matrix4d(s * H));
      EXPECT_LT(relativeError(Hs, Hn), 1e-13);
      EXPECT_NEAR(Hs.determinant(), 1.0, 1e-12);
      // The constructors normalise too.
      EXPECT_LT(relativeError(vpProjectiveDisplacement(toVisp(Eigen::Matrix4d(s * H))).matrix(), Hn), 1e-13);
      EXPECT_LT(relativeError(vpProjectiveDisplacement(Eigen::Matrix4d(s * H)).matrix(), Hn), 1e-13);
    }
  }
  // A rotation close to pi has a trace close to 0 (2 + 2 cos theta): the sign is still found.
  const vpHomogeneousMatrix T = vpSimulatorStereoRig::rotationAbout(Scene::fixation(), point3(0.3, 1.0, 0.2), 3.0);
  const Eigen::Matrix4d H = scene.projectiveDisplacement(T);
  EXPECT_LT(relativeError(vpProjectiveDisplacement::normalize(Eigen::Matrix4d(-2.0 * H)), H), 1e-12);
  EXPECT_NEAR(vpProjectiveDisplacement(H).getRotationAngle(), 3.0, 1e-9);
}

TEST(vpProjectiveDisplacement, CompositionAndInverseFollowTheMetricOnes)
{
  const Scene scene;
  vpUniRand rng(9);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  const vpHomogeneousMatrix T1 = randomMotion(scene, rng, body, Screw, 0.4);
  const vpHomogeneousMatrix T2 = randomMotion(scene, rng, body, Rotation, 0.9);
  const vpProjectiveDisplacement D1(truth(scene, T1)), D2(truth(scene, T2));
  // Points move by T1 then T2: T2 T1.
  EXPECT_LT(relativeError((D2 * D1).matrix(), truth(scene, T2 * T1)), 1e-10);
  EXPECT_LT(relativeError(D1.inverse().matrix(), truth(scene, T1.inverse())), 1e-10);
  EXPECT_LT(((D1 * D1.inverse()).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-10);
  EXPECT_EQ((D1 * D1.inverse()).classify(), vpProjectiveDisplacement::IDENTITY);
  // The default displacement is the identity.
  EXPECT_EQ(vpProjectiveDisplacement().matrix(), Eigen::Matrix4d::Identity());
  EXPECT_EQ(vpProjectiveDisplacement().classify(), vpProjectiveDisplacement::IDENTITY);
  EXPECT_EQ(vpProjectiveDisplacement().getRotationAngle(), 0.0);
}
