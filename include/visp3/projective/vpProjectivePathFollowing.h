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
  \file vpProjectivePathFollowing.h
  \brief How a servo task follows the plan of vpProjectivePathPlanner: when to plan, the reference of each call, a
  stalled law, the open-loop phase.
*/

#ifndef _vpProjectivePathFollowing_h_
#define _vpProjectivePathFollowing_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpServoControlLaw.h>
#include <visp3/projective/vpServoFeatureHealth.h>
#include <visp3/projective/vpServoProjectiveData.h>
#include <visp3/projective/vpServoProjectiveReport.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectivePathFollowing
  \ingroup group_projective
  \brief The path following of vpServoProjective (vpServoProjective::setPathPlanning(), \ref servo_task_planning): it
  owns the planner (vpProjectivePathPlanner) and, call by call, plans once per target, gives the reference of the
  image feedback along the path, plans again from a configuration off the plan or a stalled law (47), and allows the
  open-loop phase (\ref servo_task_open_loop). The task drives it; a program reads it through the task
  (vpServoProjective::getPathPlanner(), vpServoProjectiveReport::isFollowingPath(), getOpenLoopCalls()).

  <b>One call.</b> plan() before the task is built (it decides isFollowing()), getReference() for each feature's
  \f$ s^* \f$, shapeStep() on law (47)'s step, then commit() with the call's status. Sizes are the task's: \f$ N \f$
  features (addFeature() order), \f$ n \f$ joints (the model's joint values: radians or the encoder's length unit).

  <b>Open loop.</b> While a plan is under way, for at most vpProjectivePathPlanner::setMaxOpenLoopTime(), predict()
  gives, in place of a feature set aside, the image of its point at the zero reference where it was last active
  (vpServoFeatureHealth::getMemory(), the task's one memory of it) moved by this call's \f$ H(q) \f$; only if it was
  active since the model or its rig last changed (forgetPoints()).
*/
class VISP_EXPORT vpProjectivePathFollowing
{
public:
  typedef vpProjectiveArmModel::JointVector JointVector; //!< Joint values (n x 1).

  //! Planning off, no feature.
  vpProjectivePathFollowing();

  /*! \name Settings and features */
  //@{
  //! Planning on or off (vpServoProjective::setPathPlanning()); either way the next plan is made anew.
  void setPlanning(bool planning);
  //! True if planning is on.
  bool isPlanning() const { return m_planning; }
  //! The planner: its settings and its last plan.
  vpProjectivePathPlanner &getPlanner() { return m_planner; }
  //! The planner (read only).
  const vpProjectivePathPlanner &getPlanner() const { return m_planner; }
  //! One more feature (no memory): the task changed, the next plan is made anew.
  void addFeature();
  //! No feature, no open-loop call: the next plan is made anew.
  void clearFeatures();
  //! Forgets the features' points (the model or its rig changed: they belong to the old frame).
  void forgetPoints();
  //@}

  /*! \name One call (see the class documentation) */
  //@{
  /*!
    Plans when needed and decides whether this call follows the path (isFollowing()). Plans when a target changed
    since the last plan, or again (twice at most per target) when the arm is two path steps off the path or law
    (47), run as rehearsed, has stalled. Nothing happens with planning off.
    \param model : the acquired model.
    \param q : the joint values of the call (n x 1).
    \param data : the call's data (vpServoProjectiveData: \f$ H(q) \f$ and the features' values).
    \param targets : each feature's \f$ s^* \f$ the task uses (N of them, 4x1 pixels).
    \param control : the task's law (47), which the planner rehearses, and its joint limits.
    \param health : the task's feature checks (their image window).
    \param lastError : the task error \f$ e \f$ (4N, pixels) of the last successful call.
    \param lastErrorNorm : its norm in the unit of vpServoProjective::setErrorUnit().
    \return false if planning is on and no plan leads to the targets (SERVO_NO_PLAN).
    \exception vpProjectiveException as the planner when the joint limits do not fit \e q.
  */
  bool plan(const vpProjectiveArmModel &model, const JointVector &q, const vpServoProjectiveData &data,
            const std::vector<Eigen::Vector4d> &targets, const vpServoControlLaw &control,
            const vpServoFeatureHealth &health, const Eigen::VectorXd &lastError, double lastErrorNorm);
  //! True if this call follows the planned path (law (47) has not taken over yet).
  bool isFollowing() const { return m_following; }
  //! The reference (4x1, pixels) of feature \e i in this call: following the path, its image predicted at the sample
  //! the arm should be at; otherwise \e target, the feature's \f$ s^* \f$.
  const Eigen::Vector4d &getReference(unsigned int i, const Eigen::Vector4d &target) const
  {
    return m_following ? m_planner.getPredictedFeatures()[m_pathSample - 1][i] : target;
  }
  //! The joint target of a plan that is a path (not law (47) alone), or nullptr: the joint-limit avoidance lets the
  //! arm reach it and no step crosses a limit.
  const JointVector *getPathTarget() const;
  /*!
    Law (47)'s step \e qdot (n x 1, per call) shaped by the plan: following the path, bounded by half a path step and
    added to the path's step (feedforward), then saturated by \e law; after the path, guarded by the planner against
    an overshoot (vpProjectivePathPlanner::guardStep()). Unchanged with planning off.
  */
  void shapeStep(const vpProjectiveArmModel &model, const JointVector &q, const vpServoDampedLeastSquares &law,
                 JointVector &qdot) const;
  /*!
    True if this call may replace the features set aside by predictions: a plan is under way (a path followed, or law
    (47) within its rehearsed iterations) and one more open-loop call of \e period seconds stays within
    vpProjectivePathPlanner::getMaxOpenLoopTime().
  */
  bool mayOpenLoop(double period) const;
  /*!
    The prediction \e sHat (4x1, pixels) of feature \e i from \e health's memory of it moved by the \f$ H(q) \f$ of
    \e data. False (\e sHat unspecified) without a memory of this model and rig, or on a camera's focal plane.
  */
  bool predict(unsigned int i, const vpServoFeatureHealth &health, const vpServoProjectiveData &data,
               Eigen::Vector4d &sHat) const;
  /*!
    Ends a successful call of status \e status whose features' states are \e health's: notes the features active
    (with a point in \e data) since the last forgetPoints(), counts the open-loop calls and moves to the next sample of
    a plan under way.
  */
  void commit(vpServoProjectiveReport::vpServoStatus status, const vpServoFeatureHealth &health,
              const vpServoProjectiveData &data);
  //! Consecutive calls that ended in the open loop, up to the last commit().
  unsigned int getOpenLoopCalls() const { return m_openLoopCalls; }
  //@}

private:
  bool planIfNeeded(const vpProjectiveArmModel &model, const JointVector &q, const vpServoProjectiveData &data,
                    const std::vector<Eigen::Vector4d> &targets, const vpServoControlLaw &control,
                    const vpServoFeatureHealth &health, const Eigen::VectorXd &lastError, double lastErrorNorm);
  bool lawStalled(const Eigen::VectorXd &e);
  void restart();

  bool m_planning;
  vpProjectivePathPlanner m_planner;
  // The plan of the targets m_plannedFor, followed sample by sample.
  std::vector<Eigen::Vector4d> m_plannedFor;
  size_t m_pathSample;     // the sample the next call aims at
  bool m_following;        // the call follows the path
  unsigned int m_replans;  // plans again from an off-path configuration since the target was set
  bool m_lawLeftRehearsal; // law (47) left its rehearsal since the target was set: plan paths only
  size_t m_sincePlan;      // calls since the last plan
  bool m_replanFailed;     // the last plan was a re-plan that found nothing: law (47) runs
  // Law (47) as planned, after its rehearsed iterations: the error's sum and sum of squares over a window of calls,
  // and its squared norms over the window's halves (sized at each plan: no allocation per call).
  Eigen::VectorXd m_stallSum, m_stallSumSq;
  double m_stallHalves[2];
  unsigned int m_stallCount;
  // The open loop: the consecutive open-loop calls; per feature, active since the last forgetPoints() (its point at
  // the zero reference is the feature health's memory).
  unsigned int m_openLoopCalls;
  std::vector<char> m_seen;
};

END_VISP_NAMESPACE

#endif
