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
  \file images-report.h
  \brief The report of projective-images.cpp: markers facing the rig, statistics of the seeds (tracking
  accuracy, jitter), the table against the noise floor and the main job, seed 1's details and final images.
*/

#ifndef _app_projective_images_report_h_
#define _app_projective_images_report_h_

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTime.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>

#include "paper-world.h"
#include "images.h"
#include "servo-report.h"
#include "stereo-picture.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
//! [Visibility]
/*!
  Ground truth, only to explain the choice of marker model (see the header): the markers whose gripper face (as
  documented by vpSimulatorArm::gripperMarkers(): 0-2 on the front face -y, 3 on the finger tip +z, 4 on the left side
  -x, 5 and 6 on the back +y) is turned towards both cameras at configuration q.
*/
inline std::string markersFacingTheRig(const PaperWorld &world, const vpColVector &q)
{
  const double normal[7][3] = {{0, -1, 0}, {0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 1, 0}, {0, 1, 0}};
  const vpHomogeneousMatrix wMt = world.arm.get_wMt(q);
  const vpHomogeneousMatrix wMl = world.rig.get_wMl(), wMr = wMl * world.rig.get_rMl().inverse();
  const std::vector<vpColVector> X = world.arm.getMarkers(q);
  std::ostringstream os;
  for (unsigned int k = 0; k < X.size() && k < 7; ++k) {
    bool facing = true;
    for (const vpHomogeneousMatrix *wMc : {&wMl, &wMr}) {
      double dot = 0.0;
      for (unsigned int a = 0; a < 3; ++a) {
        const double n = wMt[a][0] * normal[k][0] + wMt[a][1] * normal[k][1] + wMt[a][2] * normal[k][2];
        dot += n * ((*wMc)[a][3] - X[k][a]); // towards the camera centre
      }
      facing = facing && dot > 0.0;
    }
    if (facing) {
      os << k << " ";
    }
  }
  return os.str();
}
//! Why the markers are lit balls: the markers that painted ones would leave visible at the task's configurations.
inline void printMarkersFacingTheRig(const PaperWorld &world)
{
  std::cout << "If the markers were painted on the gripper's faces, those turned to both cameras would be\n"
            << "  at the zero reference: "
            << markersFacingTheRig(world, vpColVector(world.arm.getNumberOfJoints(), 0.0))
            << "\n  at the start:          " << markersFacingTheRig(world, degToRad(world.startDeg))
            << "\n  at the target:         " << markersFacingTheRig(world, degToRad(world.targetDeg))
            << "\n  so the markers are lit balls seen from all around, as the main job's are (see the header)\n";
}
//! [Visibility]

//! [Images]
//! The final left and right images of a run with the features' trajectories (cyan), start (blue) and target (red).
inline void writeImages(const Session &session, const ServoRun &run, const std::string &dir)
{
  for (unsigned int c = 0; c < 2; ++c) {
    vpImage<vpRGBa> I;
    vpImageConvert::convert(c == 0 ? session.Ileft : session.Iright, I);
    const std::vector<std::vector<vpImagePoint>> &trajectory = c == 0 ? run.left : run.right;
    const std::vector<vpImagePoint> &target = c == 0 ? run.leftTarget : run.rightTarget;
    for (size_t k = 0; k < target.size(); ++k) {
      for (size_t it = 1; it < trajectory.size(); ++it) {
        vpImageDraw::drawLine(I, trajectory[it - 1][k], trajectory[it][k], vpColor::cyan);
      }
      if (!trajectory.empty()) {
        vpImageDraw::drawCircle(I, trajectory.front()[k], 8, vpColor::blue, 2);
      }
      vpImageDraw::drawCross(I, target[k], 16, vpColor::red, 1);
    }
    const std::string file =
        dir + (c == 0 ? "/projective-servo-images-left.png" : "/projective-servo-images-right.png");
    vpImageIo::write(I, file);
    std::cout << "Image written: " << file << "\n";
  }
}
//! [Images]

//! What the seeds give, for the table.
struct ImagesStudy {
  std::vector<double> iterations, imageError, prediction, calibrationResidual, frames;
  vpColVector meanAbsJointError; // rad, sum over the converged seeds until finish()
  TrackingAccuracy acquisitionAccuracy, servoAccuracy;
  unsigned int seeds = 0, trackingFailures = 0, notConverged = 0, converged = 0, jitterDof = 0;
  std::vector<std::string> failures;
  double jitterSumSquares = 0.0; // over jitterDof degrees of freedom

