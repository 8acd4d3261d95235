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
  \file vpProjectiveCellRobot.cpp
  \brief The safety layer of the real-cell program: limits, speeds, the latched stop, signals.
*/

#include <visp3/projective/vpProjectiveCellRobot.h>

#include <csignal>
#include <cmath>
#include <sstream>

#include <signal.h>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/robot/vpRobotException.h>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveCellRobot");

volatile std::sig_atomic_t g_signal = 0;

extern "C" void recordSignal(int signal)
{
  g_signal = signal;
}

std::string jointValue(double v, bool revolute)
{
  std::ostringstream os;
  os << (revolute ? vpMath::deg(v) : v) << (revolute ? " deg" : " m");
  return os.str();
}
} // namespace

vpProjectiveCellRobot::vpProjectiveCellRobot(vpProjectiveCellArm &arm, const vpColVector &qmin, const vpColVector &qmax,
                                             const vpColVector &maxVelocity)
    : vpRobot(), m_arm(arm), m_types(arm.getJointTypes()), m_qmin(), m_qmax(), m_maxVelocity(maxVelocity),
      m_command(static_cast<unsigned int>(m_types.size()), 0.0), m_haltReason(), m_stopError(), m_restTime(0.0),
      m_stops(0)
{
  const unsigned int n = static_cast<unsigned int>(m_types.size());
  nDof = static_cast<int>(n);
  if (n == 0 || maxVelocity.size() != n || qmin.size() != qmax.size() || (qmin.size() != 0 && qmin.size() != n)) {
    std::ostringstream os;
    os << "the arm has " << n << " joints: give n speeds and n lower and upper limits (or no limits), not "
       << maxVelocity.size() << " speeds and " << qmin.size() << " and " << qmax.size() << " limits";
    fail(vpProjectiveException::dimensionError, at("vpProjectiveCellRobot()"), os.str());
  }
  m_qmin = qmin; // assigned, not copy-constructed: ViSP 3.5 copies an empty vector (no limits) by memcpy from null
  m_qmax = qmax;
  double rotation = 0.0, translation = 0.0;
  for (unsigned int i = 0; i < n; ++i) {
    const bool revolute = m_types[i] == vpProjectiveJoint::REVOLUTE;
    requireFinite(maxVelocity[i], at("vpProjectiveCellRobot()"), "a speed");
    if (!(maxVelocity[i] > 0.0)) {
      fail(vpProjectiveException::invalidValueError, at("vpProjectiveCellRobot()"),
           "the speed of joint " + std::to_string(i) + " must be > 0 (rad/s or m/s)");
    }
    (revolute ? rotation : translation) = std::max(revolute ? rotation : translation, maxVelocity[i]);
    if (qmin.size() != 0) {
      requireFinite(qmin[i], at("vpProjectiveCellRobot()"), "a lower limit");
      requireFinite(qmax[i], at("vpProjectiveCellRobot()"), "an upper limit");
      if (!(qmin[i] < qmax[i])) {
        fail(vpProjectiveException::invalidValueError, at("vpProjectiveCellRobot()"),
             "joint " + std::to_string(i) + " has a lower limit " + jointValue(qmin[i], revolute) +
                 " not below its upper limit " + jointValue(qmax[i], revolute));
      }
    }
  }
  setMaxRotationVelocity(rotation > 0.0 ? rotation : getMaxRotationVelocity());
  setMaxTranslationVelocity(translation > 0.0 ? translation : getMaxTranslationVelocity());
}

vpProjectiveCellRobot::~vpProjectiveCellRobot()
{
  stop();
}

