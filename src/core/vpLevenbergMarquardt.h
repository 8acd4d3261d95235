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
  Private: the one Levenberg-Marquardt driver over normal equations the plugin writes by hand (the rigid-body tracker's
  two refinements, the inverse kinematics with its points). Not installed.
*/

#ifndef _vpLevenbergMarquardt_h_
#define _vpLevenbergMarquardt_h_

#include <algorithm>

#include <Eigen/Core>

namespace vpProjectiveInternal
{
/*!
  Levenberg-Marquardt on D parameters (Eigen::Dynamic: sized by \e evaluate): evaluate(x, &N, &g, cost) gives the
  normal equations N = J^T J, g = J^T r and the cost at x (false where the model is undefined; N and g null: the cost
  only); update(x, S, g, xNew) solves the damped system S (N with its diagonal scaled by 1 + lambda) for the step and
  applies it on the state's manifold. At most 30 accepted steps, 8 dampings each; stops at a relative decrease below
  1e-12. Returns false if the cost is undefined at the start. With a fixed D nothing is allocated.
*/
template <int D, typename State, typename Evaluate, typename Update>
bool levenbergMarquardt(State &x, double &cost, const Evaluate &evaluate, const Update &update)
{
  Eigen::Matrix<double, D, D> N, S;
  Eigen::Matrix<double, D, 1> g;
  if (!evaluate(x, &N, &g, cost)) {
    return false;
  }
  double lambda = 1e-4;
  State xNew;
  for (int iteration = 0; iteration < 30; ++iteration) {
    bool accepted = false, converged = false;
    for (int attempt = 0; attempt < 8 && !accepted; ++attempt) {
      S = N;
      S.diagonal() *= 1.0 + lambda;
      double costNew = 0.0;
      if (update(x, S, g, xNew) && evaluate(xNew, nullptr, nullptr, costNew) && costNew < cost) {
        converged = cost - costNew <= 1e-12 * cost;
        x = xNew;
        evaluate(x, &N, &g, cost);
        lambda = std::max(lambda / 10.0, 1e-12);
        accepted = true;
      } else {
        lambda *= 10.0;
      }
    }
    if (!accepted || converged) {
      break;
    }
  }
  return true;
}
} // namespace vpProjectiveInternal

#endif
