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
  The real-cell program (vpProjectiveCell) on the rendered cell behind the arm adapter, end to end (acquisition, s*
  taught by showing, the planned servo, the recording), and every way it ends leaving the arm stopped: each failure
  injected (a camera that throws, a lost tag, a bumped camera, SIGINT, SIGTERM, an arm that refuses a command, the
  end of the user's commands, a joint limit) and the simulated arm's velocity read afterwards.
*/

#include <cmath>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>

#include <unistd.h>

#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveCell.h>
#include <visp3/projective/vpProjectiveCellFingerprint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpSimulatorStereoCell.h>

#include "vpModelFileChecksum.h"
#include "vpProjectiveTestTools.h"

using vpProjectiveTest::testLog;

namespace
{
vpColVector degrees(std::initializer_list<double> values)
{
  vpColVector q(static_cast<unsigned int>(values.size()));
  unsigned int i = 0;
  for (double v : values) {
    q[i++] = vpMath::rad(v);
  }
  return q;
}

const vpColVector kTarget = degrees({10, -8, 12, 15, -12, 20});
const vpColVector kStart = degrees({-2, 2, 0, 27, -2, 8});

//! The rendered cell of the tutorial: the PUMA-like arm, the paper's rig, three tags on the tool, 25 Hz.
struct RenderedCell {
  vpSimulatorStereoCell cell;
  std::vector<vpProjectiveJoint::vpJointType> types;
  explicit RenderedCell(long seed)
      : cell(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()),
             vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0), vpColVector(), seed),
        types(6, vpProjectiveJoint::REVOLUTE)
  {
    cell.addToolTags(0.03);
    cell.getRenderer().setNoise(1.0);
    cell.getRenderer().setBlur(0.5);
    cell.getRobot().setSamplingTime(0.04);
    cell.setTiming(25.0);
  }
};

/*!
  The adapter of the simulated arm, with a fault to inject: the command number \e failAt throws (a controller that
  refuses a command); it counts the stops and remembers whether a motion was sent after the last stop.
*/
class WatchedArm : public vpProjectiveCellViSPArm
{
public:
  WatchedArm(vpSimulatorRobotArm &robot, const std::vector<vpProjectiveJoint::vpJointType> &types)
      : vpProjectiveCellViSPArm(robot, types), m_robot(robot)
  {
  }
  void setJointVelocities(const vpColVector &qdot) override
  {
    if (++commands == failAt) {
      throw vpException(vpException::fatalError, "controller fault (injected)");
    }
    if (ignoreFrom > 0 && commands >= ignoreFrom) { // a controller that takes the commands and does not move
      vpProjectiveCellViSPArm::setJointVelocities(vpColVector(qdot.size(), 0.0));
      return;
    }
    vpProjectiveCellViSPArm::setJointVelocities(qdot);
    movingSinceStop = qdot.frobeniusNorm() > 0.0;
  }
  void stop() override
  {
    ++stops;
    movingSinceStop = false;
    vpProjectiveCellViSPArm::stop();
  }
  //! The simulated arm is still: zero velocity, stopped, and no motion commanded since the last stop.
  bool still()
  {
    return m_robot.getVelocity(vpRobot::ARTICULAR_FRAME).frobeniusNorm() == 0.0 &&
           m_robot.getRobotState() == vpRobot::STATE_STOP && !movingSinceStop && stops > 0;
  }
  unsigned int commands = 0, failAt = 0, ignoreFrom = 0, stops = 0;
  bool movingSinceStop = false;

private:
  vpSimulatorRobotArm &m_robot;
};

