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
  Typed tests of both joint groups (p-rotations and p-translations, vpProjectiveJointGroupTestTools.h), exponential
  and logarithm against the metric simulator:
  - the ground truth: exp(a That) of the metric twist That (vpMetricTwist, through vpProjectiveJoint::twist) is the
    simulator's motion, with an independent matrix exponential;
  - exp(0) = I; the logarithm of H_PE^-1 T(a) H_PE with the encoder amount a is the true generator H_PE^-1 That H_PE,
    whatever the scale and sign of H (normalisation (12)), the sign given by the encoder; exp(log H) = H and
    log(exp(a)) = the generator; the generator's structure (identity, rank, trace);
  - group laws: exp(a) exp(b) = exp(a + b), exp(-a) = exp(a)^-1, exp(a) = the true p-motion for every amount
    (exp commutes with the conjugation by H_PE); conjugation by a random change of frame;
  - dexp() against numeric differentiation (vpNumericJacobian.h);
  - the static templated exp() and act() (and vpProjectiveJoint's dispatch) agree with the member exp().
*/

#include <gtest/gtest.h>

#include "vpProjectiveJointGroupTestTools.h"

using namespace vpProjectiveTest;

// The ground truth itself: the exponential of the metric twist, by an independent series and by the plugin's closed
// form, is the simulator's metric motion.
TYPED_TEST(JointGroup, MetricTwistIsTheSimulatorsMotion)
{
  using Traits = TypeParam;
  this->forEachRandomTruth(1, [&](int k, const Truth<Traits> &truth, vpUniRand &rng) {
    const Eigen::Matrix4d That = truth.metricTwist();
    std::vector<double> amounts = Traits::logAmounts();
    amounts.push_back(rng.uniform(-Traits::kRange, Traits::kRange));
    for (double a : amounts) {
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", amount " << a);
      const Eigen::Matrix4d T = truth.metricMotion(a);
      EXPECT_LT((expm(Eigen::Matrix4d(a * That)) - T).norm(), Traits::kConventionTol);
      EXPECT_LT((Traits::Group::exp(That, a) - T).norm(), Traits::kConventionTol);
    }
  });
}

TYPED_TEST(JointGroup, ExpOfZeroIsIdentity)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  // The default generator is zero: no motion, whatever the amount.
  const Group none;
  EXPECT_EQ(none.generator(), Eigen::Matrix4d::Zero());
  EXPECT_EQ(none.exp(0.7 * Traits::kRange).matrix(), I);
  this->forEachRandomTruth(2, [&](int, const Truth<Traits> &truth, vpUniRand &) {
    const Group G(truth.generator());
    EXPECT_EQ(G.exp(0.0).matrix(), I);
    EXPECT_EQ(Group::exp(G.generator(), 0.0), I);
  });
}

TYPED_TEST(JointGroup, LogRecoversTrueGenerator)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  double worst = 0.0;
  this->forEachRandomTruth(3, [&](int k, const Truth<Traits> &truth, vpUniRand &) {
    const Eigen::Matrix4d Gtrue = truth.generator();
    for (double a : Traits::logAmounts()) {
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", amount " << a);
      const Eigen::Matrix4d H = truth.motion(a);
      // Any scale and sign of H: the displacement is normalised by (12).
      for (double scale : {1.0, -2.5, 7.0, -4.0, 0.3}) {
        const Group G = Group::log(vpProjectiveDisplacement(Eigen::Matrix4d(scale * H)), a);
        EXPECT_LT(relativeError(G.generator(), Gtrue), 1e-9) << "scale " << scale;
        worst = std::max(worst, relativeError(G.generator(), Gtrue));
      }
      // The vpMatrix path.
      const Group Gv = Group::log(vpProjectiveDisplacement(toVisp(H)), a);
      EXPECT_LT(relativeError(Gv.generator(), Gtrue), 1e-9);
      // The opposite motion read by the encoder as such: the same generator. Read with the wrong sign: the generator
      // of the reversed joint.
      const vpProjectiveDisplacement Hneg(truth.motion(-a));
      EXPECT_LT(relativeError(Group::log(Hneg, -a).generator(), Gtrue), 1e-9);
      EXPECT_LT(relativeError(Group::log(Hneg, a).generator(), Eigen::Matrix4d(-Gtrue)), 1e-9);
      // The displacement is of the group's kind, with the group's image angle (21), whatever the sign.
      const vpProjectiveDisplacement D(H);
      EXPECT_EQ(D.classify(), Traits::kMotion);
      EXPECT_NEAR(D.getRotationAngle(), Traits::imageAngle(a), Traits::kAngleTol);
      EXPECT_NEAR(Hneg.getRotationAngle(), Traits::imageAngle(a), Traits::kAngleTol);
    }
  });
  testLog() << "[ stats    ] " << Traits::name() << " log, noise free: worst relative generator error " << worst
            << std::endl;
}

