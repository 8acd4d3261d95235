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
  The model check in vpProjectiveAcquisitionProcedure, on the Afma6-like gantry of vpModelCheckTestTools.h driven as
  a vpSimulatorRobotArm (constant sampling time): the noise measured on two frames at rest, the joint types identified
  for a robot of a joint count, the gantry declared revolute refused with its slides named, the progress on std::cout
  by default with the limits echoed, limits in degrees refused (by the procedure and by the servo task), and the line
  on std::cerr when the procedure replaces the mounting set.
*/

#include <gtest/gtest.h>

#include <iostream>
#include <sstream>
#include <string>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpModelCheckTestTools.h"
#include "vpProjectiveAcquisitionProcedureTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! A setup's arm driven as a vpRobot from its zero reference, and the markers' images at its joints.
struct Cell {
  ArmSetup s;
  vpArmRobot robot;
  vpGaussRand noise;
  double sigma;

  explicit Cell(const ArmSetup &setup, double pixels = 0.3)
      : s(setup), robot(setup.arm, setup.qRef), noise(1.0, 0.0, 41), sigma(pixels)
  {
  }
  vpProjectiveAcquisitionProcedure::vpImageSource source()
  {
    return [this](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      return s.images(robot.q(), left, right, sigma, noise, 0.0);
    };
  }
  vpProjectiveStereoRig rig() const { return s.rig(); }
};

//! Captures a stream while alive.
struct Capture {
  std::ostream &stream;
  std::ostringstream text;
  std::streambuf *saved;
  explicit Capture(std::ostream &os) : stream(os), text(), saved(os.rdbuf(text.rdbuf())) {}
  ~Capture() { stream.rdbuf(saved); }
};
} // namespace

/*
  A robot of a joint count: the procedure moves every joint by 0.02 (rad or m) steps, the calibration identifies the
  three slides and the wrist, the noise at rest is the cell's; the progress, on std::cout by default, says so and
  echoes the robot's own limits in radians and metres.
*/
TEST(AcquisitionModelCheckProcedure, GantryOfAJointCountIsIdentified)
{
  Cell cell(gantryEyeToHand());
  vpProjectiveAcquisitionProcedure procedure(cell.source(), cell.s.width, cell.s.height);
  vpProjectiveRobot robot(6u);
  robot.setStereoRig(cell.rig());
  Capture out(std::cout);
  procedure.run(cell.robot, robot);
  const std::string log = out.text.str();

  ASSERT_TRUE(robot.isCalibrated());
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_EQ(robot.getJointType(i), cell.s.jointTypes()[i]) << "joint " << i << "\n" << log;
  }
  EXPECT_LT(robot.getAcquisition().getCalibrationResidual(), 2.0 * cell.sigma);
  EXPECT_NEAR(procedure.getImageNoise(), cell.sigma, 0.5 * cell.sigma); // 28 differences: about 13 % spread
  EXPECT_DOUBLE_EQ(robot.getAcquisition().getModelCheck().getGivenNoise(), procedure.getImageNoise());
  EXPECT_TRUE(contains(log, "image noise at rest")) << log;
  EXPECT_TRUE(contains(log, "joint limits: the robot's own")) << log;
  EXPECT_TRUE(contains(log, "joint 0 [-0.49, 0.49] (rad or m)")) << log;
  EXPECT_TRUE(contains(log, "joint types identified from the images: prismatic prismatic prismatic revolute revolute "
                            "revolute"))
      << log;
  EXPECT_TRUE(contains(log, "acquisition done")) << log;
}

/*
  The trial: the gantry declared as 6 revolute joints. The procedure's calibration is refused with the slides
  named, the robot stays uncalibrated and back at the zero reference; setOutput(nullptr) silences the progress.
*/
TEST(AcquisitionModelCheckProcedure, GantryDeclaredRevoluteIsRefusedWithTheSlidesNamed)
{
  Cell cell(gantryEyeToHand());
  vpProjectiveAcquisitionProcedure procedure(cell.source(), cell.s.width, cell.s.height);
  procedure.setOutput(nullptr);
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  robot.setStereoRig(cell.rig());
  Capture out(std::cout);
  std::string message;
  EXPECT_EQ(codeOf([&]() { procedure.run(cell.robot, robot); }, message), vpProjectiveException::modelRejectedError);
  EXPECT_TRUE(out.text.str().empty()) << out.text.str();
  EXPECT_FALSE(robot.isCalibrated());
  EXPECT_TRUE(contains(message, "joint types: joint 0 (declared revolute) slides")) << message;
  EXPECT_TRUE(contains(message, "joint 2 (declared revolute) slides")) << message;
  EXPECT_LT((cell.robot.q() - cell.s.qRef).frobeniusNorm(), 3e-5);
}

