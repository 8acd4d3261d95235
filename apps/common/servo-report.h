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
  \file servo-report.h
  \brief How the servo apps account and print their runs: one servo run's trajectory and outcome, the
  statistics of many seeds at one noise level, and the tables (final joint errors against the noise floor and, for
  the paper's experiment, against the paper's values).
*/

#ifndef _app_projective_report_h_
#define _app_projective_report_h_

#include <cmath>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <memory>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>

#include <visp3/projective/vpProjectiveRobot.h>

#include "paper-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
//! One servo run: the trajectory and its outcome.
struct ServoRun {
  std::vector<vpColVector> q;                         // joint values per iteration (rad)
  std::vector<std::vector<vpImagePoint>> left, right; // measured markers per iteration
  std::vector<vpColVector> error;                     // s - s* per iteration (px)
  std::vector<vpImagePoint> leftTarget, rightTarget;  // s*
  std::vector<vpColVector> trackingError;             // measured minus true images per iteration (images app)
  std::vector<unsigned int> frames;                   // frames grabbed during each control period (images app)
  int convergedAt = -1;                               // first iteration with RMS(s - s*) under the threshold
  bool inView = true;                                 // the tracked markers stayed in both images
  std::string failure;                                // a tracking failure, if any
  std::string plan;                                   // the task's plan, when it planned
  vpColVector finalJointError;                        // q - q_target at the end (rad)
  double finalImageError = 0.0;                       // RMS(s - s*) at the end (px)

  //! Accounts iteration \e it: joint values, measurements and error s - s* (not the error to a planned path's
  //! intermediate features); convergence below \e threshold px RMS.
  void record(unsigned int it, const vpColVector &qIt, const std::vector<vpImagePoint> &l,
              const std::vector<vpImagePoint> &r, const vpColVector &e, double threshold)
  {
    q.push_back(qIt);
    left.push_back(l);
    right.push_back(r);
    error.push_back(e);
    finalImageError = std::sqrt(e.sumSquare() / e.size());
    if (convergedAt < 0 && finalImageError < threshold) {
      convergedAt = static_cast<int>(it);
    }
  }
  //! True if the run converged with its markers in view and no tracking failure.
  bool converged() const { return inView && failure.empty() && convergedAt >= 0; }
};

//! Statistics of one noise level over all seeds.
struct Study {
  double sigma = 0.0;
  std::vector<double> paperDeg; // the paper's final joint errors, if any
  unsigned int seeds = 0, lostView = 0, notConverged = 0;
  std::vector<int> iterations;
  std::vector<double> imageError, prediction, calibrationResidual;
  vpColVector meanAbsJointError; // rad, mean over the converged runs once finish() is called
  vpColVector floor;             // rad
  std::vector<std::string> failures;
  std::shared_ptr<Study> settled; // the same seeds with s* taught from 16 frames and settling on (if run)

  //! Accounts the run of seed \e seed with the model \e robot (its prediction error \e predictionPx).
  void add(unsigned int seed, const ServoRun &run, const vpProjectiveRobot &robot, double predictionPx)
  {
    ++seeds;
    prediction.push_back(predictionPx);
    calibrationResidual.push_back(robot.getAcquisition().getCalibrationResidual());
    if (meanAbsJointError.size() == 0) {
      meanAbsJointError.resize(robot.getNumberOfJoints(), true);
    }
    if (!run.inView) {
      failures.push_back("seed " + std::to_string(seed) + ": a tracked marker left an image");
      ++lostView;
    } else if (run.convergedAt < 0) {
      std::ostringstream os;
      os << "seed " << seed << ": not converged, image error " << run.finalImageError << " px RMS after "
         << run.error.size() - 1 << " iterations, joint error (deg) " << (run.finalJointError * (180.0 / M_PI)).t();
      failures.push_back(os.str());
      ++notConverged;
    } else {
      iterations.push_back(run.convergedAt);
      imageError.push_back(run.finalImageError);
      for (unsigned int i = 0; i < meanAbsJointError.size(); ++i) {
        meanAbsJointError[i] += std::abs(run.finalJointError[i]);
      }
    }
  }
  //! Turns the sums into means over the converged runs.
  void finish()
  {
    if (!iterations.empty()) {
      meanAbsJointError /= static_cast<double>(iterations.size());
    }
  }
  //! True if every seed converged.
  bool allConverged() const { return iterations.size() == seeds; }
};

