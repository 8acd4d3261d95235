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

/*!
  Projective kinematics of a rotation seen by an uncalibrated stereo rig (Ruf & Horaud, ICCV'99, sections 2 to 5).

  A stereo rig that nobody calibrated watches 7 markers on a rigid body that rotates by 30 deg about an axis.
  From the images alone, the program
  1. weakly calibrates the rig: the fundamental matrix F from noisy matches of a random scene;
  2. images the 7 markers before and after the rotation;
  3. estimates the projective displacement H (4x4): linearly from triangulated points, then by maximum likelihood
     from the images;
  4. reads the rotation angle off H, eq. (21), and the generator Hhat of the rotation, eq. (25);
  5. compares them with the ground truth known to the simulator: Hhat = H_PE^-1 That H_PE, with That the metric
     twist of the axis in the left camera frame and H_PE the projective-to-Euclidean link (4) of the rig's frame.
  It then repeats the experiment over many noise seeds and prints the mean and maximum errors.

  Usage: projective-displacement [--seed N] [--noise SIGMA] [--seeds K] [--help]
*/

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

#include "command-line.h"
#include "displacement-truth.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace app; // the scene and its ground truth

namespace
{
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
  const vpProjectiveDisplacement Hlinear =
      vpProjectiveDisplacement::estimate(rig.triangulate(left0, right0), rig.triangulate(left1, right1));

  // Maximum-likelihood estimate: the H and points that best explain the four images (Ceres, from the linear one).
  const vpProjectiveDisplacement Hrefined = vpProjectiveDisplacement::estimate(rig, left0, right0, left1, right1);

  // Angle (21) and generator (25). The signed amount read by an encoder fixes the sign: H = exp(amount Hhat).
  const vpProjectiveDisplacement *H[2] = {&Hlinear, &Hrefined};
  Estimate *out[2] = {&linear, &refined};
  for (int k = 0; k < 2; ++k) {
    const vpProjectiveRotation R = vpProjectiveRotation::log(*H[k], scene.angle);
    out[k]->angle = vpMath::deg(H[k]->getRotationAngle());
    out[k]->angleError = std::fabs(out[k]->angle - vpMath::deg(scene.angle));
    const vpMatrix Hhat = toVpMatrix(R.generator());
    compare(Hhat, HhatTrue, Hpe, scene, sim, *out[k]);
    if (verbose && k == 1) {
      std::cout << "    refined H, normalised by eq. (12):" << std::endl;
      toVpMatrix(H[k]->matrix()).print(std::cout, 10, "");
    }
    if (verbose) {
      std::cout << "    generator Hhat (25) of the " << (k == 0 ? "linear" : "refined") << " H:" << std::endl;
      Hhat.print(std::cout, 10, "");
    }
  }
}
//! [Displacement]

/*!
  One experiment with noise seed \e seed and pixel noise \e sigma: steps 1 to 5 of the program. Prints every step
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

} // namespace

int main(int argc, char **argv)
{
  unsigned int seed = 1, seeds = 100;
  double sigma = 0.5;
  app::CommandLine cmd;
  cmd.add("--seed", seed, "N", "noise seed of the detailed run")
      .add("--noise", sigma, "SIGMA", "standard deviation of the pixel noise, px", 0.0)
      .add("--seeds", seeds, "K", "summary over seeds 1..K, 0 to skip it");
  int exitCode = EXIT_SUCCESS;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
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
              << "Detailed run: seed " << seed << ", noise " << sigma << " px" << std::endl
              << std::endl;

    // One experiment, printed step by step, then its errors next to the ground truth.
    const Result result = runExperiment(scene, seed, sigma, true);
    std::cout << std::endl;
    printResult(scene, result);

    // The same experiment over many seeds: errors before and after the non-linear refinement.
    if (seeds > 0) {
      std::cout << std::endl;
      const double t0 = vpTime::measureTimeMs();
      Summary summary;
      for (unsigned int s = 1; s <= seeds; ++s) {
        summary.add(runExperiment(scene, s, sigma, false));
      }
      summary.print(seeds, sigma, (vpTime::measureTimeMs() - t0) / 1000.0);
    }
    //! [Main]
  } catch (const vpException &e) {
    std::cerr << "Catch an exception: " << e.getMessage() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
