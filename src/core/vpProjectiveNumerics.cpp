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

#include "core/vpProjectiveNumerics.h"
#include "core/vpProjectiveErrors.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>
#include <Eigen/QR>

namespace vpProjectiveInternal
{
Eigen::Matrix4d whitening(const std::vector<Eigen::Vector4d> &points)
{
  Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
  for (const Eigen::Vector4d &M : points) {
    const Eigen::Vector4d u = M.normalized();
    C += u * u.transpose();
  }
  C /= static_cast<double>(points.size());
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(C);
  // Eigenvalues of degenerate sets are floored so that T stays invertible; the caller detects degeneracy itself.
  const Eigen::Vector4d lambda = eig.eigenvalues().cwiseMax(1e-12 * eig.eigenvalues().maxCoeff());
  return eig.eigenvectors() * lambda.cwiseSqrt().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();
}

std::vector<std::pair<size_t, double>> slopeWeights(const std::vector<double> &t, size_t k, size_t halfWindow,
                                                    const std::string &where)
{
  if (k >= t.size()) {
    std::ostringstream os;
    os << "sample " << k << " is out of range; the sequence has " << t.size() << " samples";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (halfWindow == 0) {
    fail(vpProjectiveException::invalidValueError, where, "the half window must be at least 1 sample");
  }
  const size_t first = k >= halfWindow ? k - halfWindow : 0;
  const size_t last = std::min(t.size() - 1, k + halfWindow);
  if (last == first) {
    fail(vpProjectiveException::invalidValueError, where, "a velocity needs at least two samples");
  }
  // Normal equations of x_j - x_k = a d_j + b d_j^2, d_j = t_j - t_k (a line through x_k when the window has one
  // other sample): a = sum_j w_j (x_j - x_k).
  double s2 = 0.0, s3 = 0.0, s4 = 0.0;
  for (size_t j = first; j <= last; ++j) {
    if (!std::isfinite(t[j]) || (j > first && !(t[j] > t[j - 1]))) {
      fail(vpProjectiveException::invalidValueError, where, "the times must be finite and strictly increasing");
    }
    const double d = t[j] - t[k];
    s2 += d * d;
    s3 += d * d * d;
    s4 += d * d * d * d;
  }
  const bool quadratic = last - first >= 2;
  const double det = s2 * s4 - s3 * s3;
  std::vector<std::pair<size_t, double>> weights;
  for (size_t j = first; j <= last; ++j) {
    if (j != k) {
      const double d = t[j] - t[k];
      weights.emplace_back(j, quadratic ? (s4 * d - s3 * d * d) / det : d / s2);
    }
  }
  return weights;
}

Eigen::Matrix<double, 4, 3> sphereTangentBasis(const Eigen::Vector4d &M)
{
  Eigen::HouseholderQR<Eigen::Vector4d> qr(M);
  const Eigen::Matrix4d Q = qr.householderQ();
  return Q.rightCols<3>();
}
} // namespace vpProjectiveInternal
