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
  Per-frame cost of the model's motion-capture uses, on the PUMA of the tests (eye-to-hand, 6 joints, 7 markers), its
  model acquired at 0.5 px, a 25 Hz sequence of 200 frames (one period of a smooth joint trajectory, so that the
  sequence loops without a jump) with 0.5 px noise:
  - vpProjectiveMotionCapture::capture() (Eigen API: the joints by the warm-started inverse kinematics, and the
    velocity fit); target at most 20 us per frame;
  - vpProjectiveRobot::inverseKinematics() warm-started at the previous frame (the vpColVector / vpImagePoint API);
  - vpProjectiveRigidBodyTracker::track() on the same 7 markers as a rigid set, projective (15 parameters) and rigid
    (6, with the model's metric upgrade).
  Run: tests/benchmark/benchmarkMotionCapture (medians over 10 repetitions).
*/

#include <cmath>
#include <vector>

#include <benchmark/benchmark.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveMotionCapture.h>
#include <visp3/projective/vpProjectiveRigidBodyTracker.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "../vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
const double kSigma = 0.5;
const unsigned int kFrames = 200;
const double kPeriod = 8.0; // seconds: 200 frames at 25 Hz

//! The PUMA, its model acquired at 0.5 px, and the noisy frames of one period of the trajectory.
struct Sequence {
  ArmSetup setup = pumaEyeToHand();
  vpProjectiveRobot robot;
  std::vector<std::vector<Eigen::Vector4d>> frames;
  std::vector<std::vector<vpImagePoint>> left, right;
  std::vector<vpColVector> truth;

  Sequence() : robot(setup.jointTypes())
  {
    vpGaussRand noise(1.0, 0.0, 1);
    setup.acquire(robot, kSigma, noise);
    robot.calibrate();
    const double amplitude[6] = {6.0, 5.0, 6.0, 20.0, 20.0, 30.0};
    for (unsigned int f = 0; f < kFrames; ++f) {
      const double w = 2.0 * M_PI * f / kFrames;
      vpColVector q(6);
      for (unsigned int i = 0; i < 6; ++i) {
        q[i] = vpMath::rad(amplitude[i]) * (0.6 * std::sin(w + i) + 0.4 * std::sin(2.0 * w + 2.0 * i));
      }
      std::vector<vpImagePoint> l, r;
      setup.images(setup.armJoints(q), l, r, kSigma, noise);
      std::vector<Eigen::Vector4d> s;
      for (size_t j = 0; j < l.size(); ++j) {
        s.push_back(Eigen::Vector4d(l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v()));
      }
      frames.push_back(s);
      left.push_back(l);
      right.push_back(r);
      truth.push_back(q);
    }
  }
};

const Sequence &sequence()
{
  static const Sequence data;
  return data;
}

double frameTime(unsigned long long k)
{
  return static_cast<double>(k) * kPeriod / kFrames;
}

void BM_MotionCapture_6joints_7markers(benchmark::State &state)
{
  const Sequence &seq = sequence();
  vpProjectiveMotionCapture capture(seq.robot.getModel());
  capture.setInitialJoints(seq.truth[0]);
  unsigned long long k = 0;
  for (auto _ : state) {
    const vpProjectiveArmModel::JointVector &q = capture.capture(frameTime(k), seq.frames[k % kFrames]);
    benchmark::DoNotOptimize(q.data());
    ++k;
  }
  state.SetLabel("joint error at the last frame " +
                 std::to_string(vpMath::deg((capture.getJoints() - seq.truth[(k - 1) % kFrames]).frobeniusNorm())) +
                 " deg");
}

void BM_RobotInverseKinematics_warmStarted(benchmark::State &state)
{
  const Sequence &seq = sequence();
  vpColVector q = seq.truth[0];
  unsigned long long k = 0;
  for (auto _ : state) {
    q = seq.robot.inverseKinematics(seq.left[k % kFrames], seq.right[k % kFrames], q);
    benchmark::DoNotOptimize(q.data);
    ++k;
  }
}

void BM_RigidBodyTracker_7markers(benchmark::State &state)
{
  const Sequence &seq = sequence();
  vpProjectiveRigidBodyTracker tracker;
  tracker.init(seq.robot.getStereoRig(), seq.left[0], seq.right[0], 0.0);
  if (state.range(0) != 0) {
    vpMatrix G(4, 4);
    for (unsigned int r = 0; r < 4; ++r) {
      for (unsigned int c = 0; c < 4; ++c) {
        G[r][c] = seq.robot.getModel().projectiveToMetric()(r, c);
      }
    }
    tracker.setProjectiveToMetric(G);
  }
  unsigned long long k = 1;
  for (auto _ : state) {
    const Eigen::Matrix4d &H = tracker.track(seq.frames[k % kFrames], frameTime(k));
    benchmark::DoNotOptimize(H.data());
    ++k;
  }
}
} // namespace

BENCHMARK(BM_MotionCapture_6joints_7markers)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RobotInverseKinematics_warmStarted)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_RigidBodyTracker_7markers)
    ->ArgName("rigid")
    ->Arg(0)
    ->Arg(1)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);

BENCHMARK_MAIN();
