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
  Tests of vpSimulatorStereoRig, the metric stereo rig of the simulator (helpers in vpSimulatorTestTools.h): the
  paper's rig geometry, the pinhole convention, visibility and margins, the epipolar constraint, the metric
  projections, the camera frame, rigid motions of point sets, the noise statistics and the bad inputs.
*/

#include <gtest/gtest.h>

#include "vpSimulatorTestTools.h"

using namespace vpProjectiveTest;

TEST(SimulatorStereoRig, PaperRigGeometry)
{
  const vpColVector fixation = point3(0.1, -0.2, 0.3);
  const vpSimulatorStereoRig sim = vpSimulatorStereoRig::paperRig(fixation, 1.0);
  const vpCameraParameters &cam = sim.getLeftCameraParameters();
  EXPECT_NEAR(cam.get_px(), 12.5 / 0.0075, 1e-9);
  EXPECT_NEAR(cam.get_py(), 12.5 / 0.0075, 1e-9);
  EXPECT_DOUBLE_EQ(cam.get_u0(), 320.0);
  EXPECT_DOUBLE_EQ(cam.get_v0(), 240.0);
  EXPECT_EQ(sim.getWidth(), 640u);
  EXPECT_EQ(sim.getHeight(), 480u);

  // Centres 20 cm apart along world X, midpoint 1 m in front of the fixation point along world -Z.
  const vpHomogeneousMatrix wMl = sim.get_wMl();
  const vpHomogeneousMatrix wMr = wMl * sim.get_rMl().inverse();
  const Eigen::Vector3d cl(wMl[0][3], wMl[1][3], wMl[2][3]);
  const Eigen::Vector3d cr(wMr[0][3], wMr[1][3], wMr[2][3]);
  EXPECT_LT((cl - Eigen::Vector3d(0.0, -0.2, -0.7)).norm(), 1e-12);
  EXPECT_LT((cr - Eigen::Vector3d(0.2, -0.2, -0.7)).norm(), 1e-12);
  // y axes along world +Y; optical axes toed in towards each other by atan(0.1 / 1).
  EXPECT_NEAR(wMl[1][1], 1.0, 1e-12);
  EXPECT_NEAR(wMr[1][1], 1.0, 1e-12);
  const double toeIn = std::atan2(0.1, 1.0);
  EXPECT_NEAR(std::atan2(wMl[0][2], wMl[2][2]), toeIn, 1e-12);
  EXPECT_NEAR(std::atan2(wMr[0][2], wMr[2][2]), -toeIn, 1e-12);

  // The fixation point images at the principal point in both images.
  vpImagePoint l, r;
  ASSERT_TRUE(sim.project(fixation, l, r));
  EXPECT_NEAR(l.get_u(), 320.0, 1e-9);
  EXPECT_NEAR(l.get_v(), 240.0, 1e-9);
  EXPECT_NEAR(r.get_u(), 320.0, 1e-9);
  EXPECT_NEAR(r.get_v(), 240.0, 1e-9);
  // A point 1 cm to the right of the fixation point appears to the right (+u) in both images; 1 cm down, +v.
  vpImagePoint l2, r2;
  ASSERT_TRUE(sim.project(point3(0.11, -0.2, 0.3), l2, r2));
  EXPECT_GT(l2.get_u(), 330.0);
  EXPECT_GT(r2.get_u(), 330.0);
  ASSERT_TRUE(sim.project(point3(0.1, -0.19, 0.3), l2, r2));
  EXPECT_NEAR(l2.get_v(), 240.0 + cam.get_py() * 0.01 / std::hypot(0.1, 1.0), 1e-6);

  // The field of view at 1 m is about 38 x 29 cm.
  EXPECT_TRUE(sim.isVisible(point3(0.1 + 0.18, -0.2, 0.3)));
  EXPECT_FALSE(sim.isVisible(point3(0.1 + 0.22, -0.2, 0.3)));
  EXPECT_TRUE(sim.isVisible(point3(0.1, -0.2 + 0.14, 0.3)));
  EXPECT_FALSE(sim.isVisible(point3(0.1, -0.2 + 0.155, 0.3)));
}

