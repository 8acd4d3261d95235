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
  Global servoing against the simulator's truth:
  - vpProjectiveInverseKinematics::solveAll() and the planner find every inverse-kinematic branch of noise-free PUMA
    and Viper850 targets that a dense multi-start finds, and every branch is a true one (the simulated arm there
    shows the desired images);
  - plans stay inside the joint limits and keep the features in view (the simulator's images, not only the model's
    predictions), one needs a waypoint, and the cases without a plan say so;
  - vpServoProjective with path planning reaches targets that law (47) alone misses, and stops with SERVO_NO_PLAN
    and a zero velocity when no plan exists.
*/

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveInverseKinematics.h>
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
typedef vpProjectivePathPlanner::JointVector JointVector;

//! The model acquired from noise-free images.
vpProjectiveRobot acquireNoiseFree(const ArmSetup &s)
{
  vpProjectiveRobot robot(s.jointTypes());
  vpGaussRand noise(1.0, 0.0, 1);
  EXPECT_TRUE(s.acquire(robot, 0.0, noise)) << s.name;
  robot.calibrate();
  return robot;
}

JointVector toJoints(const vpColVector &q)
{
  JointVector v(q.size());
  for (unsigned int i = 0; i < q.size(); ++i) {
    v(i) = q[i];
  }
  return v;
}

vpColVector toVisp(const JointVector &q)
{
  vpColVector v(static_cast<unsigned int>(q.size()));
  for (unsigned int i = 0; i < v.size(); ++i) {
    v[i] = q(i);
  }
  return v;
}

//! Largest joint difference, revolute joints (all of them here) modulo a turn.
double branchDistance(const JointVector &a, const JointVector &b)
{
  double d = 0.0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(std::remainder(a(i) - b(i), 2.0 * M_PI)));
  }
  return d;
}

//! True images (u, v, u', v') of the markers \e tracked at model joints q.
std::vector<Eigen::Vector4d> trueImages(const ArmSetup &s, const vpColVector &q,
                                        const std::vector<unsigned int> &tracked)
{
  std::vector<Eigen::Vector4d> images;
  for (unsigned int j : tracked) {
    images.push_back(s.imageOf(s.armJoints(q), j));
  }
  return images;
}

std::vector<unsigned int> allMarkers(const ArmSetup &s)
{
  std::vector<unsigned int> tracked(s.numberOfMarkers());
  for (unsigned int j = 0; j < tracked.size(); ++j) {
    tracked[j] = j;
  }
  return tracked;
}

//! The model's zero-reference points of the markers \e tracked.
std::vector<Eigen::Vector4d> modelPoints(const vpProjectiveRobot &robot, const std::vector<unsigned int> &tracked)
{
  std::vector<Eigen::Vector4d> points;
  for (unsigned int j : tracked) {
    points.push_back(robot.getModel().markers()[j]);
  }
  return points;
}

//! True when the simulated markers \e tracked at model joints q are in front of both cameras and \e border px inside.
bool trulyInView(const ArmSetup &s, const vpColVector &q, const std::vector<unsigned int> &tracked, double border)
{
  const vpSimulatorStereoRig sim = s.simAt(s.armJoints(q));
  const std::vector<vpColVector> X = s.markersAt(s.armJoints(q));
  for (unsigned int j : tracked) {
    if (!sim.isVisible(X[j], border)) {
      return false;
    }
  }
  return true;
}

struct SetupCase {
  const char *label;
  ArmSetup (*make)();
  double rangeDeg; //!< targets drawn within +-rangeDeg of the zero reference
};

void PrintTo(const SetupCase &setup, std::ostream *os)
{
  *os << setup.label;
}

const SetupCase kSetups[] = {{"PumaEyeToHand", pumaEyeToHand, 30.0}, {"Viper850EyeToHand", viperEyeToHand, 15.0}};

class PathPlannerArms : public ::testing::TestWithParam<SetupCase>
{
};

INSTANTIATE_TEST_SUITE_P(Arms, PathPlannerArms, ::testing::ValuesIn(kSetups),
                         [](const ::testing::TestParamInfo<SetupCase> &info) { return info.param.label; });
} // namespace

