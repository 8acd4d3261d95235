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
/*!
  Cholesky factorisation \f$ L L^T = S + a I \f$ of a symmetric matrix \e S shifted by \e a on its diagonal (lower
  triangle of S read, lower triangle of L written, L resized; S is not copied); false if \f$ S + a I \f$ is not
  numerically positive definite (a pivot is not positive, or is NaN). Plain loops: for the few joints of an arm they are
  several times faster than Eigen's dynamic-size LLT and LDLT, which dispatch every column to matrix-vector kernels.
*/
template <typename Matrix> bool choleskyShifted(const Matrix &S, double a, Matrix &L)
{
  const Eigen::Index n = S.rows();
  L.resize(n, n);
  for (Eigen::Index j = 0; j < n; ++j) {
    double d = S(j, j) + a;
    for (Eigen::Index k = 0; k < j; ++k) {
      d -= L(j, k) * L(j, k);
    }
    if (!(d > 0.0)) {
      return false;
    }
    const double ljj = std::sqrt(d);
    L(j, j) = ljj;
    for (Eigen::Index i = j + 1; i < n; ++i) {
      double x = S(i, j);
      for (Eigen::Index k = 0; k < j; ++k) {
        x -= L(i, k) * L(j, k);
      }
      L(i, j) = x / ljj;
    }
  }
  return true;
}

//! Solves \f$ L L^T x = b \f$ in place (x holds b on entry), L from choleskyShifted().
template <typename Matrix, typename Vector> void choleskySolveInPlace(const Matrix &L, Vector &x)
{
  const Eigen::Index n = L.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    double y = x(i);
    for (Eigen::Index k = 0; k < i; ++k) {
      y -= L(i, k) * x(k);
    }
    x(i) = y / L(i, i);
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    double y = x(i);
    for (Eigen::Index k = i + 1; k < n; ++k) {
      y -= L(k, i) * x(k);
    }
    x(i) = y / L(i, i);
  }
}

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
  \f$ \mu^2 \f$ of the law for \f$ J^T J \f$; \e positiveDefinite is set when \f$ J^T J + \mu^2 I \f$ is known to be
  positive definite (\f$ \sigma_{min} > \sigma_0 > 0 \f$ proven, or \f$ \mu > 0 \f$).
*/
double squaredDamping(const vpServoDampedLeastSquares::JointMatrix &JtJ, double sigmaThreshold, double maxDamping,
                      bool &positiveDefinite)
{
  // mu > 0 only if sigma_min < sigma_0. Away from singularities a Cholesky factorisation of J^T J - sigma_0^2 I
  // proves sigma_min > sigma_0 at a fraction of the cost of the eigenvalues; otherwise the eigenvalues decide.
  double mu2 = 0.0;
  positiveDefinite = false;
  if (sigmaThreshold > 0.0) {
    vpServoDampedLeastSquares::JointMatrix L;
    positiveDefinite = choleskyShifted(JtJ, -(sigmaThreshold * sigmaThreshold), L);
    if (!positiveDefinite) {
      Eigen::SelfAdjointEigenSolver<vpServoDampedLeastSquares::JointMatrix> eig(JtJ, Eigen::EigenvaluesOnly);
      const double sigmaMin = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
      if (sigmaMin < sigmaThreshold) {
        const double ratio = sigmaMin / sigmaThreshold;
        mu2 = maxDamping * maxDamping * (1.0 - ratio * ratio);
      }
    }
  }
  positiveDefinite = positiveDefinite || mu2 > 0.0;
  return mu2;
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

void vpServoDampedLeastSquares::computeNormalEquations(const Eigen::MatrixXd &J, const Eigen::VectorXd &e,
                                                       JointMatrix &JtJ, JointVector &Jte)
{
  // Column dot products, the lower triangle mirrored: cheaper than a matrix product kernel at these sizes.
  const Eigen::Index n = J.cols();
  JtJ.resize(n, n);
  Jte.resize(n);
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = c; r < n; ++r) {
      JtJ(r, c) = J.col(r).dot(J.col(c));
    }
    for (Eigen::Index r = 0; r < c; ++r) {
      JtJ(r, c) = JtJ(c, r);
    }
    Jte(c) = J.col(c).dot(e);
  }
}

void vpServoDampedLeastSquares::computeVelocity(const JointMatrix &JtJ, const JointVector &Jte, double lambda,
                                                JointVector &qdot)
{
  bool positiveDefinite = false;
  const double mu2 = squaredDamping(JtJ, m_sigmaThreshold, m_maxDamping, positiveDefinite);
  // Cholesky where J^T J + mu^2 I is known to be positive definite; elsewhere (no damping configured, J possibly rank
  // deficient) the pivoting LDLT, which gives what it can of a singular system.
  JointMatrix L;
  qdot = Jte;
  if (positiveDefinite && choleskyShifted(JtJ, mu2, L)) {
    choleskySolveInPlace(L, qdot);
  } else {
    JointMatrix A = JtJ;
    A.diagonal().array() += mu2;
    qdot = A.ldlt().solve(Jte);
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
  JointMatrix JtJ;
  JointVector Jte, qdot;
  computeNormalEquations(JE, eE, JtJ, Jte);
  computeVelocity(JtJ, Jte, lambda, qdot);
  return toVispVector(qdot);
}

bool vpServoDampedLeastSquares::saturate(JointVector &qdot) const
{
  return saturateInPlace(m_qdotMax, qdot);
}

void vpServoDampedLeastSquares::addNullSpaceProjector(const JointMatrix &JtJ, double weight, JointMatrix &P) const
{
  // The eigenvectors of J^T J whose singular value is below the pseudo-inverse threshold (vpServo's rule).
  const Eigen::Index n = JtJ.rows();
  if (n == 0) {
    return;
  }
  Eigen::SelfAdjointEigenSolver<JointMatrix> eig(JtJ, Eigen::ComputeEigenvectors);
  const double lambdaMax = eig.eigenvalues()(n - 1);
  const double zero = m_pseudoInverseThreshold * m_pseudoInverseThreshold * std::max(0.0, lambdaMax);
  for (Eigen::Index k = 0; k < n; ++k) {
    if (eig.eigenvalues()(k) <= zero) {
      P.noalias() += weight * eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose();
    }
  }
}
