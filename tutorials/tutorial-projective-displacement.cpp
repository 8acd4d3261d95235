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

//! \example tutorial-projective-displacement.cpp
/*!
  Projective kinematics of a rotation seen by an uncalibrated stereo rig (Ruf & Horaud, ICCV'99, sections 2 to 5).

  A stereo rig that nobody calibrated watches 7 markers on a rigid body that rotates by 30 deg about an axis.
  From the images alone, the tutorial
  1. weakly calibrates the rig: the fundamental matrix F from noisy matches of a random scene;
  2. images the 7 markers before and after the rotation;
  3. estimates the projective displacement H (4x4): linearly from triangulated points, then by maximum likelihood
     from the images;
  4. reads the rotation angle off H, eq. (21), and the generator Hhat of the rotation, eq. (25);
  5. compares them with the ground truth known to the simulator: Hhat = H_PE^-1 That H_PE, with That the metric
     twist of the axis in the left camera frame and H_PE the projective-to-Euclidean link (4) of the rig's frame.
  It then repeats the experiment over many noise seeds and prints the mean and maximum errors.

  Usage: tutorial-projective-displacement [--seed N] [--noise SIGMA] [--seeds K] [--help]
*/

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTime.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
//! [Scene]
//! The metric world, known only to the simulator: markers, motion and the scene used for the weak calibration.
struct Scene {
  vpColVector fixation;             // world point (m) the rig verges on, 1 m in front of its midpoint
  std::vector<vpColVector> markers; // 7 markers on a ~10 cm rigid body, no 4 coplanar (world frame, m)
  vpColVector axisPoint;            // a point on the rotation axis (world frame, m)
  vpColVector axisDirection;        // unit direction of the rotation axis (world frame)
  double angle;                     // rotation angle (rad)
  unsigned int nbCalibrationPoints; // random scene points matched to estimate F
  double calibrationBox;            // side (m) of the cube around the fixation point they are drawn in
};

Scene buildScene()
{
  Scene scene;
  // The rig's midpoint is the world origin; it looks along the world +Z axis (X to the right, Y down in the images).
  scene.fixation = vpColVector({0.0, 0.0, 1.0});
  // Marker offsets (m) from the fixation point: any 4 of them are at least 1 cm away from a common plane.
  const double offsets[7][3] = {{0.05, 0.05, -0.01},  {-0.03, 0.00, 0.04}, {0.00, -0.02, 0.04},  {0.03, -0.04, -0.01},
                                {-0.02, 0.04, -0.03}, {0.04, 0.04, 0.03},  {-0.04, -0.04, -0.01}};
  for (unsigned int j = 0; j < 7; ++j) {
    scene.markers.push_back(vpColVector(
        {scene.fixation[0] + offsets[j][0], scene.fixation[1] + offsets[j][1], scene.fixation[2] + offsets[j][2]}));
  }
  // A general axis: 7 cm away from the body's centre, parallel to none of the camera axes.
  scene.axisPoint = vpColVector({0.06, -0.03, 1.02});
  scene.axisDirection = vpColVector({0.3, 0.8, 0.5});
  scene.axisDirection.normalize();
  scene.angle = vpMath::rad(30.0);
  scene.nbCalibrationPoints = 50;
  scene.calibrationBox = 0.40;
  return scene;
}
//! [Scene]

//! [Twist]
/*!
  Unit-speed metric twist (4x4 matrix of se(3)) of the rotation about the axis through \e p with unit direction
  \e w: d/dtheta (R(theta) (X - p) + p) = [w]x X - [w]x p at theta = 0.
*/
vpMatrix rotationTwist(const vpColVector &p, const vpColVector &w)
{
  const vpMatrix wx = vpColVector::skew(w);
  const vpColVector v = -(wx * p);
  vpMatrix T(4, 4, 0.0);
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int k = 0; k < 3; ++k) {
      T[i][k] = wx[i][k];
    }
    T[i][3] = v[i];
  }
  return T;
}
//! [Twist]

