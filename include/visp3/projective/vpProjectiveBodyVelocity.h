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
  \file vpProjectiveBodyVelocity.h
  \brief Projective body velocities (pse(3)) of rigid motions seen by an uncalibrated stereo rig.
*/

#ifndef _vpProjectiveBodyVelocity_h_
#define _vpProjectiveBodyVelocity_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveDisplacement.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveBodyVelocity
  \ingroup group_projective
  \brief The projective body velocity \f$ \hat H = \dot H H^{-1} \f$ of a rigid motion \f$ H(t) \f$ (Ruf & Horaud,
  section 4, eqs. (13)-(16)): an element of pse(3), per unit of time.

  It is \f$ \hat H = H_{PE}^{-1} \hat T H_{PE} \f$ (14) with \f$ \hat T \in se(3) \f$ the spatial velocity of the
  motion in the metric frame of the left camera: the 4x4 matrix of angular velocity \f$ \omega \f$ (rad per time
  unit) and linear velocity \f$ v \f$ (length per time unit) of vpMetricTwist. A projective point \f$ M \f$ moving
  with the body has the velocity (16)
  \f[ \dot M = \hat H M = \rho\, H_{PE}^{-1} \dot N, \f]
  \f$ \rho \f$ its orbit height (vpProjectiveArmModel::orbitHeight()) and \f$ \dot N \f$ its metric velocity.

  Velocities are estimated from displacements, which the rig measures: between two displacements, assuming a constant
  velocity, \f$ \hat H = \log(H_1 H_0^{-1}) / (t_1 - t_0) \f$ (vpProjectiveDisplacement::log()); over a sequence, by
  the least-squares slope of the logarithms around a sample, which smooths the noise of single displacements.

  The velocity \f$ \hat H \f$ is matrix(), an Eigen matrix; a ViSP program converts it to a vpMatrix with ViSP's
  eigen2visp(), as vpProjectiveDisplacement and the page \ref page_groups show.
*/
class VISP_EXPORT vpProjectiveBodyVelocity
{
public:
  //! No motion.
  vpProjectiveBodyVelocity();
  /*!
    A velocity \e Hhat (4x4 pse(3) element per time unit).
    \exception vpProjectiveException if it is not finite.
  */
  explicit vpProjectiveBodyVelocity(const Eigen::Matrix4d &Hhat);

  /*!
    The constant velocity that moves \e H0 (at time t) to \e H1 (at time t + dt): \f$ \log(H_1 H_0^{-1}) / dt \f$.
    \exception vpProjectiveException (invalidValueError) if \e dt is not positive and finite; as
    vpProjectiveDisplacement::log() if the body turned by half a turn in between.
  */
  static vpProjectiveBodyVelocity fromDisplacements(const vpProjectiveDisplacement &H0,
                                                    const vpProjectiveDisplacement &H1, double dt);
  /*!
    The smoothed velocity at sample \e k of a sequence of displacements \e H at times \e t: the least-squares slope
    \f[ \hat H_k = \frac{\sum_j (t_j - t_k) \log(H_j H_k^{-1})}{\sum_j (t_j - t_k)^2} \f]
    over the samples \f$ |j - k| \le \f$ \e halfWindow (clipped at the ends of the sequence: at the last sample the fit
    is one-sided, as a real-time filter needs). The fit is linear in the logarithms, so it commutes with the change
    of projective frame: it is the same in every frame. With noise \f$ \sigma \f$ on the logarithms and a window of
    \f$ w \f$ samples at period \f$ \Delta t \f$, its noise falls as \f$ \sigma / (\Delta t\, w^{3/2}) \f$.
    \exception vpProjectiveException (dimensionError, invalidValueError) if the sizes differ, \e k is out of range,
    \e halfWindow is 0, or the times are not finite and strictly increasing.
  */
  static vpProjectiveBodyVelocity fromSequence(const std::vector<vpProjectiveDisplacement> &H,
                                               const std::vector<double> &t, size_t k, size_t halfWindow);

  //! \f$ \hat H \f$ (4x4); as a vpMatrix: see the class description.
  const Eigen::Matrix4d &matrix() const { return m_Hhat; }
  //! The displacement \f$ \exp(\hat H\, dt) \f$ of the motion during \e dt at this velocity.
  vpProjectiveDisplacement integrate(double dt) const;

  //! Point velocity (16) \f$ \dot M = \hat H M \f$ (4x1) of the projective point \e M (4x1) moving with the body.
  Eigen::Vector4d pointVelocity(const Eigen::Vector4d &M) const { return m_Hhat * M; }
  /*!
    \overload
    \exception vpProjectiveException (dimensionError, nonFiniteValueError) if \e M is not a finite 4-vector.
  */
  vpColVector pointVelocity(const vpColVector &M) const;

  /*!
    The metric twist \f$ (v, \omega) \f$ (6x1: linear velocity, then angular velocity in rad per time unit) of
    \f$ G \hat H G^{-1} \f$ in the frame of \e G (4x4, projective to metric, such as
    vpProjectiveArmModel::projectiveToMetric(): then \f$ v \f$ is in that frame's length unit per time unit).
    \exception vpProjectiveException if \e G is not 4x4, not finite or singular.
  */
  vpColVector getTwist(const vpMatrix &G) const;

private:
  Eigen::Matrix4d m_Hhat;
};

END_VISP_NAMESPACE

#endif
