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
  Tests of vpProjectiveDisplacement, the p-displacement H = H_PE^-1 T H_PE of a rigid motion T (Ruf & Horaud, eqs.
  (10)-(12), (21)), against the metric simulator:
  - estimate() from projective points and from images equals H_PE^-1 T_l H_PE normalised by (12), for rotations about
    a general axis, general screw motions, pure translations and no motion; getRotationAngle() is the metric angle and
    classify() tells the kind of motion;
  - the normalisation (12) removes any scale and sign and gives det H = 1; composition and inverse follow the metric
    ones;
  - with 0.5 px noise on 7 markers, the angle and matrix errors stay within bounds derived below, and the Ceres
    (maximum-likelihood) estimate from images is on average no worse than the linear one from triangulated points;
  - robust estimation (estimateRobust(), estimate(..., inlierThreshold, inliers)) with 20 % mismatched
    correspondences: the accuracy of the outlier-free estimate on the same data, every mismatch flagged, hardly any
    correct point lost, the ML estimate itself on correct data, every kind of motion accepted, a time per call
    below the ML estimate's; unresolvable configurations reported by estimationFailedError; noise-free data exact
    with degenerate minimal sets skipped;
  - every degenerate or invalid input throws a vpProjectiveException with a meaningful code and message.

  Noise-free bounds (1e-8 relative, 1e-8 rad) leave orders of magnitude above rounding for any modelling error; the
  noisy bounds are explained at the test.
*/

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>

#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
const double kSigma = 0.5; // pixel noise of the noisy test (px)

// A rigid body: n random points in a cube of half side halfSide around the fixation point, pairwise at least
// minDistance apart.
std::vector<vpColVector> rigidBody(const Scene &scene, vpUniRand &rng, size_t n, double halfSide, double minDistance)
{
  std::vector<vpColVector> body;
  while (body.size() < n) {
    const vpColVector X = randomVisiblePoints(scene.sim, rng, Scene::fixation(), halfSide, 1, 20.0)[0];
    bool farEnough = true;
    for (const vpColVector &Y : body) {
      farEnough = farEnough && (X - Y).frobeniusNorm() >= minDistance;
    }
    if (farEnough) {
      body.push_back(X);
    }
  }
  return body;
}

vpColVector centroid(const std::vector<vpColVector> &points)
{
  vpColVector c(3, 0.0);
  for (const vpColVector &X : points) {
    c += X;
  }
  return c / static_cast<double>(points.size());
}

enum MotionKind { Rotation, Screw, Translation, NoMotion };

const char *kindName(MotionKind k)
{
  static const char *names[] = {"rotation", "screw", "translation", "identity"};
  return names[k];
}

/*
  A random motion of the given kind that keeps every point of the body visible (10 px margin): a rotation by theta
  about a random axis through a point within 3 cm of the centroid; the same followed by 3 cm along the axis (a screw);
  a translation by 5 cm along a random direction; the identity.
*/
vpHomogeneousMatrix randomMotion(const Scene &scene, vpUniRand &rng, const std::vector<vpColVector> &body,
                                 MotionKind kind, double theta)
{
  const vpColVector c = centroid(body);
  for (;;) {
    const vpColVector axis = randomDirection(rng);
    const vpColVector p = c + point3(rng.uniform(-0.03, 0.03), rng.uniform(-0.03, 0.03), rng.uniform(-0.03, 0.03));
    vpHomogeneousMatrix T;
    switch (kind) {
    case Rotation:
      T = vpSimulatorStereoRig::rotationAbout(p, axis, theta);
      break;
    case Screw:
      T = vpSimulatorStereoRig::translationAlong(axis, 0.03) * vpSimulatorStereoRig::rotationAbout(p, axis, theta);
      break;
    case Translation:
      T = vpSimulatorStereoRig::translationAlong(axis, 0.05);
      break;
    case NoMotion:
      break;
    }
    bool visible = true;
    for (const vpColVector &X : vpSimulatorStereoRig::transform(T, body)) {
      visible = visible && scene.sim.isVisible(X, 10.0);
    }
    if (visible) {
      return T;
    }
  }
}

// Images of the body before and after the motion, and their triangulations with the scene's rig.
struct Observation {
  std::vector<vpImagePoint> left0, right0, left1, right1;
  std::vector<vpColVector> M0, M1;
};

Observation observe(const Scene &scene, const std::vector<vpColVector> &body, const vpHomogeneousMatrix &T,
                    double sigma, vpGaussRand &noise)
{
  Observation o;
  scene.sim.project(body, o.left0, o.right0, sigma, noise);
  scene.sim.project(vpSimulatorStereoRig::transform(T, body), o.left1, o.right1, sigma, noise);
  for (size_t j = 0; j < body.size(); ++j) {
    o.M0.push_back(scene.rig.triangulate(o.left0[j], o.right0[j]));
    o.M1.push_back(scene.rig.triangulate(o.left1[j], o.right1[j]));
  }
  return o;
}

// The truth the estimates are compared with, as the work order states it: vpProjectiveDisplacement(H_PE^-1 T_l H_PE).
Eigen::Matrix4d truth(const Scene &scene, const vpHomogeneousMatrix &T)
{
  return vpProjectiveDisplacement(scene.projectiveDisplacement(T)).matrix();
}

double rotationAngle(const vpHomogeneousMatrix &T)
{
  return vpThetaUVector(T.getRotationMatrix()).getTheta();
}

std::vector<vpColVector> projectivePoints(const Scene &scene, const std::vector<vpColVector> &wX)
{
  std::vector<vpColVector> M;
  for (const vpColVector &X : wX) {
    M.push_back(toVispVector(scene.projectivePoint(X)));
  }
  return M;
}
} // namespace

// ---------------------------------------------------------------------------------------------------------------
// Noise-free estimation
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveDisplacement, EstimateNoiseFreeEqualsTruth)
{
  const Scene scene;
  const vpProjectiveDisplacement::vpMotionType expected[] = {
      vpProjectiveDisplacement::ROTATION, vpProjectiveDisplacement::GENERAL, vpProjectiveDisplacement::TRANSLATION,
      vpProjectiveDisplacement::IDENTITY};
  for (int k = Rotation; k <= NoMotion; ++k) {
    const MotionKind kind = static_cast<MotionKind>(k);
    for (unsigned int seed = 1; seed <= 5; ++seed) {
      SCOPED_TRACE(::testing::Message() << kindName(kind) << ", seed " << seed);
      vpUniRand rng(1000 * (k + 1) + seed);
      vpGaussRand noise(1.0, 0.0, 1);
      // 5 (the minimum) to 9 points.
      const std::vector<vpColVector> body = rigidBody(scene, rng, 4 + seed, 0.08, 0.03);
      const double theta = rng.uniform(0.2, 1.0);
      const vpHomogeneousMatrix T = randomMotion(scene, rng, body, kind, theta);
      const Observation o = observe(scene, body, T, 0.0, noise);
      const Eigen::Matrix4d Htrue = truth(scene, T);

      const vpProjectiveDisplacement D = vpProjectiveDisplacement::estimate(o.M0, o.M1);
      EXPECT_LT(relativeError(D.matrix(), Htrue), 1e-8);
      const vpProjectiveDisplacement Di =
          vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, o.right1);
      EXPECT_LT(relativeError(Di.matrix(), Htrue), 1e-8);

      // The angle of (21) is the metric one; translations and the identity have angle 0 (acos near 1 loses half
      // the digits: 1e-6).
      const double metricAngle = rotationAngle(T);
      const double angleTolerance = (kind == Rotation || kind == Screw) ? 1e-8 : 1e-6;
      EXPECT_NEAR(D.getRotationAngle(), metricAngle, angleTolerance);
      EXPECT_NEAR(Di.getRotationAngle(), metricAngle, angleTolerance);

      EXPECT_EQ(D.classify(), expected[k]);
      EXPECT_EQ(Di.classify(), expected[k]);
      EXPECT_EQ(vpProjectiveDisplacement(Htrue).classify(), expected[k]);
    }
  }
}

