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
  The mistakes study (issue 30, point 7; docs/mistakes.dox, page_mistakes): user mistakes made as a user program makes
  them, through the public API, on three arms (the PUMA-like arm, ViSP's Viper850 geometry, the R-R-P-R-R-R arm). Each
  ends either corrected (the plugin converges or returns a right model) or refused/stopped with a message that names
  its cause: an exception's code and message at acquisition time, SERVO_ARM_NOT_FOLLOWING or SERVO_MODEL_MISMATCH
  with qdot = 0 within 3 s of simulated time (60 calls of 50 ms) and the task's line on std::cerr at servo time.
  With VISP_PROJECTIVE_TEST_VERBOSE set, each case prints one table row: mistake | arm | outcome | message head.
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveModelCheck.h>
#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpModelCheckTestTools.h"
#include "vpProjectiveAcquisitionProcedureTestTools.h"
#include "vpRigUpdateTestTools.h"
#include "vpServoArmFollowingTestTools.h"
#include "vpServoProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
const ArmCase kArms[] = {{"PUMA", pumaEyeToHand}, {"Viper850", viperEyeToHand}, {"RRPRRR", rrprrrEyeToHand}};
const double kPeriod = 0.05;                                           // s per servo call
const unsigned int kCallsIn3s = static_cast<unsigned int>(3.0 / kPeriod); // 60

//! One row of the table of page_mistakes, printed only when the tests are verbose.
void row(const std::string &mistake, const std::string &arm, const std::string &outcome, const std::string &message)
{
  const std::string line = message.substr(0, message.find('\n'));
  testLog() << "| " << mistake << " | " << arm << " | " << outcome << " | "
            << (line.size() > 150 ? line.substr(0, 150) + "..." : line) << " |" << std::endl;
}

/*
  An acquisition with a mistake (acquireWithMistakes()'s hooks) refused by calibrate(): modelRejectedError, the
  likeliest cause \e cause, its finding holding \e words; the row printed.
*/
void expectRefused(const char *mistake, const ArmCase &arm, const std::vector<vpProjectiveRobot::vpJointType> &types,
                   vpProjectiveModelCheck::vpCause cause, const std::string &words,
                   const std::function<void(unsigned int, UserTrial &)> &before,
                   const std::function<void(unsigned int, UserTrial &)> &after = nullptr)
{
  const ArmSetup s = arm.make();
  vpProjectiveRobot robot(types);
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.3, 7, before, after)) << arm.label;
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError)
      << mistake << ", " << arm.label << ": " << message;
  EXPECT_FALSE(robot.isCalibrated());
  const std::vector<vpProjectiveModelCheck::vpDiagnosis> &causes = robot.getAcquisition().getModelCheck().getCauses();
  ASSERT_FALSE(causes.empty()) << mistake << ", " << arm.label;
  EXPECT_EQ(causes.front().cause, cause) << mistake << ", " << arm.label << ": " << message;
  EXPECT_NE(causes.front().finding.find(words), std::string::npos) << causes.front().finding;
  row(mistake, arm.label, "refused (modelRejectedError)", causes.front().finding);
}

//! What a servo run with a mistake showed: the loop's result and the task's line on std::cerr.
struct ServoOutcome {
  LoopResult r;
  std::string err;
  int stoppedAt() const { return r.notFollowingAt >= 0 ? r.notFollowingAt : r.mismatchAt; }
};

/*
  A task of the setup from a start to a target drawn from \e seed, with the model \e model and the user's program
  \e settings (its read/send hooks, a fault from \e faultAt): the notices on, as a drop-in program has them.
*/
ServoOutcome servoWithMistake(const ArmSetup &s, const vpProjectiveRobot &model, const LoopSettings &settings,
                              long seed, ArmFault fault = NO_FAULT, unsigned int faultAt = 0,
                              const ArmSetup *moved = nullptr)
{
  vpUniRand rng(seed);
  std::vector<double> range(s.n(), vpMath::rad(10.0));
  for (unsigned int i = 0; i < s.n(); ++i) {
    range[i] = s.jointTypes()[i] == vpProjectiveRobot::REVOLUTE ? range[i] : 0.03; // m
  }
  const vpColVector qStart = s.randomVisibleJoints(rng, range), qTarget = s.randomVisibleJoints(rng, range);
  const NoticesSetting on(true);
  vpProjectiveNotices::reset();
  ServoOutcome o;
  {
    CapturedStreams streams;
    o.r = runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, seed, 300, fault, faultAt, moved, 3, 0.5);
    o.err = streams.err.str();
  }
  return o;
}

