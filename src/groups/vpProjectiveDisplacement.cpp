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

#include <visp3/projective/vpProjectiveDisplacement.h>

#include <algorithm>
#include <cmath>
#include <string>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpProjectiveDisplacement"); // const: internal linkage, one per source

vpProjectiveDisplacement::vpProjectiveDisplacement() : m_H(Eigen::Matrix4d::Identity()) {}

vpProjectiveDisplacement::vpProjectiveDisplacement(const vpMatrix &H)
    : m_H(normalize(toEigen<4, 4>(H, at("vpProjectiveDisplacement()"), "H")))
{
}

vpProjectiveDisplacement::vpProjectiveDisplacement(const Eigen::Matrix4d &H) : m_H(normalize(H)) {}

Eigen::Matrix4d vpProjectiveDisplacement::normalize(const Eigen::Matrix4d &H)
{
  const std::string where = at("normalize()");
  if (!H.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, where, "H has a NaN or infinite entry");
  }
  const double scale = H.norm();
  if (scale == 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "H is the zero matrix");
  }
  const Eigen::Matrix4d Hs = H / scale; // avoids overflow of det for large entries
  // Singular when the condition number is beyond working precision. Not a threshold on det(H / |H|): in the rig's
  // pixel-scaled frame a valid H = H_PE^-1 T H_PE has singular values spread over 5 orders of magnitude or more, so
  // that det(H / |H|), the product of three small ratios, may be 1e-15 for a matrix that is far from singular.
  const Eigen::Vector4d sigma = Eigen::JacobiSVD<Eigen::Matrix4d>(Hs).singularValues();
  const double det = Hs.determinant();
  if (!(sigma(3) > 1e-13 * sigma(0)) || det == 0.0) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "H is singular; a projective displacement is an invertible 4x4 homography");
  }
  const double trace = Hs.trace();
  const double gamma = (trace < 0.0 ? -1.0 : 1.0) * std::pow(std::abs(det), 0.25);
  return Hs / gamma;
}

double vpProjectiveDisplacement::getRotationAngle() const
{
  const double c = 0.5 * (m_H.trace() - 2.0);
  return std::acos(std::max(-1.0, std::min(1.0, c)));
}

vpProjectiveDisplacement::vpMotionType vpProjectiveDisplacement::classify(double tolerance) const
{
  const Eigen::Matrix4d D = m_H - Eigen::Matrix4d::Identity();
  if (D.norm() <= tolerance * m_H.norm()) {
    return IDENTITY;
  }
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(D);
  const Eigen::Vector4d sigma = svd.singularValues();
  int rank = 0;
  for (int k = 0; k < 4; ++k) {
    rank += sigma(k) > tolerance * sigma(0) ? 1 : 0;
  }
  if (rank == 1) {
    return TRANSLATION;
  }
  if (rank == 2) {
    return ROTATION;
  }
  return GENERAL;
}

vpProjectiveDisplacement vpProjectiveDisplacement::operator*(const vpProjectiveDisplacement &other) const
{
  return vpProjectiveDisplacement(Eigen::Matrix4d(m_H * other.m_H));
}

vpProjectiveDisplacement vpProjectiveDisplacement::inverse() const
{
  return vpProjectiveDisplacement(Eigen::Matrix4d(m_H.inverse()));
}

Eigen::Matrix4d vpProjectiveDisplacement::log(const vpProjectiveDisplacement &H, double amount)
{
  const std::string where = at("log()");
  if (!std::isfinite(amount)) {
    fail(vpProjectiveException::nonFiniteValueError, where, "the amount is not finite");
  }
  if (amount == 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the amount is zero; give the amount q with H = exp(q Hhat), or 1 for the logarithm itself");
  }
  const Eigen::Matrix4d &Hn = H.m_H;
  const double c = std::max(-1.0, std::min(1.0, 0.5 * (Hn.trace() - 2.0)));
  const double theta = std::acos(c);
  const double s = std::sin(theta);
  if (c < 0.0 && s < 1e-6) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the rotation angle is pi: the logarithm of a half turn is not unique (the axis direction is); compose two "
         "smaller displacements instead");
  }
  // Coefficients of the Hermite interpolant of log at 1, 1, exp(+-i theta); their series below 1e-3 rad, where the
  // closed forms lose digits (theta - sin(theta) and 1 - cos(theta) cancel).
  double b2, b3;
  if (theta < 1e-3) {
    const double t2 = theta * theta;
    b2 = -0.5 + t2 / 4.0 + t2 * t2 / 80.0;
    b3 = 1.0 / 3.0 + t2 / 20.0;
  } else {
    const double oneMinusCos = 2.0 * std::sin(0.5 * theta) * std::sin(0.5 * theta);
    b2 = 1.0 - 0.5 * theta * (1.0 / std::tan(0.5 * theta) + c / s);
    b3 = (s - theta * c) / (2.0 * oneMinusCos * s);
  }
  const Eigen::Matrix4d D = Hn - Eigen::Matrix4d::Identity();
  const Eigen::Matrix4d D2 = D * D;
  return (D + b2 * D2 + b3 * (D2 * D)) / amount;
}

vpMatrix vpProjectiveDisplacement::log() const
{
  return toVisp(log(*this));
}

vpProjectiveDisplacement vpProjectiveDisplacement::exp(const Eigen::Matrix4d &Hhat)
{
  if (!Hhat.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, at("exp()"), "Hhat has a NaN or infinite entry");
  }
  return vpProjectiveDisplacement(exp(Hhat, 1.0), vpNormalized());
}

vpProjectiveDisplacement vpProjectiveDisplacement::exp(const vpMatrix &Hhat)
{
  return exp(toEigen<4, 4>(Hhat, at("exp()"), "Hhat"));
}

vpColVector vpProjectiveDisplacement::act(const vpColVector &M) const
{
  return toVispVector(act(toEigen<4>(M, at("act()"), "the point M")));
}
