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
  Tests of vpServoProjective's reduced task (issue 6, points 3 and 4): features lost, outside the image or non-finite
  are set aside (their rows of e and J zero, SERVO_REDUCED) and used again when back; the reduced law is the damped
  law of the active rows; the task stops (qdot = 0 exactly) when the active points no longer constrain every joint
  (2 points: rank 5).
*/

#include <gtest/gtest.h>

#include "vpServoProjectiveTestTools.h"

using namespace vpProjectiveTest;

TEST(ServoProjective, LostFeatureIsSetAsideThenUsedAgain)
{
  // 4 markers: while marker 1 is lost (iterations 5 to 9, mid-run: the pairs need 25 to 35 iterations) the 3 others
  // keep rank 6 (see StopsWhenTheActiveFeaturesNoLongerConstrainEveryJoint) and the task goes on with them.
  const std::vector<unsigned int> tracked = {0, 1, 2, 3};
  for (const ArmSetup &s : {pumaEyeToHand(), viperEyeToHand()}) {
    const vpProjectiveRobot robot = calibratedRobot(s);
    for (int p = 0; p < 3; ++p) {
      vpColVector qStart, qTarget;
      randomPair(s, 61, vpMath::rad(20.0), vpMath::rad(15.0), qStart, qTarget);
      int reference = -1;
      vpColVector afterLoss[2]; // joints at iteration 10, when the marker is back
      for (int withLoss = 0; withLoss < 2; ++withLoss) {
        vpColVector q = qStart;
        Task t(s, robot, tracked, q, qTarget);
        configure(t.task);
        int converged = -1;
        for (int it = 0; it <= 200 && converged < 0; ++it) {
          const bool lost = withLoss == 1 && it >= 5 && it < 10;
          if (it == 10) {
            afterLoss[withLoss] = q;
          }
          setFeatures(s, q, tracked, t.s);
          t.task.setFeatureTracked(1, !lost);
          const vpColVector qdot = t.task.computeControlLaw(q);
          ASSERT_TRUE(toEigenV(qdot).allFinite());
          const Eigen::VectorXd e = toEigenV(t.task.getError());
          const Eigen::MatrixXd J = toEigenX(t.task.getReport().getTaskJacobian());
          ASSERT_EQ(e.size(), 16);
          ASSERT_EQ(J.rows(), 16);
          if (lost) {
            EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_REDUCED) << s.name << " iteration " << it;
            EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_NOT_TRACKED);
            EXPECT_EQ(t.task.getFeatureHealth().getNumberOfActiveFeatures(), 3u);
            EXPECT_TRUE(allZero(e.segment<4>(4)));
            EXPECT_TRUE(allZero(Eigen::Map<const Eigen::VectorXd>(J.middleRows(4, 4).eval().data(), 24)));
            EXPECT_GT(qdot.frobeniusNorm(), 0.0);
          } else {
            EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_RUNNING) << s.name << " iteration " << it;
            EXPECT_EQ(t.task.getFeatureHealth().getNumberOfActiveFeatures(), 4u);
            for (unsigned int k = 0; k < 4; ++k) {
              EXPECT_EQ(t.task.getReport().getFeatureState(k), vpServoProjective::FEATURE_ACTIVE);
            }
          }
          if (!lost && activeRms(t.task) < 1e-6) {
            converged = it;
          } else {
            q = s.arm.integrate(s.armJoints(q), qdot, 1.0) - s.qRef;
          }
        }
        EXPECT_GE(converged, withLoss == 1 ? 10 : 0) << s.name << " pair " << p << ": no convergence in 200 iterations";
        EXPECT_LT(jointError(q, qTarget), 1e-5) << s.name << " pair " << p;
        if (withLoss == 0) {
          reference = converged;
        } else {
          // The loss changed the path (another law: noise free, the Gauss-Newton steps of any full-rank subset of the
          // markers agree to first order, hence a small but far-above-rounding difference), not the end.
          EXPECT_GT(jointError(afterLoss[1], afterLoss[0]), 1e-7) << s.name << " pair " << p;
          testLog() << "[ measured ] " << s.name << " pair " << p << ": marker 1 lost at iterations 5-9, converged in "
                    << converged << " iterations (" << reference << " without the loss), joint error "
                    << jointError(q, qTarget) << " rad; the path differed by " << jointError(afterLoss[1], afterLoss[0])
                    << " rad at iteration 10" << std::endl;
        }
      }
    }
  }
}

