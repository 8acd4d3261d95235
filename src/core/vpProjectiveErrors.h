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
  Private: how the plugin's sources raise errors (a vpProjectiveException naming Class::method() and what to do) and
  check the values they are given. Not installed.
*/

#ifndef _vpProjectiveErrors_h_
#define _vpProjectiveErrors_h_

#include <cmath>
#include <string>

#include <visp3/core/vpArray2D.h>
#include <visp3/core/vpConfig.h>
#include <visp3/projective/vpProjectiveException.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
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

//! A setter's count (calls, starts, frames), checked: \e count if at least 1, else the error \e why (what one means
//! and what to pass).
inline unsigned int atLeastOne(unsigned int count, const std::string &where, const std::string &why)
{
  if (count == 0) {
    fail(vpProjectiveException::invalidValueError, where, why);
  }
  return count;
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

//! A positive setting or argument (a threshold, a tolerance), checked: \e x if finite and > 0, else the error saying
//! that \e what (e.g. "the inlier threshold") must be positive, with \e use (its unit, what a value means).
inline double positive(double x, const std::string &where, const std::string &what, const std::string &use)
{
  requireFinite(x, where, what);
  if (!(x > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where, what + " must be positive (" + use + ")");
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

} // namespace vpProjectiveInternal

#endif
