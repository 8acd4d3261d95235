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

/*
  Private: the one way the plugin runs Ceres. Not installed.
*/

#ifndef _vpProjectiveCeres_h_
#define _vpProjectiveCeres_h_

#include <ceres/ceres.h>

namespace vpProjectiveInternal
{
/*!
  Levenberg-Marquardt on \e problem, single-threaded (the caller's loop owns the cores) and silent (a library does not
  print). \e tolerance bounds the relative change of the cost and of the parameters at convergence.
*/
inline ceres::Solver::Summary solveLeastSquares(ceres::Problem &problem, ceres::LinearSolverType linearSolver,
                                                int maxIterations, double tolerance = 1e-12)
{
  ceres::Solver::Options options;
  options.linear_solver_type = linearSolver;
  options.max_num_iterations = maxIterations;
  options.function_tolerance = tolerance;
  options.parameter_tolerance = tolerance;
  options.gradient_tolerance = 1e-2 * tolerance;
  options.num_threads = 1;
  options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary;
}
} // namespace vpProjectiveInternal

#endif
