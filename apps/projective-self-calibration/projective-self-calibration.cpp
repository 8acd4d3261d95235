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
  Metric self-calibration for free: the projective model of an arm, acquired from images alone, holds the metric
  stereo rig (vpProjectiveRobot::getMetricStereoRig(): both cameras' intrinsics, skew included, and the right
  camera's pose in the left one), here compared with the simulator's truth and with ViSP's own calibration
  (vpCalibration) of the same rig from a planar target seen with the same pixel noise.

  1. Self-calibration: the paper's world (apps/projective-paper), the arm acquired by its trial motions at
     --noise px; the baseline's length comes from the distance between two markers (measured once with a ruler), the
     arm having no prismatic joint. The same with the markers spread twice as wide (a 20 cm pattern).
  2. ViSP's calibration: a planar grid of 6 x 5 points (10 cm wide, then 30 cm wide) seen by both cameras in 13 poses
     around 1 m (the acquisition's number of images), each camera calibrated by vpCalibration::computeCalibrationMulti()
     (virtual visual servoing, no distortion), the rig's pose from the two cameras' poses of the grid.
  3. The errors against the truth, median over the seeds: focal lengths, principal points, the rig's rotation,
     baseline direction and length.

  The principal point is the weak part of any calibration from a small pattern: its trade-off with the rotation of the
  whole rig is determined by the perspective of the pattern as it moves, which a 10 cm pattern 1 m away shows little
  of. A wider pattern (more markers spread further on the tool) or larger trial motions improve it.

  Usage: projective-self-calibration [--seeds N] [--noise SIGMA] [--help]
  Exits with 1 if the self-calibration's median focal length error exceeds 2 % or its rig rotation 2 deg.
*/

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/vision/vpCalibration.h>

#include <visp3/projective/vpProjectiveRobot.h>

#include "command-line.h"
#include "paper-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
//! Errors of a calibrated rig against the truth (worst of the two cameras for the intrinsics).
struct RigErrors {
  double focal;     //!< relative
  double principal; //!< px
  double rotation;  //!< deg, right camera's orientation in the left one
  double direction; //!< deg, baseline direction
  double length;    //!< relative, baseline length
};

RigErrors compare(const vpCameraParameters &camL, const vpCameraParameters &camR, const vpHomogeneousMatrix &lMr,
                  const vpSimulatorStereoRig &truth)
{
  const vpCameraParameters cams[2] = {camL, camR};
  const vpCameraParameters trueCams[2] = {truth.getLeftCameraParameters(), truth.getRightCameraParameters()};
  RigErrors e{0, 0, 0, 0, 0};
  for (int c = 0; c < 2; ++c) {
    e.focal = std::max({e.focal, std::abs(cams[c].get_px() / trueCams[c].get_px() - 1.0),
                        std::abs(cams[c].get_py() / trueCams[c].get_py() - 1.0)});
    e.principal = std::max({e.principal, std::abs(cams[c].get_u0() - trueCams[c].get_u0()),
                            std::abs(cams[c].get_v0() - trueCams[c].get_v0())});
  }
  const vpHomogeneousMatrix lMrTrue = truth.get_rMl().inverse();
  e.rotation = vpMath::deg(vpThetaUVector((lMrTrue.getRotationMatrix().t() * lMr.getRotationMatrix())).getTheta());
  const vpColVector b = lMr.getTranslationVector(), bTrue = lMrTrue.getTranslationVector();
  e.direction = vpMath::deg(
      std::acos(std::min(1.0, vpColVector::dotProd(b, bTrue) / (b.frobeniusNorm() * bTrue.frobeniusNorm()))));
  e.length = std::abs(b.frobeniusNorm() / bTrue.frobeniusNorm() - 1.0);
  return e;
}

//! [Self-calibration]
//! The arm acquired at sigma px, then the metric rig its model holds.
RigErrors selfCalibrate(const vpSimulatorArm &arm, const vpSimulatorStereoRig &rig, double sigma, unsigned int seed)
{
  vpGaussRand noise(sigma, 0.0, seed);
  const app::ImagesAt imagesAt = [&](const vpColVector &q, std::vector<vpImagePoint> &left,
                                     std::vector<vpImagePoint> &right) {
    return rig.project(arm.getMarkers(q), left, right, sigma, noise);
  };
  const vpProjectiveRobot robot =
      app::acquireByTrials({30, 20, 30, 40, 60, 60}, imagesAt, std::max(1.0, 4.0 * sigma), false);
  // The scale: two markers whose distance was measured with a ruler.
  const std::vector<vpColVector> &tMarkers = arm.getToolMarkers();
  const double distance = (tMarkers[0] - tMarkers[1]).frobeniusNorm();
  vpMatrix Kl, Kr;
  vpHomogeneousMatrix lMr;
  robot.getMetricStereoRig(Kl, Kr, lMr, 0, 1, distance);
  const vpCameraParameters camL(Kl[0][0], Kl[1][1], Kl[0][2], Kl[1][2]), camR(Kr[0][0], Kr[1][1], Kr[0][2], Kr[1][2]);
  return compare(camL, camR, lMr, rig);
}
//! [Self-calibration]

//! [Planar calibration]
//! ViSP's calibration of both cameras from 13 views of a 6 x 5 planar grid \e width metres wide, at sigma px.
RigErrors planarCalibrate(const vpSimulatorStereoRig &rig, double width, double sigma, unsigned int seed)
{
  vpGaussRand noise(sigma, 0.0, seed);
  vpUniRand uniform(seed);
  std::vector<vpCalibration> views[2];
  std::vector<vpHomogeneousMatrix> wMo;
  const vpColVector centre = rig.get_wMl() * vpColVector({0.0, 0.0, 1.0, 1.0}); // 1 m in front of the left camera
  while (wMo.size() < 13) {
    // The grid 1 m away, tilted by up to 30 deg about its axes, placed where the rig sees all of it.
    // Drawn last to first, the order g++ evaluated them in as the arguments of one call (C++ leaves that order
    // unspecified; the documented figures were measured with g++): the same poses whichever the compiler.
    const double tuz = vpMath::rad(uniform.uniform(-180, 180));
    const double tuy = vpMath::rad(uniform.uniform(-30, 30));
    const double tux = vpMath::rad(uniform.uniform(-30, 30));
    const double z = centre[2] + uniform.uniform(-0.1, 0.1);
    const double y = centre[1] + uniform.uniform(-0.05, 0.05);
    const double x = centre[0] + uniform.uniform(-0.05, 0.05);
    const vpHomogeneousMatrix M(x, y, z, tux, tuy, tuz);
    vpCalibration calib[2];
    bool visible = true;
    for (int i = 0; i < 6 && visible; ++i) {
      for (int j = 0; j < 5 && visible; ++j) {
        const double X = width * (i / 5.0 - 0.5), Y = 0.8 * width * (j / 4.0 - 0.5);
        const vpColVector wX = M * vpColVector({X, Y, 0.0, 1.0});
        vpImagePoint ip[2];
        visible = rig.isVisible(vpColVector({wX[0], wX[1], wX[2]}), 5.0) &&
                  rig.project(vpColVector({wX[0], wX[1], wX[2]}), ip[0], ip[1], sigma, noise);
        for (int c = 0; c < 2; ++c) {
          calib[c].addPoint(X, Y, 0.0, ip[c]);
        }
      }
    }
    if (visible) {
      wMo.push_back(M);
      views[0].push_back(calib[0]);
      views[1].push_back(calib[1]);
    }
  }
  vpCameraParameters cam[2];
  for (int c = 0; c < 2; ++c) {
    // The virtual visual servoing starts from a rough guess (a focal length 15 % off, the image centre 20 px off):
    // what a user knows from the lens and the sensor.
    cam[c].initPersProjWithoutDistortion(1400.0, 1400.0, 340.0, 220.0);
    double residual = 0.0;
    vpCalibration::computeCalibrationMulti(vpCalibration::CALIB_VIRTUAL_VS, views[c], cam[c], residual);
  }
  // The rig from the grid's poses in both cameras, lMr = lMo rMo^-1, averaged over the views.
  vpColVector t(3, 0.0), thetaU(3, 0.0);
  for (size_t k = 0; k < wMo.size(); ++k) {
    const vpHomogeneousMatrix lMr = views[0][k].cMo * views[1][k].cMo.inverse();
    t += lMr.getTranslationVector() / wMo.size();
    thetaU += vpColVector(vpThetaUVector(lMr.getRotationMatrix())) / wMo.size();
  }
  const vpHomogeneousMatrix lMr(vpTranslationVector(t[0], t[1], t[2]), vpThetaUVector(thetaU[0], thetaU[1], thetaU[2]));
  return compare(cam[0], cam[1], lMr, rig);
}
//! [Planar calibration]

double medianOf(const std::vector<RigErrors> &runs, double RigErrors::*field)
{
  std::vector<double> x;
  for (const RigErrors &r : runs) {
    x.push_back(r.*field);
  }
  return app::median(x);
}
} // namespace

int main(int argc, char **argv)
{
  unsigned int seeds = 10;
  double sigma = 0.5;
  app::CommandLine cmd;
  cmd.add("--seeds", seeds, "N", "number of noise seeds", 1)
      .add("--noise", sigma, "SIGMA", "pixel noise (px, Gaussian, every image coordinate)", 0.0);
  int exitCode = 0;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
  }
  try {
    const app::PaperWorld world;
    std::vector<vpColVector> wide = vpSimulatorArm::gripperMarkers(); // the same markers, spread twice as wide
    for (vpColVector &X : wide) {
      X *= 2.0;
    }
    const vpSimulatorArm wideArm(vpSimulatorArm::pumaTable(), vpSimulatorArm::gripperMount(), wide,
                                 vpSimulatorArm::paperBasePose());
    const char *names[4] = {"self-calibration, 7 markers on 10 cm", "self-calibration, 7 markers on 20 cm",
                            "vpCalibration, 6 x 5 grid 10 cm wide", "vpCalibration, 6 x 5 grid 30 cm wide"};
    std::vector<RigErrors> runs[4];
    for (unsigned int seed = 1; seed <= seeds; ++seed) {
      runs[0].push_back(selfCalibrate(world.arm, world.rig, sigma, seed));
      runs[1].push_back(selfCalibrate(wideArm, world.rig, sigma, seed));
      runs[2].push_back(planarCalibrate(world.rig, 0.10, sigma, seed));
      runs[3].push_back(planarCalibrate(world.rig, 0.30, sigma, seed));
    }
    const vpCameraParameters cam = world.rig.getLeftCameraParameters();
    std::cout << std::setprecision(3) << "The rig's truth: px = py = " << cam.get_px() << " px, (u0, v0) = ("
              << cam.get_u0() << ", " << cam.get_v0() << ") px, baseline "
              << world.rig.get_rMl().getTranslationVector().frobeniusNorm() << " m\n\nErrors at " << sigma
              << " px, median over " << seeds << " seeds:\n"
              << "| method | focal length | principal point | rig rotation | baseline direction | baseline length "
                 "|\n|---|---|---|---|---|---|\n";
    for (int m = 0; m < 4; ++m) {
      std::cout << "| " << names[m] << " | " << 100 * medianOf(runs[m], &RigErrors::focal) << " % | "
                << medianOf(runs[m], &RigErrors::principal) << " px | " << medianOf(runs[m], &RigErrors::rotation)
                << " deg | " << medianOf(runs[m], &RigErrors::direction) << " deg | "
                << 100 * medianOf(runs[m], &RigErrors::length) << " % |\n";
    }
    const bool ok = medianOf(runs[0], &RigErrors::focal) <= 0.02 && medianOf(runs[0], &RigErrors::rotation) <= 2.0;
    return ok ? 0 : 1;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return 1;
  }
}