TEST(vpProjectiveDisplacement, EstimateFromExactProjectivePoints)
{
  // The true projective points H_PE^-1 N, not triangulated, and with arbitrary scales and signs: M ~ H M0 is a
  // relation between projective points, so the scale of each M must not matter.
  const Scene scene;
  vpUniRand rng(77);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Screw, 0.6);
  std::vector<vpColVector> M0 = projectivePoints(scene, body);
  std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));
  for (size_t j = 0; j < M0.size(); ++j) {
    M0[j] *= rng.uniform(-3.0, 3.0);
    M1[j] *= rng.uniform(-3.0, 3.0);
  }
  const vpProjectiveDisplacement D = vpProjectiveDisplacement::estimate(M0, M1);
  EXPECT_LT(relativeError(D.matrix(), truth(scene, T)), 1e-8);
  EXPECT_LT((D.getMatrix() - toVisp(D.matrix())).frobeniusNorm(), 1e-15);
}

/*
  The minimal case, 5 points, on a small object: 5 random points in a 4 cm cube 1 m away are in general position
  (no 4 coplanar, with probability 1), so the estimate must succeed and be exact. In the rig's frame the unit
  projective points of a small object are nearly parallel, which is a matter of conditioning (the estimator whitens
  its points), not a degeneracy.
*/
TEST(vpProjectiveDisplacement, EstimateMinimalFivePointsOnSmallObject)
{
  const Scene scene;
  for (unsigned int seed = 1; seed <= 20; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(500 + seed);
    const std::vector<vpColVector> body = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.02, 5);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Screw, 0.5);
    const std::vector<vpColVector> M0 = projectivePoints(scene, body);
    const std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));
    try {
      EXPECT_LT(relativeError(vpProjectiveDisplacement::estimate(M0, M1).matrix(), truth(scene, T)), 1e-6);
    } catch (const vpException &e) {
      ADD_FAILURE() << "estimate() rejected 5 points in general position: " << e.getStringMessage();
    }
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Normalisation, composition, inverse
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveDisplacement, NormalisationRemovesScaleAndSign)
{
  const Scene scene;
  vpUniRand rng(5);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  for (int k = Rotation; k <= Translation; ++k) {
    SCOPED_TRACE(kindName(static_cast<MotionKind>(k)));
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, static_cast<MotionKind>(k), 0.7);
    // H_PE with an arbitrary scale: the conjugate does not depend on it, and with det H_PE = +-1 from the simulator
    // it is exactly the normalised displacement (det 1, positive trace).
    const Eigen::Matrix4d Hpe = 3.7 * scene.Hpe;
    const Eigen::Matrix4d H = Hpe.inverse() * scene.cameraDisplacement(T) * Hpe;
    const Eigen::Matrix4d Hn = vpProjectiveDisplacement::normalize(H);
    EXPECT_NEAR(Hn.determinant(), 1.0, 1e-12);
    EXPECT_GT(Hn.trace(), 0.0);
    EXPECT_LT(relativeError(Hn, H), 1e-12);
    for (double s : {-5.0, 1e-3, -1e4, 7.5, -1.0}) {
      SCOPED_TRACE(::testing::Message() << "scale " << s);
      const Eigen::Matrix4d Hs = vpProjectiveDisplacement::normalize(Eigen::Matrix4d(s * H));
      EXPECT_LT(relativeError(Hs, Hn), 1e-13);
      EXPECT_NEAR(Hs.determinant(), 1.0, 1e-12);
      // The constructors normalise too.
      EXPECT_LT(relativeError(vpProjectiveDisplacement(toVisp(Eigen::Matrix4d(s * H))).matrix(), Hn), 1e-13);
      EXPECT_LT(relativeError(vpProjectiveDisplacement(Eigen::Matrix4d(s * H)).matrix(), Hn), 1e-13);
    }
  }
  // A rotation close to pi has a trace close to 0 (2 + 2 cos theta): the sign is still found.
  const vpHomogeneousMatrix T = vpSimulatorStereoRig::rotationAbout(Scene::fixation(), point3(0.3, 1.0, 0.2), 3.0);
  const Eigen::Matrix4d H = scene.projectiveDisplacement(T);
  EXPECT_LT(relativeError(vpProjectiveDisplacement::normalize(Eigen::Matrix4d(-2.0 * H)), H), 1e-12);
  EXPECT_NEAR(vpProjectiveDisplacement(H).getRotationAngle(), 3.0, 1e-9);
}

TEST(vpProjectiveDisplacement, CompositionAndInverseFollowTheMetricOnes)
{
  const Scene scene;
  vpUniRand rng(9);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  const vpHomogeneousMatrix T1 = randomMotion(scene, rng, body, Screw, 0.4);
  const vpHomogeneousMatrix T2 = randomMotion(scene, rng, body, Rotation, 0.9);
  const vpProjectiveDisplacement D1(truth(scene, T1)), D2(truth(scene, T2));
  // Points move by T1 then T2: T2 T1.
  EXPECT_LT(relativeError((D2 * D1).matrix(), truth(scene, T2 * T1)), 1e-10);
  EXPECT_LT(relativeError(D1.inverse().matrix(), truth(scene, T1.inverse())), 1e-10);
  EXPECT_LT(((D1 * D1.inverse()).matrix() - Eigen::Matrix4d::Identity()).norm(), 1e-10);
  EXPECT_EQ((D1 * D1.inverse()).classify(), vpProjectiveDisplacement::IDENTITY);
  // The default displacement is the identity.
  EXPECT_EQ(vpProjectiveDisplacement().matrix(), Eigen::Matrix4d::Identity());
  EXPECT_EQ(vpProjectiveDisplacement().classify(), vpProjectiveDisplacement::IDENTITY);
  EXPECT_EQ(vpProjectiveDisplacement().getRotationAngle(), 0.0);
}

// ---------------------------------------------------------------------------------------------------------------
// Noisy estimation
// ---------------------------------------------------------------------------------------------------------------

