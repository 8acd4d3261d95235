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
  The bundle adjustment of a re-registered rig with tracked points (issue 30, point 5;
  vpProjectiveRigRegistration::adjustRig()), in a synthetic projective world (a metric scene seen through a projective
  change of frame G): exact recovery from noise-free images, a camera that did not move stays, a common error of the
  points' priors is removed where a fit with the priors held fixed takes it in, the bad inputs.
*/

#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRigRegistration.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
typedef Eigen::Matrix<double, 3, 4> Camera;
typedef vpProjectiveRigRegistration::vpTrackedImage TrackedImage;

//! A rigid motion of the metric frame: rotation by \e angle (rad) about \e axis, then translation \e t.
Eigen::Matrix4d rigid(const Eigen::Vector3d &axis, double angle, const Eigen::Vector3d &t)
{
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  T.block<3, 1>(0, 3) = t;
  return T;
}

Eigen::Vector3d uniform3(vpUniRand &rng, double a)
{
  return Eigen::Vector3d(rng.uniform(-a, a), rng.uniform(-a, a), rng.uniform(-a, a));
}

Eigen::Vector4d image(const Camera &P, const Camera &Pp, const Eigen::Vector4d &X, vpGaussRand &noise, double sigma)
{
  const Eigen::Vector3d m = P * X, mp = Pp * X;
  Eigen::Vector4d s;
  s << m.head<2>() / m(2), mp.head<2>() / mp(2);
  for (int c = 0; c < 4; ++c) {
    s(c) += sigma * noise();
  }
  return s;
}

/*
  A stereo rig 1 m from a tool of 7 points (within 5 cm), in the projective frame X = G^-1 N of the metric points N;
  after the move (the left camera, or the whole rig with \e wholeRig), 3 observation poses of 7 known points and 30
  frames of the tool turned by up to 15 deg; the tool's priors triangulated from 6 pairs before the move.
*/
struct World {
  World(long seed, double sigma, bool wholeRig) : rng(seed), noise(1.0, 0.0, seed)
  {
    G << 1.0, 0.1, 0.0, 0.05, 0.0, 1.0, 0.2, 0.0, 0.1, 0.0, 1.0, 0.0, 0.2, 0.1, 0.0, 1.0;
    const Eigen::Matrix4d Ginv = G.inverse();
    Eigen::Matrix3d K;
    K << 1600.0, 0.0, 320.0, 0.0, 1600.0, 240.0, 0.0, 0.0, 1.0;
    Camera E = Camera::Zero();
    E.leftCols<3>().setIdentity();
    const Camera Al = K * E;
    const Camera Ar = K * (E * rigid(Eigen::Vector3d::UnitY(), 0.2, Eigen::Vector3d(-0.2, 0.0, 0.02)));
    before.setProjections(Al * G, Ar * G);
    const Eigen::Matrix4d T = rigid(uniform3(rng, 1.0), 0.035, uniform3(rng, 0.01));
    truth.setProjections(Al * T * G, (wholeRig ? Ar * T : Ar) * G);
    const Eigen::Matrix4d pivot = rigid(Eigen::Vector3d::UnitX(), 0.0, Eigen::Vector3d(0.0, 0.0, 1.0));
    for (int i = 0; i < 7; ++i) {
      toolMetric.push_back(uniform3(rng, 0.05).homogeneous());
      tool.push_back(Ginv * toolMetric.back());
    }
    // H = G^-1 D G: the projective image of a rigid motion D of the tool about its centre, 1 m in front.
    auto displacement = [&](double angle) {
      return Eigen::Matrix4d(Ginv * pivot * rigid(uniform3(rng, 1.0), angle, uniform3(rng, 0.05)) * G);
    };
    for (int k = 0; k < 3; ++k) {
      const Eigen::Matrix4d H = displacement(0.3);
      for (const Eigen::Vector4d &M : tool) {
        fixedPoints.push_back(H * M);
        fixedImages.push_back(image(truth.leftProjection(), truth.rightProjection(), H * M, noise, sigma));
      }
    }
    for (int k = 0; k < 30; ++k) {
      frames.push_back(displacement(0.26 * (1.0 - k / 30.0)));
      for (unsigned int i = 0; i < tool.size(); ++i) {
        const Eigen::Vector4d X = frames.back() * tool[i];
        images.push_back(TrackedImage{i, static_cast<unsigned int>(k),
                                      image(truth.leftProjection(), truth.rightProjection(), X, noise, sigma)});
      }
    }
  }

  //! RMS pixel distance (per coordinate) between the images of \e rig and of the true moved rig, over the frames.
  double rigError(const vpProjectiveStereoRig &rig) const
  {
    double sum = 0.0;
    for (const TrackedImage &t : images) {
      const Eigen::Vector4d X = frames[t.frame] * tool[t.point];
      const Eigen::Vector3d m = rig.leftProjection() * X, mt = truth.leftProjection() * X;
      const Eigen::Vector3d mp = rig.rightProjection() * X, mpt = truth.rightProjection() * X;
      sum += (m.head<2>() / m(2) - mt.head<2>() / mt(2)).squaredNorm() +
             (mp.head<2>() / mp(2) - mpt.head<2>() / mpt(2)).squaredNorm();
    }
    return std::sqrt(sum / (4.0 * static_cast<double>(images.size())));
  }

