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
  Tests of vpProjectiveRotation, the one-parameter Lie group of p-rotations exp(theta Hhat) (Ruf & Horaud, eqs.
  (18)-(27)), against the metric simulator:
  - the logarithm (25) of H_PE^-1 T_l(theta) H_PE is the true generator H_PE^-1 That H_PE, That the unit-speed twist
    [[w]x, -w x p; 0 0] of the axis (w unit, p on the axis, left camera frame), with the sign given by the encoder
    amount; the angle is the metric one; exp(log H) = H;
  - the generator's structure: Hhat^3 = -Hhat, rank 2, trace(Hhat^2) = -2 (unit speed);
  - group laws: exp(a) exp(b) = exp(a + b), exp(-t) = exp(t)^-1, d/dt exp(t Hhat) = Hhat exp(t Hhat), conjugation;
  - the logarithm of a noisy H is projected on an exact generator whose error is first order in the noise;
  - invalid inputs throw a vpProjectiveException with a meaningful code and message.

  Noise-free bounds: 1e-9 relative (the work order's), far above rounding (the frame is conditioned by the rig's
  canonical normalisation), far below any modelling error (a wrong sign or axis gives errors of order 1). The central
  difference bound 1e-7 is explained at the test, the noisy bounds too.
*/

#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
//! The tests' view of the one log() signature: the image angle of H comes back in \e angle.
template <typename Matrix> vpProjectiveRotation logOf(const Matrix &H, double &angle, double amount = 0.0)
{
  const vpProjectiveDisplacement D(H);
  angle = D.getRotationAngle();
  return vpProjectiveRotation::log(D, amount);
}

// A revolute axis in the world: a point on it and a unit direction.
struct Axis {
  vpColVector point;
  vpColVector direction;
};

Axis randomAxis(vpUniRand &rng)
{
  Axis a;
  a.point = Scene::fixation() + point3(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1));
  a.direction = randomDirection(rng);
  return a;
}

// The unit-speed metric twist of the axis in the left camera frame: [[w]x, -w x p; 0 0].
Eigen::Matrix4d metricTwist(const Scene &scene, const Axis &a)
{
  const Eigen::Vector3d w = scene.cameraDirection(a.direction).normalized();
  const Eigen::Vector3d p = scene.cameraPoint(a.point).head<3>();
  Eigen::Matrix4d That = Eigen::Matrix4d::Zero();
  That.topLeftCorner<3, 3>() = vpMetricTwist::skew(w);
  That.topRightCorner<3, 1>() = -w.cross(p);
  return That;
}

// The true generator H_PE^-1 That H_PE.
Eigen::Matrix4d trueGenerator(const Scene &scene, const Axis &a)
{
  return scene.HpeInv * metricTwist(scene, a) * scene.Hpe;
}

// The true p-rotation by theta about the axis, H_PE^-1 T_l H_PE (det 1).
Eigen::Matrix4d pRotation(const Scene &scene, const Axis &a, double theta)
{
  return scene.projectiveDisplacement(vpSimulatorStereoRig::rotationAbout(a.point, a.direction, theta));
}

// Standard normal 4x4 matrix scaled to unit Frobenius norm on average (entries of std 1/4).
Eigen::Matrix4d noiseMatrix(vpGaussRand &noise)
{
  Eigen::Matrix4d N;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      N(i, j) = 0.25 * noise();
    }
  }
  return N;
}
} // namespace

// The twist convention of the tests themselves: Rodrigues' formula on That gives the simulator's metric rotation.
TEST(vpProjectiveRotation, MetricTwistConvention)
{
  const Scene scene;
  vpUniRand rng(1);
  for (int k = 0; k < 5; ++k) {
    const Axis a = randomAxis(rng);
    const Eigen::Matrix4d That = metricTwist(scene, a);
    for (double theta : {-2.0, 0.3, 1.0, 3.0}) {
      const Eigen::Matrix4d T =
          scene.cameraDisplacement(vpSimulatorStereoRig::rotationAbout(a.point, a.direction, theta));
      const Eigen::Matrix4d R =
          Eigen::Matrix4d::Identity() + std::sin(theta) * That + (1.0 - std::cos(theta)) * That * That;
      EXPECT_LT((R - T).norm(), 1e-12);
    }
  }
}

