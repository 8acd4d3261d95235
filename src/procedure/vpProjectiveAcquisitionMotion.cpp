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
  How vpProjectiveAcquisitionProcedure drives the vpRobot: to a joint position (by velocity, by position or by the
  user's motion), checking the arrival, and one joint step by step until a stop reason.
*/

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>

#include "acquisition/vpProjectiveAcquisitionInternal.h"

using namespace vpProjectiveAcquisitionInternal;

namespace
{
void sleepSeconds(double s)
{
  std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

/*!
  A marker that moved, between the images \e prev and \e cur, to where another marker was: its index (and the
  other's in \e other), or -1. The markers' common image motion (their mean displacement, which a swap of two
  markers leaves unchanged) is taken out first; a marker must then be four times nearer another marker's previous
  images than its own.
*/
int orderChange(const std::vector<vpImagePoint> &prevL, const std::vector<vpImagePoint> &prevR,
                const std::vector<vpImagePoint> &l, const std::vector<vpImagePoint> &r, int &other, double &dOwn,
                double &dOther)
{
  const size_t K = l.size();
  std::vector<Eigen::Vector4d> p(K), c(K);
  Eigen::Vector4d mean = Eigen::Vector4d::Zero();
  for (size_t j = 0; j < K; ++j) {
    p[j] << prevL[j].get_u(), prevL[j].get_v(), prevR[j].get_u(), prevR[j].get_v();
    c[j] << l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v();
    mean += (c[j] - p[j]) / static_cast<double>(K);
  }
  for (size_t j = 0; j < K; ++j) {
    const double own = (c[j] - mean - p[j]).norm();
    for (size_t k = 0; k < K; ++k) {
      const double d = (c[j] - mean - p[k]).norm();
      if (k != j && d < 0.25 * own) {
        other = static_cast<int>(k);
        dOwn = own;
        dOther = d;
        return static_cast<int>(j);
      }
    }
  }
  return -1;
}
} // namespace

void vpProjectiveAcquisitionProcedure::stopRobot(vpRobot &robot) const
{
  if (!m_motion && m_control == VELOCITY_CONTROL && !m_types.empty()) {
    robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector(static_cast<unsigned int>(m_types.size()), 0.0));
  }
}

void vpProjectiveAcquisitionProcedure::measureEncoderNoise(vpRobot &robot)
{
  // Readings at rest, spread over 50 ms: a controller that refreshes its readings every few milliseconds shows its
  // noise; their standard deviation per joint sets how close a move can be asked to arrive.
  const unsigned int readings = 10;
  std::vector<vpColVector> q(readings);
  for (unsigned int k = 0; k < readings; ++k) {
    if (k > 0) {
      sleepSeconds(0.005);
    }
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q[k]);
  }
  const unsigned int n = q[0].size();
  vpColVector mean(n, 0.0);
  m_encoderNoise.resize(n, true);
  for (unsigned int k = 0; k < readings; ++k) {
    mean += q[k] / static_cast<double>(readings);
  }
  double largest = 0.0;
  for (unsigned int i = 0; i < n; ++i) {
    double sum = 0.0;
    for (unsigned int k = 0; k < readings; ++k) {
      sum += (q[k][i] - mean[i]) * (q[k][i] - mean[i]);
    }
    m_encoderNoise[i] = std::sqrt(sum / (readings - 1));
    largest = std::max(largest, m_encoderNoise[i]);
  }
  m_tolerance = std::max(m_minTolerance, 4.0 * largest);
  std::ostringstream os;
  os << "encoder noise at rest: " << largest << " (rad or m, the largest standard deviation of 10 readings); arrival "
     << "tolerance " << m_tolerance
     << (m_tolerance > m_minTolerance ? " (4 times the noise)" : " (setArrivalTolerance())");
  progress(os.str());
}

void vpProjectiveAcquisitionProcedure::checkArrival(vpRobot &robot, const vpColVector &q, double tolerance,
                                                    const char *how) const
{
  vpColVector reading;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, reading);
  for (unsigned int k = 0; k < q.size(); ++k) {
    const double allowed = std::max(tolerance, 0.1 * stepOf(k));
    if (reading.size() != q.size() || !(std::abs(reading[k] - q[k]) <= allowed)) {
      std::ostringstream os;
      os << at("run") << ": joint " << k << " did not arrive: commanded " << valueText(q[k], k) << ", read "
         << (reading.size() == q.size() ? valueText(reading[k], k) : std::string("nothing")) << " after " << how
         << " (allowed " << valueText(allowed, k)
         << "): check the robot (joint limit, state, controller), or use setMotionControl(VELOCITY_CONTROL).";
      throw vpProjectiveException(vpProjectiveException::robotMotionError, os.str());
    }
  }
}

