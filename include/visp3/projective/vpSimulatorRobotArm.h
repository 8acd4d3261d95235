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
  \file vpSimulatorRobotArm.h
  \brief A vpSimulatorArm behind ViSP's vpRobot interface: joint velocity and position control, as
  vpSimulatorViper850 offers, without a thread.
*/

#ifndef _vpSimulatorRobotArm_h_
#define _vpSimulatorRobotArm_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <chrono>
#include <deque>
#include <utility>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/robot/vpRobot.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpSimulatorRobotArm
  \ingroup group_projective_simulator
  \brief A simulated serial arm (vpSimulatorArm) driven through ViSP's vpRobot interface, the way a program drives
  vpSimulatorViper850 or a real arm: setRobotState(), setVelocity() and setPosition() in the joint space, and
  getPosition() to read the encoders.

  Only the joint space is supported: vpRobot::ARTICULAR_FRAME (= vpRobot::JOINT_STATE). The other frames
  (REFERENCE_FRAME, END_EFFECTOR_FRAME, CAMERA_FRAME, MIXT_FRAME) throw vpRobotException (wrongStateError); the arm's
  Jacobians get_fJe() and get_eJe() are given for a caller's own Cartesian law. Joint values are radians (revolute)
  and metres (prismatic).

  <b>Velocity control</b> (setRobotState(vpRobot::STATE_VELOCITY_CONTROL), then
  setVelocity(vpRobot::ARTICULAR_FRAME, qdot)): the command is saturated the way ViSP's simulators do it
  (vpRobot::saturateVelocities(): the whole vector scaled down, its direction kept, until no revolute joint exceeds
  getMaxRotationVelocity() and no prismatic joint getMaxTranslationVelocity()), then integrated by
  vpSimulatorArm::integrate(): a joint stops at its limit. Two time bases, as in vpRobotWireFrameSimulator:
  - <i>constant sampling time</i> (setConstantSamplingTimeMode(true), the default): each setVelocity() moves the arm
    by exactly one sampling period (setSamplingTime(), default 10 ms) at the command; the readings do not change
    otherwise. Deterministic: tests and studies run as fast as the computer allows.
  - <i>real time</i> (setConstantSamplingTimeMode(false)): the arm moves at the last command for the wall-clock time
    that passes; there is no thread, the motion is integrated lazily whenever the robot is called (getPosition(),
    setVelocity(), setRobotState(), ...), from the last call's time to now (exactly: a constant velocity clamped at
    the limits needs no sub-steps).

  <b>Position control</b> (setPosition(vpRobot::ARTICULAR_FRAME, q)): blocking; the arm moves along the straight
  joint-space line to \e q, every joint arriving together, the slowest at its largest velocity; in real time the call
  takes the motion's duration (a sleep), in the constant sampling time mode it returns at once. A target outside the
  joint limits throws vpRobotException (positionOutOfRangeError) naming the joint, and the arm does not move. As in
  vpSimulatorViper850, setPosition() switches the robot to position control if it was not.

  <b>Encoders.</b> Real arms read absolute encoders whose zero is not the model's: setEncoderOffset() gives the
  readings \f$ q_{enc} = q_{arm} + offset \f$. getPosition(), setPosition(), getJointMin() and getJointMax() are in
  encoder readings; getArmJoints() gives the joints of the vpSimulatorArm (getArm()), to render the cell. A real
  encoder's readings are noisy at rest: setEncoderNoise() adds a seeded Gaussian noise to each getPosition().

  <b>Time.</b> getTime() is the simulated time the arm has moved for. The arm keeps its joints over the last
  seconds (getArmJointsAt()): a simulated camera renders the arm as it was when its image was taken, before the
  encoders were read (vpSimulatorStereoCell::setTiming()). wait() lets time pass at the current command, as a program
  that waits for a camera does.
*/
class VISP_EXPORT vpSimulatorRobotArm : public vpRobot
{
public:
  /*!
    The robot moving \e arm, at the arm's joints \e q0 (n x 1; empty: all zero), in STATE_STOP.
    \exception vpRobotException (positionOutOfRangeError) if \e q0 is outside the arm's joint limits;
    vpProjectiveException (dimensionError) if \e q0 has not n values.
  */
  explicit vpSimulatorRobotArm(const vpSimulatorArm &arm, const vpColVector &q0 = vpColVector());

  //! Nothing to initialise (vpRobot::init()).
  void init() override {}

  /*!
    Changes the state (STATE_STOP, STATE_VELOCITY_CONTROL, STATE_POSITION_CONTROL): the motion so far is integrated,
    and the velocity set to zero unless the new state is velocity control and the robot was already in it.
    \exception vpRobotException (wrongStateError) on STATE_ACCELERATION_CONTROL or STATE_FORCE_TORQUE_CONTROL.
  */
  vpRobotStateType setRobotState(const vpRobot::vpRobotStateType newState) override;

  /*!
    Joint velocities (ARTICULAR_FRAME, n x 1, rad/s or m/s) in STATE_VELOCITY_CONTROL: saturated and integrated (see
    the class documentation).
    \exception vpRobotException (wrongStateError) in another state or another frame;
    vpProjectiveException (dimensionError, nonFiniteValueError) on a vector without n finite values.
  */
  void setVelocity(const vpRobot::vpControlFrameType frame, const vpColVector &qdot) override;
  /*!
    The velocity the arm moves at (ARTICULAR_FRAME): the last command after saturation, zero when stopped; a joint
    held at its limit moves no more but keeps its commanded value.
    \exception vpRobotException (wrongStateError) in another frame.
  */
  void getVelocity(const vpRobot::vpControlFrameType frame, vpColVector &qdot);
  //! The same, returned.
  vpColVector getVelocity(const vpRobot::vpControlFrameType frame);

