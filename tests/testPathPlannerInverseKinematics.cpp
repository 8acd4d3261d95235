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
  Global servoing on the model, against the simulator's truth:
  - vpProjectiveInverseKinematics::solveAll() and the planner find every inverse-kinematic branch of noise-free PUMA
    and Viper850 targets that a dense multi-start finds, and every branch is a true one (the simulated arm there
    shows the desired images); an extra start in the target's basin finds its branch;
  - the two-view refinement of the points brings the residual to the noise, and the planner recognises the acquired
    markers among the features and solves the target with their points.
*/

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveInverseKinematics.h>
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "vpPathPlannerTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! Tasks with noisy images on markers 0-2 of a noise-free model, drawn one after the other (next()): start and target
//! within +-rangeDeg, the images seen at the start and s* at the target with kSigma px of noise, and the points
//! triangulated from the seen images by the model's rig and carried to the zero reference by H(q_start)^-1, as
//! vpServoProjective does.
struct NoisyTasks {
  static constexpr double kSigma = 0.5;
  const ArmSetup s;
  const vpProjectiveRobot robot;
  const vpProjectiveArmModel &model;
  const std::vector<unsigned int> tracked = {0, 1, 2};
  const std::vector<double> range;
  vpUniRand rng;
  vpGaussRand noise;

  NoisyTasks(const ArmSetup &setup, double rangeDeg, long drawSeed, long noiseSeed)
      : s(setup), robot(calibratedRobot(s)), model(robot.getModel()), range(s.n(), vpMath::rad(rangeDeg)),
        rng(drawSeed), noise(kSigma, 0.0, noiseSeed)
  {
  }

  struct Task {
    vpColVector qStart, qTarget;
    std::vector<Eigen::Vector4d> seen, sStar, points;
  };

  Task next()
  {
    Task t;
    t.qStart = s.randomVisibleJoints(rng, range);
    t.qTarget = s.randomVisibleJoints(rng, range);
    t.seen = trueImages(s, t.qStart, tracked);
    t.sStar = trueImages(s, t.qTarget, tracked);
    for (size_t k = 0; k < tracked.size(); ++k) {
      for (int c = 0; c < 4; ++c) {
        t.seen[k](c) += noise();
        t.sStar[k](c) += noise();
      }
    }
    const Eigen::PartialPivLU<Eigen::Matrix4d> H(model.displacement(toEigenV(t.qStart)));
    for (const Eigen::Vector4d &p : t.seen) {
      t.points.push_back(H.solve(model.getStereoRig().triangulate(p.head<2>(), p.tail<2>())));
    }
    return t;
  }
};

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
  const vpProjectiveRobot robot = calibratedRobot(s);
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
        vpProjectiveInverseKinematics::solveAll(model, sStar, points, toEigenV(qStart), qmin, qmax, 1500, &residuals);
    vpProjectivePathPlanner planner;
    planner.plan(model, toEigenV(qStart), points, sStar);
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
      const std::vector<Eigen::Vector4d> images = trueImages(s, toVispVector(f), tracked);
      for (size_t k = 0; k < images.size(); ++k) {
        EXPECT_LT((images[k] - sStar[k]).cwiseAbs().maxCoeff(), 1e-3) << s.name << " branch " << f.transpose();
      }
      nearestToTruth = std::min(nearestToTruth, branchDistance(f, toEigenV(qTarget)));
    }
    EXPECT_LT(nearestToTruth, 1e-4) << s.name << " task " << task;
    testLog() << s.name << " task " << task << ": " << exact << " exact branches by 1500 starts, " << found.size()
              << " found by the planner's default starts" << std::endl;
  }
}

