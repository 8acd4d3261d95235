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
  \file main.cpp
  \brief projective-study: which servo should I use? The projective servo of Ruf & Horaud against two baselines, on
  many random tasks of one world: by default the main job's (the paper's rig watching the PUMA-like arm, its 7
  gripper markers tracked); --world viper850 (ViSP's Viper850 kinematics and joint limits) or prismatic (an
  R-R-P-R-R-R arm), --rig random (a verged rig drawn per task: baseline, vergence, focal length, image size); see
  makeWorld() and randomRig() in study-world.h. Each run reports one world; the CSV files name it.
  - calibrated joint-space stereo IBVS written with ViSP's metric features (vpFeaturePoint interaction matrices of
    both cameras, the arm's Jacobian from its DH table by the product of exponentials, vpVelocityTwistMatrix from
    the world to each camera), with the exact calibration and with calibration errors of 1, 2 and 4 times
    (intrinsics 5 %, rig rotation 2 deg, base-to-rig 5 deg and 5 cm, link lengths 2 %) in a random direction drawn
    per task (study-calibration.h, study-ibvs.h);
  - uncalibrated Broyden servoing (rank-one Jacobian updates, initialised by one exploratory motion per joint;
    study-broyden.h).

  Every method gets the same control law settings (gain 0.5, joint steps limited to 15 deg, the damped least squares
  of vpServoProjective with setDamping(30, 30); study-control.h), the same noisy measurements (the same random draws),
  the same tasks (study-task.h), the same 100-iteration budget and the same success criterion (study-run.h): image RMS
  error below max(2 sigma, 1e-6) px within the budget, the tracked markers in view of both cameras the whole time, no
  joint limit hit. The projective servo acquires its model anew for every task and noise level, as in the main
  tutorial (study-projective.h); a failed acquisition counts as its failure and is reported apart.

  The tasks: start and target drawn uniformly in the box |q_i| <= 30 deg (--box) around the acquisition's zero
  reference (clipped to the arm's joint limits; a prismatic joint's box is 2 mm per degree), kept if the tracked
  markers are 20 px inside both images at both ends and the target is in the start's inverse-kinematic branch (same
  shoulder, elbow and wrist configuration; PUMA only: the other arms have no closed-form branch test and take their
  targets in any branch, as --any-branch). They are the same for the three noise
  levels 0.1, 0.5 and 1 px. Robustness cases at 0.5 px: 5 % gross outliers, one feature occluded for 5 iterations,
  a start near the wrist singularity. With --markers 3 the servo tracks only the main job's markers 0-2: the
  image error of three points has local minima where every method stalls (a third of the tasks); with --box 90 the
  tasks turn the tool by 96 deg in the median and half of them defeat every method.

  Outputs (study-report.h): a markdown table (stdout and study.md), CSV data (study-runs.csv one line per run,
  study-summary.csv, study-calibration.csv) and PNG figures through gnuplot (study-success.png, study-iterations.png).

  The planned projective servo (global servoing: vpServoProjective::setPathPlanning() inside the joint limits and
  the image window with a 10 px border) runs beside them on the nominal tasks; with --any-branch the targets need
  not be in the start's branch, and the report counts the plans that chose another branch than the true target's.

  Usage: projective-study [--world puma|viper850|prismatic] [--rig paper|random] [--tasks N (default 500)]
  [--seed S (default 1)] [--box DEG (default 30)]
  [--markers 3|7 (default 7)] [--sigma PX (one noise level)] [--any-branch] [--nominal-only] [--output DIR]
  Task k uses the seed S + k for everything random about it: projective-study --seed S+k --tasks 1 reproduces it
  alone.
*/

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpException.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpTime.h>

#include <visp3/projective/vpProjectiveRobot.h>

#include "study-methods.h"
#include "study-report.h"
#include "study-statistics.h"
#include "study-tags.h"
#include "study-task.h"
#include "study-world.h"
#include "command-line.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace study;

namespace
{
//! The acquisition noise stream of a noise level: its index among the default levels (so that --sigma 0.5 draws the
//! same models as the default run), else \e s.
unsigned int noiseStream(double sigma, unsigned int s)
{
  const std::vector<double> levels = World().sigmas;
  const auto it = std::find(levels.begin(), levels.end(), sigma);
  return it == levels.end() ? s : static_cast<unsigned int>(it - levels.begin());
}
} // namespace

