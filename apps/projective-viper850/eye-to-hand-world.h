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
  \file eye-to-hand-world.h
  \brief The eye-to-hand scene of projective-viper850: a tree of 7 markers on the Viper850's flange, seen by a fixed
  rig.
*/

#ifndef _app_eye_to_hand_world_h_
#define _app_eye_to_hand_world_h_

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "viper850-robot.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#if defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_PTHREAD)
namespace viper850
{
//! [World]
/*!
  What only the simulation knows: the marker tree on the flange, the rig, and the task in joint values. Every frame
  is expressed in the Viper's base frame f (z up, x forward).
*/
struct EyeToHandWorld {
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

  explicit EyeToHandWorld(const vpViper850 &viper) : rig(placeRig(get_fMe(viper, app::degToRad(qRefDeg)) * eMt)) {}

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
} // namespace viper850
#endif
#endif