//! [Link]
/*!
  Ground-truth link H_PE (N ~ H_PE M) of the projective frame of \e rig, fitted over the workspace: the noise-free
  images of the world points \e wX are triangulated in the rig's frame (M) and matched with their metric left-camera
  coordinates (N); the 3D homography between them is the linear fit of vpProjectiveDisplacement (a DLT of any 3D
  homography; its scale and sign do not matter here). For the true F this is H_PE exactly; for an estimated F,
  whose frame no homography maps exactly onto the metric cameras, it is the homography that best explains the
  workspace.
*/
vpMatrix projectiveToEuclidean(const vpSimulatorStereoRig &sim, const vpProjectiveStereoRig &rig,
                               const std::vector<vpColVector> &wX)
{
  const vpHomogeneousMatrix lMw = sim.get_wMl().inverse();
  std::vector<vpColVector> M, N;
  for (size_t k = 0; k < wX.size(); ++k) {
    vpImagePoint ipLeft, ipRight;
    sim.project(wX[k], ipLeft, ipRight); // no noise: only the simulator can do this
    M.push_back(rig.triangulate(ipLeft, ipRight));
    N.push_back(vpColVector(lMw * vpColVector({wX[k][0], wX[k][1], wX[k][2], 1.0})));
  }
  return vpProjectiveDisplacement::estimate(M, N).getMatrix();
}
//! [Link]

//! Angle (deg) between two fundamental matrices seen as 9-vectors, up to scale and sign.
double angleBetween(const vpMatrix &F1, const vpMatrix &F2)
{
  double dot = 0.0;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      dot += F1[i][j] * F2[i][j];
    }
  }
  const double c = std::fabs(dot) / (F1.frobeniusNorm() * F2.frobeniusNorm());
  return vpMath::deg(std::acos(std::min(1.0, c)));
}

//! RMS distance (px) of the noise-free images of \e wX to the epipolar lines of \e F, in both images.
double epipolarError(const vpSimulatorStereoRig &sim, const vpMatrix &F, const std::vector<vpColVector> &wX)
{
  double sum = 0.0;
  for (size_t k = 0; k < wX.size(); ++k) {
    vpImagePoint ipLeft, ipRight;
    sim.project(wX[k], ipLeft, ipRight);
    const vpColVector m({ipLeft.get_u(), ipLeft.get_v(), 1.0});
    const vpColVector mp({ipRight.get_u(), ipRight.get_v(), 1.0});
    const vpColVector l = F * m;                  // epipolar line of m in the right image
    const vpColVector lp = F.transpose() * mp;    // epipolar line of m' in the left image
    const double r = vpColVector::dotProd(mp, l); // m'^T F m
    sum += r * r / (l[0] * l[0] + l[1] * l[1]) + r * r / (lp[0] * lp[0] + lp[1] * lp[1]);
  }
  return std::sqrt(sum / (2.0 * wX.size()));
}

//! One estimate of the motion and its errors against the ground truth of the same projective frame.
struct Estimate {
  double angle;          // eq. (21), deg
  double angleError;     // |angle - true angle|, deg
  double generatorError; // ||Hhat - Hhat_true||_F / ||Hhat_true||_F
  double axisError;      // angle (deg) between the true axis and the estimated one (fixed points of Hhat)
  double offsetError;    // distance (mm) from the true axis' point nearest the body to the estimated axis
};

//! Everything one experiment produces.
struct Result {
  double fResidual;     // RMS reprojection residual of the weak calibration (px)
  unsigned int inliers; // matches kept by the robust estimation of F
  double fEpipolar;     // RMS distance of noise-free matches to the estimated epipolar lines (px)
  double fAngle;        // angle between estimated and true F (deg)
  double frameDistance; // ||Hhat_true(estimated F frame) - Hhat_true(true F frame)||_F / ||Hhat_true(true F frame)||_F
  Estimate linearEst;   // linear, from triangulated points, in the frame of the estimated F
  Estimate refinedEst;  // refined from the images, in the frame of the estimated F
  Estimate linearTrue;  // linear, in the frame of the true F
  Estimate refinedTrue; // refined, in the frame of the true F
};

