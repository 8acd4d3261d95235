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
  ends either corrected (the task converges, the acquisition returns a right model) or refused/stopped with a message
  that names its cause: an exception's code and message when the mistake is made (a setter, calibrate(), check()), or
  SERVO_ARM_NOT_FOLLOWING / SERVO_MODEL_MISMATCH with qdot = 0 within 3 s of simulated time (60 calls of 50 ms) and
  the task's line on std::cerr, as a drop-in program that never reads the status gets it.
  With VISP_PROJECTIVE_TEST_VERBOSE set, each case prints one row of the page's table: mistake | arm | outcome |
  message head.
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveModelCheck.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpModelCheckTestTools.h"
#include "vpProjectiveAcquisitionProcedureTestTools.h"
#include "vpProjectiveRobotTestTools.h"
#include "vpProjectiveSessionTestTools.h"
#include "vpRigUpdateTestTools.h"
#include "vpServoArmFollowingTestTools.h"
#include "vpUserMistakesTestTools.h"

using namespace vpProjectiveTest;

// Wrong joint types: one joint declared of the other type (a revolute one prismatic, the slide revolute).
TEST(UserMistakes, WrongJointTypes)
{
  const unsigned int joint[] = {3, 1, 2};
  for (unsigned int a = 0; a < 3; ++a) {
    const ArmSetup s = kMistakeArms[a].make();
    expectRefused("wrong joint types", kMistakeArms[a], withOtherType(s, joint[a]),
                  vpProjectiveModelCheck::CAUSE_JOINT_TYPE, "joint " + std::to_string(joint[a]) + " (declared",
                  nullptr);
  }
}

// Readings in degrees: the revolute joints' readings given in degrees (the slide's in metres).
TEST(UserMistakes, ReadingsInDegrees)
{
  for (const ArmCase &arm : kMistakeArms) {
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
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    expectRefused("markers in another order between frames", arm, s.jointTypes(),
                  vpProjectiveModelCheck::CAUSE_MARKERS_SWAPPED, "markers 1 and 4 are exchanged", nullptr,
                  [](unsigned int k, UserTrial &t) {
                    if (k == 3) {
                      std::swap(t.left[1], t.left[4]);
                      std::swap(t.right[1], t.right[4]);
                    }
                  });
    expectRefused("markers in another order between images", arm, s.jointTypes(),
                  vpProjectiveModelCheck::CAUSE_MARKERS_SWAPPED, "off the epipolar geometry", nullptr,
                  [](unsigned int k, UserTrial &t) {
                    if (k == 8) {
                      std::swap(t.right[2], t.right[5]);
                    }
                  });
  }
}

// A trial that moved two joints: joint 4 also turned by 6 deg during joint 3's first trial.
TEST(UserMistakes, TrialThatMovedTwoJoints)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    expectRefused("a trial that moved two joints", arm, s.jointTypes(), vpProjectiveModelCheck::CAUSE_SECOND_JOINT,
                  "if joint 4 also moved", [](unsigned int k, UserTrial &t) {
                    if (k == 6) {
                      t.qTrue[4] += vpMath::rad(6.0);
                    }
                  });
  }
}

// A marker occluded during the acquisition: a cable hides marker 3 once joint 1 has turned past half its trial
// amount; the image source reports the marker lost there. The procedure shortens that trial and ends with a right
// model (within 1 px of the true images at random configurations of the trials' range).
TEST(UserMistakes, MarkerOccludedDuringTheAcquisition)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    const ProcedureRun run =
        runProcedure(s, 30, [&s](const vpColVector &qArm, std::vector<vpImagePoint> &, std::vector<vpImagePoint> &) {
          return qArm[1] - s.qRef[1] <= 0.5 * s.trialAmounts[1]; // marker 3 hidden beyond
        });
    ASSERT_EQ(run.code, -1) << arm.label << ": " << run.message;
    const vpProjectiveRobot &model = run.model;
    ASSERT_TRUE(model.isCalibrated()) << arm.label;
    const vpProjectiveAcquisitionProcedure::vpJointReport &joint1 = run.reports[1];
    EXPECT_EQ(joint1.stopPositive, vpProjectiveAcquisitionProcedure::MARKER_LOST) << arm.label;
    EXPECT_LE(joint1.amountPositive, 0.5 * s.trialAmounts[1] + 1e-9) << arm.label;
    const size_t line = run.progress.find("joint 1 +: ");
    EXPECT_NE(run.progress.find("(marker lost)", line), std::string::npos) << run.progress;
    double worst = 0.0;
    const double rms = predictionRms(s, model, s.trialAmounts, 31, worst);
    EXPECT_LT(rms, 1.0) << arm.label << ": worst " << worst << " px";
    row("a marker occluded during the acquisition", arm.label,
        "right model (" + std::to_string(rms).substr(0, 4) + " px RMS at random poses), trial shortened",
        run.progress.substr(line, run.progress.find('\n', line) - line));
  }
}