TEST(SimulatorStereoRig, ProjectionFollowsPinholeConvention)
{
  vpCameraParameters cam;
  cam.initPersProjWithoutDistortion(800.0, 900.0, 300.0, 200.0);
  vpHomogeneousMatrix rMl;
  rMl[0][3] = -0.1; // right camera 10 cm to the right, parallel axes
  const vpSimulatorStereoRig sim(cam, cam, rMl, vpHomogeneousMatrix(), 640, 480);
  vpImagePoint l, r;
  ASSERT_TRUE(sim.project(point3(0.05, -0.02, 2.0), l, r));
  EXPECT_NEAR(l.get_u(), 300.0 + 800.0 * 0.025, 1e-12); // u = u0 + px X / Z, the column j
  EXPECT_NEAR(l.get_v(), 200.0 - 900.0 * 0.01, 1e-12);  // v = v0 + py Y / Z, the row i
  EXPECT_DOUBLE_EQ(l.get_j(), l.get_u());
  EXPECT_DOUBLE_EQ(l.get_i(), l.get_v());
  EXPECT_NEAR(r.get_u(), 300.0 + 800.0 * (-0.05 / 2.0), 1e-12);
  EXPECT_NEAR(r.get_v(), l.get_v(), 1e-12);
  // Homogeneous input with a last entry other than 1.
  vpColVector Xh(4);
  Xh[0] = 0.1;
  Xh[1] = -0.04;
  Xh[2] = 4.0;
  Xh[3] = 2.0;
  vpImagePoint lh, rh;
  ASSERT_TRUE(sim.project(Xh, lh, rh));
  EXPECT_NEAR(lh.get_u(), l.get_u(), 1e-12);
  EXPECT_NEAR(rh.get_v(), r.get_v(), 1e-12);
}

TEST(SimulatorStereoRig, VisibilityAndMargins)
{
  const vpSimulatorStereoRig sim = paperRig();
  vpImagePoint l, r;
  // Behind the cameras.
  EXPECT_FALSE(sim.project(point3(0.0, 0.0, -2.0), l, r));
  EXPECT_FALSE(sim.isVisible(point3(0.0, 0.0, -2.0)));
  // Outside the images.
  EXPECT_FALSE(sim.project(point3(0.5, 0.0, 0.0), l, r));
  // A point imaged 5 px from the left border of the left image: visible without margin, not with 10 px.
  const double px = sim.getLeftCameraParameters().get_px();
  const vpHomogeneousMatrix wMl = sim.get_wMl();
  const double uTarget = 5.0;
  const Eigen::Vector3d lX((uTarget - 320.0) / px * 1.0, 0.0, 1.0);
  const Eigen::Matrix4d wMlE = toEigen<4, 4>(wMl);
  const Eigen::Vector3d wX = wMlE.topLeftCorner<3, 3>() * lX + wMlE.topRightCorner<3, 1>();
  const vpColVector X = point3(wX(0), wX(1), wX(2));
  ASSERT_TRUE(sim.project(X, l, r));
  EXPECT_NEAR(l.get_u(), uTarget, 1e-9);
  EXPECT_TRUE(sim.isVisible(X, 0.0));
  EXPECT_TRUE(sim.isVisible(X, 4.9));
  EXPECT_FALSE(sim.isVisible(X, 10.0));
  // Depth threshold: the left camera centre is at depth 0.
  EXPECT_FALSE(sim.isVisible(point3(-0.1, 0.0, -0.97), 0.0, 0.05));
}