//! Errors of the generator \e Hhat (4x4) against the ground truth of its frame (link \e Hpe, generator \e HhatTrue).
void compare(const vpMatrix &Hhat, const vpMatrix &HhatTrue, const vpMatrix &Hpe, const Scene &scene,
             const vpSimulatorStereoRig &sim, Estimate &e)
{
  e.generatorError = (Hhat - HhatTrue).frobeniusNorm() / HhatTrue.frobeniusNorm();

  // The axis is the line of fixed points of the motion, the kernel of Hhat (rank 2). Mapped to metric left-camera
  // coordinates by H_PE, then to the world, it is spanned by two homogeneous points: a direction (last entry 0) and
  // a finite point (last entry 1).
  vpMatrix kernel;
  (Hpe * Hhat * Hpe.inverseByLU()).nullSpace(kernel, 2);
  const vpMatrix wKernel = vpMatrix(sim.get_wMl()) * kernel;
  const double a0 = wKernel[3][0], a1 = wKernel[3][1];
  const vpColVector d = wKernel * vpColVector({a1, -a0});
  const vpColVector X = wKernel * vpColVector({a0, a1});
  const vpColVector w = vpColVector(d.extract(0, 3)).normalize();
  const vpColVector p = X.extract(0, 3) / X[3];
  e.axisError = vpMath::deg(std::acos(std::min(1.0, std::fabs(vpColVector::dotProd(w, scene.axisDirection)))));

  // Distance from the point of the true axis nearest the body's centre to the estimated axis.
  vpColVector centre(3, 0.0);
  for (size_t j = 0; j < scene.markers.size(); ++j) {
    centre += scene.markers[j] / static_cast<double>(scene.markers.size());
  }
  const vpColVector &a = scene.axisDirection;
  const vpColVector q = scene.axisPoint + vpColVector::dotProd(centre - scene.axisPoint, a) * a;
  e.offsetError = 1000.0 * vpColVector::cross(q - p, w).frobeniusNorm();
}

//! [Displacement]
/*!
  Steps 3 and 4 in the projective frame of \e rig: the displacement (linear, then refined), its angle (21) and its
  generator (25), compared with the ground truth of that frame.
*/
void estimateMotion(const vpProjectiveStereoRig &rig, const std::vector<vpImagePoint> &left0,
                    const std::vector<vpImagePoint> &right0, const std::vector<vpImagePoint> &left1,
                    const std::vector<vpImagePoint> &right1, const Scene &scene, const vpSimulatorStereoRig &sim,
                    const vpMatrix &Hpe, const vpMatrix &HhatTrue, Estimate &linear, Estimate &refined, bool verbose)
{
  // Linear estimate: triangulate every marker before (M0) and after (M1) the motion, then M1 ~ H M0 (DLT).
  std::vector<vpColVector> M0, M1;
  for (size_t j = 0; j < left0.size(); ++j) {
    M0.push_back(rig.triangulate(left0[j], right0[j]));
    M1.push_back(rig.triangulate(left1[j], right1[j]));
  }
  const vpProjectiveDisplacement Hlinear = vpProjectiveDisplacement::estimate(M0, M1);

  // Maximum-likelihood estimate: the H and points that best explain the four images (Ceres, from the linear one).
  const vpProjectiveDisplacement Hrefined = vpProjectiveDisplacement::estimate(rig, left0, right0, left1, right1);

  // Angle (21) and generator (25). The signed amount read by an encoder fixes the sign: H = exp(amount Hhat).
  const vpProjectiveDisplacement *H[2] = {&Hlinear, &Hrefined};
  Estimate *out[2] = {&linear, &refined};
  for (int k = 0; k < 2; ++k) {
    const vpProjectiveRotation R = vpProjectiveRotation::log(*H[k], scene.angle);
    out[k]->angle = vpMath::deg(H[k]->getRotationAngle());
    out[k]->angleError = std::fabs(out[k]->angle - vpMath::deg(scene.angle));
    compare(R.getGenerator(), HhatTrue, Hpe, scene, sim, *out[k]);
    if (verbose && k == 1) {
      std::cout << "    refined H, normalised by eq. (12):" << std::endl;
      H[k]->getMatrix().print(std::cout, 10, "");
    }
    if (verbose) {
      std::cout << "    generator Hhat (25) of the " << (k == 0 ? "linear" : "refined") << " H:" << std::endl;
      R.getGenerator().print(std::cout, 10, "");
    }
  }
}
//! [Displacement]

