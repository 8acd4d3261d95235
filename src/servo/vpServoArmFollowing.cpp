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

#include <visp3/projective/vpServoArmFollowing.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpServoArmFollowing");

//! Image motion (pixels RMS) below which a motion is not judged: well above what encoders resolve (1e-5 rad moves a
//! feature 1 m away by 0.01 px), well below a control step.
const double kMinMotion = 0.1;
//! A joint follows when it makes between kSlower and kFaster times its expected motion; below kStill it is still.
const double kSlower = 0.5, kFaster = 2.0, kStill = 0.1;
//! The arm does not move when its image motion is below this fraction of the command's (a robot clipped 10 times
//! below the task still moves).
const double kNotMoving = 0.03;
//! Image motion (pixels RMS) below which the arm's motion may be the encoders' noise alone (1e-5 rad: about 0.01 px).
const double kNoise = 0.025;
//! Two consecutive calls are regular when their durations differ by at most this fraction.
const double kRegular = 0.2;
//! Without a reference duration: the arm does not move when it stayed within kMinMotion of where it was (above the
//! encoders' noise) over kStillCalls commanding calls whose commands would have moved the images by kStillMotion
//! pixels, ten times more, even if each lasted kShortestCall seconds: the task is called once per image pair, and a
//! fast camera gives 200 pairs per second (a robot starts within the 0.2 s of 40 such calls).
const unsigned int kStillCalls = 40;
const double kStillMotion = 1.0, kShortestCall = 0.005;

/*!
  What joint i did: its measured motion \e d against scale c, \e c its command (per second), \e s the image motion of
  one joint unit. It is judged when it moved measurably or its command would have over \e reach seconds (the
  reference; 0 without one: the measured motion only), not over the time scale, which noise sets when the command
  hardly moves the images.
*/
vpServoArmFollowing::vpJointFollowing jointFollowing(double d, double c, double scale, double reach, double s,
                                                     double &ratio)
{
  ratio = 0.0;
  if (!(s * std::max(std::abs(reach * c), std::abs(d)) >= kMinMotion)) {
    return vpServoArmFollowing::JOINT_NOT_JUDGED;
  }
  if (!(scale > 0.0) || s * std::abs(scale * c) < 0.5 * kMinMotion) {
    // Hardly commanded at the arm's time scale: a fault only if it moved measurably (without a command, or the other
    // way when no joint moves along the command).
    if (!(s * std::abs(d) >= kMinMotion)) {
      return vpServoArmFollowing::JOINT_NOT_JUDGED;
    }
    return scale > 0.0 || d * c >= 0.0 ? vpServoArmFollowing::JOINT_UNCOMMANDED : vpServoArmFollowing::JOINT_REVERSED;
  }
  ratio = d / (scale * c);
  if (ratio <= -kStill) {
    return vpServoArmFollowing::JOINT_REVERSED;
  }
  if (ratio < kStill) {
    return vpServoArmFollowing::JOINT_STILL;
  }
  if (ratio < kSlower) {
    return vpServoArmFollowing::JOINT_SLOWER;
  }
  return ratio > kFaster ? vpServoArmFollowing::JOINT_FASTER : vpServoArmFollowing::JOINT_FOLLOWS;
}

//! Every joint's state against the time scale \e scale (seconds), judged over \e reach (jointFollowing()). Returns
//! the number of joints that follow.
unsigned int classifyJoints(const vpServoArmFollowing::JointVector &d, const vpServoArmFollowing::JointVector &c,
                            const vpServoArmFollowing::JointMatrix &G, double scale, double reach,
                            vpServoArmFollowing::vpJointFollowing *states, double *ratios)
{
  unsigned int follows = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    states[i] = jointFollowing(d(i), c(i), scale, reach, std::sqrt(std::max(0.0, G(i, i))), ratios[i]);
    follows += states[i] == vpServoArmFollowing::JOINT_FOLLOWS ? 1 : 0;
  }
  return follows;
}

