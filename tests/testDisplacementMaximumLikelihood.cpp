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
  The plugin has one maximum-likelihood estimator of a p-displacement from stereo images: a dedicated
  Levenberg-Marquardt (vpProjectiveDisplacement::estimateFromImages(), also the refit of estimateRobust()). This test
  minimises the same cost with Ceres, written here independently of the library (its own projection, its own
  parametrisation: H on the unit sphere of R^16 in the rig's frame, each point on the unit sphere of R^4), from the
  same linear start, and checks that both reach the same optimum.
*/

#include <cmath>
#include <vector>

#include <Eigen/Dense>
#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! Ceres' own solver (Schur complement on the points), converged to the rounding: the reference the library is checked
//! against.
ceres::Solver::Summary solveTight(ceres::Problem &problem, int maxIterations)
{
  ceres::Solver::Options options;
  options.linear_solver_type = ceres::DENSE_SCHUR;
  options.function_tolerance = options.parameter_tolerance = 1e-15;
  options.gradient_tolerance = 1e-17;
  options.max_num_iterations = maxIterations;
  ceres::Solver::Summary summary;
  ceres::Solve(options, &problem, &summary);
  return summary;
}

//! The pixel error of one rigid point in the four images (before: P, P'; after: P H, P' H), 8 residuals.
struct FourImageError {
  FourImageError(const Eigen::Matrix<double, 3, 4> &P, const Eigen::Matrix<double, 3, 4> &Pp, const Eigen::Vector4d &s0,
                 const Eigen::Vector4d &s1)
      : P(P), Pp(Pp), s0(s0), s1(s1)
  {
  }

  template <typename T> static void pixel(const Eigen::Matrix<double, 3, 4> &C, const T *X, T *uv)
  {
    T m[3];
    for (int r = 0; r < 3; ++r) {
      m[r] = T(C(r, 0)) * X[0] + T(C(r, 1)) * X[1] + T(C(r, 2)) * X[2] + T(C(r, 3)) * X[3];
    }
    uv[0] = m[0] / m[2];
    uv[1] = m[1] / m[2];
  }

  template <typename T> bool operator()(const T *H, const T *M0, T *r) const
  {
    T M1[4];
    for (int i = 0; i < 4; ++i) {
      M1[i] = H[4 * i] * M0[0] + H[4 * i + 1] * M0[1] + H[4 * i + 2] * M0[2] + H[4 * i + 3] * M0[3];
    }
    pixel(P, M0, r);
    pixel(Pp, M0, r + 2);
    pixel(P, M1, r + 4);
    pixel(Pp, M1, r + 6);
    for (int k = 0; k < 4; ++k) {
      r[k] -= T(s0(k));
      r[4 + k] -= T(s1(k));
    }
    return true;
  }

  Eigen::Matrix<double, 3, 4> P, Pp;
  Eigen::Vector4d s0, s1;
};

//! Sum of squared pixel errors of H and the points that best explain the images: the cost both solvers minimise.
double costOf(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
              const std::vector<Eigen::Vector4d> &s1, const Eigen::Matrix4d &H, std::vector<Eigen::Vector4d> &M0)
{
  // The points for this H: a few Ceres iterations on the points alone (H fixed).
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> Hr = H / H.norm();
  vpProjectiveStereoRig::Projection P, Pp;
  rig.getLeftProjection(P);
  rig.getRightProjection(Pp);
  ceres::Problem problem;
  for (size_t j = 0; j < s0.size(); ++j) {
    problem.AddResidualBlock(
        new ceres::AutoDiffCostFunction<FourImageError, 8, 16, 4>(new FourImageError(P, Pp, s0[j], s1[j])), nullptr,
        Hr.data(), M0[j].data());
    problem.SetManifold(M0[j].data(), new ceres::SphereManifold<4>());
  }
  problem.SetParameterBlockConstant(Hr.data());
  return 2.0 * solveTight(problem, 50).final_cost;
}
} // namespace

