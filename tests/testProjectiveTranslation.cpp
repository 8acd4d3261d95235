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
  Tests of vpProjectiveTranslation, the one-parameter Lie group of p-translations exp(tau Hhat) = I + tau Hhat
  (Ruf & Horaud, eqs. (28)-(31)), against the metric simulator:
  - the logarithm of H_PE^-1 T_l(tau) H_PE with the encoder length tau is the true generator H_PE^-1 That H_PE,
    That = [[0, d]; [0, 0]] with d the unit direction in the left camera frame (unit metric speed); exp(log H) = H;
  - the generator's structure: Hhat^2 = 0, rank 1;
  - group laws: exp(a) exp(b) = exp(a + b), exp(-t) = exp(t)^-1, d/dtau exp(tau Hhat) = Hhat, conjugation;
  - the logarithm of a noisy H is projected on an exact generator whose error is first order in the noise;
  - invalid inputs throw a vpProjectiveException with a meaningful code and message.

  Noise-free bounds: 1e-9 relative, far above rounding in the rig's frame (cond(H_PE) ~ 4e3), far below any modelling
  error (wrong sign or scale of the generator: errors of order 1). The noisy bound is derived at the test.
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
#include <visp3/projective/vpProjectiveTranslation.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
//! The tests' view of the one log() signature, from a matrix of any scale.
template <typename Matrix> vpProjectiveTranslation logOf(const Matrix &H, double tau)
{
  return vpProjectiveTranslation::log(vpProjectiveDisplacement(H), tau);
}

// The unit-speed metric twist of a translation along the world direction dir, in the left camera frame.
Eigen::Matrix4d metricTwist(const Scene &scene, const vpColVector &dir)
{
  Eigen::Matrix4d That = Eigen::Matrix4d::Zero();
  That.topRightCorner<3, 1>() = scene.cameraDirection(dir).normalized();
  return That;
}

Eigen::Matrix4d trueGenerator(const Scene &scene, const vpColVector &dir)
{
  return scene.HpeInv * metricTwist(scene, dir) * scene.Hpe;
}

// The true p-translation by tau metres along dir, H_PE^-1 T_l H_PE (det 1).
Eigen::Matrix4d pTranslation(const Scene &scene, const vpColVector &dir, double tau)
{
  return scene.projectiveDisplacement(vpSimulatorStereoRig::translationAlong(dir, tau));
}

Eigen::Matrix4d noiseMatrix(vpGaussRand &noise)
{
  Eigen::Matrix4d N;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      N(i, j) = noise();
    }
  }
  return N / N.norm();
}
} // namespace

// The twist convention of the tests themselves: I + tau That is the simulator's metric translation.
TEST(vpProjectiveTranslation, MetricTwistConvention)
{
  const Scene scene;
  vpUniRand rng(1);
  for (int k = 0; k < 5; ++k) {
    const vpColVector d = randomDirection(rng);
    for (double tau : {-0.2, 0.01, 0.35}) {
      const Eigen::Matrix4d T = scene.cameraDisplacement(vpSimulatorStereoRig::translationAlong(d, tau));
      EXPECT_LT((Eigen::Matrix4d(Eigen::Matrix4d::Identity() + tau * metricTwist(scene, d)) - T).norm(), 1e-14);
    }
  }
}

