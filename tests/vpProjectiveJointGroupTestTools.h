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
  Helpers for the suites of the two one-parameter Lie groups of the joints, p-rotations exp(theta Hhat)
  (vpProjectiveRotation, Ruf & Horaud eqs. (18)-(27)) and p-translations exp(tau Hhat) = I + tau Hhat
  (vpProjectiveTranslation, eqs. (28)-(31)) (header only, not a test itself). They share one interface (log(H,
  amount), exp(), dexp(), the static templated exp() and act(), generator(), project(), generatorResidual()), so one
  typed fixture (JointGroup) checks both, with a traits struct per group for what truly differs: the simulator's
  motion of that kind, the amounts, the generator identity (Hhat^3 = -Hhat or Hhat^2 = 0), the rank (2 or 1) and the
  bounds that follow from them. The suites: testProjectiveJointGroupExpLog, testProjectiveJointGroupNoise,
  testProjectiveJointGroupBadInput (typed), testProjectiveRotation and testProjectiveTranslation (what belongs to one
  group only).

  Noise-free bounds: 1e-9 relative, far above rounding in the rig's frame (cond(H_PE) ~ 4e3, canonical
  normalisation), far below any modelling error (a wrong sign, axis or scale of the generator gives errors of order
  1); tighter where the structure makes the result exact to rounding (1e-12 for a p-translation's nilpotency, 1e-12
  and 1e-11 for logarithms in well-conditioned frames). Each other bound is explained at its test. Every random
  number comes from a seeded vpUniRand or vpGaussRand.
*/

#ifndef _vpProjectiveJointGroupTestTools_h_
#define _vpProjectiveJointGroupTestTools_h_

#include <algorithm>
#include <cmath>
#include <complex>
#include <iostream>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveTranslation.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpNumericJacobian.h"
#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
// A joint in the simulator's world: a unit direction, and a point on the axis (unused by a prismatic joint).
struct Joint {
  vpColVector point;
  vpColVector direction;
};

inline Joint randomJoint(vpUniRand &rng)
{
  Joint j;
  const double dz = rng.uniform(-0.1, 0.1); // drawn last to first: see point3(), vpProjectiveTestTools.h
  const double dy = rng.uniform(-0.1, 0.1);
  const double dx = rng.uniform(-0.1, 0.1);
  j.point = Scene::fixation() + point3(dx, dy, dz);
  j.direction = randomDirection(rng);
  return j;
}

// A 4x4 matrix of entries draw() (row by row).
template <typename Draw> Eigen::Matrix4d drawnMatrix(Draw draw)
{
  Eigen::Matrix4d A;
  for (int i = 0; i < 4; ++i) {
    for (int j = 0; j < 4; ++j) {
      A(i, j) = draw();
    }
  }
  return A;
}

// A random 4x4 matrix of unit Frobenius norm (Gaussian entries): the direction of a perturbation.
inline Eigen::Matrix4d unitNoise(vpGaussRand &noise)
{
  const Eigen::Matrix4d N = drawnMatrix([&] { return noise(); });
  return N / N.norm();
}

// Entries uniform in +-1.
inline Eigen::Matrix4d randomMatrix(vpUniRand &rng)
{
  return drawnMatrix([&] { return rng.uniform(-1.0, 1.0); });
}

// A random, well-conditioned change of frame: I plus entries uniform in +-0.4.
inline Eigen::Matrix4d randomFrame(vpUniRand &rng)
{
  return Eigen::Matrix4d::Identity() + 0.4 * randomMatrix(rng);
}

// ---------------------------------------------------------------------------------------------------------------
// What differs between the groups
// ---------------------------------------------------------------------------------------------------------------

// What names a group in the typed tests: its class, the joint type it moves, the motion type of its elements.
template <typename G, vpProjectiveJoint::vpJointType type, vpProjectiveDisplacement::vpMotionType motion>
struct GroupIdentity {
  using Group = G;
  static constexpr vpProjectiveJoint::vpJointType kType = type;
  static constexpr vpProjectiveDisplacement::vpMotionType kMotion = motion;
  static std::string name() { return type == vpProjectiveJoint::REVOLUTE ? "Rotation" : "Translation"; }
};

