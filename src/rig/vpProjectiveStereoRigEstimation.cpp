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
  \file vpProjectiveStereoRigEstimation.cpp
  \brief vpProjectiveStereoRig::estimate(): the robust fundamental matrix (RANSAC, linear 8-point on Hartley-normalised
  pixels) and its gold-standard refinement, then the canonical camera pair.
*/

#include <visp3/projective/vpProjectiveStereoRig.h>

#include <visp3/projective/vpMetricTwist.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>
#include <opencv2/calib3d.hpp>
#include <opencv2/core.hpp>

#include "core/vpProjectiveCeres.h"
#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveNumerics.h"
#include "rig/vpStereoReprojectionError.h"
#include "rig/vpStereoRigGeometry.h"

using namespace vpProjectiveInternal;

double vpProjectiveInternal::epipolarDistance(const Eigen::Matrix3d &F, const Eigen::Vector2d &m,
                                              const Eigen::Vector2d &mp)
{
  const Eigen::Vector3d lp = F * m.homogeneous();
  const Eigen::Vector3d l = F.transpose() * mp.homogeneous();
  const double algebraic = std::abs(mp.homogeneous().dot(lp));
  return std::max(algebraic / lp.head<2>().norm(), algebraic / l.head<2>().norm());
}

namespace
{

Eigen::Vector2d dehomogenize(const Eigen::Vector3d &m)
{
  return m.head<2>() / m(2);
}

// Normalised 8-point estimate on the rows \e inliers of the design matrix A, with rank 2 enforced.
Eigen::Matrix3d linearFundamental(const Eigen::MatrixXd &A, const std::vector<size_t> &inliers)
{
  Eigen::MatrixXd Ain(inliers.size(), 9);
  for (size_t k = 0; k < inliers.size(); ++k) {
    Ain.row(static_cast<Eigen::Index>(k)) = A.row(static_cast<Eigen::Index>(inliers[k]));
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(Ain, Eigen::ComputeFullV);
  Eigen::Matrix3d F;
  for (int a = 0; a < 3; ++a) {
    F.row(a) = svd.matrixV().col(8).segment<3>(3 * a).transpose();
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svdF(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  return svdF.matrixU() * Eigen::Vector3d(svdF.singularValues()(0), svdF.singularValues()(1), 0.0).asDiagonal() *
         svdF.matrixV().transpose();
}

/*
  The matches within \e threshold pixels of their epipolar lines under the pixel F (epipolarDistance()), and the
  truncated quadratic cost sum_i min(d_i^2, t^2) over all matches (MSAC).
*/
double consensus(const Eigen::Matrix3d &F, const std::vector<Eigen::Vector2d> &l, const std::vector<Eigen::Vector2d> &r,
                 double threshold, std::vector<size_t> &inliers)
{
  inliers.clear();
  double cost = 0.0;
  for (size_t i = 0; i < l.size(); ++i) {
    const double d = epipolarDistance(F, l[i], r[i]);
    if (d <= threshold) {
      inliers.push_back(i);
      cost += d * d;
    } else {
      cost += threshold * threshold;
    }
  }
  return std::isfinite(cost) ? cost : std::numeric_limits<double>::infinity();
}

/*
  Gold-standard F of the matches \e index: in Hartley-normalised coordinates (T, Tp), P = [I|0] fixed, P' (scale
  fixed on the unit sphere; the remaining 3-dof gauge P' + e' a^T is left to Levenberg-Marquardt's damping) and the
  points free, from the normalised rank-2 \e Fn0; Ceres minimises the reprojection error of the matches, weighted back
  to pixels. Returns the pixel F, or that of Fn0 if the refinement fails.
*/
Eigen::Matrix3d goldStandardFundamental(const std::vector<Eigen::Vector2d> &l, const std::vector<Eigen::Vector2d> &r,
                                        const Eigen::Matrix3d &T, const Eigen::Matrix3d &Tp,
                                        const std::vector<size_t> &index, const Eigen::Matrix3d &Fn0)
{
  Eigen::JacobiSVD<Eigen::Matrix3d> svdF(Fn0, Eigen::ComputeFullU);
  const Eigen::Vector3d epn = svdF.matrixU().col(2);
  const vpProjectiveStereoRig::Projection Ppn = canonicalRightProjection(Fn0 / Fn0.norm(), epn);
  vpProjectiveStereoRig::Projection Pn = vpProjectiveStereoRig::Projection::Zero();
  Pn.leftCols<3>().setIdentity();

  Eigen::Matrix<double, 3, 4, Eigen::RowMajor> PpRowMajor = Ppn / Ppn.norm();
  std::vector<Eigen::Vector4d> points(index.size());
  ceres::Problem problem;
  for (size_t k = 0; k < index.size(); ++k) {
    const size_t i = index[k];
    const Eigen::Vector2d mn = dehomogenize(T * l[i].homogeneous());
    const Eigen::Vector2d mpn = dehomogenize(Tp * r[i].homogeneous());
    points[k] = linearTriangulation(Pn, Ppn, mn, mpn);
    auto *cost = new ceres::AutoDiffCostFunction<StereoReprojectionError, 4, 12, 4>(
        new StereoReprojectionError(mn, mpn, T(0, 0), Tp(0, 0)));
    problem.AddResidualBlock(cost, nullptr, PpRowMajor.data(), points[k].data());
    problem.SetManifold(points[k].data(), new ceres::SphereManifold<4>());
  }
  problem.SetManifold(PpRowMajor.data(), new ceres::SphereManifold<12>());
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_SCHUR, 100);

  const vpProjectiveStereoRig::Projection PpRefined = PpRowMajor;
  const Eigen::Vector3d epRefined = PpRefined.col(3);
  const Eigen::Matrix3d Fn = vpMetricTwist::skew(epRefined) * PpRefined.leftCols<3>();
  const Eigen::Matrix3d F = Tp.transpose() * Fn * T;
  if (!F.allFinite() || F.norm() == 0.0 || summary.final_cost > summary.initial_cost) {
    return Tp.transpose() * Fn0 * T; // the refinement failed: keep the start
  }
  return F;
}
} // namespace

void vpProjectiveStereoRig::estimate(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                     double inlierThreshold)
{
  const std::string where = stereoRigAt("estimate()");
  if (left.size() != right.size()) {
    std::ostringstream os;
    os << "got " << left.size() << " left points but " << right.size() << " right points; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (left.size() < 8) {
    std::ostringstream os;
    os << "needs at least 8 matches to estimate the fundamental matrix, got " << left.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  positive(inlierThreshold, where, "the inlier threshold", "pixels");
  const size_t n = left.size();
  std::vector<Eigen::Vector2d> l(n), r(n);
  std::vector<cv::Point2d> cvl(n), cvr(n);
  for (size_t i = 0; i < n; ++i) {
    l[i] = toEigen(left[i], where, "a left image point");
    r[i] = toEigen(right[i], where, "a right image point");
    cvl[i] = cv::Point2d(l[i](0), l[i](1));
    cvr[i] = cv::Point2d(r[i](0), r[i](1));
  }

  // Degeneracy: the normalised 8-point system must have a one-dimensional null space.
  const Eigen::Matrix3d T = hartleyNormalization(l);
  const Eigen::Matrix3d Tp = hartleyNormalization(r);
  Eigen::MatrixXd A(n, 9);
  for (size_t i = 0; i < n; ++i) {
    const Eigen::Vector3d m = T * l[i].homogeneous();
    const Eigen::Vector3d mp = Tp * r[i].homogeneous();
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        A(static_cast<Eigen::Index>(i), 3 * a + b) = mp(a) * m(b);
      }
    }
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svdA(A);
  const Eigen::VectorXd sA = svdA.singularValues();
  if (sA(7) < 1e-8 * sA(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the matches do not determine the epipolar geometry (points collinear, coincident, or all on one plane "
         "seen without parallax); use matches spread over a 3D scene");
  }

  // Robust selection of the inliers: OpenCV's RANSAC needs 15 matches (it silently switches to LMedS below that),
  // so fewer matches are all kept and screened by the consensus loop below (which is then not robust: see the
  // header).
  const Eigen::Matrix3d Tinv = T.inverse(), Tpinv = Tp.inverse();
  std::vector<size_t> inliers;
  Eigen::Matrix3d Fn0 = Eigen::Matrix3d::Zero();
  double cost = std::numeric_limits<double>::infinity();
  if (n >= 15) {
    std::vector<uchar> mask;
    // RANSAC draws from OpenCV's global generator: reseed it so that the same matches give the same estimate,
    // whatever was computed before in the process.
    cv::theRNG() = cv::RNG(0x5eedULL);
    cv::Mat Fcv = cv::findFundamentalMat(cvl, cvr, cv::FM_RANSAC, inlierThreshold, 0.999, mask);
    if (Fcv.empty() || Fcv.rows != 3 || Fcv.cols != 3 || mask.size() != n) {
      fail(vpProjectiveException::estimationFailedError, where,
           "OpenCV's robust estimator found no fundamental matrix; check that the matches are correct");
    }
    Eigen::Matrix3d Fransac;
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        Fransac(a, b) = Fcv.at<double>(a, b);
      }
    }
    if (Fransac.allFinite() && Fransac.norm() > 0.0) {
      Fn0 = Tpinv.transpose() * Fransac * Tinv;
      Fn0 /= Fn0.norm();
      cost = consensus(Tp.transpose() * Fn0 * T, l, r, inlierThreshold, inliers);
    }
    std::vector<size_t> masked;
    for (size_t i = 0; i < n; ++i) {
      if (mask[i]) {
        masked.push_back(i);
      }
    }
    if (masked.size() >= 8) {
      std::vector<size_t> set;
      const Eigen::Matrix3d Fn = linearFundamental(A, masked);
      const double c = consensus(Tp.transpose() * Fn * T, l, r, inlierThreshold, set);
      if (c < cost) {
        Fn0 = Fn;
        cost = c;
        inliers = set;
      }
    }
  } else {
    std::vector<size_t> all(n);
    for (size_t i = 0; i < n; ++i) {
      all[i] = i;
    }
    Fn0 = linearFundamental(A, all);
    inliers = all;
  }

  // Consensus loop: refit linearly on all inliers (RANSAC's F comes from a minimal sample), reclassify every match by
  // its distance to the epipolar lines of that fit, and keep the refit while it lowers the truncated quadratic cost
  // sum_i min(d_i^2, t^2) over all matches (MSAC): a refit on a poor set, which would lose matches, is refused.
  for (int round = 0; round < 10 && n >= 15 && inliers.size() >= 8; ++round) {
    std::vector<size_t> set;
    const Eigen::Matrix3d Fn = linearFundamental(A, inliers);
    const double c = consensus(Tp.transpose() * Fn * T, l, r, inlierThreshold, set);
    if (!(c < cost)) {
      break;
    }
    Fn0 = Fn;
    cost = c;
    const bool stable = set == inliers;
    inliers = set;
    if (stable) {
      break;
    }
  }
  if (inliers.size() < 8) {
    std::ostringstream os;
    os << "only " << inliers.size() << " of " << n
       << " matches agree with one epipolar geometry (8 needed); check the matches or raise the inlier threshold";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }

  // Gold-standard refinement on the inliers, repeated on the inliers of the refined geometry until they are the
  // matches it was fitted to.
  Eigen::Matrix3d F = goldStandardFundamental(l, r, T, Tp, inliers, Fn0);
  for (int round = 0; round < 4; ++round) {
    std::vector<size_t> set;
    consensus(F, l, r, inlierThreshold, set);
    if (set == inliers) {
      break;
    }
    if (set.size() < 8) {
      std::ostringstream os;
      os << "only " << set.size() << " of " << n << " matches agree with one epipolar geometry (8 needed); check "
         << "the matches or raise the inlier threshold";
      fail(vpProjectiveException::estimationFailedError, where, os.str());
    }
    inliers = set;
    Eigen::Matrix3d Fn = Tpinv.transpose() * F * Tinv;
    F = goldStandardFundamental(l, r, T, Tp, inliers, Fn / Fn.norm());
  }
  setFundamentalMatrix(toVisp(F));

  // Inliers of the refined geometry, and their residual in pixels.
  inliers.clear();
  for (size_t i = 0; i < n; ++i) {
    if (epipolarDistance(m_F, l[i], r[i]) <= inlierThreshold) {
      inliers.push_back(i);
    }
  }
  double sum = 0.0;
  m_inliers.assign(n, false);
  for (size_t i : inliers) {
    m_inliers[i] = true;
    const Eigen::Vector4d M = triangulate(l[i], r[i]);
    Eigen::Vector4d s;
    if (project(M, s)) {
      sum += (s.head<2>() - l[i]).squaredNorm() + (s.tail<2>() - r[i]).squaredNorm();
    }
  }
  m_residual = inliers.empty() ? 0.0 : std::sqrt(sum / (2.0 * static_cast<double>(inliers.size())));
}