/*
  7 markers pairwise >= 8 cm apart in a 20 cm cube 1 m in front of the paper's rig, a 30 deg rotation about a random
  axis through their centroid (+- 3 cm), 0.5 px noise on all four images, the true F (so that the truth is exact),
  20 seeds. Two estimates: linear (DLT on the triangulated points) and maximum likelihood (Ceres, from the images).

  First-order sizes. A marker's stereo depth has std sigma_Z = Z^2 sqrt(2) sigma / (f b) = 0.71 / (1667 * 0.2) =
  2.1 mm (lateral: Z sigma / f = 0.3 mm). Measured over 400 seeds offline (20-seed blocks: worst block mean):
  - angle: a rotation read off 7 points at a lever of ~7 cm has sigma_theta ~ sigma_Z / (7 cm sqrt(7)) = 0.011 rad,
    i.e. a mean |error| of ~0.8 sigma_theta = 0.009 rad. Measured ML: RMS 0.0100, mean 0.0075 (worst block 0.0096),
    max 0.042 rad; linear: mean 0.0098 (worst block 0.0158), max 0.121 rad (the algebraic estimator has a heavy
    tail). Bounds: ML mean 1.3 sigma_theta = 0.015, max 4.5 sigma_theta = 0.051; linear mean 0.025, max 0.15.
  - transfer error: RMS distance (mm) between the true markers moved by H_PE H H_PE^-1 and by the true motion. Both
    point sets are noisy (sqrt(2) sigma_Z) and 15 parameters are fitted on 21 coordinates, so ~ sqrt(2 * 15/21)
    sigma_Z = 2.5 mm. Measured ML mean 2.24 (worst block 2.52), max 5.0 mm; linear mean 2.90 (worst block 3.23), max
    7.1 mm. Bounds: ML mean 1.5 sigma_Z, max 3.5 sigma_Z; linear mean 2 sigma_Z, max 5 sigma_Z.
  - relative matrix error in the markers' whitened frame (W H W^-1, W the whitening of the true points M0, the frame
    the estimator itself works in): ~ sigma_Z / (10 cm spread) = 0.02. Measured ML mean 0.022 (worst block 0.027),
    max 0.079; linear mean 0.030 (worst block 0.035), max 0.117. Bounds: ML mean 0.04, max 0.12; linear mean 0.05,
    max 0.18.
  - relative matrix error in the rig's frame, |H - Htrue|_F / |Htrue|_F: dominated by the entries that the pixel-based
    frame scales up, it has a heavy tail (max over 400 seeds 1.34 ML, 1.93 linear) and only its mean is bounded:
    measured ML mean 0.084 (worst block 0.146), linear 0.224 (worst block 0.31); bounds 0.3 and 0.6.
  The ML estimate must be no worse than the linear one on average, for every measure (it was better in every one of
  the 20 offline blocks for the transfer and whitened errors).
*/
TEST(vpProjectiveDisplacement, EstimateNoisyWithinBounds)
{
  const Scene scene;
  const double theta = vpMath::rad(30.0);
  const double sigmaZ = std::sqrt(2.0) * kSigma / (scene.sim.getLeftCameraParameters().get_px() * 0.20); // Z = 1 m
  const double sigmaTheta = sigmaZ / (0.07 * std::sqrt(7.0));
  const int seeds = 20;
  enum { Angle, Transfer, Whitened, Raw, Measures };
  const char *names[Measures] = {"angle (rad)", "transfer (mm)", "whitened relative", "rig-frame relative"};
  double mean[2][Measures] = {{0.0}}, worst[2][Measures] = {{0.0}};
  for (int seed = 1; seed <= seeds; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(static_cast<uint64_t>(300 + seed));
    vpGaussRand noise(1.0, 0.0, 300 + seed);
    const std::vector<vpColVector> body = rigidBody(scene, rng, 7, 0.10, 0.08);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, theta);
    const Observation o = observe(scene, body, T, kSigma, noise);
    const Eigen::Matrix4d Htrue = truth(scene, T);
    const Eigen::Matrix4d Tl = scene.cameraDisplacement(T);
    // Whitening of the true points: W = (sum u u^T / n)^(-1/2), u the unit projective points.
    Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
    for (const vpColVector &X : body) {
      const Eigen::Vector4d u = scene.projectivePoint(X);
      C += u * u.transpose() / static_cast<double>(body.size());
    }
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(C);
    const Eigen::Matrix4d W =
        eig.eigenvectors() * eig.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() * eig.eigenvectors().transpose();

    const vpProjectiveDisplacement estimates[2] = {
        vpProjectiveDisplacement::estimate(o.M0, o.M1),
        vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, o.right1)};
    for (int k = 0; k < 2; ++k) {
      const Eigen::Matrix4d &H = estimates[k].matrix();
      const Eigen::Matrix4d Tm = scene.Hpe * H * scene.HpeInv;
      double transfer = 0.0;
      for (const vpColVector &X : body) {
        const Eigen::Vector4d N0 = scene.cameraPoint(X);
        const Eigen::Vector4d a = Tm * N0, b = Tl * N0;
        transfer += (a.head<3>() / a(3) - b.head<3>()).squaredNorm() / static_cast<double>(body.size());
      }
      const double e[Measures] = {
          std::abs(estimates[k].getRotationAngle() - theta), 1000.0 * std::sqrt(transfer),
          relativeError(Eigen::Matrix4d(W * H * W.inverse()), Eigen::Matrix4d(W * Htrue * W.inverse())),
          relativeError(H, Htrue)};
      for (int m = 0; m < Measures; ++m) {
        mean[k][m] += e[m] / seeds;
        worst[k][m] = std::max(worst[k][m], e[m]);
      }
    }
  }
  for (int k = 0; k < 2; ++k) {
    std::cout << "[ stats    ] displacement, 7 markers, 30 deg, sigma " << kSigma << " px, " << seeds << " seeds, "
              << (k == 0 ? "linear" : "ML") << ":";
    for (int m = 0; m < Measures; ++m) {
      std::cout << " " << names[m] << " mean " << mean[k][m] << " max " << worst[k][m] << ";";
    }
    std::cout << std::endl;
  }
  const double sigmaZmm = 1000.0 * sigmaZ;
  // Linear estimate.
  EXPECT_LT(mean[0][Angle], 0.025);
  EXPECT_LT(worst[0][Angle], 0.15);
  EXPECT_LT(mean[0][Transfer], 2.0 * sigmaZmm);
  EXPECT_LT(worst[0][Transfer], 5.0 * sigmaZmm);
  EXPECT_LT(mean[0][Whitened], 0.05);
  EXPECT_LT(worst[0][Whitened], 0.18);
  EXPECT_LT(mean[0][Raw], 0.6);
  // Maximum likelihood.
  EXPECT_LT(mean[1][Angle], 1.3 * sigmaTheta);
  EXPECT_LT(worst[1][Angle], 4.5 * sigmaTheta);
  EXPECT_LT(mean[1][Transfer], 1.5 * sigmaZmm);
  EXPECT_LT(worst[1][Transfer], 3.5 * sigmaZmm);
  EXPECT_LT(mean[1][Whitened], 0.04);
  EXPECT_LT(worst[1][Whitened], 0.12);
  EXPECT_LT(mean[1][Raw], 0.3);
  // The ML estimate is on average no worse than the linear one.
  for (int m = 0; m < Measures; ++m) {
    EXPECT_LE(mean[1][m], mean[0][m]) << names[m];
  }
}

