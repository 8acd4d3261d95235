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
  Tests of vpProjectiveStereoRig, the weakly calibrated rig (Ruf & Horaud, section 2), against the metric simulator:
  - estimate(): exact epipolar geometry from noise-free matches; under 0.5 px noise an accuracy near the first-order
    prediction; robustness to 20 % wrong matches (far ones, and random wrong pairings: accuracy against the
    outlier-free estimate, recall and precision of getInliers()); below 15 matches (no RANSAC) correct sets are
    estimated and a wrong match is mostly reported;
  - the canonical frame: P = [I|0], P' independent of the scale and sign of F, epipoles, F ~ [e']_x P'(:, 0:3);
  - triangulate() / project(): round trips, agreement with the true projective points H_PE^-1 N, optimality of the
    refined triangulation, invariance to the scale of M, points on a focal plane;
  - every degenerate or invalid input throws a vpProjectiveException with a meaningful code and message.

  Bounds. Noise-free quantities are exact up to rounding: pixel coordinates of a few hundred, a frame conditioned by
  Hartley normalisation, hence 1e-8 relative (or 1e-8 px) leaves several orders of magnitude of margin while any
  modelling error (wrong P', wrong sign, wrong epipole) gives errors of order 1. The noisy bounds are derived in the
  tests from the standard first-order results for least-squares estimators (residual and prediction error of a fit
  with p parameters on n measurements), and were checked against measurements over all the seeds used.
*/

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
const double kSigma = 0.5; // pixel noise of the noisy tests (px)

// Matches of n random points around the fixation point (a 24 cm cube, 1 m away: they fill most of both images).
void randomMatches(const Scene &scene, vpUniRand &rng, size_t n, double sigma, vpGaussRand &noise,
                   std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right,
                   std::vector<vpColVector> *points = nullptr)
{
  const std::vector<vpColVector> wX = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.12, n);
  scene.sim.project(wX, left, right, sigma, noise);
  if (points) {
    *points = wX;
  }
}

/*
  The data of one seed: a vpUniRand and a vpGaussRand seeded alike, n matches with noise sigma, then nFresh noise-free
  matches to judge a fitted F on; the generators go on with what the test draws next.
*/
struct SeededMatches {
  vpUniRand rng;
  vpGaussRand noise;
  std::vector<vpColVector> points; //!< the world points of the matches
  std::vector<vpImagePoint> left, right, freshLeft, freshRight;

  SeededMatches(const Scene &scene, long seed, size_t n, double sigma, size_t nFresh = 0)
      : rng(static_cast<uint64_t>(seed)), noise(1.0, 0.0, seed), points(), left(), right(), freshLeft(), freshRight()
  {
    randomMatches(scene, rng, n, sigma, noise, left, right, &points);
    if (nFresh > 0) {
      randomMatches(scene, rng, nFresh, 0.0, noise, freshLeft, freshRight);
    }
  }
};

//! The right image of a random point lying more than 20 px from the epipolar lines (true F) of \e left in both
//! images: a wrong match for \e left that no geometric test could take for a correct one.
vpImagePoint wrongRightImage(const Scene &scene, const Eigen::Matrix3d &Ftrue, const vpImagePoint &left, vpUniRand &rng,
                             vpGaussRand &noise)
{
  for (;;) {
    std::vector<vpImagePoint> otherLeft, otherRight;
    randomMatches(scene, rng, 1, 0.0, noise, otherLeft, otherRight);
    if (epipolarDistances(Ftrue, left, otherRight[0]).minCoeff() > 20.0) {
      return otherRight[0];
    }
  }
}

Eigen::Matrix3d trueF(const Scene &scene)
{
  return toEigen<3, 3>(scene.sim.getFundamentalMatrix());
}

// |m'^T F m| / (|m'| |F| |m|), the largest over the matches.
double maxAlgebraicEpipolarResidual(const Eigen::Matrix3d &F, const std::vector<vpImagePoint> &left,
                                    const std::vector<vpImagePoint> &right)
{
  double worst = 0.0;
  for (size_t i = 0; i < left.size(); ++i) {
    const Eigen::Vector3d m = pixel(left[i]), mp = pixel(right[i]);
    worst = std::max(worst, std::abs(mp.dot(F * m)) / (mp.norm() * F.norm() * m.norm()));
  }
  return worst;
}

