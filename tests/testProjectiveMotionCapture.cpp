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
  Tracking and motion capture over image sequences against the simulator's truth:
  - vpProjectiveMotionCapture on an arm moving along a joint trajectory the capture does not know, with a model
    acquired at the same noise: every frame captured, each joint's error at the per-frame floor
    sqrt(diag(sigma^2 (J^T J)^-1)) of the true stacked image Jacobian, a marker lost for some frames survived, joint
    velocities against the trajectory's;
  - vpProjectiveRigidBodyTracker on a rigid marker set: the displacement against H_PE^-1 T(t) H_PE, a lost marker,
    a jump recovered, the body velocity against the motion's.
*/

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveMotionCapture.h>
#include <visp3/projective/vpProjectiveRigidBodyTracker.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "vpNumericJacobian.h"
#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! A smooth joint trajectory (model joints, rad) within +-amplitude of the zero reference: sums of two sines.
vpColVector trajectory(double t, const std::vector<double> &amplitude)
{
  vpColVector q(static_cast<unsigned int>(amplitude.size()));
  for (unsigned int i = 0; i < q.size(); ++i) {
    q[i] = amplitude[i] * (0.6 * std::sin(0.7 * t + i) + 0.4 * std::sin(1.9 * t + 2.0 * i));
  }
  return q;
}

vpColVector trajectoryVelocity(double t, const std::vector<double> &amplitude)
{
  vpColVector qdot(static_cast<unsigned int>(amplitude.size()));
  for (unsigned int i = 0; i < qdot.size(); ++i) {
    qdot[i] = amplitude[i] * (0.6 * 0.7 * std::cos(0.7 * t + i) + 0.4 * 1.9 * std::cos(1.9 * t + 2.0 * i));
  }
  return qdot;
}

const unsigned int kVelocityWindow = 12;
} // namespace