// ---------------------------------------------------------------------------------------------------------------
// Robust estimation (mismatched correspondences)
// ---------------------------------------------------------------------------------------------------------------

namespace
{
const double kThreshold = 3.0 * kSigma; // inlier threshold of the robust estimates, the header's advice (px)

std::vector<Eigen::Vector4d> stacked(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
{
  std::vector<Eigen::Vector4d> s(left.size());
  for (size_t j = 0; j < left.size(); ++j) {
    s[j] << left[j].get_u(), left[j].get_v(), right[j].get_u(), right[j].get_v();
  }
  return s;
}

template <typename T> std::vector<T> subset(const std::vector<T> &all, const std::vector<bool> &keep)
{
  std::vector<T> kept;
  for (size_t j = 0; j < all.size(); ++j) {
    if (keep[j]) {
      kept.push_back(all[j]);
    }
  }
  return kept;
}

enum MismatchKind {
  Swapped,  // the markers' tracks are permuted cyclically after the motion (2 swapped, 3 rotated, ...)
  Spurious, // a marker is replaced after the motion by another blob of the scene (a stereo-consistent wrong point)
  Mixed     // half of each
};

/*
  One case of the robust tests: n points of a rigid body in a 20 cm cube (pairwise >= minDistance apart), a 30 deg
  rotation about a random axis through their centroid (+- 3 cm), 0.5 px of noise on the four images, and then
  nWrong of the points mismatched after the motion. s1 holds the correct matches, s1wrong the mismatched ones;
  wrong[j] tells which point is mismatched. Every mismatch moves the point's two images after the motion by at least
  minShift px RMS (a mismatch, not a slightly shifted marker): a swap is redrawn until it does, a spurious blob (the
  image of a random point of the moved body's cube) too.
*/
const double kMismatch = 10.0; // px, 20 sigma

struct MismatchCase {
  std::vector<vpColVector> body;
  vpHomogeneousMatrix T;
  double theta;
  std::vector<Eigen::Vector4d> s0, s1, s1wrong;
  std::vector<bool> wrong;
};

double imageShift(const Eigen::Vector4d &a, const Eigen::Vector4d &b)
{
  return (a - b).norm() / std::sqrt(2.0);
}

MismatchCase mismatchCase(const Scene &scene, uint64_t seed, size_t n, size_t nWrong, double minDistance,
                          MismatchKind kind, double minShift = kMismatch)
{
  vpUniRand rng(seed);
  vpGaussRand noise(1.0, 0.0, static_cast<long>(seed));
  MismatchCase c;
  c.theta = vpMath::rad(30.0);
  c.body = rigidBody(scene, rng, n, 0.10, minDistance);
  c.T = randomMotion(scene, rng, c.body, Rotation, c.theta);
  const Observation o = observe(scene, c.body, c.T, kSigma, noise);
  c.s0 = stacked(o.left0, o.right0);
  c.s1 = stacked(o.left1, o.right1);
  size_t nSpurious = kind == Swapped ? 0 : (kind == Spurious ? nWrong : nWrong / 2);
  if (nWrong - nSpurious == 1) {
    ++nSpurious; // one point cannot be swapped with itself
  }
  const size_t nSwapped = nWrong - nSpurious; // 0 or >= 2
  std::vector<size_t> chosen;
  for (bool shifted = false; !shifted;) {
    c.s1wrong = c.s1;
    c.wrong.assign(n, false);
    chosen.clear();
    while (chosen.size() < nWrong) {
      const size_t j = static_cast<size_t>(rng.uniform(0, static_cast<int>(n)));
      if (!c.wrong[j]) {
        c.wrong[j] = true;
        chosen.push_back(j);
      }
    }
    // The first nSwapped chosen points are permuted cyclically.
    shifted = true;
    for (size_t k = 0; k < nSwapped; ++k) {
      c.s1wrong[chosen[k]] = c.s1[chosen[(k + 1) % nSwapped]];
      shifted = shifted && imageShift(c.s1wrong[chosen[k]], c.s1[chosen[k]]) >= minShift;
    }
  }
  // The others see a spurious blob.
  const vpColVector center = centroid(vpSimulatorStereoRig::transform(c.T, c.body));
  for (size_t k = nSwapped; k < nWrong; ++k) {
    for (;;) {
      const vpColVector X = randomVisiblePoints(scene.sim, rng, center, 0.10, 1, 20.0)[0];
      std::vector<vpImagePoint> l, r;
      scene.sim.project(std::vector<vpColVector>(1, X), l, r, kSigma, noise);
      const Eigen::Vector4d blob = stacked(l, r)[0];
      if (imageShift(blob, c.s1[chosen[k]]) >= minShift) {
        c.s1wrong[chosen[k]] = blob;
        break;
      }
    }
  }
  return c;
}

/*
  Errors of an estimate H of the case's rotation: |angle - theta| (rad, eq. (21)); the transfer error (mm, RMS over
  the markers of the distance between the true markers moved by H_PE H H_PE^-1 and by the true motion); and the
  relative error of the generator log(H) (eq. (25), with the encoder's angle, as the robot's acquisition uses it) in
  the markers' whitened frame.
*/
struct RotationErrors {
  enum { Angle, Transfer, Generator, Count };
  double e[Count];
};

// Whitening W = (sum u u^T / n)^(-1/2) of the true unit projective points u of a body.
Eigen::Matrix4d trueWhitening(const Scene &scene, const std::vector<vpColVector> &body)
{
  Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
  for (const vpColVector &X : body) {
    const Eigen::Vector4d u = scene.projectivePoint(X);
    C += u * u.transpose() / static_cast<double>(body.size());
  }
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(C);
  return eig.eigenvectors() * eig.eigenvalues().cwiseSqrt().cwiseInverse().asDiagonal() *
         eig.eigenvectors().transpose();
}

RotationErrors rotationErrors(const Scene &scene, const MismatchCase &c, const Eigen::Matrix4d &H)
{
  const Eigen::Matrix4d W = trueWhitening(scene, c.body);
  const Eigen::Matrix4d Winv = W.inverse();
  const Eigen::Matrix4d Tm = scene.Hpe * H * scene.HpeInv, Tl = scene.cameraDisplacement(c.T);
  double transfer = 0.0;
  for (const vpColVector &X : c.body) {
    const Eigen::Vector4d N0 = scene.cameraPoint(X);
    const Eigen::Vector4d a = Tm * N0, b = Tl * N0;
    transfer += (a.head<3>() / a(3) - b.head<3>()).squaredNorm() / static_cast<double>(c.body.size());
  }
  const Eigen::Matrix4d G = vpProjectiveRotation::log(vpProjectiveDisplacement(H), c.theta).generator();
  const Eigen::Matrix4d Gtrue =
      vpProjectiveRotation::log(vpProjectiveDisplacement(truth(scene, c.T)), c.theta).generator();
  RotationErrors r;
  r.e[RotationErrors::Angle] = std::abs(vpProjectiveDisplacement(H).getRotationAngle() - c.theta);
  r.e[RotationErrors::Transfer] = 1000.0 * std::sqrt(transfer);
  r.e[RotationErrors::Generator] = relativeError(Eigen::Matrix4d(W * G * Winv), Eigen::Matrix4d(W * Gtrue * Winv));
  return r;
}
} // namespace

/*
  20 % mismatched correspondences at 0.5 px noise, 20 seeds per configuration: 7 markers (>= 8 cm apart) with 1
  spurious blob (the 21 minimal sets are enumerated); 10 points (>= 4 cm apart) with 2 markers swapped, 15 with 3
  markers permuted, 30 (>= 3 cm apart) with 3 swapped and 3 spurious (seeded random minimal sets). Five estimates of
  each case:
  - clean: the ML estimate (estimateFromImages) on the correct data, all n points;
  - oracle: the ML estimate on the n - k correctly matched points only: the outlier-free accuracy of these data, what
    a perfect rejection of the mismatches reaches;
  - robust: estimateRobust() on the mismatched data, threshold 3 sigma (the header's advice);
  - robustClean: estimateRobust() on the correct data;
  - naive: the ML estimate on the mismatched data, to check that the mismatches matter (the test could fail).
  Properties, for each error (rotation angle, transfer, generator) averaged over the seeds:
  - every mismatch is flagged an outlier (they shift image points by >= 10 px = 20 sigma, so d_j >= ~5 px, more than
    3 times the threshold): recall 1; and no more than 1 % of the correct points are flagged (a correct point's
    d_j exceeds 3 sigma with probability ~1e-6 under the true H, a little more under an estimate): precision 1 of the
    outlier flags up to that 1 %;
  - robust matches the outlier-free accuracy: its mean error is within 1.1x of the oracle's (equal when the inliers
    are exactly the correct points, as the ML refit then has the same optimum; 10 % leaves room for one correct point
    lost or one optimum found differently in 20 seeds);
  - robustClean is the ML estimate: whenever it keeps every point, its H equals estimateFromImages' (a dedicated
    Levenberg-Marquardt instead of Ceres, on the same cost) to 1e-6 in the whitened frame (both stop at relative
    cost changes near 1e-12; the estimate's own noise is ~0.02 there), so its mean errors are within 1 % of clean;
  - naive is at least 3x worse than clean (the contamination is harmful, so the properties above are not vacuous).
  The ratio robust / clean is printed: it is the price of the k lost points, of the order of sqrt(n / (n - k)).
*/
TEST(vpProjectiveDisplacement, RobustMatchesOutlierFreeAccuracy)
{
  const Scene scene;
  struct Config {
    size_t n, nWrong;
    double minDistance;
    MismatchKind kind;
  };
  const Config configs[] = {
      {7, 1, 0.08, Spurious}, {10, 2, 0.04, Swapped}, {15, 3, 0.04, Swapped}, {30, 6, 0.03, Mixed}};
  const char *measures[RotationErrors::Count] = {"angle (rad)", "transfer (mm)", "generator (relative)"};
  const int seeds = 20;
  for (const Config &config : configs) {
    SCOPED_TRACE(::testing::Message() << config.n << " points, " << config.nWrong << " mismatched");
    enum { Clean, Oracle, Robust, RobustClean, Naive, Estimates };
    const char *names[Estimates] = {"clean", "oracle", "robust", "robustClean", "naive"};
    double mean[Estimates][RotationErrors::Count] = {{0.0}};
    size_t flagged = 0, lost = 0, lostClean = 0, correct = 0;
    double worstMLDifference = 0.0;
    for (int seed = 1; seed <= seeds; ++seed) {
      SCOPED_TRACE(::testing::Message() << "seed " << seed);
      const MismatchCase c = mismatchCase(scene, static_cast<uint64_t>(1000 * config.n + seed), config.n, config.nWrong,
                                          config.minDistance, config.kind);
      std::vector<bool> correctFlags(config.n);
      for (size_t j = 0; j < config.n; ++j) {
        correctFlags[j] = !c.wrong[j];
      }
      Eigen::Matrix4d H[Estimates];
      std::vector<bool> inliers, inliersClean;
      try {
        H[Robust] = vpProjectiveDisplacement::estimateRobust(scene.rig, c.s0, c.s1wrong, kThreshold, inliers);
        H[RobustClean] = vpProjectiveDisplacement::estimateRobust(scene.rig, c.s0, c.s1, kThreshold, inliersClean);
      } catch (const vpException &e) {
        ADD_FAILURE() << "estimateRobust() threw: " << e.getStringMessage();
        return;
      }
      H[Clean] = vpProjectiveDisplacement::estimateFromImages(scene.rig, c.s0, c.s1);
      H[Oracle] = vpProjectiveDisplacement::estimateFromImages(scene.rig, subset(c.s0, correctFlags),
                                                               subset(c.s1, correctFlags));
      ASSERT_EQ(inliers.size(), config.n);
      ASSERT_EQ(inliersClean.size(), config.n);
      for (size_t j = 0; j < config.n; ++j) {
        if (c.wrong[j]) {
          EXPECT_FALSE(inliers[j]) << "mismatched point " << j << " kept";
          flagged += inliers[j] ? 0 : 1;
        } else {
          ++correct;
          lost += inliers[j] ? 0 : 1;
        }
        lostClean += inliersClean[j] ? 0 : 1;
      }
      if (std::count(inliersClean.begin(), inliersClean.end(), true) == static_cast<long>(config.n)) {
        const Eigen::Matrix4d W = trueWhitening(scene, c.body), Winv = W.inverse();
        const double difference =
            relativeError(Eigen::Matrix4d(W * H[RobustClean] * Winv), Eigen::Matrix4d(W * H[Clean] * Winv));
        EXPECT_LT(difference, 1e-6);
        worstMLDifference = std::max(worstMLDifference, difference);
      }
      for (int k = 0; k < Naive; ++k) {
        const RotationErrors r = rotationErrors(scene, c, H[k]);
        for (int m = 0; m < RotationErrors::Count; ++m) {
          mean[k][m] += r.e[m] / seeds;
        }
      }
      // The least-squares estimate on the mismatched data may be no rotation at all (a singular H, or one without a
      // rotation's eigenvalues): its errors are then infinite.
      try {
        const RotationErrors r =
            rotationErrors(scene, c, vpProjectiveDisplacement::estimateFromImages(scene.rig, c.s0, c.s1wrong));
        for (int m = 0; m < RotationErrors::Count; ++m) {
          mean[Naive][m] += r.e[m] / seeds;
        }
      } catch (const vpException &) {
        for (int m = 0; m < RotationErrors::Count; ++m) {
          mean[Naive][m] = std::numeric_limits<double>::infinity();
        }
      }
    }
    std::cout << "[ stats    ] robust displacement, " << config.n << " points, " << config.nWrong
              << " mismatched, sigma " << kSigma << " px, " << seeds << " seeds: mismatches flagged " << flagged << "/"
              << config.nWrong * seeds << ", correct points flagged " << lost << "/" << correct
              << " (on the correct data " << lostClean << "/" << config.n * seeds
              << "); robustClean vs clean H: max relative difference " << worstMLDifference << std::endl;
    for (int m = 0; m < RotationErrors::Count; ++m) {
      std::cout << "[ stats    ]   " << measures[m] << " mean:";
      for (int e = 0; e < Estimates; ++e) {
        std::cout << " " << names[e] << " " << mean[e][m];
      }
      std::cout << "; robust / oracle " << mean[Robust][m] / mean[Oracle][m] << ", robust / clean "
                << mean[Robust][m] / mean[Clean][m] << " (sqrt(n / (n - k)) "
                << std::sqrt(static_cast<double>(config.n) / static_cast<double>(config.n - config.nWrong)) << ")"
                << std::endl;
    }
    EXPECT_EQ(flagged, config.nWrong * seeds);
    EXPECT_LE(static_cast<double>(lost), 0.01 * static_cast<double>(correct));
    EXPECT_LE(static_cast<double>(lostClean), 0.01 * static_cast<double>(config.n * seeds));
    for (int m = 0; m < RotationErrors::Count; ++m) {
      SCOPED_TRACE(measures[m]);
      EXPECT_LE(mean[Robust][m], 1.1 * mean[Oracle][m]);
      EXPECT_LE(mean[RobustClean][m], 1.01 * mean[Clean][m]);
      EXPECT_GT(mean[Naive][m], 3.0 * mean[Clean][m]);
    }
  }
}

/*
  Configurations that cannot be resolved must throw estimationFailedError, not return a wrong displacement (0.5 px,
  mismatches >= 10 px). 6 points with 2 markers swapped and 7 points with 3 mismatches (2 swapped, 1 blob) leave 4
  correct points, too few to fit H: 10 seeds each must throw. With 6 points of which 1 is a blob, any 5 of them fit a
  homography exactly and the 6th is the only check: a 3D homography fitted to 6 points has 3 redundant constraints
  and may fit all 6, the blob included, within the threshold by distorting space; the estimator rejects such fits
  that are no rigid displacement (the message then says so), but a distorted fit that is rigid within its own large
  uncertainty remains possible: measured 7 in 400 seeds. Bound: over 100 seeds at least 95 throw, the others keep the
  blob (no other outcome). The same cases without the mismatches must succeed and keep every point.
  With exactly 5 points (noise-free here, where the answer is certain) nothing is redundant: 5 correct points are all
  kept, but a point whose left and right images do not match (a stereo mismatch) is still detected and throws.
*/
TEST(vpProjectiveDisplacement, RobustTooManyMismatchesThrow)
{
  const Scene scene;
  std::vector<bool> inliers;
  for (int seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    const MismatchCase six = mismatchCase(scene, static_cast<uint64_t>(6000 + seed), 6, 2, 0.08, Swapped);
    const MismatchCase seven = mismatchCase(scene, static_cast<uint64_t>(7100 + seed), 7, 3, 0.08, Mixed);
    for (const MismatchCase *c : {&six, &seven}) {
      SCOPED_TRACE(::testing::Message() << c->s0.size() << " points");
      EXPECT_TRUE(throwsProjective(
          [&] { vpProjectiveDisplacement::estimateRobust(scene.rig, c->s0, c->s1wrong, kThreshold, inliers); },
          vpProjectiveException::estimationFailedError, "mismatched"));
      try {
        vpProjectiveDisplacement::estimateRobust(scene.rig, c->s0, c->s1, kThreshold, inliers);
        EXPECT_EQ(std::count(inliers.begin(), inliers.end(), true), static_cast<long>(c->s0.size()));
      } catch (const vpException &e) {
        ADD_FAILURE() << "correct points rejected: " << e.getStringMessage();
      }
    }

    vpUniRand rng(static_cast<uint64_t>(6100 + seed));
    vpGaussRand noise(1.0, 0.0, 6100 + seed);
    const std::vector<vpColVector> body = rigidBody(scene, rng, 5, 0.10, 0.08);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, vpMath::rad(30.0));
    const Observation o = observe(scene, body, T, 0.0, noise);
    std::vector<Eigen::Vector4d> s0 = stacked(o.left0, o.right0);
    const std::vector<Eigen::Vector4d> s1 = stacked(o.left1, o.right1);
    try {
      const Eigen::Matrix4d H = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, inliers);
      EXPECT_EQ(std::count(inliers.begin(), inliers.end(), true), 5);
      EXPECT_LT(relativeError(H, truth(scene, T)), 1e-8);
    } catch (const vpException &e) {
      ADD_FAILURE() << "5 correct points rejected: " << e.getStringMessage();
    }
    s0[2](3) += kMismatch; // v' of point 2 before the motion: 10 px off its epipolar line
    EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, inliers); },
                                 vpProjectiveException::estimationFailedError, "only 4 of the 5 points agree"));
  }

  int thrown = 0, absorbed = 0;
  for (int seed = 1; seed <= 100; ++seed) {
    SCOPED_TRACE(::testing::Message() << "6 points, 1 blob, seed " << seed);
    const MismatchCase c = mismatchCase(scene, static_cast<uint64_t>(6200 + seed), 6, 1, 0.08, Spurious);
    try {
      vpProjectiveDisplacement::estimateRobust(scene.rig, c.s0, c.s1wrong, kThreshold, inliers);
      EXPECT_EQ(std::count(inliers.begin(), inliers.end(), true), 6);
      ++absorbed;
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::estimationFailedError) << e.getStringMessage();
      EXPECT_NE(e.getStringMessage().find("mismatched"), std::string::npos) << e.getStringMessage();
      ++thrown;
    }
  }
  std::cout << "[ stats    ] 6 points with 1 blob: " << thrown << " of 100 reported, " << absorbed << " absorbed"
            << std::endl;
  EXPECT_GE(thrown, 95);
}

