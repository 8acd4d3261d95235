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

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
vpProjectiveRobot acquire(const World &world, double sigma, vpGaussRand &noise)
{
  return tutorial::acquireByTrials(
      world.trialDeg,
      [&](const vpColVector &q, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        return world.rig.project(world.arm.getMarkers(q), left, right, sigma, noise);
      },
      std::max(1.0, 4.0 * sigma), false);
}

double modelPredictionError(const World &world, const vpProjectiveRobot &robot, const vpColVector &q)
{
  std::vector<vpImagePoint> left, right;
  trueImages(world, q, left, right);
  double sum = 0.0;
  for (unsigned int k = 0; k < world.nbPoints(); ++k) {
    vpImagePoint l, r;
    robot.projectMarker(world.tracked[k], q, l, r);
    sum += vpImagePoint::sqrDistance(l, left[k]) + vpImagePoint::sqrDistance(r, right[k]);
  }
  return std::sqrt(sum / (4.0 * world.nbPoints()));
}
} // namespace study