void vpProjectiveCellRobot::installSignalHandlers()
{
  struct sigaction action = {};
  action.sa_handler = recordSignal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = SA_RESETHAND; // no SA_RESTART: a blocking read returns, and the program sees the signal
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

int vpProjectiveCellRobot::getSignal()
{
  return static_cast<int>(g_signal);
}

void vpProjectiveCellRobot::clearSignal()
{
  g_signal = 0;
}

void vpProjectiveCellRobot::stop()
{
  ++m_stops;
  if (m_command.frobeniusNorm() > 0.0) { // the arm comes to rest now: images after this show it still
    try {
      vpColVector q;
      m_arm.getJoints(q, m_restTime);
    } catch (...) {
    }
  }
  m_command = 0.0;
  try {
    m_arm.stop();
  } catch (const std::exception &e) {
    m_stopError = e.what();
  } catch (...) {
    m_stopError = "an unknown exception";
  }
  vpRobot::setRobotState(vpRobot::STATE_STOP);
}

void vpProjectiveCellRobot::halt(const std::string &reason)
{
  if (m_haltReason.empty()) {
    m_haltReason = reason;
  }
  stop();
}

void vpProjectiveCellRobot::checkSignal()
{
  const int signal = getSignal();
  if (signal != 0 && !isHalted()) {
    halt(signal == SIGINT ? "SIGINT received (Ctrl-C)" : signal == SIGTERM ? "SIGTERM received" : "a signal received");
  }
  if (signal != 0) {
    throw vpProjectiveException(vpProjectiveException::robotMotionError,
                                at("getPosition()") + ": the arm was stopped: " + m_haltReason);
  }
}

vpRobot::vpRobotStateType vpProjectiveCellRobot::setRobotState(const vpRobot::vpRobotStateType newState)
{
  if (newState == vpRobot::STATE_STOP) {
    stop();
    return getRobotState();
  }
  if (newState != vpRobot::STATE_VELOCITY_CONTROL) {
    throw vpRobotException(vpRobotException::wrongStateError,
                           at("setRobotState()") + ": a real cell's arm is driven by joint velocities only "
                                                   "(STATE_VELOCITY_CONTROL) or stopped (STATE_STOP).");
  }
  return vpRobot::setRobotState(newState);
}

void vpProjectiveCellRobot::send(const vpColVector &qdot)
{
  try {
    m_arm.setJointVelocities(qdot);
    m_command = qdot;
  } catch (const std::exception &e) {
    halt(std::string("the arm refused a command (") + e.what() + ")");
    throw;
  }
}

void vpProjectiveCellRobot::setVelocity(const vpRobot::vpControlFrameType frame, const vpColVector &qdot)
{
  if (frame != vpRobot::ARTICULAR_FRAME) {
    throw vpRobotException(vpRobotException::wrongStateError,
                           at("setVelocity()") + ": only joint velocities (vpRobot::ARTICULAR_FRAME) are supported");
  }
  if (getRobotState() != vpRobot::STATE_VELOCITY_CONTROL && !isHalted()) {
    throw vpRobotException(vpRobotException::wrongStateError,
                           at("setVelocity()") + ": call setRobotState(vpRobot::STATE_VELOCITY_CONTROL) first");
  }
  const unsigned int n = static_cast<unsigned int>(m_types.size());
  if (qdot.size() != n) {
    fail(vpProjectiveException::dimensionError, at("setVelocity()"),
         "qdot has " + std::to_string(qdot.size()) + " values, the arm " + std::to_string(n) + " joints");
  }
  for (unsigned int i = 0; i < n; ++i) {
    requireFinite(qdot[i], at("setVelocity()"), "qdot");
  }
  const bool zero = qdot.frobeniusNorm() == 0.0;
  const int signal = getSignal();
  if (signal != 0 && !isHalted()) {
    halt(signal == SIGINT ? "SIGINT received (Ctrl-C)" : signal == SIGTERM ? "SIGTERM received" : "a signal received");
  }
  if (isHalted()) {
    stop();
    if (zero) {
      return;
    }
    throw vpProjectiveException(vpProjectiveException::robotMotionError, at("setVelocity()") +
                                                                             ": the arm was stopped: " + m_haltReason +
                                                                             "; no motion is sent any more");
  }
  vpColVector q;
  double t = 0.0;
  getJoints(q, t);
  if (zero) {
    if (m_command.frobeniusNorm() > 0.0) {
      m_restTime = t;
    }
    send(qdot);
    return;
  }
  vpColVector vmax(n);
  for (unsigned int i = 0; i < n; ++i) {
    const double robotMax =
        m_types[i] == vpProjectiveJoint::REVOLUTE ? getMaxRotationVelocity() : getMaxTranslationVelocity();
    vmax[i] = std::min(m_maxVelocity[i], robotMax > 0.0 ? robotMax : m_maxVelocity[i]);
  }
  const vpColVector v = vpRobot::saturateVelocities(qdot, vmax, false);
  for (unsigned int i = 0; i < n && m_qmin.size() == n; ++i) {
    if ((q[i] <= m_qmin[i] && v[i] < 0.0) || (q[i] >= m_qmax[i] && v[i] > 0.0)) {
      const bool revolute = m_types[i] == vpProjectiveJoint::REVOLUTE;
      std::ostringstream os;
      os << "joint " << i << " at " << jointValue(q[i], revolute) << " was commanded beyond its limit "
         << jointValue(v[i] < 0.0 ? m_qmin[i] : m_qmax[i], revolute);
      halt(os.str());
      throw vpProjectiveException(vpProjectiveException::robotMotionError,
                                  at("setVelocity()") + ": the arm was stopped: " + m_haltReason +
                                      "; move it back inside its limits, or check the limits given");
    }
  }
  send(v);
}

void vpProjectiveCellRobot::getJoints(vpColVector &q, double &t)
{
  checkSignal();
  m_arm.getJoints(q, t);
  if (q.size() != m_types.size()) {
    halt("the arm gave " + std::to_string(q.size()) + " joint readings");
    fail(vpProjectiveException::dimensionError, at("getPosition()"),
         "the arm gave " + std::to_string(q.size()) + " readings for " + std::to_string(m_types.size()) +
             " joints: check the adapter's getJoints()");
  }
}

void vpProjectiveCellRobot::getPosition(const vpRobot::vpControlFrameType frame, vpColVector &q)
{
  if (frame != vpRobot::ARTICULAR_FRAME) {
    throw vpRobotException(vpRobotException::wrongStateError,
                           at("getPosition()") + ": only the joints (vpRobot::ARTICULAR_FRAME) are read");
  }
  double t = 0.0;
  getJoints(q, t);
}

void vpProjectiveCellRobot::setPosition(const vpRobot::vpControlFrameType, const vpColVector &)
{
  throw vpRobotException(vpRobotException::wrongStateError,
                         at("setPosition()") + ": the cell's arm moves by joint velocities only (setVelocity())");
}

void vpProjectiveCellRobot::getDisplacement(const vpRobot::vpControlFrameType, vpColVector &)
{
  throw vpRobotException(vpRobotException::wrongStateError, at("getDisplacement()") + ": not available");
}

void vpProjectiveCellRobot::get_eJe(vpMatrix &)
{
  throw vpRobotException(vpRobotException::wrongStateError,
                         at("get_eJe()") + ": not available: the cell's model is projective");
}

void vpProjectiveCellRobot::get_fJe(vpMatrix &)
{
  throw vpRobotException(vpRobotException::wrongStateError,
                         at("get_fJe()") + ": not available: the cell's model is projective");
}
