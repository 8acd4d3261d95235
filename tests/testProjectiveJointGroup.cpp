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
  Tests of the two one-parameter Lie groups of the joints, p-rotations exp(theta Hhat) (vpProjectiveRotation, Ruf &
  Horaud eqs. (18)-(27)) and p-translations exp(tau Hhat) = I + tau Hhat (vpProjectiveTranslation, eqs. (28)-(31)),
  against the metric simulator. They share one interface (log(H, amount), exp(), dexp(), the static templated exp()
  and act(), generator(), project(), generatorResidual()), so one typed suite (JointGroup) checks both, with a traits
  struct per group for what truly differs: the simulator's motion of that kind, the amounts, the generator identity
  (Hhat^3 = -Hhat or Hhat^2 = 0), the rank (2 or 1) and the bounds that follow from them. Checked:
  - the ground truth: exp(a That) of the metric twist That (vpMetricTwist, through vpProjectiveJoint::twist) is the
    simulator's motion, with an independent matrix exponential;
  - exp(0) = I; the logarithm of H_PE^-1 T(a) H_PE with the encoder amount a is the true generator H_PE^-1 That H_PE,
    whatever the scale and sign of H (normalisation (12)), the sign given by the encoder; exp(log H) = H and
    log(exp(a)) = the generator; the generator's structure (identity, rank, trace);
  - group laws: exp(a) exp(b) = exp(a + b), exp(-a) = exp(a)^-1, exp(a) = the true p-motion for every amount
    (exp commutes with the conjugation by H_PE); conjugation by a random change of frame;
  - dexp() against numeric differentiation (vpNumericJacobian.h);
  - project() leaves exact generators unchanged and projects noisy ones on exact generators, first order in the noise;
    the logarithm of a noisy H is an exact generator whose error is first order in the noise, within a derived bound;
  - the static templated exp() and act() (and vpProjectiveJoint's dispatch) agree with the member exp();
  - invalid inputs throw a vpProjectiveException with a meaningful code and message.
  What belongs to one group only (a rotation's angle, period and encoder-less logarithm; a translation's generator per
  encoder unit; which inputs are degenerate) is in ordinary TESTs at the end.

  Noise-free bounds: 1e-9 relative, far above rounding in the rig's frame (cond(H_PE) ~ 4e3, canonical
  normalisation), far below any modelling error (a wrong sign, axis or scale of the generator gives errors of order
  1); tighter where the structure makes the result exact to rounding (1e-12 for a p-translation's nilpotency, 1e-12
  and 1e-11 for logarithms in well-conditioned frames). Each other bound is explained at its test. Every random
  number comes from a seeded vpUniRand or vpGaussRand.
*/

#include <algorithm>
#include <cmath>
#include <complex>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveTranslation.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpNumericJacobian.h"
#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
// A joint in the simulator's world: a unit direction, and a point on the axis (unused by a prismatic joint).
struct Joint {
  vpColVector point;
  vpColVector direction;
};

Joint randomJoint(vpUniRand &rng)
{
  Joint j;
  j.point = Scene::fixation() + point3(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1));
  j.direction = randomDirection(rng);
  return j;
}

// A 4x4 matrix of entries draw() (row by row).
template <typename Draw> Eigen::Matrix4d drawnMatrix(Draw draw)
{
  Eigen::Matrix4d A;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      A(i, j) = draw();
    }
  }
  return A;
}

// A random 4x4 matrix of unit Frobenius norm (Gaussian entries): the direction of a perturbation.
Eigen::Matrix4d unitNoise(vpGaussRand &noise)
{
  const Eigen::Matrix4d N = drawnMatrix([&] { return noise(); });
  return N / N.norm();
}

// Entries uniform in +-1.
Eigen::Matrix4d randomMatrix(vpUniRand &rng)
{
  return drawnMatrix([&] { return rng.uniform(-1.0, 1.0); });
}

// A random, well-conditioned change of frame: I plus entries uniform in +-0.4.
Eigen::Matrix4d randomFrame(vpUniRand &rng)
{
  return Eigen::Matrix4d::Identity() + 0.4 * randomMatrix(rng);
}

// ---------------------------------------------------------------------------------------------------------------
// What differs between the groups
// ---------------------------------------------------------------------------------------------------------------

struct RotationTraits {
  using Group = vpProjectiveRotation;
  static std::string name() { return "Rotation"; }
  static constexpr vpProjectiveJoint::vpJointType kType = vpProjectiveJoint::REVOLUTE;
  static constexpr vpProjectiveDisplacement::vpMotionType kMotion = vpProjectiveDisplacement::ROTATION;

