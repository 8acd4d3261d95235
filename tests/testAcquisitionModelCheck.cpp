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
  The model check of vpProjectiveArmAcquisition::calibrate() (vpProjectiveModelCheck) on the four arms of
  vpModelCheckTestTools.h: correct acquisitions pass the gate with the noise measured on their own images; the joint
  types are identified from a joint count alone; a declared type the trials contradict, readings in degrees, a second
  joint moving during a trial and markers swapped are refused with that cause ranked first and named. The Monte-Carlo
  version is testAcquisitionModelCheckStudy (label study).
*/

#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveModelCheck.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>

#include "vpModelCheckTestTools.h"

using namespace vpProjectiveTest;

namespace
{
bool contains(const std::string &text, const std::string &word)
{
  return text.find(word) != std::string::npos;
}

//! The first (likeliest) cause of the robot's last refused calibration.
vpProjectiveModelCheck::vpDiagnosis firstCause(const vpProjectiveRobot &robot)
{
  const vpProjectiveModelCheck &check = robot.getAcquisition().getModelCheck();
  EXPECT_FALSE(check.getCauses().empty());
  return check.getCauses().empty() ? vpProjectiveModelCheck::vpDiagnosis() : check.getCauses().front();
}
} // namespace

/*
  Right acquisitions pass on every arm, at 0.2 and 1 px: the noise measured against the epipolar geometry is within
  30 % of the true one (91 pairs; the trimmed mean's spread is about 8 %), the residual below the limit, the joint
  types as declared.
*/
TEST(AcquisitionModelCheck, AcceptsRightAcquisitionsOfEveryArm)
{
  for (const ArmCase &arm : kCheckArms) {
    const ArmSetup s = arm.make();
    for (double sigma : {0.2, 1.0}) {
      vpProjectiveRobot robot(s.jointTypes());
      ASSERT_TRUE(acquireWithMistakes(s, robot, sigma, 3)) << arm.label;
      ASSERT_NO_THROW(robot.calibrate()) << arm.label << " at " << sigma
                                         << " px: " << robot.getAcquisition().getModelCheck().getMessage();
      const vpProjectiveModelCheck &check = robot.getAcquisition().getModelCheck();
      EXPECT_TRUE(check.isChecked() && check.isAccepted()) << arm.label;
      EXPECT_NEAR(check.getEpipolarNoise(), sigma, 0.3 * sigma) << arm.label;
      EXPECT_DOUBLE_EQ(check.getLimit(), std::max(3.0 * check.getNoise(), 0.5));
      EXPECT_LT(check.getResidual(), check.getLimit()) << arm.label;
      EXPECT_DOUBLE_EQ(check.getResidual(), robot.getAcquisition().getCalibrationResidual());
      ASSERT_EQ(check.getJoints().size(), s.n());
      for (unsigned int i = 0; i < s.n(); ++i) {
        EXPECT_EQ(check.getJoints()[i].type, s.jointTypes()[i]) << arm.label << " joint " << i;
        EXPECT_FALSE(check.getJoints()[i].contradicted) << arm.label << " joint " << i;
        EXPECT_LT(check.getJoints()[i].residual, check.getLimit()) << arm.label << " joint " << i;
      }
      EXPECT_TRUE(check.getCauses().empty());
      EXPECT_TRUE(contains(check.getMessage(), "accepted")) << check.getMessage();
    }
  }
}

