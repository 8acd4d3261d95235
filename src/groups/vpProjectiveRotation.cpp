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

#include <visp3/projective/vpProjectiveRotation.h>

#include <cmath>
#include <complex>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/projective/vpProjectiveDisplacement.h>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveRotation");
}

Eigen::Matrix4d vpProjectiveRotation::project(const Eigen::Matrix4d &Hhat)
{
  Eigen::EigenSolver<Eigen::Matrix4d> eig(Hhat);
  const Eigen::Vector4cd lambda = eig.eigenvalues();
  const Eigen::Matrix4cd V = eig.eigenvectors();
  int best = 0;
  for (int k = 1; k < 4; ++k) {
    if (lambda(k).imag() > lambda(best).imag()) {
      best = k;
    }
  }
  int partner = -1;
  double partnerDistance = 0.0;
  for (int k = 0; k < 4; ++k) {
    const double d = std::abs(lambda(k) - std::conj(lambda(best)));
    if (k != best && (partner < 0 || d < partnerDistance)) {
      partner = k;
      partnerDistance = d;
    }
  }
  Eigen::Vector4cd projected = Eigen::Vector4cd::Zero();
  projected(best) = std::complex<double>(0.0, 1.0);
  projected(partner) = std::complex<double>(0.0, -1.0);
  const Eigen::Matrix4cd X = V * projected.asDiagonal() * V.inverse();
  return X.real();
}

double vpProjectiveRotation::generatorResidual(const Eigen::Matrix4d &Hhat)
{
  const double n = Hhat.norm();
  if (n == 0.0) {
    return 0.0;
  }
  return (Hhat * Hhat * Hhat + Hhat).norm() / n;
}

vpProjectiveRotation vpProjectiveRotation::log(const vpProjectiveDisplacement &H, double amount)
{
  const std::string where = at("log()");
  if (!std::isfinite(amount)) {
    fail(vpProjectiveException::nonFiniteValueError, where, "the encoder amount is not finite");
  }
  // With an encoder amount, sin(amount) replaces sin(theta): the trace of a noisy H is a poor angle estimate (it can
  // even exceed 4), while the encoder reading is exact; its sign also fixes the generator's sign.
  const double angle = amount != 0.0 ? amount : H.getRotationAngle();
  const double s = std::sin(angle);
  if (!(std::abs(s) > 1e-6)) {
    std::ostringstream os;
    os << "the rotation angle " << angle
       << " rad is too close to a multiple of pi for the logarithm (25); use a trial motion between a few degrees and "
          "170 deg";
    fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
  }
  const Eigen::Matrix4d &Hn = H.matrix();
  return fromExactGenerator(project((Hn - Hn.inverse()) / (2.0 * s)));
}

Eigen::Matrix4d vpProjectiveRotation::dexp(double theta) const
{
  return generator() * exp(generator(), theta);
}
