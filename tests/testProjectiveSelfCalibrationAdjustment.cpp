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
  The metric bundle adjustment of vpProjectiveSelfCalibration over the acquisition and calibration frames
  (vpProjectiveRobot::addCalibrationFrame()), in the self-calibration study's worlds (random rigs of two cameras with
  skew and unequal focal lengths, apps/projective-self-calibration/calibration-world.h): exact without noise on the
  three arms; its standard deviations equal to those of a covariance computed here from a numeric Jacobian of an
  independent projection, and to the spread of the errors over noise draws; the suggested configurations shrink the
  largest uncertainty as predicted; frames kept by the model file, forgotten by a re-registration; bad input refused.
*/

#include <cmath>
#include <cstdio>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "calibration-world.h"
#include "information-bound.h"
#include "vpProjectiveRobotTestTools.h"
#include "vpProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{
typedef std::vector<vpProjectiveArmAcquisition::vpFrame> Frames;

//! A world of the study: an arm, a random skewed rig drawn from \e seed, the robot acquired with \e frames frames.
struct World {
  selfcal::StudyArm arm;
  selfcal::SkewedRig rig;
  vpProjectiveRobot robot;
  World(const std::string &name, unsigned int seed, double sigma, unsigned int frames)
      : arm(selfcal::makeArm(name)), rig(), robot()
  {
    vpUniRand rigRng(seed), viewRng(seed + 100);
    vpGaussRand noise(1.0, 0.0, static_cast<long>(seed + 200));
    rig = selfcal::randomRig(arm, rigRng);
    robot = selfcal::acquire(arm, rig, sigma, frames, 30.0, noise, viewRng);
  }
  Eigen::Matrix4d lMrTrue() const { return toEigen<4, 4>(rig.lMr()); }
  //! The markers at the zero reference in the left camera's frame.
  std::vector<Eigen::Vector3d> markersTrue() const
  {
    std::vector<Eigen::Vector3d> X;
    for (const vpColVector &wX : arm.arm.getMarkers(arm.qRef)) {
      const vpColVector lX = rig.wMl.inverse() * vpColVector({wX[0], wX[1], wX[2], 1.0});
      X.emplace_back(lX[0], lX[1], lX[2]);
    }
    return X;
  }
};

double angleOf(const Eigen::Matrix3d &R)
{
  return Eigen::AngleAxisd(R).angle();
}

} // namespace

/*
  Without noise, the acquisition and 5 frames give the true cameras (skew included), rig and markers to rounding, in
  the prismatic joint's unit for the R-R-P-R-R-R arm, with a unit baseline or a marker distance for the others.
*/
TEST(vpProjectiveSelfCalibration, NoiseFreeSkewedRigsGiveTheTruth)
{
  for (const char *name : {"puma", "viper850", "prismatic"}) {
    SCOPED_TRACE(name);
    const World w(name, 7, 0.0, 5);
    vpProjectiveSelfCalibration calibration(w.robot.getModel(), w.robot.getAcquisition().getFrames());
    ASSERT_EQ(calibration.getNumberOfFrames(), 18u);
    Eigen::Matrix3d Kl, Kr;
    Eigen::Matrix4d lMr;
    calibration.getMetricStereoRig(Kl, Kr, lMr);
    EXPECT_LT(relativeError(Kl, w.rig.Kl), 1e-7);
    EXPECT_LT(relativeError(Kr, w.rig.Kr), 1e-7);
    EXPECT_GT(std::abs(w.rig.Kl(0, 1)) + std::abs(w.rig.Kr(0, 1)), 1.0); // the cameras have skew
    const Eigen::Matrix4d truth = w.lMrTrue();
    EXPECT_LT(angleOf(lMr.topLeftCorner<3, 3>().transpose() * truth.topLeftCorner<3, 3>()), 1e-7);
    const Eigen::Vector3d b = lMr.topRightCorner<3, 1>(), bTrue = truth.topRightCorner<3, 1>();
    const bool prismatic = std::string(name) == "prismatic";
    EXPECT_LT((b - (prismatic ? bTrue : bTrue.normalized())).norm(), 1e-7 * bTrue.norm());
    // A ruler's distance between two markers gives every length in metres.
    const std::vector<Eigen::Vector3d> Xtrue = w.markersTrue();
    calibration.setScale(vpProjectiveSelfCalibration::SCALE_MARKER_DISTANCE, 2, 5, (Xtrue[2] - Xtrue[5]).norm());
    calibration.getMetricStereoRig(Kl, Kr, lMr);
    EXPECT_LT((lMr.topRightCorner<3, 1>() - bTrue).norm(), 1e-7 * bTrue.norm());
    const std::vector<Eigen::Vector3d> X = calibration.getMarkers();
    for (size_t j = 0; j < X.size(); ++j) {
      EXPECT_LT((X[j] - Xtrue[j]).norm(), 1e-7) << "marker " << j;
    }
    EXPECT_LT(calibration.getResidual(), 1e-6);
  }
}

