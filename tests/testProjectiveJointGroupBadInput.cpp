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
  Typed tests of both joint groups (vpProjectiveJointGroupTestTools.h): invalid inputs throw a vpProjectiveException
  with a meaningful code and message.
*/

#include <gtest/gtest.h>

#include "vpProjectiveJointGroupTestTools.h"

using namespace vpProjectiveTest;

TYPED_TEST(JointGroup, BadInputsThrow)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(12);
  const Truth<Traits> truth = this->randomTruth(rng);
  const double a = Traits::logAmounts()[2];
  const Eigen::Matrix4d H = truth.motion(a);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto logOfMatrix = [&](const auto &M, double amount) {
    return Group::log(vpProjectiveDisplacement(M), amount);
  };

  // A displacement that cannot be normalised: non-finite, mis-sized, zero or singular.
  Eigen::Matrix4d bad = H;
  bad(2, 1) = nan;
  EXPECT_TRUE(throwsProjective([&] { logOfMatrix(bad, a); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(
      throwsProjective([&] { logOfMatrix(toVisp(bad), a); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { logOfMatrix(vpMatrix(3, 3, 1.0), a); }, vpProjectiveException::dimensionError,
                               "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { logOfMatrix(Eigen::Matrix4d(Eigen::Matrix4d::Zero()), a); },
                               vpProjectiveException::invalidValueError, "zero matrix"));
  for (int copy = 0; copy < 2; ++copy) {
    Eigen::Matrix4d singular = H;
    if (copy == 0) {
      singular.row(3) = singular.row(2);
    } else {
      singular.col(2) = singular.col(1);
    }
    EXPECT_TRUE(throwsProjective([&] { logOfMatrix(singular, a); }, vpProjectiveException::degenerateConfigurationError,
                                 "singular"));
  }
  // A non-finite encoder amount.
  for (double amount : {nan, inf, -inf}) {
    EXPECT_TRUE(
        throwsProjective([&] { logOfMatrix(H, amount); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  }

  // Matrices that are no generators of the group, or no matrices at all.
  const Eigen::Matrix4d random = randomMatrix(rng);
  EXPECT_TRUE(
      throwsProjective([&] { Group G(random); }, vpProjectiveException::invalidValueError, Traits::notAGenerator()));
  EXPECT_TRUE(throwsProjective([&] { Group G(toVisp(random)); }, vpProjectiveException::invalidValueError,
                               Traits::notAGenerator()));
  const Eigen::Matrix4d Gtrue = truth.generator();
  for (double value : {nan, inf}) {
    Eigen::Matrix4d nonFinite = Gtrue;
    nonFinite(1, 1) = value;
    EXPECT_TRUE(throwsProjective([&] { Group G(nonFinite); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  }
  EXPECT_TRUE(
      throwsProjective([&] { Group G(vpMatrix(3, 3, 0.0)); }, vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(
      throwsProjective([&] { Group G(vpMatrix(4, 3, 0.0)); }, vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { Group G(Gtrue, -1.0); }, vpProjectiveException::invalidValueError, "tolerance"));
}
