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
  \file study-task.cpp
  \brief Task generation.
*/

#include "study-task.h"

#include <cmath>

#include <visp3/core/vpException.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
vpColVector unitNoiseFloor(const World &world, const vpColVector &q)
{
  const vpMatrix J = app::imageJacobian(trueImagesAt(world), q);
  const vpMatrix covariance = J.AtA().inverseByLU();
  vpColVector floor(q.size());
  for (unsigned int i = 0; i < q.size(); ++i) {
    floor[i] = std::sqrt(covariance[i][i]);
  }
  return floor;
}

Task makeTask(const World &world, unsigned int seed, bool singularStart)
{
  Task task;
  task.seed = seed;
  task.singularStart = singularStart;
  const unsigned int n = world.arm.getNumberOfJoints(), N = world.nbPoints();
  vpUniRand rng(static_cast<uint64_t>(streamSeed(seed, singularStart ? SINGULAR_TASK_STREAM : TASK_STREAM)));
  auto draw = [&](bool nearSingular) {
    vpColVector q(n);
    for (unsigned int i = 0; i < n; ++i) {
      double lower, upper;
      world.box(i, lower, upper);
      q[i] = world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? rng.uniform(lower, upper)
                                                                       : vpMath::rad(rng.uniform(lower, upper));
    }
    if (nearSingular) {
      // Within nearSingularDeg of the singularity, on the side of the zero reference (the box's centre): the wrist
      // branch of a start exactly on the other side would not exist among the targets of a box that ends before it.
      const double towardsCentre = world.wristSingularDeg > 0.0 ? -1.0 : 1.0;
      q[4] = vpMath::rad(world.wristSingularDeg + towardsCentre * rng.uniform(0.0, world.nearSingularDeg));
    }
    return q;
  };
  const unsigned int maxDraws = 1000000;
  do {
    task.qStart = draw(singularStart);
    ++task.drawnStart;
  } while (!acceptable(world, task.qStart) && task.drawnStart < maxDraws);
  const Branch branch = world.pumaBranches ? branchOf(world.arm, task.qStart) : Branch{0, 0, 0};
  do {
    task.qTarget = draw(false);
    ++task.drawnTarget;
  } while ((!acceptable(world, task.qTarget) ||
            (!world.anyBranchTargets() && !(branchOf(world.arm, task.qTarget) == branch))) &&
           task.drawnTarget < maxDraws);
  if (task.drawnStart >= maxDraws || task.drawnTarget >= maxDraws) {
    throw vpException(vpException::fatalError, "task " + std::to_string(seed) +
                                                   ": no start and target in view and in one branch within " +
                                                   std::to_string(maxDraws) + " draws; widen --box");
  }
  task.unitFloor = unitNoiseFloor(world, task.qTarget);
  trueImages(world, task.qStart, task.leftStart, task.rightStart);
  trueImages(world, task.qTarget, task.leftTarget, task.rightTarget);

  vpGaussRand gauss(1.0, 0.0, streamSeed(seed, NOISE_STREAM + (singularStart ? 100 : 0)));
  auto normals = [&](size_t count) {
    std::vector<double> z(count);
    for (double &v : z) {
      v = gauss();
    }
    return z;
  };
  task.targetNoise = normals(4 * N);
  task.servoNoise = normals((world.budget + 1) * 4 * N);
  task.exploreNoise = normals((2 * n + 1) * 4 * N);

  vpUniRand outlierRng(static_cast<uint64_t>(streamSeed(seed, OUTLIER_STREAM + (singularStart ? 100 : 0))));
  for (unsigned int i = 0; i < (world.budget + 1) * N; ++i) {
    Outlier o;
    o.active = outlierRng.uniform(0.0, 1.0) < world.outlierProbability;
    o.rightImage = outlierRng.uniform(0.0, 1.0) < 0.5;
    const double angle = outlierRng.uniform(0.0, 2.0 * M_PI);
    const double length = outlierRng.uniform(world.outlierMinPx, world.outlierMaxPx);
    o.du = length * std::cos(angle);
    o.dv = length * std::sin(angle);
    task.outliers.push_back(o);
  }

  vpUniRand calibrationRng(static_cast<uint64_t>(streamSeed(seed, CALIBRATION_STREAM + (singularStart ? 100 : 0))));
  task.calibrationError =
      study::CalibrationErrorDirection::draw(calibrationRng, study::countLinkLengths(world.arm.getDHTable()));
  return task;
}

void addNoise(const std::vector<double> &z, size_t slot, double sigma, std::vector<vpImagePoint> &left,
              std::vector<vpImagePoint> &right)
{
  for (size_t k = 0; k < left.size(); ++k) {
    const double *zk = &z[(slot * left.size() + k) * 4];
    left[k].set_uv(left[k].get_u() + sigma * zk[0], left[k].get_v() + sigma * zk[1]);
    right[k].set_uv(right[k].get_u() + sigma * zk[2], right[k].get_v() + sigma * zk[3]);
  }
}

void measuredTarget(const Task &task, double sigma, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)
{
  left = task.leftTarget;
  right = task.rightTarget;
  addNoise(task.targetNoise, 0, sigma, left, right);
}
} // namespace study