TEST(vpProjectiveTranslation, LogRecoversTrueGenerator)
{
  const Scene scene;
  vpUniRand rng(2);
  double worst = 0.0;
  for (int k = 0; k < 5; ++k) {
    const vpColVector d = randomDirection(rng);
    const Eigen::Matrix4d Gtrue = trueGenerator(scene, d);
    for (double tau : {0.002, 0.05, -0.03, 0.3, -0.5}) {
      SCOPED_TRACE(::testing::Message() << "direction " << k << ", tau " << tau);
      // Any scale and sign of H: log() normalises it. A negative tau is a motion along -d read as negative by the
      // encoder: the generator is still that of d.
      const Eigen::Matrix4d H = pTranslation(scene, d, tau);
      const vpProjectiveTranslation T = logOf(Eigen::Matrix4d(-4.0 * H), tau);
      EXPECT_LT(relativeError(T.generator(), Gtrue), 1e-9);
      worst = std::max(worst, relativeError(T.generator(), Gtrue));
      const vpProjectiveTranslation Tv = logOf(toVisp(H), tau);
      EXPECT_LT(relativeError(Tv.generator(), Gtrue), 1e-9);
      EXPECT_LT((Tv.getGenerator() - toVisp(Tv.generator())).frobeniusNorm(), 1e-15);
      // The generator is per unit of the encoder: the same motion read as 2 tau gives half the generator, read with
      // the opposite sign gives the opposite generator.
      EXPECT_LT(relativeError(logOf(H, 2.0 * tau).generator(), Eigen::Matrix4d(0.5 * Gtrue)), 1e-9);
      EXPECT_LT(relativeError(logOf(H, -tau).generator(), Eigen::Matrix4d(-Gtrue)), 1e-9);
      // The p-displacement is a translation, with angle 0.
      const vpProjectiveDisplacement D(H);
      EXPECT_EQ(D.classify(), vpProjectiveDisplacement::TRANSLATION);
      EXPECT_NEAR(D.getRotationAngle(), 0.0, 1e-6);
    }
  }
  std::cout << "[ stats    ] p-translation log, noise free: worst relative generator error " << worst << std::endl;
}

TEST(vpProjectiveTranslation, ExpOfLogIsTheDisplacement)
{
  const Scene scene;
  vpUniRand rng(3);
  for (int k = 0; k < 5; ++k) {
    const vpColVector d = randomDirection(rng);
    for (double tau : {0.01, -0.07, 0.4}) {
      SCOPED_TRACE(::testing::Message() << "direction " << k << ", tau " << tau);
      const Eigen::Matrix4d H = pTranslation(scene, d, tau);
      const vpProjectiveTranslation T = logOf(Eigen::Matrix4d(0.3 * H), tau);
      EXPECT_LT(relativeError(T.exp(tau).matrix(), H), 1e-9);
      EXPECT_LT(relativeError(T.exp(tau).matrix(), vpProjectiveDisplacement::normalize(H)), 1e-9);
      EXPECT_LT(relativeError(vpProjectiveTranslation::exp(T.generator(), tau), H), 1e-9);
    }
  }
}

TEST(vpProjectiveTranslation, GeneratorStructure)
{
  const Scene scene;
  vpUniRand rng(4);
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(::testing::Message() << "direction " << k);
    const vpColVector d = randomDirection(rng);
    const Eigen::Matrix4d Hhat = logOf(pTranslation(scene, d, 0.1), 0.1).generator();
    // Nilpotent: Hhat^2 = 0 relative to |Hhat|^2.
    EXPECT_LT((Hhat * Hhat).norm() / Hhat.squaredNorm(), 1e-12);
    EXPECT_LT(vpProjectiveTranslation::generatorResidual(Hhat), 1e-12);
    // Rank 1.
    const Eigen::Vector4d s = singularValues(Hhat);
    EXPECT_GT(s(0), 0.0);
    EXPECT_LT(s(1), 1e-12 * s(0));
    // The constructor accepts it; it is not a p-rotation generator.
    EXPECT_NO_THROW(vpProjectiveTranslation T(Hhat));
    EXPECT_NO_THROW(vpProjectiveTranslation T(toVisp(Hhat)));
    EXPECT_GT(vpProjectiveRotation::generatorResidual(Hhat), 0.5);
  }
  const vpProjectiveTranslation T;
  EXPECT_EQ(T.generator(), Eigen::Matrix4d::Zero());
  EXPECT_EQ(T.exp(0.7).matrix(), Eigen::Matrix4d::Identity());
}