// Linear triangulation (DLT on row-normalised equations), the reference the refined triangulation must beat.
Eigen::Vector4d triangulateDLT(const Eigen::Matrix<double, 3, 4> &P, const Eigen::Matrix<double, 3, 4> &Pp,
                               const vpImagePoint &l, const vpImagePoint &r)
{
  Eigen::Matrix4d A;
  A.row(0) = l.get_u() * P.row(2) - P.row(0);
  A.row(1) = l.get_v() * P.row(2) - P.row(1);
  A.row(2) = r.get_u() * Pp.row(2) - Pp.row(0);
  A.row(3) = r.get_v() * Pp.row(2) - Pp.row(1);
  for (int i = 0; i < 4; ++i) {
    A.row(i).normalize();
  }
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  return svd.matrixV().col(3);
}

// Reprojection error (px, both images together) of M against a match.
double reprojectionError(const vpProjectiveStereoRig &rig, const Eigen::Vector4d &M, const vpImagePoint &l,
                         const vpImagePoint &r)
{
  vpImagePoint pl, pr;
  rig.project(toVispVector(M), pl, pr);
  return std::sqrt(std::pow(pixelDistance(pl, l), 2) + std::pow(pixelDistance(pr, r), 2));
}

// Sampson's first-order approximation of the smallest reprojection error of a match consistent with F.
double sampsonError(const Eigen::Matrix3d &F, const vpImagePoint &l, const vpImagePoint &r)
{
  const Eigen::Vector3d m = pixel(l), mp = pixel(r);
  const Eigen::Vector3d Fm = F * m, Ftmp = F.transpose() * mp;
  return std::abs(mp.dot(Fm)) / std::sqrt(Fm.head<2>().squaredNorm() + Ftmp.head<2>().squaredNorm());
}

// The noisy estimation tests: n = 50 matches with kSigma noise, 20 seeds (see EstimateNoisyReachesNoiseFloor).
const size_t kNoisyMatches = 50;
const int kNoisySeeds = 20;

//! First-order RMS distance of a match to its epipolar lines under the fitted F (see EstimateNoisyReachesNoiseFloor).
double expectedResidual()
{
  return kSigma * std::sqrt((kNoisyMatches - 7.0) / (2.0 * kNoisyMatches));
}

//! First-order RMS epipolar distance of fresh noise-free matches under the fitted F.
double expectedPrediction()
{
  return kSigma * std::sqrt(14.0 / kNoisyMatches);
}

struct NoiseFloor {
  double meanResidual, meanPrediction, maxPrediction, maxResidualDeviation;
};

//! estimate() with \e threshold on the data of the noisy tests, each seed within the per-seed bounds; the statistics.
NoiseFloor estimateAtNoiseFloor(const Scene &scene, double threshold)
{
  NoiseFloor f = {0.0, 0.0, 0.0, 0.0};
  for (int seed = 1; seed <= kNoisySeeds; ++seed) {
    SCOPED_TRACE(::testing::Message() << "threshold " << threshold << " px, seed " << seed);
    const SeededMatches data(scene, 100 + seed, kNoisyMatches, kSigma, 200);
    vpProjectiveStereoRig rig;
    rig.estimate(data.left, data.right, threshold);
    const double prediction = rmsEpipolarDistance(rig.fundamentalMatrix(), data.freshLeft, data.freshRight);
    const double residual = rig.getEstimationResidual();
    EXPECT_LT(prediction, 3.0 * expectedPrediction());
    EXPECT_NEAR(residual / expectedResidual(), 1.0, 0.35);
    f.meanResidual += residual / kNoisySeeds;
    f.meanPrediction += prediction / kNoisySeeds;
    f.maxPrediction = std::max(f.maxPrediction, prediction);
    f.maxResidualDeviation = std::max(f.maxResidualDeviation, std::abs(residual / expectedResidual() - 1.0));
  }
  return f;
}
} // namespace

// ---------------------------------------------------------------------------------------------------------------
// estimate()
// ---------------------------------------------------------------------------------------------------------------

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
  std::cout << "[ stats    ] F, sigma " << kSigma << " px, n " << kNoisyMatches << ": residual mean " << f.meanResidual
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
    for (size_t i = 0; i < left.size(); ++i) {
      const double d = epipolarDistances(rig.fundamentalMatrix(), left[i], right[i]).maxCoeff();
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
      EXPECT_LT(relativeErrorUpToScale(rig.fundamentalMatrix(), trueF(scene)), 1e-6);
    } catch (const vpException &e) {
      ADD_FAILURE() << "estimate() threw on exact matches: " << e.getStringMessage();
    }
  }
}