//! Limits and amounts in degrees or millimetres are refused, by the procedure and by the servo task.
TEST(AcquisitionModelCheckProcedure, RefusesJointValuesInDegrees)
{
  Cell cell(pumaEyeToHand());
  vpProjectiveAcquisitionProcedure procedure(cell.source(), cell.s.width, cell.s.height);
  procedure.setOutput(nullptr);
  std::string message;
  EXPECT_EQ(codeOf([&]() { procedure.setJointLimits(vpColVector(6, -170.0), vpColVector(6, 170.0), 2.0); }, message),
            vpProjectiveException::invalidValueError);
  EXPECT_TRUE(contains(message, "probable degrees")) << message;
  EXPECT_THROW(procedure.setMaxAmounts(vpColVector(6, 30.0)), vpProjectiveException);
  EXPECT_THROW(procedure.setSteps(vpColVector(6, 2.0 * 1000.0)), vpProjectiveException);
  // Within 10 but beyond 2 pi: refused once the types are known, before the arm moves.
  procedure.setJointLimits(vpColVector(6, -8.0), vpColVector(6, 8.0), 0.0);
  vpProjectiveRobot robot(cell.s.jointTypes());
  robot.setStereoRig(cell.rig());
  EXPECT_EQ(codeOf([&]() { procedure.run(cell.robot, robot); }, message), vpProjectiveException::invalidValueError);
  EXPECT_TRUE(contains(message, "outside [-2 pi, 2 pi] for a revolute joint")) << message;
  EXPECT_EQ(cell.robot.velocityCalls, 0u);

  // The servo task, knowing the robot's joint types.
  const ArmSetup stanford = rrprrrEyeToHand();
  const vpProjectiveRobot model = calibratedRobot(stanford);
  vpServoProjective task;
  task.setRobot(model);
  vpColVector qmin(6, -3.0), qmax(6, 3.0);
  EXPECT_NO_THROW(task.setJointLimits(qmin, qmax));
  qmax[3] = 170.0;
  EXPECT_EQ(codeOf([&]() { task.setJointLimits(qmin, qmax); }, message), vpProjectiveException::invalidValueError);
  EXPECT_TRUE(contains(message, "joint 3's qmax")) << message;
  qmax[3] = 3.0;
  qmax[2] = 8.0; // a prismatic joint: 8 m is possible
  EXPECT_NO_THROW(task.setJointLimits(qmin, qmax));
  qmax[2] = 450.0; // millimetres
  EXPECT_EQ(codeOf([&]() { task.setJointLimits(qmin, qmax); }, message), vpProjectiveException::invalidValueError);
  EXPECT_TRUE(contains(message, "probable millimetres")) << message;
}

/*
  The PUMA eye-in-hand with the mounting left at EYE_TO_HAND: the procedure tells EYE_IN_HAND and says so in one line
  on std::cerr, with the fix (vpProjectiveNotices: once per process; setEnabled(false) silences it).
*/
TEST(AcquisitionModelCheckProcedure, TellsOnStderrThatItReplacedTheMounting)
{
  Cell cell(pumaEyeInHand());
  vpProjectiveAcquisitionProcedure procedure(cell.source(), cell.s.width, cell.s.height);
  procedure.setOutput(nullptr);
  procedure.setSteps(vpColVector(6, vpMath::rad(1.0))); // the cameras on the tool: the markers leave the view within
  procedure.setMinAmounts(vpColVector(6, vpMath::rad(2.0))); // about 4 deg of the shoulder's motion
  vpProjectiveRobot robot(cell.s.jointTypes());
  robot.setStereoRig(cell.rig());
  const bool enabled = vpProjectiveNotices::isEnabled();
  vpProjectiveNotices::setEnabled(true);
  vpProjectiveNotices::reset();
  Capture err(std::cerr);
  procedure.run(cell.robot, robot);
  vpProjectiveNotices::setEnabled(enabled);
  EXPECT_EQ(robot.getRigMounting(), vpProjectiveRobot::EYE_IN_HAND);
  const std::string text = err.text.str();
  EXPECT_TRUE(contains(text, "Warning: vpProjectiveAcquisitionProcedure::run: the rig's mounting was set to "
                             "EYE_TO_HAND"))
      << text;
  EXPECT_TRUE(contains(text, "setRigMounting(EYE_IN_HAND)")) << text;
  EXPECT_EQ(text.find('\n'), text.size() - 1) << text; // one line
}
