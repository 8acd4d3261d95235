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
  \file benchmarkServo.cpp
  \brief Timings of the non-metric servo (work order, issue 5 point 1), with Google Benchmark.

  (a) One control iteration of vpServoProjective (6 revolute joints, 3 points seen by both cameras: 12 x 6 task
      Jacobian from the projective model, then the damped control law), i.e. task.computeControlLaw(q) after the
      features were updated, against ViSP's metric vpServo of the same size (6 vpFeaturePoint, EYEINHAND_L_cVe_eJe,
      eJe = vpViper850::get_eJe(q) computed in the loop, CURRENT interaction matrix, computeControlLaw()). Both APIs
      of vpServoProjective are timed: the vpColVector one (allocates its result) and the Eigen one (no allocation).
  (b) The acquisition of the paper's arm (6 joints, 7 markers, 0.5 px noise): setStereoRig(), setZeroReference(),
      12 addTrialMotion() (trials [30, 20, 30, 40, 60, 60] deg both ways, as in tutorial-projective-servo.cpp) and
      calibrate(); and the same preceded by the weak calibration rig.estimate() from the acquisition images.
  (a'') (a) on the Eigen API with every default check on (model mismatch, arm following, image window, outliers,
      joint limits set, every joint in its free interval), against the plain law (no check): issue 22 asks <= 1.2
      times. The joints stay where they are while the task commands a motion: the arm-following check runs its whole
      arithmetic at every call (the fit of the motion to the commands, the median, each joint's state) but, the
      period not given, has nothing to learn it from and never stops the task.
  (a') (a) on the Eigen API with every robustness check of issue 6 on (image window, outlier rejection with
      prediction, a lost 4th marker, joint limits with a joint in its activation band), far from and near the target.
  (c) (a) on the Eigen API for n in {3, 6, 7, 12} joints and {3, 10, 50} points: synthetic n-revolute-joint chains
      (vpSimulatorArm) calibrated noise-free through the public acquisition API in the true projective frame of the
      paper's rig, with random points near the gripper as features.

  Every benchmark is repeated 10 times (Repetitions(10), ReportAggregatesOnly(true)): only the aggregates (mean,
  median, stddev, cv) of the 10 repetitions are printed. A reporter keeps the medians of the real and CPU time per
  iteration; at the end the program prints, for both APIs,
    ratio vpServo/vpServoProjective = median real time of BM_vpServo_Viper850 / median real time of
                                      BM_vpServoProjective_<API>
  (and the same ratio of CPU-time medians, steadier on a loaded machine), the (b) medians and the (c) table with its
  per-point slopes. The "allocs" counter is the number of malloc() calls per iteration of the timed loop, counted by a
  malloc() interposed in this program (operator new and Eigen both go through it); fractions of a call come from the
  framework's own allocations amortised over the iterations. The program checks that every Eigen-API benchmark
  allocates nothing per iteration (below 0.01 calls) and exits with 1 otherwise. The interposition adds about 1% to the
  instruction count of ViSP's vpServo iteration (306 allocations) and nothing to the projective one.
  "***WARNING*** Library was built as DEBUG" refers to Debian's libbenchmark itself, not to this program.

  Usage: benchmarkServo [Google Benchmark options, e.g. --benchmark_filter=Servo --benchmark_repetitions=20]
*/

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include <unistd.h>

#include <benchmark/benchmark.h>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/robot/vpViper850.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpServo.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

// ---------------------------------------------------------------------------------------------------------------
// malloc() calls, counted by interposing glibc's malloc family (operator new and Eigen's allocations use malloc).
// The counter is a relaxed load and store, not a locked read-modify-write, so that counting costs a cycle or two
// per allocation and does not penalise the allocating code being timed (the program is single-threaded while it
// counts). Build with -DBENCHMARK_SERVO_NO_MALLOC_COUNT to time without the interposition.
// ---------------------------------------------------------------------------------------------------------------
namespace
{
std::atomic<unsigned long long> g_mallocCalls(0);

inline void countMalloc()
{
  g_mallocCalls.store(g_mallocCalls.load(std::memory_order_relaxed) + 1, std::memory_order_relaxed);
}
} // namespace

#ifndef BENCHMARK_SERVO_NO_MALLOC_COUNT
extern "C" {
void *__libc_malloc(size_t size);
void *__libc_calloc(size_t count, size_t size);
void *__libc_realloc(void *ptr, size_t size);

void *malloc(size_t size)
{
  countMalloc();
  return __libc_malloc(size);
}

void *calloc(size_t count, size_t size)
{
  countMalloc();
  return __libc_calloc(count, size);
}

void *realloc(void *ptr, size_t size)
{
  countMalloc();
  return __libc_realloc(ptr, size);
}
}
#endif

namespace
{
unsigned long long mallocCalls()
{
  return g_mallocCalls.load(std::memory_order_relaxed);
}

//! Sets the "allocs" counter: malloc() calls per iteration of the timed loop.
void reportAllocations(benchmark::State &state, unsigned long long before)
{
#ifdef BENCHMARK_SERVO_NO_MALLOC_COUNT
  (void)state;
  (void)before;
#else
  const double calls = static_cast<double>(mallocCalls() - before);
  const double iterations = static_cast<double>(std::max<benchmark::IterationCount>(1, state.iterations()));
  state.counters["allocs"] = benchmark::Counter(calls / iterations);
#endif
}

//! Times task.computeControlLaw(q, qdot) (the Eigen API) over the benchmark's iterations and counts allocations.
void timeControlLaw(benchmark::State &state, vpServoProjective &task, const vpProjectiveRobot::JointVector &q)
{
  vpProjectiveRobot::JointVector qdot(q.size());
  const unsigned long long before = mallocCalls();
  for (auto _ : state) {
    task.computeControlLaw(q, qdot);
    benchmark::DoNotOptimize(qdot.data());
    benchmark::ClobberMemory();
  }
  reportAllocations(state, before);
}

//! The joint values of a vpColVector as the Eigen API's joint vector.
vpProjectiveRobot::JointVector jointVector(const vpColVector &q)
{
  vpProjectiveRobot::JointVector v(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    v(i) = q[i];
  }
  return v;
}

const double kNoiseSigma = 0.5; // px, work order (b)

vpColVector degToRad(const std::vector<double> &deg)
{
  vpColVector q(static_cast<unsigned int>(deg.size()));
  for (unsigned int i = 0; i < q.size(); ++i) {
    q[i] = vpMath::rad(deg[i]);
  }
  return q;
}

// ---------------------------------------------------------------------------------------------------------------
// Acquisition, as tutorial-projective-servo.cpp's acquire(): images at q = 0, then each joint alone both ways.
// ---------------------------------------------------------------------------------------------------------------
struct Trial {
  unsigned int joint;
  double amount;
  std::vector<vpImagePoint> left, right;
};

struct Acquisition {
  std::vector<vpImagePoint> left0, right0;     // markers at the zero reference
  std::vector<Trial> trials;                   // 2 per joint
  std::vector<vpImagePoint> allLeft, allRight; // every image, for the weak calibration
};

Acquisition simulateAcquisition(const vpSimulatorArm &arm, const vpSimulatorStereoRig &rig,
                                const std::vector<double> &trialAmounts, double sigma, vpGaussRand &noise)
{
  const unsigned int n = arm.getNumberOfJoints();
  Acquisition a;
  if (!rig.project(arm.getMarkers(vpColVector(n, 0.0)), a.left0, a.right0, sigma, noise)) {
    throw vpException(vpException::fatalError, "benchmarkServo: markers out of view at the zero reference");
  }
  a.allLeft = a.left0;
  a.allRight = a.right0;
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      Trial t{i, sign * trialAmounts[i], {}, {}};
      vpColVector q(n, 0.0);
      q[i] = t.amount;
      while (!rig.project(arm.getMarkers(q), t.left, t.right, sigma, noise)) {
        t.amount /= 2.0; // the markers left the view: a smaller trial
        q[i] = t.amount;
        if (std::abs(t.amount) < 1e-3) {
          throw vpException(vpException::fatalError, "benchmarkServo: no trial motion keeps the markers in view");
        }
      }
      a.allLeft.insert(a.allLeft.end(), t.left.begin(), t.left.end());
      a.allRight.insert(a.allRight.end(), t.right.begin(), t.right.end());
      a.trials.push_back(t);
    }
  }
  return a;
}

