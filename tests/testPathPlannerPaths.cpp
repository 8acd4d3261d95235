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
  The plans of vpProjectivePathPlanner, against the simulator's truth: they stay inside the joint limits (and out of
  their margins when a branch allows) and keep the features in view (the simulator's images, not only the model's
  predictions), follow straight image lines within the excursion bound, need a waypoint where the lines leave the
  view, keep planar groups facing the cameras, and the cases without a plan say so.
*/

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "vpPathPlannerTestTools.h"

using namespace vpProjectiveTest;

TEST_F(PathPlanner, KeepsTheTargetOutOfTheJointLimitMargins)
{
  // A target with joint 5 at 140 deg, 30 deg from its limit: in the band of a margin of 0.1 of the 340 deg range, and
  // the nearest branch to a start 40 deg away on that joint. The wrist's other branch (joints 3 and 5 half a turn
  // away, joint 4 mirrored) shows the same images with every joint out of the margins, farther from the start.
  vpColVector qStart(s.n(), 0.0), qTarget(s.n(), 0.0);
  qStart[3] = qTarget[3] = vpMath::rad(60.0);
  qStart[4] = qTarget[4] = vpMath::rad(10.0);
  qStart[5] = vpMath::rad(100.0);
  qTarget[5] = vpMath::rad(140.0);
  const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
  const JointVector qmin = JointVector::Constant(s.n(), vpMath::rad(-170.0));
  const JointVector qmax = JointVector::Constant(s.n(), vpMath::rad(170.0));
  const double margin = 0.1, band = vpMath::rad(170.0 - 34.0);
  vpProjectivePathPlanner planner;
  planner.setJointLimits(qmin, qmax);
  EXPECT_EQ(planner.getJointLimitMargin(), 0.0);
  ASSERT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
      << planner.getDescription();
  const JointVector nearest = planner.getTarget();
  ASSERT_LT((nearest - toEigenV(qTarget)).cwiseAbs().maxCoeff(), 1e-4) << "the nearest branch is the taught one";
  ASSERT_GT(nearest.cwiseAbs().maxCoeff(), band);

  planner.setJointLimitMargin(margin);
  ASSERT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
      << planner.getDescription();
  const JointVector away = planner.getTarget();
  EXPECT_LT(away.cwiseAbs().maxCoeff(), band) << away.transpose();
  EXPECT_GT((away - toEigenV(qStart)).norm(), (nearest - toEigenV(qStart)).norm());
  const std::vector<Eigen::Vector4d> reached = trueImages(s, toVispVector(away), tracked);
  for (size_t k = 0; k < tracked.size(); ++k) {
    EXPECT_LT((reached[k] - sStar[k]).cwiseAbs().maxCoeff(), 1e-3) << "the same images, truly";
  }
  EXPECT_TRUE(planner.getPath().back().isApprox(away));

  // No branch out of the margins: the nearest inside the limits, as without a margin.
  planner.setJointLimitMargin(0.5);
  ASSERT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND);
  EXPECT_LT((planner.getTarget() - nearest).norm(), 1e-9);
  EXPECT_THROW(planner.setJointLimitMargin(-0.1), vpException);
  EXPECT_THROW(planner.setJointLimitMargin(0.6), vpException);
  EXPECT_THROW(planner.setJointLimitMargin(std::nan("")), vpException);
  EXPECT_EQ(planner.getJointLimitMargin(), 0.5);
}

