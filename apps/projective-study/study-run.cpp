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
  \file study-run.cpp
  \brief The servo loop of the study.
*/

#include "study-run.h"

#include <algorithm>
#include <cmath>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
RunResult runServo(const World &world, const Task &task, double sigma, Controller &controller, Scenario scenario)
{
  RunResult result;
  const unsigned int N = world.nbPoints(), n = world.arm.getNumberOfJoints();
  const vpColVector &qmin = world.arm.getJointMin(), &qmax = world.arm.getJointMax();
  std::vector<vpImagePoint> leftStar, rightStar;
  measuredTarget(task, sigma, leftStar, rightStar);
  vpColVector q = task.qStart;

  // Broyden's exploration: the arm moves to q and back, measuring with its own noise draws.
  size_t exploreSlot = 0;
  auto moveAndMeasure = [&](const vpColVector &qm, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
    for (unsigned int i = 0; i < n; ++i) {
      if (qm[i] < qmin[i] || qm[i] > qmax[i]) {
        return false;
      }
    }
    if (!trueImages(world, qm, left, right)) {
      return false;
    }
    addNoise(task.exploreNoise, std::min(exploreSlot++, static_cast<size_t>(2 * n)), sigma, left, right);
    return true;
  };
  try {
    if (!controller.prepare(q, moveAndMeasure, result.moves)) {
      result.explorationFailed = true;
      return result;
    }
  } catch (const vpException &e) {
    result.exception = true;
    result.message = e.getStringMessage();
    return result;
  }

  const double threshold = std::max(2.0 * sigma, 1e-6);
  std::vector<double> pathLength(2 * N, 0.0);
  std::vector<vpImagePoint> previousLeft, previousRight;
  std::vector<bool> rejected;
  double jointPath = 0.0;
  std::vector<vpColVector> trajectory(1, q);
  for (unsigned int it = 0; it <= world.budget; ++it) {
    std::vector<vpImagePoint> left, right;
    if (!trueImages(world, q, left, right)) {
      result.lostView = true;
      break;
    }
    if (result.convergedAt < 0 && it > 0) {
      for (unsigned int k = 0; k < N; ++k) {
        pathLength[2 * k] += std::sqrt(vpImagePoint::sqrDistance(left[k], previousLeft[k]));
        pathLength[2 * k + 1] += std::sqrt(vpImagePoint::sqrDistance(right[k], previousRight[k]));
      }
    }
    previousLeft = left;
    previousRight = right;
    addNoise(task.servoNoise, it, sigma, left, right);

    double sum = 0.0;
    for (unsigned int k = 0; k < N; ++k) {
      sum += vpImagePoint::sqrDistance(left[k], leftStar[k]) + vpImagePoint::sqrDistance(right[k], rightStar[k]);
    }
    result.finalImageRms = std::sqrt(sum / (4.0 * N));
    result.lastIteration = static_cast<int>(it);
    if (result.convergedAt < 0 && result.finalImageRms < threshold) {
      result.convergedAt = static_cast<int>(it);
      double length = 0.0, chord = 0.0;
      for (unsigned int k = 0; k < N; ++k) {
        length += pathLength[2 * k] + pathLength[2 * k + 1];
        chord += std::sqrt(vpImagePoint::sqrDistance(task.leftStart[k], task.leftTarget[k])) +
                 std::sqrt(vpImagePoint::sqrDistance(task.rightStart[k], task.rightTarget[k]));
      }
      result.straightness = length / chord;
      result.jointPathRatio = jointPath / (q - task.qStart).frobeniusNorm();
    }
    if (it == world.budget) {
      break;
    }

    // What the controller sees.
    std::vector<bool> tracked(N, true), gross(N, false);
    if (scenario == OUTLIERS) {
      for (unsigned int k = 0; k < N; ++k) {
        const Outlier &o = task.outliers[it * N + k];
        if (o.active) {
          vpImagePoint &ip = o.rightImage ? right[k] : left[k];
          ip.set_uv(ip.get_u() + o.du, ip.get_v() + o.dv);
          gross[k] = true;
        }
      }
    } else if (scenario == OCCLUSION && it >= world.occludedFirst && it <= world.occludedLast) {
      tracked[world.occludedFeature] = false;
    }
    vpColVector qdot;
    try {
      qdot = controller.velocity(q, left, right, tracked);
    } catch (const vpException &e) {
      result.exception = true;
      result.message = e.getStringMessage();
      break;
    }
    controller.rejected(rejected);
    for (size_t k = 0; k < rejected.size(); ++k) {
      if (tracked[k]) {
        (gross[k] ? result.outliersSeen : result.cleanSeen)++;
        if (rejected[k]) {
          (gross[k] ? result.outliersRejected : result.cleanRejected)++;
        }
      }
    }
    bool finite = true;
    for (unsigned int i = 0; i < n; ++i) {
      finite = finite && std::isfinite(qdot[i]);
      if (q[i] + qdot[i] < qmin[i] || q[i] + qdot[i] > qmax[i]) {
        result.limitHit = true;
      }
    }
    if (!finite) {
      result.exception = true;
      result.message = "non-finite joint velocity";
      break;
    }
    const vpColVector qNext = world.arm.integrate(q, qdot, 1.0);
    if (result.convergedAt < 0) {
      jointPath += (qNext - q).frobeniusNorm();
    }
    q = qNext;
    trajectory.push_back(q);
    if (result.limitHit) {
      break;
    }
  }
  // The target interval ends where the run converged (another inverse-kinematic branch of the same images counts as
  // the target it went to), at the true target otherwise.
  const vpColVector &end = result.success() ? q : task.qTarget;
  for (const vpColVector &qa : trajectory) {
    for (unsigned int i = 0; i < n; ++i) {
      const double lo = std::min(task.qStart[i], end[i]), hi = std::max(task.qStart[i], end[i]);
      result.excursionDeg = std::max(result.excursionDeg, vpMath::deg(std::max(qa[i] - hi, lo - qa[i])));
    }
  }
  double ratio = 0.0;
  for (unsigned int i = 0; i < n; ++i) {
    ratio += std::abs(q[i] - task.qTarget[i]) / (sigma * task.unitFloor[i]);
  }
  result.errorOverFloor = ratio / n;
  return result;
}
} // namespace study
