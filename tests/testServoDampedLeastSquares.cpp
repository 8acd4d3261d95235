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
  Tests of vpServoDampedLeastSquares, the damped least-squares law with saturation, on Jacobians built with known
  singular values J = U diag(sigma) V^T (seeded random orthonormal U, V), so that the closed forms are exact:
  - away from singularities (sigma_min > sigma_0) qdot = -lambda V diag(1/sigma) U^T e = -lambda J^+ e, for sizes
    from 5x3 to 40x16, and the vpServo law of a 6-point IBVS (12x6 metric interaction matrix) with sigma_0 = 0;
  - below sigma_0 the documented damping mu^2 = mu_max^2 (1 - (sigma_min / sigma_0)^2) and
    qdot = -lambda V diag(sigma / (sigma^2 + mu^2)) U^T e, on both sides of sigma_0 (0.1 % away);
  - a rank-deficient J gets mu = mu_max, a step in the row space of J bounded by lambda |e| / (2 mu); an exactly zero
    column with no damping gets a zero velocity (the LDLT's zero pivot) and the pseudo-inverse solution elsewhere;
  - the saturation scales the whole velocity (same direction), and a cap above the step changes no bit;
  - the Eigen and ViSP entry points give the same bits; addNullSpaceProjector() adds w N N^T, N the null space of J
    at the pseudo-inverse threshold;
  - the normal equations (vpServoNormalEquations) are exactly symmetric, and their factorisations agree with the SVD:
    the Gauss-Newton step J^+ e, tr((J^T J)^-1) = sum 1 / sigma^2, the eigenvalues sigma^2, the damped solve; a zero
    column is not positive definite and gets the LDLT's step; each factorisation is computed once however many parts
    read it (the law, the adaptive gain on J^+ e, settling, the null-space projector);
  - misuse throws a vpProjectiveException naming what was wrong, and changes neither the settings nor the report.
  Bounds: closed forms agree to rounding amplified by the condition number (<= 1e3 here): 1e-10 relative. Every
  random number is seeded.
*/

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpUniRand.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpServoControlLaw.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>
#include <visp3/projective/vpServoNormalEquations.h>

#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! A Jacobian of known SVD: J = U diag(sigma) V^T, U (m x n) and V (n x n) with orthonormal columns.
struct KnownSvd {
  Eigen::MatrixXd U, V, J;
  Eigen::VectorXd sigma;

  KnownSvd(vpUniRand &rng, Eigen::Index m, const Eigen::VectorXd &singularValues) : sigma(singularValues)
  {
    const Eigen::Index n = singularValues.size();
    U = Eigen::HouseholderQR<Eigen::MatrixXd>(randomMatrix(rng, m, n)).householderQ() * Eigen::MatrixXd::Identity(m, n);
    V = Eigen::HouseholderQR<Eigen::MatrixXd>(randomMatrix(rng, n, n)).householderQ() * Eigen::MatrixXd::Identity(n, n);
    J = U * sigma.asDiagonal() * V.transpose();
  }

  //! -lambda (J^T J + mu^2 I)^-1 J^T e by the SVD.
  Eigen::VectorXd velocity(const Eigen::VectorXd &e, double lambda, double mu2) const
  {
    Eigen::VectorXd gains(sigma.size());
    for (Eigen::Index k = 0; k < sigma.size(); ++k) {
      gains(k) = sigma(k) / (sigma(k) * sigma(k) + mu2);
    }
    return -lambda * V * gains.asDiagonal() * U.transpose() * e;
  }
};

//! Logarithmically spaced singular values from sigmaMax down to sigmaMin.
Eigen::VectorXd spread(Eigen::Index n, double sigmaMax, double sigmaMin)
{
  Eigen::VectorXd s(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double t = n > 1 ? static_cast<double>(k) / static_cast<double>(n - 1) : 0.0;
    s(k) = sigmaMax * std::pow(sigmaMin / sigmaMax, t);
  }
  return s;
}

Eigen::VectorXd randomVector(vpUniRand &rng, Eigen::Index m, double scale)
{
  return scale * randomMatrix(rng, m, 1).col(0);
}

vpColVector toVispV(const Eigen::VectorXd &v)
{
  vpColVector r(static_cast<unsigned int>(v.size()));
  for (unsigned int i = 0; i < r.size(); ++i) {
    r[i] = v(i);
  }
  return r;
}

double relative(const Eigen::VectorXd &a, const Eigen::VectorXd &b)
{
  return (a - b).norm() / b.norm();
}
} // namespace