TEST(vpProjectiveRotation, LogRecoversTrueGeneratorAndAngle)
{
  const Scene scene;
  vpUniRand rng(2);
  double worst = 0.0;
  for (int k = 0; k < 5; ++k) {
    const Axis a = randomAxis(rng);
    const Eigen::Matrix4d Gtrue = trueGenerator(scene, a);
    for (double theta : {0.05, 0.5, 1.2, 2.5, 3.0}) {
      SCOPED_TRACE(::testing::Message() << "axis " << k << ", theta " << theta);
      // Any scale and sign of H: log() normalises it.
      const Eigen::Matrix4d H = pRotation(scene, a, theta);
      double angle = 0.0;
      const vpProjectiveRotation R = logOf(Eigen::Matrix4d(-2.5 * H), angle, theta);
      EXPECT_NEAR(angle, theta, 1e-9);
      EXPECT_LT(relativeError(R.generator(), Gtrue), 1e-9);
      worst = std::max(worst, relativeError(R.generator(), Gtrue));
      // Without encoder reading, a positive angle: the same generator.
      const vpProjectiveRotation R0 = logOf(H, angle);
      EXPECT_LT(relativeError(R0.generator(), Gtrue), 1e-9);
      // The vpMatrix overload.
      const vpProjectiveRotation Rv = logOf(toVisp(H), angle, theta);
      EXPECT_LT(relativeError(Rv.generator(), Gtrue), 1e-9);
      EXPECT_LT((Rv.getGenerator() - toVisp(Rv.generator())).frobeniusNorm(), 1e-15);

      // A negative trial motion read by the encoder: the image angle is still positive, and the generator is the
      // same axis's (exp(-theta Hhat) = H).
      const Eigen::Matrix4d Hneg = pRotation(scene, a, -theta);
      const vpProjectiveRotation Rn = logOf(Hneg, angle, -theta);
      EXPECT_NEAR(angle, theta, 1e-9);
      EXPECT_LT(relativeError(Rn.generator(), Gtrue), 1e-9);
      // If the encoder says +theta for that motion, the generator is that of the reversed axis.
      const vpProjectiveRotation Rr = logOf(Hneg, angle, theta);
      EXPECT_LT(relativeError(Rr.generator(), Eigen::Matrix4d(-Gtrue)), 1e-9);
    }
  }
  std::cout << "[ stats    ] p-rotation log, noise free: worst relative generator error " << worst << std::endl;
}

TEST(vpProjectiveRotation, ExpOfLogIsTheDisplacement)
{
  const Scene scene;
  vpUniRand rng(3);
  for (int k = 0; k < 5; ++k) {
    const Axis a = randomAxis(rng);
    for (double amount : {0.1, -0.7, 1.5, -2.9}) {
      SCOPED_TRACE(::testing::Message() << "axis " << k << ", amount " << amount);
      const Eigen::Matrix4d H = pRotation(scene, a, amount);
      double angle = 0.0;
      const vpProjectiveRotation R = logOf(Eigen::Matrix4d(7.0 * H), angle, amount);
      EXPECT_LT(relativeError(R.exp(amount).matrix(), vpProjectiveDisplacement::normalize(H)), 1e-9);
      EXPECT_LT(relativeError(R.exp(amount).matrix(), H), 1e-9);
      EXPECT_LT(relativeError(vpProjectiveRotation::exp(R.generator(), amount), H), 1e-9);
    }
  }
}

TEST(vpProjectiveRotation, GeneratorStructure)
{
  const Scene scene;
  vpUniRand rng(4);
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(::testing::Message() << "axis " << k);
    const Axis a = randomAxis(rng);
    double angle = 0.0;
    const Eigen::Matrix4d Hhat = logOf(pRotation(scene, a, 0.8), angle, 0.8).generator();
    EXPECT_LT(relativeError(Eigen::Matrix4d(Hhat * Hhat * Hhat), Eigen::Matrix4d(-Hhat)), 1e-9);
    EXPECT_LT(vpProjectiveRotation::generatorResidual(Hhat), 1e-9);
    // Rank 2: two singular values of the order of the largest, two at rounding level.
    const Eigen::Vector4d s = singularValues(Hhat);
    EXPECT_GT(s(1), 1e-6 * s(0));
    EXPECT_LT(s(2), 1e-9 * s(0));
    // Eigenvalues +-i, 0, 0 (invariant under H_PE): trace 0, trace(Hhat^2) = -2 |w|^2 = -2 for a unit-speed axis.
    EXPECT_NEAR(Hhat.trace(), 0.0, 1e-9 * Hhat.norm());
    EXPECT_NEAR((Hhat * Hhat).trace(), -2.0, 1e-9);
    // The constructor accepts it.
    EXPECT_NO_THROW(vpProjectiveRotation R(Hhat));
    EXPECT_NO_THROW(vpProjectiveRotation R(toVisp(Hhat)));
  }
  // The default generator is zero: no motion.
  const vpProjectiveRotation R;
  EXPECT_EQ(R.generator(), Eigen::Matrix4d::Zero());
  EXPECT_EQ(R.exp(1.3).matrix(), Eigen::Matrix4d::Identity());
}