/*
  The standard deviations are those of sigma^2 (J^T J)^-1 computed here from central differences of an independent
  projection (predict()) in a minimal parametrisation of its own (each unit axis and the axis' point moved in the
  plane normal to it), sigma^2 the residuals' sum over their number less the parameters': on the R-R-P-R-R-R arm
  (lengths in its encoder's unit) at 0.5 px, the acquisition and 10 frames.
*/
TEST(vpProjectiveSelfCalibration, DeviationsMatchANumericCovariance)
{
  const World w("prismatic", 3, 0.5, 10);
  const Frames frames = w.robot.getAcquisition().getFrames();
  const vpProjectiveSelfCalibration calibration(w.robot.getModel(), frames);
  ASSERT_TRUE(calibration.isObservable());
  Eigen::Matrix3d Kl, Kr;
  Eigen::Matrix4d lMr;
  calibration.getMetricStereoRig(Kl, Kr, lMr);
  selfcal::MetricModel estimate;
  estimate.k << Kl(0, 0), Kl(1, 1), Kl(0, 1), Kl(0, 2), Kl(1, 2), Kr(0, 0), Kr(1, 1), Kr(0, 1), Kr(0, 2), Kr(1, 2);
  estimate.lRr = lMr.topLeftCorner<3, 3>();
  estimate.b = lMr.topRightCorner<3, 1>();
  estimate.types = w.robot.getModel().jointTypes();
  calibration.getJointAxes(estimate.axis, estimate.point);
  estimate.X = calibration.getMarkers();
  estimate.qRef = w.robot.getModel().zeroReferenceJoints();
  // Parameters: 10 intrinsics, the rotation (3, left camera's axes), b (3), per joint 2 (+ 2 revolute), markers 3 each.
  const selfcal::MetricParameters parameters(estimate, false);
  const Eigen::VectorXd s0 = selfcal::predict(estimate, frames);
  Eigen::VectorXd observed(s0.size());
  Eigen::Index r = 0;
  for (const vpProjectiveArmAcquisition::vpFrame &f : frames) {
    for (size_t j = 0; j < f.s.size(); ++j) {
      if (f.seen[j]) {
        observed.segment<4>(r) = f.s[j];
        r += 4;
      }
    }
  }
  ASSERT_EQ(r, s0.size());
  const Eigen::MatrixXd J = selfcal::pixelJacobian(parameters, frames);
  const double sigma2 = (s0 - observed).squaredNorm() / static_cast<double>(s0.size() - parameters.size());
  EXPECT_NEAR(std::sqrt(sigma2), calibration.getNoiseLevel(), 1e-3 * calibration.getNoiseLevel());
  EXPECT_NEAR(std::sqrt(sigma2), 0.5, 0.05);
  const Eigen::MatrixXd S = sigma2 * (J.transpose() * J).inverse();
  const vpProjectiveSelfCalibration::vpUncertainty &u = calibration.getUncertainty();
  for (int e = 0; e < 5; ++e) {
    EXPECT_NEAR(u.left(e), std::sqrt(S(e, e)), 0.01 * u.left(e)) << "left intrinsic " << e;
    EXPECT_NEAR(u.right(e), std::sqrt(S(5 + e, 5 + e)), 0.01 * u.right(e)) << "right intrinsic " << e;
  }
  for (int e = 0; e < 3; ++e) {
    EXPECT_NEAR(u.rotation(e), std::sqrt(S(10 + e, 10 + e)), 0.01 * u.rotation(e)) << "rotation " << e;
    EXPECT_NEAR(u.translation(e), std::sqrt(S(13 + e, 13 + e)), 0.01 * u.translation(e)) << "translation " << e;
  }
}