//! The servo-time outcome: stopped within 3 s of its first faulty call with qdot = 0 and a line naming \e status.
void expectStopped(const char *mistake, const char *arm, const ServoOutcome &o, unsigned int faultAt,
                   const std::string &status)
{
  EXPECT_GE(o.stoppedAt(), static_cast<int>(faultAt)) << mistake << ", " << arm << ": final " << o.r.finalRms << " px";
  EXPECT_LE(o.stoppedAt(), static_cast<int>(faultAt + kCallsIn3s)) << mistake << ", " << arm;
  EXPECT_TRUE(o.r.qdotZeroAfter) << mistake << ", " << arm;
  EXPECT_NE(o.err.find("Warning: vpServoProjective: " + status), std::string::npos) << mistake << ", " << arm << ": "
                                                                                     << o.err;
  const double seconds = (o.stoppedAt() - static_cast<int>(faultAt) + 1) * kPeriod;
  row(mistake, arm, status + " after " + std::to_string(seconds).substr(0, 4) + " s, qdot = 0",
      o.err.substr(o.err.find(status)));
}

//! The arm-following cause of a stopped run, with \e words in its diagnosis.
void expectCause(const ServoOutcome &o, const char *mistake, const char *arm,
                 std::initializer_list<vpServoArmFollowing::vpFollowingCause> causes, const std::string &words)
{
  EXPECT_NE(std::find(causes.begin(), causes.end(), o.r.cause), causes.end())
      << mistake << ", " << arm << ": " << o.r.diagnosis;
  EXPECT_NE(o.r.diagnosis.find(words), std::string::npos) << mistake << ", " << arm << ": " << o.r.diagnosis;
}
} // namespace

// Wrong joint types: one joint declared of the other type (a revolute one prismatic, the slide revolute).
TEST(UserMistakes, WrongJointTypes)
{
  const unsigned int joint[] = {3, 1, 2};
  for (unsigned int a = 0; a < 3; ++a) {
    const ArmSetup s = kArms[a].make();
    expectRefused("wrong joint types", kArms[a], withOtherType(s, joint[a]), vpProjectiveModelCheck::CAUSE_JOINT_TYPE,
                  "joint " + std::to_string(joint[a]) + " (declared", nullptr);
  }
}

// Readings in degrees: the revolute joints' readings given in degrees (the slide's in metres).
TEST(UserMistakes, ReadingsInDegrees)
{
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    const std::vector<vpProjectiveRobot::vpJointType> types = s.jointTypes();
    expectRefused("readings in degrees", arm, types, vpProjectiveModelCheck::CAUSE_READING_UNITS, "degrees",
                  [&types](unsigned int, UserTrial &t) {
                    if (types[t.joint] == vpProjectiveRobot::REVOLUTE) {
                      t.amount = vpMath::deg(t.amount);
                    }
                  });
  }
}

// Markers in another order: between the frames of one trial (markers 1 and 4 exchanged in both images), or between the
// left and right images (the right images of markers 2 and 5 exchanged).
TEST(UserMistakes, MarkersInAnotherOrder)
{
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    expectRefused("markers in another order between frames", arm, s.jointTypes(),
                  vpProjectiveModelCheck::CAUSE_MARKERS_SWAPPED, "marker", nullptr, [](unsigned int k, UserTrial &t) {
                    if (k == 3) {
                      std::swap(t.left[1], t.left[4]);
                      std::swap(t.right[1], t.right[4]);
                    }
                  });
    expectRefused("markers in another order between images", arm, s.jointTypes(),
                  vpProjectiveModelCheck::CAUSE_MARKERS_SWAPPED, "marker", nullptr, [](unsigned int k, UserTrial &t) {
                    if (k == 8) {
                      std::swap(t.right[2], t.right[5]);
                    }
                  });
  }
}

// A trial that moved two joints: joint 4 also turned by 6 deg during joint 3's first trial.
TEST(UserMistakes, TrialThatMovedTwoJoints)
{
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    expectRefused("a trial that moved two joints", arm, s.jointTypes(), vpProjectiveModelCheck::CAUSE_SECOND_JOINT,
                  "joint 4 also moved", [](unsigned int k, UserTrial &t) {
                    if (k == 6) {
                      t.qTrue[4] += vpMath::rad(6.0);
                    }
                  });
  }
}

// Velocities in the camera frame: the task's qdot sent as a twist of a camera 10 cm in front of the flange (ViSP's
// setVelocity(CAMERA_FRAME, v) on an arm that knows its eMc), the joints moving by eJe^+ eVc qdot.
TEST(UserMistakes, VelocitiesInTheCameraFrame)
{
  const NoticesSetting quiet(false);
  const vpVelocityTwistMatrix eVc(vpHomogeneousMatrix(0.0, 0.0, 0.1, 0.0, 0.0, M_PI / 2));
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
    LoopSettings user;
    user.period = kPeriod;
    user.send = [&eVc](vpSimulatorRobotArm &robot, vpColVector &command) {
      vpMatrix eJe;
      robot.get_eJe(eJe);
      command = eJe.pseudoInverse() * (eVc * command);
    };
    const ServoOutcome o = servoWithMistake(s, model, user, 21);
    expectStopped("velocities in the camera frame", arm.label, o, 0, "SERVO_ARM_NOT_FOLLOWING");
    expectCause(o, "velocities in the camera frame", arm.label, {vpServoArmFollowing::ARM_OTHER_DIRECTION},
                "ARTICULAR_FRAME");
  }
}

