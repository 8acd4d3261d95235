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
  vpSimulatorRobotArm, a vpSimulatorArm behind vpRobot: one sampling period per velocity command in the constant
  sampling time mode, the wall-clock time in real time, saturation per joint kind (prismatic joints in metres),
  joint limits in velocity and position control, encoder offsets, the Jacobians against finite differences, and
  vpProjectiveAcquisitionProcedure acquiring a PUMA-like arm through it in both modes at the noise level.
*/

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <string>
#include <thread>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpSimulatorRobotArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/robot/vpRobotException.h>

#include "vpProjectiveArmTestTools.h"

namespace
{
vpSimulatorArm puma()
{
  return vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
}

//! The revolute-prismatic-revolute arm of the acquisition tests (joint 1 slides, metres).
vpSimulatorArm mixed()
{
  return vpProjectiveTest::mixedEyeToHand().arm;
}

double seconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
} // namespace

TEST(SimulatorRobotArm, ConstantSamplingTimeIntegratesOnePeriodPerCommand)
{
  vpSimulatorRobotArm robot(puma());
  EXPECT_TRUE(robot.getConstantSamplingTimeMode());
  EXPECT_EQ(robot.getRobotState(), vpRobot::STATE_STOP);
  robot.setSamplingTime(0.02);
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  const vpColVector qdot({0.1, -0.2, 0.3, 0.0, 0.05, -0.4});
  for (int k = 0; k < 3; ++k) {
    robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  }
  std::this_thread::sleep_for(std::chrono::milliseconds(5)); // no motion between commands in this mode
  const vpColVector q = robot.getPosition(vpRobot::JOINT_STATE);
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_NEAR(q[i], 3 * 0.02 * qdot[i], 1e-15);
  }
  EXPECT_NEAR(robot.getTime(), 0.06, 1e-15);
  EXPECT_EQ(robot.getVelocity(vpRobot::ARTICULAR_FRAME), qdot);
  vpColVector d;
  robot.getDisplacement(vpRobot::ARTICULAR_FRAME, d);
  EXPECT_LT((d - q).frobeniusNorm(), 1e-15);
  robot.getDisplacement(vpRobot::ARTICULAR_FRAME, d);
  EXPECT_EQ(d.frobeniusNorm(), 0.0);
  // Stopping zeroes the velocity; velocity commands then need the velocity state again.
  robot.setRobotState(vpRobot::STATE_STOP);
  EXPECT_EQ(robot.getVelocity(vpRobot::ARTICULAR_FRAME).frobeniusNorm(), 0.0);
  EXPECT_THROW(robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot), vpRobotException);
  EXPECT_THROW(robot.setSamplingTime(0.0), vpProjectiveException);
}

TEST(SimulatorRobotArm, RealTimeIntegratesTheWallClock)
{
  vpSimulatorRobotArm robot(puma());
  robot.setConstantSamplingTimeMode(false);
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  const vpColVector qdot({0.2, 0.0, -0.1, 0.0, 0.0, 0.0});
  const double t0 = seconds();
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  const double t1 = seconds();
  const vpColVector atOnce = robot.getPosition(vpRobot::ARTICULAR_FRAME);
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double t2 = seconds();
  const vpColVector q = robot.getPosition(vpRobot::ARTICULAR_FRAME);
  const double t3 = seconds();
  // Joint 0 moved for the time between the command and the reading: at least t2 - t1, at most t3 - t0.
  EXPECT_GE(q[0], qdot[0] * (t2 - t1) - 1e-12);
  EXPECT_LE(q[0], qdot[0] * (t3 - t0) + 1e-12);
  EXPECT_NEAR(q[2] / q[0], qdot[2] / qdot[0], 1e-9); // along the command
  EXPECT_EQ(q[1], 0.0);
  EXPECT_LE(atOnce[0], q[0]);
  // Stopping freezes the joints.
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector(6, 0.0));
  const vpColVector stopped = robot.getPosition(vpRobot::ARTICULAR_FRAME);
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  EXPECT_EQ(robot.getPosition(vpRobot::ARTICULAR_FRAME), stopped);
}

