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

#include <visp3/projective/vpServoJointLimitAvoidance.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoJointLimitAvoidance");

namespace
{
//! The primary task of the ViSP-typed entry points, checked, as normal equations.
void primaryTask(const vpMatrix &J, const vpColVector &e, const std::string &where, vpServoNormalEquations &ne,
                 double &errorNorm)
{
  if (J.getRows() == 0 || J.getCols() == 0 || J.getCols() > vpProjectiveArmModel::maxJoints) {
    std::ostringstream os;
    os << "J is " << J.getRows() << "x" << J.getCols() << "; give at least one row and 1 to "
       << vpProjectiveArmModel::maxJoints << " columns (one per joint)";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (e.getRows() != J.getRows()) {
    std::ostringstream os;
    os << "e has " << e.getRows() << " entries but J has " << J.getRows() << " rows; give one error per row of J";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!allFinite(J) || !allFinite(e)) {
    fail(vpProjectiveException::nonFiniteValueError, where, "J or e has a NaN or infinite entry");
  }
  Eigen::MatrixXd JE(J.getRows(), J.getCols());
  conversion::visp2eigen(J, JE);
  const Eigen::VectorXd eE = eigenMap(e);
  ne.compute(JE, eE);
  errorNorm = eE.norm();
}
} // namespace

vpServoJointLimitAvoidance::vpServoJointLimitAvoidance()
    : m_enabled(false), m_qmin(), m_qmax(), m_rho(0.1), m_rho1(0.3), m_lambdaTune(0.7), m_e0(0.1), m_e1(0.7)
{
}

void vpServoJointLimitAvoidance::setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double rho,
                                                double rho1, double lambdaTune)
{
  const std::string where = at("setJointLimits()");
  if (qmin.getRows() != qmax.getRows()) {
    std::ostringstream os;
    os << "qmin has " << qmin.getRows() << " entries and qmax " << qmax.getRows() << "; give one limit per joint";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const unsigned int n = qmin.getRows();
  if (n == 0 || n > vpProjectiveArmModel::maxJoints) {
    std::ostringstream os;
    os << "qmin and qmax have " << n << " entries; a chain has 1 to " << vpProjectiveArmModel::maxJoints << " joints";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  for (unsigned int i = 0; i < n; ++i) {
    requireFinite(qmin[i], where, "qmin");
    requireFinite(qmax[i], where, "qmax");
    if (!(qmin[i] < qmax[i])) {
      std::ostringstream os;
      os << "joint " << i << ": qmin (" << qmin[i] << ") must be below qmax (" << qmax[i] << ")";
      fail(vpProjectiveException::invalidValueError, where, os.str());
    }
  }
  requireFinite(rho, where, "rho");
  requireFinite(rho1, where, "rho1");
  requireFinite(lambdaTune, where, "lambdaTune");
  if (!(rho > 0.0) || rho > 0.5) {
    fail(vpProjectiveException::invalidValueError, where,
         "rho must be in (0, 1/2]: the activation band is a fraction of the range at each end, and the bands of "
         "both ends must not overlap");
  }
  if (!(rho1 > 0.0) || rho1 > 1.0) {
    fail(vpProjectiveException::invalidValueError, where, "rho1 must be in (0, 1]");
  }
  if (lambdaTune < 0.0 || lambdaTune > 1.0) {
    fail(vpProjectiveException::invalidValueError, where, "lambdaTune must be in [0, 1]");
  }
  m_qmin.resize(n);
  m_qmax.resize(n);
  for (unsigned int i = 0; i < n; ++i) {
    m_qmin(i) = qmin[i];
    m_qmax(i) = qmax[i];
  }
  m_rho = rho;
  m_rho1 = rho1;
  m_lambdaTune = lambdaTune;
  m_enabled = true;
}

void vpServoJointLimitAvoidance::setLargeProjectionThresholds(double e0, double e1)
{
  const std::string where = at("setLargeProjectionThresholds()");
  requireFinite(e0, where, "e0");
  requireFinite(e1, where, "e1");
  if (!(e0 >= 0.0) || !(e1 > e0)) {
    fail(vpProjectiveException::invalidValueError, where, "the thresholds must satisfy 0 <= e0 < e1 (task units)");
  }
  m_e0 = e0;
  m_e1 = e1;
}

void vpServoJointLimitAvoidance::clearJointLimits()
{
  m_enabled = false;
  m_qmin.resize(0);
  m_qmax.resize(0);
}

vpColVector vpServoJointLimitAvoidance::getLowerLimits() const
{
  return toVispVector(m_qmin);
}

vpColVector vpServoJointLimitAvoidance::getUpperLimits() const
{
  return toVispVector(m_qmax);
}

void vpServoJointLimitAvoidance::computeLargeProjectionOperator(const vpServoNormalEquations &ne, double errorNorm,
                                                                const vpServoDampedLeastSquares &law,
                                                                JointMatrix &P) const
{
  // P = sig P_e + (1 - sig) (I - J^+ J), vpServo::computeProjectionOperators() with its thresholds on ||e||.
  const Eigen::Index n = ne.size();
  const JointVector &Jte = ne.getJte();
  double sig = 0.0;
  if (errorNorm > m_e1) {
    sig = 1.0;
  } else if (errorNorm >= m_e0) {
    sig = 1.0 / (1.0 + std::exp(-12.0 * (errorNorm - m_e0) / (m_e1 - m_e0) + 6.0));
  }
  const double pp = Jte.squaredNorm(); // e^T J J^T e
  if (!(pp > 0.0)) {
    sig = 0.0; // J^T e = 0: P_e is undefined (vpServo would divide by zero)
  }
  P.setIdentity(n, n);
  if (sig > 0.0) {
    P.noalias() -= (Jte / pp) * Jte.transpose();
    P *= sig;
  } else {
    P.setZero(n, n);
  }
  if (sig < 1.0) {
    law.addNullSpaceProjector(ne, 1.0 - sig, P);
  }
}

void vpServoJointLimitAvoidance::computeVelocity(const JointVector &q, const JointVector &qdot1,
                                                 const vpServoNormalEquations &ne, double errorNorm,
                                                 const vpServoDampedLeastSquares &law, JointVector &qdot2,
                                                 const JointVector *target) const
{
  // vpServo::secondaryTaskJointLimitAvoidance() with the large projection operator, qdot1 its dq.
  const Eigen::Index n = q.size();
  qdot2.setZero(n);
  if (!m_enabled) {
    return;
  }
  JointMatrix P;
  bool haveP = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double range = m_qmax(i) - m_qmin(i);
    const double l0min = target ? std::min(m_qmin(i) + m_rho * range, (*target)(i)) : m_qmin(i) + m_rho * range;
    const double l0max = target ? std::max(m_qmax(i) - m_rho * range, (*target)(i)) : m_qmax(i) - m_rho * range;
    double g = 0.0;
    if (q(i) < l0min) {
      g = -1.0;
    } else if (q(i) > l0max) {
      g = 1.0;
    }
    if (g == 0.0) {
      continue; // inside the free interval (on its boundary vpServo's b is infinite: no action either)
    }
    if (!haveP) {
      computeLargeProjectionOperator(ne, errorNorm, law, P);
      haveP = true;
    }
    // (P g_i)_i = g P_ii, P_ii >= 0.
    const double Pii = std::abs(P(i, i));
    if (!(Pii > 0.0)) {
      continue;
    }
    const double b = std::abs(qdot1(i)) / Pii;
    if (!(b < 1.0)) {
      continue; // vpServo: a large ratio does not activate the avoidance of this joint
    }
    const double l1min = l0min - m_rho * m_rho1 * range;
    const double l1max = l0max + m_rho * m_rho1 * range;
    double lambdaL = 1.0;
    if (q(i) >= l0max && q(i) <= l1max) {
      lambdaL = 1.0 / (1.0 + std::exp(-12.0 * (q(i) - l0max) / (l1max - l0max) + 6.0));
    } else if (q(i) >= l1min && q(i) <= l0min) {
      lambdaL = 1.0 / (1.0 + std::exp(-12.0 * (q(i) - l0min) / (l1min - l0min) + 6.0));
    }
    qdot2.noalias() -= (lambdaL * (1.0 + m_lambdaTune) * b * g) * P.col(i);
  }
}

double vpServoJointLimitAvoidance::stepInside(const JointVector &q, const JointVector &qdot) const
{
  double t = 1.0;
  for (Eigen::Index i = 0; m_enabled && i < q.size(); ++i) {
    if (q(i) + qdot(i) > m_qmax(i) && q(i) <= m_qmax(i)) {
      t = std::min(t, (m_qmax(i) - q(i)) / qdot(i) * (1.0 - 1e-12)); // rounding: land inside, not on the limit
    } else if (q(i) + qdot(i) < m_qmin(i) && q(i) >= m_qmin(i)) {
      t = std::min(t, (m_qmin(i) - q(i)) / qdot(i) * (1.0 - 1e-12));
    }
  }
  return t;
}

vpMatrix vpServoJointLimitAvoidance::computeLargeProjectionOperator(const vpMatrix &J, const vpColVector &e,
                                                                    const vpServoDampedLeastSquares &law) const
{
  vpServoNormalEquations ne;
  JointMatrix P;
  double errorNorm = 0.0;
  primaryTask(J, e, at("computeLargeProjectionOperator()"), ne, errorNorm);
  computeLargeProjectionOperator(ne, errorNorm, law, P);
  return toVisp(P);
}

vpColVector vpServoJointLimitAvoidance::computeVelocity(const vpColVector &q, const vpColVector &qdot1,
                                                        const vpMatrix &J, const vpColVector &e,
                                                        const vpServoDampedLeastSquares &law) const
{
  const std::string where = at("computeVelocity()");
  vpServoNormalEquations ne;
  double errorNorm = 0.0;
  primaryTask(J, e, where, ne, errorNorm);
  const size_t n = J.getCols();
  if (m_enabled && n != static_cast<size_t>(m_qmin.size())) {
    std::ostringstream os;
    os << "J has " << n << " columns but the joint limits are for " << m_qmin.size() << " joints";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const JointVector qE = toEigenVector<JointVector>(q, n, where, "q");
  const JointVector qdot1E = toEigenVector<JointVector>(qdot1, n, where, "qdot1");
  JointVector qdot2;
  computeVelocity(qE, qdot1E, ne, errorNorm, law, qdot2);
  return toVispVector(qdot2);
}
