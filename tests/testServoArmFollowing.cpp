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
  The arm does what the task says (issue 30, point 3): vpServoArmFollowing on its own (joint motions against commands
  in the metric of a random task Jacobian), then inside vpServoProjective on the plugin's simulated robot
  (vpSimulatorRobotArm, vpServoArmFollowingTestTools.h): a correct arm with encoder noise, command latency, pauses
  and missed cycles never stops the task; a velocity read in another frame, a robot not in velocity control, a joint
  held at a limit and a robot that clips the velocity stop it (SERVO_ARM_NOT_FOLLOWING, qdot = 0) within 3 calls of
  the first motion that shows it, with the cause named; a bumped camera is a model mismatch, not an arm fault; the
  task's one line on stderr (issue 30, point 4) comes once per kind and a setter silences it.
*/

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpServoArmFollowing.h>

#include "vpRigUpdateTestTools.h"
#include "vpServoArmFollowingTestTools.h"
#include "vpServoProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{
typedef vpServoArmFollowing::JointVector JointVector;
typedef vpServoArmFollowing::JointMatrix JointMatrix;

//! J^T J of a random 12 x n task Jacobian whose columns move the images by 100-800 px per joint unit.
JointMatrix randomJtJ(vpUniRand &rng, unsigned int n)
{
  Eigen::MatrixXd J(12, n);
  for (Eigen::Index r = 0; r < J.rows(); ++r) {
    for (Eigen::Index c = 0; c < J.cols(); ++c) {
      J(r, c) = rng.uniform(-1.0, 1.0) * (100.0 + 100.0 * c);
    }
  }
  return J.transpose() * J;
}

//! A smooth command (joint units per second): a slowly turning direction of norm \e speed.
struct SmoothCommand {
  JointVector v;
  vpUniRand rng;
  double speed;
  SmoothCommand(unsigned int n, long seed, double s) : v(JointVector::Zero(n)), rng(seed), speed(s) { next(); }
  const JointVector &next()
  {
    for (Eigen::Index i = 0; i < v.size(); ++i) {
      v(i) += rng.uniform(-0.3, 0.3);
    }
    v *= speed / v.norm();
    return v;
  }
};

//! Calls of a check fed with joint motions \e motion(call, command, previous command) until it stops the task (the
//! call index) or \e calls were made (-1).
template <typename Motion>
int feed(vpServoArmFollowing &check, const JointMatrix &JtJ, SmoothCommand &command, unsigned int calls, Motion motion)
{
  const Eigen::Index n = command.v.size();
  JointVector q = JointVector::Zero(n), previous = JointVector::Zero(n);
  for (unsigned int call = 0; call < calls; ++call) {
    const bool stop = check.evaluate(q, JtJ, 12);
    const JointVector qdot = stop ? JointVector(JointVector::Zero(n)) : command.next();
    check.commit(q, qdot);
    if (stop) {
      return static_cast<int>(call);
    }
    q += motion(call, qdot, previous);
    previous = qdot;
  }
  return -1;
}
} // namespace

