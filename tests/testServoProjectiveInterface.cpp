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
  Tests of vpServoProjective's interface: the Eigen overload and the feature references; misuse throws a
  vpProjectiveException with a meaningful code and message (the law's and the robustness checks' settings); print(),
  the number of features, getTaskSingularValues() (an SVD's) and setPseudoInverseThreshold() (the projector I - J^+ J of
  the large projection operator only); a call that throws leaves every getter and memory as it was; the const getters
  write nothing and agree when two threads call them.
*/

#include <gtest/gtest.h>

#include "vpServoProjectiveTestTools.h"

using namespace vpProjectiveTest;

TEST_F(ServoProjectivePuma, EigenOverloadAndFeatureReferences)
{
  vpColVector q, qStar;
  randomPair(s, 8, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task task(s, robot, {0, 1, 2}, q, qStar);
  EXPECT_EQ(task.task.getFeatureHealth().getNumberOfFeatures(), 3u);
  const vpColVector qdot = task.task.computeControlLaw(q);
  vpProjectiveRobot::JointVector qe(6), qdotE(6);
  for (unsigned int i = 0; i < 6; ++i) {
    qe(i) = q[i];
  }
  task.task.computeControlLaw(qe, qdotE);
  EXPECT_EQ(Eigen::VectorXd(qdotE), toEigenV(qdot));
  // The task reads the features it was given, by reference: at the target the error and the velocity vanish.
  setFeatures(s, qStar, {0, 1, 2}, task.s);
  const vpColVector atTarget = task.task.computeControlLaw(qStar);
  EXPECT_EQ(task.task.getError().frobeniusNorm(), 0.0);
  EXPECT_EQ(atTarget.frobeniusNorm(), 0.0);
  task.task.clearFeatures();
  EXPECT_EQ(task.task.getFeatureHealth().getNumberOfFeatures(), 0u);
  EXPECT_TRUE(throwsProjective([&] { task.task.computeControlLaw(q); }, vpProjectiveException::notInitializedError,
                               "addFeature"));
}

TEST_F(ServoProjectivePuma, BadInputsThrow)
{
  const int notInit = vpProjectiveException::notInitializedError;
  const int invalid = vpProjectiveException::invalidValueError;
  const int nonFinite = vpProjectiveException::nonFiniteValueError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vpColVector q(6, 0.0);
  std::vector<vpFeatureStereoPoint> f(3), fStar(3);
  setFeatures(s, q, {0, 1, 2}, f);
  setFeatures(s, q, {0, 1, 2}, fStar);

  vpServoProjective task;
  // No robot, then a robot without a model.
  task.addFeature(f[0], fStar[0]);
  EXPECT_TRUE(throwsProjective([&] { task.computeControlLaw(q); }, notInit, "setRobot"));
  const vpProjectiveRobot uncalibrated(s.jointTypes());
  EXPECT_TRUE(throwsProjective([&] { task.setRobot(uncalibrated); }, notInit, "calibrate"));
  // No features.
  vpServoProjective noFeatures;
  noFeatures.setRobot(robot);
  EXPECT_TRUE(throwsProjective([&] { noFeatures.computeControlLaw(q); }, notInit, "addFeature"));
  // Too few features: one stereo point gives 4 equations for 6 joints.
  task.setRobot(robot);
  EXPECT_TRUE(throwsProjective([&] { task.computeControlLaw(q); }, vpProjectiveException::notEnoughPointsError,
                               "add features"));
  task.addFeature(f[1], fStar[1]);
  EXPECT_NO_THROW(task.computeControlLaw(q)); // 8 equations for 6 joints
  // Wrong q size, non-finite q (both overloads).
  EXPECT_TRUE(throwsProjective([&] { task.computeControlLaw(vpColVector(5, 0.0)); },
                               vpProjectiveException::dimensionError, "q must have 6"));
  vpProjectiveRobot::JointVector qe(7), qdot(7);
  qe.setZero();
  EXPECT_TRUE(throwsProjective([&] { task.computeControlLaw(qe, qdot); }, vpProjectiveException::dimensionError,
                               "q must have 6"));
  vpColVector qNaN = q;
  qNaN[2] = nan;
  EXPECT_TRUE(throwsProjective([&] { task.computeControlLaw(qNaN); }, nonFinite, "NaN"));
  // Gains, damping, saturation.
  EXPECT_TRUE(throwsProjective([&] { task.setLambda(-0.5); }, invalid, "positive"));
  EXPECT_TRUE(throwsProjective([&] { task.setLambda(0.0); }, invalid, "positive"));
  EXPECT_TRUE(throwsProjective([&] { task.setLambda(nan); }, nonFinite, "gain"));
  EXPECT_TRUE(throwsProjective([&] { task.setLambda(0.1, 1.0, 3.0); }, invalid, "gainAtZero"));
  EXPECT_TRUE(throwsProjective([&] { task.setLambda(1.0, 0.1, -3.0); }, invalid, "slope"));
  EXPECT_TRUE(throwsProjective([&] { task.getControlLaw().setDamping(-1.0, 1.0); }, invalid, "non-negative"));
  EXPECT_TRUE(throwsProjective([&] { task.getControlLaw().setDamping(1.0, nan); }, nonFinite, "damping"));
  EXPECT_TRUE(throwsProjective([&] { task.getControlLaw().setMaxJointVelocity(-1.0); }, invalid, "positive"));
  EXPECT_TRUE(throwsProjective([&] { task.getControlLaw().setMaxJointVelocity(nan); }, nonFinite, "velocity"));
}

TEST_F(ServoProjectivePuma, BadRobustnessInputsThrow)
{
  const int dim = vpProjectiveException::dimensionError;
  const int invalid = vpProjectiveException::invalidValueError;
  const int nonFinite = vpProjectiveException::nonFiniteValueError;
  const int notInit = vpProjectiveException::notInitializedError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const vpColVector q(6, 0.0);
  Task t(s, robot, {0, 1, 2}, q, q);
  vpServoProjective &task = t.task;
  // Feature indices.
  EXPECT_TRUE(throwsProjective([&] { task.setFeatureTracked(3, false); }, dim, "feature index 3 is out of range"));
  EXPECT_TRUE(throwsProjective([&] { task.getFeatureHealth().isFeatureTracked(3); }, dim, "the task has 3 features"));
  EXPECT_TRUE(throwsProjective([&] { task.getReport().getFeatureState(7); }, dim, "feature index 7"));
  EXPECT_TRUE(throwsProjective([&] { task.getFeatureHealth().getEpipolarDistance(3); }, dim, "out of range"));
  EXPECT_TRUE(throwsProjective([&] { task.getFeatureHealth().getPredictionDistance(3); }, dim, "out of range"));
  // Image size.
  EXPECT_TRUE(throwsProjective([&] { task.setImageSize(640, 0); }, invalid, "one zero side"));
  EXPECT_TRUE(throwsProjective([&] { task.setImageSize(0, 480); }, invalid, "one zero side"));
  EXPECT_TRUE(throwsProjective([&] { task.setImageSize(640, 480, -1.0); }, invalid, "border must be non-negative"));
  EXPECT_TRUE(throwsProjective([&] { task.setImageSize(640, 480, nan); }, nonFinite, "the border"));
  EXPECT_TRUE(throwsProjective([&] { task.setImageSize(640, 480, 240.0); }, invalid, "leaves no pixel"));
  EXPECT_NO_THROW(task.setImageSize(640, 480, 239.5));
  EXPECT_NO_THROW(task.setImageSize(0, 0));
  // Outlier threshold, rank tolerance, large projection thresholds.
  EXPECT_TRUE(
      throwsProjective([&] { task.getFeatureHealth().setOutlierThreshold(-1.0); }, invalid, "must be non-negative"));
  EXPECT_TRUE(
      throwsProjective([&] { task.getFeatureHealth().setOutlierThreshold(nan); }, nonFinite, "outlier threshold"));
  EXPECT_NO_THROW(task.getFeatureHealth().setOutlierThreshold(0.0));
  EXPECT_TRUE(throwsProjective([&] { task.getFeatureHealth().setRankTolerance(0.0); }, invalid, "(0, 1)"));
  EXPECT_TRUE(throwsProjective([&] { task.getFeatureHealth().setRankTolerance(1.0); }, invalid, "(0, 1)"));
  EXPECT_TRUE(throwsProjective([&] { task.getFeatureHealth().setRankTolerance(nan); }, nonFinite, "rank tolerance"));
  EXPECT_TRUE(
      throwsProjective([&] { task.getControlLaw().getJointLimitAvoidance().setLargeProjectionThresholds(0.7, 0.1); },
                       invalid, "0 <= e0 < e1"));
  EXPECT_TRUE(
      throwsProjective([&] { task.getControlLaw().getJointLimitAvoidance().setLargeProjectionThresholds(-1.0, 1.0); },
                       invalid, "0 <= e0 < e1"));
  EXPECT_TRUE(throwsProjective(
      [&] { task.getControlLaw().getJointLimitAvoidance().setLargeProjectionThresholds(0.1, nan); }, nonFinite, "e1"));
  // Joint limits.
  const vpColVector lo(6, -1.0), hi(6, 1.0);
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(vpColVector(5, -1.0), hi); }, dim, "qmin has 5 entries"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(vpColVector(5, -1.0), vpColVector(5, 1.0)); }, dim,
                               "the robot has 6 joints"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(vpColVector(), vpColVector()); }, dim, "0 entries"));
  vpColVector bad = hi;
  bad[2] = -1.0;
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, bad); }, invalid, "joint 2: qmin (-1) must be below"));
  bad[2] = -2.0;
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, bad); }, invalid, "joint 2"));
  bad[2] = nan;
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, bad); }, nonFinite, "qmax"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, 0.0); }, invalid, "rho must be in (0, 1/2]"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, 0.6); }, invalid, "rho must be in (0, 1/2]"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, 1.5); }, invalid, "rho must be in (0, 1/2]"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, nan); }, nonFinite, "rho"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, 0.1, 0.0); }, invalid, "rho1 must be in (0, 1]"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, 0.1, 1.5); }, invalid, "rho1"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, 0.1, 0.3, -0.1); }, invalid, "lambdaTune"));
  EXPECT_TRUE(throwsProjective([&] { task.setJointLimits(lo, hi, 0.1, 0.3, 1.1); }, invalid, "lambdaTune"));
  EXPECT_FALSE(task.getControlLaw().getJointLimitAvoidance().hasJointLimits()); // nothing was set by the failed calls
  EXPECT_NO_THROW(task.setJointLimits(lo, hi, 0.5, 1.0, 0.0));
  EXPECT_TRUE(task.getControlLaw().getJointLimitAvoidance().hasJointLimits());
  task.getControlLaw().getJointLimitAvoidance().clearJointLimits();
  EXPECT_FALSE(task.getControlLaw().getJointLimitAvoidance().hasJointLimits());
  // Joint limits given before the robot, of the wrong size: caught by computeControlLaw().
  vpServoProjective early;
  std::vector<vpFeatureStereoPoint> f(2), fStar(2);
  setFeatures(s, q, {0, 1}, f);
  setFeatures(s, q, {0, 1}, fStar);
  early.addFeature(f[0], fStar[0]);
  early.addFeature(f[1], fStar[1]);
  EXPECT_NO_THROW(early.setJointLimits(vpColVector(5, -1.0), vpColVector(5, 1.0)));
  early.setRobot(robot);
  EXPECT_TRUE(
      throwsProjective([&] { early.getReport().getLargeProjectionOperator(); }, notInit, "computeControlLaw() first"));
  EXPECT_TRUE(throwsProjective([&] { early.computeControlLaw(q); }, dim, "the joint limits have 5 entries"));
}

