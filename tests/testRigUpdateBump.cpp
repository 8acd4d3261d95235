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
  A camera or the whole rig bumped during a task (issue 12, point 6; helpers in vpRigUpdateTestTools.h):
  SERVO_MODEL_MISMATCH detected, the rig re-registered and the task finished; the mismatch's precedence over single
  outliers; the task's s* re-expressed after updateRig(); a shift below the threshold seen against the noise.
*/

#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "vpRigUpdateTestTools.h"

using namespace vpProjectiveTest;

// One case of each kind, asserted one by one: detection within 2 iterations, no false alarm, re-registration close to
// the pre-bump prediction error, the task at its original target, the user's s* untouched.
TEST(RigUpdate, BumpDetectedReRegisteredAndTaskFinished)
{
  const ArmSetup s = pumaEyeToHand();
  for (BumpKind kind : {BUMP_LEFT, BUMP_RIGHT, BUMP_RIG}) {
    const BumpCase c = runBumpCase(s, 100 + kind, kind);
    EXPECT_GE(c.detectedAfter, 1) << bumpName(kind);
    EXPECT_LE(c.detectedAfter, 2) << bumpName(kind);
    EXPECT_EQ(c.falseAlarms, 0) << bumpName(kind);
    EXPECT_LT(c.ratio3, 3.0) << bumpName(kind);
    EXPECT_LT(c.ratio10, 2.0) << bumpName(kind);
    // Loose: the unbumped runs of the Monte-Carlo rest up to 1.4 mm from the target (90 % quantile) at 0.5 px.
    EXPECT_LT(c.from3.deg, 2.0) << bumpName(kind);
    EXPECT_LT(c.from3.metres, 0.005) << bumpName(kind);
    EXPECT_TRUE(c.from3.userStarUnchanged) << bumpName(kind);
    testLog() << "[ measured ] " << bumpName(kind) << ": detected after " << c.detectedAfter << ", pre-bump error "
              << c.preError << " px, ratios 3: " << c.ratio3 << " 10: " << c.ratio10
              << " (11-parameter from 3: " << c.ratio3General << "), final " << c.from3.deg << " deg "
              << 1000.0 * c.from3.metres << " mm (unbumped " << c.unbumpedDeg << " deg " << 1000.0 * c.unbumpedMetres
              << " mm)" << std::endl;
  }
}

// SERVO_MODEL_MISMATCH takes precedence over single-feature outliers, a single outlier is not a mismatch, qdot = 0,
// and a threshold of 0 turns the detection off.
TEST(RigUpdate, MismatchPrecedenceAndSwitch)
{
  NoiseFreeBump t(31, BUMP_LEFT);
  const ArmSetup &s = t.s, &b = t.b;
  const vpColVector qStart = jointsNear({&s, &b}, t.rng, t.qTarget, 8.0);
  for (double threshold : {5.0, 0.0}) {
    ServoRun run(s, t.robot, t.qTarget, 0.0, t.noise);
    run.task.getFeatureHealth().setOutlierThreshold(3.0);
    run.task.getModelMismatch().setThreshold(threshold);
    vpColVector q = qStart;
    for (int it = 0; it < 3; ++it) {
      EXPECT_EQ(run.step(s, q, 0.0, t.noise), vpServoProjective::SERVO_RUNNING);
    }
    // One feature jumps by 20 px: an outlier, not a mismatch.
    ServoRun::measure(s, q, 0.0, t.noise, run.s);
    const Eigen::Vector4d s2 = run.s[2].getFeature();
    run.s[2].buildFrom(s2(0) + 20.0, s2(1), s2(2), s2(3));
    run.task.computeControlLaw(q);
    EXPECT_EQ(run.task.getReport().getFeatureState(2), vpServoProjective::FEATURE_OUTLIER);
    EXPECT_EQ(run.task.getStatus(), vpServoProjective::SERVO_REDUCED);
    // The camera moves: every feature is an outlier for the health, and a mismatch at the second call.
    vpServoProjective::vpServoStatus first = run.step(b, q, 0.0, t.noise);
    ServoRun::measure(b, q, 0.0, t.noise, run.s);
    const vpColVector qdot = run.task.computeControlLaw(q);
    if (threshold > 0.0) {
      EXPECT_NE(first, vpServoProjective::SERVO_MODEL_MISMATCH);
      EXPECT_EQ(run.task.getStatus(), vpServoProjective::SERVO_MODEL_MISMATCH);
      EXPECT_EQ(qdot.frobeniusNorm(), 0.0);
      EXPECT_GT(run.task.getModelMismatch().getDistance(0), threshold);
      // Never re-registered since the acquisition: print() lists the rig mounting among the causes.
      std::ostringstream printed;
      run.task.print(printed);
      EXPECT_NE(printed.str().find("check the rig mounting"), std::string::npos) << printed.str();
    } else {
      EXPECT_NE(run.task.getStatus(), vpServoProjective::SERVO_MODEL_MISMATCH);
      EXPECT_EQ(run.task.getModelMismatch().getDisagreeingIterations(), 0u);
    }
  }
}

