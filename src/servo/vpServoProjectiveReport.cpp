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
  The diagnostics of a vpServoProjective task's last computeControlLaw(), as vpServoProjectiveReport gives them in
  ViSP's types and in the unit of setErrorUnit(): the features' states, e and J, their singular values and condition
  number, the large projection operator and the joint-limit avoidance's velocity.
*/

#include <visp3/projective/vpServoProjectiveReport.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpServoProjectiveReport");

//! \f$ \sigma_{max} / \sigma_{min} \f$ from the eigenvalues of \f$ J^T J \f$; infinite if singular, 0 without column.
double conditionNumber(const vpServoNormalEquations &ne)
{
  const Eigen::Index n = ne.size();
  if (n == 0) {
    return 0.0;
  }
  const double sigmaMin = std::sqrt(std::max(0.0, ne.getEigenvalues()(0)));
  const double sigmaMax = std::sqrt(std::max(0.0, ne.getEigenvalues()(n - 1)));
  return sigmaMin > 0.0 ? sigmaMax / sigmaMin : std::numeric_limits<double>::infinity();
}
} // namespace

vpServoProjectiveReport::vpServoProjectiveReport()
    : m_data(), m_status(SERVO_RUNNING), m_lambda(0.0), m_damping(0.0), m_saturated(false), m_qdot2(),
      m_following(false), m_openLoopCalls(0), m_errorScale(1.0), m_rankTolerance(1e-6), m_states(),
      m_pseudoInverseThreshold(vpServoDampedLeastSquares().getPseudoInverseThreshold()), m_largeProjectionThresholds(),
      m_arm()
{
  vpServoJointLimitAvoidance().getLargeProjectionThresholds(m_largeProjectionThresholds[0],
                                                            m_largeProjectionThresholds[1]);
}

/*
  \f$ \sigma_{min}(J D^{-1}) / \sigma_{max}(J D^{-1}) \f$, \f$ D = \mathrm{diag}(\|J_{:,k}\|) \f$, from \f$ J^T J \f$:
  the singular values squared are the eigenvalues of \f$ D^{-1} J^T J D^{-1} \f$, the Gram matrix with unit diagonal.
  0 if a column norm is below \e tolerance times the largest (a joint that moves no active feature, or too little to
  tell), or without any column.
*/
double vpServoProjectiveReport::singularValueRatio(const JointMatrix &JtJ, double tolerance)
{
  const Eigen::Index n = JtJ.rows();
  JointVector d(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    d(k) = std::sqrt(std::max(0.0, JtJ(k, k)));
  }
  const double dMax = n > 0 ? d.maxCoeff() : 0.0;
  if (!(dMax > 0.0) || !(d.minCoeff() > tolerance * dMax)) {
    return 0.0;
  }
  JointMatrix C(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = 0; r < n; ++r) {
      C(r, c) = JtJ(r, c) / (d(r) * d(c));
    }
  }
  Eigen::SelfAdjointEigenSolver<JointMatrix> eig(C, Eigen::EigenvaluesOnly);
  const double lambdaMax = eig.eigenvalues()(n - 1);
  if (lambdaMax > 0.0) {
    return std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / lambdaMax);
  }
  return 0.0;
}

vpServoProjectiveReport::vpFeatureState vpServoProjectiveReport::getFeatureState(unsigned int i) const
{
  if (i >= m_states.size()) {
    std::ostringstream os;
    os << "feature index " << i << " is out of range; the last computeControlLaw() had " << m_states.size()
       << " features (indices in addFeature() order, from 0)";
    fail(vpProjectiveException::dimensionError, at("getFeatureState()"), os.str());
  }
  return m_states[i];
}

vpColVector vpServoProjectiveReport::getError() const
{
  return toVispVector(m_data.getError() / m_errorScale);
}

vpMatrix vpServoProjectiveReport::getTaskJacobian() const
{
  return toVisp(m_data.getTaskJacobian() / m_errorScale);
}

vpColVector vpServoProjectiveReport::getTaskSingularValues() const
{
  if (m_data.getTaskJacobian().size() == 0) {
    return vpColVector();
  }
  return toVispVector(Eigen::JacobiSVD<Eigen::MatrixXd>(m_data.getTaskJacobian() / m_errorScale).singularValues());
}

double vpServoProjectiveReport::getConditionNumber() const
{
  return conditionNumber(m_data.getNormalEquations());
}

double vpServoProjectiveReport::getSingularValueRatio() const
{
  return singularValueRatio(m_data.getNormalEquations().getJtJ(), m_rankTolerance);
}

vpMatrix vpServoProjectiveReport::getLargeProjectionOperator() const
{
  if (m_data.getNormalEquations().size() == 0) {
    fail(vpProjectiveException::notInitializedError, at("getLargeProjectionOperator()"),
         "no task Jacobian yet; call computeControlLaw() first");
  }
  // The parts with the call's settings, on demand: the task does not copy its parts into the report at each call.
  vpServoDampedLeastSquares law;
  law.setPseudoInverseThreshold(m_pseudoInverseThreshold);
  vpServoJointLimitAvoidance limits;
  limits.setLargeProjectionThresholds(m_largeProjectionThresholds[0], m_largeProjectionThresholds[1]);
  JointMatrix P;
  limits.computeLargeProjectionOperator(m_data.getNormalEquations(), m_data.getError().norm() / m_errorScale, law, P);
  return toVisp(P);
}

vpColVector vpServoProjectiveReport::getJointLimitVelocity() const
{
  return toVispVector(m_qdot2);
}