TEST_P(PathPlannerArms, InverseKinematicsFindsEveryBranch)
{
  const ArmSetup s = GetParam().make();
  const vpProjectiveRobot robot = acquireNoiseFree(s);
  const vpProjectiveArmModel &model = robot.getModel();
  const std::vector<unsigned int> tracked = allMarkers(s);
  const std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked);
  vpUniRand rng(7);
  const std::vector<double> range(s.n(), vpMath::rad(GetParam().rangeDeg));
  for (int task = 0; task < 3; ++task) {
    const vpColVector qStart = s.randomVisibleJoints(rng, range), qTarget = s.randomVisibleJoints(rng, range);
    ASSERT_EQ(qTarget.size(), s.n());
    const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
    // The reference: a dense multi-start over the whole turn of every joint.
    const JointVector qmin = JointVector::Constant(s.n(), -M_PI), qmax = JointVector::Constant(s.n(), M_PI);
    std::vector<double> residuals;
    const std::vector<JointVector> dense =
        vpProjectiveInverseKinematics::solveAll(model, sStar, points, toJoints(qStart), qmin, qmax, 1500, &residuals);
    vpProjectivePathPlanner planner;
    planner.plan(model, toJoints(qStart), points, sStar);
    const std::vector<JointVector> &found = planner.getBranches();
    unsigned int exact = 0;
    for (size_t b = 0; b < dense.size(); ++b) {
      if (residuals[b] > 1e-6) {
        continue; // not an exact solution of the noise-free images
      }
      ++exact;
      double nearest = M_PI;
      for (const JointVector &f : found) {
        nearest = std::min(nearest, branchDistance(f, dense[b]));
      }
      EXPECT_LT(nearest, 1e-4) << s.name << " task " << task << ": the planner missed branch " << b << " of "
                               << dense.size() << " (" << dense[b].transpose() << ")";
    }
    EXPECT_GE(exact, 2u) << s.name << ": a 6R arm with a spherical wrist has at least the two wrist branches";
    // Every branch is true: the simulated arm there shows the desired images; the true target is one of them.
    double nearestToTruth = M_PI;
    for (const JointVector &f : found) {
      const std::vector<Eigen::Vector4d> images = trueImages(s, toVisp(f), tracked);
      for (size_t k = 0; k < images.size(); ++k) {
        EXPECT_LT((images[k] - sStar[k]).cwiseAbs().maxCoeff(), 1e-3) << s.name << " branch " << f.transpose();
      }
      nearestToTruth = std::min(nearestToTruth, branchDistance(f, toJoints(qTarget)));
    }
    EXPECT_LT(nearestToTruth, 1e-4) << s.name << " task " << task;
    std::cout << s.name << " task " << task << ": " << exact << " exact branches by 1500 starts, " << found.size()
              << " found by the planner's default starts" << std::endl;
  }
}