TEST(SimulatorStereoRig, EpipolarConstraintHolds)
{
  const vpSimulatorStereoRig sim = vpSimulatorStereoRig::paperRig(point3(0.02, 0.03, 0.5), 1.0);
  const Eigen::Matrix3d F = toEigen<3, 3>(sim.getFundamentalMatrix());
  EXPECT_NEAR(F.norm(), 1.0, 1e-12);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(F);
  EXPECT_LT(svd.singularValues()(2), 1e-12 * svd.singularValues()(0)); // rank 2

  vpUniRand rng(20240611);
  const vpSimulatorStereoRig simAtOrigin = paperRig();
  double worstDistance = 0.0;
  std::vector<vpImagePoint> lefts, rights;
  for (int k = 0; k < 200; ++k) {
    vpColVector X = visiblePoint(simAtOrigin, rng);
    X[0] += 0.02;
    X[1] += 0.03;
    X[2] += 0.5;
    vpImagePoint l, r;
    ASSERT_TRUE(sim.project(X, l, r));
    const Eigen::Vector3d line = F * pixel(l);
    const double distance = std::fabs(pixel(r).dot(line)) / line.head<2>().norm();
    worstDistance = std::max(worstDistance, distance);
    // Relative algebraic error.
    EXPECT_LT(std::fabs(pixel(r).dot(F * pixel(l))), 1e-9 * pixel(r).norm() * (F * pixel(l)).norm());
    lefts.push_back(l);
    rights.push_back(r);
  }
  EXPECT_LT(worstDistance, 1e-7); // pixels
  // The constraint is selective: a wrong match is pixels away from its epipolar line.
  const Eigen::Vector3d line = F * pixel(lefts[0]);
  EXPECT_GT(std::fabs(pixel(rights[1]).dot(line)) / line.head<2>().norm(), 0.5);
  // The epipoles are the images of the other camera's centre.
  const vpHomogeneousMatrix wMr = sim.get_wMl() * sim.get_rMl().inverse();
  const Eigen::Vector4d lCr = leftCameraPoint(sim, point3(wMr[0][3], wMr[1][3], wMr[2][3]));
  const Eigen::Vector3d e = toEigen<3, 4>(sim.getLeftMetricProjection()) * lCr;
  EXPECT_LT((F * e).norm(), 1e-12 * e.norm());
}

TEST(SimulatorStereoRig, MetricProjectionsMatchProject)
{
  const vpSimulatorStereoRig sim = paperRig();
  const Eigen::Matrix<double, 3, 4> Pm = toEigen<3, 4>(sim.getLeftMetricProjection());
  const Eigen::Matrix<double, 3, 4> Pmp = toEigen<3, 4>(sim.getRightMetricProjection());
  EXPECT_LT((Pm.rightCols<1>()).norm(), 1e-15); // K [I | 0]
  vpUniRand rng(7);
  for (int k = 0; k < 100; ++k) {
    const vpColVector X = visiblePoint(sim, rng);
    vpImagePoint l, r;
    ASSERT_TRUE(sim.project(X, l, r));
    const Eigen::Vector4d N = leftCameraPoint(sim, X);
    const Eigen::Vector3d m = Pm * N;
    const Eigen::Vector3d mp = Pmp * N;
    EXPECT_GT(m(2), 0.0);
    EXPECT_GT(mp(2), 0.0);
    EXPECT_NEAR(m(0) / m(2), l.get_u(), 1e-9);
    EXPECT_NEAR(m(1) / m(2), l.get_v(), 1e-9);
    EXPECT_NEAR(mp(0) / mp(2), r.get_u(), 1e-9);
    EXPECT_NEAR(mp(1) / mp(2), r.get_v(), 1e-9);
  }
}

TEST(SimulatorStereoRig, ToCameraFrame)
{
  const vpSimulatorStereoRig sim = paperRig();
  const vpHomogeneousMatrix wT = vpSimulatorStereoRig::rotationAbout(point3(0.1, 0.2, 0.3), point3(1, 2, 3), 0.4) *
                                 vpSimulatorStereoRig::translationAlong(point3(0, 1, 1), 0.05);
  const Eigen::Matrix4d lT = toEigen<4, 4>(sim.toCameraFrame(wT));
  vpUniRand rng(5);
  for (int k = 0; k < 20; ++k) {
    const vpColVector X = visiblePoint(sim, rng);
    const vpColVector Y = vpSimulatorStereoRig::transform(wT, std::vector<vpColVector>(1, X))[0];
    EXPECT_LT((lT * leftCameraPoint(sim, X) - leftCameraPoint(sim, Y)).norm(), 1e-12);
  }
}