TEST_F(ServoProjectivePuma, PrintDimensionSingularValuesAndPseudoInverseThreshold)
{
  vpColVector q, qStar;
  randomPair(s, 82, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task t(s, robot, {0, 1, 2}, q, qStar);
  configure(t.task);
  EXPECT_EQ(t.task.getFeatureHealth().getNumberOfFeatures(), 3u);
  EXPECT_EQ(t.task.getReport().getTaskSingularValues().size(), 0u);
  std::ostringstream before;
  t.task.print(before);
  EXPECT_NE(before.str().find("3 stereo points"), std::string::npos) << before.str();
  EXPECT_NE(before.str().find("task dimension 12"), std::string::npos) << before.str();
  EXPECT_NE(before.str().find("No computeControlLaw() yet"), std::string::npos) << before.str();

  t.task.setFeatureTracked(1, false);
  t.task.setImageSize(s.width, s.height, 5.0);
  t.task.setJointLimits(vpColVector(6, -M_PI), vpColVector(6, M_PI));
  const Eigen::VectorXd qdot = toEigenV(t.task.computeControlLaw(q));
  // Singular values of the last J (here with feature 1's rows zero), decreasing, as an SVD gives them.
  const Eigen::VectorXd sv = toEigenV(t.task.getReport().getTaskSingularValues());
  const Eigen::VectorXd expected = singularValues(toEigenX(t.task.getReport().getTaskJacobian()));
  ASSERT_EQ(sv.size(), 6);
  EXPECT_LT((sv - expected).norm(), 1e-12 * expected(0));
  EXPECT_LT(sv(5), 1e-9 * sv(0)); // 2 markers: rank 5
  std::ostringstream after;
  t.task.print(after);
  for (const char *word : {"SERVO_STOPPED", "1: s = (", "not tracked", "|e| = ", "sigma_0 1, mu_max 10",
                           "image window 640 x 480, border 5 px", "outlier threshold off", "qmin (-3.14159",
                           "pseudo-inverse threshold 1e-06", "2 active at the last computeControlLaw()"}) {
    EXPECT_NE(after.str().find(word), std::string::npos) << "no \"" << word << "\" in\n" << after.str();
  }
  EXPECT_TRUE(allZero(qdot)); // 2 markers: stopped

  // The pseudo-inverse threshold changes the projector I - J^+ J of the large projection operator, not the law:
  // below e0 (here ||e|| < e0 = 1e3 px) P = I - J^+ J, 0 for a full-rank J; at a threshold above sigma_min / sigma_max
  // the right singular vector of sigma_min counts as a null direction.
  t.task.setFeatureTracked(1, true);
  t.task.getControlLaw().getJointLimitAvoidance().setLargeProjectionThresholds(1e3, 2e3);
  const Eigen::VectorXd qdotDefault = toEigenV(t.task.computeControlLaw(q));
  EXPECT_EQ(toEigenX(t.task.getReport().getLargeProjectionOperator()).norm(), 0.0);
  const Eigen::MatrixXd J = toEigenX(t.task.getReport().getTaskJacobian());
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
  const double ratio = svd.singularValues()(5) / svd.singularValues()(0);
  EXPECT_LT((toEigenV(t.task.getReport().getTaskSingularValues()) - svd.singularValues()).norm(),
            1e-12 * svd.singularValues()(0));
  EXPECT_NEAR(t.task.getReport().getConditionNumber(), 1.0 / ratio, 1e-6 / ratio);
  t.task.getControlLaw().setPseudoInverseThreshold(1.5 * ratio);
  EXPECT_EQ(t.task.getControlLaw().getDampedLeastSquares().getPseudoInverseThreshold(), 1.5 * ratio);
  EXPECT_EQ(toEigenV(t.task.computeControlLaw(q)), qdotDefault);
  const Eigen::VectorXd v = svd.matrixV().col(5);
  EXPECT_LT((toEigenX(t.task.getReport().getLargeProjectionOperator()) - v * v.transpose()).norm(), 1e-6);
  EXPECT_TRUE(throwsProjective([&] { t.task.getControlLaw().setPseudoInverseThreshold(1.0); },
                               vpProjectiveException::invalidValueError, "[0, 1)"));
  EXPECT_TRUE(throwsProjective(
      [&] { t.task.getControlLaw().setPseudoInverseThreshold(std::numeric_limits<double>::quiet_NaN()); },
      vpProjectiveException::nonFiniteValueError, "pseudo-inverse threshold"));
  EXPECT_EQ(t.task.getControlLaw().getDampedLeastSquares().getPseudoInverseThreshold(), 1.5 * ratio);
}

TEST_F(ServoProjectivePuma, AFailedCallLeavesTheTaskAsItWas)
{
  // Feature 2, set aside at the first call (so that it has no prediction yet), comes back with its right image
  // 1e15 px along its epipolar line: it passes the epipolar test, and its triangulated point lies on the right
  // camera's focal plane, so computeControlLaw() throws. Every getter then reports the first call, and the next
  // call computes what a twin task that never saw the failure computes, to the bit (memories included).
  const Eigen::Matrix3d F = toEigen<3, 3>(robot.getStereoRig().getFundamentalMatrix());
  vpColVector q, qStar;
  randomPair(s, 83, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  const std::vector<unsigned int> tracked = {0, 1, 2, 3};
  Task failing(s, robot, tracked, q, qStar), twin(s, robot, tracked, q, qStar);
  for (Task *t : {&failing, &twin}) {
    configure(t->task);
    t->task.getFeatureHealth().setOutlierThreshold(5.0);
    t->task.setJointLimits(vpColVector(6, -M_PI), vpColVector(6, M_PI));
    t->task.setFeatureTracked(2, false);
    t->task.computeControlLaw(q);
  }
  const Eigen::VectorXd e = toEigenV(failing.task.getError());
  const Eigen::MatrixXd J = toEigenX(failing.task.getReport().getTaskJacobian());
  const double condition = failing.task.getReport().getConditionNumber(),
               ratio = failing.task.getReport().getSingularValueRatio();
  const double damping = failing.task.getReport().getDamping(), lambda = failing.task.getReport().getLambda();
  ASSERT_EQ(failing.task.getStatus(), vpServoProjective::SERVO_REDUCED);

  const Eigen::Vector4d m = failing.s[2].getFeature();
  const Eigen::Vector3d lp = F * Eigen::Vector3d(m(0), m(1), 1.0);
  const Eigen::Vector2d along = Eigen::Vector2d(lp(1), -lp(0)).normalized();
  failing.s[2].setRaw(m(0), m(1), m(2) + 1e15 * along(0), m(3) + 1e15 * along(1));
  failing.task.setFeatureTracked(2, true);
  EXPECT_TRUE(throwsProjective([&] { failing.task.computeControlLaw(q); }, vpProjectiveException::pointAtInfinityError,
                               "feature 2 triangulates onto"));
  EXPECT_EQ(toEigenV(failing.task.getError()), e);
  EXPECT_EQ(toEigenX(failing.task.getReport().getTaskJacobian()), J);
  EXPECT_EQ(failing.task.getStatus(), vpServoProjective::SERVO_REDUCED);
  EXPECT_EQ(failing.task.getReport().getFeatureState(2), vpServoProjective::FEATURE_NOT_TRACKED);
  EXPECT_EQ(failing.task.getFeatureHealth().getNumberOfActiveFeatures(), 3u);
  EXPECT_EQ(failing.task.getReport().getConditionNumber(), condition);
  EXPECT_EQ(failing.task.getReport().getSingularValueRatio(), ratio);
  EXPECT_EQ(failing.task.getReport().getDamping(), damping);
  EXPECT_EQ(failing.task.getReport().getLambda(), lambda);
  for (unsigned int k = 0; k < 4; ++k) {
    EXPECT_EQ(failing.task.getFeatureHealth().getEpipolarDistance(k),
              twin.task.getFeatureHealth().getEpipolarDistance(k));
    EXPECT_EQ(failing.task.getFeatureHealth().getPredictionDistance(k),
              twin.task.getFeatureHealth().getPredictionDistance(k));
  }

  // The next call, from the true images one step further.
  failing.s[2].setRaw(m(0), m(1), m(2), m(3));
  twin.task.setFeatureTracked(2, true);
  const vpColVector qNext = s.arm.integrate(s.armJoints(q), twin.task.computeControlLaw(q), 1.0) - s.qRef;
  failing.task.computeControlLaw(q); // as the twin: the first call after the failure, at q
  setFeatures(s, qNext, tracked, failing.s);
  setFeatures(s, qNext, tracked, twin.s);
  EXPECT_EQ(toEigenV(failing.task.computeControlLaw(qNext)), toEigenV(twin.task.computeControlLaw(qNext)));
  for (unsigned int k = 0; k < 4; ++k) {
    EXPECT_EQ(failing.task.getReport().getFeatureState(k), vpServoProjective::FEATURE_ACTIVE);
    EXPECT_GE(failing.task.getFeatureHealth().getPredictionDistance(k), 0.0);
    EXPECT_EQ(failing.task.getFeatureHealth().getPredictionDistance(k),
              twin.task.getFeatureHealth().getPredictionDistance(k))
        << "feature " << k;
  }
}

TEST_F(ServoProjectivePuma, ConstGettersWriteNothingAndCanBeSharedByThreads)
{
  // The getters that used to fill caches compute on demand: called from two threads at once they agree with the
  // values read before, to the bit (run under ThreadSanitizer, this is also a race check).
  vpColVector q, qStar;
  randomPair(s, 84, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task t(s, robot, {0, 1, 2, 3}, q, qStar);
  configure(t.task);
  t.task.setFeatureTracked(3, false);
  t.task.computeControlLaw(q);
  const vpServoProjective &task = t.task;
  const double condition = task.getReport().getConditionNumber(), ratio = task.getReport().getSingularValueRatio();
  const Eigen::MatrixXd P = toEigenX(task.getReport().getLargeProjectionOperator());
  const Eigen::VectorXd sv = toEigenV(task.getReport().getTaskSingularValues());
  bool agree[2] = {true, true};
  auto reader = [&](int k) {
    for (int it = 0; it < 200; ++it) {
      agree[k] = agree[k] && task.getReport().getConditionNumber() == condition &&
                 task.getReport().getSingularValueRatio() == ratio &&
                 toEigenX(task.getReport().getLargeProjectionOperator()) == P &&
                 toEigenV(task.getReport().getTaskSingularValues()) == sv;
    }
  };
  std::thread a(reader, 0), b(reader, 1);
  a.join();
  b.join();
  EXPECT_TRUE(agree[0]);
  EXPECT_TRUE(agree[1]);
}

TEST_F(ServoProjectivePuma, ReportIsTheLastSuccessfulCallWithItsSettings)
{
  vpColVector q, qStar;
  randomPair(s, 22, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task t(s, robot, {0, 1, 2, 3}, q, qStar);
  // Before the first call: running, every feature active, nothing computed.
  const vpServoProjectiveReport &report = t.task.getReport();
  EXPECT_EQ(report.getStatus(), vpServoProjectiveReport::SERVO_RUNNING);
  EXPECT_EQ(report.getNumberOfFeatures(), 4u);
  EXPECT_EQ(report.getFeatureState(3), vpServoProjective::FEATURE_ACTIVE);
  EXPECT_TRUE(
      throwsProjective([&] { report.getFeatureState(4); }, vpProjectiveException::dimensionError, "4 features"));
  EXPECT_EQ(report.getTaskSingularValues().size(), 0u);

  t.task.computeControlLaw(q);
  const vpServoProjectiveReport &after = t.task.getReport();
  EXPECT_EQ(after.getStatus(), t.task.getStatus());
  EXPECT_EQ(toEigenV(after.getError()), toEigenV(t.task.getError()));
  EXPECT_EQ(after.getNumberOfActiveFeatures(), 4u);
  EXPECT_EQ(after.getTaskJacobian().getRows(), 16u);
  EXPECT_EQ(after.getTaskJacobian().getCols(), 6u);
  // P is the call's: thresholds changed afterwards do not change it, the next call does.
  const Eigen::MatrixXd P = toEigenX(after.getLargeProjectionOperator());
  t.task.getControlLaw().getJointLimitAvoidance().setLargeProjectionThresholds(
      1e6,
      2e6); // ||e|| below e0: I - J^+ J from the next call on
  EXPECT_EQ(toEigenX(t.task.getReport().getLargeProjectionOperator()), P);
  // A copy is a snapshot; a call that throws changes nothing.
  const vpServoProjectiveReport snapshot = t.task.getReport();
  EXPECT_THROW(t.task.computeControlLaw(vpColVector(5, 0.0)), vpProjectiveException);
  EXPECT_EQ(toEigenV(t.task.getReport().getError()), toEigenV(snapshot.getError()));
  t.task.computeControlLaw(q);
  EXPECT_GT((toEigenX(t.task.getReport().getLargeProjectionOperator()) - P).norm(), 1e-3);
  EXPECT_EQ(toEigenX(snapshot.getLargeProjectionOperator()), P);
  // The arm-following check is not copied at each call: the task's report reads the task's, a copy keeps its own,
  // after the task is gone too.
  const unsigned int calls = t.task.getArmFollowing().getConsecutiveCalls();
  vpServoProjectiveReport kept;
  {
    vpServoProjective other(t.task);
    other.computeControlLaw(q);
    kept = other.getReport();
    other.getArmFollowing().setConsecutiveCalls(calls + 5);
    EXPECT_EQ(other.getReport().getArmFollowing().getConsecutiveCalls(), calls + 5);
  }
  t.task.getArmFollowing().setConsecutiveCalls(calls + 1);
  EXPECT_EQ(t.task.getReport().getArmFollowing().getConsecutiveCalls(), calls + 1);
  EXPECT_EQ(snapshot.getArmFollowing().getConsecutiveCalls(), calls);
  EXPECT_EQ(kept.getArmFollowing().getConsecutiveCalls(), calls);
  EXPECT_EQ(kept.getStatus(), t.task.getStatus());
}