/*
  The Cramer-Rao bound of apps/projective-self-calibration --bound (information-bound.h): its true model predicts the
  world's own projection (the simulator's Denavit-Hartenberg chain and the rig's cameras) to 1e-9 px; the adjustment's
  stated deviations on noisy images (0.5 px, the acquisition and 10 frames) are the bound of the same frames at the
  truth within 15 % (the adjustment is efficient: its covariance is the bound's, at its estimate and with the noise
  level estimated), on the three arms; the skew known never loosens the bound.
*/
TEST(vpProjectiveSelfCalibration, StatedDeviationsAreTheCramerRaoBound)
{
  for (const char *name : {"puma", "viper850", "prismatic"}) {
    SCOPED_TRACE(name);
    const World w(name, 13, 0.5, 10);
    const Frames frames = w.robot.getAcquisition().getFrames();
    const selfcal::MetricModel truth = selfcal::trueModel(w.arm, w.rig);
    const Eigen::VectorXd s = selfcal::predict(truth, frames);
    Eigen::Index r = 0;
    for (const vpProjectiveArmAcquisition::vpFrame &f : frames) {
      vpColVector q(static_cast<unsigned int>(f.q.size()));
      for (unsigned int i = 0; i < q.size(); ++i) {
        q[i] = f.q(i);
      }
      for (const vpColVector &wX : w.arm.arm.getMarkers(q)) {
        vpImagePoint left, right;
        w.rig.project(wX, left, right, 0.0);
        EXPECT_LT((s.segment<4>(r) - Eigen::Vector4d(left.get_u(), left.get_v(), right.get_u(), right.get_v()))
                      .cwiseAbs()
                      .maxCoeff(),
                  1e-9);
        r += 4;
      }
    }
    const vpProjectiveSelfCalibration calibration = selfcal::selfCalibration(w.robot, w.arm, frames);
    Eigen::Matrix3d Kl, Kr;
    Eigen::Matrix4d lMr;
    calibration.getMetricStereoRig(Kl, Kr, lMr);
    double stated[selfcal::PARAMETERS], bound[selfcal::PARAMETERS], skewKnown[selfcal::PARAMETERS];
    selfcal::statedDeviations(calibration.getUncertainty(), Kl, Kr, lMr.topRightCorner<3, 1>(), stated);
    const selfcal::MetricParameters parameters(truth, std::string(name) != "prismatic");
    const Eigen::MatrixXd J = selfcal::pixelJacobian(parameters, frames);
    selfcal::informationBound(parameters, J, 0.5, selfcal::NOTHING_KNOWN, bound);
    selfcal::informationBound(parameters, J, 0.5, selfcal::SKEW_KNOWN, skewKnown);
    for (int p = 0; p < selfcal::PARAMETERS; ++p) {
      testLog() << "[ measured ] " << selfcal::nameOf(selfcal::Parameter(p)) << ": stated " << stated[p] << ", bound "
                << bound[p] << std::endl;
      EXPECT_NEAR(stated[p], bound[p], 0.15 * bound[p]) << selfcal::nameOf(selfcal::Parameter(p));
      EXPECT_LE(skewKnown[p], bound[p] * (1.0 + 1e-9)) << selfcal::nameOf(selfcal::Parameter(p));
    }
    EXPECT_EQ(skewKnown[selfcal::SKEW], 0.0);
  }
}

