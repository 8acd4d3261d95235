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
  \file vpServoProjective.h
  \brief Non-metric joint-space visual servoing from an uncalibrated stereo rig.
*/

#ifndef _vpServoProjective_h_
#define _vpServoProjective_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <iostream>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectivePathFollowing.h>
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoControlLaw.h>
#include <visp3/projective/vpServoFeatureHealth.h>
#include <visp3/projective/vpServoModelMismatch.h>
#include <visp3/projective/vpServoProjectiveReport.h>
#include <visp3/projective/vpServoRigRefinement.h>
#include <visp3/vs/vpAdaptiveGain.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoProjective
  \ingroup group_projective
  \brief The non-metric visual servo of Ruf & Horaud (section 6): joint velocities from the image error of stereo
  point features, through the projective kinematic model of the arm. No intrinsics, rig geometry, robot geometry or
  hand-eye transform enter it.

  For \f$ N \f$ stereo points the task error is \f$ e = s - s^* \f$ (4N x 1, pixels, rows \f$ (u, v, u', v') \f$ per
  point), and the task Jacobian \f$ J \f$ (4N x n, pixels per joint unit) stacks, for each point, eq. (46) at the
  current joint values \f$ q \f$ (n x 1, the model's joint values: radians or the encoder's length unit) and the
  point \f$ M \f$ (4x1, projective frame of the rig) triangulated from the current features:
  \f[ J_i = \begin{bmatrix} J_C(P M_i) P \\ J_C(P' M_i) P' \end{bmatrix} J_H(q, M_i). \f]
  The control law (47) is \f$ \dot q = -\lambda J^+ e \f$, with the pseudo-inverse damped near singular
  configurations: \f$ J^+ = (J^T J + \mu^2 I)^{-1} J^T \f$, \f$ \mu^2 = \mu_{max}^2 (1 - (\sigma_{min} /
  \sigma_0)^2) \f$ when the smallest singular value \f$ \sigma_{min} \f$ of J falls below \f$ \sigma_0 \f$, 0 otherwise,
  then saturated (vpServoControlLaw, getControlLaw()).

  Like vpServo, the task keeps references to the features: the loop updates them and calls computeControlLaw()
  (\ref page_porting maps vpServo's calls to this task's). Each iteration computes its data once
  (vpServoProjectiveData), which every part of the task reads (\ref servo_task_data).

  Each feature gets a state (vpServoFeatureHealth); the rows of the features set aside are zero, and getStatus()
  tells whether the active ones still constrain every joint (\ref servo_task_features); getReport() gives the rest
  of the last call. Every getter is const and writes nothing: several threads may read one task while none computes.

  \code
  task.setRobot(robot); task.setLambda(0.5);
  for (unsigned int i = 0; i < 4; ++i) task.addFeature(s[i], s_star[i]);
  while (!converged) { // track, s[i].buildFrom(ipLeft[i], ipRight[i]), task.setFeatureTracked(i, found[i])
    vpColVector qdot = task.computeControlLaw(q); // SERVO_STOPPED: getReport().getFeatureState(i) says why
  }
  \endcode
*/
class VISP_EXPORT vpServoProjective
{
public:
  //! What happened to feature i at the last computeControlLaw() (see vpServoFeatureHealth::vpFeatureState).
  typedef vpServoFeatureHealth::vpFeatureState vpFeatureState;
  //! Used by the control law.
  static constexpr vpFeatureState FEATURE_ACTIVE = vpServoFeatureHealth::FEATURE_ACTIVE;
  //! Set aside: setFeatureTracked(i, false).
  static constexpr vpFeatureState FEATURE_NOT_TRACKED = vpServoFeatureHealth::FEATURE_NOT_TRACKED;
  //! Set aside: outside the image window of setImageSize() in the left or right image.
  static constexpr vpFeatureState FEATURE_OUT_OF_IMAGE = vpServoFeatureHealth::FEATURE_OUT_OF_IMAGE;
  //! Set aside: a coordinate of \f$ s_i \f$ or \f$ s^*_i \f$ is NaN or infinite.
  static constexpr vpFeatureState FEATURE_NOT_FINITE = vpServoFeatureHealth::FEATURE_NOT_FINITE;
  //! Set aside: farther than getFeatureHealth().setOutlierThreshold() from its epipolar line or its prediction.
  static constexpr vpFeatureState FEATURE_OUTLIER = vpServoFeatureHealth::FEATURE_OUTLIER;

  //! Outcome of the last computeControlLaw() (\ref servo_task_features): see vpServoProjectiveReport::vpServoStatus.
  typedef vpServoProjectiveReport::vpServoStatus vpServoStatus;
  static constexpr vpServoStatus SERVO_RUNNING = vpServoProjectiveReport::SERVO_RUNNING; //!< Every feature used.
  //! Some features set aside, the others keep rank n.
  static constexpr vpServoStatus SERVO_REDUCED = vpServoProjectiveReport::SERVO_REDUCED;
  //! Rank < n: \f$ \dot q = 0 \f$.
  static constexpr vpServoStatus SERVO_STOPPED = vpServoProjectiveReport::SERVO_STOPPED;
  //! No plan for the target: \f$ \dot q = 0 \f$.
  static constexpr vpServoStatus SERVO_NO_PLAN = vpServoProjectiveReport::SERVO_NO_PLAN;
  //! The features disagree with the model (a moved camera): \f$ \dot q = 0 \f$.
  static constexpr vpServoStatus SERVO_MODEL_MISMATCH = vpServoProjectiveReport::SERVO_MODEL_MISMATCH;
  //! Planned task on the model's predictions of the features set aside.
  static constexpr vpServoStatus SERVO_OPEN_LOOP = vpServoProjectiveReport::SERVO_OPEN_LOOP;
  //! The arm does not make the commanded motion (getArmFollowing()): \f$ \dot q = 0 \f$.
  static constexpr vpServoStatus SERVO_ARM_NOT_FOLLOWING = vpServoProjectiveReport::SERVO_ARM_NOT_FOLLOWING;

  //! The unit of the task error \f$ e \f$ that the gain sees (see setErrorUnit()).
  enum vpErrorUnit {
    ERROR_PIXELS,    //!< Pixels (the default).
    ERROR_NORMALIZED //!< Pixels divided by a focal length in pixels, the unit of vpServo's \f$ x = (u - u_0)/p_x \f$.
  };

  //! A task without robot or feature: gain 0.5, damping (1, 10), no saturation, no check, no joint limit.
  vpServoProjective();

  /*! \name Model and gain */
  //@{
  /*!
    The acquired projective model of the arm (calibrated or loaded). The task keeps a reference and attaches itself:
    the robot tells it of a new model or rig (\ref servo_task_data); a destroyed robot leaves the task without one.
    \exception vpProjectiveException (notInitializedError) if the model is not acquired.
  */
  void setRobot(const vpProjectiveRobot &robot);
  /*!
    The same, with leave to refine the robot's re-registered rig with the task's own frames (getRigRefinement()): a
    task given a robot it may not change never refines.
    \exception vpProjectiveException (notInitializedError) if the model is not acquired.
  */
  void setRobot(vpProjectiveRobot &robot);
  //! Constant gain \f$ \lambda > 0 \f$ (per second; per call with the default period of 1 s).
  //! \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if not positive and finite.
  void setLambda(double lambda);
  //! Adaptive gain (vpAdaptiveGain) of \f$ \|e\|_\infty \f$, or of \f$ \|J^+ e\|_\infty \f$
  //! (getControlLaw().setAdaptiveGainInput()).
  void setLambda(const vpAdaptiveGain &lambda);
  /*!
    Adaptive gain from its value at zero error, at infinite error and its slope at zero (per pixel).
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) unless
    \f$ gainAtZero \ge gainAtInfinity > 0 \f$, \f$ slopeAtZero \ge 0 \f$, all finite.
  */
  void setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero);
  /*!
    The unit of \f$ e \f$ for its getters, print(), the large projection thresholds and an adaptive gain: pixels
    (ERROR_PIXELS, default) or \f$ (s - s^*) / f \f$ (ERROR_NORMALIZED), \f$ f \f$ = \e focalLength (pixels) if
    positive, else estimated from the model (\ref servo_task_error_unit). The control law does not depend on it.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if \e focalLength is negative or not
    finite; (notInitializedError, estimationFailedError) if the estimate is needed and the model gives none. The
    unit is then unchanged. The pixels per unit: getControlLaw().getErrorScale().
  */
  void setErrorUnit(vpErrorUnit unit, double focalLength = 0.0);
  /*!
    Settling (default off): once converged, the gain becomes \f$ \lambda / (1 + \lambda k) \f$ at the \f$ k \f$-th
    settled call (vpServoSettling): the joint error falls as \f$ 1/\sqrt{k} \f$ below the single-frame floor; the
    full gain returns when an F-test at \f$ 10^{-4} \f$ sees a real error (\ref servo_task_settling). Its state:
    getControlLaw().getSettling().
  */
  void setSettling(bool settling);
  //@}

  /*! \name Control law (vpServoControlLaw: getControlLaw()) */
  //@{
  /*!
    The time \e T (seconds) between two calls of computeControlLaw() (default 1: one call is one step of the
    discrete law), for the control law and the arm-following check. The gain and the saturation are per second; what
    acts per call (path samples, rehearsal, settling) is scaled by \f$ T \f$ (\ref servo_task_period).
    \exception vpProjectiveException (invalidValueError) if not positive and finite; the period is then unchanged.
  */
  void setControlPeriod(double seconds);
  /*!
    Law (47) and its settings: setLambda()'s gain and its input (setAdaptiveGainInput()), setDamping(),
    setMaxJointVelocity() (per second), setPseudoInverseThreshold(), the joint-limit avoidance
    (getJointLimitAvoidance(): thresholds of the large projection operator, clearJointLimits()), the error's scale
    (setErrorUnit()) and the settling state (getSettling()). The planner rehearses a copy of it.
  */
  vpServoControlLaw &getControlLaw() { return m_control; }
  //@}

  /*! \name Feature checks (forwarded to vpServoFeatureHealth) */
  //@{
  /*!
    Image window (pixels): FEATURE_OUT_OF_IMAGE outside \f$ [b, w - 1 - b] \times [b, h - 1 - b] \f$ in either image
    (\e border \f$ b \f$); 0 x 0 (default) disables it (vpServoFeatureHealth::setImageSize()).
    \exception vpProjectiveException if one side only is 0, or \e border is negative, not finite or leaves no pixel.
  */
  void setImageSize(unsigned int width, unsigned int height, double border = 0.0);
  //! The tracker's verdict on feature \e i (addFeature() order; default true): false sets it aside
  //! (FEATURE_NOT_TRACKED) until set back. \exception vpProjectiveException (dimensionError) on a bad index.
  void setFeatureTracked(unsigned int i, bool tracked);
  //@}

  /*! \name Model mismatch (forwarded to vpServoModelMismatch) and re-registered rigs */
  //@{
  /*!
    The model-mismatch check (vpServoModelMismatch; default threshold 5 px, 0: off): SERVO_MODEL_MISMATCH,
    \f$ \dot q = 0 \f$, when every usable feature (at least two) lies farther than its threshold from the image of its
    remembered point moved by \f$ H(q) \f$, on 2 consecutive calls; it takes precedence over every status but
    SERVO_ARM_NOT_FOLLOWING. Its settings (setThreshold()) and its last distances.
  */
  vpServoModelMismatch &getModelMismatch() { return m_mismatch; }
  /*!
    The desired value (4x1, pixels) the task uses for feature \e i: the user's \f$ s^*_i \f$, or after the robot
    told of a re-registered rig (vpProjectiveRobot::updateRig()) the new rig's image of the point \f$ s^*_i \f$
    showed (the user's feature is not rewritten): the same joint target. \exception vpProjectiveException on a bad i.
  */
  vpColVector getDesiredFeature(unsigned int i) const;
  /*!
    Refinement of a re-registered rig with the task's own frames (vpServoRigRefinement::setRefinement(); default on,
    every 40 calls, 3 times): after vpProjectiveRobot::updateRig() the task refines the rig with its active features
    every period of calls that move the arm (\ref servo_meas_mismatch). Needs the robot given to setRobot() as
    modifiable and the model-mismatch check on. Its settings and its state since the last re-registration.
  */
  vpServoRigRefinement &getRigRefinement() { return m_refinement; }
  //@}

  /*! \name Joint limits (forwarded to vpServoJointLimitAvoidance) */
  //@{
  /*!
    Joint-limit avoidance as a secondary task with the large projection operator, as
    vpServo::secondaryTaskJointLimitAvoidance() (Marey and Chaumette, ICRA 2010; vpServoJointLimitAvoidance):
    \f$ \dot q = \dot q_1 + \dot q_2 \f$, saturated again (\ref servo_task_limits).
    \param qmin, qmax : limits (n x 1), \f$ q_i^{min} < q_i^{max} \f$, in the model's joint values (those of q).
    \param rho : \f$ \rho \in ]0, 1/2] \f$, relative width of the activation band at each end.
    \param rho1 : \f$ \rho_1 \in ]0, 1] \f$, where inside the band the avoidance reaches its full strength.
    \param lambdaTune : \f$ \lambda_t \in [0, 1] \f$, by how much the avoidance exceeds the primary motion.
    \exception vpProjectiveException if the sizes differ (or differ from the robot's joints), an entry is not
    finite, some \f$ q_i^{min} \ge q_i^{max} \f$, or a parameter is out of range. Nothing is changed then.
    getControlLaw().getJointLimitAvoidance().clearJointLimits() removes them.
  */
  void setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double rho = 0.1, double rho1 = 0.3,
                      double lambdaTune = 0.7);
  //@}

  /*! \name Features */
  //@{
  //! Adds a stereo point and its desired value, both kept by reference, like vpServo::addFeature().
  void addFeature(vpFeatureStereoPoint &s, vpFeatureStereoPoint &s_star);
  //! Removes every feature (getFeatureHealth().getNumberOfFeatures() counts them).
  void clearFeatures();
  //@}

  /*! \name The control law */
  //@{
  /*!
    Law (47) \f$ \dot q = -\lambda J^+ (s - s^*) \f$ on the active features, plus the joint-limit avoidance, then
    saturated; a feature set aside never throws (getStatus(), getReport()).
    \param q : joint values (n x 1), the model's (radians, or the encoder's length unit).
    \return \f$ \dot q \f$ (n x 1), joint units per call (or per second, following \f$ \lambda \f$).
    \exception vpProjectiveException if the robot or the features are missing, q has the wrong size or is not
    finite, fewer than n equations were added, the joint limits do not match the robot, or an active feature lies
    on a camera's focal plane. The task is then left as it was.
  */
  vpColVector computeControlLaw(const vpColVector &q);
  //! The same on Eigen types, without allocation once the sizes are known.
  void computeControlLaw(const vpProjectiveRobot::JointVector &q, vpProjectiveRobot::JointVector &qdot);
  /*!
    The joint values (n x 1, encoder readings) for the next computeControlLaw() without argument, as
    vpServo::set_eJe(): the Jacobian (46) is the model's at the current joints.
    \exception vpProjectiveException (nonFiniteValueError, dimensionError) on a non-finite entry or a wrong size.
  */
  void setJointPositions(const vpColVector &q);
  //! computeControlLaw(q) at the joints of the last setJointPositions(), which serves one call. \exception
  //! vpProjectiveException (notInitializedError) without new joints; otherwise as computeControlLaw(q).
  vpColVector computeControlLaw();
  //@}

  /*! \name What the last computeControlLaw() did */
  //@{
  //! \f$ e = s - s^* \f$ (4N, in the unit of setErrorUnit(): pixels by default) of the last computeControlLaw(); the
  //! 4 rows of a feature set aside are zero.
  vpColVector getError() const { return last().getError(); }
  //! Outcome of the last computeControlLaw() (SERVO_RUNNING before the first one); its name and meaning:
  //! vpServoProjectiveReport::toString().
  vpServoStatus getStatus() const { return last().getStatus(); }
  //! Everything else the last computeControlLaw() did: features' states, J, gain, damping, saturation, ...
  const vpServoProjectiveReport &getReport() const { return last(); }
  //@}

  /*! \name Global servoing: plan with the acquired model, follow the plan, finish with law (47) */
  //@{
  /*!
    Path planning (default off: law (47) alone). On, computeControlLaw() plans once per target with
    vpProjectivePathPlanner from the features' points \f$ H(q)^{-1} M \f$, follows the path one sample per call (the
    step plus law (47) on the error to the sample's predicted images), then law (47) finishes. No plan:
    SERVO_NO_PLAN and \f$ \dot q = 0 \f$ (\ref servo_task_planning).
  */
  void setPathPlanning(bool planning);
  //! The joint values (n x 1) the plan ends at: the inverse kinematics of \f$ s^* \f$.
  //! \exception vpProjectiveException (notInitializedError) when no plan was found.
  vpColVector getPlannedTarget() const;
  /*!
    The planner: its settings (setMaxJointStep(), setMaxExcursion(), setNumberOfStarts()), those of the path following
    (setPathFollowingGain(), setMaxOpenLoopTime(): \ref servo_task_open_loop) and its last plan (target, branches,
    path, description).
  */
  vpProjectivePathPlanner &getPathPlanner() { return m_path.getPlanner(); }
  //@}

  /*! \name The parts of the task */
  //@{
  //! The feature checks, their settings (setOutlierThreshold(), setRankTolerance(); setImageSize() and
  //! setFeatureTracked() on the task) and their last verdicts: active features, epipolar and prediction distances.
  vpServoFeatureHealth &getFeatureHealth() { return m_health; }
  //! Arm-following check (\ref servo_task_following): settings, reset(); verdict: getReport().getArmFollowing().
  vpServoArmFollowing &getArmFollowing() { return m_follow; }
  //@}

  //! Prints the task in the layout of vpServo::print(vpServo::ALL) (J in place of Ls), then the status, each
  //! feature's state and distances, and the settings.
  void print(std::ostream &os = std::cout) const;

