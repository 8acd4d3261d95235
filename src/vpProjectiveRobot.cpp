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

#include <visp3/projective/vpProjectiveRobot.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <limits>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveTranslation.h>

#include "vpProjectiveCeres.h"
#include "vpProjectiveInternal.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;

namespace
{
const char *const kClass = "vpProjectiveRobot";

std::string at(const char *method)
{
  return std::string(kClass) + "::" + method;
}

// Metric twist matrix (4x4 se(3), eq. (9)) of a revolute joint (unit axis w through p) or a prismatic one (d).
Eigen::Matrix4d twistMatrix(vpProjectiveRobot::vpJointType type, const Eigen::Vector3d &axis,
                            const Eigen::Vector3d &point)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Zero();
  if (type == vpProjectiveRobot::REVOLUTE) {
    T.topLeftCorner<3, 3>() = skew(axis);
    T.topRightCorner<3, 1>() = point.cross(axis);
  } else {
    T.topRightCorner<3, 1>() = axis;
  }
  return T;
}

// Rigid motion exp(q That) applied to a homogeneous metric point N: rotation about the axis (w, p) or translation.
template <typename T> void moveRevolute(const T *w, const T *p, double q, const T *N, T *out)
{
  const T c = T(std::cos(q)), s = T(std::sin(q));
  // X - p rotated by Rodrigues about the unit axis w, written for homogeneous N = (X, n4): X' = R (X - n4 p) + n4 p.
  T x[3] = {N[0] - N[3] * p[0], N[1] - N[3] * p[1], N[2] - N[3] * p[2]};
  const T wnorm = ceres::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
  const T u[3] = {w[0] / wnorm, w[1] / wnorm, w[2] / wnorm};
  const T dot = u[0] * x[0] + u[1] * x[1] + u[2] * x[2];
  const T cr[3] = {u[1] * x[2] - u[2] * x[1], u[2] * x[0] - u[0] * x[2], u[0] * x[1] - u[1] * x[0]};
  for (int k = 0; k < 3; ++k) {
    out[k] = c * x[k] + s * cr[k] + (T(1.0) - c) * dot * u[k] + N[3] * p[k];
  }
  out[3] = N[3];
}

template <typename T> void projectPixels(const Eigen::Matrix<double, 3, 4> &P, const T *M, T *uv)
{
  T m[3];
  for (int r = 0; r < 3; ++r) {
    m[r] = T(P(r, 0)) * M[0] + T(P(r, 1)) * M[1] + T(P(r, 2)) * M[2] + T(P(r, 3)) * M[3];
  }
  uv[0] = m[0] / m[2];
  uv[1] = m[1] / m[2];
}

// Pixel error of marker N (metric, homogeneous) after a motion, seen through G^-1 (row-major 4x4) by the rig.
struct MarkerObservation {
  MarkerObservation(const vpProjectiveStereoRig &rig, const Eigen::Vector4d &s)
      : P(rig.leftProjection()), Pp(rig.rightProjection()), s(s)
  {
  }
  template <typename T> void residual(const T *Ginv, const T *N, T *r) const
  {
    T M[4];
    for (int i = 0; i < 4; ++i) {
      M[i] = Ginv[4 * i] * N[0] + Ginv[4 * i + 1] * N[1] + Ginv[4 * i + 2] * N[2] + Ginv[4 * i + 3] * N[3];
    }
    T uv[2];
    projectPixels(P, M, uv);
    r[0] = uv[0] - T(s(0));
    r[1] = uv[1] - T(s(1));
    projectPixels(Pp, M, uv);
    r[2] = uv[0] - T(s(2));
    r[3] = uv[1] - T(s(3));
  }
  Eigen::Matrix<double, 3, 4> P, Pp;
  Eigen::Vector4d s;
};

struct ZeroReferenceError : MarkerObservation {
  using MarkerObservation::MarkerObservation;
  template <typename T> bool operator()(const T *Ginv, const T *N, T *r) const
  {
    residual(Ginv, N, r);
    return true;
  }
};

struct RevoluteTrialError : MarkerObservation {
  RevoluteTrialError(const vpProjectiveStereoRig &rig, const Eigen::Vector4d &s, double q)
      : MarkerObservation(rig, s), q(q)
  {
  }
  template <typename T> bool operator()(const T *Ginv, const T *N, const T *w, const T *p, T *r) const
  {
    T moved[4];
    moveRevolute(w, p, q, N, moved);
    residual(Ginv, moved, r);
    return true;
  }
  double q;
};

struct PrismaticTrialError : MarkerObservation {
  PrismaticTrialError(const vpProjectiveStereoRig &rig, const Eigen::Vector4d &s, double q)
      : MarkerObservation(rig, s), q(q)
  {
  }
  template <typename T> bool operator()(const T *Ginv, const T *N, const T *d, T *r) const
  {
    const T moved[4] = {N[0] + T(q) * N[3] * d[0], N[1] + T(q) * N[3] * d[1], N[2] + T(q) * N[3] * d[2], N[3]};
    residual(Ginv, moved, r);
    return true;
  }
  double q;
};

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
} // namespace

vpProjectiveRobot::vpProjectiveRobot()
    : m_types(), m_mounting(EYE_TO_HAND), m_rig(), m_zeroImages(), m_trials(), m_G(Eigen::Matrix4d::Identity()),
      m_Ginv(Eigen::Matrix4d::Identity()), m_axis(), m_point(), m_Hhat(), m_M0(), m_residual(0.0),
      m_algebraicResidual(0.0), m_outlierThreshold(0.0), m_inlier(), m_calibrated(false)
{
}

vpProjectiveRobot::vpProjectiveRobot(const std::vector<vpJointType> &joints) : vpProjectiveRobot()
{
  if (joints.empty() || joints.size() > maxJoints) {
    std::ostringstream os;
    os << "a chain needs between 1 and " << maxJoints << " joints, got " << joints.size();
    fail(vpProjectiveException::dimensionError, at("vpProjectiveRobot()"), os.str());
  }
  for (vpJointType t : joints) {
    if (t != REVOLUTE && t != PRISMATIC) {
      fail(vpProjectiveException::invalidValueError, at("vpProjectiveRobot()"),
           "a joint type is neither REVOLUTE nor PRISMATIC");
    }
  }
  m_types = joints;
}

