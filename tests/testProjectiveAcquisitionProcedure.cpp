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
  vpProjectiveAcquisitionProcedure on vpSimulatorRobotArm (PUMA, the paper's rig), instrumented by the test:
  the acquired model predicts the markers at the noise level, tight images and joint limits bound the trial amounts
  and the report says so, a joint that cannot move without losing markers throws and leaves the robot at the zero
  reference and the acquisition unchanged, bad settings throw. Seeded noise.
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorRobotArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
/*!
  The library's vpSimulatorRobotArm (constant sampling time: each setVelocity() moves the joints by one step of 10 ms)
  with what the tests check: the calls it received, every position reached (commands), a setPosition() that can be
  made to block, and a joint that velocity commands do not move.
*/
class vpArmRobot : public vpSimulatorRobotArm
{
public:
  explicit vpArmRobot(const vpSimulatorArm &arm, const vpColVector &q0 = vpColVector())
      : vpSimulatorRobotArm(arm, q0), commands(), positionCalls(0), velocityCalls(0), blockInSetPosition(false),
        stuckJoint(-1), lastVelocity(arm.getNumberOfJoints(), 0.0)
  {
  }
  void setPosition(const vpRobot::vpControlFrameType frame, const vpColVector &qIn) override
  {
    ++positionCalls;
    if (blockInSetPosition) {
      // A controller that never reports the move done (ViSP's setPosition() has no timeout): "forever" is 30 s
      // here, so that a procedure that calls it fails the test instead of hanging the suite.
      std::this_thread::sleep_for(std::chrono::seconds(30));
      return;
    }
    vpSimulatorRobotArm::setPosition(frame, qIn);
    commands.push_back(getArmJoints());
  }
  void setVelocity(const vpRobot::vpControlFrameType frame, const vpColVector &qdot) override
  {
    ++velocityCalls;
    lastVelocity = qdot;
    vpColVector v = qdot;
    if (stuckJoint >= 0 && static_cast<unsigned int>(stuckJoint) < v.size()) {
      v[static_cast<unsigned int>(stuckJoint)] = 0.0;
    }
    vpSimulatorRobotArm::setVelocity(frame, v);
    commands.push_back(getArmJoints());
  }
  //! The arm's joints now.
  vpColVector q() { return getArmJoints(); }

  std::vector<vpColVector> commands;
  unsigned int positionCalls, velocityCalls;
  bool blockInSetPosition; //!< setPosition() blocks (30 s)
  int stuckJoint;          //!< a joint that velocity commands do not move (-1: none)
  vpColVector lastVelocity;
};

struct AcquisitionSetup {
  vpSimulatorArm arm;
  vpSimulatorStereoRig sim;
  vpArmRobot robot;
  vpGaussRand noise;
  double sigma;

  AcquisitionSetup()
      : arm(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose())),
        sim(vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0)), robot(arm), noise(1.0, 0.0, 12), sigma(0.5)
  {
  }

  vpProjectiveAcquisitionProcedure::vpImageSource source()
  {
    return [this](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      return sim.project(arm.getMarkers(robot.q()), left, right, sigma, noise);
    };
  }

  vpProjectiveArmAcquisition acquisition() const
  {
    std::vector<vpProjectiveArmAcquisition::vpJointType> types(6, vpProjectiveJoint::REVOLUTE);
    vpProjectiveArmAcquisition acq(types);
    vpProjectiveStereoRig rig;
    rig.setFundamentalMatrix(sim.getFundamentalMatrix());
    acq.setStereoRig(rig);
    return acq;
  }

  //! Largest distance (px) of a marker to the image border, over both images, at joints q (noise-free).
  double borderDistance(const vpColVector &q) const
  {
    double d = 1e9;
    for (const vpColVector &X : arm.getMarkers(q)) {
      vpImagePoint l, r;
      sim.project(X, l, r);
      for (const vpImagePoint &p : {l, r}) {
        d = std::min({d, p.get_u(), p.get_v(), sim.getWidth() - 1.0 - p.get_u(), sim.getHeight() - 1.0 - p.get_v()});
      }
    }
    return d;
  }
};

