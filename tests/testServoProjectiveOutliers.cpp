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
  Tests of vpServoProjective's outlier check (issue 6, point 3): the documented distances, gross outliers flagged and
  set aside with the accuracy kept, and with nothing to catch the checks change no bit of the velocities.
*/

#include <gtest/gtest.h>

#include "vpServoProjectiveTestTools.h"

using namespace vpProjectiveTest;

TEST_F(ServoProjectivePuma, OutlierDistancesAreTheDocumentedOnes)
{
  // d_F is the larger of the two point-to-epipolar-line distances; the prediction distance is that of the features
  // to the projections of H(q) H(q_l)^-1 M_l. Noise free with an exact model, an accepted feature is predicted to
  // rounding; a feature moved along its epipolar line keeps d_F but not its prediction distance.
  const Eigen::Matrix3d F = toEigen<3, 3>(robot.getStereoRig().getFundamentalMatrix());
  vpColVector q, qStar;
  randomPair(s, 66, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task t(s, robot, {0, 1, 2, 3}, q, qStar);
  configure(t.task);
  t.task.computeControlLaw(q);
  for (unsigned int k = 0; k < 4; ++k) {
    EXPECT_EQ(t.task.getFeatureHealth().getEpipolarDistance(k), -1.0); // rejection off: not evaluated
    EXPECT_EQ(t.task.getFeatureHealth().getPredictionDistance(k), -1.0);
  }
  t.task.getFeatureHealth().setOutlierThreshold(2.0);
  vpColVector qNext = q;
  for (int it = 0; it < 3; ++it) {
    const vpColVector qdot = t.task.computeControlLaw(qNext);
    for (unsigned int k = 0; k < 4; ++k) {
      const double expected = epipolarDistances(F, t.s[k].getLeft(), t.s[k].getRight()).maxCoeff();
      EXPECT_NEAR(t.task.getFeatureHealth().getEpipolarDistance(k), expected, 1e-9);
      EXPECT_LT(t.task.getFeatureHealth().getEpipolarDistance(k), 1e-6);
      if (it == 0) {
        EXPECT_EQ(t.task.getFeatureHealth().getPredictionDistance(k), -1.0); // never accepted before
      } else {
        EXPECT_GE(t.task.getFeatureHealth().getPredictionDistance(k), 0.0);
        EXPECT_LT(t.task.getFeatureHealth().getPredictionDistance(k), 1e-5) << "iteration " << it << " marker " << k;
      }
      EXPECT_EQ(t.task.getReport().getFeatureState(k), vpServoProjective::FEATURE_ACTIVE);
    }
    qNext = s.arm.integrate(s.armJoints(qNext), qdot, 1.0) - s.qRef;
    setFeatures(s, qNext, {0, 1, 2, 3}, t.s);
  }
  // Marker 1 slid 20 px along its epipolar line in the right image: on its line, 20 px from its prediction.
  const Eigen::Vector4d m = t.s[1].getFeature();
  const Eigen::Vector3d lp = F * Eigen::Vector3d(m(0), m(1), 1.0);
  const Eigen::Vector2d along = Eigen::Vector2d(lp(1), -lp(0)).normalized();
  t.s[1].setRaw(m(0), m(1), m(2) + 20.0 * along(0), m(3) + 20.0 * along(1));
  t.task.computeControlLaw(qNext);
  EXPECT_LT(t.task.getFeatureHealth().getEpipolarDistance(1), 1e-6);
  EXPECT_NEAR(t.task.getFeatureHealth().getPredictionDistance(1), 20.0, 1e-4);
  EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_OUTLIER);
  EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_REDUCED);
  // 20 px across the line: caught by the epipolar test first (the prediction is then not evaluated).
  const Eigen::Vector2d across = lp.head<2>().normalized();
  t.s[1].setRaw(m(0), m(1), m(2) + 20.0 * across(0), m(3) + 20.0 * across(1));
  t.task.computeControlLaw(qNext);
  EXPECT_GT(t.task.getFeatureHealth().getEpipolarDistance(1), 19.0);
  EXPECT_EQ(t.task.getFeatureHealth().getPredictionDistance(1), -1.0);
  EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_OUTLIER);
  // Back on its true image: accepted again, predicted from its last acceptance two iterations ago.
  t.s[1].setRaw(m(0), m(1), m(2), m(3));
  t.task.computeControlLaw(qNext);
  EXPECT_EQ(t.task.getReport().getFeatureState(1), vpServoProjective::FEATURE_ACTIVE);
  EXPECT_LT(t.task.getFeatureHealth().getPredictionDistance(1), 1e-5);
}

