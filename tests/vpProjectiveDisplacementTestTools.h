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
  Helpers for the suites of vpProjectiveDisplacement, the p-displacement H = H_PE^-1 T H_PE of a rigid motion T (Ruf
  & Horaud, eqs. (10)-(12), (21)) (header only, not a test itself): rigid bodies, motions of every kind, their
  observations by the metric simulator's rig, the truth the estimates are compared with, and the mismatched
  correspondences of the robust estimation. The suites: testProjectiveDisplacementEstimate,
  testProjectiveDisplacementGroup, testProjectiveDisplacementRobust and testProjectiveDisplacementBadInput.

  Noise-free bounds (1e-8 relative, 1e-8 rad) leave orders of magnitude above rounding for any modelling error; the
  noisy bounds are explained at the tests.
*/

#ifndef _vpProjectiveDisplacementTestTools_h_
#define _vpProjectiveDisplacementTestTools_h_

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

namespace vpProjectiveTest
{
const double kSigma = 0.5; // pixel noise of the noisy test (px)

// A rigid body: n random points in a cube of half side halfSide around the fixation point, pairwise at least
// minDistance apart.
inline std::vector<vpColVector> rigidBody(const Scene &scene, vpUniRand &rng, size_t n, double halfSide,
                                          double minDistance)
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

inline vpColVector centroid(const std::vector<vpColVector> &points)
{
  vpColVector c(3, 0.0);
  for (const vpColVector &X : points) {
    c += X;
  }
  return c / static_cast<double>(points.size());
}

enum MotionKind { Rotation, Screw, Translation, NoMotion };

inline const char *kindName(MotionKind k)
{
  static const char *names[] = {"rotation", "screw", "translation", "identity"};
  return names[k];
}

/*
  A random motion of the given kind that keeps every point of the body visible (10 px margin): a rotation by theta
  about a random axis through a point within 3 cm of the centroid; the same followed by 3 cm along the axis (a screw);
  a translation by 5 cm along a random direction; the identity.
*/
inline vpHomogeneousMatrix randomMotion(const Scene &scene, vpUniRand &rng, const std::vector<vpColVector> &body,
                                        MotionKind kind, double theta)
{
  const vpColVector c = centroid(body);
  for (;;) {
    const vpColVector axis = randomDirection(rng);
    const double dz = rng.uniform(-0.03, 0.03); // drawn last to first: see point3(), vpProjectiveTestTools.h
    const double dy = rng.uniform(-0.03, 0.03);
    const double dx = rng.uniform(-0.03, 0.03);
    const vpColVector p = c + point3(dx, dy, dz);
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

inline Observation observe(const Scene &scene, const std::vector<vpColVector> &body, const vpHomogeneousMatrix &T,
                           double sigma, vpGaussRand &noise)
{
  Observation o;
  scene.sim.project(body, o.left0, o.right0, sigma, noise);
  scene.sim.project(vpSimulatorStereoRig::transform(T, body), o.left1, o.right1, sigma, noise);
  o.M0 = scene.rig.triangulate(o.left0, o.right0);
  o.M1 = scene.rig.triangulate(o.left1, o.right1);
  return o;
}

// The truth the estimates are compared with, as the work order states it: vpProjectiveDisplacement(H_PE^-1 T_l H_PE).
inline Eigen::Matrix4d truth(const Scene &scene, const vpHomogeneousMatrix &T)
{
  return vpProjectiveDisplacement(scene.projectiveDisplacement(T)).matrix();
}

inline double rotationAngle(const vpHomogeneousMatrix &T)
{
  return vpThetaUVector(T.getRotationMatrix()).getTheta();
}

inline std::vector<vpColVector> projectivePoints(const Scene &scene, const std::vector<vpColVector> &wX)
{
  std::vector<vpColVector> M;
  for (const vpColVector &X : wX) {
    M.push_back(toVispVector(scene.projectivePoint(X)));
  }
  return M;
}

// ---------------------------------------------------------------------------------------------------------------
// Robust estimation (mismatched correspondences)
// ---------------------------------------------------------------------------------------------------------------

const double kThreshold = 3.0 * kSigma; // inlier threshold of the robust estimates, the header's advice (px)

inline std::vector<Eigen::Vector4d> stacked(const std::vector<vpImagePoint> &left,
                                            const std::vector<vpImagePoint> &right)
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

inline double imageShift(const Eigen::Vector4d &a, const Eigen::Vector4d &b)
{
  return (a - b).norm() / std::sqrt(2.0);
}

inline MismatchCase mismatchCase(const Scene &scene, uint64_t seed, size_t n, size_t nWrong, double minDistance,
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
inline Eigen::Matrix4d trueWhitening(const Scene &scene, const std::vector<vpColVector> &body)
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

inline RotationErrors rotationErrors(const Scene &scene, const MismatchCase &c, const Eigen::Matrix4d &H)
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
} // namespace vpProjectiveTest

#endif