//! The rendered cameras, with a failure to inject from frame \e at on.
class FaultyCameras : public vpStereoImageSource
{
public:
  enum Fault { NONE, THROW, BLANK, SHIFT_RIGHT, SIGNAL_INT, SIGNAL_TERM };
  explicit FaultyCameras(vpSimulatorStereoCell &cell) : m_cell(cell) {}
  bool acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright) override
  {
    m_cell.acquire(Ileft, Iright);
    if (fault == NONE || ++frames < at) {
      return true;
    }
    switch (fault) {
    case THROW:
      throw vpException(vpException::ioError, "the left camera was unplugged (injected)");
    case BLANK: // a hand in front of the tags: nothing to detect
      Ileft = 128;
      Iright = 128;
      break;
    case SHIFT_RIGHT: { // the right camera bumped: its image shifted by 12 px
      const vpImage<unsigned char> I = Iright;
      for (unsigned int i = 0; i < I.getHeight(); ++i) {
        for (unsigned int j = 0; j < I.getWidth(); ++j) {
          Iright[i][j] = j >= 12 ? I[i][j - 12] : 128;
        }
      }
      break;
    }
    default:
      if (frames == at) {
        std::raise(fault == SIGNAL_INT ? SIGINT : SIGTERM);
      }
    }
    return true;
  }
  unsigned int getWidth() const override { return m_cell.getWidth(); }
  unsigned int getHeight() const override { return m_cell.getHeight(); }
  bool getTimestamps(double &left, double &right) const override { return m_cell.getTimestamps(left, right); }
  bool getCameraIdentities(vpCameraIdentity &left, vpCameraIdentity &right) const override
  {
    left = identities[0];
    right = identities[1];
    return !identities[0].serial.empty();
  }
  Fault fault = NONE;
  unsigned int at = 0, frames = 0;
  vpCameraIdentity identities[2]; // left, right: known if the left one has a serial

private:
  vpSimulatorStereoCell &m_cell;
};

vpProjectiveCell::vpSettings testSettings()
{
  vpProjectiveCell::vpSettings settings;
  settings.maxRotationSpeed = vpMath::rad(30.0);
  settings.gain = 1.0;
  settings.settleTime = 0.04;
  settings.timeout = 20.0;
  return settings;
}

std::string temporaryFolder(const std::string &name)
{
  const std::string folder = (std::filesystem::temp_directory_path() /
                              ("visp-projective-cell-" + name + "-" + std::to_string(static_cast<long>(::getpid()))))
                                 .string();
  std::filesystem::remove_all(folder);
  return folder;
}

//! The model of the rendered cell, acquired once for the suites that start at the servo.
class ProjectiveCellServo : public ::testing::Test
{
protected:
  static void SetUpTestSuite()
  {
    RenderedCell rendered(5);
    WatchedArm arm(rendered.cell.getRobot(), rendered.types);
    vpProjectiveCell::vpSettings settings = testSettings();
    settings.stepRotation = settings.amountRotation; // one trial each way per joint: a model in a few frames
    vpProjectiveCell cell(arm, rendered.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
    cell.acquire();
    s_model = temporaryFolder("model") + ".json";
    cell.saveModel(s_model);
  }
  static void TearDownTestSuite() { std::remove(s_model.c_str()); }

  /*!
    A cell from the suite's model, s* taught at the target, the arm at the start: \e fault injected from frame \e at
    of the servo.
  */
  void prepare(FaultyCameras::Fault fault, unsigned int at)
  {
    m_rendered.reset(new RenderedCell(11));
    m_arm.reset(new WatchedArm(m_rendered->cell.getRobot(), m_rendered->types));
    m_cameras.reset(new FaultyCameras(m_rendered->cell));
    m_cell.reset(new vpProjectiveCell(*m_arm, *m_cameras, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"),
                                      testSettings()));
    m_cell->setOutput(&testLog());
    m_cell->loadModel(s_model);
    m_cell->moveTo(kTarget);
    m_cell->teachHere();
    m_cell->moveTo(kStart);
    m_cameras->frames = 0;
    m_cameras->fault = fault;
    m_cameras->at = at;
  }

  static std::string s_model;
  std::unique_ptr<RenderedCell> m_rendered;
  std::unique_ptr<WatchedArm> m_arm;
  std::unique_ptr<FaultyCameras> m_cameras;
  std::unique_ptr<vpProjectiveCell> m_cell;
};
std::string ProjectiveCellServo::s_model;
} // namespace

