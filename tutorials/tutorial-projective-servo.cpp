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

//! \example tutorial-projective-servo.cpp
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

  Usage: tutorial-projective-servo [--seeds N] [--output DIR] [--model FILE] [--max-excursion DEG] [--no-display]
                                   [--help]
  --max-excursion 40 lets the plan follow straight image lines (Fig. 2) at the price of joints folding past their
  targets (Fig. 4); the default 20 keeps the joints monotonic.
  With --model FILE, the first run acquires the arm and saves its model; later runs load it instead of acquiring
  (the multi-seed study always acquires anew, since it measures the acquisition's noise too).
*/

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "tutorial-command-line.h"
#include "tutorial-projective-common.h"
#include "tutorial-projective-figures.h"
#include "tutorial-projective-report.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
using tutorial::degToRad;

//! [Acquisition]
/*!
  Acquisition (paper section 6, Fig. 3): marker images at the zero reference q = 0, then joint i alone moved by
  +-trial_i (halved until every marker stays in view). The fundamental matrix is estimated from the same images, so
  nothing but pixels and encoder values enters the model.
*/
vpProjectiveRobot acquire(const tutorial::PaperWorld &world, double sigma, vpGaussRand &noise, bool verbose)
{
  // The images at q: noisy projections of all the markers, in view of both cameras or not.
  const tutorial::ImagesAt imagesAt = [&](const vpColVector &q, std::vector<vpImagePoint> &left,
                                          std::vector<vpImagePoint> &right) {
    return world.rig.project(world.arm.getMarkers(q), left, right, sigma, noise);
  };
  return tutorial::acquireByTrials(world.trialDeg, imagesAt, std::max(1.0, 4.0 * sigma), verbose);
}
//! [Acquisition]

//! [Servo]
/*!
  The servo loop, written as in ViSP's tutorial-ibvs-4pts.cpp: build the features, compute the control law, send
  the joint velocities to the (simulated) robot. s* is the noisy image of the target: taught by showing.
*/
tutorial::ServoRun servo(const tutorial::PaperWorld &world, const vpProjectiveRobot &robot, double sigma,
                         vpGaussRand &noise, unsigned int iterations, double maxExcursionDeg)
{
  tutorial::ServoRun run;
  const vpColVector qTarget = degToRad(world.targetDeg);
  const unsigned int nbPoints = static_cast<unsigned int>(world.tracked.size());

  std::vector<vpFeatureStereoPoint> s(nbPoints), s_star(nbPoints);
  vpServoProjective task;
  task.setRobot(robot);
  task.setLambda(0.5);
  // The task starts 240 px away from its target: joint steps are limited to 15 deg and damped when the smallest
  // singular value of J falls below 30 px/rad, so that no step leaves the domain where J is a good linearisation.
  task.setMaxJointVelocity(vpMath::rad(15.0));
  task.setDamping(30.0, 30.0);
  // Global servoing: the model plans the task once (inverse kinematics of s*, a path inside the joint limits that
  // keeps the markers 10 px inside the images), the task follows it, and law (47) finishes.
  task.setJointLimits(world.arm.getJointMin(), world.arm.getJointMax());
  task.setImageSize(world.rig.getWidth(), world.rig.getHeight(), 10.0);
  task.setPathPlanning(true);
  // Path samples 10 deg apart; a path of straight image lines is kept if no joint goes farther than maxExcursionDeg
  // beyond its start and target values (this task's need 31 deg: by default its path is the joint-space line).
  task.getPathPlanner().setMaxJointStep(vpMath::rad(10.0));
  task.getPathPlanner().setMaxExcursion(vpMath::rad(maxExcursionDeg));
  const std::vector<vpColVector> targetMarkers = world.arm.getMarkers(qTarget);
  for (unsigned int k = 0; k < nbPoints; ++k) {
    vpImagePoint l, r;
    world.rig.project(targetMarkers[world.tracked[k]], l, r, sigma, noise);
    s_star[k].buildFrom(l, r);
    run.leftTarget.push_back(l);
    run.rightTarget.push_back(r);
    task.addFeature(s[k], s_star[k]);
  }

  vpColVector q = degToRad(world.startDeg);
  for (unsigned int it = 0; it <= iterations; ++it) {
    // Image processing stand-in: noisy images of the tracked markers at the current configuration.
    const std::vector<vpColVector> markers = world.arm.getMarkers(q);
    std::vector<vpImagePoint> left(nbPoints), right(nbPoints);
    for (unsigned int k = 0; k < nbPoints; ++k) {
      run.inView = world.rig.project(markers[world.tracked[k]], left[k], right[k], sigma, noise) && run.inView;
      s[k].buildFrom(left[k], right[k]);
    }
    if (!run.inView) {
      break;
    }
    const vpColVector qdot = task.computeControlLaw(q); // eq. (47), J from the model at q
    if (it == 0) {
      run.plan = task.getPathPlanner().getDescription();
    }
    vpColVector e; // s - s*, whatever intermediate features a planned path aims at
    for (unsigned int k = 0; k < nbPoints; ++k) {
      e.stack(s[k].error(s_star[k]));
    }
    run.record(it, q, left, right, e, std::max(2.0 * sigma, 1e-6));
    if (it < iterations) {
      q = world.arm.integrate(q, qdot, 1.0); // one control period
    }
  }
  run.finalJointError = q - qTarget;
  return run;
}
//! [Servo]

//! [Monte Carlo]
//! Seeds 1 to \e seeds at noise \e sigma: a fresh acquisition and a servo run each, against the noise floor
//! sqrt(diag(sigma^2 (J^T J)^-1)) of the true stacked image Jacobian of the tracked markers at the target.
tutorial::Study study(const tutorial::PaperWorld &world, double sigma, const std::vector<double> &paperDeg,
                      unsigned int seeds, double maxExcursionDeg)
{
  tutorial::Study st;
  st.sigma = sigma;
  st.paperDeg = paperDeg;
  const tutorial::ImagesAt trueTracked = tutorial::trueMarkerImages(world.rig, world.arm, world.tracked);
  st.floor = tutorial::noiseFloor(tutorial::imageJacobian(trueTracked, degToRad(world.targetDeg)), sigma);
  for (unsigned int seed = 1; seed <= seeds; ++seed) {
    vpGaussRand noise(1.0, 0.0, static_cast<long>(seed));
    const vpProjectiveRobot robot = acquire(world, sigma, noise, false);
    const double prediction = tutorial::predictionError(robot, tutorial::trueMarkerImages(world.rig, world.arm), seed);
    st.add(seed, servo(world, robot, sigma, noise, 40, maxExcursionDeg), robot, prediction);
  }
  st.finish();
  return st;
}
//! [Monte Carlo]
} // namespace

