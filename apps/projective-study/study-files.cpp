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
  \file study-files.cpp
  \brief The study's data files: the summary CSV, the calibration sweep's CSV and its two figures (gnuplot).
*/

#include "study-report.h"

#include "figures.h"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
void writeSummary(const Results &results, const std::string &filename)
{
  std::ofstream out(filename.c_str());
  out << "case,method,sigma_px,calibration_error,tasks,success_percent,acquisition_failed,lost_view,joint_limit,"
         "not_converged,other,median_iterations,p95_iterations,median_joint_error_over_floor,median_straightness,"
         "median_extra_moves,median_joint_path_ratio,median_excursion_deg,max_excursion_deg,no_plan,plans,"
         "other_branch,mismatch_runs\n";
  for (const Cell &c : results.cells) {
    out << c.scenario << "," << c.method << "," << c.sigma << "," << c.calibrationFactor << "," << c.tasks << ","
        << c.successRate() << "," << c.count("acquisition") << "," << c.count("lost view") << ","
        << c.count("joint limit") << "," << c.count("not converged") << ","
        << c.count("exception") + c.count("exploration") << "," << percentile(c.iterations, 0.5) << ","
        << percentile(c.iterations, 0.95) << "," << percentile(c.errorOverFloor, 0.5) << ","
        << percentile(c.straightness, 0.5) << "," << percentile(c.moves, 0.5) << ","
        << percentile(c.jointPathRatio, 0.5) << "," << percentile(c.excursionDeg, 0.5) << ","
        << percentile(c.excursionDeg, 1.0) << "," << c.noPlan << "," << c.planned << "," << c.otherBranch << ","
        << c.mismatchRuns << "\n";
  }
}

void writeFigures(const World &world, const Results &results, const std::string &dir, std::ostream &log)
{
  const std::string csv = dir + "/study-calibration.csv";
  std::ofstream out(csv.c_str());
  out << "calibration_error";
  for (double sigma : world.sigmas) {
    out << ",ibvs_success_" << sigma << ",ibvs_median_it_" << sigma << ",projective_success_" << sigma
        << ",projective_median_it_" << sigma << ",broyden_success_" << sigma << ",broyden_median_it_" << sigma;
  }
  out << "\n";
  for (double factor : world.calibrationFactors) {
    out << factor;
    for (double sigma : world.sigmas) {
      const Cell &ibvs = results.get("nominal", "IBVS", sigma, factor);
      const Cell &proj = results.get("nominal", "projective", sigma);
      const Cell &broyden = results.get("nominal", "Broyden", sigma);
      for (const Cell *c : {&ibvs, &proj, &broyden}) {
        const double it = percentile(c->iterations, 0.5);
        out << "," << c->successRate() << "," << (std::isfinite(it) ? std::to_string(it) : std::string("NaN"));
      }
    }
    out << "\n";
  }
  out.close();

  const char *colors[3] = {"#1f77b4", "#d62728", "#2ca02c"};
  std::ostringstream gp;
  gp << "set datafile separator ','\nset datafile missing 'NaN'\nset terminal pngcairo size 900,600\nset key outside "
        "right\n"
     << "set xlabel 'calibration error of IBVS (x intrinsics 5 %, rig 2 deg, base 5 deg + 5 cm, links 2 %)'\n"
     << "set xtics ('0' 0, '1x' 1, '2x' 2, '4x' 4)\nset xrange [-0.2:4.2]\nset grid\n";
  for (int figure = 0; figure < 2; ++figure) {
    gp << "set output '" << dir << (figure == 0 ? "/study-success.png'\n" : "/study-iterations.png'\n") << "set title '"
       << (figure == 0 ? "success rate" : "median iterations to converge (successes)") << " over "
       << results.tasks.size() << " random tasks'\nset ylabel '" << (figure == 0 ? "success [%]" : "iterations")
       << "'\n"
       << (figure == 0 ? "set yrange [0:100]\n" : "set yrange [0:*]\n") << "plot ";
    for (size_t j = 0; j < world.sigmas.size(); ++j) {
      const size_t base = 2 + 6 * j + figure;
      gp << "'" << csv << "' using 1:" << base << " with linespoints lw 2 pt 7 lc rgb '" << colors[j % 3]
         << "' title 'IBVS, " << world.sigmas[j] << " px', '" << csv << "' using 1:" << base + 2
         << " with lines lw 2 dt 2 lc rgb '" << colors[j % 3] << "' title 'projective, " << world.sigmas[j] << " px', '"
         << csv << "' using 1:" << base + 4 << " with lines lw 2 dt 3 lc rgb '" << colors[j % 3] << "' title 'Broyden, "
         << world.sigmas[j] << " px'" << (j + 1 < world.sigmas.size() ? ", " : "\n");
    }
  }
  app::runGnuplot(gp.str(), dir + "/study-figures.gp", dir + "/study-success.png, " + dir + "/study-iterations.png",
                  csv, log);
}
} // namespace study