// A correct arm: exact motion, one call of latency, a random mix of both, encoder noise (1e-5 rad), pauses of 2 to 20
// periods while the robot holds the command, missed cycles (no motion for a call), with and without the period: never
// 3 disagreeing calls in a row, over 6 x 3000 calls per variant.
TEST(ArmFollowing, correctArmNeverStops)
{
  const double T = 0.04;
  for (bool givePeriod : {true, false}) {
    for (int variant = 0; variant < 6; ++variant) {
      vpUniRand rng(10 + variant);
      const JointMatrix JtJ = randomJtJ(rng, 6);
      vpServoArmFollowing check;
      if (givePeriod) {
        check.setControlPeriod(T);
      }
      SmoothCommand command(6, 20 + variant, 0.3);
      vpGaussRand encoder(1e-5, 0.0, 30 + variant);
      const int stopped =
          feed(check, JtJ, command, 3000, [&](unsigned int call, const JointVector &c, const JointVector &p) {
            JointVector d = T * c;
            if (variant == 1) {
              d = T * p;
            } else if (variant == 2) {
              const double a = rng.uniform(0.0, 1.0);
              d = T * (a * c + (1.0 - a) * p);
            } else if (variant == 3) {
              for (Eigen::Index i = 0; i < d.size(); ++i) {
                d(i) += encoder();
              }
            } else if (variant == 4 && call % 50 == 49) {
              d *= 2.0 + std::floor(rng.uniform(0.0, 19.0)); // a pause: the robot holds the command
            } else if (variant == 5 && rng.uniform(0.0, 1.0) < 0.05) {
              d.setZero(); // a missed cycle
            }
            return d;
          });
      EXPECT_EQ(stopped, -1) << "variant " << variant << (givePeriod ? " with" : " without")
                             << " the period: " << check.getDiagnosis();
      EXPECT_FALSE(check.isNotFollowing());
      if (!givePeriod) {
        EXPECT_NEAR(check.getReferenceDuration(), T, 0.01 * T) << "variant " << variant; // learned
      }
    }
  }
}

// Each fault from call 10 on, the period given: stopped at call 10 + 3 (the motion of call k shows at call k + 1,
// then 3 disagreeing calls; a few calls more for a fault of one joint, which shows only while that joint moves
// measurably), cause and joints named.
TEST(ArmFollowing, eachFaultStopsWithinThreeCallsAndIsNamed)
{
  const double T = 0.04;
  vpUniRand rng(3);
  const JointMatrix JtJ = randomJtJ(rng, 6);
  Eigen::Matrix<double, 6, 6> otherFrame;
  for (Eigen::Index r = 0; r < 6; ++r) {
    for (Eigen::Index c = 0; c < 6; ++c) {
      otherFrame(r, c) = rng.uniform(-1.0, 1.0);
    }
  }
  struct Case {
    const char *name;
    vpServoArmFollowing::vpFollowingCause cause;
    const char *words;
  };
  const Case cases[] = {{"not moving", vpServoArmFollowing::ARM_NOT_MOVING, "velocity control"},
                        {"clipped", vpServoArmFollowing::ARM_SLOWER, "clips the velocity"},
                        {"joint 2 held", vpServoArmFollowing::ARM_JOINTS_LAGGING, "joint 2 does not move"},
                        {"another frame", vpServoArmFollowing::ARM_OTHER_DIRECTION, "ARTICULAR_FRAME"},
                        {"joint 4 reversed", vpServoArmFollowing::ARM_OTHER_DIRECTION, "joint 4 moves the other way"}};
  for (int k = 0; k < 5; ++k) {
    vpServoArmFollowing check;
    check.setControlPeriod(T);
    SmoothCommand command(6, 40 + k, 0.3);
    const int stopped =
        feed(check, JtJ, command, 100, [&](unsigned int call, const JointVector &c, const JointVector &) {
          JointVector d = T * c;
          if (call >= 10) {
            if (k == 0) {
              d.setZero();
            } else if (k == 1) {
              d *= 0.3;
            } else if (k == 2) {
              d(2) = 0.0;
            } else if (k == 3) {
              d = otherFrame * d;
            } else {
              d(4) = -d(4);
            }
          }
          return d;
        });
    // A fault of one joint shows only at the calls where that joint is commanded measurably.
    EXPECT_GE(stopped, 13) << cases[k].name;
    EXPECT_LE(stopped, k < 2 ? 13 : 16) << cases[k].name;
    EXPECT_TRUE(check.isNotFollowing()) << cases[k].name;
    EXPECT_EQ(check.getCause(), cases[k].cause) << cases[k].name << ": " << check.getDiagnosis();
    EXPECT_NE(check.getDiagnosis().find(cases[k].words), std::string::npos) << check.getDiagnosis();
    if (k == 1) {
      EXPECT_NEAR(check.getMotionRatio(), 0.3, 1e-9);
    }
    if (k == 2) {
      for (unsigned int i = 0; i < 6; ++i) {
        EXPECT_EQ(check.getJointFollowing(i),
                  i == 2 ? vpServoArmFollowing::JOINT_STILL : vpServoArmFollowing::JOINT_FOLLOWS)
            << "joint " << i;
      }
    }
    testLog() << "[ measured ] " << cases[k].name << ": " << check.getDiagnosis() << std::endl;
  }
}