TEST(vpProjectiveTranslation, OneParameterSubgroup)
{
  const Scene scene;
  vpUniRand rng(5);
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(::testing::Message() << "direction " << k);
    const vpColVector d = randomDirection(rng);
    const vpProjectiveTranslation T(trueGenerator(scene, d));
    for (int trial = 0; trial < 5; ++trial) {
      const double x = rng.uniform(-0.5, 0.5), y = rng.uniform(-0.5, 0.5);
      EXPECT_LT(relativeError(Eigen::Matrix4d(T.exp(x).matrix() * T.exp(y).matrix()), T.exp(x + y).matrix()), 1e-9);
      EXPECT_LT(relativeError(Eigen::Matrix4d(T.exp(-x).matrix() * T.exp(x).matrix()), I), 1e-9);
      EXPECT_LT(relativeError(T.exp(-x).matrix(), Eigen::Matrix4d(T.exp(x).matrix().inverse())), 1e-9);
      EXPECT_LT(relativeError(T.exp(x).matrix(), pTranslation(scene, d, x)), 1e-9);
      // d/dtau exp(tau Hhat) = Hhat (exactly: exp is affine in tau), = Hhat exp(tau Hhat) as Hhat^2 = 0.
      const double h = 1e-3;
      const Eigen::Matrix4d numeric = (T.exp(x + h).matrix() - T.exp(x - h).matrix()) / (2.0 * h);
      EXPECT_LT(relativeError(numeric, T.generator()), 1e-9);
      EXPECT_LT(relativeError(Eigen::Matrix4d(T.generator() * T.exp(x).matrix()), T.generator()), 1e-9);
    }
    EXPECT_EQ(T.exp(0.0).matrix(), I);
  }
}

TEST(vpProjectiveTranslation, Conjugation)
{
  const Scene scene;
  vpUniRand rng(6);
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  for (int k = 0; k < 5; ++k) {
    SCOPED_TRACE(::testing::Message() << "trial " << k);
    const vpColVector d = randomDirection(rng);
    const Eigen::Matrix4d Hhat = trueGenerator(scene, d);
    Eigen::Matrix4d Q = I;
    for (int i = 0; i < 4; ++i) {
      for (int j = 0; j < 4; ++j) {
        Q(i, j) += 0.4 * rng.uniform(-1.0, 1.0);
      }
    }
    ASSERT_GT(singularValues(Q)(3), 0.05);
    const Eigen::Matrix4d Qi = Q.inverse();
    const vpProjectiveTranslation Tc(Eigen::Matrix4d(Qi * Hhat * Q)); // still a generator
    for (double tau : {-0.2, 0.05, 0.3}) {
      EXPECT_LT(relativeError(Tc.exp(tau).matrix(), Eigen::Matrix4d(Qi * vpProjectiveTranslation::exp(Hhat, tau) * Q)),
                1e-10);
      // The logarithm commutes with the change of frame (here from the metric frame, see testProjectiveRotation).
      const Eigen::Matrix4d Tl = scene.cameraDisplacement(vpSimulatorStereoRig::translationAlong(d, tau));
      EXPECT_LT(relativeError(logOf(Tl, tau).generator(), metricTwist(scene, d)), 1e-12);
      EXPECT_LT(relativeError(logOf(Eigen::Matrix4d(Qi * Tl * Q), tau).generator(),
                              Eigen::Matrix4d(Qi * metricTwist(scene, d) * Q)),
                1e-11);
    }
  }
}

