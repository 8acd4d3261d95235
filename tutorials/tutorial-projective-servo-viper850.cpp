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

//! \example tutorial-projective-servo-viper850.cpp
/*!
  Non-metric visual servoing of ViSP's own arm: the simulated Viper850 of vpSimulatorViper850 watched by a fixed,
  uncalibrated stereo rig (eye-to-hand).

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

  Usage: tutorial-projective-servo-viper850 [--seeds N] [--model FILE] [--no-display] [--help]
  With --model FILE, the first run acquires the arm and saves its model; later runs load it instead of acquiring
  (the multi-seed study always acquires anew, since it measures the acquisition's noise too). With a display (the
  DISPLAY environment variable set and no --no-display), ViSP's external view shows the arm and two windows show the
  camera images while seed 1 is servoed. The exit code is 0 only if every run converged.

  The machinery this tutorial shares with tutorial-projective-servo-eye-in-hand.cpp (driving the simulator,
  acquisition, servo loop, study, table and live display) is in tutorial-projective-servo-viper850-common.h; this
  file holds the scene and the program.
*/

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/robot/vpSimulatorViper850.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "tutorial-projective-servo-viper850-common.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace viper850; // the machinery and program shared with tutorial-projective-servo-eye-in-hand.cpp

#if defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_PTHREAD)
namespace
{
//! [World]
/*!
  What only the simulation knows: the marker tree on the flange, the rig, and the task in joint values. Every frame
  is expressed in the Viper's base frame f (z up, x forward).
*/
struct World {
  std::string title = "Non-metric visual servoing of ViSP's simulated Viper850 from a fixed, uncalibrated stereo rig";
  std::string servoed = "the marker tree"; // what the task moves
  std::string tool = "tool";               // whose pose error the detailed run prints
  // Zero reference of the projective model (where the acquisition starts): the arm raised, the flange 61 cm in front
  // of the base and 66 cm high, pointing 45 deg down, towards the rig.
  std::vector<double> qRefDeg = {0, -90, 180, 0, 45, 0};
  // The marker tree is mounted 8 cm beyond the flange. Its 7 markers (tool frame t, metres) fit in a 9 cm cube with
  // no 4 of them coplanar (each is at least 8.5 mm away from the plane through any other 3); markers 0-2, the
  // largest triangle (35 cm^2), are the tracked ones.
  vpHomogeneousMatrix eMt = vpHomogeneousMatrix(0.0, 0.0, 0.08, 0.0, 0.0, 0.0);
  std::vector<vpColVector> tMarkers = {vpColVector({-0.015, 0.045, -0.035}), vpColVector({-0.045, 0.000, 0.035}),
                                       vpColVector({0.040, -0.010, 0.020}),  vpColVector({-0.025, 0.040, 0.040}),
                                       vpColVector({0.035, 0.020, -0.035}),  vpColVector({-0.005, -0.015, -0.045}),
                                       vpColVector({0.000, -0.030, 0.010})};
  std::vector<unsigned int> tracked = {0, 1, 2};
  double predictionRangeDeg = 15.0; // model check at random q within +-15 deg of the zero reference (in view)
  double minTrialDeg = 5.0;         // the procedure's default: every joint moves 5 deg or more in view
  // Start and target of the servo task (deg): the marker tree translates by 37 cm and rotates by 49 deg. The pair
  // was found once by a seeded search over random configurations within +-35 deg of the zero reference: the 3
  // tracked markers at least 20 px inside both images at both ends, the ViSP simulator's joint limits respected, the
  // three singularity measures of the Viper (wrist sin q5, elbow, shoulder) of the same sign and away from zero at
  // both ends (one inverse-kinematic branch), a noise floor below 1.5 deg at 0.5 px, and convergence with 4 models
  // acquired at other seeds. Rounded to 0.01 deg, it converges for every one of seeds 1 to 100 at both noise levels
  // (--seeds 100).
  std::vector<double> startDeg = {12.59, -86.29, 171.57, -15.77, 36.73, -34.72};
  std::vector<double> targetDeg = {-16.10, -102.07, 192.62, -6.75, 58.01, -25.00};
  // The rig is fixed, the markers ride on the last link (vpProjectiveRobot's default).
  vpProjectiveRobot::vpRigMounting mounting = vpProjectiveRobot::EYE_TO_HAND;
  // The control law is damped when the smallest singular value of J falls below 30 px/rad. It is 37 px/rad at the
  // start of this task and 45 at the target: the damping only acts if the path comes near a singularity.
  double damping = 30.0;
  vpSimulatorStereoRig rig;

  explicit World(const vpViper850 &viper) : rig(placeRig(get_fMe(viper, degToRad(qRefDeg)) * eMt)) {}

  //! The pose of the servoed frame, the marker tree, when the joints are at q.
  vpHomogeneousMatrix servoedPose(const vpViper850 &viper, const vpColVector &q) const
  {
    return get_fMe(viper, q) * eMt;
  }

  unsigned int nbMarkers() const { return static_cast<unsigned int>(tMarkers.size()); }

  //! The rig when the joints are at q: it is fixed.
  const vpSimulatorStereoRig &rigAt(const vpViper850 &, const vpColVector &) const { return rig; }

  //! The markers (base frame) when the joints are at q: they ride on the flange, whose pose comes from ViSP's
  //! kinematic model.
  std::vector<vpColVector> markersAt(const vpViper850 &viper, const vpColVector &q) const
  {
    return vpSimulatorStereoRig::transform(get_fMe(viper, q) * eMt, tMarkers);
  }

  /*!
    The paper's cameras (12.5 mm lenses on a 1/3 inch CCD, 640 x 480) on a 20 cm verging baseline, verging on the
    marker tree at the zero reference (fMt0) from 1.2 m away, in front of the robot and 20 deg above the tree.
  */
  static vpSimulatorStereoRig placeRig(const vpHomogeneousMatrix &fMt0)
  {
    // vergingRig() builds the rig in its own frame r: vergence point at the origin, looking along +z, image rows
    // along +y. fMr puts that point on the tree, z from the rig towards the robot (-x of f, tilted 20 deg down) and
    // y as close as possible to the downward vertical, hence x along +y of f.
    const vpSimulatorStereoRig rRig = vpSimulatorStereoRig::vergingRig(vpColVector(3, 0.0), 1.2, 0.20);
    const double c = std::cos(vpMath::rad(20.0)), s = std::sin(vpMath::rad(20.0));
    vpHomogeneousMatrix fMr = fMt0;
    const double fRr[3][3] = {{0.0, s, -c}, {1.0, 0.0, 0.0}, {0.0, -c, -s}};
    for (unsigned int i = 0; i < 3; ++i) {
      for (unsigned int j = 0; j < 3; ++j) {
        fMr[i][j] = fRr[i][j];
      }
    }
    return vpSimulatorStereoRig(rRig.getLeftCameraParameters(), rRig.getRightCameraParameters(), rRig.get_rMl(),
                                fMr * rRig.get_wMl(), rRig.getWidth(), rRig.getHeight());
  }
};
//! [World]
} // namespace
#endif

int main(int argc, char **argv)
{
  return runTutorial<World>(
      argc, argv); // the program of the common header on this scene: the marker tree on the flange, seen by a fixed rig
}