// Joint limits in degrees (and millimetres for the slide): refused by the procedure's and the task's setters.
TEST(UserMistakes, JointLimitsInDegrees)
{
  for (const ArmCase &arm : kMistakeArms) {
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
    EXPECT_NE(message.find("probable degrees"), std::string::npos) << message;
    row("joint limits in degrees (task)", arm.label, "refused (invalidValueError)",
        message.substr(message.find(": ") + 2));
  }
}

// Velocities in the camera frame: the task's qdot sent as a twist of a camera 10 cm in front of the flange (ViSP's
// setVelocity(CAMERA_FRAME, v) on an arm that knows its eMc), the joints moving by eJe^+ eVc qdot.
TEST(UserMistakes, VelocitiesInTheCameraFrame)
{
  const vpVelocityTwistMatrix eVc(vpHomogeneousMatrix(0.0, 0.0, 0.1, 0.0, 0.0, M_PI / 2));
  for (const ArmCase &arm : kMistakeArms) {
    UserProgram user(arm);
    user.loop.send = [&eVc](vpSimulatorRobotArm &robot, vpColVector &command) {
      vpMatrix eJe;
      robot.get_eJe(eJe);
      command = eJe.pseudoInverse() * (eVc * command);
    };
    const ServoOutcome o = user.servo(21);
    expectStopped("velocities in the camera frame", arm.label, o, 0, {"SERVO_ARM_NOT_FOLLOWING"},
                  "setVelocity(vpRobot::ARTICULAR_FRAME, qdot)");
  }
}

// The robot not in velocity mode: the program never calls setRobotState(STATE_VELOCITY_CONTROL) (here: the robot in
// STATE_STOP from the first call), and gives the task its period as ViSP's servo examples do with their loop time.
TEST(UserMistakes, RobotNotInVelocityMode)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ServoOutcome o = UserProgram(arm).servo(22, NOT_IN_VELOCITY, 0);
    expectStopped("robot not in velocity mode", arm.label, o, 0, {"SERVO_ARM_NOT_FOLLOWING"},
                  "setRobotState(vpRobot::STATE_VELOCITY_CONTROL)");
    EXPECT_EQ(o.r.cause, vpServoArmFollowing::ARM_NOT_MOVING) << arm.label << ": " << o.r.diagnosis;
  }
}

// Joints listed in another order: the program reads joints 1 and 2 exchanged (a joint-state message in alphabetical
// order) and sends qdot in the task's order, as the robot takes it.
TEST(UserMistakes, JointsListedInAnotherOrder)
{
  for (const ArmCase &arm : kMistakeArms) {
    UserProgram user(arm);
    user.loop.read = [](vpColVector &q) { std::swap(q[1], q[2]); };
    const ServoOutcome o = user.servo(23);
    expectStopped("joints listed in another order", arm.label, o, 0,
                  {"SERVO_ARM_NOT_FOLLOWING", "SERVO_MODEL_MISMATCH"}, "order");
  }
}

