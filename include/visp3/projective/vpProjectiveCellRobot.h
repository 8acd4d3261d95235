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
  \file vpProjectiveCellRobot.h
  \brief A vpProjectiveCellArm as a ViSP vpRobot, with the safety layer every command of a real-cell program goes
  through: joint limits, speeds, a latched stop, SIGINT and SIGTERM.
*/

#ifndef _vpProjectiveCellRobot_h_
#define _vpProjectiveCellRobot_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveCellArm.h>
#include <visp3/robot/vpRobot.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveCellRobot
  \ingroup group_projective
  \brief The arm of a vpProjectiveCellArm behind ViSP's vpRobot (joint space, velocity control), so that
  vpProjectiveAcquisitionProcedure and any ViSP loop drive it; every command passes its safety checks.

  setVelocity(vpRobot::ARTICULAR_FRAME, qdot), in STATE_VELOCITY_CONTROL:
  - a vector without n finite values is refused (vpProjectiveException, dimensionError or nonFiniteValueError);
  - it is scaled down, its direction kept (vpRobot::saturateVelocities()), until no joint exceeds the smaller of its
    speed of the constructor and vpRobot::getMaxRotationVelocity() (revolute) or getMaxTranslationVelocity()
    (prismatic);
  - the joints are read first: a joint at or beyond its limit (the range of the constructor) that the command moves
    further out halts the robot;
  - after halt(), a received SIGINT or SIGTERM (installSignalHandlers()) or an exception of the arm, the robot is
    halted: the arm is stopped, and every later command that is not zero throws vpProjectiveException
    (robotMotionError) with the reason; a zero command stops the arm again. The halt is latched: it lasts until the
    object is destroyed (a program starts again from a stopped arm, by a new robot).
  getPosition() reads the arm (and halts on a pending signal: the procedures that only read notice a Ctrl-C too).
  setRobotState(STATE_STOP) and the destructor stop the arm; setPosition(), getDisplacement(), get_eJe() and
  get_fJe() throw vpRobotException (wrongStateError): the cell moves by joint velocities only, and its model is the
  projective one.
*/
class VISP_EXPORT vpProjectiveCellRobot : public vpRobot
{
public:
  /*!
    The robot of \e arm (which must outlive it), kept within \e qmin, \e qmax (n x 1 each, rad or m, encoder
    readings: the safe range, the arm's limits less a margin; both empty: no limit check, which a program should allow
    only when its user says so) and below the speeds \e maxVelocity (n x 1, > 0, rad/s or m/s).
    vpRobot::getMaxRotationVelocity() and getMaxTranslationVelocity() start at the largest of those speeds.
    \exception vpProjectiveException (dimensionError, invalidValueError, nonFiniteValueError) on sizes that are not
    the arm's, qmin >= qmax, a speed that is not positive, or a value that is not finite.
  */
  vpProjectiveCellRobot(vpProjectiveCellArm &arm, const vpColVector &qmin, const vpColVector &qmax,
                        const vpColVector &maxVelocity);
  //! Stops the arm.
  ~vpProjectiveCellRobot() override;

  //! Nothing to initialise (vpRobot::init()).
  void init() override {}
  /*!
    STATE_STOP stops the arm; STATE_VELOCITY_CONTROL allows setVelocity().
    \exception vpRobotException (wrongStateError) on another state.
  */
  vpRobotStateType setRobotState(const vpRobot::vpRobotStateType newState) override;
  /*!
    Joint velocities (ARTICULAR_FRAME, n x 1) after the checks of the class documentation.
    \exception vpRobotException (wrongStateError) in another frame or state; vpProjectiveException (robotMotionError)
    when halted, (dimensionError, nonFiniteValueError) on a bad vector.
  */
  void setVelocity(const vpRobot::vpControlFrameType frame, const vpColVector &qdot) override;
  /*!
    The encoder readings (ARTICULAR_FRAME, n x 1).
    \exception vpRobotException (wrongStateError) in another frame; vpProjectiveException (robotMotionError) on a
    pending signal.
  */
  void getPosition(const vpRobot::vpControlFrameType frame, vpColVector &q) override;
  using vpRobot::getPosition;
  //! The encoder readings \e q and their time \e t (seconds, the arm's clock); as getPosition().
  void getJoints(vpColVector &q, double &t);
  //! \exception vpRobotException (wrongStateError): the cell moves by joint velocities only.
  void setPosition(const vpRobot::vpControlFrameType frame, const vpColVector &q) override;
  //! \exception vpRobotException (wrongStateError): not available.
  void getDisplacement(const vpRobot::vpControlFrameType frame, vpColVector &d) override;
  //! \exception vpRobotException (wrongStateError): not available (the model is projective).
  void get_eJe(vpMatrix &eJe) override;
  //! \exception vpRobotException (wrongStateError): not available (the model is projective).
  void get_fJe(vpMatrix &fJe) override;

  //! Stops the arm (vpProjectiveCellArm::stop()); an exception of the arm is caught and kept (getStopError()).
  void stop();
  //! Stops the arm and halts the robot (see the class documentation) for \e reason, unless already halted.
  void halt(const std::string &reason);
  //! Whether the robot is halted.
  bool isHalted() const { return !m_haltReason.empty(); }
  //! Why the robot is halted (empty if not).
  const std::string &getHaltReason() const { return m_haltReason; }
  //! The message of the last exception the arm's stop() threw (empty if none).
  const std::string &getStopError() const { return m_stopError; }
  /*!
    The time (the arm's clock) of the reading that came with the last command after which the arm was at rest: a
    zero command that followed a motion, or the construction; images taken after it show the arm still.
  */
  double getRestTime() const { return m_restTime; }
  //! The last command sent to the arm (n x 1; zero after a stop).
  const vpColVector &getLastCommand() const { return m_command; }
  //! The number of the arm's stop() calls so far.
  unsigned int getStopCount() const { return m_stops; }

  /*!
    Makes SIGINT (Ctrl-C) and SIGTERM halt every vpProjectiveCellRobot at its next call (reading or command), the
    arm stopped: the handler only records the signal. It is reset to the default one when it runs, so that a second
    Ctrl-C ends a program that does not call the robot any more. Blocking reads of the standard input are not
    restarted (they fail, and the program notices the signal).
  */
  static void installSignalHandlers();
  //! The signal received since installSignalHandlers() or clearSignal() (0: none).
  static int getSignal();
  //! Forgets the signal received (a program that handled it and starts again; tests).
  static void clearSignal();

private:
  void checkSignal();
  void send(const vpColVector &qdot);

  vpProjectiveCellArm &m_arm;
  std::vector<vpProjectiveJoint::vpJointType> m_types;
  vpColVector m_qmin, m_qmax, m_maxVelocity, m_command;
  std::string m_haltReason, m_stopError;
  double m_restTime;
  unsigned int m_stops;
};

END_VISP_NAMESPACE

#endif