/*!
  One experiment with noise seed \e seed and pixel noise \e sigma: steps 1 to 5 of the tutorial. Prints every step
  when \e verbose.
*/
Result runExperiment(const Scene &scene, unsigned int seed, double sigma, bool verbose)
{
  //! [Rig]
  // The paper's rig: 20 cm baseline, 12.5 mm lenses on a 1/3 inch CCD (640 x 480), verging on a point 1 m away.
  const vpSimulatorStereoRig sim = vpSimulatorStereoRig::paperRig(scene.fixation, 1.0);
  vpGaussRand noise(1.0, 0.0, static_cast<long>(seed)); // pixel noise, reproducible
  vpUniRand uniform(seed);                              // random scene for the weak calibration
  //! [Rig]

  //! [Weak calibration]
  // 1. Weak calibration. Noisy matches of random scene points, all visible in both images, give F and with it the
  // projective frame of the rig: P = [I|0], P' = [[e']x F + e' e'^T | e'].
  std::vector<vpColVector> scenePoints;
  std::vector<vpImagePoint> left, right;
  const double h = 0.5 * scene.calibrationBox;
  while (scenePoints.size() < scene.nbCalibrationPoints) {
    const vpColVector X({scene.fixation[0] + uniform.uniform(-h, h), scene.fixation[1] + uniform.uniform(-h, h),
                         scene.fixation[2] + uniform.uniform(-h, h)});
    if (sim.isVisible(X, 5.0)) {
      vpImagePoint ipLeft, ipRight;
      sim.project(X, ipLeft, ipRight, sigma, noise);
      scenePoints.push_back(X);
      left.push_back(ipLeft);
      right.push_back(ipRight);
    }
  }
  vpProjectiveStereoRig rig;
  rig.estimate(left, right);

  // The rig of the true F, which the simulator alone knows: the reference for a comparison free of F's error.
  vpProjectiveStereoRig rigTrue;
  rigTrue.setFundamentalMatrix(sim.getFundamentalMatrix());

  Result result;
  result.fResidual = rig.getEstimationResidual();
  result.inliers = static_cast<unsigned int>(std::count(rig.getInliers().begin(), rig.getInliers().end(), true));
  result.fEpipolar = epipolarError(sim, rig.getFundamentalMatrix(), scenePoints);
  result.fAngle = angleBetween(rig.getFundamentalMatrix(), sim.getFundamentalMatrix());
  //! [Weak calibration]

  //! [Images]
  // 2. Images of the markers before and after the rotation, with Gaussian noise of sigma pixels.
  const vpHomogeneousMatrix wT = vpSimulatorStereoRig::rotationAbout(scene.axisPoint, scene.axisDirection, scene.angle);
  const std::vector<vpColVector> moved = vpSimulatorStereoRig::transform(wT, scene.markers);
  std::vector<vpImagePoint> left0, right0, left1, right1;
  const bool visible0 = sim.project(scene.markers, left0, right0, sigma, noise);
  const bool visible1 = sim.project(moved, left1, right1, sigma, noise);
  if (!visible0 || !visible1) {
    throw vpException(vpException::fatalError, "a marker leaves the images; move the body or the axis");
  }
  //! [Images]

  //! [Ground truth]
  // 5. Ground truth of the generator in a projective frame: Hhat_true = H_PE^-1 That H_PE, That the unit-speed twist
  // of the axis in the left camera frame (it does not depend on the scale of H_PE). Two frames:
  // - "true F": the frame of the true F, where H_PE is exact (vpSimulatorStereoRig::getProjectiveToEuclidean());
  // - "estimated F": the frame an application works in. It is not exactly a frame of the metric rig, so its H_PE is
  //   the homography fitted over the workspace (calibration scene and markers), see projectiveToEuclidean().
  const vpMatrix That = sim.toCameraFrame(rotationTwist(scene.axisPoint, scene.axisDirection));
  const vpMatrix HpeTrue = sim.getProjectiveToEuclidean(rigTrue);
  std::vector<vpColVector> workspace = scenePoints;
  workspace.insert(workspace.end(), scene.markers.begin(), scene.markers.end());
  workspace.insert(workspace.end(), moved.begin(), moved.end());
  const vpMatrix HpeEst = projectiveToEuclidean(sim, rig, workspace);
  const vpMatrix HhatTrue = HpeTrue.inverseByLU() * That * HpeTrue;
  const vpMatrix HhatTrueEst = HpeEst.inverseByLU() * That * HpeEst;
  result.frameDistance = (HhatTrueEst - HhatTrue).frobeniusNorm() / HhatTrue.frobeniusNorm();
  //! [Ground truth]

  if (verbose) {
    std::cout << "1. Weak calibration from " << left.size() << " noisy matches (sigma = " << sigma << " px)"
              << std::endl
              << "    inliers kept: " << result.inliers << " / " << left.size()
              << ", their RMS reprojection residual: " << result.fResidual << " px" << std::endl
              << "    RMS distance of the noise-free matches to the estimated epipolar lines: " << result.fEpipolar
              << " px" << std::endl
              << "    angle between estimated and true F (9-vectors): " << result.fAngle << " deg" << std::endl
              << "    true generator in the estimated-F frame vs in the true-F frame: relative difference "
              << result.frameDistance << std::endl
              << std::endl
              << "2. Marker images (px) before (0) and after (1) the rotation, left and right (')" << std::endl;
    std::cout << "    " << std::setw(6) << "marker";
    const char *headers[8] = {"u0", "v0", "u0'", "v0'", "u1", "v1", "u1'", "v1'"};
    for (int c = 0; c < 8; ++c) {
      std::cout << std::setw(10) << headers[c];
    }
    std::cout << std::endl << std::fixed << std::setprecision(2);
    for (size_t j = 0; j < left0.size(); ++j) {
      const vpImagePoint *ips[4] = {&left0[j], &right0[j], &left1[j], &right1[j]};
      std::cout << "    " << std::setw(6) << j;
      for (int c = 0; c < 4; ++c) {
        std::cout << std::setw(10) << ips[c]->get_u() << std::setw(10) << ips[c]->get_v();
      }
      std::cout << std::endl;
    }
    std::cout.unsetf(std::ios::floatfield);
    std::cout << std::setprecision(6) << std::endl
              << "3-4. Projective displacement and generator in the estimated-F frame" << std::endl
              << "    true generator H_PE^-1 That H_PE (H_PE fitted over the workspace, see projectiveToEuclidean()):"
              << std::endl;
    HhatTrueEst.print(std::cout, 10, "");
  }

  //! [Estimation]
  // 3-4. The displacement, its angle and its generator in both frames: the estimated-F one is what an application
  // gets; the true-F one isolates the error of the displacement estimate.
  estimateMotion(rig, left0, right0, left1, right1, scene, sim, HpeEst, HhatTrueEst, result.linearEst,
                 result.refinedEst, verbose);
  estimateMotion(rigTrue, left0, right0, left1, right1, scene, sim, HpeTrue, HhatTrue, result.linearTrue,
                 result.refinedTrue, false);
  //! [Estimation]
  return result;
}