  // The simulator's rotation by \e amount radians about the joint's axis.
  static vpHomogeneousMatrix worldMotion(const Joint &j, double amount)
  {
    return vpSimulatorStereoRig::rotationAbout(j.point, j.direction, amount);
  }
  // Encoder amounts for the logarithm (25): both signs, from 3 deg to 172 deg, away from the multiples of pi where
  // it is undefined.
  static std::vector<double> logAmounts() { return {0.05, 0.1, 0.5, -0.7, -1.0, 1.2, 1.5, 2.2, 2.5, -2.9, 3.0}; }
  // Random amounts of exp() lie in +-kRange: beyond pi, the exponential is defined everywhere.
  static constexpr double kRange = 4.0;
  // The image angle (21) of the p-rotation by \e amount, and how well getRotationAngle() reads it.
  static double imageAngle(double amount) { return std::abs(amount); }
  static constexpr double kAngleTol = 1e-9;

  // Hhat^3 = -Hhat, written here as a relative defect (not through generatorResidual(), which it checks).
  static double identityDefect(const Eigen::Matrix4d &G)
  {
    return relativeError(Eigen::Matrix4d(G * G * G), Eigen::Matrix4d(-G));
  }
  static constexpr int kRank = 2;
  // Eigenvalues +-i, 0, 0 (invariant under H_PE): trace(Hhat^2) = -2 |w|^2 = -2 at unit speed.
  static constexpr double kTraceOfSquare = -2.0;
  // Identity and rank of a noise-free logarithm: sin(amount) and H^-1 in (25) put the rounding of the rig's frame at
  // ~1e-12; 1e-9 as the other noise-free bounds.
  static constexpr double kStructureTol = 1e-9;
  // |expm(a That) - T|_F of the ground truth itself (|T| ~ 2, |a| <= 4): rounding of a scaled-and-squared series.
  static constexpr double kConventionTol = 1e-12;
  static const char *notAGenerator() { return "not a p-rotation generator"; }

  /*
    The logarithm of a noisy p-rotation (see NoisyLogIsExactGeneratorWithBoundedError). Its algebraic generator, read
    in the metric frame: from (25) and (21),
      dHhat = (T E + E T^-1) / (2 sin theta) - cot(theta) Hhat dtheta,  |dtheta| <= eps |T|_F / (2 sin theta),
    hence |dHhat| / |That| <= C eps with C = (|T| + |T^-1| + |cot theta| |That| |T|) / (2 sin theta |That|)
    (Frobenius norms; the change of the normalisation (12), 1 - tr(E)/4, is of lower size).
  */
  static std::vector<double> noisyAmounts() { return {0.3, 0.8, 2.0}; }
  static constexpr double kNoise[2] = {1e-6, 1e-4};
  static double algebraicBound(const Eigen::Matrix4d &T, const Eigen::Matrix4d &That, double theta)
  {
    return (T.norm() + T.inverse().norm() + std::abs(std::cos(theta) / std::sin(theta)) * That.norm() * T.norm()) /
           (2.0 * std::sin(theta) * That.norm());
  }
  // The generator (25) before its projection, (H - H^-1) / (2 sin(amount)), of a normalised H.
  static Eigen::Matrix4d algebraicGenerator(const Eigen::Matrix4d &Hn, double amount)
  {
    return (Hn - Hn.inverse()) / (2.0 * std::sin(amount));
  }
  /*
    How much project() can amplify an error, and where. It is the matrix function f(A) with f = +-i near +-i and 0
    near 0 (the eigenvalues set to +-i, 0, 0), so it commutes with any change of frame: errors are read in the metric
    frame. Its first-order change at That = V diag(i, -i, 0, 0) V^-1 is V (F o (V^-1 dA V)) V^-1 with F the divided
    differences of f, all of modulus 0 or 1 (Higham, Functions of Matrices, Thm 3.11), hence |df|_F <= kappa_2(V)^2
    |dA|_F; 1.1 times that covers the second order at these noise levels. V, with unit columns: for That = [[w]x, v;
    0, 0] (w unit, v orthogonal to w), (e1 -+ i e2, 0) / sqrt(2) for +-i ((e1, e2, w) orthonormal and right-handed),
    (w, 0) and (w x v, 1) for 0; its conditioning grows with the distance |w x v| of the axis to the camera centre.
  */
  static Eigen::Matrix4d errorFrame(const Scene &scene, const Eigen::Matrix4d &X)
  {
    return scene.Hpe * X * scene.HpeInv;
  }
  static double amplificationBound(const Eigen::Matrix4d &That)
  {
    const Eigen::Matrix<double, 6, 1> xi = vpMetricTwist::vee(That);
    const Eigen::Vector3d v = xi.head<3>(), w = xi.tail<3>();
    const Eigen::Vector3d e1 = w.unitOrthogonal(), e2 = w.cross(e1);
    const std::complex<double> i(0.0, 1.0);
    Eigen::Matrix4cd V = Eigen::Matrix4cd::Zero();
    V.block<3, 1>(0, 0) = (e1.cast<std::complex<double>>() - i * e2.cast<std::complex<double>>()) / std::sqrt(2.0);
    V.block<3, 1>(0, 1) = V.block<3, 1>(0, 0).conjugate();
    V.block<3, 1>(0, 2) = w.cast<std::complex<double>>();
    V.col(3) = Eigen::Vector4d(w.cross(v).homogeneous()).normalized().cast<std::complex<double>>();
    const Eigen::Vector4d s = Eigen::JacobiSVD<Eigen::Matrix4cd>(V).singularValues();
    return 1.1 * std::pow(s(0) / s(3), 2);
  }
  // Identity and rank of a projected generator: exact to the rounding of the eigen-decomposition in project().
  static constexpr double kProjectedTol = 1e-10;
};

