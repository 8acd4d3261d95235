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
  \file viper850-experiment.h
  \brief The experiment of projective-viper850 on its two scenes (eye-to-hand-world.h: a fixed rig watches markers on
  the arm; eye-in-hand-world.h: the rig on the arm's hand watches a static object): driving ViSP's
  vpSimulatorViper850, the servo loop, and the experiment itself (acquisition, detailed run, multi-seed study, table).

  Each scene is a struct World, the template parameter of the functions below, with:
  - qRefDeg, startDeg, targetDeg (std::vector<double>, deg): the zero reference of the projective model, and the
    start and target of the servo task;
  - tracked (std::vector<unsigned int>): the markers the servo tracks;
  - predictionRangeDeg (double): the model is checked at random q within +-predictionRangeDeg of the zero reference;
  - minTrialDeg (double): the acquisition fails if a joint cannot move that far (deg) without a marker leaving the view;
  - mounting (vpProjectiveRobot::vpRigMounting): where the rig is;
  - damping (double, px/rad): the control law is damped when the smallest singular value of J falls below it
    (vpServoProjective::setDamping(damping, damping));
  - title, servoed, tool (std::string): what the program servoes, for the printed report;
  - nbMarkers(): the number of markers;
  - rigAt(viper, q) and markersAt(viper, q): the metric rig and the markers (base frame) when the joints are at q;
    the one carried by the arm follows ViSP's kinematic model of the Viper850, the other stays where it is;
  - servoedPose(viper, q): the pose of the servoed frame (the marker tree, or the hand relative to the object).
*/

#ifndef _app_projective_servo_viper850_common_h_
#define _app_projective_servo_viper850_common_h_

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/robot/vpSimulatorViper850.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "command-line.h"
#include "paper-world.h"
#include "figures.h"
#include "servo-report.h"
#include "viper850-robot.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#if defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_PTHREAD)

//! The machinery shared by the two scenes on ViSP's simulated Viper850.
namespace viper850
{
using app::degToRad;

//! [Acquisition]
/*!
  Acquisition (paper section 6) on the simulated arm by vpProjectiveAcquisitionProcedure: from the zero reference,
  each joint alone moved both ways in 2 deg steps, up to 45 deg, a marker 10 px from an image border or 5 deg from
  the simulator's joint limits, whichever comes first; the fundamental matrix from every stereo pair of the run; the
  model calibrated from the encoder readings, so it takes them as they are. A line per joint with \e verbose, every
  step's images in \e view if it is open.
*/
template <class World>
vpProjectiveRobot acquire(const World &world, vpSimulatorViper850 &robot, double sigma, vpGaussRand &noise,
                          bool verbose, app::LiveView *view = nullptr)
{
  const app::ImagesAt images = imagesAt(world, robot, allMarkers(world), sigma, &noise, vpColVector());
  const vpSimulatorStereoRig &rig = world.rigAt(robot, degToRad(world.qRefDeg));
  vpProjectiveAcquisitionProcedure procedure(
      [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        vpColVector q;
        robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
        return images(q, left, right); // a real rig: the stereo tracker's markers (vpStereoDotTracker)
      },
      rig.getWidth(), rig.getHeight());
  const unsigned int n = static_cast<unsigned int>(world.qRefDeg.size());
  procedure.setMaxAmounts(vpColVector(n, vpMath::rad(45.0)));
  procedure.setSteps(vpColVector(n, vpMath::rad(2.0)));
  procedure.setMinAmounts(vpColVector(n, vpMath::rad(world.minTrialDeg)));
  procedure.setJointLimits(robot.getJointMin(), robot.getJointMax(), vpMath::rad(5.0));
  procedure.setEpipolarThreshold(std::max(1.0, 4.0 * sigma));
  procedure.setMotion([](vpRobot &arm, const vpColVector &q) { moveTo(static_cast<vpSimulatorViper850 &>(arm), q); });
  procedure.setOutput(verbose ? &std::cout : nullptr);
  if (view != nullptr && view->isOpen()) {
    procedure.setStepCallback([view](unsigned int joint, const vpColVector &, const std::vector<vpImagePoint> &left,
                                     const std::vector<vpImagePoint> &right) {
      view->showMarkers("acquisition: joint " + std::to_string(joint), left, right);
    });
  }

  vpProjectiveRobot model(std::vector<vpProjectiveRobot::vpJointType>(n, vpProjectiveRobot::REVOLUTE));
  model.setRigMounting(world.mounting);
  moveTo(robot, degToRad(world.qRefDeg)); // the zero reference, where the procedure starts
  procedure.run(robot, model);
  return model;
}
//! [Acquisition]

//! [Servo]
/*!
  The servo loop, in the shape of ViSP's tutorial-ibvs-4pts-wireframe-robot-viper.cpp: read the robot, build the
  features, compute the control law, send the joint velocities. s* is taught by showing: the arm is brought to the
  target once and the noisy images of the tracked markers are recorded. \e show, if set, is called at every
  iteration (live display).
*/
template <class World>
app::ServoRun servo(const World &world, vpSimulatorViper850 &robot, const vpProjectiveRobot &model, double sigma,
                    vpGaussRand &noise, unsigned int iterations,
                    const std::function<void(const app::ServoRun &)> &show = nullptr)
{
  app::ServoRun run;
  const vpColVector qTarget = degToRad(world.targetDeg);
  const unsigned int nbPoints = static_cast<unsigned int>(world.tracked.size());
  const app::ImagesAt trackedImages = imagesAt(world, robot, world.tracked, sigma, &noise, vpColVector());

  trackedImages(moveTo(robot, qTarget), run.leftTarget, run.rightTarget);
  std::vector<vpFeatureStereoPoint> s(nbPoints), s_star(nbPoints);
  vpServoProjective task;
  task.setRobot(model);
  // qdot is a velocity: lambda = 0.5 per control period, joint steps limited to maxStep per period, and damping when
  // the smallest singular value of J falls below world.damping (px/rad).
  task.setLambda(0.5 / robot.getSamplingTime());
  task.getControlLaw().setMaxJointVelocity(maxStep / robot.getSamplingTime());
  task.getControlLaw().setDamping(world.damping, world.damping);
  for (unsigned int k = 0; k < nbPoints; ++k) {
    s_star[k].buildFrom(run.leftTarget[k], run.rightTarget[k]);
    task.addFeature(s[k], s_star[k]);
  }

  vpColVector q = moveTo(robot, degToRad(world.startDeg));
  for (unsigned int it = 0; it <= iterations; ++it) {
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    std::vector<vpImagePoint> left, right;
    run.inView = trackedImages(q, left, right);
    if (!run.inView) {
      break;
    }
    for (unsigned int k = 0; k < nbPoints; ++k) {
      s[k].buildFrom(left[k], right[k]);
    }
    const vpColVector qdot = task.computeControlLaw(q); // the model takes the encoder readings
    run.record(it, q, left, right, task.getError(), std::max(2.0 * sigma, 1e-6));
    if (show) {
      show(run);
    }
    if (it < iterations) {
      applyVelocity(robot, qdot); // ViSP's tutorial sends it and waits one period with vpTime::wait()
    }
  }
  run.finalJointError = q - qTarget;
  return run;
}
//! [Servo]

//! [Monte Carlo]
//! Seeds 1 to \e seeds at noise \e sigma: a fresh acquisition and a servo run each, against the noise floor.
template <class World>
app::Study study(const World &world, vpSimulatorViper850 &robot, double sigma, unsigned int seeds,
                 unsigned int iterations)
{
  app::Study st;
  st.sigma = sigma;
  const app::ImagesAt trueTracked = imagesAt(world, robot, world.tracked, 0.0, nullptr, vpColVector());
  st.floor = app::noiseFloor(app::imageJacobian(trueTracked, degToRad(world.targetDeg)), sigma);
  const app::ImagesAt trueAll = imagesAt(world, robot, allMarkers(world), 0.0, nullptr, degToRad(world.qRefDeg));
  for (unsigned int seed = 1; seed <= seeds; ++seed) {
    vpGaussRand noise(1.0, 0.0, static_cast<long>(seed));
    const vpProjectiveRobot model = acquire(world, robot, sigma, noise, false);
    const double prediction = app::predictionError(model, trueAll, seed, world.predictionRangeDeg);
    st.add(seed, servo(world, robot, model, sigma, noise, iterations), model, prediction);
  }
  st.finish();
  return st;
}
//! [Monte Carlo]

//! [Experiment]
/*!
  The experiment of both scenes on the simulated arm \e robot in \e world: the task, seed 1's acquisition (or the
  model of \e modelFile) and servo run in detail (live in \e view if open), then \e seeds seeds at 0.5 and 0.1 px and
  their table. Returns the exit code: EXIT_SUCCESS only if every run converged.
*/
template <class World>
int runExperiment(const World &world, vpSimulatorViper850 &robot, unsigned int seeds, const std::string &modelFile,
                  app::LiveView &view)
{
  std::cout << world.title << "\n";
  const vpColVector qStart = degToRad(world.startDeg), qTarget = degToRad(world.targetDeg);
  app::printTask(world.servoed, world.servoedPose(robot, qStart).inverse() * world.servoedPose(robot, qTarget), qStart,
                 qTarget);

  std::cout << "\nSeed 1 at 0.5 px: acquisition and calibration\n";
  vpGaussRand noise(1.0, 0.0, 1);
  const vpProjectiveRobot model = app::loadOrAcquire(
      modelFile, [&] { return acquire(world, robot, 0.5, noise, true, &view); },
      imagesAt(world, robot, allMarkers(world), 0.0, nullptr, degToRad(world.qRefDeg)), world.predictionRangeDeg);

  const unsigned int iterations = 30;
  const app::ServoRun run = servo(world, robot, model, 0.5, noise, iterations, view.callback());
  app::printDetailedRun(run, world.tool,
                        world.servoedPose(robot, run.q.back()).inverse() * world.servoedPose(robot, qTarget),
                        run.error.size());

  const std::vector<app::Study> studies = {study(world, robot, 0.5, seeds, iterations),
                                           study(world, robot, 0.1, seeds, iterations)};
  app::printTable(studies, world.predictionRangeDeg);
  robot.setRobotState(vpRobot::STATE_STOP);
  view.waitForClick();
  const bool converged = run.converged() && studies[0].allConverged() && studies[1].allConverged();
  return converged ? EXIT_SUCCESS : EXIT_FAILURE;
}
//! [Experiment]

/*!
  Sets ViSP's simulated Viper850 up (its external view, a window of its own, only with a display), builds the scene
  World around it, opens the camera windows if there is a display, and runs the experiment with \e options (--seeds,
  --model, -d, -c). Returns the exit code.
*/
template <class World> int run(const app::ServoOptions &options)
{
  try {
    //! [Robot setup]
    vpSimulatorViper850 robot(options.display);
    const World world(robot);
    setupRobot(robot, options.display);
    //! [Robot setup]
    const vpSimulatorStereoRig rig = world.rigAt(robot, degToRad(world.qRefDeg));
    app::LiveView view(rig.getWidth(), rig.getHeight(), options.display, options.click, 0, 520); // under ViSP's view
    return runExperiment(world, robot, options.seeds, options.modelFile, view);
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
} // namespace viper850

#else
namespace viper850
{
//! Where ViSP has no threaded robot simulator: says so and succeeds.
template <class World> int run(const app::ServoOptions &)
{
  std::cout << "This program needs ViSP's threaded robot simulator (ViSP's gui module and pthread)" << std::endl;
  return EXIT_SUCCESS;
}
} // namespace viper850
#endif
#endif
