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
  The one group API of the three groups, p-displacements (vpProjectiveDisplacement, PSE(3)), p-rotations
  (vpProjectiveRotation) and p-translations (vpProjectiveTranslation), checked by one typed suite (GroupAPI) as
  manif's common tester does: every group is driven through the same names, and a traits struct per group says only
  what truly differs (its metric generator, its amounts, how an element is made from a generator). Operations:
  - exp: the kernel G::exp(Hhat, q) (static, templated on the scalar) is the true motion H_PE^-1 expm(q That) H_PE
    (independent series), the object form (vpProjectiveDisplacement::exp(q Hhat), or G(Hhat).exp(q)) is the kernel,
    and every group's kernel is the general series vpProjectiveDisplacement::exp(Hhat, q) it specialises;
  - log: G::log(H, q) inverts exp for any scale and sign of H;
  - inverse: exp(Hhat, q)^-1 = exp(Hhat, -q), as the element's inverse();
  - compose: exp(Hhat, a) exp(Hhat, b) = exp(Hhat, a + b), as the elements' operator*();
  - act: the kernel G::act(Hhat, q, M) is exp(Hhat, q) M, and the element's act(M) is H M, also for points at
    infinity (no division by a last coordinate);
  - the kernels on ceres::Jet: their derivatives in q are Hhat exp(q Hhat) and Hhat exp(q Hhat) M (the analytic
    derivative of a one-parameter subgroup), checked against central differences of the double kernels too.
  Bounds: errors relative (Frobenius), read in the metric frame (H_PE X H_PE^-1) where the matrices are of order 1;
  1e-9 noise-free as in testProjectiveJointGroup (rounding in the rig's frame, cond(H_PE) ~ 4e3, is ~1e-12), 1e-14
  where two forms of one expression are compared (rounding of a few products). Seeded vpUniRand throughout.
*/

#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <ceres/jet.h>
#include <gtest/gtest.h>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveTranslation.h>

#include "vpProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{
Eigen::Vector3d unitVector(vpUniRand &rng)
{
  return toEigen<3, 1>(randomDirection(rng));
}

// A point near the fixation point, in the left camera frame (metres).
Eigen::Vector3d pointNearFixation(const Scene &scene, vpUniRand &rng)
{
  const double dz = rng.uniform(-0.1, 0.1); // drawn last to first: see point3(), vpProjectiveTestTools.h
  const double dy = rng.uniform(-0.1, 0.1);
  const double dx = rng.uniform(-0.1, 0.1);
  return scene.cameraPoint(Scene::fixation()).head<3>() + Eigen::Vector3d(dx, dy, dz);
}

// ---------------------------------------------------------------------------------------------------------------
// What differs between the groups
// ---------------------------------------------------------------------------------------------------------------

struct DisplacementTraits {
  using Group = vpProjectiveDisplacement;
  static std::string name() { return "Displacement"; }
  // A screw of unit angular speed about an axis near the fixation point, with a pitch up to 5 cm per radian.
  static Eigen::Matrix4d metricGenerator(const Scene &scene, vpUniRand &rng)
  {
    const Eigen::Vector3d w = unitVector(rng);
    // The pitch, then the point: drawn last to first, see point3(), vpProjectiveTestTools.h.
    const double pitch = rng.uniform(-0.05, 0.05);
    const Eigen::Vector3d point = pointNearFixation(scene, rng);
    return vpMetricTwist::revolute(w, point) + vpMetricTwist::prismatic(Eigen::Vector3d(pitch * w));
  }
  // Angles in (-pi, pi), where the principal logarithm is this exponential's inverse.
  static std::vector<double> amounts() { return {0.05, -0.3, 0.9, -1.7, 2.4, -2.9, 3.0}; }
  static vpProjectiveDisplacement element(const Eigen::Matrix4d &Hhat, double q)
  {
    return vpProjectiveDisplacement::exp(Eigen::Matrix4d(q * Hhat));
  }
  static Eigen::Matrix4d generatorOf(const Eigen::Matrix4d &Hhat) { return Hhat; }
};

struct RotationTraits {
  using Group = vpProjectiveRotation;
  static std::string name() { return "Rotation"; }
  static Eigen::Matrix4d metricGenerator(const Scene &scene, vpUniRand &rng)
  {
    // The point, then the axis: drawn last to first, see point3(), vpProjectiveTestTools.h.
    const Eigen::Vector3d point = pointNearFixation(scene, rng);
    const Eigen::Vector3d axis = unitVector(rng);
    return vpMetricTwist::revolute(axis, point);
  }
  static std::vector<double> amounts() { return {0.05, -0.3, 0.9, -1.7, 2.4, -2.9, 3.0}; }
  static vpProjectiveDisplacement element(const Eigen::Matrix4d &Hhat, double q)
  {
    return vpProjectiveRotation(Hhat).exp(q);
  }
  static Eigen::Matrix4d generatorOf(const vpProjectiveRotation &G) { return G.generator(); }
};

struct TranslationTraits {
  using Group = vpProjectiveTranslation;
  static std::string name() { return "Translation"; }
  static Eigen::Matrix4d metricGenerator(const Scene &, vpUniRand &rng)
  {
    return vpMetricTwist::prismatic(unitVector(rng));
  }
  // Lengths in metres.
  static std::vector<double> amounts() { return {0.002, -0.01, 0.05, -0.2, 0.3, -0.5}; }
  static vpProjectiveDisplacement element(const Eigen::Matrix4d &Hhat, double q)
  {
    return vpProjectiveTranslation(Hhat).exp(q);
  }
  static Eigen::Matrix4d generatorOf(const vpProjectiveTranslation &G) { return G.generator(); }
};

template <typename Traits> class GroupAPI : public ::testing::Test
{
protected:
  const Scene scene;

  // The generator H_PE^-1 That H_PE of a random metric generator That of the group.
  Eigen::Matrix4d randomGenerator(vpUniRand &rng, Eigen::Matrix4d &That) const
  {
    That = Traits::metricGenerator(scene, rng);
    return scene.HpeInv * That * scene.Hpe;
  }
  // X read in the metric frame.
  Eigen::Matrix4d metric(const Eigen::Matrix4d &X) const { return scene.Hpe * X * scene.HpeInv; }
  // body(k, Hhat, That, q, rng) for 5 random generators k drawn from \e seed and each of the group's amounts q, traced.
  template <typename Body> void forEachGeneratorAndAmount(long seed, Body body) const
  {
    vpUniRand rng(seed);
    for (int k = 0; k < 5; ++k) {
      Eigen::Matrix4d That;
      const Eigen::Matrix4d Hhat = randomGenerator(rng, That);
      for (double q : Traits::amounts()) {
        SCOPED_TRACE(::testing::Message() << "generator " << k << ", amount " << q);
        body(k, Hhat, That, q, rng);
      }
    }
  }
  // A random projective point near the fixation point, unit norm; every fourth one at infinity (last coordinate 0).
  Eigen::Vector4d randomPoint(vpUniRand &rng, int k) const
  {
    Eigen::Vector4d N = pointNearFixation(scene, rng).homogeneous();
    if (k % 4 == 3) {
      N(3) = 0.0;
    }
    return (scene.HpeInv * N).normalized();
  }
};

struct GroupNames {
  template <typename Traits> static std::string GetName(int) { return Traits::name(); }
};

using Groups = ::testing::Types<DisplacementTraits, RotationTraits, TranslationTraits>;
} // namespace

