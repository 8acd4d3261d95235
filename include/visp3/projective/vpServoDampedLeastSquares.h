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
  \file vpServoDampedLeastSquares.h
  \brief The damped least-squares control law with velocity saturation shared by the plugin's servos.
*/

#ifndef _vpServoDampedLeastSquares_h_
#define _vpServoDampedLeastSquares_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoNormalEquations.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoDampedLeastSquares
  \ingroup group_projective
  \brief The damped least-squares control law of the plugin, with its velocity saturation: joint velocities from a
  task Jacobian and a task error, damped near singular configurations.

  For a task error \f$ e \f$ (m x 1) and its Jacobian \f$ J \f$ (m x n, \f$ 1 \le n \le \f$ maxJoints, any m) with
  respect to the joint values \f$ q \f$ (n x 1),
  \f[ \dot q = -\lambda\, (J^T J + \mu^2 I_n)^{-1} J^T e, \qquad
      \mu^2 = \left\{ \begin{array}{ll} \mu_{max}^2 \left(1 - (\sigma_{min} / \sigma_0)^2\right) &
      \mbox{if } \sigma_{min} < \sigma_0, \\ 0 & \mbox{otherwise,} \end{array} \right. \f]
  \f$ \sigma_{min} \f$ the smallest singular value of \f$ J \f$, \f$ \sigma_0 \f$ and \f$ \mu_{max} \f$ the settings
  of setDamping(). Away from singularities (\f$ \sigma_{min} \ge \sigma_0 \f$) and for a full column rank
  \f$ J \f$ this is vpServo's law (47) \f$ \dot q = -\lambda J^+ e \f$; near them the damping bounds the step by
  \f$ \lambda \|e\| / (2 \mu) \f$ and keeps it in the row space of \f$ J \f$. Then the velocity saturation of
  setMaxJointVelocity(): when some \f$ |\dot q_i| > \dot q_{max} \f$, the whole \f$ \dot q \f$ is scaled by
  \f$ \dot q_{max} / \max_i |\dot q_i| \f$, which keeps its direction.

  Units and frames: the rows of \f$ J \f$ and \f$ e \f$ are in the task's unit and frame (pixels for the image
  coordinates of vpServoProjective; the camera frame's normalised coordinates or metres for a metric IBVS), the
  columns of \f$ J \f$ are the joints in the order of \f$ q \f$, in task units per joint unit (radian for a revolute
  joint, the encoder's length unit for a prismatic one). \f$ \sigma_0 \f$ and \f$ \mu_{max} \f$ are in the unit of
  \f$ J \f$; \f$ \lambda \f$ and \f$ \dot q_{max} \f$ are per control step (\f$ \dot q \f$ is then the step) or per
  second (\f$ \dot q \f$ a velocity), consistently.

  Numerics, for the few joints of an arm and without any allocation on the Eigen path: the law reads the normal
  equations and their factorisations from a vpServoNormalEquations, which the other parts of the law share (each
  factorisation computed once per iteration). Away from singularities its Cholesky factor both proves
  \f$ \sigma_{min} > \sigma_0 \f$ (\f$ \mathrm{tr}((J^T J)^{-1}) < 1 / \sigma_0^2 \f$, \f$ \mu = 0 \f$) and gives
  \f$ \dot q = -\lambda (J^T J)^{-1} J^T e \f$; otherwise the eigenvalues of \f$ J^T J \f$ decide
  (\f$ \sigma_{min}^2 \f$ the smallest, clamped at 0) and, for \f$ \mu > 0 \f$, solve the damped system. Without
  damping (\f$ \sigma_0 = 0 \f$) a rank-deficient \f$ J \f$ is solved by Eigen's pivoting LDLT (zero pivots
  contribute nothing).

  The same law serves vpServoProjective (which feeds it the Jacobian of its active features) and any controller that
  has a Jacobian and an error, for instance an IBVS with a metric interaction matrix:
  \code
  vpServoDampedLeastSquares law;
  law.setDamping(30, 30);                          // sigma_0, mu_max in the unit of J
  law.setMaxJointVelocity(vpMath::rad(15));        // per call
  vpColVector qdot = law.computeVelocity(J, e, 0.5); // J 12x6, e 12x1
  if (law.isSaturated()) { ... }
  \endcode
  vpServoControlLaw::getDampedLeastSquares() gives a servo task's law with its settings
  (vpServoProjective::getControlLaw()).
*/
class VISP_EXPORT vpServoDampedLeastSquares
{
public:
  //! Largest number of joints (columns of \f$ J \f$).
  static const unsigned int maxJoints = vpProjectiveArmModel::maxJoints;
  //! Joint values or velocities (n x 1) without heap allocation.
  typedef vpProjectiveArmModel::JointVector JointVector;
  //! An n x n matrix without heap allocation.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;

  /*!
    The law with its default settings: damping \f$ (\sigma_0, \mu_{max}) = (1, 10) \f$, no saturation, pseudo-inverse
    threshold \f$ 10^{-6} \f$ (vpServo's).
  */
  vpServoDampedLeastSquares();

  /*! \name Settings */
  //@{
  /*!
    Damped least squares: below \e sigmaThreshold \f$ \sigma_0 \f$ for the smallest singular value of \f$ J \f$ the
    damping \f$ \mu \f$ rises to \e maxDamping \f$ \mu_{max} \f$ (both in the unit of \f$ J \f$: pixels per joint
    unit for vpServoProjective). 0 for \e sigmaThreshold disables the damping. A higher threshold keeps damping on
    near the target, which does not move the fixed point (\f$ J^T e = 0 \f$) but slows the final convergence;
    combine it with setMaxJointVelocity() for large initial errors. Typical values for the plugin's stereo tasks:
    \ref page_servo_measurements.
    \exception vpProjectiveException (nonFiniteValueError, invalidValueError) if a value is not finite or negative;
    nothing is changed then.
  */
  void setDamping(double sigmaThreshold, double maxDamping);
  /*!
    Velocity saturation: when some \f$ |\dot q_i| \f$ exceeds \e qdotMax (joint units per call, or per second when
    \f$ \dot q \f$ is a velocity), the whole \f$ \dot q \f$ is scaled down so that the largest one equals it, which
    keeps its direction. Large initial errors otherwise ask for joint steps far beyond the validity of the
    linearisation. 0 (the default) disables it.
    \exception vpProjectiveException (nonFiniteValueError, invalidValueError) if \e qdotMax is not finite or
    negative; nothing is changed then.
  */
  void setMaxJointVelocity(double qdotMax);
  /*!
    Relative threshold \f$ \tau_+ \f$ of the pseudo-inverse \f$ J^+ \f$, as vpServo::setPseudoInverseThreshold():
    the singular values of \f$ J \f$ below \f$ \tau_+ \sigma_{max} \f$ count as zero in the projector
    \f$ I_n - J^+ J \f$ on the null space of \f$ J \f$ (addNullSpaceProjector(), used by the large projection
    operator of vpServoJointLimitAvoidance). Default \f$ 10^{-6} \f$, vpServo's.

    It is neither the damping nor a rank test: the law itself never truncates singular values, it damps them below
    \f$ \sigma_0 \f$ (setDamping()), which is continuous in \f$ J \f$; and vpServoProjective decides that its
    active features no longer constrain every joint (SERVO_STOPPED) with its own, scale-free test
    (vpServoFeatureHealth::setRankTolerance()). The singular values come from the eigenvalues of \f$ J^T J \f$, which
    resolve \f$ \sigma / \sigma_{max} \f$ down to about \f$ \sqrt{n \epsilon} \approx 4 \cdot 10^{-8} \f$: keep
    \f$ \tau_+ \f$ above.
    \exception vpProjectiveException (nonFiniteValueError, invalidValueError) if \e threshold is not finite or not in
    [0, 1); nothing is changed then.
  */
  void setPseudoInverseThreshold(double threshold);
  //! \f$ \sigma_0 \f$ of setDamping() (unit of \f$ J \f$).
  double getSigmaThreshold() const { return m_sigmaThreshold; }
  //! \f$ \mu_{max} \f$ of setDamping() (unit of \f$ J \f$).
  double getMaxDamping() const { return m_maxDamping; }
  //! \f$ \dot q_{max} \f$ of setMaxJointVelocity() (0: no saturation).
  double getMaxJointVelocity() const { return m_qdotMax; }
  //! \f$ \tau_+ \f$ of setPseudoInverseThreshold().
  double getPseudoInverseThreshold() const { return m_pseudoInverseThreshold; }
  //@}

  /*! \name The law */
  //@{
  /*!
    \f$ \dot q \f$ (n x 1) of the damped law with saturation (see the class documentation), with ViSP types.
    \param J : task Jacobian (m x n, \f$ m \ge 1 \f$, \f$ 1 \le n \le \f$ maxJoints), task units per joint unit.
    \param e : task error (m x 1), task units, in the frame of the rows of \e J.
    \param lambda : gain \f$ \lambda \ge 0 \f$ (per call, or per second).
    \return \f$ \dot q \f$ (n x 1) in the joint order of the columns of \e J. getDamping() and isSaturated() then
    report what the law did.
    \exception vpProjectiveException dimensionError if the sizes do not match or \e J has no row, no column or more
    than maxJoints columns; nonFiniteValueError if \e J, \e e or \e lambda is not finite; invalidValueError if
    \e lambda is negative; estimationFailedError if the result is not finite (an overflow: scale the task). Nothing
    is changed then.
  */
  vpColVector computeVelocity(const vpMatrix &J, const vpColVector &e, double lambda);
  /*!
    The same from the normal equations, on Eigen types and without allocation: the control loop's path.
    \param ne : \f$ J^T J \f$ (n x n, \f$ 1 \le n \le \f$ maxJoints) and \f$ J^T e \f$ (n x 1) with their
    factorisations (the task's, shared with the other parts of the law).
    \param lambda : gain \f$ \lambda \ge 0 \f$.
    \param qdot : \f$ \dot q \f$ (n x 1, resized).
    \exception vpProjectiveException (estimationFailedError) if the result is not finite (an overflow); the report of
    getDamping() and isSaturated() is then unchanged.
  */
  void computeVelocity(const vpServoNormalEquations &ne, double lambda, JointVector &qdot);
  /*!
    The velocity saturation alone: scales \e qdot by \f$ \dot q_{max} / \max_i |\dot q_i| \f$ when that is below 1
    (see setMaxJointVelocity()). Returns true if it did. Does not change the report of isSaturated().
  */
  bool saturate(JointVector &qdot) const;
  /*!
    \f$ P \leftarrow P + w\, (I_n - J^+ J) \f$: adds \e weight times the orthogonal projector on the null space of
    \f$ J \f$, the eigenvectors of \f$ J^T J \f$ (\e ne's eigen decomposition) whose singular value is at most
    \f$ \tau_+ \sigma_{max} \f$ (setPseudoInverseThreshold()), as vpServo's projection operator. \e P must be n x n.
    No allocation; sizes not checked.
  */
  void addNullSpaceProjector(const vpServoNormalEquations &ne, double weight, JointMatrix &P) const;
  //@}

  /*! \name What the last computeVelocity() did */
  //@{
  //! Damping \f$ \mu \f$ (unit of \f$ J \f$) of the last computeVelocity(): 0 away from singularities.
  double getDamping() const { return m_damping; }
  //! True if the last computeVelocity() was scaled down by the velocity saturation.
  bool isSaturated() const { return m_saturated; }
  //@}

private:
  double m_sigmaThreshold;
  double m_maxDamping;
  double m_qdotMax;
  double m_pseudoInverseThreshold;
  double m_damping;
  bool m_saturated;
};

END_VISP_NAMESPACE

#endif