TEST(ServoDampedLeastSquares, IsThePseudoInverseAwayFromSingularities)
{
  vpUniRand rng(1);
  const Eigen::Index sizes[][2] = {{5, 3}, {12, 6}, {28, 6}, {16, 7}, {40, 12}, {40, 16}};
  for (const auto &size : sizes) {
    const KnownSvd svd(rng, size[0], spread(size[1], 500.0, 2.0));
    const Eigen::VectorXd e = randomVector(rng, size[0], 20.0);
    vpServoDampedLeastSquares law; // sigma_0 = 1 < sigma_min = 2: no damping
    const Eigen::VectorXd qdot = toEigenV(law.computeVelocity(toVisp(svd.J), toVispV(e), 0.4));
    ASSERT_EQ(qdot.size(), size[1]);
    EXPECT_EQ(law.getDamping(), 0.0);
    EXPECT_FALSE(law.isSaturated());
    EXPECT_LT(relative(qdot, svd.velocity(e, 0.4, 0.0)), 1e-10) << size[0] << "x" << size[1];
    const Eigen::VectorXd pinv = -0.4 * toEigenX(toVisp(svd.J).pseudoInverse()) * e; // ViSP's J^+
    EXPECT_LT(relative(qdot, pinv), 1e-10) << size[0] << "x" << size[1];
  }
}

TEST(ServoDampedLeastSquares, IsVpServosLawOnAMetricIbvsTask)
{
  // Six image points (x, y, Z), their desired positions, vpServo with the current interaction matrix: the law with no
  // damping gives vpServo's -lambda L^+ (s - s*) on the 12 x 6 L.
  vpUniRand rng(2);
  for (int t = 0; t < 5; ++t) {
    std::vector<vpFeaturePoint> s(6), sStar(6);
    vpServo servo;
    servo.setServo(vpServo::EYEINHAND_CAMERA);
    servo.setInteractionMatrixType(vpServo::CURRENT);
    servo.setLambda(0.5);
    for (unsigned int k = 0; k < 6; ++k) {
      for (vpFeaturePoint *f : {&s[k], &sStar[k]}) {
        const double Z = rng.uniform(0.8, 1.5); // drawn last to first: see point3(), vpProjectiveTestTools.h
        const double y = rng.uniform(-0.3, 0.3);
        const double x = rng.uniform(-0.3, 0.3);
        f->buildFrom(x, y, Z);
      }
      servo.addFeature(s[k], sStar[k]);
    }
    const vpColVector v = servo.computeControlLaw();
    const vpMatrix L = servo.getTaskJacobian();
    const vpColVector e = servo.getError();
    ASSERT_EQ(L.getRows(), 12u);
    ASSERT_EQ(L.getCols(), 6u);
    vpServoDampedLeastSquares law;
    law.setDamping(0.0, 0.0);
    const Eigen::VectorXd qdot = toEigenV(law.computeVelocity(L, e, 0.5));
    EXPECT_LT(relative(qdot, toEigenV(v)), 1e-9) << "task " << t;
    servo.kill();
  }
}

TEST(ServoDampedLeastSquares, DampingIsTheDocumentedOne)
{
  vpUniRand rng(3);
  const double lambda = 0.5, muMax = 4.0;
  for (int t = 0; t < 5; ++t) {
    const KnownSvd svd(rng, 12, spread(6, 300.0, 3.0));
    const Eigen::VectorXd e = randomVector(rng, 12, 10.0);
    for (double factor : {2.0, 1.001, 0.999, 0.5}) { // sigma_0 = factor sigma_min
      const double sigma0 = factor * 3.0;
      vpServoDampedLeastSquares law;
      law.setDamping(sigma0, muMax);
      const Eigen::VectorXd qdot = toEigenV(law.computeVelocity(toVisp(svd.J), toVispV(e), lambda));
      const double ratio = 3.0 / sigma0;
      const double mu2 = ratio < 1.0 ? muMax * muMax * (1.0 - ratio * ratio) : 0.0;
      EXPECT_NEAR(law.getDamping(), std::sqrt(mu2), 1e-9 * muMax) << "sigma_0 = " << factor << " sigma_min";
      EXPECT_LT(relative(qdot, svd.velocity(e, lambda, mu2)), 1e-10) << "sigma_0 = " << factor << " sigma_min";
      if (factor < 1.0) {
        EXPECT_EQ(law.getDamping(), 0.0); // decided exactly (the eigenvalues, where the trace bound cannot prove it)
      }
    }
  }
}