/*
  No false alarm on any kind of motion: 7 markers, 0.5 px, no mismatch, 20 seeds of each kind (rotation by 10 to 60
  deg, screw, translation by 5 cm, no motion). The rigidity check works on the characteristic polynomial, whose
  sensitivity to the noise vanishes at a translation and at the identity: it must not reject them. The robust estimate
  must keep every point (at most 1 % lost, as above) and then be the ML estimate (1e-6, as above).
*/
TEST(vpProjectiveDisplacement, RobustAcceptsEveryMotionKind)
{
  const Scene scene;
  for (int k = Rotation; k <= NoMotion; ++k) {
    const MotionKind kind = static_cast<MotionKind>(k);
    size_t lost = 0;
    for (int seed = 1; seed <= 20; ++seed) {
      SCOPED_TRACE(::testing::Message() << kindName(kind) << ", seed " << seed);
      vpUniRand rng(static_cast<uint64_t>(9100 + 100 * k + seed));
      vpGaussRand noise(1.0, 0.0, 9100 + 100 * k + seed);
      const std::vector<vpColVector> body = rigidBody(scene, rng, 7, 0.10, 0.08);
      const vpHomogeneousMatrix T = randomMotion(scene, rng, body, kind, rng.uniform(vpMath::rad(10.0), 1.0));
      const Observation o = observe(scene, body, T, kSigma, noise);
      const std::vector<Eigen::Vector4d> s0 = stacked(o.left0, o.right0), s1 = stacked(o.left1, o.right1);
      std::vector<bool> inliers;
      try {
        const Eigen::Matrix4d H = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, kThreshold, inliers);
        const size_t kept = static_cast<size_t>(std::count(inliers.begin(), inliers.end(), true));
        lost += body.size() - kept;
        if (kept == body.size()) {
          const Eigen::Matrix4d W = trueWhitening(scene, body), Winv = W.inverse();
          const Eigen::Matrix4d Hml = vpProjectiveDisplacement::estimateFromImages(scene.rig, s0, s1);
          EXPECT_LT(relativeError(Eigen::Matrix4d(W * H * Winv), Eigen::Matrix4d(W * Hml * Winv)), 1e-6);
        }
      } catch (const vpException &e) {
        ADD_FAILURE() << "a correct " << kindName(kind) << " rejected: " << e.getStringMessage();
      }
    }
    EXPECT_LE(static_cast<double>(lost), 0.01 * 7 * 20) << kindName(kind);
  }
}