struct TranslationTraits {
  using Group = vpProjectiveTranslation;
  static std::string name() { return "Translation"; }
  static constexpr vpProjectiveJoint::vpJointType kType = vpProjectiveJoint::PRISMATIC;
  static constexpr vpProjectiveDisplacement::vpMotionType kMotion = vpProjectiveDisplacement::TRANSLATION;

  // The simulator's translation by \e amount metres along the joint's (unit) direction.
  static vpHomogeneousMatrix worldMotion(const Joint &j, double amount)
  {
    return vpSimulatorStereoRig::translationAlong(j.direction, amount);
  }
  // Encoder lengths (m) for the logarithm (31): both signs, from 2 mm to 50 cm.
  static std::vector<double> logAmounts() { return {0.002, 0.01, 0.05, -0.03, -0.07, -0.2, 0.3, 0.4, -0.5}; }
  static constexpr double kRange = 0.5;
  // A translation turns by no angle; the angle of (21) is then an arccos near 1, which turns a rounding d of its
  // argument into sqrt(2 d): ~5e-7 at the worst d ~ 1e-13 of the rig's frame.
  static double imageAngle(double) { return 0.0; }
  static constexpr double kAngleTol = 1e-6;

  // Hhat^2 = 0 relative to |Hhat|^2 (written here, not through generatorResidual()).
  static double identityDefect(const Eigen::Matrix4d &G) { return (G * G).norm() / G.squaredNorm(); }
  static constexpr int kRank = 1;
  // Nilpotent: every eigenvalue is 0.
  static constexpr double kTraceOfSquare = 0.0;
  // A rank-1 sigma u v^T with u orthogonal to v is nilpotent to rounding.
  static constexpr double kStructureTol = 1e-12;
  // I + a That is the simulator's translation to rounding (|a| <= 0.5, unit That).
  static constexpr double kConventionTol = 1e-14;
  static const char *notAGenerator() { return "not a p-translation generator"; }

  /*
    The logarithm of a noisy p-translation. Read in the metric frame (|That| = 1), the algebraic generator's error is
    |T E| / tau <= eps |T|_F / tau; the normalisation (12) changes T (I + E) by 1 - tr(E)/4, of the same order: bound
    C eps with C = 1.5 |T|_F / tau. The relative noise must stay well below tau for the log to mean anything, hence
    smaller eps than for rotations.
  */
  static std::vector<double> noisyAmounts() { return {0.02, 0.1, -0.3}; }
  static constexpr double kNoise[2] = {1e-7, 1e-5};
  static double algebraicBound(const Eigen::Matrix4d &T, const Eigen::Matrix4d &, double tau)
  {
    return 1.5 * T.norm() / std::abs(tau);
  }
  // The generator (31) before its projection, (H - I) / tau, of a normalised H.
  static Eigen::Matrix4d algebraicGenerator(const Eigen::Matrix4d &Hn, double tau)
  {
    return (Hn - Eigen::Matrix4d::Identity()) / tau;
  }
  /*
    How much project() can amplify an error, and where. It works in the rig's frame, where its errors are read: the
    best rank-1 approximation sigma_1 u_1 v_1^T of A = Hhat + dA is within |dA| of A (Eckart-Young; Hhat has rank 1),
    to first order the orthogonal projection of dA on the tangent space of rank-1 matrices, of norm <= |dA|_F; making
    u_1 orthogonal to v_1 then subtracts sigma_1 (v_1 . u_1) v_1 v_1^T, to first order (v^T dA v + u^T dA u) v v^T,
    of norm <= |<dA, v v^T + u u^T>| <= sqrt(2) |dA|_F. Bound (1 + sqrt(2)) |dA|_F, 3 with the second order. (Not a
    metric-frame bound: an SVD does not commute with the change of frame, whose conditioning, ~4e3, could amplify
    errors read there by up to its square.)
  */
  static Eigen::Matrix4d errorFrame(const Scene &, const Eigen::Matrix4d &X) { return X; }
  static double amplificationBound(const Eigen::Matrix4d &) { return 3.0; }
  // Identity and rank of a projected generator: an SVD and one orthogonalisation, exact to rounding.
  static constexpr double kProjectedTol = 1e-12;
};

