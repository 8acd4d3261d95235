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
  \file vpServoJointLimitAvoidance.h
  \brief ViSP's joint-limit avoidance as a secondary task, projected with the large projection operator.
*/

#ifndef _vpServoJointLimitAvoidance_h_
#define _vpServoJointLimitAvoidance_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoJointLimitAvoidance
  \ingroup group_projective
  \brief Joint-limit avoidance as a secondary task, as ViSP's vpServo::secondaryTaskJointLimitAvoidance() with
  vpServo::secondaryTask(..., useLargeProjectionOperator = true) (Marey and Chaumette, ICRA 2010): the same numbers,
  on any primary task given by its Jacobian \f$ J \f$ (m x n) and error \f$ e \f$ (m x 1).

  <b>Activation.</b> With \f$ \Delta_i = q_i^{max} - q_i^{min} \f$, joint \f$ i \f$ is left alone inside
  \f$ ]q_{l_0,i}^{min}, q_{l_0,i}^{max}[ \f$,
  \f[ q_{l_0,i}^{min} = q_i^{min} + \rho \Delta_i, \quad q_{l_0,i}^{max} = q_i^{max} - \rho \Delta_i, \quad
     q_{l_1,i}^{min} = q_{l_0,i}^{min} - \rho \rho_1 \Delta_i, \quad
     q_{l_1,i}^{max} = q_{l_0,i}^{max} + \rho \rho_1 \Delta_i. \f]
  Outside it, with \f$ g_i = -u_i \f$ below \f$ q_{l_0,i}^{min} \f$ and \f$ g_i = +u_i \f$ above
  \f$ q_{l_0,i}^{max} \f$ (\f$ u_i \f$ the i-th basis vector of the joint space), \f$ \dot q_1 \f$ the primary
  velocity (the motion the arm really makes, after its saturation: vpServo's \e dq) and
  \f$ b_i = |\dot q_{1,i}| / |(P g_i)_i| \f$, joint \f$ i \f$ adds, when \f$ b_i < 1 \f$ (vpServo: a larger ratio
  does not activate it),
  \f[ \dot q_{2}^{(i)} = -\lambda_{l,i} (1 + \lambda_t)\, b_i\, P g_i, \qquad
      \lambda_{l,i} = \frac{1}{1 + \exp\left(-12 \frac{q_i - q_{l_0,i}}{q_{l_1,i} - q_{l_0,i}} + 6\right)} \f]
  between \f$ q_{l_0,i} \f$ and \f$ q_{l_1,i} \f$ (of the side it is on) and \f$ \lambda_{l,i} = 1 \f$ beyond, and
  \f$ \dot q_2 = \sum_i \dot q_2^{(i)} \f$. Since \f$ (P g_i)_i = \pm P_{ii} \f$, joint \f$ i \f$ then moves at
  \f$ \dot q_{1,i} - \lambda_{l,i} (1 + \lambda_t) |\dot q_{1,i}| \f$ toward its limit: it stops where
  \f$ \lambda_{l,i} = 1 / (1 + \lambda_t) \f$ and turns back beyond, the other joints compensating within \f$ P \f$.

  <b>Large projection operator.</b>
  \f[ P = \bar\lambda(\|e\|)\, P_{\|e\|} + (1 - \bar\lambda(\|e\|)) (I_n - J^+ J), \qquad
      P_{\|e\|} = I_n - \frac{J^T e\, e^T J}{e^T J J^T e}, \f]
  \f$ \bar\lambda = 1 \f$ above \f$ \|e\| = e_1 \f$, 0 below \f$ e_0 \f$ and
  \f$ 1 / (1 + \exp(-12 (\|e\| - e_0) / (e_1 - e_0) + 6)) \f$ between (setLargeProjectionThresholds()),
  \f$ I_n - J^+ J \f$ the projector on the null space of \f$ J \f$ of the primary law
  (vpServoDampedLeastSquares::addNullSpaceProjector(): singular values below the pseudo-inverse threshold times
  \f$ \sigma_{max} \f$ count as zero, as in vpServo). Since \f$ P_{\|e\|} J^T e = 0 \f$ and
  \f$ (I_n - J^+ J) J^T e = 0 \f$, \f$ P J^T e = 0 \f$: the secondary task does not change \f$ \|e\|^2 \f$ to first
  order, and acts although \f$ J \f$ has full column rank, where \f$ I_n - J^+ J = 0 \f$ and the classical
  projection would leave nothing. When \f$ J^T e = 0 \f$ exactly, \f$ P = I_n - J^+ J \f$.

  Units: \f$ q \f$, the limits and \f$ \dot q \f$ in joint units (radians, or the encoder's length unit), \f$ e \f$,
  \f$ e_0 \f$ and \f$ e_1 \f$ in the task's unit (pixels for vpServoProjective), \f$ J \f$ in task units per joint
  unit. vpServo's scheme is a continuous-time one: it needs several control periods inside the activation band
  (keep \f$ \dot q_{max}\, \Delta t \f$ well below \f$ \rho \rho_1 \Delta_i \f$); see
  \ref page_servo_measurements.
*/
class VISP_EXPORT vpServoJointLimitAvoidance
{
public:
  //! Joint values or velocities (n x 1) without heap allocation.
  typedef vpProjectiveArmModel::JointVector JointVector;
  //! An n x n matrix without heap allocation.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;

  //! No joint limits; large projection thresholds \f$ (e_0, e_1) = (0.1, 0.7) \f$, vpServo's.
  vpServoJointLimitAvoidance();

  /*! \name Settings */
  //@{
  /*!
    The joint limits and the activation band (see the class documentation).
    \param qmin, qmax : limits (n x 1, \f$ 1 \le n \le \f$ vpProjectiveArmModel::maxJoints),
    \f$ q_i^{min} < q_i^{max} \f$, in the joint values of the \e q given to computeVelocity().
    \param rho : \f$ \rho \in ]0, 1/2] \f$, the relative width of the activation band at each end (0.1: the last
    10 % of the range; above 1/2 the bands of the two ends would overlap).
    \param rho1 : \f$ \rho_1 \in ]0, 1] \f$, where inside the band the avoidance reaches its full strength.
    \param lambdaTune : \f$ \lambda_t \in [0, 1] \f$, by how much the avoidance exceeds the primary motion toward
    the limit (vpServo's default 0.7).
    \exception vpProjectiveException (dimensionError, nonFiniteValueError, invalidValueError) if the sizes differ or
    are out of range, an entry is not finite, some \f$ q_i^{min} \ge q_i^{max} \f$, or a parameter is out of range.
    Nothing is changed then.
  */
  void setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double rho = 0.1, double rho1 = 0.3,
                      double lambdaTune = 0.7);
  /*!
    The error norms \f$ 0 \le e_0 < e_1 \f$ (task units: pixels for vpServoProjective) of the switch
    \f$ \bar\lambda(\|e\|) \f$ between the large projection operator \f$ P_{\|e\|} \f$ (above \f$ e_1 \f$) and the
    classical \f$ I_n - J^+ J \f$ (below \f$ e_0 \f$). Default: vpServo's 0.1 and 0.7. \f$ P_{\|e\|} \f$ turns with
    the direction of \f$ J^T e \f$, which follows the noise once \f$ \|e\| \f$ is down to it: raise \f$ e_0 \f$ above
    the noise level of \f$ \|e\| \f$ if a joint may rest in its activation band at the target. Larger values switch
    the avoidance off sooner: with a full-rank task \f$ I_n - J^+ J = 0 \f$.
    \exception vpProjectiveException (nonFiniteValueError, invalidValueError) if they are not finite or not
    \f$ 0 \le e_0 < e_1 \f$; nothing is changed then.
  */
  void setLargeProjectionThresholds(double e0, double e1);
  //! Removes the joint limits (the large projection thresholds stay).
  void clearJointLimits();
  //! True if setJointLimits() is in effect.
  bool hasJointLimits() const { return m_enabled; }
  //! Number of joints \e n of the limits (0 without limits).
  unsigned int getNumberOfJoints() const { return m_enabled ? static_cast<unsigned int>(m_qmin.size()) : 0u; }
  //! \f$ q^{min} \f$ (n x 1; empty without limits).
  vpColVector getLowerLimits() const;
  //! \f$ q^{max} \f$ (n x 1; empty without limits).
  vpColVector getUpperLimits() const;
  //! \f$ \rho \f$ of setJointLimits().
  double getRho() const { return m_rho; }
  //! \f$ \rho_1 \f$ of setJointLimits().
  double getRho1() const { return m_rho1; }
  //! \f$ \lambda_t \f$ of setJointLimits().
  double getLambdaTune() const { return m_lambdaTune; }
  //! \f$ e_0 \f$ and \f$ e_1 \f$ of setLargeProjectionThresholds() (task units).
  void getLargeProjectionThresholds(double &e0, double &e1) const
  {
    e0 = m_e0;
    e1 = m_e1;
  }
  //@}

  /*! \name The secondary task, with ViSP types */
  //@{
  /*!
    Large projection operator \f$ P \f$ (n x n, see the class documentation) of a primary task.
    \param J : primary task Jacobian (m x n), task units per joint unit.
    \param e : primary task error (m x 1), task units.
    \param law : the primary law, whose pseudo-inverse threshold defines \f$ J^+ \f$.
    \exception vpProjectiveException (dimensionError, nonFiniteValueError) if the sizes do not match (\f$ m \ge 1
    \f$, \f$ 1 \le n \le \f$ vpProjectiveArmModel::maxJoints) or a value is not finite.
  */
  vpMatrix computeLargeProjectionOperator(const vpMatrix &J, const vpColVector &e,
                                          const vpServoDampedLeastSquares &law) const;
  /*!
    Secondary-task velocity \f$ \dot q_2 \f$ (n x 1, see the class documentation); 0 without joint limits.
    \param q : joint values (n x 1), those of the limits.
    \param qdot1 : primary velocity \f$ \dot q_1 \f$ (n x 1), after its saturation.
    \param J, e, law : the primary task, as for computeLargeProjectionOperator().
    \exception vpProjectiveException (dimensionError, nonFiniteValueError) if the sizes do not match each other or
    the limits, or a value is not finite.
  */
  vpColVector computeVelocity(const vpColVector &q, const vpColVector &qdot1, const vpMatrix &J, const vpColVector &e,
                              const vpServoDampedLeastSquares &law) const;
  //@}

  /*! \name The secondary task, on Eigen types without allocation (the control loop's path; sizes not checked) */
  //@{
  /*!
    \f$ P \f$ (n x n, resized) from the normal equations of the primary task, \e ne (\f$ J^T J \f$ n x n,
    \f$ J^T e \f$ n x 1, their eigen decomposition for \f$ I_n - J^+ J \f$), and \e errorNorm \f$ = \|e\| \f$.
  */
  void computeLargeProjectionOperator(const vpServoNormalEquations &ne, double errorNorm,
                                      const vpServoDampedLeastSquares &law, JointMatrix &P) const;
  /*!
    \f$ \dot q_2 \f$ (n x 1, resized) at joint values \e q for the primary velocity \e qdot1 and the primary task's
    normal equations; 0 without joint limits. \f$ P \f$ is computed only when a joint is outside its free interval.
    \param q : joint values (n x 1).
    \param qdot1 : the primary velocity (n x 1), after its saturation.
    \param ne : the normal equations of the primary task (\f$ J^T J \f$ n x n, \f$ J^T e \f$ n x 1).
    \param errorNorm : \f$ \|e\| \f$, in the unit of setLargeProjectionThresholds().
    \param law : the primary law (its pseudo-inverse threshold for \f$ I_n - J^+ J \f$).
    \param qdot2 : \f$ \dot q_2 \f$ (n x 1, resized).
    \param target : if given (n x 1), the joint values the primary task converges to, known inside the limits (a
    planned target, vpProjectivePathPlanner): the free interval of each joint grows to contain it,
    \f$ q_{l_0,i}^{min} \leftarrow \min(q_{l_0,i}^{min}, q^*_i) \f$ and \f$ q_{l_0,i}^{max} \leftarrow
    \max(q_{l_0,i}^{max}, q^*_i) \f$, the bands moving with it. Without it a target inside a band holds the arm short,
    at the compromise where the avoidance balances the primary task; with it a joint is pushed back only beyond the
    target, toward its limit.
  */
  void computeVelocity(const JointVector &q, const JointVector &qdot1, const vpServoNormalEquations &ne,
                       double errorNorm, const vpServoDampedLeastSquares &law, JointVector &qdot2,
                       const JointVector *target = nullptr) const;
  /*!
    The largest \f$ t \in [0, 1] \f$ such that \f$ q + t \dot q \f$ (n x 1 each) stays within the limits on every
    joint inside them at \e q (a joint already beyond a limit is not held); 1 without limits.
  */
  double stepInside(const JointVector &q, const JointVector &qdot) const;
  //@}

private:
  bool m_enabled;
  JointVector m_qmin;
  JointVector m_qmax;
  double m_rho;
  double m_rho1;
  double m_lambdaTune;
  double m_e0;
  double m_e1;
};

END_VISP_NAMESPACE

#endif
