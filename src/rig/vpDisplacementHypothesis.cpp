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

#include "rig/vpDisplacementHypothesis.h"

#include <Eigen/Dense>

namespace vpProjectiveInternal
{
MinimalResult minimalHomography(const Eigen::Vector4d *const X[5], const Eigen::Vector4d *const Y[5],
                                Eigen::Matrix4d &Hw)
{
  const double eps = 1e-9; // as checkGeneralPosition(): |det| of 4 unit whitened points
  Eigen::Matrix4d A, B;
  for (int c = 0; c < 4; ++c) {
    A.col(c) = *X[c];
    B.col(c) = *Y[c];
  }
  const double detA = A.determinant(), detB = B.determinant();
  if (!(std::abs(detA) > eps) || !(std::abs(detB) > eps)) {
    return MinimalDegenerate;
  }
  const Eigen::Matrix4d Ainv = A.inverse();
  const Eigen::Vector4d a = Ainv * *X[4];
  const Eigen::Vector4d b = B.inverse() * *Y[4];
  for (int c = 0; c < 4; ++c) {
    if (!(std::abs(a(c) * detA) > eps) || !(std::abs(b(c) * detB) > eps)) {
      return MinimalDegenerate;
    }
  }
  // Hw = B diag(b) (A diag(a))^-1 = B diag(b ./ a) A^-1.
  Hw = B * b.cwiseQuotient(a).asDiagonal() * Ainv;
  if (!Hw.allFinite()) {
    return MinimalDegenerate;
  }
  return Hw.determinant() > 0.0 ? MinimalValid : MinimalReversed;
}
} // namespace vpProjectiveInternal