// The ground truth of one joint of the group of \e Traits, seen by the scene's rig.
template <typename Traits> struct Truth {
  const Scene &scene;
  Joint joint;

  // The unit metric twist That of the joint in the left camera frame.
  Eigen::Matrix4d metricTwist() const
  {
    const Eigen::Vector3d w = scene.cameraDirection(joint.direction).normalized();
    const Eigen::Vector3d p = scene.cameraPoint(joint.point).head<3>();
    return vpProjectiveJoint::twist(Traits::kType, w, p);
  }
  // The true generator H_PE^-1 That H_PE.
  Eigen::Matrix4d generator() const { return scene.HpeInv * metricTwist() * scene.Hpe; }
  // The simulator's metric motion by \e amount in the left camera frame, T_l.
  Eigen::Matrix4d metricMotion(double amount) const
  {
    return scene.cameraDisplacement(Traits::worldMotion(joint, amount));
  }
  // The true p-motion H_PE^-1 T_l H_PE (det 1).
  Eigen::Matrix4d motion(double amount) const
  {
    return scene.projectiveDisplacement(Traits::worldMotion(joint, amount));
  }
};

template <typename Traits> class JointGroup : public ::testing::Test
{
protected:
  const Scene scene;

  Truth<Traits> randomTruth(vpUniRand &rng) const { return Truth<Traits>{scene, randomJoint(rng)}; }
};

struct GroupNames {
  template <typename Traits> static std::string GetName(int) { return Traits::name(); }
};

using Groups = ::testing::Types<RotationTraits, TranslationTraits>;
} // namespace

TYPED_TEST_SUITE(JointGroup, Groups, GroupNames);

// ---------------------------------------------------------------------------------------------------------------
// Both groups
// ---------------------------------------------------------------------------------------------------------------

// The ground truth itself: the exponential of the metric twist, by an independent series and by the plugin's closed
// form, is the simulator's metric motion.
TYPED_TEST(JointGroup, MetricTwistIsTheSimulatorsMotion)
{
  using Traits = TypeParam;
  vpUniRand rng(1);
  for (int k = 0; k < 5; ++k) {
    const Truth<Traits> truth = this->randomTruth(rng);
    const Eigen::Matrix4d That = truth.metricTwist();
    std::vector<double> amounts = Traits::logAmounts();
    amounts.push_back(rng.uniform(-Traits::kRange, Traits::kRange));
    for (double a : amounts) {
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", amount " << a);
      const Eigen::Matrix4d T = truth.metricMotion(a);
      EXPECT_LT((expm(Eigen::Matrix4d(a * That)) - T).norm(), Traits::kConventionTol);
      EXPECT_LT((Traits::Group::exp(That, a) - T).norm(), Traits::kConventionTol);
    }
  }
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
  vpUniRand rng(2);
  for (int k = 0; k < 5; ++k) {
    const Group G(this->randomTruth(rng).generator());
    EXPECT_EQ(G.exp(0.0).matrix(), I);
    EXPECT_EQ(Group::exp(G.generator(), 0.0), I);
  }
}

TYPED_TEST(JointGroup, LogRecoversTrueGenerator)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(3);
  double worst = 0.0;
  for (int k = 0; k < 5; ++k) {
    const Truth<Traits> truth = this->randomTruth(rng);
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
      // The vpMatrix path, and the vpMatrix accessor.
      const Group Gv = Group::log(vpProjectiveDisplacement(toVisp(H)), a);
      EXPECT_LT(relativeError(Gv.generator(), Gtrue), 1e-9);
      EXPECT_LT((Gv.getGenerator() - toVisp(Gv.generator())).frobeniusNorm(), 1e-15);
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
  }
  std::cout << "[ stats    ] " << Traits::name() << " log, noise free: worst relative generator error " << worst
            << std::endl;
}

// exp(log H) = H from H of any scale, and log(exp(a)) = the generator.
TYPED_TEST(JointGroup, ExpAndLogAreInverse)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(4);
  for (int k = 0; k < 5; ++k) {
    const Truth<Traits> truth = this->randomTruth(rng);
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
  }
}

