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
  Cost of the metric self-calibration (vpProjectiveSelfCalibration: the bundle adjustment and its covariance) on the
  self-calibration study's PUMA-like arm (6 joints, 7 markers, a random rig of skewed cameras, 0.5 px): the
  acquisition's 13 images and 0, 30, 100 or 300 calibration frames at random configurations within +-30 deg; and
  suggestConfigurations() choosing 5 of 200 candidates after the acquisition and 30 frames.
  Run: tests/benchmark/benchmarkSelfCalibration (medians over 5 repetitions).
*/

#include <vector>

#include <benchmark/benchmark.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "calibration-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
//! The study's PUMA world (seed 1) with \e frames calibration frames.
struct World {
  selfcal::StudyArm arm = selfcal::makeArm("puma");
  selfcal::SkewedRig rig;
  vpProjectiveRobot robot;
  explicit World(unsigned int frames)
  {
    vpUniRand rigRng(1), viewRng(2);
    vpGaussRand noise(1.0, 0.0, 3);
    rig = selfcal::randomRig(arm, rigRng);
    robot = selfcal::acquire(arm, rig, 0.5, frames, 30.0, noise, viewRng);
  }
};

void BM_SelfCalibration(benchmark::State &state)
{
  const World world(static_cast<unsigned int>(state.range(0)));
  const std::vector<vpProjectiveArmAcquisition::vpFrame> frames = world.robot.getAcquisition().getFrames();
  for (auto _ : state) {
    const vpProjectiveSelfCalibration calibration(world.robot.getModel(), frames);
    benchmark::DoNotOptimize(calibration.getNoiseLevel());
  }
  state.counters["frames"] = static_cast<double>(frames.size());
}

void BM_SuggestConfigurations(benchmark::State &state)
{
  const World world(30);
  const vpProjectiveSelfCalibration calibration(world.robot.getModel(), world.robot.getAcquisition().getFrames());
  vpColVector qmin(6), qmax(6);
  for (unsigned int i = 0; i < 6; ++i) {
    qmin[i] = world.arm.qRef[i] - vpMath::rad(30.0);
    qmax[i] = world.arm.qRef[i] + vpMath::rad(30.0);
  }
  for (auto _ : state) {
    benchmark::DoNotOptimize(
        calibration.suggestConfigurations(5, qmin, qmax, world.rig.width, world.rig.height, nullptr, 200, 1));
  }
}
} // namespace

BENCHMARK(BM_SelfCalibration)
    ->Arg(0)
    ->Arg(30)
    ->Arg(100)
    ->Arg(300)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_SuggestConfigurations)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

BENCHMARK_MAIN();