// An encoder sign flipped: joint 1 reads -q during the acquisition (the model learns it so, and is accepted) and the
// servo; the robot moves it by +qdot.
TEST(UserMistakes, EncoderSignFlipped)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    vpProjectiveRobot model(s.jointTypes());
    ASSERT_TRUE(acquireWithMistakes(s, model, 0.3, 2, [](unsigned int, UserTrial &t) {
      if (t.joint == 1) {
        t.amount = -t.amount;
      }
    }));
    ASSERT_NO_THROW(model.calibrate()) << arm.label; // a consistent acquisition: nothing to see in it
    LoopSettings user = userLoop();
    user.read = [](vpColVector &q) { q[1] = -q[1]; };
    const ServoOutcome o = servoWithMistake(s, model, user, 24);
    expectStopped("an encoder sign flipped", arm.label, o, 0, {"SERVO_ARM_NOT_FOLLOWING", "SERVO_MODEL_MISMATCH"},
                  "signs");
  }
}

// A camera bumped between the acquisition and the servo (a left-camera bump of RigUpdate's draw) at call 15: a model
// mismatch, never taken for an arm that does not follow.
TEST(UserMistakes, CameraBumpedBetweenAcquisitionAndServo)
{
  vpUniRand rng(25);
  for (const ArmCase &arm : kMistakeArms) {
    const UserProgram user(arm);
    const ArmSetup moved = bumped(user.s, BUMP_LEFT, rng);
    const ServoOutcome o = user.servo(25, CAMERA_BUMPED, 15, &moved);
    expectStopped("a camera bumped", arm.label, o, 15, {"SERVO_MODEL_MISMATCH"}, "re-register a moved rig");
    EXPECT_EQ(o.r.notFollowingAt, -1) << arm.label << ": " << o.r.diagnosis;
  }
}

// Left and right images swapped in the whole program (acquisition, rig, servo): nothing depends on which camera is
// called left. On three tasks per arm, the swapped program ends as the right one does: converged (0.5 px) or not
// (the same tasks, in the same number of calls within 10 %), never stopped.
TEST(UserMistakes, LeftAndRightSwappedEverywhere)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    ArmSetup swapped = s; // the right camera called left
    swapped.camLeft = s.camRight;
    swapped.camRight = s.camLeft;
    swapped.wMl = s.wMl * s.rMl.inverse();
    swapped.rMl = s.rMl.inverse();
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2), swappedModel = calibratedRobot(swapped, 0.3, 2);
    unsigned int converged = 0;
    for (long seed = 26; seed < 29; ++seed) {
      const ServoOutcome right = servoWithMistake(s, model, userLoop(), seed);
      const ServoOutcome o = servoWithMistake(swapped, swappedModel, userLoop(), seed);
      EXPECT_EQ(o.stoppedAt(), -1) << arm.label << ": " << o.err;
      EXPECT_TRUE(o.err.empty()) << o.err;
      EXPECT_EQ(o.r.finalRms < 0.5, right.r.finalRms < 0.5)
          << arm.label << ", seed " << seed << ": " << o.r.finalRms << " px swapped, " << right.r.finalRms << " px";
      EXPECT_NEAR(o.r.calls, right.r.calls, 0.1 * right.r.calls + 2) << arm.label << ", seed " << seed;
      converged += o.r.finalRms < 0.5 ? 1 : 0;
    }
    row("left and right images swapped (acquisition and servo)", arm.label,
        "converged as the right program: " + std::to_string(converged) + "/3 tasks", "(none needed)");
  }
}

namespace
{
// \e tasks tasks of the setup (seeds from \e firstSeed) run by the program \e user with \e model: each stops on
// SERVO_MODEL_MISMATCH naming the left and right images exchanged; the row gives the latest stop.
void expectExchangeNamed(const char *mistake, const ArmCase &arm, const UserProgram &user, long firstSeed, int tasks)
{
  int latest = 0;
  for (long seed = firstSeed; seed < firstSeed + tasks; ++seed) {
    const ServoOutcome o = user.servo(seed);
    expectStopped(mistake, arm.label, o, 0, {"SERVO_MODEL_MISMATCH"}, "the left and right images are exchanged");
    latest = std::max(latest, o.stoppedAt());
  }
  row(mistake, arm.label,
      "SERVO_MODEL_MISMATCH at call " + std::to_string(latest) + " at the latest of " + std::to_string(tasks) +
          " tasks",
      "the left and right images are exchanged ...");
}
} // namespace

