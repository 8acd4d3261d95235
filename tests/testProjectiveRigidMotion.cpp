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
  Rigid motion seen in the projective frame (Ruf & Horaud, section 4) against the simulator's truth: the logarithm
  of any p-displacement is H_PE^-1 log(T) H_PE, the exponential of a pse(3) element is H_PE^-1 exp(That) H_PE, body
  velocities from displacements and from noisy sequences, point velocities against finite differences of the metric
  motion conjugated by H_PE, and the orbit height of points.
*/

#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveBodyVelocity.h>
#include <visp3/projective/vpProjectiveDisplacement.h>

#include "vpProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! A metric twist (left camera frame) of rotation angle \e theta about a random axis through a point near the
//! scene, plus a translation of \e along along it (a screw) and \e across it.
Eigen::Matrix4d randomTwist(const Scene &scene, vpUniRand &rng, double theta, double along, double across)
{
  const Eigen::Vector3d w = scene.cameraDirection(randomDirection(rng));
  const double dz = rng.uniform(-0.1, 0.1); // drawn last to first: see point3(), vpProjectiveTestTools.h
  const double dy = rng.uniform(-0.1, 0.1);
  const double dx = rng.uniform(-0.1, 0.1);
  const Eigen::Vector3d p = scene.cameraPoint(Scene::fixation()).head<3>() + Eigen::Vector3d(dx, dy, dz);
  const Eigen::Vector3d u = scene.cameraDirection(randomDirection(rng));
  const Eigen::Vector3d v = p.cross(w) * theta + along * w + across * (u - u.dot(w) * w).normalized();
  return vpMetricTwist::hat(v, Eigen::Vector3d(theta * w));
}

struct MotionCase {
  const char *name;
  double theta, along, across;
};

const MotionCase kCases[] = {{"rotation", 0.7, 0.0, 0.0},
                             {"screw", 1.2, 0.05, 0.0},
                             {"general", 2.0, 0.03, 0.08},
                             {"translation", 0.0, 0.0, 0.1},
                             {"tiny rotation", 1e-5, 0.0, 0.0},
                             {"tiny screw", 3e-4, 1e-4, 2e-4},
                             {"nearly a half turn", M_PI - 1e-3, 0.02, 0.0},
                             {"identity", 0.0, 0.0, 0.0}};
} // namespace

/*
  log H = H_PE^-1 That H_PE for H = H_PE^-1 exp(That) H_PE given at any scale and sign, and exp(log H) = H. Errors are
  relative (Frobenius), in the frame whitened by H_PE (where the matrices are of order 1; the rig's pixel-scaled
  projective frame spreads their entries over many orders of magnitude).
*/
TEST(vpProjectiveDisplacement, LogarithmOfAnyDisplacement)
{
  const Scene scene;
  vpUniRand rng(3);
  double worstLog = 0.0, worstExp = 0.0;
  for (const MotionCase &c : kCases) {
    for (int k = 0; k < 10; ++k) {
      SCOPED_TRACE(::testing::Message() << c.name << " " << k);
      const Eigen::Matrix4d That = randomTwist(scene, rng, c.theta, c.along, c.across);
      const Eigen::Matrix4d T = expm(That);
      const double scale = (k % 2 ? -1.0 : 1.0) * rng.uniform(0.01, 100.0);
      const vpProjectiveDisplacement H(Eigen::Matrix4d(scale * scene.HpeInv * T * scene.Hpe));
      const Eigen::Matrix4d Hhat = vpProjectiveDisplacement::log(H);
      // Back in the metric frame, the logarithm is the twist.
      const Eigen::Matrix4d metric = scene.Hpe * Hhat * scene.HpeInv;
      // The logarithm's conditioning grows as 1 / (pi - theta) (b3 of log() does): the bound follows it.
      const double tolerance = 1e-10 + 5e-11 / (M_PI - c.theta);
      const double errLog = (metric - That).norm() / std::max(1.0, That.norm());
      EXPECT_LT(errLog, tolerance) << "theta " << c.theta;
      const Eigen::Matrix4d back = scene.Hpe * vpProjectiveDisplacement::exp(Hhat).matrix() * scene.HpeInv;
      const double errExp = (back - T).norm() / T.norm();
      EXPECT_LT(errExp, tolerance);
      // The exponential of a pse(3) element against the independent series.
      const Eigen::Matrix4d E =
          scene.Hpe * vpProjectiveDisplacement::exp(Eigen::Matrix4d(scene.HpeInv * That * scene.Hpe)).matrix() *
          scene.HpeInv;
      EXPECT_LT((E - T).norm() / T.norm(), 1e-10);
      worstLog = std::max(worstLog, errLog);
      worstExp = std::max(worstExp, errExp);
    }
  }
  // The ViSP-typed contract: vpProjectiveDisplacement(H).log() is a vpMatrix.
  const Eigen::Matrix4d That = randomTwist(scene, rng, 0.4, 0.01, 0.02);
  const vpMatrix Hhat = vpProjectiveDisplacement(toVisp(Eigen::Matrix4d(scene.HpeInv * expm(That) * scene.Hpe))).log();
  ASSERT_EQ(Hhat.getRows(), 4u);
  EXPECT_LT((scene.Hpe * toEigen<4, 4>(Hhat) * scene.HpeInv - That).norm(), 1e-10);
  testLog() << "[ measured ] log of p-displacements: worst relative error " << worstLog << ", exp(log H) " << worstExp
            << std::endl;
}

