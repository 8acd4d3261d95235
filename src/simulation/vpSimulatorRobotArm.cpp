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

#include <visp3/projective/vpSimulatorRobotArm.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <thread>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/robot/vpRobotException.h>

#include "core/vpProjectiveErrors.h"
#include "simulation/vpSimulatorArmInternal.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpSimulatorRobotArm");

std::string jointValue(double v, bool revolute)
{
  std::ostringstream os;
  os << (revolute ? vpMath::deg(v) : v) << (revolute ? " deg" : " m");
  return os.str();
}
} // namespace

vpSimulatorRobotArm::vpSimulatorRobotArm(const vpSimulatorArm &arm, const vpColVector &q0)
    : vpRobot(), m_arm(arm), m_q(arm.getNumberOfJoints(), 0.0), m_qdot(arm.getNumberOfJoints(), 0.0),
      m_offset(arm.getNumberOfJoints(), 0.0), m_qLastRead(), m_constantSampling(true), m_samplingTime(0.01),
      m_time(0.0), m_last(std::chrono::steady_clock::now()), m_history(), m_encoderNoise(0.0), m_encoderRand()
{
  nDof = static_cast<int>(arm.getNumberOfJoints());
  if (q0.size() != 0) {
    const vpColVector q = jointVector(q0, "vpSimulatorRobotArm()", "q0");
    for (unsigned int i = 0; i < q.size(); ++i) {
      if (q[i] < m_arm.getJointMin()[i] || q[i] > m_arm.getJointMax()[i]) {
        const bool revolute = m_arm.getJointType(i) == vpProjectiveJoint::REVOLUTE;
        std::ostringstream os;
        os << at("vpSimulatorRobotArm()") << ": joint " << i << " starts at " << jointValue(q[i], revolute)
           << ", outside its limits [" << jointValue(m_arm.getJointMin()[i], revolute) << ", "
           << jointValue(m_arm.getJointMax()[i], revolute) << "]: give joints inside the limits.";
        throw vpRobotException(vpRobotException::positionOutOfRangeError, os.str());
      }
    }
    m_q = q;
  }
  m_qLastRead = m_q;
  remember();
}

void vpSimulatorRobotArm::remember()
{
  // The history a camera model looks back into: 10 s is more than any latency studied; the oldest entry before that
  // horizon is kept as the joints before it.
  if (!m_history.empty() && m_history.back().first == m_time) {
    m_history.back().second = m_q;
  } else {
    m_history.emplace_back(m_time, m_q);
  }
  while (m_history.size() > 2 && m_history[1].first < m_time - 10.0) {
    m_history.pop_front();
  }
}

void vpSimulatorRobotArm::requireJointSpace(vpRobot::vpControlFrameType frame, const char *method) const
{
  if (frame != vpRobot::ARTICULAR_FRAME) {
    throw vpRobotException(vpRobotException::wrongStateError,
                           at(method) + ": only the joint space is supported (vpRobot::ARTICULAR_FRAME, or "
                                        "JOINT_STATE); for a Cartesian law, map it to joint velocities with get_eJe() "
                                        "or get_fJe().");
  }
}

