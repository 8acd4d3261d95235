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
  \file vpServoControlLaw.h
  \brief Law (47) of Ruf & Horaud in one place: gain, damped least squares with saturation, joint-limit avoidance.
*/

#ifndef _vpServoControlLaw_h_
#define _vpServoControlLaw_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>
#include <visp3/projective/vpServoJointLimitAvoidance.h>
#include <visp3/projective/vpServoSettling.h>
#include <visp3/vs/vpAdaptiveGain.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoControlLaw
  \ingroup group_projective
  \brief Law (47) \f$ \dot q = -\lambda (J^T J + \mu^2 I_n)^{-1} J^T e \f$, saturated, plus the joint-limit task
  \f$ \dot q_2 \f$ and saturated again: the one implementation that vpServoProjective runs in the loop and
  vpProjectivePathPlanner rehearses on the model.

  A step works from the normal equations \f$ J^T J \f$ (n x n), \f$ J^T e \f$ (n x 1), the error's norms and the
  joints \f$ q \f$ (n x 1, the model's joint values); it returns the joint step of one call (joint units per call,
  the control period \f$ T \f$ of setControlPeriod() folded in):
  - the gain \f$ T \lambda(x) \f$ of a constant or adaptive vpAdaptiveGain, \f$ x = \|e\|_\infty \f$ in the unit of
    the error (setErrorScale()) or \f$ x = \|J^+ e\|_\infty \f$ (setAdaptiveGainInput());
  - the damped least squares with its saturation at \f$ T \dot q_{max} \f$ (getDampedLeastSquares());
  - the joint-limit avoidance (getJointLimitAvoidance()), added and saturated again, only when limits are set.

  No allocation: fixed-size Eigen types.
*/
class VISP_EXPORT vpServoControlLaw
{
public:
  //! Joint values or steps (n x 1) without heap allocation.
  typedef vpProjectiveArmModel::JointVector JointVector;
  //! An n x n matrix without heap allocation.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;

  //! What an adaptive gain is a function of (see setAdaptiveGainInput()).
  enum vpGainInput {
    GAIN_INPUT_ERROR,         //!< \f$ \|e\|_\infty \f$ in the unit of the error (the default).
    GAIN_INPUT_JOINT_VELOCITY //!< \f$ \|J^+ e\|_\infty \f$ (joint units): what vpServo evaluates its gain on.
  };

  //! Gain 0.5, period 1 s, no saturation, damping (1, 10), no joint limit, error in pixels.
  vpServoControlLaw();

