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
  Tests of vpProjectiveDisplacement's robust estimation (estimateRobust(), estimate(..., inlierThreshold, inliers))
  with 20 % mismatched correspondences: the accuracy of the outlier-free estimate on the same data, every mismatch
  flagged, hardly any correct point lost, the ML estimate itself on correct data, every kind of motion accepted;
  unresolvable configurations reported by estimationFailedError; noise-free data exact with degenerate minimal sets
  skipped; its invalid inputs throw.
*/

#include <gtest/gtest.h>

#include "vpProjectiveDisplacementTestTools.h"

using namespace vpProjectiveTest;

/*
  20 % mismatched correspondences at 0.5 px noise, 20 seeds per configuration: 7 markers (>= 8 cm apart) with 1
  spurious blob (the 21 minimal sets are enumerated); 10 points (>= 4 cm apart) with 2 markers swapped, 15 with 3
  markers permuted, 30 (>= 3 cm apart) with 3 swapped and 3 spurious (seeded random minimal sets). Five estimates of
  each case:
  - clean: the ML estimate (estimateFromImages) on the correct data, all n points;
  - oracle: the ML estimate on the n - k correctly matched points only: the outlier-free accuracy of these data, what
    a perfect rejection of the mismatches reaches;
  - robust: estimateRobust() on the mismatched data, threshold 3 sigma (the header's advice);
  - robustClean: estimateRobust() on the correct data;
  - naive: the ML estimate on the mismatched data, to check that the mismatches matter (the test could fail).
  Properties, for each error (rotation angle, transfer, generator) averaged over the seeds:
  - every mismatch is flagged an outlier (they shift image points by >= 10 px = 20 sigma, so d_j >= ~5 px, more than
    3 times the threshold): recall 1; and no more than 1 % of the correct points are flagged (a correct point's
    d_j exceeds 3 sigma with probability ~1e-6 under the true H, a little more under an estimate): precision 1 of the
    outlier flags up to that 1 %;
  - robust matches the outlier-free accuracy: its mean error is within 1.1x of the oracle's (equal when the inliers
    are exactly the correct points, as the ML refit then has the same optimum; 10 % leaves room for one correct point
    lost or one optimum found differently in 20 seeds);
  - robustClean is the ML estimate: whenever it keeps every point, its H equals estimateFromImages' (a dedicated
    Levenberg-Marquardt instead of Ceres, on the same cost) to 1e-6 in the whitened frame (both stop at relative
    cost changes near 1e-12; the estimate's own noise is ~0.02 there), so its mean errors are within 1 % of clean;
  - naive is at least 3x worse than clean (the contamination is harmful, so the properties above are not vacuous).
  The ratio robust / clean is printed: it is the price of the k lost points, of the order of sqrt(n / (n - k)).
*/
TEST(vpProjectiveDisplacement, RobustMatchesOutlierFreeAccuracy)
{
  const Scene scene;
  struct Config {
    size_t n, nWrong;
    double minDistance;
    MismatchKind kind;
  };
  const Config configs[] = {
      {7, 1, 0.08, Spurious}, {10, 2, 0.04, Swapped}, {15, 3, 0.04, Swapped}, {30, 6, 0.03, Mixed}};
  const char *measures[RotationErrors::Count] = {"angle (rad)", "transfer (mm)", "generator (relative)"};
  const int seeds = 20;
  for (const Config &config : configs) {
    SCOPED_TRACE(::testing::Message() << config.n << " points, " << config.nWrong << " mismatched");
    enum { Clean, Oracle, Robust, RobustClean, Naive, Estimates };
    const char *names[Estimates] = {"clean", "oracle", "robust", "robustClean", "naive"};
    double mean[Estimates][RotationErrors::Count] = {{0.0}};
    size_t flagged = 0, lost = 0, lostClean = 0, correct = 0;
    double worstMLDifference = 0.0;
    for (int seed = 1; seed <= seeds; ++seed) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed);
      const MismatchCase c = mismatchCase(scene, static_cast<uint64_t>(1000 * config.n + seed), config.n, config.nWrong,
                                          config.minDistance, config.kind);
      std::vector<bool> correctFlags(config.n);
      for (size_t j = 0; j < config.n; ++j) {
        correctFlags[j] = !c.wrong[j];
      }
      Eigen::Matrix4d H[Estimates];
      std::vector<bool> inliers, inliersClean;
      try {
        H[Robust] = vpProjectiveDisplacement::estimateRobust(scene.rig, c.s0, c.s1wrong, kThreshold, inliers);
        H[RobustClean] = vpProjectiveDisplacement::estimateRobust(scene.rig, c.s0, c.s1, kThreshold, inliersClean);
      } catch (const vpException &e) {
        ADD_FAILURE() << "estimateRobust() threw: " << e.getStringMessage();
        return;
      }
      H[Clean] = vpProjectiveDisplacement::estimateFromImages(scene.rig, c.s0, c.s1);
      H[Oracle] = vpProjectiveDisplacement::estimateFromImages(scene.rig, subset(c.s0, correctFlags),
                                                               subset(c.s1, correctFlags));
      ASSERT_EQ(inliers.size(), config.n);
      ASSERT_EQ(inliersClean.size(), config.n);
      for (size_t j = 0; j < config.n; ++j) {
        if (c.wrong[j]) {
          EXPECT_FALSE(inliers[j]) << "mismatched point " << j << " kept";
          flagged += inliers[j] ? 0 : 1;
        } else {
          ++correct;
          lost += inliers[j] ? 0 : 1;
        }
        lostClean += inliersClean[j] ? 0 : 1;
      }
      if (std::count(inliersClean.begin(), inliersClean.end(), true) == static_cast<long>(config.n)) {
        const Eigen::Matrix4d W = trueWhitening(scene, c.body), Winv = W.inverse();
        const double difference =
            relativeError(Eigen::Matrix4d(W * H[RobustClean] * Winv), Eigen::Matrix4d(W * H[Clean] * Winv));
        EXPECT_LT(difference, 1e-6);
        worstMLDifference = std::max(worstMLDifference, difference);
      }
      for (int k = 0; k < Naive; ++k) {
        const RotationErrors r = rotationErrors(scene, c, H[k]);
        for (int m = 0; m < RotationErrors::Count; ++m) {
          mean[k][m] += r.e[m] / seeds;
        }
      }
      // The least-squares estimate on the mismatched data may be no rotation at all (a singular H, or one without a
      // rotation's eigenvalues): its errors are then infinite.
      try {
        const RotationErrors r =
            rotationErrors(scene, c, vpProjectiveDisplacement::estimateFromImages(scene.rig, c.s0, c.s1wrong));
        for (int m = 0; m < RotationErrors::Count; ++m) {
          mean[Naive][m] += r.e[m] / seeds;
        }
      } catch (const vpException &) {
        for (int m = 0; m < RotationErrors::Count; ++m) {
          mean[Naive][m] = std::numeric_limits<double>::infinity();
        }
      }
    }
    testLog() << "[ stats    ] robust displacement, " << config.n << " points, " << config.nWrong
              << " mismatched, sigma " << kSigma << " px, " << seeds << " seeds: mismatches flagged " << flagged << "/"
              << config.nWrong * seeds << ", correct points flagged " << lost << "/" << correct
              << " (on the correct data " << lostClean << "/" << config.n * seeds
              << "); robustClean vs clean H: max relative difference " << worstMLDifference << std::endl;
    for (int m = 0; m < RotationErrors::Count; ++m) {
      testLog() << "[ stats    ]   " << measures[m] << " mean:";
      for (int e = 0; e < Estimates; ++e) {
        testLog() << " " << names[e] << " " << mean[e][m];
      }
      testLog() << "; robust / oracle " << mean[Robust][m] / mean[Oracle][m] << ", robust / clean "
                << mean[Robust][m] / mean[Clean][m] << " (sqrt(n / (n - k)) "
                << std::sqrt(static_cast<double>(config.n) / static_cast<double>(config.n - config.nWrong)) << ")"
                << std::endl;
    }
    EXPECT_EQ(flagged, config.nWrong * seeds);
    EXPECT_LE(static_cast<double>(lost), 0.01 * static_cast<double>(correct));
    EXPECT_LE(static_cast<double>(lostClean), 0.01 * static_cast<double>(config.n * seeds));
    for (int m = 0; m < RotationErrors::Count; ++m) {
      SCOPED_TRACE(measures[m]);
      EXPECT_LE(mean[Robust][m], 1.1 * mean[Oracle][m]);
      EXPECT_LE(mean[RobustClean][m], 1.01 * mean[Clean][m]);
      EXPECT_GT(mean[Naive][m], 3.0 * mean[Clean][m]);
    }
  }
}