//! The timed part of (b): setStereoRig(), setZeroReference(), the trial motions and calibrate().
void calibrateRobot(vpProjectiveRobot &robot, const vpProjectiveStereoRig &rig, const Acquisition &a)
{
  robot.setStereoRig(rig);
  robot.setZeroReference(a.left0, a.right0);
  for (const Trial &t : a.trials) {
    robot.addTrialMotion(t.joint, t.amount, t.left, t.right);
  }
  robot.calibrate();
}

std::vector<vpProjectiveRobot::vpJointType> revoluteJoints(unsigned int n)
{
  return std::vector<vpProjectiveRobot::vpJointType>(n, vpProjectiveRobot::REVOLUTE);
}

// ---------------------------------------------------------------------------------------------------------------
// The paper's world (tutorial-projective-servo.cpp): rig 1 m away, PUMA-like arm, trials [30, 20, 30, 40, 60, 60].
// ---------------------------------------------------------------------------------------------------------------
struct PaperWorld {
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  std::vector<double> trialDeg = {30, 20, 30, 40, 60, 60};
  std::vector<unsigned int> tracked = {0, 1, 2};
  std::vector<double> startDeg = {-10.4112, 26.0700, 2.7911, -78.4711, 89.8020, 77.2404};
  std::vector<double> targetDeg = {1.2066, -3.1934, -44.1684, -2.8137, 52.3233, -85.8786};

  std::vector<double> trialAmounts() const
  {
    std::vector<double> amounts;
    for (double d : trialDeg) {
      amounts.push_back(vpMath::rad(d));
    }
    return amounts;
  }
};

const PaperWorld &paperWorld()
{
  static const PaperWorld world;
  return world;
}

//! Acquisitions of the paper's arm at 0.5 px for a few noise seeds, with the rig each one estimates.
struct PaperAcquisitions {
  std::vector<Acquisition> acquisitions;
  std::vector<vpProjectiveStereoRig> rigs;
  PaperAcquisitions()
  {
    const PaperWorld &w = paperWorld();
    for (long seed = 1; seed <= 4; ++seed) {
      vpGaussRand noise(1.0, 0.0, seed);
      acquisitions.push_back(simulateAcquisition(w.arm, w.rig, w.trialAmounts(), kNoiseSigma, noise));
      vpProjectiveStereoRig rig;
      rig.estimate(acquisitions.back().allLeft, acquisitions.back().allRight, std::max(1.0, 4.0 * kNoiseSigma));
      rigs.push_back(rig);
    }
  }
};

const PaperAcquisitions &paperAcquisitions()
{
  static const PaperAcquisitions data;
  return data;
}