/*
  The stated deviations describe the errors: over 16 noise draws on one world (the PUMA-like arm, the acquisition
  and 10 frames at 0.5 px), the spread of the errors of the focal lengths, principal points and rotation is within
  -40 % / +50 % of the mean stated deviation (16 draws estimate a deviation to about 18 %).
*/
TEST(vpProjectiveSelfCalibration, DeviationsMatchTheSpreadOverNoiseDraws)
{
  const selfcal::StudyArm arm = selfcal::makeArm("puma");
  vpUniRand rigRng(11);
  const selfcal::SkewedRig rig = selfcal::randomRig(arm, rigRng);
  const int kDraws = 16, kQuantities = 5; // left fx, left u0, right v0, rotation x and y
  Eigen::Matrix<double, kDraws, kQuantities> error, sigma;
  for (int d = 0; d < kDraws; ++d) {
    vpUniRand viewRng(5); // the same configurations, other noise
    vpGaussRand noise(1.0, 0.0, 300 + d);
    const vpProjectiveRobot robot = selfcal::acquire(arm, rig, 0.5, 10, 30.0, noise, viewRng);
    const vpProjectiveSelfCalibration calibration(robot.getModel(), robot.getAcquisition().getFrames());
    Eigen::Matrix3d Kl, Kr;
    Eigen::Matrix4d lMr;
    calibration.getMetricStereoRig(Kl, Kr, lMr);
    const Eigen::Matrix3d lRrTrue = toEigen<4, 4>(rig.lMr()).topLeftCorner<3, 3>();
    const Eigen::AngleAxisd e(Eigen::Matrix3d(lMr.topLeftCorner<3, 3>() * lRrTrue.transpose()));
    const vpProjectiveSelfCalibration::vpUncertainty &u = calibration.getUncertainty();
    error.row(d) << Kl(0, 0) - rig.Kl(0, 0), Kl(0, 2) - rig.Kl(0, 2), Kr(1, 2) - rig.Kr(1, 2), e.angle() * e.axis()(0),
        e.angle() * e.axis()(1);
    sigma.row(d) << u.left(0), u.left(3), u.right(4), u.rotation(0), u.rotation(1);
  }
  for (int c = 0; c < kQuantities; ++c) {
    const double spread = std::sqrt(error.col(c).squaredNorm() / kDraws), stated = sigma.col(c).mean();
    testLog() << "[ measured ] quantity " << c << ": spread " << spread << ", stated " << stated << std::endl;
    EXPECT_GT(spread, 0.6 * stated) << "quantity " << c;
    EXPECT_LT(spread, 1.5 * stated) << "quantity " << c;
  }
}

/*
  The suggested configurations: with the acquisition and 5 frames, 3 configurations within +-30 deg chosen among 150
  candidates; the predicted largest uncertainty falls with each, and once their images are added (the arm moved
  there), the largest uncertainty is below what it was and within 25 % of the prediction.
*/
TEST(vpProjectiveSelfCalibration, SuggestionsShrinkTheLargestUncertainty)
{
  World w("puma", 21, 0.5, 5);
  const vpProjectiveSelfCalibration before(w.robot.getModel(), w.robot.getAcquisition().getFrames());
  const double largest = before.getLargestUncertainty();
  vpColVector qmin(6), qmax(6);
  for (unsigned int i = 0; i < 6; ++i) {
    qmin[i] = w.arm.qRef[i] - vpMath::rad(30.0);
    qmax[i] = w.arm.qRef[i] + vpMath::rad(30.0);
  }
  std::vector<double> predicted;
  const std::vector<vpColVector> next =
      before.suggestConfigurations(3, qmin, qmax, w.rig.width, w.rig.height, &predicted, 150, 4);
  ASSERT_EQ(next.size(), 3u);
  ASSERT_EQ(predicted.size(), 3u);
  EXPECT_LT(predicted[0], largest);
  EXPECT_LT(predicted[1], predicted[0]);
  EXPECT_LT(predicted[2], predicted[1]);
  vpGaussRand noise(1.0, 0.0, 17);
  for (const vpColVector &q : next) {
    for (unsigned int i = 0; i < 6; ++i) {
      EXPECT_GE(q[i], qmin[i]);
      EXPECT_LE(q[i], qmax[i]);
    }
    std::vector<vpImagePoint> left, right;
    ASSERT_TRUE(w.rig.images(w.arm.arm.getMarkers(q), 0.5, noise, left, right)) << "a suggested view leaves the images";
    w.robot.addCalibrationFrame(q, left, right);
  }
  const vpProjectiveSelfCalibration after(w.robot.getModel(), w.robot.getAcquisition().getFrames());
  testLog() << "[ measured ] largest uncertainty " << largest << ", predicted " << predicted[2] << ", after "
            << after.getLargestUncertainty() << std::endl;
  EXPECT_LT(after.getLargestUncertainty(), largest);
  EXPECT_NEAR(after.getLargestUncertainty(), predicted[2], 0.25 * predicted[2]);
}