//! A half turn has no unique logarithm: it throws; a noisy estimate's trace beyond the range is clamped.
TEST(vpProjectiveDisplacement, LogarithmOfHalfTurnThrows)
{
  const Scene scene;
  vpUniRand rng(5);
  const Eigen::Matrix4d T = expm(randomTwist(scene, rng, M_PI, 0.02, 0.0));
  const vpProjectiveDisplacement H(Eigen::Matrix4d(scene.HpeInv * T * scene.Hpe));
  EXPECT_TRUE(throwsProjective([&] { H.log(); }, vpProjectiveException::degenerateConfigurationError, "half turn"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveDisplacement::exp(vpMatrix(3, 3, 0.0)); },
                               vpProjectiveException::dimensionError, "4x4"));
  Eigen::Matrix4d bad = Eigen::Matrix4d::Zero();
  bad(1, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(
      throwsProjective([&] { vpProjectiveDisplacement::exp(bad); }, vpProjectiveException::nonFiniteValueError, "NaN"));
}

/*
  Body velocity (13): from two displacements of a constant-velocity motion it is exact; from a sequence with noisy
  displacements the least-squares slope reduces the error of the two-sample estimate; the point velocity (16) equals
  the finite difference of the moving point, H(t) M(0), in the projective frame; G Hhat G^-1 with G = H_PE is the
  metric twist.
*/
TEST(vpProjectiveBodyVelocity, AgainstTheMetricMotion)
{
  const Scene scene;
  vpUniRand rng(11);
  for (const MotionCase &c : kCases) {
    if (c.theta > 3.0) {
      continue; // a half-turn per step has no logarithm
    }
    SCOPED_TRACE(c.name);
    const Eigen::Matrix4d Xi = randomTwist(scene, rng, c.theta, c.along, c.across); // per second
    const Eigen::Matrix4d Hhat = scene.HpeInv * Xi * scene.Hpe;
    auto H = [&](double t) {
      return vpProjectiveDisplacement(Eigen::Matrix4d(scene.HpeInv * expm(t * Xi) * scene.Hpe));
    };
    const double dt = 0.1;
    const vpProjectiveBodyVelocity V = vpProjectiveBodyVelocity::fromDisplacements(H(0.3), H(0.3 + dt), dt);
    EXPECT_LT((scene.Hpe * V.matrix() * scene.HpeInv - Xi).norm(), 1e-8 * std::max(1.0, Xi.norm()));
    // The metric twist read with G = H_PE.
    const vpColVector xi = V.getTwist(toVisp(scene.Hpe));
    EXPECT_LT((Eigen::Map<const Eigen::Matrix<double, 6, 1>>(xi.data) - vpMetricTwist::vee(Xi)).norm(),
              1e-7 * std::max(1.0, Xi.norm()));
    // Point velocity against a central difference of M(t) = H(t) M(0) (the same scale of M at every t).
    const Eigen::Vector4d M0 = scene.projectivePoint(Scene::fixation());
    const double t = 0.5, h = 1e-5;
    const Eigen::Vector4d numeric = (H(t + h).matrix() * M0 - H(t - h).matrix() * M0) / (2.0 * h);
    const Eigen::Vector4d Mt = H(t).matrix() * M0;
    EXPECT_LT((V.pointVelocity(Mt) - numeric).norm(), 1e-6 * std::max(1.0, numeric.norm()));
    // The ViSP overload of the same name: the same values, and a wrong size refused.
    EXPECT_EQ(toEigen4(V.pointVelocity(toVispVector(Mt))), V.pointVelocity(Mt));
    EXPECT_TRUE(throwsProjective([&] { V.pointVelocity(vpColVector(3, 1.0)); }, vpProjectiveException::dimensionError,
                                 "pointVelocity()"));
    // And the integration of the velocity moves H(0.3) to H(0.3 + dt).
    EXPECT_LT(relativeError((V.integrate(dt) * H(0.3)).matrix(), H(0.3 + dt).matrix()), 1e-8);
    (void)Hhat;
  }
}

