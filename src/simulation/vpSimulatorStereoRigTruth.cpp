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

/*!
  \file vpSimulatorStereoRigTruth.cpp
  \brief The simulator's ground truth for a projective rig: H_PE, the projective-to-Euclidean collineation, fitted on
  points sampled in the cameras' common view.
*/

#include <visp3/projective/vpSimulatorStereoRig.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpImageWindow.h"
#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

vpMatrix vpSimulatorStereoRig::getProjectiveToEuclidean(const vpProjectiveStereoRig &rig) const
{
  double residual = 0.0;
  return getProjectiveToEuclidean(rig, residual);
}

double vpSimulatorStereoRig::getMaxProjectiveToEuclideanResidual() const
{
  return 0.02 * std::hypot(static_cast<double>(m_width), static_cast<double>(m_height));
}

std::vector<Eigen::Vector4d> vpSimulatorStereoRig::samplePoints() const
{
  // Depth (left camera) where the optical axes come closest: the vergence distance of a verging rig.
  const Eigen::Matrix4d rMl = toEigenUnchecked<4, 4>(m_rMl);
  const Eigen::Matrix3d R = rMl.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = rMl.topRightCorner<3, 1>();
  const double baseline = t.norm();
  const Eigen::Vector3d zl(0.0, 0.0, 1.0);
  const Eigen::Vector3d cr = -R.transpose() * t; // right centre, left coordinates
  const Eigen::Vector3d zr = R.transpose() * zl; // right optical axis, left coordinates
  const double b = zl.dot(zr);
  const double denom = 1.0 - b * b;
  double d0 = 10.0 * baseline;
  if (denom > 1e-8) {
    const double depth = (zl.dot(cr) - b * zr.dot(cr)) / denom;
    if (depth > baseline && depth < 100.0 * baseline) {
      d0 = depth;
    }
  }
  const Eigen::Matrix3d Kinv = toEigenUnchecked<3, 3>(m_camLeft.get_K()).inverse();
  const Eigen::Matrix3d Kp = toEigenUnchecked<3, 3>(m_camRight.get_K());
  const double depths[5] = {0.6, 0.8, 1.0, 1.25, 1.6};
  std::vector<Eigen::Vector4d> inView, inFront;
  for (int i = 0; i < 7; ++i) {
    for (int j = 0; j < 7; ++j) {
      const Eigen::Vector3d m(m_width * (0.1 + 0.8 * i / 6.0), m_height * (0.1 + 0.8 * j / 6.0), 1.0);
      for (int k = 0; k < 5; ++k) {
        const Eigen::Vector3d lX = depths[k] * d0 * (Kinv * m);
        const Eigen::Vector3d rX = R * lX + t;
        if (rX(2) <= 0.05 * d0) {
          continue;
        }
        const Eigen::Vector3d mp = Kp * rX / rX(2);
        const Eigen::Vector4d N(lX(0), lX(1), lX(2), 1.0);
        inFront.push_back(N);
        if (vpImageWindow(m_width, m_height, 0.0).contains(mp(0), mp(1))) {
          inView.push_back(N);
        }
      }
    }
  }
  return (inView.size() >= 20) ? inView : inFront;
}