/*
  200 frames at 0.5 px of the paper's arm moving within +-5 to +-30 deg of its zero reference (the 7 markers in view),
  captured with a model acquired at 0.5 px. Per joint, the capture error of each frame is divided by that frame's floor
  (the true stacked Jacobian of the 7 markers, numeric differences of the simulator's projections): an efficient
  estimator has a standardised error of RMS 1 and median |.| 0.67. The bound is RMS <= 1.25 on every joint (the model's
  own error, at the acquisition noise, adds to the floor). Markers 5 and 6 are lost on frames 50 to 69: the capture goes
  on with
  5. Joint velocities (derivative of a quadratic fitted to the last 12 frames, 25 Hz) against the trajectory's.
*/
TEST(vpProjectiveMotionCapture, ArmAtTheNoiseFloor)
{
  const ArmSetup s = pumaEyeToHand();
  const double sigma = 0.5;
  vpProjectiveRobot robot(s.jointTypes());
  vpGaussRand noise(sigma, 0.0, 21);
  // The acquisition averages 16 frames per pose (the arm stands still): its noise is sigma / 4.
  ASSERT_TRUE(s.acquire(robot, sigma / 4.0, noise));
  robot.calibrate();
  vpProjectiveMotionCapture capture(robot.getModel());
  capture.setVelocityWindow(kVelocityWindow);
  // The shoulder joints swing the markers through the 38 x 29 cm view with a long lever: smaller amplitudes there.
  const std::vector<double> amplitude = {vpMath::rad(6.0),  vpMath::rad(5.0),  vpMath::rad(6.0),
                                         vpMath::rad(20.0), vpMath::rad(20.0), vpMath::rad(30.0)};
  const double dt = 0.04;
  capture.setInitialJoints(trajectory(0.0, amplitude) + vpColVector(6, 0.02)); // near the first pose, not on it
  std::vector<std::vector<double>> standardised(6);
  double velocityError = 0.0, velocityNorm = 0.0, naiveError = 0.0;
  const size_t K = s.numberOfMarkers();
  std::vector<Eigen::VectorXd> captured;
  for (int f = 0; f < 200; ++f) {
    const double t = f * dt;
    const vpColVector qModel = trajectory(t, amplitude);
    std::vector<vpImagePoint> left, right;
    ASSERT_TRUE(s.images(s.armJoints(qModel), left, right, sigma, noise)) << "frame " << f;
    std::vector<bool> visible(K, true);
    if (f >= 50 && f < 70) {
      visible[5] = visible[6] = false;
    }
    ASSERT_NO_THROW(capture.capture(t, left, right, visible)) << "frame " << f;
    EXPECT_EQ(capture.getNumberOfTrackedMarkers(), (f >= 50 && f < 70) ? K - 2 : K);
    // The floor of this frame: the true Jacobian of the visible markers' images.
    auto images = [&](const Eigen::VectorXd &q) {
      vpColVector qv(6);
      for (unsigned int i = 0; i < 6; ++i) {
        qv[i] = q(i);
      }
      Eigen::VectorXd y(4 * K);
      for (size_t j = 0; j < K; ++j) {
        y.segment<4>(4 * static_cast<Eigen::Index>(j)) = s.imageOf(s.armJoints(qv), j);
      }
      return y;
    };
    Eigen::MatrixXd J = numericJacobian(images, toEigenV(qModel), 1e-4);
    for (size_t j = 0; j < K; ++j) {
      if (!visible[j]) {
        J.middleRows(4 * static_cast<Eigen::Index>(j), 4).setZero();
      }
    }
    const Eigen::VectorXd floor = (sigma * sigma * (J.transpose() * J).inverse()).diagonal().cwiseSqrt();
    const Eigen::VectorXd error = toEigenV(capture.getJoints()) - toEigenV(qModel);
    captured.push_back(toEigenV(capture.getJoints()));
    for (int i = 0; i < 6; ++i) {
      standardised[i].push_back(error(i) / floor(i));
    }
    if (f >= static_cast<int>(kVelocityWindow) && (f < 50 || f >= 70 + static_cast<int>(kVelocityWindow))) {
      velocityError += (capture.getJointVelocities() - trajectoryVelocity(t, amplitude)).sumSquare();
      velocityNorm += trajectoryVelocity(t, amplitude).sumSquare();
      // The two-frame difference, for comparison: the frames' errors divided by dt.
      const Eigen::VectorXd naive = (captured.back() - captured[captured.size() - 2]) / dt;
      naiveError += (naive - toEigenV(trajectoryVelocity(t, amplitude))).squaredNorm();
    }
  }
  testLog() << "[ measured ] motion capture, 200 frames at 0.5 px, error / floor per joint (RMS, median |.|):";
  for (int i = 0; i < 6; ++i) {
    double rms = 0.0;
    std::vector<double> magnitude;
    for (double z : standardised[i]) {
      rms += z * z / standardised[i].size();
      magnitude.push_back(std::abs(z));
    }
    rms = std::sqrt(rms);
    testLog() << " j" << i << " " << rms << ", " << median(magnitude);
    EXPECT_LT(rms, 1.25) << "joint " << i;
    EXPECT_LT(median(magnitude), 1.25 * 0.6745) << "joint " << i;
  }
  const double relativeVelocityError = std::sqrt(velocityError / velocityNorm);
  const double naiveRatio = std::sqrt(velocityError / naiveError);
  testLog() << "; velocity error " << relativeVelocityError << " of the RMS velocity (window " << kVelocityWindow
            << " frames), " << naiveRatio << " times that of a two-frame difference" << std::endl;
  // At the floor, the frames' errors dominate the velocity (its lag on this trajectory is checked noise-free below):
  // the fit over the window averages them out. For independent frame errors of equal spread the ratio to a two-frame
  // difference is sqrt((sum w^2 + (sum w)^2) dt^2 / 2) = 0.25 with 12 frames at 25 Hz (w the fit's weights); the
  // floor changes from frame to frame along the trajectory, which raises it.
  EXPECT_LT(naiveRatio, 0.5);
}

