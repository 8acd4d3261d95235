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
  Non-metric visual servoing of ViSP's own arm: the simulated Viper850 of vpSimulatorViper850 watched by a fixed,
  uncalibrated stereo rig (eye-to-hand, eye-to-hand-world.h), or carrying the rig on its hand and servoed relative to
  a static object (--eye-in-hand, eye-in-hand-world.h).

  The arm is ViSP's vpSimulatorViper850, driven as in ViSP's tutorial-ibvs-4pts-wireframe-robot-viper.cpp: joint
  positions are read with getPosition(vpRobot::ARTICULAR_FRAME, q) and joint velocities sent with
  setVelocity(vpRobot::ARTICULAR_FRAME, qdot). A tree of 7 markers is bolted to its flange; a stereo rig (the paper's
  cameras, 20 cm apart, 1.2 m in front of the robot) sees them. The marker positions come from ViSP's kinematic model
  of the Viper850 (vpViper::get_fMe()); the plugin gets only joint encoder values and noisy pixels, and
  1. acquires the arm with vpProjectiveAcquisitionProcedure: the marker images at a zero reference, then each joint
     moved alone both ways in 2 deg steps until 45 deg, a marker near an image border or a joint near its limit (no
     hand-picked amounts); the fundamental matrix comes from the images of these very steps;
  2. calibrates the projective model of the 6 revolute joints, which then takes the encoder readings as they are;
  3. servoes the marker tree with 3 tracked markers from a start to a target configuration (37 cm and 49 deg of tool
     motion) with the control law qdot = -lambda J^+ (s - s*) of vpServoProjective;
  4. repeats 1-3 over many noise seeds at 0.5 px and 0.1 px and prints the final joint errors next to the accuracy
     floor sqrt(diag(sigma^2 (J^T J)^-1)) of the true image Jacobian at the target.

  ViSP's simulator moves the arm in a thread of its own, in real time by default. Here it runs in its constant
  sampling time mode and the program waits for each of its steps, so that two runs print the same numbers.

  Usage: projective-viper850 [--eye-in-hand] [--seeds N] [--model FILE] [-d] [-c] [--help]
  With --model FILE, the first run acquires the arm and saves its model; later runs load it instead of acquiring
  (the multi-seed study always acquires anew, since it measures the acquisition's noise too). With a display (the
  DISPLAY environment variable set and no -d), ViSP's external view shows the arm, and a window both camera images
  while seed 1 is servoed, with a vpPlot of the error and the joints; it waits for a click at the end (-c: not).
  The exit code is 0 only if every run converged.

  The scenes are in eye-to-hand-world.h and eye-in-hand-world.h; the machinery they share (driving the simulator,
  acquisition, servo loop, study, table and live display) in viper850-experiment.h and viper850-robot.h.
*/

#include <cstdlib>

#include "command-line.h"
#include "eye-in-hand-world.h"
#include "eye-to-hand-world.h"
#include "viper850-experiment.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main(int argc, char **argv)
{
  app::ServoOptions options;
  bool eyeInHand = false;
  app::CommandLine cmd;
  cmd.flag("--eye-in-hand", eyeInHand, true, "the rig on the hand, looking at a static object (default: a fixed rig)")
      .add("--seeds", options.seeds, "N", "noise seeds of the study", 1)
      .add("--model", options.modelFile, "FILE", "model file (arm.json): acquired and saved once, loaded by later runs")
      .displayOptions(options.display, options.click);
  int exitCode = EXIT_SUCCESS;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
  }
  return eyeInHand ? viper850::run<viper850::EyeInHandWorld>(options)
                   : viper850::run<viper850::EyeToHandWorld>(options);
}
