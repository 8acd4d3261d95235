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
  \brief The study's worlds (an arm and a rig: the main job's PUMA-like arm, ViSP's Viper850, an R-R-P-R-R-R arm
  with a prismatic joint; the paper's rig or a random verged rig drawn per task) and the study's fixed settings, its
  seeded random streams, the arm's inverse-kinematic branches and what the rig sees.
*/

#ifndef _study_study_world_h_
#define _study_study_world_h_

#include <cstdint>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "study-control.h"
#include "paper-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [World]
/*!
  A world of the study (an arm watched by a rig) and the study's fixed settings. By default the main job's: the
  paper's rig watching the PUMA-like arm (makeWorld() gives the others). The arm's joint values are relative to its
  zero reference (q = 0 is where the acquisition starts and the centre of the tasks' box), its joint limits are its
  true limits expressed the same way.
*/
struct World {
  std::string name = "puma";     // --world: puma, viper850 or prismatic
  std::string rigName = "paper"; // --rig: paper, or random (a verged rig drawn per task by randomRig())
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  // The acquisition's trial motion of each joint (rad, or m for a prismatic joint): the paper's for the PUMA.
  std::vector<double> trials = {vpMath::rad(30), vpMath::rad(20), vpMath::rad(30),
                                vpMath::rad(40), vpMath::rad(60), vpMath::rad(60)};
  bool pumaBranches = true;       // branchOf() applies (the PUMA-like arm); else the targets are in any branch
  double prismaticPerDeg = 0.002; // a prismatic joint's box: this many metres per degree of --box
  // Markers fed to the servo (every method): all 7 by default; --markers 3 takes the main job's 0-2, on the face
  // that looks at the rig at the zero reference. Three points leave the image error of a joint-space servo with local
  // minima that stall a third of the tasks of the +-30 deg box, whatever the method.
  std::vector<unsigned int> tracked = {0, 1, 2, 3, 4, 5, 6};
  double boxDeg = 30.0;        // tasks: |q_i| <= boxDeg around the zero reference, clipped to the joint limits
  double marginPx = 20.0;      // tracked markers this far inside both images at both ends of a task
  bool anyBranch = false;      // --any-branch: targets need not be in the start's inverse-kinematic branch
  double planBorderPx = 10.0;  // planned servo: the image window's border (setImageSize()), as the main job
  double planStepDeg = 10.0;   // planned servo: the path's largest joint step per sample, as the main job
  int rehearsal = -1;          // planned servo: the law rehearsal's budget (--rehearsal; -1: the planner's default)
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
  study::ControlSettings control; // gain 0.5, 15 deg, damping (30, 30): the main job's projective task

  World()
  {
    // Joint 4 bends the spherical wrist: the axes of joints 3 and 5 align when theta_4 = offset_4 + q_4 = 0 (mod pi),
    // i.e. at q_4 = -offset_4 (40 deg for puma(): the zero reference has the wrist bent by 40 deg).
    wristSingularDeg = -vpMath::deg(arm.getDHTable()[4].theta);
  }
  unsigned int nbPoints() const { return static_cast<unsigned int>(tracked.size()); }
  //! Targets need not be in the start's branch: --any-branch, or an arm without branchOf().
  bool anyBranchTargets() const { return anyBranch || !pumaBranches; }
  //! The box of joint \e i: [lower, upper] in deg (in m for a prismatic joint), clipped to the joint limits.
  void box(unsigned int i, double &lower, double &upper) const;
};
//! [World]

