/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

/*
  Tests of vpServoProjective, the non-metric stereo servo of eq. (47), with models acquired noise-free from the
  metric simulator (vpProjectiveArmTestTools.h):
  - closed-loop convergence: 10 random start/target pairs (target within +-20 deg of the zero reference, start within
    +-15 deg of the target, markers in view at both ends) for the PUMA and for the Viper850 with markers 0-2, and 10
    small pairs (+-3 deg, +-2 deg) eye-in-hand with all 7 markers, all reach an RMS image error below 1e-6 px within
    200 iterations, and the joints reach the target's;
  - the control law: e = s - s*, J = stacked eq. (46), qdot = -lambda J^+ e (vpMatrix::pseudoInverse) away from
    singularities, the documented damping mu^2 = mu_max^2 (1 - (sigma_min / sigma_0)^2) below sigma_0, the adaptive
    gain lambda(|e|_inf) of vpAdaptiveGain, the velocity saturation that keeps the direction;
  - singular tasks (one marker used three times: rank 3; the Viper's wrist singularity q5 = 0: rank 5): damping at its
    maximum, a finite qdot bounded by lambda |e| / (2 mu), orthogonal to the null space of J;
  - misuse throws a vpProjectiveException with a meaningful code and message.

  Settings of the convergence tests: lambda = 0.5, dt = 1, damping (sigma_0, mu_max) = (1, 10) px/rad, saturation
  10 deg per step. Measured: 24-36 iterations for all 20 pairs. With the library's default damping (30, 30) the same
  pairs need up to 223 iterations or stall (2 of 10 PUMA and 4 of 10 Viper pairs above 300 iterations): three tracked
  markers 8 cm apart seen from 1 m give sigma_min of 1 to 50 px/rad in healthy configurations, so the default
  threshold damps the last, small steps too (reported to the maintainers). Without damping and saturation one Viper
  pair crosses a near-singularity (condition 2700) and ends in another local minimum.
  Bounds: noise free, qdot must match the closed forms to rounding (1e-9 relative); the final joint error is bounded
  by the image error over sigma_min: 3.5e-6 px / 0.9 px/rad < 1e-5 rad. Every random number is seeded.
*/

#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/vs/vpAdaptiveGain.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
vpProjectiveRobot calibratedRobot(const ArmSetup &s)
{
  vpProjectiveRobot robot(s.jointTypes());
  vpGaussRand noise(1.0, 0.0, 1);
  EXPECT_TRUE(s.acquire(robot, 0.0, noise)) << s.name;
  robot.calibrate();
  return robot;
}

//! Noise-free features of the markers \e tracked at model joints q.
void setFeatures(const ArmSetup &s, const vpColVector &q, const std::vector<unsigned int> &tracked,
                 std::vector<vpFeatureStereoPoint> &features)
{
  for (size_t k = 0; k < tracked.size(); ++k) {
    const Eigen::Vector4d sk = s.imageOf(s.armJoints(q), tracked[k]);
    features[k].buildFrom(sk(0), sk(1), sk(2), sk(3));
  }
}

//! A task on \e tracked markers, current features at q, desired ones at qStar.
struct Task {
  std::vector<vpFeatureStereoPoint> s, sStar;
  vpServoProjective task;

  Task(const ArmSetup &setup, const vpProjectiveRobot &robot, const std::vector<unsigned int> &tracked,
       const vpColVector &q, const vpColVector &qStar)
      : s(tracked.size()), sStar(tracked.size()), task()
  {
    setFeatures(setup, qStar, tracked, sStar);
    setFeatures(setup, q, tracked, s);
    task.setRobot(robot);
    for (size_t k = 0; k < tracked.size(); ++k) {
      task.addFeature(s[k], sStar[k]);
    }
  }
};

Eigen::VectorXd singularValues(const Eigen::MatrixXd &J)
{
  return Eigen::JacobiSVD<Eigen::MatrixXd>(J).singularValues();
}

//! A pair (start, target) of model joints: target within +-targetRange, start within +-startRange of it, both in view.
void randomPair(const ArmSetup &s, vpUniRand &rng, double targetRange, double startRange, vpColVector &qStart,
                vpColVector &qTarget)
{
  for (int attempt = 0; attempt < 100000; ++attempt) {
    qTarget.resize(s.n());
    for (unsigned int i = 0; i < s.n(); ++i) {
      qTarget[i] = rng.uniform(-targetRange, targetRange);
    }
    qStart = qTarget;
    for (unsigned int i = 0; i < s.n(); ++i) {
      qStart[i] += rng.uniform(-startRange, startRange);
    }
    if (s.visible(s.armJoints(qTarget)) && s.visible(s.armJoints(qStart))) {
      return;
    }
  }
  ADD_FAILURE() << s.name << ": no start/target pair in view";
}