// Without the period (a ViSP program that never calls setControlPeriod()), the check learns it from the arm that
// follows (10 ms per call) and sees a robot that stops against it; an arm that moves a quarter as far is a loop that
// runs faster as well as a clipping robot: not judged without the period, a fault with it.
TEST(ArmFollowing, learnsThePeriodWhenNotGiven)
{
  const double T = 0.01;
  vpUniRand rng(5);
  const JointMatrix JtJ = randomJtJ(rng, 6);
  for (double factor : {0.0, 0.25}) {
    for (bool givePeriod : {false, true}) {
      vpServoArmFollowing check;
      if (givePeriod) {
        check.setControlPeriod(T);
      }
      SmoothCommand command(6, 50, 2.0);
      const int stopped =
          feed(check, JtJ, command, 200, [&](unsigned int call, const JointVector &c, const JointVector &) {
            return JointVector((call >= 30 ? factor : 1.0) * T * c);
          });
      const bool judged = factor == 0.0 || givePeriod;
      EXPECT_EQ(stopped, judged ? 33 : -1) << factor << (givePeriod ? " with" : " without") << " the period";
      // Unjudged, the slower motion is regular: it becomes the learned period.
      EXPECT_NEAR(check.getReferenceDuration(), judged ? T : factor * T, 1e-9);
      if (judged) {
        EXPECT_EQ(check.getCause(),
                  factor == 0.0 ? vpServoArmFollowing::ARM_NOT_MOVING : vpServoArmFollowing::ARM_SLOWER)
            << check.getDiagnosis();
        EXPECT_NE(check.getDiagnosis().find(givePeriod ? "setControlPeriod()" : "learned"), std::string::npos)
            << check.getDiagnosis();
      }
    }
  }
}

// Settings: bad values throw and change nothing; a stopped check stays stopped until reset(); off, it never stops.
TEST(ArmFollowing, settingsResetAndSwitch)
{
  vpServoArmFollowing check;
  EXPECT_THROW(check.setConsecutiveCalls(0), vpProjectiveException);
  EXPECT_EQ(check.getConsecutiveCalls(), 3u);
  for (double bad : {-0.01, std::nan(""), HUGE_VAL}) {
    EXPECT_THROW(check.setControlPeriod(bad), vpProjectiveException);
    EXPECT_EQ(check.getControlPeriod(), 0.0);
  }
  vpUniRand rng(7);
  const JointMatrix JtJ = randomJtJ(rng, 6);
  check.setControlPeriod(0.04);
  check.setConsecutiveCalls(1);
  SmoothCommand command(6, 60, 0.3);
  EXPECT_EQ(feed(check, JtJ, command, 20,
                 [](unsigned int, const JointVector &c, const JointVector &) {
                   return JointVector(JointVector::Zero(c.size()));
                 }),
            1); // the first call judges nothing, the second sees no motion
  EXPECT_TRUE(check.evaluate(JointVector::Zero(6), JtJ, 12)); // stays stopped
  check.reset();
  EXPECT_FALSE(check.isNotFollowing());
  EXPECT_FALSE(check.evaluate(JointVector::Zero(6), JtJ, 12)); // a first call again
  check.setEnabled(false);
  EXPECT_EQ(feed(check, JtJ, command, 20,
                 [](unsigned int, const JointVector &c, const JointVector &) {
                   return JointVector(JointVector::Zero(c.size()));
                 }),
            -1);
}