struct RotationTraits
    : GroupIdentity<vpProjectiveRotation, vpProjectiveJoint::REVOLUTE, vpProjectiveDisplacement::ROTATION> {

  // The simulator's rotation by \e amount radians about the joint's axis.
  static vpHomogeneousMatrix worldMotion(const Joint &j, double amount)
  {
    return vpSimulatorStereoRig::rotationAbout(j.point, j.direction, amount);
  }
  // Encoder amounts for the logarithm (25): both signs, from 3 deg to 172 deg, away from the multiples of pi where
  // it is undefined.
  static std::vector<double> logAmounts() { return {0.05, 0.1, 0.5, -0.7, -1.0, 1.2, 1.5, 2.2, 2.5, -2.9, 3.0}; }
  // Random amounts of exp() lie in +-kRange: beyond pi, the exponential is defined everywhere.
  static constexpr double kRange = 4.0;
  // The image angle (21) of the p-rotation by \e amount, and how well getRotationAngle() reads it.
  static double imageAngle(double amount) { return std::abs(amount); }
  static constexpr double kAngleTol = 1e-9;

  // Hhat^3 = -Hhat, written here as a relative defect (not through generatorResidual(), which it checks).
  static double identityDefect(const Eigen::Matrix4d &G)
  {
    return relativeError(Eigen::Matrix4d(G * G * G), Eigen::Matrix4d(-G));
  }
  static constexpr int kRank = 2;
  // Eigenvalues +-i, 0, 0 (invariant under H_PE): trace(Hhat^2) = -2 |w|^2 = -2 at unit speed.
  static constexpr double kTraceOfSquare = -2.0;
  // Identity and rank of a noise-free logarithm: sin(amount) and H^-1 in (25) put the rounding of the rig's frame at
  // ~1e-12; 1e-9 as the other noise-free bounds.
  static constexpr double kStructureTol = 1e-9;
  // |expm(a That) - T|_F of the ground truth itself (|T| ~ 2, |a| <= 4): rounding of a scaled-and-squared series.
  static constexpr double kConventionTol = 1e-12;
  static const char *notAGenerator() { return "not a p-rotation generator"; }

  /*
    The logarithm of a noisy p-rotation (see NoisyLogIsExactGeneratorWithBoundedError). Its algebraic generator, read
    in the metric frame: from (25) and (21),
      dHhat = (T E + E T^-1) / (2 sin theta) - cot(theta) Hhat dtheta,  |dtheta| <= eps |T|_F / (2 sin theta),
    hence |dHhat| / |That| <= C eps with C = (|T| + |T^-1| + |cot theta| |That| |T|) / (2 sin theta |That|)
    (Frobenius norms; the change of the normalisation (12), 1 - tr(E)/4, is of lower size).
  */
  static std::vector<double> noisyAmounts() { return {0.3, 0.8, 2.0}; }
  static constexpr double kNoise[2] = {1e-6, 1e-4};
  static double algebraicBound(const Eigen::Matrix4d &T, const Eigen::Matrix4d &That, double theta)
  {
    return (T.norm() + T.inverse().norm() + std::abs(std::cos(theta) / std::sin(theta)) * That.norm() * T.norm()) /
           (2.0 * std::sin(theta) * That.norm());
  }
  // The generator (25) before its projection, (H - H^-1) / (2 sin(amount)), of a normalised H.
  static Eigen::Matrix4d algebraicGenerator(const Eigen::Matrix4d &Hn, double amount)
  {
    return (Hn - Hn.inverse()) / (2.0 * std::sin(amount));
  }
  /*
    How much project() can amplify an error, and where. It is the matrix function f(A) with f = +-i near +-i and 0
    near 0 (the eigenvalues set to +-i, 0, 0), so it commutes with any change of frame: errors are read in the metric
    frame. Its first-order change at That = V diag(i, -i, 0, 0) V^-1 is V (F o (V^-1 dA V)) V^-1 with F the divided
    differences of f, all of modulus 0 or 1 (Higham, Functions of Matrices, Thm 3.11), hence |df|_F <= kappa_2(V)^2
    |dA|_F; 1.1 times that covers the second order at these noise levels. V, with unit columns: for That = [[w]x, v;
    0, 0] (w unit, v orthogonal to w), (e1 -+ i e2, 0) / sqrt(2) for +-i ((e1, e2, w) orthonormal and right-handed),
    (w, 0) and (w x v, 1) for 0; its conditioning grows with the distance |w x v| of the axis to the camera centre.
  */
  static Eigen::Matrix4d errorFrame(const Scene &scene, const Eigen::Matrix4d &X)
  {
    return scene.Hpe * X * scene.HpeInv;
  }
  static double amplificationBound(const Eigen::Matrix4d &That)
  {
    const Eigen::Matrix<double, 6, 1> xi = vpMetricTwist::vee(That);
    const Eigen::Vector3d v = xi.head<3>(), w = xi.tail<3>();
    const Eigen::Vector3d e1 = w.unitOrthogonal(), e2 = w.cross(e1);
    const std::complex<double> i(0.0, 1.0);
    Eigen::Matrix4cd V = Eigen::Matrix4cd::Zero();
    V.block<3, 1>(0, 0) = (e1.cast<std::complex<double>>() - i * e2.cast<std::complex<double>>()) / std::sqrt(2.0);
    V.block<3, 1>(0, 1) = V.block<3, 1>(0, 0).conjugate();
    V.block<3, 1>(0, 2) = w.cast<std::complex<double>>();
    V.col(3) = Eigen::Vector4d(w.cross(v).homogeneous()).normalized().cast<std::complex<double>>();
    const Eigen::Vector4d s = Eigen::JacobiSVD<Eigen::Matrix4cd>(V).singularValues();
    return 1.1 * std::pow(s(0) / s(3), 2);
  }
  // Identity and rank of a projected generator: exact to the rounding of the eigen-decomposition in project().
  static constexpr double kProjectedTol = 1e-10;
};

