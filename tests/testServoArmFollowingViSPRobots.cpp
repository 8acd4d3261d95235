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
  The arm-following check (vpServoArmFollowing, SERVO_ARM_NOT_FOLLOWING) on the robots ViSP 3.5 ships,
  vpSimulatorViper850 (6 revolute joints) and vpSimulatorAfma6 (3 prismatic, 3 revolute), in their constant sampling
  time mode (one 10 ms step per setVelocity(), made by the simulator's own thread: the loop waits for it, as a program
  waits for its next frame) and, once, in real time without setControlPeriod() (the period learned from the arm): a
  correct loop never stops the task; a velocity sent with setVelocity(vpRobot::CAMERA_FRAME, qdot), a robot put in
  STATE_STOP, a joint that reaches the simulator's limit (which then holds every joint) and a robot whose maximum
  velocity is below the task's stop it within a few calls, with the cause named. The cell: a fixed rig of two 800 px
  cameras 1 m from 7 markers on the flange; the model calibrated from the simulators' own kinematics (get_fMe()), as
  an acquisition would give it. VISP_PROJECTIVE_FOLLOW_CALLS sets the calls of the correct runs (default 200).
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <fcntl.h>
#include <unistd.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpTime.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/robot/vpSimulatorAfma6.h>
#include <visp3/robot/vpSimulatorViper850.h>

#include "vpProjectiveTestTools.h"
#include "vpServoArmFollowingTestTools.h"

using namespace vpProjectiveTest;

