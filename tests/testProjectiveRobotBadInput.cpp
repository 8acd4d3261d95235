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
  Tests of vpProjectiveRobot's bad inputs, of the calibration and of the inverse kinematics: misuse throws a
  vpProjectiveException with a meaningful code and message.
*/

#include <gtest/gtest.h>

#include "vpProjectiveRobotTestTools.h"

using namespace vpProjectiveTest;

TEST(ProjectiveRobot, BadInputsThrow)
{
  const ArmSetup s = pumaEyeToHand();
  const int dim = vpProjectiveException::dimensionError;
  const int notInit = vpProjectiveException::notInitializedError;
  const int invalid = vpProjectiveException::invalidValueError;
  const int nonFinite = vpProjectiveException::nonFiniteValueError;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();

  // Construction.
  EXPECT_TRUE(throwsProjective([] { vpProjectiveRobot r((std::vector<vpProjectiveRobot::vpJointType>())); }, dim,
                               "between 1 and"));
  EXPECT_TRUE(throwsProjective(
      [] { vpProjectiveRobot r(std::vector<vpProjectiveRobot::vpJointType>(17, vpProjectiveRobot::REVOLUTE)); }, dim,
      "between 1 and"));
  EXPECT_NO_THROW(
      [] { vpProjectiveRobot r(std::vector<vpProjectiveRobot::vpJointType>(16, vpProjectiveRobot::PRISMATIC)); }());

  vpProjectiveRobot robot(s.jointTypes());
  std::vector<vpImagePoint> left, right;
  s.images(s.qRef, left, right);
  // Rig first, and an initialised one.
  EXPECT_TRUE(throwsProjective([&] { robot.setZeroReference(left, right); }, notInit, "setStereoRig"));
  EXPECT_TRUE(throwsProjective([&] { robot.setStereoRig(vpProjectiveStereoRig()); }, notInit, "fundamental matrix"));
  // calibrate() before data.
  EXPECT_TRUE(throwsProjective([&] { robot.calibrate(); }, notInit, "zero reference"));
  robot.setStereoRig(s.rig());
  EXPECT_TRUE(throwsProjective([&] { robot.calibrate(); }, notInit, "zero reference"));
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, 0.5, left, right); }, notInit, "setZeroReference"));

  // Zero reference: fewer than 5 markers, sizes, non-finite.
  const std::vector<vpImagePoint> l4(left.begin(), left.begin() + 4), r4(right.begin(), right.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { robot.setZeroReference(l4, r4); }, vpProjectiveException::notEnoughPointsError,
                               "at least 5"));
  const std::vector<vpImagePoint> r6(right.begin(), right.begin() + 6);
  EXPECT_TRUE(throwsProjective([&] { robot.setZeroReference(left, r6); }, dim, "left"));
  std::vector<vpImagePoint> lBad = left;
  lBad[2].set_v(inf);
  EXPECT_TRUE(throwsProjective([&] { robot.setZeroReference(lBad, right); }, nonFinite, "not finite"));
  robot.setZeroReference(left, right);

  // Trials: joint index, amount, sizes, non-finite images.
  std::vector<vpImagePoint> lt, rt;
  vpColVector qt(6, 0.0);
  qt[0] = s.trialAmounts[0];
  s.images(s.armJoints(qt), lt, rt);
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(6, 0.5, lt, rt); }, dim, "out of range"));
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, 0.0, lt, rt); }, invalid, "zero"));
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, 2.0 * M_PI, lt, rt); }, invalid, "2 pi"));
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, nan, lt, rt); }, nonFinite, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, inf, lt, rt); }, nonFinite, "not finite"));
  const std::vector<vpImagePoint> lt6(lt.begin(), lt.begin() + 6), rt6(rt.begin(), rt.begin() + 6);
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, qt[0], lt6, rt6); }, dim, "same markers"));
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, qt[0], lt, rt6); }, dim, "left"));
  std::vector<vpImagePoint> ltBad = lt;
  ltBad[0].set_u(nan);
  EXPECT_TRUE(throwsProjective([&] { robot.addTrialMotion(0, qt[0], ltBad, rt); }, nonFinite, "not finite"));

  // A joint without trial.
  for (unsigned int i = 0; i < 6; ++i) {
    if (i == 3) {
      continue;
    }
    vpColVector q(6, 0.0);
    q[i] = s.trialAmounts[i];
    s.images(s.armJoints(q), lt, rt);
    robot.addTrialMotion(i, q[i], lt, rt);
  }
  EXPECT_TRUE(throwsProjective([&] { robot.calibrate(); }, notInit, "joint 3 has no trial motion"));
  EXPECT_FALSE(robot.isCalibrated());

  // Everything that needs a model, before calibration.
  const vpColVector q0(6, 0.0);
  const vpColVector M(4, 1.0);
  EXPECT_TRUE(throwsProjective([&] { robot.getImageJacobian(q0, M); }, notInit, "not acquired"));
  EXPECT_TRUE(throwsProjective([&] { robot.getDisplacement(q0); }, notInit, "not acquired"));
  EXPECT_TRUE(throwsProjective([&] { robot.getGenerator(0); }, notInit, "not acquired"));
  EXPECT_TRUE(throwsProjective([&] { robot.getModel(); }, notInit, "not acquired"));

  // With a model: sizes, indices, non-finite values, degenerate points.
  const vpProjectiveRobot model = calibratedRobot(s);
  EXPECT_TRUE(throwsProjective([&] { model.getDisplacement(vpColVector(5, 0.0)); }, dim, "q must have 6"));
  EXPECT_TRUE(throwsProjective([&] { model.getImageJacobian(vpColVector(7, 0.0), M); }, dim, "q must have 6"));
  vpColVector qNaN(6, 0.0);
  qNaN[4] = nan;
  EXPECT_TRUE(throwsProjective([&] { model.getDisplacement(qNaN); }, nonFinite, "joint value"));
  EXPECT_TRUE(throwsProjective([&] { model.getImageJacobian(qNaN, M); }, nonFinite, "joint value"));
  EXPECT_TRUE(throwsProjective([&] { model.getImageJacobian(q0, vpColVector(3, 1.0)); }, dim, "M"));
  vpColVector MNaN(4, 1.0);
  MNaN[1] = nan;
  EXPECT_TRUE(throwsProjective([&] { model.getImageJacobian(q0, MNaN); }, nonFinite, "M"));
  EXPECT_TRUE(throwsProjective([&] { model.getImageJacobian(q0, vpColVector(4, 0.0)); }, invalid, "zero vector"));
  // P = [I | 0]: M = (1, 0, 0, 0) has P M = (1, 0, 0), on the left camera's focal plane.
  vpColVector Mfocal(4, 0.0);
  Mfocal[0] = 1.0;
  EXPECT_TRUE(throwsProjective([&] { model.getImageJacobian(q0, Mfocal); }, vpProjectiveException::pointAtInfinityError,
                               "focal plane"));
  EXPECT_TRUE(throwsProjective([&] { model.getGenerator(6); }, dim, "out of range"));
  EXPECT_TRUE(throwsProjective([&] { model.getJointType(6); }, dim, "out of range"));
  vpImagePoint l, r;
  const vpProjectiveArmModel &arm = model.getModel(); // the model's own checked ViSP-typed call
  EXPECT_TRUE(throwsProjective([&] { arm.projectMarker(7, q0, l, r); }, dim, "marker index"));
  EXPECT_TRUE(throwsProjective([&] { arm.projectMarker(0, vpColVector(5, 0.0), l, r); }, dim, "q must have 6"));
  EXPECT_TRUE(throwsProjective([&] { arm.projectMarker(0, qNaN, l, r); }, nonFinite, "joint value"));

  // Setting another rig clears the acquisition.
  vpProjectiveRobot again = calibratedRobot(s);
  again.setStereoRig(s.rig());
  EXPECT_FALSE(again.isCalibrated());
  EXPECT_TRUE(throwsProjective([&] { again.calibrate(); }, notInit, "zero reference"));
}