  /*!
    Jitter of the tracked centres once converged: the spread of their errors about their mean over the iterations
    while the arm stays at the target. The rest of the tracking error is a fixed function of where a blob falls on
    the pixel grid, the same when s* was taught and at the end: it cancels, the jitter does not.
  */
  void addJitter(const ServoRun &run)
  {
    const size_t first = static_cast<size_t>(run.convergedAt), m = run.trackingError.size() - first;
    if (run.convergedAt < 0 || m < 2) {
      return;
    }
    for (unsigned int r = 0; r < run.trackingError[first].size(); ++r) {
      double mean = 0.0;
      for (size_t it = first; it < run.trackingError.size(); ++it) {
        mean += run.trackingError[it][r] / m;
      }
      for (size_t it = first; it < run.trackingError.size(); ++it) {
        jitterSumSquares += (run.trackingError[it][r] - mean) * (run.trackingError[it][r] - mean);
      }
      jitterDof += static_cast<unsigned int>(m - 1);
    }
  }
  //! Accounts a model acquired from images: its prediction error (px) and the tracking accuracy of its acquisition.
  void addModel(const vpProjectiveRobot &robot, double predictionPx, const TrackingAccuracy &accuracy)
  {
    prediction.push_back(predictionPx);
    calibrationResidual.push_back(robot.getAcquisition().getCalibrationResidual());
    acquisitionAccuracy.add(accuracy);
  }
  //! The jitter (px RMS).
  double jitter() const { return jitterDof > 0 ? std::sqrt(jitterSumSquares / jitterDof) : 0.0; }

  //! Accounts the servo run of seed \e seed, which grabbed \e nbFrames stereo frames in all.
  void add(unsigned int seed, const ServoRun &run, unsigned int nbFrames)
  {
    if (!run.failure.empty()) {
      failures.push_back("seed " + std::to_string(seed) + ": tracking failure " + run.failure);
      ++trackingFailures;
    } else if (run.convergedAt < 0) {
      std::ostringstream os;
      os << "seed " << seed << ": not converged, image error " << run.finalImageError
         << " px RMS after 40 iterations, joint error (deg) " << degrees(run.finalJointError);
      failures.push_back(os.str());
      ++notConverged;
    } else {
      ++converged;
      addJitter(run);
      iterations.push_back(run.convergedAt);
      imageError.push_back(run.finalImageError);
      frames.push_back(nbFrames);
      if (meanAbsJointError.size() != run.finalJointError.size()) {
        meanAbsJointError.resize(run.finalJointError.size(), true);
      }
      for (unsigned int i = 0; i < run.finalJointError.size(); ++i) {
        meanAbsJointError[i] += std::abs(run.finalJointError[i]);
      }
    }
  }
};

//! [Table]
//! The main job's table for the loop closed on images, against the noise floor and the main job at 0.5 px.
//! Returns true if the final joint errors are within 2 times the main job's.
inline bool printTable(const PaperWorld &world, const ImageModel &model, const ImagesStudy &st)
{
  const unsigned int n = world.arm.getNumberOfJoints(), seeds = st.seeds;
  const vpColVector meanAbs = st.converged > 0 ? vpColVector(st.meanAbsJointError / st.converged) : vpColVector(n, 0.0);
  const ImagesAt trueTracked = trueMarkerImages(world.rig, world.arm, world.tracked);
  const vpMatrix J = imageJacobian(trueTracked, degToRad(world.targetDeg));
  const vpColVector floorAccuracy = noiseFloor(J, st.servoAccuracy.rms()), floorJitter = noiseFloor(J, st.jitter());
  const std::vector<double> mainJob = {0.051, 0.081, 0.119, 0.486, 0.151, 0.501}; // main job, 0.5 px, 20 seeds
  std::vector<double> it = st.iterations;
  std::sort(it.begin(), it.end());
  std::cout << std::fixed << std::setprecision(3) << "\nClosed on images, " << seeds << " seeds: converged "
            << st.converged << "/" << seeds << " (tracking failures " << st.trackingFailures << ", not converged "
            << st.notConverged << "), iterations to converge (RMS(s - s*) < " << model.convergenceThreshold
            << " px): median " << std::setprecision(0) << (it.empty() ? 0.0 : it[it.size() / 2]) << ", max "
            << maxOf(it) << std::setprecision(3) << "; final image error RMS " << mean(st.imageError) << " px; "
            << std::setprecision(0) << mean(st.frames) << " stereo frames per seed\n"
            << std::setprecision(3);
  std::cout << "  tracking accuracy, vpDot2 centre - true projection, px per coordinate (the main job's noise: 0.5 "
               "and 0.1 px):\n    ";
  if (st.acquisitionAccuracy.coordinates > 0) {
    std::cout << "acquisition " << st.acquisitionAccuracy.rms() << " RMS (largest " << st.acquisitionAccuracy.largest
              << "), ";
  }
  std::cout << "servo " << st.servoAccuracy.rms() << " RMS (largest " << st.servoAccuracy.largest
            << "), jitter once converged " << st.jitter() << " RMS\n";
  if (!st.prediction.empty()) {
    std::cout << "  acquired models: bundle-adjustment residual " << mean(st.calibrationResidual)
              << " px RMS, marker prediction error at random q within +-30 deg: mean " << mean(st.prediction)
              << " px, max " << maxOf(st.prediction) << " px RMS\n";
  }
  if (st.converged == 0) {
    std::cout << "  no seed converged:\n";
    for (const std::string &failure : st.failures) {
      std::cout << "    " << failure << "\n";
    }
    return false;
  }
  std::cout << "  Final joint error |q - q*| (deg), mean over the converged seeds; the noise floor\n"
            << "  sqrt(diag(sigma^2 (J^T J)^-1)) with sigma the servo's tracking accuracy and with sigma the jitter;\n"
            << "  the main job at 0.5 px:\n";
  std::cout << "    joint   images  floor(accuracy)  floor(jitter)  images/floor(jitter)  main 0.5 px  images/main\n";
  bool within = st.converged > 0;
  for (unsigned int i = 0; i < n; ++i) {
    const double ours = vpMath::deg(meanAbs[i]), ratio = ours / mainJob[i];
    within = within && ratio <= 2.0;
    std::cout << std::setw(9) << i << std::setw(9) << ours << std::setw(17) << vpMath::deg(floorAccuracy[i])
              << std::setw(15) << vpMath::deg(floorJitter[i]) << std::setw(22) << ours / vpMath::deg(floorJitter[i])
              << std::setw(13) << mainJob[i] << std::setw(13) << ratio << "\n";
  }
  for (const std::string &failure : st.failures) {
    std::cout << "    " << failure << "\n";
  }
  return within;
}
//! [Table]