namespace
{
/*!
  ViSP's simulators print what they refuse or clip: std::cout and std::cerr (captured) and, through vpERROR_TRACE,
  C's stderr, sent to /dev/null while alive (GoogleTest reports on stdout).
*/
struct QuietSimulator {
  CapturedStreams streams;
  int savedStderr;
  QuietSimulator() : streams(), savedStderr(dup(2))
  {
    std::fflush(stderr);
    const int null = open("/dev/null", O_WRONLY);
    if (null >= 0) {
      dup2(null, 2);
      close(null);
    }
  }
  ~QuietSimulator()
  {
    std::fflush(stderr);
    if (savedStderr >= 0) {
      dup2(savedStderr, 2);
      close(savedStderr);
    }
  }
};

//! The calls of a correct run: VISP_PROJECTIVE_FOLLOW_CALLS, or \e fallback.
unsigned int correctCalls(unsigned int fallback)
{
  const char *value = std::getenv("VISP_PROJECTIVE_FOLLOW_CALLS");
  const long v = value == nullptr ? 0 : std::strtol(value, nullptr, 10);
  return v > 0 ? static_cast<unsigned int>(v) : fallback;
}

//! The cell around a ViSP simulated arm \e Robot with kinematics \e Kinematics (vpViper or vpAfma6).
template <class Robot, class Kinematics> struct Cell {
  vpColVector qRef;                  // the robot's joints when the cell was set up
  std::vector<vpColVector> eMarkers; // on the flange
  vpSimulatorStereoRig rig;

  explicit Cell(Robot &robot)
      : qRef(joints(robot)), eMarkers(vpSimulatorStereoRig::transform(vpHomogeneousMatrix(0.0, 0.0, 0.1, 0.3, 0.2, 0.1),
                                                                      vpSimulatorArm::gripperMarkers())),
        rig(vpSimulatorStereoRig::vergingRig(markers(robot, qRef)[0], 1.0, 0.3,
                                             vpCameraParameters(800.0, 800.0, 320.0, 240.0)))
  {
  }
  static vpColVector joints(Robot &robot)
  {
    vpColVector q;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    return q;
  }
  static bool prismatic(unsigned int i) { return std::is_same<Kinematics, vpAfma6>::value && i < 3; }
  std::vector<vpColVector> markers(const Robot &robot, const vpColVector &q) const
  {
    vpHomogeneousMatrix fMe;
    static_cast<const Kinematics &>(robot).get_fMe(q, fMe);
    return vpSimulatorStereoRig::transform(fMe, eMarkers);
  }
  bool images(const Robot &robot, const vpColVector &q, std::vector<vpImagePoint> &l, std::vector<vpImagePoint> &r,
              double sigma, vpGaussRand &noise) const
  {
    const std::vector<vpColVector> X = markers(robot, q);
    rig.project(X, l, r, sigma, noise);
    for (const vpColVector &x : X) {
      if (!rig.isVisible(x, 20.0)) {
        return false;
      }
    }
    return true;
  }
  //! The projective model from noise-free images of the kinematics: each joint alone by +-10 deg or +-3 cm.
  vpProjectiveRobot model(const Robot &robot) const
  {
    std::vector<vpProjectiveRobot::vpJointType> types(6, vpProjectiveRobot::REVOLUTE);
    for (unsigned int i = 0; i < 3; ++i) {
      types[i] = prismatic(i) ? vpProjectiveRobot::PRISMATIC : vpProjectiveRobot::REVOLUTE;
    }
    vpProjectiveRobot m(types);
    vpProjectiveStereoRig r;
    r.setFundamentalMatrix(rig.getFundamentalMatrix());
    m.setStereoRig(r);
    vpGaussRand none(0.0, 0.0, 1);
    std::vector<vpImagePoint> left, right;
    EXPECT_TRUE(images(robot, qRef, left, right, 0.0, none));
    m.setZeroReference(left, right);
    for (unsigned int i = 0; i < 6; ++i) {
      for (double sign : {-1.0, 1.0}) {
        vpColVector q = qRef;
        const double amount = sign * (prismatic(i) ? 0.03 : vpMath::rad(10.0));
        q[i] += amount;
        EXPECT_TRUE(images(robot, q, left, right, 0.0, none)) << "joint " << i;
        m.addTrialMotion(i, amount, left, right);
      }
    }
    m.calibrate();
    return m;
  }
};

/*!
  A servo loop on a ViSP simulated robot from its initial joints to qRef + \e offset, tracked markers 0-3, as a user
  writes it: read the encoders, build the features, computeControlLaw(), setVelocity(ARTICULAR_FRAME) (CAMERA_FRAME
  with OTHER_FRAME), then wait for the robot (constant sampling time: for its step; real time: 10 ms).
*/
template <class Robot, class Kinematics>
LoopResult runViSP(Robot &robot, const Cell<Robot, Kinematics> &cell, const vpProjectiveRobot &model,
                   const vpColVector &offset, bool constantSampling, unsigned int maxCalls, ArmFault fault,
                   unsigned int faultAt, long seed)
{
  LoopResult r;
  vpGaussRand pixels(0.3, 0.0, seed), encoders(1e-5, 0.0, seed + 1);
  const unsigned int N = 4;
  std::vector<vpFeatureStereoPoint> s(N), sStar(N);
  std::vector<vpImagePoint> left, right;
  EXPECT_TRUE(cell.images(robot, cell.qRef + offset, left, right, 0.0, pixels));
  for (unsigned int k = 0; k < N; ++k) {
    sStar[k].buildFrom(left[k], right[k]);
  }
  vpServoProjective task;
  task.setRobot(model);
  task.setLambda(3.0);
  task.getControlLaw().setMaxJointVelocity(0.5); // the simulators' 0.7 rad/s (and m/s, joint space) above it
  if (constantSampling) {
    task.setControlPeriod(robot.getSamplingTime());
  }
  for (unsigned int k = 0; k < N; ++k) {
    task.addFeature(s[k], sStar[k]);
  }
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  vpColVector command(6, 0.0);
  for (unsigned int call = 0; call < maxCalls; ++call) {
    const double t0 = vpTime::measureTimeMs();
    if (fault == NOT_IN_VELOCITY && call == faultAt) {
      robot.setRobotState(vpRobot::STATE_STOP);
    }
    if (fault == ROBOT_CLIPS && call == faultAt) {
      // The simulators' joint-space maximum (every joint, prismatic ones too) at 30 % of the last command.
      robot.setMaxRotationVelocity(0.3 * std::max(command.getMaxValue(), -command.getMinValue()));
    }
    vpColVector q;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    if (fault == JOINT_AT_LIMIT && call == faultAt) {
      unsigned int j = 0;
      for (unsigned int i = 1; i < 6; ++i) {
        j = std::abs(command[i]) > std::abs(command[j]) ? i : j;
      }
      vpColVector qmin = robot.getJointMin(), qmax = robot.getJointMax();
      (command[j] > 0.0 ? qmax : qmin)[j] = q[j] + (command[j] > 0.0 ? 1e-4 : -1e-4);
      robot.setJointLimit(qmin, qmax);
    }
    cell.images(robot, q, left, right, 0.0, pixels);
    for (unsigned int k = 0; k < N; ++k) {
      s[k].buildFrom(left[k].get_u() + pixels(), left[k].get_v() + pixels(), right[k].get_u() + pixels(),
                     right[k].get_v() + pixels());
    }
    vpColVector qModel = q - cell.qRef; // the model's joints: zero at its zero reference
    for (unsigned int i = 0; i < 6; ++i) {
      qModel[i] += encoders();
    }
    command = task.computeControlLaw(qModel);
    ++r.calls;
    if (task.getStatus() == vpServoProjective::SERVO_ARM_NOT_FOLLOWING && r.notFollowingAt < 0) {
      r.notFollowingAt = static_cast<int>(call);
      r.cause = task.getReport().getArmFollowing().getCause();
      r.diagnosis = task.getReport().getArmFollowing().getDiagnosis();
    }
    if (task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH && r.mismatchAt < 0) {
      r.mismatchAt = static_cast<int>(call);
    }
    if (r.notFollowingAt >= 0) {
      r.qdotZeroAfter = r.qdotZeroAfter && command.frobeniusNorm() == 0.0;
      if (call >= static_cast<unsigned int>(r.notFollowingAt) + 3) {
        break;
      }
    }
    const vpColVector before = q;
    try {
      robot.setVelocity(fault == OTHER_FRAME && call >= faultAt ? vpRobot::CAMERA_FRAME : vpRobot::ARTICULAR_FRAME,
                        command);
    } catch (const vpRobotException &) {
      // A careless loop goes on.
    }
    if (constantSampling) {
      // The simulator's thread makes one step per command, at most every sampling period; on a loaded machine it may
      // not run for tens of milliseconds (a 15 ms limit read a starved thread as an arm that does not move: one fault
      // of the Afma6 misnamed at load 6), so the loop waits up to 200 ms, longer than any scheduling delay, for the
      // step of an arm that moves.
      do {
        vpTime::wait(1);
        robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
      } while (q == before && vpTime::measureTimeMs() - t0 < 200.0);
    } else {
      vpTime::wait(t0, 10.0);
    }
  }
  robot.setRobotState(vpRobot::STATE_STOP);
  vpColVector q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  std::vector<vpImagePoint> l2, r2;
  cell.images(robot, q, l2, r2, 0.0, pixels);
  double sum = 0.0;
  for (unsigned int k = 0; k < N; ++k) {
    sum += vpImagePoint::sqrDistance(l2[k], sStar[k].getLeft()) + vpImagePoint::sqrDistance(r2[k], sStar[k].getRight());
  }
  r.finalRms = std::sqrt(sum / (2.0 * N));
  return r;
}

//! A target offset in view: revolute joints within +-8 deg, prismatic ones within +-3 cm.
template <class Robot, class Kinematics>
vpColVector targetOffset(const Robot &robot, const Cell<Robot, Kinematics> &cell, vpUniRand &rng)
{
  vpGaussRand none(0.0, 0.0, 1);
  std::vector<vpImagePoint> l, r;
  for (int attempt = 0; attempt < 1000; ++attempt) {
    vpColVector d(6);
    for (unsigned int i = 0; i < 6; ++i) {
      d[i] = Cell<Robot, Kinematics>::prismatic(i) ? rng.uniform(-0.03, 0.03) : vpMath::rad(rng.uniform(-8.0, 8.0));
    }
    if (cell.images(robot, cell.qRef + d, l, r, 0.0, none)) {
      return d;
    }
  }
  ADD_FAILURE() << "no target in view";
  return vpColVector(6, 0.0);
}

template <class Robot, class Kinematics> void correctAndFaultyRuns(const char *name)
{
  const NoticesSetting quietNotices(false); // the faults below are provoked
  std::ostringstream log;                   // testLog() after the simulators' prints are let through again
  std::unique_ptr<QuietSimulator> quiet(new QuietSimulator);
  vpUniRand rng(std::is_same<Kinematics, vpAfma6>::value ? 21 : 22);
  // A correct loop, constant sampling time with the period, then real time without it.
  for (bool constantSampling : {true, false}) {
    Robot robot(false);
    robot.setConstantSamplingTimeMode(constantSampling);
    const Cell<Robot, Kinematics> cell(robot);
    const vpProjectiveRobot model = cell.model(robot);
    const vpColVector offset = targetOffset(robot, cell, rng);
    const LoopResult r = runViSP(robot, cell, model, offset, constantSampling, correctCalls(200), NO_FAULT, 0, 30);
    EXPECT_EQ(r.notFollowingAt, -1) << name << (constantSampling ? ", constant" : ", real time") << ": " << r.diagnosis;
    EXPECT_EQ(r.mismatchAt, -1) << name;
    EXPECT_LT(r.finalRms, 2.0) << name << (constantSampling ? ", constant" : ", real time");
    log << "[ measured ] " << name << (constantSampling ? ", constant sampling: " : ", real time: ") << r.calls
        << " calls without an alarm, final error " << r.finalRms << " px" << std::endl;
  }
  struct Case {
    ArmFault fault;
    vpServoArmFollowing::vpFollowingCause cause;
  };
  // ViSP's simulators hold every joint once one reaches its limit: the arm does not move at all.
  const Case cases[] = {{OTHER_FRAME, vpServoArmFollowing::ARM_OTHER_DIRECTION},
                        {NOT_IN_VELOCITY, vpServoArmFollowing::ARM_NOT_MOVING},
                        {JOINT_AT_LIMIT, vpServoArmFollowing::ARM_NOT_MOVING},
                        {ROBOT_CLIPS, vpServoArmFollowing::ARM_SLOWER}};
  for (const Case &c : cases) {
    Robot robot(false);
    robot.setConstantSamplingTimeMode(true);
    const Cell<Robot, Kinematics> cell(robot);
    const vpProjectiveRobot model = cell.model(robot);
    const vpColVector offset = targetOffset(robot, cell, rng);
    const LoopResult r = runViSP(robot, cell, model, offset, true, 60, c.fault, 10, 40);
    EXPECT_GE(r.notFollowingAt, 11) << name << ", " << faultName(c.fault);
    EXPECT_LE(r.notFollowingAt, 14) << name << ", " << faultName(c.fault) << ": " << r.diagnosis;
    EXPECT_TRUE(r.qdotZeroAfter) << name << ", " << faultName(c.fault);
    EXPECT_EQ(r.cause, c.cause) << name << ", " << faultName(c.fault) << ": " << r.diagnosis;
    EXPECT_EQ(r.mismatchAt, -1) << name << ", " << faultName(c.fault);
    log << "[ measured ] " << name << ", " << faultName(c.fault) << ": stopped " << r.notFollowingAt - 10
        << " calls after the first faulty command: " << r.diagnosis << std::endl;
  }
  quiet.reset();
  testLog() << log.str();
}
} // namespace

TEST(ServoArmFollowingViSPRobots, Viper850)
{
  correctAndFaultyRuns<vpSimulatorViper850, vpViper>("Viper850");
}

TEST(ServoArmFollowingViSPRobots, Afma6)
{
  correctAndFaultyRuns<vpSimulatorAfma6, vpAfma6>("Afma6");
}
