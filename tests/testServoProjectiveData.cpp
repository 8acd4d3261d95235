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
  Tests of the servo's data layer (vpServoProjectiveData) and of how a new model or rig reaches a task:
  - one computeControlLaw() computes H(q) exactly once (vpServoProjectiveData::getDisplacementCount()) and factorises
    J^T J once (vpServoNormalEquations::getFactorisationCount(): the Cholesky factorisation, plus the eigen
    decomposition when the joint-limit avoidance needs its projector), whatever
    part of the servo runs: law (47) with the default model-mismatch check, feature health with the image window
    and outlier rejection (epipolar and prediction tests), a feature set aside, joint limits, settling, path planning
    and its following; the data's H(q), joint motions and points are the model's, to the bit, and its prediction
    (predict()) is the rig's projection of H(q) M0, to the bit;
  - the robot tells its tasks of a new model (calibrate(), loadModel(), an assignment): a task forgets its
    model-mismatch memories at its next call, a copy of the task too, and a task on a destroyed robot throws instead
    of reading freed memory.
*/

#include <memory>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpServoNormalEquations.h>
#include <visp3/projective/vpServoProjectiveData.h>

#include "vpProjectiveArmTestTools.h"
#include "vpProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{
vpProjectiveRobot::JointVector toJoints(const vpColVector &q)
{
  vpProjectiveRobot::JointVector qe(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    qe(i) = q[i];
  }
  return qe;
}

//! The paper's task on 4 markers: the features follow the simulated arm (noise-free), s* at the target.
struct Task {
  const ArmSetup &setup;
  std::vector<vpFeatureStereoPoint> s, sStar;
  vpServoProjective task;
  vpColVector q;

  Task(const ArmSetup &armSetup, const vpProjectiveRobot &robot)
      : setup(armSetup), s(4), sStar(4), task(), q(paperTaskStart())
  {
    task.setRobot(robot);
    task.setLambda(0.5);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(15.0));
    for (unsigned int k = 0; k < 4; ++k) {
      const Eigen::Vector4d target = setup.imageOf(setup.armJoints(paperTaskTarget()), k);
      sStar[k].buildFrom(target(0), target(1), target(2), target(3));
      task.addFeature(s[k], sStar[k]);
    }
    see();
  }

  void see()
  {
    for (unsigned int k = 0; k < 4; ++k) {
      const Eigen::Vector4d m = setup.imageOf(setup.armJoints(q), k);
      s[k].buildFrom(m(0), m(1), m(2), m(3));
    }
  }

  //! One iteration: q moves by qdot, the features follow; \e seen receives the features the iteration used.
  void step()
  {
    seen.clear();
    for (const vpFeatureStereoPoint &f : s) {
      seen.push_back(f.getFeature());
    }
    q += task.computeControlLaw(q);
    see();
  }
  std::vector<Eigen::Vector4d> seen;
};

//! The data of the last iteration is the model's at the joints it was computed at, to the bit.
void expectModelData(const vpServoProjective &task, const vpProjectiveArmModel &model,
                     const std::vector<vpFeatureStereoPoint> &s, const std::vector<Eigen::Vector4d> &seen)
{
  const vpServoProjectiveData &d = task.getReport().getData();
  ASSERT_EQ(d.getDisplacementCount(), 1u) << "H(q) computed more than once in one iteration";
  // J^T J factorised once by Cholesky (every part reads it), and at most once more by its eigen decomposition (the
  // joint-limit avoidance's null-space projector, the damping near a singularity).
  const vpServoNormalEquations &ne = d.getNormalEquations();
  EXPECT_GE(ne.getFactorisationCount(), 1u);
  EXPECT_LE(ne.getFactorisationCount(), 2u) << "J^T J factorised more than once in one iteration";
  vpServoNormalEquations rebuilt;
  rebuilt.compute(d.getTaskJacobian(), d.getError());
  EXPECT_EQ(Eigen::MatrixXd(ne.getJtJ()), Eigen::MatrixXd(rebuilt.getJtJ()));
  const Eigen::Matrix4d H = model.displacement(d.getJoints());
  // The same exponentials, to rounding (H is far from orthogonal: entries from 1e-3 to 3e2 here, and the rounding of
  // its products grows with it).
  EXPECT_LT((d.getDisplacement() - H).norm(), 1e-10 * H.norm());
  EXPECT_LT((d.getDisplacementInverse() * H - Eigen::Matrix4d::Identity()).norm(), 1e-6);
  vpProjectiveArmData arm;
  vpProjectiveKinematics::forwardKinematics(model, arm, d.getJoints());
  for (unsigned int k = 0; k < model.getNumberOfJoints(); ++k) {
    EXPECT_EQ(d.getArmData().getJointMotions()[k], arm.getJointMotions()[k]) << "joint " << k;
  }
  ASSERT_EQ(d.getNumberOfFeatures(), s.size());
  for (unsigned int i = 0; i < s.size(); ++i) {
    const Eigen::Vector4d &si = d.getFeature(i); // the features seen by that call
    ASSERT_TRUE(d.hasPoint(i));
    EXPECT_EQ(d.getFeature(i), seen[i]) << "feature " << i;
    EXPECT_EQ(d.getPoint(i), model.getStereoRig().triangulateLinear(si.head<2>(), si.tail<2>())) << "feature " << i;
    EXPECT_NEAR((model.displacement(d.getJoints()) * d.getZeroPoint(i))
                    .normalized()
                    .cwiseAbs()
                    .dot(d.getPoint(i).normalized().cwiseAbs()),
                1.0, 1e-9)
        << "feature " << i << ": M0 = H(q)^-1 M";
    // The checks' prediction is the rig's projection of H(q) M0, to the bit, and the rig's projection without its
    // Jacobian (the checks' path) gives the bits of the one with it.
    Eigen::Vector4d predicted, projected, withJacobian;
    Eigen::Matrix4d L;
    ASSERT_TRUE(d.predict(d.getZeroPoint(i), predicted)) << "feature " << i;
    ASSERT_TRUE(model.getStereoRig().project(Eigen::Vector4d(d.getDisplacement() * d.getZeroPoint(i)), projected));
    ASSERT_TRUE(
        model.getStereoRig().project(Eigen::Vector4d(d.getDisplacement() * d.getZeroPoint(i)), withJacobian, &L));
    EXPECT_EQ(predicted, projected) << "feature " << i;
    EXPECT_EQ(projected, withJacobian) << "feature " << i;
  }
}
} // namespace