// On the simulated PUMA, 10 tasks at 0.5 px with every realistic effect at once (encoder noise, one call of latency,
// a pause every 40 calls, 3 % missed cycles), then planned with limits, then without the period: every task
// converges, none stops, no SERVO_ARM_NOT_FOLLOWING line on stderr.
TEST(ServoArmFollowing, correctArmConvergesWithoutAlarm)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
  const NoticesSetting on(true); // none may say SERVO_ARM_NOT_FOLLOWING
  vpUniRand rng(11);
  unsigned int calls = 0;
  for (int run = 0; run < 10; ++run) {
    vpColVector qStart, qTarget;
    randomPair(s, rng, vpMath::rad(15.0), vpMath::rad(15.0), qStart, qTarget);
    LoopSettings settings;
    settings.encoderNoise = 1e-5;
    settings.latency = run % 2 == 0;
    settings.pauseEvery = 40;
    settings.skipProbability = 0.03;
    settings.planning = run >= 6;
    settings.givePeriod = run < 8;
    vpProjectiveNotices::reset();
    CapturedStreams streams;
    const LoopResult r =
        runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, 100 + run, 300); // converging, then settled
    calls += r.calls;
    EXPECT_EQ(r.notFollowingAt, -1) << "run " << run << ": " << r.diagnosis;
    EXPECT_EQ(r.mismatchAt, -1) << "run " << run;
    EXPECT_LT(r.finalRms, 1.5) << "run " << run;
    EXPECT_EQ(streams.err.str().find("SERVO_ARM_NOT_FOLLOWING"), std::string::npos) << "run " << run;
  }
  testLog() << "[ measured ] " << calls << " calls without an alarm" << std::endl;
}

// Each fault from call 15 on, on the simulated PUMA with the effects of a correct arm: SERVO_ARM_NOT_FOLLOWING within
// 4 calls (the motion of call 15 shows at call 16, then 3 disagreeing calls), qdot = 0 from then on, the cause named,
// never a model mismatch (the images agree with the model at the joints the arm reached).
TEST(ServoArmFollowing, faultsStopTheTaskAndNameTheCause)
{
  const NoticesSetting quiet(false); // the faults are provoked
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
  struct Case {
    ArmFault fault;
    vpServoArmFollowing::vpFollowingCause cause;
  };
  const Case cases[] = {{OTHER_FRAME, vpServoArmFollowing::ARM_OTHER_DIRECTION},
                        {NOT_IN_VELOCITY, vpServoArmFollowing::ARM_NOT_MOVING},
                        {JOINT_AT_LIMIT, vpServoArmFollowing::ARM_JOINTS_LAGGING},
                        {ROBOT_CLIPS, vpServoArmFollowing::ARM_SLOWER}};
  vpUniRand rng(12);
  for (const Case &c : cases) {
    for (int run = 0; run < 3; ++run) {
      vpColVector qStart, qTarget;
      randomPair(s, rng, vpMath::rad(20.0), vpMath::rad(25.0), qStart, qTarget);
      LoopSettings settings;
      settings.encoderNoise = 1e-5;
      settings.latency = run == 1;
      const LoopResult r = runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, 200 + run, 200, c.fault, 15);
      EXPECT_GE(r.notFollowingAt, 16) << faultName(c.fault) << " run " << run;
      EXPECT_LE(r.notFollowingAt, 15 + 3 + (settings.latency ? 1 : 0)) << faultName(c.fault) << " run " << run;
      EXPECT_TRUE(r.qdotZeroAfter) << faultName(c.fault);
      EXPECT_EQ(r.cause, c.cause) << faultName(c.fault) << " run " << run << ": " << r.diagnosis;
      EXPECT_EQ(r.mismatchAt, -1) << faultName(c.fault) << " run " << run;
      testLog() << "[ measured ] " << faultName(c.fault) << ", run " << run << ": stopped " << r.notFollowingAt - 15
                << " calls after the first faulty command: " << r.diagnosis << std::endl;
    }
  }
}

