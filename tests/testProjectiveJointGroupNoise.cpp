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
  Typed tests of both joint groups (vpProjectiveJointGroupTestTools.h) on noisy data: project() leaves exact
  generators unchanged and projects noisy ones on exact generators, first order in the noise; the logarithm of a noisy
  H is an exact generator whose error is first order in the noise, within a derived bound.
*/

#include <gtest/gtest.h>

#include "vpProjectiveJointGroupTestTools.h"

using namespace vpProjectiveTest;

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
  testLog() << "[ stats    ] " << Traits::name() << " project(): worst amplification / bound " << worstAmplification
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
  testLog() << "[ stats    ] " << Traits::name()
            << " log of a noisy H: worst algebraic error / (C eps) = " << worstAlgebraicOverC
            << ", worst projection amplification / bound = " << worstAmplification << std::endl;
}
