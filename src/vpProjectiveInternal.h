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
  Private helpers shared by the plugin's sources: conversions between ViSP and Eigen types that validate sizes and
  finiteness on the way in, and the small linear-algebra pieces every class needs. Not installed.
*/

#ifndef _vpProjectiveInternal_h_
#define _vpProjectiveInternal_h_

#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <Eigen/SVD>

#include <visp3/core/vpArray2D.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpEigenConversion.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveException.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#ifndef VISP_HAVE_EIGEN3
#error "visp_projective needs a ViSP built with Eigen3 (USE_EIGEN3=ON): it converts through ViSP's vpEigenConversion.h"
#endif

namespace vpProjectiveInternal
{
/*!
  Where an error comes from, "Class::method()": a source names its class once, `const vpErrorSite at("vpFoo");`, and
  its errors say `at("bar()")`.
*/
class vpErrorSite
{
public:
  explicit vpErrorSite(const char *className) : m_className(className) {}
  std::string operator()(const char *method) const { return std::string(m_className) + "::" + method; }

private:
  const char *m_className;
};

//! Throws a vpProjectiveException with code and a message built from \e where and \e what.
[[noreturn]] inline void fail(int code, const std::string &where, const std::string &what)
{
  throw vpProjectiveException(code, where + ": " + what);
}

inline void requireFinite(double x, const std::string &where, const std::string &what)
{
  if (!std::isfinite(x)) {
    fail(vpProjectiveException::nonFiniteValueError, where, what + " is not finite (NaN or infinity)");
  }
}

//! A setter's non-negative setting, checked: \e x if finite and >= 0, else the error saying that \e what (e.g. "the
//! gain") must be, with \e use (what 0 or a value means, e.g. "pixels; 0 disables the outlier rejection").
inline double nonNegative(double x, const std::string &where, const std::string &what, const std::string &use)
{
  requireFinite(x, where, what);
  if (x < 0.0) {
    fail(vpProjectiveException::invalidValueError, where, what + " must be non-negative: positive or 0 (" + use + ")");
  }
  return x;
}

//! True if every entry of a ViSP matrix, vector or transform is finite.
inline bool allFinite(const vpArray2D<double> &A)
{
  for (unsigned int i = 0; i < A.getRows(); ++i) {
    for (unsigned int j = 0; j < A.getCols(); ++j) {
      if (!std::isfinite(A[i][j])) {
        return false;
      }
    }
  }
  return true;
}

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

//! Flips the sign of \e x so that its entry of largest magnitude is positive: a canonical sign for a direction.
template <typename Derived> void canonicalSign(Eigen::MatrixBase<Derived> &x)
{
  Eigen::Index r = 0, c = 0;
  x.cwiseAbs().maxCoeff(&r, &c);
  if (x(r, c) < 0) {
    x = -x;
  }
}

//! Hartley's isotropic normalisation of pixels: centroid to 0, mean distance to sqrt(2). Returns the 3x3 similarity.
inline Eigen::Matrix3d hartleyNormalization(const std::vector<Eigen::Vector2d> &points)
{
  Eigen::Vector2d c = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d &p : points) {
    c += p;
  }
  c /= static_cast<double>(points.size());
  double meanDistance = 0.0;
  for (const Eigen::Vector2d &p : points) {
    meanDistance += (p - c).norm();
  }
  meanDistance /= static_cast<double>(points.size());
  const double s = meanDistance > 0.0 ? std::sqrt(2.0) / meanDistance : 1.0;
  Eigen::Matrix3d T;
  T << s, 0, -s * c(0), 0, s, -s * c(1), 0, 0, 1;
  return T;
}

/*!
  Whitening of homogeneous 4-vectors without dividing by any coordinate: with each point scaled to unit norm and
  signed canonically, T = (sum M M^T / n)^(-1/2), so that the points T M are spread isotropically over the sphere.
*/
Eigen::Matrix4d whitening(const std::vector<Eigen::Vector4d> &points);

/*!
  The weights of the derivative at sample \e k of a sequence sampled at times \e t: over the samples
  \f$ |j - k| \le \f$ \e halfWindow (clipped at the ends), the least-squares fit
  \f$ x_j - x_k \approx a (t_j - t_k) + b (t_j - t_k)^2 \f$ (a line when the window holds one other sample) gives
  \f$ \dot x_k = a = \sum_j w_j (x_j - x_k) \f$, \f$ x_j - x_k \f$ being a difference in the group (joint values, or
  \f$ \log(H_j H_k^{-1}) \f$). The quadratic term removes the lag that a straight line has at the end of a window
  (the real-time case, k the newest sample), at the price of more noise. Returns the pairs (j, w_j), j != k. Throws
  (dimensionError, invalidValueError, naming \e where) if \e k is out of range, \e halfWindow is 0, the window has
  one sample or its times are not finite and strictly increasing.
*/
std::vector<std::pair<size_t, double>> slopeWeights(const std::vector<double> &t, size_t k, size_t halfWindow,
                                                    const std::string &where);

//! Orthonormal basis (4x3) of the tangent space of the unit sphere at the unit vector M.
Eigen::Matrix<double, 4, 3> sphereTangentBasis(const Eigen::Vector4d &M);

} // namespace vpProjectiveInternal

#endif
