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
  \file vpProjectiveCellArm.h
  \brief The arm of a real cell as vpProjectiveCell drives it: the five calls an adapter gives (read the joints, send
  joint velocities, stop, the limits, the largest speeds), and the adapter of any ViSP vpRobot.
*/

#ifndef _vpProjectiveCellArm_h_
#define _vpProjectiveCellArm_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/robot/vpRobot.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveCellArm
  \ingroup group_projective
  \brief What a real-cell program needs of an arm, and nothing more: an adapter to write for an arm without a ViSP
  driver (a ROS controller, a vendor's SDK, a socket protocol), in five calls.

  Units: joint values in radians (revolute) and metres (prismatic), velocities per second, joints indexed from 0 at
  the robot's base, as the encoders read them (any fixed zero). Times in seconds on the clock the cameras stamp their
  images with (vpStereoImageSource::getTimestamps()): CLOCK_MONOTONIC on Linux, which is both
  std::chrono::steady_clock and the clock of V4L2's buffer time stamps.

  The contract, which vpProjectiveCellRobot relies on and tests with the rendered cell:
  - getJoints() reads the encoders now, and says when they were read;
  - setJointVelocities() commands joint velocities that the arm keeps until the next call or stop(); they come
    already checked (size, finite values, within getMaxJointVelocities() and the joint limits): the adapter sends
    them. A controller with a command watchdog (most have one: the arm stops when no command came for a few
    control periods) is safest, since a program blocked in a camera call sends nothing;
  - stop() brings the arm to rest at once (zero velocity; its brakes if that is how it stops). It is called on every
    exit path of vpProjectiveCell, possibly several times and after an error of the arm itself: it should not throw
    (an exception from it is caught and reported, and the program still ends);
  - getJointLimits() gives the limits if the arm knows them (false otherwise: vpProjectiveCell then refuses to move
    the arm unless the user gives limits or says explicitly that there are none);
  - getMaxJointVelocities() gives the largest speed the arm allows per joint (the commands stay below the smaller of
    it and the user's setting).
  \code
  class MyArm : public vpProjectiveCellArm
  {
  public:
    std::vector<vpProjectiveJoint::vpJointType> getJointTypes() const override
    {
      return std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE);
    }
    void getJoints(vpColVector &q, double &t) override { q = m_driver.readJoints(); t = steadySeconds(); }
    void setJointVelocities(const vpColVector &qdot) override { m_driver.speedJ(qdot); }
    void stop() override { m_driver.stopJ(); }
    bool getJointLimits(vpColVector &qmin, vpColVector &qmax) override { ...; return true; }
    vpColVector getMaxJointVelocities() override { return vpColVector(6, vpMath::rad(60.0)); }
  };
  \endcode
*/
class VISP_EXPORT vpProjectiveCellArm
{
public:
  virtual ~vpProjectiveCellArm() {}
  //! The kinds of the joints, base to tip; their number is the arm's.
  virtual std::vector<vpProjectiveJoint::vpJointType> getJointTypes() const = 0;
  /*!
    Reads the encoders: \e q (n x 1, rad or m) and the instant \e t (seconds) of the reading, on the cameras' clock.
  */
  virtual void getJoints(vpColVector &q, double &t) = 0;
  //! Commands the joint velocities \e qdot (n x 1, rad/s or m/s, checked), kept until the next call or stop().
  virtual void setJointVelocities(const vpColVector &qdot) = 0;
  //! Brings the arm to rest now (zero velocity). Should not throw.
  virtual void stop() = 0;
  /*!
    The joint limits (n x 1 each, rad or m, in encoder readings) if the arm knows them: true. Default: false.
  */
  virtual bool getJointLimits(vpColVector &qmin, vpColVector &qmax)
  {
    (void)qmin;
    (void)qmax;
    return false;
  }
  //! The largest velocity of each joint (n x 1, rad/s or m/s, > 0) that the arm allows.
  virtual vpColVector getMaxJointVelocities() = 0;
};

/*!
  \class vpProjectiveCellViSPArm
  \ingroup group_projective
  \brief Any ViSP robot (vpRobot: vpRobotFranka, vpRobotViper850, vpRobotAfma6, vpRobotUniversalRobots, the simulators
  vpSimulatorViper850 and vpSimulatorRobotArm...) as a vpProjectiveCellArm, driven in the joint space.

  getJoints() is vpRobot::getPosition(vpRobot::ARTICULAR_FRAME) (its time: the simulated time of a vpSimulatorRobotArm,
  std::chrono::steady_clock otherwise); setJointVelocities() switches the robot to STATE_VELOCITY_CONTROL if needed
  and calls vpRobot::setVelocity(vpRobot::ARTICULAR_FRAME); stop() sends a zero velocity and
  setRobotState(vpRobot::STATE_STOP). The joint limits are those of the robot classes that know theirs (vpViper,
  vpAfma4, vpAfma6, vpRobotFranka, vpSimulatorRobotArm); the largest speeds are vpRobot::getMaxRotationVelocity() and
  getMaxTranslationVelocity() (ViSP's defaults: 0.7 rad/s, 0.2 m/s) as the robot has them when the adapter is made.
*/
class VISP_EXPORT vpProjectiveCellViSPArm : public vpProjectiveCellArm
{
public:
  /*!
    The adapter of \e robot (which must outlive it), whose joints are of the kinds \e types.
    \exception vpProjectiveException (dimensionError) if \e types is empty.
  */
  vpProjectiveCellViSPArm(vpRobot &robot, const std::vector<vpProjectiveJoint::vpJointType> &types);
  std::vector<vpProjectiveJoint::vpJointType> getJointTypes() const override { return m_types; }
  void getJoints(vpColVector &q, double &t) override;
  void setJointVelocities(const vpColVector &qdot) override;
  void stop() override;
  bool getJointLimits(vpColVector &qmin, vpColVector &qmax) override;
  vpColVector getMaxJointVelocities() override { return m_maxVelocities; }

private:
  vpRobot &m_robot;
  std::vector<vpProjectiveJoint::vpJointType> m_types;
  vpColVector m_maxVelocities;
};

END_VISP_NAMESPACE

#endif