TEST(ServoDampedLeastSquares, RankDeficientTasksAreDampedToTheMaximum)
{
  vpUniRand rng(4);
  const double lambda = 0.5, muMax = 10.0;
  Eigen::VectorXd sigma(6);
  sigma << 200.0, 80.0, 20.0, 0.0, 0.0, 0.0;
  const KnownSvd svd(rng, 12, sigma);
  const Eigen::VectorXd e = randomVector(rng, 12, 10.0);
  vpServoDampedLeastSquares law;
  law.setDamping(1.0, muMax);
  const Eigen::VectorXd qdot = toEigenV(law.computeVelocity(toVisp(svd.J), toVispV(e), lambda));
  ASSERT_TRUE(qdot.allFinite());
  EXPECT_NEAR(law.getDamping(), muMax, 1e-6);
  const double mu2 = law.getDamping() * law.getDamping();
  EXPECT_LT(relative(qdot, svd.velocity(e, lambda, mu2)), 1e-9);
  EXPECT_LE(qdot.norm(), lambda * e.norm() / (2.0 * law.getDamping()) * (1.0 + 1e-9));
  EXPECT_LT((svd.V.rightCols(3).transpose() * qdot).norm(), 1e-9 * qdot.norm()); // in the row space of J

  // Without damping, a joint that moves nothing (an exactly zero column) gets 0, the others J^+ e.
  Eigen::MatrixXd J = randomMatrix(rng, 12, 6);
  J.col(2).setZero();
  law.setDamping(0.0, 0.0);
  const Eigen::VectorXd qdot0 = toEigenV(law.computeVelocity(toVisp(J), toVispV(e), lambda));
  EXPECT_EQ(qdot0(2), 0.0);
  Eigen::MatrixXd reduced(12, 5);
  reduced << J.leftCols(2), J.rightCols(3);
  const Eigen::VectorXd expected = -lambda * reduced.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).solve(e);
  Eigen::VectorXd others(5);
  others << qdot0.head(2), qdot0.tail(3);
  EXPECT_LT(relative(others, expected), 1e-10);
}

TEST(ServoDampedLeastSquares, SaturationKeepsTheDirection)
{
  vpUniRand rng(5);
  const KnownSvd svd(rng, 12, spread(6, 300.0, 3.0));
  const Eigen::VectorXd e = randomVector(rng, 12, 50.0);
  vpServoDampedLeastSquares law;
  const Eigen::VectorXd free = toEigenV(law.computeVelocity(toVisp(svd.J), toVispV(e), 0.5));
  EXPECT_FALSE(law.isSaturated());
  const double cap = 0.3 * free.cwiseAbs().maxCoeff();
  law.setMaxJointVelocity(cap);
  EXPECT_EQ(law.getMaxJointVelocity(), cap);
  const Eigen::VectorXd capped = toEigenV(law.computeVelocity(toVisp(svd.J), toVispV(e), 0.5));
  EXPECT_TRUE(law.isSaturated());
  EXPECT_NEAR(capped.cwiseAbs().maxCoeff(), cap, 1e-15);
  EXPECT_LT((capped - 0.3 * free).norm(), 1e-12 * free.norm());
  EXPECT_LT(std::abs(capped.normalized().dot(free.normalized()) - 1.0), 1e-15);
  // saturate() alone: the same scaling, no report.
  vpServoDampedLeastSquares::JointVector q = free;
  EXPECT_TRUE(law.saturate(q));
  EXPECT_EQ(Eigen::VectorXd(q), capped);
  // A cap above the step changes no bit.
  law.setMaxJointVelocity(2.0 * free.cwiseAbs().maxCoeff());
  EXPECT_EQ(toEigenV(law.computeVelocity(toVisp(svd.J), toVispV(e), 0.5)), free);
  EXPECT_FALSE(law.isSaturated());
  q = free;
  EXPECT_FALSE(law.saturate(q));
  EXPECT_EQ(Eigen::VectorXd(q), free);
}