TEST(vpProjectiveBodyVelocity, SequenceSmoothsNoise)
{
  const Scene scene;
  vpUniRand rng(17);
  vpGaussRand noise(1.0, 0.0, 19);
  const Eigen::Matrix4d Xi = randomTwist(scene, rng, 0.8, 0.02, 0.05);
  const double dt = 0.04;
  const size_t N = 41, k = 20;
  double errTwo = 0.0, errFit = 0.0, errExact = 0.0;
  const int trials = 20;
  for (int trial = 0; trial < trials; ++trial) {
    std::vector<vpProjectiveDisplacement> H, Hexact;
    std::vector<double> t;
    for (size_t j = 0; j < N; ++j) {
      t.push_back(static_cast<double>(j) * dt);
      // Noise of 1 mrad and 1 mm on each measured displacement, in the metric frame.
      Eigen::Vector3d w, v; // drawn last to first: see point3(), vpProjectiveTestTools.h (w, then v)
      for (int i = 2; i >= 0; --i) {
        w(i) = 1e-3 * noise();
      }
      for (int i = 2; i >= 0; --i) {
        v(i) = 1e-3 * noise();
      }
      const Eigen::Matrix4d noiseTwist = vpMetricTwist::hat(v, w);
      const Eigen::Matrix4d T = expm(t.back() * Xi);
      H.push_back(vpProjectiveDisplacement(Eigen::Matrix4d(scene.HpeInv * expm(noiseTwist) * T * scene.Hpe)));
      Hexact.push_back(vpProjectiveDisplacement(Eigen::Matrix4d(scene.HpeInv * T * scene.Hpe)));
    }
    auto error = [&](const vpProjectiveBodyVelocity &V) {
      return (scene.Hpe * V.matrix() * scene.HpeInv - Xi).norm() / Xi.norm();
    };
    errTwo += error(vpProjectiveBodyVelocity::fromDisplacements(H[k], H[k + 1], dt)) / trials;
    errFit += error(vpProjectiveBodyVelocity::fromSequence(H, t, k, 10)) / trials;
    errExact = std::max(errExact, error(vpProjectiveBodyVelocity::fromSequence(Hexact, t, k, 10)));
  }
  EXPECT_LT(errExact, 1e-8); // a constant velocity is fitted exactly
  EXPECT_LT(errFit, errTwo / 5.0);
  testLog() << "[ measured ] body velocity, 1 mrad / 1 mm noise per displacement: two samples " << errTwo
            << ", 21-sample fit " << errFit << " (relative)" << std::endl;
  // Bad inputs.
  std::vector<vpProjectiveDisplacement> H(3);
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpProjectiveBodyVelocity::fromSequence(H, {0.0, 1.0}, 0, 1);
      },
      vpProjectiveException::dimensionError, "times"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpProjectiveBodyVelocity::fromSequence(H, {0.0, 1.0, 1.0}, 1, 1);
      },
      vpProjectiveException::invalidValueError, "increasing"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpProjectiveBodyVelocity::fromSequence(H, {0.0, 1.0, 2.0}, 3, 1);
      },
      vpProjectiveException::dimensionError, "out of range"));
  EXPECT_TRUE(throwsProjective([&] { vpProjectiveBodyVelocity::fromDisplacements(H[0], H[1], 0.0); },
                               vpProjectiveException::invalidValueError, "positive"));
}
