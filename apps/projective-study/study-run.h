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
  \file study-run.h
  \brief One servo run of the study: the scenario, the loop every method runs, and its outcome.
*/

#ifndef _study_study_run_h_
#define _study_study_run_h_

#include <limits>
#include <string>

#include "study-control.h"
#include "study-task.h"
#include "study-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! What the controllers see: the plain Gaussian noise, gross outliers, or an occluded feature.
enum Scenario { NOMINAL, OUTLIERS, OCCLUSION };

//! The outcome of one servo run.
struct RunResult {
  bool acquisitionFailed = false, explorationFailed = false, exception = false, lostView = false, limitHit = false;
  int convergedAt = -1;
  int lastIteration = 0;
  unsigned int moves = 0;
  double finalImageRms = std::numeric_limits<double>::quiet_NaN();
  double errorOverFloor = std::numeric_limits<double>::quiet_NaN(); // mean over joints of |q - q*|_i / floor_i
  double straightness = std::numeric_limits<double>::quiet_NaN();
  double modelErrorTarget = std::numeric_limits<double>::quiet_NaN(); // projective only (px RMS)
  // Joint path (successes): its length (Euclidean, joint space) from the start to the convergence over the straight
  // distance |q_c - q_0| to the joints q_c reached at the convergence; the largest excursion of a joint beyond the
  // interval [start, end] of its values over the whole run (deg), the end being the joints at the end of the budget
  // for a success (the branch it converged in) and the true target otherwise.
  double jointPathRatio = std::numeric_limits<double>::quiet_NaN();
  double excursionDeg = 0.0;
  // Planned servo only: no plan (SERVO_NO_PLAN at the first iteration); the planned target's branch differs from the
  // taught target's (-1 when unknown).
  bool noPlan = false;
  int otherBranch = -1;
  // Outlier rejection by the controller (robust projective): gross errors seen and rejected, clean points rejected.
  unsigned int outliersSeen = 0, outliersRejected = 0, cleanSeen = 0, cleanRejected = 0;
  unsigned int stoppedIterations = 0;
  unsigned int mismatchIterations = 0; // projective and planned: SERVO_MODEL_MISMATCH (false alarms: no camera moves)
  std::string message;
  bool success() const
  {
    return !acquisitionFailed && !explorationFailed && !exception && !lostView && !limitHit && convergedAt >= 0;
  }
  std::string cause() const
  {
    if (acquisitionFailed) {
      return "acquisition";
    }
    if (explorationFailed) {
      return "exploration";
    }
    if (exception) {
      return "exception";
    }
    if (lostView) {
      return "lost view";
    }
    if (limitHit) {
      return "joint limit";
    }
    return convergedAt >= 0 ? "success" : "not converged";
  }
};

//! [Servo loop]
/*!
  The loop every method runs: measure, judge, command, integrate. The study judges convergence on the measurement
  with Gaussian noise only, of every tracked point (gross errors and the occlusion only affect what the controller
  sees). It runs the whole budget so that the final joint error is that of a settled arm, and stops early only when
  the markers leave an image or a joint limit is hit. Straightness: the noise-free image paths of the tracked points
  in both images from the start to the convergence, their total length over the total length of the straight
  segments from their start to their target images. Joint path: see RunResult.
*/
RunResult runServo(const World &world, const Task &task, double sigma, Controller &controller, Scenario scenario);
//! [Servo loop]
} // namespace study

#endif