TEST(ServoDampedLeastSquares, EigenAndViSPEntryPointsGiveTheSameBits)
{
  vpUniRand rng(6);
  for (double sigma0 : {0.0, 1.0, 50.0}) {
    const KnownSvd svd(rng, 16, spread(7, 400.0, 5.0));
    const Eigen::VectorXd e = randomVector(rng, 16, 10.0);
    vpServoDampedLeastSquares law;
    law.setDamping(sigma0, 20.0);
    law.setMaxJointVelocity(0.05);
    const Eigen::VectorXd viaViSP = toEigenV(law.computeVelocity(toVisp(svd.J), toVispV(e), 0.7));
    const double damping = law.getDamping();
    const bool saturated = law.isSaturated();
    vpServoNormalEquations ne;
    ne.compute(svd.J, e);
    vpServoDampedLeastSquares::JointVector qdot;
    law.computeVelocity(ne, 0.7, qdot);
    EXPECT_EQ(Eigen::VectorXd(qdot), viaViSP) << "sigma_0 " << sigma0;
    EXPECT_EQ(law.getDamping(), damping);
    EXPECT_EQ(law.isSaturated(), saturated);
  }
}

TEST(ServoDampedLeastSquares, NullSpaceProjectorFollowsThePseudoInverseThreshold)
{
  vpUniRand rng(7);
  Eigen::VectorXd sigma(6);
  sigma << 100.0, 50.0, 10.0, 1e-2, 0.0, 0.0; // sigma_3 / sigma_max = 1e-4
  const KnownSvd svd(rng, 12, sigma);
  vpServoNormalEquations ne;
  ne.compute(svd.J, Eigen::VectorXd::Zero(12));
  vpServoDampedLeastSquares law;
  EXPECT_EQ(law.getPseudoInverseThreshold(), 1e-6);
  for (double threshold : {1e-6, 1e-3}) {
    law.setPseudoInverseThreshold(threshold);
    const int nullity = threshold < 1e-4 ? 2 : 3;
    const Eigen::MatrixXd N = svd.V.rightCols(nullity);
    vpServoDampedLeastSquares::JointMatrix P = vpServoDampedLeastSquares::JointMatrix::Identity(6, 6);
    law.addNullSpaceProjector(ne, 0.25, P);
    const Eigen::MatrixXd expected = Eigen::MatrixXd::Identity(6, 6) + 0.25 * N * N.transpose();
    EXPECT_LT((Eigen::MatrixXd(P) - expected).norm(), 1e-9) << "threshold " << threshold;
  }
  // A full-rank J adds nothing.
  const KnownSvd full(rng, 12, spread(6, 100.0, 1.0));
  ne.compute(full.J, Eigen::VectorXd::Zero(12));
  vpServoDampedLeastSquares::JointMatrix P = vpServoDampedLeastSquares::JointMatrix::Zero(6, 6);
  law.addNullSpaceProjector(ne, 1.0, P);
  EXPECT_EQ(P.norm(), 0.0);
}

TEST(ServoNormalEquations, FactorisationsAgreeWithTheSvd)
{
  vpUniRand rng(8);
  // 6 and 7 joints run the kernels unrolled for the common arms, the other counts their run-time form.
  for (const auto &size : std::vector<std::array<Eigen::Index, 2>>{{5, 3}, {12, 6}, {28, 7}, {40, 16}}) {
    const KnownSvd svd(rng, size[0], spread(size[1], 400.0, 5.0));
    const Eigen::VectorXd e = randomVector(rng, size[0], 20.0);
    vpServoNormalEquations ne;
    ne.compute(svd.J, e);
    const Eigen::MatrixXd JtJ = ne.getJtJ();
    EXPECT_EQ(JtJ, Eigen::MatrixXd(JtJ.transpose())); // exactly symmetric
    EXPECT_LT((JtJ - svd.J.transpose() * svd.J).norm(), 1e-12 * JtJ.norm());
    EXPECT_LT(relative(ne.getJte(), svd.J.transpose() * e), 1e-12);
    EXPECT_EQ(ne.getFactorisationCount(), 0u); // nothing factorised before it is read
    ASSERT_TRUE(ne.isPositiveDefinite());
    EXPECT_LT(relative(ne.getGaussNewtonStep(), svd.velocity(e, -1.0, 0.0)), 1e-10) << size[0] << "x" << size[1];
    EXPECT_NEAR(ne.getInverseTrace(), svd.sigma.array().square().inverse().sum(),
                1e-10 * svd.sigma.array().square().inverse().sum());
    EXPECT_EQ(ne.getFactorisationCount(), 1u); // the Cholesky factorisation, once
    Eigen::VectorXd sigma2 = svd.sigma.array().square();
    std::sort(sigma2.data(), sigma2.data() + sigma2.size());
    EXPECT_LT((Eigen::VectorXd(ne.getEigenvalues()) - sigma2).norm(), 1e-12 * sigma2.maxCoeff());
    const Eigen::MatrixXd V = ne.getEigenvectors();
    EXPECT_LT((V * Eigen::VectorXd(ne.getEigenvalues()).asDiagonal() * V.transpose() - JtJ).norm(), 1e-12 * JtJ.norm());
    for (double mu2 : {1e-3, 30.0, 1e4}) {
      vpServoNormalEquations::JointVector x;
      ne.solveDamped(mu2, x);
      EXPECT_LT(relative(x, svd.velocity(e, -1.0, mu2)), 1e-10) << "mu^2 " << mu2;
    }
    EXPECT_EQ(ne.getFactorisationCount(), 2u); // and the eigen decomposition, once
    ne.compute(svd.J, e);
    EXPECT_EQ(ne.getFactorisationCount(), 0u); // new equations, nothing factorised yet
  }
}

