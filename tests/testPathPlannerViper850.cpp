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
  vpServoProjective with path planning on ViSP's Viper850, written as a user writes it (the true joint limits, the
  image window, noisy images, s* measured once), the model acquired as vpProjectiveAcquisitionProcedure does: planning
  never loses a task that law (47) solves, solves the wide tasks the study traced, and respects the user's step limit
  (issue 18).
*/

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpPathPlannerTestTools.h"

using namespace vpProjectiveTest;

namespace
{
/*!
  ViSP's Viper850 (vpViper850 kinematics and joint limits) watched by a verged rig of other cameras than the paper's
  (30 cm baseline, 1.2 m away, 1200 px focal length), acquired as vpProjectiveAcquisitionProcedure does: each joint
  alone both ways, as far as 30 deg while the markers stay 10 px inside both images, pixel noise \e sigma.
*/
struct ViperWorld {
  ArmSetup s;
  vpProjectiveRobot robot;
  vpColVector qmin, qmax; //!< the true joint limits, in the model's joint values

  ViperWorld(double sigma, long seed, bool paperRig = false) : s(viperEyeToHand()), robot(s.jointTypes())
  {
    if (!paperRig) {
      const vpSimulatorStereoRig sim = vpSimulatorStereoRig::vergingRig(
          point3(0.0, 0.0, 0.0), 1.2, 0.3, vpCameraParameters(1200.0, 1200.0, 320.0, 240.0), 640, 480);
      s.camLeft = sim.getLeftCameraParameters();
      s.camRight = sim.getRightCameraParameters();
      s.rMl = sim.get_rMl();
      s.wMl = sim.get_wMl();
    }
    qmin = s.arm.getJointMin() - s.qRef;
    qmax = s.arm.getJointMax() - s.qRef;
    vpGaussRand noise(sigma, 0.0, seed);
    std::vector<vpImagePoint> left, right;
    robot.setStereoRig(s.rig());
    s.images(s.qRef, left, right, sigma, noise);
    robot.setZeroReference(left, right);
    for (unsigned int i = 0; i < s.n(); ++i) {
      for (int sign = -1; sign <= 1; sign += 2) {
        vpColVector q(s.n(), 0.0);
        for (int deg = 1; deg <= 30; ++deg) {
          vpColVector next(s.n(), 0.0);
          next[i] = sign * vpMath::rad(deg);
          if (next[i] < qmin[i] || next[i] > qmax[i] || !s.visible(s.armJoints(next), 10.0)) {
            break;
          }
          q = next;
        }
        s.images(s.armJoints(q), left, right, sigma, noise);
        robot.addTrialMotion(i, q[i], left, right);
      }
    }
    robot.calibrate();
  }

