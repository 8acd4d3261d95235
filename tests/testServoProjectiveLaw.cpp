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
  Tests of vpServoProjective's control law: e = s - s*, J = stacked eq. (46), qdot = -lambda J^+ e
  (vpMatrix::pseudoInverse) away from singularities, the documented damping mu^2 = mu_max^2 (1 - (sigma_min /
  sigma_0)^2) below sigma_0, the adaptive gain lambda(|e|_inf) of vpAdaptiveGain, the velocity saturation that keeps
  the direction; singular tasks (one marker used three times: rank 3; the Viper's wrist singularity q5 = 0: rank 5):
  damping at its maximum, a finite qdot bounded by lambda |e| / (2 mu), orthogonal to the null space of J; the
  task's velocity is vpServoDampedLeastSquares' on its J, e and gain, to the bit.
*/

#include <gtest/gtest.h>

#include "vpServoProjectiveTestTools.h"

using namespace vpProjectiveTest;

TEST_F(ServoProjectivePuma, ControlLawIsPseudoInverseAwayFromSingularities)
{
  const vpProjectiveStereoRig &rig = robot.getStereoRig();
  const std::vector<unsigned int> tracked = {0, 1, 2, 3, 4, 5, 6};
  for (int t = 0; t < 5; ++t) {
    vpColVector q, qStar;
    randomPair(s, 4, vpMath::rad(20.0), vpMath::rad(5.0), q, qStar);
    Task task(s, robot, tracked, q, qStar);
    task.task.setLambda(0.4);
    // e and J as documented.
    task.task.getControlLaw().setDamping(0.0, 0.0);
    const vpColVector qdot = task.task.computeControlLaw(q);
    const Eigen::VectorXd e = toEigenV(task.task.getError());
    const Eigen::MatrixXd J = toEigenX(task.task.getReport().getTaskJacobian());
    ASSERT_EQ(e.size(), 28);
    ASSERT_EQ(J.rows(), 28);
    ASSERT_EQ(J.cols(), 6);
    for (size_t k = 0; k < tracked.size(); ++k) {
      EXPECT_LT((e.segment<4>(4 * k) - toEigenV(task.s[k].error(task.sStar[k]))).norm(), 1e-15);
      const vpColVector M = rig.triangulate(task.s[k].getLeft(), task.s[k].getRight());
      const Eigen::MatrixXd Jk = toEigenX(robot.getImageJacobian(q, M));
      EXPECT_LT((J.middleRows(4 * k, 4) - Jk).norm() / Jk.norm(), 1e-9) << "marker " << k;
    }
    const Eigen::VectorXd sv = singularValues(J);
    EXPECT_NEAR(task.task.getReport().getConditionNumber(), sv(0) / sv(5), 1e-9 * sv(0) / sv(5));
    // qdot = -lambda J^+ e with ViSP's pseudo-inverse.
    const Eigen::VectorXd expected = -0.4 * toEigenX(task.task.getReport().getTaskJacobian().pseudoInverse()) * e;
    EXPECT_EQ(task.task.getReport().getDamping(), 0.0);
    EXPECT_DOUBLE_EQ(task.task.getReport().getLambda(), 0.4);
    EXPECT_FALSE(task.task.getReport().isSaturated());
    EXPECT_LT((toEigenV(qdot) - expected).norm() / expected.norm(), 1e-9);
    // Below sigma_0 the documented damping: mu^2 = mu_max^2 (1 - (sigma_min / sigma_0)^2).
    const double sigma0 = 2.0 * sv(5), muMax = 0.5 * sv(5);
    task.task.getControlLaw().setDamping(sigma0, muMax);
    const Eigen::VectorXd qdotDamped = toEigenV(task.task.computeControlLaw(q));
    const double mu2 = muMax * muMax * (1.0 - 0.25);
    EXPECT_NEAR(task.task.getReport().getDamping(), std::sqrt(mu2), 1e-9 * std::sqrt(mu2));
    const Eigen::MatrixXd A = J.transpose() * J + mu2 * Eigen::MatrixXd::Identity(6, 6);
    const Eigen::VectorXd dls = -0.4 * A.ldlt().solve(J.transpose() * e);
    EXPECT_LT((qdotDamped - dls).norm() / dls.norm(), 1e-9);
    EXPECT_LT(qdotDamped.norm(), toEigenV(qdot).norm()); // damping shortens the step
    // Just above sigma_min: no damping again.
    task.task.getControlLaw().setDamping(0.99 * sv(5), muMax);
    task.task.computeControlLaw(q);
    EXPECT_EQ(task.task.getReport().getDamping(), 0.0);
  }
}

TEST_F(ServoProjectivePuma, AdaptiveGain)
{
  const std::vector<unsigned int> tracked = {0, 1, 2, 3, 4, 5, 6};
  vpColVector qStar, qFar;
  randomPair(s, 5, vpMath::rad(15.0), vpMath::rad(10.0), qFar, qStar);
  const vpAdaptiveGain gain(2.0, 0.2, 0.05); // lambda(0) = 2, lambda(inf) = 0.2, slope 0.05 per pixel at 0
  double lambdaFar = 0.0, lambdaNear = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    const vpColVector q = pass == 0 ? qFar : qStar + 0.01 * (qFar - qStar);
    Task task(s, robot, tracked, q, qStar);
    task.task.getControlLaw().setDamping(0.0, 0.0);
    task.task.setLambda(gain);
    const Eigen::VectorXd qdot = toEigenV(task.task.computeControlLaw(q));
    const Eigen::VectorXd e = toEigenV(task.task.getError());
    const double expectedLambda = gain.value_const(e.cwiseAbs().maxCoeff());
    EXPECT_NEAR(task.task.getReport().getLambda(), expectedLambda, 1e-15);
    const Eigen::VectorXd expected =
        -expectedLambda * toEigenX(task.task.getReport().getTaskJacobian().pseudoInverse()) * e;
    EXPECT_LT((qdot - expected).norm() / expected.norm(), 1e-9);
    (pass == 0 ? lambdaFar : lambdaNear) = task.task.getReport().getLambda();
    // The three-value overload is the same gain.
    task.task.setLambda(2.0, 0.2, 0.05);
    EXPECT_LT((toEigenV(task.task.computeControlLaw(q)) - qdot).norm(), 1e-12 * qdot.norm());
  }
  testLog() << "[ measured ] adaptive gain " << lambdaFar << " far, " << lambdaNear << " near" << std::endl;
  EXPECT_LT(lambdaFar, lambdaNear);
  EXPECT_GT(lambdaNear, 1.0);
  EXPECT_LT(lambdaFar, 1.0);
}