TEST(ProjectiveRobot, SetCalibrationTakesAModelOfItsJointsOnly)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot model = calibratedRobot(s);
  const vpColVector q(6, 0.3);
  // What vpProjectiveAcquisitionProcedure::run() does: a model computed outside the robot, taken as calibrate() would.
  vpProjectiveRobot other(model.getModel().jointTypes());
  other.setCalibration(model.getAcquisition(), model.getModel(), model.getAcquisition().getCalibrationResidual());
  EXPECT_TRUE(other.isCalibrated());
  EXPECT_EQ(other.getAcquisition().getCalibrationResidual(), model.getAcquisition().getCalibrationResidual());
  EXPECT_EQ(other.getAcquisition().getAlgebraicResidual(), model.getAcquisition().getAlgebraicResidual());
  EXPECT_EQ((other.getDisplacement(q) - model.getDisplacement(q)).frobeniusNorm(), 0.0);
  // Another arm's model, or a residual that is no RMS error: refused, the robot unchanged.
  vpProjectiveRobot five(std::vector<vpProjectiveRobot::vpJointType>(5, vpProjectiveRobot::REVOLUTE));
  EXPECT_TRUE(throwsProjective([&] { five.setCalibration(model.getAcquisition(), model.getModel(), 0.1); },
                               vpProjectiveException::dimensionError, "different joints"));
  EXPECT_FALSE(five.isCalibrated());
  vpProjectiveRobot fresh(model.getModel().jointTypes());
  EXPECT_TRUE(throwsProjective([&] { fresh.setCalibration(model.getAcquisition(), model.getModel(), -1.0); },
                               vpProjectiveException::invalidValueError, "residual"));
  EXPECT_FALSE(fresh.isCalibrated());
}