/*
  Noise-free data with mismatches are estimated exactly, and degenerate minimal sets are skipped without throwing:
  8 points of which 4 are exactly coplanar (the 4 of the 56 minimal sets that hold them are degenerate), 2 of the
  others swapped after the motion. The estimate must be the true H (1e-8, as the noise-free tests) with exactly the
  swapped points rejected; the result must not depend on the call (seeded) and the vpImagePoint overload must give the
  same. All points coplanar: no minimal set is valid, degenerateConfigurationError.
*/
TEST(vpProjectiveDisplacement, RobustNoiseFreeIsExactAndSkipsDegenerateSets)
{
  const Scene scene;
  for (int seed = 1; seed <= 5; ++seed) {
    SCOPED_TRACE(::testing::Message() << "seed " << seed);
    vpUniRand rng(static_cast<uint64_t>(8000 + seed));
    vpGaussRand noise(1.0, 0.0, 8000 + seed);
    std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.10, 0.04);
    // Points 0..3 on the plane of 0, 1, 2.
    const vpColVector a = body[0], b = body[1], d = body[2];
    body[3] = a + 0.4 * (b - a) + 0.5 * (d - a);
    const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
    const Observation o = observe(scene, body, T, 0.0, noise);
    const std::vector<Eigen::Vector4d> s0 = stacked(o.left0, o.right0);
    std::vector<Eigen::Vector4d> s1 = stacked(o.left1, o.right1);
    std::swap(s1[2], s1[6]);
    std::vector<bool> inliers, again;
    Eigen::Matrix4d H, H2;
    try {
      H = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, inliers);
      H2 = vpProjectiveDisplacement::estimateRobust(scene.rig, s0, s1, 1.0, again);
    } catch (const vpException &e) {
      ADD_FAILURE() << "estimateRobust() threw: " << e.getStringMessage();
      continue;
    }
    EXPECT_LT(relativeError(H, truth(scene, T)), 1e-8);
    for (size_t j = 0; j < 8; ++j) {
      EXPECT_EQ(inliers[j], j != 2 && j != 6) << "point " << j;
    }
    EXPECT_EQ(H, H2);
    EXPECT_EQ(inliers, again);
    std::vector<vpImagePoint> left1 = o.left1, right1 = o.right1;
    std::swap(left1[2], left1[6]);
    std::swap(right1[2], right1[6]);
    const vpProjectiveDisplacement D =
        vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, left1, right1, 1.0, again);
    EXPECT_LT(relativeError(D.matrix(), H), 1e-12);
    EXPECT_EQ(inliers, again);
  }
  // All points on one plane.
  vpUniRand rng(8100);
  vpGaussRand noise(1.0, 0.0, 8100);
  std::vector<vpColVector> planar;
  const vpColVector c = Scene::fixation();
  while (planar.size() < 8) {
    const double x = rng.uniform(-0.08, 0.08), y = rng.uniform(-0.08, 0.08);
    planar.push_back(c + point3(x, y, 0.5 * x + 0.2 * y));
  }
  const vpHomogeneousMatrix T = randomMotion(scene, rng, planar, Rotation, 0.5);
  const Observation o = observe(scene, planar, T, 0.0, noise);
  std::vector<bool> inliers;
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpProjectiveDisplacement::estimateRobust(scene.rig, stacked(o.left0, o.right0), stacked(o.left1, o.right1), 1.0,
                                                 inliers);
      },
      vpProjectiveException::degenerateConfigurationError, "general position"));
}

