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

#include <visp3/projective/vpProjectiveTranslation.h>

#include <cmath>

#include <Eigen/Dense>

#include <visp3/projective/vpProjectiveDisplacement.h>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveTranslation");
}

double vpProjectiveTranslation::generatorResidual(const Eigen::Matrix4d &Hhat)
{
  const double n2 = Hhat.squaredNorm();
  if (n2 == 0.0) {
    return 0.0;
  }
  return (Hhat * Hhat).norm() / n2;
}

vpProjectiveTranslation vpProjectiveTranslation::log(const vpProjectiveDisplacement &H, double amount)
{
  const std::string where = at("log()");
  if (!std::isfinite(amount)) {
    fail(vpProjectiveException::nonFiniteValueError, where, "the encoder amount tau is not finite");
  }
  if (amount == 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the encoder amount tau is zero; a prismatic joint must move to reveal its generator, and the length of its "
         "motion must be read by its encoder");
  }
  return fromExactGenerator(project((H.matrix() - Eigen::Matrix4d::Identity()) / amount));
}

Eigen::Matrix4d vpProjectiveTranslation::dexp(double) const
{
  return generator();
}

Eigen::Matrix4d vpProjectiveTranslation::project(const Eigen::Matrix4d &Hhat)
{
  // Closest rank-1 matrix sigma u v^T, then u made orthogonal to v so that Hhat^2 = (v^T u) sigma u v^T = 0.
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(Hhat, Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Vector4d v = svd.matrixV().col(0);
  Eigen::Vector4d u = svd.matrixU().col(0);
  u -= v.dot(u) * v;
  return svd.singularValues()(0) * u * v.transpose();
}
