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
  \file calibration-world.h
  \brief The self-calibration study's worlds: an arm (the PUMA-like arm, ViSP's Viper850, the R-R-P-R-R-R arm) with
  the gripper's 7 markers, watched by a random verged rig of two different cameras with skew and unequal focal
  lengths (pinhole with a full K, which vpSimulatorStereoRig does not model); the acquisition by trial motions and the
  calibration frames at random configurations, imaged with Gaussian pixel noise.
*/

#ifndef _selfcal_calibration_world_h_
#define _selfcal_calibration_world_h_

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>
#include <visp3/projective/vpSimulatorArm.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
//! \e M as an Eigen matrix.
Eigen::Matrix4d eigenOf(const vpHomogeneousMatrix &M);

//! A stereo rig of two pinhole cameras with full intrinsics (skew included), and its images.
struct SkewedRig {
  Eigen::Matrix3d Kl, Kr;  //!< intrinsics (K(2, 2) = 1)
  vpHomogeneousMatrix wMl; //!< the left camera's pose in the world
  vpHomogeneousMatrix rMl; //!< left-camera coordinates to right-camera ones
  unsigned int width = 0, height = 0;

  //! Noise-free images of the world point \e wX (3x1); true if in front of both cameras and \e margin px inside.
  bool project(const vpColVector &wX, vpImagePoint &left, vpImagePoint &right, double margin) const;
  //! Images of \e wX with Gaussian noise \e sigma (px, drawn u, v, u', v' per point); true if all are \e margin px in.
  bool images(const std::vector<vpColVector> &wX, double sigma, vpGaussRand &noise, std::vector<vpImagePoint> &left,
              std::vector<vpImagePoint> &right, double margin = 10.0) const;
  //! The right camera's pose in the left camera's frame.
  vpHomogeneousMatrix lMr() const { return rMl.inverse(); }
};

//! An arm of the study, its zero reference and its trial motions.
struct StudyArm {
  std::string name;           //!< puma, viper850 or prismatic
  vpSimulatorArm arm;         //!< its true geometry and markers
  vpColVector qRef;           //!< encoder readings at the zero reference
  std::vector<double> trials; //!< one trial per joint (rad, m for a prismatic joint), made both ways
};

/*!
  The arm \e name: "puma" (the paper's arm and base pose, q_ref = 0, trials 30, 20, 30, 40, 60, 60 deg), "viper850"
  (vpViper850's geometry, q_ref = (0, -150, 190, 0, -75, 0) deg, trials 30, 8, 12, 30, 30, 60 deg) or "prismatic"
  (vpSimulatorArm::stanfordTable(), q_ref = (0, 60 deg, 0.45 m, 0, -50 deg, 0), trials 20 deg, 10 deg, 4 cm, 40, 40,
  60 deg); the Viper850 and the R-R-P-R-R-R arm standing where their gripper faces the same way as the PUMA's.
  \exception vpException for another name.
*/
StudyArm makeArm(const std::string &name);

/*!
  A random verged rig looking at the front face of the arm's gripper (markers 0-2) at the zero reference, drawn from
  \e rng: distance 0.8-1.3 m, vergence 10-30 deg, the view turned by up to 20 deg about the gripper and rolled by up
  to 10 deg, an image size among 640 x 480 to 1280 x 960, a field 30-50 cm wide at the markers; each camera its own
  focal length (+-3 %), aspect ratio (fy / fx within +-2 %), skew (within +-1 % of fx) and principal point (within
  5 % of the image size from its centre). Drawn again until the markers are 20 px inside both images.
*/
SkewedRig randomRig(const StudyArm &arm, vpUniRand &rng);

//! The same rig with natural cameras (no skew): vpCalibration's camera model.
SkewedRig withoutSkew(const SkewedRig &rig);

/*!
  What the plugin is given: the acquisition (zero reference, each joint's trial both ways, halved until the markers
  stay in view) and \e frames calibration frames at random readings within +-\e rangeDeg (prismatic: +-2 mm per deg)
  of the zero reference's, all with noise \e sigma; the fundamental matrix estimated from the acquisition's images.
  Returns the robot, calibrated, with its calibration frames. Throws if no visible configuration is found.
*/
vpProjectiveRobot acquire(const StudyArm &arm, const SkewedRig &rig, double sigma, unsigned int frames, double rangeDeg,
                          vpGaussRand &noise, vpUniRand &rng);

//! The random streams of a study's world, seed \e seed, arm \e a of the run: the rig's, the robot's views', the
//! grid's and the pixel noise.
struct WorldStreams {
  vpUniRand rig, view, grid;
  vpGaussRand noise;
  WorldStreams(unsigned int seed, size_t a);
};

/*!
  The self-calibration of \e robot over \e frames, its lengths in the prismatic joint's unit or, for the other arms,
  in metres from the distance of markers 0 and 1 (measured with a ruler).
*/
vpProjectiveSelfCalibration selfCalibration(const vpProjectiveRobot &robot, const StudyArm &arm,
                                            const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames);
} // namespace selfcal

#endif
