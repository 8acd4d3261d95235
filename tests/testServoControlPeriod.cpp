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

/*!
  \file testServoControlPeriod.cpp
  \brief vpServoProjective::setControlPeriod(): a task called at a vpRobot's velocity-loop rate. On the paper's arm
  and rig (vpProjectiveArmTestTools.h: pumaEyeToHand(), a model acquired without noise):
  - law (47) alone gives the same joint velocity for every period, with and without saturation (the gain and the
    saturation are per second);
  - the planned servo of the tutorial's wide task (82 cm, 88 deg) in a 25 Hz loop (qdot held 40 ms per call, 30 deg/s
    at most) converges with setControlPeriod(0.04) at the pace of the saturation, inside the limits, along the
    straight joint-space line;
  - a bad period throws and changes nothing.
*/

#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{

//! The paper's task on markers 0-2, its features updated from the exact images at q.
struct Task {
  ArmSetup setup = pumaEyeToHand();
  vpSimulatorStereoRig rig = paperRigAtOrigin();
  vpProjectiveRobot robot = calibratedRobot(setup);
  vpFeatureStereoPoint s[3], s_star[3];
  vpServoProjective task;

  Task()
  {
    update(paperTaskTarget(), s_star);
    task.setRobot(robot);
    for (unsigned int k = 0; k < 3; ++k) {
      task.addFeature(s[k], s_star[k]);
    }
  }
  bool update(const vpColVector &q, vpFeatureStereoPoint *features) const
  {
    const std::vector<vpColVector> markers = setup.arm.getMarkers(q);
    bool visible = true;
    for (unsigned int k = 0; k < 3; ++k) {
      vpImagePoint l, r;
      visible = rig.project(markers[k], l, r) && visible;
      features[k].buildFrom(l, r);
    }
    return visible;
  }
  double errorRms()
  {
    double sum = 0.0;
    for (unsigned int k = 0; k < 3; ++k) {
      sum += s[k].error(s_star[k]).sumSquare();
    }
    return std::sqrt(sum / 12.0);
  }
  //! A velocity loop of \e calls calls, qdot held \e dt seconds each; returns the final RMS image error.
  double run(double dt, unsigned int calls, bool &insideLimits, double &pathLength, unsigned int &converged)
  {
    vpColVector q = paperTaskStart();
    insideLimits = true;
    pathLength = 0.0;
    converged = calls;
    for (unsigned int it = 0; it < calls; ++it) {
      if (!update(q, s)) {
        return -1.0; // a marker left the images
      }
      if (converged == calls && errorRms() < 0.1) {
        converged = it;
      }
      const vpColVector qdot = task.computeControlLaw(q);
      const vpColVector qNext = setup.arm.integrate(q, qdot, dt);
      pathLength += (qNext - q).frobeniusNorm();
      q = qNext;
      for (unsigned int i = 0; i < 6; ++i) {
        insideLimits = insideLimits && q[i] >= setup.arm.getJointMin()[i] && q[i] <= setup.arm.getJointMax()[i];
      }
    }
    update(q, s);
    return errorRms();
  }
};
} // namespace

// Law (47) alone: qdot = -lambda J^+ e (saturated at the same rad/s) whatever the period.
TEST(ServoControlPeriod, lawIsTheSameForEveryPeriod)
{
  for (double saturation : {0.0, vpMath::rad(5.0)}) {
    Task a, b;
    a.task.setLambda(0.8);
    b.task.setLambda(0.8);
    a.task.getControlLaw().setMaxJointVelocity(saturation);
    b.task.setControlPeriod(0.01);
    b.task.getControlLaw().setMaxJointVelocity(saturation);
    const vpColVector q = paperTaskStart();
    a.update(q, a.s);
    b.update(q, b.s);
    const vpColVector qa = a.task.computeControlLaw(q), qb = b.task.computeControlLaw(q);
    ASSERT_GT(qa.frobeniusNorm(), 0.01);
    EXPECT_LT((qa - qb).frobeniusNorm(), 1e-9 * qa.frobeniusNorm()) << "saturation " << saturation;
  }
}

// The planned servo in a 25 Hz velocity loop with the period: the joint-space line of the plan, followed at the
// saturation, converges inside the limits in 70 calls (2.8 s) along a joint path no longer than the straight line.
// (Without setControlPeriod(), each call's planned step is read as a step of 1 s of which the arm makes 1/25: the
// follower falls behind, re-plans and finishes on law (47) at call 234 after a joint path 1.7 times longer.)
TEST(ServoControlPeriod, plannedServoInAVelocityLoop)
{
  const double dt = 0.04;
  Task t;
  t.task.setLambda(1.0);
  t.task.setControlPeriod(dt);
  t.task.getControlLaw().setMaxJointVelocity(vpMath::rad(30.0));
  t.task.getControlLaw().setDamping(30.0, 30.0);
  t.task.setJointLimits(t.setup.arm.getJointMin(), t.setup.arm.getJointMax());
  t.task.setImageSize(t.rig.getWidth(), t.rig.getHeight(), 10.0);
  t.task.setPathPlanning(true);
  bool inside = false;
  double length = 0.0;
  unsigned int converged = 0;
  const double error = t.run(dt, 250, inside, length, converged);
  EXPECT_GE(error, 0.0); // every marker stayed in view
  EXPECT_LT(error, 0.01);
  EXPECT_TRUE(inside);
  EXPECT_LE(converged, 100u);
  // 30 deg/s on the joint that moves most (joint 5, 55.5 deg): 1.85 s, 46 calls at least.
  EXPECT_GE(converged, 46u);
  EXPECT_LT(length, 1.05 * (paperTaskTarget() - paperTaskStart()).frobeniusNorm());
}

// A period that is not positive and finite throws and leaves the task as it was.
TEST(ServoControlPeriod, badPeriodThrows)
{
  vpServoProjective task;
  task.setControlPeriod(0.02);
  for (double bad : {0.0, -0.01, std::nan(""), HUGE_VAL}) {
    EXPECT_THROW(task.setControlPeriod(bad), vpException);
    EXPECT_EQ(task.getControlLaw().getControlPeriod(), 0.02);
  }
}
