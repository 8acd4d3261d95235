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
  \file study-calibration.h
  \brief What the calibrated baseline believes: the truth, or the truth off by a calibration error of a given size in a
  direction drawn per task.
*/

#ifndef _study_study_calibration_h_
#define _study_study_calibration_h_

#include <cmath>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Believed calibration]
/*!
  What the calibrated baseline believes: the intrinsics of both cameras, the rig's left-to-right transform, the pose
  of the rig with respect to the arm (here the left camera's pose in the world, the arm's base pose being part of the
  arm), and the arm's Denavit-Hartenberg table with its tool mount.
*/
struct BelievedCalibration {
  vpCameraParameters camLeft, camRight;
  vpHomogeneousMatrix rMl; // left-camera to right-camera
  vpHomogeneousMatrix lMw; // world (arm side) to left camera
  vpSimulatorArm arm;
};

/*!
  A direction of calibration error, drawn once per task: a sign per intrinsic parameter (px, py, u0, v0 of each
  camera), a rotation axis for the rig, a rotation axis and a translation direction for the base-to-rig transform,
  and a sign per link length (the non-zero d and a of the DH table and the tool mount's length).
*/
struct CalibrationErrorDirection {
  std::vector<double> intrinsicSigns; // 8
  vpColVector rigAxis;                // 3, unit
  vpColVector baseAxis;               // 3, unit
  vpColVector baseDirection;          // 3, unit
  std::vector<double> linkSigns;      // one per non-zero DH length, then the tool mount

  //! Uniform unit vector on the sphere.
  static vpColVector unitVector(vpUniRand &rng)
  {
    const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * M_PI), r = std::sqrt(1.0 - z * z);
    vpColVector u(3);
    u[0] = r * std::cos(phi);
    u[1] = r * std::sin(phi);
    u[2] = z;
    return u;
  }

  static CalibrationErrorDirection draw(vpUniRand &rng, unsigned int nbLinkLengths)
  {
    CalibrationErrorDirection d;
    for (unsigned int i = 0; i < 8; ++i) {
      d.intrinsicSigns.push_back(rng.uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0);
    }
    d.rigAxis = unitVector(rng);
    d.baseAxis = unitVector(rng);
    d.baseDirection = unitVector(rng);
    for (unsigned int i = 0; i < nbLinkLengths + 1; ++i) {
      d.linkSigns.push_back(rng.uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0);
    }
    return d;
  }
};

//! Magnitudes of the unit calibration error ("1x"): intrinsics 5 %, rig rotation 2 deg, base-to-rig 5 deg and 5 cm,
//! link lengths 2 %.
struct CalibrationErrorMagnitude {
  double intrinsics = 0.05;
  double rigRotation = vpMath::rad(2.0);
  double baseRotation = vpMath::rad(5.0);
  double baseTranslation = 0.05;
  double linkLengths = 0.02;
};

//! Number of non-zero lengths (d and a) in a DH table.
unsigned int countLinkLengths(const std::vector<vpSimulatorArm::vpDHRow> &dh);

/*!
  The believed calibration at \e factor times the unit error magnitude in the direction \e dir (factor 0: the truth).
  Rotations of the rig and of the base-to-rig transform are applied about the camera centres (\c rMl becomes
  \f$ \delta_r\, {}^rM_l \f$ and \c lMw becomes \f$ \delta_b\, {}^lM_w \f$), the base translation in the left camera
  frame.
*/
BelievedCalibration believedCalibration(const vpSimulatorStereoRig &rig, const vpSimulatorArm &arm,
                                        const CalibrationErrorDirection &dir, double factor,
                                        const CalibrationErrorMagnitude &magnitude = CalibrationErrorMagnitude());
} // namespace study

#endif
