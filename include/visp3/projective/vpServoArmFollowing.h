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
  \file vpServoArmFollowing.h
  \brief Whether the arm makes the joint motion a servo task commands: a velocity sent in another frame, a robot not
  in velocity control, a joint held at a limit, a velocity the robot clips.
*/

#ifndef _vpServoArmFollowing_h_
#define _vpServoArmFollowing_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoArmFollowing
  \ingroup group_projective
  \brief A part of vpServoProjective (vpServoProjective::getArmFollowing()): compares the joint motion the encoders
  measure between two calls with the motion the task commanded, and stops the task (SERVO_ARM_NOT_FOLLOWING,
  \f$ \dot q = 0 \f$) when the arm does not make it. The model-mismatch check (vpServoModelMismatch) compares the
  images with the model's prediction at the measured joints: a bumped camera moves the images away from it while the
  arm follows, an arm that does not follow leaves the images where the model puts them at the joints it reached. The
  two checks thus tell the two faults apart.

  <b>Motion.</b> At call \f$ k \f$ the task measures \f$ q_k \f$ (n x 1, the model's joint units) and returns
  \f$ \dot q_k \f$ (joint units per second); the robot holds it until the next call. The arm moved by
  \f$ d_k = q_k - q_{k-1} \f$, which an arm that follows makes from the last command or, with one call of latency
  (a controller that applies a command at its next cycle, a simulator thread), from the one before, or a mix:
  \f$ d_k \approx a\, \dot q_{k-1} + b\, \dot q_{k-2} \f$, \f$ a, b \ge 0 \f$ minimising
  \f$ \|d_k - a \dot q_{k-1} - b \dot q_{k-2}\|_G^2 \f$ (a 2 x 2 non-negative least squares), where
  \f$ \|x\|_G^2 = x^T G x \f$, \f$ G = J^T J / m \f$ from the task's \f$ J \f$ (\f$ m \f$ rows of its active
  features): \f$ \|x\|_G \f$ is the RMS image motion (pixels) of a joint motion \f$ x \f$, so that every threshold
  is in pixels whatever the joint units (radians, metres, millimetres). The command as the arm received it,
  \f$ c = \alpha \dot q_{k-1} + (1 - \alpha) \dot q_{k-2} \f$, is the one of three mixes (the least-squares one
  \f$ \alpha = a / (a + b) \f$, no latency \f$ \alpha = 1 \f$, one call of latency \f$ \alpha = 0 \f$) that most
  joints follow (a joint held at a limit can bend the least-squares mix where it dominates the image motion), and the
  time it acted
  \f[ \tau_k = \mathrm{median}_i \; d_{k,i} / c_i \f]
  over the commanded joints (\f$ s_i |c_i| \tau_{ref} \ge \f$ 0.1 px, \f$ s_i = \sqrt{G_{ii}} \f$ the image motion
  of one unit of joint \e i): a median, so that a joint that does not follow does not drag the others' scale
  (without such a joint, the least-squares \f$ \tau_k = d_k^T G c / c^T G c \f$: small joint motions that add up).

  <b>Shape</b> (which joints follow; needs no period): joint \e i is judged when \f$ s_i \max(\tau_k |c_i|,
  |d_{k,i}|) \ge \f$ 0.1 px (its motion is measurable), and follows when \f$ 0.5 \le d_{k,i} / (\tau_k c_i) \le
  2 \f$. Otherwise it is still (ratio within \f$ \pm 0.1 \f$), slower (below 0.5), faster (above 2), reversed
  (negative), or uncommanded (\f$ s_i \tau_k |c_i| < 0.05 \f$ px: it moves without a command). When no joint moves
  along the command (\f$ \tau_k \le 0 \f$), the joints are compared with \f$ \tau_{ref} c \f$; when the median
  joint moved less than half of it (\f$ \tau_k < 0.5\, \tau_{ref} \f$), with both, and the comparison where more
  joints follow is kept (two of three moving joints held at their limits make the median one of them).

  <b>Scale</b> (whether the arm moves as far as commanded), against the reference duration \f$ \tau_{ref} \f$: the
  period of setControlPeriod() (vpServoProjective::setControlPeriod() sets it) or, when it was never given, one
  learned from the arm (a ViSP program that never sets the period runs its loop at its own rate): the shortest
  \f$ \tau \f$ of the last 7 regular calls, a call being regular when the arm followed it measurably and it lasted
  as the call before it, within 20 % (a pause between calls, the robot holding the command, lengthens one call).
  When the command would move the images by \f$ \tau_{ref} \|c\|_G \ge \f$ 0.1 px, the call fails if the arm
  moved them by less than 3 % of that (or by less than 0.025 px, the encoders' noise, and half of it) (\f$ \|d_k\|_G
  \f$: it does not move) or, with the period given, if \f$ \tau_k < 0.5\, \tau_{ref} \f$ (it moves less than commanded).
  A learned period follows the loop's own timing, which a loaded computer stretches from call to call: against it, only
  an arm that does not move is judged. A pause between calls, while the robot holds the last command, moves the arm
  further: never a failure.

  <b>Decision.</b> A call disagrees when a judged joint does not follow or the scale fails; a call where nothing was
  commanded or measurable (the first call, a call after reset(), a task at rest, \f$ \dot q = 0 \f$ returned) is not
  judged and restarts the count. setConsecutiveCalls() (default 3) consecutive disagreeing calls stop the task:
  isNotFollowing() stays true, and the task returns \f$ \dot q = 0 \f$, until reset() (or a new robot,
  vpServoProjective::setRobot()). Single odd calls (a skipped cycle, a pause, a call where the user moved the arm, the
  first command of a controller with one call of latency) never stop it. The cause, from the detecting call:
  - ARM_NOT_MOVING: no joint moves: the robot is not in velocity control, stopped, or holds every joint when one
    reaches a limit (ViSP's simulators do);
  - ARM_SLOWER: every joint in the commanded direction, \f$ \tau < 0.5\, \tau_{ref} \f$ (the period given): the
    robot clips the velocity (its maximum below the task's setMaxJointVelocity()), or calls come more often than the
    period;
  - ARM_JOINTS_LAGGING: some joints still or slower, the others follow: a joint at a limit, a per-joint clipping;
  - ARM_OTHER_DIRECTION: the joints move in another direction: a velocity sent in another frame (vpRobot::
    setVelocity() with CAMERA_FRAME instead of ARTICULAR_FRAME), or readings that are not the joints of the model.

  <b>Without any reference</b> (no period given, none learned yet: a robot that has not moved since the first call
  leaves nothing to learn it from), the arm does not move when, over 40 consecutive commanding calls, the joints
  stayed where they were (\f$ \|q_k - q_{start}\|_G < \f$ 0.1 px, the smallest motion judged) while the commands
  would have moved the images by at least 1 px, ten times more, even at 5 ms per call (\f$ 0.005\,\sum_k \|c_k\|_G
  \ge 1 \f$ px; the task is called once per image pair, and a fast camera gives 200 pairs per second): 2 s of a
  20 Hz loop, 0.2 s of a 200 Hz one, longer than a robot takes to start. The cause is ARM_NOT_MOVING.

  Limitation: without a period (setControlPeriod()), a robot that clips is not told from a loop that runs faster, and
  a robot that does not move is found after 40 calls instead of setConsecutiveCalls(). The shape needs no period.

  Usage (the task does it): evaluate() once per call before the status is decided, commit() with the call's
  \f$ \dot q \f$ once the call succeeded; a call that throws in between changes nothing. No allocation per call:
  fixed-size Eigen types, \f$ O(n^2) \f$ operations.
*/
class VISP_EXPORT vpServoArmFollowing
{
public:
  typedef vpProjectiveArmModel::JointVector JointVector; //!< Joint values (n x 1) without heap allocation.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix; //!< n x n without heap allocation.

  //! What the arm does (see the class documentation).
  enum vpFollowingCause {
    ARM_FOLLOWING,      //!< No fault seen.
    ARM_NOT_MOVING,     //!< No joint moves.
    ARM_SLOWER,         //!< Every joint moves in the commanded direction, by less than half the command.
    ARM_JOINTS_LAGGING, //!< Some joints are still or slower, the others follow.
    ARM_OTHER_DIRECTION //!< The joints move in another direction than commanded.
  };

  //! What one joint did at the judged call.
  enum vpJointFollowing {
    JOINT_NOT_JUDGED, //!< Its motion was too small to tell (below 0.1 px of image motion).
    JOINT_FOLLOWS,    //!< \f$ 0.5 \le d_i / (\tau c_i) \le 2 \f$.
    JOINT_STILL,      //!< \f$ |d_i / (\tau c_i)| < 0.1 \f$.
    JOINT_SLOWER,     //!< \f$ 0.1 \le d_i / (\tau c_i) < 0.5 \f$.
    JOINT_FASTER,     //!< \f$ d_i / (\tau c_i) > 2 \f$.
    JOINT_REVERSED,   //!< \f$ d_i / (\tau c_i) \le -0.1 \f$.
    JOINT_UNCOMMANDED //!< Moves without a command.
  };

  //! On, 3 consecutive calls, period learned, no history.
  vpServoArmFollowing();

  /*! \name Settings */
  //@{
  //! On (default) or off; off, evaluate() never stops the task and the history is forgotten.
  void setEnabled(bool enabled);
  //! True if the check is on.
  bool isEnabled() const { return m_enabled; }
  /*!
    Consecutive disagreeing calls that stop the task (default 3).
    \exception vpProjectiveException (invalidValueError) if 0.
  */
  void setConsecutiveCalls(unsigned int calls);
  //! The number of setConsecutiveCalls().
  unsigned int getConsecutiveCalls() const { return m_calls; }
  /*!
    The time between two calls (seconds), \f$ \tau_{ref} \f$; 0 (default): learned from the arm's motion.
    vpServoProjective::setControlPeriod() sets it.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if negative or not finite.
  */
  void setControlPeriod(double seconds);
  //! The period of setControlPeriod() (0: learned).
  double getControlPeriod() const { return m_period; }
  //! Forgets the history and the verdict: the next call is a first call (after the user fixed the arm).
  void reset();
  //@}

  /*! \name Per call (vpServoProjective::computeControlLaw()) */
  //@{
  /*!
    Judges the motion from the last commit() to the joints \e q (n x 1), with the metric \e JtJ (n x n, the task's
    \f$ J^T J \f$) of \e rows active rows (0: not judged). True if the task must stop: already stopped, or this call
    is the setConsecutiveCalls()-th disagreeing one. Changes nothing until commit().
  */
  bool evaluate(const JointVector &q, const JointMatrix &JtJ, unsigned int rows);
  //! Ends the call: the joints \e q and the returned \e qdot (n x 1, per second) become the history, the verdict of
  //! evaluate() the current one.
  void commit(const JointVector &q, const JointVector &qdot);
  //@}

  /*! \name Verdict */
  //@{
  //! True once the arm was found not to follow (until reset()).
  bool isNotFollowing() const { return m_notFollowing; }
  //! The cause (ARM_FOLLOWING while the arm follows).
  vpFollowingCause getCause() const { return m_notFollowing ? m_detection.cause : ARM_FOLLOWING; }
  //! Number of joints of the last judged call (0 before any).
  unsigned int getNumberOfJoints() const { return shown().joints; }
  //! What joint \e i did at the detecting call, or at the last judged call while the arm follows; JOINT_NOT_JUDGED
  //! for \e i out of range.
  vpJointFollowing getJointFollowing(unsigned int i) const;
  //! \f$ d_i / (\tau c_i) \f$ of joint \e i at that call (0 if not judged or out of range).
  double getJointRatio(unsigned int i) const;
  //! \f$ \tau / \tau_{ref} \f$ at that call: the fraction of the commanded motion made (-1 without a reference).
  double getMotionRatio() const { return shown().ratio; }
  //! \f$ \tau \f$ at that call (seconds): how long the commands acted between the two calls.
  double getCallDuration() const { return shown().duration; }
  //! \f$ \tau_{ref} \f$ now: the period of setControlPeriod(), else the learned one (0: none yet).
  double getReferenceDuration() const;
  //! Consecutive disagreeing calls so far.
  unsigned int getDisagreeingCalls() const { return m_disagreeing; }
  //! One sentence for a log: the cause, the joints that do not follow and the fix; empty while the arm follows.
  std::string getDiagnosis() const;
  //@}

private:
  //! The verdict of one call.
  struct vpVerdict {
    bool judged = false;
    bool disagrees = false;
    vpFollowingCause cause = ARM_FOLLOWING;
    unsigned int joints = 0;
    double ratio = -1.0;    // tau / tau_ref
    double duration = 0.0;  // tau
    double reference = 0.0; // tau_ref
    double commanded = 0.0; // tau_ref ||qdot_{k-1}||_G (px), 0 without a reference
    bool learnable = false; // followed, measurably: tau joins the learned durations
    // Without a reference: consecutive commanding calls with the joints within 0.1 px of m_qStill (the smallest motion
    // judged), and the sum of ||c_k||_G over them (px per second).
    unsigned int stillCalls = 0;
    double stillCommand = 0.0;
    vpJointFollowing states[vpProjectiveArmModel::maxJoints] = {};
    double ratios[vpProjectiveArmModel::maxJoints] = {};
  };
  static const unsigned int kLearned = 7; // durations kept to learn the period from

  const vpVerdict &shown() const { return m_notFollowing ? m_detection : m_last; }
  double learnedDuration() const;

  bool m_enabled;
  unsigned int m_calls;
  double m_period;
  // History: the joints and the commands of the last two calls (zero before the first).
  bool m_hasPrevious;
  JointVector m_qPrevious, m_qdot1, m_qdot2;
  // Verdicts: of evaluate() (until commit()), of the last judged call, and of the call that stopped the task.
  vpVerdict m_pending, m_last, m_detection;
  unsigned int m_disagreeing;
  bool m_notFollowing;
  double m_durations[kLearned];
  unsigned int m_nbDurations, m_nextDuration;
  double m_lastDuration; // of the last call if it was learnable, else 0
  // Without a reference: the joints where the arm has been still since, over how many commanding calls, and the sum
  // of their commands' image speeds (px per second).
  JointVector m_qStill;
  unsigned int m_stillCalls;
  double m_stillCommand;
};

END_VISP_NAMESPACE

#endif
