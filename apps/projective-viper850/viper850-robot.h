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
  \file viper850-robot.h
  \brief Driving ViSP's vpSimulatorViper850 deterministically: constant sampling time, one simulator step per command,
  positioning by velocity steps; and the scene helpers of projective-viper850.
*/

#ifndef _app_projective_servo_viper850_robot_h_
#define _app_projective_servo_viper850_robot_h_

#include <algorithm>
#include <cmath>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpRxyzVector.h>
#include <visp3/core/vpTime.h>
#include <visp3/robot/vpSimulatorViper850.h>

#include <visp3/projective/vpSimulatorStereoRig.h>

#include "paper-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#if defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_PTHREAD)

namespace viper850
{
//! End-effector pose in the robot's base frame from ViSP's kinematic model of the Viper850.
inline vpHomogeneousMatrix get_fMe(const vpViper850 &viper, const vpColVector &q)
{
  vpHomogeneousMatrix fMe;
  viper.get_fMe(q, fMe);
  return fMe;
}

//! [Robot]
const double samplingTime = 0.005;        //!< s, the simulator's sampling time, here the control period too
const double maxStep = vpMath::rad(15.0); //!< largest joint motion per period (rad), for positioning and servoing alike

/*!
  vpSimulatorViper850 integrates the joint velocities in a thread of its own, in real time by default. In the
  constant sampling time mode (vpRobotWireFrameSimulator::setConstantSamplingTimeMode()), it instead makes exactly
  one step of getSamplingTime() seconds for each setVelocity() call, when its thread next polls the command (it does
  so every 4 ms). Waiting for that step before the next image makes the run independent of the machine's load. The
  thread still waits getSamplingTime() in real time after each step: ViSP's default of 10 ms would lengthen the
  study by half, and it refuses less than 4 ms (vpTime::getMinTimeForUsleepCall()).

  With \e externalView (the robot built with its display), ViSP's external camera is placed to show the arm.
*/
inline void setupRobot(vpSimulatorViper850 &robot, bool externalView)
{
  robot.setConstantSamplingTimeMode(true);
  robot.setSamplingTime(samplingTime);
  // setVelocity() would scale down any command above this joint velocity (rad/s).
  robot.setMaxRotationVelocity(maxStep / robot.getSamplingTime());
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  if (externalView) {
    // ViSP's external camera 2 m to the right of the arm, looking at it along +y of the base frame.
    const vpHomogeneousMatrix fMc(vpTranslationVector(0.4, -2.0, 0.5), vpRotationMatrix(vpRxyzVector(-M_PI / 2, 0, 0)));
    robot.setExternalCameraPosition(fMc.inverse());
  }
}

//! Sends qdot (rad/s) and returns the joint positions read once the simulator has integrated it over one period.
inline vpColVector applyVelocity(vpSimulatorViper850 &robot, const vpColVector &qdot)
{
  vpColVector q0, q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q0);
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  // The simulator's step is q0 + Ts qdot; if that rounds to q0 there is no change to wait for.
  bool moves = false;
  for (unsigned int i = 0; i < q0.size(); ++i) {
    moves = moves || (q0[i] + robot.getSamplingTime() * qdot[i] != q0[i]);
  }
  q = q0;
  const double t0 = vpTime::measureTimeMs();
  while (moves) {
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    bool changed = false;
    for (unsigned int i = 0; i < q.size(); ++i) {
      changed = changed || q[i] != q0[i];
    }
    if (changed) {
      break;
    }
    if (vpTime::measureTimeMs() - t0 > 10000.0) {
      throw vpException(vpException::fatalError, "the simulated Viper850 did not move within 10 s of a command");
    }
    vpTime::sleepMs(0.2);
  }
  return q;
}

/*!
  Moves the arm along a straight line in joint space to qGoal, by steps of at most maxStep, and returns the joint
  positions reached (qGoal up to rounding). vpSimulatorViper850::setPosition() would be the natural call, but in
  ViSP 3.5 its thread overwrites the positioning velocity with the last setVelocity() command (zero after a stop), so
  that a 20 deg move did not finish within minutes; velocity steps are exact and repeatable.
*/
inline vpColVector moveTo(vpSimulatorViper850 &robot, const vpColVector &qGoal)
{
  vpColVector q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  double largest = 0.0;
  for (unsigned int i = 0; i < q.size(); ++i) {
    largest = std::max(largest, std::abs(qGoal[i] - q[i]));
  }
  for (unsigned int k = static_cast<unsigned int>(std::ceil(largest / maxStep)); k > 0; --k) {
    q = applyVelocity(robot, (qGoal - q) / (k * robot.getSamplingTime())); // what remains, spread over k steps
  }
  return q;
}
//! [Robot]

//! [Images]
/*!
  The images of the markers \e which seen by the rig where it is when the joints are at qRef + q (World::rigAt()),
  at the markers where they are then (World::markersAt()), with Gaussian noise \e sigma (none if \e noise is null),
  as an ImagesAt of the model's joint values q (of the arm's joint values if \\e qRef is empty). \e world, \e viper and
  \e noise must outlive it.
*/
template <class World>
app::ImagesAt imagesAt(const World &world, const vpViper850 &viper, const std::vector<unsigned int> &which,
                       double sigma, vpGaussRand *noise, const vpColVector &qRef)
{
  return [&world, &viper, which, sigma, noise, qRef](const vpColVector &q, std::vector<vpImagePoint> &left,
                                                     std::vector<vpImagePoint> &right) {
    const vpColVector qArm = qRef.size() > 0 ? qRef + q : q;
    const vpSimulatorStereoRig &rig = world.rigAt(viper, qArm);
    const std::vector<vpColVector> &fMarkers = world.markersAt(viper, qArm);
    left.resize(which.size());
    right.resize(which.size());
    bool inView = true;
    for (size_t k = 0; k < which.size(); ++k) {
      inView = (noise == nullptr ? rig.project(fMarkers[which[k]], left[k], right[k])
                                 : rig.project(fMarkers[which[k]], left[k], right[k], sigma, *noise)) &&
               inView;
    }
    return inView;
  };
}

//! All the markers of the world, 0 to nbMarkers() - 1.
template <class World> std::vector<unsigned int> allMarkers(const World &world)
{
  std::vector<unsigned int> all(world.nbMarkers());
  for (unsigned int j = 0; j < all.size(); ++j) {
    all[j] = j;
  }
  return all;
}
//! [Images]
} // namespace viper850

#endif
#endif