TEST_F(ServoProjectivePuma, ReducedTaskIsTheDampedLawOfTheActiveFeatures)
{
  // A task on markers 0-3 with marker 2 set aside computes what a task on markers 0, 1, 3 computes: same gain (the
  // set-aside feature carries the largest error, which must not reach the adaptive gain), same damping (from the
  // reduced J's sigma_min), same condition number, same step, and that step is the closed form on the active rows.
  vpUniRand rng(62);
  const vpAdaptiveGain gain(2.0, 0.2, 0.05);
  for (int p = 0; p < 5; ++p) {
    vpColVector q, qStar;
    randomPair(s, rng, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
    Task four(s, robot, {0, 1, 2, 3}, q, qStar);
    Task three(s, robot, {0, 1, 3}, q, qStar);
    four.s[2].setRaw(four.s[2].get_u() + 300.0, four.s[2].get_v(), four.s[2].get_up() + 300.0, four.s[2].get_vp());
    four.task.setFeatureTracked(2, false);
    three.task.getControlLaw().setDamping(0.0, 0.0);
    three.task.computeControlLaw(q);
    const Eigen::MatrixXd J3 = toEigenX(three.task.getReport().getTaskJacobian());
    const Eigen::VectorXd e3 = toEigenV(three.task.getError());
    const Eigen::VectorXd sv3 = singularValues(J3);
    const double sigma0 = 2.0 * sv3(5), muMax = sv3(5);
    for (Task *t : {&four, &three}) {
      t->task.setLambda(gain);
      t->task.getControlLaw().setDamping(sigma0, muMax);
    }
    const Eigen::VectorXd qdot4 = toEigenV(four.task.computeControlLaw(q));
    const Eigen::VectorXd qdot3 = toEigenV(three.task.computeControlLaw(q));
    EXPECT_EQ(four.task.getStatus(), vpServoProjective::SERVO_REDUCED);
    EXPECT_EQ(four.task.getReport().getFeatureState(2), vpServoProjective::FEATURE_NOT_TRACKED);
    EXPECT_LT((qdot4 - qdot3).norm(), 1e-12 * qdot3.norm()) << "pair " << p;
    const double mu2 = muMax * muMax * (1.0 - 0.25);
    EXPECT_NEAR(four.task.getReport().getDamping(), std::sqrt(mu2), 1e-9 * muMax);
    EXPECT_NEAR(four.task.getReport().getDamping(), three.task.getReport().getDamping(), 1e-12 * muMax);
    EXPECT_DOUBLE_EQ(four.task.getReport().getLambda(), gain.value_const(e3.cwiseAbs().maxCoeff()));
    EXPECT_NEAR(four.task.getReport().getConditionNumber(), sv3(0) / sv3(5), 1e-7 * sv3(0) / sv3(5));
    const double lambda = four.task.getReport().getLambda();
    const Eigen::VectorXd dls =
        -lambda * (J3.transpose() * J3 + mu2 * Eigen::MatrixXd::Identity(6, 6)).ldlt().solve(J3.transpose() * e3);
    EXPECT_LT((qdot4 - dls).norm(), 1e-9 * dls.norm());
    // The law of the 4 features, for contrast: the set-aside one would have changed the step.
    four.task.setFeatureTracked(2, true);
    const Eigen::VectorXd qdotAll = toEigenV(four.task.computeControlLaw(q));
    EXPECT_GT((qdotAll - qdot4).norm(), 0.1 * qdot4.norm());
  }
}

TEST(ServoProjective, StopsWhenTheActiveFeaturesNoLongerConstrainEveryJoint)
{
  // The real rank of the remaining stereo points, by an SVD of the active rows: 3 markers -> 6 (REDUCED), 2 markers
  // (8 equations) -> 5: the rotation about the line through the two points moves neither (STOPPED), 1 marker -> 3
  // (J_C annihilates M), none -> 0.
  struct Case {
    std::vector<bool> tracked;
    vpServoProjective::vpServoStatus status;
    int rank;
  };
  const std::vector<Case> cases = {
      {{true, true, true, true}, vpServoProjective::SERVO_RUNNING, 6},
      {{true, true, true, false}, vpServoProjective::SERVO_REDUCED, 6},
      {{true, false, true, false}, vpServoProjective::SERVO_STOPPED, 5},
      {{false, true, false, false}, vpServoProjective::SERVO_STOPPED, 3},
      {{false, false, false, false}, vpServoProjective::SERVO_STOPPED, 0},
      {{true, true, true, true}, vpServoProjective::SERVO_RUNNING, 6},
  };
  for (const ArmSetup &s : {pumaEyeToHand(), viperEyeToHand(), pumaEyeInHand()}) {
    const vpProjectiveRobot robot = calibratedRobot(s);
    const bool eyeInHand = s.mounting == vpProjectiveRobot::EYE_IN_HAND;
    for (int p = 0; p < 3; ++p) {
      vpColVector q, qStar;
      randomPair(s, 63, vpMath::rad(eyeInHand ? 3.0 : 20.0), vpMath::rad(eyeInHand ? 2.0 : 10.0), q, qStar);
      Task t(s, robot, {0, 1, 2, 3}, q, qStar);
      configure(t.task);
      t.task.getControlLaw().setDamping(0.1, 10.0);
      vpProjectiveRobot::JointVector qe(6), qdotE(6);
      for (unsigned int i = 0; i < 6; ++i) {
        qe(i) = q[i];
      }
      for (const Case &c : cases) {
        for (unsigned int k = 0; k < 4; ++k) {
          t.task.setFeatureTracked(k, c.tracked[k]);
        }
        const Eigen::VectorXd qdot = toEigenV(t.task.computeControlLaw(q));
        t.task.computeControlLaw(qe, qdotE);
        EXPECT_EQ(Eigen::VectorXd(qdotE), qdot);
        unsigned int active = 0;
        for (unsigned int k = 0; k < 4; ++k) {
          active += c.tracked[k] ? 1 : 0;
          EXPECT_EQ(t.task.getReport().getFeatureState(k),
                    c.tracked[k] ? vpServoProjective::FEATURE_ACTIVE : vpServoProjective::FEATURE_NOT_TRACKED);
        }
        ASSERT_EQ(t.task.getFeatureHealth().getNumberOfActiveFeatures(), active);
        std::ostringstream what;
        what << s.name << " pair " << p << ", " << active << " active markers";
        if (active > 0) {
          const Eigen::MatrixXd Ja = activeRows(t.task);
          const Eigen::VectorXd sv = singularValues(Ja);
          EXPECT_GT(sv(c.rank - 1) / sv(0), 1e-5) << what.str();
          if (c.rank < 6) {
            EXPECT_LT(sv(c.rank) / sv(0), 1e-9) << what.str();
          }
          if (c.rank == 6) {
            const double ratio = equilibratedRatio(Ja);
            EXPECT_NEAR(t.task.getReport().getSingularValueRatio(), ratio, 1e-6 * ratio) << what.str();
          }
          testLog() << "[ measured ] " << what.str() << ": singular values of the active rows " << sv.transpose()
                    << ", ratio of J D^-1 " << t.task.getReport().getSingularValueRatio() << std::endl;
        }
        EXPECT_EQ(t.task.getStatus(), c.status) << what.str();
        if (c.status == vpServoProjective::SERVO_STOPPED) {
          EXPECT_TRUE(allZero(qdot)) << what.str() << ": qdot " << qdot.transpose();
          EXPECT_EQ(t.task.getReport().getDamping(), 0.0);
          EXPECT_EQ(t.task.getReport().getLambda(), 0.0);
          EXPECT_FALSE(t.task.getReport().isSaturated());
          EXPECT_LT(t.task.getReport().getSingularValueRatio(), 1e-6) << what.str();
        } else {
          EXPECT_GT(qdot.norm(), 0.0) << what.str();
          EXPECT_GT(t.task.getReport().getSingularValueRatio(), 1e-6) << what.str();
        }
      }
    }
  }
}

TEST_F(ServoProjectivePuma, FeatureOutsideTheImageIsDetectedNotExtrapolated)
{
  const double w = s.width, h = s.height, border = 5.0;
  vpUniRand rng(64);
  vpColVector q, qStar;
  randomPair(s, rng, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task t(s, robot, {0, 1, 2, 3}, q, qStar);
  t.task.setImageSize(s.width, s.height, border);
  t.task.computeControlLaw(q); // all markers at least 10 px inside
  EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_RUNNING);
  // The window [border, w-1-border] x [border, h-1-border], bounds included, in either image.
  const Eigen::Vector4d s1 = t.s[1].getFeature();
  const double low[4] = {border, border, border, border};
  const double high[4] = {w - 1.0 - border, h - 1.0 - border, w - 1.0 - border, h - 1.0 - border};
  for (int c = 0; c < 4; ++c) {
    for (int side = 0; side < 2; ++side) {
      const double bound = side == 0 ? low[c] : high[c];
      const double outside = side == 0 ? bound - 1e-9 * w : bound + 1e-9 * w;
      for (int beyond = 0; beyond < 2; ++beyond) {
        Eigen::Vector4d m = s1;
        m(c) = beyond == 1 ? outside : bound;
        t.s[1].setRaw(m(0), m(1), m(2), m(3));
        const Eigen::VectorXd qdot = toEigenV(t.task.computeControlLaw(q));
        ASSERT_TRUE(qdot.allFinite());
        const Eigen::VectorXd e = toEigenV(t.task.getError());
        if (beyond == 1) {
          EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_OUT_OF_IMAGE)
              << "coordinate " << c;
          EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_REDUCED);
          EXPECT_TRUE(allZero(e.segment<4>(4)));
        } else {
          EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_ACTIVE) << "coordinate " << c;
          EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_RUNNING);
        }
      }
    }
  }
  // 0 x 0 disables the check.
  t.s[1].setRaw(-100.0, s1(1), s1(2), s1(3));
  t.task.computeControlLaw(q);
  EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_OUT_OF_IMAGE);
  t.task.setImageSize(0, 0);
  t.task.computeControlLaw(q);
  EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_ACTIVE);

  // Closed loop: all 7 markers tracked from a start where one of them is more than 30 px outside an image (the
  // simulator still gives its extrapolated pixels, as a tracker predicting it would). It is set aside exactly while it
  // is outside, the other 6 bring it back in view, and the task converges on all 7.
  const std::vector<unsigned int> all = {0, 1, 2, 3, 4, 5, 6};
  int runs = 0;
  for (int attempt = 0; attempt < 20000 && runs < 3; ++attempt) {
    vpColVector qStart(6), qTarget(6);
    for (unsigned int i = 0; i < 6; ++i) {
      qTarget[i] = rng.uniform(vpMath::rad(-20.0), vpMath::rad(20.0));
      qStart[i] = qTarget[i] + rng.uniform(vpMath::rad(-15.0), vpMath::rad(15.0));
    }
    if (!s.visible(s.armJoints(qTarget))) {
      continue;
    }
    int outside = 0, inside = 0;
    for (unsigned int k = 0; k < 7; ++k) {
      const Eigen::Vector4d m = s.imageOf(s.armJoints(qStart), k);
      const bool in = m(0) >= 10.0 && m(0) <= w - 11.0 && m(1) >= 10.0 && m(1) <= h - 11.0 && m(2) >= 10.0 &&
                      m(2) <= w - 11.0 && m(3) >= 10.0 && m(3) <= h - 11.0;
      const bool out = m(0) < -30.0 || m(0) > w + 29.0 || m(1) < -30.0 || m(1) > h + 29.0 || m(2) < -30.0 ||
                       m(2) > w + 29.0 || m(3) < -30.0 || m(3) > h + 29.0;
      inside += in ? 1 : 0;
      outside += out ? 1 : 0;
    }
    if (outside != 1 || inside != 6) {
      continue;
    }
    ++runs;
    vpColVector qv = qStart;
    Task loop(s, robot, all, qv, qTarget);
    configure(loop.task);
    loop.task.setImageSize(s.width, s.height);
    int converged = -1, iterationsOut = 0;
    for (int it = 0; it <= 200 && converged < 0; ++it) {
      setFeatures(s, qv, all, loop.s);
      const vpColVector qdot = loop.task.computeControlLaw(qv);
      ASSERT_TRUE(toEigenV(qdot).allFinite());
      bool anyOut = false;
      for (unsigned int k = 0; k < 7; ++k) {
        const Eigen::Vector4d m = s.imageOf(s.armJoints(qv), k);
        const bool out = m(0) < 0.0 || m(0) > w - 1.0 || m(1) < 0.0 || m(1) > h - 1.0 || m(2) < 0.0 || m(2) > w - 1.0 ||
                         m(3) < 0.0 || m(3) > h - 1.0;
        anyOut = anyOut || out;
        EXPECT_EQ(loop.task.getReport().getFeatureState(k),
                  out ? vpServoProjective::FEATURE_OUT_OF_IMAGE : vpServoProjective::FEATURE_ACTIVE)
            << "iteration " << it << " marker " << k;
        if (out) {
          EXPECT_TRUE(allZero(toEigenV(loop.task.getError()).segment<4>(4 * k)));
        }
      }
      EXPECT_EQ(loop.task.getStatus(), anyOut ? vpServoProjective::SERVO_REDUCED : vpServoProjective::SERVO_RUNNING)
          << "iteration " << it;
      iterationsOut += anyOut ? 1 : 0;
      if (!anyOut && activeRms(loop.task) < 1e-6) {
        converged = it;
      } else {
        qv = s.arm.integrate(s.armJoints(qv), qdot, 1.0) - s.qRef;
      }
    }
    EXPECT_GE(converged, 0) << "run " << runs << ": no convergence in 200 iterations";
    EXPECT_EQ(loop.task.getStatus(), vpServoProjective::SERVO_RUNNING);
    EXPECT_LT(jointError(qv, qTarget), 1e-5);
    testLog() << "[ measured ] start with one marker outside an image: set aside for " << iterationsOut
              << " iterations, converged in " << converged << ", joint error " << jointError(qv, qTarget) << " rad"
              << std::endl;
  }
  EXPECT_EQ(runs, 3) << "fewer than 3 starts with exactly one marker outside the image were found";
}