TYPED_TEST_SUITE(GroupAPI, Groups, GroupNames);

// exp: the kernel is the true motion; the object form is the kernel; each kernel is the general series.
TYPED_TEST(GroupAPI, ExpIsTheTrueMotion)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  this->forEachGeneratorAndAmount(
      11, [&](int, const Eigen::Matrix4d &Hhat, const Eigen::Matrix4d &That, double q, vpUniRand &) {
        const Eigen::Matrix4d E = Group::exp(Hhat, q);
        const Eigen::Matrix4d T = expm(Eigen::Matrix4d(q * That));
        EXPECT_LT(relativeError(this->metric(E), T), 1e-9);
        EXPECT_LT(relativeError(Traits::element(Hhat, q).matrix(), E), 1e-14);
        EXPECT_LT(relativeError(this->metric(vpProjectiveDisplacement::exp(Hhat, q)), this->metric(E)), 1e-9);
        EXPECT_EQ(Group::exp(Hhat, 0.0), Eigen::Matrix4d(Eigen::Matrix4d::Identity()));
      });
}

// log: the inverse of exp, whatever the scale and sign of H (normalisation (12)).
TYPED_TEST(GroupAPI, LogInvertsExp)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  this->forEachGeneratorAndAmount(
      12, [&](int k, const Eigen::Matrix4d &Hhat, const Eigen::Matrix4d &That, double q, vpUniRand &rng) {
        const double scale = (k % 2 ? -1.0 : 1.0) * rng.uniform(0.01, 100.0);
        const vpProjectiveDisplacement H(Eigen::Matrix4d(scale * Group::exp(Hhat, q)));
        const Eigen::Matrix4d back = Traits::generatorOf(Group::log(H, q));
        EXPECT_LT(relativeError(this->metric(back), That), 1e-9);
      });
}

