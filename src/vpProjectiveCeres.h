/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
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
