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

/*!
  \file benchmarkAprilTag.cpp
  \brief Timings of the stereo tag detector (issue 20 point 1), with Google Benchmark, per 640 x 480 stereo pair.

  The pair: 8 tags of 36h11 (4 cm, about 67 px wide) 1 m in front of the paper's rig, tilted by up to 0.5 rad,
  rendered by vpSimulatorTagRenderer at its defaults (noise 1 grey level, no blur).
  - BM_ViSPDetectorTwice: vpDetectorAprilTag::detect() on the left, then on the right image, ViSP's defaults (one
    thread, decimation 1, AprilTag's edge refinement on): the reference.
  - BM_StereoDetectorFull: vpStereoAprilTagDetector::detect() on the full images at its defaults (quads searched at
    decimation 1.5 without AprilTag's edge refinement, then the gradient refit of the corners at full resolution,
    pairing).
  - BM_StereoDetectorFullDecimation1, BM_StereoDetectorFullDecimation2: the same with setDecimation(1), (2).
  - BM_StereoDetectorTracking, BM_StereoDetectorTrackingDecimation1: the same with the regions predicted from the
    corners of a first detection (setPredictedRegions(), margin 10 px), defaults otherwise: what a servo loop does
    with the model's predictions.
  - BM_ViSPDetectorTwiceDecimation1_5: BM_ViSPDetectorTwice with setAprilTagQuadDecimate(1.5), for comparison: most
    of the gain of the stereo detector's default is this decimation, which a plain user can set too (AprilTag's edge
    refinement keeps its corners at their decimation-1 accuracy, 0.09 px RMS on these renderings, against 0.03 px for
    the stereo detector's refit).
  - BM_RenderPair: vpSimulatorTagRenderer::render() of the pair.
  The targets: Full <= ViSPDetectorTwice, Tracking <= half of it. Compare the medians (CPU time is steadier on
  a loaded machine). Usage: benchmarkAprilTag [Google Benchmark options]
*/

#include <vector>

#include <benchmark/benchmark.h>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/detection/vpDetectorAprilTag.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/projective/vpSimulatorTagRenderer.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#if defined(VISP_HAVE_APRILTAG)
namespace
{
struct Scene {
  vpSimulatorTagRenderer renderer;
  vpImage<unsigned char> left, right;

  Scene() : renderer(vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0), 1)
  {
    vpUniRand rnd(1);
    for (int n = 0; n < 8; ++n) {
      // Drawn last to first, the order g++ evaluated these arguments in (C++ leaves it unspecified): the same tags
      // whichever the compiler.
      const double tuz = rnd.uniform(-3.14, 3.14);
      const double tuy = rnd.uniform(-0.5, 0.5);
      const double tux = rnd.uniform(-0.5, 0.5);
      const double tz = rnd.uniform(-0.03, 0.03);
      const vpHomogeneousMatrix wMt(-0.12 + 0.08 * (n % 4), -0.05 + 0.1 * (n / 4), tz, tux, tuy, tuz);
      renderer.addTag(3 * n, 0.04, wMt);
    }
    renderer.render(left, right);
  }
};

Scene &scene()
{
  static Scene s;
  return s;
}

void BM_ViSPDetectorTwice(benchmark::State &state)
{
  Scene &s = scene();
  vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11);
  detector.setAprilTagNbThreads(1);
  for (auto _ : state) {
    detector.detect(s.left);
    detector.detect(s.right);
    benchmark::DoNotOptimize(detector.getNbObjects());
  }
  state.counters["tags"] = static_cast<double>(detector.getNbObjects());
}

void BM_ViSPDetectorTwiceDecimation1_5(benchmark::State &state)
{
  Scene &s = scene();
  vpDetectorAprilTag detector(vpDetectorAprilTag::TAG_36h11);
  detector.setAprilTagNbThreads(1);
  detector.setAprilTagQuadDecimate(1.5f);
  for (auto _ : state) {
    detector.detect(s.left);
    detector.detect(s.right);
    benchmark::DoNotOptimize(detector.getNbObjects());
  }
  state.counters["tags"] = static_cast<double>(detector.getNbObjects());
}

void runStereo(benchmark::State &state, double decimation, bool tracking)
{
  Scene &s = scene();
  vpStereoAprilTagDetector detector(vpDetectorAprilTag::TAG_36h11);
  detector.setDecimation(decimation);
  if (tracking) {
    detector.detect(s.left, s.right);
    detector.setPredictedRegions(detector.getIds(), detector.getLeftPoints(), detector.getRightPoints());
  }
  unsigned int n = 0;
  for (auto _ : state) {
    n = detector.detect(s.left, s.right);
    benchmark::DoNotOptimize(n);
  }
  state.counters["corners"] = n;
}

void BM_StereoDetectorFull(benchmark::State &state)
{
  runStereo(state, 1.5, false);
}
void BM_StereoDetectorFullDecimation1(benchmark::State &state)
{
  runStereo(state, 1.0, false);
}
void BM_StereoDetectorFullDecimation2(benchmark::State &state)
{
  runStereo(state, 2.0, false);
}
void BM_StereoDetectorTracking(benchmark::State &state)
{
  runStereo(state, 1.5, true);
}
void BM_StereoDetectorTrackingDecimation1(benchmark::State &state)
{
  runStereo(state, 1.0, true);
}

void BM_RenderPair(benchmark::State &state)
{
  Scene &s = scene();
  for (auto _ : state) {
    s.renderer.render(s.left, s.right);
    benchmark::DoNotOptimize(s.left.bitmap);
  }
}
} // namespace

BENCHMARK(BM_ViSPDetectorTwice)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_ViSPDetectorTwiceDecimation1_5)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_StereoDetectorFull)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_StereoDetectorFullDecimation1)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_StereoDetectorFullDecimation2)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_StereoDetectorTracking)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_StereoDetectorTrackingDecimation1)
    ->Unit(benchmark::kMillisecond)
    ->Repetitions(5)
    ->ReportAggregatesOnly(true);
BENCHMARK(BM_RenderPair)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

BENCHMARK_MAIN();

#else
int main()
{
  return 0;
} // ViSP without AprilTag: nothing to time
#endif