/*!
  RMS error (px) of the model's marker predictions against the true images at 100 random configurations inside half
  the explored box with all markers 10 px inside the images; fails the test if fewer than 20 such configurations.
*/
double predictionRms(const AcquisitionSetup &s, const vpProjectiveAcquisitionProcedure &procedure,
                     const vpProjectiveArmModel &model)
{
  vpUniRand rng(7);
  double sum = 0.0;
  unsigned int count = 0;
  for (int k = 0; k < 100; ++k) {
    vpColVector q(6);
    vpProjectiveArmModel::JointVector qm(6);
    for (unsigned int i = 0; i < 6; ++i) {
      const vpProjectiveAcquisitionProcedure::vpJointReport &r = procedure.getReports()[i];
      q[i] = rng.uniform(-0.5 * r.amountNegative, 0.5 * r.amountPositive);
      qm[i] = q[i];
    }
    if (s.borderDistance(q) < 10.0) {
      continue;
    }
    const Eigen::Matrix4d H = model.displacement(qm);
    const std::vector<vpColVector> X = s.arm.getMarkers(q);
    for (unsigned int j = 0; j < X.size(); ++j) {
      Eigen::Vector4d p;
      EXPECT_TRUE(model.predictMarker(j, H, p));
      vpImagePoint l, r;
      s.sim.project(X[j], l, r);
      sum += (p - Eigen::Vector4d(l.get_u(), l.get_v(), r.get_u(), r.get_v())).squaredNorm();
      count += 4;
    }
  }
  EXPECT_GT(count, 4u * 7u * 20u);
  return count == 0 ? 1e9 : std::sqrt(sum / count);
}

TEST(ProjectiveAcquisitionProcedure, AcquiredModelPredictsMarkersAtNoiseLevel)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setSteps(vpColVector(6, vpMath::rad(2.0)));
  std::ostringstream log;
  procedure.setOutput(&log);
  unsigned int steps = 0;
  procedure.setStepCallback([&steps](unsigned int, const vpColVector &, const std::vector<vpImagePoint> &,
                                     const std::vector<vpImagePoint> &) { ++steps; });
  vpProjectiveArmAcquisition acq = s.acquisition();
  const vpProjectiveArmModel model = procedure.run(s.robot, acq);

  EXPECT_LT(procedure.getCalibrationResidual(), 2.0 * s.sigma);
  ASSERT_EQ(procedure.getReports().size(), 6u);
  EXPECT_EQ(acq.getNumberOfTrials(), 12u);
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_EQ(procedure.getReports()[i].trials, 2u);
    EXPECT_GT(procedure.getReports()[i].amountPositive, vpMath::rad(5.0));
  }
  EXPECT_NE(log.str().find("joint 5"), std::string::npos);
  EXPECT_GT(steps, 12u);
  EXPECT_LT((s.robot.q() - vpColVector(6, 0.0)).frobeniusNorm(), 3e-5); // back at the zero reference (1e-5 per joint)
  EXPECT_LT(predictionRms(s, procedure, model), s.sigma);               // 0.22 px at seed 12
  // Moved by joint velocities only, and the mounting told by a check motion of two joints.
  EXPECT_EQ(s.robot.positionCalls, 0u);
  EXPECT_GT(s.robot.velocityCalls, 100u);
  EXPECT_TRUE(procedure.getMountingReport().checked);
  EXPECT_EQ(procedure.getMountingReport().kept, vpProjectiveArmModel::EYE_TO_HAND);
  EXPECT_EQ(model.getRigMounting(), vpProjectiveArmModel::EYE_TO_HAND);
  // The check motion moves two joints to the ends of their explored ranges, where the model's error is largest.
  EXPECT_LT(procedure.getMountingReport().residual, 4.0 * s.sigma);
  EXPECT_GT(procedure.getMountingReport().otherResidual, 4.0 * procedure.getMountingReport().residual);
}