TEST(SimulatorStereoRig, RigidMotionsOfPointSets)
{
  const vpColVector p = point3(0.1, -0.2, 0.3);
  const vpColVector axis = point3(0.0, 0.0, 2.0); // not unit: normalised
  const vpHomogeneousMatrix T = vpSimulatorStereoRig::rotationAbout(p, axis, vpMath::rad(90.0));
  // Points on the axis are fixed; a point 1 m off the axis turns by 90 deg about it.
  std::vector<vpColVector> X;
  X.push_back(point3(0.1, -0.2, 5.0));
  X.push_back(point3(1.1, -0.2, 0.3));
  const std::vector<vpColVector> Y = vpSimulatorStereoRig::transform(T, X);
  EXPECT_LT((toEigen<3, 1>(Y[0]) - toEigen<3, 1>(X[0])).norm(), 1e-12);
  EXPECT_LT((toEigen<3, 1>(Y[1]) - Eigen::Vector3d(0.1, 0.8, 0.3)).norm(), 1e-12);
  // Homogeneous points keep their form.
  vpColVector Xh(4);
  Xh[0] = 2.2;
  Xh[1] = -0.4;
  Xh[2] = 0.6;
  Xh[3] = 2.0;
  const vpColVector Yh = vpSimulatorStereoRig::transform(T, std::vector<vpColVector>(1, Xh))[0];
  ASSERT_EQ(Yh.getRows(), 4u);
  EXPECT_LT(((toEigen<4, 1>(Yh)).hnormalized() - Eigen::Vector3d(0.1, 0.8, 0.3)).norm(), 1e-12);
  // Translation of 5 cm along a non-unit direction.
  const vpHomogeneousMatrix D = vpSimulatorStereoRig::translationAlong(point3(3.0, 0.0, 4.0), 0.05);
  EXPECT_NEAR(D[0][3], 0.03, 1e-15);
  EXPECT_NEAR(D[2][3], 0.04, 1e-15);
  EXPECT_TRUE(D.getRotationMatrix().isARotationMatrix());
}

TEST(SimulatorStereoRig, NoiseStatistics)
{
  const vpSimulatorStereoRig sim = paperRig();
  const vpColVector X = point3(0.02, -0.03, 0.05);
  vpImagePoint l0, r0;
  ASSERT_TRUE(sim.project(X, l0, r0));
  // The generator's own sigma (7) and mean (3) must not matter: only its stream is used.
  vpGaussRand noise(7.0, 3.0, 1234);
  const double sigma = 0.5;
  const int n = 10000;
  Eigen::Vector4d sum = Eigen::Vector4d::Zero();
  Eigen::Matrix4d sum2 = Eigen::Matrix4d::Zero();
  for (int k = 0; k < n; ++k) {
    vpImagePoint l, r;
    EXPECT_TRUE(sim.project(X, l, r, sigma, noise));
    const Eigen::Vector4d d(l.get_u() - l0.get_u(), l.get_v() - l0.get_v(), r.get_u() - r0.get_u(),
                            r.get_v() - r0.get_v());
    sum += d;
    sum2 += d * d.transpose();
  }
  const Eigen::Vector4d mean = sum / n;
  const Eigen::Matrix4d cov = sum2 / n - mean * mean.transpose();
  // Standard errors: mean sigma / sqrt(n) = 0.005 px, standard deviation about sigma / sqrt(2 n) = 0.0035 px,
  // correlation 1 / sqrt(n) = 0.01. Bounds at 5 standard errors: a wrong sigma, a bias or shared draws fail.
  for (int i = 0; i < 4; ++i) {
    EXPECT_LT(std::fabs(mean(i)), 5.0 * sigma / std::sqrt(n)) << "coordinate " << i;
    EXPECT_LT(std::fabs(std::sqrt(cov(i, i)) - sigma), 5.0 * sigma / std::sqrt(2.0 * n)) << "coordinate " << i;
    for (int j = 0; j < i; ++j) {
      EXPECT_LT(std::fabs(cov(i, j) / std::sqrt(cov(i, i) * cov(j, j))), 5.0 / std::sqrt(n));
    }
  }

  // Reproducible from the seed; another seed gives other draws; sigma = 0 gives the exact image.
  vpGaussRand a(1.0, 0.0, 99), b(1.0, 0.0, 99), c(1.0, 0.0, 100);
  vpImagePoint la, ra, lb, rb, lc, rc;
  sim.project(X, la, ra, sigma, a);
  sim.project(X, lb, rb, sigma, b);
  sim.project(X, lc, rc, sigma, c);
  EXPECT_DOUBLE_EQ(la.get_u(), lb.get_u());
  EXPECT_DOUBLE_EQ(rb.get_v(), ra.get_v());
  EXPECT_NE(la.get_u(), lc.get_u());
  vpImagePoint lz, rz;
  sim.project(X, lz, rz, 0.0, a);
  EXPECT_DOUBLE_EQ(lz.get_u(), l0.get_u());
  EXPECT_DOUBLE_EQ(rz.get_v(), r0.get_v());
}

