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
  Helpers for the suites of the arm-following check (vpServoArmFollowing, SERVO_ARM_NOT_FOLLOWING; header only, not a
  test itself): a servo loop as a user writes it around a vpRobot (read the encoders, update the features from the
  images, computeControlLaw(q), setVelocity(ARTICULAR_FRAME, qdot)), here the plugin's vpSimulatorRobotArm in its
  constant sampling time mode moving an ArmSetup's arm, with the realistic effects a correct arm shows (encoder noise,
  one call of command latency, pauses between calls, skipped controller cycles) and the faults a user makes (a
  velocity read in another frame, a robot not in velocity control, a joint held at a limit, a robot that clips the
  velocity, a bumped camera). Used by testServoArmFollowing (suite), testServoArmFollowingStudy and testUserMistakes
  (studies).
*/

#ifndef _vpServoArmFollowingTestTools_h_
#define _vpServoArmFollowingTestTools_h_

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/robot/vpRobotException.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorRobotArm.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
//! What goes wrong from the fault's call on (NO_FAULT: a correct arm).
//! ROBOT_CLIPS: the robot's maxima 0.05 rad/s and 0.05 m/s (a reduced-speed mode), 10 times below the task's
//! saturation.
enum ArmFault { NO_FAULT, OTHER_FRAME, NOT_IN_VELOCITY, JOINT_AT_LIMIT, ROBOT_CLIPS, CAMERA_BUMPED };

inline const char *faultName(ArmFault f)
{
  static const char *const names[] = {"none",
                                      "velocity in another frame",
                                      "robot not in velocity control",
                                      "joint held at a limit",
                                      "robot clips the velocity",
                                      "camera bumped"};
  return names[f];
}

//! The realistic effects of a correct arm and loop, and the task's settings.
struct LoopSettings {
  double period = 0.05;          //!< s: the robot's sampling time, one call per sample
  bool givePeriod = true;        //!< setControlPeriod(period); false: the task learns it
  double lambda = 2.0;           //!< per second
  double qdotMax = 0.5;          //!< the task's saturation (rad/s or m/s; the robot's: 0.7 rad/s, 0.2 m/s)
  double sigma = 0.5;            //!< pixel noise of the features
  double encoderNoise = 0.0;     //!< standard deviation of each reading (rad or m)
  bool latency = false;          //!< each command reaches the robot one call late
  unsigned int pauseEvery = 0;   //!< every so many calls, a pause between two calls (0: none)
  unsigned int pauseSamples = 5; //!< the pause's length in samples, the robot holding the last command
  double skipProbability = 0.0;  //!< a controller cycle missed: no step before the next call
  bool planning = false;         //!< setPathPlanning(true) with the arm's limits and the image window
  bool settling = false;         //!< setSettling(true)
  // The user's program, from the first call (testUserMistakes): \e read changes the encoder readings before the task
  // sees them (joints listed in another order, a sign flipped), \e send the task's qdot before the robot gets it (a
  // twist of another frame); \e swapImages gives the task each left image as the right one and conversely.
  std::function<void(vpColVector &q)> read;
  std::function<void(vpSimulatorRobotArm &robot, vpColVector &command)> send;
  bool swapImages = false;
};

//! What a run saw.
struct LoopResult {
  unsigned int calls = 0;    //!< computeControlLaw() calls made
  int notFollowingAt = -1;   //!< the first call that returned SERVO_ARM_NOT_FOLLOWING
  int mismatchAt = -1;       //!< the first call that returned SERVO_MODEL_MISMATCH
  bool qdotZeroAfter = true; //!< every qdot from the first stop (notFollowingAt or mismatchAt) on was exactly 0
  double finalRms = -1.0;    //!< image error at the end (px), noise-free
  vpServoArmFollowing::vpFollowingCause cause = vpServoArmFollowing::ARM_FOLLOWING;
  std::string diagnosis;
  vpServoArmFollowing report; //!< the check at the end of the run
  bool atArmLimit = false;    //!< a joint of the simulated arm reached one of its own limits during the run
};

//! Noise-free RMS image error (px) of the tracked markers at arm joints qArm against the target's.
inline double imageRms(const ArmSetup &s, const std::vector<unsigned int> &tracked, const vpColVector &qArm,
                       const vpColVector &qArmTarget)
{
  double sum = 0.0;
  for (unsigned int j : tracked) {
    sum += (s.imageOf(qArm, j) - s.imageOf(qArmTarget, j)).squaredNorm();
  }
  return std::sqrt(sum / (4.0 * tracked.size()));
}

