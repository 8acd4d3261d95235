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
  \file study-task.h
  \brief The study's tasks: a start and a target in one inverse-kinematic branch, and every random draw a task needs
  (noise, gross outliers, calibration error direction), shared by all methods and noise levels.
*/

#ifndef _study_study_task_h_
#define _study_study_task_h_

#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>

#include "study-calibration.h"
#include "study-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! A gross measurement error of one stereo point at one iteration.
struct Outlier {
  bool active;
  bool rightImage;
  double du, dv;
};

//! [Task]
//! A servo task and every random draw it needs, shared by all methods and noise levels.
struct Task {
  unsigned int seed = 0;
  bool singularStart = false;
  vpColVector qStart, qTarget;
  unsigned int drawnStart = 0, drawnTarget = 0; // configurations drawn to find them
  vpColVector unitFloor;                        // sqrt(diag((J^T J)^-1)) at the target (rad per px of noise)
  std::vector<vpImagePoint> leftStart, rightStart, leftTarget, rightTarget; // noise-free images
  std::vector<double> targetNoise;                                          // 4N standard normal draws: the measured s*
  std::vector<double> servoNoise;   // (budget + 1) x 4N: the measurement at each iteration
  std::vector<double> exploreNoise; // (2n + 1) x 4N: Broyden's exploratory measurements
  std::vector<Outlier> outliers;    // (budget + 1) x N
  study::CalibrationErrorDirection calibrationError;
};

//! sqrt(diag((J^T J)^-1)) with J the true stacked image Jacobian (central differences) of the tracked markers at q.
vpColVector unitNoiseFloor(const World &world, const vpColVector &q);

/*!
  Draws a task: the start uniformly in the box (for a singular start, q_4 within nearSingularDeg of the wrist
  singularity instead) until it is within the joint limits and the tracked markers are marginPx inside both images;
  then the target uniformly in the box until it is too and (unless World::anyBranchTargets()) in the start's branch.
  The box is World::box(): +-boxDeg (prismatic joints: World::prismaticPerDeg metres per degree) clipped to the
  joint limits. Then all the
  noise, outliers and the calibration error direction, from their own streams of the task's seed.
*/
Task makeTask(const World &world, unsigned int seed, bool singularStart);

//! Measured images: the noise-free ones plus sigma times the task's standard normal draws at \e slot.
void addNoise(const std::vector<double> &z, size_t slot, double sigma, std::vector<vpImagePoint> &left,
              std::vector<vpImagePoint> &right);

//! The measured target s* (noisy, taught by showing): the same for every method.
void measuredTarget(const Task &task, double sigma, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right);
} // namespace study

#endif