// A robot that never moves, in a program that does not give the task its period: nothing to learn the period from,
// yet SERVO_ARM_NOT_FOLLOWING (ARM_NOT_MOVING) after the 40 still calls plus setConsecutiveCalls(), within 3 s of a
// 20 Hz loop, qdot = 0 from then on, the missing period named; a robot that moves, with the same settings, never
// stops (its period is learned from its first calls).
TEST(ServoArmFollowing, robotStillFromTheFirstCallWithoutPeriodStopsTheTask)
{
  const NoticesSetting quiet(false); // the fault is provoked
  vpUniRand rng(14);
  for (const ArmSetup &s : {pumaEyeToHand(), viperEyeToHand()}) {
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
    for (int run = 0; run < 2; ++run) {
      vpColVector qStart, qTarget;
      randomPair(s, rng, vpMath::rad(20.0), vpMath::rad(25.0), qStart, qTarget);
      LoopSettings settings;
      settings.givePeriod = false;
      settings.encoderNoise = run == 1 ? 1e-5 : 0.0;
      const LoopResult still =
          runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, 300 + run, 100, NOT_IN_VELOCITY, 0);
      EXPECT_GE(still.notFollowingAt, 40) << s.name << " run " << run;
      EXPECT_LE(still.notFollowingAt * settings.period, 3.0) << s.name << " run " << run;
      EXPECT_TRUE(still.qdotZeroAfter) << s.name << " run " << run;
      EXPECT_EQ(still.cause, vpServoArmFollowing::ARM_NOT_MOVING)
          << s.name << " run " << run << ": " << still.diagnosis;
      EXPECT_NE(still.diagnosis.find("setControlPeriod()"), std::string::npos) << still.diagnosis;
      const LoopResult moving = runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, 300 + run, 100);
      EXPECT_EQ(moving.notFollowingAt, -1) << s.name << " run " << run << ": " << moving.diagnosis;
      testLog() << "[ measured ] " << s.name << ", run " << run << ": a still robot without a period stopped at call "
                << still.notFollowingAt << ": " << still.diagnosis << std::endl;
    }
  }
}

// A bumped camera (1-3 deg, 0.5-2 cm) is a model mismatch, never an arm that does not follow: the arm follows.
TEST(ServoArmFollowing, bumpedCameraIsAMismatchNotAnArmFault)
{
  const NoticesSetting quiet(false); // the faults are provoked
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
  vpUniRand rng(13);
  for (BumpKind kind : {BUMP_LEFT, BUMP_RIGHT, BUMP_RIG}) {
    const ArmSetup b = bumped(s, kind, rng);
    vpColVector qStart, qTarget;
    randomPair(s, rng, vpMath::rad(15.0), vpMath::rad(15.0), qStart, qTarget);
    LoopSettings settings;
    settings.encoderNoise = 1e-5;
    const LoopResult r =
        runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, 300 + kind, 100, CAMERA_BUMPED, 15, &b);
    EXPECT_GE(r.mismatchAt, 16) << bumpName(kind);
    EXPECT_LE(r.mismatchAt, 17) << bumpName(kind);
    EXPECT_EQ(r.notFollowingAt, -1) << bumpName(kind) << ": " << r.diagnosis;
  }
}