/*
  20 % wrong matches: the right image point of 8 of 40 matches is replaced by the image of another random point,
  drawn until it lies more than 20 px from the true epipolar line in both images (a closer "wrong" match would be
  geometrically plausible). Noise-free with a 1 px threshold, and with 0.5 px noise with a 5 px threshold
  (7 std of the epipolar distance, 4x below the outliers' distance): the wrong matches must all be rejected, the true
  ones all kept, and F be exact (noise-free) or within the noisy test's per-seed bound for 32 matches (noisy).
*/
TEST(vpProjectiveStereoRig, EstimateRejectsOutliers)
{
  const Scene scene;
  const Eigen::Matrix3d Ftrue = trueF(scene);
  const size_t n = 40, nOut = 8;
  for (int noisy = 0; noisy < 2; ++noisy) {
    for (int seed = 1; seed <= 5; ++seed) {
      SCOPED_TRACE(::testing::Message() << (noisy ? "noisy" : "noise-free") << ", seed " << seed);
      const double sigma = noisy ? kSigma : 0.0;
      SeededMatches data(scene, 200 + seed, n, sigma, 200);
      std::vector<bool> outlier(n, false);
      for (size_t k = 0; k < nOut; ++k) {
        const size_t i = static_cast<size_t>(data.rng.uniform(0, static_cast<int>(n)));
        if (outlier[i]) {
          --k;
          continue;
        }
        data.right[i] = wrongRightImage(scene, Ftrue, data.left[i], data.rng, data.noise);
        outlier[i] = true;
      }

      vpProjectiveStereoRig rig;
      rig.estimate(data.left, data.right, noisy ? 5.0 : 1.0);
      const std::vector<bool> &inliers = rig.getInliers();
      ASSERT_EQ(inliers.size(), n);
      size_t lost = 0;
      for (size_t i = 0; i < n; ++i) {
        if (outlier[i]) {
          EXPECT_FALSE(inliers[i]) << "wrong match " << i << " kept";
        } else if (!inliers[i]) {
          ++lost;
        }
      }
      const Eigen::Matrix3d F = toEigen<3, 3>(rig.getFundamentalMatrix());
      EXPECT_EQ(lost, 0u);
      if (noisy) {
        EXPECT_LT(rmsEpipolarDistance(F, data.freshLeft, data.freshRight), 3.0 * kSigma * std::sqrt(14.0 / (n - nOut)));
      } else {
        EXPECT_LT(relativeErrorUpToScale(F, Ftrue), 1e-6);
        EXPECT_LT(rig.getEstimationResidual(), 1e-6);
      }
    }
  }
}

/*
  Random wrong pairings: the right image points of nWrong random matches are permuted cyclically (seeded), as a
  matcher that confuses similar features does. Returns the wrong matches.
*/
std::vector<bool> mispair(vpUniRand &rng, size_t nWrong, std::vector<vpImagePoint> &right)
{
  const size_t n = right.size();
  std::vector<bool> wrong(n, false);
  std::vector<size_t> chosen;
  while (chosen.size() < nWrong) {
    const size_t i = static_cast<size_t>(rng.uniform(0, static_cast<int>(n)));
    if (!wrong[i]) {
      wrong[i] = true;
      chosen.push_back(i);
    }
  }
  const std::vector<vpImagePoint> original = right;
  for (size_t k = 0; k < nWrong; ++k) {
    right[chosen[k]] = original[chosen[(k + 1) % nWrong]];
  }
  return wrong;
}