//! From a joint count alone the types of every arm come out right, and the model fits at the noise level.
TEST(AcquisitionModelCheck, IdentifiesJointTypesFromJointCount)
{
  for (const ArmCase &arm : kCheckArms) {
    const ArmSetup s = arm.make();
    vpProjectiveRobot robot(s.n());
    EXPECT_THROW(robot.getJointType(0), vpProjectiveException);
    ASSERT_TRUE(acquireWithMistakes(s, robot, 0.5, 5)) << arm.label;
    ASSERT_NO_THROW(robot.calibrate()) << arm.label << ": " << robot.getAcquisition().getModelCheck().getMessage();
    EXPECT_FALSE(robot.getAcquisition().hasDeclaredJointTypes());
    for (unsigned int i = 0; i < s.n(); ++i) {
      EXPECT_EQ(robot.getJointType(i), s.jointTypes()[i]) << arm.label << " joint " << i;
      const vpProjectiveModelCheck::vpJointTypeFit &j = robot.getAcquisition().getModelCheck().getJoints()[i];
      EXPECT_FALSE(j.declared);
      // A joint tried both ways: the type kept fits better (evidence > 0).
      EXPECT_TRUE(std::isnan(j.evidence) || j.evidence > 0.0) << arm.label << " joint " << i;
    }
    EXPECT_LT(robot.getAcquisition().getCalibrationResidual(), 0.5);
  }
}

/*
  The trial: an Afma6-like gantry declared as 6 revolute joints. Refused, the joint types ranked first, naming
  the three slides, and the model with them prismatic fits within the limit.
*/
TEST(AcquisitionModelCheck, RefusesGantryDeclaredRevoluteAndNamesTheSlides)
{
  const ArmSetup s = gantryEyeToHand();
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.3, 7));
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError) << message;
  EXPECT_FALSE(robot.isCalibrated());
  const vpProjectiveModelCheck &check = robot.getAcquisition().getModelCheck();
  EXPECT_TRUE(check.isChecked());
  EXPECT_FALSE(check.isAccepted());
  EXPECT_EQ(check.getMessage(), message.substr(message.find(": ") + 2));
  const vpProjectiveModelCheck::vpDiagnosis first = firstCause(robot);
  EXPECT_EQ(first.cause, vpProjectiveModelCheck::CAUSE_JOINT_TYPE) << message;
  EXPECT_TRUE(first.likely);
  EXPECT_LT(first.residualIfFixed, check.getLimit());
  for (unsigned int i = 0; i < 3; ++i) {
    EXPECT_TRUE(check.getJoints()[i].contradicted) << "joint " << i;
    EXPECT_TRUE(contains(first.finding, "joint " + std::to_string(i) + " (declared revolute) slides")) << message;
    EXPECT_LT(check.getJoints()[i].residualPrismatic, check.getJoints()[i].residualRevolute);
  }
  for (unsigned int i = 3; i < 6; ++i) {
    EXPECT_FALSE(check.getJoints()[i].contradicted) << "joint " << i;
  }
  EXPECT_TRUE(contains(message, "PRISMATIC")) << message;
}

//! A revolute joint declared prismatic (the PUMA's joint 3) is named: it turns.
TEST(AcquisitionModelCheck, NamesARevoluteJointDeclaredPrismatic)
{
  const ArmSetup s = pumaEyeToHand();
  vpProjectiveRobot robot(withOtherType(s, 3));
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.5, 11));
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError);
  const vpProjectiveModelCheck::vpDiagnosis first = firstCause(robot);
  EXPECT_EQ(first.cause, vpProjectiveModelCheck::CAUSE_JOINT_TYPE) << message;
  EXPECT_EQ(first.joint, 3);
  EXPECT_TRUE(contains(first.finding, "joint 3 (declared prismatic) turns")) << first.finding;
  EXPECT_TRUE(contains(first.fix, "joint 3 REVOLUTE")) << first.fix;
}

//! Revolute readings in degrees: the units ranked first, the joints named, the model with radians within the limit.
TEST(AcquisitionModelCheck, NamesReadingsInDegrees)
{
  const ArmSetup s = pumaEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  ASSERT_TRUE(
      acquireWithMistakes(s, robot, 0.5, 13, [](unsigned int, UserTrial &t) { t.amount = vpMath::deg(t.amount); }));
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError);
  const vpProjectiveModelCheck::vpDiagnosis first = firstCause(robot);
  EXPECT_EQ(first.cause, vpProjectiveModelCheck::CAUSE_READING_UNITS) << message;
  EXPECT_TRUE(first.likely);
  EXPECT_LT(first.residualIfFixed, robot.getAcquisition().getModelCheck().getLimit());
  EXPECT_TRUE(contains(first.finding, "degrees")) << first.finding;
  EXPECT_TRUE(contains(first.fix, "vpMath::rad()")) << first.fix;
}

