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
  The task refines a re-registered rig with its own frames (issue 18, point 5; vpServoRigRefinement::setRefinement(),
  vpProjectiveRobot::refineRig()): the switch and its settings, nothing without a re-registration, nothing when off or
  on a robot given as const, a failed refinement leaves everything as it was, features set aside never enter, the
  frames' points are in the frame of the rig that saw them. The rate at which the task then reaches its target is
  measured by testRigUpdateMonteCarlo.
*/

#include <gtest/gtest.h>

#include "vpRigUpdateTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! Both cameras of a rig as one 3x8 matrix, to compare rigs exactly.
Eigen::Matrix<double, 3, 8> cameras(const vpProjectiveRobot &robot)
{
  vpProjectiveStereoRig::Projection P, Pp;
  robot.getModel().getStereoRig().getLeftProjection(P);
  robot.getModel().getStereoRig().getRightProjection(Pp);
  Eigen::Matrix<double, 3, 8> C;
  C << P, Pp;
  return C;
}

/*!
  A noise-free task toward its target whose left camera is bumped after 3 calls, detected, and re-registered from 3
  observation poses (0.5 px): the state the refinement starts from. The task is given the robot as modifiable unless
  \e modifiable is false.
*/
struct BumpedTask {
  explicit BumpedTask(bool modifiable = true)
      : t(41, BUMP_LEFT), run(t.s, t.robot, t.qTarget, 0.0, t.noise),
        q(jointsNear({&t.s, &t.b}, t.rng, t.qTarget, 10.0))
  {
    if (modifiable) {
      run.task.setRobot(t.robot);
    }
  }

  //! Runs until the mismatch, then re-registers from 3 poses; true if the mismatch was detected.
  bool bumpAndReRegister()
  {
    for (int it = 0; it < 3; ++it) {
      run.step(t.s, q, 0.0, t.noise);
    }
    bool detected = false;
    for (int it = 0; it < 4 && !detected; ++it) {
      detected = run.step(t.b, q, 0.0, t.noise) == vpServoProjective::SERVO_MODEL_MISMATCH;
    }
    reRegister(t.robot, t.b, 3, t.rng, t.noise, q, 20.0);
    return detected;
  }

  NoiseFreeBump t;
  ServoRun run;
  vpColVector q;
};
} // namespace

// The switch: on by default (every 40 calls, 3 times), bad settings refused with a clear message and no change.
TEST(RigRefinement, SettingsAndTheirErrors)
{
  vpServoProjective task;
  EXPECT_TRUE(task.getRigRefinement().isEnabled());
  EXPECT_EQ(task.getRigRefinement().getPeriod(), 40u);
  EXPECT_EQ(task.getRigRefinement().getCount(), 3u);
  EXPECT_FALSE(task.getRigRefinement().isActive());
  task.getRigRefinement().setRefinement(true, 25, 2);
  EXPECT_EQ(task.getRigRefinement().getPeriod(), 25u);
  EXPECT_EQ(task.getRigRefinement().getCount(), 2u);
  EXPECT_TRUE(throwsWith([&] { task.getRigRefinement().setRefinement(true, 0, 3); },
                         vpProjectiveException::invalidValueError, "must be positive"));
  EXPECT_TRUE(throwsWith([&] { task.getRigRefinement().setRefinement(false, 40, 0); },
                         vpProjectiveException::invalidValueError, "must be positive"));
  EXPECT_TRUE(throwsWith([&] { task.getRigRefinement().setRefinement(true, 1000, 1000); },
                         vpProjectiveException::invalidValueError, "exceeds 100000"));
  EXPECT_TRUE(task.getRigRefinement().isEnabled());
  EXPECT_EQ(task.getRigRefinement().getPeriod(), 25u);
  EXPECT_EQ(task.getRigRefinement().getCount(), 2u);
  task.getRigRefinement().setRefinement(false);
  EXPECT_FALSE(task.getRigRefinement().isEnabled());
}

// Without a re-registration nothing is recorded nor refined, even on a modifiable robot.
TEST(RigRefinement, NothingWithoutReRegistration)
{
  BumpedTask b;
  for (int it = 0; it < 100; ++it) {
    b.run.step(b.t.s, b.q, 0.0, b.t.noise);
  }
  EXPECT_FALSE(b.run.task.getRigRefinement().isActive());
  EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfPoints(), 0u);
  EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfRefinements(), 0u);
  EXPECT_EQ(b.t.robot.getRigUpdate().getGeneration(), 0u);
}

