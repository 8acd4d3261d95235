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
  The arm-following check over long seeded runs (issue 30, point 3; ctest label "study"), on the plugin's simulated
  robot (vpSimulatorRobotArm, vpServoArmFollowingTestTools.h) moving four arms: the PUMA-like arm, ViSP's Viper850
  geometry, the R-R-P-R-R-R arm (a prismatic third joint) and a 3-joint R-P-R arm, each acquired at the run's pixel
  noise.
  - False alarms: tasks at 0.1, 0.5 and 1 px, each with a share of the realistic effects of a correct arm (encoder
    noise 1e-5, one call of command latency on every other task, a pause of 2-8 samples every 37 calls, 2 % missed
    cycles, path planning with limits on every third task, settling on every fourth, the period learned on every
    fifth): no call may end in SERVO_ARM_NOT_FOLLOWING. The number of calls is printed.
  - Detection: each fault (a velocity read in another frame, for the 3-joint arm its joints in reverse order; a robot
    not in velocity control; a joint held at a limit; from the start, a robot in a reduced-speed mode that clips the
    velocity) from call 5 of 5 tasks per arm: stopped within 10 calls of the first faulty command, every time (3 calls
    most of the time: a command read in another frame can happen to move the joints nearly as commanded for a few
    calls). The calls to detection are printed.
  VISP_PROJECTIVE_FOLLOW_TASKS sets the tasks per arm and noise level (default 8) for longer runs.
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveNotices.h>

#include "vpProjectiveSessionTestTools.h"
#include "vpServoArmFollowingTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! The fault's first call: the task halfway to its target, moving the images by a few pixels per call.
const unsigned int kFaultAt = 5;

long tasksPerLevel()
{
  const char *value = std::getenv("VISP_PROJECTIVE_FOLLOW_TASKS");
  const long v = value == nullptr ? 0 : std::strtol(value, nullptr, 10);
  return v > 0 ? v : 8;
}

std::vector<ArmSetup> arms()
{
  return {pumaEyeToHand(), viperEyeToHand(), rrprrrEyeToHand(), mixedEyeToHand()};
}

//! A start and a target in view: the target within +-12 deg (3 cm for a prismatic joint) of the zero reference, the
//! start within as much again of the target.
void drawTask(const ArmSetup &s, vpUniRand &rng, vpColVector &qStart, vpColVector &qTarget)
{
  std::vector<double> range(s.n());
  for (unsigned int i = 0; i < s.n(); ++i) {
    range[i] = s.arm.getJointType(i) == vpProjectiveJoint::REVOLUTE ? vpMath::rad(12.0) : 0.03;
  }
  const vpColVector &qmin = s.arm.getJointMin(), &qmax = s.arm.getJointMax();
  for (int attempt = 0; attempt < 10000; ++attempt) {
    qTarget = s.randomVisibleJoints(rng, range, 20.0);
    ASSERT_EQ(qTarget.size(), s.n()) << s.name;
    qStart = qTarget;
    bool inside = true;
    for (unsigned int i = 0; i < s.n(); ++i) {
      qStart[i] += rng.uniform(-range[i], range[i]);
      const double margin = 0.02 * (qmax[i] - qmin[i]); // inside the arm's limits
      inside = inside && s.armJoints(qStart)[i] > qmin[i] + margin && s.armJoints(qStart)[i] < qmax[i] - margin &&
               s.armJoints(qTarget)[i] > qmin[i] + margin && s.armJoints(qTarget)[i] < qmax[i] - margin;
    }
    if (inside && s.visible(s.armJoints(qStart), 20.0)) {
      return;
    }
  }
  FAIL() << s.name << ": no task in view";
}
} // namespace