TEST_F(ServoProjectivePuma, GrossOutliersAreRejected)
{
  // All 7 markers, Gaussian noise sigma = 0.3 px on the current features (s* exact), and from the second iteration
  // on 5 % of the features per iteration shifted by 30 px in a random direction in one image (seeded). Three runs
  // with the same noise: A without outliers, B with outliers and setOutlierThreshold(5 px), C with outliers and no
  // threshold. Accuracy: RMS of q - q* over the last 50 of 150 iterations. B must flag every injected outlier (the
  // first iteration is left clean: a feature seen for the first time has no prediction yet), flag at most 1 % of
  // the clean features, and be as accurate as A; C is visibly disturbed.
  const std::vector<unsigned int> tracked = {0, 1, 2, 3, 4, 5, 6};
  const double sigma = 0.3, offset = 30.0, rate = 0.05, threshold = 5.0;
  const int iterations = 150, tail = 50;
  for (int p = 0; p < 3; ++p) {
    vpColVector qStart, qTarget;
    randomPair(s, 67, vpMath::rad(20.0), vpMath::rad(15.0), qStart, qTarget);
    double accuracy[3] = {0.0, 0.0, 0.0};
    int injected = 0, missed = 0, falseAlarms = 0, clean = 0;
    double worstRms[3] = {0.0, 0.0, 0.0};
    for (int run = 0; run < 3; ++run) {
      vpGaussRand noise(1.0, 0.0, 100 + p);
      vpUniRand outliers(200 + p);
      vpColVector q = qStart;
      Task t(s, robot, tracked, q, qTarget);
      configure(t.task);
      if (run == 1) {
        t.task.getFeatureHealth().setOutlierThreshold(threshold);
      }
      double sum = 0.0;
      int count = 0;
      for (int it = 0; it < iterations; ++it) {
        std::vector<bool> corrupted(tracked.size(), false);
        for (size_t k = 0; k < tracked.size(); ++k) {
          Eigen::Vector4d m = s.imageOf(s.armJoints(q), tracked[k]);
          for (int c = 0; c < 4; ++c) {
            m(c) += sigma * noise();
          }
          const bool corrupt = outliers.uniform(0.0, 1.0) < rate;
          const double angle = outliers.uniform(0.0, 2.0 * M_PI);
          const int image = outliers.uniform(0.0, 1.0) < 0.5 ? 0 : 2;
          if (run > 0 && corrupt && it > 0) {
            m(image) += offset * std::cos(angle);
            m(image + 1) += offset * std::sin(angle);
            corrupted[k] = true;
          }
          t.s[k].buildFrom(m(0), m(1), m(2), m(3));
        }
        const vpColVector qdot = t.task.computeControlLaw(q);
        ASSERT_TRUE(toEigenV(qdot).allFinite());
        if (run == 1) {
          for (size_t k = 0; k < tracked.size(); ++k) {
            const bool flagged =
                t.task.getReport().getFeatureState(static_cast<unsigned int>(k)) == vpServoProjective::FEATURE_OUTLIER;
            injected += corrupted[k] ? 1 : 0;
            missed += corrupted[k] && !flagged ? 1 : 0;
            clean += corrupted[k] ? 0 : 1;
            falseAlarms += !corrupted[k] && flagged ? 1 : 0;
          }
          EXPECT_NE(t.task.getStatus(), vpServoProjective::SERVO_STOPPED);
        }
        if (it >= iterations - tail) {
          sum += (toEigenV(q) - toEigenV(qTarget)).squaredNorm() / 6.0;
          ++count;
          worstRms[run] = std::max(worstRms[run], activeRms(t.task));
        }
        q = s.arm.integrate(s.armJoints(q), qdot, 1.0) - s.qRef;
      }
      accuracy[run] = std::sqrt(sum / count);
    }
    testLog() << "[ measured ] pair " << p << ": RMS joint error over the last " << tail << " iterations "
              << vpMath::deg(accuracy[0]) << " deg without outliers, " << vpMath::deg(accuracy[1])
              << " deg with outliers rejected, " << vpMath::deg(accuracy[2])
              << " deg with outliers not rejected; worst image RMS in that window " << worstRms[0] << ", "
              << worstRms[1] << ", " << worstRms[2] << " px; " << injected << " outliers injected, " << missed
              << " missed, " << falseAlarms << " false alarms among " << clean << " clean features" << std::endl;
    EXPECT_GT(injected, 20);
    EXPECT_EQ(missed, 0) << "pair " << p;
    EXPECT_LE(falseAlarms, clean / 100) << "pair " << p;
    EXPECT_LT(accuracy[1], 1.3 * accuracy[0]) << "pair " << p;
    EXPECT_GT(accuracy[2], 3.0 * accuracy[0]) << "pair " << p;
  }
}