/*
  Configurations that cannot be resolved must throw estimationFailedError, not return a wrong displacement (0.5 px,
  mismatches >= 10 px). 6 points with 2 markers swapped and 7 points with 3 mismatches (2 swapped, 1 blob) leave 4
  correct points, too few to fit H: 10 seeds each must throw. With 6 points of which 1 is a blob, any 5 of them fit a
  homography exactly and the 6th is the only check: a 3D homography fitted to 6 points has 3 redundant constraints
  and may fit all 6, the blob included, within the threshold by distorting space; the estimator rejects such fits
  that are no rigid displacement (the message then says so), but a distorted fit that is rigid within its own large
  uncertainty remains possible: measured 7 in 400 seeds. Bound: over 100 seeds at least 95 throw, the others keep the
  blob (no other outcome). The same cases without the mismatches must succeed and keep every point.
  With exactly 5 points (noise-free here, where the answer is certain) nothing is redundant: 5 correct points are all
  kept, but a point whose left and right images do not match (a stereo mismatch) is still detected and throws.
*/
TEST(vpProjectiveDisplacement, RobustTooManyMismatchesThrow)
{
  const Scene scene;
  std::vector<bool> inliers;
  for (int seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const MismatchCase six = mismatchCase(scene, static_cast<uint64_t>(6000 + seed), 6, 2, 0.08, Swapped);
    const MismatchCase seven = mismatchCase(scene, static_cast<uint64_t>(7100 + seed), 7, 3, 0.08, Mixed);
    for (const MismatchCase *c : {&six, &seven}) {
      SCOPED_TRACE(::testing::Message() << c->s0.size() << " points");
      EXPECT_TRUE(throwsProjective(
          [&] { vpProjectiveDisplacement::estimateRobust(scene.rig, c->s0, c->s1wrong, kThreshold, inliers); },
          vpProjectiveException::estimationFailedError, "mismatched"));
      try {
        vpProjectiveDisplacement::estimateRobust(scene.rig, c->s0, c->s1, kThreshold, inliers);
        EXPECT_EQ(std::count(inliers.begin(), inliers.end(), true), static_cast<long>(c->s0.size()));
      } catch (const vpException &e) {
        ADD_FAILURE() << "correct points rejected: " << e.getStringMessage();
      }
    }

    vpUniRand rng(static_cast<uint64_t>(6100 + seed));
    vpGaussRand noise(1.0, 0.0, 6100 + seed);
    const std::vector<vpColVector> body = rigidBody(scene, rng, 5, 0.10, 0.08);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, vpMath::rad(30.0));
    const Observation o = observe(scene, body, T, 0.0, noise);
    std::vector<Eigen::Vector4d> s0 = stacked(o.left0, o.right0);
    const std::vector<Eigen::Vector4d> s1 = stacked(o.left1, o.right1);
    try {
      const Eigen::Matrix4d H = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, inliers);
      EXPECT_EQ(std::count(inliers.begin(), inliers.end(), true), 5);
      EXPECT_LT(relativeError(H, truth(scene, T)), 1e-8);
    } catch (const vpException &e) {
      ADD_FAILURE() << "5 correct points rejected: " << e.getStringMessage();
    }
    s0[2](3) += kMismatch; // v' of point 2 before the motion: 10 px off its epipolar line
    EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, inliers); },
                                 vpProjectiveException::estimationFailedError, "only 4 of the 5 points agree"));
  }

  int thrown = 0, absorbed = 0;
  for (int seed = 1; seed <= 100; ++seed) {
    SCOPED_TRACE(::testing::Message() << "6 points, 1 blob, seed " << seed);
    const MismatchCase c = mismatchCase(scene, static_cast<uint64_t>(6200 + seed), 6, 1, 0.08, Spurious);
    try {
      vpProjectiveDisplacement::estimateRobust(scene.rig, c.s0, c.s1wrong, kThreshold, inliers);
      EXPECT_EQ(std::count(inliers.begin(), inliers.end(), true), 6);
      ++absorbed;
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::estimationFailedError) << e.getStringMessage();
      EXPECT_NE(e.getStringMessage().find("mismatched"), std::string::npos) << e.getStringMessage();
      ++thrown;
    }
  }
  testLog() << "[ stats    ] 6 points with 1 blob: " << thrown << " of 100 reported, " << absorbed << " absorbed"
            << std::endl;
  EXPECT_GE(thrown, 95);
}

