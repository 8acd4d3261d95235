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
  vpProjectiveAcquisitionProcedure's model (helpers in vpProjectiveAcquisitionProcedureTestTools.h): the acquired
  model predicts the markers at the noise level, the rig estimated from its own images, the facade calibrated from
  absolute readings, tight images and joint limits bound the trial amounts and the report says so.
*/

#include <gtest/gtest.h>

#include "vpProjectiveAcquisitionProcedureTestTools.h"

using namespace vpProjectiveTest;

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
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  procedure.setSteps(vpColVector(6, vpMath::rad(2.0)));
  std::vector<vpProjectiveJoint::vpJointType> types(6, vpProjectiveJoint::REVOLUTE);
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
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
  procedure.setSteps(vpColVector(6, vpMath::rad(2.0)));
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  procedure.run(s.robot, robot);
  ASSERT_TRUE(robot.isCalibrated());
  EXPECT_EQ(robot.getAcquisition().getNumberOfTrials(), 12u);
  EXPECT_LT((robot.getAcquisition().getZeroReferenceJoints() - qRef).frobeniusNorm(), 1e-12);
  EXPECT_LT(robot.getAcquisition().getCalibrationResidual(), 2.0 * s.sigma);

  // Encoder readings as they are: the markers predicted at qRef + dq against the true ones, within the noise.
  double sum = 0.0;
  unsigned int count = 0;
  for (double a : {-0.05, 0.05}) {
    const vpColVector q = qRef + vpColVector(6, a);
    const std::vector<vpColVector> X = s.arm.getMarkers(q);
    for (unsigned int j = 0; j < X.size(); ++j) {
      vpImagePoint l, r, lp, rp;
      s.sim.project(X[j], l, r);
      robot.getModel().projectMarker(j, q, lp, rp);
      sum += vpImagePoint::sqrDistance(l, lp) + vpImagePoint::sqrDistance(r, rp);
      count += 4;
    }
  }
  EXPECT_LT(std::sqrt(sum / count), s.sigma);

  const unsigned long generation = robot.getRigUpdate().getModelGeneration();
  const Eigen::Matrix4d G = robot.getModel().projectiveToMetric();
  procedure.setMinAmounts(vpColVector(6, vpMath::rad(89.0))); // no joint gets that far: run() throws
  EXPECT_THROW(procedure.run(s.robot, robot), vpProjectiveException);
  EXPECT_EQ(robot.getRigUpdate().getModelGeneration(), generation);
  EXPECT_EQ((robot.getModel().projectiveToMetric() - G).norm(), 0.0);
  EXPECT_EQ(robot.getAcquisition().getNumberOfTrials(), 12u);
  EXPECT_LT((s.robot.q() - qRef).frobeniusNorm(), 3e-5); // back at the zero reference (1e-5 per joint)
}

TEST(ProjectiveAcquisitionProcedure, TightImageBoundsAmountsAndReportSaysSo)
{
  AcquisitionSetup s;
  const double margin = 120.0;
  vpProjectiveAcquisitionProcedure procedure(s.source(), s.sim.getWidth(), s.sim.getHeight());
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
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
  procedure.setOutput(&vpProjectiveTest::testLog()); // progress only when the tests are verbose
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