void vpProjectiveAcquisitionProcedure::moveByVelocity(vpRobot &robot, const vpColVector &target, double tolerance)
{
  const unsigned int n = target.size();
  vpColVector q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  std::vector<double> vmax(n);
  double travel = 0.0;
  for (unsigned int k = 0; k < n; ++k) {
    vmax[k] = byType(k, robot.getMaxRotationVelocity(), robot.getMaxTranslationVelocity(),
                     std::min(robot.getMaxRotationVelocity(), robot.getMaxTranslationVelocity()));
    if (!(vmax[k] > 0.0)) {
      throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                  at("run") + ": the robot's largest joint velocity is not positive: give one "
                                              "(setSpeed(), or vpRobot::setMaxRotationVelocity()).");
    }
    travel = std::max(travel, std::abs(target[k] - q[k]) / vmax[k]);
  }
  const double timeout = m_moveTimeout > 0.0 ? m_moveTimeout : 2.0 + 4.0 * travel;
  const double t0 = seconds();
  vpColVector v(n, 0.0);
  auto fail = [&](const char *what) {
    stopRobot(robot);
    unsigned int worst = 0;
    for (unsigned int k = 1; k < n; ++k) {
      if (std::abs(target[k] - q[k]) * vmax[worst] > std::abs(target[worst] - q[worst]) * vmax[k]) {
        worst = k;
      }
    }
    std::ostringstream os;
    os << at("run") << ": joint " << worst << " did not arrive within " << timeout << " s (" << what << "): commanded "
       << valueText(target[worst], worst) << ", read " << valueText(q[worst], worst) << ", velocity " << v[worst]
       << (!m_typesKnown                                   ? " (rad or m)/s"
           : m_types[worst] == vpProjectiveJoint::REVOLUTE ? " rad/s"
                                                           : " m/s")
       << "; the robot was stopped. Check that setVelocity(ARTICULAR_FRAME) moves this joint (robot state, joint "
          "limit, emergency stop), or raise setMoveTimeout(), or use setMotionControl(POSITION_CONTROL).";
    throw vpProjectiveException(vpProjectiveException::robotMotionError, os.str());
  };
  for (;;) {
    bool arrived = true;
    for (unsigned int k = 0; k < n; ++k) {
      arrived = arrived && std::abs(target[k] - q[k]) <= tolerance;
    }
    if (arrived) {
      // Stop, then read again once a command period has passed: the joint must stay within the tolerance.
      v = 0.0;
      robot.setVelocity(vpRobot::ARTICULAR_FRAME, v);
      sleepSeconds(std::min(0.1, std::max(0.001, 1.5 * m_wallPeriod)));
      robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
      bool still = true;
      for (unsigned int k = 0; k < n; ++k) {
        still = still && std::abs(target[k] - q[k]) <= tolerance;
      }
      if (still) {
        return;
      }
      if (seconds() - t0 > timeout) {
        fail("it moved off the target after the stop");
      }
      continue;
    }
    const double dt = m_commandPeriod > 0.0 ? m_commandPeriod : 0.05;
    unsigned int fastest = 0;
    for (unsigned int k = 0; k < n; ++k) {
      const double e = target[k] - q[k];
      v[k] = std::abs(e) <= tolerance ? 0.0 : std::max(-vmax[k], std::min(vmax[k], e / dt));
      if (std::abs(v[k]) * vmax[fastest] > std::abs(v[fastest]) * vmax[k]) {
        fastest = k;
      }
    }
    robot.setVelocity(vpRobot::ARTICULAR_FRAME, v);
    // Wait for the reading to change: one command period of a real-time controller, or the one step a simulator
    // in its constant sampling time mode makes per command. No change within 0.1 s: command again.
    const double tc = seconds();
    vpColVector next = q;
    bool changed = false;
    while (!changed && seconds() - tc < 0.1) {
      sleepSeconds(0.0002);
      robot.getPosition(vpRobot::ARTICULAR_FRAME, next);
      for (unsigned int k = 0; k < n && !changed; ++k) {
        changed = next[k] != q[k];
      }
      if (seconds() - t0 > timeout) {
        fail("the joint readings did not reach the target");
      }
    }
    if (changed) {
      m_wallPeriod = seconds() - tc;
    }
    if (changed && v[fastest] != 0.0) {
      const double observed = (next[fastest] - q[fastest]) / v[fastest];
      if (observed > 1e-4 && observed < 0.5 && std::abs(next[fastest] - q[fastest]) > 1e-9) {
        m_commandPeriod = observed;
      }
    }
    q = next;
    if (seconds() - t0 > timeout) {
      fail("the joint readings did not reach the target");
    }
  }
}