/*
  The logarithm of a noisy p-translation: the metric motion is perturbed, T (I + E), |E|_F = eps (E Gaussian), and seen
  in the rig's frame, H = H_PE^-1 T (I + E) H_PE. (H - I) / tau is then not exactly nilpotent; log() projects it on a
  rank-1 nilpotent matrix, so the result must satisfy Hhat^2 = 0 and rank 1 to rounding. Read in the metric frame
  (H_PE Hhat H_PE^-1 against That, |That| = 1), the algebraic generator's error is |T E| / tau <= eps |T|_F / tau
  (the normalisation (12) changes T (I + E) by 1 - tr(E)/4, of the same order: bound eps |T|_F (1 + 1/2) / tau), and
  the projection at most doubles it (triangle inequality, the truth belongs to the set). Bound: C eps with
  C = 3 |T|_F / tau. The ratio error / eps must be the same at eps = 1e-7 and 1e-5 (first order; the relative noise
  must stay well below tau for the log to mean anything, hence smaller eps than for rotations).
*/
TEST(vpProjectiveTranslation, NoisyLogIsExactGeneratorWithBoundedError)
{
  const Scene scene;
  vpUniRand rng(7);
  const vpColVector d = randomDirection(rng);
  const Eigen::Matrix4d That = metricTwist(scene, d);
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  double worstRatioOverC = 0.0;
  for (double tau : {0.02, 0.1, -0.3}) {
    const Eigen::Matrix4d T = scene.cameraDisplacement(vpSimulatorStereoRig::translationAlong(d, tau));
    const double C = 3.0 * T.norm() / std::abs(tau);
    const double eps[2] = {1e-7, 1e-5};
    double meanRatio[2] = {0.0, 0.0};
    const int seeds = 20;
    for (int level = 0; level < 2; ++level) {
      for (int seed = 1; seed <= seeds; ++seed) {
        SCOPED_TRACE(::testing::Message() << "tau " << tau << ", eps " << eps[level] << ", seed " << seed);
        vpGaussRand noise(1.0, 0.0, seed);
        const Eigen::Matrix4d Tn = T * (I + eps[level] * noiseMatrix(noise));
        const vpProjectiveTranslation R = logOf(Eigen::Matrix4d(scene.HpeInv * Tn * scene.Hpe), tau);
        const Eigen::Matrix4d &Hhat = R.generator();
        EXPECT_LT(vpProjectiveTranslation::generatorResidual(Hhat), 1e-12);
        EXPECT_LT(singularValues(Hhat)(1), 1e-12 * singularValues(Hhat)(0));
        const double error = relativeError(Eigen::Matrix4d(scene.Hpe * Hhat * scene.HpeInv), That);
        EXPECT_LT(error, C * eps[level]);
        meanRatio[level] += error / eps[level] / seeds;
        worstRatioOverC = std::max(worstRatioOverC, error / (C * eps[level]));
      }
    }
    EXPECT_NEAR(meanRatio[1] / meanRatio[0], 1.0, 0.05) << "tau " << tau;
  }
  std::cout << "[ stats    ] p-translation log of a noisy H: worst (error / eps) / C = " << worstRatioOverC
            << std::endl;
}

// ---------------------------------------------------------------------------------------------------------------
// Invalid inputs
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveTranslation, InvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(8);
  const vpColVector d = randomDirection(rng);
  const Eigen::Matrix4d H = pTranslation(scene, d, 0.1);

  EXPECT_TRUE(throwsProjective([&] { logOf(H, 0.0); }, vpProjectiveException::invalidValueError, "zero"));
  EXPECT_TRUE(throwsProjective([&] { logOf(H, std::numeric_limits<double>::quiet_NaN()); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { logOf(H, std::numeric_limits<double>::infinity()); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  Eigen::Matrix4d bad = H;
  bad(3, 0) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { logOf(bad, 0.1); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(
      throwsProjective([&] { logOf(toVisp(bad), 0.1); }, vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(
      throwsProjective([&] { logOf(vpMatrix(3, 3, 1.0), 0.1); }, vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { logOf(Eigen::Matrix4d(Eigen::Matrix4d::Zero()), 0.1); },
                               vpProjectiveException::invalidValueError, "zero matrix"));
  Eigen::Matrix4d singular = H;
  singular.col(2) = singular.col(1);
  EXPECT_TRUE(
      throwsProjective([&] { logOf(singular, 0.1); }, vpProjectiveException::degenerateConfigurationError, "singular"));

  // Matrices that are no p-translation generators: a p-rotation generator (Hhat^3 = -Hhat, not nilpotent), a random
  // matrix, a rank-1 matrix that is not nilpotent (a projector).
  Eigen::Matrix4d rotation = Eigen::Matrix4d::Zero();
  rotation.topLeftCorner<3, 3>() = vpMetricTwist::skew(Eigen::Vector3d(0.0, 0.0, 1.0));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(Eigen::Matrix4d(scene.HpeInv * rotation * scene.Hpe)); },
                               vpProjectiveException::invalidValueError, "not a p-translation generator"));
  Eigen::Matrix4d random;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      random(i, j) = rng.uniform(-1.0, 1.0);
    }
  }
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(random); }, vpProjectiveException::invalidValueError,
                               "not a p-translation generator"));
  const Eigen::Vector4d u(1.0, 2.0, -1.0, 0.5);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(Eigen::Matrix4d(u * u.transpose())); },
                               vpProjectiveException::invalidValueError, "not a p-translation generator"));
  Eigen::Matrix4d nan = trueGenerator(scene, d);
  nan(1, 1) = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveTranslation T(nan); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(vpMatrix(4, 3, 0.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveTranslation T(trueGenerator(scene, d), -1.0); },
                               vpProjectiveException::invalidValueError, "tolerance"));
}
