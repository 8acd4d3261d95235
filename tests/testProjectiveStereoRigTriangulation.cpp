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
  Tests of vpProjectiveStereoRig::triangulate() / project(): round trips, agreement with the true projective points
  H_PE^-1 N, optimality of the refined triangulation, invariance to the scale of M, points on a focal plane.
*/

#include <gtest/gtest.h>

#include "vpProjectiveStereoRigTestTools.h"

using namespace vpProjectiveTest;

TEST(vpProjectiveStereoRig, TriangulateNoiseFreeIsExact)
{
  const Scene scene;
  const SeededMatches data(scene, 21, 50, 0.0);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  const std::vector<vpColVector> &wX = data.points;
  double worstPixel = 0.0, worstPoint = 0.0;
  const std::vector<vpColVector> all = scene.rig.triangulate(left, right); // the overload for lists of matches
  ASSERT_EQ(all.size(), wX.size());
  for (size_t i = 0; i < wX.size(); ++i) {
    const vpColVector M = scene.rig.triangulate(left[i], right[i]);
    EXPECT_EQ(all[i], M); // the same arithmetic, hence the same bits
    ASSERT_EQ(M.getRows(), 4u);
    EXPECT_NEAR(M.frobeniusNorm(), 1.0, 1e-12);
    vpImagePoint l, r;
    scene.rig.project(M, l, r);
    worstPixel = std::max(worstPixel, std::max(pixelDistance(l, left[i]), pixelDistance(r, right[i])));
    // The true projective point H_PE^-1 N, up to scale and sign.
    worstPoint = std::max(worstPoint, relativeErrorUpToScale(toEigen4(M), scene.projectivePoint(wX[i])));
    // The Eigen overload gives the same point.
    const Eigen::Vector4d Me = scene.rig.triangulate(Eigen::Vector2d(left[i].get_u(), left[i].get_v()),
                                                     Eigen::Vector2d(right[i].get_u(), right[i].get_v()));
    EXPECT_LT((Me - toEigen4(M)).norm(), 1e-15);
  }
  EXPECT_LT(worstPixel, 1e-8);
  EXPECT_LT(worstPoint, 1e-8);
}

/*
  0.5 px noise, 100 matches. The refined triangulation minimises the reprojection error over M, so it can be no worse
  than the linear (DLT) point on any match; its minimum is, to first order, Sampson's error (relative accuracy of the
  approximation ~ sigma / f, far below 2 %); and the squared minimum is sigma^2 chi-square with 1 dof (4
  measurements, 3 point parameters), whose mean over 100 matches is within +-40 % of sigma^2 (2.8 std).
  The corrected matches (projections of M) lie exactly on corresponding epipolar lines.
*/
TEST(vpProjectiveStereoRig, TriangulateNoisyIsOptimal)
{
  const Scene scene;
  const vpProjectiveStereoRig &rig = scene.rig;
  Eigen::Matrix3d F;
  rig.getFundamentalMatrix(F);
  vpProjectiveStereoRig::Projection P, Pp;
  rig.getLeftProjection(P);
  rig.getRightProjection(Pp);
  const SeededMatches data(scene, 31, 100, kSigma);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  double sumSquares = 0.0, sumLinear = 0.0, sumRefined = 0.0;
  for (size_t i = 0; i < left.size(); ++i) {
    SCOPED_TRACE(::testing::Message() << "match " << i);
    const Eigen::Vector4d M = toEigen4(rig.triangulate(left[i], right[i]));
    const Eigen::Vector4d Mlin = triangulateDLT(P, Pp, left[i], right[i]);
    const double refined = reprojectionError(rig, M, left[i], right[i]);
    const double linear = reprojectionError(rig, Mlin, left[i], right[i]);
    const double sampson = sampsonError(F, left[i], right[i]);
    EXPECT_LE(refined, linear + 1e-9);
    EXPECT_NEAR(refined, sampson, 0.02 * sampson + 1e-6);
    vpImagePoint l, r;
    rig.project(toVispVector(M), l, r);
    const Eigen::Vector3d m = pixel(l), mp = pixel(r);
    EXPECT_LT(std::abs(mp.dot(F * m)) / (mp.norm() * m.norm()), 1e-12);
    sumSquares += refined * refined;
    sumLinear += linear;
    sumRefined += refined;
  }
  const double meanSquare = sumSquares / left.size();
  testLog() << "[ stats    ] triangulation, sigma " << kSigma << " px: mean squared refined error " << meanSquare
            << " px^2 (expected " << kSigma * kSigma << "), mean error linear " << sumLinear / left.size()
            << " px, refined " << sumRefined / left.size() << " px" << std::endl;
  EXPECT_NEAR(meanSquare / (kSigma * kSigma), 1.0, 0.4);
}