TEST_F(ServoProjectivePuma, NonFiniteFeatureIsSetAsideWithoutNaN)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vpColVector q, qStar;
  randomPair(s, 65, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task t(s, robot, {0, 1, 2, 3}, q, qStar);
  configure(t.task);
  auto check = [&](const std::vector<vpServoProjective::vpFeatureState> &expected,
                   vpServoProjective::vpServoStatus status, const char *what) {
    vpColVector qdot;
    ASSERT_NO_THROW(qdot = t.task.computeControlLaw(q)) << what;
    const Eigen::VectorXd e = toEigenV(t.task.getError());
    const Eigen::MatrixXd J = toEigenX(t.task.getReport().getTaskJacobian());
    EXPECT_TRUE(toEigenV(qdot).allFinite()) << what;
    EXPECT_TRUE(e.allFinite()) << what;
    EXPECT_TRUE(J.allFinite()) << what;
    EXPECT_EQ(t.task.getStatus(), status) << what;
    for (unsigned int k = 0; k < 4; ++k) {
      EXPECT_EQ(t.task.getReport().getFeatureState(k), expected[k]) << what << ", feature " << k;
      if (expected[k] != vpServoProjective::FEATURE_ACTIVE) {
        EXPECT_TRUE(allZero(e.segment<4>(4 * k))) << what;
      }
    }
    if (status == vpServoProjective::SERVO_STOPPED) {
      EXPECT_TRUE(allZero(toEigenV(qdot))) << what;
    } else {
      EXPECT_GT(qdot.frobeniusNorm(), 0.0) << what;
    }
  };
  const vpServoProjective::vpFeatureState A = vpServoProjective::FEATURE_ACTIVE;
  const vpServoProjective::vpFeatureState N = vpServoProjective::FEATURE_NOT_FINITE;
  const Eigen::Vector4d s2 = t.s[2].getFeature(), star0 = t.sStar[0].getFeature();
  t.s[2].setRaw(nan, s2(1), s2(2), s2(3));
  check({A, A, N, A}, vpServoProjective::SERVO_REDUCED, "NaN in s_2");
  t.s[2].setRaw(s2(0), s2(1), s2(2), -inf);
  check({A, A, N, A}, vpServoProjective::SERVO_REDUCED, "-inf in s_2");
  t.s[2].setRaw(s2(0), s2(1), s2(2), s2(3));
  t.sStar[0].setRaw(star0(0), inf, star0(2), star0(3));
  check({N, A, A, A}, vpServoProjective::SERVO_REDUCED, "inf in s*_0");
  t.s[2].setRaw(nan, nan, nan, nan);
  check({N, A, N, A}, vpServoProjective::SERVO_STOPPED, "two non-finite features of four: 2 points, rank 5");
  t.s[2].setRaw(s2(0), s2(1), s2(2), s2(3));
  t.sStar[0].setRaw(star0(0), star0(1), star0(2), star0(3));
  check({A, A, A, A}, vpServoProjective::SERVO_RUNNING, "all finite again");
  // Misuse still throws: q itself non-finite.
  vpColVector qNaN = q;
  qNaN[0] = nan;
  EXPECT_TRUE(throwsProjective([&] { t.task.computeControlLaw(qNaN); }, vpProjectiveException::nonFiniteValueError,
                               "q has a NaN"));
}