// The robot not in velocity mode: the program never calls setRobotState(STATE_VELOCITY_CONTROL) (here: an emergency
// stop from the first call).
TEST(UserMistakes, RobotNotInVelocityMode)
{
  const NoticesSetting quiet(false);
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
    LoopSettings user;
    user.period = kPeriod;
    const ServoOutcome o = servoWithMistake(s, model, user, 22, NOT_IN_VELOCITY, 0);
    expectStopped("robot not in velocity mode", arm.label, o, 0, "SERVO_ARM_NOT_FOLLOWING");
    expectCause(o, "robot not in velocity mode", arm.label, {vpServoArmFollowing::ARM_NOT_MOVING},
                "STATE_VELOCITY_CONTROL");
  }
}

// Joints listed in another order: the program reads joints 1 and 2 exchanged (a joint-state message in alphabetical
// order) and sends qdot in the task's order, as the robot takes it.
TEST(UserMistakes, JointsListedInAnotherOrder)
{
  const NoticesSetting quiet(false);
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
    LoopSettings user;
    user.period = kPeriod;
    user.read = [](vpColVector &q) { std::swap(q[1], q[2]); };
    const ServoOutcome o = servoWithMistake(s, model, user, 23);
    expectStopped("joints listed in another order", arm.label, o, 0, "SERVO_ARM_NOT_FOLLOWING");
    expectCause(o, "joints listed in another order", arm.label, {vpServoArmFollowing::ARM_OTHER_DIRECTION},
                "in its order");
  }
}

// An encoder sign flipped: joint 1 reads -q during the acquisition (the model learns it so, and is accepted) and the
// servo; the robot moves it by +qdot.
TEST(UserMistakes, EncoderSignFlipped)
{
  const NoticesSetting quiet(false);
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    vpProjectiveRobot model(s.jointTypes());
    ASSERT_TRUE(acquireWithMistakes(s, model, 0.3, 2, [](unsigned int, UserTrial &t) {
      if (t.joint == 1) {
        t.amount = -t.amount;
      }
    }));
    ASSERT_NO_THROW(model.calibrate()) << arm.label; // a consistent acquisition: nothing to see in it
    LoopSettings user;
    user.period = kPeriod;
    user.read = [](vpColVector &q) { q[1] = -q[1]; };
    const ServoOutcome o = servoWithMistake(s, model, user, 24);
    expectStopped("an encoder sign flipped", arm.label, o, 0, "SERVO_ARM_NOT_FOLLOWING");
    expectCause(o, "an encoder sign flipped", arm.label, {vpServoArmFollowing::ARM_OTHER_DIRECTION},
                "joint 1 moves the other way");
  }
}

// A camera bumped between the acquisition and the servo (1-3 deg, 0.5-2 cm) at call 15: a model mismatch.
TEST(UserMistakes, CameraBumpedBetweenAcquisitionAndServo)
{
  const NoticesSetting quiet(false);
  vpUniRand rng(25);
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
    const ArmSetup moved = bumped(s, BUMP_LEFT, rng);
    LoopSettings user;
    user.period = kPeriod;
    const ServoOutcome o = servoWithMistake(s, model, user, 25, CAMERA_BUMPED, 15, &moved);
    expectStopped("a camera bumped", arm.label, o, 15, "SERVO_MODEL_MISMATCH");
    EXPECT_EQ(o.r.notFollowingAt, -1) << arm.label << ": " << o.r.diagnosis;
    EXPECT_NE(o.err.find("re-register a moved rig"), std::string::npos) << o.err;
  }
}

// Left and right images swapped in the whole program (acquisition, rig, servo): nothing depends on which camera is
// called left, and the task converges.
TEST(UserMistakes, LeftAndRightSwappedEverywhereConverges)
{
  const NoticesSetting quiet(false);
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    ArmSetup swapped = s; // the right camera called left
    swapped.camLeft = s.camRight;
    swapped.camRight = s.camLeft;
    swapped.wMl = s.wMl * s.rMl.inverse();
    swapped.rMl = s.rMl.inverse();
    const vpProjectiveRobot model = calibratedRobot(swapped, 0.3, 2);
    LoopSettings user;
    user.period = kPeriod;
    const ServoOutcome o = servoWithMistake(swapped, model, user, 26);
    EXPECT_EQ(o.stoppedAt(), -1) << arm.label << ": " << o.err;
    EXPECT_LT(o.r.finalRms, 0.5) << arm.label;
    EXPECT_TRUE(o.err.empty()) << o.err;
    row("left and right images swapped (acquisition and servo)", arm.label,
        "converged, " + std::to_string(o.r.finalRms).substr(0, 4) + " px", "(none needed)");
  }
}