TEST(ProjectiveCell, EndToEndAcquisitionTeachingServoRecording)
{
  RenderedCell rendered(3);
  WatchedArm arm(rendered.cell.getRobot(), rendered.types);
  vpProjectiveCell cell(arm, rendered.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), testSettings());
  cell.setOutput(&testLog());
  const std::string folder = temporaryFolder("session");
  cell.setRecording(folder);
  cell.acquire();
  EXPECT_TRUE(arm.still());
  EXPECT_LT(cell.getModel().getAcquisition().getCalibrationResidual(), 0.5);
  std::ostringstream script, prompt;
  script << "move";
  for (unsigned int i = 0; i < 6; ++i) {
    script << " " << kTarget[i];
  }
  script << "\nthis is not a command\n\nmove";
  for (unsigned int i = 0; i < 6; ++i) {
    script << " " << kStart[i];
  }
  script << "\nok\n";
  std::istringstream commands(script.str());
  cell.teach(commands, prompt);
  EXPECT_NE(prompt.str().find("not understood"), std::string::npos);
  EXPECT_GE(cell.getTargetIds().size(), 8u);
  EXPECT_TRUE(arm.still());
  const vpProjectiveCell::vpServoResult result = cell.servo();
  testLog() << "[ measured ] " << result.message << ", " << result.frames << " frames, " << result.seconds << " s\n";
  EXPECT_EQ(result.end, vpProjectiveCell::SERVO_CONVERGED) << result.message;
  EXPECT_LT(result.error, 0.5);
  EXPECT_LT((result.q - kTarget).frobeniusNorm(), vpMath::rad(1.0));
  EXPECT_TRUE(arm.still());
  const vpProjectiveSession session = vpProjectiveSession::read(folder);
  unsigned int roles[5] = {0, 0, 0, 0, 0};
  for (unsigned int f = 0; f < session.getNumberOfFrames(); ++f) {
    ++roles[session.getFrame(f).role];
  }
  EXPECT_EQ(roles[vpProjectiveSession::ZERO], 1u);
  EXPECT_GE(roles[vpProjectiveSession::TRIAL], 12u);
  EXPECT_EQ(roles[vpProjectiveSession::TARGET], testSettings().targetFrames);
  EXPECT_EQ(roles[vpProjectiveSession::SERVO], result.frames);
  std::filesystem::remove_all(folder);
}

TEST(ProjectiveCell, RefusesAnArmWithoutKnownLimitsUnlessTold)
{
  // An arm whose adapter knows no limits (most adapters of other arms): refused, nothing moved; moved when the user
  // gives limits or says there are none.
  struct Unlimited : public WatchedArm {
    using WatchedArm::WatchedArm;
    bool getJointLimits(vpColVector &, vpColVector &) override { return false; }
  };
  RenderedCell rendered(3);
  Unlimited arm(rendered.cell.getRobot(), rendered.types);
  vpProjectiveCell::vpSettings settings = testSettings();
  try {
    vpProjectiveCell cell(arm, rendered.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
    FAIL() << "an arm without known limits was accepted";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("no joint limits"), std::string::npos) << e.getStringMessage();
  }
  EXPECT_EQ(arm.commands, 0u);
  settings.noJointLimits = true;
  EXPECT_NO_THROW(
      vpProjectiveCell(arm, rendered.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings));
  settings.noJointLimits = false;
  settings.qmin = vpColVector(6, -1.0);
  settings.qmax = vpColVector(6, 1.0);
  vpProjectiveCell cell(arm, rendered.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
  // A move outside the safe range (the limits less 5 deg) is refused before the arm moves.
  vpColVector q(6, 0.0);
  q[2] = 0.95;
  EXPECT_THROW(cell.moveTo(q), vpProjectiveException);
  EXPECT_EQ(arm.commands, 0u);
}

TEST(ProjectiveCell, AcquisitionStopsTheArmOnACameraError)
{
  RenderedCell rendered(3);
  WatchedArm arm(rendered.cell.getRobot(), rendered.types);
  FaultyCameras cameras(rendered.cell);
  cameras.fault = FaultyCameras::THROW;
  cameras.at = 20; // during joint 1's trials
  vpProjectiveCell cell(arm, cameras, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), testSettings());
  EXPECT_THROW(cell.acquire(), vpException);
  EXPECT_GT(arm.commands, 10u); // the arm was moving
  EXPECT_TRUE(arm.still());
  EXPECT_TRUE(cell.getRobot().isHalted());
  EXPECT_THROW(cell.moveTo(kTarget), vpProjectiveException); // latched: no motion after a fault
  EXPECT_TRUE(arm.still());
}

