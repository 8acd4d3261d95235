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
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>
#include <visp3/projective/vpServoFeatureHealth.h>
#include <visp3/projective/vpServoJointLimitAvoidance.h>
#include <visp3/projective/vpServoModelMismatch.h>
#include <visp3/projective/vpServoSettling.h>
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
  then saturated (vpServoDampedLeastSquares, getDampedLeastSquares()).

  Like vpServo, the task keeps references to the features: the loop updates them and calls computeControlLaw().
  Coming from vpServo: \ref page_porting maps each of its calls to this task's (and says which have no meaning here
  and why): setJointPositions() plays set_eJe(), setAdaptiveGainInput() evaluates an adaptive gain as vpServo does,
  setErrorUnit() gives its normalised error, print() its layout.

  <b>Lost features, outliers and singularities.</b> At every computeControlLaw() each feature \f$ i \f$ gets a state
  (getFeatureState(), vpServoFeatureHealth): FEATURE_NOT_TRACKED (setFeatureTracked()), FEATURE_NOT_FINITE,
  FEATURE_OUT_OF_IMAGE (setImageSize()), FEATURE_OUTLIER (setOutlierThreshold()), tested in this order, or
  FEATURE_ACTIVE.

  Features that are not active are set aside: their 4 rows of \f$ e \f$ and \f$ J \f$ are set to zero, so that
  getError() and getTaskJacobian() keep their sizes \f$ 4N \f$ and \f$ 4N \times n \f$, and the control law,
  its damping, its gain and getConditionNumber() all act on the reduced task (zero rows change neither
  \f$ J^T J \f$ nor \f$ J^T e \f$). getStatus() then tells what happened:
  - SERVO_RUNNING: every feature is active. Whatever the rank of \f$ J \f$: a singular task with all its features
    (an arm singularity, a repeated feature) is left to the damped least squares;
  - SERVO_REDUCED: some features are set aside and the active ones still constrain every joint; the task goes on
    with them;
  - SERVO_STOPPED: some features are set aside and the active ones no longer constrain every joint; then
    \f$ \dot q = 0 \f$ exactly. The test is scale-aware: with \f$ D = \mathrm{diag}(\|J_{:,k}\|) \f$ the
    column norms of the reduced \f$ J \f$, the task stops when \f$ \sigma_{min}(J D^{-1}) < \tau \,
    \sigma_{max}(J D^{-1}) \f$ (\f$ \tau \f$: setRankTolerance(), default \f$ 10^{-6} \f$), which depends
    neither on the pixel unit nor on the joint units (radians, metres), when a column is below \f$ \tau \f$ times the
    largest, or when fewer than \f$ n/3 \f$ points are active (a stereo point gives at most 3 independent equations:
    its 4 x 4 \f$ [J_C(P M) P; J_C(P' M) P'] \f$ annihilates \f$ M \f$). Two points never suffice for 6 joints: the
    rotation about the line through them moves neither (rank 5). Values measured in the simulator:
    \ref page_servo_measurements.

  <b>Joint limits.</b> setJointLimits() adds ViSP's joint-limit avoidance (Marey and Chaumette 2010) as a secondary
  task projected with the large projection operator, which acts even when \f$ J \f$ has full column rank
  (vpServoJointLimitAvoidance).

  Every getter is const and reads the state left by the last computeControlLaw() without writing anything: several
  threads may read one task while none computes.

  \code
  vpServoProjective task;
  task.setRobot(robot);
  task.setLambda(0.5);
  for (unsigned int i = 0; i < 4; ++i)
    task.addFeature(s[i], s_star[i]);
  task.setImageSize(640, 480, 5); // optional checks
  task.setOutlierThreshold(5);
  task.setJointLimits(qmin, qmax);
  while (!converged) {
    // ... track the points, then s[i].buildFrom(ipLeft[i], ipRight[i]) and task.setFeatureTracked(i, found[i]);
    vpColVector qdot = task.computeControlLaw(q);
    if (task.getStatus() == vpServoProjective::SERVO_STOPPED) {
      // qdot = 0: too few features left to constrain the arm; recover them (getFeatureState(i) tells why)
    }
    // send qdot to the robot
  }
  task.print();
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
  //! Set aside: farther than setOutlierThreshold() from its epipolar line or its prediction.
  static constexpr vpFeatureState FEATURE_OUTLIER = vpServoFeatureHealth::FEATURE_OUTLIER;

  //! Outcome of the last computeControlLaw().
  enum vpServoStatus {
    SERVO_RUNNING,       //!< Every feature used.
    SERVO_REDUCED,       //!< Some features set aside, the remaining ones keep rank n: the task continues on them.
    SERVO_STOPPED,       //!< The active features no longer constrain every joint (rank < n): \f$ \dot q = 0 \f$.
    SERVO_NO_PLAN,       //!< Path planning is on and no plan exists for the target (getPathPlanner() says why):
                         //!< \f$ \dot q = 0 \f$.
    SERVO_MODEL_MISMATCH //!< Every usable feature disagrees with the model's prediction, over consecutive
                         //!< iterations (a moved camera, slipped markers; see setModelMismatchThreshold()):
                         //!< \f$ \dot q = 0 \f$. Re-register the rig (vpProjectiveRobot::updateRig()); a model
                         //!< that never fit since its acquisition may have the wrong rig mounting (print() says so).
  };

  /*!
    The unit of the task error \f$ e \f$ that the gain sees (see setErrorUnit()).
  */
  enum vpErrorUnit {
    ERROR_PIXELS,    //!< Pixels (the default).
    ERROR_NORMALIZED //!< Pixels divided by a focal length in pixels, the unit of vpServo's \f$ x = (u - u_0)/p_x \f$.
  };

  /*!
    What an adaptive gain is a function of (see setAdaptiveGainInput()).
  */
  enum vpGainInput {
    GAIN_INPUT_ERROR,         //!< \f$ \|e\|_\infty \f$ in the unit of setErrorUnit() (the default).
    GAIN_INPUT_JOINT_VELOCITY //!< \f$ \|J^+ e\|_\infty \f$ (joint units): what vpServo evaluates its gain on.
  };

  //! A task without robot or feature: gain 0.5, damping (1, 10), no saturation, no check, no joint limit.
  vpServoProjective();

  /*! \name Model and gain */
  //@{
  /*!
    The acquired projective model of the arm (calibrated or loaded). The task keeps a reference: the robot must
    outlive it.
    \exception vpProjectiveException (notInitializedError) if the model is not acquired.
  */
  void setRobot(const vpProjectiveRobot &robot);
  /*!
    Constant gain \f$ \lambda > 0 \f$ (per call, or per second when \f$ \dot q \f$ is sent as a velocity).
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if it is not positive and finite.
  */
  void setLambda(double lambda);
  /*!
    Adaptive gain (see vpAdaptiveGain): by default a function of the infinity norm of the error \f$ e \f$, in the unit
    of setErrorUnit() (pixels by default); setAdaptiveGainInput(GAIN_INPUT_JOINT_VELOCITY) evaluates it as vpServo
    does, on \f$ \|J^+ e\|_\infty \f$.
  */
  void setLambda(const vpAdaptiveGain &lambda);
  /*!
    Adaptive gain from its value at zero error, at infinite error and its slope at zero (per pixel).
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) unless
    \f$ gainAtZero \ge gainAtInfinity > 0 \f$, \f$ slopeAtZero \ge 0 \f$, all finite.
  */
  void setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero);
  /*!
    What the adaptive gain of setLambda() is evaluated on, \f$ \lambda(x) \f$:
    - GAIN_INPUT_ERROR (default): \f$ x = \|e\|_\infty \f$, in the unit of setErrorUnit();
    - GAIN_INPUT_JOINT_VELOCITY: \f$ x = \|J^+ e\|_\infty \f$, the joint velocity of a unit gain (radians or the
      prismatic joints' unit, whatever the image unit), with \f$ J^+ = (J^T J)^{-1} J^T \f$ (\f$ x = \infty \f$,
      hence the gain at infinity, if \f$ J^T J \f$ is singular). This is what vpServo does: ViSP 3.5's
      vpServo::computeControlLaw() sets \f$ e_1 = J_1^+ e \f$ and \f$ \dot q = -\lambda(e_1)\, e_1 \f$, and
      vpAdaptiveGain::operator()(const vpColVector &) takes the infinity norm of \f$ e_1 \f$, not of the error. A
      gain tuned on a joint-space vpServo program (EYEINHAND_L_cVe_eJe, EYETOHAND_L_cVe_eJe, ...) therefore gets
      the same argument here when the Jacobians agree; on a camera-frame program (EYEINHAND_CAMERA) its argument was
      the largest component of the camera velocity (m/s, rad/s), of the same order as the joint rates of an arm.
    Measured against vpServo on a simulated task: tests/testServoProjectiveParity.cpp.
  */
  void setAdaptiveGainInput(vpGainInput input);
  //! What the adaptive gain is evaluated on (setAdaptiveGainInput()).
  vpGainInput getAdaptiveGainInput() const { return m_gainInput; }
  /*!
    The unit of the error \f$ e \f$: getError(), getTaskJacobian(), getTaskSingularValues(), print(), the
    \f$ \|e\| \f$ of the large projection thresholds (setLargeProjectionThresholds(): vpServo's 0.1 and 0.7 are
    normalised units) and the \f$ \|e\|_\infty \f$ that an adaptive gain sees with GAIN_INPUT_ERROR.

    - ERROR_PIXELS (default): \f$ e = s - s^* \f$ in pixels.
    - ERROR_NORMALIZED: \f$ e = (s - s^*) / f \f$, \f$ f \f$ a focal length in pixels: \e focalLength if it is
      positive, else the mean \f$ \sqrt{p_x p_y} \f$ of the two cameras of the model's metric self-calibration
      (vpProjectiveRobot::getMetricStereoRig()), computed here, or at setRobot() if no robot is set yet. For a camera
      with \f$ p_x = p_y = f \f$ these are vpServo's normalised coordinates: \f$ (u - u^*)/f = x - x^* \f$ with
      \f$ x = (u - u_0)/p_x \f$: getError() is then a vpServo program's error on the same points in both images, and
      the printed norms compare (the principal point \f$ u_0 \f$ cancels in the difference; with
      \f$ p_x \neq p_y \f$ the rows are off by \f$ \sqrt{p_y/p_x} \f$ and its inverse).

    A constant gain and the control law itself do not depend on the unit: \f$ J^+ e \f$ is unchanged when
    \f$ e \f$ and \f$ J \f$ are divided by the same \f$ f \f$. The settings in pixels stay in pixels: the damping
    (\f$ \sigma_0 \f$, \f$ \mu_{max} \f$ per joint unit), the image window, the outlier and model-mismatch
    thresholds. Nothing is needed from the cameras but that one number: the intrinsics of the rig are unknown to
    the task, hence the estimate.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if \e focalLength is negative or not
    finite; (notInitializedError, estimationFailedError) if the estimate is needed and the model gives none (the
    message says to give \e focalLength). The unit is then unchanged.
  */
  void setErrorUnit(vpErrorUnit unit, double focalLength = 0.0);
  //! The unit of setErrorUnit().
  vpErrorUnit getErrorUnit() const { return m_errorUnit; }
  //! Pixels per unit of the error: 1 for ERROR_PIXELS, the focal length \f$ f \f$ for ERROR_NORMALIZED.
  double getErrorScale() const { return m_errorScale; }
  /*!
    Settling (default off): once converged, the gain of law (47) decreases as \f$ \lambda / (1 + \lambda k) \f$ at
    the \f$ k \f$-th settled call (vpServoSettling), so that the joints become the running mean of the frames'
    estimates of the target instead of chasing each frame's noise: at rest, the joint error falls as
    \f$ 1/\sqrt{k} \f$ below the single-frame floor, down to what \f$ s^* \f$ allows (teach it from several
    frames: vpFeatureStereoPoint::buildFrom(const std::vector<vpImagePoint> &, const std::vector<vpImagePoint> &)).
    Converged means that the error a joint motion explains is within the noise of one frame (the noise estimated from
    what no joint motion explains: no setting), on 2 consecutive calls; the convergence from far is the law's, as
    off. The full gain comes back at once when the explained error is no longer noise (an F-test at \f$ 10^{-4} \f$:
    the target moved, the arm was bumped), and settling starts anew with another set of active features (feature
    health), another target (a user's \f$ s^* \f$, a re-registered rig), after a stop (SERVO_STOPPED,
    SERVO_MODEL_MISMATCH, SERVO_NO_PLAN) and while a planned path is followed. The gain it gives is what
    getLambda() reports and what the joint-limit avoidance sees.

    Off by default: law (47) as is, vpServo's constant gain, and a velocity proportional to the error whatever its
    history. Settling assumes a target at rest: a target that moves slowly (tracking), below the F-test, is followed
    with the lag of an average over up to 100 frames; turn it on to hold a static pose at the best accuracy the
    cameras give (measured: \ref servo_meas_settling).
  */
  void setSettling(bool settling);
  //! True if settling is on (setSettling()).
  bool getSettling() const { return m_settling.isEnabled(); }
  //! True if the last computeControlLaw() used the settling gain.
  bool isSettled() const { return m_settling.isSettled(); }
  //! The settling gain's state: settled calls, noise estimate, last test statistic.
  const vpServoSettling &getSettlingState() const { return m_settling; }
  //@}

  /*! \name Control law (forwarded to vpServoDampedLeastSquares) */
  //@{
  /*!
    Damped least squares: below \e sigmaThreshold \f$ \sigma_0 \f$ (pixels per joint unit) for the smallest
    singular value of \f$ J \f$, the damping \f$ \mu \f$ rises to \e maxDamping \f$ \mu_{max} \f$ (pixels per joint
    unit). Defaults: 1 and 10. See vpServoDampedLeastSquares::setDamping().
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if a value is negative or not finite.
  */
  void setDamping(double sigmaThreshold, double maxDamping);
  /*!
    Velocity saturation at \e qdotMax (joint units per second, i.e. per control period when that is 1 s: see
    setControlPeriod()), keeping the direction of \f$ \dot q \f$; 0 (the default) disables it. See
    vpServoDampedLeastSquares::setMaxJointVelocity().
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if it is negative or not finite.
  */
  void setMaxJointVelocity(double qdotMax);
  /*!
    The time \e T (seconds, > 0) between two calls of computeControlLaw(): the period of the loop that sends
    \f$ \dot q \f$ to the robot as a velocity (vpRobot::setVelocity(), held until the next call). Default 1: one
    call is one step of the discrete law, \f$ \dot q \f$ the joint step to make before the next call (the paper's
    loop, and the study's). The task moves the arm by \f$ T \dot q \f$ per call: the gain (setLambda()) and the
    saturation (setMaxJointVelocity()) are per second, and what acts per call is scaled by \f$ T \f$: a planned
    path's samples (at most 2/3 of \f$ T \dot q_{max} \f$ apart, one per call), the rehearsal of law (47)
    (setRehearsalBudget() calls), settling (an average over calls). Law (47) alone gives the same
    \f$ \dot q = -\lambda J^+ e \f$ for any \f$ T \f$.
    \exception vpProjectiveException (invalidValueError) if not positive and finite; the period is then unchanged.
  */
  void setControlPeriod(double seconds);
  //! The control period (seconds; see setControlPeriod()).
  double getControlPeriod() const { return m_period; }
  /*!
    Relative threshold \f$ \tau_+ \f$ of the pseudo-inverse, as vpServo::setPseudoInverseThreshold() (default
    \f$ 10^{-6} \f$): singular values of \f$ J \f$ below \f$ \tau_+ \sigma_{max} \f$ count as zero in the projector
    \f$ I_n - J^+ J \f$ of the large projection operator (getLargeProjectionOperator(), setJointLimits()). It changes
    neither the primary law, which damps small singular values below \f$ \sigma_0 \f$ (setDamping()) instead of
    truncating them, nor the test that stops the task when features are set aside (setRankTolerance(), on the
    column-equilibrated \f$ J \f$). See vpServoDampedLeastSquares::setPseudoInverseThreshold().
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if it is not in [0, 1) or not finite.
  */
  void setPseudoInverseThreshold(double threshold);
  /*!
    Tolerance \f$ \tau \in (0, 1) \f$ of the rank test that stops the task when features are set aside (see the
    class documentation). Default \f$ 10^{-6} \f$, the relative threshold of vpServo's pseudo-inverse: the
    singular values come from the eigenvalues of \f$ D^{-1} J^T J D^{-1} \f$, which resolve \f$ \sigma_{min} /
    \sigma_{max} \f$ down to about \f$ \sqrt{n \epsilon} \approx 4 \cdot 10^{-8} \f$; keep \f$ \tau \f$ above.
    \exception vpProjectiveException if \e tolerance is not in (0, 1).
  */
  void setRankTolerance(double tolerance);
  //@}

  /*! \name Feature checks (forwarded to vpServoFeatureHealth) */
  //@{
  /*!
    Image size (pixels), for the detection of features that left the view: a feature is FEATURE_OUT_OF_IMAGE when
    \f$ (u, v) \f$ or \f$ (u', v') \f$ lies outside \f$ [b, w - 1 - b] \times [b, h - 1 - b] \f$ (\f$ b \f$ =
    \e border pixels, bounds included). Such a feature is detected and set aside, never extrapolated. 0 x 0 (the
    default) disables the check. See vpServoFeatureHealth::setImageSize().
    \exception vpProjectiveException if only one of \e width and \e height is 0, or \e border is negative, not finite
    or leaves no pixel (\f$ 2b > w - 1 \f$ or \f$ 2b > h - 1 \f$).
  */
  void setImageSize(unsigned int width, unsigned int height, double border = 0.0);
  /*!
    The tracker's verdict on feature \e i (index in addFeature() order): false sets it aside as FEATURE_NOT_TRACKED
    from the next computeControlLaw() on, until it is set back to true. Default: true.
    \exception vpProjectiveException (dimensionError) if \e i is not the index of a feature.
  */
  void setFeatureTracked(unsigned int i, bool tracked);
  //! The value given by setFeatureTracked() for feature \e i. \exception vpProjectiveException on a bad index.
  bool isFeatureTracked(unsigned int i) const;
  /*!
    Outlier rejection: 0 (the default) disables it. Otherwise feature \e i is FEATURE_OUTLIER when its epipolar
    distance \f$ d_F \f$ or, from its second acceptance on, its prediction distance exceeds \e pixels. The prediction
    is the projection of \f$ \hat M_i = H(q)\, H(q_l)^{-1} M_l \f$, the point \f$ M_l \f$ triangulated when the
    feature was last accepted (at joints \f$ q_l \f$) moved by the model's displacement (34) since then (formulas:
    vpServoFeatureHealth).

    The prediction catches what the epipolar test cannot: an error along the epipolar line, a tracker that jumped to
    another marker, a feature that reappears elsewhere after a loss. Choose the threshold well above the noise:
    at \f$ \sigma \f$ px per coordinate the epipolar distance has a standard deviation of about \f$ \sqrt 2 \sigma
    \f$ and the prediction distance includes the model's own prediction error (figures:
    \ref page_servo_measurements).
    \exception vpProjectiveException if \e pixels is negative or not finite.
  */
  void setOutlierThreshold(double pixels);
  //@}

  /*! \name Model mismatch (forwarded to vpServoModelMismatch) and re-registered rigs */
  //@{
  /*!
    Threshold (pixels, default 5) of the model-mismatch detection, on by default: the status is SERVO_MODEL_MISMATCH
    and \f$ \dot q = 0 \f$ when every feature that is tracked, finite and in the image (at least two) lies farther
    than \e pixels from the model's prediction, over 2 consecutive calls (vpServoModelMismatch: the prediction is the
    image of the feature's point, remembered at the zero reference from the calls where it agreed, moved by
    \f$ H(q) \f$). It takes precedence over every other status. 0 disables it.
    \exception vpProjectiveException if \e pixels is negative or not finite.
  */
  void setModelMismatchThreshold(double pixels);
  //! The threshold of setModelMismatchThreshold() (pixels; 0: off).
  double getModelMismatchThreshold() const { return m_mismatch.getThreshold(); }
  //! The detector, its settings and its last distances.
  const vpServoModelMismatch &getModelMismatch() const { return m_mismatch; }
  /*!
    The desired value (4x1, pixels \f$ (u, v, u', v') \f$) that the task uses for feature \e i: the user's
    \f$ s^*_i \f$, or after the robot's rig was re-registered (vpProjectiveRobot::updateRig()) the new rig's image of
    the point that \f$ s^*_i \f$ showed through the rig it was given with (the task's own copy: the user's feature is
    not rewritten), so that the task goes on to the same joint target. A desired feature changed by the user is
    taken as given, in the current rig's images. Read at the last computeControlLaw(); the user's value before.
    \exception vpProjectiveException (dimensionError) on a bad index.
  */
  vpColVector getDesiredFeature(unsigned int i) const;
  //@}

  /*! \name Joint limits (forwarded to vpServoJointLimitAvoidance) */
  //@{
  /*!
    Joint-limit avoidance as a secondary task, as ViSP's vpServo::secondaryTaskJointLimitAvoidance() with
    vpServo::secondaryTask(..., useLargeProjectionOperator = true) (Marey and Chaumette, ICRA 2010); formulas in
    vpServoJointLimitAvoidance. The primary velocity \f$ \dot q_1 \f$ is the damped law after the velocity
    saturation (the motion the arm really makes, vpServo's \e dq); \f$ J \f$ and \f$ e \f$ those of the active
    features; \f$ \dot q = \dot q_1 + \dot q_2 \f$ then goes through the velocity saturation again; a stopped task
    (SERVO_STOPPED) returns 0. The scheme is a continuous-time one: it needs several control periods inside the
    activation band; keep \f$ \dot q_{max}\, \Delta t \f$ well below \f$ \rho \rho_1 \Delta_i \f$
    (\ref page_servo_measurements).

    \param qmin, qmax : limits (n x 1), \f$ q_i^{min} < q_i^{max} \f$, in the model's joint values (those of q).
    \param rho : \f$ \rho \in ]0, 1/2] \f$, the relative width of the activation band at each end (0.1: the last
    10 % of the range; above 1/2 the bands of the two ends would overlap).
    \param rho1 : \f$ \rho_1 \in ]0, 1] \f$, where inside the band the avoidance reaches its full strength.
    \param lambdaTune : \f$ \lambda_t \in [0, 1] \f$, by how much the avoidance exceeds the primary motion toward
    the limit (vpServo's default 0.7).
    \exception vpProjectiveException if the sizes differ (from each other or, once setRobot() was called, from the
    number of joints), an entry is not finite, some \f$ q_i^{min} \ge q_i^{max} \f$, or a parameter is out of range.
    Nothing is changed then.
  */
  void setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double rho = 0.1, double rho1 = 0.3,
                      double lambdaTune = 0.7);
  /*!
    The error norms \f$ 0 \le e_0 < e_1 \f$ (in the unit of setErrorUnit(): pixels by default) of the switch \f$
    \bar\lambda(\|e\|) \f$ between the large projection operator \f$ P_{\|e\|} \f$ (above \f$ e_1 \f$) and the classical
    \f$ I_n - J^+ J \f$ (below \f$ e_0 \f$), see vpServoJointLimitAvoidance. Default: vpServo's 0.1 and 0.7, taken in
    that unit (vpServo's values mean normalised units: with ERROR_NORMALIZED they mean what they mean in vpServo). Raise
    \f$ e_0 \f$ above the noise level of \f$ \|e\| \f$ (about \f$ \sqrt{8N} \sigma \f$ for N points and a noisy
    \f$ s \f$ and \f$ s^* \f$ of \f$ \sigma \f$ px) if a joint may rest in its activation band at the target.
    \exception vpProjectiveException if they are not finite or not \f$ 0 \le e_0 < e_1 \f$.
  */
  void setLargeProjectionThresholds(double e0, double e1);
  //! Removes the joint limits set by setJointLimits().
  void clearJointLimits();
  //! True if setJointLimits() is in effect.
  bool hasJointLimits() const { return m_jointLimits.hasJointLimits(); }
  //@}

  /*! \name Features */
  //@{
  /*!
    Adds a stereo point and its desired value. Both are kept by reference, like vpServo::addFeature().
  */
  void addFeature(vpFeatureStereoPoint &s, vpFeatureStereoPoint &s_star);
  //! Removes every feature.
  void clearFeatures();
  //! Number of stereo point features \f$ N \f$ added.
  unsigned int getNumberOfFeatures() const { return static_cast<unsigned int>(m_features.size()); }
  //! Dimension \f$ 4N \f$ of the task: the rows of \f$ e \f$ and \f$ J \f$, as vpServo::getDimension().
  unsigned int getDimension() const { return 4 * getNumberOfFeatures(); }
  //@}

  /*! \name The control law */
  //@{
  /*!
    \f$ \dot q = -\lambda J^+ (s - s^*) \f$ at joint values \e q, on the active features (see the class
    documentation), plus the joint-limit avoidance of setJointLimits() if set, then saturated.
    A lost, non-finite, out-of-image or outlying feature never throws: it is set aside and reported by
    getFeatureState() and getStatus(); when the active features no longer constrain every joint, \f$ \dot q = 0 \f$.
    \param q : joint values (n x 1), the model's (radians, or the encoder's length unit).
    \return \f$ \dot q \f$ (n x 1), joint units per call (or per second, following \f$ \lambda \f$).
    \exception vpProjectiveException if the robot or the features are missing, q has the wrong size or is not
    finite, fewer than n equations were added, the joint limits do not match the robot, or an active feature
    cannot be triangulated (it lies on a camera's focal plane). The task is then left as it was (its getters report
    the last successful call).
  */
  vpColVector computeControlLaw(const vpColVector &q);
  //! The same on Eigen types, without allocation once the sizes are known.
  void computeControlLaw(const vpProjectiveRobot::JointVector &q, vpProjectiveRobot::JointVector &qdot);
  /*!
    The joint values (n x 1, encoder readings) for the next computeControlLaw() without argument: the counterpart of
    vpServo::set_eJe(), which a vpServo program calls at every iteration with the robot's current Jacobian. This task
    cannot do without them: its Jacobian (46) is the model's at the current joints, and nothing else gives them.
    \exception vpProjectiveException (nonFiniteValueError, dimensionError) if \e q has a non-finite entry or, once
    setRobot() was called, not one entry per joint.
  */
  void setJointPositions(const vpColVector &q);
  /*!
    computeControlLaw(q) at the joints of the last setJointPositions(), as vpServo::computeControlLaw() uses the
    Jacobian of the last set_eJe(). Each setJointPositions() serves one call: a second call without new joints throws
    rather than compute a velocity for where the arm was.
    \exception vpProjectiveException (notInitializedError) if setJointPositions() was not called since the last
    computeControlLaw() without argument; otherwise as computeControlLaw(q).
  */
  vpColVector computeControlLaw();
  //@}

  /*! \name State of the last computeControlLaw() */
  //@{
  //! \f$ e = s - s^* \f$ (4N, in the unit of setErrorUnit(): pixels by default) of the last computeControlLaw(); the
  //! 4 rows of a feature set aside are zero.
  vpColVector getError() const;
  //! \f$ J \f$ (4N x n, unit of setErrorUnit() per joint unit) of the last computeControlLaw(); the 4 rows of a
  //! feature set aside are zero.
  vpMatrix getTaskJacobian() const;
  /*!
    Singular values of the \f$ J \f$ of the last computeControlLaw() (n x 1, unit of setErrorUnit() per joint unit,
    decreasing), as
    vpServo::getTaskSingularValues(); empty before the first computeControlLaw(). Computed on demand by an SVD of
    \f$ J \f$.
  */
  vpColVector getTaskSingularValues() const;

  //! Outcome of the last computeControlLaw() (SERVO_RUNNING before the first one).
  vpServoStatus getStatus() const { return last().status; }
  //! The status's name and what it means (as print() gives it), e.g. for a program's log when it stops.
  static std::string toString(vpServoStatus status);
  /*!
    State of feature \e i (index in addFeature() order) at the last computeControlLaw() (FEATURE_ACTIVE before).
    \exception vpProjectiveException (dimensionError) on a bad index.
  */
  vpFeatureState getFeatureState(unsigned int i) const;
  //! Number of features used by the last computeControlLaw().
  unsigned int getNumberOfActiveFeatures() const { return m_health.getNumberOfActiveFeatures(); }
  /*!
    Epipolar distance \f$ d_F \f$ (pixels, see vpServoFeatureHealth) of feature \e i at the last
    computeControlLaw(); -1 if it was not evaluated (outlier rejection off, or the feature set aside before the test).
    \exception vpProjectiveException on a bad index.
  */
  double getEpipolarDistance(unsigned int i) const;
  /*!
    Prediction distance (pixels, see vpServoFeatureHealth) of feature \e i at the last computeControlLaw(); -1 if it
    was not evaluated (outlier rejection off, no earlier acceptance, the feature set aside before the test, or the
    prediction on a camera's focal plane).
    \exception vpProjectiveException on a bad index.
  */
  double getPredictionDistance(unsigned int i) const;
  /*!
    \f$ \sigma_{min}(J D^{-1}) / \sigma_{max}(J D^{-1}) \f$ of the reduced \f$ J \f$ of the last
    computeControlLaw(), \f$ D \f$ its column norms (0 if a column is below the rank tolerance times the largest):
    the quantity compared with setRankTolerance(). Computed on demand from the \f$ J^T J \f$ of that call.
  */
  double getSingularValueRatio() const;
  /*!
    Large projection operator \f$ P \f$ (n x n, see vpServoJointLimitAvoidance) of the \f$ J \f$ and \f$ e \f$ of the
    last computeControlLaw(), whether or not joint limits are set.
    \exception vpProjectiveException (notInitializedError) before the first computeControlLaw().
  */
  vpMatrix getLargeProjectionOperator() const;
  /*!
    Secondary-task velocity \f$ \dot q_2 \f$ (n x 1, before the final saturation) of the last computeControlLaw(): 0
    without joint limits, with every joint in its free interval, or when the task stopped; empty before the first
    computeControlLaw().
  */
  vpColVector getJointLimitVelocity() const;
  /*!
    Condition number \f$ \sigma_{max} / \sigma_{min} \f$ of \f$ J \f$ (reduced to the active features) at the last
    computeControlLaw() (infinite if \f$ J \f$ is rank deficient, 0 before the first call). Computed on demand from
    the eigenvalues of the \f$ J^T J \f$ of that call, so that the control loop does not pay for an
    eigen-decomposition it needs only near singularities.
  */
  double getConditionNumber() const;
  //! Damping \f$ \mu \f$ (pixels per joint unit) used at the last computeControlLaw() (0 away from singularities,
  //! and when it stopped).
  double getDamping() const { return last().damping; }
  //! Gain used at the last computeControlLaw() (0 when it stopped: SERVO_STOPPED).
  double getLambda() const { return last().lambda; }
  //! True if the last computeControlLaw() was scaled down by the velocity saturation.
  bool isSaturated() const { return last().saturated; }
  //@}

  /*! \name Global servoing: plan with the acquired model, follow the plan, finish with law (47) */
  //@{
  /*!
    Path planning (default off: law (47) alone, as before). On, the first computeControlLaw() for a target (and again
    whenever a desired feature changes) plans the task with vpProjectivePathPlanner. Planning is never worse than law
    (47): the planner rehearses the task's own law (gain, damping, saturation, joint-limit avoidance) on the model,
    and when that rehearsal solves the task inside the limits with the features in view, the task runs law (47)
    (vpProjectivePathPlanner::PATH_LAW) unless a path is faster. The features are triangulated
    at the current joints and carried to the zero reference by \f$ H(q)^{-1} \f$ (no marker identity is needed; a
    feature recognised as an acquired marker takes that marker's point), the inverse kinematics of \f$ s^* \f$ gives
    every branch it can find, the target is the one inside the joint limits (setJointLimits()) nearest to \f$ q \f$
    (the joint-limit avoidance then lets the arm reach it inside its activation band, and no planned step crosses a
    limit), and the path keeps the features' predicted images inside the image
    window (setImageSize()) and the joints within their limits: straight image lines when no joint needs to go
    farther than vpProjectivePathPlanner::setMaxExcursion() beyond its start and target values, else the joint-space
    line (monotonic joints), else two lines through a waypoint. The task then follows the path, one sample (no joint
    more than vpProjectivePathPlanner::setMaxJointStep() away) per call, with image feedback: \f$ \dot q \f$ is the
    path's step \f$ q_{k+1} - q_k \f$ plus law (47) with the gain setPathFollowingGain() on the error to the model's
    predicted images at sample \f$ k \f$ (getError() then returns that error), saturated as a whole, without the
    joint-limit avoidance (the path is inside the limits; getJointLimitVelocity() is zero); after the last
    sample law (47) toward \f$ s^* \f$ with the task's gain finishes the motion, so the final accuracy is the law's.
    While following a path, a joint more than two path steps away from the sample it should be at (the arm does not
    move as the model predicts: a velocity saturation, a model error), or, running law
    (47) as rehearsed, an RMS error still above twice the rehearsed one plus 2 px after twice the rehearsed
    iterations plus 10 (near a singular configuration the law's course depends on the noise), makes the task plan
    again from where it is, at most twice per target, without rehearsing law (47) again once it left its rehearsal;
    a third time, or when a re-plan finds nothing, it runs law (47) from there.
    When no plan exists the status is SERVO_NO_PLAN and \f$ \dot q = 0 \f$. Planning allocates and takes a few
    milliseconds; following is as cheap as the law.
  */
  void setPathPlanning(bool planning);
  //! True if path planning is on.
  bool getPathPlanning() const { return m_planning; }
  /*!
    The joint values (n x 1, encoder readings) the plan ends at: the inverse kinematics of \f$ s^* \f$.
    \exception vpProjectiveException (notInitializedError) when no plan was found (planning off, no call yet, or
    SERVO_NO_PLAN).
  */
  vpColVector getPlannedTarget() const;
  /*!
    Gain of the path following's feedback (default 1): the fraction of the error to the current sample's predicted
    features corrected by one call, in the unit of the task's gain (per call when the loop applies \f$ \dot q \f$ as
    the step of one call, as the tutorials do).
    \exception vpProjectiveException if it is not in (0, 1].
  */
  void setPathFollowingGain(double gain);
  //! True while the last computeControlLaw() followed the planned path (before the final law (47)).
  bool isFollowingPath() const { return m_following; }
  //! The planner, its settings and its last plan (target, branches, path, description).
  const vpProjectivePathPlanner &getPathPlanner() const { return m_planner; }
  //! The planner, to change its settings (setMaxJointStep(), setMaxExcursion(), setNumberOfStarts()).
  vpProjectivePathPlanner &getPathPlanner() { return m_planner; }
  //@}

  /*! \name The parts of the task */
  //@{
  //! The control law and its settings (setDamping(), setMaxJointVelocity(), setPseudoInverseThreshold()).
  const vpServoDampedLeastSquares &getDampedLeastSquares() const { return m_law; }
  //! The feature checks and their settings (setImageSize(), setOutlierThreshold(), setFeatureTracked()).
  const vpServoFeatureHealth &getFeatureHealth() const { return m_health; }
  //! The joint-limit avoidance and its settings (setJointLimits(), setLargeProjectionThresholds()).
  const vpServoJointLimitAvoidance &getJointLimitAvoidance() const { return m_jointLimits; }
  //@}

  /*!
    Prints the task in the layout of vpServo::print(vpServo::ALL): the type of control law (the rig's mounting, the
    joint-space law), the list of visual features s, the list of desired features s*, the task Jacobian J (in place of
    vpServo's interaction matrix Ls), the error vector (s - s*), the gain; then what vpServo has not: the status of the
    last computeControlLaw(), each feature's state and distances, and the settings of the law, the checks and the
    joint limits.
  */
  void print(std::ostream &os = std::cout) const;