TEST(vpProjectiveRotation, OneParameterSubgroup)
{
  const Scene scene;
  vpUniRand rng(5);
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(::testing::Message() << "axis " << k);
    const Axis a = randomAxis(rng);
    const vpProjectiveRotation R(trueGenerator(scene, a));
    const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
    for (int trial = 0; trial < 5; ++trial) {
      const double x = rng.uniform(-4.0, 4.0), y = rng.uniform(-4.0, 4.0);
      const Eigen::Matrix4d Exy = R.exp(x + y).matrix();
      EXPECT_LT(relativeError(Eigen::Matrix4d(R.exp(x).matrix() * R.exp(y).matrix()), Exy), 1e-9);
      EXPECT_LT(relativeError(Eigen::Matrix4d(R.exp(-x).matrix() * R.exp(x).matrix()), I), 1e-9);
      EXPECT_LT(relativeError(R.exp(-x).matrix(), Eigen::Matrix4d(R.exp(x).matrix().inverse())), 1e-9);
      // The subgroup is the true p-rotation for every angle, beyond pi too.
      EXPECT_LT(relativeError(R.exp(x).matrix(), pRotation(scene, a, x)), 1e-9);
    }
    EXPECT_EQ(R.exp(0.0).matrix(), I);
    EXPECT_LT(relativeError(R.exp(2.0 * M_PI).matrix(), I), 1e-9);
  }
}

/*
  d/dt exp(t Hhat) = Hhat exp(t Hhat), checked by central differences with h = 1e-4: the truncation error is
  h^2 / 6 |Hhat^3 exp| ~ 2e-9 relative (Hhat^3 = -Hhat, so of the size of the derivative itself) and rounding
  eps |exp| / h ~ 1e-12 |exp| / |Hhat exp|; the bound 1e-7 covers both with margin and catches any wrong sign or
  missing term (errors of order 1).
*/
TEST(vpProjectiveRotation, DerivativeByCentralDifferences)
{
  const Scene scene;
  vpUniRand rng(6);
  const double h = 1e-4;
  for (int k = 0; k < 5; ++k) {
    const Axis a = randomAxis(rng);
    const vpProjectiveRotation R(trueGenerator(scene, a));
    for (double t : {-2.0, 0.0, 0.4, 1.7, 3.1}) {
      SCOPED_TRACE(::testing::Message() << "axis " << k << ", t " << t);
      const Eigen::Matrix4d numeric = (R.exp(t + h).matrix() - R.exp(t - h).matrix()) / (2.0 * h);
      const Eigen::Matrix4d analytic = R.generator() * R.exp(t).matrix();
      EXPECT_LT(relativeError(numeric, analytic), 1e-7);
      // Hhat commutes with exp(t Hhat).
      EXPECT_LT(relativeError(Eigen::Matrix4d(R.exp(t).matrix() * R.generator()), analytic), 1e-9);
    }
  }
}

/*
  Conjugation by a change of projective frame G. exp: exp(theta G^-1 Hhat G) = G^-1 exp(theta Hhat) G for a random
  well-conditioned G applied to the rig's frame. log: it commutes with G too; this is checked in frames G = H_PE^-1 Q,
  Q random and well-conditioned (G = H_PE^-1 maps the rig's frame to the metric one, where the generator is the
  metric twist itself). The rig's frame alone has cond(H_PE) ~ 4e3, so a p-rotation there has cond(H) ~ 1e5 - 1e6;
  a random G on top of it raises cond(H) to 1e7 and the rounding error of H^-1 in the logarithm (25) to ~1e-6
  relative: that is conditioning, not a property of the log, hence the choice of frames for the log part.
*/
TEST(vpProjectiveRotation, Conjugation)
{
  const Scene scene;
  vpUniRand rng(7);
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(::testing::Message() << "trial " << k);
    const Axis a = randomAxis(rng);
    const Eigen::Matrix4d Hhat = trueGenerator(scene, a);
    // A random, well-conditioned matrix Q.
    Eigen::Matrix4d Q = I;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        Q(i, j) += 0.4 * rng.uniform(-1.0, 1.0);
      }
    }
    ASSERT_GT(singularValues(Q)(3), 0.05);
    const Eigen::Matrix4d Qi = Q.inverse();
    const Eigen::Matrix4d conj = Qi * Hhat * Q;
    const vpProjectiveRotation Rc(conj); // still a generator
    for (double theta : {-1.0, 0.6, 2.2}) {
      SCOPED_TRACE(::testing::Message() << "theta " << theta);
      EXPECT_LT(relativeError(Rc.exp(theta).matrix(), Eigen::Matrix4d(Qi * vpProjectiveRotation::exp(Hhat, theta) * Q)),
                1e-10);
    }
    // The logarithm in the metric frame (G = H_PE^-1) is the metric twist, and in G = H_PE^-1 Q its conjugate.
    const Eigen::Matrix4d That = metricTwist(scene, a);
    for (double theta : {-1.0, 0.6, 2.2}) {
      SCOPED_TRACE(::testing::Message() << "theta " << theta);
      const Eigen::Matrix4d Tl =
          scene.cameraDisplacement(vpSimulatorStereoRig::rotationAbout(a.point, a.direction, theta));
      double angle = 0.0;
      EXPECT_LT(relativeError(logOf(Tl, angle, theta).generator(), That), 1e-12);
      EXPECT_LT(
          relativeError(logOf(Eigen::Matrix4d(Qi * Tl * Q), angle, theta).generator(), Eigen::Matrix4d(Qi * That * Q)),
          1e-11);
    }
  }
}