// Left and right images swapped in the servo only (the acquisition had them right: a program that builds its features
// with the images in the other order): SERVO_MODEL_MISMATCH naming the exchange, on ten tasks per arm.
TEST(UserMistakes, LeftAndRightSwappedInTheServoOnly)
{
  for (const ArmCase &arm : kMistakeArms) {
    UserProgram user(arm);
    user.loop.swapImages = true;
    expectExchangeNamed("left and right images swapped (servo only)", arm, user, 40, 10);
  }
}

// Left and right images swapped in the acquisition, against the rig's F given to it: the images meet the given rig
// only exchanged, and calibrate() refuses the model before fitting it (a model of the exchanged cameras would fit them
// at the noise, and the servo given the images in the right order would stop at once). The procedure, every image
// right first (two seeds per arm), and calibrate() with the trials' images exchanged after the zero reference.
TEST(UserMistakes, LeftAndRightSwappedInTheAcquisition)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    for (long seed = 32; seed < 34; ++seed) {
      const ProcedureRun run = runProcedure(
          s, seed, [](const vpColVector &, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
            std::swap(left, right);
            return true;
          });
      EXPECT_EQ(run.code, vpProjectiveException::modelRejectedError) << arm.label << ": " << run.message;
      EXPECT_NE(run.message.find("left and right images are swapped against the rig"), std::string::npos)
          << arm.label << ": " << run.message;
      EXPECT_FALSE(run.model.isCalibrated()) << arm.label;
      const size_t finding = std::min(run.message.find("the images meet"), run.message.size());
      row("left and right images swapped (acquisition, the rig's F given)", arm.label, "refused (modelRejectedError)",
          run.message.substr(finding));
    }
    expectRefused("left and right images swapped after the zero reference", arm, s.jointTypes(),
                  vpProjectiveModelCheck::CAUSE_IMAGES_EXCHANGED, "with left and right exchanged", nullptr,
                  [](unsigned int, UserTrial &t) { std::swap(t.left, t.right); });
  }
}

// A session of another cell: a model calibrated from a session of this cell (vpProjectiveSessionCalibration) checked
// against a session recorded in another cell of the same arm and markers, whose rig stands 6 cm and 4 deg elsewhere
// (vpProjectiveSessionCalibration::check(), the sessions without recorded cameras). Every frame is refused, both
// images are off, the conclusion says to calibrate again and the diagnosis names another rig.
TEST(UserMistakes, SessionOfAnotherCell)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    TemporaryFolder tmp;
    auto rec = std::make_shared<Recording>();
    ASSERT_TRUE(recordCalibrationSession(s, tmp / "acquisition", *rec, 0.1, 1)) << arm.label;
    vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
    calibration.setOutput(nullptr);
    calibration.calibrate(vpProjectiveSession::read(tmp / "acquisition"));
    calibration.saveModel(tmp / "model.json");
    std::vector<int> ids;
    const vpProjectiveArmModel model = vpProjectiveModelFile::load(tmp / "model.json", nullptr, nullptr, &ids);

    ArmSetup other = s;
    other.wMl = s.wMl * vpHomogeneousMatrix(0.06, 0.0, 0.0, 0.0, vpMath::rad(4.0), 0.0);
    {
      vpProjectiveSessionWriter writer(tmp / "other", other.jointTypes());
      vpGaussRand noise(1.0, 0.0, 33);
      vpUniRand rng(34);
      ASSERT_TRUE(recordFrame(other, writer, *rec, vpProjectiveSession::ZERO, other.qRef, 0.1, noise)) << arm.label;
      for (unsigned int k = 0; k < 4;) {
        const vpColVector q = other.randomVisibleJoints(rng, other.trialAmounts);
        ASSERT_EQ(q.getRows(), s.n());
        k += recordFrame(other, writer, *rec, vpProjectiveSession::OBSERVATION, other.armJoints(q), 0.1, noise) ? 1 : 0;
      }
    }
    vpProjectiveSessionCalibration checker(recordedMarkers(rec));
    checker.setOutput(nullptr);
    const std::vector<vpProjectiveSessionCalibration::vpFrameCheck> checks =
        checker.check(model, ids, vpProjectiveSession::read(tmp / "other"));
    ASSERT_EQ(checks.size(), 5u) << arm.label;
    for (const vpProjectiveSessionCalibration::vpFrameCheck &c : checks) {
      EXPECT_FALSE(c.fits) << arm.label << ", frame " << c.frame << ": " << c.left << " / " << c.right << " px";
    }
    EXPECT_EQ(checker.getRigState(), vpProjectiveSessionCalibration::BOTH_CAMERAS_MOVED) << arm.label;
    const std::string conclusion = vpProjectiveSessionCalibration::toString(checker.getRigState());
    EXPECT_NE(conclusion.find("calibrate again"), std::string::npos) << conclusion;
    // The same images as the rig moved by 6 cm: the diagnosis names both, another rig among them (sessions without
    // recorded cameras cannot tell them apart; with them, the cameras' identities name the other cell first).
    const std::string diagnosis = checker.getDiagnosisMessage();
    EXPECT_NE(diagnosis.find("another rig"), std::string::npos) << diagnosis;
    row("a session of another cell (check)", arm.label,
        "no frame fits: left " + std::to_string(checker.getLeftResidual()).substr(0, 5) + " px, right " +
            std::to_string(checker.getRightResidual()).substr(0, 5) + " px",
        conclusion);
  }
}

