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
  \file vpProjectiveCellServo.cpp
  \brief The planned servo of the real-cell program: features aligned to the joint readings' time, the task's period
  from the loop's own, and every way it ends with the arm stopped.
*/

#include <visp3/projective/vpProjectiveCell.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpServoProjective.h>

#include "cell/vpProjectiveCellInternal.h"

using namespace vpProjectiveInternal;
using vpProjectiveCellInternal::at;

namespace
{
//! \e ip moved by the rows \e r, \e r + 1 of \e J times \e dq (a first-order prediction of its motion).
vpImagePoint moved(const vpImagePoint &ip, const vpMatrix &J, unsigned int r, const vpColVector &dq)
{
  double du = 0.0, dv = 0.0;
  for (unsigned int k = 0; k < dq.size(); ++k) {
    du += J[r][k] * dq[k];
    dv += J[r + 1][k] * dq[k];
  }
  return vpImagePoint(ip.get_v() + dv, ip.get_u() + du);
}
} // namespace

vpProjectiveCell::vpServoResult vpProjectiveCell::servo()
{
  vpStopGuard guard(*m_robot);
  if (!m_model.isCalibrated()) {
    fail(vpProjectiveException::notInitializedError, at("servo()"), "no model: call acquire() or loadModel() first");
  }
  if (m_targetIds.empty()) {
    fail(vpProjectiveException::notInitializedError, at("servo()"), "no s*: call teach() or teachHere() first");
  }
  const unsigned int N = static_cast<unsigned int>(m_targetIds.size());
  std::vector<vpFeatureStereoPoint> s(N), sStar(N);
  vpServoProjective task;
  task.setRobot(m_model);
  task.setLambda(m_settings.gain);
  task.setControlPeriod(m_settings.period);
  const bool anyRevolute = std::find(m_types.begin(), m_types.end(), vpProjectiveJoint::REVOLUTE) != m_types.end();
  task.getControlLaw().setMaxJointVelocity(anyRevolute ? m_settings.maxRotationSpeed : m_settings.maxTranslationSpeed);
  if (m_lower.size() != 0) {
    task.setJointLimits(m_lower, m_upper);
  }
  task.setImageSize(m_cameras.getWidth(), m_cameras.getHeight(), m_settings.imageBorder);
  task.setPathPlanning(m_settings.planning);
  task.setSettling(true);
  task.getPathPlanner().setMaxOpenLoopTime(
      m_settings.maxLostTime);                      // blind along the plan no longer than the arm may go without tags
  std::map<int, std::vector<unsigned int>> corners; // of each tag: a planar group, kept facing the cameras
  for (unsigned int k = 0; k < N; ++k) {
    sStar[k].buildFrom(m_targetLeft[k], m_targetRight[k]);
    task.addFeature(s[k], sStar[k]);
    corners[m_targetIds[k] / 4].push_back(k);
  }
  std::vector<std::vector<unsigned int>> groups;
  for (const auto &tag : corners) {
    if (tag.second.size() == 4) {
      groups.push_back(tag.second);
    }
  }
  task.getPathPlanner().setPlanarGroups(groups);

  m_robot->setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  m_history.clear();
  const vpProjectiveStereoRig &rig = m_model.getStereoRig();
  vpServoResult result;
  result.end = SERVO_TIMEOUT;
  result.error = std::numeric_limits<double>::quiet_NaN();
  double t0 = 0.0, tPrev = 0.0, period = m_settings.period, lostSince = -1.0, shown = -1.0;
  unsigned int converged = 0;
  std::string timing; // the last timing limit a frame passed
  vpColVector q;
  double t = 0.0;
  for (result.frames = 1;; ++result.frames) {
    vpFrame frame;
    grab(false, frame);
    m_robot->getJoints(q, t);
    remember(t, q);
    if (result.frames == 1) {
      t0 = t;
    } else if (t > tPrev) { // the loop's own period, smoothed, for what the task does per call
      const double estimate = 0.7 * period + 0.3 * (t - tPrev);
      if (std::abs(estimate - task.getControlLaw().getControlPeriod()) >
          0.2 * task.getControlLaw().getControlPeriod()) {
        task.setControlPeriod(estimate);
      }
      period = estimate;
    }
    const double tPrevious = tPrev;
    tPrev = t;
    // Recorded with the readings of when the images were taken (the left one's; between the two, a skewed right
    // image shows the arm where it was then): check and calibrate pair each image with its joints.
    record(vpProjectiveSession::SERVO, frame.stamped ? jointsAt(frame.tLeft) : q, frame.stamped ? frame.tLeft : t);
    // The features at the readings' time: each image's pixels moved by the model's motion since it was taken.
    // A frame beyond the timing limits is not used: its features count as lost (the arm stops if that lasts).
    std::ostringstream late;
    if (frame.stamped && std::abs(frame.tRight - frame.tLeft) > m_settings.maxSkew) {
      late << "the right image taken " << 1000.0 * (frame.tRight - frame.tLeft) << " ms after the left (limit "
           << 1000.0 * m_settings.maxSkew << " ms, maxSkew)";
    } else if (frame.stamped && t - std::min(frame.tLeft, frame.tRight) > m_settings.maxLatency) {
      late << "images " << 1000.0 * (t - std::min(frame.tLeft, frame.tRight)) << " ms older than the readings (limit "
           << 1000.0 * m_settings.maxLatency << " ms, maxLatency)";
    } else if (result.frames > 1 && t - tPrevious > 1.0 / m_settings.minFrameRate) {
      late << "a frame " << 1000.0 * (t - tPrevious) << " ms after the last (limit " << 1000.0 / m_settings.minFrameRate
           << " ms, minFrameRate)";
    }
    if (!late.str().empty()) {
      timing = late.str();
      frame.ids.clear();
    } else if (!frame.ids.empty()) {
      timing.clear();
    }
    const bool align = m_settings.latencyCompensation && frame.stamped;
    const vpColVector dLeft = align ? vpColVector(q - jointsAt(frame.tLeft)) : vpColVector(q.size(), 0.0);
    const vpColVector dRight = align ? vpColVector(q - jointsAt(frame.tRight)) : vpColVector(q.size(), 0.0);
    const bool moving = dLeft.frobeniusNorm() > 0.0 || dRight.frobeniusNorm() > 0.0;
    double sum = 0.0;
    unsigned int seen = 0;
    for (unsigned int k = 0; k < N; ++k) {
      const auto it = std::find(frame.ids.begin(), frame.ids.end(), m_targetIds[k]);
      const bool found = it != frame.ids.end();
      if (found) {
        const size_t j = static_cast<size_t>(it - frame.ids.begin());
        vpImagePoint ipLeft = frame.left[j], ipRight = frame.right[j];
        if (moving) {
          const vpMatrix J = m_model.getImageJacobian(q, rig.triangulate(ipLeft, ipRight));
          ipLeft = moved(ipLeft, J, 0, dLeft);
          ipRight = moved(ipRight, J, 2, dRight);
        }
        s[k].buildFrom(ipLeft, ipRight);
        sum += s[k].error(sStar[k]).sumSquare();
        ++seen;
      }
      task.setFeatureTracked(k, found);
    }
    result.error = seen > 0 ? std::sqrt(sum / (4.0 * seen)) : std::numeric_limits<double>::quiet_NaN();
    const vpColVector qdot = task.computeControlLaw(q);
    const vpServoProjective::vpServoStatus status = task.getStatus();
    std::ostringstream why;
    if (status == vpServoProjective::SERVO_MODEL_MISMATCH || status == vpServoProjective::SERVO_NO_PLAN ||
        status == vpServoProjective::SERVO_ARM_NOT_FOLLOWING) {
      result.end = SERVO_STATUS;
      why << "the task stopped: " << vpServoProjectiveReport::toString(status);
      if (status == vpServoProjective::SERVO_MODEL_MISMATCH && task.getModelMismatch().isImagesExchanged()) {
        why << "; the left and right images are exchanged: the stereo image source gives the model's left camera "
               "as its right one (check the order of the cameras given to it)";
      } else if (status == vpServoProjective::SERVO_MODEL_MISMATCH) {
        why << "; run visp-projective check on the recorded session: if a camera moved, re-register the rig or "
               "acquire again";
      } else if (status == vpServoProjective::SERVO_NO_PLAN) {
        why << "; teach a target reachable within the joint limits, the tags in view";
      } else { // the task's qdot stays 0 until its check is reset: the cell stops rather than wait
        why << "; " << task.getArmFollowing().getDiagnosis();
      }
      if (!timing.empty()) { // no frame used: the cause is the cameras', not the target's
        why << "; no frame was used: the cameras' timing is out of the limits, " << timing;
      }
    }
    const bool lost = status == vpServoProjective::SERVO_STOPPED || status == vpServoProjective::SERVO_OPEN_LOOP;
    lostSince = lost ? (lostSince < 0.0 ? t : lostSince) : -1.0;
    if (lostSince >= 0.0 && t - lostSince > m_settings.maxLostTime) {
      result.end = SERVO_TAGS_LOST;
      why << "too few of the " << N << " corners of s* seen (" << seen << " now) for " << t - lostSince << " s: "
          << (timing.empty() ? "bring the tags back in view (occlusion, lighting, the tags out of the images)"
                             : "the cameras' timing is out of the limits, " + timing);
    }
    converged = seen == N && result.error < m_settings.convergedError ? converged + 1 : 0;
    if (converged >= m_settings.convergedFrames) {
      result.end = SERVO_CONVERGED;
      why << "converged: image error " << result.error << " px RMS";
    } else if (why.str().empty() && t - t0 > m_settings.timeout) {
      why << "no convergence within " << m_settings.timeout << " s (image error " << result.error
          << " px RMS): check the status lines, raise the gain or the timeout";
    }
    if (!why.str().empty()) {
      result.message = why.str();
      break;
    }
    m_robot->setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
    if (shown < 0.0 || t - shown >= 1.0) {
      std::ostringstream os;
      os << "servo " << t - t0 << " s: image error " << result.error << " px RMS, " << seen << "/" << N << " corners, "
         << vpServoProjectiveReport::toString(status).substr(0, vpServoProjectiveReport::toString(status).find(' '));
      progress(os.str());
      shown = t;
    }
  }
  m_robot->stop();
  result.seconds = t - t0;
  result.q = q;
  progress(result.message);
  if (m_writer) {
    m_writer->close();
  }
  return result;
}
