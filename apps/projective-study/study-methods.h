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
  \file study-methods.h
  \brief Every method of the study on one task: the projective servo (a fresh acquisition per task and noise level),
  calibrated IBVS at each calibration error, Broyden; and the self-check of the calibrated baseline.
*/

#ifndef _study_study_methods_h_
#define _study_study_methods_h_

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include <visp3/projective/vpProjectiveRobot.h>

#include "study-run.h"
#include "study-statistics.h"
#include "study-task.h"
#include "study-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Run all methods]
//! One line of study-runs.csv.
void writeRun(std::ofstream &csv, const World &world, const std::string &scenario, const std::string &method,
              double sigma, double factor, const Task &task, const RunResult &r);

/*!
  Runs every method on \e task at noise \e sigma in \e scenario and records them: the projective servo on \e robot
  (the model acquired for this task and noise level; null if the acquisition failed, with \e acquisitionMessage),
  plain and, if \e robust, with its robustness API; IBVS at each calibration error factor of \e factors; Broyden.
*/
void runMethods(const World &world, const Task &task, double sigma, const vpProjectiveRobot *robot,
                const std::string &acquisitionMessage, Scenario scenario, const std::string &scenarioName,
                const std::vector<double> &factors, bool robust, Results &results, std::ofstream &csv);

//! A fresh acquisition for \e task at noise \e sigma (its own seeded noise); null and a message if it throws.
std::unique_ptr<vpProjectiveRobot> acquireForTask(const World &world, const Task &task, double sigma,
                                                  unsigned int sigmaIndex, std::string &message, Results &results);
//! [Run all methods]

//! [Check]
/*!
  Self-check of the calibrated baseline: with the exact calibration and noise-free images, the stacked IBVS Jacobian
  must be the true image Jacobian (central differences of the simulator's projection). Returns the largest
  difference relative to the largest entry.
*/
double checkIbvsJacobian(const World &world, const Task &task);
//! [Check]
} // namespace study

#endif
