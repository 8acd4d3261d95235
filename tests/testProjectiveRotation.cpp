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
  Tests of what belongs to the p-rotations only (vpProjectiveRotation; helpers in vpProjectiveJointGroupTestTools.h):
  the encoder-less logarithm, the period of exp(), the degenerate inputs.
*/

#include <gtest/gtest.h>

#include "vpProjectiveJointGroupTestTools.h"

using namespace vpProjectiveTest;

// Without an encoder reading (amount 0), the generator turns by the positive image angle (21): the joint's own for a
// positive motion, the reversed joint's for a negative one.
TEST(vpProjectiveRotation, LogWithoutEncoderUsesThePositiveImageAngle)
{
  const Scene scene;
  forEachRandomTruth<RotationTraits>(scene, 21, [&](int k, const Truth<RotationTraits> &truth, vpUniRand &) {
    const Eigen::Matrix4d Gtrue = truth.generator();
    for (double theta : {0.05, 0.5, 1.2, 2.5, 3.0}) {
      SCOPED_TRACE(::testing::Message() << "axis " << k << ", theta " << theta);
      const vpProjectiveDisplacement H(truth.motion(theta)), Hneg(truth.motion(-theta));
      EXPECT_LT(relativeError(vpProjectiveRotation::log(H, 0.0).generator(), Gtrue), 1e-9);
      EXPECT_LT(relativeError(vpProjectiveRotation::log(Hneg, 0.0).generator(), Eigen::Matrix4d(-Gtrue)), 1e-9);
    }
  });
}

TEST(vpProjectiveRotation, ExpIsPeriodic)
{
  const Scene scene;
  forEachRandomTruth<RotationTraits>(scene, 22, [](int, const Truth<RotationTraits> &truth, vpUniRand &rng) {
    const vpProjectiveRotation R(truth.generator());
    EXPECT_LT(relativeError(R.exp(2.0 * M_PI).matrix(), Eigen::Matrix4d(Eigen::Matrix4d::Identity())), 1e-9);
    const double t = rng.uniform(-4.0, 4.0);
    EXPECT_LT(relativeError(R.exp(t + 2.0 * M_PI).matrix(), R.exp(t).matrix()), 1e-9);
  });
}

TEST(vpProjectiveRotation, DegenerateInputsThrow)
{
  const Scene scene;
  vpUniRand rng(23);
  const Truth<RotationTraits> truth{scene, randomJoint(rng)};
  const auto logOf = [](const Eigen::Matrix4d &H, double amount) {
    return vpProjectiveRotation::log(vpProjectiveDisplacement(H), amount);
  };

  // No rotation, or a half turn: the logarithm (25) divides by sin(theta).
  EXPECT_TRUE(throwsProjective([&] { logOf(Eigen::Matrix4d::Identity(), 0.0); },
                               vpProjectiveException::degenerateConfigurationError, "multiple of pi"));
  EXPECT_TRUE(throwsProjective([&] { logOf(truth.motion(1e-9), 1e-9); },
                               vpProjectiveException::degenerateConfigurationError, "multiple of pi"));
  EXPECT_TRUE(throwsProjective([&] { logOf(truth.motion(M_PI), M_PI); },
                               vpProjectiveException::degenerateConfigurationError, "pi"));
  // A pure translation has angle 0 (21).
  const Eigen::Matrix4d Ht = scene.projectiveDisplacement(vpSimulatorStereoRig::translationAlong(point3(1, 0, 0), 0.1));
  EXPECT_TRUE(
      throwsProjective([&] { logOf(Ht, 0.0); }, vpProjectiveException::degenerateConfigurationError, "multiple of pi"));

  // Twice a generator: Hhat^3 = 4 (-Hhat), no longer -Hhat.
  const Eigen::Matrix4d G = truth.generator();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(Eigen::Matrix4d(2.0 * G)); },
                               vpProjectiveException::invalidValueError, "not a p-rotation generator"));
  // A p-translation generator (nilpotent) is not a p-rotation generator: its residual |Hhat^3 + Hhat| / |Hhat| is 1.
  const Eigen::Matrix4d Tt = scene.HpeInv * vpMetricTwist::prismatic(Eigen::Vector3d(1.0, 0.0, 0.0)) * scene.Hpe;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(Tt); }, vpProjectiveException::invalidValueError,
                               "not a p-rotation generator"));
}