// On: after updateRig(), 3 refinements every 40 moving calls, then none; each refined rig differs from the last and
// the robot's re-registration count does not change. Off, or on a robot given as const: the rig stays as updateRig()
// left it.
TEST(RigRefinement, RefinesOnlyWhenOnAndAllowed)
{
  for (int variant = 0; variant < 3; ++variant) {
    const bool on = variant != 1, modifiable = variant != 2;
    BumpedTask b(modifiable);
    b.run.task.getRigRefinement().setRefinement(on);
    ASSERT_TRUE(b.bumpAndReRegister());
    EXPECT_EQ(b.t.robot.getRigUpdate().getGeneration(), 1u);
    const Eigen::Matrix<double, 3, 8> registered = cameras(b.t.robot);
    for (int it = 0; it < 39; ++it) {
      b.run.step(b.t.b, b.q, 0.0, b.t.noise);
    }
    EXPECT_EQ(b.run.task.getRigRefinement().isActive(), on && modifiable) << variant;
    std::ostringstream printed;
    b.run.task.print(printed);
    const char *expected = !on ? "Rig refinement: off" : (modifiable ? "refining: 0 done" : "not with this robot");
    EXPECT_NE(printed.str().find(expected), std::string::npos) << printed.str();
    EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfPoints(), on && modifiable ? 39u * kTracked.size() : 0u)
        << variant;
    EXPECT_EQ(b.t.robot.getRigUpdate().getGeneration(), 1u);
    for (int it = 39; it < 200; ++it) {
      b.run.step(b.t.b, b.q, 0.0, b.t.noise);
      if (on && modifiable && it == 39) {
        EXPECT_EQ(b.t.robot.getRigUpdate().getGeneration(), 2u); // the 40th call refined
        EXPECT_GT((cameras(b.t.robot) - registered).norm(), 0.0);
      }
    }
    EXPECT_FALSE(b.run.task.getRigRefinement().isActive());
    EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfRefinements(), on && modifiable ? 3u : 0u) << variant;
    EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfFailures(), 0u) << variant;
    EXPECT_EQ(b.t.robot.getRigUpdate().getGeneration(), on && modifiable ? 4u : 1u) << variant;
    EXPECT_EQ(b.t.robot.getRigUpdate().getUpdateCount(), 1u) << variant;
    if (!(on && modifiable)) {
      EXPECT_EQ(cameras(b.t.robot), registered) << variant;
    }
    // The task ends at its original target either way here (noise-free frames).
    double deg = 0.0, metres = 0.0;
    toolPoseError(b.t.s, b.q, b.t.qTarget, deg, metres);
    EXPECT_LT(deg, 2.0) << variant;
    EXPECT_LT(metres, 0.002) << variant;
  }
}

// A feature set aside (an outlier, not tracked) never enters the refinement.
TEST(RigRefinement, FeaturesSetAsideNeverEnter)
{
  BumpedTask b;
  b.run.task.getFeatureHealth().setOutlierThreshold(3.0);
  ASSERT_TRUE(b.bumpAndReRegister());
  for (int it = 0; it < 5; ++it) {
    b.run.step(b.t.b, b.q, 0.0, b.t.noise);
  }
  const unsigned int N = static_cast<unsigned int>(kTracked.size());
  unsigned int before = b.run.task.getRigRefinement().getNumberOfPoints();
  EXPECT_EQ(before, 5 * N);
  // Feature 2 jumps by 20 px: an outlier, left out of this call's frame.
  ServoRun::measure(b.t.b, b.q, 0.0, b.t.noise, b.run.s);
  const Eigen::Vector4d s2 = b.run.s[2].getFeature();
  b.run.s[2].buildFrom(s2(0) + 20.0, s2(1), s2(2), s2(3));
  b.run.task.computeControlLaw(b.q);
  ASSERT_EQ(b.run.task.getReport().getFeatureState(2), vpServoProjective::FEATURE_OUTLIER);
  EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfPoints(), before + N - 1);
  // Feature 4 not tracked: left out too.
  before = b.run.task.getRigRefinement().getNumberOfPoints();
  b.run.task.setFeatureTracked(4, false);
  b.run.step(b.t.b, b.q, 0.0, b.t.noise);
  EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfPoints(), before + N - 1);
}