TEST(vpProjectiveDisplacement, RobustInvalidInputsThrow)
{
  const Scene scene;
  const MismatchCase c = mismatchCase(scene, 9001, 7, 1, 0.08, Spurious);
  std::vector<bool> inliers;
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  const auto robust = [&](const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                          const std::vector<Eigen::Vector4d> &s1, double threshold, int iterations) {
    return [&rig, s0, s1, threshold, iterations, &inliers] {
      vpProjectiveDisplacement::estimateRobust(rig, s0, s1, threshold, inliers, iterations);
    };
  };
  const int code[] = {vpProjectiveException::invalidValueError, vpProjectiveException::nonFiniteValueError};
  // The threshold.
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, 0.0, 100), code[0], "must be positive"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, -1.0, 100), code[0], "must be positive"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, nan, 100), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, inf, 100), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, c.s1, 1.5, 0), code[0], "maxIterations"));
  // Sizes and values.
  const std::vector<Eigen::Vector4d> six(c.s1.begin(), c.s1.begin() + 6);
  EXPECT_TRUE(
      throwsProjective(robust(scene.rig, c.s0, six, 1.5, 100), vpProjectiveException::dimensionError, "same points"));
  const std::vector<Eigen::Vector4d> four0(c.s0.begin(), c.s0.begin() + 4), four1(c.s1.begin(), c.s1.begin() + 4);
  EXPECT_TRUE(throwsProjective(robust(scene.rig, four0, four1, 1.5, 100), vpProjectiveException::notEnoughPointsError,
                               "at least 5"));
  std::vector<Eigen::Vector4d> bad = c.s0;
  bad[3](2) = nan;
  EXPECT_TRUE(throwsProjective(robust(scene.rig, bad, c.s1, 1.5, 100), code[1], "not finite"));
  bad = c.s1;
  bad[6](0) = -inf;
  EXPECT_TRUE(throwsProjective(robust(scene.rig, c.s0, bad, 1.5, 100), code[1], "not finite"));
  const vpProjectiveStereoRig empty;
  EXPECT_TRUE(throwsProjective(robust(empty, c.s0, c.s1, 1.5, 100), vpProjectiveException::notInitializedError,
                               "no fundamental matrix"));

  // The vpImagePoint overload.
  vpUniRand rng(9002);
  vpGaussRand noise(1.0, 0.0, 9002);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 7, 0.08, 0.03);
  const Observation o = observe(scene, body, randomMotion(scene, rng, body, Rotation, 0.5), kSigma, noise);
  const auto estimate = [&](const std::vector<vpImagePoint> &left1, double threshold) {
    return [&o, left1, threshold, &scene, &inliers] {
      vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, left1, o.right1, threshold, inliers);
    };
  };
  EXPECT_TRUE(throwsProjective(estimate(o.left1, 0.0), code[0], "must be positive"));
  EXPECT_TRUE(throwsProjective(estimate(o.left1, nan), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(estimate(std::vector<vpImagePoint>(o.left1.begin(), o.left1.begin() + 6), 1.5),
                               vpProjectiveException::dimensionError, "same size"));
  std::vector<vpImagePoint> badLeft = o.left1;
  badLeft[1].set_u(nan);
  EXPECT_TRUE(throwsProjective(estimate(badLeft, 1.5), code[1], "not finite"));
  EXPECT_TRUE(throwsProjective(
      [&] { vpProjectiveDisplacement::estimate(empty, o.left0, o.right0, o.left1, o.right1, 1.5, inliers); },
      vpProjectiveException::notInitializedError, "no fundamental matrix"));
  // A valid call succeeds (the lambdas above are not vacuous).
  EXPECT_NO_THROW(estimate(o.left1, 1.5)());
  EXPECT_EQ(inliers.size(), body.size());
}

