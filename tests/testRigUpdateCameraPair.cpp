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
  A camera or the whole rig moved (issue 12, points 3 and 4; helpers in vpRigUpdateTestTools.h): the general camera
  pair of vpProjectiveStereoRig, the re-registration of vpProjectiveRobot (addRigObservation(), updateRig(),
  getPredictionError()) and its model file, the bad inputs.
*/

#include <gtest/gtest.h>

#include "vpRigUpdateTestTools.h"

using namespace vpProjectiveTest;

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
  vpProjectiveStereoRig::Projection Pc, Ppc;
  canonical.getLeftProjection(Pc);
  canonical.getRightProjection(Ppc);
  const Eigen::Matrix<double, 3, 4> P = Pc * W.inverse();
  const Eigen::Matrix<double, 3, 4> Pp = Ppc * W.inverse();
  vpProjectiveStereoRig rig;
  rig.setProjections(toVisp(P), toVisp(Pp));
  EXPECT_FALSE(rig.isCanonical());
  EXPECT_TRUE(canonical.isCanonical());
  const Eigen::Matrix3d F = toEigen<3, 3>(rig.getFundamentalMatrix());
  // The same epipolar geometry as the canonical pair: F equal up to sign.
  Eigen::Matrix3d F0;
  canonical.getFundamentalMatrix(F0);
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
  vpProjectiveStereoRig::Projection Pkept;
  rig.getLeftProjection(Pkept);
  EXPECT_EQ(Pkept, P / P.norm());
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
      robot.getRigUpdate().setRegistrationMode(mode);
      EXPECT_EQ(robot.getRigUpdate().getGeneration(), 0u);
      for (int k = 0; k < 3; ++k) {
        std::vector<vpImagePoint> left, right;
        b.images(b.armJoints(poses[static_cast<size_t>(k)]), left, right, -1e9);
        robot.addRigObservation(poses[static_cast<size_t>(k)], left, right);
      }
      robot.updateRig();
      EXPECT_EQ(robot.getRigUpdate().getGeneration(), 1u);
      EXPECT_EQ(robot.getRigUpdate().getNumberOfObservations(), 0u);
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
  Eigen::Matrix3d F0;
  robot.getStereoRig().getFundamentalMatrix(F0);
  const ArmSetup b = bumped(s, BUMP_LEFT, rng);
  reRegister(robot, b, 4, rng, noise);
  robot.saveModel(generalFile);
  vpProjectiveRobot loaded;
  loaded.loadModel(generalFile);
  EXPECT_FALSE(loaded.getStereoRig().isCanonical());
  vpProjectiveStereoRig::Projection P, Pp, Ploaded, Pploaded;
  robot.getStereoRig().getLeftProjection(P);
  robot.getStereoRig().getRightProjection(Pp);
  loaded.getStereoRig().getLeftProjection(Ploaded);
  loaded.getStereoRig().getRightProjection(Pploaded);
  EXPECT_EQ(Ploaded, P);
  EXPECT_EQ(Pploaded, Pp);
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
  Eigen::Matrix3d Fold;
  old.getStereoRig().getFundamentalMatrix(Fold);
  EXPECT_LT((Fold - F0).norm(), 1e-12);
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
  vpProjectiveStereoRig::Projection P0, Pp0;
  robot.getStereoRig().getLeftProjection(P0);
  robot.getStereoRig().getRightProjection(Pp0);
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
  EXPECT_EQ(robot.getRigUpdate().getNumberOfObservations(), 0u);

  // Identical configurations; too few observations.
  robot.addRigObservation(q, left, right);
  EXPECT_TRUE(throwsWith([&] { robot.addRigObservation(q, left, right); },
                         vpProjectiveException::degenerateConfigurationError, "move the arm"));
  EXPECT_EQ(robot.getRigUpdate().getNumberOfObservations(), 1u);
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
  EXPECT_EQ(robot.getRigUpdate().getNumberOfObservations(), 4u);
  EXPECT_EQ(robot.getRigUpdate().getGeneration(), 0u);
  vpProjectiveStereoRig::Projection P1, Pp1;
  robot.getStereoRig().getLeftProjection(P1);
  robot.getStereoRig().getRightProjection(Pp1);
  EXPECT_EQ(P1, P0);
  EXPECT_EQ(Pp1, Pp0);
  robot.getRigUpdate().clearObservations();
  EXPECT_EQ(robot.getRigUpdate().getNumberOfObservations(), 0u);

  // Degenerate geometry: coplanar points leave a camera undetermined.
  std::vector<Eigen::Vector4d> X;
  std::vector<Eigen::Vector2d> uv;
  for (int k = 0; k < 12; ++k) {
    const double y = rng.uniform(-1.0, 1.0); // drawn last to first: see point3(), vpProjectiveTestTools.h
    const double x = rng.uniform(-1.0, 1.0);
    const Eigen::Vector4d Xk(x, y, 0.0, 1.0);
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
  EXPECT_TRUE(throwsWith([&] { task.getModelMismatch().setThreshold(-1.0); }, vpProjectiveException::invalidValueError,
                         "pixels"));
  EXPECT_TRUE(throwsWith([&] { task.getModelMismatch().setThreshold(std::numeric_limits<double>::quiet_NaN()); },
                         vpProjectiveException::nonFiniteValueError, "threshold"));
  EXPECT_EQ(task.getModelMismatch().getThreshold(), 5.0);
  task.getModelMismatch().setThreshold(8.0);
  EXPECT_EQ(task.getModelMismatch().getThreshold(), 8.0);
}