// A refinement that fails (frames no camera explains) leaves the robot, its rig and the task's targets as they were;
// the task goes on and counts it.
TEST(RigRefinement, FailureLeavesEverythingAsItWas)
{
  BumpedTask b;
  b.run.task.getRigRefinement().setRefinement(true, 10, 1);
  ASSERT_TRUE(b.bumpAndReRegister());
  b.run.step(b.t.b, b.q, 0.0, b.t.noise);          // re-expresses s* in the re-registered rig
  b.run.task.getModelMismatch().setThreshold(0.0); // the garbage below must reach the recording, not stop the task
  b.run.task.getArmFollowing().setEnabled(false);  // nor the arm kept still below
  const Eigen::Matrix<double, 3, 8> registered = cameras(b.t.robot);
  std::vector<Eigen::Vector4d> desired;
  for (unsigned int i = 0; i < kTracked.size(); ++i) {
    desired.push_back(toEigen4(b.run.task.getDesiredFeature(i)));
  }
  vpUniRand garbage(5);
  const vpColVector q = b.q;
  for (int it = 0; it < 9; ++it) { // frames no camera explains: every feature thrown by up to 60 px, the arm still
    ServoRun::measure(b.t.b, q, 0.0, b.t.noise, b.run.s);
    for (vpFeatureStereoPoint &f : b.run.s) {
      const Eigen::Vector4d v = f.getFeature();
      Eigen::Vector4d thrown; // drawn last to first: see point3(), vpProjectiveTestTools.h
      for (int i = 3; i >= 0; --i) {
        thrown(i) = v(i) + garbage.uniform(-60.0, 60.0);
      }
      f.buildFrom(thrown(0), thrown(1), thrown(2), thrown(3));
    }
    b.run.task.computeControlLaw(q);
  }
  EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfFailures(), 1u);
  EXPECT_EQ(b.run.task.getRigRefinement().getNumberOfRefinements(), 0u);
  EXPECT_FALSE(b.run.task.getRigRefinement().isActive());
  EXPECT_EQ(cameras(b.t.robot), registered);
  EXPECT_EQ(b.t.robot.getRigUpdate().getGeneration(), 1u);
  b.run.step(b.t.b, b.q, 0.0, b.t.noise);
  for (unsigned int i = 0; i < kTracked.size(); ++i) {
    EXPECT_EQ(toEigen4(b.run.task.getDesiredFeature(i)), desired[i]);
  }
}

// vpProjectiveRobot::refineRig() alone: refused without a re-registration or with sizes that differ; a failure
// leaves the model and the kept observations as they were (a later refinement still works).
TEST(RigRefinement, RobotRefineRigChecksAndFailures)
{
  NoiseFreeBump t(43, BUMP_RIGHT);
  const std::vector<Eigen::Vector4d> none;
  EXPECT_FALSE(t.robot.getRigUpdate().hasRegistration());
  EXPECT_TRUE(throwsWith([&] { t.robot.refineRig(none, none); }, vpProjectiveException::notInitializedError,
                         "updateRig() first"));
  reRegister(t.robot, t.b, 3, t.rng, t.noise);
  EXPECT_TRUE(t.robot.getRigUpdate().hasRegistration());
  const Eigen::Matrix<double, 3, 8> registered = cameras(t.robot);
  // Points of the last link seen at other joints (the markers, as a task's features would be).
  std::vector<Eigen::Vector4d> X, s;
  for (int k = 0; k < 5; ++k) {
    const vpColVector qk = visibleJoints({&t.b}, t.rng);
    vpProjectiveRobot::JointVector qe(qk.getRows());
    for (unsigned int i = 0; i < qk.getRows(); ++i) {
      qe(i) = qk[i];
    }
    const Eigen::Matrix4d H = t.robot.getModel().displacement(qe);
    for (unsigned int j : kTracked) {
      X.push_back(H * t.robot.getModel().markers()[j]);
      s.push_back(t.b.imageOf(t.b.armJoints(qk), j));
    }
  }
  EXPECT_TRUE(throwsWith([&] { t.robot.refineRig(X, none); }, vpProjectiveException::dimensionError, "one per point"));
  std::vector<Eigen::Vector4d> wrong = s;
  for (size_t k = 0; k < wrong.size(); ++k) {
    wrong[k] += Eigen::Vector4d(40.0, -40.0, 40.0, 40.0) * (k % 2 == 0 ? 1.0 : -1.0);
  }
  EXPECT_TRUE(throwsWith([&] { t.robot.refineRig(X, wrong); }, vpProjectiveException::estimationFailedError,
                         "does not explain"));
  EXPECT_EQ(cameras(t.robot), registered);
  EXPECT_EQ(t.robot.getRigUpdate().getGeneration(), 1u);
  // The observations of the update are kept: a refinement from good points works, and predicts the bumped rig better.
  std::vector<vpColVector> test;
  for (int k = 0; k < 5; ++k) {
    test.push_back(visibleJoints({&t.b}, t.rng));
  }
  vpGaussRand quiet(1.0, 0.0, 3);
  const double before = predictionError(t.robot, t.b, test, quiet, 0.0);
  t.robot.refineRig(X, s);
  EXPECT_EQ(t.robot.getRigUpdate().getGeneration(), 2u);
  EXPECT_EQ(t.robot.getRigUpdate().getUpdateCount(), 1u);
  EXPECT_LT(predictionError(t.robot, t.b, test, quiet, 0.0), before);
}