// The planner's extra start: the inverse kinematics tracked along straight image lines from q to s*. With a single
// random start, the branch of a wide target is found from the tracked start and not without it (the random start and
// q converge elsewhere); an extra start of the wrong size is refused.
TEST(PathPlanner, TrackedStartFindsTheBranchTheMotionMeets)
{
  const ArmSetup s = viperEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  const vpProjectiveArmModel &model = robot.getModel();
  const std::vector<unsigned int> tracked = {0, 1, 2};
  const std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked);
  vpUniRand rng(23);
  const std::vector<double> range(s.n(), vpMath::rad(15.0));
  const JointVector qmin = JointVector::Constant(s.n(), -2.0 * M_PI), qmax = JointVector::Constant(s.n(), 2.0 * M_PI);
  int withTracked = 0, without = 0;
  const int tasks = 6;
  for (int task = 0; task < tasks; ++task) {
    const vpColVector qStart = s.randomVisibleJoints(rng, range), qTarget = s.randomVisibleJoints(rng, range);
    ASSERT_EQ(qTarget.size(), s.n());
    const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
    // The extra start: the target perturbed by 10 deg per joint, a configuration in its branch's basin.
    std::vector<JointVector> extra(1, toEigenV(qTarget) + JointVector::Constant(s.n(), vpMath::rad(10.0)));
    const auto finds = [&](const std::vector<JointVector> *starts) {
      const std::vector<JointVector> found = vpProjectiveInverseKinematics::solveAll(
          model, sStar, points, toEigenV(qStart), qmin, qmax, 1, nullptr, nullptr, starts);
      double nearest = M_PI;
      for (const JointVector &f : found) {
        nearest = std::min(nearest, branchDistance(f, toEigenV(qTarget)));
      }
      return nearest < 1e-4;
    };
    withTracked += finds(&extra);
    without += finds(nullptr);
  }
  EXPECT_EQ(withTracked, tasks) << "an extra start in the target's basin finds its branch";
  EXPECT_LE(without, withTracked);
  std::vector<JointVector> wrong(1, JointVector::Zero(s.n() - 1));
  EXPECT_THROW(vpProjectiveInverseKinematics::solveAll(model, trueImages(s, s.qRef, tracked), points,
                                                       JointVector::Zero(s.n()), qmin, qmax, 1, nullptr, nullptr,
                                                       &wrong),
               vpException);
}