/*
  Noise-free frames: the capture recovers the joints to 1e-9 rad and the velocities (slope over 4 past frames at
  25 Hz) within the lag of a one-sided slope on this trajectory: 3 % of the RMS velocity.
*/
TEST(vpProjectiveMotionCapture, NoiseFreeJointsAndVelocities)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  vpProjectiveMotionCapture capture(robot.getModel());
  const std::vector<double> amplitude = {vpMath::rad(6.0),  vpMath::rad(5.0),  vpMath::rad(6.0),
                                         vpMath::rad(20.0), vpMath::rad(20.0), vpMath::rad(30.0)};
  const double dt = 0.04;
  double worst = 0.0, velocityError = 0.0, velocityNorm = 0.0;
  for (int f = 0; f < 100; ++f) {
    const double t = f * dt;
    const vpColVector qModel = trajectory(t, amplitude);
    std::vector<vpImagePoint> left, right;
    ASSERT_TRUE(s.images(s.armJoints(qModel), left, right));
    capture.capture(t, left, right);
    worst = std::max(worst, (capture.getJoints() - qModel).frobeniusNorm());
    if (f >= 4) {
      velocityError += (capture.getJointVelocities() - trajectoryVelocity(t, amplitude)).sumSquare();
      velocityNorm += trajectoryVelocity(t, amplitude).sumSquare();
    }
  }
  EXPECT_LT(worst, 1e-9);
  EXPECT_LT(std::sqrt(velocityError / velocityNorm), 0.03);
  testLog() << "[ measured ] noise-free capture: worst joint error " << worst << " rad, velocity error "
            << std::sqrt(velocityError / velocityNorm) << " of the RMS velocity" << std::endl;
}

TEST(vpProjectiveMotionCapture, BadInputs)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpProjectiveMotionCapture(robot.getModel(), {0, 99});
      },
      vpProjectiveException::dimensionError, "out of range"));
  const vpProjectiveArmModel empty;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveMotionCapture unusable(empty); },
                               vpProjectiveException::notInitializedError, "empty"));
  vpProjectiveMotionCapture capture(robot.getModel());
  std::vector<vpImagePoint> left, right;
  s.images(s.qRef, left, right);
  EXPECT_TRUE(throwsProjective([&] { capture.getJointVelocities(); }, vpProjectiveException::notInitializedError,
                               "two frames"));
  std::vector<vpImagePoint> l6(left.begin(), left.begin() + 6);
  EXPECT_TRUE(
      throwsProjective([&] { capture.capture(0.0, l6, right); }, vpProjectiveException::dimensionError, "left"));
  std::vector<bool> two(left.size(), false);
  two[0] = two[1] = true;
  EXPECT_TRUE(throwsProjective([&] { capture.capture(0.0, left, right, two); },
                               vpProjectiveException::notEnoughPointsError, "visible"));
  capture.capture(1.0, left, right);
  const vpColVector q = capture.getJoints();
  EXPECT_TRUE(
      throwsProjective([&] { capture.capture(1.0, left, right); }, vpProjectiveException::invalidValueError, "after"));
  EXPECT_LT((capture.getJoints() - q).frobeniusNorm(), 1e-15); // a failed frame changes nothing
  EXPECT_TRUE(throwsProjective([&] { capture.setInitialJoints(vpColVector(5, 0.0)); },
                               vpProjectiveException::dimensionError, "q0"));
}