TEST_F(PathPlanner, PlansStayInsideLimitsAndView)
{
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
    ASSERT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
        << "task " << task << ": " << planner.getDescription();
    ++kinds[planner.getPathKind()];
    const std::vector<JointVector> &path = planner.getPath();
    EXPECT_LT((path.front() - toEigenV(qStart)).norm(), 1e-12);
    EXPECT_LT((path.back() - planner.getTarget()).norm(), 1e-12);
    for (size_t j = 0; j < path.size(); ++j) {
      EXPECT_TRUE((path[j].array() >= qmin.array()).all() && (path[j].array() <= qmax.array()).all())
          << "task " << task << " sample " << j;
      EXPECT_TRUE(trulyInView(s, toVispVector(path[j]), tracked, border - 0.01)) << "task " << task << " sample " << j;
      if (j > 0) {
        EXPECT_LE((path[j] - path[j - 1]).cwiseAbs().maxCoeff(), step + 1e-12) << "task " << task << " sample " << j;
      }
    }
    // The target shows s*, truly.
    const std::vector<Eigen::Vector4d> reached = trueImages(s, toVispVector(planner.getTarget()), tracked);
    for (size_t k = 0; k < tracked.size(); ++k) {
      EXPECT_LT((reached[k] - sStar[k]).cwiseAbs().maxCoeff(), 1e-3) << "task " << task;
    }
  }
  testLog() << "path kinds: " << kinds[0] << " straight image lines, " << kinds[1] << " joint lines, " << kinds[2]
            << " waypoints" << std::endl;
  EXPECT_GT(kinds[vpProjectivePathPlanner::PATH_IMAGE_LINE], 0u);
}

TEST_F(PathPlanner, FollowsStraightImageLinesWithinTheExcursionBound)
{
  // The main tutorial's task (the gripper moves by 82 cm and turns by 88 deg, start near the wrist singularity):
  // straight image lines need joint 2 to fold some 30 deg past its target. Under the default bound (twice the 10 deg
  // step) the plan is the joint-space line, every joint monotonic; allowed 40 deg, it follows the straight lines.
  const vpColVector qStart = paperTaskStart(), qTarget = paperTaskTarget();
  const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
  const double border = 10.0, step = vpMath::rad(10.0);
  vpProjectivePathPlanner planner;
  planner.setImageSize(s.width, s.height, border);
  planner.setMaxJointStep(step);
  EXPECT_DOUBLE_EQ(planner.getMaxExcursion(), 2.0 * step);
  // The largest motion of a joint beyond the interval of its values at the path's ends.
  auto excursion = [](const std::vector<JointVector> &path) {
    const JointVector lo = path.front().cwiseMin(path.back()), hi = path.front().cwiseMax(path.back());
    double e = 0.0;
    for (const JointVector &q : path) {
      e = std::max(e, std::max((q - hi).maxCoeff(), (lo - q).maxCoeff()));
    }
    return e;
  };

  // The largest distance of the simulator's images of the tracked markers along a path to the straight lines from their
  // images at the start to s*, in either image.
  const std::vector<Eigen::Vector4d> s0 = trueImages(s, qStart, tracked);
  auto lineDeviation = [&](const std::vector<JointVector> &path) {
    double deviation = 0.0;
    for (const JointVector &q : path) {
      const std::vector<Eigen::Vector4d> sq = trueImages(s, toVispVector(q), tracked);
      for (size_t k = 0; k < tracked.size(); ++k) {
        for (int c = 0; c < 4; c += 2) {
          const Eigen::Vector2d chord = sStar[k].segment<2>(c) - s0[k].segment<2>(c);
          const Eigen::Vector2d d = sq[k].segment<2>(c) - s0[k].segment<2>(c);
          deviation = std::max(deviation, std::abs(chord(0) * d(1) - chord(1) * d(0)) / chord.norm());
        }
      }
    }
    return deviation;
  };

  ASSERT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
      << planner.getDescription();
  EXPECT_EQ(planner.getPathKind(), vpProjectivePathPlanner::PATH_JOINT_LINE) << planner.getDescription();
  const std::vector<JointVector> jointLine = planner.getPath();
  EXPECT_LT((planner.getTarget() - toEigenV(qTarget)).cwiseAbs().maxCoeff(), 1e-3);
  EXPECT_LT(excursion(planner.getPath()), 1e-12);

  EXPECT_THROW(planner.setMaxExcursion(-0.1), vpException);
  EXPECT_THROW(planner.setMaxExcursion(std::numeric_limits<double>::infinity()), vpException);
  EXPECT_DOUBLE_EQ(planner.getMaxExcursion(), 2.0 * step);
  planner.setMaxExcursion(vpMath::rad(40.0));
  ASSERT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
      << planner.getDescription();
  ASSERT_EQ(planner.getPathKind(), vpProjectivePathPlanner::PATH_IMAGE_LINE) << planner.getDescription();
  const std::vector<JointVector> &path = planner.getPath();
  const double e = excursion(path);
  EXPECT_GT(e, 2.0 * step) << "the straight lines needed the larger bound";
  EXPECT_LE(e, vpMath::rad(40.0));
  // Truly near the straight lines (the simulator's images of the planned joints), and in view.
  for (size_t j = 0; j < path.size(); ++j) {
    EXPECT_TRUE(trulyInView(s, toVispVector(path[j]), tracked, border - 0.01)) << "sample " << j;
    EXPECT_LE((path[j] - (j > 0 ? path[j - 1] : path[j])).cwiseAbs().maxCoeff(), step + 1e-12) << "sample " << j;
  }
  const double straight = lineDeviation(path), arc = lineDeviation(jointLine);
  testLog() << "straight image lines: largest joint excursion " << vpMath::deg(e) << " deg, largest distance of a "
            << "feature to its line " << straight << " px (the joint-space line: " << arc << " px), " << path.size() - 1
            << " steps" << std::endl;
  EXPECT_LT(straight, 0.25 * arc);
}