// The normalised 8-point F of all the matches (rank 2, no robustness): what a least-squares estimate makes of them.
Eigen::Matrix3d eightPoint(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
{
  const auto normalisation = [](const std::vector<vpImagePoint> &points) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const vpImagePoint &p : points) {
      c += pixel(p).head<2>() / static_cast<double>(points.size());
    }
    double d = 0.0;
    for (const vpImagePoint &p : points) {
      d += (pixel(p).head<2>() - c).norm() / static_cast<double>(points.size());
    }
    Eigen::Matrix3d T;
    T << std::sqrt(2.0) / d, 0, -std::sqrt(2.0) / d * c(0), 0, std::sqrt(2.0) / d, -std::sqrt(2.0) / d * c(1), 0, 0, 1;
    return T;
  };
  const Eigen::Matrix3d T = normalisation(left), Tp = normalisation(right);
  Eigen::MatrixXd A(left.size(), 9);
  for (size_t i = 0; i < left.size(); ++i) {
    const Eigen::Vector3d m = T * pixel(left[i]), mp = Tp * pixel(right[i]);
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        A(static_cast<Eigen::Index>(i), 3 * a + b) = mp(a) * m(b);
      }
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  Eigen::Matrix3d Fn;
  for (int a = 0; a < 3; ++a) {
    Fn.row(a) = svd.matrixV().col(8).segment<3>(3 * a).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svdF(Fn, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Fn = svdF.matrixU() * Eigen::Vector3d(svdF.singularValues()(0), svdF.singularValues()(1), 0.0).asDiagonal() *
       svdF.matrixV().transpose();
  return Tp.transpose() * Fn * T;
}

/*
  20 % random wrong pairings (mispair(): the right points of a fifth of the matches permuted, as a confused matcher
  does), 0.5 px noise, the default 2 px threshold, 40 seeds, n = 40 and 100 matches (RANSAC is used from 15). Four
  estimates per case, compared by the RMS epipolar distance of 200 fresh noise-free matches:
  - oracle: estimate() on the 80 % correct matches only (the outlier-free accuracy of these data);
  - robust: estimate() on all the matches, wrong pairings included;
  - clean: estimate() on the same matches correctly paired (printed: the price of the lost fifth);
  - naive: the normalised 8-point F of all the matches (must be at least 5x worse than the oracle: the wrong
    pairings matter, so the properties below are not vacuous).
  Properties:
  - accuracy: the robust mean is within 1.25x of the oracle's. It cannot equal it: a wrong pairing that lands within
    the threshold of its true epipolar line (about 2 % of them here) is kept and acts as a match with up to 2 px of
    error, and a correct match beyond it is lost. Measured over four blocks of 20 seeds: ratios 0.90 to 1.12
    (n = 40), 1.00 to 1.18 (n = 100).
  - recall: of the wrong pairings farther than 2 t = 4 px from their true epipolar lines in both images, at least
    98 % are flagged (getInliers() false); measured 99.4 % (n = 40) and 99.7 % (n = 100). Those closer cannot be
    told from noisy correct matches (their count and the flagged share are printed).
  - precision: at least 95 % of the flagged matches are wrong pairings, and at most 1 % of the correct matches are
    flagged (at 2 px, 2.8 times the standard deviation of a correct match's distance, about 0.5 % are); measured
    97.2 and 97.8 %, 0.7 and 0.6 %.
*/
TEST(vpProjectiveStereoRig, EstimateWrongPairingsMatchOutlierFreeAccuracy)
{
  const Scene scene;
  const Eigen::Matrix3d Ftrue = trueF(scene);
  const double threshold = 2.0;
  const int seeds = 40;
  for (size_t n : {40, 100}) {
    SCOPED_TRACE(::testing::Message() << n << " matches");
    const size_t nWrong = n / 5;
    double oracle = 0.0, robust = 0.0, clean = 0.0, naive = 0.0;
    size_t detectable = 0, detectableFlagged = 0, close = 0, closeFlagged = 0, correct = 0, correctFlagged = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed);
      SeededMatches data(scene, 400 + seed, n, kSigma, 200);
      const std::vector<vpImagePoint> &left = data.left, &right = data.right, &freshLeft = data.freshLeft,
                                      &freshRight = data.freshRight;
      std::vector<vpImagePoint> wrongRight = right;
      const std::vector<bool> wrong = mispair(data.rng, nWrong, wrongRight);
      std::vector<vpImagePoint> correctLeft, correctRight;
      for (size_t i = 0; i < n; ++i) {
        if (!wrong[i]) {
          correctLeft.push_back(left[i]);
          correctRight.push_back(right[i]);
        }
      }
      vpProjectiveStereoRig oracleRig, robustRig, cleanRig;
      try {
        oracleRig.estimate(correctLeft, correctRight, threshold);
        robustRig.estimate(left, wrongRight, threshold);
        cleanRig.estimate(left, right, threshold);
      } catch (const vpException &e) {
        ADD_FAILURE() << "estimate() threw: " << e.getStringMessage();
        continue;
      }
      oracle += rmsEpipolarDistance(oracleRig.fundamentalMatrix(), freshLeft, freshRight) / seeds;
      robust += rmsEpipolarDistance(robustRig.fundamentalMatrix(), freshLeft, freshRight) / seeds;
      clean += rmsEpipolarDistance(cleanRig.fundamentalMatrix(), freshLeft, freshRight) / seeds;
      naive += rmsEpipolarDistance(eightPoint(left, wrongRight), freshLeft, freshRight) / seeds;
      const std::vector<bool> &inliers = robustRig.getInliers();
      ASSERT_EQ(inliers.size(), n);
      for (size_t i = 0; i < n; ++i) {
        const bool flagged = !inliers[i];
        if (!wrong[i]) {
          ++correct;
          correctFlagged += flagged ? 1 : 0;
        } else if (epipolarDistances(Ftrue, left[i], wrongRight[i]).minCoeff() > 2.0 * threshold) {
          ++detectable;
          detectableFlagged += flagged ? 1 : 0;
        } else {
          ++close;
          closeFlagged += flagged ? 1 : 0;
        }
      }
    }
    const size_t flagged = detectableFlagged + closeFlagged + correctFlagged;
    const double recall = static_cast<double>(detectableFlagged) / static_cast<double>(detectable);
    const double precision = static_cast<double>(detectableFlagged + closeFlagged) / static_cast<double>(flagged);
    std::cout << "[ stats    ] F with " << nWrong << " of " << n << " matches wrongly paired, sigma " << kSigma
              << " px, " << seeds << " seeds: fresh RMS epipolar distance robust " << robust << " px, oracle " << oracle
              << " (ratio " << robust / oracle << "), clean " << clean << ", naive " << naive << "; flagged "
              << detectableFlagged << "/" << detectable << " wrong pairings beyond 4 px (recall " << recall << "), "
              << closeFlagged << "/" << close << " within, " << correctFlagged << "/" << correct
              << " correct matches (precision " << precision << ")" << std::endl;
    EXPECT_LT(robust, 1.25 * oracle);
    EXPECT_GT(naive, 5.0 * oracle);
    EXPECT_GE(recall, 0.98);
    EXPECT_GE(precision, 0.95);
    EXPECT_LE(static_cast<double>(correctFlagged), 0.01 * static_cast<double>(correct));
  }
}

