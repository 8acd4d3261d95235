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
  A camera or the whole rig moved (issue 12, points 3, 4 and 6): the general camera pair of vpProjectiveStereoRig,
  the re-registration of vpProjectiveRobot (addRigObservation(), updateRig(), getPredictionError()) and its model
  file, SERVO_MODEL_MISMATCH, the task's re-expressed s*, the bad inputs, and a seeded Monte-Carlo of bumps at 0.5 px
  whose figures are printed as "[ measured ]" lines.
*/

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRigRegistration.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpModelFileChecksum.h"
#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
const double kSigma = 0.5; // pixels

//! True if \e f throws a vpProjectiveException of \e code whose message contains \e text.
template <typename F> bool throwsWith(F f, int code, const std::string &text)
{
  try {
    f();
  } catch (const vpProjectiveException &e) {
    const bool ok = e.getCode() == code && e.getStringMessage().find(text) != std::string::npos;
    if (!ok) {
      std::cout << "unexpected error " << e.getCode() << ": " << e.getStringMessage() << std::endl;
    }
    return ok;
  } catch (...) {
    return false;
  }
  return false;
}

enum BumpKind { BUMP_LEFT, BUMP_RIGHT, BUMP_RIG };

const char *bumpName(BumpKind kind)
{
  return kind == BUMP_LEFT ? "left camera" : (kind == BUMP_RIGHT ? "right camera" : "whole rig");
}

/*!
  \e s with a camera (or the rig) moved by 1-3 deg about a random axis and 0.5-2 cm along a random direction, in the
  moved camera's frame (the rig's left camera for the whole rig).
*/
ArmSetup bumped(const ArmSetup &s, BumpKind kind, vpUniRand &rng)
{
  const double angle = vpMath::rad(rng.uniform(1.0, 3.0));
  const double length = rng.uniform(0.005, 0.02);
  const vpColVector axis = randomDirection(rng), direction = randomDirection(rng);
  const vpHomogeneousMatrix d(vpTranslationVector(length * direction[0], length * direction[1], length * direction[2]),
                              vpThetaUVector(angle * axis[0], angle * axis[1], angle * axis[2]));
  ArmSetup b = s;
  if (kind == BUMP_LEFT) {
    b.wMl = s.wMl * d; // the right camera stays: wMr = wMl rMl^-1 unchanged
    b.rMl = s.rMl * d;
  } else if (kind == BUMP_RIGHT) {
    b.rMl = d.inverse() * s.rMl; // wMr <- wMr d
  } else {
    b.wMl = s.wMl * d;
  }
  return b;
}

//! Model joints drawn by \e draw until every marker is in view in all \e setups (\e fallback if none in 100000 draws).
vpColVector drawInView(const std::vector<const ArmSetup *> &setups, const std::function<vpColVector()> &draw,
                       const vpColVector &fallback)
{
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const vpColVector q = draw();
    bool ok = true;
    for (const ArmSetup *setup : setups) {
      ok = ok && setup->visible(setup->armJoints(q), 20.0);
    }
    if (ok) {
      return q;
    }
  }
  ADD_FAILURE() << "no configuration in view";
  return fallback;
}

//! Random model joints (within 0.6 times the trial amounts) with every marker in view in all \e setups.
vpColVector visibleJoints(const std::vector<const ArmSetup *> &setups, vpUniRand &rng)
{
  const ArmSetup &s = *setups[0];
  return drawInView(
      setups,
      [&] {
        vpColVector q(s.n());
        for (unsigned int i = 0; i < s.n(); ++i) {
          q[i] = rng.uniform(-0.6 * s.trialAmounts[i], 0.6 * s.trialAmounts[i]);
        }
        return q;
      },
      vpColVector(s.n(), 0.0));
}

//! Model joints within +-range of \e center (per joint) with every marker in view in all \e setups.
vpColVector jointsNear(const std::vector<const ArmSetup *> &setups, vpUniRand &rng, const vpColVector &center,
                       double range)
{
  return drawInView(
      setups,
      [&] {
        vpColVector q = center;
        for (unsigned int i = 0; i < q.getRows(); ++i) {
          q[i] += rng.uniform(-range, range);
        }
        return q;
      },
      center);
}

vpProjectiveRobot acquiredRobot(const ArmSetup &s, vpGaussRand &noise, double sigma = kSigma)
{
  vpProjectiveRobot robot(s.jointTypes());
  EXPECT_TRUE(s.acquire(robot, sigma, noise)) << s.name;
  robot.calibrate();
  return robot;
}

//! RMS over the configurations \e q of the robot's prediction error on noisy images of \e s.
double predictionError(const vpProjectiveRobot &robot, const ArmSetup &s, const std::vector<vpColVector> &q,
                       vpGaussRand &noise, double sigma = kSigma)
{
  double sum = 0.0;
  for (const vpColVector &qk : q) {
    std::vector<vpImagePoint> left, right;
    s.images(s.armJoints(qk), left, right, sigma, noise, -1e9);
    const double e = robot.getPredictionError(qk, left, right);
    sum += e * e;
  }
  return std::sqrt(sum / static_cast<double>(q.size()));
}

