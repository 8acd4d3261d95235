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
  \file eye-in-hand-world.h
  \brief The eye-in-hand scene of projective-viper850 (--eye-in-hand): the rig on the Viper850's hand, looking at a
  static object of 7 markers.
*/

#ifndef _app_eye_in_hand_world_h_
#define _app_eye_in_hand_world_h_

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
  What only the simulation knows: the rig on the flange, the static object, and the task in joint values. Every
  frame is expressed in the Viper's base frame f (z up, x forward).
*/
struct EyeInHandWorld {
  std::string title =
      "Non-metric visual servoing of ViSP's simulated Viper850 by an uncalibrated stereo rig on its hand";
  std::string servoed = "the hand"; // what the task moves
  std::string tool = "hand";        // whose pose error the detailed run prints
  // Zero reference of the projective model (where the acquisition starts): the arm raised, the flange 64 cm in front
  // of the base and 70 cm high, pointing 30 deg down, towards the object.
  std::vector<double> qRefDeg = {0, -90, 180, 0, 30, 0};
  // The rig: two wide-angle cameras (px = 600 px for 640 x 480 images, a 56 x 44 deg field) 15 cm apart on a bar
  // 10 cm beyond the flange, verging 70 cm in front of them on the flange's z axis. vergingRig() builds it in its own
  // frame r (vergence point at the origin, looking along +z, image rows along +y); eMr puts that frame on the flange.
  vpSimulatorStereoRig rRig =
      vpSimulatorStereoRig::vergingRig(vpColVector(3, 0.0), 0.7, 0.15, vpCameraParameters(600.0, 600.0, 320.0, 240.0));
  vpHomogeneousMatrix eMr = vpHomogeneousMatrix(0.0, 0.0, 0.8, 0.0, 0.0, 0.0);
  // The object: 7 markers (object frame o, metres) spread over 34 x 30 x 34 cm, no 4 of them coplanar (each is at
  // least 3.4 cm away from the plane through any other 3); markers 0-2, the largest triangle (560 cm^2), are the
  // tracked ones. It stands where the rig verges at the zero reference, turned by the rotation rMo. A large object
  // seen from close matters: with one three quarters this size seen from 1 m, the bundle adjustment of the
  // acquisition stopped in a local minimum (1 to 2.5 px RMS) for about one seed in six at 0.5 px.
  std::vector<vpColVector> oMarkers = {vpColVector({-0.06, 0.18, -0.14}), vpColVector({-0.18, 0.00, 0.14}),
                                       vpColVector({0.16, -0.04, 0.08}),  vpColVector({-0.10, 0.16, 0.16}),
                                       vpColVector({0.14, 0.08, -0.14}),  vpColVector({-0.02, -0.06, -0.18}),
                                       vpColVector({0.00, -0.12, 0.04})};
  vpHomogeneousMatrix rMo = vpHomogeneousMatrix(0.0, 0.0, 0.0, 0.3, 0.2, 0.1);
  std::vector<unsigned int> tracked = {0, 1, 2};
  // Start and target of the servo task (deg): the hand moves by 34 cm and turns by 44 deg relative to the object.
  // The pair was found once by a seeded search over viewpoints of the object (the rig turned by up to +-25 deg about
  // the vergence point and +-45 deg about its axis, moved by +-20 cm along it, then the Viper's inverse kinematics
  // from the zero reference): the 3 tracked markers at least 20 px inside both images at both ends, the ViSP
  // simulator's joint limits respected, the three singularity measures of the Viper (wrist sin q5, elbow, shoulder)
  // of the same sign as at the zero reference and away from zero (one inverse-kinematic branch), a noise floor below
  // 1.5 deg at 0.5 px, and convergence with 4 models acquired at other seeds. Rounded to 0.01 deg, it converges for
  // every one of seeds 1 to 100 at both noise levels (--seeds 100).
  std::vector<double> startDeg = {3.07, -117.07, 207.39, -9.15, 23.82, 13.58};
  std::vector<double> targetDeg = {11.91, -60.17, 151.94, -33.80, 37.19, -3.11};
  double predictionRangeDeg = 5.0; // model check at random q within +-5 deg of the zero reference (in view)
  // The object fills much of the wide-angle images: the base joint turns it out of view within 2 to 5 deg one way
  // (the acquisition reports it), and trials that small still give a model at the noise level.
  double minTrialDeg = 2.0;
  // The hand holds the rig: it is the base of the kinematic chain.
  vpProjectiveRobot::vpRigMounting mounting = vpProjectiveRobot::EYE_IN_HAND;
  // The control law is damped when the smallest singular value of J falls below 10 px/rad. It is 7 px/rad at the
  // start of this task and 26 at the target: wide-angle lenses and a hand-held rig give a weaker J than a fixed rig,
  // and a higher threshold would keep the damping on near the target and slow the final convergence.
  double damping = 10.0;
  std::vector<vpColVector> fMarkers; // the object's markers in the base frame: static

  explicit EyeInHandWorld(const vpViper850 &viper)
      : fMarkers(vpSimulatorStereoRig::transform(get_fMe(viper, app::degToRad(qRefDeg)) * eMr * rMo, oMarkers))
  {
  }

  //! The pose of the servoed frame, the hand (the object is static: its motion relative to the object is its motion
  //! in the base frame), when the joints are at q.
  vpHomogeneousMatrix servoedPose(const vpViper850 &viper, const vpColVector &q) const { return get_fMe(viper, q); }

  unsigned int nbMarkers() const { return static_cast<unsigned int>(fMarkers.size()); }

  //! The metric rig when the joints are at q: the same cameras, carried by the flange.
  vpSimulatorStereoRig rigAt(const vpViper850 &viper, const vpColVector &q) const
  {
    return vpSimulatorStereoRig(rRig.getLeftCameraParameters(), rRig.getRightCameraParameters(), rRig.get_rMl(),
                                get_fMe(viper, q) * eMr * rRig.get_wMl(), rRig.getWidth(), rRig.getHeight());
  }

  //! The markers (base frame) when the joints are at q: the object is static.
  const std::vector<vpColVector> &markersAt(const vpViper850 &, const vpColVector &) const { return fMarkers; }
};
//! [World]
} // namespace viper850
#endif
#endif