TEST_F(PathPlanner, FindsAWaypointWhenTheLinesLeaveTheView)
{
  // Tasks drawn (seeded) in a wide box with a narrow image window, until one needs a waypoint: then the joint-space
  // line truly leaves the window and the plan truly stays inside.
  const double border = 60.0;
  vpProjectivePathPlanner planner;
  planner.setImageSize(s.width, s.height, border);
  vpUniRand rng(3);
  const std::vector<double> range(s.n(), vpMath::rad(60.0));
  bool found = false;
  for (int task = 0; task < 300 && !found; ++task) {
    const vpColVector qStart = s.randomVisibleJoints(rng, range, border + 2.0);
    const vpColVector qTarget = s.randomVisibleJoints(rng, range, border + 2.0);
    if (planner.plan(robot.getModel(), toEigenV(qStart), points, trueImages(s, qTarget, tracked)) !=
            vpProjectivePathPlanner::PLAN_FOUND ||
        planner.getPathKind() != vpProjectivePathPlanner::PATH_WAYPOINT) {
      continue;
    }
    found = true;
    bool lineInView = true;
    const JointVector q0 = toEigenV(qStart), q1 = planner.getTarget();
    for (int j = 0; j <= 100; ++j) {
      lineInView = lineInView && trulyInView(s, toVispVector(q0 + (j / 100.0) * (q1 - q0)), tracked, border);
    }
    EXPECT_FALSE(lineInView) << "task " << task << ": the joint line stays in view, no waypoint was needed";
    for (const JointVector &q : planner.getPath()) {
      EXPECT_TRUE(trulyInView(s, toVispVector(q), tracked, border - 0.01)) << "task " << task;
    }
  }
  EXPECT_TRUE(found) << "no task of 300 needed a waypoint";
}