// The task's own s*: re-expressed after updateRig(), the user's objects unchanged, a new s* taken as given.
TEST(RigUpdate, TaskReExpressesItsDesiredFeatures)
{
  NoiseFreeBump t(21, BUMP_RIG);
  const ArmSetup &s = t.s, &b = t.b;
  ServoRun run(s, t.robot, t.qTarget, 0.0, t.noise);
  vpColVector q = jointsNear({&s, &b}, t.rng, t.qTarget, 8.0);
  run.step(s, q, 0.0, t.noise);
  EXPECT_EQ(toEigen4(run.task.getDesiredFeature(0)), run.sStar[0].getFeature());
  vpColVector qObs;
  for (int k = 0; k < 3; ++k) {
    qObs = visibleJoints({&b}, t.rng);
    std::vector<vpImagePoint> left, right;
    b.images(b.armJoints(qObs), left, right, -1e9);
    t.robot.addRigObservation(qObs, left, right);
  }
  t.robot.updateRig();
  const Eigen::Vector4d user = run.sStar[0].getFeature();
  run.step(b, q, 0.0, t.noise);
  // Noise-free: the re-expressed s* is the new rig's image of the target, i.e. what the bumped rig sees there.
  for (size_t k = 0; k < kTracked.size(); ++k) {
    const Eigen::Vector4d expected = b.imageOf(b.armJoints(t.qTarget), kTracked[k]);
    EXPECT_LT((toEigen4(run.task.getDesiredFeature(static_cast<unsigned int>(k))) - expected).norm(), 1e-3);
  }
  EXPECT_EQ(run.sStar[0].getFeature(), user);
  EXPECT_GT((toEigen4(run.task.getDesiredFeature(0)) - user).norm(), 1.0);
  for (int it = 0; it < 100; ++it) {
    const vpServoProjective::vpServoStatus st = run.step(b, q, 0.0, t.noise);
    if (it % 10 == 0)
      testLog() << it << " " << st << " " << run.task.getError().frobeniusNorm() << " "
                << run.task.getReport().getConditionNumber() << std::endl;
  }
  double deg = 0.0, metres = 0.0;
  {
    vpColVector qq = t.qTarget;
    run.step(b, qq, 0.0, t.noise);
    testLog() << "at target e " << run.task.getError().t() << std::endl;
    std::vector<vpImagePoint> l, r;
    b.images(b.armJoints(t.qTarget), l, r, -1e9);
    testLog() << "pred err at target " << t.robot.getPredictionError(t.qTarget, l, r) << std::endl;
    testLog() << "q-qT " << (q - t.qTarget).t() << std::endl;
  }
  toolPoseError(s, q, t.qTarget, deg, metres);
  EXPECT_LT(deg, 1e-3);
  EXPECT_LT(metres, 1e-5);
  // A new s* given by the user after the update is in the new images: taken as given.
  ServoRun::measure(b, qObs, 0.0, t.noise, run.sStar);
  run.step(b, q, 0.0, t.noise);
  EXPECT_EQ(toEigen4(run.task.getDesiredFeature(1)), run.sStar[1].getFeature());
}