  /*!
    Moves the arm to the encoder readings \e q (ARTICULAR_FRAME) and returns once there (see the class
    documentation).
    \exception vpRobotException (positionOutOfRangeError) naming the joint if \e q is outside the joint limits,
    (wrongStateError) in another frame; vpProjectiveException (dimensionError, nonFiniteValueError).
  */
  void setPosition(const vpRobot::vpControlFrameType frame, const vpColVector &q) override;
  /*!
    The encoder readings (ARTICULAR_FRAME, n x 1): the arm's joints plus the encoder offset.
    \exception vpRobotException (wrongStateError) in another frame.
  */
  void getPosition(const vpRobot::vpControlFrameType frame, vpColVector &q) override;
  using vpRobot::getPosition;
  /*!
    The joint motion (ARTICULAR_FRAME) since the last call (since construction for the first).
    \exception vpRobotException (wrongStateError) in another frame.
  */
  void getDisplacement(const vpRobot::vpControlFrameType frame, vpColVector &d) override;

  /*!
    The arm's Jacobian in its base frame \c f (6 x n): \f$ (v, \omega) = {}^fJ_e \dot q \f$, the velocity of the
    origin of the last link \c e and its angular velocity, both in the base frame, as vpViper::get_fJe().
  */
  void get_fJe(vpMatrix &fJe) override;
  //! The same in the last link's frame: \f$ {}^eJ_e = \mathrm{diag}({}^eR_f, {}^eR_f)\, {}^fJ_e \f$.
  void get_eJe(vpMatrix &eJe) override;

  /*!
    True (default): constant sampling time, each setVelocity() integrates one sampling period; false: real time.
    The motion so far is integrated first.
  */
  void setConstantSamplingTimeMode(bool constant);
  //! Whether the constant sampling time mode is on.
  bool getConstantSamplingTimeMode() const { return m_constantSampling; }
  /*!
    The sampling period (seconds, > 0; default 0.01): the step of a setVelocity() in the constant sampling time mode
    (unused in real time).
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setSamplingTime(double seconds);
  //! The sampling period (seconds).
  double getSamplingTime() const { return m_samplingTime; }

  /*!
    Encoder readings minus arm joints (n x 1; default zero): getPosition() reads \f$ q_{arm} + offset \f$.
    \exception vpProjectiveException (dimensionError, nonFiniteValueError) on a vector without n finite values.
  */
  void setEncoderOffset(const vpColVector &offset);
  //! The encoder offset (n x 1).
  const vpColVector &getEncoderOffset() const { return m_offset; }

  //! Lower joint limits, in encoder readings (the arm's plus the offset).
  vpColVector getJointMin() const;
  //! Upper joint limits, in encoder readings.
  vpColVector getJointMax() const;
  /*!
    Replaces the arm's joint limits (n x 1 each, in the arm's joints, qmin <= qmax, the current joints inside).
    \exception vpProjectiveException (dimensionError, invalidValueError) as vpSimulatorArm::setJointLimits().
  */
  void setJointLimits(const vpColVector &qmin, const vpColVector &qmax);

  //! Number of joints.
  unsigned int getNumberOfJoints() const { return m_arm.getNumberOfJoints(); }
  //! The simulated arm (its geometry, markers and limits).
  const vpSimulatorArm &getArm() const { return m_arm; }
  //! The arm's joints now (n x 1, without the encoder offset): what to render the cell with.
  vpColVector getArmJoints();
  //! Simulated time (seconds) the arm has moved for since construction: sampling periods and position moves.
  double getTime() const { return m_time; }
  /*!
    The arm's joints (n x 1, without the encoder offset) at the simulated time \e t (seconds, getTime()'s clock):
    interpolated in the motion of the last 10 s (the joints move linearly between two commands); before that, the
    oldest joints kept; after getTime(), the joints now.
  */
  vpColVector getArmJointsAt(double t);
  /*!
    Lets \e seconds (>= 0) of simulated time pass at the current command: the arm moves on at its velocity in
    STATE_VELOCITY_CONTROL and stays put otherwise; in real time the call sleeps for that long.
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void wait(double seconds);
  /*!
    Standard deviation \e sigma (>= 0, rad for a revolute joint, m for a prismatic one) of a Gaussian noise added to
    each joint of every getPosition(), from the seed \e seed; 0 (default): exact readings.
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setEncoderNoise(double sigma, long seed = 1);

private:
  void requireJointSpace(vpRobot::vpControlFrameType frame, const char *method) const;
  vpColVector jointVector(const vpColVector &v, const char *method, const char *name) const;
  vpColVector maxVelocities() const;
  void advance(double dt);
  void catchUp();
  void remember();

  vpSimulatorArm m_arm;
  vpColVector m_q;         // arm joints
  vpColVector m_qdot;      // saturated command
  vpColVector m_offset;    // encoder readings - arm joints
  vpColVector m_qLastRead; // arm joints at the last getDisplacement()
  bool m_constantSampling;
  double m_samplingTime;
  double m_time;
  std::chrono::steady_clock::time_point m_last;         // real time: the instant the motion was integrated to
  std::deque<std::pair<double, vpColVector>> m_history; // (time, arm joints) at each change of the motion
  double m_encoderNoise;
  vpGaussRand m_encoderRand;
};

END_VISP_NAMESPACE

#endif
