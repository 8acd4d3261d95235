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
  Metric self-calibration (vpProjectiveSelfCalibration, vpProjectiveRobot::getMetricStereoRig()) and the plane at
  infinity of an acquired model, against the simulator's truth: noise-free acquisitions of every test arm give the
  true intrinsics, rig and joint axes to rounding; at 0.5 px the errors are measured over seeds.
*/

#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
Eigen::Matrix3d intrinsics(const vpCameraParameters &cam)
{
  Eigen::Matrix3d K;
  K << cam.get_px(), 0.0, cam.get_u0(), 0.0, cam.get_py(), cam.get_v0(), 0.0, 0.0, 1.0;
  return K;
}

//! Angle (rad) between two rotations.
double rotationError(const Eigen::Matrix3d &R1, const Eigen::Matrix3d &R2)
{
  return Eigen::AngleAxisd(R1.transpose() * R2).angle();
}

//! Angle (rad) between two directions.
double directionError(const Eigen::Vector3d &a, const Eigen::Vector3d &b)
{
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/*!
  The acquisition as a user makes it: the images of the zero reference and of every trial (both ways), the
  fundamental matrix estimated from all of them, then the model. False if a marker left the view.
*/
bool acquireFromImages(const ArmSetup &s, vpProjectiveRobot &robot, double sigma, vpGaussRand &noise)
{
  std::vector<std::vector<vpImagePoint>> left(1), right(1);
  std::vector<vpColVector> q(1, vpColVector(s.n(), 0.0));
  bool ok = s.images(s.qRef, left[0], right[0], sigma, noise);
  for (unsigned int i = 0; i < s.n(); ++i) {
    for (int sign = -1; sign <= 1; sign += 2) {
      q.push_back(vpColVector(s.n(), 0.0));
      q.back()[i] = sign * s.trialAmounts[i];
      left.emplace_back();
      right.emplace_back();
      ok = s.images(s.armJoints(q.back()), left.back(), right.back(), sigma, noise) && ok;
    }
  }
  std::vector<vpImagePoint> allLeft, allRight;
  for (size_t k = 0; k < left.size(); ++k) {
    allLeft.insert(allLeft.end(), left[k].begin(), left[k].end());
    allRight.insert(allRight.end(), right[k].begin(), right[k].end());
  }
  vpProjectiveStereoRig rig;
  rig.estimate(allLeft, allRight, std::max(1.0, 4.0 * sigma));
  robot.setStereoRig(rig);
  robot.setRigMounting(s.mounting);
  robot.setZeroReference(left[0], right[0]);
  for (size_t k = 1; k < left.size(); ++k) {
    robot.addTrialMotion(q[k], left[k], right[k]);
  }
  return ok;
}

/*!
  The paper's arm with a 7th, prismatic joint that slides the gripper along its approach direction: the scale of the
  metric upgrade comes from its encoder (trials of +-4 cm; the other joints' are the paper's).
*/
ArmSetup pumaWithSlide()
{
  std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::pumaTable();
  dh.push_back({vpProjectiveJoint::PRISMATIC, 0.0, 0.0, 0.0, 0.0});
  const vpSimulatorArm arm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                           vpSimulatorArm::paperBasePose());
  ArmSetup s("PUMA with a slide", arm, vpColVector(7, 0.0), paperRigAtOrigin());
  for (unsigned int i = 0; i < 6; ++i) {
    s.trialAmounts.push_back(vpMath::rad(kPaperTrialDeg[i]));
  }
  s.trialAmounts.push_back(0.04);
  return s;
}

struct SetupCase {
  const char *label;
  ArmSetup (*make)();
};

class SelfCalibrationSetup : public ::testing::TestWithParam<SetupCase>
{
};
} // namespace