/*
  Without a rig the procedure estimates F from every pair it saw (about 300 steps of 7 markers here): the model from
  pixels and encoders only predicts the markers as well as with the true F, the rig is the acquisition's, and a
  rig-free acquisition that fails leaves the acquisition without a rig.
*/
TEST(ProjectiveAcquisitionProcedure, EstimatesTheRigFromItsOwnImages)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setSteps(vpColVector(6, vpMath::rad(2.0)));
  std::vector<vpProjectiveArmAcquisition::vpJointType> types(6, vpProjectiveJoint::REVOLUTE);
  vpProjectiveArmAcquisition acq(types);
  ASSERT_FALSE(acq.getStereoRig().isInitialized());
  const vpProjectiveArmModel model = procedure.run(s.robot, acq);

  ASSERT_TRUE(acq.getStereoRig().isInitialized());
  EXPECT_EQ(acq.getNumberOfTrials(), 12u);
  EXPECT_LT(procedure.getCalibrationResidual(), 2.0 * s.sigma);
  EXPECT_LT(acq.getStereoRig().getEstimationResidual(), s.sigma);
  // The estimated F against the true one: the true images satisfy it within a fraction of a pixel.
  const vpMatrix F = acq.getStereoRig().getFundamentalMatrix();
  double worst = 0.0;
  for (const vpColVector &X : s.arm.getMarkers(vpColVector(6, 0.1))) {
    vpImagePoint l, r;
    s.sim.project(X, l, r);
    const vpColVector m({l.get_u(), l.get_v(), 1.0}), mp({r.get_u(), r.get_v(), 1.0});
    const vpColVector line = F * m;
    worst = std::max(worst, std::abs(vpColVector::dotProd(mp, line)) / std::hypot(line[0], line[1]));
  }
  EXPECT_LT(worst, s.sigma);
  EXPECT_LT(predictionRms(s, procedure, model), s.sigma);

  // Bad threshold: a clear error; a run that fails (a 1-step minimum amount no joint can reach) changes nothing.
  EXPECT_THROW(procedure.setEpipolarThreshold(0.0), vpProjectiveException);
  EXPECT_THROW(procedure.setEpipolarThreshold(std::nan("")), vpProjectiveException);
  procedure.setMinAmounts(vpColVector(6, vpMath::rad(89.0)));
  vpProjectiveArmAcquisition fresh(types);
  EXPECT_THROW(procedure.run(s.robot, fresh), vpProjectiveException);
  EXPECT_FALSE(fresh.getStereoRig().isInitialized());
  EXPECT_EQ(fresh.getNumberOfTrials(), 0u);
}

/*
  The facade: run(vpRobot &, vpProjectiveRobot &) calibrates the vpProjectiveRobot (rig estimated, as it has none),
  whose model takes the encoder readings from a zero reference away from 0; a failed run leaves it as it was.
*/
TEST(ProjectiveAcquisitionProcedure, CalibratesTheFacadeFromAbsoluteReadings)
{
  AcquisitionSetup s;
  const vpColVector qRef({0.1, -0.05, 0.08, 0.2, -0.1, 0.3});
  s.robot.setPosition(vpRobot::ARTICULAR_FRAME, qRef);
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setSteps(vpColVector(6, vpMath::rad(2.0)));
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  procedure.run(s.robot, robot);
  ASSERT_TRUE(robot.isCalibrated());
  EXPECT_EQ(robot.getAcquisition().getNumberOfTrials(), 12u);
  EXPECT_LT((robot.getZeroReferenceJoints() - qRef).frobeniusNorm(), 1e-12);
  EXPECT_LT(robot.getCalibrationResidual(), 2.0 * s.sigma);

  // Encoder readings as they are: the markers predicted at qRef + dq against the true ones, within the noise.
  double sum = 0.0;
  unsigned int count = 0;
  for (double a : {-0.05, 0.05}) {
    const vpColVector q = qRef + vpColVector(6, a);
    const std::vector<vpColVector> X = s.arm.getMarkers(q);
    for (unsigned int j = 0; j < X.size(); ++j) {
      vpImagePoint l, r, lp, rp;
      s.sim.project(X[j], l, r);
      robot.projectMarker(j, q, lp, rp);
      sum += vpImagePoint::sqrDistance(l, lp) + vpImagePoint::sqrDistance(r, rp);
      count += 4;
    }
  }
  EXPECT_LT(std::sqrt(sum / count), s.sigma);

  const unsigned long generation = robot.getModelGeneration();
  const vpMatrix G = robot.getProjectiveToMetric();
  procedure.setMinAmounts(vpColVector(6, vpMath::rad(89.0))); // no joint gets that far: run() throws
  EXPECT_THROW(procedure.run(s.robot, robot), vpProjectiveException);
  EXPECT_EQ(robot.getModelGeneration(), generation);
  EXPECT_EQ((robot.getProjectiveToMetric() - G).frobeniusNorm(), 0.0);
  EXPECT_EQ(robot.getAcquisition().getNumberOfTrials(), 12u);
  EXPECT_LT((s.robot.q() - qRef).frobeniusNorm(), 3e-5); // back at the zero reference (1e-5 per joint)
}