// exp(log H) = H from H of any scale, and log(exp(a)) = the generator.
TYPED_TEST(JointGroup, ExpAndLogAreInverse)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  this->forEachRandomTruth(4, [&](int k, const Truth<Traits> &truth, vpUniRand &) {
    const Group Gtrue(truth.generator());
    for (double a : Traits::logAmounts()) {
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", amount " << a);
      const Eigen::Matrix4d H = truth.motion(a);
      for (double scale : {7.0, 0.3, -2.5}) {
        const Group G = Group::log(vpProjectiveDisplacement(Eigen::Matrix4d(scale * H)), a);
        EXPECT_LT(relativeError(G.exp(a).matrix(), H), 1e-9) << "scale " << scale;
        EXPECT_LT(relativeError(G.exp(a).matrix(), vpProjectiveDisplacement::normalize(H)), 1e-9) << "scale " << scale;
        EXPECT_LT(relativeError(Group::exp(G.generator(), a), H), 1e-9) << "scale " << scale;
      }
      EXPECT_LT(relativeError(Group::log(Gtrue.exp(a), a).generator(), Gtrue.generator()), 1e-9);
    }
  });
}

TYPED_TEST(JointGroup, GeneratorStructure)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  this->forEachRandomTruth(5, [&](int k, const Truth<Traits> &truth, vpUniRand &) {
    for (double a : Traits::logAmounts()) {
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", amount " << a);
      const Eigen::Matrix4d Hhat = Group::log(vpProjectiveDisplacement(truth.motion(a)), a).generator();
      EXPECT_LT(Traits::identityDefect(Hhat), Traits::kStructureTol);
      EXPECT_LT(Group::generatorResidual(Hhat), Traits::kStructureTol);
      // Rank: kRank singular values of the order of the largest, the others at rounding level.
      const Eigen::Vector4d s = singularValues(Hhat);
      EXPECT_GT(s(Traits::kRank - 1), 1e-6 * s(0));
      EXPECT_LT(s(Traits::kRank), Traits::kStructureTol * s(0));
      // The eigenvalues (invariant under H_PE): trace 0, and trace(Hhat^2) their sum of squares.
      EXPECT_NEAR(Hhat.trace(), 0.0, 1e-9 * Hhat.norm());
      EXPECT_NEAR((Hhat * Hhat).trace(), Traits::kTraceOfSquare, 1e-9);
      // The constructors accept it.
      EXPECT_NO_THROW(Group G(Hhat));
      EXPECT_NO_THROW(Group G(toVisp(Hhat)));
    }
  });
}