/*!
  The joints' states for the command \e c as the arm received it (per second), against the others' time scale, the
  median of d_i / c_i over the joints judged (jointFollowing(): over \e reference, the measured motion only without
  one), written to \e duration (without such a joint, the least-squares scale of d on c in the metric G), and, when it
  is below half of \e reference, against the reference: the comparison where more joints follow. Returns the number
  of joints that follow.
*/
unsigned int judgeJoints(const vpServoArmFollowing::JointVector &d, const vpServoArmFollowing::JointVector &c,
                         const vpServoArmFollowing::JointMatrix &G, double reference,
                         vpServoArmFollowing::vpJointFollowing *states, double *ratios, double &duration)
{
  double timeScales[vpProjectiveArmModel::maxJoints];
  unsigned int commanded = 0;
  for (Eigen::Index i = 0; i < d.size(); ++i) {
    const double s = std::sqrt(std::max(0.0, G(i, i)));
    if (c(i) != 0.0 && s * std::max(std::abs(reference * c(i)), std::abs(d(i))) >= kMinMotion) {
      timeScales[commanded++] = d(i) / c(i);
    }
  }
  if (commanded > 0) {
    std::nth_element(timeScales, timeScales + commanded / 2, timeScales + commanded);
    duration = timeScales[commanded / 2];
  } else { // no joint measurable on its own (their motions may still add up): the least-squares scale
    const vpServoArmFollowing::JointVector Gc = G * c;
    const double cc = c.dot(Gc);
    duration = cc > 0.0 ? d.dot(Gc) / cc : 0.0;
  }
  const double scale = duration > 0.0 ? duration : reference;
  unsigned int follows = classifyJoints(d, c, G, scale, reference, states, ratios);
  if (reference > 0.0 && scale != reference && duration < kSlower * reference) {
    vpServoArmFollowing::vpJointFollowing other[vpProjectiveArmModel::maxJoints];
    double otherRatios[vpProjectiveArmModel::maxJoints];
    const unsigned int otherFollows = classifyJoints(d, c, G, reference, reference, other, otherRatios);
    if (otherFollows > follows) {
      std::copy(other, other + d.size(), states);
      std::copy(otherRatios, otherRatios + d.size(), ratios);
      follows = otherFollows;
    }
  }
  return follows;
}
} // namespace

vpServoArmFollowing::vpServoArmFollowing()
    : m_enabled(true), m_calls(3), m_period(0.0), m_hasPrevious(false), m_qPrevious(), m_qdot1(), m_qdot2(),
      m_pending(), m_last(), m_detection(), m_disagreeing(0), m_notFollowing(false), m_durations(), m_nbDurations(0),
      m_nextDuration(0), m_lastDuration(0.0), m_qStill(), m_stillCalls(0), m_stillCommand(0.0)
{
}

void vpServoArmFollowing::setEnabled(bool enabled)
{
  m_enabled = enabled;
  if (!enabled) {
    reset();
  }
}

void vpServoArmFollowing::setConsecutiveCalls(unsigned int calls)
{
  m_calls = atLeastOne(calls, at("setConsecutiveCalls()"),
                       "the arm must disagree on at least one call to stop the task; pass 1 or more (default 3)");
}

void vpServoArmFollowing::setControlPeriod(double seconds)
{
  m_period = nonNegative(seconds, at("setControlPeriod()"), "the control period",
                         "seconds between two calls; 0 learns it from the arm's motion");
}

void vpServoArmFollowing::reset()
{
  m_hasPrevious = false;
  m_pending = m_last = m_detection = vpVerdict();
  m_disagreeing = 0;
  m_notFollowing = false;
  m_nbDurations = m_nextDuration = 0;
  m_lastDuration = 0.0;
  m_stillCalls = 0;
  m_stillCommand = 0.0;
}

double vpServoArmFollowing::learnedDuration() const
{
  if (m_nbDurations == 0) {
    return 0.0;
  }
  // The shortest of the regular calls kept: a low reference makes the check less sensitive, never too sensitive.
  return *std::min_element(m_durations, m_durations + m_nbDurations);
}

double vpServoArmFollowing::getReferenceDuration() const
{
  return m_period > 0.0 ? m_period : learnedDuration();
}