  //! Model joints within +-range of the zero reference, inside the limits, the markers 20 px inside both images.
  vpColVector draw(vpUniRand &rng, double range) const
  {
    for (;;) {
      const vpColVector q = s.randomVisibleJoints(rng, std::vector<double>(s.n(), range), 20.0);
      bool inside = q.size() == s.n();
      for (unsigned int i = 0; inside && i < q.size(); ++i) {
        inside = q[i] >= qmin[i] && q[i] <= qmax[i];
      }
      if (inside) {
        return q;
      }
    }
  }
};

struct NoisyRun {
  bool reached = false;       //!< image RMS error below 2 sigma within the budget, markers in view, no limit crossed
  double largestStep = 0.0;   //!< largest |qdot_i| commanded (joint units per call)
  double largestSample = 0.0; //!< largest joint step between two samples of the plan
  int followedInBand = 0;     //!< calls that followed the path with a joint in the avoidance's activation band
  double avoidanceWhileFollowing = 0.0; //!< largest |qdot2_i| of the joint-limit avoidance while following
  int mismatches = 0; //!< calls that reported SERVO_MODEL_MISMATCH (false alarms: no camera moves here)
};

//! A servo run as a user writes it (gain 0.5, no damping setting, the true limits, a 640 x 480 window with a 10 px
//! border), noisy images (sigma) of markers 0-2, s* measured once at the target; q <- q + qdot per call.
NoisyRun runNoisy(const ViperWorld &w, vpColVector q, const vpColVector &qTarget, bool planning, double sigma,
                  double qdotMax, long seed, int budget = 150)
{
  const ArmSetup &s = w.s;
  const std::vector<unsigned int> tracked = {0, 1, 2};
  vpGaussRand noise(sigma, 0.0, seed);
  auto measure = [&](const vpColVector &qm, std::vector<vpFeatureStereoPoint> &f) {
    for (size_t k = 0; k < tracked.size(); ++k) {
      const Eigen::Vector4d p = s.imageOf(s.armJoints(qm), tracked[k]);
      // Drawn last coordinate first (see point3() on the order).
      const double n3 = noise(), n2 = noise(), n1 = noise(), n0 = noise();
      f[k].buildFrom(p(0) + n0, p(1) + n1, p(2) + n2, p(3) + n3);
    }
  };
  std::vector<vpFeatureStereoPoint> f(tracked.size()), fStar(tracked.size());
  measure(qTarget, fStar);
  vpServoProjective task;
  task.setRobot(w.robot);
  task.setLambda(0.5);
  task.getControlLaw().setMaxJointVelocity(qdotMax);
  task.setJointLimits(w.qmin, w.qmax);
  task.setImageSize(640, 480, 10.0);
  task.setPathPlanning(planning);
  for (size_t k = 0; k < tracked.size(); ++k) {
    task.addFeature(f[k], fStar[k]);
  }
  NoisyRun run;
  for (int it = 0; it <= budget; ++it) {
    if (!trulyInView(s, q, tracked, 0.0)) {
      return run;
    }
    const std::vector<Eigen::Vector4d> sNow = trueImages(s, q, tracked);
    double error = 0.0;
    for (size_t k = 0; k < tracked.size(); ++k) {
      error += (sNow[k] - fStar[k].getFeature()).squaredNorm();
    }
    if (std::sqrt(error / (4.0 * tracked.size())) < 2.0 * sigma) {
      run.reached = true;
      return run;
    }
    measure(q, f);
    const vpColVector qdot = task.computeControlLaw(q);
    if (it == 0 && planning && task.getStatus() != vpServoProjective::SERVO_NO_PLAN) {
      const std::vector<JointVector> &path = task.getPathPlanner().getPath();
      for (size_t j = 1; path.size() > 1 && j < path.size() &&
                         task.getPathPlanner().getPathKind() != vpProjectivePathPlanner::PATH_LAW;
           ++j) {
        run.largestSample = std::max(run.largestSample, (path[j] - path[j - 1]).cwiseAbs().maxCoeff());
      }
    }
    run.mismatches += task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH;
    if (task.getReport().isFollowingPath()) {
      bool inBand = false;
      for (unsigned int i = 0; i < q.size(); ++i) {
        const double band = 0.1 * (w.qmax[i] - w.qmin[i]); // the avoidance's default activation band
        inBand = inBand || q[i] < w.qmin[i] + band || q[i] > w.qmax[i] - band;
      }
      run.followedInBand += inBand;
      const vpColVector qdot2 = task.getReport().getJointLimitVelocity();
      for (unsigned int i = 0; i < qdot2.size(); ++i) {
        run.avoidanceWhileFollowing = std::max(run.avoidanceWhileFollowing, std::abs(qdot2[i]));
      }
    }
    for (unsigned int i = 0; i < q.size(); ++i) {
      run.largestStep = std::max(run.largestStep, std::abs(qdot[i]));
      if (q[i] + qdot[i] < w.qmin[i] || q[i] + qdot[i] > w.qmax[i]) {
        return run;
      }
    }
    q += qdot;
  }
  return run;
}
} // namespace

// Issue 18: on ViSP's Viper850, with the user's settings (15 deg steps, the true limits, the image window), planning
// never loses a task that law (47) solves, and solves most of those that it does not.
TEST(PathPlanner, PlannedServoOnViper850NeverLosesWhatLawSolves)
{
  const double sigma = 0.5;
  const ViperWorld w(sigma, 3);
  vpUniRand rng(11);
  int law = 0, planned = 0, lawOnly = 0, followedInBand = 0;
  const int tasks = 16;
  for (int t = 0; t < tasks; ++t) {
    const vpColVector qStart = w.draw(rng, vpMath::rad(60.0)), qTarget = w.draw(rng, vpMath::rad(60.0));
    const bool byLaw = runNoisy(w, qStart, qTarget, false, sigma, vpMath::rad(15.0), 100 + t).reached;
    const NoisyRun run = runNoisy(w, qStart, qTarget, true, sigma, vpMath::rad(15.0), 100 + t);
    const bool byPlan = run.reached;
    // Following a path, the joint-limit avoidance stays out: the path is inside the limits, and its push on a joint
    // that starts in the band, projected on the other joints, threw the arm off its path.
    EXPECT_EQ(run.avoidanceWhileFollowing, 0.0) << "task " << t;
    // No camera moves: the model-mismatch detection must not stop a healthy task (the model's local motion is a
    // few percent off far from the acquisition, times path steps of 10 deg).
    EXPECT_EQ(run.mismatches, 0) << "task " << t;
    followedInBand += run.followedInBand;
    law += byLaw;
    planned += byPlan;
    lawOnly += byLaw && !byPlan;
    EXPECT_TRUE(!byLaw || byPlan) << "task " << t << ": law (47) reaches it, the planned servo does not";
  }
  EXPECT_EQ(lawOnly, 0);
  EXPECT_GE(planned, law + 4) << "wide tasks: planning must solve some that law (47) does not";
  EXPECT_GE(planned, tasks - 2);
  EXPECT_GT(followedInBand, 0) << "some path starts or passes in the avoidance's band (the case the check is for)";
  if (verboseTests()) {
    testLog() << "Viper850 +-60 deg: planned " << planned << "/" << tasks << ", law (47) " << law << "/" << tasks
              << std::endl;
  }
}

