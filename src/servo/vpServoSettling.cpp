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

#include <visp3/projective/vpServoSettling.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpServoSettling");

// Converged: (chi / n) <= kConvergedRatio * r / (m - n) on kQuietCalls consecutive calls.
const double kConvergedRatio = 3.0;
const unsigned int kQuietCalls = 2;
// Re-engagement: (chi / n) / sigma^2 above the quantile 1 - 1e-4 (normal quantile 3.719) of F(n, nu), nu the degrees
// of freedom of sigma^2.
const double kJumpQuantileZ = 3.719;

/*!
  The quantile of the F distribution F(d1, d2) at the normal quantile \e z, by Paulson's cube-root approximation:
  \f$ z = ((1 - a_2) y - (1 - a_1)) / \sqrt{a_1 + a_2 y^2} \f$, \f$ y = F^{1/3} \f$, \f$ a_i = 2 / (9 d_i) \f$,
  solved for the larger root (within a few percent of the exact quantile from d2 = 6 on).
*/
double fQuantile(double d1, double d2, double z)
{
  const double a1 = 2.0 / (9.0 * d1), a2 = 2.0 / (9.0 * d2), z2 = z * z;
  const double A = (1.0 - a2) * (1.0 - a2) - z2 * a2, B = -2.0 * (1.0 - a2) * (1.0 - a1),
               C = (1.0 - a1) * (1.0 - a1) - z2 * a1;
  const double disc = B * B - 4.0 * A * C;
  if (!(A > 0.0) || !(disc >= 0.0)) {
    return std::numeric_limits<double>::infinity(); // too few degrees of freedom to tell: never a jump
  }
  const double y = (-B + std::sqrt(disc)) / (2.0 * A);
  return y * y * y;
}
} // namespace

vpServoSettling::vpServoSettling() : m_enabled(false), m_horizon(100), m_state(), m_next() {}

void vpServoSettling::setEnabled(bool enabled, unsigned int horizon)
{
  if (horizon == 0) {
    fail(vpProjectiveException::invalidValueError, at("setEnabled()"),
         "the horizon is a number of calls and must be at least 1, e.g. 100");
  }
  m_enabled = enabled;
  m_horizon = horizon;
  m_state = vpState();
  m_next = vpState();
}

void vpServoSettling::reset()
{
  m_next = vpState();
}

double vpServoSettling::getNoiseEstimate() const
{
  return std::sqrt(m_state.noise2);
}

double vpServoSettling::gain(double lambda, const vpServoNormalEquations &ne, double errorSquaredNorm,
                             unsigned int rows, unsigned long context)
{
  m_next = m_state;
  const Eigen::Index n = ne.size();
  if (!m_enabled || static_cast<Eigen::Index>(rows) <= n || n == 0) {
    m_next = vpState();
    return lambda;
  }
  if (m_next.context != context) {
    m_next = vpState(); // another task: converge anew
    m_next.context = context;
  }
  // The Gauss-Newton step g = (J^T J)^-1 J^T e of the normal equations' factorisation, the law's.
  const JointVector &g = ne.getGaussNewtonStep();
  const double chi = ne.getJte().dot(g);
  const double dofResidual = static_cast<double>(rows - n), dof = static_cast<double>(n);
  const double residual = std::max(0.0, errorSquaredNorm - chi) / dofResidual; // per row
  if (!g.allFinite() || !std::isfinite(chi) || !(chi >= 0.0) || !std::isfinite(residual)) {
    m_next = vpState();
    m_next.context = context;
    return lambda;
  }
  vpState &s = m_next;
  const double horizon = static_cast<double>(m_horizon);
  if (s.settled) {
    // Is this frame's explained error noise? F-test against the estimate of the calls before.
    s.statistic = s.noise2 > 0.0 ? (chi / dof) / s.noise2 : 0.0;
    if (s.statistic > fQuantile(dof, dofResidual * s.frames, kJumpQuantileZ)) {
      const double statistic = s.statistic;
      s = vpState(); // not noise: the target moved or the arm was bumped; full gain, and converge anew
      s.context = context;
      s.statistic = statistic;
      return lambda;
    }
  } else {
    s.statistic = residual > 0.0 ? (chi / dof) / residual : std::numeric_limits<double>::infinity();
    if (!(s.statistic <= kConvergedRatio)) {
      s.quiet = 0;
      s.frames = 0.0;
      s.noise2 = 0.0;
      return lambda;
    }
    ++s.quiet; // the quiet calls start the noise estimate
    s.frames = std::min(s.frames + 1.0, horizon);
    s.noise2 += (residual - s.noise2) / s.frames;
    if (s.quiet < kQuietCalls) {
      return lambda;
    }
    s.settled = true;
    s.k = 0;
    return lambda; // k = 0: the gain is lambda
  }
  // Settled: the k-th call's gain lambda / (1 + lambda k), k capped at the horizon; the noise estimate is the running
  // mean of the unexplained part per row over the quiet and settled calls, over the same horizon.
  ++s.k;
  s.k = std::min(s.k, m_horizon);
  s.frames = std::min(s.frames + 1.0, horizon);
  s.noise2 += (residual - s.noise2) / s.frames;
  return lambda / (1.0 + lambda * static_cast<double>(s.k));
}