/*!
  Adds \e count observations of \e s at random configurations in view (around \e center within +-range if given,
  else within 0.6 times the trial amounts of the zero reference) and updates the rig.
*/
struct Observation {
  vpColVector q;
  std::vector<vpImagePoint> left, right;
};

std::vector<Observation> reRegister(vpProjectiveRobot &robot, const ArmSetup &s, unsigned int count, vpUniRand &rng,
                                    vpGaussRand &noise, const vpColVector &center = vpColVector(), double range = 0.0)
{
  std::vector<Observation> observations(count);
  for (Observation &o : observations) {
    o.q = center.getRows() > 0 ? jointsNear({&s}, rng, center, range) : visibleJoints({&s}, rng);
    s.images(s.armJoints(o.q), o.left, o.right, kSigma, noise, -1e9);
    robot.addRigObservation(o.q, o.left, o.right);
  }
  robot.updateRig();
  return observations;
}

//! Tool pose error (rotation in degrees, translation in metres) between model joints qa and qb of \e s.
void toolPoseError(const ArmSetup &s, const vpColVector &qa, const vpColVector &qb, double &deg, double &metres)
{
  const vpHomogeneousMatrix d = s.arm.get_wMt(s.armJoints(qa)).inverse() * s.arm.get_wMt(s.armJoints(qb));
  deg = vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta());
  metres = d.getTranslationVector().frobeniusNorm();
}

const std::vector<unsigned int> kTracked = {0, 1, 2, 3, 4, 5, 6};

//! A servo task on the markers kTracked, features from noisy images; s* taught at qTarget through \e s.
struct ServoRun {
  std::vector<vpFeatureStereoPoint> s, sStar;
  vpServoProjective task;

  ServoRun(const ArmSetup &setup, const vpProjectiveRobot &robot, const vpColVector &qTarget, double sigma,
           vpGaussRand &noise)
      : s(kTracked.size()), sStar(kTracked.size()), task()
  {
    measure(setup, qTarget, sigma, noise, sStar);
    s = sStar;
    task.setRobot(robot);
    task.setLambda(0.5);
    task.setMaxJointVelocity(vpMath::rad(10.0));
    task.setPathPlanning(true); // plans from the model: no task ends in another branch (issue 11)
    for (size_t k = 0; k < kTracked.size(); ++k) {
      task.addFeature(s[k], sStar[k]);
    }
  }

  static void measure(const ArmSetup &setup, const vpColVector &q, double sigma, vpGaussRand &noise,
                      std::vector<vpFeatureStereoPoint> &features, Observation *frame = nullptr)
  {
    std::vector<vpImagePoint> left, right;
    setup.images(setup.armJoints(q), left, right, sigma, noise, -1e9);
    if (frame != nullptr) {
      *frame = Observation{q, left, right};
    }
    for (size_t k = 0; k < kTracked.size(); ++k) {
      features[k].buildFrom(left[kTracked[k]], right[kTracked[k]]);
    }
  }

  //! One iteration at q seen through \e setup; moves q; returns the status.
  vpServoProjective::vpServoStatus step(const ArmSetup &setup, vpColVector &q, double sigma, vpGaussRand &noise,
                                        Observation *frame = nullptr)
  {
    measure(setup, q, sigma, noise, s, frame);
    const vpColVector qdot = task.computeControlLaw(q);
    q = setup.arm.integrate(setup.armJoints(q), qdot, 1.0) - setup.qRef;
    return task.getStatus();
  }
};

//! The figures of one bump case.
struct BumpCase {
  int detectedAfter = -1;     // iterations after the bump until SERVO_MODEL_MISMATCH (1 or 2 wanted; -1: never)
  int falseAlarms = 0;        // SERVO_MODEL_MISMATCH in the unbumped runs (0.5 and 1 px) and before the bump
  double preError = 0.0;      // prediction error before the bump (px)
  double ratio3 = 0.0;        // after updateRig() from 3 observations, over preError
  double ratio10 = 0.0;       // from 10
  double ratio3General = 0.0; // from 3, plain 11-parameter resection
  double finalDeg = 0.0;      // tool pose error at the end of the task after updateRig() (where the arm rests:
  double finalMetres = 0.0;   // its mean joints over the last 30 of 150 iterations, the law jittering with the noise)
  double unbumpedDeg = 0.0;   // the same for the unbumped run at 0.5 px
  double unbumpedMetres = 0.0;
  bool userStarUnchanged = true;
};

