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
  Tests of vpSimulatorMarkerRenderer: rendered blobs against the rig's projections (centroids, areas), occlusion,
  noise statistics, seeded determinism, and the rejection of bad settings.
*/

#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorMarkerRenderer.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{

const vpSimulatorStereoRig kRig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);

//! Grey-level centroid and area (in covered pixels) of the blob around \e ip, background subtracted.
void blobMoments(const vpImage<unsigned char> &I, const vpImagePoint &ip, double background, double contrast,
                 vpImagePoint &centroid, double &area)
{
  double s = 0.0, su = 0.0, sv = 0.0;
  const int r = 14;
  for (int i = static_cast<int>(ip.get_i()) - r; i <= static_cast<int>(ip.get_i()) + r; ++i) {
    for (int j = static_cast<int>(ip.get_j()) - r; j <= static_cast<int>(ip.get_j()) + r; ++j) {
      const double w = I[i][j] - background;
      s += w;
      su += w * j;
      sv += w * i;
    }
  }
  centroid.set_uv(su / s, sv / s);
  area = s / contrast;
}

std::vector<vpColVector> gripperMarkers()
{
  return vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()).getMarkers(vpColVector(6, 0.0));
}
} // namespace

TEST(SimulatorMarkerRenderer, CentroidsAreTheProjectionsWithoutNoise)
{
  vpSimulatorMarkerRenderer renderer(kRig, 1);
  renderer.setNoise(0.0);
  const std::vector<vpColVector> X = gripperMarkers();
  vpImage<unsigned char> Il, Ir;
  renderer.render(X, Il, Ir);
  ASSERT_EQ(Il.getWidth(), kRig.getWidth());
  ASSERT_EQ(Ir.getHeight(), kRig.getHeight());
  double worst = 0.0;
  for (const vpColVector &wX : X) {
    vpImagePoint l, r;
    ASSERT_TRUE(kRig.project(wX, l, r));
    for (int c = 0; c < 2; ++c) {
      vpImagePoint centroid;
      double area;
      blobMoments(c == 0 ? Il : Ir, c == 0 ? l : r, 30.0, 190.0, centroid, area);
      worst = std::max(worst, vpImagePoint::distance(centroid, c == 0 ? l : r));
    }
  }
  // 8-bit quantisation of the blurred edge only: the silhouette's centre is within 0.01 px of the projection.
  EXPECT_LT(worst, 0.03);
}

TEST(SimulatorMarkerRenderer, CentroidsWithNoiseAndBlur)
{
  vpSimulatorMarkerRenderer renderer(kRig, 7);
  renderer.setBlur(1.5);
  renderer.setNoise(4.0);
  const std::vector<vpColVector> X = gripperMarkers();
  vpImage<unsigned char> Il, Ir;
  renderer.render(X, Il, Ir);
  double sum = 0.0;
  for (const vpColVector &wX : X) {
    vpImagePoint l, r, centroid;
    double area;
    kRig.project(wX, l, r);
    blobMoments(Il, l, 30.0, 190.0, centroid, area);
    sum += vpImagePoint::sqrDistance(centroid, l);
  }
  EXPECT_LT(std::sqrt(sum / X.size()), 0.15);
}

TEST(SimulatorMarkerRenderer, SilhouetteSizeFollowsDepth)
{
  vpSimulatorMarkerRenderer renderer(kRig, 1);
  renderer.setNoise(0.0);
  renderer.setMarkerRadius(0.004);
  const vpHomogeneousMatrix wMl = kRig.get_wMl();
  for (double depth : {0.6, 1.0, 1.5}) {
    // A ball on the left camera's optical axis.
    const vpColVector wX =
        point3(wMl[0][2] * depth + wMl[0][3], wMl[1][2] * depth + wMl[1][3], wMl[2][2] * depth + wMl[2][3]);
    vpImage<unsigned char> Il, Ir;
    renderer.render(std::vector<vpColVector>(1, wX), Il, Ir);
    vpImagePoint centroid;
    double area;
    blobMoments(Il, vpImagePoint(240, 320), 30.0, 190.0, centroid, area);
    const double rho = renderer.getImageRadius(depth);
    EXPECT_NEAR(area, M_PI * rho * rho, 0.01 * M_PI * rho * rho) << "depth " << depth;
    EXPECT_LT(vpImagePoint::distance(centroid, vpImagePoint(240, 320)), 0.01);
  }
}

TEST(SimulatorMarkerRenderer, NearerBallHidesFartherOne)
{
  vpSimulatorMarkerRenderer renderer(kRig, 1);
  renderer.setNoise(0.0);
  const vpHomogeneousMatrix wMl = kRig.get_wMl();
  const vpColVector nearBall =
      point3(wMl[0][2] * 0.9 + wMl[0][3], wMl[1][2] * 0.9 + wMl[1][3], wMl[2][2] * 0.9 + wMl[2][3]);
  const vpColVector farBall =
      point3(wMl[0][2] * 1.2 + wMl[0][3], wMl[1][2] * 1.2 + wMl[1][3], wMl[2][2] * 1.2 + wMl[2][3]);
  vpImage<unsigned char> Inear, Iboth, Ir;
  renderer.render(std::vector<vpColVector>(1, nearBall), Inear, Ir);
  renderer.render({farBall, nearBall}, Iboth, Ir);
  EXPECT_TRUE(Inear == Iboth); // in the left image the farther ball is entirely behind the nearer one
}

