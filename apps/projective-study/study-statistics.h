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
  \file study-statistics.h
  \brief The study's statistics: the results of one method in one case at one noise level, and all of them.
*/

#ifndef _study_study_statistics_h_
#define _study_study_statistics_h_

#include <cmath>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpException.h>

#include "study-run.h"
#include "study-task.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Statistics]
//! Results of one method in one case at one noise level.
struct Cell {
  std::string scenario; // "nominal", "outliers", "occlusion", "singular start"
  std::string method;   // "projective", "projective (robust)", "IBVS", "Broyden"
  double sigma = 0.0;
  double calibrationFactor = -1.0; // IBVS only
  unsigned int tasks = 0;
  std::map<std::string, unsigned int> causes;
  std::map<std::string, std::vector<unsigned int>> seeds; // first seeds of each failure cause
  std::vector<double> iterations, errorOverFloor, straightness, moves, notConvergedRms, modelErrorTarget;
  std::vector<double> jointPathRatio;                    // successful runs
  std::vector<double> excursionDeg;                      // every run
  unsigned int noPlan = 0, planned = 0, otherBranch = 0; // planned servo: no plan; plans; plans in another branch
  std::vector<bool> successes;                           // per task, in task order (paired comparisons)
  unsigned int outliersSeen = 0, outliersRejected = 0, cleanSeen = 0, cleanRejected = 0, stoppedIterations = 0;
  unsigned int mismatchRuns = 0, mismatchIterations = 0; // runs with a SERVO_MODEL_MISMATCH, and its iterations

  void add(const RunResult &r, unsigned int seed)
  {
    ++tasks;
    const std::string c = r.cause();
    ++causes[c];
    successes.push_back(r.success());
    if (r.success()) {
      iterations.push_back(r.convergedAt);
      errorOverFloor.push_back(r.errorOverFloor);
      straightness.push_back(r.straightness);
      jointPathRatio.push_back(r.jointPathRatio);
    } else if (seeds[c].size() < 6) {
      seeds[c].push_back(seed);
    }
    if (!r.acquisitionFailed && !r.explorationFailed) {
      excursionDeg.push_back(r.excursionDeg);
    }
    noPlan += r.noPlan;
    planned += r.otherBranch >= 0;
    otherBranch += r.otherBranch == 1;
    if (c == "not converged") {
      notConvergedRms.push_back(r.finalImageRms);
    }
    if (std::isfinite(r.modelErrorTarget)) {
      modelErrorTarget.push_back(r.modelErrorTarget);
    }
    moves.push_back(r.moves);
    outliersSeen += r.outliersSeen;
    outliersRejected += r.outliersRejected;
    cleanSeen += r.cleanSeen;
    cleanRejected += r.cleanRejected;
    stoppedIterations += r.stoppedIterations;
    mismatchRuns += r.mismatchIterations > 0;
    mismatchIterations += r.mismatchIterations;
  }
  unsigned int count(const std::string &c) const
  {
    const auto it = causes.find(c);
    return it == causes.end() ? 0 : it->second;
  }
  double successRate() const { return tasks ? 100.0 * count("success") / tasks : 0.0; }
  std::string name() const
  {
    if (method == "IBVS") {
      if (calibrationFactor == 0.0) {
        return "IBVS, exact calibration";
      }
      std::ostringstream os;
      os << "IBVS, calibration error " << calibrationFactor << "x";
      return os.str();
    }
    if (method == "planned") {
      return "projective, planned";
    }
    if (method == "projective") {
      return "projective, law (47)";
    }
    if (method == "projective (robust)") {
      return "projective + robustness API";
    }
    return method;
  }
};

//! Nearest-rank percentile (p in [0, 1]); NaN for an empty set.

//! Nearest-rank percentile (p in [0, 1]); NaN for an empty set.
double percentile(std::vector<double> x, double p);
//! \e x with \e digits decimals, "-" if not finite.
std::string fixed(double x, int digits);
//! "a, b, c".
std::string seedList(const std::vector<unsigned int> &seeds);
//! [Statistics]

//! Everything the study computes, and the wall-clock time of each part.
struct Results {
  std::vector<Cell> cells;
  std::vector<Task> tasks;         // nominal tasks
  std::vector<Task> singularTasks; // singular-start tasks
  std::map<std::string, double> timeMs;
  unsigned int acquisitions = 0;

  Cell &cell(const std::string &scenario, const std::string &method, double sigma, double factor = -1.0)
  {
    for (Cell &c : cells) {
      if (c.scenario == scenario && c.method == method && c.sigma == sigma && c.calibrationFactor == factor) {
        return c;
      }
    }
    Cell c;
    c.scenario = scenario;
    c.method = method;
    c.sigma = sigma;
    c.calibrationFactor = factor;
    cells.push_back(c);
    return cells.back();
  }
  const Cell &get(const std::string &scenario, const std::string &method, double sigma, double factor = -1.0) const
  {
    for (const Cell &c : cells) {
      if (c.scenario == scenario && c.method == method && c.sigma == sigma && c.calibrationFactor == factor) {
        return c;
      }
    }
    throw vpException(vpException::fatalError, "no results for " + scenario + ", " + method);
  }
  std::vector<const Cell *> select(const std::string &scenario, double sigma) const
  {
    std::vector<const Cell *> out;
    for (const Cell &c : cells) {
      if (c.scenario == scenario && c.sigma == sigma) {
        out.push_back(&c);
      }
    }
    return out;
  }
};
} // namespace study

#endif