/*!
  A servo loop of at most \e maxCalls calls from model joints \e qStart to \e qTarget on the markers \e tracked of
  setup \e s (the model \e model acquired on it), the fault \e fault from call \e faultAt on (\e bumped: the setup
  the cameras see after a bump). Stops at the first SERVO_ARM_NOT_FOLLOWING or SERVO_MODEL_MISMATCH plus
  \e afterStop calls (to check that qdot stays 0), or when the error is below \e goal px for 5 calls.
*/
inline LoopResult runLoop(const ArmSetup &s, const vpProjectiveRobot &model, const std::vector<unsigned int> &tracked,
                          const vpColVector &qStart, const vpColVector &qTarget, const LoopSettings &settings,
                          long seed, unsigned int maxCalls, ArmFault fault = NO_FAULT, unsigned int faultAt = 0,
                          const ArmSetup *bumped = nullptr, unsigned int afterStop = 3, double goal = 0.0)
{
  LoopResult r;
  vpGaussRand pixels(settings.sigma, 0.0, seed), encoders(1.0, 0.0, seed + 1);
  vpUniRand rng(seed + 2);
  vpSimulatorRobotArm robot(s.arm, s.armJoints(qStart));
  robot.setSamplingTime(settings.period);
  robot.setEncoderOffset(-1.0 * s.qRef); // readings in the model's joints
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);

  const size_t N = tracked.size();
  std::vector<vpFeatureStereoPoint> feat(N), featStar(N);
  for (size_t k = 0; k < N; ++k) {
    const Eigen::Vector4d t = s.imageOf(s.armJoints(qTarget), tracked[k]);
    if (settings.swapImages) {
      featStar[k].buildFrom(t(2), t(3), t(0), t(1));
    } else {
      featStar[k].buildFrom(t(0), t(1), t(2), t(3));
    }
  }
  vpServoProjective task;
  task.setRobot(model);
  task.setLambda(settings.lambda);
  task.getControlLaw().setMaxJointVelocity(settings.qdotMax);
  if (settings.givePeriod) {
    task.setControlPeriod(settings.period);
  }
  // The arm's limits, so that the task keeps its joints off them (an arm held at its own limit does not follow).
  task.setJointLimits(s.arm.getJointMin() - s.qRef, s.arm.getJointMax() - s.qRef);
  if (settings.planning) {
    task.setImageSize(s.width, s.height, 10.0);
    task.setPathPlanning(true);
  }
  task.setSettling(settings.settling);
  for (size_t k = 0; k < N; ++k) {
    task.addFeature(feat[k], featStar[k]);
  }

  vpColVector previous(s.n(), 0.0), command(s.n(), 0.0);
  unsigned int quiet = 0;
  int stoppedAt = -1;
  for (unsigned int call = 0; call < maxCalls; ++call) {
    const bool faulty = fault != NO_FAULT && call >= faultAt;
    if (fault == NOT_IN_VELOCITY && call == faultAt) {
      robot.setRobotState(vpRobot::STATE_STOP); // an emergency stop, a driver that dropped out of velocity mode
    }
    if (fault == JOINT_AT_LIMIT && call == faultAt) {
      // The joint that moves most is held where it is now: the robot's limit, which the task was not told.
      const vpColVector qArm = robot.getArmJoints();
      unsigned int j = 0;
      for (unsigned int i = 1; i < s.n(); ++i) {
        j = std::abs(command[i]) > std::abs(command[j]) ? i : j;
      }
      vpColVector qmin = s.arm.getJointMin(), qmax = s.arm.getJointMax();
      (command[j] > 0.0 ? qmax : qmin)[j] = qArm[j];
      robot.setJointLimits(qmin, qmax);
    }
    if (fault == ROBOT_CLIPS && call == faultAt) {
      // A robot in a reduced-speed mode: 0.05 rad/s and 0.05 m/s at most, against the task's saturation of 0.5.
      robot.setMaxRotationVelocity(0.05);
      robot.setMaxTranslationVelocity(0.05);
    }
    const ArmSetup &seen = fault == CAMERA_BUMPED && faulty && bumped != nullptr ? *bumped : s;
    vpColVector q;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    for (unsigned int i = 0; i < q.size(); ++i) {
      q[i] += settings.encoderNoise * encoders();
    }
    if (settings.read) {
      settings.read(q);
    }
    const vpColVector qArm = robot.getArmJoints();
    for (unsigned int i = 0; i < s.n(); ++i) {
      r.atArmLimit = r.atArmLimit || qArm[i] <= s.arm.getJointMin()[i] || qArm[i] >= s.arm.getJointMax()[i];
    }
    for (size_t k = 0; k < N; ++k) {
      const Eigen::Vector4d m = seen.imageOf(qArm, tracked[k]);
      const Eigen::Index left = settings.swapImages ? 2 : 0, right = 2 - left;
      feat[k].buildFrom(m(left) + pixels(), m(left + 1) + pixels(), m(right) + pixels(), m(right + 1) + pixels());
    }
    const vpColVector qdot = task.computeControlLaw(q);
    ++r.calls;
    const vpServoProjective::vpServoStatus status = task.getStatus();
    if (status == vpServoProjective::SERVO_ARM_NOT_FOLLOWING && r.notFollowingAt < 0) {
      r.notFollowingAt = static_cast<int>(call);
      r.cause = task.getReport().getArmFollowing().getCause();
      r.diagnosis = task.getReport().getArmFollowing().getDiagnosis();
    }
    if (status == vpServoProjective::SERVO_MODEL_MISMATCH && r.mismatchAt < 0) {
      r.mismatchAt = static_cast<int>(call);
    }
    if (r.notFollowingAt >= 0 || r.mismatchAt >= 0) {
      r.qdotZeroAfter = r.qdotZeroAfter && qdot.frobeniusNorm() == 0.0;
    }
    if (stoppedAt < 0 && (r.notFollowingAt >= 0 || r.mismatchAt >= 0)) {
      stoppedAt = static_cast<int>(call);
    }
    if (stoppedAt >= 0 && call >= static_cast<unsigned int>(stoppedAt) + afterStop) {
      break;
    }
    r.finalRms = imageRms(s, tracked, qArm, s.armJoints(qTarget));
    quiet = r.finalRms < goal ? quiet + 1 : 0;
    if (quiet >= 5) {
      break;
    }

    // The command the robot gets: the task's qdot, one call late with latency, read in another frame by a faulty
    // program (an end-effector twist: the joints move by eJe^+ qdot; the joints reversed on a 3-joint arm).
    command = settings.latency ? previous : qdot;
    previous = qdot;
    if (fault == OTHER_FRAME && faulty && s.n() == 6) {
      vpMatrix eJe;
      robot.get_eJe(eJe);
      command = eJe.pseudoInverse() * command;
    } else if (fault == OTHER_FRAME && faulty) {
      const vpColVector c = command; // a twist means nothing to a 3-joint arm: its joints listed in reverse order
      for (unsigned int i = 0; i < s.n(); ++i) {
        command[i] = c[s.n() - 1 - i];
      }
    }
    if (settings.send) {
      settings.send(robot, command);
    }
    const bool skip = settings.skipProbability > 0.0 && rng.uniform(0.0, 1.0) < settings.skipProbability;
    try {
      if (!skip) {
        robot.setVelocity(vpRobot::ARTICULAR_FRAME, command); // one sample at the command
      } // else the controller missed this cycle: the arm makes no step before the next call
      if (settings.pauseEvery > 0 && call % settings.pauseEvery == settings.pauseEvery - 1) {
        vpColVector held;
        robot.getVelocity(vpRobot::ARTICULAR_FRAME, held);
        for (unsigned int p = 0; p < settings.pauseSamples; ++p) {
          robot.setVelocity(vpRobot::ARTICULAR_FRAME, held); // the program is busy: the robot holds the command
        }
      }
    } catch (const vpRobotException &) {
      // The program catches the robot's refusal and goes on, as a careless loop does.
    }
  }
  r.report = task.getReport().getArmFollowing();
  return r;
}

//! The task's notices on or off while alive (vpProjectiveTestLogging.cpp turns them off in every suite).
struct NoticesSetting {
  bool saved;
  explicit NoticesSetting(bool on) : saved(vpProjectiveNotices::isEnabled()) { vpProjectiveNotices::setEnabled(on); }
  ~NoticesSetting() { vpProjectiveNotices::setEnabled(saved); }
};

//! Swallows std::cerr (and std::cout) while alive, keeping what was written.
struct CapturedStreams {
  std::ostringstream err, out;
  std::streambuf *savedErr, *savedOut;
  CapturedStreams() : err(), out(), savedErr(std::cerr.rdbuf(err.rdbuf())), savedOut(std::cout.rdbuf(out.rdbuf())) {}
  ~CapturedStreams()
  {
    std::cerr.rdbuf(savedErr);
    std::cout.rdbuf(savedOut);
  }
};
} // namespace vpProjectiveTest

#endif