vpProjectiveRobot::vpJointType vpProjectiveRobot::getJointType(unsigned int i) const
{
  if (i >= m_types.size()) {
    std::ostringstream os;
    os << "joint index " << i << " is out of range; the chain has " << m_types.size() << " joints";
    fail(vpProjectiveException::dimensionError, at("getJointType()"), os.str());
  }
  return m_types[i];
}

void vpProjectiveRobot::setStereoRig(const vpProjectiveStereoRig &rig)
{
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, at("setStereoRig()"),
         "the rig has no fundamental matrix; estimate or set it first");
  }
  m_rig = rig;
  m_zeroImages.clear();
  m_trials.clear();
  m_calibrated = false;
}

namespace
{
std::vector<Eigen::Vector4d> stackImages(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                         const std::string &where)
{
  if (left.size() != right.size()) {
    std::ostringstream os;
    os << "got " << left.size() << " left and " << right.size() << " right marker images; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  std::vector<Eigen::Vector4d> s(left.size());
  for (size_t j = 0; j < left.size(); ++j) {
    s[j] << toEigen(left[j], where, "a left marker image"), toEigen(right[j], where, "a right marker image");
  }
  return s;
}
} // namespace

void vpProjectiveRobot::setZeroReference(const std::vector<vpImagePoint> &left0,
                                         const std::vector<vpImagePoint> &right0)
{
  const std::string where = at("setZeroReference()");
  if (!m_rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where, "call setStereoRig() with a weakly calibrated rig first");
  }
  std::vector<Eigen::Vector4d> s = stackImages(left0, right0, where);
  if (s.size() < 5) {
    std::ostringstream os;
    os << "needs the images of at least 5 markers (no 4 coplanar) on the last link, got " << s.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  m_zeroImages = s;
  m_trials.clear();
  m_calibrated = false;
}

void vpProjectiveRobot::addTrialMotion(unsigned int i, double amount, const std::vector<vpImagePoint> &left,
                                       const std::vector<vpImagePoint> &right)
{
  const std::string where = at("addTrialMotion()");
  getJointType(i);
  requireFinite(amount, where, "the trial amount");
  if (amount == 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the trial amount is zero; move the joint (e.g. 20 to 60 deg) so that its motion can be observed");
  }
  if (m_types[i] == REVOLUTE && std::abs(std::remainder(amount, 2.0 * M_PI)) < 1e-3) {
    fail(vpProjectiveException::invalidValueError, where,
         "a revolute trial by a multiple of 2 pi leaves the markers where they were; use another amount");
  }
  if (m_zeroImages.empty()) {
    fail(vpProjectiveException::notInitializedError, where, "call setZeroReference() before adding trial motions");
  }
  vpTrial trial;
  trial.joint = i;
  trial.amount = amount;
  trial.s = stackImages(left, right, where);
  if (trial.s.size() != m_zeroImages.size()) {
    std::ostringstream os;
    os << "the trial shows " << trial.s.size() << " markers but the zero reference " << m_zeroImages.size()
       << "; pass the same markers in the same order";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  m_trials.push_back(trial);
  m_calibrated = false;
}

std::vector<Eigen::Vector4d> vpProjectiveRobot::triangulateZeroReference() const
{
  std::vector<Eigen::Vector4d> M0(m_zeroImages.size());
  for (size_t j = 0; j < M0.size(); ++j) {
    M0[j] = m_rig.triangulate(Eigen::Vector2d(m_zeroImages[j].head<2>()), Eigen::Vector2d(m_zeroImages[j].tail<2>()));
  }
  return M0;
}

void vpProjectiveRobot::algebraicGenerators(const std::vector<Eigen::Vector4d> &M0, std::vector<Eigen::Matrix4d> &Hhat)
{
  const std::string where = at("calibrate()");
  const size_t n = m_types.size();
  // Candidate generators of each joint: the logarithm of each of its trials, and their projected mean.
  std::vector<std::vector<Eigen::Matrix4d>> candidates(n);
  std::vector<unsigned int> trialCount(n, 0);
  for (size_t k = 0; k < m_trials.size(); ++k) {
    const vpTrial &trial = m_trials[k];
    // A blocked joint or a tiny trial leaves the markers where they were: H = I has no logarithm to speak of.
    double motion = 0.0;
    for (size_t j = 0; j < trial.s.size(); ++j) {
      motion += (trial.s[j] - m_zeroImages[j]).squaredNorm();
    }
    motion = std::sqrt(motion / (2.0 * static_cast<double>(trial.s.size())));
    if (motion < 1.0) {
      std::ostringstream os;
      os << "the trial of joint " << trial.joint << " by " << trial.amount << " moved the markers by only " << motion
         << " px RMS; the joint may be blocked or the trial too small to observe (use 20 to 60 deg)";
      fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
    }
    // Maximum-likelihood displacement: the linear one from 7 noisy markers is too poor a start for the upgrade. 12
    // Levenberg-Marquardt iterations (of about 25 to full convergence) are enough for a start: the bundle adjustment
    // refines everything, and at 1 px noise no acquisition of 300 failed with 12 (one failed with 8).
    ++trialCount[trial.joint];
    try {
      // With an outlier threshold, mismatched markers are found by the 5-point consensus of estimateRobust() and
      // left out of everything that follows (the candidates' scores, the rigid motions, the bundle adjustment).
      const Eigen::Matrix4d H =
          m_outlierThreshold > 0.0
              ? vpProjectiveDisplacement::estimateRobust(m_rig, m_zeroImages, trial.s, m_outlierThreshold, m_inlier[k])
              : vpProjectiveDisplacement::estimateFromImages(m_rig, m_zeroImages, trial.s, 12);
      double theta = 0.0;
      candidates[trial.joint].push_back(m_types[trial.joint] == REVOLUTE
                                            ? vpProjectiveRotation::log(H, theta, trial.amount).generator()
                                            : vpProjectiveTranslation::log(H, trial.amount).generator());
    } catch (const vpProjectiveException &) {
      // A noisy homography so far off that it is singular or has no logarithm gives no candidate; the joint's other
      // trials, or the rigid motions of its markers in the metric frame (initialTwists()), still do. A trial where
      // too few markers agree on one displacement stays out of the initial model: the model of the other trials
      // decides which of its observations to keep.
      if (m_outlierThreshold > 0.0) {
        m_inlier[k].assign(m_inlier[k].size(), false);
      }
    }
  }
  // A single trial's homography occasionally lands far off (a small marker set gives a poorly conditioned 15-dof
  // fit), which spoils the mean: keep the candidate that best predicts all the trials of its joint.
  Hhat.assign(n, Eigen::Matrix4d::Zero());
  for (size_t i = 0; i < n; ++i) {
    if (trialCount[i] == 0) {
      std::ostringstream os;
      os << "joint " << i << " has no trial motion; call addTrialMotion(" << i << ", amount, left, right) first";
      fail(vpProjectiveException::notInitializedError, where, os.str());
    }
    if (candidates[i].empty()) {
      continue; // Hhat_i = 0: the upgrade leaves joint i out
    }
    Eigen::Matrix4d mean = Eigen::Matrix4d::Zero();
    for (const Eigen::Matrix4d &G : candidates[i]) {
      if (G.allFinite()) {
        mean += G / static_cast<double>(candidates[i].size());
      }
    }
    candidates[i].push_back(m_types[i] == REVOLUTE ? vpProjectiveRotation::project(mean)
                                                   : vpProjectiveTranslation::project(mean));
    double best = std::numeric_limits<double>::quiet_NaN();
    for (const Eigen::Matrix4d &G : candidates[i]) {
      if (!G.allFinite()) {
        continue; // the projection of a degenerate logarithm
      }
      double sum = 0.0;
      size_t count = 0;
      accumulateTrialError(static_cast<unsigned int>(i), G, M0, sum, count);
      const double error = sum / static_cast<double>(count);
      if (!(error >= best)) { // the first finite candidate, then any better one
        best = error;
        Hhat[i] = G;
      }
    }
  }
}

void vpProjectiveRobot::accumulateTrialError(unsigned int i, const Eigen::Matrix4d &Hhat,
                                             const std::vector<Eigen::Vector4d> &M0, double &sum, size_t &count) const
{
  // A prediction with no image (on a camera's focal plane) counts as an error of one image diagonal per coordinate.
  const double noImage = 1e6;
  // With an outlier threshold t, an error counts at most as 3 t (RMS over the two images): a mismatch the consensus
  // missed cannot outweigh the markers that agree.
  const double cap = m_outlierThreshold > 0.0 ? 2.0 * 9.0 * m_outlierThreshold * m_outlierThreshold
                                              : std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < m_trials.size(); ++k) {
    const vpTrial &trial = m_trials[k];
    if (trial.joint != i) {
      continue;
    }
    const Eigen::Matrix4d H = m_types[i] == REVOLUTE ? vpProjectiveRotation::exp(Hhat, trial.amount)
                                                     : vpProjectiveTranslation::exp(Hhat, trial.amount);
    for (size_t j = 0; j < M0.size(); ++j) {
      if (!m_inlier[k][j]) {
        continue;
      }
      Eigen::Vector4d s;
      const double e2 =
          m_rig.project(Eigen::Vector4d(H * M0[j]), s) ? (s - trial.s[j]).squaredNorm() : 4.0 * noImage * noImage;
      sum += std::min(e2, cap);
      count += 4;
    }
  }
}

double vpProjectiveRobot::predictionResidual(const std::vector<Eigen::Matrix4d> &Hhat,
                                             const std::vector<Eigen::Vector4d> &M0) const
{
  double sum = 0.0;
  size_t count = 0;
  for (unsigned int i = 0; i < m_types.size(); ++i) {
    accumulateTrialError(i, Hhat[i], M0, sum, count);
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

namespace
{
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

bool vpProjectiveRobot::metricUpgrade(const std::vector<Eigen::Matrix4d> &Hhat, const std::vector<bool> &use,
                                      const std::vector<Eigen::Vector4d> &M0, Eigen::Matrix4d &G) const
{
  const size_t n = m_types.size();
  const size_t K = M0.size();

  // 1. Conditioning: whiten the projective frame with the zero-reference points.
  const Eigen::Matrix4d Tn = whitening(M0);
  const Eigen::Matrix4d TnInv = Tn.inverse();

  // 2. Affine step: the plane pi with pi^T Hhat_i = 0 for every joint used is the plane at infinity.
  std::vector<Eigen::Matrix4d> Hw;
  std::vector<vpJointType> types;
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
    types.push_back(m_types[i]);
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
    if (types[i] == REVOLUTE) {
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

bool vpProjectiveRobot::initialTwists(const Eigen::Matrix4d &G, const std::vector<Eigen::Matrix4d> &Hhat,
                                      const std::vector<Eigen::Vector4d> &M0,
                                      const std::vector<std::vector<Eigen::Vector4d>> &trialPoints,
                                      std::vector<Eigen::Vector3d> &axis, std::vector<Eigen::Vector3d> &point) const
{
  const size_t n = m_types.size();
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
    if (m_types[i] == REVOLUTE) {
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
    for (size_t k = 0; k < m_trials.size(); ++k) {
      if (m_trials[k].joint != i) {
        continue;
      }
      // A trial whose markers did not agree on one homography (more mismatches than the 5-point consensus can
      // verify) gets the consensus of rigid motions instead: 3 points fix one, and the metric frame (markers spread
      // over a unit RMS radius) makes a tenth of that radius a tolerance far above the noise and below a mismatch;
      // wider ones serve when a rough upgrade distorts the markers' shape more than that.
      const bool verified = std::find(m_inlier[k].begin(), m_inlier[k].end(), true) != m_inlier[k].end();
      std::vector<Eigen::Vector3d> X0k, X1k;
      bool finite = true;
      for (size_t j = 0; j < K && finite; ++j) {
        Eigen::Vector3d X1;
        finite = euclidean(G * trialPoints[k][j], X1);
        if (m_inlier[k][j] || !verified) {
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
      const double amount = m_trials[k].amount;
      if (m_types[i] == REVOLUTE) {
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
      if (m_types[i] == REVOLUTE) {
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
      accumulateTrialError(static_cast<unsigned int>(i), Ginv * twistMatrix(m_types[i], axes[c], points[c]) * G, M0,
                           sum, count);
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

void vpProjectiveRobot::initialMetricModel(const std::vector<Eigen::Matrix4d> &Hhat,
                                           const std::vector<Eigen::Vector4d> &M0, Eigen::Matrix4d &G,
                                           std::vector<Eigen::Vector3d> &axis,
                                           std::vector<Eigen::Vector3d> &point) const
{
  const size_t n = m_types.size();
  std::vector<std::vector<Eigen::Vector4d>> trialPoints(m_trials.size());
  for (size_t k = 0; k < m_trials.size(); ++k) {
    for (const Eigen::Vector4d &s : m_trials[k].s) {
      trialPoints[k].push_back(m_rig.triangulate(Eigen::Vector2d(s.head<2>()), Eigen::Vector2d(s.tail<2>())));
    }
  }
  // The upgrade from every joint's generator, then leaving one or two joints out in turn: a joint whose axis is far
  // from a small marker set (the shoulder of an arm) can have a generator too poor for the common plane at infinity
  // and metric conic (at 1 px noise, 6 PUMA acquisitions of 300 failed with every joint in). The candidate that
  // predicts all the trials best starts the bundle adjustment.
  double best = std::numeric_limits<double>::infinity();
  std::vector<std::vector<bool>> subsets(1, std::vector<bool>(n, true));
  for (size_t a = 0; n >= 3 && a < n; ++a) {
    for (size_t b = a; b < n && (b == a || n >= 4); ++b) {
      std::vector<bool> use(n, true);
      use[a] = false;
      use[b] = false; // b == a: one joint left out
      subsets.push_back(use);
    }
  }
  for (const std::vector<bool> &use : subsets) {
    Eigen::Matrix4d Gc;
    std::vector<Eigen::Vector3d> axisC, pointC;
    if (!metricUpgrade(Hhat, use, M0, Gc) || !initialTwists(Gc, Hhat, M0, trialPoints, axisC, pointC)) {
      continue;
    }
    const Eigen::Matrix4d GcInv = Gc.inverse();
    std::vector<Eigen::Matrix4d> HhatC(n);
    for (size_t i = 0; i < n; ++i) {
      HhatC[i] = GcInv * twistMatrix(m_types[i], axisC[i], pointC[i]) * Gc;
    }
    const double residual = predictionResidual(HhatC, M0);
    if (residual < best) {
      best = residual;
      G = Gc;
      axis = axisC;
      point = pointC;
    }
  }
  if (!(best < std::numeric_limits<double>::infinity())) {
    fail(vpProjectiveException::estimationFailedError, at("calibrate()"),
         "the affine and metric upgrade of the generators failed; check that the trial motions are large enough and "
         "that the markers are matched in the same order in every image");
  }
}

void vpProjectiveRobot::bundleAdjust(const std::vector<Eigen::Vector4d> &M0, const Eigen::Matrix4d &G,
                                     std::vector<Eigen::Vector3d> axis, std::vector<Eigen::Vector3d> point,
                                     bool robustLoss)
{
  const size_t n = m_types.size();
  const size_t K = m_zeroImages.size();
  std::vector<Eigen::Vector4d> N(K);
  // 5. Bundle adjustment over G^-1, the twists and the markers, on the pixel error of every acquisition image.
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> Ginv = G.inverse();
  for (size_t j = 0; j < K; ++j) {
    N[j] = (G * M0[j]).normalized();
  }
  ceres::Problem problem;
  for (size_t j = 0; j < K; ++j) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<ZeroReferenceError, 4, 16, 4>(new ZeroReferenceError(m_rig, m_zeroImages[j])),
        nullptr, Ginv.data(), N[j].data());
  }
  size_t observations = K;
  for (size_t k = 0; k < m_trials.size(); ++k) {
    const vpTrial &trial = m_trials[k];
    const unsigned int i = trial.joint;
    for (size_t j = 0; j < K; ++j) {
      if (!m_inlier[k][j] && !robustLoss) {
        continue;
      }
      ++observations;
      // Cauchy loss at the outlier threshold (on the squared 4-vector error, 2 d^2): a mismatch pulls with a force
      // that fades with its error instead of growing with it.
      ceres::LossFunction *loss = robustLoss ? new ceres::CauchyLoss(std::sqrt(2.0) * m_outlierThreshold) : nullptr;
      if (m_types[i] == REVOLUTE) {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<RevoluteTrialError, 4, 16, 4, 3, 3>(
                                     new RevoluteTrialError(m_rig, trial.s[j], trial.amount)),
                                 loss, Ginv.data(), N[j].data(), axis[i].data(), point[i].data());
      } else {
        problem.AddResidualBlock(new ceres::AutoDiffCostFunction<PrismaticTrialError, 4, 16, 4, 3>(
                                     new PrismaticTrialError(m_rig, trial.s[j], trial.amount)),
                                 loss, Ginv.data(), N[j].data(), axis[i].data());
      }
    }
  }
  for (size_t j = 0; j < K; ++j) {
    problem.SetManifold(N[j].data(), new ceres::SphereManifold<4>());
  }
  problem.SetManifold(Ginv.data(), new ceres::SphereManifold<16>());
  for (size_t i = 0; i < n; ++i) {
    // A joint whose trials are all left out of this adjustment keeps its initial axis.
    if (m_types[i] == REVOLUTE && problem.HasParameterBlock(axis[i].data())) {
      problem.SetManifold(axis[i].data(), new ceres::SphereManifold<3>());
    }
  }
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_SCHUR, 200);

  const Eigen::Matrix4d GinvFinal = Ginv;
  if (!GinvFinal.allFinite() || !summary.IsSolutionUsable()) {
    fail(vpProjectiveException::estimationFailedError, at("calibrate()"),
         "the bundle adjustment of the generators failed; check that the trial motions are large enough and that "
         "the markers are matched in the same order in every image");
  }
  // G is the model; its inverse is recomputed from it exactly as loadModel() does, so that a saved and reloaded
  // model gives bit-identical generators and Jacobians.
  m_G = GinvFinal.inverse();
  m_Ginv = m_G.inverse();
  m_axis = axis;
  m_point = point;
  for (size_t i = 0; i < n; ++i) {
    if (m_types[i] == REVOLUTE) {
      m_axis[i].normalize();
    }
  }
  m_M0.resize(K);
  for (size_t j = 0; j < K; ++j) {
    m_M0[j] = (m_Ginv * N[j]).normalized();
  }
  m_residual = std::sqrt(2.0 * summary.final_cost / static_cast<double>(4 * observations));
  setModelFromTwists();
}

void vpProjectiveRobot::setModelFromTwists()
{
  m_Hhat.resize(m_types.size());
  for (size_t i = 0; i < m_types.size(); ++i) {
    m_Hhat[i] = m_Ginv * twistMatrix(m_types[i], m_axis[i], m_point[i]) * m_G;
  }
}

void vpProjectiveRobot::calibrate()
{
  const std::string where = at("calibrate()");
  if (m_types.empty()) {
    fail(vpProjectiveException::notInitializedError, where, "the robot has no joints; construct it with joint types");
  }
  if (m_zeroImages.empty()) {
    fail(vpProjectiveException::notInitializedError, where,
         "no zero reference; call setStereoRig(), setZeroReference() and addTrialMotion() for every joint first");
  }
  const size_t K = m_zeroImages.size();
  m_inlier.assign(m_trials.size(), std::vector<bool>(K, true));
  const std::vector<Eigen::Vector4d> M0 = triangulateZeroReference();
  if (m_outlierThreshold > 0.0) {
    // The zero reference defines which marker is which: a marker whose two images there do not meet (a left-right
    // mismatch) cannot be repaired, only reported.
    for (size_t j = 0; j < K; ++j) {
      Eigen::Vector4d s;
      const double d = m_rig.project(M0[j], s) ? std::sqrt(0.5 * (s - m_zeroImages[j]).squaredNorm())
                                               : std::numeric_limits<double>::infinity();
      if (!(d <= m_outlierThreshold)) {
        std::ostringstream os;
        os << "the left and right images of marker " << j << " at the zero reference are " << d
           << " px away from any 3D point (outlier threshold " << m_outlierThreshold
           << " px): they are not the same marker; fix the matching of the zero-reference images";
        fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
      }
    }
  }
  std::vector<Eigen::Matrix4d> Hhat;
  algebraicGenerators(M0, Hhat);
  m_algebraicResidual = predictionResidual(Hhat, M0);
  Eigen::Matrix4d G;
  std::vector<Eigen::Vector3d> axis, point;
  initialMetricModel(Hhat, M0, G, axis, point);
  if (m_outlierThreshold > 0.0) {
    // Every trial observation, mismatches down-weighted by a robust loss; then least squares on exactly those the
    // model accepts, until that set no longer changes (at most 3 rounds).
    bundleAdjust(M0, G, axis, point, true);
    classifyTrialObservations();
    bundleAdjust(m_M0, m_G, m_axis, m_point, false);
    for (int round = 0; round < 2 && classifyTrialObservations(); ++round) {
      bundleAdjust(m_M0, m_G, m_axis, m_point, false);
    }
  } else {
    bundleAdjust(M0, G, axis, point, false);
  }
  m_calibrated = true;
}

bool vpProjectiveRobot::classifyTrialObservations()
{
  bool changed = false;
  for (size_t k = 0; k < m_trials.size(); ++k) {
    const vpTrial &trial = m_trials[k];
    const Eigen::Matrix4d H = jointExp(trial.joint, trial.amount);
    for (size_t j = 0; j < m_M0.size(); ++j) {
      Eigen::Vector4d s;
      const double d = m_rig.project(Eigen::Vector4d(H * m_M0[j]), s) ? std::sqrt(0.5 * (s - trial.s[j]).squaredNorm())
                                                                      : std::numeric_limits<double>::infinity();
      const bool inlier = d <= m_outlierThreshold;
      changed = changed || inlier != m_inlier[k][j];
      m_inlier[k][j] = inlier;
    }
  }
  return changed;
}

void vpProjectiveRobot::setOutlierThreshold(double pixels)
{
  if (!std::isfinite(pixels) || pixels < 0.0) {
    std::ostringstream os;
    os << "the outlier threshold must be a finite number of pixels >= 0 (0 disables the rejection), got " << pixels;
    fail(vpProjectiveException::invalidValueError, at("setOutlierThreshold()"), os.str());
  }
  m_outlierThreshold = pixels;
  m_calibrated = false;
}

unsigned int vpProjectiveRobot::getNumberOfOutliers() const
{
  unsigned int outliers = 0;
  for (const std::vector<bool> &trial : m_inlier) {
    outliers += static_cast<unsigned int>(std::count(trial.begin(), trial.end(), false));
  }
  return outliers;
}

bool vpProjectiveRobot::isOutlier(unsigned int trial, unsigned int marker) const
{
  if (trial >= m_inlier.size() || marker >= m_inlier[trial].size()) {
    std::ostringstream os;
    os << "no observation of marker " << marker << " in trial " << trial << " (calibrate() saw " << m_inlier.size()
       << " trials of " << m_zeroImages.size() << " markers)";
    fail(vpProjectiveException::dimensionError, at("isOutlier()"), os.str());
  }
  return !m_inlier[trial][marker];
}

void vpProjectiveRobot::checkCalibrated(const char *method) const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at(method),
         "the robot model is not acquired yet; call calibrate() after the acquisition, or loadModel()");
  }
}

vpProjectiveRobot::JointVector vpProjectiveRobot::toJointVector(const vpColVector &q, const std::string &where) const
{
  if (q.getRows() != m_types.size()) {
    std::ostringstream os;
    os << "q must have " << m_types.size() << " entries (one per joint), got " << q.getRows();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  JointVector qe(m_types.size());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    requireFinite(q[i], where, "a joint value");
    qe(i) = q[i];
  }
  return qe;
}

vpMatrix vpProjectiveRobot::getGenerator(unsigned int i) const
{
  checkCalibrated("getGenerator()");
  getJointType(i);
  return toVisp(m_Hhat[i]);
}

vpMatrix vpProjectiveRobot::getProjectiveToMetric() const
{
  checkCalibrated("getProjectiveToMetric()");
  return toVisp(m_G);
}

vpMatrix vpProjectiveRobot::getTwist(unsigned int i) const
{
  checkCalibrated("getTwist()");
  getJointType(i);
  return toVisp(twistMatrix(m_types[i], m_axis[i], m_point[i]));
}

std::vector<vpColVector> vpProjectiveRobot::getZeroReferencePoints() const
{
  checkCalibrated("getZeroReferencePoints()");
  std::vector<vpColVector> M(m_M0.size());
  for (size_t j = 0; j < m_M0.size(); ++j) {
    M[j] = toVispVector(m_M0[j]);
  }
  return M;
}

Eigen::Matrix4d vpProjectiveRobot::jointExp(unsigned int i, double q) const
{
  return m_types[i] == REVOLUTE ? vpProjectiveRotation::exp(m_Hhat[i], q) : vpProjectiveTranslation::exp(m_Hhat[i], q);
}

Eigen::Matrix4d vpProjectiveRobot::displacement(const JointVector &q) const
{
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  for (unsigned int k = 0; k < m_types.size(); ++k) {
    const unsigned int i = chainJoint(k);
    H = H * jointExp(i, q(i));
  }
  return H;
}

void vpProjectiveRobot::jointMotions(const JointVector &q, Eigen::Matrix4d *HhatKq) const
{
  // A_{k-1} Hhat_k A_{k-1}^-1 with A_{k-1}^-1 = exp(-q_{k-1} Hhat_{k-1}) ... exp(-q_0 Hhat_0): no matrix inverse.
  // exp(+-q Hhat) share their terms: I +- sin(q) Hhat + (1 - cos(q)) Hhat^2 (26), I +- q Hhat (31), i.e.
  // jointExp(i, q) and jointExp(i, -q) up to rounding. A_{-1} = I needs no product, and the last joint's exponential
  // no value.
  const unsigned int n = static_cast<unsigned int>(m_types.size());
  Eigen::Matrix4d A, Ainv, AH, E, Einv;
  for (unsigned int k = 0; k < n; ++k) {
    const unsigned int i = chainJoint(k);
    const Eigen::Matrix4d &Hhat = m_Hhat[i];
    if (k == 0) {
      HhatKq[i] = Hhat;
    } else {
      AH.noalias() = A * Hhat;
      HhatKq[i].noalias() = AH * Ainv;
    }
    if (k + 1 == n) {
      break;
    }
    if (m_types[i] == REVOLUTE) {
      const double s = std::sin(q(i));
      const double c = 1.0 - std::cos(q(i));
      Eigen::Matrix4d Hhat2;
      Hhat2.noalias() = Hhat * Hhat;
      E = Eigen::Matrix4d::Identity() + s * Hhat + c * Hhat2;
      Einv = Eigen::Matrix4d::Identity() - s * Hhat + c * Hhat2;
    } else {
      E = Eigen::Matrix4d::Identity() + q(i) * Hhat;
      Einv = Eigen::Matrix4d::Identity() - q(i) * Hhat;
    }
    if (k == 0) {
      A = E;
      Ainv = Einv;
    } else {
      A = A * E;
      Ainv = Einv * Ainv;
    }
  }
}

void vpProjectiveRobot::pointJacobian(const Eigen::Matrix4d *HhatKq, const Eigen::Vector4d &M, PointJacobian &JH) const
{
  JH.resize(4, static_cast<Eigen::Index>(m_types.size()));
  for (unsigned int k = 0; k < m_types.size(); ++k) {
    JH.col(k) = HhatKq[k] * M;
  }
}

bool vpProjectiveRobot::imageJacobian(const Eigen::Matrix4d *HhatKq, const Eigen::Vector4d &M, PointJacobian &J) const
{
  const vpProjectiveStereoRig::Projection &P = m_rig.leftProjection();
  const vpProjectiveStereoRig::Projection &Pp = m_rig.rightProjection();
  const Eigen::Vector3d m = P * M;
  const Eigen::Vector3d mp = Pp * M;
  const double eps = 1e-12 * M.norm();
  if (!(std::abs(m(2)) > eps * P.norm()) || !(std::abs(mp(2)) > eps * Pp.norm())) {
    return false;
  }
  // Rows of J_C(m) P and J_C(m') P', eq. (45), then times each column Hhat_{k,q} M, eq. (46).
  Eigen::Matrix4d L;
  L.row(0) = (P.row(0) - (m(0) / m(2)) * P.row(2)) / m(2);
  L.row(1) = (P.row(1) - (m(1) / m(2)) * P.row(2)) / m(2);
  L.row(2) = (Pp.row(0) - (mp(0) / mp(2)) * Pp.row(2)) / mp(2);
  L.row(3) = (Pp.row(1) - (mp(1) / mp(2)) * Pp.row(2)) / mp(2);
  J.resize(4, static_cast<Eigen::Index>(m_types.size()));
  for (unsigned int k = 0; k < m_types.size(); ++k) {
    J.col(k) = L * (HhatKq[k] * M);
  }
  return true;
}

vpMatrix vpProjectiveRobot::getDisplacement(const vpColVector &q) const
{
  checkCalibrated("getDisplacement()");
  return toVisp(displacement(toJointVector(q, at("getDisplacement()"))));
}

vpMatrix vpProjectiveRobot::getJointMotion(unsigned int k, const vpColVector &q) const
{
  checkCalibrated("getJointMotion()");
  getJointType(k);
  Eigen::Matrix4d HhatKq[maxJoints];
  jointMotions(toJointVector(q, at("getJointMotion()")), HhatKq);
  return toVisp(HhatKq[k]);
}

vpMatrix vpProjectiveRobot::getPointJacobian(const vpColVector &q, const vpColVector &M) const
{
  const std::string where = at("getPointJacobian()");
  checkCalibrated("getPointJacobian()");
  const JointVector qe = toJointVector(q, where);
  const Eigen::Vector4d Me = toEigen<4>(M, where, "the point M");
  Eigen::Matrix4d HhatKq[maxJoints];
  jointMotions(qe, HhatKq);
  PointJacobian JH;
  pointJacobian(HhatKq, Me, JH);
  return toVisp(JH);
}

vpMatrix vpProjectiveRobot::getImageJacobian(const vpColVector &q, const vpColVector &M) const
{
  const std::string where = at("getImageJacobian()");
  checkCalibrated("getImageJacobian()");
  const JointVector qe = toJointVector(q, where);
  const Eigen::Vector4d Me = toEigen<4>(M, where, "the point M");
  if (Me.norm() == 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "M is the zero vector, which is no projective point");
  }
  Eigen::Matrix4d HhatKq[maxJoints];
  jointMotions(qe, HhatKq);
  PointJacobian J;
  if (!imageJacobian(HhatKq, Me, J)) {
    fail(vpProjectiveException::pointAtInfinityError, where,
         "M lies on the focal plane of a camera: its image and image Jacobian are undefined");
  }
  return toVisp(J);
}

void vpProjectiveRobot::projectMarker(unsigned int j, const vpColVector &q, vpImagePoint &ipLeft,
                                      vpImagePoint &ipRight) const
{
  const std::string where = at("projectMarker()");
  checkCalibrated("projectMarker()");
  if (j >= m_M0.size()) {
    std::ostringstream os;
    os << "marker index " << j << " is out of range; the model has " << m_M0.size() << " markers";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  Eigen::Vector4d s;
  if (!m_rig.project(Eigen::Vector4d(displacement(toJointVector(q, where)) * m_M0[j]), s)) {
    fail(vpProjectiveException::pointAtInfinityError, where, "the marker lies on a camera's focal plane at this q");
  }
  ipLeft.set_uv(s(0), s(1));
  ipRight.set_uv(s(2), s(3));
}

namespace
{
// Pixel error of the observed markers at configuration q, with the analytic Jacobian of eqs. (45)-(46).
class InverseKinematicsCost : public ceres::CostFunction
{
public:
  InverseKinematicsCost(const vpProjectiveRobot &robot, const std::vector<Eigen::Vector4d> &M0,
                        const std::vector<Eigen::Vector4d> &s)
      : m_robot(robot), m_M0(M0), m_s(s)
  {
    set_num_residuals(static_cast<int>(4 * s.size()));
    mutable_parameter_block_sizes()->push_back(static_cast<int>(robot.getNumberOfJoints()));
  }

  bool Evaluate(double const *const *parameters, double *residuals, double **jacobians) const override
  {
    const unsigned int n = m_robot.getNumberOfJoints();
    vpProjectiveRobot::JointVector q(n);
    for (unsigned int i = 0; i < n; ++i) {
      q(i) = parameters[0][i];
    }
    const Eigen::Matrix4d H = m_robot.displacement(q);
    Eigen::Matrix4d HhatKq[vpProjectiveRobot::maxJoints];
    m_robot.jointMotions(q, HhatKq);
    vpProjectiveRobot::PointJacobian J;
    for (size_t j = 0; j < m_s.size(); ++j) {
      const Eigen::Vector4d M = H * m_M0[j];
      Eigen::Vector4d s;
      if (!m_robot.getStereoRig().project(M, s)) {
        return false;
      }
      for (int r = 0; r < 4; ++r) {
        residuals[4 * j + r] = s(r) - m_s[j](r);
      }
      if (jacobians != nullptr && jacobians[0] != nullptr) {
        if (!m_robot.imageJacobian(HhatKq, M, J)) {
          return false;
        }
        for (int r = 0; r < 4; ++r) {
          for (unsigned int i = 0; i < n; ++i) {
            jacobians[0][(4 * j + r) * n + i] = J(r, i);
          }
        }
      }
    }
    return true;
  }

private:
  const vpProjectiveRobot &m_robot;
  const std::vector<Eigen::Vector4d> &m_M0;
  const std::vector<Eigen::Vector4d> &m_s;
};
} // namespace

vpColVector vpProjectiveRobot::inverseKinematics(const std::vector<vpImagePoint> &left,
                                                 const std::vector<vpImagePoint> &right, const vpColVector &q0,
                                                 const std::vector<unsigned int> &indices, double *residual) const
{
  const std::string where = at("inverseKinematics()");
  checkCalibrated("inverseKinematics()");
  const std::vector<Eigen::Vector4d> s = stackImages(left, right, where);
  std::vector<Eigen::Vector4d> M0;
  if (indices.empty()) {
    if (s.size() != m_M0.size()) {
      std::ostringstream os;
      os << "got the images of " << s.size() << " markers but the model has " << m_M0.size()
         << "; pass all markers in order, or their indices";
      fail(vpProjectiveException::dimensionError, where, os.str());
    }
    M0 = m_M0;
  } else {
    if (indices.size() != s.size()) {
      fail(vpProjectiveException::dimensionError, where, "there must be one marker index per image point pair");
    }
    for (unsigned int j : indices) {
      if (j >= m_M0.size()) {
        std::ostringstream os;
        os << "marker index " << j << " is out of range; the model has " << m_M0.size() << " markers";
        fail(vpProjectiveException::dimensionError, where, os.str());
      }
      M0.push_back(m_M0[j]);
    }
  }
  if (2 * s.size() < m_types.size()) {
    std::ostringstream os;
    os << s.size() << " markers give " << 4 * s.size() << " equations for " << m_types.size()
       << " joints, but each marker constrains at most 2 degrees of freedom of the chain; observe more markers";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  std::vector<double> q(m_types.size(), 0.0);
  if (q0.getRows() != 0) {
    const JointVector qe = toJointVector(q0, where);
    for (size_t i = 0; i < q.size(); ++i) {
      q[i] = qe(static_cast<Eigen::Index>(i));
    }
  }
  ceres::Problem problem;
  problem.AddResidualBlock(new InverseKinematicsCost(*this, M0, s), nullptr, q.data());
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_QR, 100, 1e-15);
  if (!summary.IsSolutionUsable()) {
    fail(vpProjectiveException::estimationFailedError, where,
         "the inverse kinematics did not converge; start closer to the solution (q0) or check the marker images");
  }
  if (residual != nullptr) {
    *residual = std::sqrt(2.0 * summary.final_cost / static_cast<double>(4 * s.size()));
  }
  vpColVector result(static_cast<unsigned int>(q.size()));
  for (size_t i = 0; i < q.size(); ++i) {
    result[static_cast<unsigned int>(i)] = q[i];
  }
  return result;
}

namespace
{
const char *const kModelMagic = "visp_projective_robot_model";
const int kModelVersion = 1;

// FNV-1a 64-bit hash of the file body: detects truncation and corruption of the model file.
unsigned long long fnv1a(const std::string &text)
{
  unsigned long long h = 14695981039346656037ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

template <typename Derived> void writeValues(std::ostream &os, const Eigen::MatrixBase<Derived> &x)
{
  for (Eigen::Index i = 0; i < x.rows(); ++i) {
    for (Eigen::Index j = 0; j < x.cols(); ++j) {
      os << ' ' << x(i, j);
    }
  }
}

// Reads "key v1 ... vN" from one line of the model file, checking the key, the count and finiteness.
class ModelReader
{
public:
  ModelReader(const std::string &body, const std::string &filename) : m_in(body), m_filename(filename), m_line(0) {}

  std::istringstream next(const std::string &key)
  {
    std::string line;
    if (!std::getline(m_in, line)) {
      bad("it ends before the entry '" + key + "' (truncated file)");
    }
    ++m_line;
    std::istringstream is(line);
    std::string k;
    is >> k;
    if (k != key) {
      bad("line " + std::to_string(m_line) + " has '" + k + "' where '" + key + "' was expected");
    }
    return is;
  }

  template <typename Derived> void values(const std::string &key, Eigen::MatrixBase<Derived> &x)
  {
    std::istringstream is = next(key);
    for (Eigen::Index i = 0; i < x.rows(); ++i) {
      for (Eigen::Index j = 0; j < x.cols(); ++j) {
        if (!(is >> x(i, j)) || !std::isfinite(x(i, j))) {
          bad("the entry '" + key + "' has a missing or non-finite value");
        }
      }
    }
  }

  [[noreturn]] void bad(const std::string &what) const
  {
    fail(vpProjectiveException::fileError, at("loadModel()"),
         "cannot read the model file '" + m_filename + "': " + what);
  }

private:
  std::istringstream m_in;
  std::string m_filename;
  int m_line;
};
} // namespace

void vpProjectiveRobot::saveModel(const std::string &filename) const
{
  const std::string where = at("saveModel()");
  checkCalibrated("saveModel()");
  std::ostringstream os;
  os.precision(17);
  os << kModelMagic << '\n';
  os << "version " << kModelVersion << '\n';
  os << "mounting " << (m_mounting == EYE_TO_HAND ? "eye-to-hand" : "eye-in-hand") << '\n';
  os << "joints " << m_types.size();
  for (vpJointType t : m_types) {
    os << ' ' << (t == REVOLUTE ? 'R' : 'P');
  }
  os << '\n';
  os << "fundamental";
  writeValues(os, m_rig.fundamentalMatrix());
  os << "\nG";
  writeValues(os, m_G);
  os << '\n';
  for (size_t i = 0; i < m_types.size(); ++i) {
    os << "twist";
    writeValues(os, m_axis[i]);
    writeValues(os, m_point[i]);
    os << '\n';
  }
  os << "markers " << m_M0.size() << '\n';
  for (const Eigen::Vector4d &M : m_M0) {
    os << "marker";
    writeValues(os, M);
    os << '\n';
  }
  os << "residual " << m_residual << ' ' << m_algebraicResidual << '\n';
  const std::string body = os.str();
  std::ofstream file(filename.c_str());
  if (!file) {
    fail(vpProjectiveException::fileError, where, "cannot open '" + filename + "' for writing");
  }
  file << body << "checksum " << std::hex << fnv1a(body) << '\n';
  if (!file) {
    fail(vpProjectiveException::fileError, where, "writing '" + filename + "' failed (disk full?)");
  }
}

void vpProjectiveRobot::loadModel(const std::string &filename)
{
  std::ifstream file(filename.c_str(), std::ios::binary);
  if (!file) {
    fail(vpProjectiveException::fileError, at("loadModel()"),
         "cannot open the model file '" + filename + "'; check the path, or acquire a model and save it first");
  }
  std::ostringstream all;
  all << file.rdbuf();
  const std::string text = all.str();
  ModelReader header(text, filename);
  const size_t checksumAt = text.rfind("checksum ");
  if (checksumAt == std::string::npos || (checksumAt > 0 && text[checksumAt - 1] != '\n')) {
    header.bad("it has no checksum line (truncated or not a model file)");
  }
  const std::string body = text.substr(0, checksumAt);
  std::istringstream checksumLine(text.substr(checksumAt + 9));
  unsigned long long stored = 0;
  if (!(checksumLine >> std::hex >> stored) || stored != fnv1a(body)) {
    header.bad("its checksum does not match its content (corrupted or edited file)");
  }

  ModelReader reader(body, filename);
  {
    std::istringstream is = reader.next(kModelMagic);
  }
  int version = 0;
  if (!(reader.next("version") >> version) || version != kModelVersion) {
    reader.bad("it has format version " + std::to_string(version) + ", this build reads version " +
               std::to_string(kModelVersion));
  }
  std::string mounting;
  reader.next("mounting") >> mounting;
  if (mounting != "eye-to-hand" && mounting != "eye-in-hand") {
    reader.bad("the rig mounting is neither eye-to-hand nor eye-in-hand");
  }
  std::istringstream jointsLine = reader.next("joints");
  size_t n = 0;
  if (!(jointsLine >> n) || n == 0 || n > maxJoints) {
    reader.bad("the number of joints is missing or not in [1, " + std::to_string(maxJoints) + "]");
  }
  std::vector<vpJointType> types(n);
  for (size_t i = 0; i < n; ++i) {
    char c = 0;
    if (!(jointsLine >> c) || (c != 'R' && c != 'P')) {
      reader.bad("a joint type is neither R (revolute) nor P (prismatic)");
    }
    types[i] = c == 'R' ? REVOLUTE : PRISMATIC;
  }
  Eigen::Matrix3d F;
  reader.values("fundamental", F);
  Eigen::Matrix4d G;
  reader.values("G", G);
  if (!(std::abs(G.determinant()) > 1e-12 * std::pow(G.norm(), 4))) {
    reader.bad("its matrix G is singular");
  }
  std::vector<Eigen::Vector3d> axis(n), point(n);
  for (size_t i = 0; i < n; ++i) {
    Eigen::Matrix<double, 6, 1> t;
    reader.values("twist", t);
    axis[i] = t.head<3>();
    point[i] = t.tail<3>();
    if (types[i] == REVOLUTE && std::abs(axis[i].norm() - 1.0) > 1e-9) {
      reader.bad("the axis of revolute joint " + std::to_string(i) + " is not a unit vector");
    }
  }
  size_t K = 0;
  if (!(reader.next("markers") >> K) || K < 5 || K > 100000) {
    reader.bad("the number of markers is missing or below 5");
  }
  std::vector<Eigen::Vector4d> M0(K);
  for (size_t j = 0; j < K; ++j) {
    reader.values("marker", M0[j]);
    if (M0[j].norm() == 0.0) {
      reader.bad("a marker is the zero vector");
    }
  }
  Eigen::Vector2d residuals;
  reader.values("residual", residuals);

  vpProjectiveStereoRig rig;
  try {
    rig.setFundamentalMatrix(toVisp(F));
  } catch (const vpException &e) {
    reader.bad(std::string("its fundamental matrix is invalid: ") + e.getStringMessage());
  }
  m_types = types;
  m_mounting = mounting == "eye-to-hand" ? EYE_TO_HAND : EYE_IN_HAND;
  m_rig = rig;
  m_zeroImages.clear();
  m_trials.clear();
  m_G = G;
  m_Ginv = G.inverse();
  m_axis = axis;
  m_point = point;
  m_M0 = M0;
  m_residual = residuals(0);
  m_algebraicResidual = residuals(1);
  setModelFromTwists();
  m_calibrated = true;
}
