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
  Tests of vpProjectiveStereoRig's canonical frame: P = [I|0], P' independent of the scale and sign of F, epipoles,
  F ~ [e']_x P'(:, 0:3); a rank-3 input is projected on rank 2.
*/

#include <gtest/gtest.h>

#include "vpProjectiveStereoRigTestTools.h"

using namespace vpProjectiveTest;

TEST(vpProjectiveStereoRig, FrameIndependentOfScaleAndSignOfF)
{
  const Scene scene;
  const vpMatrix F = scene.sim.getFundamentalMatrix();
  vpProjectiveStereoRig a, b;
  a.setFundamentalMatrix(F);
  b.setFundamentalMatrix(-3.0 * F);
  const Eigen::Matrix<double, 3, 4> Pa = toEigen<3, 4>(a.getRightProjection());
  const Eigen::Matrix<double, 3, 4> Pb = toEigen<3, 4>(b.getRightProjection());
  EXPECT_LT(relativeError(Pb, Pa), 1e-12);
  EXPECT_LT(relativeError(toEigen<3, 3>(b.getFundamentalMatrix()), toEigen<3, 3>(a.getFundamentalMatrix())), 1e-12);

  // The same projective points, hence the same models, from either rig.
  const SeededMatches data(scene, 7, 10, 0.0);
  const std::vector<vpImagePoint> &left = data.left, &right = data.right;
  for (size_t i = 0; i < left.size(); ++i) {
    EXPECT_LT(
        relativeErrorUpToScale(toEigen4(b.triangulate(left[i], right[i])), toEigen4(a.triangulate(left[i], right[i]))),
        1e-10);
  }
}

TEST(vpProjectiveStereoRig, CanonicalCameraPair)
{
  const Scene scene;
  const vpProjectiveStereoRig &rig = scene.rig;
  const Eigen::Matrix3d F = toEigen<3, 3>(rig.getFundamentalMatrix());
  const Eigen::Matrix<double, 3, 4> P = toEigen<3, 4>(rig.getLeftProjection());
  const Eigen::Matrix<double, 3, 4> Pp = toEigen<3, 4>(rig.getRightProjection());
  Eigen::Matrix<double, 3, 4> I0 = Eigen::Matrix<double, 3, 4>::Zero();
  I0.leftCols<3>().setIdentity();
  EXPECT_EQ(P, I0);

  const Eigen::Vector3d e = toEigen<3, 1>(rig.getLeftEpipole());
  const Eigen::Vector3d ep = toEigen<3, 1>(rig.getRightEpipole());
  EXPECT_NEAR(e.norm(), 1.0, 1e-12);
  EXPECT_NEAR(ep.norm(), 1.0, 1e-12);
  EXPECT_LT((F * e).norm(), 1e-12);
  EXPECT_LT((F.transpose() * ep).norm(), 1e-12);
  // The last column of P' is e', the image of the left camera centre (0, 0, 0, 1).
  EXPECT_LT((Pp.col(3) - ep).norm(), 1e-12);
  // P' is consistent with F: F ~ [e']_x P'(:, 0:3) (here exactly -F for unit e').
  EXPECT_LT(relativeErrorUpToScale(Eigen::Matrix3d(vpMetricTwist::skew(ep) * Pp.leftCols<3>()), F), 1e-12);
  // ... and the left 3x3 block of P' is invertible (the frame is not degenerate).
  EXPECT_GT(Eigen::JacobiSVD<Eigen::Matrix3d>(Pp.leftCols<3>()).singularValues()(2), 1e-3);

  // The Eigen overloads give exactly the values of the ViSP getters of the same name.
  Eigen::Matrix3d Fe;
  vpProjectiveStereoRig::Projection Pe, Ppe;
  rig.getFundamentalMatrix(Fe);
  rig.getLeftProjection(Pe);
  rig.getRightProjection(Ppe);
  EXPECT_EQ(Fe, F);
  EXPECT_EQ(Pe, P);
  EXPECT_EQ(Ppe, Pp);
}

TEST(vpProjectiveStereoRig, RankThreeInputIsProjectedOnRankTwo)
{
  const Scene scene;
  vpUniRand rng(11);
  vpMatrix F = scene.sim.getFundamentalMatrix();
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      F[i][j] += 1e-3 * rng.uniform(-1.0, 1.0);
    }
  }
  ASSERT_GT(std::abs(toEigen<3, 3>(F).determinant()), 1e-12);
  vpProjectiveStereoRig rig;
  rig.setFundamentalMatrix(F);
  Eigen::Matrix3d F2;
  rig.getFundamentalMatrix(F2);
  EXPECT_LT(Eigen::JacobiSVD<Eigen::Matrix3d>(F2).singularValues()(2), 1e-14);
  EXPECT_LT((F2 * toEigen<3, 1>(rig.getLeftEpipole())).norm(), 1e-12);
  EXPECT_LT((F2.transpose() * toEigen<3, 1>(rig.getRightEpipole())).norm(), 1e-12);
  // The closest rank-2 matrix is close to the input.
  EXPECT_LT(relativeErrorUpToScale(F2, toEigen<3, 3>(F)), 1e-2);
}