private:
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;
  typedef vpProjectiveArmModel::JointVector JointVector;

  //! What one computeControlLaw() computes; kept only when it succeeds.
  struct vpIteration {
    Eigen::MatrixXd J;                    // 4N x n, zero rows for the features set aside
    Eigen::VectorXd e;                    // 4N
    JointMatrix JtJ;                      // J^T J
    JointVector Jte;                      // J^T e
    double errorNorm = 0.0;               // ||e||
    unsigned int nbActive = 0;            // features used
    vpServoStatus status = SERVO_RUNNING; // outcome
    double lambda = 0.0;                  // gain used
    double damping = 0.0;                 // mu used
    bool saturated = false;               // scaled down by the saturation
    JointVector qdot2;                    // secondary task
  };

  void check(const char *method) const;
  void checkFeatureIndex(unsigned int i, const char *method) const;
  void checkJoints(const JointVector &q, const char *method) const;
  void buildTask(const JointVector &q, vpIteration &it, const char *method);
  vpServoStatus decideStatus(const vpIteration &it) const;
  void computePrimaryVelocity(const JointVector &q, vpIteration &it, JointVector &qdot);
  // The task's gain (setLambda(), setAdaptiveGainInput(), setErrorUnit()) for the normal equations and |e|_inf (px).
  static double taskGain(const vpAdaptiveGain &lambda, vpGainInput input, double errorScale, const JointMatrix &JtJ,
                         const JointVector &Jte, double errorInf);
  void addJointLimitAvoidance(const JointVector &q, vpIteration &it, JointVector &qdot) const;
  void stop(vpIteration &it, JointVector &qdot);
  void commit();
  const vpIteration &last() const { return m_iterations[m_lastIteration]; }
  bool planIfNeeded(const JointVector &q);
  Eigen::Vector4d desired(unsigned int i) const;
  void refreshTargets();
  bool detectMismatch(const JointVector &q);

  //! The task's copy of a desired feature.
  struct vpTarget {
    Eigen::Vector4d user = Eigen::Vector4d::Zero();      // the user's s* when last read
    Eigen::Vector4d effective = Eigen::Vector4d::Zero(); // the s* the task uses
    Eigen::Vector4d point = Eigen::Vector4d::Zero();     // the point (model frame) that user showed through its rig
    bool hasPoint = false;                               // point is set
    bool valid = false;                                  // user and effective are set
    unsigned long rigGeneration = 0;                     // the rig effective is expressed in
    unsigned long modelGeneration = 0;
  };

  const vpProjectiveRobot *m_robot;
  std::vector<vpFeatureStereoPoint *> m_features;
  std::vector<vpFeatureStereoPoint *> m_desired;
  vpAdaptiveGain m_lambda;
  double m_rankTolerance;
  vpServoDampedLeastSquares m_law;
  vpServoFeatureHealth m_health;
  vpServoJointLimitAvoidance m_jointLimits;
  vpServoModelMismatch m_mismatch;
  std::vector<vpTarget> m_targets;
  unsigned long m_mismatchRigGeneration;
  unsigned long m_mismatchModelGeneration;
  const vpProjectiveRobot *m_mismatchRobot;
  // Two iterations: m_iterations[m_lastIteration] is the last successful computeControlLaw(), the one the getters
  // read; the other is the one in progress, which commit() makes the last by flipping the index (nothing is copied).
  vpIteration m_iterations[2];
  unsigned int m_lastIteration;

  // Path planning: the plan of the desired features m_plannedFor, followed sample by sample.
  bool m_planning;
  vpProjectivePathPlanner m_planner;
  std::vector<Eigen::Vector4d> m_plannedFor;
  size_t m_pathSample;     // the sample the next call aims at
  bool m_following;        // the last call followed the path
  unsigned int m_replans;  // plans again from an off-path configuration since the target was set
  bool m_lawLeftRehearsal; // law (47) left its rehearsal since the target was set: plan paths only
  size_t m_sincePlan;      // calls since the last plan
  bool m_replanFailed;     // the last plan was a re-plan that found nothing: law (47) runs
  double m_followGain;
  double m_period;  // seconds per computeControlLaw() call (setControlPeriod())
  double m_qdotMax; // the user's saturation, per second (the law's is per call: m_qdotMax * m_period)

  // setErrorUnit(): the unit, the focal length given (0: estimated), pixels per unit of error.
  vpGainInput m_gainInput;
  vpErrorUnit m_errorUnit;
  double m_focalLength;
  double m_errorScale;
  // setJointPositions(): the joints for computeControlLaw() without argument, and whether they are new.
  JointVector m_q;
  bool m_qFresh;
  // setSettling(): the settling gain, and the generation of the task's targets (refreshTargets()) it settles on.
  vpServoSettling m_settling;
  unsigned long m_targetGeneration;
};

END_VISP_NAMESPACE

#endif