// The detector knows the noise it works in (vpServoModelMismatch, "Noise"): a shift of 2 px common to the features,
// which the 5 px threshold's vote does not see, at 0.5 px of noise is a mismatch within 2 calls, while healthy noisy
// tasks never are one, and the noise it learned is the residual's, sqrt(2) times the features'. The model acquired at
// 0.5 px; each task's target within 20 deg of the zero reference, its start within 15 deg of it; the shift, 2 px in a
// random direction in both images (a moved rig), 10 calls after the start. Measured over 7 seeds of 200 such cases:
// 1395 of 1400 detected within 2 calls (the others never: 2 px is 6 standard deviations of the features' mean
// residual, and a call that misses it takes the shifted images in), no mismatch in 294000 healthy calls at 0.5 and
// 1 px, the learned noise 0.92-1.14 times its expected value. Asserted below the measured rates, not at them.
TEST(RigUpdate, MismatchSeesASmallShiftAgainstTheNoise)
{
  const ArmSetup s = pumaEyeToHand();
  vpUniRand rng(4242);
  vpGaussRand noise(1.0, 0.0, 4242);
  const vpProjectiveRobot robot = acquiredRobot(s, noise);
  const int cases = 20, healthyCalls = 200;
  int detected = 0, alarms = 0, calls = 0;
  int seenByTheVote = 0; // shifts of which more than half of the features are beyond the threshold at the first call
  double noiseMin = 1e9, noiseMax = 0.0;
  for (int k = 0; k < cases; ++k) {
    const vpColVector qTarget = jointsNear({&s}, rng, vpColVector(s.n(), 0.0), 20.0);
    const vpColVector qStart = jointsNear({&s}, rng, qTarget, 15.0);
    // Healthy: 200 calls at 0.5 px (the even cases) or 1 px (the odd ones).
    {
      const double sigma = k % 2 == 0 ? kSigma : 2.0 * kSigma;
      ServoRun run(s, robot, qTarget, sigma, noise);
      vpColVector q = qStart;
      for (int it = 0; it < healthyCalls; ++it, ++calls) {
        alarms += run.step(s, q, sigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH ? 1 : 0;
      }
      // The residual's noise is sqrt(2) times the features' own: 0.71 px at 0.5 px, 1.41 px at 1 px.
      const double learned = run.task.getModelMismatch().getNoise() / (std::sqrt(2.0) * sigma);
      noiseMin = std::min(noiseMin, learned);
      noiseMax = std::max(noiseMax, learned);
    }
    // The shift: 2 px in one direction, in both images, from the 11th call on.
    ServoRun run(s, robot, qTarget, kSigma, noise);
    vpColVector q = qStart;
    for (int it = 0; it < 10; ++it, ++calls) {
      alarms += run.step(s, q, kSigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH ? 1 : 0;
    }
    const double angle = rng.uniform(0.0, 2.0 * M_PI), du = 2.0 * std::cos(angle), dv = 2.0 * std::sin(angle);
    int after = -1;
    for (int it = 1; it <= 4 && after < 0; ++it) {
      ServoRun::measure(s, q, kSigma, noise, run.s);
      for (vpFeatureStereoPoint &f : run.s) {
        const Eigen::Vector4d v = f.getFeature();
        f.buildFrom(v(0) + du, v(1) + dv, v(2) + du, v(3) + dv);
      }
      const vpColVector qdot = run.task.computeControlLaw(q);
      q = s.arm.integrate(s.armJoints(q), qdot, 1.0) - s.qRef;
      if (it == 1) {
        const vpServoModelMismatch &m = run.task.getModelMismatch();
        unsigned int beyond = 0;
        for (unsigned int i = 0; i < m.getNumberOfFeatures(); ++i) {
          beyond += m.getDistance(i) > m.getThreshold() ? 1 : 0;
        }
        seenByTheVote += 2 * beyond > m.getNumberOfFeatures() ? 1 : 0;
      }
      after = run.task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH ? it : -1;
    }
    detected += after >= 1 && after <= 2 ? 1 : 0;
    if (after < 1 || after > 2) {
      testLog() << "[ measured ] case " << k << ": the 2 px shift detected after " << after << " calls" << std::endl;
    }
  }
  testLog() << "[ measured ] 2 px shift at 0.5 px of noise detected within 2 calls in " << detected << " of " << cases
            << " (" << seenByTheVote << " that the 5 px threshold's vote sees); " << alarms << " mismatches in "
            << calls << " healthy calls; learned noise over its "
            << "expected value " << noiseMin << "-" << noiseMax << std::endl;
  EXPECT_EQ(seenByTheVote, 0); // the threshold alone would not see them
  EXPECT_GE(detected, cases - 1);
  EXPECT_EQ(alarms, 0);
  EXPECT_GE(calls, 2000);
  EXPECT_GT(noiseMin, 0.8); // the detector knows the noise it works in, within 20 %
  EXPECT_LT(noiseMax, 1.25);
}

// The learned noise's floor (0.5 px per coordinate of a residual): features rounded to whole pixels, whose residuals
// are most often 0 and otherwise 1 px, at 0, 0.1 and 0.2 px of noise before the rounding, never make a mismatch
// (measured: none in 15000 calls). The model acquired at 0.5 px; targets and starts as above.
TEST(RigUpdate, MismatchDoesNotAlarmOnFeaturesRoundedToWholePixels)
{
  const ArmSetup s = pumaEyeToHand();
  vpUniRand rng(77);
  vpGaussRand noise(1.0, 0.0, 77);
  const vpProjectiveRobot robot = acquiredRobot(s, noise);
  int alarms = 0, calls = 0;
  for (int k = 0; k < 100; ++k) {
    const vpColVector qTarget = jointsNear({&s}, rng, vpColVector(s.n(), 0.0), 20.0);
    const vpColVector qStart = jointsNear({&s}, rng, qTarget, 15.0);
    const double sigma = 0.1 * (k % 3);
    ServoRun run(s, robot, qTarget, sigma, noise);
    vpColVector q = qStart;
    for (int it = 0; it < 150; ++it, ++calls) {
      ServoRun::measure(s, q, sigma, noise, run.s);
      for (vpFeatureStereoPoint &f : run.s) {
        const Eigen::Vector4d v = f.getFeature();
        f.buildFrom(std::round(v(0)), std::round(v(1)), std::round(v(2)), std::round(v(3)));
      }
      const vpColVector qdot = run.task.computeControlLaw(q);
      q = s.arm.integrate(s.armJoints(q), qdot, 1.0) - s.qRef;
      alarms += run.task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH ? 1 : 0;
    }
  }
  testLog() << "[ measured ] features rounded to whole pixels: " << alarms << " mismatches in " << calls << " calls"
            << std::endl;
  EXPECT_EQ(alarms, 0);
}