struct TranslationTraits
    : GroupIdentity<vpProjectiveTranslation, vpProjectiveJoint::PRISMATIC, vpProjectiveDisplacement::TRANSLATION> {

  // The simulator's translation by \e amount metres along the joint's (unit) direction.
  static vpHomogeneousMatrix worldMotion(const Joint &j, double amount)
  {
    return vpSimulatorStereoRig::translationAlong(j.direction, amount);
  }
  // Encoder lengths (m) for the logarithm (31): both signs, from 2 mm to 50 cm.
  static std::vector<double> logAmounts() { return {0.002, 0.01, 0.05, -0.03, -0.07, -0.2, 0.3, 0.4, -0.5}; }
  static constexpr double kRange = 0.5;
  // A translation turns by no angle; the angle of (21) is then an arccos near 1, which turns a rounding d of its
  // argument into sqrt(2 d): ~5e-7 at the worst d ~ 1e-13 of the rig's frame.
  static double imageAngle(double) { return 0.0; }
  static constexpr double kAngleTol = 1e-6;

  // Hhat^2 = 0 relative to |Hhat|^2 (written here, not through generatorResidual()).
  static double identityDefect(const Eigen::Matrix4d &G) { return (G * G).norm() / G.squaredNorm(); }
  static constexpr int kRank = 1;
  // Nilpotent: every eigenvalue is 0.
  static constexpr double kTraceOfSquare = 0.0;
  // A rank-1 sigma u v^T with u orthogonal to v is nilpotent to rounding.
  static constexpr double kStructureTol = 1e-12;
  // I + a That is the simulator's translation to rounding (|a| <= 0.5, unit That).
  static constexpr double kConventionTol = 1e-14;
  static const char *notAGenerator() { return "not a p-translation generator"; }

  /*
    The logarithm of a noisy p-translation. Read in the metric frame (|That| = 1), the algebraic generator's error is
    |T E| / tau <= eps |T|_F / tau; the normalisation (12) changes T (I + E) by 1 - tr(E)/4, of the same order: bound
    C eps with C = 1.5 |T|_F / tau. The relative noise must stay well below tau for the log to mean anything, hence
    smaller eps than for rotations.
  */
  static std::vector<double> noisyAmounts() { return {0.02, 0.1, -0.3}; }
  static constexpr double kNoise[2] = {1e-7, 1e-5};
  static double algebraicBound(const Eigen::Matrix4d &T, const Eigen::Matrix4d &, double tau)
  {
    return 1.5 * T.norm() / std::abs(tau);
  }
  // The generator (31) before its projection, (H - I) / tau, of a normalised H.
  static Eigen::Matrix4d algebraicGenerator(const Eigen::Matrix4d &Hn, double tau)
  {
    return (Hn - Eigen::Matrix4d::Identity()) / tau;
  }
  /*
    How much project() can amplify an error, and where. It works in the rig's frame, where its errors are read: the
    best rank-1 approximation sigma_1 u_1 v_1^T of A = Hhat + dA is within |dA| of A (Eckart-Young; Hhat has rank 1),
    to first order the orthogonal projection of dA on the tangent space of rank-1 matrices, of norm <= |dA|_F; making
    u_1 orthogonal to v_1 then subtracts sigma_1 (v_1 . u_1) v_1 v_1^T, to first order (v^T dA v + u^T dA u) v v^T,
    of norm <= |<dA, v v^T + u u^T>| <= sqrt(2) |dA|_F. Bound (1 + sqrt(2)) |dA|_F, 3 with the second order. (Not a
    metric-frame bound: an SVD does not commute with the change of frame, whose conditioning, ~4e3, could amplify
    errors read there by up to its square.)
  */
  static Eigen::Matrix4d errorFrame(const Scene &, const Eigen::Matrix4d &X) { return X; }
  static double amplificationBound(const Eigen::Matrix4d &) { return 3.0; }
  // Identity and rank of a projected generator: an SVD and one orthogonalisation, exact to rounding.
  static constexpr double kProjectedTol = 1e-12;
};