TEST(ProjectiveAcquisitionProcedure, TightImageBoundsAmountsAndReportSaysSo)
{
  AcquisitionSetup s;
  const double margin = 120.0;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setSteps(vpColVector(6, vpMath::rad(2.0)));
  procedure.setMaxAmounts(vpColVector(6, vpMath::rad(40.0)));
  procedure.setImageMargin(margin);
  procedure.setMinAmounts(vpColVector(6, vpMath::rad(1.0)));
  vpProjectiveArmAcquisition acq = s.acquisition();
  procedure.run(s.robot, acq);
  unsigned int border = 0;
  for (unsigned int i = 0; i < 6; ++i) {
    const vpProjectiveAcquisitionProcedure::vpJointReport &r = procedure.getReports()[i];
    for (int sign = -1; sign <= 1; sign += 2) {
      const double amount = sign < 0 ? r.amountNegative : r.amountPositive;
      const auto reason = sign < 0 ? r.stopNegative : r.stopPositive;
      vpColVector q(6, 0.0);
      q[i] = sign * amount;
      EXPECT_GT(s.borderDistance(q), margin - 3.0 * s.sigma); // the trial kept the markers inside the margin
      if (reason == vpProjectiveAcquisitionProcedure::IMAGE_BORDER) {
        ++border;
        EXPECT_LT(amount, vpMath::rad(40.0));
        q[i] = sign * (amount + vpMath::rad(2.0));
        EXPECT_LT(s.borderDistance(q), margin + 3.0 * s.sigma); // one more step would have crossed it
      } else {
        EXPECT_EQ(reason, vpProjectiveAcquisitionProcedure::AMOUNT_REACHED);
        EXPECT_NEAR(amount, vpMath::rad(40.0), 1e-12);
      }
    }
  }
  EXPECT_GE(border, 2u);
}

TEST(ProjectiveAcquisitionProcedure, JointLimitsRespected)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  vpColVector qmin(6, -vpMath::rad(170.0)), qmax(6, vpMath::rad(170.0));
  qmin[1] = -vpMath::rad(8.0);
  qmax[1] = vpMath::rad(12.0);
  const double limitMargin = vpMath::rad(1.0);
  procedure.setJointLimits(qmin, qmax, limitMargin);
  procedure.setSteps(vpColVector(6, vpMath::rad(3.0)));
  vpProjectiveArmAcquisition acq = s.acquisition();
  procedure.run(s.robot, acq);
  for (const vpColVector &q : s.robot.commands) {
    for (unsigned int i = 0; i < 6; ++i) {
      EXPECT_GE(q[i], qmin[i] + limitMargin - 1e-12);
      EXPECT_LE(q[i], qmax[i] - limitMargin + 1e-12);
    }
  }
  const vpProjectiveAcquisitionProcedure::vpJointReport &r = procedure.getReports()[1];
  EXPECT_EQ(r.stopNegative, vpProjectiveAcquisitionProcedure::JOINT_LIMIT);
  EXPECT_EQ(r.stopPositive, vpProjectiveAcquisitionProcedure::JOINT_LIMIT);
  EXPECT_NEAR(r.amountNegative, vpMath::rad(6.0), 1e-12);
  EXPECT_NEAR(r.amountPositive, vpMath::rad(9.0), 1e-12);
}

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