/*
  Below 15 matches there is no robust selection (OpenCV's RANSAC needs 15; with so few matches F's 7 degrees of
  freedom leave little redundancy): all matches are fitted, then those farther than the threshold from the refined
  epipolar lines are dropped and the rest refitted. Measured behaviour, 0.5 px, 40 seeds per size:
  - correctly paired sets from the minimum up are estimated: from 9 matches all succeed, keeping all but at most one
    match; 8 matches (one redundant constraint) fail in about 4 % of cases (a noisy match beyond 2 px);
  - with one wrong match (> 20 px from its true epipolar lines) among 10, 12 or 14, the error is reported
    (estimationFailedError: too few matches agree once the wrong one spoils the fit) or, rarely, the wrong match alone
    is rejected, in 84 to 94 % of 100 measured seeds; otherwise it is silently absorbed by the 7 degrees of freedom
    of F (the residual does not reveal it either: it stays within the spread of correct sets). Bound: at least 75 %
    reported or rejected.
*/
TEST(vpProjectiveStereoRig, EstimateSmallSetsAreNotRobust)
{
  const Scene scene;
  const Eigen::Matrix3d Ftrue = trueF(scene);
  const int seeds = 40;
  for (size_t n = 8; n <= 14; ++n) {
    SCOPED_TRACE(::testing::Message() << n << " correct matches");
    int succeeded = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      const SeededMatches data(scene, 600 + seed, n, kSigma);
      vpProjectiveStereoRig rig;
      try {
        rig.estimate(data.left, data.right);
        ++succeeded;
        EXPECT_GE(std::count(rig.getInliers().begin(), rig.getInliers().end(), true), static_cast<long>(n) - 1)
            << "seed " << seed;
      } catch (const vpProjectiveException &e) {
        EXPECT_EQ(e.getCode(), vpProjectiveException::estimationFailedError) << e.getStringMessage();
      }
    }
    EXPECT_GE(succeeded, n == 8 ? static_cast<int>(0.9 * seeds) : seeds);
  }
  for (size_t n : {10, 12, 14}) {
    SCOPED_TRACE(::testing::Message() << n << " matches, one wrong");
    int reported = 0, rejected = 0;
    for (int seed = 1; seed <= seeds; ++seed) {
      SeededMatches data(scene, 700 + seed, n, kSigma);
      data.right[0] = wrongRightImage(scene, Ftrue, data.left[0], data.rng, data.noise);
      vpProjectiveStereoRig rig;
      try {
        rig.estimate(data.left, data.right);
        rejected += rig.getInliers()[0] ? 0 : 1;
      } catch (const vpProjectiveException &e) {
        EXPECT_EQ(e.getCode(), vpProjectiveException::estimationFailedError) << e.getStringMessage();
        EXPECT_NE(e.getStringMessage().find("agree"), std::string::npos) << e.getStringMessage();
        ++reported;
      }
    }
    std::cout << "[ stats    ] F from " << n << " matches with one wrong: reported in " << reported << " of " << seeds
              << " seeds, wrong match rejected in " << rejected << ", absorbed in " << seeds - reported - rejected
              << std::endl;
    EXPECT_GE(reported + rejected, static_cast<int>(0.75 * seeds));
  }
}