TEST(ProjectiveCell, AcquisitionStopsTheArmOnSigint)
{
  vpProjectiveCellRobot::installSignalHandlers();
  RenderedCell rendered(3);
  WatchedArm arm(rendered.cell.getRobot(), rendered.types);
  FaultyCameras cameras(rendered.cell);
  cameras.fault = FaultyCameras::SIGNAL_INT;
  cameras.at = 8;
  vpProjectiveCell cell(arm, cameras, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), testSettings());
  try {
    cell.acquire();
    ADD_FAILURE() << "the acquisition went on after SIGINT";
  } catch (const vpException &e) {
    EXPECT_NE(cell.getRobot().getHaltReason().find("SIGINT"), std::string::npos) << e.getStringMessage();
  }
  const unsigned int commands = arm.commands;
  EXPECT_TRUE(arm.still());
  EXPECT_THROW(cell.moveTo(kTarget), vpProjectiveException);
  EXPECT_EQ(arm.commands, commands); // nothing sent after the signal
  vpProjectiveCellRobot::clearSignal();
  vpProjectiveCellRobot::installSignalHandlers(); // the handler resets itself when it runs
}

TEST(ProjectiveCell, TeachingStopsTheArmWhenTheCommandsEnd)
{
  RenderedCell rendered(3);
  WatchedArm arm(rendered.cell.getRobot(), rendered.types);
  vpProjectiveCell cell(arm, rendered.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), testSettings());
  std::ostringstream script, prompt;
  script << "jog 3 0.2\n"; // moves joint 3, then no confirmation: the input ends
  std::istringstream commands(script.str());
  EXPECT_THROW(cell.teach(commands, prompt), vpProjectiveException);
  EXPECT_GT(arm.commands, 0u);
  EXPECT_TRUE(arm.still());
  std::istringstream quit("quit\n");
  EXPECT_THROW(cell.teach(quit, prompt), vpProjectiveException);
  EXPECT_TRUE(arm.still());
}

TEST_F(ProjectiveCellServo, CameraErrorStopsTheArm)
{
  prepare(FaultyCameras::THROW, 6);
  EXPECT_THROW(m_cell->servo(), vpException);
  EXPECT_TRUE(m_arm->still());
}

TEST_F(ProjectiveCellServo, LostTagStopsTheArm)
{
  prepare(FaultyCameras::BLANK, 6);
  const vpProjectiveCell::vpServoResult result = m_cell->servo();
  EXPECT_EQ(result.end, vpProjectiveCell::SERVO_TAGS_LOST) << result.message;
  EXPECT_TRUE(m_arm->still());
}

TEST_F(ProjectiveCellServo, ModelMismatchStopsTheArm)
{
  prepare(FaultyCameras::SHIFT_RIGHT, 4);
  const vpProjectiveCell::vpServoResult result = m_cell->servo();
  EXPECT_EQ(result.end, vpProjectiveCell::SERVO_STATUS) << result.message;
  EXPECT_NE(result.message.find("SERVO_MODEL_MISMATCH"), std::string::npos) << result.message;
  EXPECT_TRUE(m_arm->still());
}

TEST_F(ProjectiveCellServo, SigtermStopsTheArm)
{
  vpProjectiveCellRobot::installSignalHandlers();
  prepare(FaultyCameras::SIGNAL_TERM, 5);
  EXPECT_THROW(m_cell->servo(), vpProjectiveException);
  EXPECT_NE(m_cell->getRobot().getHaltReason().find("SIGTERM"), std::string::npos);
  EXPECT_TRUE(m_arm->still());
  vpProjectiveCellRobot::clearSignal();
  vpProjectiveCellRobot::installSignalHandlers();
}

TEST_F(ProjectiveCellServo, ArmFaultStopsTheArm)
{
  prepare(FaultyCameras::NONE, 0);
  m_arm->failAt = m_arm->commands + 5; // the fifth command of the servo
  EXPECT_THROW(m_cell->servo(), vpException);
  EXPECT_NE(m_cell->getRobot().getHaltReason().find("controller fault"), std::string::npos);
  EXPECT_TRUE(m_arm->still());
}

