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
  A camera gets bumped in the middle of a servo task, and the projective model survives it without a new
  acquisition. Everything is measured on images rendered by vpSimulatorMarkerRenderer and tracked by
  vpStereoDotTracker (vpDot2), as in projective-images.cpp: the acquisition, the taught target, the
  servo. During one control period one camera of the simulated rig is knocked (2 deg about a random axis and 1 cm
  along a random direction, seeded); the tracker loses the blobs that jumped and the simulated user clicks them again;
  the task (vpServoProjective) then sees every feature far from the model's prediction and reports
  SERVO_MODEL_MISMATCH with zero velocity. The arm visits three observation poses, the tracked images go to
  vpProjectiveRobot::addRigObservation() and updateRig() re-registers both cameras in the model's projective frame,
  keeping the arm model and the taught target; the task goes back to where it stopped and ends at its original target.

  Usage: projective-bumped-camera [--seed N] [--camera 0|1] [--bump-deg DEG] [--bump-mm MM]
  [--bump-after N] [--iterations N] [--output DIR] [-d] [-c] [--help]
  With a display (and no -d), both images are shown live with the tracked blobs, the target and the servo's paths, and
  a vpPlot of the error and the joints; it then waits for a click (-c: not).
  --output DIR (default .) receives the prediction-error figure and three PNGs of the stereo pair with the tracked
  markers and the model's predictions: at the start, just after the bump, at the end. The exit code is 0 only if the
  bump was detected, the rig re-registered and the task ended within 2 deg / 2 mm of its target.
*/

#include <algorithm>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numeric>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpStereoDotTracker.h>

#include "command-line.h"
#include "paper-world.h"
#include "figures.h"
#include "images-acquisition.h"
#include "images.h"
#include "stereo-picture.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace app; // the paper's world, the session of rendered images, the figures

namespace
{
//! [Re-registration]
/*!
  The rig moved: the arm visits the observation poses \e poses with every marker lit (where the task stopped, and
  two joint offsets from there: observed where the task runs, the new rig predicts best there), the simulated user
  clicks them once at the first pose and the tracker follows them to the others without the model (its rig is the
  old one); a pose where a marker would leave the view or merge with another is observed where the arm stopped, and
  the user clicks the markers again when a move loses one on its way. Each pose's tracked images go to
  addRigObservation(); then updateRig(). \e oldError and \e newError are
  getPredictionError() over all the markers with the old rig (RMS over the poses) and with the new one (a new frame back
  at the first pose).
*/
void reRegister(Session &session, vpProjectiveRobot &robot, const std::vector<vpColVector> &poses,
                const std::vector<unsigned int> &all, double &oldError, double &newError)
{
  session.lit = all;
  session.q = poses[0];
  session.grab();
  session.click(all);
  session.withModel = false;
  const auto moveTo = [&](const vpColVector &q) {
    const vpColVector from = session.q;
    MoveResult r = session.move(q);
    if (!r.complete && session.q == from) { // lost on the first frame, near the border: clicked again, on its way
      std::cout << "    " << r.failure << ": clicked again\n";
      session.click(all);
      r = session.move(q);
    }
    return r;
  };
  double sum = 0.0;
  for (size_t p = 0; p < poses.size(); ++p) {
    session.caption = "observation pose " + std::to_string(p + 1);
    MoveResult r;
    if (p > 0) {
      r = moveTo(poses[0]); // each observation pose from the first one
      r = r.complete ? moveTo(poses[p]) : r;
    }
    const std::vector<vpImagePoint> left = session.tracker.getLeftPoints(), right = session.tracker.getRightPoints();
    robot.addRigObservation(session.q, left, right);
    const double e = robot.getPredictionError(session.q, left, right);
    sum += e * e;
    std::cout << "    observation " << p + 1 << ": prediction error with the old rig " << e << " px"
              << (r.complete ? "" : " (stopped short: " + r.failure + ")") << "\n";
  }
  oldError = std::sqrt(sum / poses.size());
  robot.updateRig(); // both cameras re-estimated in the model's frame, the arm model kept
  const MoveResult r = moveTo(poses[0]);
  if (!r.complete) {
    throw vpException(vpException::fatalError, "back to the first observation pose: " + r.failure);
  }
  newError = robot.getPredictionError(session.q, session.tracker.getLeftPoints(), session.tracker.getRightPoints());
}
//! [Re-registration]
} // namespace