/*
  No false alarm on any kind of motion: 7 markers, 0.5 px, no mismatch, 20 seeds of each kind (rotation by 10 to 60
  deg, screw, translation by 5 cm, no motion). The rigidity check works on the characteristic polynomial, whose
  sensitivity to the noise vanishes at a translation and at the identity: it must not reject them. The robust estimate
  must keep every point (at most 1 % lost, as above) and then be the ML estimate (1e-6, as above).
*/
TEST(vpProjectiveDisplacement, RobustAcceptsEveryMotionKind)
{
  const Scene scene;
  for (int k = Rotation; k <= NoMotion; ++k) {
    const MotionKind kind = static_cast<MotionKind>(k);
    size_t lost = 0;
    for (int seed = 1; seed <= 20; ++seed) {
      SCOPED_TRACE(::testing::Message() << kindName(kind) << ", seed " << seed);
      vpUniRand rng(static_cast<uint64_t>(9100 + 100 * k + seed));
      vpGaussRand noise(1.0, 0.0, 9100 + 100 * k + seed);
      const std::vector<vpColVector> body = rigidBody(scene, rng, 7, 0.10, 0.08);
      const vpHomogeneousMatrix T = randomMotion(scene, rng, body, kind, rng.uniform(vpMath::rad(10.0), 1.0));
      const Observation o = observe(scene, body, T, kSigma, noise);
      const std::vector<Eigen::Vector4d> s0 = stacked(o.left0, o.right0), s1 = stacked(o.left1, o.right1);
      std::vector<bool> inliers;
      try {
        const Eigen::Matrix4d H = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, kThreshold, inliers);
        const size_t kept = static_cast<size_t>(std::count(inliers.begin(), inliers.end(), true));
        lost += body.size() - kept;
        if (kept == body.size()) {
          const Eigen::Matrix4d W = trueWhitening(scene, body), Winv = W.inverse();
          const Eigen::Matrix4d Hml = vpProjectiveDisplacement::estimateFromImages(scene.rig, s0, s1);
          EXPECT_LT(relativeError(Eigen::Matrix4d(W * H * Winv), Eigen::Matrix4d(W * Hml * Winv)), 1e-6);
        }
      } catch (const vpException &e) {
        ADD_FAILURE() << "a correct " << kindName(kind) << " rejected: " << e.getStringMessage();
      }
    }
    EXPECT_LE(static_cast<double>(lost), 0.01 * 7 * 20) << kindName(kind);
  }
}