// ---------------------------------------------------------------------------------------------------------------
// Invalid inputs
// ---------------------------------------------------------------------------------------------------------------

TEST(vpProjectiveDisplacement, EstimateFromPointsInvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(13);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 8, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
  const std::vector<vpColVector> M0 = projectivePoints(scene, body);
  const std::vector<vpColVector> M1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, body));

  const std::vector<vpColVector> M0four(M0.begin(), M0.begin() + 4), M1four(M1.begin(), M1.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0four, M1four); },
                               vpProjectiveException::notEnoughPointsError, "at least 5"));
  const std::vector<vpColVector> M1short(M1.begin(), M1.begin() + 7);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0, M1short); },
                               vpProjectiveException::dimensionError, "matched pairs"));

  std::vector<vpColVector> bad = M0;
  bad[2][1] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  bad = M1;
  bad[4][3] = -std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(M0, bad); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  bad = M0;
  bad[1] = point3(1.0, 2.0, 3.0);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::dimensionError, "must have 4 entries"));
  bad = M0;
  bad[0] = vpColVector(4, 0.0);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(bad, M1); },
                               vpProjectiveException::invalidValueError, "zero vector"));

  // 5 points, 4 of them on one world plane (hence on one projective plane).
  const vpColVector c = Scene::fixation();
  std::vector<vpColVector> five = {c + point3(0.05, 0.0, 0.01), c + point3(-0.04, 0.03, -0.02),
                                   c + point3(0.01, -0.05, 0.03), c + point3(-0.03, -0.02, -0.01),
                                   c + point3(0.0, 0.0, 0.0)};
  // Put the 4th on the plane of the first three.
  {
    const Eigen::Vector3d a = toEigen<3, 1>(five[0]), b = toEigen<3, 1>(five[1]), d = toEigen<3, 1>(five[2]);
    five[3] = toVispVector(Eigen::Vector3d(a + 0.3 * (b - a) + 0.4 * (d - a)));
  }
  const vpHomogeneousMatrix T5 = randomMotion(scene, rng, five, Rotation, 0.5);
  const std::vector<vpColVector> P0 = projectivePoints(scene, five);
  const std::vector<vpColVector> P1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T5, five));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(P0, P1); },
                               vpProjectiveException::degenerateConfigurationError, "4 of the 5"));
  // A repeated point among 5.
  std::vector<vpColVector> R0 = projectivePoints(scene, std::vector<vpColVector>(body.begin(), body.begin() + 5));
  std::vector<vpColVector> R1 = std::vector<vpColVector>(M1.begin(), M1.begin() + 5);
  R0[4] = R0[1];
  R1[4] = R1[1];
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(R0, R1); },
                               vpProjectiveException::degenerateConfigurationError, "4 of the 5"));

  // All 8 points on one plane.
  std::vector<vpColVector> planar;
  while (planar.size() < 8) {
    const double x = rng.uniform(-0.08, 0.08), y = rng.uniform(-0.08, 0.08);
    planar.push_back(c + point3(x, y, 0.5 * x + 0.2 * y));
  }
  const std::vector<vpColVector> Q0 = projectivePoints(scene, planar);
  const std::vector<vpColVector> Q1 = projectivePoints(scene, vpSimulatorStereoRig::transform(T, planar));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(Q0, Q1); },
                               vpProjectiveException::degenerateConfigurationError, "are coplanar"));
}

TEST(vpProjectiveDisplacement, EstimateFromImagesInvalidInputsThrow)
{
  const Scene scene;
  vpUniRand rng(17);
  vpGaussRand noise(1.0, 0.0, 17);
  const std::vector<vpColVector> body = rigidBody(scene, rng, 6, 0.08, 0.03);
  const vpHomogeneousMatrix T = randomMotion(scene, rng, body, Rotation, 0.5);
  const Observation o = observe(scene, body, T, 0.0, noise);

  const vpProjectiveStereoRig empty;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(empty, o.left0, o.right0, o.left1, o.right1); },
                               vpProjectiveException::notInitializedError, "no fundamental matrix"));
  const std::vector<vpImagePoint> short1(o.right1.begin(), o.right1.begin() + 5);
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, o.left1, short1); },
                       vpProjectiveException::dimensionError, "same size"));
  const std::vector<vpImagePoint> l0(o.left0.begin(), o.left0.begin() + 4), r0(o.right0.begin(), o.right0.begin() + 4),
      l1(o.left1.begin(), o.left1.begin() + 4), r1(o.right1.begin(), o.right1.begin() + 4);
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, l0, r0, l1, r1); },
                               vpProjectiveException::notEnoughPointsError, "at least 5"));
  std::vector<vpImagePoint> bad = o.left1;
  bad[3].set_i(std::numeric_limits<double>::quiet_NaN());
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::estimate(scene.rig, o.left0, o.right0, bad, o.right1); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
}

TEST(vpProjectiveDisplacement, InvalidMatricesThrow)
{
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  H(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(H); },
                               vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveDisplacement D(H); }, vpProjectiveException::nonFiniteValueError, "NaN"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(toVisp(H)); },
                               vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(vpMatrix(3, 3, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(vpMatrix(4, 3, 1.0)); },
                               vpProjectiveException::dimensionError, "must be 4x4"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(Eigen::Matrix4d::Zero()); },
                               vpProjectiveException::invalidValueError, "zero matrix"));
  Eigen::Matrix4d singular = Eigen::Matrix4d::Identity();
  singular(3, 3) = 0.0;
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::normalize(singular); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement D(singular); },
                               vpProjectiveException::degenerateConfigurationError, "singular"));
}