//! The paper's arm calibrated at 0.5 px (seed 1): the model used by (a).
const vpProjectiveRobot &paperRobot()
{
  static const std::unique_ptr<vpProjectiveRobot> robot = [] {
    const PaperAcquisitions &data = paperAcquisitions();
    std::unique_ptr<vpProjectiveRobot> r(new vpProjectiveRobot(revoluteJoints(6)));
    calibrateRobot(*r, data.rigs[0], data.acquisitions[0]);
    return r;
  }();
  return *robot;
}

// ---------------------------------------------------------------------------------------------------------------
// (a) One control iteration, 12 x 6.
// ---------------------------------------------------------------------------------------------------------------

//! The servo task of the tutorial at its start: 3 tracked markers at the start configuration, s* at the target.
struct ProjectiveTask {
  std::vector<vpFeatureStereoPoint> s, sStar;
  vpServoProjective task;
  vpColVector q;

  explicit ProjectiveTask(const vpProjectiveRobot &robot) : s(3), sStar(3)
  {
    const PaperWorld &w = paperWorld();
    vpGaussRand noise(1.0, 0.0, 7);
    q = degToRad(w.startDeg);
    const std::vector<vpColVector> markers = w.arm.getMarkers(q);
    const std::vector<vpColVector> targets = w.arm.getMarkers(degToRad(w.targetDeg));
    task.setRobot(robot);
    task.setLambda(0.5);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(15.0));
    for (unsigned int k = 0; k < 3; ++k) {
      vpImagePoint l, r;
      w.rig.project(targets[w.tracked[k]], l, r, kNoiseSigma, noise);
      sStar[k].buildFrom(l, r);
      w.rig.project(markers[w.tracked[k]], l, r, kNoiseSigma, noise);
      s[k].buildFrom(l, r); // the features are updated: the loop below times computeControlLaw() alone
    }
    for (unsigned int k = 0; k < 3; ++k) {
      task.addFeature(s[k], sStar[k]);
    }
  }
};

//! Condition number and damping of the timed task: they tell whether the damped branch of the control law ran.
std::string taskLabel(const vpServoProjective &task)
{
  // The status first: a task that stopped would time its stop, not its law.
  const std::string status = vpServoProjectiveReport::toString(task.getStatus());
  char label[96];
  std::snprintf(label, sizeof(label), "%s, cond %.3g, damping %.3g", status.substr(0, status.find(' ')).c_str(),
                task.getReport().getConditionNumber(), task.getReport().getDamping());
  return label;
}

/*
  The timed loops below hold q where it is, as a benchmark must to time the same iteration again; the arm-following
  check (vpServoArmFollowing, on by default) rightly stops such a task after a few calls, and the loop would then time
  the stop. So it is off in them; the label starts with the status, which says the law ran.
*/
void BM_vpServoProjective_vpColVector(benchmark::State &state)
{
  ProjectiveTask t(paperRobot());
  t.task.getArmFollowing().setEnabled(false);
  const unsigned long long before = mallocCalls();
  for (auto _ : state) {
    vpColVector qdot = t.task.computeControlLaw(t.q);
    benchmark::DoNotOptimize(qdot.data);
    benchmark::ClobberMemory();
  }
  reportAllocations(state, before);
  state.SetLabel(taskLabel(t.task));
}

void BM_vpServoProjective_Eigen(benchmark::State &state)
{
  ProjectiveTask t(paperRobot());
  t.task.getArmFollowing().setEnabled(false);
  timeControlLaw(state, t.task, jointVector(t.q));
  state.SetLabel(taskLabel(t.task));
}

//! The same with the model-mismatch detection off (setModelMismatchThreshold(0)) and the arm-following check off
//! (getArmFollowing().setEnabled(false)): the law alone, as before issues 12 and 30.
void BM_vpServoProjective_Eigen_NoMismatchCheck(benchmark::State &state)
{
  ProjectiveTask t(paperRobot());
  t.task.getModelMismatch().setThreshold(0.0);
  t.task.getArmFollowing().setEnabled(false);
  timeControlLaw(state, t.task, jointVector(t.q));
  state.SetLabel(taskLabel(t.task));
}

/*!
  The same 12 x 6 task with every default check on and the optional ones that a real loop sets: the model-mismatch
  check (on by default), the feature health with an image window and outlier rejection (epipolar distance and
  prediction, the features accepted once before the loop), and joint limits (every joint in its free interval, as
  during most of a task). Issue 22 asks it to cost at most 1.2 times the plain law (NoMismatchCheck: no check at all).
*/
void BM_vpServoProjective_Eigen_DefaultChecks(benchmark::State &state)
{
  ProjectiveTask t(paperRobot());
  const PaperWorld &w = paperWorld();
  t.task.getArmFollowing().setEnabled(false);
  t.task.setImageSize(w.rig.getWidth(), w.rig.getHeight(), 10);
  t.task.getFeatureHealth().setOutlierThreshold(5.0);
  vpColVector qmin(6), qmax(6);
  for (unsigned int i = 0; i < 6; ++i) {
    qmin[i] = t.q[i] - vpMath::rad(100.0);
    qmax[i] = t.q[i] + vpMath::rad(100.0);
  }
  t.task.setJointLimits(qmin, qmax);
  const vpProjectiveRobot::JointVector q = jointVector(t.q);
  vpProjectiveRobot::JointVector qdot(q.size());
  t.task.computeControlLaw(q, qdot); // accepts the features once: the loop also evaluates their predictions
  t.task.computeControlLaw(q, qdot); // and remembers their points for the mismatch check
  timeControlLaw(state, t.task, q);
  state.SetLabel(taskLabel(t.task));
}

