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
  \file vpMetricTwist.h
  \brief Twists of se(3), the metric Lie algebra whose projective image the plugin works in: hat, vee, and the unit
  twists of revolute and prismatic joints.
*/

#ifndef _vpMetricTwist_h_
#define _vpMetricTwist_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <Eigen/Core>

BEGIN_VISP_NAMESPACE

/*!
  \class vpMetricTwist
  \ingroup group_projective
  \brief The metric twists \f$ \hat T \in se(3) \f$ (4x4) of rigid motions (Ruf & Horaud, eq. (9)), the one place
  where the plugin builds or reads them.

  A twist \f$ \xi = (v, \omega) \f$ (linear part first, as ViSP's velocity twists) has the 4x4 matrix
  \f[ \hat T = \begin{bmatrix} [\omega]_\times & v \\ 0 & 0 \end{bmatrix}, \qquad
      [\omega]_\times = \begin{bmatrix} 0 & -\omega_3 & \omega_2 \\ \omega_3 & 0 & -\omega_1 \\
      -\omega_2 & \omega_1 & 0 \end{bmatrix}, \f]
  and a point \f$ X \f$ moving with it has the velocity \f$ \omega \times X + v \f$. Its projective image is
  \f$ \hat H = H_{PE}^{-1} \hat T H_{PE} \f$, a generator of pse(3).

  The functions are templates on the scalar, so that Ceres' automatic differentiation uses them as they are.
*/
class VISP_EXPORT vpMetricTwist
{
public:
  //! \f$ [\omega]_\times \f$ (3x3), the so(3) hat: \f$ [\omega]_\times x = \omega \times x \f$.
  template <typename T> static Eigen::Matrix<T, 3, 3> skew(const Eigen::Matrix<T, 3, 1> &w)
  {
    Eigen::Matrix<T, 3, 3> S;
    S << T(0.0), -w(2), w(1), w(2), T(0.0), -w(0), -w(1), w(0), T(0.0);
    return S;
  }

  //! \f$ \hat T \f$ (4x4) of the twist \f$ (v, \omega) \f$, the se(3) hat.
  template <typename T>
  static Eigen::Matrix<T, 4, 4> hat(const Eigen::Matrix<T, 3, 1> &v, const Eigen::Matrix<T, 3, 1> &w)
  {
    Eigen::Matrix<T, 4, 4> That = Eigen::Matrix<T, 4, 4>::Zero();
    That.template topLeftCorner<3, 3>() = skew(w);
    That.template topRightCorner<3, 1>() = v;
    return That;
  }

  /*!
    \f$ (v, \omega) \f$ (6x1) of a 4x4 twist matrix, the se(3) vee; the skew-symmetric part of its upper-left block
    is read, so that a noisy matrix gives its nearest twist.
  */
  template <typename T> static Eigen::Matrix<T, 6, 1> vee(const Eigen::Matrix<T, 4, 4> &That)
  {
    Eigen::Matrix<T, 6, 1> xi;
    xi.template head<3>() = That.template topRightCorner<3, 1>();
    xi(3) = T(0.5) * (That(2, 1) - That(1, 2));
    xi(4) = T(0.5) * (That(0, 2) - That(2, 0));
    xi(5) = T(0.5) * (That(1, 0) - That(0, 1));
    return xi;
  }

  /*!
    Unit twist of a revolute joint: rotation at unit speed about the axis of direction \e axis (unit, 3x1) through
    \e point (3x1), \f$ v = p \times \omega \f$, so that a point on the axis does not move.
  */
  template <typename T>
  static Eigen::Matrix<T, 4, 4> revolute(const Eigen::Matrix<T, 3, 1> &axis, const Eigen::Matrix<T, 3, 1> &point)
  {
    return hat<T>(point.cross(axis), axis);
  }

  /*!
    Twist of a prismatic joint: translation by \e direction (3x1) per unit of joint motion (its length is the
    joint's unit, metres per encoder unit).
  */
  template <typename T> static Eigen::Matrix<T, 4, 4> prismatic(const Eigen::Matrix<T, 3, 1> &direction)
  {
    return hat<T>(direction, Eigen::Matrix<T, 3, 1>::Zero());
  }
};

END_VISP_NAMESPACE

#endif
