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
  The state of a vpServoProjective task's last computeControlLaw(), as its getters give it in ViSP's types and in the
  unit of setErrorUnit(): the features' states, e and J, their singular values and condition number, the large
  projection operator and the joint-limit avoidance's velocity.
*/

#include <visp3/projective/vpServoProjective.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpServoProjective");

//! \f$ \sigma_{max} / \sigma_{min} \f$ from the eigenvalues of \f$ J^T J \f$; infinite if singular, 0 without column.
double conditionNumber(const vpProjectiveArmModel::JointMatrix &JtJ)
{
  const Eigen::Index n = JtJ.rows();
  if (n == 0) {
    return 0.0;
  }
  Eigen::SelfAdjointEigenSolver<vpProjectiveArmModel::JointMatrix> eig(JtJ, Eigen::EigenvaluesOnly);
  const double sigmaMin = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
  const double sigmaMax = std::sqrt(std::max(0.0, eig.eigenvalues()(n - 1)));
  return sigmaMin > 0.0 ? sigmaMax / sigmaMin : std::numeric_limits<double>::infinity();
}
} // namespace

vpServoProjective::vpFeatureState vpServoProjective::getFeatureState(unsigned int i) const
{
  checkFeatureIndex(i, "getFeatureState()");
  return m_health.getFeatureState(i);
}

vpColVector vpServoProjective::getError() const
{
  return toVispVector(last().data.m_e / m_errorScale);
}

vpMatrix vpServoProjective::getTaskJacobian() const
{
  return toVisp(last().data.m_J / m_errorScale);
}

vpColVector vpServoProjective::getTaskSingularValues() const
{
  if (last().data.m_J.size() == 0) {
    return vpColVector();
  }
  return toVispVector(Eigen::JacobiSVD<Eigen::MatrixXd>(last().data.m_J / m_errorScale).singularValues());
}

double vpServoProjective::getConditionNumber() const
{
  return conditionNumber(last().data.m_JtJ);
}

vpMatrix vpServoProjective::getLargeProjectionOperator() const
{
  if (last().data.m_JtJ.rows() == 0) {
    fail(vpProjectiveException::notInitializedError, at("getLargeProjectionOperator()"),
         "no task Jacobian yet; call computeControlLaw() first");
  }
  JointMatrix P;
  m_jointLimits.computeLargeProjectionOperator(last().data.m_JtJ, last().data.m_Jte, last().data.m_errorNorm, m_law, P);
  return toVisp(P);
}

vpColVector vpServoProjective::getJointLimitVelocity() const
{
  return toVispVector(last().qdot2);
}