//! Joint 4 also moved by 6 deg during trial 6 (joint 3's first): that trial and joint 4 are named.
TEST(AcquisitionModelCheck, NamesASecondJointMovingDuringATrial)
{
  const ArmSetup s = pumaEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.3, 17, [](unsigned int k, UserTrial &t) {
    if (k == 6) {
      t.qTrue[4] += vpMath::rad(6.0);
    }
  }));
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError);
  const vpProjectiveModelCheck::vpDiagnosis first = firstCause(robot);
  EXPECT_EQ(first.cause, vpProjectiveModelCheck::CAUSE_SECOND_JOINT) << message;
  EXPECT_EQ(first.trial, 6);
  EXPECT_EQ(first.joint, 3);
  EXPECT_EQ(first.other, 4);
  EXPECT_TRUE(contains(first.finding, "if joint 4 also moved, by 6")) << first.finding;
}

//! Markers 1 and 5 exchanged in both images of trial 3: the swap ranked first, naming the trial and the markers.
TEST(AcquisitionModelCheck, NamesMarkersSwappedBetweenFrames)
{
  const ArmSetup s = viperEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.3, 19, nullptr, [](unsigned int k, UserTrial &t) {
    if (k == 3) {
      std::swap(t.left[1], t.left[5]);
      std::swap(t.right[1], t.right[5]);
    }
  }));
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError);
  const vpProjectiveModelCheck::vpDiagnosis first = firstCause(robot);
  EXPECT_EQ(first.cause, vpProjectiveModelCheck::CAUSE_MARKERS_SWAPPED) << message;
  EXPECT_EQ(first.trial, 3);
  EXPECT_EQ(first.marker, 1);
  EXPECT_EQ(first.other, 5);
}

//! Marker 2's right image is marker 6's in trial 8: its left and right images do not meet; named by the epipolar gap.
TEST(AcquisitionModelCheck, NamesMarkersSwappedBetweenLeftAndRightImages)
{
  const ArmSetup s = rrprrrEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.3, 23, nullptr, [](unsigned int k, UserTrial &t) {
    if (k == 8) {
      std::swap(t.right[2], t.right[6]);
    }
  }));
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError);
  const vpProjectiveModelCheck::vpDiagnosis first = firstCause(robot);
  EXPECT_EQ(first.cause, vpProjectiveModelCheck::CAUSE_MARKERS_SWAPPED) << message;
  EXPECT_EQ(first.trial, 8);
  EXPECT_TRUE(first.marker == 2 || first.marker == 6) << first.finding;
}

