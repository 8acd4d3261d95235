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

/*
  vpProjectiveAcquisitionProcedure on the robots ViSP 3.5 ships: vpSimulatorViper850 (6 revolute joints) and
  vpSimulatorAfma6 (a gantry: 3 prismatic joints, then 3 revolute), in both their modes (real time, and constant
  sampling time: one step per setVelocity()), with its default motion (joint velocities). Each simulator runs its own
  thread; the runs are kept short (a few seconds each: 4 deg or 1 cm steps, 3 times ViSP's default speeds). A stereo rig
  of paper cameras watches markers on the tool (eye-to-hand) or rides on the flange looking at static markers
  (eye-in-hand, the mounting left at its default EYE_TO_HAND: the procedure must tell it). The model must fit at the
  noise level, the mounting be found, the robot end at the zero reference.
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <sstream>
#include <string>
#include <type_traits>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/robot/vpSimulatorAfma6.h>
#include <visp3/robot/vpSimulatorViper850.h>

#include "vpProjectiveTestTools.h"

namespace
{
//! Swallows std::cout while alive: ViSP's simulators print their state changes.
struct QuietCout {
  std::ostringstream sink;
  std::streambuf *saved;
  QuietCout() : sink(), saved(std::cout.rdbuf(sink.rdbuf())) {}
  ~QuietCout() { std::cout.rdbuf(saved); }
};

/*!
  A cell around a ViSP simulated arm \e Robot (kinematics \e Kinematics: vpViper or vpAfma6): the rig and the
  markers, and the images the procedure reads at the arm's current joints.
*/
template <class Robot, class Kinematics> struct Cell {
  Robot &robot;
  bool eyeInHand;
  vpColVector qRef;
  vpSimulatorStereoRig rig0;         // the rig at qRef
  vpHomogeneousMatrix eMl;           // eye-in-hand: the left camera on the flange
  std::vector<vpColVector> fMarkers; // eye-in-hand: static markers (robot base frame)
  std::vector<vpColVector> eMarkers; // eye-to-hand: markers on the flange
  vpGaussRand noise;
  double sigma;

  Cell(Robot &r, bool inHand)
      : robot(r), eyeInHand(inHand), qRef(currentJoints(r)), rig0(initialRig(r, inHand, qRef)),
        eMl(flangeRig().get_wMl()), fMarkers(), eMarkers(), noise(1.0, 0.0, 3), sigma(0.2)
  {
    const vpHomogeneousMatrix fMe0 = fMe(qRef);
    if (eyeInHand) {
      fMarkers = vpSimulatorStereoRig::transform(fMe0 * eMo(true), vpSimulatorArm::gripperMarkers());
    } else {
      eMarkers = vpSimulatorStereoRig::transform(eMo(false), vpSimulatorArm::gripperMarkers());
    }
  }

  static vpColVector currentJoints(Robot &r)
  {
    vpColVector q;
    r.getPosition(vpRobot::ARTICULAR_FRAME, q);
    return q;
  }

  static vpCameraParameters camera() { return vpCameraParameters(800.0, 800.0, 320.0, 240.0); }

  //! The 7 gripper markers (no 4 coplanar) in front of the flange on its z axis, turned a little.
  static vpHomogeneousMatrix eMo(bool inHand)
  {
    return vpHomogeneousMatrix(0.0, 0.0, inHand ? 0.6 : 0.1, 0.3, 0.2, 0.1);
  }

  //! Eye-in-hand: cameras 15 cm apart on the flange, verging on the point 60 cm in front of it (flange frame).
  static vpSimulatorStereoRig flangeRig()
  {
    return vpSimulatorStereoRig::vergingRig(vpProjectiveTest::point3(0.0, 0.0, 0.6), 0.6, 0.15, camera());
  }

  static vpHomogeneousMatrix fMeOf(const Robot &r, const vpColVector &q)
  {
    vpHomogeneousMatrix M;
    static_cast<const Kinematics &>(r).get_fMe(q, M);
    return M;
  }

  //! The rig at qRef: on the flange, or fixed 1 m from the markers (30 cm baseline) looking along the base's z axis.
  static vpSimulatorStereoRig initialRig(const Robot &r, bool inHand, const vpColVector &q0)
  {
    const vpHomogeneousMatrix fMe0 = fMeOf(r, q0);
    if (inHand) {
      const vpSimulatorStereoRig f = flangeRig();
      return vpSimulatorStereoRig(f.getLeftCameraParameters(), f.getRightCameraParameters(), f.get_rMl(),
                                  fMe0 * f.get_wMl(), f.getWidth(), f.getHeight());
    }
    const vpHomogeneousMatrix fMo = fMe0 * eMo(false);
    return vpSimulatorStereoRig::vergingRig(vpProjectiveTest::point3(fMo[0][3], fMo[1][3], fMo[2][3]), 1.0, 0.3,
                                            camera());
  }

  vpHomogeneousMatrix fMe(const vpColVector &q) const { return fMeOf(robot, q); }

  vpSimulatorStereoRig simAt(const vpColVector &q) const
  {
    if (!eyeInHand) {
      return rig0;
    }
    return vpSimulatorStereoRig(rig0.getLeftCameraParameters(), rig0.getRightCameraParameters(), rig0.get_rMl(),
                                fMe(q) * eMl, rig0.getWidth(), rig0.getHeight());
  }

  bool images(const vpColVector &q, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right, double s)
  {
    const std::vector<vpColVector> X = eyeInHand ? fMarkers : vpSimulatorStereoRig::transform(fMe(q), eMarkers);
    return simAt(q).project(X, left, right, s, noise);
  }

  vpProjectiveAcquisitionProcedure::vpImageSource source()
  {
    return [this](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      vpColVector q;
      robot.getPosition(vpRobot::ARTICULAR_FRAME, q); // a real cell: the stereo tracker's markers
      return images(q, left, right, sigma);
    };
  }
};