bool vpServoArmFollowing::evaluate(const JointVector &q, const JointMatrix &JtJ, unsigned int rows)
{
  vpVerdict &v = m_pending;
  v = vpVerdict();
  if (!m_enabled || m_notFollowing) {
    return m_enabled && m_notFollowing;
  }
  const Eigen::Index n = q.size();
  if (!m_hasPrevious || m_qPrevious.size() != n || JtJ.rows() != n || rows == 0) {
    return false;
  }
  // The latency's mix: d = q_k - q_{k-1} against a qdot_{k-1} + b qdot_{k-2}, a, b >= 0, least squares in the metric
  // G = J^T J / m (pixels).
  const JointMatrix G = JtJ / static_cast<double>(rows);
  const JointVector d = q - m_qPrevious;
  const JointVector GA = G * m_qdot1, GB = G * m_qdot2;
  const double aa = m_qdot1.dot(GA), bb = m_qdot2.dot(GB), ab = m_qdot1.dot(GB);
  const double ad = d.dot(GA), bd = d.dot(GB);
  if (!(aa > 0.0)) {
    return false; // nothing commanded at the last call: nothing to judge
  }
  double a = std::max(0.0, ad / aa), b = 0.0, gain = a * ad; // the last command alone; gain: |d|^2 - residual
  if (bb > 0.0 && bd > 0.0 && bd * bd / bb > gain) {
    a = 0.0, b = bd / bb, gain = bd * bd / bb; // the one before alone (one call of latency)
  }
  const double det = aa * bb - ab * ab;
  if (det > 1e-12 * aa * bb) {
    const double a2 = (ad * bb - bd * ab) / det, b2 = (bd * aa - ad * ab) / det;
    if (a2 >= 0.0 && b2 >= 0.0 && a2 * ad + b2 * bd > gain) {
      a = a2, b = b2; // a mix of both
    }
  }
  // The command as the arm received it, c = alpha qdot_{k-1} + (1 - alpha) qdot_{k-2}: the least-squares mix, no
  // latency or one call of it, whichever most joints follow (a joint held at a limit can bend the least-squares mix
  // where it dominates the images' motion).
  v.joints = static_cast<unsigned int>(n);
  v.reference = getReferenceDuration();
  const double mixes[3] = {a + b > 0.0 ? a / (a + b) : 1.0, 1.0, 0.0};
  double commandNorm = 0.0;
  int best = -1;
  for (int k = 0; k < (bb > 0.0 ? 3 : 2); ++k) {
    if (k > 0 && mixes[k] == mixes[0]) {
      continue;
    }
    const JointVector c = mixes[k] * m_qdot1 + (1.0 - mixes[k]) * m_qdot2;
    const double norm = std::sqrt(std::max(0.0, c.dot(G * c)));
    vpJointFollowing states[vpProjectiveArmModel::maxJoints];
    double jointRatios[vpProjectiveArmModel::maxJoints], duration = 0.0;
    const int follows = static_cast<int>(judgeJoints(d, c, G, v.reference, states, jointRatios, duration));
    if (norm > 0.0 && follows > best) {
      best = follows;
      commandNorm = norm;
      v.duration = duration;
      std::copy(states, states + n, v.states);
      std::copy(jointRatios, jointRatios + n, v.ratios);
    }
  }
  bool shapeFails = false, anyJudged = false, anyFollows = false, onlyLagging = true;
  for (Eigen::Index i = 0; i < n; ++i) {
    const vpJointFollowing state = v.states[i];
    anyJudged = anyJudged || state != JOINT_NOT_JUDGED;
    anyFollows = anyFollows || state == JOINT_FOLLOWS;
    if (state != JOINT_NOT_JUDGED && state != JOINT_FOLLOWS) {
      shapeFails = true;
      onlyLagging = onlyLagging && (state == JOINT_STILL || state == JOINT_SLOWER);
    }
  }
  // The scale: an arm that does not move (its image motion below 3 % of the command's over the reference, or within
  // the encoders' noise while the command's is at least twice as large), one
  // that moves less than half as far as commanded over the period given (a learned period follows the loop's own
  // timing, which a loaded computer stretches: only an arm at rest is judged against it).
  bool notMoving = false, slower = false;
  if (v.reference > 0.0) {
    v.commanded = v.reference * commandNorm;
    v.ratio = v.duration / v.reference;
    const double measured = std::sqrt(std::max(0.0, d.dot(G * d)));
    notMoving = v.commanded >= kMinMotion &&
                (measured < kNotMoving * v.commanded || (measured < kNoise && measured < kSlower * v.commanded));
    slower = m_period > 0.0 && v.commanded >= kMinMotion && v.ratio < kSlower;
  }
  // Without a reference: the arm still since m_qStill over enough commanding calls (evaluated only while it has been).
  if (!(v.reference > 0.0)) {
    const JointVector moved = m_qStill.size() == n ? JointVector(q - m_qStill) : d;
    if (std::sqrt(std::max(0.0, moved.dot(G * moved))) < kMinMotion) {
      v.stillCalls = m_stillCalls + 1;
      v.stillCommand = m_stillCommand + commandNorm;
      if (v.stillCalls >= kStillCalls && kShortestCall * v.stillCommand >= kStillMotion) {
        notMoving = true;
        anyJudged = true;
      }
    }
  }
  v.judged = anyJudged || v.commanded >= kMinMotion;
  v.disagrees = notMoving || shapeFails || slower;
  if (notMoving) {
    v.cause = ARM_NOT_MOVING;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double expected = v.reference * std::abs(m_qdot1(i));
      const bool seen = v.reference > 0.0 ? std::sqrt(std::max(0.0, G(i, i))) * expected >= kMinMotion
                                          : m_qdot1(i) != 0.0; // still over the streak, whatever the period
      v.states[i] = seen ? JOINT_STILL : JOINT_NOT_JUDGED;
      v.ratios[i] = seen && v.reference > 0.0 ? d(i) / (v.reference * m_qdot1(i)) : 0.0;
    }
  } else if (shapeFails) {
    v.cause = onlyLagging && anyFollows ? ARM_JOINTS_LAGGING : ARM_OTHER_DIRECTION;
  } else if (slower) {
    v.cause = ARM_SLOWER;
  }
  v.learnable = v.judged && !v.disagrees && v.duration > 0.0 && v.duration * commandNorm >= kMinMotion;
  return v.disagrees && m_disagreeing + 1 >= m_calls;
}

