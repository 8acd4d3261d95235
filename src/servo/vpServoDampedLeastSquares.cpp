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

#include <visp3/projective/vpServoDampedLeastSquares.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoDampedLeastSquares");

namespace
{
//! The velocity saturation of setMaxJointVelocity() (0 disables it); true if it scaled \e qdot.
bool saturateInPlace(double qdotMax, vpServoDampedLeastSquares::JointVector &qdot)
{
  if (!(qdotMax > 0.0) || qdot.size() == 0) {
    return false;
  }
  const double largest = qdot.cwiseAbs().maxCoeff();
  if (!(largest > qdotMax)) {
    return false;
  }
  qdot *= qdotMax / largest;
  return true;
}

/*!
  \f$ \mu^2 \f$ of the law for the normal equations \e ne: 0 unless \f$ \sigma_{min} < \sigma_0 \f$.
*/
double squaredDamping(const vpServoNormalEquations &ne, double sigmaThreshold, double maxDamping)
{
  // Away from singularities the Cholesky factor the undamped law solves with proves sigma_min > sigma_0 at once:
  // tr((J^T J)^-1) >= 1 / sigma_min^2. Otherwise the eigenvalues decide (and then also give the damped solve).
  if (!(sigmaThreshold > 0.0) ||
      (ne.isPositiveDefinite() && ne.getInverseTrace() * sigmaThreshold * sigmaThreshold < 1.0)) {
    return 0.0;
  }
  const double sigmaMin = std::sqrt(std::max(0.0, ne.getEigenvalues()(0)));
  if (!(sigmaMin < sigmaThreshold)) {
    return 0.0;
  }
  const double ratio = sigmaMin / sigmaThreshold;
  return maxDamping * maxDamping * (1.0 - ratio * ratio);
}
} // namespace

vpServoDampedLeastSquares::vpServoDampedLeastSquares()
    : m_sigmaThreshold(1.0), m_maxDamping(10.0), m_qdotMax(0.0), m_pseudoInverseThreshold(1e-6), m_damping(0.0),
      m_saturated(false)
{
}

void vpServoDampedLeastSquares::setDamping(double sigmaThreshold, double maxDamping)
{
  const std::string where = at("setDamping()");
  const double threshold = nonNegative(sigmaThreshold, where, "the singular value threshold", "px/rad; 0: no damping");
  m_maxDamping = nonNegative(maxDamping, where, "the maximum damping", "px/rad"); // both checked before any change
  m_sigmaThreshold = threshold;
}

void vpServoDampedLeastSquares::setMaxJointVelocity(double qdotMax)
{
  m_qdotMax = nonNegative(qdotMax, at("setMaxJointVelocity()"), "the maximum joint velocity",
                          "rad/s or m/s per joint; 0 disables the limit");
}

void vpServoDampedLeastSquares::setPseudoInverseThreshold(double threshold)
{
  const std::string where = at("setPseudoInverseThreshold()");
  requireFinite(threshold, where, "the pseudo-inverse threshold");
  if (!(threshold >= 0.0) || !(threshold < 1.0)) {
    fail(vpProjectiveException::invalidValueError, where,
         "the pseudo-inverse threshold is a ratio of singular values and must be in [0, 1), e.g. 1e-6");
  }
  m_pseudoInverseThreshold = threshold;
}

void vpServoDampedLeastSquares::computeVelocity(const vpServoNormalEquations &ne, double lambda, JointVector &qdot)
{
  // mu = 0: the Gauss-Newton step of the normal equations' one Cholesky factorisation (their pivoting LDLT where J is
  // rank deficient and no damping is configured: zero pivots contribute nothing); mu > 0: their eigen decomposition,
  // which the damping's decision computed.
  const double mu2 = squaredDamping(ne, m_sigmaThreshold, m_maxDamping);
  if (mu2 > 0.0) {
    ne.solveDamped(mu2, qdot);
  } else {
    qdot = ne.getGaussNewtonStep();
  }
  qdot *= -lambda;
  const bool saturated = saturateInPlace(m_qdotMax, qdot);
  if (!qdot.allFinite()) {
    fail(vpProjectiveException::estimationFailedError, at("computeVelocity()"),
         "the control law gave a non-finite velocity (singular task Jacobian); increase the damping");
  }
  m_damping = std::sqrt(mu2);
  m_saturated = saturated;
}

vpColVector vpServoDampedLeastSquares::computeVelocity(const vpMatrix &J, const vpColVector &e, double lambda)
{
  const std::string where = at("computeVelocity()");
  if (J.getRows() == 0 || J.getCols() == 0 || J.getCols() > maxJoints) {
    std::ostringstream os;
    os << "J is " << J.getRows() << "x" << J.getCols() << "; give at least one row and 1 to " << maxJoints
       << " columns (one per joint)";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (e.getRows() != J.getRows()) {
    std::ostringstream os;
    os << "e has " << e.getRows() << " entries but J has " << J.getRows() << " rows; give one error per row of J";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!allFinite(J)) {
    fail(vpProjectiveException::nonFiniteValueError, where, "J has a NaN or infinite entry");
  }
  if (!allFinite(e)) {
    fail(vpProjectiveException::nonFiniteValueError, where, "e has a NaN or infinite entry");
  }
  nonNegative(lambda, where, "the gain", "1/s");
  Eigen::MatrixXd JE(J.getRows(), J.getCols());
  conversion::visp2eigen(J, JE);
  const Eigen::VectorXd eE = eigenMap(e);
  vpServoNormalEquations ne;
  ne.compute(JE, eE);
  JointVector qdot;
  computeVelocity(ne, lambda, qdot);
  return toVispVector(qdot);
}

bool vpServoDampedLeastSquares::saturate(JointVector &qdot) const
{
  return saturateInPlace(m_qdotMax, qdot);
}

void vpServoDampedLeastSquares::addNullSpaceProjector(const vpServoNormalEquations &ne, double weight,
                                                      JointMatrix &P) const
{
  // The eigenvectors of J^T J whose singular value is below the pseudo-inverse threshold (vpServo's rule).
  const Eigen::Index n = ne.size();
  if (n == 0) {
    return;
  }
  const JointVector &eigenvalues = ne.getEigenvalues();
  const JointMatrix &eigenvectors = ne.getEigenvectors();
  const double zero = m_pseudoInverseThreshold * m_pseudoInverseThreshold * std::max(0.0, eigenvalues(n - 1));
  for (Eigen::Index k = 0; k < n; ++k) {
    if (eigenvalues(k) <= zero) {
      P.noalias() += weight * eigenvectors.col(k) * eigenvectors.col(k).transpose();
    }
  }
}
