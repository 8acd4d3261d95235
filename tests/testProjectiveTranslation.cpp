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
  Tests of what belongs to the p-translations only (vpProjectiveTranslation; helpers in
  vpProjectiveJointGroupTestTools.h): the generator per encoder unit, the degenerate inputs.
*/

#include <gtest/gtest.h>

#include "vpProjectiveJointGroupTestTools.h"

using namespace vpProjectiveTest;

/*
  The generator is per unit of the encoder: the same motion read as 2 tau gives half the generator. exp is affine in
  tau, so its derivative is the generator itself: dexp(tau) = Hhat = Hhat exp(tau Hhat) (Hhat^2 = 0). A p-translation
  generator is no p-rotation generator (|Hhat^3 + Hhat| / |Hhat| = 1).
*/
TEST(vpProjectiveTranslation, GeneratorIsPerUnitOfEncoder)
{
  const Scene scene;
  forEachRandomTruth<TranslationTraits>(scene, 31, [&](int k, const Truth<TranslationTraits> &truth, vpUniRand &) {
    const Eigen::Matrix4d Gtrue = truth.generator();
    for (double tau : TranslationTraits::logAmounts()) {
      SCOPED_TRACE(::testing::Message() << "direction " << k << ", tau " << tau);
      const vpProjectiveDisplacement H(truth.motion(tau));
      EXPECT_LT(relativeError(vpProjectiveTranslation::log(H, 2.0 * tau).generator(), Eigen::Matrix4d(0.5 * Gtrue)),
                1e-9);
      const vpProjectiveTranslation T = vpProjectiveTranslation::log(H, tau);
      EXPECT_EQ(T.dexp(tau), T.generator());
      EXPECT_LT(relativeError(Eigen::Matrix4d(T.generator() * T.exp(tau).matrix()), T.generator()), 1e-9);
      EXPECT_GT(vpProjectiveRotation::generatorResidual(T.generator()), 0.5);
    }
  });
}

TEST(vpProjectiveTranslation, DegenerateInputsThrow)
{
  const Scene scene;
  vpUniRand rng(32);
  const Truth<TranslationTraits> truth{scene, randomJoint(rng)};
  const vpProjectiveDisplacement H(truth.motion(0.1));

  // No encoder length: the generator cannot be scaled.
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation::log(H, 0.0); }, vpProjectiveException::invalidValueError,
                               "zero"));
  // A p-rotation generator (Hhat^3 = -Hhat, not nilpotent), a rank-1 matrix that is not nilpotent (a projector).
  const Eigen::Matrix4d rotation =
      scene.HpeInv * vpMetricTwist::hat(Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 1.0)) * scene.Hpe;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(rotation); }, vpProjectiveException::invalidValueError,
                               "not a p-translation generator"));
  const Eigen::Vector4d u(1.0, 2.0, -1.0, 0.5);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(Eigen::Matrix4d(u * u.transpose())); },
                               vpProjectiveException::invalidValueError, "not a p-translation generator"));
}