void vpServoArmFollowing::commit(const JointVector &q, const JointVector &qdot)
{
  if (!m_enabled) {
    return;
  }
  const vpVerdict &v = m_pending;
  if (!m_notFollowing && v.judged) {
    m_last = v;
    m_disagreeing = v.disagrees ? m_disagreeing + 1 : 0;
    if (m_disagreeing >= m_calls) {
      m_notFollowing = true;
      m_detection = v;
    }
    // A call lasts as the one before it (within 20 %): the calls are regular, and their duration the loop's period.
    // A pause (the robot holding the command while the program is busy) lasts longer than the calls around it.
    if (v.learnable && std::abs(v.duration - m_lastDuration) <= kRegular * m_lastDuration) {
      m_durations[m_nextDuration] = v.duration;
      m_nextDuration = (m_nextDuration + 1) % kLearned;
      const unsigned int learned = kLearned; // a value: std::min() would bind the undefined static member
      m_nbDurations = std::min(m_nbDurations + 1, learned);
    }
    m_lastDuration = v.learnable ? v.duration : 0.0;
  } else if (!m_notFollowing) {
    m_disagreeing = 0; // nothing to judge: only consecutive disagreements stop the task
    m_lastDuration = 0.0;
  }
  // The still streak goes on only through calls where evaluate() found the arm still (a call that commanded nothing
  // or moved the arm starts a new one here).
  m_stillCalls = m_notFollowing ? m_stillCalls : v.stillCalls;
  m_stillCommand = m_notFollowing ? m_stillCommand : v.stillCommand;
  if (m_stillCalls == 0) {
    m_qStill = q;
  }
  m_qdot2 = m_hasPrevious && m_qdot1.size() == q.size() ? m_qdot1 : JointVector(JointVector::Zero(q.size()));
  m_qdot1 = qdot;
  m_qPrevious = q;
  m_hasPrevious = true;
}

