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

void vpServoNormalEquations::factoriseCholesky() const
{
  // Plain loops: for the few joints of an arm they are several times faster than Eigen's dynamic-size LLT and LDLT,
  // which dispatch every column to matrix-vector kernels.
  m_hasCholesky = true;
  ++m_factorisations;
  const Eigen::Index n = m_JtJ.rows();
  m_L.resize(n, n);
  m_positiveDefinite = true;
  for (Eigen::Index j = 0; j < n; ++j) {
    double d = m_JtJ(j, j);
    for (Eigen::Index k = 0; k < j; ++k) {
      d -= m_L(j, k) * m_L(j, k);
    }
    if (!(d > 0.0) || !std::isfinite(d)) {
      m_positiveDefinite = false;
      return;
    }
    const double ljj = std::sqrt(d);
    m_L(j, j) = ljj;
    for (Eigen::Index i = j + 1; i < n; ++i) {
      double x = m_JtJ(i, j);
      for (Eigen::Index k = 0; k < j; ++k) {
        x -= m_L(i, k) * m_L(j, k);
      }
      m_L(i, j) = x / ljj;
    }
  }
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
  // L L^T g = J^T e: forward then backward substitution.
  const Eigen::Index n = m_JtJ.rows();
  m_g = m_Jte;
  for (Eigen::Index i = 0; i < n; ++i) {
    double y = m_g(i);
    for (Eigen::Index k = 0; k < i; ++k) {
      y -= m_L(i, k) * m_g(k);
    }
    m_g(i) = y / m_L(i, i);
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    double y = m_g(i);
    for (Eigen::Index k = i + 1; k < n; ++k) {
      y -= m_L(k, i) * m_g(k);
    }
    m_g(i) = y / m_L(i, i);
  }
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
  // ||L^-1||_F^2, column by column of L^-1 (lower triangular: x_j = 1 / L_jj, then forward substitution), with the
  // reciprocals of the diagonal computed once: divisions are the cost at these sizes.
  const Eigen::Index n = m_JtJ.rows();
  JointVector x(n), reciprocal(n);
  for (Eigen::Index j = 0; j < n; ++j) {
    reciprocal(j) = 1.0 / m_L(j, j);
  }
  double sum = 0.0;
  for (Eigen::Index j = 0; j < n; ++j) {
    x(j) = reciprocal(j);
    sum += x(j) * x(j);
    for (Eigen::Index i = j + 1; i < n; ++i) {
      double y = 0.0;
      for (Eigen::Index k = j; k < i; ++k) {
        y -= m_L(i, k) * x(k);
      }
      x(i) = y * reciprocal(i);
      sum += x(i) * x(i);
    }
  }
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