/*
  exp(x) exp(y) = exp(x + y), exp(-x) exp(x) = I, exp(-x) = exp(x)^-1 (as matrices and through
  vpProjectiveDisplacement's composition and inverse), and exp(x Hhat) = H_PE^-1 exp(x That) H_PE is the true p-motion
  for every amount (for rotations beyond pi too): exp commutes with the conjugation by H_PE.
*/
TYPED_TEST(JointGroup, OneParameterSubgroup)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  this->forEachRandomTruth(6, [&](int k, const Truth<Traits> &truth, vpUniRand &rng) {
    const Group G(truth.generator());
    for (int trial = 0; trial < 5; ++trial) {
      const double x = rng.uniform(-Traits::kRange, Traits::kRange), y = rng.uniform(-Traits::kRange, Traits::kRange);
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", x " << x << ", y " << y);
      const Eigen::Matrix4d Ex = G.exp(x).matrix(), Exy = G.exp(x + y).matrix();
      EXPECT_LT(relativeError(Eigen::Matrix4d(Ex * G.exp(y).matrix()), Exy), 1e-9);
      EXPECT_LT(relativeError(Eigen::Matrix4d(G.exp(-x).matrix() * Ex), I), 1e-9);
      EXPECT_LT(relativeError(G.exp(-x).matrix(), Eigen::Matrix4d(Ex.inverse())), 1e-9);
      EXPECT_LT(relativeError((G.exp(x) * G.exp(y)).matrix(), Exy), 1e-9);
      EXPECT_LT(relativeError(G.exp(x).inverse().matrix(), G.exp(-x).matrix()), 1e-9);
      EXPECT_LT(relativeError(Ex, truth.motion(x)), 1e-9);
    }
  });
}

/*
  dexp(t) = d/dt exp(t Hhat) against vpNumericJacobian's Richardson-extrapolated central differences of exp(), step
  h = 1e-3 (rad or m): the truncation error h^4 |Hhat^5 exp| / 480 is ~1e-15 relative for rotations (Hhat^5 = Hhat)
  and zero for translations (exp is affine), the rounding ~3 eps |exp| / (h |Hhat exp|) ~ 1e-12 or less in the rig's
  frame; the bound 1e-9 (tighter than the former plain central differences' 1e-7 for rotations) catches any wrong
  sign or missing term (errors of order 1). dexp(t) = Hhat exp(t) = exp(t) Hhat (Hhat commutes with its exponential).
*/
TYPED_TEST(JointGroup, DexpIsTheDerivativeOfExp)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  double worst = 0.0;
  this->forEachRandomTruth(7, [&](int k, const Truth<Traits> &truth, vpUniRand &rng) {
    const Group G(truth.generator());
    const auto expOf = [&](const Eigen::VectorXd &x) { return stacked(G.exp(x(0)).matrix()); };
    std::vector<double> amounts(1, 0.0);
    for (int trial = 0; trial < 5; ++trial) {
      amounts.push_back(rng.uniform(-Traits::kRange, Traits::kRange));
    }
    for (double t : amounts) {
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", t " << t);
      const Eigen::Matrix4d D = G.dexp(t);
      const Eigen::MatrixXd numeric = numericJacobian(expOf, Eigen::VectorXd::Constant(1, t), 1e-3);
      EXPECT_TRUE(jacobianMatches(stacked(D), numeric, 1e-9));
      worst = std::max(worst, jacobianRelativeError(stacked(D), numeric));
      EXPECT_LT(relativeError(Eigen::Matrix4d(G.generator() * G.exp(t).matrix()), D), 1e-9);
      EXPECT_LT(relativeError(Eigen::Matrix4d(G.exp(t).matrix() * G.generator()), D), 1e-9);
    }
  });
  testLog() << "[ stats    ] " << Traits::name() << " dexp against numeric differentiation: worst relative error "
            << worst << std::endl;
}