  //! The rig registered from the observation poses only (FIXED_INTRINSICS): the adjustment's start.
  vpProjectiveStereoRig registered() const
  {
    return vpProjectiveRigRegistration::registerRig(before, G, fixedPoints, fixedImages);
  }

  vpUniRand rng;
  vpGaussRand noise;
  Eigen::Matrix4d G;
  vpProjectiveStereoRig before, truth;
  std::vector<Eigen::Vector4d> toolMetric, tool, fixedPoints, fixedImages; // the tool: metric, then G^-1 N
  std::vector<Eigen::Matrix4d> frames;
  std::vector<TrackedImage> images;
};
} // namespace

// Noise-free images and exact priors: the true rig and points, from the registration's start (0.5 px observations).
TEST(RigAdjustment, RecoversTheRigAndPointsFromNoiseFreeImages)
{
  for (bool wholeRig : {false, true}) {
    World w(3, 0.0, wholeRig);
    World noisy(3, 0.5, wholeRig); // the same world, its observation poses seen at 0.5 px: another start
    const vpProjectiveStereoRig start = noisy.registered();
    EXPECT_GT(w.rigError(start), 0.01);
    std::vector<Eigen::Vector4d> points = w.tool;
    double rms = -1.0;
    const vpProjectiveStereoRig rig =
        vpProjectiveRigRegistration::adjustRig(w.before, start, w.G, w.fixedPoints, w.fixedImages, w.frames.front(),
                                               std::vector<double>(7, 6.0), w.frames, w.images, points, &rms);
    EXPECT_LT(w.rigError(rig), 1e-6) << (wholeRig ? "whole rig" : "left camera");
    EXPECT_LT(rms, 1e-6);
    for (size_t i = 0; i < points.size(); ++i) {
      const Eigen::Vector4d M = w.tool[i].normalized();
      EXPECT_LT(std::min((points[i] - M).norm(), (points[i] + M).norm()), 1e-9);
    }
    if (!wholeRig) { // registerRig() kept the right camera: so does the adjustment, exactly
      EXPECT_EQ(rig.rightProjection(), w.before.rightProjection());
    }
  }
}

/*
  Priors with an error common to the points (the whole tool shifted by 1.4 mm, as the mean of a few noisy pairs):
  the fit with the priors held fixed (registerRig() on the points moved by the frames) takes the shift in, the
  adjustment tells it from a camera motion by the frames' other displacements. 10 seeded worlds at 0.5 px.
*/
TEST(RigAdjustment, RemovesACommonErrorOfThePriors)
{
  double fixedSum = 0.0, adjustedSum = 0.0;
  int better = 0;
  for (long seed = 1; seed <= 10; ++seed) {
    World w(seed, 0.5, seed % 2 == 0);
    std::vector<Eigen::Vector4d> priors;
    for (const Eigen::Vector4d &N : w.toolMetric) {
      priors.push_back((w.G.inverse() * (N + Eigen::Vector4d(0.001, -0.001, 0.0, 0.0))).normalized());
    }
    std::vector<Eigen::Vector4d> X, s = w.fixedImages;
    X = w.fixedPoints;
    for (const TrackedImage &t : w.images) {
      X.push_back(w.frames[t.frame] * priors[t.point]);
      s.push_back(t.s);
    }
    const double fixedError = w.rigError(vpProjectiveRigRegistration::registerRig(w.before, w.G, X, s));
    std::vector<Eigen::Vector4d> points = priors;
    const double adjustedError = w.rigError(vpProjectiveRigRegistration::adjustRig(
        w.before, w.registered(), w.G, w.fixedPoints, w.fixedImages, w.frames.front(), std::vector<double>(7, 6.0),
        w.frames, w.images, points));
    fixedSum += fixedError;
    adjustedSum += adjustedError;
    better += adjustedError < fixedError ? 1 : 0;
  }
  EXPECT_LT(adjustedSum, 0.5 * fixedSum);
  EXPECT_GE(better, 9);
}

// Bad input: a clear error, the points unchanged.
TEST(RigAdjustment, BadInputLeavesThePointsUnchanged)
{
  World w(5, 0.5, false);
  const vpProjectiveStereoRig start = w.registered();
  std::vector<Eigen::Vector4d> points = w.tool;
  const std::vector<Eigen::Vector4d> original = points;
  auto expectError = [&](const std::vector<double> &weights, const std::vector<TrackedImage> &images, int code) {
    try {
      vpProjectiveRigRegistration::adjustRig(w.before, start, w.G, w.fixedPoints, w.fixedImages, w.frames.front(),
                                             weights, w.frames, images, points);
      ADD_FAILURE() << "no error";
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), code) << e.getStringMessage();
    }
    EXPECT_EQ(points, original);
  };
  expectError(std::vector<double>(6, 6.0), w.images, vpProjectiveException::dimensionError);
  std::vector<TrackedImage> outOfRange = w.images;
  outOfRange.back().frame = static_cast<unsigned int>(w.frames.size());
  expectError(std::vector<double>(7, 6.0), outOfRange, vpProjectiveException::dimensionError);
  std::vector<double> zeroWeight(7, 6.0);
  zeroWeight[3] = 0.0;
  expectError(zeroWeight, w.images, vpProjectiveException::nonFiniteValueError);
  std::vector<TrackedImage> notFinite = w.images;
  notFinite[4].s(1) = std::nan("");
  expectError(std::vector<double>(7, 6.0), notFinite, vpProjectiveException::nonFiniteValueError);
}
