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
  Tests of vpFeatureStereoPoint, the non-metric stereo point s = (u, v, u', v') as a ViSP visual feature:
  - construction, accessors and the ViSP selection masks (selectU() ... selectVp(), FEATURE_ALL);
  - error() = s - s* on the selected rows, also through the vpBasicFeature interface;
  - interaction() = L_s of eq. (45), the derivative of the projections (P M, P' M) with respect to the projective
    point M triangulated from s, checked against the Richardson-extrapolated central differences of the rig's
    projection (vpNumericJacobian.h) at random points seen by the paper's rig; L_s M = 0 (the images do not change when
  M is scaled); L_s J_H(q, M) is the robot's image Jacobian (46), which the servo relies on;
  - duplicate() is a deep, independent copy keeping the rig; print() honours the selection;
  - misuse throws a vpProjectiveException with a meaningful code and message.

  Bounds. Noise-free, L_s is exact: in the canonical frame P = [I | 0] acts on pixels, so M = (m, *) / |(m, *)| has
  a tiny third entry (~1/|m| ~ 3e-3) and L_s entries up to ~1e5; steps h = 1e-6 (three orders below that entry) make
  the extrapolated truncation error negligible and the rounding error ~1e-16 |s| / h ~ 1e-8 px against entries of
  1e3-1e5: measured ~1e-11 relative, bound 1e-8. Algebraic identities (L_s M = 0, L_s J_H = J) hold to rounding:
  1e-12 relative to the norms involved. Every random number comes from a seeded vpUniRand.
*/

#include <cmath>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/visual_features/vpFeaturePoint.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#include "vpNumericJacobian.h"
#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
vpImagePoint imagePoint(double u, double v)
{
  vpImagePoint ip;
  ip.set_uv(u, v);
  return ip;
}

//! Noise-free images of \e n random points within \e halfSide of the scene's fixation point (seed \e seed).
void randomImages(const Scene &scene, long seed, double halfSide, size_t n, std::vector<vpImagePoint> &left,
                  std::vector<vpImagePoint> &right)
{
  vpUniRand rng(seed);
  imagesOf(scene.sim, randomVisiblePoints(scene.sim, rng, Scene::fixation(), halfSide, n), left, right);
}

//! A feature built from a match, given the rig.
vpFeatureStereoPoint featureOf(const vpImagePoint &left, const vpImagePoint &right, const vpProjectiveStereoRig &rig)
{
  vpFeatureStereoPoint s;
  s.buildFrom(left, right);
  s.setStereoRig(rig);
  return s;
}
} // namespace

TEST(FeatureStereoPoint, BuildFromAndAccessors)
{
  vpFeatureStereoPoint s;
  EXPECT_EQ(s.getDimension(), 4u);
  s.buildFrom(imagePoint(101.5, 202.25), imagePoint(303.75, 204.5));
  EXPECT_EQ(s.get_u(), 101.5);
  EXPECT_EQ(s.get_v(), 202.25);
  EXPECT_EQ(s.get_up(), 303.75);
  EXPECT_EQ(s.get_vp(), 204.5);
  // vpImagePoint(i, j) is (row, column) = (v, u).
  EXPECT_EQ(s.getLeft().get_i(), 202.25);
  EXPECT_EQ(s.getLeft().get_j(), 101.5);
  EXPECT_EQ(s.getRight().get_u(), 303.75);
  EXPECT_EQ(s.getRight().get_v(), 204.5);
  EXPECT_EQ(s.getFeature(), Eigen::Vector4d(101.5, 202.25, 303.75, 204.5));
  const vpColVector all = s.get_s();
  ASSERT_EQ(all.getRows(), 4u);
  EXPECT_EQ(all[2], 303.75);
  s.buildFrom(1.0, 2.0, 3.0, 4.0);
  EXPECT_EQ(s.getFeature(), Eigen::Vector4d(1.0, 2.0, 3.0, 4.0));
  // The selectors are ViSP's FEATURE_LINE bits, one per coordinate.
  EXPECT_EQ(vpFeatureStereoPoint::selectU(), vpBasicFeature::FEATURE_LINE[0]);
  EXPECT_EQ(vpFeatureStereoPoint::selectV(), vpBasicFeature::FEATURE_LINE[1]);
  EXPECT_EQ(vpFeatureStereoPoint::selectUp(), vpBasicFeature::FEATURE_LINE[2]);
  EXPECT_EQ(vpFeatureStereoPoint::selectVp(), vpBasicFeature::FEATURE_LINE[3]);
  EXPECT_EQ(s.getDimension(vpFeatureStereoPoint::selectU() | vpFeatureStereoPoint::selectVp()), 2u);
  EXPECT_EQ(s.getDimension(vpBasicFeature::FEATURE_ALL), 4u);
}

