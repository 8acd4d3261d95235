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

#include <visp3/projective/vpServoNormalEquations.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

#include <Eigen/Dense>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

vpServoNormalEquations::vpServoNormalEquations()
    : m_JtJ(), m_Jte(), m_L(), m_g(), m_inverseTrace(0.0), m_eigenvalues(), m_eigenvectors(), m_hasCholesky(false),
      m_positiveDefinite(false), m_hasStep(false), m_hasInverseTrace(false), m_hasEigen(false), m_factorisations(0)
{
}

void vpServoNormalEquations::compute(const Eigen::MatrixXd &J, const Eigen::VectorXd &e)
{
  // Column dot products, the lower triangle mirrored: cheaper than a matrix product kernel at these sizes.
  const Eigen::Index n = J.cols();
  m_JtJ.resize(n, n);
  m_Jte.resize(n);
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = c; r < n; ++r) {
      m_JtJ(r, c) = J.col(r).dot(J.col(c));
    }
    for (Eigen::Index r = 0; r < c; ++r) {
      m_JtJ(r, c) = m_JtJ(c, r);
    }
    m_Jte(c) = J.col(c).dot(e);
  }
  m_hasCholesky = m_positiveDefinite = m_hasStep = m_hasInverseTrace = m_hasEigen = false;
  m_factorisations = 0;
}

void vpServoNormalEquations::set(const JointMatrix &JtJ, const JointVector &Jte)
{
  m_JtJ = JtJ;
  m_Jte = Jte;
  m_hasCholesky = m_positiveDefinite = m_hasStep = m_hasInverseTrace = m_hasEigen = false;
  m_factorisations = 0;
}

namespace
{
/*
  The kernels of the Cholesky factorisation and what reads its factor, on column-major storage of leading dimension n
  (a JointMatrix's). Each is written once, with the joint count a template parameter N where it is that of a common
  arm (N > 0) and the run-time n otherwise (N = 0): a constant N gives the loops constant bounds and the columns a
  constant stride, which the compiler unrolls into straight-line code. Plain loops either way: for the few joints of
  an arm they are several times faster than Eigen's dynamic-size LLT and LDLT, which dispatch every column to
  matrix-vector kernels. The operations and their order do not depend on N: the same bits.
*/
template <int N> Eigen::Index jointCount(Eigen::Index n)
{
  return N > 0 ? N : n;
}

//! L with L L^T = A, A n x n symmetric, stored as its strictly lower triangle and the reciprocals of its diagonal on
//! the diagonal (every use of L_jj is a division: one per row instead, and products); false at the first pivot that
//! is not positive and finite (L then partly written).
template <int N> bool choleskyFactor(const double *A, double *L, Eigen::Index runtimeN)
{
  const Eigen::Index n = jointCount<N>(runtimeN);
  for (Eigen::Index j = 0; j < n; ++j) {
    double d = A[j + j * n];
    for (Eigen::Index k = 0; k < j; ++k) {
      d -= L[j + k * n] * L[j + k * n];
    }
    if (!(d > 0.0) || !std::isfinite(d)) {
      return false;
    }
    const double rjj = 1.0 / std::sqrt(d);
    L[j + j * n] = rjj;
    for (Eigen::Index i = j + 1; i < n; ++i) {
      double x = A[i + j * n];
      for (Eigen::Index k = 0; k < j; ++k) {
        x -= L[i + k * n] * L[j + k * n];
      }
      L[i + j * n] = x * rjj;
    }
  }
  return true;
}

//! g := (L L^T)^-1 g: forward then backward substitution (L as choleskyFactor() stores it).
template <int N> void choleskySolve(const double *L, double *g, Eigen::Index runtimeN)
{
  const Eigen::Index n = jointCount<N>(runtimeN);
  for (Eigen::Index i = 0; i < n; ++i) {
    double y = g[i];
    for (Eigen::Index k = 0; k < i; ++k) {
      y -= L[i + k * n] * g[k];
    }
    g[i] = y * L[i + i * n];
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    double y = g[i];
    for (Eigen::Index k = i + 1; k < n; ++k) {
      y -= L[k + i * n] * g[k];
    }
    g[i] = y * L[i + i * n];
  }
}

//! ||L^-1||_F^2, row by row of X = L^-1: X_ij = y_ij / L_ii with y_ij = -sum_{k=j}^{i-1} L_ik X_kj (j < i) and
//! X_ii = 1 / L_ii (L as choleskyFactor() stores it), so that row i's squared norm is (1 + sum_j y_ij^2) / L_ii^2.
//! Row i needs 1 / L_ii only at its end, and the rows before it only theirs: the trace's work overlaps the
//! factorisation's chain of square roots instead of waiting for its last pivot, three operations away from the
//! result.
template <int N> double inverseFrobeniusSquared(const double *L, Eigen::Index runtimeN)
{
  const Eigen::Index n = jointCount<N>(runtimeN);
  double X[vpProjectiveArmModel::maxJoints * vpProjectiveArmModel::maxJoints]; // row-major, lower triangle
  double sum = 0.0;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double r = L[i + i * n];
    double rowSum = 1.0;
    for (Eigen::Index j = 0; j < i; ++j) {
      double y = 0.0;
      for (Eigen::Index k = j; k < i; ++k) {
        y -= L[i + k * n] * X[k * n + j];
      }
      X[i * n + j] = y * r;
      rowSum += y * y;
    }
    X[i * n + i] = r;
    sum += rowSum * (r * r);
  }
  return sum;
}