/*!
  The same task settled (setSettling(true)): s at the target, s* taught from 16 frames there, both noisy at 0.5 px,
  and enough calls before the loop that the settling gain decreases as lambda / (1 + lambda k) in every timed call
  (its F-tests and its noise estimate included); the label tells whether it was settled at the end.
*/
void BM_vpServoProjective_Eigen_Settling(benchmark::State &state)
{
  const PaperWorld &w = paperWorld();
  ProjectiveTask t(paperRobot());
  vpGaussRand noise(1.0, 0.0, 11);
  const std::vector<vpColVector> targets = w.arm.getMarkers(degToRad(w.targetDeg));
  for (unsigned int k = 0; k < 3; ++k) {
    std::vector<vpImagePoint> left(16), right(16);
    for (unsigned int f = 0; f < 16; ++f) {
      w.rig.project(targets[w.tracked[k]], left[f], right[f], kNoiseSigma, noise);
    }
    t.sStar[k].buildFrom(left, right);
    vpImagePoint l, r;
    w.rig.project(targets[w.tracked[k]], l, r, kNoiseSigma, noise);
    t.s[k].buildFrom(l, r);
  }
  t.task.setSettling(true);
  t.task.getArmFollowing().setEnabled(false);
  const vpProjectiveRobot::JointVector q = jointVector(degToRad(w.targetDeg));
  vpProjectiveRobot::JointVector qdot(q.size());
  for (unsigned int i = 0; i < 5; ++i) {
    t.task.computeControlLaw(q, qdot); // converged: settled from the second call on
  }
  timeControlLaw(state, t.task, q);
  state.SetLabel(t.task.getControlLaw().getSettling().isSettled() ? "settled" : "NOT settled");
}

/*!
  The same task with every check of issue 6 on, so that each one runs in the timed loop: an image window
  (setImageSize), outlier rejection (setOutlierThreshold: epipolar distance and prediction H(q) H(q_l)^-1 M_l, the
  features accepted once before the loop), a 4th marker declared lost (SERVO_REDUCED: the rank test's
  eigenvalues), and joint limits with joint 0 beyond l1 in its upper activation band (the large projection operator
  and the avoidance term). \e nearTarget puts s* 0.1 px from s on every coordinate (||e|| = 0.35 px, between vpServo's
  e0 = 0.1 and e1 = 0.7): the operator then also needs the eigenvectors of J^T J for I - J^+ J.
*/
struct RobustTask {
  std::vector<vpFeatureStereoPoint> s, sStar;
  vpServoProjective task;
  vpProjectiveRobot::JointVector q;

  RobustTask(const vpProjectiveRobot &robot, bool nearTarget) : s(4), sStar(4), task(), q(6)
  {
    const PaperWorld &w = paperWorld();
    vpGaussRand noise(1.0, 0.0, 7);
    const vpColVector qv = degToRad(w.startDeg);
    const std::vector<vpColVector> markers = w.arm.getMarkers(qv);
    const std::vector<vpColVector> targets = w.arm.getMarkers(degToRad(w.targetDeg));
    const unsigned int tracked[4] = {w.tracked[0], w.tracked[1], w.tracked[2], 3};
    task.setRobot(robot);
    task.setLambda(0.5);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(15.0));
    for (unsigned int k = 0; k < 4; ++k) {
      vpImagePoint l, r;
      w.rig.project(markers[tracked[k]], l, r, kNoiseSigma, noise);
      s[k].buildFrom(l, r);
      if (nearTarget) {
        sStar[k].buildFrom(l.get_u() + 0.1, l.get_v() - 0.1, r.get_u() + 0.1, r.get_v() - 0.1);
      } else {
        w.rig.project(targets[tracked[k]], l, r, kNoiseSigma, noise);
        sStar[k].buildFrom(l, r);
      }
      task.addFeature(s[k], sStar[k]);
    }
    vpColVector qmin(6), qmax(6);
    const double range = vpMath::rad(200.0);
    for (unsigned int i = 0; i < 6; ++i) {
      q(i) = qv[i];
      const double position = i == 0 ? 0.95 : 0.5; // fraction of [qmin, qmax]: joint 0 beyond l1 = 0.93
      qmin[i] = qv[i] - position * range;
      qmax[i] = qmin[i] + range;
    }
    task.setImageSize(w.rig.getWidth(), w.rig.getHeight());
    task.getFeatureHealth().setOutlierThreshold(5.0);
    task.setJointLimits(qmin, qmax);
    task.getArmFollowing().setEnabled(false);
    vpProjectiveRobot::JointVector qdot(6);
    task.computeControlLaw(q, qdot); // accepts the features once: the loop also evaluates their predictions
    task.setFeatureTracked(3, false);
  }
};

std::string robustLabel(const vpServoProjective &task)
{
  // The status's name (every status: a stopped task's label says why), then the features and the avoidance.
  const std::string status = vpServoProjectiveReport::toString(task.getStatus());
  char label[96];
  std::snprintf(label, sizeof(label), "%s, %u/%u active, |q2| %.2g", status.substr(0, status.find(' ')).c_str(),
                task.getReport().getNumberOfActiveFeatures(), task.getReport().getNumberOfFeatures(),
                task.getReport().getJointLimitVelocity().frobeniusNorm());
  return label;
}

void BM_vpServoProjective_Eigen_Robust(benchmark::State &state)
{
  RobustTask t(paperRobot(), state.range(0) != 0);
  timeControlLaw(state, t.task, t.q);
  state.SetLabel(robustLabel(t.task));
}