// The points the refinement pairs with the images after a re-registration are the old rig's triangulations
// (vpServoModelMismatch::getTriangulatedMemory()), the frame of the task's re-expressed s*; for an acquired marker,
// which the mismatch check remembers as the model's point, the mean of both (vpServoRigRefinement::start()). The two
// memories differ: the model's point from what the rig saw by the arm model's own error (a model acquired at 0.5 px),
// the triangulations by the noise of the few calls they average (none here: noise-free images).
TEST(RigRefinement, PointsInTheFrameOfTheRigThatSawThem)
{
  const ArmSetup s = pumaEyeToHand();
  vpGaussRand noise(1.0, 0.0, 18);
  vpUniRand rng(18);
  const vpProjectiveRobot robot = acquiredRobot(s, noise);
  const vpProjectiveArmModel &model = robot.getModel();
  const vpColVector q = jointsNear({&s}, rng, vpColVector(s.n(), 0.0), 20.0);
  const unsigned int K = static_cast<unsigned int>(model.markers().size());
  vpProjectiveArmModel::JointVector qe(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    qe(i) = q[i];
  }
  vpServoProjectiveData data;
  vpServoModelMismatch mismatch;
  mismatch.resize(K);
  for (int it = 0; it < 3; ++it) { // a task at rest: three agreeing iterations at q, noise-free images
    data.computeKinematics(model, qe, K);
    for (unsigned int j = 0; j < K; ++j) {
      data.computeFeature(model, j, s.imageOf(s.armJoints(q), j));
    }
    mismatch.startIteration(model, data);
    for (unsigned int j = 0; j < K; ++j) {
      mismatch.observe(j, true);
    }
    EXPECT_FALSE(mismatch.endIteration());
  }
  double triangulated2 = 0.0, markers2 = 0.0;
  for (unsigned int j = 0; j < K; ++j) {
    Eigen::Vector4d M, T, sT, sM;
    ASSERT_TRUE(mismatch.isMemoryExact(j)) << "marker " << j;
    ASSERT_TRUE(mismatch.getMemory(j, M) && mismatch.getTriangulatedMemory(j, T));
    EXPECT_LT((M - model.markers()[j].normalized()).norm(), 1e-12); // the model's point
    EXPECT_NEAR(T.norm(), 1.0, 1e-12);
    ASSERT_TRUE(data.predict(T, sT) && data.predict(M, sM));
    triangulated2 += (sT - s.imageOf(s.armJoints(q), j)).squaredNorm();
    markers2 += (sM - s.imageOf(s.armJoints(q), j)).squaredNorm();
  }
  const double triangulated = std::sqrt(triangulated2 / (4.0 * K)), markers = std::sqrt(markers2 / (4.0 * K));
  testLog() << "[ measured ] images of the memories at the joints of their triangulations, RMS: triangulated "
            << triangulated << " px, acquired markers' points " << markers << " px" << std::endl;
  EXPECT_LT(triangulated, 0.1);           // what that rig saw, but for its epipolar error (0.08 px here)
  EXPECT_GT(markers, 2.0 * triangulated); // the arm model's own error
  mismatch.reset();
  Eigen::Vector4d T;
  EXPECT_FALSE(mismatch.getTriangulatedMemory(0, T)); // forgotten with the rig (a re-registration)
}
