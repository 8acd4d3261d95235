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

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/vs/vpAdaptiveGain.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoProjective
  \ingroup group_projective
  \brief The non-metric visual servo of Ruf & Horaud (section 6): joint velocities from the image error of stereo
  point features, through the projective kinematic model of the arm. No intrinsics, rig geometry, robot geometry or
  hand-eye transform enter it.

  For \f$ N \f$ stereo points the task error is \f$ e = s - s^* \f$ (4N), and the task Jacobian \f$ J \f$ (4N x n)
  stacks, for each point, eq. (46) at the current joint values \f$ q \f$ and the point \f$ M \f$ triangulated from the
  current features:
  \f[ J_i = \begin{bmatrix} J_C(P M_i) P \\ J_C(P' M_i) P' \end{bmatrix} J_H(q, M_i). \f]
  The control law (47) is \f$ \dot q = -\lambda J^+ e \f$, with the pseudo-inverse damped near singular
  configurations: \f$ J^+ = (J^T J + \mu^2 I)^{-1} J^T \f$, \f$ \mu^2 = \mu_{max}^2 (1 - (\sigma_{min} /
  \sigma_0)^2) \f$ when the smallest singular value \f$ \sigma_{min} \f$ of J falls below \f$ \sigma_0 \f$, 0 otherwise.

  Like vpServo, the task keeps references to the features: the loop updates them and calls computeControlLaw().

  <b>Lost features, outliers and singularities.</b> At every computeControlLaw() each feature \f$ i \f$ gets a state
  (getFeatureState()), tested in this order:
  -# FEATURE_NOT_TRACKED: the tracker said so with setFeatureTracked(i, false);
  -# FEATURE_NOT_FINITE: \f$ s_i \f$ or \f$ s^*_i \f$ holds a NaN or an infinity (a tracker that lost the point);
  -# FEATURE_OUT_OF_IMAGE: outside the image window of setImageSize() in either image;
  -# FEATURE_OUTLIER: with setOutlierThreshold(), too far from its epipolar line or from the model's prediction;
  -# FEATURE_ACTIVE otherwise.

  Features that are not active are set aside: their 4 rows of \f$ e \f$ and \f$ J \f$ are set to zero, so that
  getError() and getTaskJacobian() keep their sizes \f$ 4N \f$ and \f$ 4N \times n \f$, and the control law,
  its damping, its gain and getConditionNumber() all act on the reduced task (zero rows change neither
  \f$ J^T J \f$ nor \f$ J^T e \f$). getStatus() then tells what happened:
  - SERVO_RUNNING: every feature is active. Whatever the rank of \f$ J \f$: a singular task with all its features
    (an arm singularity, a repeated feature) is left to the damped least squares, as before;
  - SERVO_REDUCED: some features are set aside and the active ones still constrain every joint; the task goes on
    with them;
  - SERVO_STOPPED: some features are set aside and the active ones no longer constrain every joint; then
    \f$ \dot q = 0 \f$ exactly. The test is scale-aware: with \f$ D = \mathrm{diag}(\|J_{:,k}\|) \f$ the
    column norms of the reduced \f$ J \f$, the task stops when \f$ \sigma_{min}(J D^{-1}) < \tau \,
    \sigma_{max}(J D^{-1}) \f$ (\f$ \tau \f$: setRankTolerance(), default \f$ 10^{-6} \f$), which depends
    neither on the pixel unit nor on the joint units (radians, metres), when a column is below \f$ \tau \f$ times the
    largest, or when fewer than \f$ n/3 \f$ points are active (a stereo point gives at most 3 independent equations:
    its 4 x 4 \f$ [J_C(P M) P; J_C(P' M) P'] \f$ annihilates \f$ M \f$). Two points never suffice for 6 joints: the
    rotation about the line through them moves neither (rank 5). Measured in the simulator: 3 to 7 markers of the
    8 cm gripper give ratios of \f$ 10^{-4} \f$ (eye-in-hand) to \f$ 4 \cdot 10^{-2} \f$, 2 markers
    \f$ 10^{-8} \f$ or less (the rounding of the eigenvalues).

  <b>Joint limits.</b> setJointLimits() adds ViSP's joint-limit avoidance (Marey and Chaumette 2010) as a secondary
  task projected with the large projection operator, which acts even when \f$ J \f$ has full column rank (see
  setJointLimits()).

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
  \endcode
*/
class VISP_EXPORT vpServoProjective
{
public:
  //! What happened to feature i at the last computeControlLaw().
  enum vpFeatureState {
    FEATURE_ACTIVE,       //!< Used by the control law.
    FEATURE_NOT_TRACKED,  //!< Set aside: setFeatureTracked(i, false).
    FEATURE_OUT_OF_IMAGE, //!< Set aside: outside the image window of setImageSize() in the left or right image.
    FEATURE_NOT_FINITE,   //!< Set aside: a coordinate of \f$ s_i \f$ or \f$ s^*_i \f$ is NaN or infinite.
    FEATURE_OUTLIER       //!< Set aside: farther than setOutlierThreshold() from its epipolar line or its prediction.
  };

  //! Outcome of the last computeControlLaw().
  enum vpServoStatus {
    SERVO_RUNNING, //!< Every feature used.
    SERVO_REDUCED, //!< Some features set aside, the remaining ones keep rank n: the task continues on them.
    SERVO_STOPPED  //!< The active features no longer constrain every joint (rank < n): \f$ \dot q = 0 \f$.
  };

  vpServoProjective();

  /*!
    The acquired projective model of the arm (calibrated or loaded). The task keeps a reference: the robot must
    outlive it.
  */
  void setRobot(const vpProjectiveRobot &robot);
  //! Constant gain \f$ \lambda > 0 \f$.
  void setLambda(double lambda);
  //! Adaptive gain, a function of the infinity norm of the error (see vpAdaptiveGain).
  void setLambda(const vpAdaptiveGain &lambda);
  //! Adaptive gain from its value at zero error, at infinite error and its slope at zero.
  void setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero);
  /*!
    Damped least squares: below \e sigmaThreshold (pixels per joint unit) for the smallest singular value of J, the
    damping \f$ \mu \f$ rises to \e maxDamping. Defaults: 1 and 10. Three markers 8 cm apart seen from 1 m give
    \f$ \sigma_{min} \f$ of 1 to 50 pixels per radian in healthy poses: a higher threshold keeps damping on near the
    target, which does not move the fixed point (\f$ J^T e = 0 \f$) but slows the final convergence. For large
    initial errors, combine a higher threshold with setMaxJointVelocity().
  */
  void setDamping(double sigmaThreshold, double maxDamping);
  /*!
    Velocity saturation: when some \f$ |\dot q_i| \f$ exceeds \e qdotMax (joint units per call), the whole
    \f$ \dot q \f$ is scaled down so that the largest one equals it, which keeps its direction. Large initial errors
    otherwise ask for joint steps far beyond the validity of the linearisation. 0 (the default) disables it.
  */
  void setMaxJointVelocity(double qdotMax);

  /*!
    Image size, for the detection of features that left the view. A feature is FEATURE_OUT_OF_IMAGE when
    \f$ (u, v) \f$ or \f$ (u', v') \f$ lies outside
    \f[ [b, w - 1 - b] \times [b, h - 1 - b] \f]
    (\f$ u \f$ the column, \f$ v \f$ the row, \f$ b \f$ = \e border pixels, bounds included). Such a feature is
    detected and set aside, never extrapolated. 0 x 0 (the default) disables the check.
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
    Outlier rejection: 0 (the default) disables it. Otherwise feature \e i is FEATURE_OUTLIER when one of these
    pixel distances exceeds \e pixels:
    - its epipolar distance, the larger of the distances of \f$ m \f$ to the line \f$ F^T m' \f$ and of
      \f$ m' \f$ to the line \f$ F m \f$ (\f$ F \f$ of the rig),
      \f[ d_F = \max\left( \frac{|m'^T F m|}{\|(F^T m')_{1,2}\|}, \frac{|m'^T F m|}{\|(F m)_{1,2}\|} \right); \f]
    - its prediction distance, the larger over both images of the pixel distance between \f$ s_i \f$ and
      the projection of
      \f[ \hat M_i = H(q)\, H(q_l)^{-1} M_l, \f]
      the point \f$ M_l \f$ triangulated when the feature was last accepted (at joints \f$ q_l \f$) moved by the
      model's displacement (34) since then. The task keeps \f$ H(q_l)^{-1} M_l \f$ (unit norm), so that each
      iteration needs one \f$ H(q) \f$; the 4-vectors are never divided by their last coordinate. The prediction is
      tested once the feature has been accepted at least once (from its second appearance on).

    The prediction catches what the epipolar test cannot: an error along the epipolar line, a tracker that jumped to
    another marker, a feature that reappears elsewhere after a loss. Choose the threshold well above the noise:
    at \f$ \sigma \f$ px per coordinate the epipolar distance has a standard deviation of about \f$ \sqrt 2 \sigma
    \f$ and the prediction distance includes the model's own prediction error (0.3 px RMS for a model acquired at
    0.5 px). Measured in the simulator (PUMA, 7 markers, 0.3 px noise, 5 % of the features shifted by 30 px in one
    image): a 5 px threshold flagged every shifted feature and none of some 3000 others, and the servo kept the
    accuracy it has without outliers (0.09 to 0.11 deg RMS), against 0.67 to 0.91 deg without the rejection.
    \exception vpProjectiveException if \e pixels is negative or not finite.
  */
  void setOutlierThreshold(double pixels);
  /*!
    Tolerance \f$ \tau \in (0, 1) \f$ of the rank test that stops the task when features are set aside (see the
    class documentation). Default \f$ 10^{-6} \f$, the relative threshold of vpServo's pseudo-inverse: the
    singular values come from the eigenvalues of \f$ D^{-1} J^T J D^{-1} \f$, which resolve \f$ \sigma_{min} /
    \sigma_{max} \f$ down to about \f$ \sqrt{n \epsilon} \approx 4 \cdot 10^{-8} \f$; keep \f$ \tau \f$ above.
    \exception vpProjectiveException if \e tolerance is not in (0, 1).
  */
  void setRankTolerance(double tolerance);

  /*!
    Joint-limit avoidance as a secondary task, as ViSP's vpServo::secondaryTaskJointLimitAvoidance() with
    vpServo::secondaryTask(..., useLargeProjectionOperator = true) (Marey and Chaumette, ICRA 2010). With
    \f$ \Delta_i = q_i^{max} - q_i^{min} \f$, joint \f$ i \f$ is left alone inside
    \f$ ]q_{l_0,i}^{min}, q_{l_0,i}^{max}[ \f$,
    \f[ q_{l_0,i}^{min} = q_i^{min} + \rho \Delta_i, \quad q_{l_0,i}^{max} = q_i^{max} - \rho \Delta_i, \quad
       q_{l_1,i}^{min} = q_{l_0,i}^{min} - \rho \rho_1 \Delta_i, \quad
       q_{l_1,i}^{max} = q_{l_0,i}^{max} + \rho \rho_1 \Delta_i. \f]
    Outside it, with \f$ g_i = -u_i \f$ below \f$ q_{l_0,i}^{min} \f$ and \f$ g_i = +u_i \f$ above
    \f$ q_{l_0,i}^{max} \f$ (\f$ u_i \f$ the i-th basis vector of the joint space), \f$ \dot q_1 \f$ the primary
    velocity (the damped law, after the velocity saturation: the motion the arm really makes, vpServo's \e dq) and \f$
    b_i = |\dot q_{1,i}| / |(P g_i)_i| \f$, joint \f$ i \f$ adds, when \f$ b_i < 1 \f$ (vpServo: a larger ratio does not
    activate it), \f[ \dot q_{2}^{(i)} = -\lambda_{l,i} (1 + \lambda_t)\, b_i\, P g_i, \qquad \lambda_{l,i} = \frac{1}{1
    + \exp\left(-12 \frac{q_i - q_{l_0,i}}{q_{l_1,i} - q_{l_0,i}} + 6\right)} \f] between \f$ q_{l_0,i} \f$ and \f$
    q_{l_1,i} \f$ (of the side it is on) and \f$ \lambda_{l,i} = 1 \f$ beyond, and \f$ \dot q_2 = \sum_i \dot q_2^{(i)}
    \f$. Since \f$ (P g_i)_i = \pm P_{ii} \f$, joint \f$ i \f$ then moves at \f$ \dot q_{1,i} - \lambda_{l,i} (1 +
    \lambda_t) |\dot q_{1,i}| \f$ toward its limit: it stops where \f$ \lambda_{l,i} = 1 / (1 + \lambda_t) \f$ and turns
    back beyond, the other joints compensating within \f$ P \f$. The large projection operator is \f[ P =
    \bar\lambda(\|e\|)\, P_{\|e\|} + (1 - \bar\lambda(\|e\|)) (I_n - J^+ J), \qquad P_{\|e\|} = I_n - \frac{J^T e\, e^T
    J}{e^T J J^T e}, \f] \f$ \bar\lambda = 1 \f$ above \f$ \|e\| = e_1 \f$, 0 below \f$ e_0 \f$ and \f$ 1 / (1 +
    \exp(-12 (\|e\| - e_0) / (e_1 - e_0) + 6)) \f$ between (setLargeProjectionThresholds(), default vpServo's 0.1 and
    0.7), \f$ J^+ J \f$ the projector on the row space of the (reduced) \f$ J \f$, singular values below \f$ 10^{-6}
    \sigma_{max} \f$ counting as zero as in vpServo. Since \f$ P_{\|e\|} J^T e = 0 \f$ and \f$ (I_n - J^+ J) J^T e = 0
    \f$, \f$ P J^T e = 0 \f$: the secondary task does not change \f$ \|e\|^2 \f$ to first order, and acts although \f$ J
    \f$ (4N x n) has full column rank, where \f$ I_n - J^+ J = 0 \f$ and the classical projection would leave nothing.
    When \f$ J^T e = 0 \f$ exactly, \f$ P = I_n - J^+ J \f$. Then \f$ \dot q = \dot q_1 + \dot q_2 \f$ goes through the
    velocity saturation again; a stopped task (SERVO_STOPPED) returns 0.

    vpServo's scheme is a continuous-time one: it needs several control periods inside the activation band, and
    \f$ P_{\|e\|} \f$ only keeps \f$ \|e\| \f$ from growing to first order. Measured in the simulator (PUMA and
    Viper850, 3 markers, joints overshooting by 3 to 30 deg, bands of 1 to 12 deg, 5 seeds): at 10 Hz with
    \f$ \lambda = 0.5 \f$/s and 10 deg/s at most, the limit held in 111 of 111 runs and 98 converged, the other 13
    held in their band by the conflict between the avoidance and the task; with one 10 deg step per call
    (\f$ \lambda = 0.5 \f$ per call, as tutorial-projective-servo.cpp) the joints jump across such bands and the
    limit held in only 33 of 125 runs (3 seeds). Keep \f$ \dot q_{max}\, \Delta t \f$ well below
    \f$ \rho \rho_1 \Delta_i \f$.

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
    The error norms \f$ 0 \le e_0 < e_1 \f$ (pixels) of the switch \f$ \bar\lambda(\|e\|) \f$ between the large
    projection operator \f$ P_{\|e\|} \f$ (above \f$ e_1 \f$) and the classical \f$ I_n - J^+ J \f$ (below
    \f$ e_0 \f$), see setJointLimits(). Default: vpServo's 0.1 and 0.7, taken in pixels. \f$ P_{\|e\|} \f$ turns with
    the direction of \f$ J^T e \f$, which follows the image noise once \f$ \|e\| \f$ is down to it: raise
    \f$ e_0 \f$ above the noise level of \f$ \|e\| \f$ (about \f$ \sqrt{8N} \sigma \f$ for N points and a noisy
    \f$ s \f$ and \f$ s^* \f$ of \f$ \sigma \f$ px) if a joint may rest in its activation band at the target. Larger
    values switch the avoidance off sooner: with a full-rank task \f$ I_n - J^+ J = 0 \f$.
    \exception vpProjectiveException if they are not finite or not \f$ 0 \le e_0 < e_1 \f$.
  */
  void setLargeProjectionThresholds(double e0, double e1);
  //! Removes the joint limits set by setJointLimits().
  void clearJointLimits();
  //! True if setJointLimits() is in effect.
  bool hasJointLimits() const { return m_jointLimits; }

  /*!
    Adds a stereo point and its desired value. Both are kept by reference, like vpServo::addFeature().
  */
  void addFeature(vpFeatureStereoPoint &s, vpFeatureStereoPoint &s_star);
  //! Removes every feature.
  void clearFeatures();
  //! Number of stereo point features \f$ N \f$ added.
  unsigned int getNumberOfFeatures() const { return static_cast<unsigned int>(m_features.size()); }

  /*!
    \f$ \dot q = -\lambda J^+ (s - s^*) \f$ at joint values \e q, on the active features (see the class
    documentation), plus the joint-limit avoidance of setJointLimits() if set, then saturated.
    A lost, non-finite, out-of-image or outlying feature never throws: it is set aside and reported by
    getFeatureState() and getStatus(); when the active features no longer constrain every joint, \f$ \dot q = 0 \f$.
    \exception vpProjectiveException if the robot or the features are missing, q has the wrong size or is not
    finite, fewer than n equations were added, the joint limits do not match the robot, or an active feature
    cannot be triangulated (it lies on a camera's focal plane).
  */
  vpColVector computeControlLaw(const vpColVector &q);
  //! The same on Eigen types, without allocation once the sizes are known.
  void computeControlLaw(const vpProjectiveRobot::JointVector &q, vpProjectiveRobot::JointVector &qdot);

  //! \f$ e = s - s^* \f$ (4N) of the last computeControlLaw(); the 4 rows of a feature set aside are zero.
  vpColVector getError() const;
  //! \f$ J \f$ (4N x n) of the last computeControlLaw(); the 4 rows of a feature set aside are zero.
  vpMatrix getTaskJacobian() const;

  //! Outcome of the last computeControlLaw() (SERVO_RUNNING before the first one).
  vpServoStatus getStatus() const { return m_status; }
  /*!
    State of feature \e i (index in addFeature() order) at the last computeControlLaw() (FEATURE_ACTIVE before).
    \exception vpProjectiveException (dimensionError) on a bad index.
  */
  vpFeatureState getFeatureState(unsigned int i) const;
  //! Number of features used by the last computeControlLaw().
  unsigned int getNumberOfActiveFeatures() const { return m_nbActive; }
  /*!
    Epipolar distance \f$ d_F \f$ (pixels, see setOutlierThreshold()) of feature \e i at the last
    computeControlLaw(); -1 if it was not evaluated (outlier rejection off, or the feature set aside before the test).
    \exception vpProjectiveException on a bad index.
  */
  double getEpipolarDistance(unsigned int i) const;
  /*!
    Prediction distance (pixels, see setOutlierThreshold()) of feature \e i at the last computeControlLaw(); -1 if it
    was not evaluated (outlier rejection off, no earlier acceptance, the feature set aside before the test, or the
    prediction on a camera's focal plane).
    \exception vpProjectiveException on a bad index.
  */
  double getPredictionDistance(unsigned int i) const;
  /*!
    \f$ \sigma_{min}(J D^{-1}) / \sigma_{max}(J D^{-1}) \f$ of the reduced \f$ J \f$ of the last
    computeControlLaw(), \f$ D \f$ its column norms (0 if a column is below the rank tolerance times the largest):
    the quantity compared with setRankTolerance(). Computed by the rank test when features were set aside, on demand
    otherwise.
  */
  double getSingularValueRatio() const;
  /*!
    Large projection operator \f$ P \f$ (n x n, see setJointLimits()) of the \f$ J \f$ and \f$ e \f$ of the last
    computeControlLaw(), whether or not joint limits are set.
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
    computeControlLaw() (infinite if \f$ J \f$ is rank deficient). Computed on the first call after computeControlLaw()
    from the \f$ J^T J \f$ it kept, so that the control loop does not pay for an eigen-decomposition it needs only near
    singularities.
  */
  double getConditionNumber() const;
  //! Damping \f$ \mu \f$ used at the last computeControlLaw() (0 away from singularities, and when it stopped).
  double getDamping() const { return m_damping; }
  //! Gain used at the last computeControlLaw() (0 when it stopped: SERVO_STOPPED).
  double getLambda() const { return m_lambdaUsed; }
  //! True if the last computeControlLaw() was scaled down by the velocity saturation.
  bool isSaturated() const { return m_saturated; }

private:
  //! Square matrices of joint size, in fixed storage (no allocation).
  typedef Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, vpProjectiveRobot::maxJoints,
                        vpProjectiveRobot::maxJoints>
      JointMatrix;

  void check(const char *method) const;
  void checkFeatureIndex(unsigned int i, const char *method) const;
  void checkJointLimitSize(unsigned int n, const char *method) const;
  void computeSpectrum() const;
  void computeSingularValueRatio() const;
  vpFeatureState classify(size_t i, const Eigen::Vector4d &s, const Eigen::Vector4d &sStar, bool predict,
                          const Eigen::Matrix4d &H);
  void largeProjectionOperator(JointMatrix &P) const;
  void jointLimitAvoidance(const vpProjectiveRobot::JointVector &q, const vpProjectiveRobot::JointVector &dq,
                           vpProjectiveRobot::JointVector &q2) const;

  const vpProjectiveRobot *m_robot;
  std::vector<vpFeatureStereoPoint *> m_features;
  std::vector<vpFeatureStereoPoint *> m_desired;
  vpAdaptiveGain m_lambda;
  double m_sigmaThreshold;
  double m_maxDamping;
  double m_qdotMax;
  Eigen::MatrixXd m_J;
  Eigen::VectorXd m_e;
  JointMatrix m_JtJ;            // J^T J of the last computeControlLaw(), for getConditionNumber()
  mutable bool m_spectrumValid; // m_sigmaMin and m_condition are those of m_JtJ
  mutable double m_sigmaMin;
  mutable double m_condition;
  double m_damping;
  double m_lambdaUsed;
  bool m_saturated;

  // Robustness (per feature, sized by addFeature(): no allocation in the loop).
  std::vector<vpFeatureState> m_states;
  std::vector<char> m_tracked;
  std::vector<Eigen::Vector4d> m_M0;        // H(q_l)^-1 M_l at the last acceptance, unit norm
  std::vector<char> m_hasM0;                // m_M0[i] is set
  std::vector<double> m_epipolarDistance;   // -1: not evaluated
  std::vector<double> m_predictionDistance; // -1: not evaluated
  unsigned int m_width;
  unsigned int m_height;
  double m_border;
  double m_outlierThreshold;
  double m_rankTolerance;
  vpServoStatus m_status;
  unsigned int m_nbActive;
  mutable bool m_ratioValid; // m_ratio is that of m_JtJ
  mutable double m_ratio;
  vpProjectiveRobot::JointVector m_b; // J^T e of the last computeControlLaw()
  double m_errorNorm;                 // ||e|| of the last computeControlLaw()

  // Joint limits.
  bool m_jointLimits;
  vpProjectiveRobot::JointVector m_qmin;
  vpProjectiveRobot::JointVector m_qmax;
  double m_rho;
  double m_rho1;
  double m_lambdaTune;
  double m_e0;
  double m_e1;
  vpProjectiveRobot::JointVector m_qdot2; // secondary task of the last computeControlLaw()
};

END_VISP_NAMESPACE

#endif
