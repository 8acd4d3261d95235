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
  Non-metric visual servoing of a 6-axis arm by an uncalibrated stereo rig (Ruf & Horaud, ICCV'99, section 6), in
  one main() to copy: the acquisition of the arm's projective model, then the servo loop.

  The simulator plays the world (replace it by your cameras and your robot): the paper's rig watches a PUMA-like arm
  with 7 markers on its gripper. The plugin sees only joint encoder values and pixels, and
  1. acquires the arm: the marker images at the zero reference q = 0, then each joint moved alone both ways by the
     paper's trial amounts (halved until every marker stays in view); the fundamental matrix comes from the same
     images; the projective model is calibrated from them;
  2. servoes the gripper with 3 tracked markers through a task of 82 cm and 88 deg, s* taught by showing (the image
     of the target configuration), with the planned path and the control law qdot = -lambda J^+ (s - s*), eq. (47).
  While it servoes, both images (white: the simulated cameras give pixels) show the markers (blue), s* (red), the
  tracked markers and their paths (green), and a vpPlot of the error and the joints (vpStereoServoDisplay, with a
  display).

  The paper's experiment itself (its table over 20 noise seeds and its figures) is the application
  apps/projective-paper.

  Usage: tutorial-projective-servo [-c] [-d] [--noise SIGMA] [--seed S] [--help]
  -d (--no-display): no window; -c (--no-click): no click awaited at the end (the options of ViSP's examples).
  The exit code is 0 if the task converged (image error within 2 sigma RMS).
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
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main(int argc, char **argv)
{
  double sigma = 0.5; // pixel noise (px)
  long seed = 1;
  bool opt_display = true, opt_click_allowed = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-d" || arg == "--no-display" || arg == "-c" || arg == "--no-click") {
      (arg == "-d" || arg == "--no-display" ? opt_display : opt_click_allowed) = false;
    } else if (arg == "--noise" && i + 1 < argc) {
      sigma = std::atof(argv[++i]);
    } else if (arg == "--seed" && i + 1 < argc) {
      seed = std::atol(argv[++i]);
    } else {
      std::cout << "Usage: " << argv[0] << " [-c] [-d] [--noise SIGMA (px, default 0.5)] [--seed S (default 1)]\n";
      return arg == "--help" || arg == "-h" ? EXIT_SUCCESS : EXIT_FAILURE;
    }
  }

  try {
    //! [World]
    // The simulated world: the paper's rig 1 m away, the PUMA-like arm, the task's start and target (deg).
    const vpSimulatorStereoRig world_rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
    const vpSimulatorArm world_arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
    const double trialDeg[6] = {30, 20, 30, 40, 60, 60};
    const unsigned int tracked[3] = {0, 1, 2}; // markers on the face that looks at the rig
    const double startDeg[6] = {15.4461, 54.9087, -48.3752, 62.3954, 29.0729, 1.7330};
    const double targetDeg[6] = {8.1330, 7.0830, -56.4826, 90.4984, 76.3260, 57.1987};
    vpColVector qStart(6), qTarget(6);
    for (unsigned int i = 0; i < 6; ++i) {
      qStart[i] = vpMath::rad(startDeg[i]);
      qTarget[i] = vpMath::rad(targetDeg[i]);
    }
    vpGaussRand noise(1.0, 0.0, seed);
    // The cameras: noisy images of the markers at joint values q; false if a marker is out of view.
    auto grab = [&](const vpColVector &q, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      return world_rig.project(world_arm.getMarkers(q), left, right, sigma, noise);
    };
    //! [World]

    //! [Acquisition]
    // The zero reference, then each joint alone moved by +-trial, halved until every marker stays in view.
    std::vector<vpImagePoint> left0, right0;
    grab(vpColVector(6, 0.0), left0, right0);
    std::vector<vpImagePoint> allLeft = left0, allRight = right0;
    std::vector<unsigned int> joints;
    std::vector<double> amounts;
    std::vector<std::vector<vpImagePoint>> trialLeft, trialRight;
    for (unsigned int i = 0; i < 6; ++i) {
      for (double sign : {1.0, -1.0}) {
        vpColVector q(6, 0.0);
        q[i] = sign * vpMath::rad(trialDeg[i]);
        std::vector<vpImagePoint> left, right;
        while (!grab(q, left, right)) {
          q[i] /= 2.0; // a marker left the view: a smaller trial
        }
        joints.push_back(i);
        amounts.push_back(q[i]); // as read by the encoder
        trialLeft.push_back(left);
        trialRight.push_back(right);
        allLeft.insert(allLeft.end(), left.begin(), left.end());
        allRight.insert(allRight.end(), right.begin(), right.end());
      }
    }
    // The fundamental matrix from every match of the acquisition, then the projective model of the 6 revolute joints.
    vpProjectiveStereoRig rig;
    rig.estimate(allLeft, allRight, std::max(1.0, 4.0 * sigma));
    vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
    robot.setStereoRig(rig);
    robot.setZeroReference(left0, right0);
    for (size_t k = 0; k < joints.size(); ++k) {
      robot.addTrialMotion(joints[k], amounts[k], trialLeft[k], trialRight[k]);
    }
    robot.calibrate();
    std::cout << "Acquired: " << allLeft.size() << " marker matches, bundle-adjustment residual "
              << robot.getAcquisition().getCalibrationResidual() << " px RMS\n";
    //! [Acquisition]

    //! [Task]
    // s* taught by showing: the images of the tracked markers with the arm at its target.
    std::vector<vpImagePoint> leftStar, rightStar;
    grab(qTarget, leftStar, rightStar);
    vpFeatureStereoPoint s[3], s_star[3];
    vpServoProjective task;
    task.setRobot(robot);
    task.setLambda(0.5);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(15.0)); // joint steps of at most 15 deg
    task.getControlLaw().setDamping(30.0, 30.0); // damped below 30 px/rad of J's smallest singular value
    // Global servoing: the model plans the task (a joint path inside the limits that keeps the markers 10 px inside
    // the images), the task follows it, and law (47) finishes.
    task.setJointLimits(world_arm.getJointMin(), world_arm.getJointMax());
    task.setImageSize(world_rig.getWidth(), world_rig.getHeight(), 10.0);
    task.setPathPlanning(true);
    task.getPathPlanner().setMaxJointStep(vpMath::rad(10.0));
    for (unsigned int k = 0; k < 3; ++k) {
      s_star[k].buildFrom(leftStar[tracked[k]], rightStar[tracked[k]]);
      task.addFeature(s[k], s_star[k]);
    }
    //! [Task]

    //! [Loop]
    vpStereoServoDisplay display(world_rig.getWidth(), world_rig.getHeight(),
                                 opt_display && vpStereoServoDisplay::hasDisplay());
    vpColVector q = qStart;
    double errorRms = 0.0;
    for (unsigned int it = 0; it <= 40; ++it) {
      std::vector<vpImagePoint> left, right;
      if (!grab(q, left, right)) {
        std::cout << "A marker left the view at iteration " << it << std::endl;
        return EXIT_FAILURE;
      }
      for (unsigned int k = 0; k < 3; ++k) {
        s[k].buildFrom(left[tracked[k]], right[tracked[k]]);
      }
      const vpColVector qdot = task.computeControlLaw(q); // eq. (47), J from the model at q
      if (it == 0) {
        std::cout << "Plan: " << task.getPathPlanner().getDescription() << "\n";
      }
      vpColVector e; // s - s* (the final target, whatever intermediate features the planned path aims at)
      for (unsigned int k = 0; k < 3; ++k) {
        e.stack(s[k].error(s_star[k]));
      }
      errorRms = std::sqrt(e.sumSquare() / e.size());
      display.display(); // white images, the 7 markers (blue), then s* (red), s and the paths of s (green)
      display.displayMarkers(left, right, vpColor::blue);
      for (unsigned int k = 0; k < 3; ++k) {
        display.displayFeature(k, s[k], s_star[k]);
      }
      display.displayText("iteration " + std::to_string(it) + ": error " + std::to_string(errorRms) + " px RMS");
      display.flush();
      display.plot(e, q);
      if (it % 5 == 0) {
        std::cout << "iteration " << it << ": image error " << errorRms << " px RMS\n";
      }
      q = world_arm.integrate(q, qdot, 1.0); // one control period: send qdot to the robot
    }
    //! [Loop]

    std::cout << "Final joint error (deg):";
    for (unsigned int i = 0; i < 6; ++i) {
      std::cout << " " << vpMath::deg(q[i] - qTarget[i]);
    }
    std::cout << "\n";
    const bool converged = errorRms <= std::max(2.0 * sigma, 1e-6);
    std::cout << (converged ? "Converged" : "Not converged") << std::endl;
    if (display.isOpen() && opt_click_allowed) {
      std::cout << "Click in the window to quit" << std::endl;
      display.getClick();
    }
    return converged ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