// inverse: exp(Hhat, q)^-1 = exp(Hhat, -q), the element's inverse().
TYPED_TEST(GroupAPI, InverseIsExpOfTheOppositeAmount)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  this->forEachGeneratorAndAmount(
      13, [&](int, const Eigen::Matrix4d &Hhat, const Eigen::Matrix4d &, double q, vpUniRand &) {
        const vpProjectiveDisplacement H = Traits::element(Hhat, q);
        EXPECT_LT(relativeError(this->metric(H.inverse().matrix()), this->metric(Group::exp(Hhat, -q))), 1e-9);
        EXPECT_LT(relativeError(this->metric(Eigen::Matrix4d(Group::exp(Hhat, -q) * H.matrix())), I), 1e-9);
      });
}

// compose: exp(Hhat, a) exp(Hhat, b) = exp(Hhat, a + b), by the elements' operator*() and by the kernels.
TYPED_TEST(GroupAPI, ComposeAddsAmounts)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(14);
  const std::vector<double> amounts = Traits::amounts();
  for (int k = 0; k < 5; ++k) {
    Eigen::Matrix4d That;
    const Eigen::Matrix4d Hhat = this->randomGenerator(rng, That);
    for (size_t i = 0; i + 1 < amounts.size(); ++i) {
      const double a = amounts[i], b = amounts[i + 1];
      SCOPED_TRACE(::testing::Message() << "generator " << k << ", amounts " << a << ", " << b);
      const Eigen::Matrix4d Eab = this->metric(Group::exp(Hhat, a + b));
      EXPECT_LT(relativeError(this->metric((Traits::element(Hhat, a) * Traits::element(Hhat, b)).matrix()), Eab), 1e-9);
      EXPECT_LT(relativeError(this->metric(Eigen::Matrix4d(Group::exp(Hhat, a) * Group::exp(Hhat, b))), Eab), 1e-9);
    }
  }
}

