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
  The paper's experiment of apps/projective-paper with the loop closed on images: the same arm, rig, trial
  motions and servo task, but every pixel the plugin gets is the centre of a blob that vpStereoDotTracker (vpDot2 in
  both images) followed in 8-bit images rendered by vpSimulatorMarkerRenderer (6 mm lit balls, exact silhouettes,
  supersampled, blurred, noisy). No ground-truth projection enters the loop: a simulated user clicks each marker once
  at the start, and from then on a marker is whatever its tracker followed, predicted at constant image velocity
  during the acquisition and by the acquired model afterwards, its correspondences checked by the model's epipolar
  geometry. The acquisition (F, zero reference, trial motions), the teaching of the target and the servo all use the
  tracked centres; a marker lost during a motion ends a trial at its last good frame, or the servo run. It prints the
  main job's table, the tracking accuracy (against the truth, for the report only) and the final joint errors
  against the main job's at 0.5 px. See its documentation page for the markers (active, seen from all around).

  Usage: projective-images [--seeds N] [--model FILE] [--output DIR] [-d] [-c] [--help]
  With --model arm.json, the model is loaded if the file exists, otherwise acquired by seed 1 and saved; the other
  seeds servo with it. --output DIR writes seed 1's final images with the feature trajectories, and the stereo pair
  at the start and at the end with the tracked markers and the model's predictions. The exit code is 0
  only if every seed converged.
*/

#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpTime.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpStereoDotTracker.h>

#include "command-line.h"
#include "paper-world.h"
#include "images-report.h"
#include "images-acquisition.h"
#include "images.h"
#include "servo-report.h"
#include "stereo-picture.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace app; // the paper's world, the session of rendered images and the report

namespace
{

//! [Servo]
/*!
  Teaching by showing, then the main job's servo loop on tracked centres. The arm, at the zero reference with
  its servo markers tracked, is driven by the start to the target, where s* is the tracked centres, then back to the
  start. With \e output, the stereo pair at the start goes there (writeStereoPicture()). The tracker predicts the blobs
  with the model from then on. At every iteration the features are the centres tracked in the last frame; the arm
  executes the control law's joint step while the cameras grab frames.
*/
ServoRun servo(Session &session, const vpProjectiveRobot &robot, TrackingAccuracy &accuracy, unsigned int iterations,
               const std::string &output)
{
  const PaperWorld &world = session.world;
  ServoRun run;
  const vpColVector qTarget = degToRad(world.targetDeg);
  const unsigned int nbPoints = static_cast<unsigned int>(world.tracked.size());
  session.tracker.setRobot(robot, world.tracked); // model prediction, and the model's epipolar geometry
  session.withModel = true;

  run.failure = teachTarget(session, run.leftTarget, run.rightTarget); // by the start, then back there
  if (!run.failure.empty()) {
    return run;
  }
  MoveResult r;
  std::vector<vpFeatureStereoPoint> s(nbPoints), s_star(nbPoints);
  vpServoProjective task;
  task.setRobot(robot);
  task.setLambda(0.5);
  task.getControlLaw().setMaxJointVelocity(vpMath::rad(15.0)); // as in the main job
  task.getControlLaw().setDamping(30.0, 30.0);
  for (unsigned int k = 0; k < nbPoints; ++k) {
    s_star[k].buildFrom(run.leftTarget[k], run.rightTarget[k]);
    task.addFeature(s[k], s_star[k]);
  }
  for (unsigned int it = 0; it <= iterations; ++it) {
    const std::vector<vpImagePoint> left = session.tracker.getLeftPoints(), right = session.tracker.getRightPoints();
    for (unsigned int k = 0; k < nbPoints; ++k) {
      s[k].buildFrom(left[k], right[k]); // the centres tracked in the last frame
    }
    run.trackingError.push_back(accuracy.add(world, session.q, session.tracker, session.markers));
    const vpColVector qdot = task.computeControlLaw(session.q); // eq. (47), J from the model at q
    if (it == 0 && !output.empty()) {                           // what the tracker and the model see at the start
      vpIoTools::makeDirectory(output);
      writeStereoPicture(output + "/projective-servo-images-start.png", session.Ileft, session.Iright, session.tracker,
                         session.markers, &robot, session.q, "start of the servo");
    }
    run.record(it, session.q, left, right, task.getError(), session.model.convergenceThreshold);
    run.frames.push_back(r.frames);
    session.showServo(task.getError());
    if (it < iterations) {
      session.caption = "servo: iteration " + std::to_string(it + 1);
      r = session.move(world.arm.integrate(session.q, qdot, 1.0)); // one control period
      if (!r.complete) {
        run.failure = "servo iteration " + std::to_string(it + 1) + ": " + r.failure;
        break;
      }
    }
  }
  run.finalJointError = session.q - qTarget;
  return run;
}
//! [Servo]
} // namespace

