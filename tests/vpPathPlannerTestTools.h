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
  Helpers for the suites of the global servoing (vpProjectiveInverseKinematics, vpProjectivePathPlanner and
  vpServoProjective with path planning), checked against the simulator's truth (header only, not a test itself): the
  true images of the markers at model joints, the model's zero-reference points, whether the simulated markers are in
  view, the distance between two inverse-kinematic branches. The arm setups and their noise-free models come from
  vpProjectiveArmTestTools.h (calibratedRobot()). The suites: testPathPlannerInverseKinematics (planning on the model),
  testPathPlannerPaths (the plans), testPathPlannerServo (the planned servo on the PUMA) and
  testPathPlannerViper850 (the planned servo on ViSP's Viper850, as a user writes it).
*/

#ifndef _vpPathPlannerTestTools_h_
#define _vpPathPlannerTestTools_h_

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
typedef vpProjectivePathPlanner::JointVector JointVector;

//! Largest joint difference, revolute joints (all of them here) modulo a turn.
inline double branchDistance(const JointVector &a, const JointVector &b)
{
  double d = 0.0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    d = std::max(d, std::abs(std::remainder(a(i) - b(i), 2.0 * M_PI)));
  }
  return d;
}

//! True images (u, v, u', v') of the markers \e tracked at model joints q.
inline std::vector<Eigen::Vector4d> trueImages(const ArmSetup &s, const vpColVector &q,
                                               const std::vector<unsigned int> &tracked)
{
  std::vector<Eigen::Vector4d> images;
  for (unsigned int j : tracked) {
    images.push_back(s.imageOf(s.armJoints(q), j));
  }
  return images;
}

inline std::vector<unsigned int> allMarkers(const ArmSetup &s)
{
  std::vector<unsigned int> tracked(s.numberOfMarkers());
  for (unsigned int j = 0; j < tracked.size(); ++j) {
    tracked[j] = j;
  }
  return tracked;
}

//! The model's zero-reference points of the markers \e tracked.
inline std::vector<Eigen::Vector4d> modelPoints(const vpProjectiveRobot &robot,
                                                const std::vector<unsigned int> &tracked)
{
  std::vector<Eigen::Vector4d> points;
  for (unsigned int j : tracked) {
    points.push_back(robot.getModel().markers()[j]);
  }
  return points;
}

//! True when the simulated markers \e tracked at model joints q are in front of both cameras and \e border px inside.
inline bool trulyInView(const ArmSetup &s, const vpColVector &q, const std::vector<unsigned int> &tracked,
                        double border)
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

/*!
  The tests on the PUMA-like arm watched by the paper's rig (testPathPlannerPaths, testPathPlannerServo): its model
  acquired noise-free, markers 0-2 tracked, their zero-reference points in the model.
*/
class PathPlanner : public ::testing::Test
{
protected:
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  const std::vector<unsigned int> tracked = {0, 1, 2};
  const std::vector<Eigen::Vector4d> points = modelPoints(robot, tracked);
};
} // namespace vpProjectiveTest

#endif