/*
  The logarithm of a noisy p-rotation: the metric motion is perturbed, T (I + E) with |E|_F = eps (E Gaussian; a
  relative error of the motion, the kind an estimate from noisy markers has), and seen in the rig's frame,
  H = H_PE^-1 T (I + E) H_PE. The algebraic generator (H - H^-1) / (2 sin theta) is then not exactly a generator;
  log() projects it on one, so the result must satisfy Hhat^3 = -Hhat, rank 2 and unit speed to rounding.
  Its error, read in the metric frame (H_PE Hhat H_PE^-1 against That, so that it does not depend on the scaling of
  the rig's frame), is first order in eps. From (25) and (21):
    dHhat = (T E + E T^-1) / (2 sin theta) - cot(theta) Hhat dtheta,  |dtheta| <= eps |T|_F / (2 sin theta),
  hence |dHhat| / |That| <= C eps with C = (|T| + |T^-1| + |cot theta| |That| |T|) / (2 sin theta |That|) (Frobenius
  norms; the change of the normalisation (12), 1 - tr(E)/4, is of lower size). Checked: every error below C eps, the
  ratio error / eps the same at eps = 1e-6 and 1e-4 (first order), and the projection at most doubles the error of the
  algebraic generator (the triangle-inequality bound of a projection onto a set that contains the truth).
  Measured (4 axes x 3 angles x 20 seeds, offline): ratio / C <= 0.42, projected / algebraic error <= 1.62.
*/
TEST(vpProjectiveRotation, NoisyLogIsExactGeneratorWithBoundedError)
{
  const Scene scene;
  vpUniRand rng(8);
  const Axis a = randomAxis(rng);
  const Eigen::Matrix4d That = metricTwist(scene, a);
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  double worstRatioOverC = 0.0, worstAmplification = 0.0;
  for (double theta : {0.3, 0.8, 2.0}) {
    const Eigen::Matrix4d T =
        scene.cameraDisplacement(vpSimulatorStereoRig::rotationAbout(a.point, a.direction, theta));
    const double C =
        (T.norm() + T.inverse().norm() + std::abs(std::cos(theta) / std::sin(theta)) * That.norm() * T.norm()) /
        (2.0 * std::sin(theta) * That.norm());
    const double eps[2] = {1e-6, 1e-4};
    double meanRatio[2] = {0.0, 0.0};
    const int seeds = 20;
    for (int level = 0; level < 2; ++level) {
      for (int seed = 1; seed <= seeds; ++seed) {
        SCOPED_TRACE(::testing::Message() << "theta " << theta << ", eps " << eps[level] << ", seed " << seed);
        vpGaussRand noise(1.0, 0.0, seed);
        const Eigen::Matrix4d E = noiseMatrix(noise);
        const Eigen::Matrix4d Tn = T * (I + eps[level] * E / E.norm());
        double angle = 0.0;
        const vpProjectiveRotation R = logOf(Eigen::Matrix4d(scene.HpeInv * Tn * scene.Hpe), angle, theta);
        const Eigen::Matrix4d &Hhat = R.generator();
        EXPECT_LT(vpProjectiveRotation::generatorResidual(Hhat), 1e-10);
        EXPECT_LT(singularValues(Hhat)(2), 1e-10 * singularValues(Hhat)(0));
        EXPECT_NEAR((Hhat * Hhat).trace(), -2.0, 1e-9);

        const double error = relativeError(Eigen::Matrix4d(scene.Hpe * Hhat * scene.HpeInv), That);
        const Eigen::Matrix4d Tnn = vpProjectiveDisplacement::normalize(Tn);
        const Eigen::Matrix4d algebraic = (Tnn - Tnn.inverse()) / (2.0 * std::sin(angle));
        const double algebraicError = relativeError(algebraic, That);
        EXPECT_LT(error, C * eps[level]);
        EXPECT_LT(error, 2.0 * algebraicError);
        meanRatio[level] += error / eps[level] / seeds;
        worstRatioOverC = std::max(worstRatioOverC, error / (C * eps[level]));
        worstAmplification = std::max(worstAmplification, error / algebraicError);
      }
    }
    EXPECT_NEAR(meanRatio[1] / meanRatio[0], 1.0, 0.05) << "theta " << theta;
  }
  std::cout << "[ stats    ] p-rotation log of a noisy H: worst (error / eps) / C = " << worstRatioOverC
            << ", worst projected / algebraic error = " << worstAmplification << std::endl;
}