int main(int argc, char **argv)
{
  tutorial::ServoOptions options;
  options.output = ".";
  int exitCode = EXIT_SUCCESS;
  if (!tutorial::parseServoOptions(argc, argv, options, exitCode, true, true)) {
    return exitCode;
  }

  try {
    const tutorial::PaperWorld world;
    vpIoTools::makeDirectory(options.output);

    //! [Detailed run]
    std::cout << "Non-metric visual servoing of a PUMA-like arm from an uncalibrated stereo rig (Ruf & Horaud)\n";
    const vpColVector qStart = degToRad(world.startDeg), qTarget = degToRad(world.targetDeg);
    tutorial::printTask("the gripper", world.arm.get_wMt(qStart).inverse() * world.arm.get_wMt(qTarget), qStart,
                        qTarget);

    std::cout << "\nSeed 1 at 0.5 px: acquisition and calibration\n";
    vpGaussRand noise(1.0, 0.0, 1);
    const vpProjectiveRobot robot = tutorial::loadOrAcquire(
        options.modelFile, [&] { return acquire(world, 0.5, noise, true); },
        tutorial::trueMarkerImages(world.rig, world.arm), 30.0);

    const tutorial::ServoRun run = servo(world, robot, 0.5, noise, 40, options.maxExcursionDeg);
    tutorial::printDetailedRun(run, "tool", world.arm.get_wMt(run.q.back()).inverse() * world.arm.get_wMt(qTarget), 26);
    tutorial::writeFigures(run, options.output);
    //! [Detailed run]

    //! [Monte Carlo table]
    const std::vector<tutorial::Study> studies = {
        study(world, 0.5, {0.04, 0.15, 0.23, 0.31, 0.10, 1.5}, options.seeds, options.maxExcursionDeg),
        study(world, 0.1, {0.01, 0.04, 0.09, 0.19, 0.21, 0.35}, options.seeds, options.maxExcursionDeg)};
    tutorial::printTable(studies, 30.0);
    //! [Monte Carlo table]

    // With a display, seed 1's run again, live: both images with the feature trajectories, and the image error.
    tutorial::LiveView view(world.rig.getWidth(), world.rig.getHeight(), options.display, 0, 0, true);
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