std::string messageOf(const std::function<void()> &f, int &code)
{
  try {
    f();
  } catch (const vpProjectiveException &e) {
    code = e.getCode();
    return e.getStringMessage();
  }
  code = -1;
  return "";
}

bool contains(const std::string &text, const std::string &word)
{
  return text.find(word) != std::string::npos;
}

/*
  A robot whose setPosition() never returns (30 s here): by default the procedure drives the joints by velocity and
  never calls it; the model is as good as ever.
*/
TEST(ProjectiveAcquisitionProcedure, DefaultMotionNeverCallsABlockingSetPosition)
{
  AcquisitionSetup s;
  s.robot.blockInSetPosition = true;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
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

//! Markers given in the tool frame (3x1, metres), seen on the PUMA of the setup.
vpProjectiveAcquisitionProcedure::vpImageSource toolMarkersSource(AcquisitionSetup &s,
                                                                  const std::vector<vpColVector> &tMarkers)
{
  return [&s, tMarkers](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
    return s.sim.project(vpSimulatorStereoRig::transform(s.arm.get_wMt(s.robot.q()), tMarkers), left, right, s.sigma,
                         s.noise);
  };
}

std::vector<vpColVector> planarMarkers(unsigned int count)
{
  const double xy[6][2] = {{-0.04, -0.03}, {0.04, -0.03}, {0.04, 0.03}, {-0.04, 0.03}, {0.0, 0.05}, {0.02, -0.01}};
  std::vector<vpColVector> m;
  for (unsigned int j = 0; j < count; ++j) {
    m.push_back(vpProjectiveTest::point3(xy[j][0], xy[j][1], 0.0));
  }
  return m;
}

//! ViSP's 4-point target: fails at second 0 (before any motion), saying "markers", how many, and the fix.
TEST(ProjectiveAcquisitionProcedure, FourMarkersFailBeforeTheArmMoves)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(toolMarkersSource(s, planarMarkers(4)), s.sim.getWidth(),
                                             s.sim.getHeight());
  for (bool withRig : {true, false}) {
    vpProjectiveArmAcquisition acq =
        withRig
            ? s.acquisition()
            : vpProjectiveArmAcquisition(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
    int code = 0;
    const std::string message = messageOf([&]() { procedure.run(s.robot, acq); }, code);
    EXPECT_EQ(code, vpProjectiveException::notEnoughPointsError);
    EXPECT_TRUE(contains(message, "4 markers")) << message;
    EXPECT_TRUE(contains(message, "at least 5 markers")) << message;
    EXPECT_TRUE(contains(message, "Nothing moved")) << message;
    EXPECT_EQ(s.robot.velocityCalls + s.robot.positionCalls, 0u);
  }
}

/*
  Six coplanar markers (a planar target): with or without a rig, the homography between the two images shows it at
  second 0, before any motion.
*/
TEST(ProjectiveAcquisitionProcedure, CoplanarMarkersFailBeforeTheArmMoves)
{
  AcquisitionSetup s;
  vpProjectiveAcquisitionProcedure procedure(toolMarkersSource(s, planarMarkers(6)), s.sim.getWidth(),
                                             s.sim.getHeight());
  for (bool withRig : {true, false}) {
    vpProjectiveArmAcquisition acq =
        withRig
            ? s.acquisition()
            : vpProjectiveArmAcquisition(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
    int code = 0;
    const std::string message = messageOf([&]() { procedure.run(s.robot, acq); }, code);
    EXPECT_EQ(code, vpProjectiveException::degenerateConfigurationError);
    EXPECT_TRUE(contains(message, "markers are coplanar")) << message;
    EXPECT_TRUE(contains(message, "add markers off the plane")) << message;
    EXPECT_EQ(s.robot.velocityCalls + s.robot.positionCalls, 0u);
  }
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
} // namespace