/*
  The robot's frames: added before or after calibrate(), used by getMetricStereoRig(), saved in the model file and
  read back (the same rig to rounding), forgotten by updateRig() (they show the rig before it moved).
*/
TEST(vpProjectiveSelfCalibration, RobotFramesModelFileAndReRegistration)
{
  World w("viper850", 5, 0.5, 6);
  EXPECT_EQ(w.robot.getAcquisition().getNumberOfCalibrationFrames(), 6u);
  vpMatrix Kl, Kr, Kl2, Kr2;
  vpHomogeneousMatrix lMr, lMr2;
  w.robot.getMetricStereoRig(Kl, Kr, lMr);
  Eigen::Matrix3d Ke, Kre;
  Eigen::Matrix4d M;
  vpProjectiveSelfCalibration(w.robot.getModel(), w.robot.getAcquisition().getFrames()).getMetricStereoRig(Ke, Kre, M);
  EXPECT_TRUE((toEigen<3, 3>(Kl) - Ke).norm() == 0.0);
  // Without the frames, another rig: getMetricStereoRig() does use them.
  const Frames all = w.robot.getAcquisition().getFrames();
  vpProjectiveSelfCalibration(w.robot.getModel(), Frames(all.begin(), all.begin() + 13)).getMetricStereoRig(Ke, Kre, M);
  EXPECT_GT((toEigen<3, 3>(Kl) - Ke).norm(), 1e-3);
  const std::string file = tempFile("selfcal");
  w.robot.saveModel(file);
  vpProjectiveRobot loaded;
  loaded.loadModel(file);
  std::remove(file.c_str());
  EXPECT_EQ(loaded.getAcquisition().getNumberOfCalibrationFrames(), 19u); // the acquisition's 13 and the 6 frames
  loaded.getMetricStereoRig(Kl2, Kr2, lMr2);
  EXPECT_LT(relativeError(toEigen<3, 3>(Kl2), toEigen<3, 3>(Kl)), 1e-12);
  EXPECT_LT(relativeError(toEigen<4, 4>(lMr2), toEigen<4, 4>(lMr)), 1e-12);
  // Frames after loadModel(): the markers are the model's.
  std::vector<vpImagePoint> left, right;
  vpGaussRand noise(1.0, 0.0, 3);
  ASSERT_TRUE(w.rig.images(w.arm.arm.getMarkers(w.arm.qRef), 0.5, noise, left, right));
  loaded.addCalibrationFrame(w.arm.qRef, left, right);
  EXPECT_EQ(loaded.getAcquisition().getNumberOfCalibrationFrames(), 20u);
  // A re-registration (the same rig seen from 3 configurations) forgets them: they show the rig before it moved.
  for (int k = 0; k < 3; ++k) {
    vpColVector q = w.arm.qRef;
    q[5] += vpMath::rad(10.0 * (k + 1));
    ASSERT_TRUE(w.rig.images(w.arm.arm.getMarkers(q), 0.5, noise, left, right));
    loaded.addRigObservation(q, left, right);
  }
  loaded.updateRig();
  EXPECT_EQ(loaded.getAcquisition().getNumberOfCalibrationFrames(), 0u);
  EXPECT_NO_THROW(loaded.getMetricStereoRig(Kl2, Kr2, lMr2)); // the re-registered model's upgrade
}

