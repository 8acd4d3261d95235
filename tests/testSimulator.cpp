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
  Tests of the metric simulator (vpSimulatorStereoRig, vpSimulatorArm): the ground truth every other suite and the
  tutorials rely on. Every random number comes from a seeded vpUniRand or vpGaussRand.
*/

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/robot/vpViper850.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
using vpProjectiveTest::expm; // independent reference: a scaled and squared Taylor series
using vpProjectiveTest::pixel;
using vpProjectiveTest::point3;
using vpProjectiveTest::toEigen; // checks the size of the ViSP array

const double kTrialDeg[6] = {30.0, 20.0, 30.0, 40.0, 60.0, 60.0}; // the paper's trial motions

//! A world point drawn uniformly in a box around the fixation point, visible in both images of \e sim.
vpColVector visiblePoint(const vpSimulatorStereoRig &sim, vpUniRand &rng)
{
  for (;;) {
    const vpColVector X = point3(rng.uniform(-0.15, 0.15), rng.uniform(-0.12, 0.12), rng.uniform(-0.2, 0.2));
    if (sim.isVisible(X, 5.0)) {
      return X;
    }
  }
}

//! Left-camera homogeneous coordinates N = (lX, 1) of a world point.
Eigen::Vector4d leftCameraPoint(const vpSimulatorStereoRig &sim, const vpColVector &wX)
{
  return toEigen<4, 4>(sim.get_wMl().inverse()) * toEigen<3, 1>(wX).homogeneous();
}

//! Random joint values within the arm's limits.
vpColVector randomJoints(const vpSimulatorArm &arm, vpUniRand &rng)
{
  vpColVector q(arm.getNumberOfJoints());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    q[i] = rng.uniform(arm.getJointMin()[i], arm.getJointMax()[i]);
  }
  return q;
}

//! Checks the product of exponentials (35): wMt(q) = exp(q0 T0) ... exp(q_{n-1} T_{n-1}) wMt(0).
void expectProductOfExponentials(const vpSimulatorArm &arm, vpUniRand &rng, int trials)
{
  const unsigned int n = arm.getNumberOfJoints();
  const Eigen::Matrix4d wMt0 = toEigen<4, 4>(arm.get_wMt(vpColVector(n, 0.0)));
  for (int k = 0; k < trials; ++k) {
    const vpColVector q = randomJoints(arm, rng);
    Eigen::Matrix4d poe = Eigen::Matrix4d::Identity();
    for (unsigned int i = 0; i < n; ++i) {
      poe = poe * expm(q[i] * toEigen<4, 4>(arm.getTwist(i)));
    }
    poe = poe * wMt0;
    const Eigen::Matrix4d wMt = toEigen<4, 4>(arm.get_wMt(q));
    EXPECT_LT((poe - wMt).cwiseAbs().maxCoeff(), 1e-12) << "q = " << q.t();
  }
}

template <typename F> void expectThrowsCode(F f, int code)
{
  try {
    f();
    ADD_FAILURE() << "no vpProjectiveException thrown";
  } catch (const vpProjectiveException &e) {
    EXPECT_EQ(e.getCode(), code) << e.getStringMessage();
    EXPECT_FALSE(e.getStringMessage().empty());
  }
}

vpSimulatorArm paperArm()
{
  return vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
}

vpSimulatorStereoRig paperRig()
{
  return vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
}
} // namespace

// ---------------------------------------------------------------------------------------------------------------
// Stereo rig
// ---------------------------------------------------------------------------------------------------------------

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