//! Mean and maximum of a series.
struct Stats {
  double sum = 0.0, max = 0.0;
  unsigned int n = 0;
  void add(double x)
  {
    sum += x;
    max = std::max(max, x);
    ++n;
  }
  double mean() const { return n > 0 ? sum / n : 0.0; }
};

const char *const kMethods[4] = {"linear (triangulated)", "refined (images, Ceres)", "linear (triangulated)",
                                 "refined (images, Ceres)"};
const char *const kFrames[4] = {"estimated F", "estimated F", "true F", "true F"};

void printHeader(const char *const columns[], int n)
{
  std::cout << "    " << std::left << std::setw(25) << "method" << std::setw(13) << "frame" << std::right;
  for (int c = 0; c < n; ++c) {
    std::cout << std::setw(11) << columns[c];
  }
  std::cout << std::endl;
}

//! Prints the errors of one run next to the ground truth.
void printResult(const Scene &scene, const Result &r)
{
  const char *const columns[6] = {"angle", "angle err", "gen. err", "axis err", "offset err"};
  std::cout << "5. Results next to the ground truth" << std::endl
            << "   angle (deg): eq. (21); gen. err: ||Hhat - Hhat_true||_F / ||Hhat_true||_F in the same frame;"
            << std::endl
            << "   axis err (deg), offset err (mm): axis of fixed points of Hhat, mapped to metric by H_PE, against the"
            << std::endl
            << "   true axis (offset: distance between the two axes at the body)" << std::endl;
  printHeader(columns, 5);
  std::cout << "    " << std::left << std::setw(25) << "ground truth" << std::setw(13) << "-" << std::right
            << std::fixed << std::setprecision(4) << std::setw(11) << vpMath::deg(scene.angle) << std::setw(11) << 0.0
            << std::setw(11) << 0.0 << std::setw(11) << 0.0 << std::setw(11) << 0.0 << std::endl;
  const Estimate *e[4] = {&r.linearEst, &r.refinedEst, &r.linearTrue, &r.refinedTrue};
  for (int k = 0; k < 4; ++k) {
    std::cout << "    " << std::left << std::setw(25) << kMethods[k] << std::setw(13) << kFrames[k] << std::right
              << std::setw(11) << e[k]->angle << std::setw(11) << e[k]->angleError << std::setw(11)
              << e[k]->generatorError << std::setw(11) << e[k]->axisError << std::setw(11) << e[k]->offsetError
              << std::endl;
  }
  std::cout.unsetf(std::ios::floatfield);
  std::cout << std::setprecision(6);
}