/*!
  The world \e armName ("puma", "viper850" or "prismatic") with the paper's rig:
  - puma: the main job's (World()).
  - viper850: ViSP's Viper850 kinematics and true joint limits (vpSimulatorArm::viper850(), as vpSimulatorViper850
    uses), zero reference (0, -150, 190, 0, -75, 0) deg with the gripper at the PUMA's zero-reference tool pose, so
    the markers face the paper's rig (the tests' viperEyeToHand()); trials 30, 8, 12, 30, 30, 60 deg.
  - prismatic: the Stanford arm's R-R-P-R-R-R structure (a telescoping prismatic third joint, spherical wrist; see
    vpSimulatorArm::stanfordTable()), zero reference (0, 60 deg, 0.45 m, 0, -50 deg, 0), tool at the same pose;
    limits +-170 deg, the wrist bend +-120 deg, the slide 0.25-0.75 m; trials 20, 10, 0.04 m, 40, 40, 60 deg.
  The arm's DH offsets hold the zero reference, so that its q = 0 is the zero reference.
  \exception vpException for another name.
*/
World makeWorld(const std::string &armName);

//! \e arm with its DH offsets moved by qRef (theta of a revolute joint, d of a prismatic one) and its limits with
//! them, so that the new q = 0 is the old qRef.
vpSimulatorArm shiftedArm(const vpSimulatorArm &arm, const vpColVector &qRef);

//! A random verged rig of a task and what was drawn.
struct RigDraw {
  double distance = 0, baseline = 0, vergenceDeg = 0, focal = 0, azimuthDeg = 0, elevationDeg = 0;
  unsigned int width = 0, height = 0, draws = 0;
};

/*!
  --rig random: a verged rig drawn from the task's seed (its own stream): two identical cameras verging on the
  centroid of the tracked markers at the zero reference (vpSimulatorStereoRig::vergingRig()), at a distance uniform
  in [0.7, 1.4] m, a full vergence angle uniform in [10, 30] deg (the baseline follows: 2 distance tan(vergence / 2),
  12-75 cm), an image size among 640 x 480, 800 x 600, 1024 x 768 and 1280 x 960, a field of view 30-55 cm wide at
  the fixation point (the focal length follows: width x distance / field, 800-4300 px), square pixels, the principal
  point at the image centre, the rig then turned about the fixation point by an azimuth within +-20 deg (about the
  world's vertical) and an elevation within +-15 deg. Drawn again (same stream) until every tracked marker is marginPx
  inside both images at the zero reference.
  \exception vpException if no rig fits within 1000 draws.
*/
vpSimulatorStereoRig randomRig(const World &world, unsigned int seed, RigDraw &draw);

//! A 63-bit seed for random stream \e stream of the task with seed \e seed (splitmix64 mixing).
long streamSeed(unsigned int seed, unsigned int stream);

enum RandomStream {
  TASK_STREAM = 1,
  SINGULAR_TASK_STREAM = 2,
  NOISE_STREAM = 3,
  OUTLIER_STREAM = 4,
  CALIBRATION_STREAM = 5,
  RIG_STREAM = 6,
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

/*!
  True if the planner's target \e qPlanned is another inverse-kinematic solution than the true target \e qTarget:
  the PUMA's branches differ (branchOf()); for the other arms (no closed-form branch test), Gauss-Newton on the true
  arm from \e qPlanned to the true target's tool pose does not end at \e qTarget (revolute joints modulo 2 pi): the
  solutions of one tool pose are isolated, and the plan's target (the model's inverse kinematics of the measured,
  noisy target images) lies near the solution of its own branch, often degrees away with 3 markers, whose noise
  floor reaches 4-25 deg at 0.5 px, which a plain joint distance could not tell from a branch change.
*/
bool otherBranch(const World &world, const vpColVector &qPlanned, const vpColVector &qTarget);
//! [Branch]

//! Noise-free images of the tracked markers at q; true if all are in view of both cameras (margin 0, as in the main
//! tutorial).
bool trueImages(const World &world, const vpColVector &q, std::vector<vpImagePoint> &left,
                std::vector<vpImagePoint> &right);

//! trueImages() as a app::ImagesAt (\e world must outlive it).
app::ImagesAt trueImagesAt(const World &world);

//! True if q is within the joint limits and the tracked markers are marginPx inside both images.
bool acceptable(const World &world, const vpColVector &q);
} // namespace study

#endif