//! Runs the loop; returns the iterations to reach rmsGoal (or maxIterations + 1) and leaves q at the end.
int servo(const ArmSetup &s, const vpProjectiveRobot &robot, const std::vector<unsigned int> &tracked, vpColVector &q,
          const vpColVector &qTarget, double rmsGoal, int maxIterations, double sigma0, double &rms)
{
  Task t(s, robot, tracked, q, qTarget);
  t.task.setLambda(0.5);
  t.task.setDamping(sigma0, 10.0);
  t.task.setMaxJointVelocity(vpMath::rad(10.0));
  for (int it = 0; it <= maxIterations; ++it) {
    setFeatures(s, q, tracked, t.s); // the tracker: images of the true arm
    const vpColVector qdot = t.task.computeControlLaw(q);
    rms = t.task.getError().frobeniusNorm() / std::sqrt(static_cast<double>(4 * tracked.size()));
    if (rms < rmsGoal) {
      return it;
    }
    q = s.arm.integrate(s.armJoints(q), qdot, 1.0) - s.qRef;
  }
  return maxIterations + 1;
}

void expectConvergence(const ArmSetup &s, long seed, int pairs, double targetRange, double startRange,
                       double sigma0 = 1.0, const std::vector<unsigned int> &tracked = {0, 1, 2})
{
  const vpProjectiveRobot robot = calibratedRobot(s);
  vpUniRand rng(seed);
  int worst = 0;
  for (int p = 0; p < pairs; ++p) {
    vpColVector qStart, qTarget;
    randomPair(s, rng, targetRange, startRange, qStart, qTarget);
    vpColVector q = qStart;
    double rms = 0.0;
    const int iterations = servo(s, robot, tracked, q, qTarget, 1e-6, 200, sigma0, rms);
    worst = std::max(worst, iterations);
    EXPECT_LE(iterations, 200) << s.name << " pair " << p << ": RMS " << rms << " px";
    EXPECT_LT((toEigenV(q) - toEigenV(qTarget)).cwiseAbs().maxCoeff(), 1e-5) << s.name << " pair " << p;
    std::cout << "[ measured ] " << s.name << " pair " << p << ": " << iterations << " iterations, start error "
              << vpMath::deg((toEigenV(qStart) - toEigenV(qTarget)).cwiseAbs().maxCoeff()) << " deg, final RMS " << rms
              << " px, joint error " << (toEigenV(q) - toEigenV(qTarget)).cwiseAbs().maxCoeff() << " rad" << std::endl;
  }
}
} // namespace

TEST(ServoProjective, ConvergesNoiseFreePuma)
{
  expectConvergence(pumaEyeToHand(), 1, 10, vpMath::rad(20.0), vpMath::rad(15.0));
}

TEST(ServoProjective, ConvergesNoiseFreeViper850)
{
  expectConvergence(viperEyeToHand(), 2, 10, vpMath::rad(20.0), vpMath::rad(15.0));
}

TEST(ServoProjective, ConvergesNoiseFreeEyeInHand)
{
  // The rig on the PUMA's tool, 7 static markers; the eye-in-hand view allows only a few degrees per joint. A camera
  // 1 m from an 8 cm object barely tells a sideways translation from a rotation: sigma_min / sigma_max ~ 4e-4 at the
  // zero reference (3 and 8100 px/rad with markers 0-2, 4.7 and 12300 with all 7) and lower on some paths. Measured
  // on these pairs: damping from sigma_0 = 1 stalls 3 of 10 pairs with markers 0-2 (2 of 10 with all 7); without any
  // damping one 3-marker pair wandered off near a singularity; all 7 markers with sigma_0 = 0.1 converge.
  expectConvergence(pumaEyeInHand(), 3, 10, vpMath::rad(3.0), vpMath::rad(2.0), 0.1, {0, 1, 2, 3, 4, 5, 6});
}