TEST(FeatureStereoPoint, ErrorIsDifferenceOnSelectedRows)
{
  vpFeatureStereoPoint s, s_star;
  s.buildFrom(10.0, 20.0, 30.0, 40.0);
  s_star.buildFrom(1.5, 2.5, 3.5, 4.5);
  const vpColVector e = s.error(s_star);
  ASSERT_EQ(e.getRows(), 4u);
  EXPECT_EQ(toEigenV(e), Eigen::Vector4d(8.5, 17.5, 26.5, 35.5));
  // Each selector alone, then pairs, in the order u, v, u', v'.
  const unsigned int sel[4] = {vpFeatureStereoPoint::selectU(), vpFeatureStereoPoint::selectV(),
                               vpFeatureStereoPoint::selectUp(), vpFeatureStereoPoint::selectVp()};
  for (int i = 0; i < 4; ++i) {
    const vpColVector ei = s.error(s_star, sel[i]);
    ASSERT_EQ(ei.getRows(), 1u);
    EXPECT_EQ(ei[0], e[static_cast<unsigned int>(i)]);
  }
  const vpColVector uvp = s.error(s_star, sel[0] | sel[3]);
  ASSERT_EQ(uvp.getRows(), 2u);
  EXPECT_EQ(uvp[0], 8.5);
  EXPECT_EQ(uvp[1], 35.5);
  const vpColVector right = s.error(s_star, sel[3] | sel[2]); // bit order, not argument order
  ASSERT_EQ(right.getRows(), 2u);
  EXPECT_EQ(right[0], 26.5);
  EXPECT_EQ(right[1], 35.5);
  EXPECT_EQ(s.error(s_star, 0).getRows(), 0u);
  // Through the vpBasicFeature interface, as vpServo uses it; and antisymmetric.
  vpBasicFeature &base = s;
  EXPECT_EQ(toEigenV(base.error(s_star)), toEigenV(e));
  EXPECT_EQ(toEigenV(s_star.error(s)), -toEigenV(e));
  EXPECT_EQ(s.error(s).frobeniusNorm(), 0.0);
}

TEST(FeatureStereoPoint, InteractionIsDerivativeOfProjections)
{
  const Scene scene;
  std::vector<vpImagePoint> left, right;
  randomImages(scene, 7, 0.15, 20, left, right);
  double worst = 0.0;
  for (size_t k = 0; k < left.size(); ++k) {
    SCOPED_TRACE(::testing::Message() << "point " << k);
    vpFeatureStereoPoint s = featureOf(left[k], right[k], scene.rig);
    const Eigen::MatrixXd L = toEigenX(s.interaction());
    ASSERT_EQ(L.rows(), 4);
    ASSERT_EQ(L.cols(), 4);
    // The point the feature triangulates: the rig's own (unit norm, its sign convention).
    const Eigen::Vector4d M = toEigen4(scene.rig.triangulate(left[k], right[k]));
    const auto project = [&](const Eigen::VectorXd &X) {
      Eigen::Vector4d image;
      EXPECT_TRUE(scene.rig.project(Eigen::Vector4d(X), image));
      return image;
    };
    const Eigen::MatrixXd Lfd = numericJacobian(project, M, 1e-6);
    worst = std::max(worst, jacobianRelativeError(L, Lfd));
    EXPECT_TRUE(jacobianMatches(L, Lfd, 1e-8));
    // The images do not move when M is scaled: L_s M = 0.
    EXPECT_LT((L * M).norm(), 1e-12 * L.norm() * M.norm());
    // The rows of a selection are those rows.
    const Eigen::MatrixXd Lv = toEigenX(s.interaction(vpFeatureStereoPoint::selectV()));
    ASSERT_EQ(Lv.rows(), 1);
    EXPECT_EQ(Lv.row(0), L.row(1));
    const Eigen::MatrixXd Luup =
        toEigenX(s.interaction(vpFeatureStereoPoint::selectU() | vpFeatureStereoPoint::selectUp()));
    ASSERT_EQ(Luup.rows(), 2);
    EXPECT_EQ(Luup.row(0), L.row(0));
    EXPECT_EQ(Luup.row(1), L.row(2));
    // Through the vpBasicFeature interface.
    vpBasicFeature &base = s;
    EXPECT_EQ(toEigenX(base.interaction()), L);
  }
  testLog() << "[ measured ] worst interaction error " << worst << std::endl;
}

TEST(FeatureStereoPoint, InteractionTimesPointJacobianIsImageJacobian)
{
  // What vpServoProjective computes: L_s(M) J_H(q, M) = J(q, M), eq. (46), with M triangulated from s.
  const ArmSetup setup = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(setup);
  const vpProjectiveStereoRig &rig = robot.getStereoRig();
  vpUniRand rng(17);
  for (int t = 0; t < 5; ++t) {
    const vpColVector q = setup.randomVisibleJoints(rng, std::vector<double>(6, vpMath::rad(20.0)));
    ASSERT_EQ(q.getRows(), 6u);
    for (size_t j = 0; j < setup.numberOfMarkers(); ++j) {
      const Eigen::Vector4d sj = setup.imageOf(setup.armJoints(q), j);
      vpFeatureStereoPoint s;
      s.buildFrom(sj(0), sj(1), sj(2), sj(3));
      s.setStereoRig(rig);
      const vpColVector M = rig.triangulate(s.getLeft(), s.getRight());
      const Eigen::MatrixXd LJ = toEigenX(s.interaction()) * pointJacobian(robot.getModel(), q, M);
      const Eigen::MatrixXd J = toEigenX(robot.getImageJacobian(q, M));
      EXPECT_LT((LJ - J).norm() / J.norm(), 1e-10) << "marker " << j;
    }
  }
}