TEST_P(PathPlannerArms, TwoViewRefinementBringsTheResidualToTheNoise)
{
  // A task's points triangulated at the start from noisy pixels, then the inverse kinematics of noisy desired pixels:
  // points fixed (solve()) against points refined by both views (solveWithPoints()), from the true target.
  NoisyTasks tasks(GetParam().make(), 2.0 * GetParam().rangeDeg, 23, 29);
  const ArmSetup &s = tasks.s;
  const vpProjectiveRobot &robot = tasks.robot;
  const vpProjectiveArmModel &model = tasks.model;
  const std::vector<unsigned int> &tracked = tasks.tracked;
  const double sigma = NoisyTasks::kSigma;
  std::vector<double> fixedError, refinedError, fixedResidual, refinedResidual;
  for (int task = 0; task < 30; ++task) {
    NoisyTasks::Task t = tasks.next();
    const vpColVector &qStart = t.qStart, &qTarget = t.qTarget;
    const std::vector<Eigen::Vector4d> &seen = t.seen, &sStar = t.sStar;
    std::vector<Eigen::Vector4d> &points = t.points;
    const std::vector<Eigen::Vector4d> triangulated = points;
    double fixedRms = 0.0, rms = 0.0;
    const JointVector fixed = vpProjectiveInverseKinematics::solve(model, sStar, points, toEigenV(qTarget), &fixedRms);
    const JointVector refined = vpProjectiveInverseKinematics::solveWithPoints(model, sStar, seen, toEigenV(qStart),
                                                                               toEigenV(qTarget), points, &rms);
    fixedError.push_back(vpMath::deg((fixed - toEigenV(qTarget)).norm()));
    refinedError.push_back(vpMath::deg((refined - toEigenV(qTarget)).norm()));
    fixedResidual.push_back(fixedRms);
    refinedResidual.push_back(rms);
    // The refined points still explain the start's pixels at the noise level.
    const Eigen::Matrix4d Hs = model.displacement(toEigenV(qStart));
    for (size_t k = 0; k < points.size(); ++k) {
      Eigen::Vector4d p;
      ASSERT_TRUE(model.getStereoRig().project(Hs * points[k], p));
      EXPECT_LT((p - seen[k]).norm(), 10.0 * sigma) << s.name << " task " << task << " point " << k;
      EXPECT_NEAR(points[k].norm(), 1.0, 1e-12);
      EXPECT_FALSE(points[k].isApprox(triangulated[k].normalized(), 1e-12)) << "the point did not move";
    }
  }
  const double fixedMedian = median(fixedError);
  const double refinedMedian = median(refinedError);
  const double fixedResidualMedian = median(fixedResidual), residualMedian = median(refinedResidual);
  testLog() << s.name << ", medians over 30 tasks: residual " << fixedResidualMedian
            << " px RMS with the points fixed, " << residualMedian << " px refined; target joint error " << fixedMedian
            << " deg fixed, " << refinedMedian << " deg refined" << std::endl;
  // 24 pixels for 6 joints and 9 point coordinates: sigma sqrt(9 / 24) = 0.61 sigma expected; with the points fixed
  // the true target leaves more than the 12 pixels' noise for 6 joints (0.71 sigma), the points' depth errors turned
  // sideways.
  EXPECT_GT(residualMedian, 0.3 * sigma);
  EXPECT_LT(residualMedian, 1.0 * sigma);
  EXPECT_GT(fixedResidualMedian, 1.5 * residualMedian);
  EXPECT_LT(refinedMedian, fixedMedian);

  // Noise-free: the true target and points from a start 3 deg off on every joint, to working precision.
  const vpColVector qStart(s.n(), 0.0);
  vpColVector qTarget(s.n(), vpMath::rad(5.0));
  const std::vector<Eigen::Vector4d> seen = trueImages(s, qStart, tracked), sStar = trueImages(s, qTarget, tracked);
  std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked);
  double rms = 1.0;
  const JointVector q = vpProjectiveInverseKinematics::solveWithPoints(
      model, sStar, seen, toEigenV(qStart), toEigenV(qTarget) + JointVector::Constant(s.n(), vpMath::rad(3.0)), points,
      &rms);
  EXPECT_LT((q - toEigenV(qTarget)).cwiseAbs().maxCoeff(), 1e-6) << s.name;
  EXPECT_LT(rms, 1e-6) << s.name;
  // A point without seen pixels is exact: it stays where it is, the others and q still converge.
  std::vector<Eigen::Vector4d> seenFixed = seen, fixedPoints = modelPoints(robot, tracked);
  seenFixed[1].setConstant(std::nan(""));
  const Eigen::Vector4d exact = fixedPoints[1].normalized();
  const JointVector qFixed = vpProjectiveInverseKinematics::solveWithPoints(
      model, sStar, seenFixed, toEigenV(qStart), toEigenV(qTarget) + JointVector::Constant(s.n(), vpMath::rad(3.0)),
      fixedPoints, &rms);
  EXPECT_LT((qFixed - toEigenV(qTarget)).cwiseAbs().maxCoeff(), 1e-6) << s.name;
  EXPECT_LT((fixedPoints[1] - exact).norm(), 1e-15);
  EXPECT_LT(rms, 1e-6) << s.name;

  // Bad input throws and leaves the points as they were.
  const std::vector<Eigen::Vector4d> before = points;
  std::vector<Eigen::Vector4d> shortSeen(seen.begin(), seen.end() - 1), nanStar = sStar;
  nanStar[0](1) = std::nan("");
  EXPECT_THROW(vpProjectiveInverseKinematics::solveWithPoints(model, sStar, shortSeen, toEigenV(qStart), q, points),
               vpException);
  EXPECT_THROW(vpProjectiveInverseKinematics::solveWithPoints(model, nanStar, seen, toEigenV(qStart), q, points),
               vpException);
  EXPECT_THROW(vpProjectiveInverseKinematics::solveWithPoints(model, sStar, seen, JointVector::Zero(2), q, points),
               vpException);
  for (size_t k = 0; k < points.size(); ++k) {
    EXPECT_EQ(points[k], before[k]);
  }
}

