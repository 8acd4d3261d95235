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
  \file vpProjectiveRotation.h
  \brief Projective rotations (p-rotations): the one-parameter Lie subgroup of a revolute joint.
*/

#ifndef _vpProjectiveRotation_h_
#define _vpProjectiveRotation_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <cmath>

#include <Eigen/Core>

#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveJointSubgroup.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveRotation
  \ingroup group_projective
  \brief A p-rotation \f$ H_R(\theta) = \exp(\theta \hat H_R) \f$: a rotation about a fixed axis seen in the
  projective frame of a weakly calibrated rig (Ruf & Horaud, section 5.1, eqs. (18)-(27)).

  The generator \f$ \hat H_R \f$ (4x4) is \f$ H_{PE}^{-1} \hat T_R H_{PE} \f$, \f$ \hat T_R \in se(3) \f$ a unit-speed
  rotational twist (vpMetricTwist::revolute()). Equivalently \f$ \hat H_R = k_2 h_1^T - k_1 h_2^T \f$ with
  \f$ h_i^T k_j = \delta_{ij} \f$ (27). It satisfies \f$ \hat H_R^3 = -\hat H_R \f$ and has rank 2, which gives
  - the exponential, Rodrigues' form (26): \f$ \exp(\theta \hat H_R) = I + \sin\theta\, \hat H_R + (1 - \cos\theta)
    \hat H_R^2 \f$;
  - the logarithm (25) of a normalised p-rotation \f$ H \f$ with angle \f$ \theta \in (0, \pi) \f$ from (21):
    \f$ \hat H_R = (H - H^{-1}) / (2 \sin\theta) \f$;
  - the derivative \f$ \frac{d}{d\theta} \exp(\theta \hat H_R) = \hat H_R \exp(\theta \hat H_R) \f$;
  - the inverse \f$ \exp(\theta \hat H_R)^{-1} = \exp(-\theta \hat H_R) \f$.

  The generator is unique although the Jordan decomposition of \f$ H_R \f$ is not.

  The group API is the one of vpProjectiveDisplacement and vpProjectiveTranslation (see vpProjectiveDisplacement,
  Group operations, and the page \ref page_groups): the kernels exp(Hhat, q) and act(Hhat, q, M), log(H, amount),
  and for the elements exp(q) returns, their inverse(), operator*() and act(M); with dexp(), generator(), project()
  and generatorResidual() shared by the two joint subgroups, so that generic code and tests treat the groups alike.
  What the two share is written once in their base vpProjectiveJointSubgroup: generator(), exp(theta)
  and the checks of the constructors. vpProjectiveJoint dispatches on a joint's type.
*/
class VISP_EXPORT vpProjectiveRotation : public vpProjectiveJointSubgroup<vpProjectiveRotation>
{
public:
  //! Zero generator (no motion); set one with the constructor or log().
  vpProjectiveRotation() = default;
  /*!
    Takes a generator (4x4). \exception vpProjectiveException if it is not finite, not 4x4, or violates
    \f$ \hat H^3 = -\hat H \f$ (26) by more than \e tolerance relative to \f$ \|\hat H\| \f$ (generatorResidual()).
  */
  explicit vpProjectiveRotation(const vpMatrix &Hhat, double tolerance = 1e-6)
      : vpProjectiveJointSubgroup(Hhat, tolerance)
  {
  }
  //! \overload
  explicit vpProjectiveRotation(const Eigen::Matrix4d &Hhat, double tolerance = 1e-6)
      : vpProjectiveJointSubgroup(Hhat, tolerance)
  {
  }

  /*!
    Logarithm (25) of a p-rotation: the generator \f$ \hat H_R \f$ with \f$ H = \exp(\theta \hat H_R) \f$, projected on
    the exact generators (see project()). \e H is normalised by eq. (12) on construction.

    \e amount is the signed angle (radians) read by the joint's encoder, or 0 when there is none. With an amount the
    generator is \f$ (H - H^{-1}) / (2 \sin(\mathrm{amount})) \f$, so that \f$ H = \exp(\mathrm{amount}\, \hat H_R)
    \f$ up to the noise in \e H: the encoder is more reliable than the trace of a noisy \e H, and fixes the
    generator's sign; \e H is then trusted to be a rotation (the eigenvalues of a homography estimated from a few
    markers are too noisy to tell). With 0 the image angle \f$ \theta \in (0, \pi) \f$ of eq. (21)
    (vpProjectiveDisplacement::getRotationAngle()) is used, and the generator turns by a positive angle.
    \exception vpProjectiveException if \e amount is not finite, or the angle used is too close to a multiple of
    \f$ \pi \f$ for the logarithm to be defined.
  */
  static vpProjectiveRotation log(const vpProjectiveDisplacement &H, double amount);

  //! The p-rotation \f$ \exp(\theta \hat H_R) \f$ by Rodrigues' form (26): the kernel exp(generator(), theta).
  using vpProjectiveJointSubgroup::exp;
  //! \f$ \frac{d}{d\theta} \exp(\theta \hat H_R) = \hat H_R \exp(\theta \hat H_R) \f$ (4x4).
  Eigen::Matrix4d dexp(double theta) const;

  /*!
    Rodrigues' form (26), \f$ \exp(\theta \hat H) = I + \sin\theta\, \hat H + (1 - \cos\theta) \hat H^2 \f$ (4x4), for
    any \e Hhat with \f$ \hat H^3 = -\hat H \f$: the plugin's one exponential of a revolute joint, templated on the
    scalar (double, or a Ceres Jet for automatic differentiation), unchecked. Same signature as
    vpProjectiveDisplacement::exp(Hhat, q), whose general series it specialises.
  */
  template <typename T> static Eigen::Matrix<T, 4, 4> exp(const Eigen::Matrix<T, 4, 4> &Hhat, const T &theta)
  {
    using std::cos;
    using std::sin;
    return Eigen::Matrix<T, 4, 4>::Identity() + sin(theta) * Hhat + (T(1.0) - cos(theta)) * (Hhat * Hhat);
  }
  /*!
    \f$ \exp(\theta \hat H) M \f$ (4x1) from the same form (26), with two matrix-vector products instead of a 4x4
    product.
  */
  template <typename T>
  static Eigen::Matrix<T, 4, 1> act(const Eigen::Matrix<T, 4, 4> &Hhat, const T &theta, const Eigen::Matrix<T, 4, 1> &M)
  {
    using std::cos;
    using std::sin;
    const Eigen::Matrix<T, 4, 1> HM = Hhat * M;
    return M + sin(theta) * HM + (T(1.0) - cos(theta)) * (Hhat * HM);
  }

  /*!
    Closest exact generator to an approximate one (for instance an average of noisy logarithms): in the eigenbasis of
    \e Hhat, the conjugate pair of eigenvalues nearest to \f$ \pm i \f$ is set to exactly \f$ \pm i \f$ and the
    two others to 0, so that \f$ \hat H^3 = -\hat H \f$ and rank 2 hold exactly. An exact generator is unchanged.
  */
  static Eigen::Matrix4d project(const Eigen::Matrix4d &Hhat);

  //! \f$ \|\hat H^3 + \hat H\|_F / \|\hat H\|_F \f$: zero for an exact p-rotation generator.
  static double generatorResidual(const Eigen::Matrix4d &Hhat);
};

END_VISP_NAMESPACE

#endif