TEST(SimulatorStereoRig, BadInputsThrow)
{
  const vpSimulatorStereoRig sim = paperRig();
  vpImagePoint l, r;
  vpGaussRand noise(1.0, 0.0, 1);
  expectThrowsCode([&]() { sim.project(vpColVector(2, 0.0), l, r); }, vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { sim.project(vpColVector(5, 1.0), l, r); }, vpProjectiveException::dimensionError);
  vpColVector nan = point3(0.0, std::numeric_limits<double>::quiet_NaN(), 1.0);
  expectThrowsCode([&]() { sim.project(nan, l, r); }, vpProjectiveException::nonFiniteValueError);
  vpColVector inf = point3(std::numeric_limits<double>::infinity(), 0.0, 1.0);
  expectThrowsCode([&]() { sim.isVisible(inf); }, vpProjectiveException::nonFiniteValueError);
  vpColVector atInfinity(4, 0.0);
  atInfinity[2] = 1.0;
  expectThrowsCode([&]() { sim.project(atInfinity, l, r); }, vpProjectiveException::pointAtInfinityError);
  expectThrowsCode([&]() { sim.project(point3(0, 0, 0), l, r, -1.0, noise); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { sim.project(point3(0, 0, 0), l, r, std::nan(""), noise); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { sim.toCameraFrame(vpMatrix(3, 3, 0.0)); }, vpProjectiveException::dimensionError);
  vpMatrix T(4, 4, 0.0);
  T[0][0] = std::numeric_limits<double>::infinity();
  expectThrowsCode([&]() { sim.toCameraFrame(T); }, vpProjectiveException::nonFiniteValueError);
  expectThrowsCode([&]() { vpSimulatorStereoRig::rotationAbout(point3(0, 0, 0), point3(0, 0, 0), 1.0); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { vpSimulatorStereoRig::rotationAbout(vpColVector(2, 0.0), point3(0, 0, 1), 1.0); },
                   vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { vpSimulatorStereoRig::translationAlong(point3(0, 0, 0), 1.0); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { vpSimulatorStereoRig::transform(vpHomogeneousMatrix(), {vpColVector(2, 0.0)}); },
                   vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { vpSimulatorStereoRig::paperRig(point3(0, 0, 0), -1.0); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { vpSimulatorStereoRig::paperRig(vpColVector(4, 0.0), 1.0); },
                   vpProjectiveException::dimensionError);
  // Constructor: distortion, non-positive focal length, zero baseline, non-rigid pose, empty image.
  vpCameraParameters distorted;
  distorted.initPersProjWithDistortion(800, 800, 320, 240, 0.1, -0.1);
  vpCameraParameters cam = vpSimulatorStereoRig::paperCameraParameters();
  vpHomogeneousMatrix rMl;
  rMl[0][3] = -0.2;
  expectThrowsCode([&]() { vpSimulatorStereoRig(distorted, cam, rMl, vpHomogeneousMatrix(), 640, 480); },
                   vpProjectiveException::invalidValueError);
  vpCameraParameters flat;
  flat.initPersProjWithoutDistortion(-800, 800, 320, 240);
  expectThrowsCode([&]() { vpSimulatorStereoRig(cam, flat, rMl, vpHomogeneousMatrix(), 640, 480); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { vpSimulatorStereoRig(cam, cam, vpHomogeneousMatrix(), vpHomogeneousMatrix(), 640, 480); },
                   vpProjectiveException::degenerateConfigurationError);
  vpHomogeneousMatrix sheared = rMl;
  sheared[0][1] = 0.5;
  expectThrowsCode([&]() { vpSimulatorStereoRig(cam, cam, sheared, vpHomogeneousMatrix(), 640, 480); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { vpSimulatorStereoRig(cam, cam, rMl, vpHomogeneousMatrix(), 0, 480); },
                   vpProjectiveException::invalidValueError);
}