/*!
  Global servoing (setPathPlanning): (d) the planning of the tutorial's task, once per target (the inverse kinematics
  from 24 starts, the target, the path: straight image lines, tracked), timed as setPathPlanning(true) followed by the
  computeControlLaw() that plans; (e) one control iteration while following the path (the sample's predicted features
  as the reference, the path step as feedforward), with a path of steps of 0.03 deg so that every timed iteration
  follows it (the fixed number of iterations below stays within it).
*/
void BM_vpServoProjective_Planning(benchmark::State &state)
{
  ProjectiveTask t(paperRobot());
  t.task.setPathPlanning(true);
  for (auto _ : state) {
    t.task.setPathPlanning(true);
    vpColVector qdot = t.task.computeControlLaw(t.q);
    benchmark::DoNotOptimize(qdot.data);
  }
  state.SetLabel(t.task.getPathPlanner().getDescription());
}

void BM_vpServoProjective_Eigen_Following(benchmark::State &state)
{
  ProjectiveTask t(paperRobot());
  t.task.setPathPlanning(true);
  t.task.getPathPlanner().setMaxJointStep(vpMath::rad(0.03));
  t.task.getPathPlanner().setRehearsalBudget(0); // a path, even where law (47) would do: this times the follower
  const vpProjectiveRobot::JointVector q = jointVector(t.q);
  vpProjectiveRobot::JointVector qdot(6);
  t.task.computeControlLaw(q, qdot); // plans; the next call aims at sample 2 with the arm at sample 1
  // The arm where the plan puts it at every call (a fixed q would leave the path: the task would plan again).
  const std::vector<vpProjectiveRobot::JointVector> &path = t.task.getPathPlanner().getPath();
  size_t sample = 1;
  const unsigned long long before = mallocCalls();
  for (auto _ : state) {
    t.task.computeControlLaw(path[std::min(sample++, path.size() - 1)], qdot);
    benchmark::DoNotOptimize(qdot.data());
    benchmark::ClobberMemory();
  }
  reportAllocations(state, before);
  state.SetLabel(std::string(t.task.getReport().isFollowingPath() ? "following, " : "NOT following, ") +
                 std::to_string(t.task.getPathPlanner().getPath().size()) + " samples");
}

/*!
  ViSP's metric eye-in-hand servo of the same size: 6 image points (x, y, Z), a 12 x 6 task Jacobian
  L cVe eJe with eJe = vpViper850::get_eJe(q) (the metric counterpart of the projective model Jacobian) computed in
  the loop, and the pseudo-inverse control law.
*/
void BM_vpServo_Viper850(benchmark::State &state)
{
  vpViper850 robot;
  const vpColVector q = degToRad({10.0, -20.0, 30.0, 15.0, 40.0, -25.0});
  vpVelocityTwistMatrix cVe;
  robot.get_cVe(cVe);
  const double x[6] = {-0.12, 0.05, 0.11, -0.04, 0.02, 0.13};
  const double y[6] = {-0.08, -0.10, 0.03, 0.09, 0.12, -0.02};
  const double Z[6] = {0.95, 1.02, 1.10, 0.98, 1.05, 0.90};
  std::vector<vpFeaturePoint> s(6), sStar(6);
  vpServo task;
  task.setServo(vpServo::EYEINHAND_L_cVe_eJe);
  task.setInteractionMatrixType(vpServo::CURRENT);
  task.setLambda(0.5);
  task.set_cVe(cVe);
  for (unsigned int k = 0; k < 6; ++k) {
    s[k].buildFrom(x[k], y[k], Z[k]);
    sStar[k].buildFrom(0.9 * x[k] + 0.01, 0.9 * y[k] - 0.02, 1.0);
    task.addFeature(s[k], sStar[k]);
  }
  vpMatrix eJe;
  const unsigned long long before = mallocCalls();
  for (auto _ : state) {
    robot.get_eJe(q, eJe);
    task.set_eJe(eJe);
    vpColVector v = task.computeControlLaw();
    benchmark::DoNotOptimize(v.data);
    benchmark::ClobberMemory();
  }
  reportAllocations(state, before);
}

// ---------------------------------------------------------------------------------------------------------------
// (b) Acquisition and calibration, 6 joints, 7 markers, 0.5 px.
// ---------------------------------------------------------------------------------------------------------------
void BM_Calibrate_6joints_7markers(benchmark::State &state)
{
  const PaperAcquisitions &data = paperAcquisitions();
  size_t k = 0;
  double residual = 0.0;
  const unsigned long long before = mallocCalls();
  for (auto _ : state) {
    vpProjectiveRobot robot(revoluteJoints(6));
    calibrateRobot(robot, data.rigs[k], data.acquisitions[k]);
    residual = robot.getAcquisition()
                   .getCalibrationResidual(); // not DoNotOptimize(residual): GCC can corrupt a double lvalue there
    benchmark::ClobberMemory();
    k = (k + 1) % data.acquisitions.size();
  }
  reportAllocations(state, before);
  char label[64];
  std::snprintf(label, sizeof(label), "BA RMS %.2f px", residual); // the self-check: about the noise level
  state.SetLabel(label);
}

void BM_RigEstimateAndCalibrate_6joints_7markers(benchmark::State &state)
{
  const PaperAcquisitions &data = paperAcquisitions();
  size_t k = 0;
  for (auto _ : state) {
    const Acquisition &a = data.acquisitions[k];
    vpProjectiveStereoRig rig;
    rig.estimate(a.allLeft, a.allRight, std::max(1.0, 4.0 * kNoiseSigma));
    vpProjectiveRobot robot(revoluteJoints(6));
    calibrateRobot(robot, rig, a);
    benchmark::DoNotOptimize(robot.getAcquisition().getCalibrationResidual());
    k = (k + 1) % data.acquisitions.size();
  }
}