//! Repeats the experiment over seeds 1..K and prints mean and maximum errors before and after the refinement.
void printSummary(const Scene &scene, unsigned int seeds, double sigma)
{
  const double t0 = vpTime::measureTimeMs();
  Stats fAngle, fEpipolar, angle[4], generator[4], axis[4], offset[4];
  for (unsigned int seed = 1; seed <= seeds; ++seed) {
    const Result r = runExperiment(scene, seed, sigma, false);
    const Estimate *e[4] = {&r.linearEst, &r.refinedEst, &r.linearTrue, &r.refinedTrue};
    fAngle.add(r.fAngle);
    fEpipolar.add(r.fEpipolar);
    for (int k = 0; k < 4; ++k) {
      angle[k].add(e[k]->angleError);
      generator[k].add(e[k]->generatorError);
      axis[k].add(e[k]->axisError);
      offset[k].add(e[k]->offsetError);
    }
  }
  std::cout << "Summary over seeds 1.." << seeds << " at " << sigma << " px (" << std::setprecision(3)
            << (vpTime::measureTimeMs() - t0) / 1000.0 << " s)" << std::endl
            << "    weak calibration: RMS epipolar error of the noise-free matches, mean " << fEpipolar.mean()
            << " px, max " << fEpipolar.max << " px" << std::endl
            << "    angle between the estimated and the true F: mean " << fAngle.mean() << " deg, max " << fAngle.max
            << " deg" << std::endl;
  const char *const columns[8] = {"angle mean", "angle max", "gen. mean", "gen. max", "axis mean", "offs. mean"};
  printHeader(columns, 6);
  std::cout << std::fixed << std::setprecision(4);
  for (int k = 0; k < 4; ++k) {
    std::cout << "    " << std::left << std::setw(25) << kMethods[k] << std::setw(13) << kFrames[k] << std::right
              << std::setw(11) << angle[k].mean() << std::setw(11) << angle[k].max << std::setw(11)
              << generator[k].mean() << std::setw(11) << generator[k].max << std::setw(11) << axis[k].mean()
              << std::setw(11) << offset[k].mean() << std::endl;
  }
  std::cout.unsetf(std::ios::floatfield);
  std::cout << std::setprecision(6);
}

