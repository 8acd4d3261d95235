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
  The paper's experiment (Ruf & Horaud, ICCV'99, section 6): a PUMA-like arm servoed by an uncalibrated stereo rig.

  The simulator plays the world: the paper's rig (20 cm baseline, 12.5 mm lenses, 1/3 inch CCD, 1 m away) watches a
  6R arm with 36, 48 and 40 cm links carrying a 10 cm gripper with 7 markers. The plugin sees only joint encoder values
  and pixels, and
  1. acquires the arm: the marker images at the zero reference, then each joint moved alone both ways by the paper's
     trial amounts [30, 20, 30, 40, 60, 60] deg; the fundamental matrix comes from these very images;
  2. calibrates the projective model (generators of all joints sharing one projective-to-metric link, bundle
     adjusted) and checks how well it predicts the markers at random configurations;
  3. servoes the gripper with 3 tracked markers through a task that translates it by 82 cm and rotates it by 88 deg,
     with the control law qdot = -lambda J^+ (s - s*), eq. (47);
  4. repeats 1-3 over many noise seeds at 0.5 px and 0.1 px, and prints the paper's table next to the accuracy floor
     sigma^2 (J^T J)^-1 of the true Jacobian at the target;
  5. writes the trajectories of seed 1 as CSV and as PNG figures like the paper's Fig. 2, 4 and 5 (with gnuplot);
     with a display it also shows them live.

  Usage: projective-paper [--seeds N] [--output DIR] [--model FILE] [--max-excursion DEG] [--record DIR]
                          [--replay DIR] [-d] [-c] [--help]
  --max-excursion 40 lets the plan follow straight image lines (Fig. 2) at the price of joints folding past their
  targets (Fig. 4); the default 20 keeps the joints monotonic.
  With --model FILE, the first run acquires the arm and saves its model; later runs load it instead of acquiring
  (the multi-seed study always acquires anew, since it measures the acquisition's noise too).
  With --record DIR, seed 1's detailed run (the figures) is recorded as a session: its acquisition, target and servo
  frames with the marker pixels it used (paper-record.h). --replay DIR makes the figures again from a recording,
  offline, and checks that each recorded servo step is the replayed control law's; `visp-projective calibrate DIR
  --recorded-markers` calibrates it with the tool's own pipeline.

  The steps (acquisition, servo run, study) are in paper-experiment.cpp; the paper's world, the report and the
  figures in apps/common/ (paper-world.h, servo-report.h, figures.h). tutorials/tutorial-projective-servo.cpp is the
  same acquisition and servo, once, in one main() to copy.
*/

#include <cstdlib>
#include <memory>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpIoTools.h>

#include <visp3/projective/vpProjectiveRobot.h>

#include "command-line.h"
#include "paper-world.h"
#include "figures.h"
#include "paper-experiment.h"
#include "paper-record.h"
#include "servo-report.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main(int argc, char **argv)
{
  app::ServoOptions options;
  options.output = ".";
  std::string record, replay;
  app::CommandLine cmd;
  cmd.add("--seeds", options.seeds, "N", "noise seeds of the study", 1)
      .add("--model", options.modelFile, "FILE", "model file (arm.json): acquired and saved once, loaded by later runs")
      .add("--output", options.output, "DIR", "where to write the run's data and figures")
      .add("--max-excursion", options.maxExcursionDeg, "DEG",
           "largest motion of a joint beyond its start and target values on the plan (40: straight image lines)", 0.0)
      .add("--record", record, "DIR", "record seed 1's detailed run (the figures) as a session in the new folder DIR")
      .add("--replay", replay, "DIR", "make the figures again from the recording DIR (offline), and nothing else")
      .displayOptions(options.display, options.click);
  int exitCode = EXIT_SUCCESS;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
  }
  if (!record.empty() && !options.modelFile.empty()) {
    std::cerr << "Error: --record records the acquisition too: it cannot be combined with --model" << std::endl;
    return EXIT_FAILURE;
  }

  try {
    const app::PaperWorld world;
    vpIoTools::makeDirectory(options.output);
    if (!replay.empty()) { // the figures from a recording, offline
      const app::PaperReplay r = app::replay(world, replay);
      const vpColVector qStart = app::degToRad(world.startDeg), qTarget = app::degToRad(world.targetDeg);
      app::printTask("the gripper", world.arm.get_wMt(qStart).inverse() * world.arm.get_wMt(qTarget), qStart, qTarget);
      std::cout << "Replay of " << replay << ": model from the recorded acquisition, servo law on " << r.run.q.size()
                << " recorded frames; largest difference between a recorded step and the replayed "
                << "law's: " << r.maxStepMismatch << " rad\n";
      app::printDetailedRun(
          r.run, "tool",
          world.arm.get_wMt(r.run.q.back()).inverse() * world.arm.get_wMt(app::degToRad(world.targetDeg)), 26);
      app::writeFigures(r.run, options.output);
      return r.maxStepMismatch < 1e-9 ? EXIT_SUCCESS : EXIT_FAILURE;
    }
    std::unique_ptr<app::PaperRecorder> recorder;
    if (!record.empty()) {
      recorder.reset(new app::PaperRecorder(record, world, {0.5, options.maxExcursionDeg, 40}));
    }

    //! [Detailed run]
    std::cout << "Non-metric visual servoing of a PUMA-like arm from an uncalibrated stereo rig (Ruf & Horaud)\n";
    const vpColVector qStart = app::degToRad(world.startDeg), qTarget = app::degToRad(world.targetDeg);
    app::printTask("the gripper", world.arm.get_wMt(qStart).inverse() * world.arm.get_wMt(qTarget), qStart, qTarget);

    std::cout << "\nSeed 1 at 0.5 px: acquisition and calibration\n";
    vpGaussRand noise(1.0, 0.0, 1);
    const vpProjectiveRobot robot = app::loadOrAcquire(
        options.modelFile, [&] { return app::acquire(world, 0.5, noise, true, recorder.get()); },
        app::trueMarkerImages(world.rig, world.arm), 30.0);

    const app::ServoRun run =
        app::servo(world, robot, 0.5, noise, 40, options.maxExcursionDeg, 1, false, 1, recorder.get());
    if (recorder) {
      recorder->close();
      std::cout << "Recorded " << recorder->getNumberOfFrames() << " frames in " << record << "\n";
    }
    app::printDetailedRun(run, "tool", world.arm.get_wMt(run.q.back()).inverse() * world.arm.get_wMt(qTarget), 26);
    app::writeFigures(run, options.output);
    //! [Detailed run]

    //! [Monte Carlo table]
    const std::vector<app::Study> studies = {
        app::study(world, 0.5, {0.04, 0.15, 0.23, 0.31, 0.10, 1.5}, options.seeds, options.maxExcursionDeg),
        app::study(world, 0.1, {0.01, 0.04, 0.09, 0.19, 0.21, 0.35}, options.seeds, options.maxExcursionDeg)};
    app::printTable(studies, 30.0);
    //! [Monte Carlo table]

    // With a display, seed 1's run again, live: both images with the feature trajectories, the error and the joints.
    app::LiveView view(world.rig.getWidth(), world.rig.getHeight(), options.display, options.click);
    for (size_t it = 1; view.isOpen() && it <= run.q.size(); ++it) {
      view.show(run, it);
      vpTime::wait(100);
    }
    view.waitForClick();
    const unsigned int failed =
        studies[0].lostView + studies[0].notConverged + studies[1].lostView + studies[1].notConverged;
    if (failed > 0) {
      std::cerr << failed << " runs did not converge" << std::endl;
      return EXIT_FAILURE; // the table says which
    }
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
