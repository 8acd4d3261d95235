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
  Tests of vpProjectiveRobot's acquisition and calibration (bounds in vpProjectiveRobotTestTools.h): at 0.5 and 1 px
  acquisition noise the calibration residual sits at the noise level and the model predicts images to <= 1 px;
  mismatched markers, an estimated rig, several trials per joint; a blocked joint is reported, not a crash.
*/

#include <gtest/gtest.h>

#include "vpProjectiveRobotTestTools.h"

using namespace vpProjectiveTest;

TEST(ProjectiveRobot, CalibrationAtHalfPixelNoise)
{
  /*
    The paper's acquisition (PUMA, 7 markers, trials [30, 20, 30, 40, 60, 60] deg both ways) at sigma = 0.5 px on
    every coordinate, 5 seeds.
    Residual: N = 4 x 7 x 13 = 364 image coordinates, p = 53 effective parameters (G: 15 - 7 gauge = 8; 6 axes with
    their lines: 4 each; 7 points: 3 each), so the RMS residual of a maximum-likelihood fit is about
    sigma sqrt((N - p) / N) = 0.462 px, with a relative spread of 1 / sqrt(2 (N - p)) = 4 %. Accepted: [0.38, 0.55] px,
    beyond 4 spreads either way (an under-fitting model would sit above, an over-fitted one below).
    Prediction: over 50 random configurations within +-30 deg of the zero reference with all markers in view, the RMS
    distance between the model's images P H(q) M_j(0) and the true noise-free ones must stay <= 1 px (the design
    notes: ~0.4 px; the one-sided algebraic estimate gives 5-10 px).
  */
  const ArmSetup s = pumaEyeToHand();
  const double sigma = 0.5;
  for (long seed = 1; seed <= 5; ++seed) {
    const vpProjectiveRobot robot = calibratedRobot(s, sigma, seed);
    const double residual = robot.getAcquisition().getCalibrationResidual();
    EXPECT_GT(residual, 0.38) << "seed " << seed;
    EXPECT_LT(residual, 0.55) << "seed " << seed;
    EXPECT_LT(residual, robot.getAcquisition().getAlgebraicResidual())
        << "the refinement must improve on the algebraic generators";
    double worst = 0.0;
    const double rms = predictionRms(s, robot, std::vector<double>(6, vpMath::rad(30.0)), 100 + seed, worst);
    testLog() << "[ measured ] seed " << seed << ": calibration residual " << residual << " px (algebraic "
              << robot.getAcquisition().getAlgebraicResidual() << " px), prediction RMS " << rms << " px, worst "
              << worst << " px" << std::endl;
    EXPECT_LE(rms, 1.0) << "seed " << seed;
  }
}

TEST(ProjectiveRobot, CalibrationAtOnePixelNoise)
{
  /*
    The acquisition must not fail at 1 px noise, on any arm: at that level a single trial's homography of a joint
    whose axis is far from the markers (the PUMA's shoulder, 20 deg trials) can be far off, which spoiled the upgrade
    of 6 PUMA acquisitions out of 300 (an exception, or a bundle adjustment ending 100+ px off) before the upgrade
    learned to leave such joints out. 60 seeds of the PUMA (eye-to-hand) and 20 of each other arm; at random
    configurations within the trial amounts, the model must predict the markers within 5 sigma RMS: a failed
    calibration is 20 times beyond, while the eye-in-hand models, acquired with 4 deg trials, measure 0.59 px mean and
    0.68 px worst (1.8 and 3.4 px before the calibration tried its other starts; the PUMA eye-to-hand: 0.64 and 1.05
    px). The model gate may refuse one eye-in-hand acquisition of the 20 (modelRejectedError, never another error): with
    4 deg trials at 1 px its declared model's adjustment can end in a local minimum, 1.4 px against 1.03 px of noise for
    seed 2, where a prismatic elbow fits at 1.14 px and is named (every one of 22 metric starts ends there).
  */
  const double sigma = 1.0;
  const std::vector<std::pair<ArmSetup, long>> setups = {
      {pumaEyeToHand(), 60}, {pumaEyeInHand(), 20}, {viperEyeToHand(), 20}, {mixedEyeToHand(), 20}};
  for (const auto &setup : setups) {
    const ArmSetup &s = setup.first;
    double meanRms = 0.0, worstRms = 0.0;
    unsigned int refused = 0;
    for (long seed = 1; seed <= setup.second; ++seed) {
      vpProjectiveRobot robot(s.jointTypes());
      vpGaussRand noise(1.0, 0.0, seed);
      ASSERT_TRUE(s.acquire(robot, sigma, noise)) << s.name << ": a marker left the view during the acquisition";
      try {
        robot.calibrate();
      } catch (const vpProjectiveException &e) {
        EXPECT_EQ(e.getCode(), vpProjectiveException::modelRejectedError)
            << s.name << ", seed " << seed << ": calibrate() failed: " << e.getStringMessage();
        ++refused;
        testLog() << "[ measured ] " << s.name << ", seed " << seed << ": refused: " << e.getStringMessage()
                  << std::endl;
        continue;
      } catch (const vpException &e) {
        ADD_FAILURE() << s.name << ", seed " << seed << ": calibrate() failed: " << e.getStringMessage();
        continue;
      }
      double worst = 0.0;
      const double rms = predictionRms(s, robot, s.trialAmounts, 200 + seed, worst);
      EXPECT_LE(rms, 5.0 * sigma) << s.name << ", seed " << seed;
      meanRms += rms; // over the accepted models, divided below
      worstRms = std::max(worstRms, rms);
    }
    EXPECT_LE(refused, s.mounting == vpProjectiveRobot::EYE_IN_HAND ? 1u : 0u) << s.name;
    meanRms /= static_cast<double>(std::max<long>(1, setup.second - static_cast<long>(refused)));
    testLog() << "[ measured ] " << s.name << " at 1 px, " << setup.second << " seeds: prediction RMS " << meanRms
              << " px mean, " << worstRms << " px worst; refused " << refused << std::endl;
  }
}

