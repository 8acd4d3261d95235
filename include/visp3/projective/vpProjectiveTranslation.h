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
  \file vpProjectiveTranslation.h
  \brief Projective translations (p-translations): the one-parameter Lie subgroup of a prismatic joint.
*/

#ifndef _vpProjectiveTranslation_h_
#define _vpProjectiveTranslation_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <Eigen/Core>

#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveJointSubgroup.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveTranslation
  \ingroup group_projective
  \brief A p-translation \f$ H_T(\tau) = \exp(\tau \hat H_T) = I + \tau \hat H_T \f$: a translation along a fixed
  direction seen in the projective frame of a weakly calibrated rig (Ruf & Horaud, section 5.2, eqs. (28)-(31)).

  The generator \f$ \hat H_T = k_3 h_4^T \f$ (4x4, rank 1) is the product of the direction's vanishing point
  \f$ k_3 \f$ and the plane at infinity \f$ h_4^T \f$ (30). It is \f$ H_{PE}^{-1} \hat T_T H_{PE} \f$ with
  \f$ \hat T_T \in se(3) \f$ a translation of unit speed (metres per unit of \f$ \tau \f$, vpMetricTwist::prismatic()),
  and it is nilpotent: \f$ \hat H_T^2 = 0 \f$, so
  - the exponential is exact at first order (31): \f$ \exp(\tau \hat H_T) = I + \tau \hat H_T \f$;
  - the logarithm of a normalised p-translation \f$ H_T \f$ of encoder-measured length \f$ \tau \f$ is
    \f$ \hat H_T = (H_T - I) / \tau \f$;
  - the derivative is \f$ \frac{d}{d\tau} \exp(\tau \hat H_T) = \hat H_T = \hat H_T \exp(\tau \hat H_T) \f$, and the
    inverse is \f$ I - \tau \hat H_T \f$.

  The group API is the one of vpProjectiveDisplacement and vpProjectiveRotation (see there and the page
  \ref page_groups); generator(), exp(tau) and the checks of the constructors are written once in the base
  vpProjectiveJointSubgroup.
*/
class VISP_EXPORT vpProjectiveTranslation : public vpProjectiveJointSubgroup<vpProjectiveTranslation>
{
public:
  //! Zero generator (no motion).
  vpProjectiveTranslation() = default;
  /*!
    Takes a generator (4x4). \exception vpProjectiveException if it is not finite, not 4x4, or violates
    \f$ \hat H^2 = 0 \f$ (31) by more than \e tolerance relative to \f$ \|\hat H\|^2 \f$ (generatorResidual()).
  */
  explicit vpProjectiveTranslation(const vpMatrix &Hhat, double tolerance = 1e-6)
      : vpProjectiveJointSubgroup(Hhat, tolerance)
  {
  }
  //! \overload
  explicit vpProjectiveTranslation(const Eigen::Matrix4d &Hhat, double tolerance = 1e-6)
      : vpProjectiveJointSubgroup(Hhat, tolerance)
  {
  }

  /*!
    Logarithm of a p-translation of length \e amount (31): \f$ \hat H_T = (H_T - I) / \tau \f$, \f$ \tau \f$ =
    \e amount, the signed length read by the joint's encoder (the length of a translation cannot be seen by an
    uncalibrated rig, so it is required). The result is projected on the closest exact generator (see project()), so
    that \f$ \hat H_T^2 = 0 \f$ holds up to the noise of H.
    \exception vpProjectiveException if \e amount is zero or not finite.
  */
  static vpProjectiveTranslation log(const vpProjectiveDisplacement &H, double amount);

  //! The p-translation \f$ I + \tau \hat H_T \f$ (31): the kernel exp(generator(), tau).
  using vpProjectiveJointSubgroup::exp;
  //! \f$ \frac{d}{d\tau} \exp(\tau \hat H_T) = \hat H_T \f$ (4x4).
  Eigen::Matrix4d dexp(double tau) const;

  /*!
    \f$ \exp(\tau \hat H) = I + \tau \hat H \f$ (31) (4x4) for any \e Hhat with \f$ \hat H^2 = 0 \f$: the plugin's one
    exponential of a prismatic joint, templated on the scalar (double, or a Ceres Jet), unchecked. Same signature as
    vpProjectiveDisplacement::exp(Hhat, q), whose general series it specialises.
  */
  template <typename T> static Eigen::Matrix<T, 4, 4> exp(const Eigen::Matrix<T, 4, 4> &Hhat, const T &tau)
  {
    return Eigen::Matrix<T, 4, 4>::Identity() + tau * Hhat;
  }
  //! \f$ \exp(\tau \hat H) M = M + \tau \hat H M \f$ (4x1).
  template <typename T>
  static Eigen::Matrix<T, 4, 1> act(const Eigen::Matrix<T, 4, 4> &Hhat, const T &tau, const Eigen::Matrix<T, 4, 1> &M)
  {
    return M + tau * (Hhat * M);
  }

  /*!
    Closest exact generator to an approximate one: the best rank-1 approximation \f$ \sigma u v^T \f$ with \f$ u \f$
    made orthogonal to \f$ v \f$, so that \f$ \hat H^2 = 0 \f$ holds exactly. An exact generator is unchanged.
  */
  static Eigen::Matrix4d project(const Eigen::Matrix4d &Hhat);

  //! \f$ \|\hat H^2\|_F / \|\hat H\|_F^2 \f$: zero for an exact p-translation generator.
  static double generatorResidual(const Eigen::Matrix4d &Hhat);
};

END_VISP_NAMESPACE

#endif