// ---------------------------------------------------------------------------------------------------------------
// (c) Growth with the number of joints and of points.
// ---------------------------------------------------------------------------------------------------------------

/*!
  A synthetic chain of n revolute joints (standard DH rows, alternating +-90 deg twists, reach about 0.5 m whatever
  n) carrying the paper's gripper and its 7 markers, its base placed so that the gripper is where the PUMA's is at
  q = 0 (in view of the paper's rig).
*/
vpSimulatorArm syntheticChain(unsigned int n)
{
  std::vector<vpSimulatorArm::vpDHRow> dh;
  const double link = 0.5 / n;
  for (unsigned int i = 0; i < n; ++i) {
    const double theta = vpMath::rad(i % 2 == 0 ? -25.0 : 35.0);
    const double alpha = vpMath::rad(i % 2 == 0 ? 90.0 : -90.0);
    dh.push_back({vpProjectiveJoint::REVOLUTE, theta, 0.6 * link, 0.8 * link, alpha});
  }
  const vpSimulatorArm atOrigin(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                                vpHomogeneousMatrix());
  const vpHomogeneousMatrix wMt = paperWorld().arm.get_wMt(vpColVector(6, 0.0));
  const vpHomogeneousMatrix bMt = atOrigin.get_wMt(vpColVector(n, 0.0));
  return vpSimulatorArm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(), wMt * bMt.inverse());
}

//! A calibrated model of syntheticChain(n): noise-free images, the rig's true fundamental matrix, 20 deg trials.
struct SyntheticRobot {
  vpSimulatorArm arm;
  vpProjectiveRobot robot;
  explicit SyntheticRobot(unsigned int n) : arm(syntheticChain(n)), robot(revoluteJoints(n))
  {
    const vpSimulatorStereoRig &simRig = paperWorld().rig;
    vpGaussRand noise(1.0, 0.0, 1);
    const Acquisition a = simulateAcquisition(arm, simRig, std::vector<double>(n, vpMath::rad(20.0)), 0.0, noise);
    vpProjectiveStereoRig rig;
    rig.setFundamentalMatrix(simRig.getFundamentalMatrix());
    calibrateRobot(robot, rig, a);
  }
};

const SyntheticRobot &syntheticRobot(unsigned int n)
{
  static std::map<unsigned int, std::unique_ptr<SyntheticRobot>> robots;
  std::unique_ptr<SyntheticRobot> &r = robots[n];
  if (!r) {
    r.reset(new SyntheticRobot(n));
  }
  return *r;
}

/*!
  (a) for n joints and N points: N random points within 4 cm of the gripper's centre at a random configuration
  (within +-5 deg of the zero reference), seen by both cameras; s* their images at q = 0.
*/
void BM_Scaling(benchmark::State &state)
{
  const unsigned int n = static_cast<unsigned int>(state.range(0));
  const unsigned int N = static_cast<unsigned int>(state.range(1));
  const SyntheticRobot *synthetic = nullptr;
  try {
    synthetic = &syntheticRobot(n);
  } catch (const vpException &e) {
    state.SkipWithError(("calibration of the synthetic chain failed: " + e.getStringMessage()).c_str());
    return;
  }
  const vpSimulatorStereoRig &simRig = paperWorld().rig;
  vpUniRand uniform(static_cast<long>(100 * n + N));
  vpProjectiveRobot::JointVector q(n);
  vpColVector qv(n);
  for (unsigned int i = 0; i < n; ++i) {
    q(i) = qv[i] = vpMath::rad(uniform.uniform(-5.0, 5.0));
  }
  const vpHomogeneousMatrix wMt = synthetic->arm.get_wMt(qv);
  const vpHomogeneousMatrix wMt0 = synthetic->arm.get_wMt(vpColVector(n, 0.0));
  std::vector<vpFeatureStereoPoint> s(N), sStar(N);
  vpServoProjective task;
  task.setRobot(synthetic->robot);
  task.setLambda(0.5);
  task.getArmFollowing().setEnabled(false);
  for (unsigned int k = 0; k < N; ++k) {
    vpColVector tX(4, 1.0), wX;
    do {
      for (unsigned int c = 0; c < 3; ++c) {
        tX[c] = uniform.uniform(-0.04, 0.04);
      }
      wX = wMt * tX;
    } while (!simRig.isVisible(wX));
    vpImagePoint l, r;
    simRig.project(wX, l, r);
    s[k].buildFrom(l, r);
    simRig.project(wMt0 * tX, l, r);
    sStar[k].buildFrom(l, r);
    task.addFeature(s[k], sStar[k]);
  }
  timeControlLaw(state, task, q);
  state.SetLabel(taskLabel(task));
}

// ---------------------------------------------------------------------------------------------------------------
// Reporting: the console output, plus the medians over the repetitions of the real and CPU time per iteration.
// ---------------------------------------------------------------------------------------------------------------
struct Median {
  double real = -1.0;   //!< us, negative if the benchmark did not run
  double cpu = -1.0;    //!< us
  double allocs = -1.0; //!< malloc() calls per iteration (median), negative if not counted
  bool valid() const { return real > 0.0 && cpu > 0.0; }
};

class MedianReporter : public benchmark::ConsoleReporter
{
public:
  //! Colours only on a terminal (the display reporter's --benchmark_color does not reach a custom reporter).
  MedianReporter() : ConsoleReporter(isatty(fileno(stdout)) ? OO_ColorTabular : OO_Tabular) {}