TEST(PathPlanner, PlansStayInsideLimitsAndView)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = acquireNoiseFree(s);
  const std::vector<unsigned int> tracked = {0, 1, 2};
  const std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked);
  const double border = 10.0, step = vpMath::rad(5.0);
  const JointVector qmin = JointVector::Constant(s.n(), vpMath::rad(-50.0));
  const JointVector qmax = JointVector::Constant(s.n(), vpMath::rad(50.0));
  vpProjectivePathPlanner planner;
  planner.setJointLimits(qmin, qmax);
  planner.setImageSize(s.width, s.height, border);
  planner.setMaxJointStep(step);
  vpUniRand rng(11);
  const std::vector<double> range(s.n(), vpMath::rad(40.0));
  unsigned int kinds[3] = {0, 0, 0};
  for (int task = 0; task < 12; ++task) {
    const vpColVector qStart = s.randomVisibleJoints(rng, range, border + 2.0);
    const vpColVector qTarget = s.randomVisibleJoints(rng, range, border + 2.0);
    const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
    ASSERT_EQ(planner.plan(robot.getModel(), toJoints(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
        << "task " << task << ": " << planner.getDescription();
    ++kinds[planner.getPathKind()];
    const std::vector<JointVector> &path = planner.getPath();
    EXPECT_LT((path.front() - toJoints(qStart)).norm(), 1e-12);
    EXPECT_LT((path.back() - planner.getTarget()).norm(), 1e-12);
    for (size_t j = 0; j < path.size(); ++j) {
      EXPECT_TRUE((path[j].array() >= qmin.array()).all() && (path[j].array() <= qmax.array()).all())
          << "task " << task << " sample " << j;
      EXPECT_TRUE(trulyInView(s, toVisp(path[j]), tracked, border - 0.01)) << "task " << task << " sample " << j;
      if (j > 0) {
        EXPECT_LE((path[j] - path[j - 1]).cwiseAbs().maxCoeff(), step + 1e-12) << "task " << task << " sample " << j;
      }
    }
    // The target shows s*, truly.
    const std::vector<Eigen::Vector4d> reached = trueImages(s, toVisp(planner.getTarget()), tracked);
    for (size_t k = 0; k < tracked.size(); ++k) {
      EXPECT_LT((reached[k] - sStar[k]).cwiseAbs().maxCoeff(), 1e-3) << "task " << task;
    }
  }
  std::cout << "path kinds: " << kinds[0] << " straight image lines, " << kinds[1] << " joint lines, " << kinds[2]
            << " waypoints" << std::endl;
  EXPECT_GT(kinds[vpProjectivePathPlanner::PATH_IMAGE_LINE], 0u);
}

TEST(PathPlanner, FindsAWaypointWhenTheLinesLeaveTheView)
{
  // Tasks drawn (seeded) in a wide box with a narrow image window, until one needs a waypoint: then the joint-space
  // line truly leaves the window and the plan truly stays inside.
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = acquireNoiseFree(s);
  const std::vector<unsigned int> tracked = {0, 1, 2};
  const std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked);
  const double border = 60.0;
  vpProjectivePathPlanner planner;
  planner.setImageSize(s.width, s.height, border);
  vpUniRand rng(3);
  const std::vector<double> range(s.n(), vpMath::rad(60.0));
  bool found = false;
  for (int task = 0; task < 300 && !found; ++task) {
    const vpColVector qStart = s.randomVisibleJoints(rng, range, border + 2.0);
    const vpColVector qTarget = s.randomVisibleJoints(rng, range, border + 2.0);
    if (planner.plan(robot.getModel(), toJoints(qStart), points, trueImages(s, qTarget, tracked)) !=
            vpProjectivePathPlanner::PLAN_FOUND ||
        planner.getPathKind() != vpProjectivePathPlanner::PATH_WAYPOINT) {
      continue;
    }
    found = true;
    bool lineInView = true;
    const JointVector q0 = toJoints(qStart), q1 = planner.getTarget();
    for (int j = 0; j <= 100; ++j) {
      lineInView = lineInView && trulyInView(s, toVisp(q0 + (j / 100.0) * (q1 - q0)), tracked, border);
    }
    EXPECT_FALSE(lineInView) << "task " << task << ": the joint line stays in view, no waypoint was needed";
    for (const JointVector &q : planner.getPath()) {
      EXPECT_TRUE(trulyInView(s, toVisp(q), tracked, border - 0.01)) << "task " << task;
    }
  }
  EXPECT_TRUE(found) << "no task of 300 needed a waypoint";
}

TEST(PathPlanner, SaysWhenThereIsNoPlan)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = acquireNoiseFree(s);
  const std::vector<unsigned int> tracked = {0, 1, 2};
  const std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked);
  vpColVector qStart(s.n(), 0.0), qTarget(s.n(), 0.0);
  qTarget[0] = vpMath::rad(20.0);
  qTarget[4] = vpMath::rad(-15.0);
  const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
  vpProjectivePathPlanner planner;
  ASSERT_EQ(planner.plan(robot.getModel(), toJoints(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
      << planner.getDescription();
  const std::vector<JointVector> pathBefore = planner.getPath();

  // Bad input throws and leaves the plan as it was.
  EXPECT_THROW(planner.plan(robot.getModel(), JointVector::Zero(3), points, sStar), vpException);
  std::vector<Eigen::Vector4d> nanStar = sStar;
  nanStar[1](2) = std::nan("");
  EXPECT_THROW(planner.plan(robot.getModel(), toJoints(qStart), points, nanStar), vpException);
  EXPECT_EQ(planner.getStatus(), vpProjectivePathPlanner::PLAN_FOUND);
  EXPECT_EQ(planner.getPath().size(), pathBefore.size());
  EXPECT_THROW(planner.setJointLimits(JointVector::Constant(6, 1.0), JointVector::Constant(6, 0.0)), vpException);
  EXPECT_THROW(planner.setImageSize(640, 0), vpException);
  EXPECT_THROW(planner.setImageSize(640, 480, 300.0), vpException);
  EXPECT_THROW(planner.setMaxJointStep(0.0), vpException);
  EXPECT_THROW(planner.setNumberOfStarts(0), vpException);
  EXPECT_THROW(planner.setMaxResidual(-1.0), vpException);

  // Limits that hold the start but no branch of the target.
  planner.setJointLimits(JointVector::Constant(6, vpMath::rad(-10.0)), JointVector::Constant(6, vpMath::rad(10.0)));
  EXPECT_EQ(planner.plan(robot.getModel(), toJoints(qStart), points, sStar),
            vpProjectivePathPlanner::PLAN_OUTSIDE_JOINT_LIMITS)
      << planner.getDescription();
  EXPECT_TRUE(planner.getPath().empty());
  planner.setJointLimits(JointVector(), JointVector());

  // Desired features no configuration shows: one of them 150 px off its place in both images.
  std::vector<Eigen::Vector4d> impossible = sStar;
  impossible[2] += Eigen::Vector4d(150.0, 0.0, 150.0, 0.0);
  EXPECT_EQ(planner.plan(robot.getModel(), toJoints(qStart), points, impossible),
            vpProjectivePathPlanner::PLAN_NO_INVERSE_KINEMATICS)
      << planner.getDescription();

  // A window that the target's features are outside of.
  std::vector<Eigen::Vector4d> sStarWindow = sStar;
  double uMax = 0.0;
  for (const Eigen::Vector4d &f : sStar) {
    uMax = std::max(uMax, std::max(f(0), f(2)));
  }
  planner.setImageSize(static_cast<unsigned int>(uMax) + 5, s.height, 10.0);
  EXPECT_EQ(planner.plan(robot.getModel(), toJoints(qStart), points, sStarWindow),
            vpProjectivePathPlanner::PLAN_NO_VISIBLE_PATH)
      << planner.getDescription();
}

namespace
{
//! A servo run on the true arm (noise-free images of \e tracked): iterations to reach 1e-3 px RMS, or -1.
int runServo(const ArmSetup &s, const vpProjectiveRobot &robot, const std::vector<unsigned int> &tracked, vpColVector q,
             const vpColVector &qTarget, bool planning, const vpColVector &qmin, const vpColVector &qmax,
             double &largestExcursion)
{
  std::vector<vpFeatureStereoPoint> f(tracked.size()), fStar(tracked.size());
  const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
  vpServoProjective task;
  task.setRobot(robot);
  task.setLambda(0.5);
  task.setMaxJointVelocity(vpMath::rad(15.0));
  task.setDamping(30.0, 30.0);
  task.setImageSize(s.width, s.height, 10.0);
  task.setJointLimits(qmin, qmax);
  task.setPathPlanning(planning);
  for (size_t k = 0; k < tracked.size(); ++k) {
    fStar[k].buildFrom(sStar[k](0), sStar[k](1), sStar[k](2), sStar[k](3));
    task.addFeature(f[k], fStar[k]);
  }
  const vpColVector qStart = q;
  largestExcursion = 0.0;
  for (int it = 0; it < 100; ++it) {
    if (!trulyInView(s, q, tracked, 0.0)) {
      return -1;
    }
    const std::vector<Eigen::Vector4d> sNow = trueImages(s, q, tracked);
    double error = 0.0;
    for (size_t k = 0; k < tracked.size(); ++k) {
      f[k].buildFrom(sNow[k](0), sNow[k](1), sNow[k](2), sNow[k](3));
      error += (sNow[k] - sStar[k]).squaredNorm();
    }
    if (std::sqrt(error / (4.0 * tracked.size())) < 1e-3) {
      return it;
    }
    const vpColVector qdot = task.computeControlLaw(q);
    q = s.arm.integrate(s.armJoints(q), qdot, 1.0) - s.qRef;
    for (unsigned int i = 0; i < q.size(); ++i) {
      const double lo = std::min(qStart[i], qTarget[i]), hi = std::max(qStart[i], qTarget[i]);
      largestExcursion = std::max(largestExcursion, std::max(lo - q[i], q[i] - hi));
    }
  }
  return -1;
}
} // namespace

TEST(PathPlanner, PlannedServoReachesWideTargets)
{
  // Three tracked markers, tasks within +-60 deg (same branch or not): law (47) meets local minima and lost
  // features; the planned servo reaches every target, with joints that stay near their [start, target] intervals.
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = acquireNoiseFree(s);
  const std::vector<unsigned int> tracked = {0, 1, 2};
  const vpColVector qmin(s.n(), vpMath::rad(-80.0)), qmax(s.n(), vpMath::rad(80.0));
  vpUniRand rng(5);
  const std::vector<double> range(s.n(), vpMath::rad(60.0));
  const int tasks = 10;
  int planned = 0, law = 0;
  double worstExcursion = 0.0;
  for (int task = 0; task < tasks; ++task) {
    const vpColVector qStart = s.randomVisibleJoints(rng, range, 20.0);
    const vpColVector qTarget = s.randomVisibleJoints(rng, range, 20.0);
    double excursion = 0.0, unused = 0.0;
    const int itPlanned = runServo(s, robot, tracked, qStart, qTarget, true, qmin, qmax, excursion);
    planned += itPlanned >= 0;
    worstExcursion = std::max(worstExcursion, excursion);
    law += runServo(s, robot, tracked, qStart, qTarget, false, qmin, qmax, unused) >= 0;
    EXPECT_GE(itPlanned, 0) << "task " << task;
  }
  std::cout << "wide tasks reached: planned " << planned << "/" << tasks << ", law (47) " << law << "/" << tasks
            << "; largest planned excursion beyond [start, target] " << vpMath::deg(worstExcursion) << " deg"
            << std::endl;
  EXPECT_LT(worstExcursion, vpMath::rad(20.0));
}

TEST(PathPlanner, ServoStopsWithoutAPlan)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = acquireNoiseFree(s);
  const std::vector<unsigned int> tracked = {0, 1, 2};
  vpColVector q(s.n(), 0.0), qTarget(s.n(), 0.0);
  qTarget[0] = vpMath::rad(20.0);
  std::vector<vpFeatureStereoPoint> f(3), fStar(3);
  const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked), sNow = trueImages(s, q, tracked);
  vpServoProjective task;
  task.setRobot(robot);
  task.setJointLimits(vpColVector(s.n(), vpMath::rad(-10.0)), vpColVector(s.n(), vpMath::rad(10.0)));
  task.setPathPlanning(true);
  for (size_t k = 0; k < 3; ++k) {
    f[k].buildFrom(sNow[k](0), sNow[k](1), sNow[k](2), sNow[k](3));
    fStar[k].buildFrom(sStar[k](0), sStar[k](1), sStar[k](2), sStar[k](3));
    task.addFeature(f[k], fStar[k]);
  }
  for (int it = 0; it < 2; ++it) {
    const vpColVector qdot = task.computeControlLaw(q);
    EXPECT_EQ(task.getStatus(), vpServoProjective::SERVO_NO_PLAN);
    EXPECT_EQ(qdot.frobeniusNorm(), 0.0);
  }
  EXPECT_THROW(task.getPlannedTarget(), vpException);
  // Without planning the same task runs law (47).
  task.setPathPlanning(false);
  EXPECT_GT(task.computeControlLaw(q).frobeniusNorm(), 0.0);
  // Limits that hold the target: a plan, and its target is the true one.
  task.setJointLimits(vpColVector(s.n(), vpMath::rad(-30.0)), vpColVector(s.n(), vpMath::rad(30.0)));
  task.setPathPlanning(true);
  task.computeControlLaw(q);
  EXPECT_NE(task.getStatus(), vpServoProjective::SERVO_NO_PLAN);
  EXPECT_LT((task.getPlannedTarget() - qTarget).frobeniusNorm(), 1e-4);
}
