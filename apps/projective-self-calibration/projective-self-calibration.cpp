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
  The self-calibration study: the metric stereo rig that an arm's projective model gives for free
  (vpProjectiveSelfCalibration: the metric bundle adjustment over the acquisition and calibration frames at random
  configurations), beside ViSP's own calibration (vpCalibration) of the same rig from as many views of a planar grid
  at the same noise.

  Worlds (calibration-world.h): the PUMA-like arm, ViSP's Viper850 and the R-R-P-R-R-R arm, each carrying the
  gripper's 7 markers (10 cm), watched by a random verged rig of two different cameras with skew and unequal focal
  lengths, drawn per seed. Per seed and arm:
  1. the acquisition (13 images: each joint's trial both ways) and --frames frames at random readings within
     +---range deg of the zero reference's (prismatic: 2 mm per deg), all at --noise px; the fundamental matrix
     estimated from the acquisition's images;
  2. the self-calibration from the acquisition alone, then from the acquisition and the frames, each with its
     standard deviations; the baseline's length from the prismatic joint's encoder (R-R-P-R-R-R) or from the distance
     between two markers (the other arms: measured once with a ruler);
  3. vpCalibration of the same rig from as many views of a --grid-points x --grid-points grid --grid-width m wide,
     and of the same rig without skew (vpCalibration's camera model has none).
  The table gives each parameter's error (the worst of both cameras for the intrinsics), median / worst over the
  seeds, and how often the self-calibration's stated standard deviations cover its errors (every component within
  3 sigma).

  With --bound, instead of vpCalibration: what the data allows (what-the-data-allows.cpp), the Cramer-Rao bound of
  these frames at the true parameters beside the self-calibration's errors and stated deviations, with parameters
  known, and of more, wider and suggested frames.

  Usage: projective-self-calibration [--seeds N] [--first S] [--noise SIGMA] [--frames N] [--range DEG] [--arm NAME]
                                     [--grid-points N] [--grid-width M] [--grid-views N] [--grid-seeds N] [--bound]
  (vpCalibration's virtual visual servoing takes most of the time: about 10 s of CPU per camera with 43 views.)
  Exits with 1 if a self-calibration's median focal length error exceeds 1 % or its rig rotation 1 deg.
*/

#include <algorithm>
#include <iomanip>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "calibration-world.h"
#include "command-line.h"
#include "information-bound.h"
#include "paper-world.h"
#include "planar-calibration.h"
#include "rig-errors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
enum Method { ACQUISITION, SELF_CALIBRATION, GRID, GRID_NO_SKEW, METHODS };
const char *const kMethods[METHODS] = {"self-calibration, acquisition only", "self-calibration, acquisition + frames",
                                       "vpCalibration, same rig", "vpCalibration, same rig without skew"};

//! [Self-calibration]
//! The rig of the self-calibration over \e frames, its lengths in the prismatic joints' unit or a marker distance's.
selfcal::RigErrors selfCalibrate(const vpProjectiveRobot &robot, const selfcal::StudyArm &arm,
                                 const selfcal::SkewedRig &rig,
                                 const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames)
{
  const vpProjectiveSelfCalibration calibration = selfcal::selfCalibration(robot, arm, frames);
  Eigen::Matrix3d Kl, Kr;
  Eigen::Matrix4d lMr;
  calibration.getMetricStereoRig(Kl, Kr, lMr);
  return selfcal::compare(Kl, Kr, lMr, rig, true, &calibration.getUncertainty());
}
//! [Self-calibration]

void printTable(const std::vector<selfcal::RigErrors> (&runs)[METHODS])
{
  std::cout << std::defaultfloat << std::setprecision(3) << "| method |";
  for (int p = 0; p < selfcal::PARAMETERS; ++p) {
    std::cout << " " << selfcal::nameOf(selfcal::Parameter(p)) << " (" << selfcal::unitOf(selfcal::Parameter(p))
              << ") |";
  }
  std::cout << "\n|---|---|---|---|---|---|---|\n";
  for (int m = 0; m < METHODS; ++m) {
    std::cout << "| " << kMethods[m] << " (" << runs[m].size() << " seeds) |";
    for (int p = 0; p < selfcal::PARAMETERS; ++p) {
      std::vector<double> x;
      for (const selfcal::RigErrors &e : runs[m]) {
        x.push_back(selfcal::scaleOf(selfcal::Parameter(p)) * e.error[p]);
      }
      std::cout << " " << app::median(x) << " / " << app::maxOf(x) << " |";
    }
    std::cout << "\n";
  }
}

//! How often the stated deviations cover the errors of \e runs, per parameter and all at once.
void printCoverage(const std::vector<selfcal::RigErrors> &runs)
{
  std::cout << std::defaultfloat << std::setprecision(3)
            << "standard deviations of the self-calibration (acquisition + frames), errors within 3 sigma in:";
  unsigned int all = 0;
  std::vector<double> ratios;
  for (int p = 0; p < selfcal::PARAMETERS; ++p) {
    unsigned int covered = 0;
    for (const selfcal::RigErrors &e : runs) {
      covered += e.covered[p] ? 1 : 0;
    }
    std::cout << (p > 0 ? ", " : " ") << selfcal::nameOf(selfcal::Parameter(p)) << " " << covered << "/" << runs.size();
  }
  for (const selfcal::RigErrors &e : runs) {
    all += std::all_of(std::begin(e.covered), std::end(e.covered), [](bool c) { return c; }) ? 1 : 0;
    ratios.push_back(e.sigmaRatio);
  }
  std::cout << "; all at once " << all << "/" << runs.size() << " seeds; largest error of a seed in standard "
            << "deviations: median " << app::median(ratios) << ", worst " << app::maxOf(ratios) << "\n";
}
} // namespace

int main(int argc, char **argv)
{
  unsigned int seeds = 10, first = 1, frames = 30, gridPoints = 7, gridViews = 0, gridSeeds = 0;
  double sigma = 0.5, range = 30.0, gridWidth = 0.30;
  std::string armName = "all";
  bool bound = false;
  app::CommandLine cmd;
  cmd.add("--seeds", seeds, "N", "number of seeds (worlds) per arm", 1)
      .add("--first", first, "S", "the first seed")
      .add("--noise", sigma, "SIGMA", "pixel noise (px, Gaussian, every image coordinate)", 0.0)
      .add("--frames", frames, "N", "calibration frames at random configurations beside the acquisition")
      .add("--range", range, "DEG", "the frames' joints within +-DEG of the zero reference (prismatic: 2 mm/deg)", 0.0)
      .add("--arm", armName, "NAME", "puma, viper850, prismatic or all")
      .add("--grid-points", gridPoints, "N", "the planar grid's points per side", 2)
      .add("--grid-width", gridWidth, "M", "the planar grid's width (m)", 0.01)
      .add("--grid-views", gridViews, "N", "the grid's views (0: as many as the self-calibration's images)")
      .add("--grid-seeds", gridSeeds, "N",
           "vpCalibration on the first N seeds only (0: all; it takes most of the time)")
      .flag("--bound", bound, true,
            "instead of vpCalibration, what the data allows: the Cramer-Rao bound of these and other frames");
  int exitCode = 0;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
  }
  try {
    const std::vector<std::string> arms = armName == "all" ? std::vector<std::string>{"puma", "viper850", "prismatic"}
                                                           : std::vector<std::string>{armName};
    if (bound) {
      return selfcal::whatTheDataAllows(arms, seeds, first, sigma, frames, range);
    }
    bool ok = true;
    std::cout << std::setprecision(3) << "Errors at " << sigma << " px, " << frames << " frames within +-" << range
              << " deg, vpCalibration on a " << gridPoints << " x " << gridPoints << " grid " << 100 * gridWidth
              << " cm wide with " << (gridViews > 0 ? std::to_string(gridViews) : std::string("as many"))
              << " views; median / worst over " << seeds << " seeds (from " << first << ")\n";
    for (size_t a = 0; a < arms.size(); ++a) {
      const selfcal::StudyArm arm = selfcal::makeArm(arms[a]);
      std::vector<selfcal::RigErrors> runs[METHODS];
      std::vector<double> grids; // the grid's width (cm): smaller than asked when both views cannot see it whole
      for (unsigned int seed = first; seed < first + seeds; ++seed) {
        selfcal::WorldStreams streams(seed, a);
        const selfcal::SkewedRig rig = selfcal::randomRig(arm, streams.rig);
        const vpProjectiveRobot robot = selfcal::acquire(arm, rig, sigma, frames, range, streams.noise, streams.view);
        std::vector<vpProjectiveArmAcquisition::vpFrame> all = robot.getAcquisition().getFrames();
        const std::vector<vpProjectiveArmAcquisition::vpFrame> acquisition(
            all.begin(), all.end() - robot.getAcquisition().getNumberOfCalibrationFrames());
        runs[ACQUISITION].push_back(selfCalibrate(robot, arm, rig, acquisition));
        runs[SELF_CALIBRATION].push_back(selfCalibrate(robot, arm, rig, all));
        if (gridSeeds > 0 && seed >= first + gridSeeds) {
          continue;
        }
        const unsigned int views = gridViews > 0 ? gridViews : static_cast<unsigned int>(all.size());
        Eigen::Matrix3d Kl, Kr;
        Eigen::Matrix4d lMr;
        double used = 0.0;
        selfcal::planarCalibration(rig, views, gridPoints, gridWidth, sigma, streams.noise, streams.grid, Kl, Kr, lMr,
                                   used);
        grids.push_back(100.0 * used);
        runs[GRID].push_back(selfcal::compare(Kl, Kr, lMr, rig, true));
        const selfcal::SkewedRig natural = selfcal::withoutSkew(rig);
        selfcal::planarCalibration(natural, views, gridPoints, gridWidth, sigma, streams.noise, streams.grid, Kl, Kr,
                                   lMr, used);
        runs[GRID_NO_SKEW].push_back(selfcal::compare(Kl, Kr, lMr, natural, true));
      }
      std::cout << std::defaultfloat << std::setprecision(3) << "\n"
                << arms[a] << " ("
                << (arms[a] == "prismatic" ? "lengths in the prismatic joint's unit" : "lengths from a marker distance")
                << "; the grid " << app::median(grids) << " cm wide in the median, "
                << *std::min_element(grids.begin(), grids.end()) << " cm at least):\n";
      printTable(runs);
      printCoverage(runs[SELF_CALIBRATION]);
      std::vector<double> focal, rotation;
      for (const selfcal::RigErrors &e : runs[SELF_CALIBRATION]) {
        focal.push_back(e.error[selfcal::FOCAL]);
        rotation.push_back(e.error[selfcal::ROTATION]);
      }
      ok = ok && app::median(focal) <= 0.01 && app::median(rotation) <= 1.0;
    }
    return ok ? 0 : 1;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return 1;
  }
}