int main(int argc, char **argv)
{
  unsigned int nbTasks = 500, seed = 1, markers = 7;
  double rehearsal = -1.0;
  double boxDeg = 30.0, sigma = 0.0, checkPlanned = 0.0;
  bool anyBranch = false, robustness = true, tagStudy = false;
  TagStudySettings tagSettings;
  std::string output = ".", worldName = "puma", rigName = "paper";
  app::CommandLine cmd;
  cmd.add("--world", worldName, "puma|viper850|prismatic",
          "the arm: the PUMA-like arm, ViSP's Viper850, or an R-R-P-R-R-R arm with a prismatic joint")
      .add("--rig", rigName, "paper|random", "the paper's rig, or a random verged rig drawn per task")
      .add("--tasks", nbTasks, "N", "number of random tasks", 1)
      .add("--seed", seed, "S", "seed of the first task")
      .add("--box", boxDeg, "DEG",
           "start and target uniformly within +-DEG of the zero reference on every joint (a prismatic joint: 2 mm "
           "per degree), clipped to the joint limits")
      .choice("--markers", markers, {3, 7}, "the servo tracks the 7 gripper markers, or the main job's 0-2")
      .add("--sigma", sigma, "PX", "one noise level only (default: 0.1, 0.5 and 1 px)")
      .flag("--any-branch", anyBranch, true, "targets in any inverse-kinematic branch, not only the start's")
      .flag("--nominal-only", robustness, false, "skip the robustness cases (outliers, occlusion, singular start)")
      .add("--rehearsal", rehearsal, "N",
           "planned servo: the law (47) rehearsal's budget in iterations (0: always a path; default: the planner's)",
           -1.0)
      .add("--check-planned", checkPlanned, "PCT",
           "exit with failure if the planned servo succeeds on less than PCT % of the nominal tasks at a noise level",
           0.0)
      .flag("--tags", tagStudy, true,
            "the study on rendered AprilTags instead (tutorial-projective-servo-apriltag.cpp's servo on random tasks)")
      .add("--blur", tagSettings.blur, "PX", "--tags: the cameras' optical blur (default 0)")
      .flag("--lighting", tagSettings.lighting, true, "--tags: a lighting change at call 50 of each task")
      .add("--output", output, "DIR", "directory of the tables, data and figures")
      .note("Single threaded and deterministic. Task k (0-based) uses the seed S + k for all its random draws:\n"
            "--seed S+k --tasks 1 reproduces it alone.");
  int exitCode = EXIT_SUCCESS;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
  }

  if (rigName != "paper" && rigName != "random") {
    std::cerr << "Error: --rig " << rigName << ": use paper or random" << std::endl;
    return EXIT_FAILURE;
  }

  try {
    const double start = vpTime::measureTimeMs();
    World world = makeWorld(worldName);
    world.rigName = rigName;
    world.boxDeg = boxDeg;
    world.tracked.resize(markers);
    world.anyBranch = anyBranch;
    world.rehearsal = static_cast<int>(rehearsal);
    world.robustness = robustness;
    if (sigma > 0.0) {
      world.sigmas = {sigma};
      world.robustnessSigma = sigma;
    }
    vpIoTools::makeDirectory(output);
    if (tagStudy) {
      tagSettings.tasks = nbTasks;
      tagSettings.seed = seed;
      tagSettings.output = output;
      const double rate = runTagStudy(world, tagSettings, std::cout);
      return rate >= checkPlanned ? EXIT_SUCCESS : EXIT_FAILURE;
    }
    Results results;
    std::ofstream csv((output + "/study-runs.csv").c_str());
    csv << "seed,case,method,sigma_px,calibration_error,outcome,converged_at,last_iteration,final_image_rms_px,"
           "joint_error_over_floor,straightness,exploration_moves,model_error_target_px,outliers_seen,"
           "outliers_rejected,clean_seen,clean_rejected,joint_path_ratio,excursion_deg,no_plan,other_branch,message,"
           "world,rig\n";
    std::cout << "Servo study: the projective servo against calibrated stereo IBVS and Broyden servoing, " << nbTasks
              << " random tasks from seed " << seed << ", world " << world.name << ", rig " << world.rigName << "\n";

    // The world of task \e taskSeed: its own random rig with --rig random (the same for its singular start).
    std::vector<RigDraw> rigDraws;
    const auto worldOf = [&](unsigned int taskSeed, bool record) {
      World w = world;
      if (world.rigName == "random") {
        RigDraw draw;
        w.rig = randomRig(world, taskSeed, draw);
        if (record) {
          rigDraws.push_back(draw);
        }
      }
      return w;
    };
    World reportWorld = worldOf(seed, false);

    //! [Main study]
    const std::vector<double> robustFactors = {0.0, 1.0};
    for (unsigned int t = 0; t < nbTasks; ++t) {
      double t0 = vpTime::measureTimeMs();
      const World taskWorld = worldOf(seed + t, true);
      results.tasks.push_back(makeTask(taskWorld, seed + t, false));
      results.timeMs["task generation"] += vpTime::measureTimeMs() - t0;
      const Task &task = results.tasks.back();
      for (unsigned int s = 0; s < world.sigmas.size(); ++s) {
        std::string message;
        const std::unique_ptr<vpProjectiveRobot> robot =
            acquireForTask(taskWorld, task, world.sigmas[s], noiseStream(world.sigmas[s], s), message, results);
        runMethods(taskWorld, task, world.sigmas[s], robot.get(), message, NOMINAL, "nominal", world.calibrationFactors,
                   false, results, csv);
        if (world.robustness && world.sigmas[s] == world.robustnessSigma) {
          // Robustness (a) and (b) on the same tasks and models as the nominal case.
          runMethods(taskWorld, task, world.sigmas[s], robot.get(), message, OUTLIERS, "outliers", robustFactors, true,
                     results, csv);
          runMethods(taskWorld, task, world.sigmas[s], robot.get(), message, OCCLUSION, "occlusion", robustFactors,
                     true, results, csv);
        }
      }
      if ((t + 1) % 50 == 0) {
        std::cout << "  " << t + 1 << " tasks done, " << fixed((vpTime::measureTimeMs() - start) / 1000.0, 0) << " s\n"
                  << std::flush;
      }
    }
    //! [Main study]

    //! [Singular start]
    // Robustness (c): starts near the wrist singularity, a fresh acquisition per task.
    for (unsigned int t = 0; world.robustness && t < nbTasks; ++t) {
      double t0 = vpTime::measureTimeMs();
      const World taskWorld = worldOf(seed + t, false);
      results.singularTasks.push_back(makeTask(taskWorld, seed + t, true));
      results.timeMs["task generation"] += vpTime::measureTimeMs() - t0;
      const Task &task = results.singularTasks.back();
      const unsigned int s = noiseStream(
          world.robustnessSigma,
          static_cast<unsigned int>(std::find(world.sigmas.begin(), world.sigmas.end(), world.robustnessSigma) -
                                    world.sigmas.begin()));
      std::string message;
      const std::unique_ptr<vpProjectiveRobot> robot =
          acquireForTask(taskWorld, task, world.robustnessSigma, s, message, results);
      runMethods(taskWorld, task, world.robustnessSigma, robot.get(), message, NOMINAL, "singular start", robustFactors,
                 true, results, csv);
    }
    //! [Singular start]
    csv.close();

    const double t0 = vpTime::measureTimeMs();
    std::ostringstream md;
    md << markdownReport(reportWorld, results, nbTasks, seed);
    if (!rigDraws.empty()) {
      md << "\n## Random rigs\n\n" << rigDistribution(rigDraws);
    }
    results.timeMs["report"] += vpTime::measureTimeMs() - t0;

    std::ostringstream log;
    writeSummary(results, output + "/study-summary.csv");
    writeFigures(world, results, output, log);
    const double total = (vpTime::measureTimeMs() - start) / 1000.0;
    md << "\n## Run time\n\n" << fixed(total, 1) << " s in all, single threaded:";
    for (const auto &kv : results.timeMs) {
      md << " " << kv.first << " " << fixed(kv.second / 1000.0, 1) << " s;";
    }
    md << " " << results.acquisitions << " acquisitions ("
       << fixed(results.timeMs["acquisition"] / std::max(1u, results.acquisitions), 1) << " ms each).\n";

    std::ofstream((output + "/study.md").c_str()) << md.str();
    std::cout << "\n"
              << md.str() << "\n"
              << log.str() << "Table: " << output << "/study.md; runs: " << output << "/study-runs.csv\n";
    for (double level : world.sigmas) {
      const double rate = results.get("nominal", "planned", level).successRate();
      if (rate < checkPlanned) {
        std::cerr << "Check failed: the planned servo succeeds on " << rate << " % of the tasks at " << level
                  << " px, below " << checkPlanned << " %" << std::endl;
        return EXIT_FAILURE;
      }
    }
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
  return EXIT_SUCCESS;
}
