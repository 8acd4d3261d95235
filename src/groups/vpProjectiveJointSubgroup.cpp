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

#include <visp3/projective/vpProjectiveJointSubgroup.h>

#include <sstream>
#include <string>

#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveTranslation.h>

#include "core/vpProjectiveConversions.h"

// The definitions and the explicit instantiations stand in the namespace of the template, which an explicit
// instantiation by its unqualified name requires. The instantiations are exported by the VISP_EXPORT of the template
// (an attribute on an explicit instantiation of an already defined class is ignored by GCC).
BEGIN_VISP_NAMESPACE

template <typename Derived> std::string vpProjectiveJointSubgroup<Derived>::constructorSite()
{
  return vpProjectiveInternal::vpErrorSite(s_identity.className)((std::string(s_identity.className) + "()").c_str());
}

template <typename Derived>
vpProjectiveJointSubgroup<Derived>::vpProjectiveJointSubgroup() : m_Hhat(Eigen::Matrix4d::Zero())
{
}

template <typename Derived>
vpProjectiveJointSubgroup<Derived>::vpProjectiveJointSubgroup(const Eigen::Matrix4d &Hhat, double tolerance)
    : m_Hhat(Hhat)
{
  using vpProjectiveInternal::fail;
  if (!Hhat.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, constructorSite(), "the generator has a NaN or infinite entry");
  }
  if (!(tolerance >= 0.0)) {
    fail(vpProjectiveException::invalidValueError, constructorSite(), "the tolerance must be non-negative");
  }
  const double residual = Derived::generatorResidual(Hhat);
  if (residual > tolerance) {
    std::ostringstream os;
    os << "not a " << s_identity.kind << " generator: " << s_identity.residual << " = " << residual << " exceeds "
       << tolerance << " (" << s_identity.identity << ")";
    fail(vpProjectiveException::invalidValueError, constructorSite(), os.str());
  }
}

template <typename Derived>
vpProjectiveJointSubgroup<Derived>::vpProjectiveJointSubgroup(const vpMatrix &Hhat, double tolerance)
    : vpProjectiveJointSubgroup(vpProjectiveInternal::toEigen<4, 4>(Hhat, constructorSite(), "Hhat"), tolerance)
{
}

template <typename Derived> vpProjectiveDisplacement vpProjectiveJointSubgroup<Derived>::exp(double q) const
{
  return vpProjectiveDisplacement(Derived::exp(m_Hhat, q), vpProjectiveDisplacement::vpNormalized());
}

// The subgroups: the words of their errors, and the instantiations that the shared library exports.
template <>
const vpProjectiveJointSubgroup<vpProjectiveRotation>::vpIdentity
    vpProjectiveJointSubgroup<vpProjectiveRotation>::s_identity = {
        "vpProjectiveRotation", "p-rotation", "|Hhat^3 + Hhat| / |Hhat|", "eq. (26) needs Hhat^3 = -Hhat"};
template class vpProjectiveJointSubgroup<vpProjectiveRotation>;

template <>
const vpProjectiveJointSubgroup<vpProjectiveTranslation>::vpIdentity
    vpProjectiveJointSubgroup<vpProjectiveTranslation>::s_identity = {
        "vpProjectiveTranslation", "p-translation", "|Hhat^2| / |Hhat|^2", "eq. (31) needs Hhat^2 = 0"};
template class vpProjectiveJointSubgroup<vpProjectiveTranslation>;

END_VISP_NAMESPACE