//! [Table]
/*!
  The apps' table: per noise level, convergence, the acquired models' accuracy, and the final joint errors
  beside the noise floor (and the paper's values, with a verdict, when the studies have them). \e rangeDeg is the
  range of the random configurations where the models' predictions were checked.
*/
inline void printTable(const std::vector<Study> &studies, double rangeDeg)
{
  const bool paper = !studies.empty() && !studies.front().paperDeg.empty();
  if (paper) {
    std::cout << "\nFinal joint error |q - q*| (deg), mean over " << studies.front().seeds
              << " seeds, beside the paper's values and the noise floor sqrt(diag(sigma^2 (J^T J)^-1)):\n";
  } else {
    std::cout << "\nFinal joint error |q - q*| (deg), mean over the converged runs, beside the noise floor "
                 "sqrt(diag(sigma^2 (J^T J)^-1)):\n";
  }
  std::cout << std::fixed << std::setprecision(3);
  for (const Study &st : studies) {
    std::cout << "\n  sigma = " << st.sigma << " px: converged " << st.iterations.size() << "/" << st.seeds
              << " (lost view " << st.lostView << ", not converged " << st.notConverged
              << "), iterations to converge: median ";
    if (paper) { // as reals, as the paper's table always printed them
      std::cout << static_cast<double>(median(st.iterations)) << ", max " << static_cast<double>(maxOf(st.iterations));
    } else {
      std::cout << median(st.iterations) << ", max " << maxOf(st.iterations);
    }
    std::cout << "; final image error RMS " << mean(st.imageError) << " px\n";
    std::cout << "  acquired model: bundle-adjustment residual " << mean(st.calibrationResidual)
              << " px RMS, marker prediction error at random q within +-" << std::setprecision(0) << rangeDeg
              << std::setprecision(3) << " deg: mean " << mean(st.prediction) << " px, max " << maxOf(st.prediction)
              << " px RMS\n";
    const Study *settled = st.settled ? st.settled.get() : nullptr;
    if (settled != nullptr) {
      std::cout << "  16-frame s* and settling (setSettling(true)): converged " << settled->iterations.size() << "/"
                << settled->seeds << ", iterations to converge: median " << median(settled->iterations) << ", max "
                << maxOf(settled->iterations) << "\n";
    }
    std::cout << (paper ? "    joint      paper       ours      floor  ours/floor   "
                        : "    joint       ours      floor  ours/floor   ")
              << (settled != nullptr ? "settled  sett./floor   " : "") << (paper ? "verdict\n" : "\n");
    for (unsigned int i = 0; i < st.floor.size(); ++i) {
      const double ours = vpMath::deg(st.meanAbsJointError[i]), floor = vpMath::deg(st.floor[i]);
      std::cout << std::setw(9) << i;
      if (paper) {
        std::cout << std::setw(11) << st.paperDeg[i];
      }
      std::cout << std::setw(11) << ours << std::setw(11) << floor << std::setw(12) << ours / floor;
      if (settled != nullptr) {
        const double averaged = vpMath::deg(settled->meanAbsJointError[i]);
        std::cout << std::setw(10) << averaged << std::setw(12) << averaged / floor;
      }
      if (paper) {
        std::cout << "   "
                  << (ours <= st.paperDeg[i]   ? "beats the paper"
                      : floor > st.paperDeg[i] ? "floor above the paper"
                                               : "paper better");
      }
      std::cout << "\n";
    }
    for (const std::string &failure : st.failures) {
      std::cout << "    " << failure << "\n";
    }
  }
}
//! [Table]

