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

#include <visp3/projective/vpProjectiveBodyVelocity.h>

#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/projective/vpMetricTwist.h>

#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveNumerics.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpProjectiveBodyVelocity");

vpProjectiveBodyVelocity::vpProjectiveBodyVelocity() : m_Hhat(Eigen::Matrix4d::Zero()) {}

vpProjectiveBodyVelocity::vpProjectiveBodyVelocity(const Eigen::Matrix4d &Hhat) : m_Hhat(Hhat)
{
  if (!Hhat.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, at("vpProjectiveBodyVelocity()"),
         "the velocity has a NaN or infinite entry");
  }
}

vpProjectiveBodyVelocity vpProjectiveBodyVelocity::fromDisplacements(const vpProjectiveDisplacement &H0,
                                                                     const vpProjectiveDisplacement &H1, double dt)
{
  if (!std::isfinite(dt) || !(dt > 0.0)) {
    std::ostringstream os;
    os << "the time step must be positive and finite, got " << dt;
    fail(vpProjectiveException::invalidValueError, at("fromDisplacements()"), os.str());
  }
  return vpProjectiveBodyVelocity(vpProjectiveDisplacement::log(H1 * H0.inverse(), dt));
}

vpProjectiveBodyVelocity vpProjectiveBodyVelocity::fromSequence(const std::vector<vpProjectiveDisplacement> &H,
                                                                const std::vector<double> &t, size_t k,
                                                                size_t halfWindow)
{
  const std::string where = at("fromSequence()");
  if (H.size() != t.size()) {
    std::ostringstream os;
    os << "got " << H.size() << " displacements but " << t.size() << " times; give one time per displacement";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const std::vector<std::pair<size_t, double>> weights = slopeWeights(t, k, halfWindow, where); // checks k too
  const vpProjectiveDisplacement HkInv = H[k].inverse();
  Eigen::Matrix4d slope = Eigen::Matrix4d::Zero();
  for (const std::pair<size_t, double> &w : weights) {
    slope += w.second * vpProjectiveDisplacement::log(H[w.first] * HkInv);
  }
  return vpProjectiveBodyVelocity(slope);
}

vpProjectiveDisplacement vpProjectiveBodyVelocity::integrate(double dt) const
{
  requireFinite(dt, at("integrate()"), "the duration");
  return vpProjectiveDisplacement::exp(Eigen::Matrix4d(dt * m_Hhat));
}

vpColVector vpProjectiveBodyVelocity::pointVelocity(const vpColVector &M) const
{
  return toVispVector(pointVelocity(toEigen<4>(M, at("pointVelocity()"), "the point M")));
}

vpColVector vpProjectiveBodyVelocity::getTwist(const vpMatrix &G) const
{
  const std::string where = at("getTwist()");
  const Eigen::Matrix4d Ge = toEigen<4, 4>(G, where, "G");
  Eigen::FullPivLU<Eigen::Matrix4d> lu(Ge);
  if (!lu.isInvertible()) {
    fail(vpProjectiveException::degenerateConfigurationError, where, "G is singular");
  }
  const Eigen::Matrix4d That = Ge * m_Hhat * lu.inverse();
  return toVispVector(vpMetricTwist::vee(That));
}