TEST(SimulatorStereoRig, ProjectiveToEuclideanOfTrueFundamentalMatrix)
{
  const vpSimulatorStereoRig sim = paperRig();
  vpProjectiveStereoRig rig;
  rig.setFundamentalMatrix(sim.getFundamentalMatrix());
  double residual = 1.0;
  const Eigen::Matrix4d H = toEigen<4, 4>(sim.getProjectiveToEuclidean(rig, residual));
  EXPECT_LT(residual, 1e-8); // pixels
  EXPECT_NEAR(std::fabs(H.determinant()), 1.0, 1e-9);
  const Eigen::Matrix<double, 3, 4> P = toEigen<3, 4>(rig.getLeftProjection());
  const Eigen::Matrix<double, 3, 4> Pp = toEigen<3, 4>(rig.getRightProjection());
  const Eigen::Matrix4d Hinv = H.inverse();

  vpUniRand rng(11);
  for (int k = 0; k < 100; ++k) {
    const vpColVector X = visiblePoint(sim, rng);
    vpImagePoint l, r;
    ASSERT_TRUE(sim.project(X, l, r));
    const Eigen::Vector4d M = Hinv * leftCameraPoint(sim, X);
    const Eigen::Vector3d m = P * M;
    const Eigen::Vector3d mp = Pp * M;
    EXPECT_GT(m(2), 0.0); // sign convention: K[I|0] H = s P with s > 0
    EXPECT_LT((m.head<2>() / m(2) - pixel(l).head<2>()).norm(), 1e-9 * pixel(l).norm());
    EXPECT_LT((mp.head<2>() / mp(2) - pixel(r).head<2>()).norm(), 1e-9 * pixel(r).norm());
  }
  // Any scale of F gives the same frame, hence the same H.
  vpProjectiveStereoRig rig2;
  rig2.setFundamentalMatrix(-3.0 * sim.getFundamentalMatrix());
  const Eigen::Matrix4d H2 = toEigen<4, 4>(sim.getProjectiveToEuclidean(rig2));
  EXPECT_LT((H2 - H).norm(), 1e-9 * H.norm());
}

TEST(SimulatorStereoRig, ProjectiveToEuclideanOfEstimatedFundamentalMatrix)
{
  // F estimated from noisy matches: no homography maps the frame exactly onto the metric cameras; the best one
  // reproduces the true images to about the noise level, and the residual reports the (small) mismatch.
  const vpSimulatorStereoRig sim = paperRig();
  vpUniRand rng(3);
  vpGaussRand noise(1.0, 0.0, 4);
  std::vector<vpColVector> points;
  std::vector<vpImagePoint> left, right;
  for (int k = 0; k < 60; ++k) {
    points.push_back(visiblePoint(sim, rng));
  }
  const double sigma = 0.5;
  ASSERT_TRUE(sim.project(points, left, right, sigma, noise));
  vpProjectiveStereoRig rig;
  rig.estimate(left, right);
  double residual = 0.0;
  const Eigen::Matrix4d H = toEigen<4, 4>(sim.getProjectiveToEuclidean(rig, residual));
  EXPECT_GT(residual, 1e-6);
  EXPECT_LT(residual, sim.getMaxProjectiveToEuclideanResidual());
  EXPECT_NEAR(sim.getMaxProjectiveToEuclideanResidual(), 16.0, 1e-12);
  const Eigen::Matrix<double, 3, 4> P = toEigen<3, 4>(rig.getLeftProjection());
  const Eigen::Matrix<double, 3, 4> Pp = toEigen<3, 4>(rig.getRightProjection());
  const Eigen::Matrix4d Hinv = H.inverse();
  double sumLeft2 = 0.0, sumRight2 = 0.0;
  for (size_t k = 0; k < points.size(); ++k) {
    vpImagePoint l, r;
    ASSERT_TRUE(sim.project(points[k], l, r));
    const Eigen::Vector4d M = Hinv * leftCameraPoint(sim, points[k]);
    const Eigen::Vector3d m = P * M;
    const Eigen::Vector3d mp = Pp * M;
    sumLeft2 += (m.head<2>() / m(2) - pixel(l).head<2>()).squaredNorm();
    sumRight2 += (mp.head<2>() / mp(2) - pixel(r).head<2>()).squaredNorm();
  }
  // The left cameras are matched exactly; the right images of the true points are off by about the noise.
  EXPECT_LT(std::sqrt(sumLeft2 / points.size()), 1e-9);
  EXPECT_LT(std::sqrt(sumRight2 / points.size()), 4.0 * sigma);
}

