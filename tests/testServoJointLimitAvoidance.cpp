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
  Tests of vpServoJointLimitAvoidance against ViSP 3.5's own vpServo on the same primary task: a vpGenericFeature
  with L = J and s - s* = e (EYEINHAND_CAMERA, so that vpServo's J1 = J), seeded random J (12 x 6, of full rank or of
  rank 3) and e, the primary velocity dq = -lambda J^+ e:
  - the large projection operator P equals vpServo::getLargeP() for ||e|| above e1 (P = P_e), between e0 and e1
    (the blend, with I - J^+ J = 0 at full rank and != 0 at rank 3) and below e0 (P = I - J^+ J), for vpServo's
    pseudo-inverse threshold and for 1e-3, where a singular value ratio of 1e-4 counts as zero in both;
  - the secondary velocity equals vpServo::secondaryTaskJointLimitAvoidance() with each joint somewhere in its range
    (beyond l1, between l0 and l1, free) at both ends, for the default and other rho, rho1, with primary steps small
    enough that b < 1 for every joint in a band; with b >= 1 the joint adds nothing (vpServo 3.5 adds the previous
    joint's term once more there, a quirk of its loop that the class does not copy);
  - P J^T e = 0 and P is symmetric; joints inside their free interval, or no limits, give exactly 0;
  - misuse throws a vpProjectiveException naming what was wrong and changes nothing.
  Bound: vpServo's SVD and our eigen-decomposition agree to 1e-9. Every random number is seeded.
*/

#include <cmath>
#include <iostream>
#include <limits>
#include <sstream>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/visual_features/vpGenericFeature.h>
#include <visp3/vs/vpServo.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>
#include <visp3/projective/vpServoJointLimitAvoidance.h>

#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
vpColVector toVispV(const Eigen::VectorXd &v)
{
  vpColVector r(static_cast<unsigned int>(v.size()));
  for (unsigned int i = 0; i < r.size(); ++i) {
    r[i] = v(i);
  }
  return r;
}

//! vpServo on the task (J, e): its P and its joint-limit velocity for dq.
struct ViSPReference {
  Eigen::MatrixXd P;
  Eigen::VectorXd q2;

  ViSPReference(const Eigen::MatrixXd &J, const Eigen::VectorXd &e, double pinvThreshold, const vpColVector &q,
                const Eigen::VectorXd &dq, const vpColVector &qmin, const vpColVector &qmax, double rho, double rho1)
  {
    vpGenericFeature f(static_cast<unsigned int>(e.size())), fStar(static_cast<unsigned int>(e.size()));
    f.setInteractionMatrix(toVisp(J));
    f.set_s(toVispV(e));
    fStar.set_s(vpColVector(static_cast<unsigned int>(e.size()), 0.0));
    vpServo servo;
    servo.setServo(vpServo::EYEINHAND_CAMERA);
    servo.setInteractionMatrixType(vpServo::CURRENT);
    servo.setLambda(0.5);
    servo.setPseudoInverseThreshold(pinvThreshold);
    servo.addFeature(f, fStar);
    servo.computeControlLaw();
    q2 = toEigenV(servo.secondaryTaskJointLimitAvoidance(q, toVispV(dq), qmin, qmax, rho, rho1));
    P = toEigenX(servo.getLargeP());
    servo.kill();
  }
};
} // namespace