// The ground truth of one joint of the group of \e Traits, seen by the scene's rig.
template <typename Traits> struct Truth {
  const Scene &scene;
  Joint joint;

  // The unit metric twist That of the joint in the left camera frame.
  Eigen::Matrix4d metricTwist() const
  {
    const Eigen::Vector3d w = scene.cameraDirection(joint.direction).normalized();
    const Eigen::Vector3d p = scene.cameraPoint(joint.point).head<3>();
    return vpProjectiveJoint::twist(Traits::kType, w, p);
  }
  // The true generator H_PE^-1 That H_PE.
  Eigen::Matrix4d generator() const { return scene.HpeInv * metricTwist() * scene.Hpe; }
  // The simulator's metric motion by \e amount in the left camera frame, T_l.
  Eigen::Matrix4d metricMotion(double amount) const
  {
    return scene.cameraDisplacement(Traits::worldMotion(joint, amount));
  }
  // The true p-motion H_PE^-1 T_l H_PE (det 1).
  Eigen::Matrix4d motion(double amount) const
  {
    return scene.projectiveDisplacement(Traits::worldMotion(joint, amount));
  }
};

//! body(k, truth, rng) for 5 random joints k of the group of \e Traits in \e scene, drawn from \e seed.
template <typename Traits, typename Body> void forEachRandomTruth(const Scene &scene, long seed, Body body)
{
  vpUniRand rng(seed);
  for (int k = 0; k < 5; ++k) {
    body(k, Truth<Traits>{scene, randomJoint(rng)}, rng);
  }
}

template <typename Traits> class JointGroup : public ::testing::Test
{
protected:
  const Scene scene;

  Truth<Traits> randomTruth(vpUniRand &rng) const { return Truth<Traits>{scene, randomJoint(rng)}; }
  //! body(k, truth, rng) for 5 random joints k (randomTruth()) drawn from \e seed.
  template <typename Body> void forEachRandomTruth(long seed, Body body) const
  {
    vpProjectiveTest::forEachRandomTruth<Traits>(scene, seed, body);
  }
};

struct GroupNames {
  template <typename Traits> static std::string GetName(int) { return Traits::name(); }
};

using Groups = ::testing::Types<RotationTraits, TranslationTraits>;
} // namespace vpProjectiveTest

//! The typed suites of both groups (testProjectiveJointGroupExpLog, Noise and BadInput), named after the group.
TYPED_TEST_SUITE(JointGroup, vpProjectiveTest::Groups, vpProjectiveTest::GroupNames);

#endif