vpColVector vpSimulatorRobotArm::jointVector(const vpColVector &v, const char *method, const char *name) const
{
  const unsigned int n = m_arm.getNumberOfJoints();
  if (v.size() != n) {
    std::ostringstream os;
    os << name << " has " << v.size() << " values, the arm " << n << " joints: give one per joint";
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
  for (unsigned int i = 0; i < n; ++i) {
    requireFinite(v[i], at(method), name);
  }
  return v;
}

vpColVector vpSimulatorRobotArm::maxVelocities() const
{
  const unsigned int n = m_arm.getNumberOfJoints();
  vpColVector vmax(n);
  for (unsigned int i = 0; i < n; ++i) {
    vmax[i] =
        m_arm.getJointType(i) == vpProjectiveJoint::REVOLUTE ? getMaxRotationVelocity() : getMaxTranslationVelocity();
  }
  return vmax;
}

void vpSimulatorRobotArm::advance(double dt)
{
  if (dt > 0.0) {
    if (m_qdot.frobeniusNorm() > 0.0) {
      m_q = m_arm.integrate(m_q, m_qdot, dt);
    }
    m_time += dt;
    remember();
  }
}

void vpSimulatorRobotArm::catchUp()
{
  const std::chrono::steady_clock::time_point now = std::chrono::steady_clock::now();
  if (!m_constantSampling && getRobotState() == vpRobot::STATE_VELOCITY_CONTROL) {
    advance(std::chrono::duration<double>(now - m_last).count());
  }
  m_last = now;
}

vpRobot::vpRobotStateType vpSimulatorRobotArm::setRobotState(const vpRobot::vpRobotStateType newState)
{
  if (newState != vpRobot::STATE_STOP && newState != vpRobot::STATE_VELOCITY_CONTROL &&
      newState != vpRobot::STATE_POSITION_CONTROL) {
    throw vpRobotException(vpRobotException::wrongStateError,
                           at("setRobotState()") + ": the simulated arm has STATE_STOP, STATE_VELOCITY_CONTROL and "
                                                   "STATE_POSITION_CONTROL only.");
  }
  catchUp();
  if (!(newState == vpRobot::STATE_VELOCITY_CONTROL && getRobotState() == vpRobot::STATE_VELOCITY_CONTROL)) {
    m_qdot = 0.0;
  }
  return vpRobot::setRobotState(newState);
}

void vpSimulatorRobotArm::setVelocity(const vpRobot::vpControlFrameType frame, const vpColVector &qdot)
{
  requireJointSpace(frame, "setVelocity()");
  if (getRobotState() != vpRobot::STATE_VELOCITY_CONTROL) {
    throw vpRobotException(vpRobotException::wrongStateError,
                           at("setVelocity()") + ": the robot is not in velocity control: call "
                                                 "setRobotState(vpRobot::STATE_VELOCITY_CONTROL) first.");
  }
  const vpColVector v = jointVector(qdot, "setVelocity()", "qdot");
  catchUp(); // real time: the previous command ran until now
  m_qdot = vpRobot::saturateVelocities(v, maxVelocities(), false);
  if (m_constantSampling) {
    advance(m_samplingTime);
  }
}

void vpSimulatorRobotArm::getVelocity(const vpRobot::vpControlFrameType frame, vpColVector &qdot)
{
  requireJointSpace(frame, "getVelocity()");
  catchUp();
  qdot = m_qdot;
}

vpColVector vpSimulatorRobotArm::getVelocity(const vpRobot::vpControlFrameType frame)
{
  vpColVector qdot;
  getVelocity(frame, qdot);
  return qdot;
}

void vpSimulatorRobotArm::setPosition(const vpRobot::vpControlFrameType frame, const vpColVector &q)
{
  requireJointSpace(frame, "setPosition()");
  const vpColVector target = jointVector(q, "setPosition()", "q") - m_offset;
  const unsigned int n = m_arm.getNumberOfJoints();
  for (unsigned int i = 0; i < n; ++i) {
    if (target[i] < m_arm.getJointMin()[i] || target[i] > m_arm.getJointMax()[i]) {
      const bool revolute = m_arm.getJointType(i) == vpProjectiveJoint::REVOLUTE;
      std::ostringstream os;
      os << at("setPosition()") << ": joint " << i << " target " << jointValue(q[i], revolute)
         << " (encoder reading) is outside its limits [" << jointValue(m_arm.getJointMin()[i] + m_offset[i], revolute)
         << ", " << jointValue(m_arm.getJointMax()[i] + m_offset[i], revolute)
         << "]: give a target inside the limits (getJointMin(), getJointMax()). The arm did not move.";
      throw vpRobotException(vpRobotException::positionOutOfRangeError, os.str());
    }
  }
  if (getRobotState() != vpRobot::STATE_POSITION_CONTROL) {
    setRobotState(vpRobot::STATE_POSITION_CONTROL); // as vpSimulatorViper850
  }
  catchUp();
  // The straight joint-space line, every joint arriving together: the slowest joint at its largest velocity.
  const vpColVector vmax = maxVelocities();
  double duration = 0.0;
  for (unsigned int i = 0; i < n; ++i) {
    if (vmax[i] > 0.0) {
      duration = std::max(duration, std::abs(target[i] - m_q[i]) / vmax[i]);
    }
  }
  if (!m_constantSampling && duration > 0.0) {
    std::this_thread::sleep_for(std::chrono::duration<double>(duration));
  }
  remember();
  m_q = target;
  m_time += duration;
  remember();
  m_last = std::chrono::steady_clock::now();
}

void vpSimulatorRobotArm::getPosition(const vpRobot::vpControlFrameType frame, vpColVector &q)
{
  requireJointSpace(frame, "getPosition()");
  catchUp();
  q = m_q + m_offset;
  if (m_encoderNoise > 0.0) {
    for (unsigned int i = 0; i < q.size(); ++i) {
      q[i] += m_encoderRand();
    }
  }
}

void vpSimulatorRobotArm::getDisplacement(const vpRobot::vpControlFrameType frame, vpColVector &d)
{
  requireJointSpace(frame, "getDisplacement()");
  catchUp();
  d = m_q - m_qLastRead;
  m_qLastRead = m_q;
}

void vpSimulatorRobotArm::get_fJe(vpMatrix &fJe)
{
  catchUp();
  const std::vector<vpSimulatorArm::vpDHRow> &dh = m_arm.getDHTable();
  const unsigned int n = m_arm.getNumberOfJoints();
  // Frame i: the base followed by rows 0 to i-1; joint i turns about (slides along) its z axis.
  std::vector<Eigen::Matrix4d> bMi(n + 1);
  bMi[0].setIdentity();
  for (unsigned int i = 0; i < n; ++i) {
    bMi[i + 1] = bMi[i] * linkTransform(dh[i], m_q[i]);
  }
  const Eigen::Vector3d pe = bMi[n].topRightCorner<3, 1>();
  fJe.resize(6, n, false);
  for (unsigned int i = 0; i < n; ++i) {
    const Eigen::Vector3d z = bMi[i].block<3, 1>(0, 2);
    const Eigen::Vector3d o = bMi[i].topRightCorner<3, 1>();
    const bool revolute = m_arm.getJointType(i) == vpProjectiveJoint::REVOLUTE;
    const Eigen::Vector3d v = revolute ? Eigen::Vector3d(z.cross(pe - o)) : z;
    const Eigen::Vector3d w = revolute ? z : Eigen::Vector3d::Zero();
    for (unsigned int r = 0; r < 3; ++r) {
      fJe[r][i] = v(r);
      fJe[r + 3][i] = w(r);
    }
  }
}

void vpSimulatorRobotArm::get_eJe(vpMatrix &eJe)
{
  vpMatrix fJe;
  get_fJe(fJe);
  const vpHomogeneousMatrix bMe = m_arm.get_wMb().inverse() * m_arm.get_wMe(m_q);
  const vpRotationMatrix eRb = bMe.getRotationMatrix().t();
  const unsigned int n = m_arm.getNumberOfJoints();
  eJe.resize(6, n, false);
  for (unsigned int i = 0; i < n; ++i) {
    for (unsigned int r = 0; r < 3; ++r) {
      double v = 0.0, w = 0.0;
      for (unsigned int c = 0; c < 3; ++c) {
        v += eRb[r][c] * fJe[c][i];
        w += eRb[r][c] * fJe[c + 3][i];
      }
      eJe[r][i] = v;
      eJe[r + 3][i] = w;
    }
  }
}

void vpSimulatorRobotArm::setConstantSamplingTimeMode(bool constant)
{
  catchUp();
  m_constantSampling = constant;
}

void vpSimulatorRobotArm::setSamplingTime(double seconds)
{
  if (!std::isfinite(seconds) || !(seconds > 0.0)) {
    std::ostringstream os;
    os << "the sampling time must be finite and > 0 (seconds), got " << seconds;
    fail(vpProjectiveException::invalidValueError, at("setSamplingTime()"), os.str());
  }
  m_samplingTime = seconds;
}

void vpSimulatorRobotArm::setEncoderOffset(const vpColVector &offset)
{
  m_offset = jointVector(offset, "setEncoderOffset()", "the offset");
}

vpColVector vpSimulatorRobotArm::getJointMin() const
{
  return m_arm.getJointMin() + m_offset;
}

vpColVector vpSimulatorRobotArm::getJointMax() const
{
  return m_arm.getJointMax() + m_offset;
}

void vpSimulatorRobotArm::setJointLimits(const vpColVector &qmin, const vpColVector &qmax)
{
  catchUp();
  const unsigned int n = m_arm.getNumberOfJoints();
  for (unsigned int i = 0; i < n && qmin.size() == n && qmax.size() == n; ++i) {
    if (m_q[i] < qmin[i] || m_q[i] > qmax[i]) {
      std::ostringstream os;
      os << "joint " << i << " is at " << m_q[i] << ", outside the new limits [" << qmin[i] << ", " << qmax[i]
         << "]: move it inside first";
      fail(vpProjectiveException::invalidValueError, at("setJointLimits()"), os.str());
    }
  }
  m_arm.setJointLimits(qmin, qmax);
}

vpColVector vpSimulatorRobotArm::getArmJoints()
{
  catchUp();
  return m_q;
}

vpColVector vpSimulatorRobotArm::getArmJointsAt(double t)
{
  catchUp();
  if (!(t < m_time) || m_history.empty()) {
    return m_q;
  }
  const auto after = std::upper_bound(m_history.begin(), m_history.end(), t,
                                      [](double v, const std::pair<double, vpColVector> &h) { return v < h.first; });
  if (after == m_history.begin()) {
    return m_history.front().second;
  }
  const auto before = after - 1;
  if (after == m_history.end()) {
    return before->second;
  }
  const double s = (t - before->first) / (after->first - before->first);
  return before->second + s * (after->second - before->second);
}

void vpSimulatorRobotArm::wait(double seconds)
{
  if (!std::isfinite(seconds) || seconds < 0.0) {
    std::ostringstream os;
    os << "the time to wait must be finite and >= 0 (seconds), got " << seconds;
    fail(vpProjectiveException::invalidValueError, at("wait()"), os.str());
  }
  catchUp();
  if (!m_constantSampling) {
    std::this_thread::sleep_for(std::chrono::duration<double>(seconds));
    catchUp();
  } else if (getRobotState() == vpRobot::STATE_VELOCITY_CONTROL) {
    advance(seconds);
  } else {
    m_time += seconds;
    remember();
  }
}

void vpSimulatorRobotArm::setEncoderNoise(double sigma, long seed)
{
  if (!std::isfinite(sigma) || sigma < 0.0) {
    std::ostringstream os;
    os << "the encoder noise must be finite and >= 0 (rad or m), got " << sigma;
    fail(vpProjectiveException::invalidValueError, at("setEncoderNoise()"), os.str());
  }
  m_encoderNoise = sigma;
  m_encoderRand.setSigmaMean(sigma, 0.0);
  m_encoderRand.seed(seed);
}