TEST(ProjectiveRobot, InverseKinematicsBadInputs)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  std::vector<vpImagePoint> left, right;
  s.images(s.qRef, left, right);
  const int dim = vpProjectiveException::dimensionError;
  // Not all markers and no indices.
  std::vector<vpImagePoint> l6(left.begin(), left.begin() + 6), r6(right.begin(), right.begin() + 6);
  EXPECT_TRUE(throwsProjective([&] { robot.inverseKinematics(l6, r6); }, dim, "markers"));
  // Left and right of different sizes.
  EXPECT_TRUE(throwsProjective([&] { robot.inverseKinematics(left, r6); }, dim, "left"));
  // One index per point.
  EXPECT_TRUE(throwsProjective(
      [&] {
        robot.inverseKinematics(l6, r6, vpColVector(), std::vector<unsigned int>{0, 1, 2});
      },
      dim, "index"));
  // Index out of range.
  const std::vector<vpImagePoint> l3(left.begin(), left.begin() + 3), r3(right.begin(), right.begin() + 3);
  EXPECT_TRUE(throwsProjective(
      [&] {
        robot.inverseKinematics(l3, r3, vpColVector(), std::vector<unsigned int>{0, 1, 7});
      },
      dim, "out of range"));
  // Too few markers: 2 markers fix at most 4 of 6 joints.
  const std::vector<vpImagePoint> l2(left.begin(), left.begin() + 2), r2(right.begin(), right.begin() + 2);
  EXPECT_TRUE(throwsProjective(
      [&] {
        robot.inverseKinematics(l2, r2, vpColVector(), std::vector<unsigned int>{0, 1});
      },
      vpProjectiveException::notEnoughPointsError, "markers"));
  // q0 of the wrong size, non-finite image.
  EXPECT_TRUE(throwsProjective([&] { robot.inverseKinematics(left, right, vpColVector(5, 0.0)); }, dim, "q"));
  std::vector<vpImagePoint> lNaN = left;
  lNaN[3].set_u(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(throwsProjective([&] { robot.inverseKinematics(lNaN, right); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  // Not calibrated.
  const vpProjectiveRobot empty(s.jointTypes());
  EXPECT_TRUE(throwsProjective([&] { empty.inverseKinematics(left, right); },
                               vpProjectiveException::notInitializedError, "not acquired"));
  // Noise-free at the zero reference from q0 = 0: exactly zero.
  const vpColVector q = robot.inverseKinematics(left, right);
  EXPECT_LT(toEigenV(q).cwiseAbs().maxCoeff(), 1e-9);
}
