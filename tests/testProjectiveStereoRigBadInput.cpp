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
  Tests of vpProjectiveStereoRig's bad inputs: every degenerate or invalid input throws a vpProjectiveException with a
  meaningful code and message.
*/

#include <gtest/gtest.h>

#include "vpProjectiveStereoRigTestTools.h"

using namespace vpProjectiveTest;

TEST(vpProjectiveStereoRig, EstimateInvalidInputsThrow)
{
  const Scene scene;
  SeededMatches data(scene, 51, 20, 0.0);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  vpUniRand &rng = data.rng; // the planar points below go on with it
  vpProjectiveStereoRig rig;

  const std::vector<vpImagePoint> left7(left.begin(), left.begin() + 7), right7(right.begin(), right.begin() + 7);
  EXPECT_TRUE(throwsProjective([&] { rig.estimate(left7, right7); }, vpProjectiveException::notEnoughPointsError,
                               "at least 8"));
  const std::vector<vpImagePoint> right19(right.begin(), right.begin() + 19);
  EXPECT_TRUE(
      throwsProjective([&] { rig.estimate(left, right19); }, vpProjectiveException::dimensionError, "right points"));

  std::vector<vpImagePoint> bad = left;
  bad[3].set_u(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(
      throwsProjective([&] { rig.estimate(bad, right); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  bad = right;
  bad[5].set_v(std::numeric_limits<double>::infinity());
  EXPECT_TRUE(
      throwsProjective([&] { rig.estimate(left, bad); }, vpProjectiveException::nonFiniteValueError, "not finite"));

  EXPECT_TRUE(
      throwsProjective([&] { rig.estimate(left, right, 0.0); }, vpProjectiveException::invalidValueError, "positive"));
  EXPECT_TRUE(throwsProjective([&] { rig.estimate(left, right, std::numeric_limits<double>::quiet_NaN()); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));

  // All points on one world plane: a homography relates the images and F is not determined.
  std::vector<vpColVector> planar;
  const vpColVector c = Scene::fixation();
  while (planar.size() < 20) {
    const double x = rng.uniform(-0.12, 0.12), y = rng.uniform(-0.1, 0.1);
    const vpColVector X = point3(c[0] + x, c[1] + y, c[2] + 0.3 * x - 0.2 * y);
    if (scene.sim.isVisible(X, 10.0)) {
      planar.push_back(X);
    }
  }
  std::vector<vpImagePoint> pl, pr;
  imagesOf(scene.sim, planar, pl, pr);
  EXPECT_TRUE(
      throwsProjective([&] { rig.estimate(pl, pr); }, vpProjectiveException::degenerateConfigurationError, "plane"));
  // Matches all on one image line.
  std::vector<vpImagePoint> ll(12), lr(12);
  for (size_t i = 0; i < ll.size(); ++i) {
    ll[i].set_uv(100.0 + 30.0 * i, 200.0 + 10.0 * i);
    lr[i].set_uv(80.0 + 31.0 * i, 190.0 + 12.0 * i);
  }
  EXPECT_TRUE(throwsProjective([&] { rig.estimate(ll, lr); }, vpProjectiveException::degenerateConfigurationError,
                               "collinear"));
  // Nothing of the failed calls was kept.
  EXPECT_FALSE(rig.isInitialized());
}

TEST(vpProjectiveStereoRig, SetFundamentalMatrixInvalidInputsThrow)
{
  const Scene scene;
  vpProjectiveStereoRig rig;
  vpMatrix F = scene.sim.getFundamentalMatrix();
  F[1][2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(
      throwsProjective([&] { rig.setFundamentalMatrix(F); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  F = scene.sim.getFundamentalMatrix();
  F[0][0] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(
      throwsProjective([&] { rig.setFundamentalMatrix(F); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { rig.setFundamentalMatrix(vpMatrix(4, 4, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 3x3"));
  EXPECT_TRUE(throwsProjective([&] { rig.setFundamentalMatrix(vpMatrix(3, 4, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 3x3"));
  EXPECT_TRUE(throwsProjective([&] { rig.setFundamentalMatrix(vpMatrix(3, 3, 0.0)); },
                               vpProjectiveException::invalidValueError, "zero"));
  EXPECT_TRUE(throwsProjective([&] { rig.setFundamentalMatrix(vpMatrix(3, 3, 1.0)); },
                               vpProjectiveException::degenerateConfigurationError, "rank"));
  EXPECT_FALSE(rig.isInitialized());
}

TEST(vpProjectiveStereoRig, UseBeforeInitialisationThrows)
{
  vpProjectiveStereoRig rig;
  vpImagePoint l(240.0, 320.0), r(240.0, 300.0);
  vpColVector M(4, 0.5);
  const int code = vpProjectiveException::notInitializedError;
  EXPECT_TRUE(throwsProjective([&] { rig.triangulate(l, r); }, code, "no fundamental matrix"));
  EXPECT_TRUE(
      throwsProjective([&] { rig.triangulate(std::vector<vpImagePoint>(1, l), std::vector<vpImagePoint>(1, r)); }, code,
                       "no fundamental matrix"));
  EXPECT_TRUE(throwsProjective([&] { rig.project(M, l, r); }, code, "no fundamental matrix"));
  EXPECT_TRUE(throwsProjective([&] { rig.getFundamentalMatrix(); }, code, "no fundamental matrix"));
  EXPECT_TRUE(throwsProjective([&] { rig.getLeftProjection(); }, code, "no fundamental matrix"));
  EXPECT_TRUE(throwsProjective([&] { rig.getRightProjection(); }, code, "no fundamental matrix"));
  EXPECT_TRUE(throwsProjective([&] { rig.getLeftEpipole(); }, code, "no fundamental matrix"));
  EXPECT_TRUE(throwsProjective([&] { rig.getRightEpipole(); }, code, "no fundamental matrix"));
}

TEST(vpProjectiveStereoRig, TriangulateAndProjectInvalidInputsThrow)
{
  const Scene scene;
  const vpProjectiveStereoRig &rig = scene.rig;
  vpImagePoint l(240.0, 320.0), r(240.0, 300.0);
  vpImagePoint nan(std::numeric_limits<double>::quiet_NaN(), 300.0);
  EXPECT_TRUE(
      throwsProjective([&] { rig.triangulate(nan, r); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(
      throwsProjective([&] { rig.triangulate(l, nan); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  // The overload for lists of matches: the same checks on every match, and lists of equal sizes.
  const std::vector<vpImagePoint> lefts = {l, l}, rights = {r, nan};
  EXPECT_TRUE(throwsProjective([&] { rig.triangulate(lefts, rights); }, vpProjectiveException::nonFiniteValueError,
                               "not finite"));
  EXPECT_TRUE(throwsProjective([&] { rig.triangulate(lefts, std::vector<vpImagePoint>(1, r)); },
                               vpProjectiveException::dimensionError, "pass matched pairs"));
  EXPECT_TRUE(rig.triangulate(std::vector<vpImagePoint>(), std::vector<vpImagePoint>()).empty());

  vpImagePoint pl, pr;
  EXPECT_TRUE(throwsProjective([&] { rig.project(vpColVector(3, 1.0), pl, pr); }, vpProjectiveException::dimensionError,
                               "must have 4 entries"));
  EXPECT_TRUE(throwsProjective([&] { rig.project(vpColVector(5, 1.0), pl, pr); }, vpProjectiveException::dimensionError,
                               "must have 4 entries"));
  vpColVector M(4, 1.0);
  M[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(
      throwsProjective([&] { rig.project(M, pl, pr); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { rig.project(vpColVector(4, 0.0), pl, pr); },
                               vpProjectiveException::invalidValueError, "zero vector"));
}