void vpProjectiveAcquisitionProcedure::moveTo(vpRobot &robot, const vpColVector &q, double tolerance, bool check)
{
  if (m_motion) {
    m_motion(robot, q);
    if (check) {
      checkArrival(robot, q, tolerance, "the motion of setMotion()");
    }
  } else if (m_control == POSITION_CONTROL) {
    robot.setPosition(vpRobot::ARTICULAR_FRAME, q);
    if (check) {
      checkArrival(robot, q, tolerance, "setPosition()");
    }
  } else {
    moveByVelocity(robot, q, tolerance);
  }
}

void vpProjectiveAcquisitionProcedure::moveJoint(vpRobot &robot, const vpColVector &qRef, unsigned int i, int sign,
                                                 double &amount, vpStopReason &reason, vpColVector &qReached,
                                                 std::vector<int> &ids, std::vector<vpImagePoint> &left,
                                                 std::vector<vpImagePoint> &right, std::vector<vpImagePoint> &allLeft,
                                                 std::vector<vpImagePoint> &allRight)
{
  const double maxAmount = amountOf(m_maxAmounts, i, byType(i, vpMath::rad(30.0), 0.1, 0.35));
  const double step = stepOf(i);
  amount = 0.0;
  reason = AMOUNT_REACHED;
  std::vector<int> lid;
  std::vector<vpImagePoint> l, r, prevL = left, prevR = right;
  while (amount < maxAmount) {
    const double next = std::min(maxAmount, amount + step);
    vpColVector q = qRef;
    q[i] = qRef[i] + sign * next;
    if (m_lower.size() != 0 && (q[i] < m_lower[i] || q[i] > m_upper[i])) {
      reason = JOINT_LIMIT;
      break;
    }
    // A position controller may stop short of a step where a marker is lost (a motion tracked frame by frame): the
    // lost marker stops the joint; a step that is used must have arrived.
    moveTo(robot, q, std::max(m_tolerance, 0.05 * step), false);
    vpColVector reading;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, reading);
    // Identified markers: those of the zero reference only; fewer than 5 of them is a lost step.
    if (!acquire(lid, l, r) || (m_identified && keepMarkers(m_refIds, lid, l, r) < 5)) {
      reason = MARKER_LOST;
      break;
    }
    if (m_motion || m_control == POSITION_CONTROL) {
      checkArrival(robot, q, std::max(m_tolerance, 0.05 * step),
                   m_motion ? "the motion of setMotion()" : "setPosition()");
    }
    if (m_callback) {
      m_callback(i, q, l, r);
    }
    if (!m_identified && (l.size() != prevL.size() || r.size() != prevR.size())) {
      std::ostringstream os;
      os << at("run") << ": the image source gave " << l.size() << " left and " << r.size()
         << " right marker images at step " << valueText(sign * next, i) << " of joint " << i << ", " << prevL.size()
         << " at the zero reference: give every marker, in the same order, or return false when "
         << "one is lost.";
      throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
    }
    int other = -1;
    double dOwn = 0.0, dOther = 0.0;
    const int jumped = m_identified ? -1 : orderChange(prevL, prevR, l, r, other, dOwn, dOther);
    if (jumped >= 0) {
      std::ostringstream os;
      os << at("run") << ": marker " << jumped << " jumped, at step " << valueText(sign * next, i) << " of joint " << i
         << ", to where marker " << other << " was (" << dOther << " px from it, " << dOwn
         << " px from its own previous images, the markers' common motion taken out): the image source changed the "
            "markers' order. Return the markers in "
            "the same order in every frame (track each one, or identify it: tag ids), then run again.";
      throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
    }
    prevL = l;
    prevR = r;
    if (!inside(l, r)) {
      reason = IMAGE_BORDER;
      break;
    }
    amount = next;
    qReached = reading;
    ids = lid;
    left = l;
    right = r;
    allLeft.insert(allLeft.end(), l.begin(), l.end());
    allRight.insert(allRight.end(), r.begin(), r.end());
  }
}