TEST_F(ProjectiveCellServo, ArmNotFollowingStopsTheArmWithItsCause)
{
  // The task's own check (vpServoArmFollowing): a controller that stops moving the arm from the fifth command of the
  // servo on. The cell stops with the status and the diagnosis instead of waiting for its timeout.
  prepare(FaultyCameras::NONE, 0);
  m_arm->ignoreFrom = m_arm->commands + 5;
  const vpProjectiveCell::vpServoResult result = m_cell->servo();
  EXPECT_EQ(result.end, vpProjectiveCell::SERVO_STATUS) << result.message;
  EXPECT_NE(result.message.find("SERVO_ARM_NOT_FOLLOWING"), std::string::npos) << result.message;
  EXPECT_NE(result.message.find("does not move"), std::string::npos) << result.message;
  EXPECT_TRUE(m_arm->still());
}

TEST_F(ProjectiveCellServo, JointLimitHaltsTheArm)
{
  // The safety layer's own check, under whatever the task does: a command beyond a limit halts the robot.
  prepare(FaultyCameras::NONE, 0);
  vpProjectiveCellRobot &robot = m_cell->getRobot();
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  vpColVector q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  vpProjectiveCellRobot tight(*m_arm, q - vpColVector(6, 0.01), q + vpColVector(6, 1e-6), vpColVector(6, 0.5));
  tight.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  vpColVector qdot(6, 0.0);
  qdot[1] = 0.2;
  for (int k = 0; k < 5 && !tight.isHalted(); ++k) {
    try {
      tight.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
    } catch (const vpProjectiveException &) {
    }
  }
  EXPECT_TRUE(tight.isHalted());
  EXPECT_NE(tight.getHaltReason().find("joint 1"), std::string::npos) << tight.getHaltReason();
  EXPECT_TRUE(m_arm->still());
  EXPECT_THROW(tight.setVelocity(vpRobot::ARTICULAR_FRAME, qdot), vpProjectiveException);
}

TEST(ProjectiveCell, ArrivalToleranceFollowsTheEncodersNoise)
{
  // Encoders 10 times noisier than the procedure's 1e-5 rad tolerance: the noise measured at rest sets the
  // tolerance (4 sigma), the moves arrive and the model is as good as with exact readings.
  RenderedCell rendered(3);
  rendered.cell.getRobot().setEncoderNoise(1e-4, 7);
  WatchedArm arm(rendered.cell.getRobot(), rendered.types);
  vpProjectiveCell::vpSettings settings = testSettings();
  settings.stepRotation = settings.amountRotation;
  vpProjectiveCell cell(arm, rendered.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
  std::ostringstream progress;
  cell.setOutput(&progress);
  ASSERT_NO_THROW(cell.acquire()) << progress.str();
  EXPECT_NE(progress.str().find("(4 times the noise)"), std::string::npos) << progress.str();
  EXPECT_LT(cell.getModel().getAcquisition().getCalibrationResidual(), 0.1);
  EXPECT_TRUE(arm.still());
}

TEST(ProjectiveCell, RenderedCamerasTiming)
{
  // 10 Hz, the right image 20 ms after the left, delivered 100 ms after it: the stamps are frame instants, the
  // images show the arm then, acquire() waits for a frame (the arm moving on), and a lost frame lengthens the gap.
  RenderedCell rendered(3);
  vpSimulatorStereoCell &cell = rendered.cell;
  vpSimulatorRobotArm &robot = cell.getRobot();
  cell.setTiming(10.0, 0.1, 0.02, 0.5, 4);
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  vpColVector qdot(6, 0.0);
  qdot[0] = vpMath::rad(20.0);
  vpImage<unsigned char> Il, Ir;
  double previous = -1.0;
  bool gap = false;
  for (int k = 0; k < 8; ++k) {
    robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
    const double called = robot.getTime();
    cell.acquire(Il, Ir);
    double tl = 0.0, tr = 0.0;
    ASSERT_TRUE(cell.getTimestamps(tl, tr));
    EXPECT_NEAR(tr - tl, 0.02, 1e-12);
    EXPECT_NEAR(std::remainder(tl, 0.1), 0.0, 1e-9);               // a frame instant
    EXPECT_GE(robot.getTime() + 1e-12, tr + 0.1);                  // delivered after the latency
    EXPECT_LT(robot.getTime(), std::max(called, tr + 0.1) + 1e-9); // waited no longer than for it
    EXPECT_GT(tl, previous);                                       // never the same frame twice
    gap = gap || (previous >= 0.0 && tl - previous > 0.15);
    previous = tl;
    // The arm's history: joint 0 moved at 20 deg/s since it started (time 0), so the joints at tl are behind.
    EXPECT_NEAR(robot.getArmJoints()[0] - robot.getArmJointsAt(tl)[0],
                vpMath::rad(20.0) * (robot.getTime() - std::max(tl, 0.0)), 1e-9);
  }
  EXPECT_TRUE(gap); // half the frames lost: some gaps of two periods or more
  // The images show the arm when they were taken: off the arm's corners now while it moves, on them once it rested
  // for longer than the latency.
  const auto offNow = [&]() {
    const vpProjectiveSessionCalibration::vpMarkerExtractor tags =
        vpProjectiveSessionCalibration::aprilTagMarkers("36h11");
    std::vector<int> ids, trueIds;
    std::vector<vpImagePoint> l, r, trueL, trueR;
    cell.acquire(Il, Ir);
    tags(Il, Ir, ids, l, r);
    cell.getTrueCorners(trueIds, trueL, trueR);
    double worst = 0.0;
    for (size_t j = 0; j < ids.size(); ++j) {
      for (size_t k = 0; k < trueIds.size(); ++k) {
        if (trueIds[k] == ids[j]) {
          worst =
              std::max(worst, std::max(vpImagePoint::distance(l[j], trueL[k]), vpImagePoint::distance(r[j], trueR[k])));
        }
      }
    }
    EXPECT_GE(ids.size(), 8u);
    return worst;
  };
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  EXPECT_GT(offNow(), 3.0);
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector(6, 0.0));
  robot.wait(0.5);
  EXPECT_LT(offNow(), 0.5);
  EXPECT_THROW(cell.setTiming(10.0, -0.1), vpProjectiveException);
  EXPECT_THROW(cell.setTiming(10.0, 0.0, 0.0, 0.95), vpProjectiveException);
}

