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

/*
  Private: conversions between ViSP and Eigen types that validate sizes and finiteness on the way in (user input) or
  copy unchecked (values the library produced). Not installed.
*/

#ifndef _vpProjectiveConversions_h_
#define _vpProjectiveConversions_h_

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpEigenConversion.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>

#include "core/vpProjectiveErrors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#ifndef VISP_HAVE_EIGEN3
#error "visp_projective needs a ViSP built with Eigen3 (USE_EIGEN3=ON): it converts through ViSP's vpEigenConversion.h"
#endif

namespace vpProjectiveInternal
{
/*
  ViSP's own conversions (vpEigenConversion.h) do the copies: ViSP 3.5 and 3.6 declare them in namespace vp, ViSP 3.7
  in VISP_NAMESPACE_NAME (visp), whether or not its classes are in that namespace.
*/
#ifdef VISP_NAMESPACE_NAME
namespace conversion = VISP_NAMESPACE_NAME;
#else
namespace conversion = vp;
#endif

//! The top-left R x C entries of a ViSP matrix or transform, unchecked: for values the library itself produced.
template <int R, int C, typename Array> Eigen::Matrix<double, R, C> toEigenUnchecked(const Array &A)
{
  Eigen::MatrixXd E(A.getRows(), A.getCols());
  conversion::visp2eigen(A, E);
  return E.topLeftCorner<R, C>();
}

//! A rigid 4x4 Eigen matrix as a vpHomogeneousMatrix (its last row is taken to be (0, 0, 0, 1)).
inline vpHomogeneousMatrix toHomogeneous(const Eigen::Matrix4d &E)
{
  vpHomogeneousMatrix M;
  conversion::eigen2visp(Eigen::MatrixXd(E), M);
  return M;
}

//! A vpMatrix of exactly R x C finite entries, as an Eigen fixed-size matrix.
template <int R, int C>
Eigen::Matrix<double, R, C> toEigen(const vpMatrix &A, const std::string &where, const std::string &what)
{
  if (A.getRows() != static_cast<unsigned int>(R) || A.getCols() != static_cast<unsigned int>(C)) {
    std::ostringstream os;
    os << what << " must be " << R << "x" << C << ", got " << A.getRows() << "x" << A.getCols();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!allFinite(A)) {
    fail(vpProjectiveException::nonFiniteValueError, where, what + " is not finite (NaN or infinity)");
  }
  Eigen::Matrix<double, R, C> E;
  conversion::visp2eigen(A, E);
  return E;
}

/*!
  The entries of a vpColVector seen as an Eigen vector (no copy). Not ViSP's visp2eigen(const vpColVector &,
  Eigen::VectorXd &): that one is compiled in libvisp_core and allocates the Eigen vector there, and a vector allocated
  under one Eigen configuration and freed under another breaks (with AddressSanitizer Eigen uses its own aligned
  allocator, whose free reads a header that ViSP's malloc never wrote). ViSP's matrix conversions are templates
  compiled here: they are used as they are.
*/
inline Eigen::Map<const Eigen::VectorXd> eigenMap(const vpColVector &v)
{
  return Eigen::Map<const Eigen::VectorXd>(v.data, static_cast<Eigen::Index>(v.getRows()));
}

//! A vpColVector of exactly N finite entries, as an Eigen fixed-size vector.
template <int N>
Eigen::Matrix<double, N, 1> toEigen(const vpColVector &v, const std::string &where, const std::string &what)
{
  if (v.getRows() != static_cast<unsigned int>(N)) {
    std::ostringstream os;
    os << what << " must have " << N << " entries, got " << v.getRows();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!allFinite(v)) {
    fail(vpProjectiveException::nonFiniteValueError, where, what + " is not finite (NaN or infinity)");
  }
  return eigenMap(v);
}

/*!
  A vpColVector of exactly \e n finite entries (one per joint) as an Eigen vector of type \e Vector (dynamic, or of
  fixed capacity such as vpProjectiveArmModel::JointVector).
*/
template <typename Vector>
Vector toEigenVector(const vpColVector &v, size_t n, const std::string &where, const std::string &what)
{
  if (v.getRows() != n) {
    std::ostringstream os;
    os << what << " must have " << n << " entries (one per joint), got " << v.getRows();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!allFinite(v)) {
    fail(vpProjectiveException::nonFiniteValueError, where, what + ": a joint value is NaN or infinite");
  }
  // Entry by entry: no temporary, since the servo's vpColVector API converts q at every call.
  Vector E(static_cast<Eigen::Index>(n));
  for (unsigned int i = 0; i < v.getRows(); ++i) {
    E(i) = v[i];
  }
  return E;
}

//! Pixel (u, v) of a vpImagePoint (u = column j, v = row i), checked finite.
inline Eigen::Vector2d toEigen(const vpImagePoint &ip, const std::string &where, const std::string &what)
{
  requireFinite(ip.get_u(), where, what);
  requireFinite(ip.get_v(), where, what);
  return Eigen::Vector2d(ip.get_u(), ip.get_v());
}

//! Pixels (u, v, u', v') of matched left and right image points, checked: same sizes, finite coordinates.
std::vector<Eigen::Vector4d> stackStereoImages(const std::vector<vpImagePoint> &left,
                                               const std::vector<vpImagePoint> &right, const std::string &where);

template <typename Derived> vpMatrix toVisp(const Eigen::MatrixBase<Derived> &E)
{
  vpMatrix A;
  conversion::eigen2visp(Eigen::MatrixXd(E), A);
  return A;
}

template <typename Derived> vpColVector toVispVector(const Eigen::MatrixBase<Derived> &E)
{
  vpColVector v;
  conversion::eigen2visp(Eigen::VectorXd(E), v);
  return v;
}

} // namespace vpProjectiveInternal

#endif