// act: the kernel is exp(Hhat, q) M without the 4x4 product, the element's act(M) is H M, at infinity too.
TYPED_TEST(GroupAPI, ActMovesPoints)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  vpUniRand rng(15);
  for (int k = 0; k < 8; ++k) {
    Eigen::Matrix4d That;
    const Eigen::Matrix4d Hhat = this->randomGenerator(rng, That);
    const Eigen::Vector4d M = this->randomPoint(rng, k);
    for (double q : Traits::amounts()) {
      SCOPED_TRACE(::testing::Message() << "generator " << k << ", amount " << q);
      const Eigen::Matrix4d E = Group::exp(Hhat, q);
      const Eigen::Vector4d EM = E * M;
      // Both are sums of products of the same entries, in another order: rounding relative to |E| |M|.
      EXPECT_LT((Group::act(Hhat, q, M) - EM).norm(), 1e-13 * E.norm() * M.norm());
      const vpProjectiveDisplacement H = Traits::element(Hhat, q);
      EXPECT_EQ(H.act(M), Eigen::Vector4d(H.matrix() * M));
      vpColVector Mv(4);
      for (unsigned int i = 0; i < 4; ++i) {
        Mv[i] = M(static_cast<Eigen::Index>(i));
      }
      const Eigen::Vector4d moved = toEigen<4, 1>(H.act(Mv));
      EXPECT_EQ(moved, H.act(M));
      // The moved point is the true one: H_PE^-1 T N, up to the normalisation (12) of H (det T = 1: scale 1).
      EXPECT_LT((this->scene.Hpe * H.act(M) - expm(Eigen::Matrix4d(q * That)) * (this->scene.Hpe * M)).norm(),
                1e-9 * (this->scene.Hpe * M).norm());
    }
  }
}