int main(int argc, char **argv)
{
  ServoOptions options; // --output: seed 1's final images; no --output: none
  int exitCode = EXIT_SUCCESS;
  if (!parseServoOptions(argc, argv, options, exitCode, true)) {
    return exitCode;
  }
  const unsigned int seeds = options.seeds;
  const std::string &modelFile = options.modelFile, &output = options.output;

  try {
    const PaperWorld world;
    const ImageModel model;
    const double t0 = vpTime::measureTimeMs();
    const unsigned int n = world.arm.getNumberOfJoints();
    std::cout << "Non-metric visual servoing of a PUMA-like arm from an uncalibrated stereo rig (Ruf & Horaud),\n"
              << "closed on rendered images tracked by vpStereoDotTracker\n";
    printMarkersFacingTheRig(world);

    //! [Seeds]
    vpProjectiveRobot robot; // the model of the model file, or the one each seed acquires
    bool haveModel = !modelFile.empty() && vpIoTools::checkFilename(modelFile);
    if (haveModel) {
      robot.loadModel(modelFile); // acquired from images by an earlier run
      std::cout << "Model loaded from " << modelFile << ": every seed servoes with it, no acquisition\n";
    }
    ImagesStudy st;
    std::unique_ptr<Viewer> viewer; // seed 1's live view, kept until the end
    for (unsigned int seed = 1; seed <= seeds; ++seed) {
      std::unique_ptr<Session> session(new Session(world, model, seed));
      if (seed == 1 && options.display) {
        viewer.reset(new Viewer(world.rig.getWidth(), world.rig.getHeight()));
        session->viewer = viewer.get();
      }
      const bool verbose = seed == 1, acquireModel = !haveModel;
      const double start = vpTime::measureTimeMs();
      ++st.seeds;
      std::cout << std::fixed << std::setprecision(3);
      // The model, and the servo's markers tracked at the zero reference.
      vpStereoDotTracker zeroState;
      TrackingAccuracy acquisitionAccuracy, servoAccuracy;
      ServoRun run;
      try {
        if (acquireModel) {
          std::cout << (verbose ? "\nSeed 1: acquisition from images\n" : "");
          robot = acquireFromImages(*session, acquisitionAccuracy, zeroState, verbose);
          st.addModel(robot, predictionError(robot, trueMarkerImages(world.rig, world.arm), seed), acquisitionAccuracy);
          zeroState.keepMarkers(world.tracked); // the servo's markers keep their trackers
        } else {
          session->lit = world.tracked;
          session->grab();
          session->click(world.tracked); // only the servo's markers are needed
          zeroState = session->tracker;
        }
        // Back at the zero reference with only the servo's markers lit.
        session->q = vpColVector(n, 0.0);
        session->lit = world.tracked;
        session->markers = world.tracked;
        session->tracker = zeroState;
        session->grab();
        if (!session->tracker.track(session->Ileft, session->Iright, 0.0)) {
          run.failure = "at the zero reference: " + session->tracker.getReport();
        } else {
          run = servo(*session, robot, servoAccuracy, 40, verbose ? output : std::string());
        }
      } catch (const vpException &e) {
        run.failure = e.getStringMessage();
      }
      st.servoAccuracy.add(servoAccuracy);
      if (verbose) {
        printSeedOne(*session, robot, run, acquireModel, acquisitionAccuracy, servoAccuracy, st, start, output);
      }
      st.add(seed, run, session->frames);
      if (acquireModel && !modelFile.empty() && robot.isCalibrated()) {
        robot.saveModel(modelFile); // acquired once: the other seeds, and later runs, servo with it
        std::cout << "    model saved to " << modelFile << ": the other seeds servo with it\n";
        haveModel = true;
      }
    }
    //! [Seeds]

    const bool within = printTable(world, model, st);
    std::cout << "The loop closed on images " << (within ? "ends within" : "does NOT end within")
              << " 2 times the main job's final joint errors at 0.5 px; run time " << std::setprecision(1)
              << (vpTime::measureTimeMs() - t0) / 1000.0 << " s\n";
    if (viewer && options.click) {
      viewer->waitForClick();
    }
    return st.converged == seeds ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
