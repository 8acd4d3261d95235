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
  Tests of vpServoFeatureHealth on the PUMA of the metric simulator, its model acquired noise free
  (vpProjectiveArmTestTools.h), noise-free marker images:
  - the classification order NOT_TRACKED > NOT_FINITE > OUT_OF_IMAGE > OUTLIER > ACTIVE, with features that fail
    several tests at once, and the image window's bounds included;
  - the epipolar distance is the larger of the two point-to-line distances (tests' own formula), the prediction
    distance that of the projection of H(q) H(q_l)^-1 M_l, computed here with the public ViSP-typed API; an accepted
    feature is predicted to rounding (below 1e-5 px with the acquired model), one moved 20 px along its epipolar line
    keeps d_F ~ 0 and is 20 px from its prediction;
  - isInView() is the window's verdict on s whatever s* (what the model-mismatch check reads);
  - every acceptance is remembered (getMemory(), the point H(q)^-1 M whose images are the feature's), the prediction
    is tested only with outlier rejection on, and only from the second acceptance with it on;
  - an iteration interrupted before endIteration() changes neither the outcome nor the memories: a later iteration
    gives the same bits as in a twin that never saw it;
  - the iteration's data (vpServoProjectiveData) gives the linearly triangulated point of every feature;
    endIteration() refuses an iteration that left a feature unclassified;
  - misuse throws a vpProjectiveException naming what was wrong; failed setters change nothing.
*/

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoFeatureHealth.h>
#include <visp3/projective/vpServoProjectiveData.h>

#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
typedef vpServoFeatureHealth H;

vpProjectiveRobot::JointVector toJoints(const vpColVector &q)
{
  vpProjectiveRobot::JointVector qe(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    qe(i) = q[i];
  }
  return qe;
}

//! The data of one iteration at q on the given images (what vpServoProjective computes once per iteration).
const vpServoProjectiveData &dataAt(const vpProjectiveRobot &robot, const vpColVector &q,
                                    const std::vector<Eigen::Vector4d> &s)
{
  static vpServoProjectiveData data;
  data.computeKinematics(robot.getModel(), toJoints(q), static_cast<unsigned int>(s.size()));
  for (unsigned int i = 0; i < s.size(); ++i) {
    data.computeFeature(robot.getModel(), i, s[i]);
  }
  return data;
}

//! One iteration at q on the given images; checks the point of every finite feature.
void iterate(H &health, const vpProjectiveRobot &robot, const vpColVector &q, const std::vector<Eigen::Vector4d> &s,
             const std::vector<Eigen::Vector4d> &sStar)
{
  const vpServoProjectiveData &data = dataAt(robot, q, s);
  health.startIteration(robot.getModel(), data);
  for (unsigned int i = 0; i < s.size(); ++i) {
    health.classify(i, sStar[i]);
    ASSERT_EQ(data.hasPoint(i), s[i].allFinite()) << "feature " << i;
    if (data.hasPoint(i)) {
      EXPECT_EQ(data.getPoint(i), robot.getStereoRig().triangulateLinear(s[i].head<2>(), s[i].tail<2>()))
          << "feature " << i;
    }
  }
  health.endIteration();
}

std::vector<Eigen::Vector4d> images(const ArmSetup &setup, const vpColVector &q, unsigned int count)
{
  std::vector<Eigen::Vector4d> s(count);
  for (unsigned int k = 0; k < count; ++k) {
    s[k] = setup.imageOf(setup.armJoints(q), k);
  }
  return s;
}

//! Unit vectors along and across the epipolar line of feature s in the right image.
void epipolarDirections(const Eigen::Matrix3d &F, const Eigen::Vector4d &s, Eigen::Vector2d &along,
                        Eigen::Vector2d &across)
{
  const Eigen::Vector3d lp = F * Eigen::Vector3d(s(0), s(1), 1.0);
  along = Eigen::Vector2d(lp(1), -lp(0)).normalized();
  across = lp.head<2>().normalized();
}

//! The prediction distance of the documentation, from the public ViSP-typed API of the robot and the rig.
double predictionDistance(const vpProjectiveRobot &robot, const vpColVector &qLast, const Eigen::Vector4d &sLast,
                          const vpColVector &q, const Eigen::Vector4d &s)
{
  const vpProjectiveStereoRig &rig = robot.getStereoRig();
  const vpColVector Ml = rig.triangulate(vpImagePoint(sLast(1), sLast(0)), vpImagePoint(sLast(3), sLast(2)));
  const Eigen::Vector4d M0 = toEigenX(robot.getDisplacement(qLast)).inverse() * toEigenV(Ml);
  const Eigen::Vector4d Mhat = toEigenX(robot.getDisplacement(q)) * M0;
  vpColVector Mv(4);
  for (unsigned int k = 0; k < 4; ++k) {
    Mv[k] = Mhat(k);
  }
  vpImagePoint l, r;
  rig.project(Mv, l, r);
  return std::max(std::hypot(l.get_u() - s(0), l.get_v() - s(1)), std::hypot(r.get_u() - s(2), r.get_v() - s(3)));
}
} // namespace

TEST(ServoFeatureHealth, ClassificationOrderAndImageWindow)
{
  const ArmSetup setup = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(setup);
  const Eigen::Matrix3d F = toEigen<3, 3>(robot.getStereoRig().getFundamentalMatrix());
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double w = setup.width, h = setup.height, border = 5.0;
  const vpColVector q(6, 0.0);
  const std::vector<Eigen::Vector4d> sTrue = images(setup, q, 5);
  std::vector<Eigen::Vector4d> s = sTrue;
  Eigen::Vector2d along, across;
  // The order: 0 not tracked and not finite; 1 not finite and out of image; 2 out of image and 20 px off its
  // epipolar line; 3 20 px off its epipolar line; 4 untouched.
  s[0](0) = nan;
  s[1](1) = nan;
  s[1](2) = -100.0;
  epipolarDirections(F, s[2], along, across);
  s[2].tail<2>() += 20.0 * across;
  s[2](2) = w + 100.0;
  epipolarDirections(F, s[3], along, across);
  s[3].tail<2>() += 20.0 * across;
  H health;
  for (int k = 0; k < 5; ++k) {
    health.addFeature();
  }
  EXPECT_EQ(health.getNumberOfFeatures(), 5u);
  health.setFeatureTracked(0, false);
  health.setImageSize(setup.width, setup.height, border);
  health.setOutlierThreshold(5.0);
  iterate(health, robot, q, s, sTrue);
  const H::vpFeatureState expected[5] = {H::FEATURE_NOT_TRACKED, H::FEATURE_NOT_FINITE, H::FEATURE_OUT_OF_IMAGE,
                                         H::FEATURE_OUTLIER, H::FEATURE_ACTIVE};
  for (unsigned int k = 0; k < 5; ++k) {
    EXPECT_EQ(health.getFeatureState(k), expected[k]) << "feature " << k;
    EXPECT_EQ(health.getPredictionDistance(k), -1.0) << "first iteration: no memory yet";
  }
  EXPECT_EQ(health.getNumberOfActiveFeatures(), 1u);
  // In view (what the model-mismatch check may use): tracked, finite, inside the window; an outlier is.
  for (unsigned int k = 0; k < 5; ++k) {
    EXPECT_EQ(health.isInView(k), k >= 3) << "feature " << k;
  }
  for (unsigned int k : {0u, 1u, 2u}) {
    EXPECT_EQ(health.getEpipolarDistance(k), -1.0) << "set aside before the epipolar test, feature " << k;
  }
  EXPECT_NEAR(health.getEpipolarDistance(3), 20.0, 1e-6);
  EXPECT_LT(health.getEpipolarDistance(4), 1e-6);
  // The tracker's verdict is a setting: back to true, feature 0 is active again.
  health.setFeatureTracked(0, true);
  s[0] = sTrue[0];
  iterate(health, robot, q, s, sTrue);
  EXPECT_EQ(health.getFeatureState(0), H::FEATURE_ACTIVE);

  // The window [b, w - 1 - b] x [b, h - 1 - b], bounds included, in either image; 0 x 0 disables it.
  H window;
  for (int k = 0; k < 8; ++k) {
    window.addFeature();
  }
  window.setImageSize(setup.width, setup.height, border);
  std::vector<Eigen::Vector4d> bounds(8, sTrue[4]);
  for (int c = 0; c < 4; ++c) {
    const double high = (c % 2 == 0 ? w : h) - 1.0 - border;
    bounds[2 * c](c) = c < 2 ? border : high;
    bounds[2 * c + 1](c) = c < 2 ? border - 1e-9 * w : high + 1e-9 * w;
  }
  iterate(window, robot, q, bounds, bounds);
  for (unsigned int k = 0; k < 8; ++k) {
    EXPECT_EQ(window.getFeatureState(k), k % 2 == 0 ? H::FEATURE_ACTIVE : H::FEATURE_OUT_OF_IMAGE) << "feature " << k;
  }
  for (unsigned int k = 0; k < 8; ++k) {
    EXPECT_EQ(window.isInView(k), k % 2 == 0) << "feature " << k;
  }
  // A non-finite s* sets the feature aside first, yet the window is tested on s: in view while inside it.
  std::vector<Eigen::Vector4d> noTarget(8, Eigen::Vector4d::Constant(nan));
  iterate(window, robot, q, bounds, noTarget);
  for (unsigned int k = 0; k < 8; ++k) {
    EXPECT_EQ(window.getFeatureState(k), H::FEATURE_NOT_FINITE) << "feature " << k;
    EXPECT_EQ(window.isInView(k), k % 2 == 0) << "feature " << k;
  }
  window.setImageSize(0, 0);
  iterate(window, robot, q, bounds, bounds);
  EXPECT_EQ(window.getNumberOfActiveFeatures(), 8u);
  EXPECT_TRUE(window.isInView(1));
}

TEST(ServoFeatureHealth, DistancesAreTheDocumentedOnes)
{
  const ArmSetup setup = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(setup);
  const Eigen::Matrix3d F = toEigen<3, 3>(robot.getStereoRig().getFundamentalMatrix());
  vpUniRand rng(11);
  for (int t = 0; t < 3; ++t) {
    const vpColVector q1 = setup.randomVisibleJoints(rng, std::vector<double>(6, vpMath::rad(15.0)));
    vpColVector q2 = q1;
    for (unsigned int i = 0; i < 6; ++i) {
      q2[i] += rng.uniform(vpMath::rad(-3.0), vpMath::rad(3.0));
    }
    const std::vector<Eigen::Vector4d> s1 = images(setup, q1, 4), sStar = s1;
    std::vector<Eigen::Vector4d> s2 = images(setup, q2, 4);
    H health;
    for (int k = 0; k < 4; ++k) {
      health.addFeature();
    }
    health.setOutlierThreshold(2.0);
    iterate(health, robot, q1, s1, sStar);
    for (unsigned int k = 0; k < 4; ++k) {
      const vpImagePoint l(s1[k](1), s1[k](0)), r(s1[k](3), s1[k](2));
      EXPECT_NEAR(health.getEpipolarDistance(k), epipolarDistances(F, l, r).maxCoeff(), 1e-9);
      EXPECT_EQ(health.getPredictionDistance(k), -1.0);
    }
    // Marker 1 slid 20 px along its epipolar line in the right image.
    Eigen::Vector2d along, across;
    epipolarDirections(F, s2[1], along, across);
    s2[1].tail<2>() += 20.0 * along;
    iterate(health, robot, q2, s2, sStar);
    for (unsigned int k = 0; k < 4; ++k) {
      const double expected = predictionDistance(robot, q1, s1[k], q2, s2[k]);
      EXPECT_NEAR(health.getPredictionDistance(k), expected, 1e-6) << "marker " << k;
      if (k == 1) {
        EXPECT_LT(health.getEpipolarDistance(k), 1e-6);
        EXPECT_NEAR(health.getPredictionDistance(k), 20.0, 1e-4);
        EXPECT_EQ(health.getFeatureState(k), H::FEATURE_OUTLIER);
      } else {
        EXPECT_LT(health.getPredictionDistance(k), 1e-5) << "marker " << k;
        EXPECT_EQ(health.getFeatureState(k), H::FEATURE_ACTIVE);
      }
    }
    EXPECT_EQ(health.getNumberOfActiveFeatures(), 3u);
  }
}

TEST(ServoFeatureHealth, PredictionOnlyWithOutlierRejection)
{
  const ArmSetup setup = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(setup);
  const vpColVector q(6, 0.0);
  const std::vector<Eigen::Vector4d> s = images(setup, q, 3);
  H health;
  for (int k = 0; k < 3; ++k) {
    health.addFeature();
  }
  iterate(health, robot, q, s, s);
  iterate(health, robot, q, s, s);
  for (unsigned int k = 0; k < 3; ++k) {
    EXPECT_EQ(health.getEpipolarDistance(k), -1.0);
    EXPECT_EQ(health.getPredictionDistance(k), -1.0);
  }
  // The point where each feature was last accepted is remembered without the outlier rejection too (the task's open
  // loop predicts from it): moved by H(q), its images are the feature's.
  for (unsigned int k = 0; k < 3; ++k) {
    Eigen::Vector4d M0, sHat;
    ASSERT_TRUE(health.getMemory(k, M0)) << "feature " << k;
    EXPECT_NEAR(M0.norm(), 1.0, 1e-12);
    ASSERT_TRUE(dataAt(robot, q, s).predict(M0, sHat));
    EXPECT_LT((sHat - s[k]).cwiseAbs().maxCoeff(), 1e-6) << "feature " << k;
  }
  health.setOutlierThreshold(5.0);
  iterate(health, robot, q, s, s); // first acceptance with the prediction test
  EXPECT_GE(health.getEpipolarDistance(0), 0.0);
  EXPECT_EQ(health.getPredictionDistance(0), -1.0);
  iterate(health, robot, q, s, s);
  for (unsigned int k = 0; k < 3; ++k) {
    EXPECT_GE(health.getPredictionDistance(k), 0.0);
    EXPECT_LT(health.getPredictionDistance(k), 1e-5);
  }
  health.addFeature();
  Eigen::Vector4d M0 = Eigen::Vector4d::Constant(7.0);
  EXPECT_FALSE(health.getMemory(3, M0)); // never accepted
  EXPECT_EQ(M0, Eigen::Vector4d::Constant(7.0));
  health.clearFeatures();
  EXPECT_EQ(health.getNumberOfFeatures(), 0u);
  EXPECT_EQ(health.getNumberOfActiveFeatures(), 0u);
}

TEST(ServoFeatureHealth, InterruptedIterationChangesNothing)
{
  const ArmSetup setup = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(setup);
  vpUniRand rng(12);
  const vpColVector q1 = setup.randomVisibleJoints(rng, std::vector<double>(6, vpMath::rad(15.0)));
  vpColVector q2 = q1, q3 = q1;
  for (unsigned int i = 0; i < 6; ++i) {
    q2[i] += vpMath::rad(1.0);
    q3[i] -= vpMath::rad(1.0);
  }
  const std::vector<Eigen::Vector4d> s1 = images(setup, q1, 4), s2 = images(setup, q2, 4), s3 = images(setup, q3, 4);
  H interrupted, twin;
  for (int k = 0; k < 4; ++k) {
    interrupted.addFeature();
    twin.addFeature();
  }
  interrupted.setOutlierThreshold(5.0);
  twin.setOutlierThreshold(5.0);
  iterate(interrupted, robot, q1, s1, s1);
  iterate(twin, robot, q1, s1, s1);
  // An iteration at q2 that classifies every feature (with the images of other markers: other memories) but never
  // ends.
  interrupted.setFeatureTracked(2, false);
  const std::vector<Eigen::Vector4d> s2Swapped = {s2[3], s2[2], s2[1], s2[0]};
  interrupted.startIteration(robot.getModel(), dataAt(robot, q2, s2Swapped));
  for (unsigned int k = 0; k < 4; ++k) {
    interrupted.classify(k, s1[k]);
  }
  EXPECT_EQ(interrupted.getFeatureState(2), H::FEATURE_ACTIVE); // still the outcome at q1
  interrupted.setFeatureTracked(2, true);
  for (unsigned int k = 0; k < 4; ++k) {
    EXPECT_EQ(interrupted.getFeatureState(k), twin.getFeatureState(k));
    EXPECT_EQ(interrupted.getEpipolarDistance(k), twin.getEpipolarDistance(k));
    EXPECT_EQ(interrupted.getPredictionDistance(k), twin.getPredictionDistance(k));
  }
  EXPECT_EQ(interrupted.getNumberOfActiveFeatures(), twin.getNumberOfActiveFeatures());
  // The next complete iteration predicts from the memories of q1 in both.
  iterate(interrupted, robot, q3, s3, s1);
  iterate(twin, robot, q3, s3, s1);
  for (unsigned int k = 0; k < 4; ++k) {
    EXPECT_EQ(interrupted.getFeatureState(k), H::FEATURE_ACTIVE);
    EXPECT_GE(twin.getPredictionDistance(k), 0.0);
    EXPECT_EQ(interrupted.getPredictionDistance(k), twin.getPredictionDistance(k)) << "marker " << k;
  }
}

TEST(ServoFeatureHealth, MisuseThrowsAndChangesNothing)
{
  const ArmSetup setup = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(setup);
  const int dim = vpProjectiveException::dimensionError;
  const int invalid = vpProjectiveException::invalidValueError;
  const int nonFinite = vpProjectiveException::nonFiniteValueError;
  const int notInit = vpProjectiveException::notInitializedError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Vector4d s(300.0, 200.0, 310.0, 200.0);
  H health;
  health.addFeature();
  health.addFeature();
  // Outside an iteration.
  EXPECT_TRUE(throwsProjective([&] { health.classify(0, s); }, notInit, "call startIteration() first"));
  EXPECT_TRUE(throwsProjective([&] { health.endIteration(); }, notInit, "no iteration in progress"));
  // Indices.
  health.startIteration(robot.getModel(), dataAt(robot, vpColVector(6, 0.0), {s, s}));
  EXPECT_TRUE(throwsProjective([&] { health.classify(2, s); }, dim, "feature index 2 is out of range"));
  EXPECT_TRUE(throwsProjective([&] { health.classify(5, s); }, dim, "the task has 2 features"));
  // Every feature classified before the end: once one is missing, the iteration stays open.
  health.setFeatureTracked(1, false);
  health.classify(1, s);
  EXPECT_TRUE(throwsProjective([&] { health.endIteration(); }, notInit, "only 1 of the 2 features were classified"));
  health.classify(0, s);
  health.classify(0, s); // twice: the second outcome counts once
  EXPECT_NO_THROW(health.endIteration());
  EXPECT_EQ(health.getNumberOfActiveFeatures(), 1u);
  EXPECT_EQ(health.getFeatureState(1), H::FEATURE_NOT_TRACKED);
  health.setFeatureTracked(1, true);
  EXPECT_TRUE(throwsProjective([&] { health.setFeatureTracked(2, false); }, dim, "feature index 2"));
  EXPECT_TRUE(throwsProjective([&] { health.isFeatureTracked(2); }, dim, "feature index 2"));
  EXPECT_TRUE(throwsProjective([&] { health.isInView(2); }, dim, "feature index 2"));
  Eigen::Vector4d M0;
  EXPECT_TRUE(throwsProjective([&] { health.getMemory(2, M0); }, dim, "feature index 2"));
  EXPECT_TRUE(throwsProjective([&] { health.getFeatureState(2); }, dim, "feature index 2"));
  EXPECT_TRUE(throwsProjective([&] { health.getEpipolarDistance(2); }, dim, "feature index 2"));
  EXPECT_TRUE(throwsProjective([&] { health.getPredictionDistance(2); }, dim, "feature index 2"));
  // Settings, which keep their values when refused.
  health.setImageSize(640, 480, 3.0);
  health.setOutlierThreshold(4.0);
  EXPECT_TRUE(throwsProjective([&] { health.setImageSize(640, 0); }, invalid, "one zero side"));
  EXPECT_TRUE(throwsProjective([&] { health.setImageSize(640, 480, -1.0); }, invalid, "non-negative"));
  EXPECT_TRUE(throwsProjective([&] { health.setImageSize(640, 480, 240.0); }, invalid, "leaves no pixel"));
  EXPECT_TRUE(throwsProjective([&] { health.setImageSize(640, 480, nan); }, nonFinite, "the border"));
  EXPECT_TRUE(throwsProjective([&] { health.setOutlierThreshold(-1.0); }, invalid, "0 disables"));
  EXPECT_TRUE(throwsProjective([&] { health.setOutlierThreshold(nan); }, nonFinite, "outlier threshold"));
  EXPECT_EQ(health.getImageWidth(), 640u);
  EXPECT_EQ(health.getImageHeight(), 480u);
  EXPECT_EQ(health.getImageBorder(), 3.0);
  EXPECT_EQ(health.getOutlierThreshold(), 4.0);
}