TEST(SimulatorRobotArm, SaturatesPerJointKindPrismaticInMetres)
{
  vpSimulatorRobotArm robot(mixed());
  ASSERT_EQ(robot.getNumberOfJoints(), 3u);
  robot.setMaxRotationVelocity(0.5);
  robot.setMaxTranslationVelocity(0.05);
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  // Joint 1 (prismatic) asks 4 times its limit: the whole command is scaled by 1/4, its direction kept.
  const vpColVector qdot({0.4, 0.2, -0.3});
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  const vpColVector v = robot.getVelocity(vpRobot::ARTICULAR_FRAME);
  EXPECT_NEAR(v[1], 0.05, 1e-12);
  EXPECT_NEAR(v[0], 0.1, 1e-12);
  EXPECT_NEAR(v[2], -0.075, 1e-12);
  // A revolute joint over its limit: scaled by the rotation limit, the prismatic one then well below its own.
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector({2.0, 0.01, 0.0}));
  const vpColVector w = robot.getVelocity(vpRobot::ARTICULAR_FRAME);
  EXPECT_NEAR(w[0], 0.5, 1e-12);
  EXPECT_NEAR(w[1], 0.0025, 1e-12);
  // The prismatic joint moves in metres: one period of 10 ms at 5 cm/s is 0.5 mm.
  vpSimulatorRobotArm slide(mixed());
  slide.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  slide.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector({0.0, 0.05, 0.0}));
  EXPECT_NEAR(slide.getPosition(vpRobot::ARTICULAR_FRAME)[1], 0.0005, 1e-15);
}

TEST(SimulatorRobotArm, JointLimitsBoundVelocityAndPositionControl)
{
  vpSimulatorRobotArm robot(mixed());
  vpColVector qmin(3), qmax(3);
  qmin[0] = -0.1;
  qmax[0] = 0.1;
  qmin[1] = -0.02;
  qmax[1] = 0.03; // metres
  qmin[2] = -1.0;
  qmax[2] = 1.0;
  robot.setJointLimits(qmin, qmax);
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  for (int k = 0; k < 200; ++k) {
    robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector({0.0, 0.2, 0.0}));
  }
  EXPECT_EQ(robot.getPosition(vpRobot::ARTICULAR_FRAME)[1], 0.03); // held at the limit
  // Out of the limits: an exception naming the joint, and the arm does not move.
  const vpColVector before = robot.getPosition(vpRobot::ARTICULAR_FRAME);
  try {
    robot.setPosition(vpRobot::ARTICULAR_FRAME, vpColVector({0.0, 0.05, 0.0}));
    FAIL() << "no exception";
  } catch (const vpRobotException &e) {
    EXPECT_EQ(e.getCode(), vpRobotException::positionOutOfRangeError);
    EXPECT_NE(e.getStringMessage().find("joint 1"), std::string::npos) << e.getStringMessage();
  }
  EXPECT_EQ(robot.getPosition(vpRobot::ARTICULAR_FRAME), before);
  // Inside the current limits only.
  EXPECT_THROW(robot.setJointLimits(vpColVector(3, -0.01), vpColVector(3, 0.01)), vpProjectiveException);
  EXPECT_THROW(vpSimulatorRobotArm(puma(), vpColVector(6, vpMath::rad(175.0))), vpRobotException);
}

TEST(SimulatorRobotArm, PositionControlArrivesAlongAJointLineAtMaxSpeed)
{
  vpSimulatorRobotArm robot(puma());
  robot.setMaxRotationVelocity(0.5);
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  const vpColVector target({0.2, -0.1, 0.3, 0.0, 0.1, -0.25});
  robot.setPosition(vpRobot::ARTICULAR_FRAME, target); // switches to position control, as vpSimulatorViper850
  EXPECT_EQ(robot.getRobotState(), vpRobot::STATE_POSITION_CONTROL);
  EXPECT_EQ(robot.getPosition(vpRobot::ARTICULAR_FRAME), target);
  EXPECT_NEAR(robot.getTime(), 0.3 / 0.5, 1e-12); // the slowest joint at the largest velocity
  // Real time: the call lasts the motion (a blocking move), and arrives too.
  robot.setConstantSamplingTimeMode(false);
  robot.setMaxRotationVelocity(2.0);
  const double t0 = seconds();
  robot.setPosition(vpRobot::ARTICULAR_FRAME, vpColVector(6, 0.0));
  EXPECT_GE(seconds() - t0, 0.3 / 2.0);
  EXPECT_EQ(robot.getPosition(vpRobot::ARTICULAR_FRAME), vpColVector(6, 0.0));
}