TEST(ServoNormalEquations, ARankDeficientTaskGetsThePivotingStep)
{
  vpUniRand rng(9);
  Eigen::MatrixXd J = randomMatrix(rng, 12, 6);
  J.col(4).setZero();
  const Eigen::VectorXd e = randomVector(rng, 12, 10.0);
  vpServoNormalEquations ne;
  ne.compute(J, e);
  EXPECT_FALSE(ne.isPositiveDefinite());
  EXPECT_EQ(ne.getInverseTrace(), std::numeric_limits<double>::infinity());
  const Eigen::VectorXd g = ne.getGaussNewtonStep();
  ASSERT_TRUE(g.allFinite());
  EXPECT_EQ(g(4), 0.0);
  Eigen::MatrixXd others(12, 5);
  others << J.leftCols(4), J.col(5);
  const Eigen::VectorXd expected = others.completeOrthogonalDecomposition().solve(e);
  Eigen::VectorXd gOthers(5);
  gOthers << g.head(4), g(5);
  EXPECT_LT(relative(gOthers, expected), 1e-10);
  EXPECT_EQ(ne.getFactorisationCount(), 2u); // the Cholesky attempt, then the LDLT
}

TEST(ServoNormalEquations, EachFactorisationOnceForEveryPartOfTheLaw)
{
  vpUniRand rng(10);
  const KnownSvd svd(rng, 16, spread(6, 400.0, 5.0));
  const Eigen::VectorXd e = randomVector(rng, 16, 10.0);
  vpServoNormalEquations ne;
  ne.compute(svd.J, e);
  // Away from singularities: the law, the adaptive gain on J^+ e and settling read the one Cholesky factorisation.
  vpServoControlLaw law;
  law.setLambda(2.0, 0.5, 30.0);
  law.setAdaptiveGainInput(vpServoControlLaw::GAIN_INPUT_JOINT_VELOCITY);
  vpServoSettling settling;
  settling.setEnabled(true);
  vpServoNormalEquations::JointVector qdot;
  const double lambda = settling.gain(law.gain(ne, e.cwiseAbs().maxCoeff()), ne, e.squaredNorm(), 16, 1);
  law.computePrimaryStep(ne, lambda, qdot);
  EXPECT_EQ(law.getDampedLeastSquares().getDamping(), 0.0);
  EXPECT_LT(relative(qdot, svd.velocity(e, lambda, 0.0)), 1e-10);
  EXPECT_EQ(ne.getFactorisationCount(), 1u);
  // Near a singularity the eigen decomposition decides the damping, solves the damped system and gives the null-space
  // projector: one more factorisation in all.
  law.setDamping(10.0, 20.0);
  law.computePrimaryStep(ne, lambda, qdot);
  const double mu2 = 400.0 * (1.0 - 0.25);
  EXPECT_NEAR(law.getDampedLeastSquares().getDamping(), std::sqrt(mu2), 1e-9);
  EXPECT_LT(relative(qdot, svd.velocity(e, lambda, mu2)), 1e-10);
  vpServoNormalEquations::JointMatrix P = vpServoNormalEquations::JointMatrix::Zero(6, 6);
  law.getDampedLeastSquares().addNullSpaceProjector(ne, 1.0, P);
  EXPECT_EQ(ne.getFactorisationCount(), 2u);
}