private:
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;
  typedef vpProjectiveArmModel::JointVector JointVector;
  //! What one computeControlLaw() computes (vpServoProjectiveReport); kept only when it succeeds.
  typedef vpServoProjectiveReport vpIteration;
  //! The robot of setRobot(), attached: it tells the task of a new model or rig (vpProjectiveRobot::vpListener).
  struct vpRobotLink : public vpProjectiveRobot::vpListener {
    const vpProjectiveRobot *robot = nullptr;
    vpProjectiveRobot *modifiable = nullptr; // the same robot, if given modifiable (the rig refinement)
    bool modelChanged = false;               // told since the task last took it into account
    bool rigChanged = false;
    vpRobotLink() = default;
    vpRobotLink(const vpRobotLink &other);
    vpRobotLink &operator=(const vpRobotLink &other);
    ~vpRobotLink() override;
    void set(const vpProjectiveRobot *r);
    void robotModelChanged(bool rigOnly) override;
    void robotDestroyed() override { robot = nullptr, modifiable = nullptr; }
  };

  void check(const char *method) const;
  void checkFeatureIndex(unsigned int i, const char *method) const;
  void checkJoints(const JointVector &q, const char *method) const;
  void buildTask(const JointVector &q, vpIteration &it, const char *method);
  vpServoStatus decideStatus(const vpIteration &it) const;
  void computePrimaryVelocity(const JointVector &q, vpIteration &it, JointVector &qdot);
  void addJointLimitAvoidance(const JointVector &q, vpIteration &it, JointVector &qdot) const;
  void stop(vpIteration &it, JointVector &qdot);
  void commit();
  const vpServoProjectiveReport &last() const { return m_iterations[m_lastIteration]; }
  const Eigen::Vector4d &desired(unsigned int i) const { return m_path.getReference(i, m_effective[i]); }
  void refreshTargets();
  void computeData(const JointVector &q, vpServoProjectiveData &data) const;
  bool detectMismatch(const vpServoProjectiveData &data);
  bool openLoop(vpIteration &it);

  //! The task's copy of a desired feature (the s* it uses: m_effective).
  struct vpTarget {
    Eigen::Vector4d user = Eigen::Vector4d::Zero();  // the user's s* when last read
    Eigen::Vector4d point = Eigen::Vector4d::Zero(); // the point (model frame) that user showed through its rig
    bool hasPoint = false;                           // point is set
    bool valid = false;                              // user and m_effective are set
  };

  vpRobotLink m_link;
  std::vector<vpFeatureStereoPoint *> m_features;
  std::vector<vpFeatureStereoPoint *> m_desired;
  // Law (47): the gain and its input, the period, the damped least squares with saturation, the joint limits, the
  // error's unit; the planner rehearses a copy of it.
  vpServoControlLaw m_control;
  vpServoFeatureHealth m_health;
  vpServoModelMismatch m_mismatch;
  vpServoArmFollowing m_follow;
  std::vector<vpTarget> m_targets;
  std::vector<Eigen::Vector4d> m_effective; // per feature: the s* the task uses (the path following plans for it)
  // m_iterations[m_lastIteration]: the last successful call, read by the getters; commit() flips to the other.
  vpIteration m_iterations[2];
  unsigned int m_lastIteration;

  // setPathPlanning(): the planner, when to plan, the plan's reference, the open loop.
  vpProjectivePathFollowing m_path;
  std::vector<char> m_activeNow; // per feature: active in the iteration in progress (buildTask())

  // setErrorUnit(): the unit, the focal length given (0: estimated; the scale is the law's); setJointPositions().
  vpErrorUnit m_errorUnit;
  double m_focalLength;
  JointVector m_q;
  bool m_qFresh;
  // The generation of the task's targets (refreshTargets()) that the settling gain settles on.
  unsigned long m_targetGeneration;
  // getRigRefinement(): the refinement, and the robot's re-registrations (vpProjectiveRigUpdate::getUpdateCount())
  // taken into account.
  vpServoRigRefinement m_refinement;
  unsigned long m_rigUpdatesSeen;
};

END_VISP_NAMESPACE

#endif