//! [Seed one]
/*!
  The detailed report of seed 1: its acquisition from images (if \e acquired), then its teaching and servo, and its
  final images in \e output (if not empty): per camera with the trajectories, and the stereo pair with the tracked
  markers and the model's predictions (writeStereoPicture()). \e start is the seed's start time (ms).
*/
inline void printSeedOne(const Session &session, const vpProjectiveRobot &robot, const ServoRun &run, bool acquired,
                         const TrackingAccuracy &acquisitionAccuracy, const TrackingAccuracy &servoAccuracy,
                         const ImagesStudy &st, double start, const std::string &output)
{
  if (acquired && robot.isCalibrated() && !st.prediction.empty()) {
    std::cout << "    epipolar geometry from the tracked centres: RMS residual "
              << robot.getAcquisition().getStereoRig().getEstimationResidual() << " px\n"
              << "    algebraic generators: RMS error on the acquisition images "
              << robot.getAcquisition().getAlgebraicResidual() << " px; after the bundle adjustment "
              << robot.getAcquisition().getCalibrationResidual() << " px\n"
              << "    tracking accuracy (tracked centre - true projection): " << acquisitionAccuracy.rms()
              << " px RMS, largest " << acquisitionAccuracy.largest << " px, over " << acquisitionAccuracy.coordinates
              << " coordinates\n"
              << "    marker prediction at random q within +-30 deg: " << st.prediction.back() << " px RMS\n";
  } else if (!acquired) {
    std::cout << "\nSeed 1: the model file's model; markers 0-2 clicked once at the zero reference\n";
  }
  std::cout << "Seed 1: teaching and servo from images (" << session.frames << " stereo frames in all, "
            << std::setprecision(1) << (vpTime::measureTimeMs() - start) / 1000.0 << " s)\n"
            << std::setprecision(3);
  if (!run.failure.empty()) {
    std::cout << "    TRACKING FAILURE " << run.failure << "\n";
  } else {
    std::cout << "    converged after " << run.convergedAt << " iterations, final image error " << run.finalImageError
              << " px RMS; tracking accuracy " << servoAccuracy.rms() << " px RMS\n"
              << "    final joint error (deg) " << degrees(run.finalJointError) << "\n";
    const vpHomogeneousMatrix d =
        session.world.arm.get_wMt(session.q).inverse() * session.world.arm.get_wMt(degToRad(session.world.targetDeg));
    std::cout << "    final tool pose error: " << 1000 * d.getTranslationVector().frobeniusNorm() << " mm, "
              << vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta()) << " deg\n";
    std::cout << "    iteration  image error RMS (px)  frames (to reach it; iteration 0: from the zero reference, "
                 "teaching included)\n";
    for (size_t it = 0; it < run.error.size() && it <= 25; ++it) {
      std::cout << std::setw(13) << it << std::setw(22) << std::sqrt(run.error[it].sumSquare() / run.error[it].size())
                << std::setw(8) << run.frames[it] << "\n";
    }
  }
  if (!output.empty() && !run.q.empty()) {
    vpIoTools::makeDirectory(output);
    writeImages(session, run, output);
    writeStereoPicture(output + "/projective-servo-images-end.png", session.Ileft, session.Iright, session.tracker,
                       session.markers, &robot, session.q, "end of the servo");
  }
}
//! [Seed one]
} // namespace app

#endif