TEST(ServoDampedLeastSquares, BadInputsThrowAndChangeNothing)
{
  const int dim = vpProjectiveException::dimensionError;
  const int invalid = vpProjectiveException::invalidValueError;
  const int nonFinite = vpProjectiveException::nonFiniteValueError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vpServoDampedLeastSquares law;
  law.setDamping(2.0, 3.0);
  law.setMaxJointVelocity(0.1);
  law.setPseudoInverseThreshold(1e-5);
  // Settings.
  EXPECT_TRUE(throwsProjective([&] { law.setDamping(-1.0, 1.0); }, invalid, "non-negative"));
  EXPECT_TRUE(throwsProjective([&] { law.setDamping(1.0, -1.0); }, invalid, "non-negative"));
  EXPECT_TRUE(throwsProjective([&] { law.setDamping(nan, 1.0); }, nonFinite, "singular value threshold"));
  EXPECT_TRUE(throwsProjective([&] { law.setDamping(1.0, inf); }, nonFinite, "maximum damping"));
  EXPECT_TRUE(throwsProjective([&] { law.setMaxJointVelocity(-1.0); }, invalid, "0 disables"));
  EXPECT_TRUE(throwsProjective([&] { law.setMaxJointVelocity(nan); }, nonFinite, "maximum joint velocity"));
  EXPECT_TRUE(throwsProjective([&] { law.setPseudoInverseThreshold(1.0); }, invalid, "[0, 1)"));
  EXPECT_TRUE(throwsProjective([&] { law.setPseudoInverseThreshold(-1e-6); }, invalid, "[0, 1)"));
  EXPECT_TRUE(throwsProjective([&] { law.setPseudoInverseThreshold(nan); }, nonFinite, "pseudo-inverse threshold"));
  EXPECT_EQ(law.getSigmaThreshold(), 2.0);
  EXPECT_EQ(law.getMaxDamping(), 3.0);
  EXPECT_EQ(law.getMaxJointVelocity(), 0.1);
  EXPECT_EQ(law.getPseudoInverseThreshold(), 1e-5);
  EXPECT_NO_THROW(law.setPseudoInverseThreshold(0.0));
  EXPECT_NO_THROW(law.setDamping(0.0, 0.0));
  law.setDamping(2.0, 3.0);

  // The law's arguments: a successful call first, whose report must survive the failed ones.
  vpUniRand rng(8);
  Eigen::VectorXd sigma(6);
  sigma << 100.0, 50.0, 10.0, 5.0, 1.0, 0.5;
  const KnownSvd svd(rng, 12, sigma);
  const vpMatrix J = toVisp(svd.J);
  const vpColVector e = toVispV(randomVector(rng, 12, 100.0));
  law.computeVelocity(J, e, 0.5);
  const double damping = law.getDamping();
  const bool saturated = law.isSaturated();
  ASSERT_GT(damping, 0.0);
  ASSERT_TRUE(saturated);
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(J, vpColVector(11, 0.0), 0.5); }, dim,
                               "e has 11 entries but J has 12 rows"));
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(vpMatrix(12, 0), e, 0.5); }, dim, "1 to 16 columns"));
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(vpMatrix(12, 17), e, 0.5); }, dim, "J is 12x17"));
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(vpMatrix(), vpColVector(), 0.5); }, dim, "at least one row"));
  vpMatrix Jbad = J;
  Jbad[3][2] = nan;
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(Jbad, e, 0.5); }, nonFinite, "J has a NaN"));
  vpColVector ebad = e;
  ebad[0] = -inf;
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(J, ebad, 0.5); }, nonFinite, "e has a NaN or infinite"));
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(J, e, -0.5); }, invalid, "gain must be non-negative"));
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(J, e, nan); }, nonFinite, "gain"));
  // An overflow: a finite but huge gain makes the velocity infinite.
  EXPECT_TRUE(throwsProjective([&] { law.computeVelocity(J, e, 1e308); }, vpProjectiveException::estimationFailedError,
                               "non-finite velocity"));
  EXPECT_EQ(law.getDamping(), damping);
  EXPECT_EQ(law.isSaturated(), saturated);
}