TEST(SimulatorStereoRig, ProjectiveToEuclideanRejectsForeignFrames)
{
  const vpSimulatorStereoRig sim = paperRig();
  vpProjectiveStereoRig rig;
  expectThrowsCode([&]() { sim.getProjectiveToEuclidean(rig); }, vpProjectiveException::notInitializedError);

  // The fundamental matrix of another rig: a vertical baseline (epipolar lines across those of the paper's rig).
  vpHomogeneousMatrix rMl(0.0, -0.2, 0.0, vpMath::rad(8.0), 0.0, 0.0);
  const vpSimulatorStereoRig other(sim.getLeftCameraParameters(), sim.getRightCameraParameters(), rMl,
                                   vpHomogeneousMatrix(), 640, 480);
  rig.setFundamentalMatrix(other.getFundamentalMatrix());
  expectThrowsCode([&]() { sim.getProjectiveToEuclidean(rig); }, vpProjectiveException::invalidValueError);
  // The other rig itself accepts its frame.
  double residual = 1.0;
  other.getProjectiveToEuclidean(rig, residual);
  EXPECT_LT(residual, 1e-8);
  // A random rank-2 matrix.
  Eigen::Matrix3d F;
  F << 0.3, -0.1, 0.2, 0.5, 0.4, -0.7, 0.8, 0.3, -0.5;
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(F, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Vector3d s = svd.singularValues();
  s(2) = 0.0;
  F = svd.matrixU() * s.asDiagonal() * svd.matrixV().transpose();
  vpMatrix Fv(3, 3);
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      Fv[i][j] = F(i, j);
    }
  }
  rig.setFundamentalMatrix(Fv);
  expectThrowsCode([&]() { sim.getProjectiveToEuclidean(rig); }, vpProjectiveException::invalidValueError);
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

// ---------------------------------------------------------------------------------------------------------------
// Arm
// ---------------------------------------------------------------------------------------------------------------

TEST(SimulatorArm, ProductOfExponentialsPuma)
{
  vpUniRand rng(42);
  expectProductOfExponentials(paperArm(), rng, 50);
  // With another base pose.
  const vpHomogeneousMatrix wMb(0.3, -0.2, 0.5, 0.1, -0.4, 0.7);
  expectProductOfExponentials(vpSimulatorArm::puma(wMb), rng, 20);
}

TEST(SimulatorArm, ProductOfExponentialsViper850)
{
  vpUniRand rng(43);
  expectProductOfExponentials(vpSimulatorArm::viper850(vpHomogeneousMatrix(0.1, 0.2, 0.3, 0.0, 0.5, 0.0)), rng, 50);
}

TEST(SimulatorArm, ProductOfExponentialsWithPrismaticJoint)
{
  // A SCARA-like R R P R chain.
  std::vector<vpSimulatorArm::vpDHRow> dh(4);
  dh[0] = {vpSimulatorArm::REVOLUTE, 0.2, 0.4, 0.35, 0.0};
  dh[1] = {vpSimulatorArm::REVOLUTE, -0.3, 0.0, 0.25, M_PI};
  dh[2] = {vpSimulatorArm::PRISMATIC, 0.0, 0.1, 0.0, 0.0};
  dh[3] = {vpSimulatorArm::REVOLUTE, 0.5, 0.05, 0.0, 0.0};
  const vpSimulatorArm arm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                           vpHomogeneousMatrix(0.0, 0.0, 1.0, 0.3, 0.0, 0.0));
  EXPECT_EQ(arm.getJointType(2), vpSimulatorArm::PRISMATIC);
  EXPECT_NEAR(arm.getJointMax()[2], 0.5, 1e-15);
  EXPECT_NEAR(arm.getJointMax()[0], vpMath::rad(170.0), 1e-15);
  vpUniRand rng(44);
  expectProductOfExponentials(arm, rng, 50);
  // The prismatic twist is a unit translation, the revolute ones unit rotations about lines.
  const Eigen::Matrix4d Tp = toEigen<4, 4>(arm.getTwist(2));
  const Eigen::Matrix3d Wp = Tp.topLeftCorner<3, 3>();
  const Eigen::Vector3d vp = Tp.topRightCorner<3, 1>();
  EXPECT_LT(Wp.norm(), 1e-15);
  EXPECT_NEAR(vp.norm(), 1.0, 1e-12);
}