// The model of another cell (calibrated where the rig stands 8.5 cm farther back, turned 5 deg about its axis) used
// to servo this cell: the image-based law absorbs that error and the task converges, as the task with this cell's model
// does (on a task where that one does not converge either, the other cell's model ends within 2 px of it, unstopped).
TEST(UserMistakes, ModelOfAnotherCellInTheServo)
{
  for (const ArmCase &arm : kMistakeArms) {
    const ArmSetup s = arm.make();
    ArmSetup other = s;
    other.wMl = s.wMl * vpHomogeneousMatrix(0.03, 0.0, -0.08, 0.0, 0.0, vpMath::rad(5.0));
    const vpProjectiveRobot model = calibratedRobot(s, 0.3, 2), otherModel = calibratedRobot(other, 0.3, 2);
    unsigned int converged = 0, tasks = 0;
    for (long seed = 36; seed < 39; ++seed, ++tasks) {
      const ServoOutcome right = servoWithMistake(s, model, userLoop(), seed);
      const ServoOutcome o = servoWithMistake(s, otherModel, userLoop(), seed);
      EXPECT_EQ(o.stoppedAt(), -1) << arm.label << ", seed " << seed << ": " << o.err;
      if (right.r.finalRms < 0.5) {
        EXPECT_LT(o.r.finalRms, 0.5) << arm.label << ", seed " << seed;
      } else {
        EXPECT_LT(o.r.finalRms, right.r.finalRms + 2.0) << arm.label << ", seed " << seed;
      }
      converged += o.r.finalRms < 0.5 ? 1 : 0;
    }
    row("the model of another cell in the servo", arm.label,
        "converged on " + std::to_string(converged) + "/" + std::to_string(tasks) + " tasks, as this cell's model",
        "(none needed)");
  }
}

// The robot not in velocity mode in a drop-in ViSP program that never calls setControlPeriod(): the arm never moves, so
// the arm-following check has no period to learn; it stops the task after 40 still calls of commands (2 s here).
TEST(UserMistakes, RobotNotInVelocityModeWithoutPeriod)
{
  for (const ArmCase &arm : kMistakeArms) {
    UserProgram user(arm);
    user.loop.givePeriod = false;
    const ServoOutcome o = user.servo(22, NOT_IN_VELOCITY, 0);
    testLog() << "[ measured ] " << arm.label << ": stopped at call " << o.stoppedAt() << ", final " << o.r.finalRms
              << " px, stderr: " << o.err << std::endl;
    expectStopped("robot not in velocity mode, no period", arm.label, o, 0, {"SERVO_ARM_NOT_FOLLOWING"},
                  "STATE_VELOCITY_CONTROL");
  }
}
