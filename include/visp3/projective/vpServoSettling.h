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
  \file vpServoSettling.h
  \brief The settling gain of vpServoProjective: once converged, average the frames instead of chasing their noise.
*/

#ifndef _vpServoSettling_h_
#define _vpServoSettling_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoNormalEquations.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoSettling
  \ingroup group_projective
  \brief The settling gain of vpServoProjective::setSettling(): at the noise floor, a gain that decreases as
  \f$ 1/k \f$, so that the commanded joints become the running mean of the per-frame estimates of the target.

  With the law \f$ \dot q = -\lambda J^+ e \f$ and a constant \f$ \lambda \f$, the joints at rest keep a fraction
  \f$ \lambda / (2 - \lambda) \f$ of the variance of each frame's estimate \f$ q - J^+ e \f$ of the target (1/3 at
  \f$ \lambda = 0.5 \f$): the end pose jitters at the single-frame floor. Settled, the \f$ k \f$-th call
  (\f$ k = 0, 1, \ldots \f$) uses
  \f[ \lambda_k = \frac{\lambda}{1 + \lambda k}, \qquad k \le K \f]
  (\f$ K \f$: the horizon): \f$ \lambda_0 = \lambda \f$ (no jump at the switch) and, where the task is linear (no
  damping, no saturation), the joints after \f$ k \f$ settled calls are the mean of the \f$ k \f$ frames' estimates and
  of the joints settling began at, counted as \f$ 1/\lambda - 1 \f$ frames; beyond \f$ K \f$ the gain stays at \f$
  \lambda_K \f$, an exponential average over about \f$ K \f$ frames, which follows a slow drift.

  Every quantity comes from the normal equations of the call (\f$ J^T J \f$, \f$ J^T e \f$, \f$ \|e\|^2 \f$, in
  pixels) and the number \f$ m = 4 N_{active} \f$ of rows, without allocation, with the Gauss-Newton step
  \f$ g = (J^T J)^{-1} J^T e \f$ (n x 1, joint units):
  - the part of the error that a joint motion explains, \f$ \chi = e^T J g = (J^T e)^T g \f$ (pixels squared,
    \f$ n \f$ degrees of freedom), and the part that none does, \f$ r = \|e\|^2 - \chi \f$ (\f$ m - n \f$ degrees
    of freedom: the features' noise, the epipolar rows included, and the model's error);
  - converged: the explained part per degree of freedom is at most 3 times the unexplained part per degree of
    freedom, \f$ (\chi / n) \le 3\, r / (m - n) \f$, on 2 consecutive calls. The test needs no noise level: far from
    the target the explained part dominates (a model error a few percent of the motion cannot raise \f$ r \f$ as
    much), at the floor both are noise (the ratio is then F-distributed, below 3 nine times in ten for 3 points and 6
    joints). It is the predicted step \f$ g \f$ being within the noise of one frame. Settling starts then;
  - the noise estimate \f$ \hat\sigma^2 \f$ (pixels squared per row) is the running mean of \f$ r / (m - n) \f$ over
    the calls that passed the convergence test and the settled ones (at most the horizon's);
  - re-engagement: settled, a call whose explained part is not noise,
    \f$ (\chi / n) / \hat\sigma^2 > F_{n, \nu}(1 - 10^{-4}) \f$ (\f$ \hat\sigma^2 \f$ of the calls before, with
    its \f$ \nu \f$ degrees of freedom; the quantile by Paulson's approximation: 4.7 to 6 for 6 joints), falls back
    to the full gain \f$ \lambda \f$ at once: the target moved, the arm was bumped.
    The test then starts again. So does any call that is not a plain law (47) on the same task: see reset().

  The unit of setErrorUnit() does not enter: the statistics are ratios and the law is in pixels. Needs
  \f$ m > n \f$ (with fewer rows there is no noise to estimate, and the gain stays \f$ \lambda \f$).
*/
class VISP_EXPORT vpServoSettling
{
public:
  //! Joint values (n x 1) without heap allocation.
  typedef vpProjectiveArmModel::JointVector JointVector;
  //! An n x n matrix without heap allocation.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;

  //! Off, horizon 100.
  vpServoSettling();

  /*!
    Settling on or off (off: gain() returns \f$ \lambda \f$), and its horizon \f$ K \ge 1 \f$ (calls).
    \exception vpProjectiveException (invalidValueError) if \e horizon is 0.
  */
  void setEnabled(bool enabled, unsigned int horizon = 100);
  //! True if settling is on.
  bool isEnabled() const { return m_enabled; }
  //! The horizon \f$ K \f$ of setEnabled().
  unsigned int getHorizon() const { return m_horizon; }

  /*!
    The gain for this call, from the task gain \e lambda and this call's normal equations (see the class
    documentation); the new state is kept aside until commit().
    \param lambda : the task's gain \f$ \lambda > 0 \f$.
    \param ne : the normal equations of the active features (\f$ J^T J \f$ n x n, \f$ J^T e \f$ n x 1, pixels) and
    their Gauss-Newton step, the law's.
    \param errorSquaredNorm : \f$ \|e\|^2 \f$ (pixels squared).
    \param rows : \f$ m \f$, the rows of the active features (4 per feature).
    \param context : a number that changes when the task changes (the active features, the targets): settling
    restarts when it differs from the last call's.
  */
  double gain(double lambda, const vpServoNormalEquations &ne, double errorSquaredNorm, unsigned int rows,
              unsigned long context);
  //! The call is not a law (47) on a settled task (stopped, following a path, ...): full gain from the next one.
  void reset();
  //! Makes the state of the last gain() or reset() the current one (a control law call that succeeded).
  void commit() { m_state = m_next; }

  //! True if the last committed call used the settling gain.
  bool isSettled() const { return m_state.settled; }
  //! Settled calls so far (\f$ k \f$), 0 when not settled.
  unsigned int getSettledIterations() const { return m_state.k; }
  //! \f$ \hat\sigma \f$ (pixels per row), 0 before settling.
  double getNoiseEstimate() const;
  //! \f$ \chi / \hat\sigma^2 \f$ of the last call (settled), or the ratio of the convergence test (not settled).
  double getStatistic() const { return m_state.statistic; }

private:
  struct vpState {
    bool settled = false;
    unsigned int k = 0;        // settled calls
    unsigned int quiet = 0;    // consecutive calls passing the convergence test
    double noise2 = 0.0;       // running mean of r / (m - n) over the quiet and settled calls
    double frames = 0.0;       // calls in that mean (at most the horizon)
    double statistic = 0.0;    // the last test's statistic
    unsigned long context = 0; // the task the state belongs to
  };
  bool m_enabled;
  unsigned int m_horizon;
  vpState m_state, m_next;
};

END_VISP_NAMESPACE

#endif