TEST(SimulatorArm, TwistsAreRotationsAboutJointAxes)
{
  const vpSimulatorArm arm = paperArm();
  const vpColVector q0(6, 0.0);
  for (unsigned int i = 0; i < 6; ++i) {
    const Eigen::Matrix4d T = toEigen<4, 4>(arm.getTwist(i));
    const Eigen::Matrix3d W = T.topLeftCorner<3, 3>();
    EXPECT_LT((W + W.transpose()).norm(), 1e-15); // skew
    EXPECT_LT(T.bottomRows<1>().norm(), 1e-15);
    const Eigen::Vector3d w(W(2, 1), W(0, 2), W(1, 0));
    const Eigen::Vector3d v = T.block<3, 1>(0, 3);
    EXPECT_NEAR(w.norm(), 1.0, 1e-12);
    EXPECT_NEAR(w.dot(v), 0.0, 1e-12); // a pure rotation (zero pitch)
    // Moving joint i alone rotates the tool about that line: the displacement's rotation axis is w.
    vpColVector q(6, 0.0);
    q[i] = 0.3;
    const vpHomogeneousMatrix D = arm.getDisplacement(q);
    const vpThetaUVector tu(D.getRotationMatrix());
    EXPECT_NEAR(tu.getTheta(), 0.3, 1e-12);
    EXPECT_LT((Eigen::Vector3d(tu[0], tu[1], tu[2]) / 0.3 - w).norm(), 1e-12);
  }
  // Joint 0 of puma() turns about the base's z axis.
  const vpHomogeneousMatrix wMb = arm.get_wMb();
  const Eigen::Matrix4d T0 = toEigen<4, 4>(arm.getTwist(0));
  EXPECT_LT((Eigen::Vector3d(T0(2, 1), T0(0, 2), T0(1, 0)) - Eigen::Vector3d(wMb[0][2], wMb[1][2], wMb[2][2])).norm(),
            1e-12);
}

TEST(SimulatorArm, DisplacementMovesMarkers)
{
  const vpSimulatorArm arm = paperArm();
  vpUniRand rng(8);
  const std::vector<vpColVector> m0 = arm.getMarkers(vpColVector(6, 0.0));
  ASSERT_EQ(m0.size(), 7u);
  for (int k = 0; k < 10; ++k) {
    const vpColVector q = randomJoints(arm, rng);
    const std::vector<vpColVector> moved = vpSimulatorStereoRig::transform(arm.getDisplacement(q), m0);
    const std::vector<vpColVector> mq = arm.getMarkers(q);
    for (size_t j = 0; j < m0.size(); ++j) {
      EXPECT_LT((toEigen<3, 1>(moved[j]) - toEigen<3, 1>(mq[j])).norm(), 1e-12);
    }
    // Markers are rigidly attached: wMt(q) tX.
    const Eigen::Matrix4d wMt = toEigen<4, 4>(arm.get_wMt(q));
    const vpColVector &tX = arm.getToolMarkers()[3];
    EXPECT_LT(
        (wMt.topLeftCorner<3, 3>() * toEigen<3, 1>(tX) + wMt.topRightCorner<3, 1>() - toEigen<3, 1>(mq[3])).norm(),
        1e-12);
  }
}