  void ReportRuns(const std::vector<Run> &runs) override
  {
    for (const Run &run : runs) {
      if (run.run_type == Run::RT_Aggregate && run.aggregate_name == "median" && !run.error_occurred) {
        const double toMicroseconds = 1e6 / benchmark::GetTimeUnitMultiplier(run.time_unit);
        const benchmark::BenchmarkName &name = run.run_name;
        Median &m = m_median[name.function_name + (name.args.empty() ? "" : "/" + name.args)];
        m.real = run.GetAdjustedRealTime() * toMicroseconds;
        m.cpu = run.GetAdjustedCPUTime() * toMicroseconds;
        const auto allocs = run.counters.find("allocs");
        m.allocs = allocs == run.counters.end() ? -1.0 : static_cast<double>(allocs->second);
      }
    }
    ConsoleReporter::ReportRuns(runs);
  }

  //! Medians (us) of a benchmark, by its name without the repetition suffix, e.g. "BM_Scaling/joints:3/points:10".
  Median median(const std::string &name) const
  {
    const auto it = m_median.find(name);
    return it == m_median.end() ? Median() : it->second;
  }

  //! Every benchmark that ran, by name.
  const std::map<std::string, Median> &medians() const { return m_median; }

private:
  std::map<std::string, Median> m_median;
};

//! The ratio of the medians; \e target: also says whether the work order's ratio >= 5 is met.
void printRatio(const char *api, const Median &metric, const Median &projective, bool target = true)
{
  if (!metric.valid() || !projective.valid()) {
    return;
  }
  const double ratio = metric.real / projective.real;
  std::printf("    ratio vpServo/vpServoProjective = %.2f (%s, real time; CPU time: %.2f", ratio, api,
              metric.cpu / projective.cpu);
  if (target) {
    std::printf("; target >= 5: %s", ratio >= 5.0 ? "met" : "NOT met");
  }
  std::printf(")\n");
}

void printSummary(const MedianReporter &reporter)
{
  std::printf("\nSummary: medians over the repetitions of the time per iteration, real (CPU)\n");
  const Median metric = reporter.median("BM_vpServo_Viper850");
  const Median projective = reporter.median("BM_vpServoProjective_vpColVector");
  const Median projectiveEigen = reporter.median("BM_vpServoProjective_Eigen");
  if (metric.valid() || projective.valid() || projectiveEigen.valid()) {
    std::printf("(a) one control iteration, 6 joints, 3 stereo points / 6 image points: 12 x 6 task Jacobian\n");
  }
  if (metric.valid()) {
    std::printf("    vpServo (vpViper850 eJe, 6 vpFeaturePoint)   %9.3f us (%.3f)\n", metric.real, metric.cpu);
  }
  if (projective.valid()) {
    std::printf("    vpServoProjective, vpColVector API           %9.3f us (%.3f)\n", projective.real, projective.cpu);
  }
  if (projectiveEigen.valid()) {
    std::printf("    vpServoProjective, Eigen API                 %9.3f us (%.3f)\n", projectiveEigen.real,
                projectiveEigen.cpu);
  }
  const Median robust = reporter.median("BM_vpServoProjective_Eigen_Robust/near_target:0");
  const Median robustNear = reporter.median("BM_vpServoProjective_Eigen_Robust/near_target:1");
  if (robust.valid()) {
    std::printf("    vpServoProjective, Eigen API, every check on %9.3f us (%.3f) [4 points, 1 lost, joint 0 in "
                "its band]\n",
                robust.real, robust.cpu);
  }
  if (robustNear.valid()) {
    std::printf("    the same 0.35 px from s* (I - J^+ J blended) %9.3f us (%.3f)\n", robustNear.real, robustNear.cpu);
  }
  const Median plain = reporter.median("BM_vpServoProjective_Eigen_NoMismatchCheck");
  const Median checks = reporter.median("BM_vpServoProjective_Eigen_DefaultChecks");
  if (plain.valid()) {
    std::printf("    vpServoProjective, Eigen API, plain law      %9.3f us (%.3f) [no check at all]\n", plain.real,
                plain.cpu);
  }
  if (checks.valid()) {
    std::printf("    vpServoProjective, Eigen API, default checks %9.3f us (%.3f) [mismatch, image window, outliers, "
                "joint limits]\n",
                checks.real, checks.cpu);
  }
  if (plain.valid() && checks.valid()) {
    const double cost = checks.real / plain.real;
    std::printf("    default checks / plain law = %.2f (real time; CPU time: %.2f; target <= 1.2: %s)\n", cost,
                checks.cpu / plain.cpu, cost <= 1.2 ? "met" : "NOT met");
  }
  if (metric.valid() && checks.valid()) {
    const double ratio = metric.real / checks.real;
    std::printf("    ratio vpServo/vpServoProjective = %.2f (default checks, real time; CPU time: %.2f; target >= 6: "
                "%s)\n",
                ratio, metric.cpu / checks.cpu, ratio >= 6.0 ? "met" : "NOT met");
  }
  printRatio("vpColVector API", metric, projective);
  printRatio("Eigen API", metric, projectiveEigen);
  printRatio("Eigen API, every check on", metric, robust, false);

  const Median planning = reporter.median("BM_vpServoProjective_Planning");
  const Median following = reporter.median("BM_vpServoProjective_Eigen_Following");
  if (planning.valid()) {
    std::printf("(d) global servoing: planning the task (6 joints, 3 features)   %9.3f ms (%.3f)\n",
                planning.real / 1000.0, planning.cpu / 1000.0);
  }
  if (following.valid()) {
    std::printf("    one control iteration following the path, Eigen API %9.3f us (%.3f)", following.real,
                following.cpu);
    if (projectiveEigen.valid()) {
      std::printf(": %.2f x the iteration of law (47) (target <= 2: %s)", following.real / projectiveEigen.real,
                  following.real <= 2.0 * projectiveEigen.real ? "met" : "NOT met");
    }
    std::printf("\n");
  }

  const Median calibrate = reporter.median("BM_Calibrate_6joints_7markers");
  const Median withRig = reporter.median("BM_RigEstimateAndCalibrate_6joints_7markers");
  if (calibrate.valid() || withRig.valid()) {
    std::printf("(b) acquisition, 6 joints, 7 markers, 12 trial motions, 0.5 px noise\n");
  }
  if (calibrate.valid()) {
    std::printf("    setStereoRig + setZeroReference + 12 addTrialMotion + calibrate  %7.3f ms (%.3f; target < 10 ms: "
                "%s)\n",
                calibrate.real / 1000.0, calibrate.cpu / 1000.0, calibrate.real < 10000.0 ? "met" : "NOT met");
  }
  if (withRig.valid()) {
    std::printf("    the same preceded by rig.estimate() on the 91 image pairs        %7.3f ms (%.3f)\n",
                withRig.real / 1000.0, withRig.cpu / 1000.0);
  }

  const unsigned int joints[4] = {3, 6, 7, 12};
  const unsigned int points[3] = {3, 10, 50};
  bool header = false;
  for (unsigned int n : joints) {
    Median t[3];
    bool complete = true;
    for (int p = 0; p < 3; ++p) {
      t[p] = reporter.median("BM_Scaling/joints:" + std::to_string(n) + "/points:" + std::to_string(points[p]));
      complete = complete && t[p].valid();
    }
    if (!complete) {
      continue;
    }
    if (!header) {
      std::printf("(c) one control iteration (Eigen API), real time in us; slope: us per added point (CPU time in "
                  "brackets)\n");
      std::printf("    joints  3 points  10 points  50 points  slope 3-10  slope 10-50  ratio of slopes\n");
      header = true;
    }
    const double slopeLow = (t[1].real - t[0].real) / 7.0, slopeHigh = (t[2].real - t[1].real) / 40.0;
    const double cpuLow = (t[1].cpu - t[0].cpu) / 7.0, cpuHigh = (t[2].cpu - t[1].cpu) / 40.0;
    std::printf("    %6u %9.2f %10.2f %10.2f %11.3f %12.3f %8.2f (%.2f)\n", n, t[0].real, t[1].real, t[2].real,
                slopeLow, slopeHigh, slopeHigh / slopeLow, cpuHigh / cpuLow);
  }
  if (header) {
    std::printf("    growth is linear in the points when the ratio of slopes is near 1\n");
  }
}