TEST(PathPlanner, UsesTheAcquiredMarkersItRecognises)
{
  // Noisy features of three acquired markers, triangulated at the start: the planner recognises them (their images at
  // q are the model's predictions) and solves the target with the bundle adjustment's points, which the two-view
  // refinement of one stereo pair cannot match. A feature between two markers is no marker: it stays triangulated.
  NoisyTasks tasks(pumaEyeToHand(), 30.0, 31, 37);
  const ArmSetup &s = tasks.s;
  const vpProjectiveRobot &robot = tasks.robot;
  const vpProjectiveArmModel &model = tasks.model;
  const std::vector<unsigned int> &tracked = tasks.tracked;
  std::vector<double> plannedError, refinedError;
  vpProjectivePathPlanner planner;
  for (int task = 0; task < 20; ++task) {
    NoisyTasks::Task t = tasks.next();
    const vpColVector &qStart = t.qStart, &qTarget = t.qTarget;
    const std::vector<Eigen::Vector4d> &seen = t.seen, &sStar = t.sStar;
    std::vector<Eigen::Vector4d> &points = t.points;
    ASSERT_EQ(planner.plan(model, toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
        << planner.getDescription();
    EXPECT_NE(planner.getDescription().find("3 of 3 points are acquired markers"), std::string::npos)
        << planner.getDescription();
    plannedError.push_back(vpMath::deg((planner.getTarget() - toEigenV(qTarget)).norm()));
    const JointVector refined =
        vpProjectiveInverseKinematics::solveWithPoints(model, sStar, seen, toEigenV(qStart), toEigenV(qTarget), points);
    refinedError.push_back(vpMath::deg((refined - toEigenV(qTarget)).norm()));
  }
  testLog() << "target joint error, median over 20 tasks: " << median(plannedError) << " deg planned (markers), "
            << median(refinedError) << " deg by the two-view refinement of triangulated points" << std::endl;
  EXPECT_LT(median(plannedError), 0.75 * median(refinedError));

  // A feature at the centre of markers 0, 1 and 2 (a point of the gripper, off the line of markers 0 and 1 that the
  // other two features are) matches no marker.
  const vpColVector q0(s.n(), 0.0), q1(s.n(), vpMath::rad(10.0));
  const Eigen::Matrix4d H1 = model.displacement(toEigenV(q1));
  std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked), sStar(tracked.size());
  Eigen::Vector4d centre = Eigen::Vector4d::Zero();
  for (unsigned int j : tracked) {
    const Eigen::Vector4d M = model.markers()[j].normalized();
    centre += M.dot(model.markers()[0]) < 0.0 ? Eigen::Vector4d(-M) : M; // one sign: the sum lies between them
  }
  points[2] = centre.normalized();
  for (size_t k = 0; k < points.size(); ++k) {
    ASSERT_TRUE(model.getStereoRig().project(H1 * points[k], sStar[k]));
  }
  ASSERT_EQ(planner.plan(model, toEigenV(q0), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
      << planner.getDescription();
  EXPECT_NE(planner.getDescription().find("2 of 3 points are acquired markers"), std::string::npos)
      << planner.getDescription();
  EXPECT_LT((planner.getTarget() - toEigenV(q1)).cwiseAbs().maxCoeff(), 1e-4) << planner.getDescription();
}

TEST(PathPlanner, MatchMarkerRecognisesEachAcquiredMarker)
{
  // vpProjectiveArmModel::matchMarker() on the true images of every marker with 0.5 px of noise, at random joints:
  // each is its own marker; a point between two markers and a marker's image 10 px off are none.
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  const vpProjectiveArmModel &model = robot.getModel();
  vpUniRand rng(41);
  vpGaussRand noise(0.5, 0.0, 43);
  const std::vector<double> range(s.n(), vpMath::rad(30.0));
  const std::vector<unsigned int> all = allMarkers(s);
  unsigned int ambiguous = 0;
  for (int pose = 0; pose < 10; ++pose) {
    const vpColVector q = s.randomVisibleJoints(rng, range);
    const Eigen::Matrix4d H = model.displacement(toEigenV(q));
    const std::vector<Eigen::Vector4d> images = trueImages(s, q, all);
    for (size_t j = 0; j < images.size(); ++j) {
      Eigen::Vector4d noisy = images[j];
      for (int c = 0; c < 4; ++c) {
        noisy(c) += noise();
      }
      // Markers whose images nearly coincide (another within 6 px RMS: twice the 2 px match plus the noise) are
      // ambiguous: no match rather than a wrong one.
      double separation = std::numeric_limits<double>::infinity();
      for (size_t o = 0; o < images.size(); ++o) {
        separation = o == j ? separation : std::min(separation, std::sqrt((images[o] - images[j]).squaredNorm() / 4.0));
      }
      const int match = model.matchMarker(H, noisy);
      if (separation > 6.0) {
        EXPECT_EQ(match, static_cast<int>(j)) << "pose " << pose;
      } else {
        EXPECT_TRUE(match == static_cast<int>(j) || match == -1) << "pose " << pose << ": " << match;
        ++ambiguous;
      }
      EXPECT_EQ(model.matchMarker(H, images[j] + Eigen::Vector4d(10.0, 0.0, 10.0, 0.0)), -1) << "pose " << pose;
    }
    EXPECT_EQ(model.matchMarker(H, 0.5 * (images[0] + images[1])), -1) << "pose " << pose;
  }
  EXPECT_LE(ambiguous, 7u) << "most markers stand apart in the images";
  testLog() << ambiguous << " of 70 marker images within 6 px of another" << std::endl;
}