TEST(SimulatorArm, Viper850MatchesVispModel)
{
  // vpViper::get_fMe() ignores the joint 5-6 coupling (it applies to motor positions only), so the comparison holds
  // for every q, including q5 != 0.
  const vpSimulatorArm arm = vpSimulatorArm::viper850(vpHomogeneousMatrix());
  vpViper850 viper;
  EXPECT_LT((toEigen<6, 1>(arm.getJointMin()) - toEigen<6, 1>(viper.getJointMin())).norm(), 1e-15);
  EXPECT_LT((toEigen<6, 1>(arm.getJointMax()) - toEigen<6, 1>(viper.getJointMax())).norm(), 1e-15);
  vpUniRand rng(850);
  for (int k = 0; k < 100; ++k) {
    const vpColVector q = randomJoints(arm, rng);
    vpHomogeneousMatrix fMe;
    viper.get_fMe(q, fMe);
    EXPECT_LT((toEigen<4, 4>(arm.get_wMe(q)) - toEigen<4, 4>(fMe)).cwiseAbs().maxCoeff(), 1e-12) << "q = " << q.t();
  }
  // With a base pose and the gripper mount.
  const vpHomogeneousMatrix wMb(0.5, 0.0, -0.2, 0.0, 0.0, 1.0);
  const vpSimulatorArm placed = vpSimulatorArm::viper850(wMb);
  const vpColVector q = randomJoints(placed, rng);
  vpHomogeneousMatrix fMe;
  viper.get_fMe(q, fMe);
  EXPECT_LT((toEigen<4, 4>(placed.get_wMt(q)) - toEigen<4, 4>(wMb * fMe * vpSimulatorArm::gripperMount()))
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}

TEST(SimulatorArm, GripperMarkersNoFourCoplanar)
{
  const std::vector<vpColVector> m = vpSimulatorArm::gripperMarkers();
  ASSERT_EQ(m.size(), 7u);
  double minDet = std::numeric_limits<double>::infinity();
  double minDistance = std::numeric_limits<double>::infinity();
  int subsets = 0;
  for (int a = 0; a < 7; ++a) {
    for (int b = a + 1; b < 7; ++b) {
      for (int c = b + 1; c < 7; ++c) {
        for (int d = c + 1; d < 7; ++d) {
          const int id[4] = {a, b, c, d};
          Eigen::Matrix4d M;
          for (int k = 0; k < 4; ++k) {
            M.block<3, 1>(0, k) = toEigen<3, 1>(m[id[k]]);
            M(3, k) = 1.0;
          }
          minDet = std::min(minDet, std::fabs(M.determinant())); // 6 x tetrahedron volume, m^3
          for (int k = 0; k < 4; ++k) {
            Eigen::Vector3d p[3];
            int j = 0;
            for (int l = 0; l < 4; ++l) {
              if (l != k) {
                p[j++] = M.block<3, 1>(0, l);
              }
            }
            const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
            minDistance = std::min(minDistance, std::fabs(n.dot(M.block<3, 1>(0, k) - p[0])));
          }
          ++subsets;
        }
      }
    }
  }
  EXPECT_EQ(subsets, 35);
  EXPECT_GT(minDet, 1e-5);
  EXPECT_GT(minDistance, 0.008); // every marker at least 8 mm off the plane of any other three
  // All within the 10 cm gripper.
  for (size_t k = 0; k < m.size(); ++k) {
    EXPECT_LE((toEigen<3, 1>(m[k])).cwiseAbs().maxCoeff(), 0.05 + 1e-12);
  }
  // Markers 0-2 share the front face y = -2 cm; all others are behind it.
  for (size_t k = 0; k < m.size(); ++k) {
    if (k < 3) {
      EXPECT_NEAR(m[k][1], -0.02, 1e-15);
    } else {
      EXPECT_GT(m[k][1], -0.02 + 1e-3);
    }
  }
}

TEST(SimulatorArm, PaperSetupZeroReferenceInView)
{
  const vpSimulatorArm arm = paperArm();
  const vpSimulatorStereoRig sim = paperRig();
  const vpColVector q0(6, 0.0);
  // The gripper's centre is the fixation point (world origin).
  const vpHomogeneousMatrix wMt0 = arm.get_wMt(q0);
  EXPECT_LT(wMt0.getTranslationVector().frobeniusNorm(), 1e-12);
  const std::vector<vpColVector> m = arm.getMarkers(q0);
  for (size_t k = 0; k < m.size(); ++k) {
    EXPECT_TRUE(sim.isVisible(m[k], 10.0)) << "marker " << k;
  }
  // The front face (markers 0-2) looks at both cameras: its outward normal points to each camera centre.
  const Eigen::Vector3d n = -Eigen::Vector3d(wMt0[0][1], wMt0[1][1], wMt0[2][1]);
  const vpHomogeneousMatrix wMr = sim.get_wMl() * sim.get_rMl().inverse();
  const Eigen::Vector3d centres[2] = {Eigen::Vector3d(sim.get_wMl()[0][3], sim.get_wMl()[1][3], sim.get_wMl()[2][3]),
                                      Eigen::Vector3d(wMr[0][3], wMr[1][3], wMr[2][3])};
  for (int c = 0; c < 2; ++c) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d toCamera = (centres[c] - toEigen<3, 1>(m[k])).normalized();
      EXPECT_GT(n.dot(toCamera), std::cos(vpMath::rad(35.0))) << "camera " << c << " marker " << k;
    }
  }
  // The base is below the gripper (world +Y is down) and the arm does not reach behind the rig.
  EXPECT_GT(arm.get_wMb()[1][3], 1.0);
  EXPECT_GT(arm.get_wMb()[2][3], -0.5);
}

