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
  vpProjectiveAcquisitionProcedure's failures (helpers in vpProjectiveAcquisitionProcedureTestTools.h): a joint that
  cannot move without losing markers throws and leaves the robot at the zero reference and the acquisition unchanged,
  bad settings throw, too few or coplanar markers fail before the arm moves, too small a motion, a marker order change
  and a forgotten mounting are named.
*/

#include <gtest/gtest.h>

#include "vpProjectiveAcquisitionProcedureTestTools.h"

using namespace vpProjectiveTest;

TEST(ProjectiveAcquisitionProcedure, JointThatLosesMarkersThrowsAndChangesNothing)
{
  AcquisitionSetup s;
  auto base = s.source();
  // Joint 2 loses a marker as soon as it leaves the zero reference (an occluding cable, say).
  vpProjectiveAcquisitionProcedure procedure(
      [&s, base](std::vector<vpImagePoint> &l, std::vector<vpImagePoint> &r) {
        return base(l, r) && std::fabs(s.robot.q()[2]) < vpMath::rad(0.5);
      },
      s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  vpProjectiveArmAcquisition acq = s.acquisition();
  try {
    procedure.run(s.robot, acq);
    FAIL() << "no exception";
  } catch (const vpProjectiveException &e) {
    EXPECT_EQ(e.getCode(), vpProjectiveException::degenerateConfigurationError);
    EXPECT_NE(std::string(e.getMessage()).find("joint 2"), std::string::npos);
    EXPECT_NE(std::string(e.getMessage()).find("marker lost"), std::string::npos);
  }
  EXPECT_EQ(acq.getNumberOfTrials(), 0u);
  EXPECT_TRUE(procedure.getReports().empty());
  EXPECT_LT((s.robot.q() - vpColVector(6, 0.0)).frobeniusNorm(), 3e-5);
}

TEST(ProjectiveAcquisitionProcedure, BadSettingsThrow)
{
  AcquisitionSetup s;
  EXPECT_THROW(vpProjectiveAcquisitionProcedure(nullptr, 640, 480), vpProjectiveException);
  EXPECT_THROW(vpProjectiveAcquisitionProcedure(s.source(), 0, 480), vpProjectiveException);
  vpProjectiveAcquisitionProcedure procedure(s.source(), 640, 480);
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  EXPECT_THROW(procedure.setMaxAmounts(vpColVector(6, -0.1)), vpProjectiveException);
  EXPECT_THROW(procedure.setSteps(vpColVector(6, 0.0)), vpProjectiveException);
  EXPECT_THROW(procedure.setMinAmounts(vpColVector(6, -1.0)), vpProjectiveException);
  EXPECT_THROW(procedure.setImageMargin(-1.0), vpProjectiveException);
  EXPECT_THROW(procedure.setSpeed(-1.0, 0.0), vpProjectiveException);
  EXPECT_THROW(procedure.setJointLimits(vpColVector(6, -1.0), vpColVector(5, 1.0), 0.0), vpProjectiveException);
  EXPECT_THROW(procedure.setJointLimits(vpColVector(6, 1.0), vpColVector(6, -1.0), 0.0), vpProjectiveException);
  vpColVector nan(6, 0.1);
  nan[3] = std::nan("");
  EXPECT_THROW(procedure.setSteps(nan), vpProjectiveException);
  procedure.setSteps(vpColVector(5, 0.1)); // the robot has 6 joints: run() says so
  vpProjectiveArmAcquisition acq = s.acquisition();
  EXPECT_THROW(procedure.run(s.robot, acq), vpProjectiveException);
  EXPECT_TRUE(s.robot.commands.empty());
  EXPECT_EQ(acq.getNumberOfTrials(), 0u);
}

namespace
{
/*
  The acquisition with these tool markers, with and without a rig: fails with \e code and a message containing every
  one of \e phrases, before the arm moves.
*/
void expectFailureBeforeTheArmMoves(const std::vector<vpColVector> &markers, int code,
                                    const std::vector<std::string> &phrases)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(toolMarkersSource(s, markers), s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  for (bool withRig : {true, false}) {
    vpProjectiveArmAcquisition acq =
        withRig
            ? s.acquisition()
            : vpProjectiveArmAcquisition(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
    int thrown = 0;
    const std::string message = messageOf([&]() { procedure.run(s.robot, acq); }, thrown);
    EXPECT_EQ(thrown, code) << message;
    for (const std::string &phrase : phrases) {
      EXPECT_TRUE(contains(message, phrase)) << "'" << phrase << "' not in: " << message;
    }
    EXPECT_EQ(s.robot.velocityCalls + s.robot.positionCalls, 0u);
  }
}
} // namespace

//! ViSP's 4-point target: fails at second 0 (before any motion), saying "markers", how many, and the fix.
TEST(ProjectiveAcquisitionProcedure, FourMarkersFailBeforeTheArmMoves)
{
  expectFailureBeforeTheArmMoves(planarMarkers(4), vpProjectiveException::notEnoughPointsError,
                                 {"4 markers", "at least 5 markers", "Nothing moved"});
}

/*
  Six coplanar markers (a planar target): with or without a rig, the homography between the two images shows it at
  second 0, before any motion.
*/
TEST(ProjectiveAcquisitionProcedure, CoplanarMarkersFailBeforeTheArmMoves)
{
  expectFailureBeforeTheArmMoves(planarMarkers(6), vpProjectiveException::degenerateConfigurationError,
                                 {"markers are coplanar", "add markers off the plane"});
}

/*
  Four of five markers coplanar: no 5 markers with no 4 coplanar, so no unique displacement. With the rig known the
  plane parallax of the triangulated markers shows it at second 0; without a rig the single image pair cannot, and
  the estimated rig shows it before the calibration. A fifth marker well off the plane of the others is fine, and so
  are more markers with 4 coplanar among them (the mathematics needs one projective basis, no more).
*/
TEST(ProjectiveAcquisitionProcedure, FourOfFiveCoplanarMarkersFailWithTheCause)
{
  AcquisitionSetup s;
  std::vector<vpColVector> onePlusPlane = planarMarkers(4);
  onePlusPlane.push_back(vpProjectiveTest::point3(0.0, 0.0, 0.05)); // 4 coplanar and one off: still degenerate
  vpProjectiveAcquisitionProcedure procedure(toolMarkersSource(s, onePlusPlane), s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  procedure.setSteps(vpColVector(6, vpMath::rad(3.0)));
  vpProjectiveArmAcquisition acq = s.acquisition();
  int code = 0;
  std::string message = messageOf([&]() { procedure.run(s.robot, acq); }, code);
  EXPECT_EQ(code, vpProjectiveException::degenerateConfigurationError);
  EXPECT_TRUE(contains(message, "too close to coplanar")) << message;
  EXPECT_TRUE(contains(message, "zero reference, known rig")) << message;
  EXPECT_EQ(s.robot.velocityCalls + s.robot.positionCalls, 0u);
  EXPECT_LT(procedure.getGeneralPositionParallax(), 2.0); // 0.03 px at seed 12 (the paper's gripper: 6.6 px)

  vpProjectiveArmAcquisition noRig(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
  message = messageOf([&]() { procedure.run(s.robot, noRig); }, code);
  EXPECT_EQ(code, vpProjectiveException::degenerateConfigurationError);
  EXPECT_TRUE(contains(message, "too close to coplanar")) << message;
  EXPECT_TRUE(contains(message, "estimated rig")) << message;
  EXPECT_FALSE(noRig.getStereoRig().isInitialized());

  // Eight markers at the corners of a 6 cm cube: 4 coplanar on every face, yet 5 with no 4 coplanar exist.
  std::vector<vpColVector> cube;
  for (int k = 0; k < 8; ++k) {
    cube.push_back(vpProjectiveTest::point3((k & 1) ? 0.03 : -0.03, (k & 2) ? 0.03 : -0.03, (k & 4) ? 0.03 : -0.03));
  }
  vpProjectiveAcquisitionProcedure cubeProcedure(toolMarkersSource(s, cube), s.sim.getWidth(), s.sim.getHeight());
  cubeProcedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  cubeProcedure.setSteps(vpColVector(6, vpMath::rad(3.0)));
  vpProjectiveArmAcquisition cubeAcq = s.acquisition();
  cubeProcedure.run(s.robot, cubeAcq);
  EXPECT_GT(cubeProcedure.getGeneralPositionParallax(), 4.0); // 9.2 px
  EXPECT_LT(cubeProcedure.getCalibrationResidual(), 2.0 * s.sigma);
}

//! Trials too small to observe: the calibration's failure comes with what the run saw and the fix.
TEST(ProjectiveAcquisitionProcedure, TooSmallAMotionIsNamed)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  procedure.setMaxAmounts(vpColVector(6, vpMath::rad(0.2)));
  procedure.setSteps(vpColVector(6, vpMath::rad(0.1)));
  procedure.setMinAmounts(vpColVector(6, 0.0));
  vpProjectiveArmAcquisition acq = s.acquisition();
  int code = 0;
  const std::string message = messageOf([&]() { procedure.run(s.robot, acq); }, code);
  EXPECT_NE(code, -1);
  EXPECT_TRUE(contains(message, "What the procedure saw")) << message;
  EXPECT_TRUE(contains(message, "too small a motion")) << message;
  EXPECT_TRUE(contains(message, "setMaxAmounts()")) << message;
  EXPECT_EQ(acq.getNumberOfTrials(), 0u);
}

//! A tracker that swaps two markers during a trial: the run stops at that step and says so.
TEST(ProjectiveAcquisitionProcedure, MarkerOrderChangeIsNamed)
{
  AcquisitionSetup s;
  auto base = s.source();
  vpProjectiveAcquisitionProcedure procedure(
      [&s, base](std::vector<vpImagePoint> &l, std::vector<vpImagePoint> &r) {
        const bool ok = base(l, r);
        if (s.robot.q()[1] > vpMath::rad(2.5)) {
          std::swap(l[0], l[3]);
          std::swap(r[0], r[3]);
        }
        return ok;
      },
      s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  vpProjectiveArmAcquisition acq = s.acquisition();
  int code = 0;
  const std::string message = messageOf([&]() { procedure.run(s.robot, acq); }, code);
  EXPECT_EQ(code, vpProjectiveException::degenerateConfigurationError);
  EXPECT_TRUE(contains(message, "changed the markers' order")) << message;
  EXPECT_TRUE(contains(message, "of joint 1")) << message;
  EXPECT_EQ(acq.getNumberOfTrials(), 0u);
}

/*
  The rig on the hand, the markers static (the PUMA eye-in-hand setup of the servo tests) and the mounting forgotten
  (EYE_TO_HAND, the default): the check motion of two joints tells EYE_IN_HAND, whose model predicts it at the noise
  level while the other is off by far more; the facade ends up EYE_IN_HAND and the output says so. The reverse (an
  eye-to-hand rig declared EYE_IN_HAND) is told too.
*/
TEST(ProjectiveAcquisitionProcedure, ForgottenMountingIsDetected)
{
  for (bool eyeInHand : {true, false}) {
    const vpProjectiveTest::ArmSetup setup =
        eyeInHand ? vpProjectiveTest::pumaEyeInHand() : vpProjectiveTest::pumaEyeToHand();
    vpSimulatorRobotArm arm(setup.arm, setup.qRef);
    vpGaussRand noise(1.0, 0.0, 5);
    const double sigma = 0.3;
    vpProjectiveAcquisitionProcedure procedure(
        [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
          return setup.images(arm.getArmJoints(), left, right, sigma, noise, 0.0);
        },
        setup.width, setup.height);
    procedure.setSteps(vpColVector(6, vpMath::rad(eyeInHand ? 1.0 : 3.0)));
    procedure.setMinAmounts(vpColVector(6, vpMath::rad(2.0)));
    std::ostringstream log;
    procedure.setOutput(&log);
    vpProjectiveRobot robot(setup.jointTypes());
    robot.setStereoRig(setup.rig());
    robot.setRigMounting(eyeInHand ? vpProjectiveRobot::EYE_TO_HAND : vpProjectiveRobot::EYE_IN_HAND); // wrong
    procedure.run(arm, robot);

    const vpProjectiveRobot::vpRigMounting truth = setup.mounting;
    const vpProjectiveAcquisitionProcedure::vpMountingReport &report = procedure.getMountingReport();
    EXPECT_TRUE(report.checked);
    EXPECT_NE(report.set, truth);
    EXPECT_EQ(report.kept, truth);
    EXPECT_EQ(robot.getRigMounting(), truth);
    EXPECT_EQ(robot.getModel().getRigMounting(), truth);
    EXPECT_LT(report.residual, 3.0 * sigma);
    EXPECT_GT(report.otherResidual, 10.0 * report.residual);
    EXPECT_TRUE(contains(log.str(), std::string("the model uses ") + (eyeInHand ? "EYE_IN_HAND" : "EYE_TO_HAND")))
        << log.str();
    EXPECT_LT((arm.getArmJoints() - setup.qRef).frobeniusNorm(), 3e-5);

    // The kept model predicts a motion of three joints together, within the noise.
    vpColVector q = setup.qRef;
    for (unsigned int i : {0u, 2u, 4u}) {
      q[i] += 0.5 * procedure.getReports()[i].amountPositive;
    }
    ASSERT_TRUE(setup.visible(q, 0.0));
    std::vector<vpImagePoint> left, right;
    setup.images(q, left, right, 0.0);
    EXPECT_LT(robot.getPredictionError(q, left, right), sigma) << setup.name;

    // Detection off: the mounting as set, no check motion.
    const vpProjectiveRobot::vpRigMounting wrong = report.set;
    procedure.setMountingDetection(false);
    vpProjectiveRobot asSet(setup.jointTypes());
    asSet.setStereoRig(setup.rig());
    asSet.setRigMounting(wrong);
    procedure.run(arm, asSet);
    EXPECT_FALSE(procedure.getMountingReport().checked);
    EXPECT_EQ(asSet.getRigMounting(), wrong);
  }
}