TEST(ServoJointLimitAvoidance, MatchesViSPsLargeProjectionOperatorAndSecondaryTask)
{
  vpUniRand rng(21);
  const double range = vpMath::rad(100.0);
  const double positions[6] = {0.02, 0.085, 0.5, 0.915, 0.98, 0.3}; // fraction of [qmin, qmax] where q_i sits
  struct Case {
    double errorNorm;
    int rank;
    double pinvThreshold;
    double rho, rho1;
  };
  // ||e|| = 0.4: sig = 1 / (1 + exp(-12 (0.4 - 0.1) / 0.6 + 6)) = 1/2; 0.05: below e0.
  const Case cases[] = {{5.0, 6, 1e-6, 0.1, 0.3},  {0.4, 6, 1e-6, 0.1, 0.3}, {0.4, 3, 1e-6, 0.1, 0.3},
                        {0.05, 3, 1e-6, 0.1, 0.3}, {0.4, 4, 1e-3, 0.1, 0.3}, {5.0, 6, 1e-6, 0.2, 0.5}};
  for (const Case &c : cases) {
    for (int p = 0; p < 3; ++p) {
      Eigen::MatrixXd J = randomMatrix(rng, 12, 6);
      if (c.rank < 6) {
        Eigen::JacobiSVD<Eigen::MatrixXd> svd(J, Eigen::ComputeThinU | Eigen::ComputeThinV);
        Eigen::VectorXd sigma = svd.singularValues();
        for (int k = c.rank; k < 6; ++k) {
          sigma(k) = c.pinvThreshold > 1e-4 && k == c.rank ? 1e-4 * sigma(0) : 0.0; // 1e-4: "zero" at 1e-3
        }
        J = svd.matrixU() * sigma.asDiagonal() * svd.matrixV().transpose();
      }
      Eigen::VectorXd e = randomMatrix(rng, 12, 1).col(0);
      e *= c.errorNorm / e.norm();
      vpColVector q(6), qmin(6), qmax(6);
      for (unsigned int i = 0; i < 6; ++i) {
        q[i] = rng.uniform(-1.0, 1.0);
        qmin[i] = q[i] - positions[(i + p) % 6] * range;
        qmax[i] = qmin[i] + range;
      }
      vpServoDampedLeastSquares law;
      law.setPseudoInverseThreshold(c.pinvThreshold);
      law.setDamping(0.0, 0.0);
      law.setMaxJointVelocity(1e-3); // small primary steps: b < 1 for every joint in a band (checked below)
      const Eigen::VectorXd dq = toEigenV(law.computeVelocity(toVisp(J), toVispV(e), 0.5));
      vpServoJointLimitAvoidance limits;
      limits.setJointLimits(qmin, qmax, c.rho, c.rho1);
      const Eigen::MatrixXd P = toEigenX(limits.computeLargeProjectionOperator(toVisp(J), toVispV(e), law));
      const Eigen::VectorXd q2 = toEigenV(limits.computeVelocity(q, toVispV(dq), toVisp(J), toVispV(e), law));
      const ViSPReference visp(J, e, c.pinvThreshold, q, dq, qmin, qmax, c.rho, c.rho1);
      std::ostringstream what;
      what << "||e|| " << c.errorNorm << ", rank " << c.rank << ", threshold " << c.pinvThreshold << ", rho " << c.rho
           << ", pair " << p;
      const Eigen::VectorXd b = J.transpose() * e;
      if (c.pinvThreshold < 1e-4) { // the singular values counted as zero are zero: P J^T e = 0
        EXPECT_LT((P * b).norm(), 1e-12 * std::max(1.0, b.norm())) << what.str();
      }
      for (unsigned int i = 0; i < 6; ++i) {
        const double pos = (q[i] - qmin[i]) / range;
        if (pos < c.rho || pos > 1.0 - c.rho) {
          ASSERT_LT(std::abs(dq(i)) / P(i, i), 1.0) << what.str() << ": b >= 1, where vpServo 3.5 re-adds the "
                                                    << "previous joint's term: the comparison would not hold";
        }
      }
      EXPECT_LT((P - P.transpose()).norm(), 1e-14) << what.str();
      EXPECT_LT((P - visp.P).norm(), 1e-9) << what.str();
      EXPECT_LT((q2 - visp.q2).norm(), 1e-9 * std::max(1e-12, q2.norm())) << what.str();
      if (c.errorNorm < 0.1 || c.errorNorm > 0.7) {
        EXPECT_LT((P * P - P).norm(), 1e-9) << what.str(); // I - J^+ J below e0, P_e above e1: projectors
      }
      EXPECT_GT(q2.norm(), 0.0) << what.str();
      testLog() << "[ measured ] " << what.str() << ": |P - P_ViSP| " << (P - visp.P).norm() << ", |q2| " << q2.norm()
                << ", |q2 - q2_ViSP| " << (q2 - visp.q2).norm() << std::endl;
    }
  }
}

TEST(ServoJointLimitAvoidance, ALargeRatioDoesNotActivateTheJoint)
{
  // b_i = |qdot1_i| / P_ii >= 1: joint i adds nothing, as if it were in its free interval (vpServo 3.5 adds the term
  // of the previous joint in the loop again there, a quirk the class does not copy).
  vpUniRand rng(23);
  const Eigen::MatrixXd J = randomMatrix(rng, 12, 6);
  Eigen::VectorXd e = randomMatrix(rng, 12, 1).col(0);
  e *= 5.0 / e.norm();
  const vpServoDampedLeastSquares law;
  vpServoJointLimitAvoidance limits;
  limits.setJointLimits(vpColVector(6, -1.0), vpColVector(6, 1.0)); // bands beyond +-0.8
  const Eigen::MatrixXd P = toEigenX(limits.computeLargeProjectionOperator(toVisp(J), toVispV(e), law));
  vpColVector q(6, 0.0), dq(6, 0.0);
  q[1] = 0.9;
  q[3] = -0.95;
  dq[1] = 0.5 * P(1, 1);  // b = 0.5: active
  dq[3] = -2.0 * P(3, 3); // b = 2: not activated
  const Eigen::VectorXd both = toEigenV(limits.computeVelocity(q, dq, toVisp(J), toVispV(e), law));
  q[3] = 0.0; // joint 3 in its free interval
  const Eigen::VectorXd one = toEigenV(limits.computeVelocity(q, dq, toVisp(J), toVispV(e), law));
  EXPECT_GT(one.norm(), 0.0);
  EXPECT_EQ(both, one);
}