TEST(SimulatorArm, PaperTrialMotionsStayInView)
{
  // Each joint alone moves by the paper's trial amount both ways, continuously: all markers stay 10 px inside both
  // images. Just beyond the documented reach of joints 1 and 2 they leave, which shows that the check is tight.
  const vpSimulatorArm arm = paperArm();
  const vpSimulatorStereoRig sim = paperRig();
  auto allVisible = [&](const vpColVector &q) {
    const std::vector<vpColVector> m = arm.getMarkers(q);
    for (size_t k = 0; k < m.size(); ++k) {
      if (!sim.isVisible(m[k], 10.0)) {
        return false;
      }
    }
    return true;
  };
  for (unsigned int j = 0; j < 6; ++j) {
    for (int sign = -1; sign <= 1; sign += 2) {
      for (double a = 0.0; a <= kTrialDeg[j] + 1e-9; a += 0.5) {
        vpColVector q(6, 0.0);
        q[j] = sign * vpMath::rad(a);
        EXPECT_TRUE(allVisible(q)) << "joint " << j << " at " << sign * a << " deg";
      }
    }
  }
  const double beyond[4][2] = {{1, -23.0}, {1, 35.0}, {2, -48.0}, {2, 35.0}};
  for (int k = 0; k < 4; ++k) {
    vpColVector q(6, 0.0);
    q[static_cast<unsigned int>(beyond[k][0])] = vpMath::rad(beyond[k][1]);
    EXPECT_FALSE(allVisible(q)) << "joint " << beyond[k][0] << " at " << beyond[k][1] << " deg";
  }
}

TEST(SimulatorArm, IntegrateClampsToJointLimits)
{
  const vpSimulatorArm arm = paperArm();
  const double limit = vpMath::rad(170.0);
  vpColVector q(6, 0.0);
  q[0] = limit - 0.01;
  q[1] = -limit + 0.01;
  q[2] = 0.2;
  vpColVector qdot(6, 0.0);
  qdot[0] = 1.0;
  qdot[1] = -1.0;
  qdot[2] = -0.5;
  qdot[3] = 0.25;
  const vpColVector next = arm.integrate(q, qdot, 0.1);
  EXPECT_DOUBLE_EQ(next[0], limit);
  EXPECT_DOUBLE_EQ(next[1], -limit);
  EXPECT_NEAR(next[2], 0.15, 1e-15);
  EXPECT_NEAR(next[3], 0.025, 1e-15);
  EXPECT_DOUBLE_EQ(next[4], 0.0);
  // Viper850 limits come from vpViper850.
  const vpSimulatorArm viper = vpSimulatorArm::viper850(vpHomogeneousMatrix());
  const vpColVector fast(6, 100.0);
  const vpColVector top = viper.integrate(vpColVector(6, 0.0), fast, 1.0);
  const vpColVector bottom = viper.integrate(vpColVector(6, 0.0), -1.0 * fast, 1.0);
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(top[i], vpViper850().getJointMax()[i]);
    EXPECT_DOUBLE_EQ(bottom[i], vpViper850().getJointMin()[i]);
  }
  // Custom limits.
  vpSimulatorArm custom = arm;
  custom.setJointLimits(vpColVector(6, -0.1), vpColVector(6, 0.1));
  EXPECT_DOUBLE_EQ(custom.integrate(vpColVector(6, 0.0), fast, 1.0)[5], 0.1);
}