  /*! \name Settings */
  //@{
  //! Constant gain \f$ \lambda > 0 \f$ (per second).
  //! \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if not positive and finite.
  void setLambda(double lambda);
  //! Adaptive gain (vpAdaptiveGain) of the input of setAdaptiveGainInput().
  void setLambda(const vpAdaptiveGain &lambda) { m_lambda = lambda; }
  /*!
    Adaptive gain from its value at zero error, at infinite error and its slope at zero.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) unless
    \f$ gainAtZero \ge gainAtInfinity > 0 \f$, \f$ slopeAtZero \ge 0 \f$, all finite.
  */
  void setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero);
  //! The gain of setLambda().
  const vpAdaptiveGain &getLambda() const { return m_lambda; }
  /*!
    What the adaptive gain is evaluated on: \f$ x = \|e\|_\infty \f$ (GAIN_INPUT_ERROR, default, unit of
    setErrorScale()) or \f$ x = \|J^+ e\|_\infty \f$ (GAIN_INPUT_JOINT_VELOCITY, \f$ J^+ = (J^T J)^{-1} J^T \f$;
    \f$ x = \infty \f$ if singular), as vpServo does.
    \exception vpProjectiveException (invalidValueError) on an unknown input.
  */
  void setAdaptiveGainInput(vpGainInput input);
  //! What the adaptive gain is evaluated on (setAdaptiveGainInput()).
  vpGainInput getAdaptiveGainInput() const { return m_gainInput; }
  /*!
    The time \e T (seconds) between two steps (default 1: one step of the discrete law). The gain and the saturation
    are per second; a step is \f$ T \f$ times the velocity. A task sets it with vpServoProjective::setControlPeriod(),
    which tells its arm-following check too.
    \exception vpProjectiveException (invalidValueError) if not positive and finite; nothing is changed then.
  */
  void setControlPeriod(double seconds);
  //! The control period (seconds; see setControlPeriod()).
  double getControlPeriod() const { return m_period; }
  /*!
    Velocity saturation at \e qdotMax (joint units per second), keeping the direction of \f$ \dot q \f$; 0 (default):
    none. \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if negative or not finite.
  */
  void setMaxJointVelocity(double qdotMax);
  //! \f$ \dot q_{max} \f$ of setMaxJointVelocity() (joint units per second; 0: none).
  double getMaxJointVelocity() const { return m_qdotMax; }
  //! Pixels per unit of the error that the gain and the large projection thresholds see (1: pixels; 0: not known yet).
  //! \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if negative or not finite.
  void setErrorScale(double pixelsPerUnit);
  //! Pixels per unit of the error (setErrorScale()).
  double getErrorScale() const { return m_errorScale; }
  //! Damping of the least squares (vpServoDampedLeastSquares::setDamping()). \exception vpProjectiveException if a
  //! value is negative or not finite; nothing is changed then.
  void setDamping(double sigmaThreshold, double maxDamping) { m_dls.setDamping(sigmaThreshold, maxDamping); }
  //! Threshold of the null-space projector (vpServoDampedLeastSquares::setPseudoInverseThreshold()).
  //! \exception vpProjectiveException if not in [0, 1) or not finite; nothing is changed then.
  void setPseudoInverseThreshold(double threshold) { m_dls.setPseudoInverseThreshold(threshold); }
  //! The damped least squares (setDamping(), setPseudoInverseThreshold()); its saturation is per step: that of
  //! setMaxJointVelocity() times the period.
  const vpServoDampedLeastSquares &getDampedLeastSquares() const { return m_dls; }
  //! The joint-limit avoidance and its settings (limits, thresholds of the large projection operator).
  const vpServoJointLimitAvoidance &getJointLimitAvoidance() const { return m_limits; }
  //! The same, to set or clear the limits and the thresholds (vpServoJointLimitAvoidance).
  vpServoJointLimitAvoidance &getJointLimitAvoidance() { return m_limits; }
  //! The settling gain that vpServoProjective applies at rest (vpServoProjective::setSettling()): its settings and
  //! state (settled, settled calls, noise estimate, last test statistic).
  const vpServoSettling &getSettling() const { return m_settling; }
  //! The same, to change its settings.
  vpServoSettling &getSettling() { return m_settling; }
  //@}

  /*! \name One step of the law */
  //@{
  //! The gain of this step: \f$ T \lambda(x) \f$ (per call), \e errorInf = \f$ \|e\|_\infty \f$ in pixels; with
  //! GAIN_INPUT_JOINT_VELOCITY, x is read from \e ne's Gauss-Newton step.
  double gain(const vpServoNormalEquations &ne, double errorInf) const;
  //! \f$ \dot q_1 = -\lambda (J^T J + \mu^2 I_n)^{-1} J^T e \f$, saturated (vpServoDampedLeastSquares).
  void computePrimaryStep(const vpServoNormalEquations &ne, double lambda, JointVector &qdot)
  {
    m_dls.computeVelocity(ne, lambda, qdot);
  }
  /*!
    With joint limits: \f$ \dot q_2 \f$ of the avoidance (toward \e target if given), added to \e qdot and saturated
    again; returns true if the saturation scaled it. Without: \e qdot2 = 0, \e qdot unchanged, false.
    \e errorNorm is \f$ \|e\|_2 \f$ in the unit of the error (setErrorScale()).
  */
  bool addJointLimitAvoidance(const JointVector &q, const vpServoNormalEquations &ne, double errorNorm,
                              JointVector &qdot, JointVector &qdot2, const JointVector *target = nullptr) const;
  /*!
    The whole law for one step: the gain, the primary step, the joint-limit avoidance (no target); returns the gain.
    \e ne holds the step's normal equations (\f$ J^T J \f$ n x n, \f$ J^T e \f$ n x 1) and their factorisations,
    shared by the three; \e errorInf is \f$ \|e\|_\infty \f$ (pixels), \e errorNorm \f$ \|e\|_2 \f$ in the unit of the
    error.
  */
  double computeStep(const JointVector &q, const vpServoNormalEquations &ne, double errorInf, double errorNorm,
                     JointVector &qdot, JointVector &qdot2);
  /*!
    A step that crosses no joint limit: each joint whose share of \e qdot would cross one is held (its column out of
    the normal equations \e ne, the primary step solved again with the gain \e lambda: a new system, factorised
    anew), until none crosses; then the step is scaled to stay inside (a joint already beyond its limit). Without
    limits \e qdot is unchanged.
  */
  void keepInside(const JointVector &q, const vpServoNormalEquations &ne, double lambda, JointVector &qdot) const;
  //@}

private:
  vpAdaptiveGain m_lambda;
  vpGainInput m_gainInput;
  double m_period;
  double m_qdotMax;
  double m_errorScale;
  vpServoDampedLeastSquares m_dls;
  vpServoJointLimitAvoidance m_limits;
  vpServoSettling m_settling;
};

END_VISP_NAMESPACE

#endif
