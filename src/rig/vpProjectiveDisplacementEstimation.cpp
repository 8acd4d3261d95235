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

/*
  Estimation of a p-displacement from point pairs (linear) and from stereo images (maximum likelihood).
*/

#include <visp3/projective/vpProjectiveDisplacement.h>

#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/projective/vpProjectiveStereoRig.h>

#include "rig/vpDisplacementAdjustment.h"
#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveNumerics.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveDisplacement");

// Rejects point sets that cannot determine a homography of P^3: all coplanar, or 4 coplanar among a minimal 5.
void checkGeneralPosition(const std::vector<Eigen::Vector4d> &M, const std::string &where, const char *which)
{
  const size_t n = M.size();
  Eigen::Matrix<double, 4, Eigen::Dynamic> U(4, n);
  for (size_t j = 0; j < n; ++j) {
    const double norm = M[j].norm();
    if (norm == 0.0) {
      fail(vpProjectiveException::invalidValueError, where,
           std::string("a point of ") + which + " is the zero vector, which is no projective point");
    }
    U.col(static_cast<Eigen::Index>(j)) = M[j] / norm;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(U);
  if (svd.singularValues()(3) < 1e-10 * svd.singularValues()(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         std::string("the points of ") + which + " are coplanar; a 3D homography needs points spanning 3D space");
  }
  if (n == 5) {
    // Whitened first: the points of a small object are nearly parallel 4-vectors in the rig's frame, so an absolute
    // threshold on raw determinants would reject valid sets. Whitening preserves coplanarity.
    const Eigen::Matrix4d T = whitening(M);
    for (size_t skip = 0; skip < 5; ++skip) {
      Eigen::Matrix4d S;
      for (size_t j = 0, c = 0; j < 5; ++j) {
        if (j != skip) {
          S.col(static_cast<Eigen::Index>(c++)) = (T * U.col(static_cast<Eigen::Index>(j))).normalized();
        }
      }
      if (std::abs(S.determinant()) < 1e-9) {
        fail(vpProjectiveException::degenerateConfigurationError, where,
             std::string("4 of the 5 points of ") + which +
                 " are coplanar (or repeated); 5 points determine a 3D homography only if no 4 are coplanar");
      }
    }
  }
}
std::vector<Eigen::Vector4d> toEigenPoints(const std::vector<vpColVector> &M, const std::string &where,
                                           const char *which)
{
  std::vector<Eigen::Vector4d> E(M.size());
  for (size_t j = 0; j < M.size(); ++j) {
    E[j] = toEigen<4>(M[j], where, std::string("a point of ") + which);
  }
  return E;
}
} // namespace

Eigen::Matrix4d vpProjectiveDisplacement::estimateLinear(const std::vector<Eigen::Vector4d> &M0,
                                                         const std::vector<Eigen::Vector4d> &M1)
{
  const std::string where = at("estimate()");
  if (M0.size() != M1.size()) {
    std::ostringstream os;
    os << "got " << M0.size() << " points before the motion but " << M1.size() << " after; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (M0.size() < 5) {
    std::ostringstream os;
    os << "needs at least 5 point pairs to estimate a 3D homography (15 degrees of freedom), got " << M0.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  for (size_t j = 0; j < M0.size(); ++j) {
    if (!M0[j].allFinite() || !M1[j].allFinite()) {
      fail(vpProjectiveException::nonFiniteValueError, where, "a point has a NaN or infinite coordinate");
    }
  }
  checkGeneralPosition(M0, where, "the first set");
  checkGeneralPosition(M1, where, "the second set");

  // DLT on whitened points: Y ~ H' X with X = T0 M0, Y = T1 M1, then H = T1^-1 H' T0.
  const Eigen::Matrix4d T0 = whitening(M0);
  const Eigen::Matrix4d T1 = whitening(M1);
  const size_t n = M0.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * static_cast<Eigen::Index>(n), 16);
  static const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (size_t j = 0; j < n; ++j) {
    const Eigen::Vector4d X = (T0 * M0[j]).normalized();
    const Eigen::Vector4d Y = (T1 * M1[j]).normalized();
    for (int p = 0; p < 6; ++p) {
      const int a = pairs[p][0], b = pairs[p][1];
      const Eigen::Index row = 6 * static_cast<Eigen::Index>(j) + p;
      // Y_a (H X)_b - Y_b (H X)_a = 0
      for (int c = 0; c < 4; ++c) {
        A(row, 4 * b + c) += Y(a) * X(c);
        A(row, 4 * a + c) -= Y(b) * X(c);
      }
    }
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  if (sigma(14) < 1e-9 * sigma(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the point pairs do not determine a unique 3D homography (critical configuration); add points in general "
         "position");
  }
  const Eigen::VectorXd h = svd.matrixV().col(15);
  Eigen::Matrix4d Hw;
  for (int r = 0; r < 4; ++r) {
    Hw.row(r) = h.segment<4>(4 * r).transpose();
  }
  return normalize(T1.inverse() * Hw * T0);
}
vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const std::vector<vpColVector> &M0,
                                                            const std::vector<vpColVector> &M1)
{
  const std::string where = at("estimate()");
  return vpProjectiveDisplacement(
      estimateLinear(toEigenPoints(M0, where, "the first set"), toEigenPoints(M1, where, "the second set")));
}
vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const vpProjectiveStereoRig &rig,
                                                            const std::vector<vpImagePoint> &left0,
                                                            const std::vector<vpImagePoint> &right0,
                                                            const std::vector<vpImagePoint> &left1,
                                                            const std::vector<vpImagePoint> &right1)
{
  const std::string where = at("estimate()");
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where,
         "the stereo rig has no fundamental matrix; estimate it or set it before estimating displacements");
  }
  std::vector<Eigen::Vector4d> s0, s1;
  stackImagePairs(left0, right0, left1, right1, where, s0, s1);
  if (s0.size() < 5) {
    std::ostringstream os;
    os << "needs at least 5 points seen before and after the motion, got " << s0.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  return vpProjectiveDisplacement(estimateFromImages(rig, s0, s1));
}
Eigen::Matrix4d vpProjectiveDisplacement::estimateFromImages(const vpProjectiveStereoRig &rig,
                                                             const std::vector<Eigen::Vector4d> &s0,
                                                             const std::vector<Eigen::Vector4d> &s1, int maxIterations)
{
  // The linear estimate from the triangulated points, then the maximum-likelihood refit of every point; if the
  // refit does not lower the cost (or fails), the linear estimate.
  const DisplacementData data(rig, s0, s1);
  Eigen::Matrix4d H = estimateLinear(data.M0, data.M1);
  std::vector<Eigen::Vector4d> points = data.M0;
  DisplacementAdjustment(data).refine(std::vector<bool>(s0.size(), true), H, points, maxIterations);
  return H;
}