// ---------------------------------------------------------------------------------------------------------------
// The canonical frame
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveStereoRig, FrameIndependentOfScaleAndSignOfF)
{
  const Scene scene;
  const vpMatrix F = scene.sim.getFundamentalMatrix();
  vpProjectiveStereoRig a, b;
  a.setFundamentalMatrix(F);
  b.setFundamentalMatrix(-3.0 * F);
  const Eigen::Matrix<double, 3, 4> Pa = toEigen<3, 4>(a.getRightProjection());
  const Eigen::Matrix<double, 3, 4> Pb = toEigen<3, 4>(b.getRightProjection());
  EXPECT_LT(relativeError(Pb, Pa), 1e-12);
  EXPECT_LT(relativeError(toEigen<3, 3>(b.getFundamentalMatrix()), toEigen<3, 3>(a.getFundamentalMatrix())), 1e-12);

  // The same projective points, hence the same models, from either rig.
  const SeededMatches data(scene, 7, 10, 0.0);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  for (size_t i = 0; i < left.size(); ++i) {
    EXPECT_LT(
        relativeErrorUpToScale(toEigen4(b.triangulate(left[i], right[i])), toEigen4(a.triangulate(left[i], right[i]))),
        1e-10);
  }
}

TEST(vpProjectiveStereoRig, CanonicalCameraPair)
{
  const Scene scene;
  const vpProjectiveStereoRig &rig = scene.rig;
  const Eigen::Matrix3d F = toEigen<3, 3>(rig.getFundamentalMatrix());
  const Eigen::Matrix<double, 3, 4> P = toEigen<3, 4>(rig.getLeftProjection());
  const Eigen::Matrix<double, 3, 4> Pp = toEigen<3, 4>(rig.getRightProjection());
  Eigen::Matrix<double, 3, 4> I0 = Eigen::Matrix<double, 3, 4>::Zero();
  I0.leftCols<3>().setIdentity();
  EXPECT_EQ(P, I0);

  const Eigen::Vector3d e = toEigen<3, 1>(rig.getLeftEpipole());
  const Eigen::Vector3d ep = toEigen<3, 1>(rig.getRightEpipole());
  EXPECT_NEAR(e.norm(), 1.0, 1e-12);
  EXPECT_NEAR(ep.norm(), 1.0, 1e-12);
  EXPECT_LT((F * e).norm(), 1e-12);
  EXPECT_LT((F.transpose() * ep).norm(), 1e-12);
  // The last column of P' is e', the image of the left camera centre (0, 0, 0, 1).
  EXPECT_LT((Pp.col(3) - ep).norm(), 1e-12);
  // P' is consistent with F: F ~ [e']_x P'(:, 0:3) (here exactly -F for unit e').
  EXPECT_LT(relativeErrorUpToScale(Eigen::Matrix3d(vpMetricTwist::skew(ep) * Pp.leftCols<3>()), F), 1e-12);
  // ... and the left 3x3 block of P' is invertible (the frame is not degenerate).
  EXPECT_GT(Eigen::JacobiSVD<Eigen::Matrix3d>(Pp.leftCols<3>()).singularValues()(2), 1e-3);

  // Eigen accessors agree with the ViSP getters.
  EXPECT_EQ(rig.fundamentalMatrix(), F);
  EXPECT_EQ(rig.leftProjection(), P);
  EXPECT_EQ(rig.rightProjection(), Pp);
}