TEST(ServoJointLimitAvoidance, NothingInsideTheFreeIntervalOrWithoutLimits)
{
  vpUniRand rng(22);
  const Eigen::MatrixXd J = randomMatrix(rng, 12, 6);
  const Eigen::VectorXd e = randomMatrix(rng, 12, 1).col(0);
  const vpServoDampedLeastSquares law;
  vpServoJointLimitAvoidance limits;
  const vpColVector q(6, 0.3), dq(6, 0.01);
  EXPECT_FALSE(limits.hasJointLimits());
  EXPECT_EQ(limits.getNumberOfJoints(), 0u);
  EXPECT_EQ(toEigenV(limits.computeVelocity(q, dq, toVisp(J), toVispV(e), law)), Eigen::VectorXd::Zero(6));
  limits.setJointLimits(vpColVector(6, -1.0), vpColVector(6, 1.0)); // free interval ]-0.8, 0.8[
  EXPECT_TRUE(limits.hasJointLimits());
  EXPECT_EQ(limits.getNumberOfJoints(), 6u);
  EXPECT_EQ(toEigenV(limits.computeVelocity(q, dq, toVisp(J), toVispV(e), law)), Eigen::VectorXd::Zero(6));
  vpColVector qBand = q;
  qBand[4] = 0.9;
  EXPECT_GT(toEigenV(limits.computeVelocity(qBand, dq, toVisp(J), toVispV(e), law)).norm(), 0.0);
  limits.clearJointLimits();
  EXPECT_FALSE(limits.hasJointLimits());
  EXPECT_EQ(toEigenV(limits.computeVelocity(qBand, dq, toVisp(J), toVispV(e), law)), Eigen::VectorXd::Zero(6));
}

TEST(ServoJointLimitAvoidance, BadInputsThrowAndChangeNothing)
{
  const int dim = vpProjectiveException::dimensionError;
  const int invalid = vpProjectiveException::invalidValueError;
  const int nonFinite = vpProjectiveException::nonFiniteValueError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  vpServoJointLimitAvoidance limits;
  const vpColVector lo(6, -1.0), hi(6, 1.0);
  limits.setJointLimits(lo, hi, 0.2, 0.4, 0.5);
  limits.setLargeProjectionThresholds(0.2, 0.9);
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(vpColVector(5, -1.0), hi); }, dim, "qmin has 5 entries"));
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(vpColVector(), vpColVector()); }, dim, "0 entries"));
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(vpColVector(17, -1.0), vpColVector(17, 1.0)); }, dim,
                               "1 to 16 joints"));
  vpColVector bad = hi;
  bad[2] = -1.0;
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(lo, bad); }, invalid, "joint 2: qmin (-1) must be below"));
  bad[2] = nan;
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(lo, bad); }, nonFinite, "qmax"));
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(lo, hi, 0.6); }, invalid, "rho must be in (0, 1/2]"));
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(lo, hi, 0.1, 0.0); }, invalid, "rho1 must be in (0, 1]"));
  EXPECT_TRUE(throwsProjective([&] { limits.setJointLimits(lo, hi, 0.1, 0.3, 1.5); }, invalid, "lambdaTune"));
  EXPECT_TRUE(throwsProjective([&] { limits.setLargeProjectionThresholds(0.7, 0.1); }, invalid, "0 <= e0 < e1"));
  EXPECT_TRUE(throwsProjective([&] { limits.setLargeProjectionThresholds(nan, 0.1); }, nonFinite, "e0"));
  // Nothing changed.
  EXPECT_TRUE(limits.hasJointLimits());
  EXPECT_EQ(toEigenV(limits.getLowerLimits()), toEigenV(lo));
  EXPECT_EQ(toEigenV(limits.getUpperLimits()), toEigenV(hi));
  EXPECT_EQ(limits.getRho(), 0.2);
  EXPECT_EQ(limits.getRho1(), 0.4);
  EXPECT_EQ(limits.getLambdaTune(), 0.5);
  double e0 = 0.0, e1 = 0.0;
  limits.getLargeProjectionThresholds(e0, e1);
  EXPECT_EQ(e0, 0.2);
  EXPECT_EQ(e1, 0.9);
  // The ViSP-typed entry points check their arguments.
  const vpServoDampedLeastSquares law;
  const vpMatrix J(12, 6, 1.0);
  const vpColVector e(12, 1.0), q(6, 0.0);
  EXPECT_TRUE(throwsProjective([&] { limits.computeLargeProjectionOperator(J, vpColVector(11, 1.0), law); }, dim,
                               "e has 11 entries but J has 12 rows"));
  EXPECT_TRUE(throwsProjective([&] { limits.computeVelocity(q, q, vpMatrix(12, 5, 1.0), e, law); }, dim,
                               "J has 5 columns but the joint limits are for 6 joints"));
  EXPECT_TRUE(throwsProjective([&] { limits.computeVelocity(vpColVector(5, 0.0), q, J, e, law); }, dim,
                               "q must have 6 entries"));
  vpColVector qNaN = q;
  qNaN[1] = nan;
  EXPECT_TRUE(throwsProjective([&] { limits.computeVelocity(q, qNaN, J, e, law); }, nonFinite, "qdot1"));
}