namespace
{
struct TrackingStats {
  double medianError, worstError, medianVelocityError;
};

/*
  A rigid set of 7 markers (10 cm) screwing in front of the rig (0.4 rad/s about an axis through the scene, 2 cm/s
  along it) for 150 frames at 25 Hz and 0.5 px, tracked from its first frame: errors of the displacement against the
  truth H_PE^-1 T(t) H_PE (relative, in the frame whitened by the true points) and of the body velocity against the
  motion's twist (relative). Marker 2 is lost on frames 40 to 59; after frame 100 the body jumps by 0.5 s of motion
  (12 deg), which the warm start cannot follow.
*/
TrackingStats trackRigidBody(const vpMatrix &G, unsigned int velocityWindow)
{
  const Scene scene;
  vpUniRand rng(23);
  vpGaussRand noise(0.5, 0.0, 29);
  const std::vector<vpColVector> body = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.05, 7, 60.0);
  const Eigen::Vector3d w = scene.cameraDirection(randomDirection(rng));
  const Eigen::Vector3d p = scene.cameraPoint(Scene::fixation()).head<3>();
  const Eigen::Matrix4d Xi = vpMetricTwist::hat(Eigen::Vector3d(p.cross(w) * 0.4 + 0.02 * w), Eigen::Vector3d(0.4 * w));
  const vpHomogeneousMatrix wMl = scene.sim.get_wMl();
  auto imagesAt = [&](double t, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
    const Eigen::Matrix4d lT = expm(t * Xi);
    left.resize(body.size());
    right.resize(body.size());
    for (size_t j = 0; j < body.size(); ++j) {
      const Eigen::Vector4d N = lT * scene.cameraPoint(body[j]);
      vpColVector X(3);
      for (unsigned int i = 0; i < 3; ++i) {
        X[i] = wMl[i][0] * N(0) + wMl[i][1] * N(1) + wMl[i][2] * N(2) + wMl[i][3];
      }
      if (!scene.sim.project(X, left[j], right[j], 0.5, noise)) {
        return false;
      }
    }
    return true;
  };
  Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
  for (const vpColVector &X : body) {
    const Eigen::Vector4d M = scene.projectivePoint(X);
    C += M * M.transpose();
  }
  const Eigen::Matrix4d W = Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d>(C).operatorInverseSqrt(), Winv = W.inverse();
  std::vector<vpImagePoint> left, right;
  EXPECT_TRUE(imagesAt(0.0, left, right));
  vpProjectiveRigidBodyTracker tracker;
  tracker.init(scene.rig, left, right, 0.0);
  tracker.setProjectiveToMetric(G);
  tracker.setVelocityWindow(velocityWindow);
  std::vector<double> errors, velocityErrors;
  for (int f = 1; f <= 150; ++f) {
    const double t = f * 0.04 + (f > 100 ? 0.5 : 0.0);
    EXPECT_TRUE(imagesAt(t, left, right)) << "frame " << f;
    std::vector<bool> visible(body.size(), true);
    if (f >= 40 && f < 60) {
      visible[2] = false;
    }
    vpProjectiveDisplacement H;
    try {
      H = tracker.track(left, right, t, visible);
    } catch (const vpException &e) {
      ADD_FAILURE() << "frame " << f << ": " << e.getStringMessage();
      return TrackingStats{1.0, 1.0, 1.0};
    }
    const Eigen::Matrix4d truth = vpProjectiveDisplacement::normalize(scene.HpeInv * expm(t * Xi) * scene.Hpe);
    errors.push_back(relativeError(Eigen::Matrix4d(W * H.matrix() * Winv), Eigen::Matrix4d(W * truth * Winv)));
    if (f > static_cast<int>(velocityWindow) && (f <= 100 || f > 100 + static_cast<int>(velocityWindow))) {
      const Eigen::Matrix4d V = scene.Hpe * tracker.getVelocity().matrix() * scene.HpeInv;
      velocityErrors.push_back((V - Xi).norm() / Xi.norm());
    }
  }
  return TrackingStats{median(errors), *std::max_element(errors.begin(), errors.end()), median(velocityErrors)};
}
} // namespace