/*
  Noise-free: the true intrinsics (skew 0), the true rotation of the right camera in the left one, the true baseline
  (in encoder metres for an arm with a prismatic joint, of unit length otherwise, or scaled by a true marker
  distance), and the true joint axes in the left camera frame.
*/
TEST_P(SelfCalibrationSetup, NoiseFreeGivesTheTruth)
{
  const ArmSetup s = GetParam().make();
  const vpProjectiveRobot robot = calibratedRobot(s);
  vpMatrix Kl, Kr;
  vpHomogeneousMatrix lMr;
  robot.getMetricStereoRig(Kl, Kr, lMr);
  const Eigen::Matrix3d KlTrue = intrinsics(s.camLeft), KrTrue = intrinsics(s.camRight);
  EXPECT_LT((toEigen<3, 3>(Kl) - KlTrue).norm() / KlTrue.norm(), 1e-6);
  EXPECT_LT((toEigen<3, 3>(Kr) - KrTrue).norm() / KrTrue.norm(), 1e-6);
  const Eigen::Matrix4d lMrTrue = toEigen<4, 4>(s.rMl.inverse()), lMrEst = toEigen<4, 4>(lMr);
  EXPECT_LT(rotationError(lMrEst.topLeftCorner<3, 3>(), lMrTrue.topLeftCorner<3, 3>()), 1e-6);
  const Eigen::Vector3d b = lMrEst.topRightCorner<3, 1>(), bTrue = lMrTrue.topRightCorner<3, 1>();
  EXPECT_LT(directionError(b, bTrue), 1e-6);
  bool prismatic = false;
  for (unsigned int i = 0; i < s.n(); ++i) {
    prismatic = prismatic || s.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC;
  }
  const double expectedLength = prismatic ? bTrue.norm() : 1.0;
  EXPECT_NEAR(b.norm(), expectedLength, 1e-6 * expectedLength);
  // A known marker distance gives the true metric baseline with any arm.
  const std::vector<vpColVector> X = s.markersAt(s.qRef);
  const double d01 = (X[0] - X[1]).frobeniusNorm();
  vpProjectiveSelfCalibration calibration(robot.getModel(), robot.getAcquisition().getFrames());
  calibration.setScale(vpProjectiveSelfCalibration::SCALE_MARKER_DISTANCE, 0, 1, d01);
  Eigen::Matrix3d Kle, Kre;
  Eigen::Matrix4d lMre;
  calibration.getMetricStereoRig(Kle, Kre, lMre);
  const double metricBaseline = lMre.topRightCorner<3, 1>().norm();
  EXPECT_NEAR(metricBaseline, bTrue.norm(), 1e-6 * bTrue.norm());
  // Joint axes in the left camera frame, against the simulator's twists: unit direction (up to the sign of the
  // encoder), point on the axis (distance of the estimated point to the true axis).
  std::vector<Eigen::Vector3d> direction, point; // in the unit of getMetricStereoRig(), not of the marker distance
  vpProjectiveSelfCalibration(robot.getModel(), robot.getAcquisition().getFrames()).getJointAxes(direction, point);
  ASSERT_EQ(direction.size(), s.n());
  for (unsigned int i = 0; i < s.n(); ++i) {
    SCOPED_TRACE(::testing::Message() << "joint " << i);
    const Eigen::Matrix4d T = s.cameraTwist(i);
    const Eigen::Vector3d w(T(2, 1), T(0, 2), T(1, 0)), v = T.topRightCorner<3, 1>();
    const Eigen::Vector3d &d = direction[i];
    if (s.arm.getJointType(i) == vpProjectiveJoint::REVOLUTE) {
      EXPECT_LT(directionError(d, w), 1e-6);
      // The axis is {p : w x p = -v... }: the estimated point lies on it when (p - p0) is parallel to w.
      const Eigen::Vector3d p0 = w.cross(v) / w.squaredNorm();
      const Eigen::Vector3d &p = point[i];
      const double scale = prismatic ? 1.0 : 1.0 / bTrue.norm();
      EXPECT_LT(((p - scale * p0).cross(w.normalized())).norm(), 1e-6 * scale);
    } else {
      EXPECT_LT(directionError(d, v), 1e-6);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Arms, SelfCalibrationSetup,
                         ::testing::Values(SetupCase{"PumaEyeToHand", pumaEyeToHand},
                                           SetupCase{"MixedEyeToHand", mixedEyeToHand},
                                           SetupCase{"PumaEyeInHand", pumaEyeInHand},
                                           SetupCase{"MixedEyeInHand", mixedEyeInHand},
                                           SetupCase{"ViperEyeToHand", viperEyeToHand}),
                         [](const ::testing::TestParamInfo<SetupCase> &info) { return info.param.label; });

/*
  The plane at infinity of a model: the orbit height of every marker is unchanged by the model's displacements
  (pi^T H = pi^T exactly for the model's own H, to rounding), and proportional to the true one (H_PE M)_4.
*/
TEST(vpProjectiveArmModel, OrbitHeightIsInvariant)
{
  const ArmSetup s = pumaEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  vpGaussRand noise(0.5, 0.0, 3);
  ASSERT_TRUE(s.acquire(robot, 0.5, noise));
  robot.calibrate();
  const vpProjectiveArmModel &model = robot.getModel();
  vpUniRand rng(5);
  for (int k = 0; k < 20; ++k) {
    vpProjectiveArmModel::JointVector q(6);
    for (int i = 0; i < 6; ++i) {
      q(i) = rng.uniform(-1.0, 1.0);
    }
    const Eigen::Matrix4d H = model.displacement(q);
    for (const Eigen::Vector4d &M : model.markers()) {
      EXPECT_NEAR(model.orbitHeight(H * M), model.orbitHeight(M), 1e-9 * std::abs(model.orbitHeight(M)));
    }
  }
  // Noise-free: proportional to the true orbit height (H_PE M)_4, the ratio being G's similarity scale.
  vpProjectiveRobot exact(s.jointTypes());
  ASSERT_TRUE(s.acquire(exact, 0.0, noise));
  exact.calibrate();
  const Eigen::Matrix4d Hpe = s.Hpe(exact.getStereoRig());
  const std::vector<Eigen::Vector4d> &M = exact.getModel().markers();
  const double ratio = exact.getModel().orbitHeight(M[0]) / (Hpe * M[0])(3);
  for (const Eigen::Vector4d &Mj : M) {
    EXPECT_NEAR(exact.getModel().orbitHeight(Mj) / (Hpe * Mj)(3), ratio, 1e-8 * std::abs(ratio));
  }
}

/*
  0.5 px acquisitions, the fundamental matrix estimated from the acquisition's images as a user does, of the paper's
  arm (revolute only: unit baseline), of the same arm with a slide (its prismatic joint gives the scale), and of the
  RPR arm, whose small trials are reported only: errors of the focal lengths, principal points, rotation, baseline
  direction and length over 20 seeds. The bounds are focal lengths within 2 %, rotation within 2 deg, baseline
  direction within 3 deg, baseline length within 2 % with a prismatic joint (medians; the worst seed is printed).
*/
TEST(vpProjectiveSelfCalibration, AccuracyAtHalfAPixel)
{
  for (const ArmSetup &s : {pumaEyeToHand(), pumaWithSlide(), mixedEyeToHand()}) {
    SCOPED_TRACE(s.name);
    std::vector<double> focal, principal, rotation, direction, length;
    for (unsigned int seed = 1; seed <= 20; ++seed) {
      vpProjectiveRobot robot(s.jointTypes());
      vpGaussRand noise(0.5, 0.0, seed);
      ASSERT_TRUE(acquireFromImages(s, robot, 0.5, noise));
      robot.calibrate();
      vpMatrix Kl, Kr;
      vpHomogeneousMatrix lMr;
      robot.getMetricStereoRig(Kl, Kr, lMr);
      const Eigen::Matrix3d K[2] = {toEigen<3, 3>(Kl), toEigen<3, 3>(Kr)};
      const Eigen::Matrix3d Ktrue[2] = {intrinsics(s.camLeft), intrinsics(s.camRight)};
      double f = 0.0, c = 0.0;
      for (int cam = 0; cam < 2; ++cam) {
        for (int a = 0; a < 2; ++a) {
          f = std::max(f, std::abs(K[cam](a, a) / Ktrue[cam](a, a) - 1.0));
          c = std::max(c, std::abs(K[cam](a, 2) - Ktrue[cam](a, 2)));
        }
      }
      const Eigen::Matrix4d lMrTrue = toEigen<4, 4>(s.rMl.inverse()), lMrEst = toEigen<4, 4>(lMr);
      focal.push_back(f);
      principal.push_back(c);
      rotation.push_back(vpMath::deg(rotationError(lMrEst.topLeftCorner<3, 3>(), lMrTrue.topLeftCorner<3, 3>())));
      direction.push_back(vpMath::deg(directionError(lMrEst.topRightCorner<3, 1>(), lMrTrue.topRightCorner<3, 1>())));
      length.push_back(std::abs(lMrEst.topRightCorner<3, 1>().norm() / lMrTrue.topRightCorner<3, 1>().norm() - 1.0));
    }
    auto median = [](std::vector<double> x) {
      std::sort(x.begin(), x.end());
      return 0.5 * (x[(x.size() - 1) / 2] + x[x.size() / 2]);
    };
    auto worst = [](const std::vector<double> &x) { return *std::max_element(x.begin(), x.end()); };
    testLog() << "[ measured ] " << s.name << ", 0.5 px, 20 seeds (median / worst): focal " << 100 * median(focal)
              << " / " << 100 * worst(focal) << " %, principal point " << median(principal) << " / " << worst(principal)
              << " px, rotation " << median(rotation) << " / " << worst(rotation) << " deg, baseline direction "
              << median(direction) << " / " << worst(direction) << " deg, length " << 100 * median(length) << " / "
              << 100 * worst(length) << " %" << std::endl;
    if (s.name.find("RPR") != std::string::npos) {
      continue; // reported: its trials (12 deg, 4 cm, 40 deg) are too small for a metric upgrade this accurate
    }
    EXPECT_LT(median(focal), 0.02);
    EXPECT_LT(median(rotation), 2.0);
    EXPECT_LT(median(direction), 3.0);
    if (s.name.find("slide") != std::string::npos) {
      EXPECT_LT(median(length), 0.02);
    }
  }
}

TEST(vpProjectiveSelfCalibration, BadInputs)
{
  const vpProjectiveArmModel empty;
  Eigen::Matrix3d Kl, Kr;
  Eigen::Matrix4d lMr;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveSelfCalibration::metricStereoRig(empty, Kl, Kr, lMr); },
                               vpProjectiveException::notInitializedError, "empty"));
  const ArmSetup s = pumaEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  vpMatrix K1, K2;
  vpHomogeneousMatrix M;
  EXPECT_TRUE(throwsProjective([&] { robot.getMetricStereoRig(K1, K2, M); }, vpProjectiveException::notInitializedError,
                               "calibrate"));
  vpGaussRand noise(1.0, 0.0, 1);
  ASSERT_TRUE(s.acquire(robot, 0.0, noise));
  robot.calibrate();
  const auto scaled = [&](unsigned int markerA, unsigned int markerB, double distance) {
    vpProjectiveSelfCalibration calibration(robot.getModel(), robot.getAcquisition().getFrames());
    calibration.setScale(vpProjectiveSelfCalibration::SCALE_MARKER_DISTANCE, markerA, markerB, distance);
    calibration.getMetricStereoRig(Kl, Kr, lMr);
  };
  EXPECT_TRUE(throwsProjective([&] { scaled(0, 0, 0.1); }, vpProjectiveException::dimensionError, "distinct"));
  EXPECT_TRUE(throwsProjective([&] { scaled(0, 99, 0.1); }, vpProjectiveException::dimensionError, "markers"));
  EXPECT_TRUE(throwsProjective([&] { scaled(0, 1, -0.1); }, vpProjectiveException::invalidValueError, "distance"));
}
