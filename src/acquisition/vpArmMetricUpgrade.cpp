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
  The affine and metric upgrade of an arm's algebraic generators and the metric twists they give: the metric start of
  the bundle adjustment of vpProjectiveArmAcquisition::calibrate() (the paper's section 6).
*/
#include "acquisition/vpArmCalibration.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include "core/vpProjectiveNumerics.h"

namespace vpProjectiveInternal
{
namespace
{
// Symmetric 3x3 matrix from its 6 upper-triangle entries (00, 01, 02, 11, 12, 22).
Eigen::Matrix3d symmetricFromVector(const Eigen::Matrix<double, 6, 1> &x)
{
  Eigen::Matrix3d W;
  W << x(0), x(1), x(2), x(1), x(3), x(4), x(2), x(4), x(5);
  return W;
}

double smallestEigenvalue(const Eigen::Matrix3d &W)
{
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(W, Eigen::EigenvaluesOnly).eigenvalues()(0);
}

/*
  Metric step: the symmetric positive-definite W with A_i W + W A_i^T = 0 for every revolute block A_i (in an affine
  frame A_i = B^-1 [w_i]_x B and W = B^-1 B^-T). Two non-parallel axes fix W up to scale; with fewer constraints
  (parallel axes, one revolute joint) any positive-definite member of the solution space gives a valid frame, found
  by scanning the plane of the two smallest singular vectors.
*/
Eigen::Matrix3d metricConic(const std::vector<Eigen::Matrix3d> &blocks)
{
  if (blocks.empty()) {
    return Eigen::Matrix3d::Identity();
  }
  Eigen::MatrixXd C(6 * blocks.size(), 6);
  for (size_t i = 0; i < blocks.size(); ++i) {
    for (int k = 0; k < 6; ++k) {
      Eigen::Matrix<double, 6, 1> e = Eigen::Matrix<double, 6, 1>::Zero();
      e(k) = 1.0;
      const Eigen::Matrix3d E = symmetricFromVector(e);
      const Eigen::Matrix3d R = blocks[i] * E + E * blocks[i].transpose();
      C.block<6, 1>(6 * static_cast<Eigen::Index>(i), k) << R(0, 0), R(0, 1), R(0, 2), R(1, 1), R(1, 2), R(2, 2);
    }
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(C, Eigen::ComputeFullV);
  const Eigen::Matrix3d W1 = symmetricFromVector(svd.matrixV().col(5));
  if (smallestEigenvalue(W1) > 0.0) {
    return W1;
  }
  if (smallestEigenvalue(-W1) > 0.0) {
    return -W1;
  }
  const Eigen::Matrix3d W2 = symmetricFromVector(svd.matrixV().col(4));
  double best = -1.0;
  Eigen::Matrix3d Wbest = Eigen::Matrix3d::Identity();
  for (int k = 0; k < 360; ++k) {
    const double phi = 2.0 * M_PI * k / 360.0;
    const Eigen::Matrix3d W = std::cos(phi) * W1 + std::sin(phi) * W2;
    const double lambda = smallestEigenvalue(W) / W.norm();
    if (lambda > best) {
      best = lambda;
      Wbest = W;
    }
  }
  return best > 0.0 ? Wbest : Eigen::Matrix3d::Identity();
}
// Euclidean coordinates of a metric homogeneous point, false when it is (nearly) at infinity.
bool euclidean(const Eigen::Vector4d &N, Eigen::Vector3d &X)
{
  if (!(std::abs(N(3)) > 1e-9 * N.norm())) {
    return false;
  }
  X = N.head<3>() / N(3);
  return X.allFinite();
}

// Rotation R and translation t with X1 ~ R X0 + t in the least-squares sense (Kabsch), false if degenerate.
bool rigidMotion(const std::vector<Eigen::Vector3d> &X0, const std::vector<Eigen::Vector3d> &X1, Eigen::Matrix3d &R,
                 Eigen::Vector3d &t)
{
  const size_t K = X0.size();
  if (K < 3) {
    return false;
  }
  Eigen::Vector3d c0 = Eigen::Vector3d::Zero(), c1 = Eigen::Vector3d::Zero();
  for (size_t j = 0; j < K; ++j) {
    c0 += X0[j] / static_cast<double>(K);
    c1 += X1[j] / static_cast<double>(K);
  }
  Eigen::Matrix3d C = Eigen::Matrix3d::Zero();
  for (size_t j = 0; j < K; ++j) {
    C += (X1[j] - c1) * (X0[j] - c0).transpose();
  }
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(C, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  R = svd.matrixU() * D * svd.matrixV().transpose();
  t = c1 - R * c0;
  return R.allFinite() && t.allFinite();
}

/*
  Rigid motion supported by the most point pairs (residual below tolerance, in the units of X), from every triple,
  refitted on its supporters; for pairs where some X1 are mismatched. False if no triple has support beyond itself.
*/
bool consensusRigidMotion(const std::vector<Eigen::Vector3d> &X0, const std::vector<Eigen::Vector3d> &X1,
                          double tolerance, Eigen::Matrix3d &R, Eigen::Vector3d &t)
{
  const size_t K = X0.size();
  size_t bestSupport = 3;
  std::vector<size_t> bestSet;
  for (size_t a = 0; a < K; ++a) {
    for (size_t b = a + 1; b < K; ++b) {
      for (size_t c = b + 1; c < K; ++c) {
        Eigen::Matrix3d Rc;
        Eigen::Vector3d tc;
        if (!rigidMotion({X0[a], X0[b], X0[c]}, {X1[a], X1[b], X1[c]}, Rc, tc)) {
          continue;
        }
        std::vector<size_t> set;
        for (size_t j = 0; j < K; ++j) {
          if ((Rc * X0[j] + tc - X1[j]).norm() < tolerance) {
            set.push_back(j);
          }
        }
        if (set.size() > bestSupport) {
          bestSupport = set.size();
          bestSet = set;
        }
      }
    }
  }
  if (bestSet.empty()) {
    return false;
  }
  std::vector<Eigen::Vector3d> Y0, Y1;
  for (size_t j : bestSet) {
    Y0.push_back(X0[j]);
    Y1.push_back(X1[j]);
  }
  return rigidMotion(Y0, Y1, R, t);
}
} // namespace

bool metricUpgrade(const ArmCalibrationData &data, const std::vector<Eigen::Matrix4d> &Hhat,
                   const std::vector<bool> &use, const std::vector<Eigen::Vector4d> &M0, Eigen::Matrix4d &G)
{
  const size_t n = data.types.size();
  const size_t K = M0.size();

  // 1. Conditioning: whiten the projective frame with the zero-reference points.
  const Eigen::Matrix4d Tn = whitening(M0);
  const Eigen::Matrix4d TnInv = Tn.inverse();

  // 2. Affine step: the plane pi with pi^T Hhat_i = 0 for every joint used is the plane at infinity.
  std::vector<Eigen::Matrix4d> Hw;
  std::vector<vpProjectiveJoint::vpJointType> types;
  for (size_t i = 0; i < n; ++i) {
    if (!use[i]) {
      continue;
    }
    const Eigen::Matrix4d H = Tn * Hhat[i] * TnInv;
    const double norm = H.norm();
    if (!(norm > 0.0) || !H.allFinite()) {
      return false;
    }
    Hw.push_back(H / norm);
    types.push_back(data.types[i]);
  }
  Eigen::Matrix<double, 4, Eigen::Dynamic> stacked(4, 4 * Hw.size());
  for (size_t i = 0; i < Hw.size(); ++i) {
    stacked.block<4, 4>(0, 4 * static_cast<Eigen::Index>(i)) = Hw[i];
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svdPi(stacked, Eigen::ComputeFullU);
  Eigen::Matrix4d A0;
  A0.topRows<3>() = svdPi.matrixU().leftCols<3>().transpose();
  A0.row(3) = svdPi.matrixU().col(3).transpose();

  // 3. Metric step: W = B^-1 B^-T from the revolute blocks, B from Cholesky of W^-1.
  std::vector<Eigen::Matrix3d> blocks;
  for (size_t i = 0; i < Hw.size(); ++i) {
    if (types[i] == vpProjectiveJoint::REVOLUTE) {
      blocks.push_back((A0 * Hw[i] * A0.transpose()).topLeftCorner<3, 3>()); // A0 is orthogonal
    }
  }
  const Eigen::Matrix3d W = metricConic(blocks);
  Eigen::LLT<Eigen::Matrix3d> llt(W.inverse());
  Eigen::Matrix3d B = Eigen::Matrix3d::Identity();
  if (llt.info() == Eigen::Success) {
    B = llt.matrixU();
  }
  G.setIdentity();
  G.topLeftCorner<3, 3>() = B;
  G = G * A0 * Tn;

  // Centre and scale the metric frame on the markers (a similarity, for conditioning only).
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector3d> X(K);
  for (size_t j = 0; j < K; ++j) {
    if (!euclidean(G * M0[j], X[j])) {
      return false;
    }
    centroid += X[j] / static_cast<double>(K);
  }
  double spread = 0.0;
  for (size_t j = 0; j < K; ++j) {
    spread += (X[j] - centroid).squaredNorm() / static_cast<double>(K);
  }
  spread = std::sqrt(spread);
  Eigen::Matrix4d S = Eigen::Matrix4d::Identity();
  S.topLeftCorner<3, 3>() /= spread;
  S.topRightCorner<3, 1>() = -centroid / spread;
  G = S * G;
  return G.allFinite() && std::abs(G.determinant()) > 0.0;
}

bool initialTwists(const ArmCalibrationData &data, const Eigen::Matrix4d &G, const std::vector<Eigen::Matrix4d> &Hhat,
                   const std::vector<Eigen::Vector4d> &M0, const std::vector<std::vector<Eigen::Vector4d>> &trialPoints,
                   std::vector<Eigen::Vector3d> &axis, std::vector<Eigen::Vector3d> &point)
{
  const size_t n = data.types.size();
  const size_t K = M0.size();
  const Eigen::Matrix4d Ginv = G.inverse();
  std::vector<Eigen::Vector3d> X0(K);
  for (size_t j = 0; j < K; ++j) {
    if (!euclidean(G * M0[j], X0[j])) {
      return false;
    }
  }
  axis.assign(n, Eigen::Vector3d::Zero());
  point.assign(n, Eigen::Vector3d::Zero());
  for (size_t i = 0; i < n; ++i) {
    // Candidate (a): read off the metric image G Hhat_i G^-1 of the algebraic generator.
    Eigen::Vector3d axisA, pointA = Eigen::Vector3d::Zero();
    const Eigen::Matrix4d T = G * Hhat[i] * Ginv;
    if (data.types[i] == vpProjectiveJoint::REVOLUTE) {
      const Eigen::Matrix3d S = T.topLeftCorner<3, 3>();
      axisA = Eigen::Vector3d(S(2, 1) - S(1, 2), S(0, 2) - S(2, 0), S(1, 0) - S(0, 1)).normalized();
      pointA = axisA.cross(Eigen::Vector3d(T.topRightCorner<3, 1>())); // v = p x w: w x v is the axis point nearest O
    } else {
      axisA = T.topRightCorner<3, 1>();
    }
    // Candidate (b): the rigid motions of the markers in the metric frame (Kabsch), which do not depend on how well
    // the 15 parameters of a homography are determined by a small marker set far from the joint's axis.
    Eigen::Vector3d wSum = Eigen::Vector3d::Zero(), dSum = Eigen::Vector3d::Zero();
    Eigen::Matrix3d AtA = Eigen::Matrix3d::Zero();
    Eigen::Vector3d Atb = Eigen::Vector3d::Zero();
    std::vector<Eigen::Matrix3d> R;
    std::vector<Eigen::Vector3d> t;
    size_t trials = 0;
    for (size_t k = 0; k < data.trials.size(); ++k) {
      if (data.trials[k].joint != i) {
        continue;
      }
      // A trial whose markers did not agree on one homography (more mismatches than the 5-point consensus can
      // verify) gets the consensus of rigid motions instead: 3 points fix one, and the metric frame (markers spread
      // over a unit RMS radius) makes a tenth of that radius a tolerance far above the noise and below a mismatch;
      // wider ones serve when a rough upgrade distorts the markers' shape more than that.
      const bool verified = std::find(data.inlier[k].begin(), data.inlier[k].end(), true) != data.inlier[k].end();
      std::vector<Eigen::Vector3d> X0k, X1k;
      bool finite = true;
      for (size_t j = 0; j < K && finite; ++j) {
        if (!data.trials[k].seen[j]) {
          continue; // a missing marker
        }
        Eigen::Vector3d X1;
        finite = euclidean(G * trialPoints[k][j], X1);
        if (data.inlier[k][j] || !verified) {
          X0k.push_back(X0[j]);
          X1k.push_back(X1);
        }
      }
      Eigen::Matrix3d Rk;
      Eigen::Vector3d tk;
      bool fitted = finite && verified && rigidMotion(X0k, X1k, Rk, tk);
      for (double tolerance = 0.1; finite && !verified && !fitted && tolerance < 1.0; tolerance *= 2.0) {
        fitted = consensusRigidMotion(X0k, X1k, tolerance, Rk, tk); // wider if the upgrade is still rough
      }
      if (!fitted) {
        continue;
      }
      const double amount = data.trials[k].amount;
      if (data.types[i] == vpProjectiveJoint::REVOLUTE) {
        const Eigen::AngleAxisd aa(Rk);
        wSum += (amount > 0.0 ? aa.angle() : -aa.angle()) * aa.axis(); // rotation by amount about w
        AtA += (Eigen::Matrix3d::Identity() - Rk).transpose() * (Eigen::Matrix3d::Identity() - Rk);
        Atb += (Eigen::Matrix3d::Identity() - Rk).transpose() * tk; // (I - R) p = t for p on the axis
      } else {
        dSum += tk / amount;
      }
      ++trials;
    }
    Eigen::Vector3d axisB = axisA, pointB = pointA;
    if (trials > 0) {
      if (data.types[i] == vpProjectiveJoint::REVOLUTE) {
        axisB = wSum.normalized();
        AtA += axisB * axisB.transpose(); // w^T p = 0: the axis point nearest to the origin
        pointB = AtA.ldlt().solve(Atb);
      } else {
        axisB = dSum / static_cast<double>(trials);
      }
    }
    // Keep the candidate that predicts the joint's own trials best.
    double best = std::numeric_limits<double>::infinity();
    const Eigen::Vector3d axes[2] = {axisA, axisB};
    const Eigen::Vector3d points[2] = {pointA, pointB};
    for (int c = 0; c < 2; ++c) {
      if (!axes[c].allFinite() || !points[c].allFinite() || !(axes[c].norm() > 0.0)) {
        continue;
      }
      double sum = 0.0;
      size_t count = 0;
      accumulateTrialError(data, static_cast<unsigned int>(i),
                           Ginv * vpProjectiveJoint::twist(data.types[i], axes[c], points[c]) * G, M0, sum, count);
      if (sum < best) {
        best = sum;
        axis[i] = axes[c];
        point[i] = points[c];
      }
    }
    if (!(best < std::numeric_limits<double>::infinity())) {
      return false;
    }
  }
  return true;
}
} // namespace vpProjectiveInternal