/*
  Noise-free data with mismatches are estimated exactly, and degenerate minimal sets are skipped without throwing:
  8 points of which 4 are exactly coplanar (the 4 of the 56 minimal sets that hold them are degenerate), 2 of the
  others swapped after the motion. The estimate must be the true H (1e-8, as the noise-free tests) with exactly the
  swapped points rejected; the result must not depend on the call (seeded) and the vpImagePoint overload must give the
  same. All points coplanar: no minimal set is valid, degenerateConfigurationError.
*/
TEST(vpProjectiveDisplacement, RobustNoiseFreeIsExactAndSkipsDegenerateSets)
{
  const Scene scene;
  for (int seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(static_cast<uint64_t>(8000 + seed));
    vpGaussRand noise(1.0, 0.0, 8000 + seed);
    std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.10, 0.04);
    // Points 0..3 on the plane of 0, 1, 2.
    const vpColVector a = body[0], b = body[1], d = body[2];
    body[3] = a + 0.4 * (b - a) + 0.5 * (d - a);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
    const Observation o = observe(scene, body, T, 0.0, noise);
    const std::vector<Eigen::Vector4d> s0 = stacked(o.left0, o.right0);
    std::vector<Eigen::Vector4d> s1 = stacked(o.left1, o.right1);
    std::swap(s1[2], s1[6]);
    std::vector<bool> inliers, again;
    Eigen::Matrix4d H, H2;
    try {
      H = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, inliers);
      H2 = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, again);
    } catch (const vpException &e) {
      ADD_FAILURE() << "estimateRobust() threw: " << e.getStringMessage();
      continue;
    }
    EXPECT_LT(relativeError(H, truth(scene, T)), 1e-8);
    for (size_t j = 0; j < 8; ++j) {
      EXPECT_EQ(inliers[j], j != 2 && j != 6) << "point " << j;
    }
    EXPECT_EQ(H, H2);
    EXPECT_EQ(inliers, again);
    std::vector<vpImagePoint> left1 = o.left1, right1 = o.right1;
    std::swap(left1[2], left1[6]);
    std::swap(right1[2], right1[6]);
    const vpProjectiveDisplacement D =
        vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, left1, right1, 1.0, again);
    EXPECT_LT(relativeError(D.matrix(), H), 1e-12);
    EXPECT_EQ(inliers, again);
  }
  // All points on one plane.
  vpUniRand rng(8100);
  vpGaussRand noise(1.0, 0.0, 8100);
  std::vector<vpColVector> planar;
  const vpColVector c = Scene::fixation();
  while (planar.size() < 8) {
    const double x = rng.uniform(-0.08, 0.08), y = rng.uniform(-0.08, 0.08);
    planar.push_back(c + point3(x, y, 0.5 * x + 0.2 * y));
  }
  const vpHomogeneousMatrix T = randomMotion(scene, rng, planar, Rotation, 0.5);
  const Observation o = observe(scene, planar, T, 0.0, noise);
  std::vector<bool> inliers;
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpProjectiveDisplacement::estimateRobust(scene.rig, stacked(o.left0, o.right0), stacked(o.left1, o.right1), 1.0,
                                                 inliers);
      },
      vpProjectiveException::degenerateConfigurationError, "general position"));
}