/*!
  The model of a detailed run: loaded from \e modelFile if it exists (acquired by an earlier run: no trial motion
  now), otherwise acquired by \e acquire and saved to \e modelFile if given. Prints how well it fits the acquisition
  images and predicts the markers \e trueImages at random joint values within +-\e rangeDeg.
*/
inline vpProjectiveRobot loadOrAcquire(const std::string &modelFile, const std::function<vpProjectiveRobot()> &acquire,
                                       const ImagesAt &trueImages, double rangeDeg)
{
  vpProjectiveRobot robot;
  if (!modelFile.empty() && vpIoTools::checkFilename(modelFile)) {
    robot.loadModel(modelFile);
    std::cout << "    model loaded from " << modelFile << "\n";
  } else {
    robot = acquire();
    const vpProjectiveStereoRig &estimated = robot.getAcquisition().getStereoRig(); // before the bundle adjustment
    std::cout << "    epipolar geometry from the " << estimated.getInliers().size()
              << " marker matches of the acquisition images: RMS residual " << estimated.getEstimationResidual()
              << " px\n";
    if (!modelFile.empty()) {
      robot.saveModel(modelFile);
      std::cout << "    model saved to " << modelFile << "\n";
    }
  }
  std::cout << "    algebraic generators: RMS error on the acquisition images "
            << robot.getAcquisition().getAlgebraicResidual() << " px; after the bundle adjustment "
            << robot.getAcquisition().getCalibrationResidual() << " px\n";
  std::cout << "    marker prediction at random q within +-" << rangeDeg
            << " deg: " << predictionError(robot, trueImages, 1, rangeDeg) << " px RMS\n";
  return robot;
}

//! Joint values (rad) as a line of degrees.
inline std::string degrees(const vpColVector &q)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(4);
  for (unsigned int i = 0; i < q.size(); ++i) {
    os << (i > 0 ? " " : "") << vpMath::deg(q[i]);
  }
  return os.str();
}

//! "T<unit> <separator>R deg": the translation of a relative pose in \e unit per metre and its rotation angle.
inline std::string motionOf(const vpHomogeneousMatrix &M, double unit, const std::string &separator)
{
  std::ostringstream os;
  os << unit * M.getTranslationVector().frobeniusNorm() << separator
     << vpMath::deg(vpThetaUVector(M.getRotationMatrix()).getTheta()) << " deg";
  return os.str();
}

//! Prints the task: \e motion, the pose of the servoed frame (named \e what) at the target relative to the start.
inline void printTask(const std::string &what, const vpHomogeneousMatrix &motion, const vpColVector &qStart,
                      const vpColVector &qTarget)
{
  std::cout << "Task: " << what << " translates by " << motionOf(motion, 100.0, " cm and rotates by ")
            << "; joint distance (deg) " << ((qTarget - qStart) * (180.0 / M_PI)).t() << "\n";
}

/*!
  Prints the outcome of a detailed run: convergence, final joint error, \e poseError (the final pose error of the
  servoed frame, named \e what) and the image error of the first \e rows iterations.
*/
inline void printDetailedRun(const ServoRun &run, const std::string &what, const vpHomogeneousMatrix &poseError,
                             size_t rows)
{
  std::cout << "Seed 1 servo: " << (run.inView ? "markers kept in view" : "markers LOST") << ", converged after "
            << run.convergedAt << " iterations, final image error " << run.finalImageError << " px RMS\n";
  if (!run.plan.empty()) {
    std::cout << "    plan: " << run.plan << "\n";
  }
  std::cout << "    final joint error (deg) " << (run.finalJointError * (180.0 / M_PI)).t() << "\n";
  std::cout << "    final " << what << " pose error: " << 1000 * poseError.getTranslationVector().frobeniusNorm()
            << " mm, " << vpMath::deg(vpThetaUVector(poseError.getRotationMatrix()).getTheta()) << " deg\n";
  std::cout << "    iteration  image error RMS (px)\n";
  for (size_t it = 0; it < run.error.size() && it < rows; ++it) {
    std::cout << std::setw(13) << it << std::setw(22) << std::sqrt(run.error[it].sumSquare() / run.error[it].size())
              << "\n";
  }
}
} // namespace app

#endif
