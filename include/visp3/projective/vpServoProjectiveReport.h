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
  \file vpServoProjectiveReport.h
  \brief What the last vpServoProjective::computeControlLaw() did: status, features' states, e, J, gain, damping,
  saturation, joint-limit avoidance, path following.
*/

#ifndef _vpServoProjectiveReport_h_
#define _vpServoProjectiveReport_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpServoArmFollowing.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>
#include <visp3/projective/vpServoFeatureHealth.h>
#include <visp3/projective/vpServoJointLimitAvoidance.h>
#include <visp3/projective/vpServoProjectiveData.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoProjectiveReport
  \ingroup group_projective
  \brief The diagnostics of one successful vpServoProjective::computeControlLaw(), read through
  vpServoProjective::getReport() (\ref servo_task_report). A call that throws leaves the report of the call before.

  Sizes: \f$ N \f$ features (addFeature() order), \f$ n \f$ joints. Units: the task error in the unit of
  vpServoProjective::setErrorUnit() (pixels by default, getErrorScale() pixels per unit), joint values in the model's
  unit (radians or the encoder's length unit). Before the first call: SERVO_RUNNING, no feature, empty matrices.
  Every getter is const and writes nothing; the matrices are computed on demand from what the call kept.

  \code
  task.computeControlLaw(q);
  const vpServoProjectiveReport &r = task.getReport();
  if (r.getStatus() == vpServoProjectiveReport::SERVO_STOPPED) { for (i...) std::cout << r.getFeatureState(i); }
  double mu = r.getDamping(); vpMatrix J = r.getTaskJacobian();
  \endcode
*/
class VISP_EXPORT vpServoProjectiveReport
{
public:
  //! What happened to feature i at the call (see vpServoFeatureHealth::vpFeatureState).
  typedef vpServoFeatureHealth::vpFeatureState vpFeatureState;
  //! Joint values (n x 1) without heap allocation.
  typedef vpServoProjectiveData::JointVector JointVector;

  //! Outcome of a computeControlLaw() (\ref servo_task_features); vpServoProjective::vpServoStatus is this type.
  enum vpServoStatus {
    SERVO_RUNNING,        //!< Every feature used.
    SERVO_REDUCED,        //!< Some features set aside, the remaining ones keep rank n: the task continues on them.
    SERVO_STOPPED,        //!< The active features no longer constrain every joint (rank < n): \f$ \dot q = 0 \f$.
    SERVO_NO_PLAN,        //!< Path planning is on and no plan exists for the target (getPathPlanner() says why):
                          //!< \f$ \dot q = 0 \f$.
    SERVO_MODEL_MISMATCH, //!< Every usable feature disagrees with the model's prediction on consecutive calls (a
                          //!< moved camera; vpServoModelMismatch): \f$ \dot q = 0 \f$; re-register the rig.
    SERVO_OPEN_LOOP,      //!< Planned task: the active features no longer constrain every joint, and the features
                          //!< set aside are replaced by the model's predictions at the measured joints, for at most
                          //!< vpProjectivePathPlanner::setMaxOpenLoopTime() (\ref servo_task_open_loop).
    //! The arm did not make the commanded joint motion on consecutive calls (a velocity sent in another frame, a
    //! robot not in velocity control, a joint at a limit, a clipped velocity; vpServoArmFollowing):
    //! \f$ \dot q = 0 \f$ until vpServoProjective::getArmFollowing().reset().
    SERVO_ARM_NOT_FOLLOWING
  };

  //! The report before any call: SERVO_RUNNING, no feature.
  vpServoProjectiveReport();

  /*! \name Outcome */
  //@{
  //! The status of the call.
  vpServoStatus getStatus() const { return m_status; }
  //! A status's name and what it means (as vpServoProjective::print() gives it), e.g. for a program's log when it
  //! stops.
  static std::string toString(vpServoStatus status);
  //! Number of features \f$ N \f$ of the call.
  unsigned int getNumberOfFeatures() const { return static_cast<unsigned int>(m_states.size()); }
  //! State of feature \e i at the call. \exception vpProjectiveException (dimensionError) if \f$ i \ge N \f$.
  vpFeatureState getFeatureState(unsigned int i) const;
  //! Number of features the law used (FEATURE_ACTIVE, or predicted in SERVO_OPEN_LOOP).
  unsigned int getNumberOfActiveFeatures() const { return m_data.getNumberOfActiveFeatures(); }
  //! True if the call followed the planned path (before the final law (47)).
  bool isFollowingPath() const { return m_following; }
  //! Consecutive calls that ended in SERVO_OPEN_LOOP, up to this one (0 when it did not).
  unsigned int getOpenLoopCalls() const { return m_openLoopCalls; }
  //! The arm-following check after the call: its settings, its verdict and, after SERVO_ARM_NOT_FOLLOWING, its cause
  //! and each joint's motion (vpServoArmFollowing::getDiagnosis()). The task's report reads the task's own check (a
  //! reset() or a setting of vpServoProjective::getArmFollowing() shows at once); a copy of the report holds a copy of
  //! it, kept after the task is gone.
  const vpServoArmFollowing &getArmFollowing() const { return m_arm.get(); }
  //@}

  /*! \name The law */
  //@{
  //! Gain \f$ \lambda \f$ used (per call; 0 when \f$ \dot q = 0 \f$ was forced: SERVO_STOPPED, ...).
  double getLambda() const { return m_lambda; }
  //! Damping \f$ \mu \f$ (pixels per joint unit) used (0 away from singularities and when stopped).
  double getDamping() const { return m_damping; }
  //! True if \f$ \dot q \f$ was scaled down by the velocity saturation.
  bool isSaturated() const { return m_saturated; }
  //! Secondary-task velocity \f$ \dot q_2 \f$ (n x 1, joint units per call, before the final saturation); empty
  //! before the first call.
  vpColVector getJointLimitVelocity() const;
  /*!
    Large projection operator \f$ P \f$ (n x n, no unit) of the call's \f$ J \f$ and \f$ e \f$, with the settings of
    the call (vpServoJointLimitAvoidance::computeLargeProjectionOperator()).
    \exception vpProjectiveException (notInitializedError) before the first call.
  */
  vpMatrix getLargeProjectionOperator() const;
  //@}

  /*! \name The task \f$ e \f$, \f$ J \f$ (rows of the features set aside are zero) */
  //@{
  //! \f$ e = s - s^* \f$ (4N x 1, unit of setErrorUnit()), rows \f$ (u, v, u', v') \f$ per feature.
  vpColVector getError() const;
  //! \f$ J \f$ (4N x n, unit of setErrorUnit() per joint unit), eq. (46) per feature.
  vpMatrix getTaskJacobian() const;
  //! Singular values of \f$ J \f$ (n x 1, decreasing, unit of getTaskJacobian()), as vpServo::getTaskSingularValues();
  //! empty before the first call. An SVD on demand.
  vpColVector getTaskSingularValues() const;
  //! \f$ \sigma_{max} / \sigma_{min} \f$ of \f$ J \f$ (infinite if rank deficient, 0 before the first call), from the
  //! eigenvalues of \f$ J^T J \f$ on demand.
  double getConditionNumber() const;
  //! \f$ \sigma_{min}(J D^{-1}) / \sigma_{max}(J D^{-1}) \f$, \f$ D \f$ the column norms of \f$ J \f$: what the rank
  //! tolerance (vpServoFeatureHealth::setRankTolerance()) is compared with (0 if a column is below it). On demand.
  double getSingularValueRatio() const;
  //! Pixels per unit of the error at the call: 1 (ERROR_PIXELS) or the focal length (ERROR_NORMALIZED).
  double getErrorScale() const { return m_errorScale; }
  //! What the call computed once and every part read: \f$ H(q) \f$, points, \f$ J \f$ and \f$ e \f$ in pixels.
  const vpServoProjectiveData &getData() const { return m_data; }
  //@}

private:
  friend class vpServoProjective; // fills it
  typedef vpServoProjectiveData::JointMatrix JointMatrix;

  //! \f$ \sigma_{min}(J D^{-1}) / \sigma_{max}(J D^{-1}) \f$ from \f$ J^T J \f$, 0 if a column norm is below
  //! \e tolerance times the largest: the rank test of a reduced task.
  static double singularValueRatio(const JointMatrix &JtJ, double tolerance);

  vpServoProjectiveData m_data;         // H(q), joint motions, points, J, e, J^T J, J^T e: computed once
  vpServoStatus m_status;               // outcome
  double m_lambda;                      // gain used
  double m_damping;                     // mu used
  bool m_saturated;                     // scaled down by the saturation
  JointVector m_qdot2;                  // secondary task
  bool m_following;                     // followed the path
  unsigned int m_openLoopCalls;         // consecutive open-loop calls
  double m_errorScale;                  // pixels per unit of error
  double m_rankTolerance;               // the rank test's tolerance
  std::vector<vpFeatureState> m_states; // per feature
  // The settings of the call that P depends on: the law's pseudo-inverse threshold, the limits' thresholds on ||e||.
  double m_pseudoInverseThreshold;
  double m_largeProjectionThresholds[2];
  //! The arm-following check: the task's part read in place (no copy per call) while the report is the task's, a copy
  //! of it in a copy of the report.
  class vpArmFollowingView
  {
  public:
    vpArmFollowingView() : m_shared(nullptr), m_owned() {}
    vpArmFollowingView(const vpArmFollowingView &other) : m_shared(nullptr), m_owned(other.get()) {}
    vpArmFollowingView &operator=(const vpArmFollowingView &other)
    {
      if (this != &other) {
        m_owned = other.get();
        m_shared = nullptr;
      }
      return *this;
    }
    void share(const vpServoArmFollowing &arm) { m_shared = &arm; }
    const vpServoArmFollowing &get() const { return m_shared != nullptr ? *m_shared : m_owned; }

  private:
    const vpServoArmFollowing *m_shared; // the task's part, or nullptr
    vpServoArmFollowing m_owned;
  };
  vpArmFollowingView m_arm; // the arm-following check after the call
};

END_VISP_NAMESPACE

#endif
