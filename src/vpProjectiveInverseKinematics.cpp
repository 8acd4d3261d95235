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

#include <visp3/projective/vpProjectiveInverseKinematics.h>

#include <cmath>

#include <Eigen/Dense>

#include "vpProjectiveInternal.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
/*!
  The normal equations of the pixel error at \e q: \f$ J^T J \f$ (n x n), \f$ J^T r \f$ and the cost \f$ r^T r \f$,
  accumulated marker by marker (4 rows of \f$ J \f$, eq. (46), at a time: nothing is allocated). False if a marker
  is on a camera's focal plane at \e q.
*/
bool normalEquations(const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
                     const std::vector<unsigned int> &indices, const vpProjectiveArmModel::JointVector &q,
                     vpProjectiveArmModel::JointMatrix &JtJ, vpProjectiveArmModel::JointVector &Jtr, double &cost)
{
  const Eigen::Index n = static_cast<Eigen::Index>(model.getNumberOfJoints());
  const Eigen::Matrix4d H = model.displacement(q);
  Eigen::Matrix4d HhatKq[vpProjectiveArmModel::maxJoints];
  model.jointMotions(q, HhatKq);
  JtJ.setZero(n, n);
  Jtr.setZero(n);
  cost = 0.0;
  vpProjectiveArmModel::PointJacobian J;
  for (size_t k = 0; k < s.size(); ++k) {
    const Eigen::Vector4d M = H * model.markers()[indices[k]];
    Eigen::Vector4d sM;
    if (!model.getStereoRig().project(M, sM) || !model.imageJacobian(HhatKq, M, J)) {
      return false;
    }
    const Eigen::Vector4d r = sM - s[k];
    JtJ.noalias() += J.transpose() * J;
    Jtr.noalias() += J.transpose() * r;
    cost += r.squaredNorm();
  }
  return std::isfinite(cost);
}
} // namespace

vpProjectiveArmModel::JointVector vpProjectiveInverseKinematics::solve(const vpProjectiveArmModel &model,
                                                                       const std::vector<Eigen::Vector4d> &s,
                                                                       const std::vector<unsigned int> &indices,
                                                                       const vpProjectiveArmModel::JointVector &q0,
                                                                       double *residual)
{
  // Levenberg-Marquardt on the normal equations, damping relative to their diagonal (Marquardt's scaling, so that
  // radians and length units mix): a few iterations from a nearby start (motion capture), more from afar.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;
  typedef vpProjectiveArmModel::JointVector JointVector;
  JointMatrix JtJ, A;
  JointVector Jtr, q = q0, qNew, step;
  double cost = 0.0;
  if (!normalEquations(model, s, indices, q, JtJ, Jtr, cost)) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveInverseKinematics::solve()",
         "a marker lies on a camera's focal plane at the starting joint values; start closer to the solution (q0)");
  }
  double lambda = 1e-3;
  for (int evaluation = 0; evaluation < 100; ++evaluation) {
    A = JtJ;
    A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-12 * JtJ.diagonal().maxCoeff());
    step = A.ldlt().solve(-Jtr);
    // The decrease the local quadratic model promises: below the rounding of the cost, the minimum is reached (this
    // saves the evaluations that would only find it out).
    const double promised = -Jtr.dot(step) - 0.5 * step.dot(JtJ * step);
    if (!step.allFinite() || !(promised > 1e-15 * cost) || step.norm() <= 1e-14 * (1.0 + q.norm())) {
      break;
    }
    qNew = q + step;
    JointMatrix JtJNew;
    JointVector JtrNew;
    double costNew = 0.0;
    if (normalEquations(model, s, indices, qNew, JtJNew, JtrNew, costNew) && costNew < cost) {
      q = qNew;
      JtJ = JtJNew;
      Jtr = JtrNew;
      cost = costNew;
      lambda = std::max(lambda / 10.0, 1e-12);
    } else {
      lambda *= 10.0;
      if (lambda > 1e12) {
        break; // no step lowers the cost: a minimum to working precision
      }
    }
  }
  if (!q.allFinite()) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveInverseKinematics::solve()",
         "the inverse kinematics did not converge; start closer to the solution (q0) or check the marker images");
  }
  if (residual != nullptr) {
    *residual = std::sqrt(cost / static_cast<double>(4 * s.size()));
  }
  return q;
}