/*
  Projective tracking (15 degrees of freedom per frame) of 7 markers on 10 cm: the displacement's relative error is
  that of a single 7-marker homography at 0.5 px (a few percent, see testProjectiveDisplacementEstimate), every frame
  tracked through the lost marker and the jump; its velocity, a derivative of those errors, is noise. Rigid tracking
  with the metric upgrade (here H_PE itself; in practice an arm model's G) fits 6 degrees of freedom: its displacement
  error is several times smaller and its velocity (quadratic over 12 frames) within 15 % of the motion's.
*/
TEST(vpProjectiveRigidBodyTracker, FollowsARigidBody)
{
  const TrackingStats projective = trackRigidBody(vpMatrix(), 12);
  const Scene scene;
  const TrackingStats rigid = trackRigidBody(toVisp(scene.Hpe), 12);
  testLog() << "[ measured ] rigid-body tracking, 150 frames at 0.5 px, 7 markers: projective displacement error "
            << projective.medianError << " (median), " << projective.worstError << " (worst), velocity "
            << projective.medianVelocityError << "; rigid (metric G) " << rigid.medianError << ", " << rigid.worstError
            << ", velocity " << rigid.medianVelocityError << " (relative)" << std::endl;
  EXPECT_LT(projective.medianError, 0.1);
  EXPECT_LT(projective.worstError, 0.3);
  EXPECT_LT(rigid.medianError, projective.medianError / 3.0);
  EXPECT_LT(rigid.medianVelocityError, 0.15);
}

TEST(vpProjectiveRigidBodyTracker, BadInputs)
{
  const Scene scene;
  vpUniRand rng(31);
  const std::vector<vpColVector> body = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.05, 7, 60.0);
  std::vector<vpImagePoint> left, right;
  imagesOf(scene.sim, body, left, right);
  vpProjectiveRigidBodyTracker tracker;
  EXPECT_TRUE(
      throwsProjective([&] { tracker.track(left, right, 1.0); }, vpProjectiveException::notInitializedError, "init"));
  EXPECT_TRUE(throwsProjective([&] { tracker.init(vpProjectiveStereoRig(), left, right); },
                               vpProjectiveException::notInitializedError, "fundamental"));
  const std::vector<vpImagePoint> l4(left.begin(), left.begin() + 4), r4(right.begin(), right.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { tracker.init(scene.rig, l4, r4); }, vpProjectiveException::notEnoughPointsError,
                               "5 markers"));
  tracker.init(scene.rig, left, right, 0.0);
  EXPECT_TRUE(throwsProjective([&] { tracker.getVelocity(); }, vpProjectiveException::notInitializedError, "frame"));
  EXPECT_TRUE(
      throwsProjective([&] { tracker.track(l4, r4, 1.0); }, vpProjectiveException::dimensionError, "reference"));
  EXPECT_TRUE(
      throwsProjective([&] { tracker.track(left, right, 0.0); }, vpProjectiveException::invalidValueError, "after"));
  std::vector<bool> three(left.size(), false);
  three[0] = three[1] = three[2] = true;
  EXPECT_TRUE(throwsProjective([&] { tracker.track(left, right, 1.0, three); },
                               vpProjectiveException::notEnoughPointsError, "visible"));
  EXPECT_TRUE(throwsProjective([&] { tracker.setProjectiveToMetric(vpMatrix(4, 4, 0.0)); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
  EXPECT_TRUE(
      throwsProjective([&] { tracker.setVelocityWindow(0); }, vpProjectiveException::invalidValueError, "frame"));
  // A failed frame changes nothing: the next one is tracked as if it had not been given.
  const vpProjectiveDisplacement H = tracker.track(left, right, 1.0);
  EXPECT_LT((H.matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-6);
  // With the metric upgrade, 3 markers suffice.
  tracker.setProjectiveToMetric(toVisp(scene.Hpe));
  EXPECT_NO_THROW(tracker.track(left, right, 2.0, three));
}