TEST(vpProjectiveStereoRig, ProjectIsScaleAndSignInvariant)
{
  const Scene scene;
  const SeededMatches data(scene, 41, 20, 0.0);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  const std::vector<vpColVector> &wX = data.points;
  for (size_t i = 0; i < wX.size(); ++i) {
    const Eigen::Vector4d M = scene.projectivePoint(wX[i]);
    vpImagePoint l1, r1, l2, r2;
    scene.rig.project(toVispVector(M), l1, r1);
    scene.rig.project(toVispVector(Eigen::Vector4d(-2.0 * M)), l2, r2);
    EXPECT_LT(pixelDistance(l1, l2), 1e-9);
    EXPECT_LT(pixelDistance(r1, r2), 1e-9);
    // And they are the simulator's images.
    EXPECT_LT(pixelDistance(l1, left[i]), 1e-8);
    EXPECT_LT(pixelDistance(r1, right[i]), 1e-8);
    // The Eigen overload agrees.
    Eigen::Vector4d s;
    ASSERT_TRUE(scene.rig.project(M, s));
    EXPECT_LT((s - Eigen::Vector4d(l1.get_u(), l1.get_v(), r1.get_u(), r1.get_v())).norm(), 1e-9);
  }
}

TEST(vpProjectiveStereoRig, ProjectPointOnFocalPlaneThrows)
{
  const Scene scene;
  const vpProjectiveStereoRig &rig = scene.rig;
  vpImagePoint l, r;
  // Left focal plane: (P M)_3 = M_3 = 0.
  const Eigen::Vector4d Ml(1.0, 2.0, 0.0, 0.5);
  EXPECT_TRUE(throwsProjective([&] { rig.project(toVispVector(Ml), l, r); },
                               vpProjectiveException::pointAtInfinityError, "focal plane"));
  Eigen::Vector4d s;
  EXPECT_FALSE(rig.project(Ml, s));
  // Right focal plane: (P' M)_3 = 0, M chosen orthogonal to the third row of P'.
  // The two focal planes are nearly parallel (11 deg vergence): take the point of the right one closest to (0,0,1,0).
  vpProjectiveStereoRig::Projection Pp;
  rig.getRightProjection(Pp);
  const Eigen::Vector4d p3 = Pp.row(2).transpose();
  Eigen::Vector4d Mr = Eigen::Vector4d::UnitZ() - p3(2) / p3.squaredNorm() * p3;
  Mr.normalize();
  ASSERT_GT(std::abs(Mr(2)), 1e-6); // far from the left focal plane at the library's 1e-12 tolerance
  EXPECT_TRUE(throwsProjective([&] { rig.project(toVispVector(Mr), l, r); },
                               vpProjectiveException::pointAtInfinityError, "focal plane"));
  EXPECT_FALSE(rig.project(Mr, s));
  // Close to, but off, the focal plane: a finite image.
  EXPECT_NO_THROW(rig.project(toVispVector(Eigen::Vector4d(1.0, 2.0, 1e-6, 0.5)), l, r));
}
