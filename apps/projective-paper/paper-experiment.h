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
  \file paper-experiment.h
  \brief The paper's experiment (Ruf & Horaud, ICCV'99, section 6) in three steps: the acquisition of the arm, the
  servo run, and the Monte Carlo study over noise seeds (paper-experiment.cpp).
*/

#ifndef _app_paper_experiment_h_
#define _app_paper_experiment_h_

#include <algorithm>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "paper-world.h"
#include "servo-report.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
class PaperRecorder;

/*!
  Acquisition (paper section 6, Fig. 3): marker images at the zero reference q = 0, then joint i alone moved by
  +-trial_i (halved until every marker stays in view). The fundamental matrix is estimated from the same images, so
  nothing but pixels and encoder values enters the model. With \e recorder, the zero frame and the trials used are
  recorded (paper-record.h).
*/
vpProjectiveRobot acquire(const PaperWorld &world, double sigma, vpGaussRand &noise, bool verbose,
                          PaperRecorder *recorder = nullptr);

//! The inlier threshold of the acquisition's rig estimation at noise \e sigma (px).
inline double acquisitionThreshold(double sigma)
{
  return std::max(1.0, 4.0 * sigma);
}

/*!
  The servo task of the experiment on \e robot (the control law's gain, velocity limit and damping, the planner's
  settings with a largest excursion of \e maxExcursionDeg, settling if \e settling); features are added by the caller.
*/
void configureTask(vpServoProjective &task, const PaperWorld &world, const vpProjectiveRobot &robot,
                   double maxExcursionDeg, bool settling);

/*!
  The servo loop, written as in ViSP's tutorial-ibvs-4pts.cpp: build the features, compute the control law, send
  the joint velocities to the (simulated) robot. s* is the noisy image of the target: taught by showing, the mean of
  \e targetFrames frames (the first from \e noise, the others from a generator of their own seeded by \e seed, so
  that the servo sees the same frames whatever \e targetFrames); \e settling: vpServoProjective::setSettling().
  With \e recorder, the target frames and every servo iteration are recorded (paper-record.h).
*/
ServoRun servo(const PaperWorld &world, const vpProjectiveRobot &robot, double sigma, vpGaussRand &noise,
               unsigned int iterations, double maxExcursionDeg, unsigned int targetFrames = 1, bool settling = false,
               long seed = 1, PaperRecorder *recorder = nullptr);

//! Seeds 1 to \e seeds at noise \e sigma: a fresh acquisition and a servo run each, against the noise floor
//! sqrt(diag(sigma^2 (J^T J)^-1)) of the true stacked image Jacobian of the tracked markers at the target; each
//! seed's task is also run with s* taught from 16 frames and settling on (Study::settled).
Study study(const PaperWorld &world, double sigma, const std::vector<double> &paperDeg, unsigned int seeds,
            double maxExcursionDeg);
} // namespace app
#endif