TYPED_TEST(JointGroup, GeneratorStructure)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(5);
  for (int k = 0; k < 5; ++k) {
    const Truth<Traits> truth = this->randomTruth(rng);
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
  }
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
  vpUniRand rng(6);
  for (int k = 0; k < 5; ++k) {
    const Truth<Traits> truth = this->randomTruth(rng);
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
  }
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
  vpUniRand rng(7);
  double worst = 0.0;
  for (int k = 0; k < 5; ++k) {
    const Group G(this->randomTruth(rng).generator());
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
  }
  std::cout << "[ stats    ] " << Traits::name() << " dexp against numeric differentiation: worst relative error "
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
  vpUniRand rng(9);
  for (int k = 0; k < 5; ++k) {
    const Group G(this->randomTruth(rng).generator());
    const Eigen::Matrix4d &Hhat = G.generator();
    const double terms = 2.0 + Hhat.norm() + Hhat.squaredNorm();
    for (int trial = 0; trial < 5; ++trial) {
      const double t = rng.uniform(-Traits::kRange, Traits::kRange);
      SCOPED_TRACE(::testing::Message() << "joint " << k << ", t " << t);
      const Eigen::Matrix4d E = G.exp(t).matrix();
      const Eigen::Vector4d M(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0),
                              rng.uniform(-1.0, 1.0));
      EXPECT_LT(relativeError(Group::exp(Hhat, t), E), 1e-15);
      EXPECT_LT(relativeError(vpProjectiveJoint::exp(Traits::kType, Hhat, t), E), 1e-15);
      EXPECT_LT((Group::act(Hhat, t, M) - E * M).norm(), 1e-14 * terms * M.norm());
      EXPECT_LT((vpProjectiveJoint::act(Traits::kType, Hhat, t, M) - E * M).norm(), 1e-14 * terms * M.norm());
      const Eigen::Matrix<long double, 4, 4> El =
          Group::exp(Eigen::Matrix<long double, 4, 4>(Hhat.cast<long double>()), static_cast<long double>(t));
      EXPECT_LT((Eigen::Matrix4d(El.template cast<double>()) - E).norm(), 1e-14 * terms);
    }
  }
}

/*
  project(): an exact generator is left unchanged (to the rounding of its decomposition, 1e-10 relative in the rig's
  frame); a generator perturbed by eps |Hhat| N (N random, unit norm) is projected on an exact generator (identity and
  rank to rounding), idempotently, no farther from the unperturbed one than the group's amplification bound (see the
  traits) times the perturbation, and first order in eps: the mean ratio distance / eps is the same at eps = 1e-6 and
  1e-4 (within 5 %, 20 seeds). The perturbation is drawn in the metric frame and carried to the rig's, as a noisy
  estimate of the metric twist would be.
*/
TYPED_TEST(JointGroup, ProjectKeepsExactAndProjectsNoisyGenerators)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  const Scene &scene = this->scene;
  vpUniRand rng(10);
  double worstAmplification = 0.0;
  for (int k = 0; k < 3; ++k) {
    SCOPED_TRACE(::testing::Message() << "joint " << k);
    const Truth<Traits> truth = this->randomTruth(rng);
    const Eigen::Matrix4d Hhat = truth.generator(), That = truth.metricTwist();
    EXPECT_LT(relativeError(Group::project(Hhat), Hhat), 1e-10);
    EXPECT_LT(relativeError(Group::project(That), That), 1e-10);
    EXPECT_LT(relativeError(vpProjectiveJoint::project(Traits::kType, Hhat), Hhat), 1e-10);

    const double bound = Traits::amplificationBound(That);
    const double eps[2] = {1e-6, 1e-4};
    double meanRatio[2] = {0.0, 0.0};
    const int seeds = 20;
    for (int level = 0; level < 2; ++level) {
      for (int seed = 1; seed <= seeds; ++seed) {
        SCOPED_TRACE(::testing::Message() << "eps " << eps[level] << ", seed " << seed);
        vpGaussRand noise(1.0, 0.0, seed);
        const Eigen::Matrix4d noisy = scene.HpeInv * (That + eps[level] * That.norm() * unitNoise(noise)) * scene.Hpe;
        const Eigen::Matrix4d P = Group::project(noisy);
        EXPECT_LT(Traits::identityDefect(P), Traits::kProjectedTol);
        EXPECT_LT(singularValues(P)(Traits::kRank), Traits::kProjectedTol * singularValues(P)(0));
        EXPECT_LT(relativeError(Group::project(P), P), 1e-10);
        const Eigen::Matrix4d G = Traits::errorFrame(scene, Hhat);
        const double distance = (Traits::errorFrame(scene, P) - G).norm();
        const double perturbation = (Traits::errorFrame(scene, noisy) - G).norm();
        EXPECT_LT(distance, bound * perturbation);
        worstAmplification = std::max(worstAmplification, distance / perturbation / bound);
        meanRatio[level] += relativeError(Eigen::Matrix4d(scene.Hpe * P * scene.HpeInv), That) / eps[level] / seeds;
      }
    }
    EXPECT_NEAR(meanRatio[1] / meanRatio[0], 1.0, 0.05);
  }
  std::cout << "[ stats    ] " << Traits::name() << " project(): worst amplification / bound " << worstAmplification
            << std::endl;
}