TEST(SimulatorMarkerRenderer, BallsBehindTheCameraAreNotImaged)
{
  vpSimulatorMarkerRenderer renderer(kRig, 1);
  renderer.setNoise(0.0);
  vpImage<unsigned char> Il, Ir;
  renderer.render(std::vector<vpColVector>(1, point3(0.0, 0.0, -2.0)), Il, Ir);
  for (unsigned int k = 0; k < Il.getSize(); ++k) {
    ASSERT_EQ(Il.bitmap[k], 30);
    ASSERT_EQ(Ir.bitmap[k], 30);
  }
}

TEST(SimulatorMarkerRenderer, NoiseIsGaussianSeededAndDeterministic)
{
  vpSimulatorMarkerRenderer a(kRig, 3), b(kRig, 3), c(kRig, 4);
  a.setNoise(6.0);
  b.setNoise(6.0);
  c.setNoise(6.0);
  const std::vector<vpColVector> X = gripperMarkers();
  vpImage<unsigned char> Ia, Ja, Ib, Jb, Ic, Jc;
  a.render(X, Ia, Ja);
  b.render(X, Ib, Jb);
  c.render(X, Ic, Jc);
  EXPECT_TRUE(Ia == Ib);
  EXPECT_TRUE(Ja == Jb);
  EXPECT_FALSE(Ia == Ic);
  // The background far from the markers: mean 30, standard deviation 6 (quantisation adds 1/12 grey level^2).
  double s = 0.0, s2 = 0.0;
  unsigned int count = 0;
  for (unsigned int i = 0; i < 100; ++i) {
    for (unsigned int j = 0; j < 640; ++j) {
      s += Ia[i][j];
      s2 += Ia[i][j] * Ia[i][j];
      ++count;
    }
  }
  const double mean = s / count, sd = std::sqrt(s2 / count - mean * mean);
  EXPECT_NEAR(mean, 30.0, 0.1);
  EXPECT_NEAR(sd, std::sqrt(36.0 + 1.0 / 12.0), 0.15);
  // setSeed() restarts the stream: the same images again.
  a.setSeed(3);
  a.render(X, Ic, Jc);
  EXPECT_TRUE(Ia == Ic);
}

TEST(SimulatorMarkerRenderer, BadSettingsThrowAndChangeNothing)
{
  vpSimulatorMarkerRenderer renderer(kRig, 1);
  const int invalid = vpProjectiveException::invalidValueError;
  EXPECT_TRUE(throwsProjective([&] { renderer.setMarkerRadius(-0.001); }, invalid, "radius"));
  EXPECT_TRUE(
      throwsProjective([&] { renderer.setMarkerRadius(std::numeric_limits<double>::quiet_NaN()); }, invalid, "radius"));
  EXPECT_TRUE(throwsProjective([&] { renderer.setBlur(-1.0); }, invalid, "blur"));
  EXPECT_TRUE(throwsProjective([&] { renderer.setNoise(std::numeric_limits<double>::infinity()); }, invalid, "noise"));
  EXPECT_TRUE(throwsProjective([&] { renderer.setSupersampling(0); }, invalid, "rays"));
  EXPECT_TRUE(throwsProjective([&] { renderer.setGrayLevels(30.0, 300.0); }, invalid, "grey level"));
  EXPECT_DOUBLE_EQ(renderer.getMarkerRadius(), 0.003);
  EXPECT_DOUBLE_EQ(renderer.getBlur(), 0.8);
  EXPECT_DOUBLE_EQ(renderer.getNoise(), 4.0);
  EXPECT_EQ(renderer.getSupersampling(), 8u);
  EXPECT_DOUBLE_EQ(renderer.getBackgroundLevel(), 30.0);
  EXPECT_DOUBLE_EQ(renderer.getMarkerLevel(), 220.0);

  vpImage<unsigned char> Il(2, 2, 7), Ir(2, 2, 7);
  vpColVector bad(2, 0.0);
  EXPECT_TRUE(throwsProjective(
      [&] {
        renderer.render({point3(0, 0, 1), bad}, Il, Ir);
      },
      vpProjectiveException::dimensionError, "3x1"));
  EXPECT_TRUE(
      throwsProjective([&] { renderer.render({point3(0, 0, std::numeric_limits<double>::quiet_NaN())}, Il, Ir); },
                       vpProjectiveException::nonFiniteValueError, "not finite"));
  EXPECT_EQ(Il.getWidth(), 2u);
  EXPECT_EQ(Ir[1][1], 7);
  // The noise stream did not move: the next image is the one a fresh renderer makes.
  vpSimulatorMarkerRenderer fresh(kRig, 1);
  vpImage<unsigned char> J1, J2, K1, K2;
  renderer.render(gripperMarkers(), J1, J2);
  fresh.render(gripperMarkers(), K1, K2);
  EXPECT_TRUE(J1 == K1 && J2 == K2);
}