TEST(SimulatorRobotArm, EncoderOffsetShiftsReadingsTargetsAndLimits)
{
  vpSimulatorRobotArm robot(puma(), vpColVector(6, 0.1));
  const vpColVector offset({1.0, -2.0, 0.5, 0.0, 3.0, -0.25});
  robot.setEncoderOffset(offset);
  EXPECT_LT((robot.getPosition(vpRobot::ARTICULAR_FRAME) - (vpColVector(6, 0.1) + offset)).frobeniusNorm(), 1e-15);
  robot.setPosition(vpRobot::ARTICULAR_FRAME, offset); // the arm's zero
  EXPECT_LT(robot.getArmJoints().frobeniusNorm(), 1e-15);
  EXPECT_LT((robot.getJointMax() - (robot.getArm().getJointMax() + offset)).frobeniusNorm(), 1e-15);
  EXPECT_THROW(robot.setPosition(vpRobot::ARTICULAR_FRAME, vpColVector(6, 0.0) + offset + vpColVector(6, 3.0)),
               vpRobotException);
  EXPECT_THROW(robot.setEncoderOffset(vpColVector(5, 0.0)), vpProjectiveException);
}

TEST(SimulatorRobotArm, OnlyTheJointSpaceIsSupported)
{
  vpSimulatorRobotArm robot(puma());
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  vpColVector v(6, 0.0), q;
  for (vpRobot::vpControlFrameType frame :
       {vpRobot::REFERENCE_FRAME, vpRobot::END_EFFECTOR_FRAME, vpRobot::CAMERA_FRAME, vpRobot::MIXT_FRAME}) {
    try {
      robot.setVelocity(frame, v);
      FAIL() << "no exception";
    } catch (const vpRobotException &e) {
      EXPECT_NE(e.getStringMessage().find("ARTICULAR_FRAME"), std::string::npos);
    }
    EXPECT_THROW(robot.getPosition(frame, q), vpRobotException);
    EXPECT_THROW(robot.setPosition(frame, v), vpRobotException);
  }
  EXPECT_THROW(robot.setRobotState(vpRobot::STATE_FORCE_TORQUE_CONTROL), vpRobotException);
  EXPECT_THROW(robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector(5, 0.0)), vpProjectiveException);
}

/*
  The Jacobians against central differences of the arm's forward kinematics (base frame), on both arms.
*/
TEST(SimulatorRobotArm, JacobiansMatchFiniteDifferences)
{
  vpUniRand rng(3);
  for (const vpSimulatorArm &arm : {puma(), mixed()}) {
    const unsigned int n = arm.getNumberOfJoints();
    vpColVector q(n);
    for (unsigned int i = 0; i < n; ++i) {
      q[i] = rng.uniform(-0.3, 0.3) * (arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? 0.1 : 1.0);
    }
    vpSimulatorRobotArm robot(arm, q);
    vpMatrix fJe, eJe;
    robot.get_fJe(fJe);
    robot.get_eJe(eJe);
    const vpHomogeneousMatrix bMw = arm.get_wMb().inverse();
    const vpHomogeneousMatrix bMe = bMw * arm.get_wMe(q);
    const double h = 1e-6;
    for (unsigned int i = 0; i < n; ++i) {
      vpColVector qp = q, qm = q;
      qp[i] += h;
      qm[i] -= h;
      const vpHomogeneousMatrix Mp = bMw * arm.get_wMe(qp), Mm = bMw * arm.get_wMe(qm);
      // v: the origin's velocity; w: from dR R^T (skew).
      const vpRotationMatrix dR = vpRotationMatrix((Mp.getRotationMatrix() * bMe.getRotationMatrix().t()));
      const vpRotationMatrix dRm = vpRotationMatrix((Mm.getRotationMatrix() * bMe.getRotationMatrix().t()));
      const vpThetaUVector up(dR), um(dRm);
      for (unsigned int r = 0; r < 3; ++r) {
        EXPECT_NEAR(fJe[r][i], (Mp[r][3] - Mm[r][3]) / (2 * h), 1e-6);
        EXPECT_NEAR(fJe[r + 3][i], (up[r] - um[r]) / (2 * h), 1e-6);
      }
    }
    // eJe = diag(eRb, eRb) fJe: ViSP's twist transformation of a pure rotation.
    const vpMatrix expected = vpVelocityTwistMatrix(bMe.getRotationMatrix().t()) * fJe;
    ASSERT_EQ(eJe.getRows(), 6u);
    ASSERT_EQ(eJe.getCols(), n);
    EXPECT_LT((eJe - expected).frobeniusNorm(), 1e-12);
  }
}