/*
  Conjugation by a change of projective frame G. exp: exp(a Q^-1 Hhat Q) = Q^-1 exp(a Hhat) Q for a random
  well-conditioned Q applied to the rig's frame. log: it commutes with G too; this is checked in frames G = H_PE^-1 Q
  (G = H_PE^-1 maps the rig's frame to the metric one, where the generator is the metric twist itself). The rig's
  frame alone has cond(H_PE) ~ 4e3, so a p-rotation there has cond(H) ~ 1e5 - 1e6; a random Q on top of it raises
  cond(H) to 1e7 and the rounding error of H^-1 in the logarithm (25) to ~1e-6 relative: that is conditioning, not a
  property of the log, hence the choice of frames for the log part, where 1e-12 and 1e-11 hold.
*/
TYPED_TEST(JointGroup, Conjugation)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(8);
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(::testing::Message() << "trial " << k);
    const Truth<Traits> truth = this->randomTruth(rng);
    const Eigen::Matrix4d Hhat = truth.generator(), That = truth.metricTwist();
    const Eigen::Matrix4d Q = randomFrame(rng);
    ASSERT_GT(singularValues(Q)(3), 0.05);
    const Eigen::Matrix4d Qi = Q.inverse();
    const Group Gc(Eigen::Matrix4d(Qi * Hhat * Q)); // still a generator
    for (double a : Traits::logAmounts()) {
      SCOPED_TRACE(::testing::Message() << "amount " << a);
      EXPECT_LT(relativeError(Gc.exp(a).matrix(), Eigen::Matrix4d(Qi * Group::exp(Hhat, a) * Q)), 1e-10);
      const Eigen::Matrix4d Tl = truth.metricMotion(a);
      EXPECT_LT(relativeError(Group::log(vpProjectiveDisplacement(Tl), a).generator(), That), 1e-12);
      EXPECT_LT(relativeError(Group::log(vpProjectiveDisplacement(Eigen::Matrix4d(Qi * Tl * Q)), a).generator(),
                              Eigen::Matrix4d(Qi * That * Q)),
                1e-11);
    }
  }
}

/*
  The static templated exp() and act() are the member exp(): the same closed form. act() applies it to M with
  matrix-vector products, and a long double instantiation (templated on the scalar for Ceres' Jets) computes it with
  a wider mantissa: both differ from the double 4x4 form by its rounding, a few eps times the size of its terms,
  |I| + |Hhat| + |Hhat|^2 (|sin|, |1 - cos| <= 2; |Hhat|^2, not |Hhat^2|, as the product Hhat Hhat rounds relative
  to the products of its entries); bound 1e-14 (45 eps) times that. vpProjectiveJoint::exp() and
  act() dispatch to the group of the joint type.
*/
TYPED_TEST(JointGroup, StaticExpAndActAgreeWithMemberExp)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  this->forEachRandomTruth(9, [&](int k, const Truth<Traits> &truth, vpUniRand &rng) {
    const Group G(truth.generator());
    const Eigen::Matrix4d &Hhat = G.generator();
    const double terms = 2.0 + Hhat.norm() + Hhat.squaredNorm();
    for (int trial = 0; trial < 5; ++trial) {
      const double t = rng.uniform(-Traits::kRange, Traits::kRange);
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", t " << t);
      const Eigen::Matrix4d E = G.exp(t).matrix();
      Eigen::Vector4d M; // drawn last to first: see point3(), vpProjectiveTestTools.h
      for (int i = 3; i >= 0; --i) {
        M(i) = rng.uniform(-1.0, 1.0);
      }
      EXPECT_LT(relativeError(Group::exp(Hhat, t), E), 1e-15);
      EXPECT_LT(relativeError(vpProjectiveJoint::exp(Traits::kType, Hhat, t), E), 1e-15);
      EXPECT_LT((Group::act(Hhat, t, M) - E * M).norm(), 1e-14 * terms * M.norm());
      EXPECT_LT((vpProjectiveJoint::act(Traits::kType, Hhat, t, M) - E * M).norm(), 1e-14 * terms * M.norm());
      const Eigen::Matrix<long double, 4, 4> El =
          Group::exp(Eigen::Matrix<long double, 4, 4>(Hhat.cast<long double>()), static_cast<long double>(t));
      EXPECT_LT((Eigen::Matrix4d(El.template cast<double>()) - E).norm(), 1e-14 * terms);
    }
  });
}