TEST(vpProjectiveStereoRig, RankThreeInputIsProjectedOnRankTwo)
{
  const Scene scene;
  vpUniRand rng(11);
  vpMatrix F = scene.sim.getFundamentalMatrix();
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      F[i][j] += 1e-3 * rng.uniform(-1.0, 1.0);
    }
  }
  ASSERT_GT(std::abs(toEigen<3, 3>(F).determinant()), 1e-12);
  vpProjectiveStereoRig rig;
  rig.setFundamentalMatrix(F);
  const Eigen::Matrix3d F2 = rig.fundamentalMatrix();
  EXPECT_LT(Eigen::JacobiSVD<Eigen::Matrix3d>(F2).singularValues()(2), 1e-14);
  EXPECT_LT((F2 * toEigen<3, 1>(rig.getLeftEpipole())).norm(), 1e-12);
  EXPECT_LT((F2.transpose() * toEigen<3, 1>(rig.getRightEpipole())).norm(), 1e-12);
  // The closest rank-2 matrix is close to the input.
  EXPECT_LT(relativeErrorUpToScale(F2, toEigen<3, 3>(F)), 1e-2);
}

// ---------------------------------------------------------------------------------------------------------------
// triangulate() and project()
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveStereoRig, TriangulateNoiseFreeIsExact)
{
  const Scene scene;
  const SeededMatches data(scene, 21, 50, 0.0);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  const std::vector<vpColVector> &wX = data.points;
  double worstPixel = 0.0, worstPoint = 0.0;
  for (size_t i = 0; i < wX.size(); ++i) {
    const vpColVector M = scene.rig.triangulate(left[i], right[i]);
    ASSERT_EQ(M.getRows(), 4u);
    EXPECT_NEAR(M.frobeniusNorm(), 1.0, 1e-12);
    vpImagePoint l, r;
    scene.rig.project(M, l, r);
    worstPixel = std::max(worstPixel, std::max(pixelDistance(l, left[i]), pixelDistance(r, right[i])));
    // The true projective point H_PE^-1 N, up to scale and sign.
    worstPoint = std::max(worstPoint, relativeErrorUpToScale(toEigen4(M), scene.projectivePoint(wX[i])));
    // The Eigen overload gives the same point.
    const Eigen::Vector4d Me = scene.rig.triangulate(Eigen::Vector2d(left[i].get_u(), left[i].get_v()),
                                                     Eigen::Vector2d(right[i].get_u(), right[i].get_v()));
    EXPECT_LT((Me - toEigen4(M)).norm(), 1e-15);
  }
  EXPECT_LT(worstPixel, 1e-8);
  EXPECT_LT(worstPoint, 1e-8);
}

