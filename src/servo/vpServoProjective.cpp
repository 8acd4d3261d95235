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

#include <visp3/projective/vpServoProjective.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"
#include "servo/vpServoProjectiveNotices.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpServoProjective");

vpServoProjective::vpServoProjective()
    : m_link(), m_features(), m_desired(), m_control(), m_health(), m_mismatch(), m_follow(), m_targets(),
      m_effective(), m_iterations(), m_lastIteration(0), m_path(), m_activeNow(), m_errorUnit(ERROR_PIXELS),
      m_focalLength(0.0), m_q(), m_qFresh(false), m_targetGeneration(0), m_refinement(), m_rigUpdatesSeen(0)
{
}

void vpServoProjective::addFeature(vpFeatureStereoPoint &s, vpFeatureStereoPoint &s_star)
{
  m_features.push_back(&s);
  m_desired.push_back(&s_star);
  m_health.addFeature();
  m_mismatch.resize(static_cast<unsigned int>(m_features.size()));
  m_targets.push_back(vpTarget());
  m_effective.push_back(Eigen::Vector4d::Zero());
  m_activeNow.push_back(0);
  m_path.addFeature(); // another task: plan anew
  m_refinement.stop(); // another set of features: its frames and points would not match
  m_iterations[m_lastIteration].m_states.push_back(FEATURE_ACTIVE); // the report's state before the first call
  m_iterations[m_lastIteration].m_following = false;
}

void vpServoProjective::clearFeatures()
{
  m_features.clear();
  m_desired.clear();
  m_health.clearFeatures();
  m_mismatch.resize(0);
  m_targets.clear();
  m_effective.clear();
  m_activeNow.clear();
  m_path.clearFeatures();
  m_refinement.stop();
  vpServoProjectiveReport &report = m_iterations[m_lastIteration];
  report.m_status = SERVO_RUNNING;
  report.m_data.m_nbActive = 0;
  report.m_states.clear();
  report.m_following = false;
  report.m_openLoopCalls = 0;
}

inline void vpServoProjective::check(const char *method) const
{
  if (m_link.robot == nullptr) {
    fail(vpProjectiveException::notInitializedError, at(method), "no robot model; call setRobot() first");
  }
  if (m_features.empty()) {
    fail(vpProjectiveException::notInitializedError, at(method), "no feature; call addFeature(s, s_star) first");
  }
  if (4 * m_features.size() < m_link.robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << m_features.size() << " stereo points give " << 4 * m_features.size() << " equations for "
       << m_link.robot->getNumberOfJoints() << " joints; add features";
    fail(vpProjectiveException::notEnoughPointsError, at(method), os.str());
  }
}