TEST(vpProjectiveDisplacement, RobustInvalidInputsThrow)
{
  const Scene scene;
  const MismatchCase c = mismatchCase(scene, 9001, 7, 1, 0.08, Spurious);
  std::vector<bool> inliers;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto robust = [&](const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                          const std::vector<Eigen::Vector4d> &s1, double threshold, int iterations) {
    return [&rig, s0, s1, threshold, iterations, &inliers] {
      vpProjectiveDisplacement::estimateRobust(rig, s0, s1, threshold, inliers, iterations);
    };
  };
  const int code[] = {vpProjectiveException::invalidValueError, vpProjectiveException::nonFiniteValueError};
  // The threshold.
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, 0.0, 100), code[0], "must be positive"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, -1.0, 100), code[0], "must be positive"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, nan, 100), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, inf, 100), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, 1.5, 0), code[0], "maxIterations"));
  // Sizes and values.
  const std::vector<Eigen::Vector4d> six(c.s1.begin(), c.s1.begin() + 6);
  EXPECT_TRUE(
      throwsProjective(robust(scene.rig, c.s0, six, 1.5, 100), vpProjectiveException::dimensionError, "same points"));
  const std::vector<Eigen::Vector4d> four0(c.s0.begin(), c.s0.begin() + 4), four1(c.s1.begin(), c.s1.begin() + 4);
  EXPECT_TRUE(throwsProjective(robust(scene.rig, four0, four1, 1.5, 100), vpProjectiveException::notEnoughPointsError,
                               "at least 5"));
  std::vector<Eigen::Vector4d> bad = c.s0;
  bad[3](2) = nan;
  EXPECT_TRUE(throwsProjective(robust(scene.rig, bad, c.s1, 1.5, 100), code[1], "not finite"));
  bad = c.s1;
  bad[6](0) = -inf;
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, bad, 1.5, 100), code[1], "not finite"));
  const vpProjectiveStereoRig empty;
  EXPECT_TRUE(throwsProjective(robust(empty, c.s0, c.s1, 1.5, 100), vpProjectiveException::notInitializedError,
                               "no fundamental matrix"));

  // The vpImagePoint overload.
  vpUniRand rng(9002);
  vpGaussRand noise(1.0, 0.0, 9002);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 7, 0.08, 0.03);
  const Observation o = observe(scene, body, randomMotion(scene, rng, body, Rotation, 0.5), kSigma, noise);
  const auto estimate = [&](const std::vector<vpImagePoint> &left1, double threshold) {
    return [&o, left1, threshold, &scene, &inliers] {
      vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, left1, o.right1, threshold, inliers);
    };
  };
  EXPECT_TRUE(throwsProjective(estimate(o.left1, 0.0), code[0], "must be positive"));
  EXPECT_TRUE(throwsProjective(estimate(o.left1, nan), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(estimate(std::vector<vpImagePoint>(o.left1.begin(), o.left1.begin() + 6), 1.5),
                               vpProjectiveException::dimensionError, "same size"));
  std::vector<vpImagePoint> badLeft = o.left1;
  badLeft[1].set_u(nan);
  EXPECT_TRUE(throwsProjective(estimate(badLeft, 1.5), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(
      [&] { vpProjectiveDisplacement::estimate(empty, o.left0, o.right0, o.left1, o.right1, 1.5, inliers); },
      vpProjectiveException::notInitializedError, "no fundamental matrix"));
  // A valid call succeeds (the lambdas above are not vacuous).
  EXPECT_NO_THROW(estimate(o.left1, 1.5)());
  EXPECT_EQ(inliers.size(), body.size());
}