/*
  The logarithm of a noisy motion: the metric motion is perturbed, T (I + E) with |E|_F = eps (E Gaussian; a relative
  error of the motion, the kind an estimate from noisy markers has), and seen in the rig's frame,
  H = H_PE^-1 T (I + E) H_PE. The algebraic generator A (before the projection) is then not exactly a generator;
  log() projects it on one, so the result must satisfy the identity and the rank to rounding (and the eigenvalues:
  trace(Hhat^2) = -2 for a unit-speed rotation, 0 for a translation). Its error is bounded in two derived steps: A's
  error in the metric frame is below C eps (C derived at the traits), and the projection amplifies an error at most
  by the group's bound, read in the group's frame (see the traits); and it is first order in eps: the mean ratio of
  the metric-frame error to eps is the same at both noise levels (within 5 %, 20 seeds).
*/
TYPED_TEST(JointGroup, NoisyLogIsExactGeneratorWithBoundedError)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  const Scene &scene = this->scene;
  vpUniRand rng(11);
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  double worstAlgebraicOverC = 0.0, worstAmplification = 0.0;
  for (int k = 0; k < 3; ++k) {
    const Truth<Traits> truth = this->randomTruth(rng);
    const Eigen::Matrix4d That = truth.metricTwist(), Gtrue = truth.generator();
    const double bound = Traits::amplificationBound(That);
    for (double a : Traits::noisyAmounts()) {
      const Eigen::Matrix4d T = truth.metricMotion(a);
      const double C = Traits::algebraicBound(T, That, a);
      double meanRatio[2] = {0.0, 0.0};
      const int seeds = 20;
      for (int level = 0; level < 2; ++level) {
        const double eps = Traits::kNoise[level];
        for (int seed = 1; seed <= seeds; ++seed) {
          SCOPED_TRACE(::testing::Message()
                       << "joint " << k << ", amount " << a << ", eps " << eps << ", seed " << seed);
          vpGaussRand noise(1.0, 0.0, seed);
          const Eigen::Matrix4d Tn = T * (I + eps * unitNoise(noise));
          const Group G = Group::log(vpProjectiveDisplacement(Eigen::Matrix4d(scene.HpeInv * Tn * scene.Hpe)), a);
          const Eigen::Matrix4d &Hhat = G.generator();
          EXPECT_LT(Group::generatorResidual(Hhat), Traits::kProjectedTol);
          EXPECT_LT(singularValues(Hhat)(Traits::kRank), Traits::kProjectedTol * singularValues(Hhat)(0));
          EXPECT_NEAR((Hhat * Hhat).trace(), Traits::kTraceOfSquare, 1e-9);

          const Eigen::Matrix4d A = Traits::algebraicGenerator(vpProjectiveDisplacement::normalize(Tn), a);
          const double algebraicError = relativeError(A, That);
          EXPECT_LT(algebraicError, C * eps);
          const Eigen::Matrix4d Gf = Traits::errorFrame(scene, Gtrue);
          const double amplification =
              (Traits::errorFrame(scene, Hhat) - Gf).norm() /
              (Traits::errorFrame(scene, Eigen::Matrix4d(scene.HpeInv * A * scene.Hpe)) - Gf).norm();
          EXPECT_LT(amplification, bound);
          meanRatio[level] += relativeError(Eigen::Matrix4d(scene.Hpe * Hhat * scene.HpeInv), That) / eps / seeds;
          worstAlgebraicOverC = std::max(worstAlgebraicOverC, algebraicError / (C * eps));
          worstAmplification = std::max(worstAmplification, amplification / bound);
        }
      }
      EXPECT_NEAR(meanRatio[1] / meanRatio[0], 1.0, 0.05) << "joint " << k << ", amount " << a;
    }
  }
  std::cout << "[ stats    ] " << Traits::name()
            << " log of a noisy H: worst algebraic error / (C eps) = " << worstAlgebraicOverC
            << ", worst projection amplification / bound = " << worstAmplification << std::endl;
}

