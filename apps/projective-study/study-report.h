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
  \file study-report.h
  \brief The study's report: markdown tables, verdicts, CSV data and figures.
*/

#ifndef _study_study_report_h_
#define _study_study_report_h_

#include <ostream>
#include <string>
#include <vector>

#include "study-statistics.h"
#include "study-task.h"
#include "study-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Report]
//! Paired comparison of two methods on the same tasks: "wins against", "ties with" or "loses to" (McNemar's test at
//! about 95 %: a tie when |b - c| <= 2 sqrt(b + c), b and c the tasks only one of them solves).
std::string verdict(const Cell &a, const Cell &b, unsigned int &onlyA, unsigned int &onlyB);
//! One sentence naming the world (--world and --rig), its arm, zero reference, rig and trials.
std::string worldDescription(const World &world);
//! The planned servo against law (47) on the same nominal tasks: the tasks each solves and the other does not (the
//! first seeds of those law (47) solves alone), and the planned servo's success among the tasks law (47) solves.
std::string plannedAgainstLaw(const World &world, const Results &results);
//! Distribution of the random rigs of --rig random (percentiles, image sizes).
std::string rigDistribution(const std::vector<RigDraw> &draws);
//! The joint limits relative to the zero reference, in words.
std::string jointLimits(const World &world);
//! The header of a markdown table of cells, first column \e first.
std::string tableHeader(const std::string &first);
//! One markdown row of a cell.
std::string tableRow(const std::string &first, const Cell &c);
//! Distribution of a set of tasks: percentiles 5, 50 and 95 of their sizes.
std::string taskDistribution(const World &world, const std::vector<Task> &tasks);
//! Success rate per tool rotation of the task (nominal case): where the tasks get hard for every method.
std::string rotationBreakdown(const World &world, const Results &results);
//! One line per method, case and noise level: the numbers of the markdown tables.
void writeSummary(const Results &results, const std::string &filename);
//! CSV of the calibration sweep and the two PNG figures (gnuplot).
void writeFigures(const World &world, const Results &results, const std::string &dir, std::ostream &log);
//! The plain-language verdicts: where the projective servo wins, ties and loses, with the numbers behind them.
std::string summary(const World &world, const Results &results);
/*!
  The markdown report of the study of \e nbTasks tasks from seed \e seed: the settings, the tasks, the nominal and
  robustness tables, the verdicts and the projective servo's failures (the run time is added by the caller).
*/
std::string markdownReport(const World &world, const Results &results, unsigned int nbTasks, unsigned int seed);
//! [Report]
} // namespace study

#endif
