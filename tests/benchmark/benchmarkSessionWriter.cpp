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
  Frames per second of a 500-frame servo recording (vpProjectiveSessionWriter::addFrame(), 6 joints), with images of
  32 x 24 pixels (what the writer itself costs: session.json and two tiny PNG files per frame) and of 640 x 480
  pixels (a camera's: PNG encoding dominates). The recording goes to a folder under the system's temporary folder,
  removed after each run. Counter "fps": frames recorded per second of the whole recording (writer opened, 500 frames,
  closed).
  Run: tests/benchmark/benchmarkSessionWriter (medians over 3 repetitions).
*/

#include <filesystem>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>

#include <visp3/core/vpImage.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
void recordFrames(benchmark::State &state)
{
  const unsigned int width = static_cast<unsigned int>(state.range(0)), height = width * 3 / 4, frames = 500;
  vpImage<unsigned char> Il(height, width), Ir(height, width);
  for (unsigned int i = 0; i < height; ++i) {
    for (unsigned int j = 0; j < width; ++j) {
      Il[i][j] = static_cast<unsigned char>((i * 7 + j * 3) % 251); // something for PNG to encode
      Ir[i][j] = static_cast<unsigned char>((i * 5 + j * 11) % 241);
    }
  }
  const std::vector<vpProjectiveJoint::vpJointType> types(6, vpProjectiveJoint::REVOLUTE);
  const std::filesystem::path root = std::filesystem::temp_directory_path() / "benchmarkSessionWriter";
  unsigned int run = 0;
  for (auto _ : state) {
    const std::string folder = (root / std::to_string(run++)).string();
    {
      vpProjectiveSessionWriter writer(folder, types);
      vpColVector q(6, 0.1);
      writer.addFrame(vpProjectiveSession::ZERO, q, 0.0, Il, Ir);
      for (unsigned int k = 1; k < frames; ++k) {
        q[k % 6] += 1e-3;
        writer.addFrame(vpProjectiveSession::SERVO, q, 0.04 * k, Il, Ir);
      }
    }
    state.PauseTiming();
    std::filesystem::remove_all(folder);
    state.ResumeTiming();
  }
  state.counters["fps"] =
      benchmark::Counter(static_cast<double>(frames) * state.iterations(), benchmark::Counter::kIsRate);
  std::filesystem::remove_all(root);
}
} // namespace

BENCHMARK(recordFrames)
    ->Arg(32)
    ->Arg(640)
    ->Unit(benchmark::kMillisecond)
    ->Iterations(1)
    ->Repetitions(3)
    ->ReportAggregatesOnly(true)
    ->UseRealTime();

BENCHMARK_MAIN();