//! Command-line options.
struct Options {
  unsigned int seed = 1;
  double sigma = 0.5;
  unsigned int seeds = 100;
};

//! Reads the command line; returns false when the program should stop (help requested or invalid option).
bool parseOptions(int argc, char **argv, Options &opt, bool &error)
{
  error = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seed" && i + 1 < argc) {
      opt.seed = static_cast<unsigned int>(std::atoi(argv[++i]));
    } else if (arg == "--noise" && i + 1 < argc) {
      opt.sigma = std::atof(argv[++i]);
    } else if (arg == "--seeds" && i + 1 < argc) {
      opt.seeds = static_cast<unsigned int>(std::atoi(argv[++i]));
    } else {
      error = (arg != "--help" && arg != "-h");
      if (error) {
        std::cerr << "Unknown option or missing value: " << arg << std::endl;
      }
      std::cout << "Usage: " << argv[0] << " [--seed N] [--noise SIGMA] [--seeds K] [--help]" << std::endl
                << "  --seed N       noise seed of the detailed run (default 1)" << std::endl
                << "  --noise SIGMA  standard deviation of the pixel noise, px (default 0.5)" << std::endl
                << "  --seeds K      summary over seeds 1..K, 0 to skip it (default 100)" << std::endl
                << "  --help         print this help" << std::endl;
      return false;
    }
  }
  if (!(opt.sigma >= 0.0) || !std::isfinite(opt.sigma)) {
    std::cerr << "--noise needs a non-negative number of pixels" << std::endl;
    error = true;
    return false;
  }
  return true;
}
} // namespace

int main(int argc, char **argv)
{
  Options opt;
  bool error = false;
  if (!parseOptions(argc, argv, opt, error)) {
    return error ? EXIT_FAILURE : EXIT_SUCCESS;
  }
  try {
    //! [Main]
    const Scene scene = buildScene();
    const vpSimulatorStereoRig sim = vpSimulatorStereoRig::paperRig(scene.fixation, 1.0);
    std::cout << "Paper rig: baseline " << sim.get_rMl().getTranslationVector().frobeniusNorm() << " m, vergence "
              << vpMath::deg(vpThetaUVector(sim.get_rMl().getRotationMatrix()).getTheta()) << " deg, fixation 1 m away"
              << std::endl
              << scene.markers.size() << " markers rotate by " << vpMath::deg(scene.angle)
              << " deg about a general axis" << std::endl
              << "Detailed run: seed " << opt.seed << ", noise " << opt.sigma << " px" << std::endl
              << std::endl;

    // One experiment, printed step by step, then its errors next to the ground truth.
    const Result result = runExperiment(scene, opt.seed, opt.sigma, true);
    std::cout << std::endl;
    printResult(scene, result);

    // The same experiment over many seeds: errors before and after the non-linear refinement.
    if (opt.seeds > 0) {
      std::cout << std::endl;
      printSummary(scene, opt.seeds, opt.sigma);
    }
    //! [Main]
  } catch (const vpException &e) {
    std::cerr << "Catch an exception: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