template <class Robot, class Kinematics> void acquire(Robot &robot, bool eyeInHand, const std::string &name)
{
  QuietCout quiet;
  Cell<Robot, Kinematics> cell(robot, eyeInHand);
  std::vector<vpProjectiveRobot::vpJointType> types(6, vpProjectiveRobot::REVOLUTE);
  vpColVector steps(6, vpMath::rad(4.0)), amounts(6, vpMath::rad(12.0)), minimum(6, vpMath::rad(2.0));
  if (std::is_same<Kinematics, vpAfma6>::value) {
    for (unsigned int i = 0; i < 3; ++i) {
      types[i] = vpProjectiveRobot::PRISMATIC;
      steps[i] = 0.01;
      amounts[i] = 0.03;
      minimum[i] = 0.005;
    }
  }
  vpProjectiveAcquisitionProcedure procedure(cell.source(), cell.rig0.getWidth(), cell.rig0.getHeight());
  procedure.setSteps(steps);
  procedure.setMaxAmounts(amounts);
  procedure.setMinAmounts(minimum);
  if (eyeInHand) {
    procedure.setJointLimits(robot.getJointMin(), robot.getJointMax(), vpMath::rad(2.0));
  } // else the procedure takes the robot's own (vpViper, vpAfma6 know theirs)
  procedure.setSpeed(vpMath::rad(120.0), 0.3); // 3 times ViSP's defaults: a short test
  std::ostringstream log;
  procedure.setOutput(&log);
  vpProjectiveRobot model(types); // the mounting left at EYE_TO_HAND: eye-in-hand, the procedure must tell it
  model.setStereoRig([&cell]() {
    vpProjectiveStereoRig r;
    r.setFundamentalMatrix(cell.rig0.getFundamentalMatrix());
    return r;
  }());
  procedure.run(robot, model);

  EXPECT_LT(model.getAcquisition().getCalibrationResidual(), 2.0 * cell.sigma) << name << "\n" << log.str();
  EXPECT_EQ(model.getRigMounting(), eyeInHand ? vpProjectiveRobot::EYE_IN_HAND : vpProjectiveRobot::EYE_TO_HAND)
      << name;
  EXPECT_TRUE(procedure.getMountingReport().checked) << name;
  EXPECT_NE(log.str().find(eyeInHand ? "joint limits: setJointLimits()" : "joint limits: the robot's own"),
            std::string::npos)
      << log.str();
  EXPECT_LT(procedure.getMountingReport().residual, 3.0 * cell.sigma) << name;
  vpColVector q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  EXPECT_LT((q - cell.qRef).frobeniusNorm(), 3e-5) << name; // back at the zero reference (1e-5 per joint)
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_GT(std::max(procedure.getReports()[i].amountNegative, procedure.getReports()[i].amountPositive), minimum[i])
        << name << ", joint " << i;
  }
  // The model predicts a motion of three joints together (never seen in the acquisition) within the noise.
  vpColVector q3 = cell.qRef;
  for (unsigned int i : {0u, 3u, 4u}) {
    q3[i] += 0.5 * procedure.getReports()[i].amountPositive;
  }
  std::vector<vpImagePoint> left, right;
  ASSERT_TRUE(cell.images(q3, left, right, 0.0)) << name;
  EXPECT_LT(model.getPredictionError(q3, left, right), cell.sigma) << name;
}

TEST(ProjectiveAcquisitionViSPRobots, Viper850RealTimeEyeToHand)
{
  QuietCout quiet;
  vpSimulatorViper850 robot(false);
  acquire<vpSimulatorViper850, vpViper>(robot, false, "Viper850, real time, eye-to-hand");
}

TEST(ProjectiveAcquisitionViSPRobots, Viper850ConstantSamplingEyeInHand)
{
  QuietCout quiet;
  vpSimulatorViper850 robot(false);
  robot.setConstantSamplingTimeMode(true);
  acquire<vpSimulatorViper850, vpViper>(robot, true, "Viper850, constant sampling time, eye-in-hand");
}

TEST(ProjectiveAcquisitionViSPRobots, Afma6RealTimeEyeInHand)
{
  QuietCout quiet;
  vpSimulatorAfma6 robot(false);
  acquire<vpSimulatorAfma6, vpAfma6>(robot, true, "Afma6, real time, eye-in-hand");
}

TEST(ProjectiveAcquisitionViSPRobots, Afma6ConstantSamplingEyeToHand)
{
  QuietCout quiet;
  vpSimulatorAfma6 robot(false);
  robot.setConstantSamplingTimeMode(true);
  acquire<vpSimulatorAfma6, vpAfma6>(robot, false, "Afma6, constant sampling time, eye-to-hand");
}
} // namespace