TEST(SimulatorArm, BadInputsThrow)
{
  const vpSimulatorArm arm = paperArm();
  expectThrowsCode([&]() { arm.get_wMt(vpColVector(5, 0.0)); }, vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.getMarkers(vpColVector(7, 0.0)); }, vpProjectiveException::dimensionError);
  vpColVector nan(6, 0.0);
  nan[3] = std::numeric_limits<double>::quiet_NaN();
  expectThrowsCode([&]() { arm.get_wMt(nan); }, vpProjectiveException::nonFiniteValueError);
  expectThrowsCode([&]() { arm.getDisplacement(nan); }, vpProjectiveException::nonFiniteValueError);
  expectThrowsCode([&]() { arm.getTwist(6); }, vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.getJointType(6); }, vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), vpColVector(3, 0.0), 0.1); },
                   vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), nan, 0.1); }, vpProjectiveException::nonFiniteValueError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), vpColVector(6, 0.0), -0.1); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), vpColVector(6, 0.0), std::nan("")); },
                   vpProjectiveException::invalidValueError);
  vpSimulatorArm copy = arm;
  expectThrowsCode([&]() { copy.setJointLimits(vpColVector(6, 1.0), vpColVector(6, -1.0)); },
                   vpProjectiveException::invalidValueError);

  const std::vector<vpColVector> markers = vpSimulatorArm::gripperMarkers();
  const vpHomogeneousMatrix I;
  expectThrowsCode([&]() { vpSimulatorArm(std::vector<vpSimulatorArm::vpDHRow>(), I, markers, I); },
                   vpProjectiveException::dimensionError);
  std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::pumaTable();
  dh[2].a = std::numeric_limits<double>::infinity();
  expectThrowsCode([&]() { vpSimulatorArm(dh, I, markers, I); }, vpProjectiveException::nonFiniteValueError);
  std::vector<vpColVector> badMarkers = markers;
  badMarkers[4] = vpColVector(4, 1.0);
  expectThrowsCode([&]() { vpSimulatorArm(vpSimulatorArm::pumaTable(), I, badMarkers, I); },
                   vpProjectiveException::dimensionError);
  vpHomogeneousMatrix notRigid;
  notRigid[0][0] = 2.0;
  expectThrowsCode([&]() { vpSimulatorArm(vpSimulatorArm::pumaTable(), I, markers, notRigid); },
                   vpProjectiveException::invalidValueError);
}

TEST(Simulator, BadInputsNameTheProblem)
{
  // The ground-truth classes are public API too: beyond the codes checked above, the construction and the settings
  // reject bad input with a message naming the problem.
  using vpProjectiveTest::throwsProjective;
  const int dimension = vpProjectiveException::dimensionError, nonFinite = vpProjectiveException::nonFiniteValueError,
            invalid = vpProjectiveException::invalidValueError;
  const vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  vpColVector nan(6, 0.0);
  nan[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { arm.getMarkers(nan); }, nonFinite, "contains NaN or infinity"));
  EXPECT_TRUE(
      throwsProjective([&] { arm.integrate(vpColVector(6, 0.0), vpColVector(6, 0.0), -1.0); }, invalid, "time step"));
  vpSimulatorArm limited = arm;
  vpColVector qmin(6, 0.0), qmax(6, 1.0);
  qmin[3] = 2.0;
  EXPECT_TRUE(throwsProjective([&] { limited.setJointLimits(qmin, qmax); }, invalid, "joint 3 has qmin"));
  std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::pumaTable();
  dh[1].a = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorArm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(), vpHomogeneousMatrix());
      },
      nonFinite, "Denavit-Hartenberg row 1"));
  std::vector<vpColVector> markers = vpSimulatorArm::gripperMarkers();
  markers[4] = vpColVector(2, 0.0);
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorArm(vpSimulatorArm::pumaTable(), vpSimulatorArm::gripperMount(), markers, vpHomogeneousMatrix());
      },
      dimension, "marker 4 must be a 3x1 point"));

  const vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpCameraParameters bad(-100.0, 100.0, 320.0, 240.0);
  EXPECT_TRUE(throwsProjective(
      [&] { vpSimulatorStereoRig(bad, rig.getRightCameraParameters(), rig.get_rMl(), rig.get_wMl(), 640, 480); },
      invalid, "focal lengths in pixels must be positive"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorStereoRig(rig.getLeftCameraParameters(), rig.getRightCameraParameters(), vpHomogeneousMatrix(),
                             rig.get_wMl(), 640, 480);
      },
      vpProjectiveException::degenerateConfigurationError, "non-zero baseline"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorStereoRig(rig.getLeftCameraParameters(), rig.getRightCameraParameters(), rig.get_rMl(),
                             rig.get_wMl(), 0, 480);
      },
      invalid, "image size is zero"));
}