TYPED_TEST(JointGroup, BadInputsThrow)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(12);
  const Truth<Traits> truth = this->randomTruth(rng);
  const double a = Traits::logAmounts()[2];
  const Eigen::Matrix4d H = truth.motion(a);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto logOfMatrix = [&](const auto &M, double amount) {
    return Group::log(vpProjectiveDisplacement(M), amount);
  };

  // A displacement that cannot be normalised: non-finite, mis-sized, zero or singular.
  Eigen::Matrix4d bad = H;
  bad(2, 1) = nan;
  EXPECT_TRUE(throwsProjective([&] { logOfMatrix(bad, a); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(
      throwsProjective([&] { logOfMatrix(toVisp(bad), a); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { logOfMatrix(vpMatrix(3, 3, 1.0), a); }, vpProjectiveException::dimensionError,
                               "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { logOfMatrix(Eigen::Matrix4d(Eigen::Matrix4d::Zero()), a); },
                               vpProjectiveException::invalidValueError, "zero matrix"));
  for (int copy = 0; copy < 2; ++copy) {
    Eigen::Matrix4d singular = H;
    if (copy == 0) {
      singular.row(3) = singular.row(2);
    } else {
      singular.col(2) = singular.col(1);
    }
    EXPECT_TRUE(throwsProjective([&] { logOfMatrix(singular, a); }, vpProjectiveException::degenerateConfigurationError,
                                 "singular"));
  }
  // A non-finite encoder amount.
  for (double amount : {nan, inf, -inf}) {
    EXPECT_TRUE(
        throwsProjective([&] { logOfMatrix(H, amount); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  }

  // Matrices that are no generators of the group, or no matrices at all.
  const Eigen::Matrix4d random = randomMatrix(rng);
  EXPECT_TRUE(
      throwsProjective([&] { Group G(random); }, vpProjectiveException::invalidValueError, Traits::notAGenerator()));
  EXPECT_TRUE(throwsProjective([&] { Group G(toVisp(random)); }, vpProjectiveException::invalidValueError,
                               Traits::notAGenerator()));
  const Eigen::Matrix4d Gtrue = truth.generator();
  for (double value : {nan, inf}) {
    Eigen::Matrix4d nonFinite = Gtrue;
    nonFinite(1, 1) = value;
    EXPECT_TRUE(throwsProjective([&] { Group G(nonFinite); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  }
  EXPECT_TRUE(
      throwsProjective([&] { Group G(vpMatrix(3, 3, 0.0)); }, vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(
      throwsProjective([&] { Group G(vpMatrix(4, 3, 0.0)); }, vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { Group G(Gtrue, -1.0); }, vpProjectiveException::invalidValueError, "tolerance"));
}

// ---------------------------------------------------------------------------------------------------------------
// Rotations only
// ---------------------------------------------------------------------------------------------------------------

// Without an encoder reading (amount 0), the generator turns by the positive image angle (21): the joint's own for a
// positive motion, the reversed joint's for a negative one.
TEST(vpProjectiveRotation, LogWithoutEncoderUsesThePositiveImageAngle)
{
  const Scene scene;
  vpUniRand rng(21);
  for (int k = 0; k < 5; ++k) {
    const Truth<RotationTraits> truth{scene, randomJoint(rng)};
    const Eigen::Matrix4d Gtrue = truth.generator();
    for (double theta : {0.05, 0.5, 1.2, 2.5, 3.0}) {
      SCOPED_TRACE(::testing::Message() << "axis " << k << ", theta " << theta);
      const vpProjectiveDisplacement H(truth.motion(theta)), Hneg(truth.motion(-theta));
      EXPECT_LT(relativeError(vpProjectiveRotation::log(H, 0.0).generator(), Gtrue), 1e-9);
      EXPECT_LT(relativeError(vpProjectiveRotation::log(Hneg, 0.0).generator(), Eigen::Matrix4d(-Gtrue)), 1e-9);
    }
  }
}

TEST(vpProjectiveRotation, ExpIsPeriodic)
{
  const Scene scene;
  vpUniRand rng(22);
  for (int k = 0; k < 5; ++k) {
    const vpProjectiveRotation R(Truth<RotationTraits>{scene, randomJoint(rng)}.generator());
    EXPECT_LT(relativeError(R.exp(2.0 * M_PI).matrix(), Eigen::Matrix4d(Eigen::Matrix4d::Identity())), 1e-9);
    const double t = rng.uniform(-4.0, 4.0);
    EXPECT_LT(relativeError(R.exp(t + 2.0 * M_PI).matrix(), R.exp(t).matrix()), 1e-9);
  }
}

TEST(vpProjectiveRotation, DegenerateInputsThrow)
{
  const Scene scene;
  vpUniRand rng(23);
  const Truth<RotationTraits> truth{scene, randomJoint(rng)};
  const auto logOf = [](const Eigen::Matrix4d &H, double amount) {
    return vpProjectiveRotation::log(vpProjectiveDisplacement(H), amount);
  };

  // No rotation, or a half turn: the logarithm (25) divides by sin(theta).
  EXPECT_TRUE(throwsProjective([&] { logOf(Eigen::Matrix4d::Identity(), 0.0); },
                               vpProjectiveException::degenerateConfigurationError, "multiple of pi"));
  EXPECT_TRUE(throwsProjective([&] { logOf(truth.motion(1e-9), 1e-9); },
                               vpProjectiveException::degenerateConfigurationError, "multiple of pi"));
  EXPECT_TRUE(throwsProjective([&] { logOf(truth.motion(M_PI), M_PI); },
                               vpProjectiveException::degenerateConfigurationError, "pi"));
  // A pure translation has angle 0 (21).
  const Eigen::Matrix4d Ht = scene.projectiveDisplacement(vpSimulatorStereoRig::translationAlong(point3(1, 0, 0), 0.1));
  EXPECT_TRUE(
      throwsProjective([&] { logOf(Ht, 0.0); }, vpProjectiveException::degenerateConfigurationError, "multiple of pi"));

  // Twice a generator: Hhat^3 = 4 (-Hhat), no longer -Hhat.
  const Eigen::Matrix4d G = truth.generator();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(Eigen::Matrix4d(2.0 * G)); },
                               vpProjectiveException::invalidValueError, "not a p-rotation generator"));
  // A p-translation generator (nilpotent) is not a p-rotation generator: its residual |Hhat^3 + Hhat| / |Hhat| is 1.
  const Eigen::Matrix4d Tt = scene.HpeInv * vpMetricTwist::prismatic(Eigen::Vector3d(1.0, 0.0, 0.0)) * scene.Hpe;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(Tt); }, vpProjectiveException::invalidValueError,
                               "not a p-rotation generator"));
}

// ---------------------------------------------------------------------------------------------------------------
// Translations only
// ---------------------------------------------------------------------------------------------------------------

/*
  The generator is per unit of the encoder: the same motion read as 2 tau gives half the generator. exp is affine in
  tau, so its derivative is the generator itself: dexp(tau) = Hhat = Hhat exp(tau Hhat) (Hhat^2 = 0). A p-translation
  generator is no p-rotation generator (|Hhat^3 + Hhat| / |Hhat| = 1).
*/
TEST(vpProjectiveTranslation, GeneratorIsPerUnitOfEncoder)
{
  const Scene scene;
  vpUniRand rng(31);
  for (int k = 0; k < 5; ++k) {
    const Truth<TranslationTraits> truth{scene, randomJoint(rng)};
    const Eigen::Matrix4d Gtrue = truth.generator();
    for (double tau : TranslationTraits::logAmounts()) {
      SCOPED_TRACE(::testing::Message() << "direction " << k << ", tau " << tau);
      const vpProjectiveDisplacement H(truth.motion(tau));
      EXPECT_LT(relativeError(vpProjectiveTranslation::log(H, 2.0 * tau).generator(), Eigen::Matrix4d(0.5 * Gtrue)),
                1e-9);
      const vpProjectiveTranslation T = vpProjectiveTranslation::log(H, tau);
      EXPECT_EQ(T.dexp(tau), T.generator());
      EXPECT_LT(relativeError(Eigen::Matrix4d(T.generator() * T.exp(tau).matrix()), T.generator()), 1e-9);
      EXPECT_GT(vpProjectiveRotation::generatorResidual(T.generator()), 0.5);
    }
  }
}

TEST(vpProjectiveTranslation, DegenerateInputsThrow)
{
  const Scene scene;
  vpUniRand rng(32);
  const Truth<TranslationTraits> truth{scene, randomJoint(rng)};
  const vpProjectiveDisplacement H(truth.motion(0.1));

  // No encoder length: the generator cannot be scaled.
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation::log(H, 0.0); }, vpProjectiveException::invalidValueError,
                               "zero"));
  // A p-rotation generator (Hhat^3 = -Hhat, not nilpotent), a rank-1 matrix that is not nilpotent (a projector).
  const Eigen::Matrix4d rotation =
      scene.HpeInv * vpMetricTwist::hat(Eigen::Vector3d(0.0, 0.0, 0.0), Eigen::Vector3d(0.0, 0.0, 1.0)) * scene.Hpe;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(rotation); }, vpProjectiveException::invalidValueError,
                               "not a p-translation generator"));
  const Eigen::Vector4d u(1.0, 2.0, -1.0, 0.5);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(Eigen::Matrix4d(u * u.transpose())); },
                               vpProjectiveException::invalidValueError, "not a p-translation generator"));
}