TEST(ProjectiveRobot, AcquisitionWithMismatchedMarkers)
{
  /*
    20 % of the trial observations (17 of 12 trials x 7 markers, at random) are mismatched: half of them take both
    images of another marker (a tracker jumped to another blob), half only its right image (a left-right mismatch).
    At 0.5 px noise, with setOutlierThreshold(1.5 px = 3 sigma), calibrate() must
    - find the mismatches: at least 95 % of them flagged, and at most 3 % of the correct observations;
    - give a model as accurate as the clean acquisition of the same seed (prediction RMS at random configurations,
      mean over 8 seeds within 1.25 times the clean mean, every seed within 2 times its clean value).
    Without the threshold the same contaminated data must visibly spoil the model (mean above 3 times the clean one),
    or the test would not be testing the rejection.
  */
  const ArmSetup s = pumaEyeToHand();
  const double sigma = 0.5;
  const unsigned int K = 7, trials = 12, mismatched = 17;
  double clean = 0.0, robust = 0.0, plain = 0.0;
  unsigned int found = 0, falseAlarms = 0;
  const long seeds = 8;
  for (long seed = 1; seed <= seeds; ++seed) {
    // Which observations are mismatched, and how.
    vpUniRand pick(1000 + seed);
    std::vector<std::vector<int>> donor(trials, std::vector<int>(K, -1)); // marker whose image is taken, -1: none
    std::vector<std::vector<bool>> rightOnly(trials, std::vector<bool>(K, false));
    for (unsigned int c = 0; c < mismatched;) {
      const unsigned int k = static_cast<unsigned int>(pick.uniform(0, static_cast<int>(trials)));
      const unsigned int j = static_cast<unsigned int>(pick.uniform(0, static_cast<int>(K)));
      if (donor[k][j] >= 0) {
        continue;
      }
      donor[k][j] = static_cast<int>((j + 1 + static_cast<unsigned int>(pick.uniform(0, static_cast<int>(K) - 1))) % K);
      rightOnly[k][j] = c % 2 == 1;
      ++c;
    }
    auto corrupt = [&](unsigned int k, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      const std::vector<vpImagePoint> left0 = left, right0 = right;
      for (unsigned int j = 0; j < K; ++j) {
        if (donor[k][j] >= 0) {
          right[j] = right0[static_cast<size_t>(donor[k][j])];
          if (!rightOnly[k][j]) {
            left[j] = left0[static_cast<size_t>(donor[k][j])];
          }
        }
      }
    };
    const std::vector<double> range(6, vpMath::rad(30.0));
    double worst = 0.0;
    {
      vpProjectiveRobot robot(s.jointTypes());
      vpGaussRand noise(1.0, 0.0, seed);
      ASSERT_TRUE(s.acquire(robot, sigma, noise));
      robot.calibrate();
      const double rms = predictionRms(s, robot, range, 300 + seed, worst);
      clean += rms / seeds;
      vpProjectiveRobot contaminated(s.jointTypes());
      vpGaussRand sameNoise(1.0, 0.0, seed);
      ASSERT_TRUE(s.acquire(contaminated, sigma, sameNoise, corrupt));
      contaminated.setOutlierThreshold(3.0 * sigma);
      contaminated.calibrate();
      const double rmsRobust = predictionRms(s, contaminated, range, 300 + seed, worst);
      robust += rmsRobust / seeds;
      EXPECT_LE(rmsRobust, 2.0 * rms) << "seed " << seed;
      for (unsigned int k = 0; k < trials; ++k) {
        for (unsigned int j = 0; j < K; ++j) {
          const bool flagged = contaminated.getAcquisition().isOutlier(k, j);
          found += flagged && donor[k][j] >= 0 ? 1 : 0;
          falseAlarms += flagged && donor[k][j] < 0 ? 1 : 0;
        }
      }
    }
    {
      vpProjectiveRobot naive(s.jointTypes());
      vpGaussRand sameNoise(1.0, 0.0, seed);
      ASSERT_TRUE(s.acquire(naive, sigma, sameNoise, corrupt));
      try {
        naive.calibrate();
        plain += predictionRms(s, naive, range, 300 + seed, worst) / seeds;
      } catch (const vpException &) {
        plain += 1e3 / seeds; // the contaminated data did not even calibrate
      }
    }
  }
  const double recall = found / static_cast<double>(seeds * mismatched);
  const double falseRate = falseAlarms / static_cast<double>(seeds * (trials * K - mismatched));
  testLog() << "[ measured ] 20 % mismatched trial observations at 0.5 px, " << seeds << " seeds: prediction RMS clean "
            << clean << " px, with rejection " << robust << " px, without " << plain << " px; mismatches found "
            << 100.0 * recall << " %, correct observations rejected " << 100.0 * falseRate << " %" << std::endl;
  EXPECT_LE(robust, 1.25 * clean);
  EXPECT_GE(plain, 3.0 * clean);

  // Bad inputs of the outlier API.
  vpProjectiveRobot robot(s.jointTypes());
  EXPECT_TRUE(throwsProjective([&] { robot.setOutlierThreshold(-1.0); }, vpProjectiveException::invalidValueError,
                               "outlier threshold"));
  EXPECT_TRUE(throwsProjective([&] { robot.setOutlierThreshold(std::numeric_limits<double>::quiet_NaN()); },
                               vpProjectiveException::invalidValueError, "outlier threshold"));
  EXPECT_TRUE(throwsProjective([&] { robot.getAcquisition().isOutlier(0, 0); }, vpProjectiveException::dimensionError,
                               "no observation of marker 0 in trial 0"));
  EXPECT_GE(recall, 0.95);
  EXPECT_LE(falseRate, 0.03);
}