/*!
  The allocation check: every benchmark of the Eigen API (BM_vpServoProjective_Eigen*, BM_Scaling) must allocate
  nothing per iteration (fewer than 0.01 malloc() calls: the framework's own, amortised). Returns false otherwise.
*/
bool checkAllocations(const MedianReporter &reporter)
{
#ifdef BENCHMARK_SERVO_NO_MALLOC_COUNT
  (void)reporter;
  return true;
#else
  bool ok = true, any = false;
  for (const auto &entry : reporter.medians()) {
    const std::string &name = entry.first;
    if (name.rfind("BM_vpServoProjective_Eigen", 0) != 0 && name.rfind("BM_Scaling", 0) != 0) {
      continue;
    }
    any = true;
    if (!(entry.second.allocs >= 0.0 && entry.second.allocs < 0.01)) {
      std::printf("    ALLOCATES: %s, %.3f malloc() calls per iteration\n", name.c_str(), entry.second.allocs);
      ok = false;
    }
  }
  if (any) {
    std::printf("allocation check (Eigen API, per iteration): %s\n", ok ? "no allocation" : "FAILED");
  }
  return ok;
#endif
}

} // namespace

BENCHMARK(BM_vpServo_Viper850)->Repetitions(10)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vpServoProjective_vpColVector)->Repetitions(10)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vpServoProjective_Eigen)->Repetitions(10)->ReportAggregatesOnly(true)->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vpServoProjective_Eigen_NoMismatchCheck)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vpServoProjective_Eigen_DefaultChecks)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vpServoProjective_Eigen_Settling)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vpServoProjective_Eigen_Robust)
    ->ArgName("near_target")
    ->Arg(0)
    ->Arg(1)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_vpServoProjective_Planning)->Repetitions(10)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_vpServoProjective_Eigen_Following)
    ->Iterations(2000)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);
BENCHMARK(BM_Calibrate_6joints_7markers)->Repetitions(10)->ReportAggregatesOnly(true)->Unit(benchmark::kMillisecond);
BENCHMARK(BM_RigEstimateAndCalibrate_6joints_7markers)
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMillisecond);
BENCHMARK(BM_Scaling)
    ->ArgsProduct({{3, 6, 7, 12}, {3, 10, 50}})
    ->ArgNames({"joints", "points"})
    ->Repetitions(10)
    ->ReportAggregatesOnly(true)
    ->Unit(benchmark::kMicrosecond);

int main(int argc, char **argv)
{
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) {
    return 1;
  }
  MedianReporter reporter;
  benchmark::RunSpecifiedBenchmarks(&reporter);
  printSummary(reporter);
  const bool allocationFree = checkAllocations(reporter);
  benchmark::Shutdown();
  return allocationFree ? 0 : 1;
}