// The steps of computeControlLaw(), used only in this file: inline, so that the shared library runs them without a
// call through its symbol table (a non-inline member of an exported class may be interposed, hence is never inlined).
inline void vpServoProjective::checkJoints(const JointVector &q, const char *method) const
{
  check(method);
  const Eigen::Index n = static_cast<Eigen::Index>(m_link.robot->getNumberOfJoints());
  if (q.size() != n) {
    std::ostringstream os;
    os << "q must have " << n << " entries, got " << q.size();
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
  if (!q.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, at(method), "q has a NaN or infinite entry");
  }
  const vpServoJointLimitAvoidance &limits = m_control.getJointLimitAvoidance();
  if (limits.hasJointLimits() && limits.getNumberOfJoints() != static_cast<unsigned int>(n)) {
    std::ostringstream os;
    os << "the joint limits have " << limits.getNumberOfJoints() << " entries but the robot has " << n
       << " joints; call setJointLimits() again";
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
}

inline void vpServoProjective::computeData(const JointVector &q, vpServoProjectiveData &data) const
{
  // Once per iteration: H(q), its LU, the joint motions, each feature's point; every part reads them.
  const vpProjectiveArmModel &model = m_link.robot->getModel();
  const unsigned int N = static_cast<unsigned int>(m_features.size());
  data.computeKinematics(model, q, N);
  for (unsigned int i = 0; i < N; ++i) {
    data.computeFeature(model, i, m_features[i]->getFeature());
  }
}

inline void vpServoProjective::buildTask(const JointVector &q, vpIteration &it, const char *method)
{
  // Task Jacobian, eq. (46) stacked over the active points, at the current q and triangulated points; the rows of
  // the features set aside are zero.
  vpServoProjectiveData &d = it.m_data;
  const vpProjectiveArmModel &model = m_link.robot->getModel();
  const Eigen::Index n = q.size();
  const Eigen::Index rows = 4 * static_cast<Eigen::Index>(m_features.size());
  if (d.m_J.rows() != rows || d.m_J.cols() != n) {
    d.m_J.resize(rows, n);
    d.m_e.resize(rows);
  }
  m_health.startIteration(model, d);
  vpProjectiveRobot::PointJacobian Ji;
  unsigned int active = 0;
  for (unsigned int i = 0; i < m_features.size(); ++i) {
    const Eigen::Vector4d sStar = desired(i);
    const Eigen::Index r = 4 * static_cast<Eigen::Index>(i);
    m_activeNow[i] = m_health.classify(i, sStar) == FEATURE_ACTIVE ? 1 : 0;
    if (!m_activeNow[i]) {
      d.m_J.middleRows(r, 4).setZero();
      d.m_e.segment<4>(r).setZero();
      continue;
    }
    if (!vpProjectiveKinematics::imageJacobian(model, d.getArmData(), d.getPoint(i), Ji)) {
      std::ostringstream os;
      os << "feature " << i << " triangulates onto a camera's focal plane; check that it is matched correctly";
      fail(vpProjectiveException::pointAtInfinityError, at(method), os.str());
    }
    d.m_J.middleRows(r, 4) = Ji;
    d.m_e.segment<4>(r) = d.getFeature(i) - sStar;
    ++active;
  }
  d.m_nbActive = active;
  d.m_normal.compute(d.m_J, d.m_e);
  d.m_errorNorm =
      d.m_e.norm() / m_control.getErrorScale(); // in the unit of setErrorUnit(), for the large projection thresholds
}

inline vpServoProjective::vpServoStatus vpServoProjective::decideStatus(const vpIteration &it) const
{
  // With every feature active the task is the user's: a rank loss is left to the damping. With features set aside,
  // the remaining ones must constrain every joint: a stereo point gives at most 3 independent equations, then the
  // scale-aware rank test on J D^-1.
  if (it.m_data.m_nbActive == m_features.size()) {
    return SERVO_RUNNING;
  }
  const vpServoNormalEquations &ne = it.m_data.m_normal;
  const bool stopped = 3 * static_cast<Eigen::Index>(it.m_data.m_nbActive) < ne.size() ||
                       !(vpServoProjectiveReport::singularValueRatio(ne.getJtJ(), m_health.getRankTolerance()) >=
                         m_health.getRankTolerance());
  return stopped ? SERVO_STOPPED : SERVO_REDUCED;
}

inline bool vpServoProjective::openLoop(vpIteration &it)
{
  // While the path following allows it, each set-aside feature that was active before is predicted: its remembered
  // point moved by this iteration's H(q).
  if (!m_path.mayOpenLoop(m_control.getControlPeriod())) {
    return false;
  }
  vpServoProjectiveData &d = it.m_data;
  const vpProjectiveArmModel &model = m_link.robot->getModel();
  vpProjectiveRobot::PointJacobian Ji;
  unsigned int used = d.m_nbActive;
  for (unsigned int i = 0; i < m_features.size(); ++i) {
    const Eigen::Index r = 4 * static_cast<Eigen::Index>(i);
    Eigen::Vector4d sHat;
    if (m_activeNow[i] || !m_path.predict(i, m_health, d, sHat)) {
      continue;
    }
    d.computeFeature(model, i, sHat); // the feature the model predicts here, in place of the one not seen
    if (!d.hasPoint(i) || !vpProjectiveKinematics::imageJacobian(model, d.getArmData(), d.getPoint(i), Ji)) {
      d.computeFeature(model, i, m_features[i]->getFeature()); // as it was: a prediction the model cannot use
      continue;
    }
    d.m_J.middleRows(r, 4) = Ji;
    d.m_e.segment<4>(r) = sHat - desired(i);
    ++used;
  }
  if (used == d.m_nbActive) {
    return false;
  }
  // The images' normal equations, kept (fixed-size: no allocation) for a stop below instead of being built again.
  const vpServoNormalEquations images = d.m_normal;
  const double errorNorm = d.m_errorNorm;
  d.m_normal.compute(d.m_J, d.m_e);
  const unsigned int active = d.m_nbActive;
  d.m_nbActive = used; // the rank test of decideStatus() on the measured and predicted features together
  const bool constrained = decideStatus(it) != SERVO_STOPPED || used == m_features.size();
  d.m_nbActive = active; // the features the images gave (getNumberOfActiveFeatures() is the health's)
  if (!constrained) {
    // Stopped after all: the task as the images gave it (the rows of the features set aside zero).
    for (unsigned int i = 0; i < m_features.size(); ++i) {
      if (!m_activeNow[i]) {
        d.computeFeature(model, i, m_features[i]->getFeature());
        d.m_J.middleRows(4 * static_cast<Eigen::Index>(i), 4).setZero();
        d.m_e.segment<4>(4 * static_cast<Eigen::Index>(i)).setZero();
      }
    }
    d.m_normal = images;
    d.m_errorNorm = errorNorm;
    return false;
  }
  d.m_errorNorm = d.m_e.norm() / m_control.getErrorScale();
  return true;
}

inline void vpServoProjective::stop(vpIteration &it, JointVector &qdot)
{
  m_control.getSettling().reset(); // stopped: converge anew before settling
  qdot.setZero(it.m_data.m_normal.size());
  it.m_qdot2.setZero(it.m_data.m_normal.size());
  it.m_lambda = 0.0;
  it.m_damping = 0.0;
  it.m_saturated = false;
}

inline void vpServoProjective::computePrimaryVelocity(const JointVector &q, vpIteration &it, JointVector &qdot)
{
  // qdot1 = -lambda (J^T J + mu^2 I)^-1 J^T e, saturated: the motion the arm really makes. Along a planned path it is
  // the path's step to the next sample (feedforward) plus the law on the error to the current sample (feedback, with
  // the follower's gain), saturated as a whole.
  const bool following = m_path.isFollowing();
  it.m_lambda = following ? m_path.getPlanner().getPathFollowingGain()
                          : m_control.gain(it.m_data.m_normal, it.m_data.m_e.cwiseAbs().maxCoeff());
  if (following || it.m_status == SERVO_OPEN_LOOP) {
    m_control.getSettling()
        .reset(); // a path (or a prediction) is not a rest: settle on law (47), on the images, after it
  } else if (m_control.getSettling().isEnabled()) {
    // Settling restarts with another set of active features or another target (their signature).
    unsigned long context = m_targetGeneration;
    for (unsigned int i = 0; i < m_features.size(); ++i) {
      context = 31 * context + (m_health.getFeatureState(i) == FEATURE_ACTIVE ? i + 1 : 0);
    }
    it.m_lambda = m_control.getSettling().gain(it.m_lambda, it.m_data.m_normal, it.m_data.m_e.squaredNorm(),
                                               4 * it.m_data.m_nbActive, context);
  }
  m_control.computePrimaryStep(it.m_data.m_normal, it.m_lambda, qdot);
  const vpServoDampedLeastSquares &law = m_control.getDampedLeastSquares();
  m_path.shapeStep(m_link.robot->getModel(), q, law, qdot); // the path's step, or no overshoot of a planned task
  it.m_damping = law.getDamping();
  it.m_saturated = law.isSaturated();
}

inline void vpServoProjective::addJointLimitAvoidance(const JointVector &q, vpIteration &it, JointVector &qdot) const
{
  // A planned path stays inside the limits and ends at a target inside them. While following it, no avoidance: the
  // path was checked inside the limits and no step crosses one, whereas the avoidance's push on a joint that starts
  // in its band, projected through the large projection operator, moved the other joints by up to 18 deg beside the
  // path's step and threw the features out of view. After the path, the avoidance lets the arm go to the planned
  // target (law (47) alone, even planned, is left as is); and the step never crosses a limit (the planned servo's
  // promise, which the avoidance alone cannot keep with a step of the path's size).
  const vpServoJointLimitAvoidance &limits = m_control.getJointLimitAvoidance();
  const JointVector *target = m_path.getPathTarget();
  const vpServoProjectiveData &d = it.m_data;
  if (!m_path.isFollowing()) {
    if (m_control.addJointLimitAvoidance(q, d.m_normal, d.m_errorNorm, qdot, it.m_qdot2, target)) {
      it.m_saturated = true;
    }
  } else {
    it.m_qdot2.setZero(q.size());
    if (limits.hasJointLimits() && m_control.getDampedLeastSquares().saturate(qdot)) {
      it.m_saturated = true;
    }
  }
  if (target != nullptr && limits.hasJointLimits()) {
    m_control.keepInside(q, d.m_normal, it.m_lambda, qdot); // a planned task never crosses a limit
  }
  if (!qdot.allFinite()) {
    fail(vpProjectiveException::estimationFailedError, at("computeControlLaw()"),
         "the control law gave a non-finite velocity (singular task Jacobian); increase the damping");
  }
}

inline void vpServoProjective::commit()
{
  m_lastIteration = 1 - m_lastIteration;
  m_health.endIteration();
  m_control.getSettling().commit();
  // The report of the call (no allocation once the sizes are known): what the task's parts keep of it.
  vpServoProjectiveReport &report = m_iterations[m_lastIteration];
  m_path.commit(report.m_status, m_health, report.m_data); // the open loop's memory, the plan's next sample
  report.m_states.resize(m_features.size());
  for (unsigned int i = 0; i < m_features.size(); ++i) {
    report.m_states[i] = m_health.getFeatureState(i);
  }
  report.m_following = m_path.isFollowing();
  report.m_openLoopCalls = m_path.getOpenLoopCalls();
  report.m_errorScale = m_control.getErrorScale();
  report.m_rankTolerance = m_health.getRankTolerance();
  report.m_pseudoInverseThreshold = m_control.getDampedLeastSquares().getPseudoInverseThreshold();
  m_control.getJointLimitAvoidance().getLargeProjectionThresholds(report.m_largeProjectionThresholds[0],
                                                                  report.m_largeProjectionThresholds[1]);
  report.m_arm.share(m_follow);
}

void vpServoProjective::computeControlLaw(const JointVector &q, JointVector &qdot)
{
  // No allocation once the sizes are known: messages are built only when throwing. Every step works on the iteration
  // in progress; commit() makes it the one that the getters read, so that a call that throws changes nothing.
  const char *const method = "computeControlLaw()";
  checkJoints(q, method);
  vpIteration &it = m_iterations[1 - m_lastIteration];
  refreshTargets();
  computeData(q, it.m_data);
  const vpIteration &before = last();
  const bool planned = m_path.plan(m_link.robot->getModel(), q, it.m_data, m_effective, m_control, m_health,
                                   before.m_data.m_e, before.m_data.m_errorNorm);
  buildTask(q, it, method);
  const bool mismatch = detectMismatch(it.m_data); // after the last step that may throw
  const bool notFollowing = m_follow.evaluate(q, it.m_data.m_normal.getJtJ(), 4 * it.m_data.m_nbActive);
  it.m_status = notFollowing ? SERVO_ARM_NOT_FOLLOWING
                             : (mismatch ? SERVO_MODEL_MISMATCH : (planned ? decideStatus(it) : SERVO_NO_PLAN));
  if (it.m_status == SERVO_STOPPED && openLoop(it)) {
    it.m_status = SERVO_OPEN_LOOP;
  }
  if (it.m_status == SERVO_STOPPED || it.m_status == SERVO_NO_PLAN || it.m_status == SERVO_MODEL_MISMATCH ||
      it.m_status == SERVO_ARM_NOT_FOLLOWING) {
    stop(it, qdot);
  } else {
    computePrimaryVelocity(q, it, qdot);
    addJointLimitAvoidance(q, it, qdot);
    qdot /= m_control.getControlPeriod(); // the step of this call, as a velocity held for one period
  }
  m_follow.commit(q, qdot); // the command the arm must make by the next call
  commit();
  // The rig refinement records the calls that move the arm, with the robot given modifiable; refine() never throws: a
  // failed refinement leaves everything as it was.
  const vpServoStatus status = last().m_status;
  if (m_refinement.isActive() && (status == SERVO_RUNNING || status == SERVO_REDUCED)) {
    if (m_link.modifiable == nullptr || m_link.modifiable != m_link.robot) {
      m_refinement.stop();
    } else if (m_refinement.record(last().m_data, m_health)) {
      m_refinement.refine(*m_link.modifiable);
    }
  }
  noticeServoStatus(last(), m_path.getPlanner(), m_mismatch); // a program that never reads the status hears of it once
}

vpColVector vpServoProjective::computeControlLaw(const vpColVector &q)
{
  check("computeControlLaw()");
  if (q.getRows() != m_link.robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << "q must have " << m_link.robot->getNumberOfJoints() << " entries, got " << q.getRows();
    fail(vpProjectiveException::dimensionError, at("computeControlLaw()"), os.str());
  }
  JointVector qe(q.getRows()), qdot(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    qe(i) = q[i];
  }
  computeControlLaw(qe, qdot);
  return toVispVector(qdot);
}

void vpServoProjective::setJointPositions(const vpColVector &q)
{
  const std::string where = at("setJointPositions()");
  if (m_link.robot != nullptr && q.getRows() != m_link.robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << "q must have " << m_link.robot->getNumberOfJoints() << " entries, got " << q.getRows();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const unsigned int maxJoints = vpProjectiveRobot::maxJoints;
  if (q.getRows() == 0 || q.getRows() > maxJoints) {
    std::ostringstream os;
    os << "q must have 1 to " << maxJoints << " entries, got " << q.getRows();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    requireFinite(q[i], where, "a joint value");
  }
  m_q.resize(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    m_q(i) = q[i];
  }
  m_qFresh = true;
}

vpColVector vpServoProjective::computeControlLaw()
{
  if (!m_qFresh) {
    fail(vpProjectiveException::notInitializedError, at("computeControlLaw()"),
         "no joint values since the last computeControlLaw(); read the encoders (vpRobot::getPosition(vpRobot::"
         "ARTICULAR_FRAME, q)) and call setJointPositions(q) before each call, or call computeControlLaw(q)");
  }
  JointVector qdot(m_q.size());
  computeControlLaw(m_q, qdot); // throws, changing nothing, if q does not fit the robot
  m_qFresh = false;
  return toVispVector(qdot);
}