// Joint limits in degrees (and millimetres for the slide): refused by the procedure's and the task's setters.
TEST(UserMistakes, JointLimitsInDegrees)
{
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    vpColVector qmin = s.arm.getJointMin() - s.qRef, qmax = s.arm.getJointMax() - s.qRef;
    for (unsigned int i = 0; i < s.n(); ++i) {
      const double unit = s.jointTypes()[i] == vpProjectiveRobot::REVOLUTE ? 180.0 / M_PI : 1000.0;
      qmin[i] *= unit;
      qmax[i] *= unit;
    }
    vpGaussRand noise(1.0, 0.0, 27);
    vpProjectiveAcquisitionProcedure procedure(
        [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
          return s.images(s.qRef, left, right, 0.3, noise);
        },
        s.width, s.height);
    procedure.setOutput(nullptr);
    std::string message;
    EXPECT_EQ(codeOf([&]() { procedure.setJointLimits(qmin, qmax, 0.0); }, message),
              vpProjectiveException::invalidValueError)
        << arm.label;
    EXPECT_NE(message.find("probable degrees"), std::string::npos) << message;
    row("joint limits in degrees (procedure)", arm.label, "refused (invalidValueError)",
        message.substr(message.find(": ") + 2));

    const vpProjectiveRobot model = calibratedRobot(s);
    vpServoProjective task;
    task.setRobot(model);
    EXPECT_EQ(codeOf([&]() { task.setJointLimits(qmin, qmax); }, message), vpProjectiveException::invalidValueError)
        << arm.label;
    EXPECT_NE(message.find("probable"), std::string::npos) << message;
    row("joint limits in degrees (task)", arm.label, "refused (invalidValueError)",
        message.substr(message.find(": ") + 2));
  }
}

// Left and right images swapped in the servo program only (the acquisition had them right).
TEST(UserMistakes, LeftAndRightSwappedInTheServo)
{
  const NoticesSetting quiet(false);
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2);
    LoopSettings user;
    user.period = kPeriod;
    user.swapImages = true;
    const ServoOutcome o = servoWithMistake(s, model, user, 28);
    testLog() << "[ measured ] swapped in servo " << arm.label << ": stopped " << o.stoppedAt() << " final "
              << o.r.finalRms << " err " << o.err << std::endl;
  }
}

// A session of another cell: the model calibrated from the recordings of a cell whose rig stands 20 cm and 15 deg
// elsewhere, used to servo this cell.
TEST(UserMistakes, SessionOfAnotherCell)
{
  const NoticesSetting quiet(false);
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    ArmSetup other = s;
    other.wMl = s.wMl * vpHomogeneousMatrix(0.2, 0.0, 0.0, 0.0, vpMath::rad(15.0), 0.0);
    const vpProjectiveRobot model = calibratedRobot(other, 0.3, 2);
    LoopSettings user;
    user.period = kPeriod;
    const ServoOutcome o = servoWithMistake(s, model, user, 29);
    testLog() << "[ measured ] another cell " << arm.label << ": stopped " << o.stoppedAt() << " final "
              << o.r.finalRms << " calls " << o.r.calls << " err " << o.err << std::endl;
  }
}

// A marker occluded during the acquisition: a cable hides marker 3 once joint 1 has turned past half its trial; the
// image source reports it lost there.
TEST(UserMistakes, MarkerOccludedDuringTheAcquisition)
{
  for (const ArmCase &arm : kArms) {
    const ArmSetup s = arm.make();
    vpArmRobot robot(s.arm, s.qRef);
    vpGaussRand noise(1.0, 0.0, 30);
    vpProjectiveAcquisitionProcedure procedure(
        [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
          const bool hidden = robot.q()[1] - s.qRef[1] > 0.5 * s.trialAmounts[1];
          return s.images(robot.q(), left, right, 0.3, noise, 0.0) && !hidden;
        },
        s.width, s.height);
    procedure.setOutput(&testLog());
    vpProjectiveRobot model(s.jointTypes());
    model.setStereoRig(s.rig());
    std::string message;
    const int code = codeOf([&]() { procedure.run(robot, model); }, message);
    testLog() << "[ measured ] occluded " << arm.label << ": code " << code << " " << message << " calibrated "
              << model.isCalibrated() << std::endl;
    if (model.isCalibrated()) {
      testLog() << "  residual " << model.getCalibrationResidual() << " stop+ "
                << procedure.getReports()[1].stopPositive << " amount+ " << procedure.getReports()[1].amountPositive
                << std::endl;
    }
  }
}
