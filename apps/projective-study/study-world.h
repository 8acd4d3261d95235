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
  \file study-world.h
  \brief The study's world (the main tutorial's rig and PUMA-like arm, and the study's fixed settings), its seeded
  random streams, the arm's inverse-kinematic branches and what the rig sees.
*/

#ifndef _study_study_world_h_
#define _study_study_world_h_

#include <cstdint>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "study-control.h"
#include "tutorial-projective-common.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [World]
//! The main tutorial's world, and the study's fixed settings.
struct World {
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  std::vector<double> trialDeg = {30, 20, 30, 40, 60, 60}; // the paper's trial motions
  // Markers fed to the servo (every method): all 7 by default; --markers 3 takes the main tutorial's 0-2, on the face
  // that looks at the rig at the zero reference. Three points leave the image error of a joint-space servo with local
  // minima that stall a third of the tasks of the +-30 deg box, whatever the method.
  std::vector<unsigned int> tracked = {0, 1, 2, 3, 4, 5, 6};
  double boxDeg = 30.0;        // tasks: |q_i| <= boxDeg around the zero reference
  double marginPx = 20.0;      // tracked markers this far inside both images at both ends of a task
  bool anyBranch = false;      // --any-branch: targets need not be in the start's inverse-kinematic branch
  double planBorderPx = 10.0;  // planned servo: the image window's border (setImageSize()), as the main tutorial
  double planStepDeg = 10.0;   // planned servo: the path's largest joint step per sample, as the main tutorial
  double wristSingularDeg = 0; // q_4 where the axes of joints 3 and 5 align (set from the DH table)
  double nearSingularDeg = 2.0;
  unsigned int budget = 100;                    // iterations, every method
  double exploration = vpMath::rad(2.0);        // Broyden's exploratory joint motion
  std::vector<double> sigmas = {0.1, 0.5, 1.0}; // px
  std::vector<double> calibrationFactors = {0, 1, 2, 4};
  double robustnessSigma = 0.5;
  bool robustness = true; // the robustness cases (outliers, occlusion, singular start); --nominal-only: false
  double outlierProbability = 0.05;
  double outlierMinPx = 20.0, outlierMaxPx = 50.0;
  double outlierThresholdPx = 10.0; // robustness API: half the smallest gross error, 14 times the epipolar noise
  unsigned int occludedFeature = 0, occludedFirst = 3, occludedLast = 7;
  study::ControlSettings control; // gain 0.5, 15 deg, damping (30, 30): the main tutorial's projective task

  World()
  {
    // Joint 4 bends the spherical wrist: the axes of joints 3 and 5 align when theta_4 = offset_4 + q_4 = 0 (mod pi),
    // i.e. at q_4 = -offset_4 (40 deg for puma(): the zero reference has the wrist bent by 40 deg).
    wristSingularDeg = -vpMath::deg(arm.getDHTable()[4].theta);
  }
  unsigned int nbPoints() const { return static_cast<unsigned int>(tracked.size()); }
};
//! [World]

//! A 63-bit seed for random stream \e stream of the task with seed \e seed (splitmix64 mixing).
long streamSeed(unsigned int seed, unsigned int stream);

enum RandomStream {
  TASK_STREAM = 1,
  SINGULAR_TASK_STREAM = 2,
  NOISE_STREAM = 3,
  OUTLIER_STREAM = 4,
  CALIBRATION_STREAM = 5,
  ACQUISITION_STREAM = 16 // + noise level index
};

//! [Branch]
/*!
  Inverse-kinematic branch of the PUMA-like arm: the signs of the three functions that vanish on its singularities
  (standard DH, theta_i = offset_i + q_i). Shoulder: the reach of the wrist centre from the axis of joint 0,
  a_1 cos(theta_1) - d_3 sin(theta_1 + theta_2), in the arm's plane (front or back); elbow: cos(theta_2) (the forearm
  on one side of the upper arm or the other; 0 when the arm is straight); wrist: sin(theta_4) (flip or no flip; 0
  when the axes of joints 3 and 5 align). Away from the singularities the 8 inverse-kinematic solutions of a tool
  pose have 8 different sign triples, so two configurations with the same triple are the same solution branch.
*/
struct Branch {
  int shoulder, elbow, wrist;
  bool operator==(const Branch &b) const { return shoulder == b.shoulder && elbow == b.elbow && wrist == b.wrist; }
};

//! The branch of \e q (see Branch).
Branch branchOf(const vpSimulatorArm &arm, const vpColVector &q);
//! [Branch]

//! Noise-free images of the tracked markers at q; true if all are in view of both cameras (margin 0, as in the main
//! tutorial).
bool trueImages(const World &world, const vpColVector &q, std::vector<vpImagePoint> &left,
                std::vector<vpImagePoint> &right);

//! trueImages() as a tutorial::ImagesAt (\e world must outlive it).
tutorial::ImagesAt trueImagesAt(const World &world);

//! True if q is within the joint limits and the tracked markers are marginPx inside both images.
bool acceptable(const World &world, const vpColVector &q);
} // namespace study

#endif
