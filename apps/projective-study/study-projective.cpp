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
  \file study-projective.cpp
  \brief The projective servo's acquisition in the study.
*/

#include "study-projective.h"

#include <algorithm>
#include <cmath>

#include <visp3/projective/vpProjectiveStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
vpProjectiveRobot acquire(const World &world, double sigma, vpGaussRand &noise)
{
  // app::acquireByTrials() for any joint kinds: the same images in the same order (hence the same noise draws),
  // the trial amounts in the joints' units.
  const unsigned int n = world.arm.getNumberOfJoints();
  const auto imagesAt = [&](const vpColVector &q, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
    return world.rig.project(world.arm.getMarkers(q), left, right, sigma, noise);
  };
  std::vector<vpImagePoint> left0, right0;
  imagesAt(vpColVector(n, 0.0), left0, right0);
  std::vector<app::TrialMotion> trials;
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      app::TrialMotion t{i, sign * world.trials[i], {}, {}};
      vpColVector q(n, 0.0);
      q[i] = t.amount;
      while (!imagesAt(q, t.left, t.right)) {
        t.amount /= 2.0; // the markers left the view: a smaller trial
        q[i] = t.amount;
      }
      trials.push_back(t);
    }
  }
  std::vector<vpImagePoint> allLeft = left0, allRight = right0;
  for (const app::TrialMotion &t : trials) {
    allLeft.insert(allLeft.end(), t.left.begin(), t.left.end());
    allRight.insert(allRight.end(), t.right.begin(), t.right.end());
  }
  vpProjectiveStereoRig rig;
  rig.estimate(allLeft, allRight, std::max(1.0, 4.0 * sigma));
  std::vector<vpProjectiveRobot::vpJointType> types(n);
  for (unsigned int i = 0; i < n; ++i) {
    types[i] = world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? vpProjectiveRobot::PRISMATIC
                                                                         : vpProjectiveRobot::REVOLUTE;
  }
  vpProjectiveRobot robot(types);
  robot.setRigMounting(vpProjectiveRobot::EYE_TO_HAND);
  robot.setStereoRig(rig);
  robot.setZeroReference(left0, right0);
  for (const app::TrialMotion &t : trials) {
    robot.addTrialMotion(t.joint, t.amount, t.left, t.right);
  }
  robot.calibrate();
  return robot;
}

double modelPredictionError(const World &world, const vpProjectiveRobot &robot, const vpColVector &q)
{
  std::vector<vpImagePoint> left, right;
  trueImages(world, q, left, right);
  double sum = 0.0;
  for (unsigned int k = 0; k < world.nbPoints(); ++k) {
    vpImagePoint l, r;
    robot.getModel().projectMarker(world.tracked[k], q, l, r);
    sum += vpImagePoint::sqrDistance(l, left[k]) + vpImagePoint::sqrDistance(r, right[k]);
  }
  return std::sqrt(sum / (4.0 * world.nbPoints()));
}
} // namespace study