TEST(vpProjectiveSelfCalibration, BadInputsAreRefused)
{
  World w("puma", 2, 0.5, 0);
  vpProjectiveRobot &robot = w.robot;
  std::vector<vpImagePoint> left, right;
  vpGaussRand noise(1.0, 0.0, 3);
  ASSERT_TRUE(w.rig.images(w.arm.arm.getMarkers(w.arm.qRef), 0.5, noise, left, right));
  const int dimension = vpProjectiveException::dimensionError;
  EXPECT_TRUE(throwsProjective([&] { robot.addCalibrationFrame(vpColVector(5, 0.0), left, right); }, dimension,
                               "joint readings"));
  std::vector<vpImagePoint> fewer(left.begin(), left.end() - 1);
  EXPECT_TRUE(throwsProjective([&] { robot.addCalibrationFrame(w.arm.qRef, fewer, right); }, dimension, "matched"));
  EXPECT_TRUE(throwsProjective([&] { robot.addCalibrationFrame(w.arm.qRef, fewer, fewer); }, dimension, "same order"));
  std::vector<vpImagePoint> nan = left;
  nan[2].set_u(std::nan(""));
  EXPECT_TRUE(throwsProjective([&] { robot.addCalibrationFrame(w.arm.qRef, nan, right); },
                               vpProjectiveException::nonFiniteValueError, "finite"));
  EXPECT_EQ(robot.getAcquisition().getNumberOfCalibrationFrames(), 0u); // nothing recorded on error
  vpProjectiveRobot fresh(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  EXPECT_TRUE(throwsProjective([&] { fresh.addCalibrationFrame(w.arm.qRef, left, right); },
                               vpProjectiveException::notInitializedError, "setZeroReference"));
  vpProjectiveArmAcquisition acquisition = robot.getAcquisition();
  EXPECT_TRUE(throwsProjective(
      [&] {
        acquisition.addCalibrationFrame(w.arm.qRef, {100, 101}, fewer, fewer);
      },
      dimension, "id"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        acquisition.addCalibrationFrame(w.arm.qRef, {100, 101}, {left[0], left[1]}, {right[0], right[1]});
      },
      vpProjectiveException::notEnoughPointsError, "none"));

  // The adjustment: an empty model, frames of another model, the scale's markers, bounds of the suggestions.
  const Frames frames = robot.getAcquisition().getFrames();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveSelfCalibration(vpProjectiveArmModel(), frames); },
                               vpProjectiveException::notInitializedError, "empty"));
  Frames wrong = frames;
  wrong[3].s.pop_back();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveSelfCalibration(robot.getModel(), wrong); }, dimension, "markers"));
  vpProjectiveSelfCalibration empty;
  Eigen::Matrix3d K1, K2;
  Eigen::Matrix4d M;
  EXPECT_TRUE(throwsProjective([&] { empty.getMetricStereoRig(K1, K2, M); }, vpProjectiveException::notInitializedError,
                               "no calibration"));
  vpProjectiveSelfCalibration calibration(robot.getModel(), frames);
  EXPECT_TRUE(
      throwsProjective([&] { calibration.setScale(vpProjectiveSelfCalibration::SCALE_MARKER_DISTANCE, 0, 0, 0.1); },
                       dimension, "distinct"));
  EXPECT_TRUE(
      throwsProjective([&] { calibration.setScale(vpProjectiveSelfCalibration::SCALE_MARKER_DISTANCE, 0, 1, -0.1); },
                       vpProjectiveException::invalidValueError, "distance"));
  vpColVector qmax = w.arm.qRef;
  qmax[0] -= 0.1;
  EXPECT_TRUE(
      throwsProjective([&] { calibration.suggestConfigurations(1, w.arm.qRef, qmax, w.rig.width, w.rig.height); },
                       vpProjectiveException::invalidValueError, "bound"));
  EXPECT_TRUE(throwsProjective(
      [&] { calibration.suggestConfigurations(1, w.arm.qRef, vpColVector(3, 0.0), w.rig.width, w.rig.height); },
      dimension, "bounds"));
  // One frame: no covariance, infinite deviations, no suggestion.
  const vpProjectiveSelfCalibration one(robot.getModel(), Frames(1, frames[0]));
  EXPECT_FALSE(one.isObservable());
  EXPECT_TRUE(std::isinf(one.getUncertainty().left(0)));
  EXPECT_TRUE(throwsProjective([&] { one.suggestConfigurations(1, w.arm.qRef, w.arm.qRef, w.rig.width, w.rig.height); },
                               vpProjectiveException::degenerateConfigurationError, "covariance"));
}
