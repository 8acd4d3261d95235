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
  Tests of the arm floor's data and algorithms (vpProjectiveArmData, vpProjectiveKinematics), on the five setups of
  vpProjectiveRobotTestTools.h (eye-to-hand and eye-in-hand, revolute and mixed chains):
  - forwardKinematics() gives the model's H(q) (eq. (34)) and its inverse, one pass per call;
  - pointImages() gives the model's predicted pixels of a marker, and its Jacobian is imageJacobian() at H(q) X and
    the derivative of those pixels in q (numeric differentiation of forwardKinematics() and pointImages());
  - a data object that served one model and then serves another (re-acquired) one gives the new model's values, as
    a fresh data object does.
  The joint motions themselves (eq. (39), against (dH/dq_k) H^-1) and the point and image Jacobians against the
  simulator are checked in testProjectiveRobotModel.
*/

#include <gtest/gtest.h>

#include <visp3/projective/vpProjectiveArmData.h>

#include "vpNumericJacobian.h"
#include "vpProjectiveRobotTestTools.h"

using namespace vpProjectiveTest;

namespace
{
class ProjectiveArmData : public ::testing::TestWithParam<SetupCase>
{
};

INSTANTIATE_TEST_SUITE_P(Arms, ProjectiveArmData, ::testing::ValuesIn(kSetups),
                         [](const ::testing::TestParamInfo<SetupCase> &info) { return std::string(info.param.label); });

TEST_P(ProjectiveArmData, ForwardKinematicsGivesTheModelsDisplacement)
{
  const ArmSetup s = GetParam().make();
  const vpProjectiveArmModel model = calibratedRobot(s).getModel();
  vpUniRand rng(61);
  vpProjectiveArmData data;
  EXPECT_EQ(data.getPassCount(), 0u);
  for (int t = 0; t < 5; ++t) {
    const vpProjectiveArmModel::JointVector q = toEigenV(randomJoints(s, rng));
    vpProjectiveKinematics::forwardKinematics(model, data, q);
    EXPECT_EQ(data.getPassCount(), static_cast<unsigned long>(t + 1)) << "one pass per call";
    EXPECT_EQ(data.getJoints(), q);
    const Eigen::Matrix4d H = model.displacement(q);
    EXPECT_LT(relativeError(data.getDisplacement(), H), 1e-10) << s.name << ": eq. (34)";
    EXPECT_LT((data.getDisplacementInverse() * H - Eigen::Matrix4d::Identity()).norm(), 1e-8) << s.name;
  }
}

TEST_P(ProjectiveArmData, PointImagesAndTheirJacobian)
{
  const ArmSetup s = GetParam().make();
  const vpProjectiveArmModel model = calibratedRobot(s).getModel();
  vpUniRand rng(62);
  vpProjectiveArmData data;
  double worst = 0.0;
  for (int t = 0; t < 3; ++t) {
    const vpProjectiveArmModel::JointVector q = toEigenV(randomJoints(s, rng));
    vpProjectiveKinematics::forwardKinematics(model, data, q);
    for (unsigned int j = 0; j < model.markers().size(); ++j) {
      const Eigen::Vector4d &X = model.markers()[j];
      Eigen::Vector4d sData, sModel;
      vpProjectiveArmModel::PointJacobian J, Jat;
      ASSERT_TRUE(vpProjectiveKinematics::pointImages(model, data, X, sData, &J)) << s.name << " marker " << j;
      ASSERT_TRUE(model.predictMarker(j, model.displacement(q), sModel));
      EXPECT_LT((sData - sModel).norm(), 1e-8) << s.name << " marker " << j;
      ASSERT_TRUE(vpProjectiveKinematics::imageJacobian(model, data, data.getDisplacement() * X, Jat));
      EXPECT_EQ(J, Jat) << s.name << " marker " << j;
      // d s / d q by central differences, each side its own forward kinematics.
      const Eigen::MatrixXd Jfd = numericJacobian(
          [&](const Eigen::VectorXd &x) {
            vpProjectiveArmData dx;
            vpProjectiveKinematics::forwardKinematics(model, dx, x);
            Eigen::Vector4d sx;
            EXPECT_TRUE(vpProjectiveKinematics::pointImages(model, dx, X, sx));
            return Eigen::VectorXd(sx);
          },
          q, 1e-4);
      worst = std::max(worst, jacobianRelativeError(J, Jfd));
      EXPECT_TRUE(jacobianMatches(J, Jfd, 1e-6)) << s.name << " marker " << j;
    }
  }
  testLog() << "[ measured ] " << s.name << ": worst image Jacobian error against central differences " << worst
            << std::endl;
}

TEST_P(ProjectiveArmData, FollowsAnotherModel)
{
  // The generators' squares are kept between calls: a data object that served the noise-free model must give the
  // values of a model acquired with 0.5 px of noise (other generators) as a fresh object does, to the bit.
  const ArmSetup s = GetParam().make();
  const vpProjectiveArmModel first = calibratedRobot(s).getModel();
  const vpProjectiveArmModel second = calibratedRobot(s, 0.5, 7).getModel();
  ASSERT_FALSE(first.generator(0) == second.generator(0)) << "the two acquisitions gave the same model";
  vpUniRand rng(63);
  const vpProjectiveArmModel::JointVector q = toEigenV(randomJoints(s, rng));
  vpProjectiveArmData reused, fresh;
  vpProjectiveKinematics::forwardKinematics(first, reused, q);
  vpProjectiveKinematics::forwardKinematics(second, reused, q);
  vpProjectiveKinematics::forwardKinematics(second, fresh, q);
  EXPECT_EQ(reused.getDisplacement(), fresh.getDisplacement());
  EXPECT_EQ(reused.getDisplacementInverse(), fresh.getDisplacementInverse());
  for (unsigned int k = 0; k < second.getNumberOfJoints(); ++k) {
    EXPECT_EQ(reused.getJointMotions()[k], fresh.getJointMotions()[k]) << "joint " << k;
  }
}
} // namespace