TEST(ServoArmFollowingStudy, noFalseAlarmOnCorrectArms)
{
  const NoticesSetting quiet(false); // a status other than the check's is no concern here
  const long tasks = tasksPerLevel();
  unsigned long calls = 0, alarms = 0, converged = 0, runs = 0;
  std::ostringstream table;
  for (const ArmSetup &s : arms()) {
    for (double sigma : {0.1, 0.5, 1.0}) {
      const vpProjectiveRobot model = calibratedRobot(s, sigma, 7);
      vpUniRand rng(1000 + static_cast<long>(100 * sigma));
      unsigned long armCalls = 0, armAlarms = 0;
      for (long t = 0; t < tasks; ++t) {
        vpColVector qStart, qTarget;
        drawTask(s, rng, qStart, qTarget);
        LoopSettings settings;
        settings.sigma = sigma;
        settings.encoderNoise = 1e-5;
        settings.latency = t % 2 == 1;
        settings.pauseEvery = 37;
        settings.pauseSamples = 2 + static_cast<unsigned int>(t % 7);
        settings.skipProbability = 0.02;
        settings.planning = t % 3 == 2;
        settings.settling = t % 4 == 3;
        settings.givePeriod = t % 5 != 4;
        const LoopResult r = runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, 5000 + t, 400);
        ++runs;
        armCalls += r.calls;
        armAlarms += r.notFollowingAt >= 0 ? 1 : 0;
        converged += r.finalRms < 3.0 * sigma + 0.5 ? 1 : 0;
        EXPECT_EQ(r.notFollowingAt, -1) << s.name << ", " << sigma << " px, task " << t << ": " << r.diagnosis
                                        << (r.atArmLimit ? " (a joint at the arm's limit)" : "");
      }
      calls += armCalls;
      alarms += armAlarms;
      table << "[ stats    ] " << s.name << ", " << sigma << " px: " << tasks << " tasks, " << armCalls << " calls, "
            << armAlarms << " false alarms" << std::endl;
    }
  }
  testLog() << table.str() << "[ stats    ] total: " << runs << " tasks (" << converged << " converged), " << calls
            << " calls, " << alarms << " false alarms" << std::endl;
}

TEST(ServoArmFollowingStudy, everyFaultDetectedOnEveryArm)
{
  const NoticesSetting quiet(false); // the faults are provoked
  std::ostringstream table;
  for (const ArmSetup &s : arms()) {
    const vpProjectiveRobot model = calibratedRobot(s, 0.5, 8);
    vpUniRand rng(2000);
    for (ArmFault fault : {OTHER_FRAME, NOT_IN_VELOCITY, JOINT_AT_LIMIT, ROBOT_CLIPS}) {
      std::vector<int> after;
      std::map<vpServoArmFollowing::vpFollowingCause, int> causes;
      for (int t = 0; t < 5; ++t) {
        vpColVector qStart, qTarget;
        drawTask(s, rng, qStart, qTarget);
        LoopSettings settings;
        settings.encoderNoise = 1e-5;
        settings.latency = t % 2 == 1;
        // A robot in a reduced-speed mode is so from the start (the task's commands then above its maxima).
        const unsigned int at = fault == ROBOT_CLIPS ? 0 : kFaultAt;
        const LoopResult r = runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, 6000 + t, 100, fault, at);
        after.push_back(r.notFollowingAt - static_cast<int>(at));
        ++causes[r.cause];
        EXPECT_GE(r.notFollowingAt, static_cast<int>(at)) << s.name << ", " << faultName(fault) << ", task " << t;
        EXPECT_LE(r.notFollowingAt, static_cast<int>(at) + 10)
            << s.name << ", " << faultName(fault) << ", task " << t << ": " << r.diagnosis;
        EXPECT_TRUE(r.qdotZeroAfter) << s.name << ", " << faultName(fault);
        EXPECT_EQ(r.mismatchAt, -1) << s.name << ", " << faultName(fault) << ", task " << t;
      }
      table << "[ stats    ] " << s.name << ", " << faultName(fault) << ": calls to detection";
      for (int a : after) {
        table << " " << a;
      }
      table << "; causes";
      for (const auto &c : causes) {
        table << " " << c.first << " x" << c.second;
      }
      table << std::endl;
    }
  }
  testLog() << table.str();
}
