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
  The one numeric-Jacobian checker of the test suites (header only, not a test itself): every test that checks an
  analytic derivative of the plugin does it against numericJacobian(), with jacobianMatches() as the assertion.

  numericJacobian(f, x, h) differentiates a function f : R^n -> R^m given as a callable taking an Eigen::VectorXd and
  returning any Eigen vector, by Richardson extrapolation of central differences, column k being
    (4 D_k(h/2) - D_k(h)) / 3,   D_k(s) = (f(x + s e_k) - f(x - s e_k)) / (2 s):
  the h^2 terms of the two central differences cancel, so the truncation error is h^4 |f^(5)| / 480 and the rounding
  error about 3 eps |f| / h (the four evaluations' rounding, divided by the step). The step h is the caller's, chosen
  for the scale of x (say so at the call). A matrix-valued function is passed through stacked() (column-major).

  jacobianMatches(analytic, ...) is a GoogleTest predicate: success when
    |analytic - numeric|_F <= relTol |numeric|_F
  (|analytic - numeric|_F <= relTol when the numeric Jacobian is zero), with both matrices and the measured error in
  the failure message. jacobianRelativeError() gives that error, for the tests that report their worst case.
*/

#ifndef _vpNumericJacobian_h_
#define _vpNumericJacobian_h_

#include <limits>

#include <Eigen/Core>
#include <gtest/gtest.h>

#include <visp3/core/vpConfig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
//! The entries of a matrix stacked column by column into a vector: the value of a matrix-valued function.
template <typename Derived> Eigen::VectorXd stacked(const Eigen::MatrixBase<Derived> &M)
{
  const Eigen::MatrixXd E = M;
  return Eigen::Map<const Eigen::VectorXd>(E.data(), E.size());
}

//! d f / d x (m x n) at \e x by Richardson-extrapolated central differences with step \e h (see the file comment).
template <typename F> Eigen::MatrixXd numericJacobian(F f, const Eigen::VectorXd &x, double h)
{
  const auto central = [&](Eigen::Index k, double step) {
    Eigen::VectorXd a = x, b = x;
    a(k) += step;
    b(k) -= step;
    const Eigen::VectorXd fa = f(a), fb = f(b);
    return Eigen::VectorXd((fa - fb) / (2.0 * step));
  };
  Eigen::MatrixXd J;
  for (Eigen::Index k = 0; k < x.size(); ++k) {
    const Eigen::VectorXd column = (4.0 * central(k, 0.5 * h) - central(k, h)) / 3.0;
    if (k == 0) {
      J.resize(column.size(), x.size());
    }
    J.col(k) = column;
  }
  return J;
}

//! |analytic - numeric|_F / |numeric|_F (the absolute difference when \e numeric is zero); infinite if the sizes
//! differ.
inline double jacobianRelativeError(const Eigen::MatrixXd &analytic, const Eigen::MatrixXd &numeric)
{
  if (analytic.rows() != numeric.rows() || analytic.cols() != numeric.cols()) {
    return std::numeric_limits<double>::infinity();
  }
  const double scale = numeric.norm();
  const double difference = (analytic - numeric).norm();
  return scale > 0.0 ? difference / scale : difference;
}

//! Compares an analytic Jacobian with a numeric one already computed (for instance one column of a larger one).
inline ::testing::AssertionResult jacobianMatches(const Eigen::MatrixXd &analytic, const Eigen::MatrixXd &numeric,
                                                  double relTol)
{
  if (analytic.rows() != numeric.rows() || analytic.cols() != numeric.cols()) {
    return ::testing::AssertionFailure() << "analytic Jacobian " << analytic.rows() << "x" << analytic.cols()
                                         << ", numeric " << numeric.rows() << "x" << numeric.cols();
  }
  const double error = jacobianRelativeError(analytic, numeric);
  if (!(error <= relTol)) {
    return ::testing::AssertionFailure() << "relative error " << error << " exceeds " << relTol << "\nanalytic =\n"
                                         << analytic << "\nnumeric =\n"
                                         << numeric;
  }
  return ::testing::AssertionSuccess() << "relative error " << error;
}

//! Compares \e analytic with numericJacobian(f, x, h).
template <typename F>
::testing::AssertionResult jacobianMatches(const Eigen::MatrixXd &analytic, F f, const Eigen::VectorXd &x, double h,
                                           double relTol)
{
  return jacobianMatches(analytic, numericJacobian(f, x, h), relTol);
}

} // namespace vpProjectiveTest

#endif