TEST(ServoProjective, ControlLawIsPseudoInverseAwayFromSingularities)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  const vpProjectiveStereoRig &rig = robot.getStereoRig();
  const std::vector<unsigned int> tracked = {0, 1, 2, 3, 4, 5, 6};
  vpUniRand rng(4);
  for (int t = 0; t < 5; ++t) {
    vpColVector q, qStar;
    randomPair(s, rng, vpMath::rad(20.0), vpMath::rad(5.0), q, qStar);
    Task task(s, robot, tracked, q, qStar);
    task.task.setLambda(0.4);
    // e and J as documented.
    task.task.setDamping(0.0, 0.0);
    const vpColVector qdot = task.task.computeControlLaw(q);
    const Eigen::VectorXd e = toEigenV(task.task.getError());
    const Eigen::MatrixXd J = toEigenX(task.task.getTaskJacobian());
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
    EXPECT_NEAR(task.task.getConditionNumber(), sv(0) / sv(5), 1e-9 * sv(0) / sv(5));
    // qdot = -lambda J^+ e with ViSP's pseudo-inverse.
    const Eigen::VectorXd expected = -0.4 * toEigenX(task.task.getTaskJacobian().pseudoInverse()) * e;
    EXPECT_EQ(task.task.getDamping(), 0.0);
    EXPECT_DOUBLE_EQ(task.task.getLambda(), 0.4);
    EXPECT_FALSE(task.task.isSaturated());
    EXPECT_LT((toEigenV(qdot) - expected).norm() / expected.norm(), 1e-9);
    // Below sigma_0 the documented damping: mu^2 = mu_max^2 (1 - (sigma_min / sigma_0)^2).
    const double sigma0 = 2.0 * sv(5), muMax = 0.5 * sv(5);
    task.task.setDamping(sigma0, muMax);
    const Eigen::VectorXd qdotDamped = toEigenV(task.task.computeControlLaw(q));
    const double mu2 = muMax * muMax * (1.0 - 0.25);
    EXPECT_NEAR(task.task.getDamping(), std::sqrt(mu2), 1e-9 * std::sqrt(mu2));
    const Eigen::MatrixXd A = J.transpose() * J + mu2 * Eigen::MatrixXd::Identity(6, 6);
    const Eigen::VectorXd dls = -0.4 * A.ldlt().solve(J.transpose() * e);
    EXPECT_LT((qdotDamped - dls).norm() / dls.norm(), 1e-9);
    EXPECT_LT(qdotDamped.norm(), toEigenV(qdot).norm()); // damping shortens the step
    // Just above sigma_min: no damping again.
    task.task.setDamping(0.99 * sv(5), muMax);
    task.task.computeControlLaw(q);
    EXPECT_EQ(task.task.getDamping(), 0.0);
  }
}

TEST(ServoProjective, AdaptiveGain)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  const std::vector<unsigned int> tracked = {0, 1, 2, 3, 4, 5, 6};
  vpUniRand rng(5);
  vpColVector qStar, qFar;
  randomPair(s, rng, vpMath::rad(15.0), vpMath::rad(10.0), qFar, qStar);
  const vpAdaptiveGain gain(2.0, 0.2, 0.05); // lambda(0) = 2, lambda(inf) = 0.2, slope 0.05 per pixel at 0
  double lambdaFar = 0.0, lambdaNear = 0.0;
  for (int pass = 0; pass < 2; ++pass) {
    const vpColVector q = pass == 0 ? qFar : qStar + 0.01 * (qFar - qStar);
    Task task(s, robot, tracked, q, qStar);
    task.task.setDamping(0.0, 0.0);
    task.task.setLambda(gain);
    const Eigen::VectorXd qdot = toEigenV(task.task.computeControlLaw(q));
    const Eigen::VectorXd e = toEigenV(task.task.getError());
    const double expectedLambda = gain.value_const(e.cwiseAbs().maxCoeff());
    EXPECT_NEAR(task.task.getLambda(), expectedLambda, 1e-15);
    const Eigen::VectorXd expected = -expectedLambda * toEigenX(task.task.getTaskJacobian().pseudoInverse()) * e;
    EXPECT_LT((qdot - expected).norm() / expected.norm(), 1e-9);
    (pass == 0 ? lambdaFar : lambdaNear) = task.task.getLambda();
    // The three-value overload is the same gain.
    task.task.setLambda(2.0, 0.2, 0.05);
    EXPECT_LT((toEigenV(task.task.computeControlLaw(q)) - qdot).norm(), 1e-12 * qdot.norm());
  }
  std::cout << "[ measured ] adaptive gain " << lambdaFar << " far, " << lambdaNear << " near" << std::endl;
  EXPECT_LT(lambdaFar, lambdaNear);
  EXPECT_GT(lambdaNear, 1.0);
  EXPECT_LT(lambdaFar, 1.0);
}

TEST(ServoProjective, VelocitySaturationKeepsDirection)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  vpUniRand rng(6);
  vpColVector q, qStar;
  randomPair(s, rng, vpMath::rad(20.0), vpMath::rad(15.0), q, qStar);
  Task task(s, robot, {0, 1, 2}, q, qStar);
  const Eigen::VectorXd free = toEigenV(task.task.computeControlLaw(q));
  EXPECT_FALSE(task.task.isSaturated());
  const double cap = 0.25 * free.cwiseAbs().maxCoeff();
  task.task.setMaxJointVelocity(cap);
  const Eigen::VectorXd capped = toEigenV(task.task.computeControlLaw(q));
  EXPECT_TRUE(task.task.isSaturated());
  EXPECT_NEAR(capped.cwiseAbs().maxCoeff(), cap, 1e-15);
  EXPECT_LT((capped - 0.25 * free).norm(), 1e-12 * free.norm());
  // A cap above the step changes nothing.
  task.task.setMaxJointVelocity(2.0 * free.cwiseAbs().maxCoeff());
  EXPECT_EQ(toEigenV(task.task.computeControlLaw(q)), free);
  EXPECT_FALSE(task.task.isSaturated());
}