// The kernels on ceres::Jet: the derivative in q of a one-parameter subgroup is Hhat exp(q Hhat) (and times M for
// act), against the analytic form and central differences of the double kernel.
TYPED_TEST(GroupAPI, KernelsDifferentiateOnJets)
{
  using Traits = TypeParam;
  using Group = typename Traits::Group;
  using Jet = ceres::Jet<double, 1>;
  vpUniRand rng(16);
  for (int k = 0; k < 5; ++k) {
    Eigen::Matrix4d That;
    const Eigen::Matrix4d Hhat = this->randomGenerator(rng, That);
    const Eigen::Vector4d M = this->randomPoint(rng, k);
    const Eigen::Matrix<Jet, 4, 4> HhatJ = Hhat.cast<Jet>();
    const Eigen::Matrix<Jet, 4, 1> MJ = M.cast<Jet>();
    std::vector<double> amounts = Traits::amounts();
    amounts.push_back(0.0); // the series branch of the general kernel
    for (double q : amounts) {
      SCOPED_TRACE(::testing::Message() << "generator " << k << ", amount " << q);
      const Jet qJ(q, 0);
      const Eigen::Matrix<Jet, 4, 4> EJ = Group::exp(HhatJ, qJ);
      const Eigen::Matrix<Jet, 4, 1> AJ = Group::act(HhatJ, qJ, MJ);
      Eigen::Matrix4d value, derivative;
      Eigen::Vector4d actValue, actDerivative;
      for (int i = 0; i < 4; ++i) {
        for (int j = 0; j < 4; ++j) {
          value(i, j) = EJ(i, j).a;
          derivative(i, j) = EJ(i, j).v(0);
        }
        actValue(i) = AJ(i).a;
        actDerivative(i) = AJ(i).v(0);
      }
      const Eigen::Matrix4d E = Group::exp(Hhat, q);
      // The same formula on other types: Eigen sums the double products in another (vectorised) order, and the
      // entries of the rig's frame span orders of magnitude, so rounding (measured up to 1.4e-14) rather than equality.
      EXPECT_LT(relativeError(value, E), 1e-12);
      const Eigen::Matrix4d analytic = Hhat * E;
      EXPECT_LT(relativeError(this->metric(derivative), this->metric(analytic)), 1e-9);
      const double h = 1e-4;
      const Eigen::Matrix4d numeric = (Group::exp(Hhat, q + h) - Group::exp(Hhat, q - h)) / (2.0 * h);
      // Central differences: truncation h^2 |Hhat^3| / 6 ~ 2e-9, rounding ~1e-12 |E| / h ~ 1e-8 in the metric frame.
      EXPECT_LT(relativeError(this->metric(numeric), this->metric(analytic)), 1e-6);
      EXPECT_LT((actValue - E * M).norm(), 1e-13 * E.norm() * M.norm());
      // Relative 1e-9, plus the rounding of the products Hhat M (4 terms of size |Hhat| |M| each in the projective
      // frame, read in the metric one through H_PE): 4 eps |H_PE| |Hhat| |M|. It is what is left when the derivative
      // is zero (a point at infinity under a p-translation: Hhat M = 0 by cancellation of such terms; measured
      // 2.6e-15 against 1.2e-11 for eps |H_PE| |Hhat| |M| with g++'s data, 2.58e-13 with clang++'s former draws).
      const double eps = std::numeric_limits<double>::epsilon();
      EXPECT_LT((this->scene.Hpe * (actDerivative - analytic * M)).norm(),
                1e-9 * (this->scene.Hpe * analytic * M).norm() +
                    4.0 * eps * this->scene.Hpe.norm() * Hhat.norm() * M.norm());
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// The p-displacement only
// ---------------------------------------------------------------------------------------------------------------

// The general kernel is continuous across its series branch (theta = 1e-3 rad) and agrees with the object form.
TEST(vpProjectiveDisplacementGroup, KernelSeriesBranchIsContinuous)
{
  const Scene scene;
  vpUniRand rng(17);
  const Eigen::Vector3d w = unitVector(rng);
  const Eigen::Matrix4d That =
      vpMetricTwist::revolute(w, pointNearFixation(scene, rng)) + vpMetricTwist::prismatic(Eigen::Vector3d(0.02 * w));
  const Eigen::Matrix4d Hhat = scene.HpeInv * That * scene.Hpe;
  for (double q : {1e-3 * (1.0 - 1e-9), 1e-3 * (1.0 + 1e-9), 1e-5, 3e-3}) {
    SCOPED_TRACE(::testing::Message() << "amount " << q);
    const Eigen::Matrix4d E = vpProjectiveDisplacement::exp(Hhat, q);
    EXPECT_LT(relativeError(Eigen::Matrix4d(scene.Hpe * E * scene.HpeInv), expm(Eigen::Matrix4d(q * That))), 1e-12);
    EXPECT_EQ(vpProjectiveDisplacement::exp(Eigen::Matrix4d(q * Hhat)).matrix(),
              vpProjectiveDisplacement::exp(Eigen::Matrix4d(q * Hhat), 1.0));
  }
}

// The static log(H, amount) is the member log() (the ViSP-typed contract) divided by the amount.
TEST(vpProjectiveDisplacementGroup, LogForms)
{
  const Scene scene;
  vpUniRand rng(18);
  const Eigen::Matrix4d That = DisplacementTraits::metricGenerator(scene, rng);
  const vpProjectiveDisplacement H(Eigen::Matrix4d(scene.HpeInv * expm(Eigen::Matrix4d(0.8 * That)) * scene.Hpe));
  const vpMatrix Hhat_g = H.log();
  const Eigen::Matrix4d Hhat = toEigen<4, 4>(Hhat_g);
  EXPECT_EQ(Hhat, vpProjectiveDisplacement::log(H));
  EXPECT_LT(relativeError(Eigen::Matrix4d(0.8 * vpProjectiveDisplacement::log(H, 0.8)), Hhat), 1e-15);
}

TEST(vpProjectiveDisplacementGroup, BadInputsThrow)
{
  const Scene scene;
  vpUniRand rng(19);
  const Eigen::Matrix4d That = DisplacementTraits::metricGenerator(scene, rng);
  const vpProjectiveDisplacement H(Eigen::Matrix4d(scene.HpeInv * expm(Eigen::Matrix4d(0.8 * That)) * scene.Hpe));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::log(H, 0.0); }, vpProjectiveException::invalidValueError,
                               "amount is zero"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::log(H, std::numeric_limits<double>::infinity()); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  const vpProjectiveDisplacement halfTurn(
      Eigen::Matrix4d(scene.HpeInv * expm(Eigen::Matrix4d(M_PI * That)) * scene.Hpe));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::log(halfTurn, 2.0); },
                               vpProjectiveException::degenerateConfigurationError, "half turn"));
  EXPECT_TRUE(throwsProjective([&] { H.act(vpColVector(3, 1.0)); }, vpProjectiveException::dimensionError, "4"));
  vpColVector bad(4, 1.0);
  bad[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { H.act(bad); }, vpProjectiveException::nonFiniteValueError, "NaN"));
}