vpMatrix vpSimulatorStereoRig::getProjectiveToEuclidean(const vpProjectiveStereoRig &rig, double &residual) const
{
  const char *where = "vpSimulatorStereoRig::getProjectiveToEuclidean()";
  if (!rig.isInitialized()) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                std::string(where) + ": the projective rig has no fundamental matrix yet; call its "
                                                     "estimate() or setFundamentalMatrix() first");
  }
  const vpProjectiveStereoRig::Projection P = toEigenUnchecked<3, 4>(rig.getLeftProjection());
  const vpProjectiveStereoRig::Projection Pp = toEigenUnchecked<3, 4>(rig.getRightProjection());
  if (!P.allFinite() || !Pp.allFinite()) {
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                std::string(where) + ": the projective rig's camera matrices contain NaN or infinity");
  }

  // G = H^-1 maps metric points N (homogeneous left-camera coordinates) to projective ones M. The left cameras are
  // matched exactly, P G = K[I|0]: G = P^+ K[I|0] + n g^T with n the centre of P (P n = 0) and g a free 4-vector.
  // The right camera then images N at pi(B N + e' (g^T N)), B = P' P^+ K[I|0], e' = P' n, which must be the metric
  // image pi(K'[R'|t'] N): two equations per point, linear in g. They are solved over sample points N filling the
  // rig's common field of view, weighted so that the residual is in pixels (a few reweighting passes). With this
  // rig's F the solution is exact; with an estimated F it is the H_PE that best reproduces the right image.
  const Eigen::Matrix<double, 4, 3> Pplus = P.transpose() * (P * P.transpose()).inverse();
  // Null vector of P by cofactors: n_i = (-1)^i det(P without column i).
  Eigen::Vector4d n;
  for (int i = 0; i < 4; ++i) {
    Eigen::Matrix3d Pi;
    for (int c = 0, cc = 0; c < 4; ++c) {
      if (c != i) {
        Pi.col(cc++) = P.col(c);
      }
    }
    n(i) = ((i % 2 == 0) ? 1.0 : -1.0) * Pi.determinant();
  }
  if (!(n.norm() > 0.0)) {
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError,
                                std::string(where) + ": the projective rig's left camera matrix is not of rank 3");
  }
  n.normalize();
  const vpProjectiveStereoRig::Projection Pm = toEigenUnchecked<3, 4>(getLeftMetricProjection());
  const vpProjectiveStereoRig::Projection Pmp = toEigenUnchecked<3, 4>(getRightMetricProjection());
  const vpProjectiveStereoRig::Projection B = Pp * Pplus * Pm;
  const Eigen::Vector3d e = Pp * n;

  const std::vector<Eigen::Vector4d> samples = samplePoints();
  std::vector<Eigen::Vector2d> target(samples.size());
  for (size_t k = 0; k < samples.size(); ++k) {
    const Eigen::Vector3d mp = Pmp * samples[k];
    target[k] = mp.head<2>() / mp(2);
  }
  Eigen::Vector4d g = Eigen::Vector4d::Zero();
  std::vector<double> weight(samples.size(), 1.0);
  for (int pass = 0; pass < 4; ++pass) {
    // Columns scaled to unit norm before the normal equations: the system is small (4 unknowns) and well posed.
    Eigen::Matrix4d AtA = Eigen::Matrix4d::Zero();
    Eigen::Vector4d Atb = Eigen::Vector4d::Zero();
    std::vector<Eigen::RowVector4d> rows;
    std::vector<double> rhs;
    rows.reserve(2 * samples.size());
    rhs.reserve(2 * samples.size());
    for (size_t k = 0; k < samples.size(); ++k) {
      const Eigen::Vector3d BN = B * samples[k];
      for (int c = 0; c < 2; ++c) {
        rows.push_back(weight[k] * (e(c) - target[k](c) * e(2)) * samples[k].transpose());
        rhs.push_back(-weight[k] * (BN(c) - target[k](c) * BN(2)));
      }
    }
    Eigen::Vector4d colNorm = Eigen::Vector4d::Zero();
    for (size_t r = 0; r < rows.size(); ++r) {
      colNorm += rows[r].transpose().cwiseAbs2();
    }
    colNorm = colNorm.cwiseSqrt();
    for (int c = 0; c < 4; ++c) {
      if (!(colNorm(c) > 0.0)) {
        colNorm(c) = 1.0;
      }
    }
    for (size_t r = 0; r < rows.size(); ++r) {
      const Eigen::Vector4d a = rows[r].transpose().cwiseQuotient(colNorm);
      AtA += a * a.transpose();
      Atb += a * rhs[r];
    }
    g = (AtA.inverse() * Atb).cwiseQuotient(colNorm);
    for (size_t k = 0; k < samples.size(); ++k) {
      const double x3 = (B * samples[k])(2) + e(2) * g.dot(samples[k]);
      weight[k] = (std::fabs(x3) > 0.0) ? 1.0 / std::fabs(x3) : 1.0;
    }
  }

  // Residual: RMS distance in pixels between the right images of the sample points through the projective frame and
  // through the metric camera (the left images agree exactly).
  double sum2 = 0.0;
  for (size_t k = 0; k < samples.size(); ++k) {
    const Eigen::Vector3d x = B * samples[k] + e * g.dot(samples[k]);
    sum2 += (x.head<2>() / x(2) - target[k]).squaredNorm();
  }
  residual = samples.empty() ? std::numeric_limits<double>::infinity() : std::sqrt(sum2 / samples.size());

  const Eigen::Matrix4d G = Pplus * Pm + n * g.transpose();
  const double detG = G.determinant();
  if (!(residual <= getMaxProjectiveToEuclideanResidual()) || !std::isfinite(detG) || detG == 0.0) {
    const Eigen::Matrix3d Fs = toEigenUnchecked<3, 3>(getFundamentalMatrix());
    Eigen::Matrix3d Fr = toEigenUnchecked<3, 3>(rig.getFundamentalMatrix());
    Fr /= Fr.norm();
    const double dF = std::min((Fs - Fr).norm(), (Fs + Fr).norm());
    std::ostringstream os;
    os << where << ": the projective rig's frame is not one of this simulated rig: the best homography maps its right "
       << "camera onto the metric one with an RMS error of " << residual << " px > "
       << getMaxProjectiveToEuclideanResidual() << " px (distance between the unit-norm fundamental matrices " << dF
       << "). Give the rig this simulator's getFundamentalMatrix() or one estimated from its images";
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
  // P H^-1 = K[I|0] exactly: s = 1 > 0, so that K[I|0] H M and P M have the same sign. Scale: |det H| = 1.
  Eigen::Matrix4d H = G.inverse();
  H /= std::pow(std::fabs(H.determinant()), 0.25);
  return toVisp(H);
}