TEST_F(ProjectiveCellServo, LateImagesStopTheArm)
{
  // Cameras that fall 300 ms behind the readings (the default limit is 200 ms): their frames are not used, and the
  // arm stops with the limit named (tags lost after maxLostTime, or no plan: the task never saw a feature).
  prepare(FaultyCameras::NONE, 0);
  m_rendered->cell.setTiming(25.0, 0.3);
  const vpProjectiveCell::vpServoResult result = m_cell->servo();
  EXPECT_NE(result.end, vpProjectiveCell::SERVO_CONVERGED) << result.message; // lost, or no plan without features
  EXPECT_NE(result.message.find("maxLatency"), std::string::npos) << result.message;
  EXPECT_TRUE(m_arm->still());
}

TEST_F(ProjectiveCellServo, ModelKeepsItsCamerasAndOthersOrExchangedOnesAreNamed)
{
  // The suite's model was acquired with cameras that do not say who they are: any cameras load it.
  prepare(FaultyCameras::NONE, 0);
  vpStereoImageSource::vpCameraIdentity a, b, c;
  a.device = "/dev/video0";
  a.serial = "8A3F1C2E";
  b.device = "/dev/video2";
  b.serial = "5D09B7A1";
  c.device = "/dev/video2";
  c.serial = "33334444";
  const std::string file = temporaryFolder("cameras") + ".json";
  auto loadWith = [&](const vpStereoImageSource::vpCameraIdentity &left,
                      const vpStereoImageSource::vpCameraIdentity &right) {
    m_cameras->identities[0] = left;
    m_cameras->identities[1] = right;
    m_cell->loadModel(file);
  };
  m_cameras->identities[0] = a;
  m_cameras->identities[1] = b;
  m_cell->loadModel(s_model);
  // Saved by a cell whose cameras say who they are, the model keeps them, with its right camera on the right.
  m_cell->saveModel(file);
  vpProjectiveCellFingerprint cell;
  vpProjectiveModelFile::load(file, nullptr, nullptr, nullptr, nullptr, &cell);
  EXPECT_EQ(vpProjectiveCellFingerprint::sameCamera(cell.getLeftCamera(), a), 1);
  EXPECT_EQ(vpProjectiveCellFingerprint::sameCamera(cell.getRightCamera(), b), 1);
  EXPECT_EQ(cell.getCameraSide(), vpProjectiveCellFingerprint::SIDE_RIGHT);
  EXPECT_EQ(cell.getWidth(), m_cameras->getWidth());
  EXPECT_NO_THROW(loadWith(a, b));
  // A session the cell records says which camera took the left images.
  const std::string session = temporaryFolder("cameras-session");
  m_cell->setRecording(session);
  std::ostringstream json;
  json << std::ifstream(session + "/session.json").rdbuf();
  const std::string text = json.str();
  EXPECT_NE(text.find("\"" + a.serial + "\""), std::string::npos) << text;
  EXPECT_LT(text.find(a.serial), text.find(b.serial)) << text;
  std::filesystem::remove_all(session);
  // The same cameras given the other way round, then another right camera: refused, the cause named first.
  struct Mistake {
    vpStereoImageSource::vpCameraIdentity left, right;
    std::string opening;
  };
  for (const Mistake &mistake :
       {Mistake{b, a, "the left and right cameras are exchanged"}, Mistake{a, c, "the cameras are not the model's"}}) {
    try {
      loadWith(mistake.left, mistake.right);
      ADD_FAILURE() << "loaded with " << mistake.opening;
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::invalidValueError);
      EXPECT_NE(e.getStringMessage().find("loadModel(): the model '" + file + "': " + mistake.opening),
                std::string::npos)
          << e.getStringMessage();
    }
  }
  std::remove(file.c_str());
}