TEST(ServoProjective, DampingKeepsSingularTasksFinite)
{
  const double muMax = 10.0, lambda = 0.5;
  auto check = [&](Task &task, const vpColVector &q, int expectedRank, const char *what) {
    task.task.setLambda(lambda);
    task.task.setDamping(1.0, muMax);
    const Eigen::VectorXd qdot = toEigenV(task.task.computeControlLaw(q));
    const Eigen::VectorXd e = toEigenV(task.task.getError());
    const Eigen::MatrixXd J = toEigenX(task.task.getTaskJacobian());
    Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeFullV);
    const Eigen::VectorXd sv = svd.singularValues();
    std::cout << "[ measured ] " << what << ": singular values " << sv.transpose() << ", damping "
              << task.task.getDamping() << ", |qdot| " << qdot.norm() << std::endl;
    // Rank deficient: sigma_min ~ 0, so mu = mu_max.
    EXPECT_LT(sv(expectedRank) / sv(0), 1e-9) << what;
    EXPECT_GT(sv(expectedRank - 1) / sv(0), 1e-4) << what;
    EXPECT_GT(task.task.getConditionNumber(), 1e9) << what;
    EXPECT_NEAR(task.task.getDamping(), muMax, 1e-6) << what;
    ASSERT_TRUE(qdot.allFinite()) << what;
    // |(J^T J + mu^2 I)^-1 J^T e| <= |e| / (2 mu), and the step lies in the row space of J.
    EXPECT_LE(qdot.norm(), lambda * e.norm() / (2.0 * task.task.getDamping()) * (1.0 + 1e-9)) << what;
    const Eigen::MatrixXd N = svd.matrixV().rightCols(6 - expectedRank);
    EXPECT_LT((N.transpose() * qdot).norm(), 1e-9 * qdot.norm()) << what;
    const double mu2 = task.task.getDamping() * task.task.getDamping();
    const Eigen::VectorXd dls =
        -lambda * (J.transpose() * J + mu2 * Eigen::MatrixXd::Identity(6, 6)).ldlt().solve(J.transpose() * e);
    EXPECT_LT((qdot - dls).norm(), 1e-9 * dls.norm()) << what;
    // The error still decreases to first order: e^T J qdot < 0.
    EXPECT_LT(e.dot(J * qdot), 0.0) << what;
  };

  // One marker used three times: 12 rows of rank 3.
  const ArmSetup puma = pumaEyeToHand();
  const vpProjectiveRobot pumaRobot = calibratedRobot(puma);
  vpUniRand rng(7);
  vpColVector q, qStar;
  randomPair(puma, rng, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
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
  nearTask.task.setDamping(1.0, muMax);
  const double damped = toEigenV(nearTask.task.computeControlLaw(qNear)).norm();
  EXPECT_GT(nearTask.task.getDamping(), 0.9 * muMax);
  nearTask.task.setDamping(0.0, 0.0);
  const double undamped = toEigenV(nearTask.task.computeControlLaw(qNear)).norm();
  std::cout << "[ measured ] 0.01 deg from the wrist singularity: |qdot| " << damped << " damped, " << undamped
            << " undamped" << std::endl;
  EXPECT_GT(undamped, 100.0 * damped);
}

TEST(ServoProjective, EigenOverloadAndFeatureReferences)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  vpUniRand rng(8);
  vpColVector q, qStar;
  randomPair(s, rng, vpMath::rad(20.0), vpMath::rad(10.0), q, qStar);
  Task task(s, robot, {0, 1, 2}, q, qStar);
  EXPECT_EQ(task.task.getNumberOfFeatures(), 3u);
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
  EXPECT_EQ(task.task.getNumberOfFeatures(), 0u);
  EXPECT_TRUE(throwsProjective([&] { task.task.computeControlLaw(q); }, vpProjectiveException::notInitializedError,
                               "addFeature"));
}

TEST(ServoProjective, BadInputsThrow)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
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
  EXPECT_TRUE(throwsProjective([&] { task.setDamping(-1.0, 1.0); }, invalid, "non-negative"));
  EXPECT_TRUE(throwsProjective([&] { task.setDamping(1.0, nan); }, nonFinite, "damping"));
  EXPECT_TRUE(throwsProjective([&] { task.setMaxJointVelocity(-1.0); }, invalid, "positive"));
  EXPECT_TRUE(throwsProjective([&] { task.setMaxJointVelocity(nan); }, nonFinite, "velocity"));
}
