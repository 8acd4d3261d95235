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
  Cost of vpProjectiveRobot::updateRig() (issue 12; target at most 20 ms) on the PUMA of the tests (eye-to-hand, 6
  joints, 7 markers), its model acquired at 0.5 px, the left camera bumped by 2 deg and 1 cm, from 3 and 10
  observations at random configurations in view (0.5 px), in both registration modes (0: the default fixed
  intrinsics, 1: general 11-parameter cameras). Each timed call re-adds the observations (microseconds) and updates a
  copy of the acquired robot.
  Run: tests/benchmark/benchmarkRigUpdate (medians over 10 repetitions).
*/

#include <vector>

#include <benchmark/benchmark.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "../vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! The acquired PUMA and the noisy observations of its bumped rig.
struct Bump {
  static constexpr double sigma = 0.5; // pixel noise of the acquisition and of the observations
  ArmSetup setup = pumaEyeToHand();
  vpProjectiveRobot robot;
  struct Observation {
    vpColVector q;
    std::vector<vpImagePoint> left, right;
  };
  std::vector<Observation> observations; // of the bumped rig, at random joints in view

  Bump() : robot(setup.jointTypes())
  {
    vpGaussRand noise(1.0, 0.0, 1);
    setup.acquire(robot, sigma, noise);
    robot.calibrate();
    ArmSetup bumped = setup;
    const vpHomogeneousMatrix d(vpTranslationVector(0.006, -0.008, 0.0),
                                vpThetaUVector(vpMath::rad(1.2), vpMath::rad(-1.6), 0.0));
    bumped.wMl = setup.wMl * d;
    bumped.rMl = setup.rMl * d;
    vpUniRand rng(2);
    std::vector<double> range;
    for (double a : setup.trialAmounts) {
      range.push_back(0.6 * a);
    }
    observations.resize(10);
    for (Observation &o : observations) {
      o.q = bumped.randomVisibleJoints(rng, range, 20.0);
      bumped.images(bumped.armJoints(o.q), o.left, o.right, sigma, noise, -1e9);
    }
  }
};

const Bump &bump()
{
  static const Bump b;
  return b;
}

void BM_UpdateRig(benchmark::State &state)
{
  const Bump &b = bump();
  const size_t observations = static_cast<size_t>(state.range(0));
  vpProjectiveRobot robot = b.robot;
  robot.getRigUpdate().setRegistrationMode(state.range(1) == 0 ? vpProjectiveRigRegistration::FIXED_INTRINSICS
                                                               : vpProjectiveRigRegistration::GENERAL);
  vpProjectiveStereoRig::Projection P;
  for (auto _ : state) {
    for (size_t k = 0; k < observations; ++k) {
      robot.addRigObservation(b.observations[k].q, b.observations[k].left, b.observations[k].right);
    }
    robot.updateRig();
    robot.getStereoRig().getLeftProjection(P); // the updated rig, once per update
    benchmark::DoNotOptimize(P.data());
  }
  state.SetLabel("registration RMS " + std::to_string(robot.getRigUpdate().getResidual()) + " px");
}
} // namespace

BENCHMARK(BM_UpdateRig)
    ->ArgNames({"observations", "general"})
    ->Args({3, 0})
    ->Args({10, 0})
    ->Args({3, 1})
    ->Args({10, 1})
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond);

BENCHMARK_MAIN();