/*
  0.5 px noise, 100 matches. The refined triangulation minimises the reprojection error over M, so it can be no worse
  than the linear (DLT) point on any match; its minimum is, to first order, Sampson's error (relative accuracy of the
  approximation ~ sigma / f, far below 2 %); and the squared minimum is sigma^2 chi-square with 1 dof (4
  measurements, 3 point parameters), whose mean over 100 matches is within +-40 % of sigma^2 (2.8 std).
  The corrected matches (projections of M) lie exactly on corresponding epipolar lines.
*/
TEST(vpProjectiveStereoRig, TriangulateNoisyIsOptimal)
{
  const Scene scene;
  const vpProjectiveStereoRig &rig = scene.rig;
  const Eigen::Matrix3d F = rig.fundamentalMatrix();
  const SeededMatches data(scene, 31, 100, kSigma);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  double sumSquares = 0.0, sumLinear = 0.0, sumRefined = 0.0;
  for (size_t i = 0; i < left.size(); ++i) {
    SCOPED_TRACE(::testing::Message() << "match " << i);
    const Eigen::Vector4d M = toEigen4(rig.triangulate(left[i], right[i]));
    const Eigen::Vector4d Mlin = triangulateDLT(rig.leftProjection(), rig.rightProjection(), left[i], right[i]);
    const double refined = reprojectionError(rig, M, left[i], right[i]);
    const double linear = reprojectionError(rig, Mlin, left[i], right[i]);
    const double sampson = sampsonError(F, left[i], right[i]);
    EXPECT_LE(refined, linear + 1e-9);
    EXPECT_NEAR(refined, sampson, 0.02 * sampson + 1e-6);
    vpImagePoint l, r;
    rig.project(toVispVector(M), l, r);
    const Eigen::Vector3d m = pixel(l), mp = pixel(r);
    EXPECT_LT(std::abs(mp.dot(F * m)) / (mp.norm() * m.norm()), 1e-12);
    sumSquares += refined * refined;
    sumLinear += linear;
    sumRefined += refined;
  }
  const double meanSquare = sumSquares / left.size();
  std::cout << "[ stats    ] triangulation, sigma " << kSigma << " px: mean squared refined error " << meanSquare
            << " px^2 (expected " << kSigma * kSigma << "), mean error linear " << sumLinear / left.size()
            << " px, refined " << sumRefined / left.size() << " px" << std::endl;
  EXPECT_NEAR(meanSquare / (kSigma * kSigma), 1.0, 0.4);
}

TEST(vpProjectiveStereoRig, ProjectIsScaleAndSignInvariant)
{
  const Scene scene;
  const SeededMatches data(scene, 41, 20, 0.0);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  const std::vector<vpColVector> &wX = data.points;
  for (size_t i = 0; i < wX.size(); ++i) {
    const Eigen::Vector4d M = scene.projectivePoint(wX[i]);
    vpImagePoint l1, r1, l2, r2;
    scene.rig.project(toVispVector(M), l1, r1);
    scene.rig.project(toVispVector(Eigen::Vector4d(-2.0 * M)), l2, r2);
    EXPECT_LT(pixelDistance(l1, l2), 1e-9);
    EXPECT_LT(pixelDistance(r1, r2), 1e-9);
    // And they are the simulator's images.
    EXPECT_LT(pixelDistance(l1, left[i]), 1e-8);
    EXPECT_LT(pixelDistance(r1, right[i]), 1e-8);
    // The Eigen overload agrees.
    Eigen::Vector4d s;
    ASSERT_TRUE(scene.rig.project(M, s));
    EXPECT_LT((s - Eigen::Vector4d(l1.get_u(), l1.get_v(), r1.get_u(), r1.get_v())).norm(), 1e-9);
  }
}

TEST(vpProjectiveStereoRig, ProjectPointOnFocalPlaneThrows)
{
  const Scene scene;
  const vpProjectiveStereoRig &rig = scene.rig;
  vpImagePoint l, r;
  // Left focal plane: (P M)_3 = M_3 = 0.
  const Eigen::Vector4d Ml(1.0, 2.0, 0.0, 0.5);
  EXPECT_TRUE(throwsProjective([&] { rig.project(toVispVector(Ml), l, r); },
                               vpProjectiveException::pointAtInfinityError, "focal plane"));
  Eigen::Vector4d s;
  EXPECT_FALSE(rig.project(Ml, s));
  // Right focal plane: (P' M)_3 = 0, M chosen orthogonal to the third row of P'.
  // The two focal planes are nearly parallel (11 deg vergence): take the point of the right one closest to (0,0,1,0).
  const Eigen::Vector4d p3 = rig.rightProjection().row(2).transpose();
  Eigen::Vector4d Mr = Eigen::Vector4d::UnitZ() - p3(2) / p3.squaredNorm() * p3;
  Mr.normalize();
  ASSERT_GT(std::abs(Mr(2)), 1e-6); // far from the left focal plane at the library's 1e-12 tolerance
  EXPECT_TRUE(throwsProjective([&] { rig.project(toVispVector(Mr), l, r); },
                               vpProjectiveException::pointAtInfinityError, "focal plane"));
  EXPECT_FALSE(rig.project(Mr, s));
  // Close to, but off, the focal plane: a finite image.
  EXPECT_NO_THROW(rig.project(toVispVector(Eigen::Vector4d(1.0, 2.0, 1e-6, 0.5)), l, r));
}

// ---------------------------------------------------------------------------------------------------------------
// Invalid inputs
// ---------------------------------------------------------------------------------------------------------------

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