TEST(FeatureStereoPoint, DuplicateIsIndependentCopy)
{
  const Scene scene;
  std::vector<vpImagePoint> left, right;
  randomImages(scene, 27, 0.1, 1, left, right);
  vpFeatureStereoPoint s = featureOf(left[0], right[0], scene.rig);
  const Eigen::MatrixXd L = toEigenX(s.interaction());
  std::unique_ptr<vpFeatureStereoPoint> copy(s.duplicate());
  ASSERT_NE(copy.get(), nullptr);
  EXPECT_NE(copy.get(), &s);
  EXPECT_EQ(copy->getFeature(), s.getFeature());
  EXPECT_EQ(copy->getDimension(), 4u);
  EXPECT_EQ(toEigenX(copy->interaction()), L); // the rig came along
  // Through the base class, as vpServo duplicates features.
  std::unique_ptr<vpBasicFeature> base(static_cast<const vpBasicFeature &>(s).duplicate());
  ASSERT_NE(dynamic_cast<vpFeatureStereoPoint *>(base.get()), nullptr);
  EXPECT_EQ(toEigenV(base->get_s()), toEigenV(s.get_s()));
  // Independent: changing the original leaves the copy.
  const Eigen::Vector4d before = s.getFeature();
  s.buildFrom(1.0, 2.0, 3.0, 4.0);
  EXPECT_EQ(copy->getFeature(), before);
  EXPECT_EQ(toEigenV(copy->error(s)), Eigen::Vector4d(before - Eigen::Vector4d(1.0, 2.0, 3.0, 4.0)));
}

TEST(FeatureStereoPoint, PrintAndDisplayHonourSelection)
{
  vpFeatureStereoPoint s;
  s.buildFrom(12.5, 34.5, 56.5, 78.5);
  ::testing::internal::CaptureStdout();
  s.print();
  const std::string all = ::testing::internal::GetCapturedStdout();
  EXPECT_NE(all.find("12.5"), std::string::npos) << all;
  EXPECT_NE(all.find("78.5"), std::string::npos) << all;
  ::testing::internal::CaptureStdout();
  s.print(vpFeatureStereoPoint::selectUp());
  const std::string one = ::testing::internal::GetCapturedStdout();
  EXPECT_NE(one.find("56.5"), std::string::npos) << one;
  EXPECT_EQ(one.find("12.5"), std::string::npos) << one;
  // Without a display attached, drawing is a no-op (headless test machines).
  vpImage<unsigned char> I(480, 640, 0), Ir(480, 640, 0);
  EXPECT_NO_THROW(s.display(vpCameraParameters(), I));
  EXPECT_NO_THROW(s.display(I, Ir, vpColor::red, 2));
}

TEST(FeatureStereoPoint, BadInputsThrow)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  vpFeatureStereoPoint s;
  s.buildFrom(1.0, 2.0, 3.0, 4.0);
  const int nonFinite = vpProjectiveException::nonFiniteValueError;
  EXPECT_TRUE(throwsProjective([&] { s.buildFrom(nan, 2.0, 3.0, 4.0); }, nonFinite, "coordinate u "));
  EXPECT_TRUE(throwsProjective([&] { s.buildFrom(1.0, 2.0, 3.0, -inf); }, nonFinite, "coordinate v'"));
  EXPECT_TRUE(
      throwsProjective([&] { s.buildFrom(imagePoint(1.0, 2.0), imagePoint(inf, 4.0)); }, nonFinite, "coordinate u'"));
  EXPECT_TRUE(
      throwsProjective([&] { s.buildFrom(imagePoint(1.0, nan), imagePoint(3.0, 4.0)); }, nonFinite, "not finite"));
  // A failed buildFrom leaves the feature unchanged.
  EXPECT_EQ(s.getFeature(), Eigen::Vector4d(1.0, 2.0, 3.0, 4.0));
  // No rig, or a rig without F.
  EXPECT_TRUE(throwsProjective([&] { s.interaction(); }, vpProjectiveException::notInitializedError, "setStereoRig"));
  const vpProjectiveStereoRig empty;
  s.setStereoRig(empty);
  EXPECT_TRUE(throwsProjective([&] { s.interaction(); }, vpProjectiveException::notInitializedError, "setStereoRig"));
  // A desired feature of another type.
  vpFeaturePoint p;
  p.buildFrom(0.1, 0.2, 1.0);
  EXPECT_TRUE(throwsProjective([&] { s.error(p); }, vpProjectiveException::invalidValueError, "vpFeatureStereoPoint"));
}