/*
  The task compares the rest of the fingerprint of the model's cell: a model loaded into a cell whose arm declares a
  joint of another kind, or whose cameras give images of another size, is refused with the joint or the sizes named.
*/
TEST_F(ProjectiveCellServo, ModelOfAnotherArmOrImageSizeIsRefused)
{
  RenderedCell rendered(5);
  std::vector<vpProjectiveJoint::vpJointType> types = rendered.types;
  types[2] = vpProjectiveJoint::PRISMATIC;
  WatchedArm arm(rendered.cell.getRobot(), types);
  FaultyCameras cameras(rendered.cell);
  vpProjectiveCell cell(arm, cameras, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), testSettings());
  auto expectRefused = [&cell](const std::string &file, const std::string &named) {
    try {
      cell.loadModel(file);
      ADD_FAILURE() << "loaded a model of " << named;
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::invalidValueError);
      EXPECT_NE(e.getStringMessage().find(named), std::string::npos) << e.getStringMessage();
    }
    EXPECT_THROW(cell.getModel().getModel(), vpProjectiveException); // the cell is left as it was: no model
  };
  expectRefused(s_model, "the arm is not the model's: its joint 2 is prismatic, the model's revolute");

  // The suite's model with its cell's images said to be twice as large, loaded by a cell of the right arm.
  WatchedArm right(rendered.cell.getRobot(), rendered.types);
  vpProjectiveCell rightCell(right, cameras, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), testSettings());
  EXPECT_NO_THROW(rightCell.loadModel(s_model));
  nlohmann::json file;
  std::ifstream(s_model) >> file;
  const unsigned int width = cameras.getWidth(), height = cameras.getHeight();
  ASSERT_EQ(file["model"]["cell"]["image_size"], nlohmann::json({width, height}));
  file["model"]["cell"]["image_size"] = {2 * width, 2 * height};
  const std::string larger = temporaryFolder("larger") + ".json";
  std::ofstream(larger) << vpProjectiveTest::resigned(file);
  vpProjectiveCell other(right, cameras, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), testSettings());
  try {
    other.loadModel(larger);
    ADD_FAILURE() << "loaded a model of images of another size";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("the left images are " + std::to_string(width) + " x " +
                                        std::to_string(height) + " pixels, the model's " + std::to_string(2 * width) +
                                        " x " + std::to_string(2 * height)),
              std::string::npos)
        << e.getStringMessage();
  }
  std::remove(larger.c_str());
}
