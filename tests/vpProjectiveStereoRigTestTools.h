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
  Helpers for the suites of vpProjectiveStereoRig, the weakly calibrated rig (Ruf & Horaud, section 2) (header only,
  not a test itself): seeded matches of random points seen by the metric simulator's rig, the linear triangulation,
  reprojection and Sampson errors, and the noise floor of the noisy estimation tests. The suites:
  testProjectiveStereoRigEstimate, testProjectiveStereoRigRobust, testProjectiveStereoRigCanonicalFrame,
  testProjectiveStereoRigTriangulation and testProjectiveStereoRigBadInput.

  Bounds. Noise-free quantities are exact up to rounding: pixel coordinates of a few hundred, a frame conditioned by
  Hartley normalisation, hence 1e-8 relative (or 1e-8 px) leaves several orders of magnitude of margin while any
  modelling error (wrong P', wrong sign, wrong epipole) gives errors of order 1. The noisy bounds are derived in the
  tests from the standard first-order results for least-squares estimators (residual and prediction error of a fit
  with p parameters on n measurements), and were checked against measurements over all the seeds used.
*/

#ifndef _vpProjectiveStereoRigTestTools_h_
#define _vpProjectiveStereoRigTestTools_h_

#include <algorithm>
#include <cmath>
#include <iostream>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
const double kSigma = 0.5; // pixel noise of the noisy tests (px)

// Matches of n random points around the fixation point (a 24 cm cube, 1 m away: they fill most of both images).
inline void randomMatches(const Scene &scene, vpUniRand &rng, size_t n, double sigma, vpGaussRand &noise,
                          std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right,
                          std::vector<vpColVector> *points = nullptr)
{
  const std::vector<vpColVector> wX = randomVisiblePoints(scene.sim, rng, Scene::fixation(), 0.12, n);
  scene.sim.project(wX, left, right, sigma, noise);
  if (points) {
    *points = wX;
  }
}

/*
  The data of one seed: a vpUniRand and a vpGaussRand seeded alike, n matches with noise sigma, then nFresh noise-free
  matches to judge a fitted F on; the generators go on with what the test draws next.
*/
struct SeededMatches {
  vpUniRand rng;
  vpGaussRand noise;
  std::vector<vpColVector> points; //!< the world points of the matches
  std::vector<vpImagePoint> left, right, freshLeft, freshRight;

  SeededMatches(const Scene &scene, long seed, size_t n, double sigma, size_t nFresh = 0)
      : rng(static_cast<uint64_t>(seed)), noise(1.0, 0.0, seed), points(), left(), right(), freshLeft(), freshRight()
  {
    randomMatches(scene, rng, n, sigma, noise, left, right, &points);
    if (nFresh > 0) {
      randomMatches(scene, rng, nFresh, 0.0, noise, freshLeft, freshRight);
    }
  }
};

//! The right image of a random point lying more than 20 px from the epipolar lines (true F) of \e left in both
//! images: a wrong match for \e left that no geometric test could take for a correct one.
inline vpImagePoint wrongRightImage(const Scene &scene, const Eigen::Matrix3d &Ftrue, const vpImagePoint &left,
                                    vpUniRand &rng, vpGaussRand &noise)
{
  for (;;) {
    std::vector<vpImagePoint> otherLeft, otherRight;
    randomMatches(scene, rng, 1, 0.0, noise, otherLeft, otherRight);
    if (epipolarDistances(Ftrue, left, otherRight[0]).minCoeff() > 20.0) {
      return otherRight[0];
    }
  }
}

inline Eigen::Matrix3d trueF(const Scene &scene)
{
  return toEigen<3, 3>(scene.sim.getFundamentalMatrix());
}

// |m'^T F m| / (|m'| |F| |m|), the largest over the matches.
inline double maxAlgebraicEpipolarResidual(const Eigen::Matrix3d &F, const std::vector<vpImagePoint> &left,
                                           const std::vector<vpImagePoint> &right)
{
  double worst = 0.0;
  for (size_t i = 0; i < left.size(); ++i) {
    const Eigen::Vector3d m = pixel(left[i]), mp = pixel(right[i]);
    worst = std::max(worst, std::abs(mp.dot(F * m)) / (mp.norm() * F.norm() * m.norm()));
  }
  return worst;
}

// Linear triangulation (DLT on row-normalised equations), the reference the refined triangulation must beat.
inline Eigen::Vector4d triangulateDLT(const Eigen::Matrix<double, 3, 4> &P, const Eigen::Matrix<double, 3, 4> &Pp,
                                      const vpImagePoint &l, const vpImagePoint &r)
{
  Eigen::Matrix4d A;
  A.row(0) = l.get_u() * P.row(2) - P.row(0);
  A.row(1) = l.get_v() * P.row(2) - P.row(1);
  A.row(2) = r.get_u() * Pp.row(2) - Pp.row(0);
  A.row(3) = r.get_v() * Pp.row(2) - Pp.row(1);
  for (int i = 0; i < 4; ++i) {
    A.row(i).normalize();
  }
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(A, Eigen::ComputeFullV);
  return svd.matrixV().col(3);
}

// Reprojection error (px, both images together) of M against a match.
inline double reprojectionError(const vpProjectiveStereoRig &rig, const Eigen::Vector4d &M, const vpImagePoint &l,
                                const vpImagePoint &r)
{
  vpImagePoint pl, pr;
  rig.project(toVispVector(M), pl, pr);
  return std::sqrt(std::pow(pixelDistance(pl, l), 2) + std::pow(pixelDistance(pr, r), 2));
}

// Sampson's first-order approximation of the smallest reprojection error of a match consistent with F.
inline double sampsonError(const Eigen::Matrix3d &F, const vpImagePoint &l, const vpImagePoint &r)
{
  const Eigen::Vector3d m = pixel(l), mp = pixel(r);
  const Eigen::Vector3d Fm = F * m, Ftmp = F.transpose() * mp;
  return std::abs(mp.dot(Fm)) / std::sqrt(Fm.head<2>().squaredNorm() + Ftmp.head<2>().squaredNorm());
}

// The noisy estimation tests: n = 50 matches with kSigma noise, 20 seeds (see EstimateNoisyReachesNoiseFloor).
const size_t kNoisyMatches = 50;
const int kNoisySeeds = 20;

//! First-order RMS distance of a match to its epipolar lines under the fitted F (see EstimateNoisyReachesNoiseFloor).
inline double expectedResidual()
{
  return kSigma * std::sqrt((kNoisyMatches - 7.0) / (2.0 * kNoisyMatches));
}

//! First-order RMS epipolar distance of fresh noise-free matches under the fitted F.
inline double expectedPrediction()
{
  return kSigma * std::sqrt(14.0 / kNoisyMatches);
}

struct NoiseFloor {
  double meanResidual, meanPrediction, maxPrediction, maxResidualDeviation;
};

//! estimate() with \e threshold on the data of the noisy tests, each seed within the per-seed bounds; the statistics.
inline NoiseFloor estimateAtNoiseFloor(const Scene &scene, double threshold)
{
  NoiseFloor f = {0.0, 0.0, 0.0, 0.0};
  for (int seed = 1; seed <= kNoisySeeds; ++seed) {
    SCOPED_TRACE(::testing::Message() << "threshold " << threshold << " px, seed " << seed);
    const SeededMatches data(scene, 100 + seed, kNoisyMatches, kSigma, 200);
    vpProjectiveStereoRig rig;
    rig.estimate(data.left, data.right, threshold);
    Eigen::Matrix3d F;
    rig.getFundamentalMatrix(F);
    const double prediction = rmsEpipolarDistance(F, data.freshLeft, data.freshRight);
    const double residual = rig.getEstimationResidual();
    EXPECT_LT(prediction, 3.0 * expectedPrediction());
    EXPECT_NEAR(residual / expectedResidual(), 1.0, 0.35);
    f.meanResidual += residual / kNoisySeeds;
    f.meanPrediction += prediction / kNoisySeeds;
    f.maxPrediction = std::max(f.maxPrediction, prediction);
    f.maxResidualDeviation = std::max(f.maxResidualDeviation, std::abs(residual / expectedResidual() - 1.0));
  }
  return f;
}

/*
  Random wrong pairings: the right image points of nWrong random matches are permuted cyclically (seeded), as a
  matcher that confuses similar features does. Returns the wrong matches.
*/
inline std::vector<bool> mispair(vpUniRand &rng, size_t nWrong, std::vector<vpImagePoint> &right)
{
  const size_t n = right.size();
  std::vector<bool> wrong(n, false);
  std::vector<size_t> chosen;
  while (chosen.size() < nWrong) {
    const size_t i = static_cast<size_t>(rng.uniform(0, static_cast<int>(n)));
    if (!wrong[i]) {
      wrong[i] = true;
      chosen.push_back(i);
    }
  }
  const std::vector<vpImagePoint> original = right;
  for (size_t k = 0; k < nWrong; ++k) {
    right[chosen[k]] = original[chosen[(k + 1) % nWrong]];
  }
  return wrong;
}

// The normalised 8-point F of all the matches (rank 2, no robustness): what a least-squares estimate makes of them.
inline Eigen::Matrix3d eightPoint(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
{
  const auto normalisation = [](const std::vector<vpImagePoint> &points) {
    Eigen::Vector2d c = Eigen::Vector2d::Zero();
    for (const vpImagePoint &p : points) {
      c += pixel(p).head<2>() / static_cast<double>(points.size());
    }
    double d = 0.0;
    for (const vpImagePoint &p : points) {
      d += (pixel(p).head<2>() - c).norm() / static_cast<double>(points.size());
    }
    Eigen::Matrix3d T;
    T << std::sqrt(2.0) / d, 0, -std::sqrt(2.0) / d * c(0), 0, std::sqrt(2.0) / d, -std::sqrt(2.0) / d * c(1), 0, 0, 1;
    return T;
  };
  const Eigen::Matrix3d T = normalisation(left), Tp = normalisation(right);
  Eigen::MatrixXd A(left.size(), 9);
  for (size_t i = 0; i < left.size(); ++i) {
    const Eigen::Vector3d m = T * pixel(left[i]), mp = Tp * pixel(right[i]);
    for (int a = 0; a < 3; ++a) {
      for (int b = 0; b < 3; ++b) {
        A(static_cast<Eigen::Index>(i), 3 * a + b) = mp(a) * m(b);
      }
    }
  }
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  Eigen::Matrix3d Fn;
  for (int a = 0; a < 3; ++a) {
    Fn.row(a) = svd.matrixV().col(8).segment<3>(3 * a).transpose();
  }
  const Eigen::JacobiSVD<Eigen::Matrix3d> svdF(Fn, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Fn = svdF.matrixU() * Eigen::Vector3d(svdF.singularValues()(0), svdF.singularValues()(1), 0.0).asDiagonal() *
       svdF.matrixV().transpose();
  return Tp.transpose() * Fn * T;
}
} // namespace vpProjectiveTest

#endif