/*
  The settings: a given noise raises the limit (never lowers it below the images' own), a tolerance of 0 accepts the
  gantry declared revolute (its joint types still reported as contradicted), bad values are refused, and a refused
  calibration leaves the robot as it was.
*/
TEST(AcquisitionModelCheck, SettingsAndStateOnRefusal)
{
  const ArmSetup s = gantryEyeToHand();
  vpProjectiveArmAcquisition acquisition(std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
  EXPECT_THROW(acquisition.setImageNoise(-1.0), vpProjectiveException);
  EXPECT_THROW(acquisition.setImageNoise(std::nan("")), vpProjectiveException);
  EXPECT_THROW(acquisition.setResidualTolerance(-2.0), vpProjectiveException);
  EXPECT_THROW(vpProjectiveArmAcquisition(0u), vpProjectiveException);
  EXPECT_THROW(vpProjectiveRobot(vpProjectiveArmModel::maxJoints + 1), vpProjectiveException);
  EXPECT_FALSE(acquisition.getModelCheck().isChecked());

  vpProjectiveRobot right(s.jointTypes());
  ASSERT_TRUE(acquireWithMistakes(s, right, 0.3, 29));
  right.calibrate();
  const double residual = right.getAcquisition().getCalibrationResidual();
  vpProjectiveRobot wrong(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  ASSERT_TRUE(acquireWithMistakes(s, wrong, 0.3, 29));
  EXPECT_THROW(wrong.calibrate(), vpProjectiveException);
  EXPECT_FALSE(wrong.isCalibrated());
  EXPECT_EQ(wrong.getAcquisition().getCalibrationResidual(), 0.0); // as before the refused calibration

  vpProjectiveArmAcquisition lenient = wrong.getAcquisition();
  lenient.setResidualTolerance(0.0);
  const vpProjectiveArmModel model = lenient.calibrate();
  EXPECT_TRUE(lenient.getModelCheck().isAccepted());
  EXPECT_TRUE(lenient.getModelCheck().getJoints()[0].contradicted);
  EXPECT_GT(lenient.getCalibrationResidual(), 2.0 * residual); // 5 cm slides: about 3 times (0.90 / 0.27 px)
  EXPECT_EQ(model.jointTypes(), lenient.getJointTypes());

  vpProjectiveArmAcquisition given = right.getAcquisition();
  given.setImageNoise(2.0);
  given.calibrate();
  EXPECT_DOUBLE_EQ(given.getModelCheck().getNoise(), 2.0);
  EXPECT_DOUBLE_EQ(given.getModelCheck().getLimit(), 6.0);
  given.setImageNoise(0.01);
  given.calibrate();
  EXPECT_DOUBLE_EQ(given.getModelCheck().getNoise(), given.getModelCheck().getEpipolarNoise());
}

//! The procedure's path to a robot of a joint count: setCalibration() takes the identified types.
TEST(AcquisitionModelCheck, RobotOfJointCountTakesAnIdentifiedCalibration)
{
  const ArmSetup s = rrprrrEyeToHand();
  vpProjectiveRobot robot(s.n());
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.3, 31));
  vpProjectiveArmAcquisition acquisition = robot.getAcquisition();
  const vpProjectiveArmModel model = acquisition.calibrate();
  robot.setCalibration(acquisition, model, acquisition.getCalibrationResidual());
  EXPECT_TRUE(robot.isCalibrated());
  EXPECT_EQ(robot.getJointType(2), vpProjectiveRobot::PRISMATIC);
  vpProjectiveRobot declared(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  EXPECT_THROW(declared.setCalibration(acquisition, model, 0.1), vpProjectiveException);
}

//! The session path (visp-projective calibrate): a gantry session recorded with 6 revolute joints is refused likewise.
TEST(AcquisitionModelCheck, SessionCalibrationGoesThroughTheSameGate)
{
  const ArmSetup s = gantryEyeToHand();
  TemporaryFolder tmp;
  Recording rec;
  {
    vpProjectiveSessionWriter writer(tmp / "session",
                                     std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE));
    vpGaussRand noise(1.0, 0.0, 37);
    ASSERT_TRUE(recordFrame(s, writer, rec, vpProjectiveSession::ZERO, s.qRef, 0.3, noise));
    for (unsigned int i = 0; i < s.n(); ++i) {
      for (int sign = -1; sign <= 1; sign += 2) {
        vpColVector q = s.qRef;
        q[i] += sign * s.trialAmounts[i];
        ASSERT_TRUE(recordFrame(s, writer, rec, vpProjectiveSession::TRIAL, q, 0.3, noise));
      }
    }
  }
  vpProjectiveSessionCalibration calibration(recordedMarkers(std::make_shared<Recording>(rec)));
  std::string message;
  EXPECT_EQ(codeOf([&]() { calibration.calibrate(vpProjectiveSession::read(tmp / "session")); }, message),
            vpProjectiveException::modelRejectedError);
  EXPECT_TRUE(contains(message, "joint 1 (declared revolute) slides")) << message;
  EXPECT_EQ(message.find('\n'), std::string::npos); // one line for the command-line tool
}