TEST(ServoProjectiveData, OneDisplacementPerIterationWithEveryCheckOn)
{
  const ArmSetup setup = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(setup, 0.1, 3);
  const vpProjectiveArmModel &model = robot.getModel();

  // Law (47) with its default check (model mismatch).
  Task plain(setup, robot);
  for (int k = 0; k < 5; ++k) {
    plain.step();
    expectModelData(plain.task, model, plain.s, plain.seen);
    EXPECT_EQ(plain.task.getReport().getData().getNormalEquations().getFactorisationCount(), 1u) << "call " << k;
  }
  // The adaptive gain on J^+ e and settling read the law's Gauss-Newton step: still one factorisation.
  Task adaptive(setup, robot);
  adaptive.task.getControlLaw().setLambda(1.0, 0.3, 20.0);
  adaptive.task.getControlLaw().setAdaptiveGainInput(vpServoControlLaw::GAIN_INPUT_JOINT_VELOCITY);
  adaptive.task.setSettling(true);
  for (int k = 0; k < 5; ++k) {
    adaptive.step();
    expectModelData(adaptive.task, model, adaptive.s, adaptive.seen);
    EXPECT_EQ(adaptive.task.getReport().getData().getNormalEquations().getFactorisationCount(), 1u) << "call " << k;
  }
  EXPECT_EQ(plain.task.getModelMismatch().getThreshold(), 5.0); // the default check ran

  // Every check on: image window, outlier rejection with predictions, a lost feature, joint limits, settling.
  Task checked(setup, robot);
  checked.task.setImageSize(setup.width, setup.height, 10);
  checked.task.getFeatureHealth().setOutlierThreshold(5.0);
  vpColVector qmin(6), qmax(6);
  for (unsigned int i = 0; i < 6; ++i) {
    qmin[i] = checked.q[i] - vpMath::rad(100.0);
    qmax[i] = checked.q[i] + vpMath::rad(100.0);
  }
  qmin[0] = checked.q[0] - vpMath::rad(5.0); // joint 0 starts in its activation band
  checked.task.setJointLimits(qmin, qmax);
  checked.task.setSettling(true);
  for (int k = 0; k < 8; ++k) {
    checked.task.setFeatureTracked(3, k < 4); // lost from the 5th iteration on
    checked.step();
    expectModelData(checked.task, model, checked.s, checked.seen);
    EXPECT_GE(checked.task.getFeatureHealth().getPredictionDistance(0), k > 0 ? 0.0 : -1.0); // the prediction test ran
  }
  EXPECT_EQ(checked.task.getStatus(), vpServoProjective::SERVO_REDUCED);
  EXPECT_EQ(checked.task.getReport().getFeatureState(3), vpServoProjective::FEATURE_NOT_TRACKED);

  // Path planning and following.
  Task planned(setup, robot);
  planned.task.setImageSize(setup.width, setup.height, 10);
  planned.task.setPathPlanning(true);
  planned.task.getPathPlanner().setMaxJointStep(vpMath::rad(2.0));
  planned.task.getPathPlanner().setRehearsalBudget(0); // a path to follow
  bool followed = false;
  for (int k = 0; k < 6; ++k) {
    planned.step();
    ASSERT_NE(planned.task.getStatus(), vpServoProjective::SERVO_NO_PLAN)
        << planned.task.getPathPlanner().getDescription();
    expectModelData(planned.task, model, planned.s, planned.seen);
    followed = followed || planned.task.getReport().isFollowingPath();
  }
  EXPECT_TRUE(followed);
}

TEST(ServoProjectiveData, TheRobotTellsItsTasksOfANewModel)
{
  const ArmSetup setup = pumaEyeToHand();
  vpProjectiveRobot robot = calibratedRobot(setup, 0.1, 3);
  const vpProjectiveRobot other = calibratedRobot(setup, 0.1, 4);
  Task t(setup, robot);
  for (int k = 0; k < 3; ++k) {
    t.step(); // the features agree with the model: remembered
  }
  EXPECT_GE(t.task.getModelMismatch().getDistance(0), 0.0);
  vpServoProjective copy = t.task; // attached to the robot too
  robot = other;                   // a new model: the robot tells both tasks
  t.step();
  EXPECT_EQ(t.task.getModelMismatch().getDistance(0), -1.0); // memories of the old model forgotten
  copy.computeControlLaw(t.q);
  EXPECT_EQ(copy.getModelMismatch().getDistance(0), -1.0);
  t.step();
  t.step();
  EXPECT_GE(t.task.getModelMismatch().getDistance(0), 0.0); // remembered again on the new model
  expectModelData(t.task, robot.getModel(), t.s, t.seen);

  // A task on a destroyed robot says so.
  std::unique_ptr<vpProjectiveRobot> gone(new vpProjectiveRobot(other));
  Task orphan(setup, *gone);
  orphan.step();
  gone.reset();
  EXPECT_TRUE(throwsProjective([&] { orphan.task.computeControlLaw(orphan.q); },
                               vpProjectiveException::notInitializedError, "call setRobot() first"));
}