TEST_F(PathPlanner, SaysWhenThereIsNoPlan)
{
  vpColVector qStart(s.n(), 0.0), qTarget(s.n(), 0.0);
  qTarget[0] = vpMath::rad(20.0);
  qTarget[4] = vpMath::rad(-15.0);
  const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
  vpProjectivePathPlanner planner;
  ASSERT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar), vpProjectivePathPlanner::PLAN_FOUND)
      << planner.getDescription();
  const std::vector<JointVector> pathBefore = planner.getPath();

  // Bad input throws and leaves the plan as it was.
  EXPECT_THROW(planner.plan(robot.getModel(), JointVector::Zero(3), points, sStar), vpException);
  std::vector<Eigen::Vector4d> nanStar = sStar;
  nanStar[1](2) = std::nan("");
  EXPECT_THROW(planner.plan(robot.getModel(), toEigenV(qStart), points, nanStar), vpException);
  EXPECT_EQ(planner.getStatus(), vpProjectivePathPlanner::PLAN_FOUND);
  EXPECT_EQ(planner.getPath().size(), pathBefore.size());
  EXPECT_THROW(planner.setJointLimits(JointVector::Constant(6, 1.0), JointVector::Constant(6, 0.0)), vpException);
  EXPECT_THROW(planner.setImageSize(640, 0), vpException);
  EXPECT_THROW(planner.setImageSize(640, 480, 300.0), vpException);
  EXPECT_THROW(planner.setMaxJointStep(0.0), vpException);
  EXPECT_THROW(planner.setNumberOfStarts(0), vpException);
  EXPECT_THROW(planner.setMaxResidual(-1.0), vpException);
  EXPECT_THROW(planner.setMaxExcursion(std::nan("")), vpException);

  // Limits that hold the start but no branch of the target.
  planner.setJointLimits(JointVector::Constant(6, vpMath::rad(-10.0)), JointVector::Constant(6, vpMath::rad(10.0)));
  EXPECT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStar),
            vpProjectivePathPlanner::PLAN_OUTSIDE_JOINT_LIMITS)
      << planner.getDescription();
  EXPECT_TRUE(planner.getPath().empty());
  planner.setJointLimits(JointVector(), JointVector());

  // Desired features no configuration shows: one of them 150 px off its place in both images.
  std::vector<Eigen::Vector4d> impossible = sStar;
  impossible[2] += Eigen::Vector4d(150.0, 0.0, 150.0, 0.0);
  EXPECT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, impossible),
            vpProjectivePathPlanner::PLAN_NO_INVERSE_KINEMATICS)
      << planner.getDescription();

  // A window that the target's features are outside of.
  std::vector<Eigen::Vector4d> sStarWindow = sStar;
  double uMax = 0.0;
  for (const Eigen::Vector4d &f : sStar) {
    uMax = std::max(uMax, std::max(f(0), f(2)));
  }
  planner.setImageSize(static_cast<unsigned int>(uMax) + 5, s.height, 10.0);
  EXPECT_EQ(planner.plan(robot.getModel(), toEigenV(qStart), points, sStarWindow),
            vpProjectivePathPlanner::PLAN_NO_VISIBLE_PATH)
      << planner.getDescription();
}

namespace
{
//! Twice the signed area of the image polygon of \e group in the left (offset 0) or right (2) image of \e s.
double groupArea(const std::vector<Eigen::Vector4d> &s, const std::vector<unsigned int> &group, int offset)
{
  double area = 0.0;
  for (size_t k = 0; k < group.size(); ++k) {
    const Eigen::Vector4d &a = s[group[k]], &b = s[group[(k + 1) % group.size()]];
    area += a(offset) * b(offset + 1) - b(offset) * a(offset + 1);
  }
  return area;
}

//! Whether some sample of the last plan has \e group turned from the cameras: in an image, its area's sign differs
//! from the start's, or its size falls below \e fraction of the smaller of its sizes at the start and at s*.
bool groupTurnsAway(const vpProjectivePathPlanner &planner, const std::vector<Eigen::Vector4d> &sStar,
                    const std::vector<unsigned int> &group, double fraction)
{
  const std::vector<std::vector<Eigen::Vector4d>> &features = planner.getPredictedFeatures();
  for (int c = 0; c < 2; ++c) {
    const double a = groupArea(features.front(), group, 2 * c), b = groupArea(sStar, group, 2 * c);
    if (!(a * b > 0.0)) {
      continue; // seen from behind at one end: not a facing marker
    }
    const double reference = std::min(std::abs(a), std::abs(b));
    for (const std::vector<Eigen::Vector4d> &s : features) {
      if (!(groupArea(s, group, 2 * c) * (a > 0.0 ? 1.0 : -1.0) >= fraction * reference)) {
        return true;
      }
    }
  }
  return false;
}
} // namespace