TEST_F(ServoProjectivePuma, VelocitySaturationKeepsDirection)
{
  vpColVector q, qStar;
  randomPair(s, 6, vpMath::rad(20.0), vpMath::rad(15.0), q, qStar);
  Task task(s, robot, {0, 1, 2}, q, qStar);
  const Eigen::VectorXd free = toEigenV(task.task.computeControlLaw(q));
  EXPECT_FALSE(task.task.getReport().isSaturated());
  const double cap = 0.25 * free.cwiseAbs().maxCoeff();
  task.task.getControlLaw().setMaxJointVelocity(cap);
  const Eigen::VectorXd capped = toEigenV(task.task.computeControlLaw(q));
  EXPECT_TRUE(task.task.getReport().isSaturated());
  EXPECT_NEAR(capped.cwiseAbs().maxCoeff(), cap, 1e-15);
  EXPECT_LT((capped - 0.25 * free).norm(), 1e-12 * free.norm());
  // A cap above the step changes nothing.
  task.task.getControlLaw().setMaxJointVelocity(2.0 * free.cwiseAbs().maxCoeff());
  EXPECT_EQ(toEigenV(task.task.computeControlLaw(q)), free);
  EXPECT_FALSE(task.task.getReport().isSaturated());
}

TEST(ServoProjective, DampingKeepsSingularTasksFinite)
{
  const double muMax = 10.0, lambda = 0.5;
  auto check = [&](Task &task, const vpColVector &q, int expectedRank, const char *what) {
    task.task.setLambda(lambda);
    task.task.getControlLaw().setDamping(1.0, muMax);
    const Eigen::VectorXd qdot = toEigenV(task.task.computeControlLaw(q));
    const Eigen::VectorXd e = toEigenV(task.task.getError());
    const Eigen::MatrixXd J = toEigenX(task.task.getReport().getTaskJacobian());
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
    const Eigen::VectorXd sv = svd.singularValues();
    testLog() << "[ measured ] " << what << ": singular values " << sv.transpose() << ", damping "
              << task.task.getReport().getDamping() << ", |qdot| " << qdot.norm() << std::endl;
    // Rank deficient: sigma_min ~ 0, so mu = mu_max.
    EXPECT_LT(sv(expectedRank) / sv(0), 1e-9) << what;
    EXPECT_GT(sv(expectedRank - 1) / sv(0), 1e-4) << what;
    EXPECT_GT(task.task.getReport().getConditionNumber(), 1e9) << what;
    EXPECT_NEAR(task.task.getReport().getDamping(), muMax, 1e-6) << what;
    ASSERT_TRUE(qdot.allFinite()) << what;
    // |(J^T J + mu^2 I)^-1 J^T e| <= |e| / (2 mu), and the step lies in the row space of J.
    EXPECT_LE(qdot.norm(), lambda * e.norm() / (2.0 * task.task.getReport().getDamping()) * (1.0 + 1e-9)) << what;
    const Eigen::MatrixXd N = svd.matrixV().rightCols(6 - expectedRank);
    EXPECT_LT((N.transpose() * qdot).norm(), 1e-9 * qdot.norm()) << what;
    const double mu2 = task.task.getReport().getDamping() * task.task.getReport().getDamping();
    const Eigen::VectorXd dls =
        -lambda * (J.transpose() * J + mu2 * Eigen::MatrixXd::Identity(6, 6)).ldlt().solve(J.transpose() * e);
    EXPECT_LT((qdot - dls).norm(), 1e-9 * dls.norm()) << what;
    // The error still decreases to first order: e^T J qdot < 0.
    EXPECT_LT(e.dot(J * qdot), 0.0) << what;
  };

  // One marker used three times: 12 rows of rank 3.
  const ArmSetup puma = pumaEyeToHand();
  const vpProjectiveRobot pumaRobot = calibratedRobot(puma);
  vpColVector q, qStar;
  randomPair(puma, 7, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task repeated(puma, pumaRobot, {0, 0, 0}, q, qStar);
  check(repeated, q, 3, "marker 0 three times");

  // The Viper850's wrist singularity: arm joint 5 (index 4) at 0 aligns joints 4 and 6 (rank 5 for any features).
  const ArmSetup viper = viperEyeToHand();
  const vpProjectiveRobot viperRobot = calibratedRobot(viper);
  vpColVector qSingular(6, 0.0);
  qSingular[4] = -viper.qRef[4];
  vpColVector qTarget = qSingular;
  qTarget[0] = vpMath::rad(2.0);
  qTarget[3] = vpMath::rad(5.0);
  Task wrist(viper, viperRobot, {0, 1, 2, 3, 4, 5, 6}, qSingular, qTarget);
  check(wrist, qSingular, 5, "Viper850 wrist singularity");
  // Without damping, the same step is not bounded by the error: near the singularity it explodes.
  vpColVector qNear = qSingular;
  qNear[4] += vpMath::rad(0.01);
  Task nearTask(viper, viperRobot, {0, 1, 2, 3, 4, 5, 6}, qNear, qTarget);
  nearTask.task.setLambda(lambda);
  nearTask.task.getControlLaw().setDamping(1.0, muMax);
  const double damped = toEigenV(nearTask.task.computeControlLaw(qNear)).norm();
  EXPECT_GT(nearTask.task.getReport().getDamping(), 0.9 * muMax);
  nearTask.task.getControlLaw().setDamping(0.0, 0.0);
  const double undamped = toEigenV(nearTask.task.computeControlLaw(qNear)).norm();
  testLog() << "[ measured ] 0.01 deg from the wrist singularity: |qdot| " << damped << " damped, " << undamped
            << " undamped" << std::endl;
  EXPECT_GT(undamped, 100.0 * damped);
}

TEST_F(ServoProjectivePuma, ItsVelocityIsTheDampedLeastSquaresLawOfItsTask)
{
  // The task's velocity is vpServoDampedLeastSquares::computeVelocity() on getTaskJacobian(), getError() and
  // getLambda() with the task's settings (getDampedLeastSquares()), to the bit: undamped, damped and saturated.
  for (int p = 0; p < 3; ++p) {
    vpColVector q, qStar;
    randomPair(s, 81, vpMath::rad(20.0), vpMath::rad(15.0), q, qStar);
    Task t(s, robot, {0, 1, 2, 3}, q, qStar);
    t.task.setLambda(2.0, 0.2, 0.05);
    for (int c = 0; c < 3; ++c) {
      t.task.getControlLaw().setDamping(c == 0 ? 0.0 : 1e3, 50.0);
      t.task.getControlLaw().setMaxJointVelocity(c == 2 ? vpMath::rad(1.0) : 0.0);
      const Eigen::VectorXd qdot = toEigenV(t.task.computeControlLaw(q));
      vpServoDampedLeastSquares law = t.task.getControlLaw().getDampedLeastSquares();
      const Eigen::VectorXd expected = toEigenV(
          law.computeVelocity(t.task.getReport().getTaskJacobian(), t.task.getError(), t.task.getReport().getLambda()));
      EXPECT_EQ(qdot, expected) << "pair " << p << ", case " << c;
      EXPECT_EQ(t.task.getReport().getDamping(), law.getDamping());
      EXPECT_EQ(t.task.getReport().isSaturated(), law.isSaturated());
      EXPECT_EQ(t.task.getReport().getDamping() > 0.0, c > 0);
      EXPECT_EQ(t.task.getReport().isSaturated(), c == 2);
    }
  }
}
