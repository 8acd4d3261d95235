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
  vpProjectiveAcquisitionProcedure's motion of the arm (helpers in vpProjectiveAcquisitionProcedureTestTools.h): the
  default motion never calls a blocking setPosition(), position control is an option, a stuck joint times out with a
  clear message.
*/

#include <gtest/gtest.h>

#include "vpProjectiveAcquisitionProcedureTestTools.h"

using namespace vpProjectiveTest;

/*
  A robot whose setPosition() never returns (30 s here): by default the procedure drives the joints by velocity and
  never calls it; the model is as good as ever.
*/
TEST(ProjectiveAcquisitionProcedure, DefaultMotionNeverCallsABlockingSetPosition)
{
  AcquisitionSetup s;
  s.robot.blockInSetPosition = true;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  procedure.setSteps(vpColVector(6, vpMath::rad(3.0)));
  vpProjectiveArmAcquisition acq = s.acquisition();
  const vpProjectiveArmModel model = procedure.run(s.robot, acq);
  EXPECT_EQ(s.robot.positionCalls, 0u);
  EXPECT_LT(procedure.getCalibrationResidual(), 2.0 * s.sigma);
  EXPECT_LT(predictionRms(s, procedure, model), s.sigma);
}

//! setPosition() stays available: POSITION_CONTROL moves by it alone and gives the same model quality.
TEST(ProjectiveAcquisitionProcedure, PositionControlIsAnOption)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  procedure.setSteps(vpColVector(6, vpMath::rad(3.0)));
  procedure.setMotionControl(vpProjectiveAcquisitionProcedure::POSITION_CONTROL);
  EXPECT_EQ(procedure.getMotionControl(), vpProjectiveAcquisitionProcedure::POSITION_CONTROL);
  vpProjectiveArmAcquisition acq = s.acquisition();
  const vpProjectiveArmModel model = procedure.run(s.robot, acq);
  EXPECT_EQ(s.robot.velocityCalls, 0u);
  EXPECT_GT(s.robot.positionCalls, 12u);
  EXPECT_LT(procedure.getCalibrationResidual(), 2.0 * s.sigma);
  EXPECT_LT(predictionRms(s, procedure, model), s.sigma);
  EXPECT_EQ((s.robot.q() - vpColVector(6, 0.0)).frobeniusNorm(), 0.0);
}

/*
  A joint that does not follow its velocity commands: the move times out, the robot is stopped (last command zero)
  and the message names the joint, the commanded and the read value; nothing is acquired.
*/
TEST(ProjectiveAcquisitionProcedure, StuckJointTimesOutWithAClearMessage)
{
  AcquisitionSetup s;
  s.robot.stuckJoint = 3;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  procedure.setSteps(vpColVector(6, vpMath::rad(3.0)));
  procedure.setMoveTimeout(0.2);
  vpProjectiveArmAcquisition acq = s.acquisition();
  int code = 0;
  const std::string message = messageOf([&]() { procedure.run(s.robot, acq); }, code);
  EXPECT_EQ(code, vpProjectiveException::robotMotionError);
  EXPECT_TRUE(contains(message, "joint 3 did not arrive")) << message;
  EXPECT_TRUE(contains(message, "commanded -3 deg")) << message;
  EXPECT_TRUE(contains(message, "read 0 deg")) << message;
  EXPECT_EQ(s.robot.lastVelocity.frobeniusNorm(), 0.0); // stopped
  EXPECT_EQ(acq.getNumberOfTrials(), 0u);
  EXPECT_THROW(procedure.setMoveTimeout(-1.0), vpProjectiveException);
  EXPECT_THROW(procedure.setArrivalTolerance(0.0), vpProjectiveException);
  EXPECT_THROW(procedure.setCoplanarityThreshold(0.0), vpProjectiveException);
}