/*
  The acquisition procedure on the PUMA-like arm through vpSimulatorRobotArm, in both sampling modes, from absolute
  encoder readings (an offset): the residual and the model's prediction at the noise level, the joint limits taken
  from the robot.
*/
class SimulatorRobotArmAcquisition : public ::testing::TestWithParam<bool>
{
};

TEST_P(SimulatorRobotArmAcquisition, ProcedureReachesTheNoiseLevel)
{
  const bool constant = GetParam();
  const vpSimulatorArm arm = puma();
  const vpSimulatorStereoRig sim = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorRobotArm robot(arm);
  robot.setConstantSamplingTimeMode(constant);
  const vpColVector offset({0.3, -0.2, 0.1, 1.0, -0.5, 0.25});
  robot.setEncoderOffset(offset);
  const double sigma = 0.3;
  vpGaussRand noise(1.0, 0.0, 5);
  vpProjectiveAcquisitionProcedure procedure(
      [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        return sim.project(arm.getMarkers(robot.getArmJoints()), left, right, sigma, noise);
      },
      sim.getWidth(), sim.getHeight());
  procedure.setSteps(vpColVector(6, vpMath::rad(constant ? 2.0 : 5.0)));
  procedure.setMaxAmounts(vpColVector(6, vpMath::rad(20.0)));
  if (!constant) {
    procedure.setSpeed(2.0, 0.2); // real time: a shorter run
  }
  vpProjectiveArmAcquisition acq(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
  vpProjectiveStereoRig rig;
  rig.setFundamentalMatrix(sim.getFundamentalMatrix());
  acq.setStereoRig(rig);
  std::ostringstream log;
  procedure.setOutput(&log);
  const vpProjectiveArmModel model = procedure.run(robot, acq);
  EXPECT_NE(log.str().find("joint limits: the robot's own"), std::string::npos) << log.str();
  EXPECT_LT(procedure.getCalibrationResidual(), 1.5 * sigma);
  EXPECT_EQ(acq.getNumberOfTrials(), 12u);
  EXPECT_LT(robot.getArmJoints().frobeniusNorm(), 1e-4); // back at the zero reference
  // Prediction of the true images at random joints inside half the explored ranges, from encoder readings.
  vpUniRand rng(11);
  double sum = 0.0;
  unsigned int count = 0;
  for (int k = 0; k < 50; ++k) {
    vpColVector qArm(6);
    vpProjectiveArmModel::JointVector qEnc(6);
    for (unsigned int i = 0; i < 6; ++i) {
      const vpProjectiveAcquisitionProcedure::vpJointReport &r = procedure.getReports()[i];
      qArm[i] = rng.uniform(-0.5 * r.amountNegative, 0.5 * r.amountPositive);
      qEnc[i] = qArm[i] + offset[i];
    }
    const Eigen::Matrix4d H = model.displacement(qEnc);
    const std::vector<vpColVector> X = arm.getMarkers(qArm);
    for (unsigned int j = 0; j < X.size(); ++j) {
      Eigen::Vector4d p;
      vpImagePoint l, r;
      if (model.predictMarker(j, H, p) && sim.project(X[j], l, r)) {
        sum += (p - Eigen::Vector4d(l.get_u(), l.get_v(), r.get_u(), r.get_v())).squaredNorm();
        count += 4;
      }
    }
  }
  ASSERT_GT(count, 4u * 7u * 40u);
  EXPECT_LT(std::sqrt(sum / count), sigma);
  RecordProperty("residual_px", std::to_string(procedure.getCalibrationResidual()));
  RecordProperty("prediction_px", std::to_string(std::sqrt(sum / count)));
}

INSTANTIATE_TEST_SUITE_P(BothModes, SimulatorRobotArmAcquisition, ::testing::Values(true, false),
                         [](const ::testing::TestParamInfo<bool> &info) {
                           return info.param ? std::string("ConstantSamplingTime") : std::string("RealTime");
                         });
