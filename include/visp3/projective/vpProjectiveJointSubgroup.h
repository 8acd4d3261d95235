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
  \file vpProjectiveJointSubgroup.h
  \brief The part that the two one-parameter subgroups of the joints (p-rotations, p-translations) share.
*/

#ifndef _vpProjectiveJointSubgroup_h_
#define _vpProjectiveJointSubgroup_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>

#include <Eigen/Core>

#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveDisplacement.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveJointSubgroup
  \ingroup group_projective
  \brief A one-parameter subgroup \f$ \{ \exp(q \hat H),\ q \in \mathbb{R} \} \f$ of the p-displacements, held by its
  generator \f$ \hat H \f$ (4x4): the common base of vpProjectiveRotation (a revolute joint, \e q in radians) and
  vpProjectiveTranslation (a prismatic joint, \e q in the encoder's length unit), written once by the curiously
  recurring template pattern, as manif and Sophus write their groups.

  The base holds the generator and gives what does not depend on the kind of joint: generator() (Eigen, as Sophus and
  manif give their groups' matrices; a ViSP program converts it to a vpMatrix with ViSP's eigen2visp(), as
  vpProjectiveDisplacement and the page \ref page_groups show); the element \f$ \exp(q \hat H) \f$ of the
  subgroup, exp(q), a normalised vpProjectiveDisplacement computed by Derived's closed form; and the checked
  constructors, which accept a finite \f$ \hat H \f$ whose relative defect Derived::generatorResidual() to the
  generator identity of its kind (\f$ \hat H^3 = -\hat H \f$, eq. (26), or \f$ \hat H^2 = 0 \f$, eq. (31)) is at most
  a tolerance \f$ \ge 0 \f$. The zero matrix (no motion) is accepted by both kinds.

  \tparam Derived The subgroup: vpProjectiveRotation or vpProjectiveTranslation, the two for which the library
  instantiates this template (src/groups/vpProjectiveJointSubgroup.cpp). It derives publicly from
  vpProjectiveJointSubgroup<Derived> and provides:
  - the kernel <tt>template \<typename T\> static Eigen::Matrix\<T, 4, 4\> exp(const Eigen::Matrix\<T, 4, 4\>
    &Hhat, const T &q)</tt>: the closed-form exponential of its generators, unchecked. It hides the base's exp(q)
    member, so Derived brings that one back with <tt>using vpProjectiveJointSubgroup::exp;</tt>;
  - <tt>static double generatorResidual(const Eigen::Matrix4d &Hhat)</tt>: the relative defect of its identity, zero
    for an exact generator and for the zero matrix.

  The library's source src/groups/vpProjectiveJointSubgroup.cpp gives each Derived, beside its explicit
  instantiation, the words of the error on a rejected generator (the explicit specialization of the private
  <tt>s_identity</tt>): the class name, the kind ("p-rotation"), the defect written out ("|Hhat^3 + Hhat| / |Hhat|")
  and the equation it measures ("eq. (26) needs Hhat^3 = -Hhat").
*/
template <typename Derived> class VISP_EXPORT vpProjectiveJointSubgroup
{
public:
  //! The p-displacement \f$ \exp(q \hat H) \f$ by Derived's closed form, the kernel Derived::exp(generator(), q).
  vpProjectiveDisplacement exp(double q) const;

  //! The generator \f$ \hat H \f$ (4x4); as a vpMatrix: see the class description.
  const Eigen::Matrix4d &generator() const { return m_Hhat; }

protected:
  //! Zero generator (no motion).
  vpProjectiveJointSubgroup();
  /*!
    Takes a generator (4x4). \exception vpProjectiveException (nonFiniteValueError) if it is not finite;
    (invalidValueError) if \e tolerance is negative or not a number, or Derived::generatorResidual(Hhat) exceeds it.
  */
  vpProjectiveJointSubgroup(const Eigen::Matrix4d &Hhat, double tolerance);
  /*!
    \overload
    \exception vpProjectiveException also if \e Hhat is not 4x4.
  */
  vpProjectiveJointSubgroup(const vpMatrix &Hhat, double tolerance);

  //! The subgroup of an exact generator, unchecked (the logarithms, whose result is projected).
  static Derived fromExactGenerator(const Eigen::Matrix4d &Hhat)
  {
    Derived subgroup;
    static_cast<vpProjectiveJointSubgroup &>(subgroup).m_Hhat = Hhat;
    return subgroup;
  }

private:
  //! The words of the error on a rejected generator (see the template parameter Derived).
  struct vpIdentity {
    const char *className; //!< "vpProjectiveRotation"
    const char *kind;      //!< "p-rotation"
    const char *residual;  //!< the defect written out: "|Hhat^3 + Hhat| / |Hhat|"
    const char *identity;  //!< the equation the defect measures: "eq. (26) needs Hhat^3 = -Hhat"
  };
  //! Derived's words: an explicit specialization, defined beside the explicit instantiation.
  static const vpIdentity s_identity;

  //! "vpProjectiveRotation::vpProjectiveRotation()": where the constructors' errors come from.
  static std::string constructorSite();

  Eigen::Matrix4d m_Hhat;
};

END_VISP_NAMESPACE

#endif