TEST_F(ServoProjectivePuma, NewChecksChangeNothingWhenThereIsNothingToCatch)
{
  // Defaults, then every check switched on with nothing to catch (markers 10 px inside the images, no outlier,
  // joints far from wide limits): the same velocities, bit for bit, along a whole run.
  vpColVector q, qTarget;
  randomPair(s, 69, vpMath::rad(20.0), vpMath::rad(15.0), q, qTarget);
  const std::vector<unsigned int> tracked = {0, 1, 2};
  Task plain(s, robot, tracked, q, qTarget), checked(s, robot, tracked, q, qTarget);
  configure(plain.task);
  configure(checked.task);
  EXPECT_EQ(plain.task.getStatus(), vpServoProjective::SERVO_RUNNING);
  EXPECT_FALSE(plain.task.getControlLaw().getJointLimitAvoidance().hasJointLimits());
  for (unsigned int k = 0; k < 3; ++k) {
    EXPECT_TRUE(plain.task.getFeatureHealth().isFeatureTracked(k));
    EXPECT_EQ(plain.task.getReport().getFeatureState(k), vpServoProjective::FEATURE_ACTIVE);
  }
  checked.task.setImageSize(s.width, s.height, 5.0);
  checked.task.getFeatureHealth().setOutlierThreshold(5.0);
  checked.task.setJointLimits(vpColVector(6, -M_PI), vpColVector(6, M_PI));
  for (int it = 0; it < 40; ++it) {
    setFeatures(s, q, tracked, plain.s);
    setFeatures(s, q, tracked, checked.s);
    const vpColVector a = plain.task.computeControlLaw(q);
    const vpColVector b = checked.task.computeControlLaw(q);
    ASSERT_EQ(toEigenV(a), toEigenV(b)) << "iteration " << it;
    EXPECT_EQ(checked.task.getStatus(), vpServoProjective::SERVO_RUNNING);
    EXPECT_EQ(checked.task.getFeatureHealth().getNumberOfActiveFeatures(), 3u);
    EXPECT_TRUE(allZero(toEigenV(checked.task.getReport().getJointLimitVelocity())));
    EXPECT_TRUE(allZero(toEigenV(plain.task.getReport().getJointLimitVelocity())));
    q = s.arm.integrate(s.armJoints(q), a, 1.0) - s.qRef;
  }
}
