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
  Tests of vpProjectiveStereoRig::estimate() (bounds in vpProjectiveStereoRigTestTools.h): exact epipolar geometry
  from noise-free matches; under 0.5 px noise an accuracy near the first-order prediction, with a loose threshold too;
  the inliers agree with the returned F.
*/

#include <gtest/gtest.h>

#include "vpProjectiveStereoRigTestTools.h"

using namespace vpProjectiveTest;

TEST(vpProjectiveStereoRig, EstimateNoiseFreeIsExact)
{
  const Scene scene;
  for (unsigned int seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    // The fresh points are drawn after the estimated ones: they play no part in the estimate.
    const SeededMatches data(scene, static_cast<long>(seed), 8 + 4 * seed, 0.0, 50);
    const std::vector<vpImagePoint> &left = data.left, &right = data.right;

    vpProjectiveStereoRig rig;
    ASSERT_FALSE(rig.isInitialized());
    rig.estimate(left, right);
    ASSERT_TRUE(rig.isInitialized());
    const Eigen::Matrix3d F = toEigen<3, 3>(rig.getFundamentalMatrix());

    // Epipolar constraint on the matches used and on fresh points.
    EXPECT_LT(maxAlgebraicEpipolarResidual(F, left, right), 1e-8);
    EXPECT_LT(maxAlgebraicEpipolarResidual(F, data.freshLeft, data.freshRight), 1e-8);
    EXPECT_LT(rmsEpipolarDistance(F, data.freshLeft, data.freshRight), 1e-6);

    // Proportional to the true F, unit norm, rank 2.
    EXPECT_LT(relativeErrorUpToScale(F, trueF(scene)), 1e-6);
    EXPECT_NEAR(F.norm(), 1.0, 1e-12);
    EXPECT_LT(std::abs(F.determinant()), 1e-12);

    EXPECT_LT(rig.getEstimationResidual(), 1e-6);
    // (Which matches are flagged is tested in EstimateInliersAgreeWithReturnedF.)
    ASSERT_EQ(rig.getInliers().size(), left.size());
    EXPECT_GE(std::count(rig.getInliers().begin(), rig.getInliers().end(), true), 8);
  }
}

/*
  Noise sigma = 0.5 px on each coordinate, n = 50 matches (no wrong match), 20 seeds. First-order least squares:
  - residual: the gold-standard fit has 4n measurements and 3n + 7 parameters, so the expected sum of squared
    reprojection errors is (n - 7) sigma^2; getEstimationResidual() divides it by 2n (RMS distance per image point),
    hence residual ~ sigma sqrt((n - 7) / (2n)) = 0.328 px. One seed's sum is chi-square with 43 dof (relative
    std sqrt(2/43) = 0.22, i.e. 0.11 on the RMS): each seed must be within +-35 % (3 std), their mean within +-10 %.
  - prediction: the epipolar distance of a noisy match has variance ~ 2 sigma^2 (noise in both images, the two
    cameras have the same scale); the 7 parameters fitted on n constraints leave on fresh noise-free points a mean
    squared epipolar distance of ~ (7/n) 2 sigma^2, RMS sigma sqrt(14/n) = 0.26 px. Bounds: the mean over seeds below
    1.5x that (0.40 px), every seed below 3x (0.79 px).
  Measured (20 seeds): residual mean 0.327 px, fresh RMS epipolar distance mean 0.28 px, max 0.42 px.
  The inlier threshold is 5 px (7 std of the epipolar distance): there are no wrong matches here, and this test is
  about accuracy; the inlier selection at a tight threshold is tested separately below.
*/
TEST(vpProjectiveStereoRig, EstimateNoisyReachesNoiseFloor)
{
  const Scene scene;
  const NoiseFloor f = estimateAtNoiseFloor(scene, 5.0);
  testLog() << "[ stats    ] F, sigma " << kSigma << " px, n " << kNoisyMatches << ": residual mean " << f.meanResidual
            << " px (expected " << expectedResidual() << "), max relative deviation " << f.maxResidualDeviation
            << "; fresh RMS epipolar distance mean " << f.meanPrediction << " px, max " << f.maxPrediction
            << " (first order " << expectedPrediction() << ")" << std::endl;
  EXPECT_NEAR(f.meanResidual / expectedResidual(), 1.0, 0.10);
  EXPECT_LT(f.meanPrediction, 1.5 * expectedPrediction());
}

/*
  The same data with an inlier threshold of 100 px: every match is an inlier, so the result must be as accurate as
  above (same per-seed bounds). A loose threshold must not let the refinement stop far from the optimum.
*/
TEST(vpProjectiveStereoRig, EstimateLooseThresholdStaysAccurate)
{
  const Scene scene;
  estimateAtNoiseFloor(scene, 100.0);
}

/*
  The inlier flags agree with the returned F and the documented meaning of the threshold ("maximum distance in pixels
  of an inlier to its epipolar line"): with the textbook threshold 3 sigma sqrt(2) = 2.1 px (3 std of the epipolar
  distance of a noisy match), no match lying within 0.75 of the threshold of both its epipolar lines under the
  returned F may be flagged an outlier (such a match was silently left out of the estimate).
*/
TEST(vpProjectiveStereoRig, EstimateInliersAgreeWithReturnedF)
{
  const Scene scene;
  const double threshold = 3.0 * std::sqrt(2.0) * kSigma;
  for (int seed = 1; seed <= kNoisySeeds; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const SeededMatches data(scene, 100 + seed, kNoisyMatches, kSigma);
    const std::vector<vpImagePoint> &left = data.left, &right = data.right;
    vpProjectiveStereoRig rig;
    rig.estimate(left, right, threshold);
    Eigen::Matrix3d F;
    rig.getFundamentalMatrix(F);
    for (size_t i = 0; i < left.size(); ++i) {
      const double d = epipolarDistances(F, left[i], right[i]).maxCoeff();
      if (d < 0.75 * threshold) {
        EXPECT_TRUE(rig.getInliers()[i]) << "match " << i << " at " << d << " px from its epipolar lines";
      }
    }
  }
  // Noise-free matches in general position, from the minimum of 8 up: all lie exactly on their epipolar lines, so
  // the estimate must succeed and flag them all inliers.
  for (size_t m = 8; m <= 20; ++m) {
    SCOPED_TRACE(::testing::Message() << m << " noise-free matches");
    const SeededMatches data(scene, static_cast<long>(m), m, 0.0);
    vpProjectiveStereoRig rig;
    try {
      rig.estimate(data.left, data.right);
      EXPECT_EQ(std::count(rig.getInliers().begin(), rig.getInliers().end(), true), static_cast<long>(m));
      Eigen::Matrix3d F;
      rig.getFundamentalMatrix(F);
      EXPECT_LT(relativeErrorUpToScale(F, trueF(scene)), 1e-6);
    } catch (const vpException &e) {
      ADD_FAILURE() << "estimate() threw on exact matches: " << e.getStringMessage();
    }
  }
}
