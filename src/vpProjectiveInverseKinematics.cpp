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

#include <ceres/ceres.h>

#include "vpProjectiveCeres.h"
#include "vpProjectiveInternal.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
// Pixel error of the observed markers at configuration q, with the analytic Jacobian of eqs. (45)-(46).
class InverseKinematicsCost : public ceres::CostFunction
{
public:
  InverseKinematicsCost(const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
                        const std::vector<unsigned int> &indices)
      : m_model(model), m_s(s), m_indices(indices)
  {
    set_num_residuals(static_cast<int>(4 * s.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(model.getNumberOfJoints()));
  }

  bool Evaluate(double const *const *parameters, double *residuals, double **jacobians) const override
  {
    const unsigned int n = m_model.getNumberOfJoints();
    const vpProjectiveArmModel::JointVector q =
        Eigen::Map<const Eigen::VectorXd>(parameters[0], static_cast<Eigen::Index>(n));
    const Eigen::Matrix4d H = m_model.displacement(q);
    Eigen::Matrix4d HhatKq[vpProjectiveArmModel::maxJoints];
    m_model.jointMotions(q, HhatKq);
    vpProjectiveArmModel::PointJacobian J;
    for (size_t k = 0; k < m_s.size(); ++k) {
      const Eigen::Vector4d M = H * m_model.markers()[m_indices[k]];
      Eigen::Vector4d s;
      if (!m_model.getStereoRig().project(M, s)) {
        return false;
      }
      Eigen::Map<Eigen::Vector4d>(residuals + 4 * k) = s - m_s[k];
      if (jacobians != nullptr && jacobians[0] != nullptr) {
        if (!m_model.imageJacobian(HhatKq, M, J)) {
          return false;
        }
        for (int r = 0; r < 4; ++r) {
          for (unsigned int i = 0; i < n; ++i) {
            jacobians[0][(4 * k + static_cast<size_t>(r)) * n + i] = J(r, i);
          }
        }
      }
    }
    return true;
  }

private:
  const vpProjectiveArmModel &m_model;
  const std::vector<Eigen::Vector4d> &m_s;
  const std::vector<unsigned int> &m_indices;
};
} // namespace

vpProjectiveArmModel::JointVector vpProjectiveInverseKinematics::solve(const vpProjectiveArmModel &model,
                                                                       const std::vector<Eigen::Vector4d> &s,
                                                                       const std::vector<unsigned int> &indices,
                                                                       const vpProjectiveArmModel::JointVector &q0,
                                                                       double *residual)
{
  Eigen::VectorXd q = q0;
  ceres::Problem problem;
  problem.AddResidualBlock(new InverseKinematicsCost(model, s, indices), nullptr, q.data());
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_QR, 100, 1e-15);
  if (!summary.IsSolutionUsable()) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveInverseKinematics::solve()",
         "the inverse kinematics did not converge; start closer to the solution (q0) or check the marker images");
  }
  if (residual != nullptr) {
    *residual = std::sqrt(2.0 * summary.final_cost / static_cast<double>(4 * s.size()));
  }
  return q;
}