TEST(ProjectiveRobot, NoiseFreeAcquisitionWithEstimatedRig)
{
  // The same acquisition with F estimated from the (noise-free) marker images of all acquisition views, as a user
  // without the true F does: the model lives in that rig's frame and still reproduces the images.
  const ArmSetup s = pumaEyeToHand();
  std::vector<vpImagePoint> allLeft, allRight, left, right;
  s.images(s.qRef, left, right);
  allLeft.insert(allLeft.end(), left.begin(), left.end());
  allRight.insert(allRight.end(), right.begin(), right.end());
  for (unsigned int i = 0; i < 6; ++i) {
    vpColVector q(6, 0.0);
    q[i] = s.trialAmounts[i];
    s.images(s.armJoints(q), left, right);
    allLeft.insert(allLeft.end(), left.begin(), left.end());
    allRight.insert(allRight.end(), right.begin(), right.end());
  }
  vpProjectiveStereoRig rig;
  rig.estimate(allLeft, allRight);
  vpProjectiveRobot robot(s.jointTypes());
  robot.setStereoRig(rig);
  s.images(s.qRef, left, right);
  robot.setZeroReference(left, right);
  for (unsigned int i = 0; i < 6; ++i) {
    for (int sign = -1; sign <= 1; sign += 2) {
      vpColVector q(6, 0.0);
      q[i] = sign * s.trialAmounts[i];
      s.images(s.armJoints(q), left, right);
      robot.addTrialMotion(i, q[i], left, right);
    }
  }
  robot.calibrate();
  EXPECT_LT(robot.getAcquisition().getCalibrationResidual(), 1e-6);
  const Eigen::Matrix4d H = s.Hpe(rig);
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_LT(relativeError(toEigen<4, 4>(robot.getGenerator(i)), s.trueGenerator(i, H)), 1e-6) << "joint " << i;
  }
}

TEST(ProjectiveRobot, SeveralTrialsPerJoint)
{
  // Extra trials of the same joint (here a third, smaller one per joint) are used together: noise free, the model is
  // as exact as with two.
  const ArmSetup s = pumaEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  vpGaussRand noise(1.0, 0.0, 3);
  ASSERT_TRUE(s.acquire(robot, 0.0, noise));
  std::vector<vpImagePoint> left, right;
  for (unsigned int i = 0; i < 6; ++i) {
    vpColVector q(6, 0.0);
    q[i] = 0.5 * s.trialAmounts[i];
    ASSERT_TRUE(s.images(s.armJoints(q), left, right));
    robot.addTrialMotion(i, q[i], left, right);
  }
  robot.calibrate();
  EXPECT_LT(robot.getAcquisition().getCalibrationResidual(), 1e-8);
  const Eigen::Matrix4d H = s.Hpe(robot.getStereoRig());
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_LT(relativeError(toEigen<4, 4>(robot.getGenerator(i)), s.trueGenerator(i, H)), 1e-9);
  }
}

TEST(ProjectiveRobotDeathTest, BlockedJointIsReportedNotCrashed)
{
  /*
    A joint that does not move during its trial (blocked, or its images copied by mistake) is degenerate input: the
    design requires an exception saying what is wrong (here: which joint), never a crash or a NaN model. Run in a
    child process because the library currently aborts (Ceres CHECK failure on a NaN parameter block) or, depending
    on heap contents, reads uninitialised memory: see the report of this suite.
  */
  GTEST_FLAG_SET(death_test_style, "threadsafe");
  EXPECT_EXIT(calibrateWithBlockedJoint(), ::testing::ExitedWithCode(0), "");
}