// Issue 18, wide tasks (+-90 deg) on ViSP's Viper850 seen by the paper's rig (the study's world): of the first 100
// tasks drawn here, the planned servo at 2f25c1e lost 1, 30, 66, 80, 92 and 99 (law (47) lost them too), for the
// causes the study traced: no path that keeps the three markers in view with one corner, a branch that no start of the
// inverse kinematics met, a joint at its limit that froze every joint, law (47) stalled at a minimum of the image error
// that the model cannot tell from the solution. Every one of them is solved now; and over the first 12 tasks, planning
// never loses a task that law (47) solves.
TEST(PathPlanner, PlannedServoOnViper850WideTasks)
{
  const double sigma = 0.5;
  const ViperWorld w(sigma, 7, true);
  vpUniRand rng(23);
  const std::vector<int> lost = {1, 30, 66, 80, 92, 99};
  int law = 0, planned = 0, general = 0;
  for (int t = 0; t <= lost.back(); ++t) {
    const vpColVector qStart = w.draw(rng, vpMath::rad(90.0)), qTarget = w.draw(rng, vpMath::rad(90.0));
    const bool wasLost = std::find(lost.begin(), lost.end(), t) != lost.end();
    if (t >= 12 && !wasLost) {
      continue; // drawn only to reach the next lost task
    }
    const bool byPlan = runNoisy(w, qStart, qTarget, true, sigma, vpMath::rad(15.0), 500 + t).reached;
    EXPECT_TRUE(!wasLost || byPlan) << "task " << t << ": lost again by the planned servo";
    if (t < 12) {
      const bool byLaw = runNoisy(w, qStart, qTarget, false, sigma, vpMath::rad(15.0), 500 + t).reached;
      EXPECT_TRUE(!byLaw || byPlan) << "task " << t << ": law (47) reaches it, the planned servo does not";
      law += byLaw;
      planned += byPlan;
      ++general;
    }
    if (verboseTests()) {
      testLog() << "task " << t << ": planned " << byPlan << (wasLost ? " (lost at 2f25c1e)" : "") << std::endl;
    }
  }
  EXPECT_GE(planned, general - 1) << "wide tasks: the planned servo must solve nearly all of them";
  EXPECT_GE(planned, law + 4) << "wide tasks: planning must solve several that law (47) does not";
  if (verboseTests()) {
    testLog() << "Viper850 +-90 deg, first " << general << " tasks: planned " << planned << ", law (47) " << law
              << std::endl;
  }
}

// The plan respects the user's step limit: with setMaxJointVelocity() below the planner's step, the path's samples
// are at most two thirds of it apart (room for the feedback), no call commands more, and the task is still reached.
TEST(PathPlanner, PlansRespectTheUserStepLimit)
{
  const double sigma = 0.5, qdotMax = vpMath::rad(3.0);
  const ViperWorld w(sigma, 5);
  vpUniRand rng(17);
  int reached = 0, followed = 0;
  for (int t = 0; t < 4; ++t) {
    const vpColVector qStart = w.draw(rng, vpMath::rad(45.0)), qTarget = w.draw(rng, vpMath::rad(45.0));
    const NoisyRun run = runNoisy(w, qStart, qTarget, true, sigma, qdotMax, 300 + t, 600);
    reached += run.reached;
    followed += run.largestSample > 0.0;
    EXPECT_LE(run.largestStep, qdotMax * (1.0 + 1e-9)) << "task " << t;
    EXPECT_LE(run.largestSample, 2.0 / 3.0 * qdotMax * (1.0 + 1e-9)) << "task " << t;
  }
  EXPECT_GE(reached, 3);
  EXPECT_GE(followed, 1) << "at least one task needs a path (the others run law (47) as rehearsed)";
}