//! f(std::integral_constant<int, N>()) with N = n for the joint counts of common arms (6, 7), N = 0 otherwise.
template <typename F> void withJointCount(Eigen::Index n, F &&f)
{
  switch (n) {
  case 6:
    f(std::integral_constant<int, 6>());
    break;
  case 7:
    f(std::integral_constant<int, 7>());
    break;
  default:
    f(std::integral_constant<int, 0>());
    break;
  }
}
} // namespace

void vpServoNormalEquations::factoriseCholesky() const
{
  m_hasCholesky = true;
  ++m_factorisations;
  const Eigen::Index n = m_JtJ.rows();
  m_L.resize(n, n);
  withJointCount(n,
                 [&](auto N) { m_positiveDefinite = choleskyFactor<decltype(N)::value>(m_JtJ.data(), m_L.data(), n); });
}

void vpServoNormalEquations::solveGaussNewton() const
{
  m_hasStep = true;
  if (!isPositiveDefinite()) {
    // What the pivoting LDLT gives of a singular system (zero pivots contribute nothing).
    ++m_factorisations;
    m_g = m_JtJ.ldlt().solve(m_Jte);
    return;
  }
  m_g = m_Jte; // L L^T g = J^T e
  withJointCount(m_JtJ.rows(), [&](auto N) { choleskySolve<decltype(N)::value>(m_L.data(), m_g.data(), m_g.size()); });
}

bool vpServoNormalEquations::isPositiveDefinite() const
{
  if (!m_hasCholesky) {
    factoriseCholesky();
  }
  return m_positiveDefinite;
}

const vpServoNormalEquations::JointVector &vpServoNormalEquations::getGaussNewtonStep() const
{
  if (!m_hasStep) {
    solveGaussNewton();
  }
  return m_g;
}

double vpServoNormalEquations::getInverseTrace() const
{
  if (m_hasInverseTrace) {
    return m_inverseTrace;
  }
  m_hasInverseTrace = true;
  if (!isPositiveDefinite()) {
    m_inverseTrace = std::numeric_limits<double>::infinity();
    return m_inverseTrace;
  }
  const Eigen::Index n = m_JtJ.rows();
  double sum = 0.0;
  withJointCount(n, [&](auto N) { sum = inverseFrobeniusSquared<decltype(N)::value>(m_L.data(), n); });
  m_inverseTrace = std::isfinite(sum) ? sum : std::numeric_limits<double>::infinity();
  return m_inverseTrace;
}

void vpServoNormalEquations::decompose() const
{
  m_hasEigen = true;
  ++m_factorisations;
  const Eigen::SelfAdjointEigenSolver<JointMatrix> eig(m_JtJ, Eigen::ComputeEigenvectors);
  m_eigenvalues = eig.eigenvalues();
  m_eigenvectors = eig.eigenvectors();
}

const vpServoNormalEquations::JointVector &vpServoNormalEquations::getEigenvalues() const
{
  if (!m_hasEigen) {
    decompose();
  }
  return m_eigenvalues;
}

const vpServoNormalEquations::JointMatrix &vpServoNormalEquations::getEigenvectors() const
{
  if (!m_hasEigen) {
    decompose();
  }
  return m_eigenvectors;
}

void vpServoNormalEquations::solveDamped(double mu2, JointVector &x) const
{
  if (!m_hasEigen) {
    decompose();
  }
  const Eigen::Index n = m_JtJ.rows();
  x.setZero(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    const double c = m_eigenvectors.col(k).dot(m_Jte) / (std::max(0.0, m_eigenvalues(k)) + mu2);
    x.noalias() += c * m_eigenvectors.col(k);
  }
}