TEST(vpProjectiveDisplacement, MaximumLikelihoodEqualsCeres)
{
  const Scene scene;
  vpProjectiveStereoRig::Projection P, Pp;
  scene.rig.getLeftProjection(P);
  scene.rig.getRightProjection(Pp);
  vpUniRand rng(7);
  vpGaussRand noise(0.5, 0.0, 11);
  double worstCost = 0.0, worstH = 0.0;
  for (int seed = 0; seed < 12; ++seed) {
    SCOPED_TRACE(::testing::Message() << "case " << seed);
    // 7 markers on a 10 cm body, a rotation, a screw or a translation of it.
    const std::vector<vpColVector> body = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.05, 7, 40.0);
    const vpColVector axisPoint = Scene::fixation();
    vpHomogeneousMatrix wT = vpSimulatorStereoRig::rotationAbout(axisPoint, randomDirection(rng), 0.5);
    if (seed % 3 == 1) {
      wT = vpSimulatorStereoRig::translationAlong(randomDirection(rng), 0.03) * wT;
    } else if (seed % 3 == 2) {
      wT = vpSimulatorStereoRig::translationAlong(randomDirection(rng), 0.05);
    }
    std::vector<Eigen::Vector4d> s0(body.size()), s1(body.size());
    for (size_t j = 0; j < body.size(); ++j) {
      vpImagePoint l0, r0, l1, r1;
      ASSERT_TRUE(scene.sim.project(body[j], l0, r0, 0.5, noise));
      ASSERT_TRUE(scene.sim.project(vpColVector(wT * vpColVector({body[j][0], body[j][1], body[j][2], 1.0})), l1, r1,
                                    0.5, noise));
      s0[j] << l0.get_u(), l0.get_v(), r0.get_u(), r0.get_v();
      s1[j] << l1.get_u(), l1.get_v(), r1.get_u(), r1.get_v();
    }
    // The library's estimate (linear start, then its Levenberg-Marquardt).
    const Eigen::Matrix4d Hlib = vpProjectiveDisplacement::estimateFromImages(scene.rig, s0, s1);
    // Ceres from the same linear start, to tight tolerances.
    std::vector<Eigen::Vector4d> M0(body.size()), M1(body.size());
    for (size_t j = 0; j < body.size(); ++j) {
      M0[j] = scene.rig.triangulate(Eigen::Vector2d(s0[j].head<2>()), Eigen::Vector2d(s0[j].tail<2>()));
      M1[j] = scene.rig.triangulate(Eigen::Vector2d(s1[j].head<2>()), Eigen::Vector2d(s1[j].tail<2>()));
    }
    const Eigen::Matrix4d Hlin = vpProjectiveDisplacement::estimateLinear(M0, M1);
    Eigen::Matrix<double, 4, 4, Eigen::RowMajor> H = Hlin / Hlin.norm();
    std::vector<Eigen::Vector4d> points = M0;
    ceres::Problem problem;
    for (size_t j = 0; j < body.size(); ++j) {
      problem.AddResidualBlock(
          new ceres::AutoDiffCostFunction<FourImageError, 8, 16, 4>(new FourImageError(P, Pp, s0[j], s1[j])), nullptr,
          H.data(), points[j].data());
      problem.SetManifold(points[j].data(), new ceres::SphereManifold<4>());
    }
    problem.SetManifold(H.data(), new ceres::SphereManifold<16>());
    const ceres::Solver::Summary summary = solveTight(problem, 500);
    ASSERT_TRUE(summary.IsSolutionUsable());
    const Eigen::Matrix4d Hceres = vpProjectiveDisplacement::normalize(Eigen::Matrix4d(H));

    // Same optimum: equal costs (the library's H re-evaluated by the same independent cost), equal H in the frame
    // whitened by the true points (where H's entries are of order 1).
    std::vector<Eigen::Vector4d> Mlib = M0;
    const double costLib = costOf(scene.rig, s0, s1, Hlib, Mlib);
    const double costCeres = 2.0 * summary.final_cost;
    const double costLinear = costOf(scene.rig, s0, s1, Hlin, M0);
    EXPECT_LT(costCeres, costLinear); // the refinement matters
    const double dCost = std::abs(costLib - costCeres) / costCeres;
    EXPECT_LT(dCost, 1e-6) << "library " << costLib << ", Ceres " << costCeres;
    std::vector<Eigen::Vector4d> truth(body.size());
    for (size_t j = 0; j < body.size(); ++j) {
      truth[j] = scene.projectivePoint(body[j]);
    }
    Eigen::Matrix4d C = Eigen::Matrix4d::Zero();
    for (const Eigen::Vector4d &M : truth) {
      C += M * M.transpose() / static_cast<double>(truth.size());
    }
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix4d> eig(C);
    const Eigen::Matrix4d W = eig.operatorInverseSqrt(), Winv = W.inverse();
    const double dH = relativeError(Eigen::Matrix4d(W * Hlib * Winv), Eigen::Matrix4d(W * Hceres * Winv));
    EXPECT_LT(dH, 1e-5);
    worstCost = std::max(worstCost, dCost);
    worstH = std::max(worstH, dH);
  }
  testLog() << "[ measured ] library ML vs Ceres on the same cost, 12 cases: cost difference " << worstCost
            << " (relative), H difference " << worstH << " (relative, whitened frame)" << std::endl;
}