int main(int argc, char **argv)
{
  unsigned int seed = 1, camera = 1, bumpAfter = 8, iterations = 40;
  double bumpDeg = 2.0, bumpMm = 10.0;
  std::string output = ".";
  bool display = vpStereoServoDisplay::hasDisplay(), click = true;
  CommandLine cmd;
  cmd.add("--seed", seed, "N", "seed of the image noise, the clicks and the bump's axis and direction", 1)
      .choice("--camera", camera, {0, 1}, "the camera that is bumped: 0 left, 1 right")
      .add("--bump-deg", bumpDeg, "DEG", "rotation of the bump (deg, about a random axis)", 0.0)
      .add("--bump-mm", bumpMm, "MM", "translation of the bump (mm, along a random direction)", 0.0)
      .add("--bump-after", bumpAfter, "N", "servo iterations before the bump", 1)
      .add("--iterations", iterations, "N", "servo iterations after the re-registration", 10)
      .add("--output", output, "DIR", "where to write the figure and the PNGs")
      .displayOptions(display, click);
  int exitCode = EXIT_SUCCESS;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
  }

  try {
    const PaperWorld world;
    const ImageModel model;
    Session session(world, model, seed);
    std::unique_ptr<Viewer> viewer(display ? new Viewer(world.rig.getWidth(), world.rig.getHeight()) : nullptr);
    session.viewer = viewer.get(); // the live view, with a display
    const unsigned int n = world.arm.getNumberOfJoints();
    const vpColVector qTarget = degToRad(world.targetDeg);
    std::vector<unsigned int> all(world.arm.getToolMarkers().size());
    std::iota(all.begin(), all.end(), 0u);
    vpIoTools::makeDirectory(output);
    std::cout << std::fixed << std::setprecision(2)
              << "A camera bumped during non-metric visual servoing (Ruf & Horaud), on rendered images tracked by "
                 "vpStereoDotTracker\n\n1. Acquisition from images by vpProjectiveAcquisitionProcedure\n";

    //! [Acquisition]
    TrackingAccuracy accuracy;
    vpStereoDotTracker zeroState;
    vpProjectiveRobot robot = acquireByProcedure(session, accuracy, zeroState, true);
    session.q = vpColVector(n, 0.0); // a new frame at the zero reference, all markers lit: the model's prediction
    session.tracker = zeroState;
    session.grab();
    if (!session.tracker.track(session.Ileft, session.Iright, 0.0)) {
      throw vpException(vpException::fatalError, "at the zero reference: " + session.tracker.getReport());
    }
    const double errorBefore =
        robot.getPredictionError(session.q, session.tracker.getLeftPoints(), session.tracker.getRightPoints());
    std::cout << "    tracking accuracy " << accuracy.rms() << " px; prediction error at the zero reference "
              << errorBefore << " px (all " << all.size() << " markers)\n";
    //! [Acquisition]

    //! [Task]
    session.tracker.keepMarkers(world.tracked); // the servo's markers, predicted by the model from now on
    session.lit = session.markers = world.tracked;
    session.tracker.setRobot(robot, world.tracked);
    session.withModel = true;
    std::vector<vpImagePoint> leftStar, rightStar;
    const std::string failure = teachTarget(session, leftStar, rightStar);
    if (!failure.empty()) {
      throw vpException(vpException::fatalError, "teaching: " + failure);
    }
    const size_t K = world.tracked.size();
    vpServoProjective task; // the settings of projective-paper.cpp
    task.setRobot(robot);
    task.setLambda(0.5);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(15.0));
    task.getControlLaw().setDamping(30.0, 30.0);
    std::vector<vpFeatureStereoPoint> s(K), s_star(K); // s from the tracked centres, s* from the taught ones
    for (size_t k = 0; k < K; ++k) {
      s_star[k].buildFrom(leftStar[k], rightStar[k]);
      task.addFeature(s[k], s_star[k]);
    }
    std::cout << "\n2. Servo toward the taught target, camera " << (camera == 0 ? "left" : "right") << " bumped by "
              << bumpDeg << " deg and " << bumpMm << " mm after iteration " << bumpAfter << "\n";
    writeStereoPicture(output + "/projective-bumped-start.png", session.Ileft, session.Iright, session.tracker,
                       session.markers, &robot, session.q, "start of the task");
    //! [Task]

    //! [Servo]
    std::vector<double> prediction; // per iteration: the servo's markers against the model
    std::vector<int> phase;         // 0 before the bump, 1 bumped, 2 re-registered
    int detectedAt = -1, endAt = -1;
    double errorBumped = 0.0, errorUpdated = 0.0;
    for (unsigned int it = 0; static_cast<int>(it) != endAt; ++it) {
      for (size_t k = 0; k < K; ++k) {
        s[k].buildFrom(session.tracker.getLeftPoint(k), session.tracker.getRightPoint(k));
      }
      prediction.push_back(trackedPredictionError(robot, session));
      phase.push_back(it <= bumpAfter ? 0 : (detectedAt < 0 ? 1 : 2));
      const vpColVector qdot = task.computeControlLaw(session.q);
      session.showServo(task.getError());
      if (task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH) {
        detectedAt = static_cast<int>(it);
        endAt = detectedAt + static_cast<int>(iterations) + 1;
        std::cout << "    iteration " << it << ": SERVO_MODEL_MISMATCH (" << it - bumpAfter
                  << " iterations after the bump), joint velocity zero; prediction error " << prediction.back()
                  << " px\n";
        writeStereoPicture(output + "/projective-bumped-after-bump.png", session.Ileft, session.Iright, session.tracker,
                           session.markers, &robot, session.q, "just after the bump (old rig)");
        const vpColVector qStopped = session.q;
        std::vector<vpColVector> poses(3, qStopped); // where the task stopped, and two offsets that spread the markers
        for (unsigned int i = 0; i < n; ++i) {
          poses[1][i] += vpMath::rad((i % 2 == 0 ? 1.0 : -1.0) * world.trialDeg[i] / 4.0);
          poses[2][i] += vpMath::rad((i < 3 ? -1.0 : 1.0) * world.trialDeg[i] / 4.0);
        }
        std::cout << "\n3. Re-registration from " << poses.size() << " observation poses\n";
        reRegister(session, robot, poses, all, errorBumped, errorUpdated);
        std::cout << "    updateRig(): residual " << robot.getRigUpdate().getResidual()
                  << " px; prediction error where the task stopped " << errorUpdated << " px\n\n"
                  << "4. The task goes on from where it stopped\n";
        // The arm drives back to where the task stopped, where the re-registered model finds the servo's blobs.
        session.q = qStopped;
        session.lit = session.markers = world.tracked;
        session.grab();
        session.tracker = vpStereoDotTracker();
        session.tracker.setRobot(robot, world.tracked);
        session.tracker.initTrackingByDetection(session.Ileft, session.Iright, session.q); // no click needed
        session.withModel = true;
        continue;
      }
      if (detectedAt < 0 && it > bumpAfter + 5) {
        throw vpException(vpException::fatalError, "the bump was not detected within 5 iterations");
      }
      if (it == bumpAfter) {
        session.bump(camera, randomBump(bumpDeg, bumpMm, seed)); // during this control period
      }
      session.caption = "servo: iteration " + std::to_string(it + 1);
      const MoveResult r = session.move(world.arm.integrate(session.q, qdot, 1.0));
      if (!r.complete && (it < bumpAfter || detectedAt >= 0)) {
        throw vpException(vpException::fatalError, "servo iteration " + std::to_string(it + 1) + ": " + r.failure);
      }
      if (!r.complete) { // the blobs jumped away from the model's prediction: the user clicks them again
        std::cout << "    iteration " << it + 1 << ": the tracker lost the bumped camera's blobs ("
                  << r.failure.substr(0, 60) << "...): clicked again\n";
        session.grab();
        session.click(world.tracked);
        session.withModel = false; // followed at constant image velocity: the model's rig is wrong now
      }
    }
    //! [Servo]

    //! [Results]
    writeStereoPicture(output + "/projective-bumped-end.png", session.Ileft, session.Iright, session.tracker,
                       session.markers, &robot, session.q, "end of the task (re-registered rig)");
    writePredictionFigure(prediction, phase, output);
    const vpColVector dq = session.q - qTarget;
    double worstDeg = 0.0;
    for (unsigned int i = 0; i < n; ++i) {
      worstDeg = std::max(worstDeg, std::abs(vpMath::deg(dq[i])));
    }
    const vpHomogeneousMatrix d = world.arm.get_wMt(session.q).inverse() * world.arm.get_wMt(qTarget); // truth
    const double poseDeg = vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta());
    const double poseMm = 1000.0 * d.getTranslationVector().frobeniusNorm();
    std::vector<double> before, after;
    for (size_t it = 0; it < prediction.size(); ++it) {
      if (phase[it] != 1) {
        (phase[it] == 0 ? before : after).push_back(prediction[it]);
      }
    }
    const auto median = [](std::vector<double> x) {
      std::sort(x.begin(), x.end());
      return x.empty() ? 0.0 : x[x.size() / 2];
    };
    std::cout << "\nPrediction error (getPredictionError, all markers): before the bump " << errorBefore
              << " px, just after it " << errorBumped << " px, after updateRig() " << errorUpdated << " px\n"
              << "Prediction error of the servo's markers (median per iteration): before the bump " << median(before)
              << " px, at the detection " << prediction[detectedAt] << " px, after re-registration " << median(after)
              << " px\n"
              << "Final joint error: largest " << worstDeg << " deg; tool pose error " << poseDeg << " deg, " << poseMm
              << " mm (ground truth, for the report only); refinements of the rig with the task's own frames: "
              << task.getRigRefinement().getNumberOfRefinements() << "\n";
    // Re-registered once (updateRig()); the task's own refinements of the rig (setRigRefinement()) do not count.
    const bool ok = detectedAt >= 0 && robot.getRigUpdate().getUpdateCount() == 1 && poseDeg <= 2.0 && poseMm <= 2.0;
    std::cout << (ok ? "Bump detected, rig re-registered, task ended at its original target"
                     : "FAILED: the task did not end within 2 deg / 2 mm of its target")
              << std::endl;
    if (viewer && click) {
      viewer->waitForClick();
    }
    return ok ? EXIT_SUCCESS : EXIT_FAILURE;
    //! [Results]
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