// ---------------------------------------------------------------------------------------------------------------
// Invalid inputs
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveRotation, InvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(9);
  const Axis a = randomAxis(rng);
  double angle = 0.0;

  // No rotation, or a half turn: the logarithm (25) divides by sin(theta).
  EXPECT_TRUE(throwsProjective([&] { logOf(Eigen::Matrix4d(Eigen::Matrix4d::Identity()), angle); },
                               vpProjectiveException::degenerateConfigurationError, "multiple of pi"));
  EXPECT_TRUE(throwsProjective([&] { logOf(pRotation(scene, a, 1e-9), angle, 1e-9); },
                               vpProjectiveException::degenerateConfigurationError, "multiple of pi"));
  EXPECT_TRUE(throwsProjective([&] { logOf(pRotation(scene, a, M_PI), angle, M_PI); },
                               vpProjectiveException::degenerateConfigurationError, "pi"));
  // A pure translation has angle 0 (21).
  const Eigen::Matrix4d Ht = scene.projectiveDisplacement(vpSimulatorStereoRig::translationAlong(point3(1, 0, 0), 0.1));
  EXPECT_TRUE(throwsProjective([&] { logOf(Ht, angle); }, vpProjectiveException::degenerateConfigurationError,
                               "multiple of pi"));

  // Non-finite, singular or mis-sized H, non-finite amount.
  Eigen::Matrix4d bad = pRotation(scene, a, 0.5);
  bad(2, 1) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { logOf(bad, angle, 0.5); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(throwsProjective([&] { logOf(toVisp(bad), angle, 0.5); }, vpProjectiveException::nonFiniteValueError,
                               "not finite"));
  EXPECT_TRUE(throwsProjective([&] { logOf(vpMatrix(3, 3, 1.0), angle, 0.5); }, vpProjectiveException::dimensionError,
                               "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { logOf(Eigen::Matrix4d(Eigen::Matrix4d::Zero()), angle); },
                               vpProjectiveException::invalidValueError, "zero matrix"));
  Eigen::Matrix4d singular = pRotation(scene, a, 0.5);
  singular.row(3) = singular.row(2);
  EXPECT_TRUE(throwsProjective([&] { logOf(singular, angle, 0.5); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
  EXPECT_TRUE(throwsProjective([&] { logOf(pRotation(scene, a, 0.5), angle, std::numeric_limits<double>::infinity()); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));

  // Matrices that are no p-rotation generators.
  Eigen::Matrix4d random;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      random(i, j) = rng.uniform(-1.0, 1.0);
    }
  }
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(random); }, vpProjectiveException::invalidValueError,
                               "not a p-rotation generator"));
  // Twice a generator: Hhat^3 = 4 (-Hhat)... no longer -Hhat.
  const Eigen::Matrix4d G = trueGenerator(scene, a);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(Eigen::Matrix4d(2.0 * G)); },
                               vpProjectiveException::invalidValueError, "not a p-rotation generator"));
  // A p-translation generator (nilpotent) is not a p-rotation generator.
  Eigen::Matrix4d Tt = Eigen::Matrix4d::Zero();
  Tt(0, 3) = 1.0;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(Eigen::Matrix4d(scene.HpeInv * Tt * scene.Hpe)); },
                               vpProjectiveException::invalidValueError, "not a p-rotation generator"));
  Eigen::Matrix4d nan = G;
  nan(0, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveRotation R(nan); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(vpMatrix(3, 3, 0.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveRotation R(G, -1.0); }, vpProjectiveException::invalidValueError,
                               "tolerance"));
}