// Issue 20: a tag's corners are found only while the tag faces the cameras. Declared a planar group, the points keep
// their image polygon's orientation and a fraction of its size along every plan that does not say it gave the check
// up, where plans without the check turn it away (the servo on the tag lost it, and stopped, mid-path).
TEST_F(PathPlanner, PlansKeepPlanarGroupsFacingTheCameras)
{
  const std::vector<unsigned int> group = {0, 1, 2};
  const JointVector qmin = JointVector::Constant(s.n(), vpMath::rad(-100.0));
  const JointVector qmax = JointVector::Constant(s.n(), vpMath::rad(100.0));
  vpProjectivePathPlanner plain, facing;
  for (vpProjectivePathPlanner *planner : {&plain, &facing}) {
    planner->setJointLimits(qmin, qmax);
    planner->setImageSize(s.width, s.height, 10.0);
    planner->setRehearsalBudget(0); // no law: a path, always
  }
  facing.setPlanarGroups({group});
  EXPECT_EQ(facing.getMinGroupArea(), 0.3);
  vpUniRand rng(23);
  const std::vector<double> range(s.n(), vpMath::rad(80.0)); // wide: some plans turn the markers away
  int turnedAway = 0, keptFacing = 0, gaveUp = 0;
  for (int task = 0; task < 60; ++task) {
    const vpColVector qStart = s.randomVisibleJoints(rng, range, 12.0);
    const vpColVector qTarget = s.randomVisibleJoints(rng, range, 12.0);
    const std::vector<Eigen::Vector4d> sStar = trueImages(s, qTarget, tracked);
    const bool plainFound =
        plain.plan(robot.getModel(), toEigenV(qStart), points, sStar) == vpProjectivePathPlanner::PLAN_FOUND;
    const bool plainTurns = plainFound && groupTurnsAway(plain, sStar, group, 0.3);
    turnedAway += plainTurns;
    if (facing.plan(robot.getModel(), toEigenV(qStart), points, sStar) != vpProjectivePathPlanner::PLAN_FOUND) {
      EXPECT_FALSE(plainFound) << "task " << task << ": the check's fallback must plan whatever plans without it";
      continue;
    }
    if (facing.getDescription().find("no plan keeps every planar group facing") == 0) {
      ++gaveUp;
      continue;
    }
    EXPECT_FALSE(groupTurnsAway(facing, sStar, group, 0.3)) << "task " << task << ": " << facing.getDescription();
    keptFacing += plainTurns;
  }
  testLog() << "planar group: " << turnedAway << " plans without the check turn it away; the check keeps " << keptFacing
            << " of them facing, gives up on " << gaveUp << std::endl;
  EXPECT_GT(turnedAway, 0) << "no task exercises the check";
  EXPECT_GT(keptFacing, 0);

  // Bad settings throw and change nothing.
  EXPECT_THROW(facing.setPlanarGroups({{0, 1}}), vpException);
  EXPECT_THROW(facing.setPlanarGroups({{0, 1, 1}}), vpException);
  EXPECT_EQ(facing.getPlanarGroups().size(), 1u);
  EXPECT_THROW(facing.setMinGroupArea(-0.1), vpException);
  EXPECT_THROW(facing.setMinGroupArea(1.5), vpException);
  EXPECT_THROW(facing.setMinGroupArea(std::nan("")), vpException);
  EXPECT_EQ(facing.getMinGroupArea(), 0.3);
  facing.setPlanarGroups({{0, 1, 5}});
  EXPECT_THROW(
      facing.plan(robot.getModel(), JointVector::Zero(s.n()), points, trueImages(s, vpColVector(s.n(), 0.0), tracked)),
      vpException);
}