vpServoArmFollowing::vpJointFollowing vpServoArmFollowing::getJointFollowing(unsigned int i) const
{
  return i < shown().joints ? shown().states[i] : JOINT_NOT_JUDGED;
}

double vpServoArmFollowing::getJointRatio(unsigned int i) const
{
  return i < shown().joints ? shown().ratios[i] : 0.0;
}

std::string vpServoArmFollowing::getDiagnosis() const
{
  if (!m_notFollowing) {
    return std::string();
  }
  const vpVerdict &v = m_detection;
  std::ostringstream os;
  os.precision(3);
  switch (v.cause) {
  case ARM_NOT_MOVING:
    if (v.reference > 0.0) {
      os << "the arm does not move: no joint moved over " << m_calls << " calls while the task commanded "
         << v.commanded << " px of image motion per call (" << v.reference << " s per call"
         << (m_period > 0.0 ? ", setControlPeriod()" : ", learned from the arm's motion") << ")";
    } else {
      os << "the arm does not move: no joint moved over " << v.stillCalls << " calls while the task commanded "
         << v.stillCommand / v.stillCalls << " px/s of image motion on average (no period: setControlPeriod() "
         << "was not given, and the arm never moved to learn one from)";
    }
    os << "; check that the robot is in velocity control "
       << "(setRobotState(vpRobot::STATE_VELOCITY_CONTROL)), that qdot reaches it (setVelocity(vpRobot::"
       << "ARTICULAR_FRAME, qdot)), that no joint is at a limit (some robots then stop every joint) and that q is "
       << "read from the encoders at each call";
    break;
  case ARM_SLOWER:
    os << "every joint moves in the commanded direction but only " << 100.0 * v.ratio << " % of the commanded "
       << "motion (" << v.reference << " s per call"
       << (m_period > 0.0 ? ", setControlPeriod()" : ", learned from the arm's motion") << "): the robot clips the "
       << "velocity (keep the task's setMaxJointVelocity() within the robot's maximum velocities), or the calls come "
       << "every " << v.duration << " s (setControlPeriod(" << v.duration << "))";
    break;
  case ARM_JOINTS_LAGGING:
  case ARM_OTHER_DIRECTION:
    os << (v.cause == ARM_JOINTS_LAGGING ? "some joints do not follow while the others do ("
                                         : "the joints move in another direction than commanded (");
    for (unsigned int i = 0, listed = 0; i < v.joints; ++i) {
      const vpJointFollowing s = v.states[i];
      if (s == JOINT_NOT_JUDGED || s == JOINT_FOLLOWS) {
        continue;
      }
      os << (listed++ > 0 ? ", " : "") << "joint " << i;
      if (s == JOINT_STILL) {
        os << " does not move";
      } else if (s == JOINT_SLOWER) {
        os << " moves " << 100.0 * v.ratios[i] << " % of its command";
      } else if (s == JOINT_FASTER) {
        os << " moves " << v.ratios[i] << " times its command";
      } else if (s == JOINT_REVERSED) {
        os << " moves the other way";
      } else {
        os << " moves without a command";
      }
    }
    os << (v.cause == ARM_JOINTS_LAGGING
               ? "): a joint at a limit, or a robot that clips each joint's velocity on its own (keep the task's "
                 "setMaxJointVelocity() within the robot's maximum velocities, setJointLimits() within the robot's "
                 "limits)"
               : "): send qdot as joint velocities, setVelocity(vpRobot::ARTICULAR_FRAME, qdot), not in another frame "
                 "(CAMERA_FRAME, END_EFFECTOR_FRAME); check that q holds the encoders' readings of the model's joints, "
                 "in its order, signs and units");
    break;
  case ARM_FOLLOWING:
    break;
  }
  os << "; then call getArmFollowing().reset()";
  return os.str();
}
