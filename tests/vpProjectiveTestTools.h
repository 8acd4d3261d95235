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
  Helpers shared by the GoogleTest suites (header only, not a test itself): a ground-truth scene built on
  vpSimulatorStereoRig, seeded random point sets, Eigen/ViSP conversions, error measures and a checker for the
  plugin's exceptions. Every random number comes from a vpUniRand or vpGaussRand seeded by the caller (ViSP's own
  generators, so that the draws do not depend on the C++ standard library), hence every failure reproduces.
*/

#ifndef _vpProjectiveTestTools_h_
#define _vpProjectiveTestTools_h_

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpEigenConversion.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#ifndef VISP_HAVE_EIGEN3
#error "the tests convert through ViSP's vpEigenConversion.h, which needs a ViSP built with Eigen3"
#endif

namespace vpProjectiveTest
{
/*
  ViSP <-> Eigen conversions: ViSP's own (vpEigenConversion.h), declared in namespace vp by ViSP 3.5 and 3.6 and in
  VISP_NAMESPACE_NAME by ViSP 3.7, whether or not its classes are in that namespace (as
  src/core/vpProjectiveConversions.h).
*/
#ifdef VISP_NAMESPACE_NAME
namespace conversion = VISP_NAMESPACE_NAME;
#else
namespace conversion = vp;
#endif

/*!
  Whether the tests were asked to print their diagnostics: the environment variable VISP_PROJECTIVE_TEST_VERBOSE set
  to anything but "" or "0" (tests print nothing unless asked).
*/
inline bool verboseTests()
{
  const char *value = std::getenv("VISP_PROJECTIVE_TEST_VERBOSE");
  return value != nullptr && std::string(value) != "" && std::string(value) != "0";
}

/*!
  The stream of the tests' diagnostics ("[ measured ]" and "[ stats    ]" lines, tables): std::cout when
  verboseTests(), otherwise a stream that writes nothing. What is written is still computed, so a diagnostic cannot
  hide a failure that only shows when it is printed.
*/
inline std::ostream &testLog()
{
  static std::ostream quiet(nullptr); // no buffer: every insertion is dropped
  return verboseTests() ? std::cout : quiet;
}

//! A vpMatrix as a dynamic Eigen matrix (test comparisons).
inline Eigen::MatrixXd toEigenX(const vpMatrix &A)
{
  Eigen::MatrixXd E(A.getRows(), A.getCols());
  conversion::visp2eigen(A, E);
  return E;
}

//! \overload
inline Eigen::MatrixXd toEigenX(const vpHomogeneousMatrix &M)
{
  Eigen::MatrixXd E(4, 4);
  conversion::visp2eigen(M, E);
  return E;
}

//! A vpColVector as a dynamic Eigen vector (test comparisons).
inline Eigen::VectorXd toEigenV(const vpColVector &v)
{
  // Not ViSP's compiled visp2eigen(vpColVector, VectorXd): it allocates inside libvisp_core, under another Eigen
  // allocator than this code's in the sanitizer build (see src/core/vpProjectiveConversions.h, eigenMap()).
  return Eigen::Map<const Eigen::VectorXd>(v.data, static_cast<Eigen::Index>(v.getRows()));
}

//! \overload
inline Eigen::MatrixXd toEigenX(const vpColVector &v)
{
  return toEigenV(v);
}

/*!
  A vpMatrix, vpHomogeneousMatrix or vpColVector of R x C entries as a fixed-size Eigen matrix. A size mismatch is a
  test failure, and the result is then all NaN, so that no comparison with it passes.
*/
template <int R, int C, typename Array> Eigen::Matrix<double, R, C> toEigen(const Array &A)
{
  const Eigen::MatrixXd E = toEigenX(A);
  if (E.rows() != R || E.cols() != C) {
    ADD_FAILURE() << "a " << E.rows() << "x" << E.cols() << " ViSP array where a " << R << "x" << C
                  << " one was expected";
    return Eigen::Matrix<double, R, C>::Constant(std::numeric_limits<double>::quiet_NaN());
  }
  return E;
}

inline Eigen::Vector4d toEigen4(const vpColVector &v)
{
  return toEigen<4, 1>(v);
}

//! An Eigen matrix as a ViSP \e Array: a vpMatrix (the default), vpHomogeneousMatrix or vpColVector (an Eigen vector).
template <typename Array = vpMatrix, typename Derived> Array toVisp(const Eigen::MatrixBase<Derived> &E)
{
  using Source =
      typename std::conditional<std::is_same<Array, vpColVector>::value, Eigen::VectorXd, Eigen::MatrixXd>::type;
  Array A;
  conversion::eigen2visp(Source(E), A);
  return A;
}

template <typename Derived> vpColVector toVispVector(const Eigen::MatrixBase<Derived> &E)
{
  return toVisp<vpColVector>(E);
}

/*
  Seeded draws: C++ leaves the order in which a call's arguments are evaluated unspecified, so a call such as
  point3(rng.uniform(a, b), rng.uniform(a, b), rng.uniform(a, b)) gave other points under clang++ than under g++. Every
  place that draws more than once draws into named locals, one statement each, last argument first: the order g++
  (x86-64) evaluated these calls in, with which the suites' seeded figures and tolerances were measured.
*/
inline vpColVector point3(double x, double y, double z)
{
  vpColVector p(3);
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

inline Eigen::Vector3d pixel(const vpImagePoint &ip)
{
  return Eigen::Vector3d(ip.get_u(), ip.get_v(), 1.0);
}

inline double pixelDistance(const vpImagePoint &a, const vpImagePoint &b)
{
  return std::hypot(a.get_u() - b.get_u(), a.get_v() - b.get_v());
}

//! ||A - B||_F / ||B||_F.
template <typename DA, typename DB> double relativeError(const Eigen::MatrixBase<DA> &A, const Eigen::MatrixBase<DB> &B)
{
  return (A - B).norm() / B.norm();
}

//! Distance between the unit-norm versions of A and B, minimised over the sign: compares A and B up to scale.
template <typename DA, typename DB>
double relativeErrorUpToScale(const Eigen::MatrixBase<DA> &A, const Eigen::MatrixBase<DB> &B)
{
  const auto a = A / A.norm();
  const auto b = B / B.norm();
  return std::min((a - b).norm(), (a + b).norm());
}

//! Symmetric epipolar distances (pixels) of a match to the epipolar lines of F: (left image, right image).
inline Eigen::Vector2d epipolarDistances(const Eigen::Matrix3d &F, const vpImagePoint &left, const vpImagePoint &right)
{
  const Eigen::Vector3d m = pixel(left), mp = pixel(right);
  const Eigen::Vector3d lp = F * m;             // epipolar line of m in the right image
  const Eigen::Vector3d l = F.transpose() * mp; // epipolar line of m' in the left image
  const double a = mp.dot(F * m);
  return Eigen::Vector2d(std::abs(a) / l.head<2>().norm(), std::abs(a) / lp.head<2>().norm());
}

//! RMS over matches and both images of the epipolar distances (pixels).
inline double rmsEpipolarDistance(const Eigen::Matrix3d &F, const std::vector<vpImagePoint> &left,
                                  const std::vector<vpImagePoint> &right)
{
  double sum = 0.0;
  for (size_t i = 0; i < left.size(); ++i) {
    sum += epipolarDistances(F, left[i], right[i]).squaredNorm();
  }
  return std::sqrt(sum / (2.0 * static_cast<double>(left.size())));
}

/*!
  The ground truth: the paper's rig (20 cm baseline, f = 1666.7 px, 640x480) looking at a fixation point 1 m away,
  placed off the world origin so that the world, left-camera and projective frames all differ; a vpProjectiveStereoRig
  given the true F; and H_PE of that rig's frame (N ~ H_PE M, N homogeneous left-camera coordinates).
*/
struct Scene {
  vpSimulatorStereoRig sim;
  vpProjectiveStereoRig rig;
  Eigen::Matrix4d Hpe;
  Eigen::Matrix4d HpeInv;

  static vpColVector fixation() { return point3(0.2, -0.1, 1.5); }

  Scene() : sim(vpSimulatorStereoRig::paperRig(fixation(), 1.0)), rig(), Hpe(), HpeInv()
  {
    rig.setFundamentalMatrix(sim.getFundamentalMatrix());
    Hpe = toEigen<4, 4>(sim.getProjectiveToEuclidean(rig));
    HpeInv = Hpe.inverse();
  }

  //! Homogeneous left-camera coordinates N = lMw (X, 1) of a world point (3x1).
  Eigen::Vector4d cameraPoint(const vpColVector &wX) const
  {
    return toEigen<4, 4>(sim.get_wMl().inverse()) * toEigen<3, 1>(wX).homogeneous();
  }

  //! The true projective point H_PE^-1 N of a world point, unit norm (its sign is arbitrary).
  Eigen::Vector4d projectivePoint(const vpColVector &wX) const { return (HpeInv * cameraPoint(wX)).normalized(); }

  //! A world displacement as a metric displacement of the left camera frame, T_l = lMw T wMl.
  Eigen::Matrix4d cameraDisplacement(const vpHomogeneousMatrix &wT) const
  {
    return toEigen<4, 4>(sim.toCameraFrame(vpMatrix(wT)));
  }

  //! The true p-displacement H_PE^-1 T_l H_PE (not normalised).
  Eigen::Matrix4d projectiveDisplacement(const vpHomogeneousMatrix &wT) const
  {
    return HpeInv * cameraDisplacement(wT) * Hpe;
  }

  //! Direction (3x1 world) and point (3x1 world) of an axis, expressed in the left camera frame.
  Eigen::Vector3d cameraDirection(const vpColVector &wDir) const
  {
    return toEigen<4, 4>(sim.get_wMl().inverse()).topLeftCorner<3, 3>() * toEigen<3, 1>(wDir);
  }
};

//! m x n matrix of uniform entries in [-1, 1].
inline Eigen::MatrixXd randomMatrix(vpUniRand &rng, Eigen::Index m, Eigen::Index n)
{
  Eigen::MatrixXd A(m, n);
  for (Eigen::Index i = 0; i < m; ++i) {
    for (Eigen::Index j = 0; j < n; ++j) {
      A(i, j) = rng.uniform(-1.0, 1.0);
    }
  }
  return A;
}

//! A random unit 3-vector (world frame).
inline vpColVector randomDirection(vpUniRand &rng)
{
  for (;;) {
    const double z = rng.uniform(-1.0, 1.0); // drawn last to first: see point3(), vpProjectiveTestTools.h
    const double y = rng.uniform(-1.0, 1.0);
    const double x = rng.uniform(-1.0, 1.0);
    const vpColVector d = point3(x, y, z);
    const double n = d.frobeniusNorm();
    if (n > 0.2 && n <= 1.0) {
      return d / n;
    }
  }
}

/*!
  \e n random world points, uniform in the cube of half side \e halfSide centred at \e center, each visible in both
  images at least \e margin pixels inside their borders (rejection sampling).
*/
inline std::vector<vpColVector> randomVisiblePoints(const vpSimulatorStereoRig &sim, vpUniRand &rng,
                                                    const vpColVector &center, double halfSide, size_t n,
                                                    double margin = 10.0)
{
  std::vector<vpColVector> points;
  while (points.size() < n) {
    const double dz = rng.uniform(-halfSide, halfSide); // drawn last to first: see point3(), vpProjectiveTestTools.h
    const double dy = rng.uniform(-halfSide, halfSide);
    const double dx = rng.uniform(-halfSide, halfSide);
    const vpColVector X = point3(center[0] + dx, center[1] + dy, center[2] + dz);
    if (sim.isVisible(X, margin)) {
      points.push_back(X);
    }
  }
  return points;
}

//! Noise-free images of world points.
inline void imagesOf(const vpSimulatorStereoRig &sim, const std::vector<vpColVector> &wX,
                     std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)
{
  vpGaussRand unused(1.0, 0.0, 1);
  sim.project(wX, left, right, 0.0, unused);
}

/*!
  Checks that \e f throws a vpProjectiveException (caught as a vpException) of code \e code whose message contains
  \e word.
*/
template <typename Callable>::testing::AssertionResult throwsProjective(Callable &&f, int code, const std::string &word)
{
  try {
    f();
  } catch (const vpException &e) {
    if (dynamic_cast<const vpProjectiveException *>(&e) == nullptr) {
      return ::testing::AssertionFailure()
             << "a vpException that is no vpProjectiveException: " << e.getStringMessage();
    }
    if (e.getCode() != code) {
      return ::testing::AssertionFailure()
             << "code " << e.getCode() << " instead of " << code << ": " << e.getStringMessage();
    }
    if (e.getStringMessage().find(word) == std::string::npos) {
      return ::testing::AssertionFailure()
             << "message \"" << e.getStringMessage() << "\" does not contain \"" << word << "\"";
    }
    return ::testing::AssertionSuccess();
  } catch (const std::exception &e) {
    return ::testing::AssertionFailure() << "a std::exception instead of a vpProjectiveException: " << e.what();
  } catch (...) {
    return ::testing::AssertionFailure() << "an unknown exception instead of a vpProjectiveException";
  }
  return ::testing::AssertionFailure() << "no exception thrown";
}

/*!
  Matrix exponential by scaling and squaring of a Taylor series: deliberately independent of the plugin's closed forms
  and of any twist structure, the ground truth they are checked against.
*/
inline Eigen::Matrix4d expm(const Eigen::Matrix4d &A)
{
  const double norm = A.cwiseAbs().rowwise().sum().maxCoeff();
  int squarings = 0;
  if (norm > 0.25) {
    squarings = static_cast<int>(std::ceil(std::log2(norm / 0.25)));
  }
  const Eigen::Matrix4d B = A / std::pow(2.0, squarings);
  Eigen::Matrix4d term = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d sum = Eigen::Matrix4d::Identity();
  for (int k = 1; k <= 20; ++k) {
    term = term * B / static_cast<double>(k);
    sum += term;
  }
  for (int k = 0; k < squarings; ++k) {
    sum = sum * sum;
  }
  return sum;
}

//! Singular values of a 4x4 matrix, decreasing.
inline Eigen::Vector4d singularValues(const Eigen::Matrix4d &A)
{
  return Eigen::JacobiSVD<Eigen::Matrix4d>(A).singularValues();
}

//! The median of \e x (not empty): the middle value, or the mean of the two middle values.
inline double median(std::vector<double> x)
{
  std::sort(x.begin(), x.end());
  const size_t n = x.size();
  return n % 2 == 1 ? x[n / 2] : 0.5 * (x[n / 2 - 1] + x[n / 2]);
}

} // namespace vpProjectiveTest

#endif