// After the fix (the robot back in velocity control), getArmFollowing().reset() lets the task finish.
TEST(ServoArmFollowing, resetAfterTheFixResumes)
{
  const NoticesSetting quiet(false); // the faults are provoked
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot model = calibratedRobot(s);
  vpColVector qStart, qTarget;
  randomPair(s, 14, vpMath::rad(15.0), vpMath::rad(15.0), qStart, qTarget);
  Task t(s, model, {0, 1, 2}, qStart, qTarget);
  t.task.setLambda(2.0);
  t.task.setControlPeriod(0.05);
  t.task.getControlLaw().setMaxJointVelocity(0.5); // within the robot's 0.7 rad/s
  vpSimulatorRobotArm robot(s.arm, s.armJoints(qStart));
  robot.setSamplingTime(0.05);
  robot.setEncoderOffset(-1.0 * s.qRef);
  int stoppedAt = -1; // the robot is left in STATE_STOP: never put in velocity control
  for (int call = 0; call < 300; ++call) {
    vpColVector q;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    setFeatures(s, q, {0, 1, 2}, t.s);
    const vpColVector qdot = t.task.computeControlLaw(q);
    if (t.task.getStatus() == vpServoProjective::SERVO_ARM_NOT_FOLLOWING && stoppedAt < 0) {
      stoppedAt = call;
      robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL); // the fix the message names
      t.task.getArmFollowing().reset();
    }
    if (robot.getRobotState() == vpRobot::STATE_VELOCITY_CONTROL) {
      robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
    }
  }
  EXPECT_EQ(stoppedAt, 3); // calls 1 to 3 see no motion
  EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_RUNNING);
  EXPECT_LT(activeRms(t.task), 1e-3);
}

// The task's line on stderr: once per status kind and process, named with its fix; reset() tells it again;
// vpProjectiveNotices::setEnabled(false) silences it.
TEST(ServoArmFollowing, oneNoticePerKindAndSilenced)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot model = calibratedRobot(s);
  vpColVector qStart, qTarget;
  randomPair(s, 15, vpMath::rad(15.0), vpMath::rad(15.0), qStart, qTarget);
  const std::string prefix = "Warning: vpServoProjective: SERVO_ARM_NOT_FOLLOWING";
  const NoticesSetting restored(true);
  vpProjectiveNotices::reset();
  for (int round = 0; round < 4; ++round) {
    if (round == 2) {
      vpProjectiveNotices::reset();
    }
    vpProjectiveNotices::setEnabled(round != 3);
    CapturedStreams streams;
    const LoopResult r =
        runLoop(s, model, {0, 1, 2}, qStart, qTarget, LoopSettings(), 400, 100, NOT_IN_VELOCITY, 10, nullptr, 10);
    ASSERT_GE(r.notFollowingAt, 0);
    const std::string err = streams.err.str();
    size_t lines = 0, at = err.find(prefix);
    for (size_t from = 0; (from = err.find(prefix, from)) != std::string::npos; from += prefix.size()) {
      ++lines;
    }
    EXPECT_EQ(lines, round == 0 || round == 2 ? 1u : 0u) << "round " << round << ": " << err;
    if (lines == 1) {
      EXPECT_TRUE(at == 0 || err[at - 1] == '\n') << err; // a line of its own
      EXPECT_NE(err.find("setRobotState(vpRobot::STATE_VELOCITY_CONTROL)"), std::string::npos) << err;
      EXPECT_NE(err.find("vpProjectiveNotices::setEnabled(false)"), std::string::npos) << err;
    }
  }
  // Another kind is told on its own: a feature set aside (SERVO_REDUCED), once however many calls.
  vpProjectiveNotices::setEnabled(true);
  vpProjectiveNotices::reset();
  CapturedStreams streams;
  Task t(s, model, {0, 1, 2, 3}, qTarget, qTarget);
  t.task.setFeatureTracked(3, false);
  for (int call = 0; call < 5; ++call) {
    t.task.computeControlLaw(qTarget);
  }
  EXPECT_EQ(t.task.getStatus(), vpServoProjective::SERVO_REDUCED);
  const std::string err = streams.err.str();
  EXPECT_EQ(err.find("Warning: vpServoProjective: SERVO_REDUCED"), 0u) << err;
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}