BumpCase runBumpCase(const ArmSetup &s, long seed, BumpKind kind)
{
  BumpCase c;
  vpUniRand rng(seed);
  vpGaussRand noise(1.0, 0.0, seed);
  const vpProjectiveRobot acquired = acquiredRobot(s, noise);
  const ArmSetup b = bumped(s, kind, rng);

  // Prediction error before the bump, and after re-registration from 3 and 10 observations (same test poses).
  std::vector<vpColVector> testPoses;
  for (int k = 0; k < 10; ++k) {
    testPoses.push_back(visibleJoints({&s, &b}, rng));
  }
  c.preError = predictionError(acquired, s, testPoses, noise);
  {
    vpProjectiveRobot robot = acquired;
    reRegister(robot, b, 3, rng, noise);
    c.ratio3 = predictionError(robot, b, testPoses, noise) / c.preError;
  }
  {
    vpProjectiveRobot robot = acquired;
    reRegister(robot, b, 10, rng, noise);
    c.ratio10 = predictionError(robot, b, testPoses, noise) / c.preError;
  }
  {
    vpProjectiveRobot robot = acquired;
    robot.setRigRegistrationMode(vpProjectiveRigRegistration::GENERAL);
    reRegister(robot, b, 3, rng, noise);
    c.ratio3General = predictionError(robot, b, testPoses, noise) / c.preError;
  }

  // A task of the servo tests' kind: target within 20 deg of the zero reference, start within 15 deg of it.
  const vpColVector qTarget = jointsNear({&s, &b}, rng, vpColVector(s.n(), 0.0), vpMath::rad(20.0));
  const vpColVector qStart = jointsNear({&s, &b}, rng, qTarget, vpMath::rad(15.0));

  // No false alarm in unbumped runs to the target, at 0.5 and 1 px.
  for (double sigma : {0.5, 1.0}) {
    ServoRun run(s, acquired, qTarget, sigma, noise);
    vpColVector q = qStart, qRest(s.n(), 0.0);
    for (int it = 0; it < 150; ++it) {
      if (run.step(s, q, sigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH) {
        ++c.falseAlarms;
      }
      if (it >= 120) {
        qRest += q / 30.0;
      }
    }
    if (sigma == kSigma) {
      toolPoseError(s, qRest, qTarget, c.unbumpedDeg, c.unbumpedMetres);
    }
  }

  // The bumped run: 6 iterations, the bump, detection, 3 observations, updateRig(), the task finished.
  vpProjectiveRobot robot = acquired;
  ServoRun run(s, robot, qTarget, kSigma, noise);
  const std::vector<vpFeatureStereoPoint> userStar = run.sStar;
  vpColVector q = qStart;
  for (int it = 0; it < 6; ++it) {
    if (run.step(s, q, kSigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH) {
      ++c.falseAlarms;
    }
  }
  for (int it = 1; it <= 4 && c.detectedAfter < 0; ++it) {
    if (run.step(b, q, kSigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH) {
      c.detectedAfter = it;
    }
  }
  // Three observation poses within 20 deg of where the arm stopped (spreading the markers), then back there. The
  // servo's own frames keep refining the rig: every 40 iterations, updateRig() again from the three poses and the
  // frames seen so far (20 of every 40). Frames where the task ends pin the new cameras where the re-expressed s*
  // matters: the task then ends where the model's inverse kinematics puts the taught s*.
  const std::vector<Observation> poses = reRegister(robot, b, 3, rng, noise, q, vpMath::rad(20.0));
  std::vector<Observation> observed = poses;
  vpColVector qRest(s.n(), 0.0);
  for (int it = 0; it < 150; ++it) {
    Observation frame;
    run.step(b, q, kSigma, noise, &frame);
    if (it % 40 >= 20 && it < 120) {
      observed.push_back(frame);
    }
    if (it % 40 == 39 && it < 120) {
      for (const Observation &o : observed) {
        robot.addRigObservation(o.q, o.left, o.right);
      }
      robot.updateRig();
    }
    if (it >= 120) {
      qRest += q / 30.0;
    }
  }
  toolPoseError(s, qRest, qTarget, c.finalDeg, c.finalMetres);
  for (size_t k = 0; k < userStar.size(); ++k) {
    c.userStarUnchanged = c.userStarUnchanged && userStar[k].get_s() == run.sStar[k].get_s();
  }
  return c;
}

double quantile(std::vector<double> x, double p)
{
  std::sort(x.begin(), x.end());
  return x[std::min(x.size() - 1, static_cast<size_t>(p * static_cast<double>(x.size())))];
}
} // namespace

// A general camera pair: F, epipoles, triangulation and projection agree with the cameras.
TEST(RigUpdate, GeneralCameraPairIsConsistent)
{
  const ArmSetup s = pumaEyeToHand();
  vpUniRand rng(7);
  vpProjectiveStereoRig canonical = s.rig();
  // Any projective change of frame W gives a general pair P W^-1, P' W^-1 of the same cameras.
  Eigen::Matrix4d W;
  for (int r = 0; r < 4; ++r) {
    for (int c = 0; c < 4; ++c) {
      W(r, c) = (r == c ? 1.0 : 0.0) + rng.uniform(-0.3, 0.3);
    }
  }
  const Eigen::Matrix<double, 3, 4> P = canonical.leftProjection() * W.inverse();
  const Eigen::Matrix<double, 3, 4> Pp = canonical.rightProjection() * W.inverse();
  vpProjectiveStereoRig rig;
  rig.setProjections(toVisp(P), toVisp(Pp));
  EXPECT_FALSE(rig.isCanonical());
  EXPECT_TRUE(canonical.isCanonical());
  const Eigen::Matrix3d F = toEigen<3, 3>(rig.getFundamentalMatrix());
  // The same epipolar geometry as the canonical pair: F equal up to sign.
  const Eigen::Matrix3d F0 = canonical.fundamentalMatrix();
  EXPECT_LT(std::min((F - F0).norm(), (F + F0).norm()), 1e-9);
  EXPECT_LT((F * toEigen<3, 1>(rig.getLeftEpipole())).norm(), 1e-9);
  EXPECT_LT((F.transpose() * toEigen<3, 1>(rig.getRightEpipole())).norm(), 1e-9);
  for (const vpColVector &X : s.markersAt(s.qRef)) {
    vpImagePoint l, r, l2, r2;
    s.simAt(s.qRef).project(X, l, r);
    const vpColVector M = rig.triangulate(l, r);
    // The point is W times the canonical one: the frame of the pair, not that of F.
    const Eigen::Vector4d Mc = toEigen4(canonical.triangulate(l, r));
    const Eigen::Vector4d WMc = (W * Mc).normalized();
    const Eigen::Vector4d Me = toEigen4(M);
    EXPECT_LT(std::min((Me - WMc).norm(), (Me + WMc).norm()), 1e-7);
    rig.project(M, l2, r2);
    EXPECT_LT(pixelDistance(l, l2) + pixelDistance(r, r2), 1e-6);
    EXPECT_LT(std::abs(pixel(r).dot(F * pixel(l))), 1e-9 * pixel(r).norm() * pixel(l).norm());
  }
  // Bad pairs: rank 2, a shared centre, NaN; the rig is left as it was.
  Eigen::Matrix<double, 3, 4> rank2 = P;
  rank2.row(2) = rank2.row(0) + rank2.row(1);
  EXPECT_TRUE(throwsWith([&] { rig.setProjections(toVisp(rank2), toVisp(Pp)); },
                         vpProjectiveException::degenerateConfigurationError, "rank"));
  Eigen::Matrix3d R = Eigen::AngleAxisd(0.3, Eigen::Vector3d::UnitY()).toRotationMatrix();
  const Eigen::Matrix<double, 3, 4> sameCentre = R * P;
  EXPECT_TRUE(throwsWith([&] { rig.setProjections(toVisp(P), toVisp(sameCentre)); },
                         vpProjectiveException::degenerateConfigurationError, "same centre"));
  vpMatrix nan = toVisp(P);
  nan[0][0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsWith([&] { rig.setProjections(nan, toVisp(Pp)); }, vpProjectiveException::nonFiniteValueError,
                         "not finite"));
  EXPECT_EQ(rig.leftProjection(), P / P.norm());
  EXPECT_FALSE(rig.isCanonical());
}

// Noise-free: updateRig() recovers the moved cameras exactly (the model's frame, fixed intrinsics and general).
TEST(RigUpdate, NoiseFreeReRegistrationIsExact)
{
  const ArmSetup s = pumaEyeToHand();
  for (BumpKind kind : {BUMP_LEFT, BUMP_RIGHT, BUMP_RIG}) {
    for (auto mode : {vpProjectiveRigRegistration::FIXED_INTRINSICS, vpProjectiveRigRegistration::GENERAL}) {
      vpUniRand rng(11 + kind);
      vpGaussRand noise(1.0, 0.0, 3);
      vpProjectiveRobot robot = acquiredRobot(s, noise, 0.0); // noise-free
      const ArmSetup b = bumped(s, kind, rng);
      std::vector<vpColVector> poses;
      for (int k = 0; k < 5; ++k) {
        poses.push_back(visibleJoints({&s, &b}, rng));
      }
      const double before = predictionError(robot, b, poses, noise, 0.0);
      robot.setRigRegistrationMode(mode);
      EXPECT_EQ(robot.getRigGeneration(), 0u);
      for (int k = 0; k < 3; ++k) {
        std::vector<vpImagePoint> left, right;
        b.images(b.armJoints(poses[static_cast<size_t>(k)]), left, right, -1e9);
        robot.addRigObservation(poses[static_cast<size_t>(k)], left, right);
      }
      robot.updateRig();
      EXPECT_EQ(robot.getRigGeneration(), 1u);
      EXPECT_EQ(robot.getNumberOfRigObservations(), 0u);
      EXPECT_FALSE(robot.getStereoRig().isCanonical());
      double worst = 0.0;
      for (const vpColVector &q : poses) {
        std::vector<vpImagePoint> left, right;
        b.images(b.armJoints(q), left, right, -1e9);
        worst = std::max(worst, robot.getPredictionError(q, left, right));
      }
      EXPECT_GT(before, 5.0) << bumpName(kind); // the bump is visible
      EXPECT_LT(worst, 1e-3) << bumpName(kind) << " mode " << mode;
    }
  }
}

// The model file carries a general pair bit for bit; version 2 files are still read.
TEST(RigUpdate, SaveLoadGeneralRig)
{
  const ArmSetup s = pumaEyeToHand();
  vpUniRand rng(5);
  vpGaussRand noise(1.0, 0.0, 5);
  vpProjectiveRobot robot = acquiredRobot(s, noise);
  const std::string canonicalFile = "testRigUpdate_canonical.json", generalFile = "testRigUpdate_general.json";
  robot.saveModel(canonicalFile);
  const Eigen::Matrix3d F0 = robot.getStereoRig().fundamentalMatrix();
  const ArmSetup b = bumped(s, BUMP_LEFT, rng);
  reRegister(robot, b, 4, rng, noise);
  robot.saveModel(generalFile);
  vpProjectiveRobot loaded;
  loaded.loadModel(generalFile);
  EXPECT_FALSE(loaded.getStereoRig().isCanonical());
  EXPECT_EQ(loaded.getStereoRig().leftProjection(), robot.getStereoRig().leftProjection());
  EXPECT_EQ(loaded.getStereoRig().rightProjection(), robot.getStereoRig().rightProjection());
  const vpColVector q = visibleJoints({&b}, rng);
  std::vector<vpImagePoint> left, right;
  b.images(b.armJoints(q), left, right, kSigma, noise, -1e9);
  EXPECT_EQ(loaded.getPredictionError(q, left, right), robot.getPredictionError(q, left, right));

  // A version-2 file (no camera_pair, always canonical) is read as before.
  std::ifstream in(canonicalFile);
  nlohmann::json file = nlohmann::json::parse(in);
  EXPECT_EQ(file["version"], 3);
  EXPECT_EQ(file["model"]["rig"]["camera_pair"], "canonical");
  file["version"] = 2;
  file["model"]["rig"].erase("camera_pair");
  {
    std::ofstream out(canonicalFile);
    out << resigned(file);
  }
  vpProjectiveRobot old;
  old.loadModel(canonicalFile);
  EXPECT_TRUE(old.getStereoRig().isCanonical());
  EXPECT_LT((old.getStereoRig().fundamentalMatrix() - F0).norm(), 1e-12);
  std::remove(canonicalFile.c_str());
  std::remove(generalFile.c_str());
}

// Every bad input throws a vpProjectiveException that says what to do, and changes nothing.
TEST(RigUpdate, BadInputsThrowAndChangeNothing)
{
  const ArmSetup s = pumaEyeToHand();
  vpUniRand rng(9);
  vpGaussRand noise(1.0, 0.0, 9);
  vpProjectiveRobot robot = acquiredRobot(s, noise);
  const ArmSetup b = bumped(s, BUMP_RIGHT, rng);
  const vpProjectiveStereoRig::Projection P0 = robot.getStereoRig().leftProjection();
  const vpProjectiveStereoRig::Projection Pp0 = robot.getStereoRig().rightProjection();
  const vpColVector q = visibleJoints({&b}, rng);
  std::vector<vpImagePoint> left, right;
  b.images(b.armJoints(q), left, right, kSigma, noise, -1e9);

  // Before a model.
  vpProjectiveRobot empty(s.jointTypes());
  EXPECT_TRUE(throwsWith([&] { empty.addRigObservation(q, left, right); }, vpProjectiveException::notInitializedError,
                         "calibrate()"));
  EXPECT_TRUE(throwsWith([&] { empty.updateRig(); }, vpProjectiveException::notInitializedError, "calibrate()"));

  // A missing marker, a size mismatch, a wrong joint vector, non-finite values.
  std::vector<vpImagePoint> missing(left.begin(), left.end() - 1), missingRight(right.begin(), right.end() - 1);
  EXPECT_TRUE(throwsWith([&] { robot.addRigObservation(q, missing, missingRight); },
                         vpProjectiveException::dimensionError, "every zero-reference marker"));
  EXPECT_TRUE(throwsWith([&] { robot.addRigObservation(q, missing, right); }, vpProjectiveException::dimensionError,
                         "matched pairs"));
  EXPECT_TRUE(throwsWith([&] { robot.getPredictionError(q, missing, missingRight); },
                         vpProjectiveException::dimensionError, "every zero-reference marker"));
  EXPECT_TRUE(throwsWith([&] { robot.addRigObservation(vpColVector(5, 0.0), left, right); },
                         vpProjectiveException::dimensionError, "q"));
  std::vector<vpImagePoint> nanLeft = left;
  nanLeft[2].set_u(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(throwsWith([&] { robot.addRigObservation(q, nanLeft, right); },
                         vpProjectiveException::nonFiniteValueError, "not finite"));
  vpColVector qInf = q;
  qInf[1] = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsWith([&] { robot.addRigObservation(qInf, left, right); },
                         vpProjectiveException::nonFiniteValueError, "NaN or infinite"));
  EXPECT_EQ(robot.getNumberOfRigObservations(), 0u);

  // Identical configurations; too few observations.
  robot.addRigObservation(q, left, right);
  EXPECT_TRUE(throwsWith([&] { robot.addRigObservation(q, left, right); },
                         vpProjectiveException::degenerateConfigurationError, "move the arm"));
  EXPECT_EQ(robot.getNumberOfRigObservations(), 1u);
  EXPECT_TRUE(throwsWith([&] { robot.updateRig(); }, vpProjectiveException::notEnoughPointsError, "at least 3"));

  // Observations that the model cannot explain (markers in another order: slipped or mislabelled): the update fails,
  // the rig, the generation and the observations stay.
  for (int k = 0; k < 3; ++k) {
    const vpColVector qk = visibleJoints({&b}, rng);
    std::vector<vpImagePoint> l, r;
    b.images(b.armJoints(qk), l, r, kSigma, noise, -1e9);
    std::reverse(l.begin(), l.end());
    std::reverse(r.begin(), r.end());
    robot.addRigObservation(qk, l, r);
  }
  EXPECT_TRUE(throwsWith([&] { robot.updateRig(); }, vpProjectiveException::estimationFailedError, "marker order"));
  EXPECT_EQ(robot.getNumberOfRigObservations(), 4u);
  EXPECT_EQ(robot.getRigGeneration(), 0u);
  EXPECT_EQ(robot.getStereoRig().leftProjection(), P0);
  EXPECT_EQ(robot.getStereoRig().rightProjection(), Pp0);
  robot.clearRigObservations();
  EXPECT_EQ(robot.getNumberOfRigObservations(), 0u);

  // Degenerate geometry: coplanar points leave a camera undetermined.
  std::vector<Eigen::Vector4d> X;
  std::vector<Eigen::Vector2d> uv;
  for (int k = 0; k < 12; ++k) {
    const Eigen::Vector4d Xk(rng.uniform(-1.0, 1.0), rng.uniform(-1.0, 1.0), 0.0, 1.0);
    const Eigen::Vector3d m = P0 * (Xk + Eigen::Vector4d(0.0, 0.0, 3.0, 0.0));
    X.push_back(Xk + Eigen::Vector4d(0.0, 0.0, 3.0, 0.0));
    uv.push_back(m.head<2>() / m(2));
  }
  const Eigen::Matrix4d G = robot.getModel().projectiveToMetric();
  EXPECT_TRUE(throwsWith([&] { vpProjectiveRigRegistration::resect(P0, G, X, uv); },
                         vpProjectiveException::degenerateConfigurationError, "coplanar"));
  X.resize(5);
  uv.resize(5);
  EXPECT_TRUE(throwsWith([&] { vpProjectiveRigRegistration::resect(P0, G, X, uv); },
                         vpProjectiveException::notEnoughPointsError, "at least 6"));
  uv.resize(4);
  EXPECT_TRUE(throwsWith([&] { vpProjectiveRigRegistration::resect(P0, G, X, uv); },
                         vpProjectiveException::dimensionError, "one pixel per point"));

  // The task's threshold.
  vpServoProjective task;
  EXPECT_TRUE(
      throwsWith([&] { task.setModelMismatchThreshold(-1.0); }, vpProjectiveException::invalidValueError, "pixels"));
  EXPECT_TRUE(throwsWith([&] { task.setModelMismatchThreshold(std::numeric_limits<double>::quiet_NaN()); },
                         vpProjectiveException::nonFiniteValueError, "threshold"));
  EXPECT_EQ(task.getModelMismatchThreshold(), 5.0);
  task.setModelMismatchThreshold(8.0);
  EXPECT_EQ(task.getModelMismatchThreshold(), 8.0);
}

// One case of each kind, asserted one by one: detection within 2 iterations, no false alarm, re-registration close to
// the pre-bump prediction error, the task at its original target, the user's s* untouched.
TEST(RigUpdate, BumpDetectedReRegisteredAndTaskFinished)
{
  const ArmSetup s = pumaEyeToHand();
  for (BumpKind kind : {BUMP_LEFT, BUMP_RIGHT, BUMP_RIG}) {
    const BumpCase c = runBumpCase(s, 100 + kind, kind);
    EXPECT_GE(c.detectedAfter, 1) << bumpName(kind);
    EXPECT_LE(c.detectedAfter, 2) << bumpName(kind);
    EXPECT_EQ(c.falseAlarms, 0) << bumpName(kind);
    EXPECT_LT(c.ratio3, 3.0) << bumpName(kind);
    EXPECT_LT(c.ratio10, 2.0) << bumpName(kind);
    // Loose: the unbumped runs of the Monte-Carlo rest up to 1.4 mm from the target (90 % quantile) at 0.5 px.
    EXPECT_LT(c.finalDeg, 2.0) << bumpName(kind);
    EXPECT_LT(c.finalMetres, 0.005) << bumpName(kind);
    EXPECT_TRUE(c.userStarUnchanged) << bumpName(kind);
    std::cout << "[ measured ] " << bumpName(kind) << ": detected after " << c.detectedAfter << ", pre-bump error "
              << c.preError << " px, ratios 3: " << c.ratio3 << " 10: " << c.ratio10
              << " (11-parameter from 3: " << c.ratio3General << "), final " << c.finalDeg << " deg "
              << 1000.0 * c.finalMetres << " mm (unbumped " << c.unbumpedDeg << " deg " << 1000.0 * c.unbumpedMetres
              << " mm)" << std::endl;
  }
}

//! A noise-free model of the PUMA, its rig then bumped (\e kind) and a target in view of both rigs; seeded.
struct NoiseFreeBump {
  NoiseFreeBump(long seed, BumpKind kind)
      : s(pumaEyeToHand()), rng(seed), noise(1.0, 0.0, seed), robot(acquiredRobot(s, noise, 0.0)),
        b(bumped(s, kind, rng)), qTarget(jointsNear({&s, &b}, rng, vpColVector(s.n(), 0.0), vpMath::rad(20.0)))
  {
  }
  const ArmSetup s;
  vpUniRand rng;
  vpGaussRand noise;
  vpProjectiveRobot robot;
  const ArmSetup b;
  const vpColVector qTarget;
};

// SERVO_MODEL_MISMATCH takes precedence over single-feature outliers, a single outlier is not a mismatch, qdot = 0,
// and a threshold of 0 turns the detection off.
TEST(RigUpdate, MismatchPrecedenceAndSwitch)
{
  NoiseFreeBump t(31, BUMP_LEFT);
  const ArmSetup &s = t.s, &b = t.b;
  const vpColVector qStart = jointsNear({&s, &b}, t.rng, t.qTarget, vpMath::rad(8.0));
  for (double threshold : {5.0, 0.0}) {
    ServoRun run(s, t.robot, t.qTarget, 0.0, t.noise);
    run.task.setOutlierThreshold(3.0);
    run.task.setModelMismatchThreshold(threshold);
    vpColVector q = qStart;
    for (int it = 0; it < 3; ++it) {
      EXPECT_EQ(run.step(s, q, 0.0, t.noise), vpServoProjective::SERVO_RUNNING);
    }
    // One feature jumps by 20 px: an outlier, not a mismatch.
    ServoRun::measure(s, q, 0.0, t.noise, run.s);
    const Eigen::Vector4d s2 = run.s[2].getFeature();
    run.s[2].buildFrom(s2(0) + 20.0, s2(1), s2(2), s2(3));
    run.task.computeControlLaw(q);
    EXPECT_EQ(run.task.getFeatureState(2), vpServoProjective::FEATURE_OUTLIER);
    EXPECT_EQ(run.task.getStatus(), vpServoProjective::SERVO_REDUCED);
    // The camera moves: every feature is an outlier for the health, and a mismatch at the second call.
    vpServoProjective::vpServoStatus first = run.step(b, q, 0.0, t.noise);
    ServoRun::measure(b, q, 0.0, t.noise, run.s);
    const vpColVector qdot = run.task.computeControlLaw(q);
    if (threshold > 0.0) {
      EXPECT_NE(first, vpServoProjective::SERVO_MODEL_MISMATCH);
      EXPECT_EQ(run.task.getStatus(), vpServoProjective::SERVO_MODEL_MISMATCH);
      EXPECT_EQ(qdot.frobeniusNorm(), 0.0);
      EXPECT_GT(run.task.getModelMismatch().getDistance(0), threshold);
      // Never re-registered since the acquisition: print() lists the rig mounting among the causes.
      std::ostringstream printed;
      run.task.print(printed);
      EXPECT_NE(printed.str().find("check the rig mounting"), std::string::npos) << printed.str();
    } else {
      EXPECT_NE(run.task.getStatus(), vpServoProjective::SERVO_MODEL_MISMATCH);
      EXPECT_EQ(run.task.getModelMismatch().getDisagreeingIterations(), 0u);
    }
  }
}

// The task's own s*: re-expressed after updateRig(), the user's objects unchanged, a new s* taken as given.
TEST(RigUpdate, TaskReExpressesItsDesiredFeatures)
{
  NoiseFreeBump t(21, BUMP_RIG);
  const ArmSetup &s = t.s, &b = t.b;
  ServoRun run(s, t.robot, t.qTarget, 0.0, t.noise);
  vpColVector q = jointsNear({&s, &b}, t.rng, t.qTarget, vpMath::rad(8.0));
  run.step(s, q, 0.0, t.noise);
  EXPECT_EQ(toEigen4(run.task.getDesiredFeature(0)), run.sStar[0].getFeature());
  vpColVector qObs;
  for (int k = 0; k < 3; ++k) {
    qObs = visibleJoints({&b}, t.rng);
    std::vector<vpImagePoint> left, right;
    b.images(b.armJoints(qObs), left, right, -1e9);
    t.robot.addRigObservation(qObs, left, right);
  }
  t.robot.updateRig();
  const Eigen::Vector4d user = run.sStar[0].getFeature();
  run.step(b, q, 0.0, t.noise);
  // Noise-free: the re-expressed s* is the new rig's image of the target, i.e. what the bumped rig sees there.
  for (size_t k = 0; k < kTracked.size(); ++k) {
    const Eigen::Vector4d expected = b.imageOf(b.armJoints(t.qTarget), kTracked[k]);
    EXPECT_LT((toEigen4(run.task.getDesiredFeature(static_cast<unsigned int>(k))) - expected).norm(), 1e-3);
  }
  EXPECT_EQ(run.sStar[0].getFeature(), user);
  EXPECT_GT((toEigen4(run.task.getDesiredFeature(0)) - user).norm(), 1.0);
  for (int it = 0; it < 100; ++it) {
    const vpServoProjective::vpServoStatus st = run.step(b, q, 0.0, t.noise);
    if (it % 10 == 0)
      std::cout << it << " " << st << " " << run.task.getError().frobeniusNorm() << " " << run.task.getConditionNumber()
                << std::endl;
  }
  double deg = 0.0, metres = 0.0;
  {
    vpColVector qq = t.qTarget;
    run.step(b, qq, 0.0, t.noise);
    std::cout << "at target e " << run.task.getError().t() << std::endl;
    std::vector<vpImagePoint> l, r;
    b.images(b.armJoints(t.qTarget), l, r, -1e9);
    std::cout << "pred err at target " << t.robot.getPredictionError(t.qTarget, l, r) << std::endl;
    std::cout << "q-qT " << (q - t.qTarget).t() << std::endl;
  }
  toolPoseError(s, q, t.qTarget, deg, metres);
  EXPECT_LT(deg, 1e-3);
  EXPECT_LT(metres, 1e-5);
  // A new s* given by the user after the update is in the new images: taken as given.
  ServoRun::measure(b, qObs, 0.0, t.noise, run.sStar);
  run.step(b, q, 0.0, t.noise);
  EXPECT_EQ(toEigen4(run.task.getDesiredFeature(1)), run.sStar[1].getFeature());
}

/*
  Monte-Carlo of 120 seeded bumps at 0.5 px (one camera or the whole rig, 1-3 deg and 0.5-2 cm): the figures of
  issue 12 with loose bounds (the measured values are printed).
*/
TEST(RigUpdate, MonteCarloOfBumps)
{
  const ArmSetup s = pumaEyeToHand();
  const int cases = 120;
  int detected = 0, falseAlarms = 0, finished = 0, userUnchanged = 0, unbumpedFinishedCount = 0, finishedOfThose = 0;
  std::vector<double> ratio3, ratio10, ratio3General, finalDeg, finalMm, unbumpedDeg, unbumpedMm;
  for (int k = 0; k < cases; ++k) {
    const BumpKind kind = static_cast<BumpKind>(k % 3);
    const BumpCase c = runBumpCase(s, 1000 + k, kind);
    detected += c.detectedAfter >= 1 && c.detectedAfter <= 2 ? 1 : 0;
    falseAlarms += c.falseAlarms;
    finished += c.finalDeg <= 2.0 && c.finalMetres <= 0.002 ? 1 : 0;
    const bool unbumpedFinished = c.unbumpedDeg <= 2.0 && c.unbumpedMetres <= 0.002;
    unbumpedFinishedCount += unbumpedFinished ? 1 : 0;
    finishedOfThose += unbumpedFinished && c.finalDeg <= 2.0 && c.finalMetres <= 0.002 ? 1 : 0;
    userUnchanged += c.userStarUnchanged ? 1 : 0;
    ratio3.push_back(c.ratio3);
    ratio10.push_back(c.ratio10);
    ratio3General.push_back(c.ratio3General);
    finalDeg.push_back(c.finalDeg);
    finalMm.push_back(1000.0 * c.finalMetres);
    unbumpedDeg.push_back(c.unbumpedDeg);
    unbumpedMm.push_back(1000.0 * c.unbumpedMetres);
    if (c.detectedAfter < 1 || c.detectedAfter > 2 || c.finalDeg > 2.0 || c.finalMetres > 0.002) {
      std::cout << "[ measured ] case " << k << " (" << bumpName(kind) << "): detected after " << c.detectedAfter
                << ", final " << c.finalDeg << " deg " << 1000.0 * c.finalMetres << " mm (unbumped " << c.unbumpedDeg
                << " deg " << 1000.0 * c.unbumpedMetres << " mm), ratio from 3 " << c.ratio3 << std::endl;
    }
  }
  const double n = static_cast<double>(cases);
  std::cout << "[ measured ] " << cases << " bumps at 0.5 px: detected within 2 iterations " << detected / n
            << ", false alarms " << falseAlarms << " (unbumped runs at 0.5 and 1 px and before the bumps), median "
            << "ratio of the re-registered prediction error to the pre-bump one: " << median(ratio3)
            << " from 3 observations (90 % quantile " << quantile(ratio3, 0.9) << "), " << median(ratio10)
            << " from 10 (90 %: " << quantile(ratio10, 0.9)
            << "); plain 11-parameter resection from 3: " << median(ratio3General)
            << " (90 %: " << quantile(ratio3General, 0.9) << "); task at its target within "
            << "2 deg / 2 mm: " << finished / n << " (median " << median(finalDeg) << " deg, " << median(finalMm)
            << " mm; unbumped runs: median " << median(unbumpedDeg) << " deg, " << median(unbumpedMm)
            << " mm, 90 %: " << quantile(unbumpedDeg, 0.9) << " deg, " << quantile(unbumpedMm, 0.9)
            << " mm; the unbumped task itself ends within 2 deg / 2 mm in " << unbumpedFinishedCount
            << " cases, of which the bumped one in " << finishedOfThose << ")" << std::endl;
  EXPECT_GE(detected, static_cast<int>(0.95 * n));
  EXPECT_EQ(falseAlarms, 0);
  EXPECT_LE(median(ratio3), 2.0);
  EXPECT_LE(median(ratio10), 1.2);
  // The 95 %: the unbumped runs themselves rest up to 1.3 mm from the target (90 % quantile) at 0.5 px, and
  // the re-expressed target inherits the model's error at the target (see the printed figures).
  EXPECT_GE(finished, static_cast<int>(std::ceil(0.95 * n)));
  EXPECT_GE(finishedOfThose, static_cast<int>(std::ceil(0.95 * unbumpedFinishedCount)));
  EXPECT_EQ(userUnchanged, cases);
}
