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
  \file vpSimulatorStereoRig.cpp
  \brief Metric stereo rig simulator: projections, noise, ground-truth fundamental matrix and H_PE.
*/

#include <visp3/projective/vpSimulatorStereoRig.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpImageWindow.h"
#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
bool finiteValue(double x)
{
  return std::isfinite(x);
}
bool finiteValue(const vpArray2D<double> &A)
{
  return allFinite(A);
}

void checkCamera(const vpCameraParameters &cam, const char *which)
{
  if (cam.get_projModel() != vpCameraParameters::perspectiveProjWithoutDistortion) {
    std::ostringstream os;
    os << "vpSimulatorStereoRig: the " << which
       << " camera has a distortion model; the simulator images ideal pinhole cameras: initialise it with "
          "vpCameraParameters::initPersProjWithoutDistortion()";
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
  if (!finiteValue(cam.get_px()) || !finiteValue(cam.get_py()) || !finiteValue(cam.get_u0()) ||
      !finiteValue(cam.get_v0())) {
    std::ostringstream os;
    os << "vpSimulatorStereoRig: the " << which << " camera's intrinsics are not finite; give finite px, py, u0, v0";
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
  }
  if (cam.get_px() <= 0.0 || cam.get_py() <= 0.0) {
    std::ostringstream os;
    os << "vpSimulatorStereoRig: the " << which << " camera has px = " << cam.get_px() << ", py = " << cam.get_py()
       << "; focal lengths in pixels must be positive";
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
}

void checkPose(const vpHomogeneousMatrix &M, const char *name)
{
  if (!finiteValue(M)) {
    std::ostringstream os;
    os << "vpSimulatorStereoRig: " << name << " contains NaN or infinity; give a finite rigid transformation";
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
  }
  if (!M.isAnHomogeneousMatrix(1e-6)) {
    std::ostringstream os;
    os << "vpSimulatorStereoRig: " << name
       << " is not a rigid transformation (its rotation part is not orthonormal with determinant 1, or its last row "
          "is not [0 0 0 1])";
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
}

void checkVector3(const vpColVector &v, const char *where, const char *name)
{
  if (v.getRows() != 3) {
    std::ostringstream os;
    os << where << ": " << name << " must be a 3x1 vector, got " << v.getRows() << "x" << v.getCols();
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  if (!finiteValue(v)) {
    std::ostringstream os;
    os << where << ": " << name << " contains NaN or infinity";
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
  }
}

//! A world point (3x1, or 4x1 homogeneous with a non-zero last entry) as Euclidean coordinates.
Eigen::Vector3d worldPoint(const vpColVector &wX, const char *where)
{
  if (wX.getRows() != 3 && wX.getRows() != 4) {
    std::ostringstream os;
    os << where << ": a world point must be 3x1 or 4x1 (homogeneous), got " << wX.getRows() << "x" << wX.getCols();
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  if (!finiteValue(wX)) {
    std::ostringstream os;
    os << where << ": the world point contains NaN or infinity";
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
  }
  Eigen::Vector3d X(wX[0], wX[1], wX[2]);
  if (wX.getRows() == 4) {
    const double w = wX[3];
    if (std::fabs(w) <= 1e-12 * std::max(1.0, X.norm())) {
      std::ostringstream os;
      os << where << ": the homogeneous world point has a zero last entry (a point at infinity); the simulator "
         << "images finite points only: give (X, Y, Z, 1)";
      throw vpProjectiveException(vpProjectiveException::pointAtInfinityError, os.str());
    }
    X /= w;
  }
  return X;
}
} // namespace

vpSimulatorStereoRig::vpSimulatorStereoRig(const vpCameraParameters &camLeft, const vpCameraParameters &camRight,
                                           const vpHomogeneousMatrix &rMl, const vpHomogeneousMatrix &wMl,
                                           unsigned int width, unsigned int height)
    : m_camLeft(camLeft), m_camRight(camRight), m_rMl(rMl), m_wMl(wMl), m_lMw(), m_width(width), m_height(height)
{
  checkCamera(camLeft, "left");
  checkCamera(camRight, "right");
  checkPose(rMl, "rMl");
  checkPose(wMl, "wMl");
  if (width == 0 || height == 0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                "vpSimulatorStereoRig: the image size is zero; give the width and height in pixels");
  }
  if (rMl.getTranslationVector().frobeniusNorm() < 1e-9) {
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError,
                                "vpSimulatorStereoRig: the two camera centres coincide (rMl has no translation); a "
                                "stereo rig needs a non-zero baseline");
  }
  m_lMw = wMl.inverse();
}

vpCameraParameters vpSimulatorStereoRig::paperCameraParameters()
{
  // 12.5 mm lens, 1/3 inch CCD of 4.8 x 3.6 mm imaged on 640 x 480 pixels: 7.5 um square pixels.
  const double focal = 12.5e-3;
  const double pixel = 4.8e-3 / 640.0;
  vpCameraParameters cam;
  cam.initPersProjWithoutDistortion(focal / pixel, focal / pixel, 320.0, 240.0);
  return cam;
}

vpSimulatorStereoRig vpSimulatorStereoRig::vergingRig(const vpColVector &fixation, double distance, double baseline,
                                                      const vpCameraParameters &cam, unsigned int width,
                                                      unsigned int height)
{
  const char *where = "vpSimulatorStereoRig::vergingRig()";
  checkVector3(fixation, where, "the fixation point");
  if (!finiteValue(distance) || !finiteValue(baseline)) {
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                std::string(where) + ": the distance or the baseline is not finite");
  }
  if (distance <= 0.0 || baseline <= 0.0) {
    std::ostringstream os;
    os << where << ": distance = " << distance << " m and baseline = " << baseline
       << " m must both be positive (the fixation point lies in front of the rig)";
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
  const Eigen::Vector3d wF(fixation[0], fixation[1], fixation[2]);
  const Eigen::Vector3d wMid = wF - Eigen::Vector3d(0.0, 0.0, distance);
  const Eigen::Vector3d wY(0.0, 1.0, 0.0);

  // Camera frame of a camera centred at wC looking at wF, with its y axis along the world's +Y.
  auto lookAt = [&](const Eigen::Vector3d &wC) {
    const Eigen::Vector3d z = (wF - wC).normalized();
    const Eigen::Vector3d x = wY.cross(z).normalized();
    const Eigen::Vector3d y = z.cross(x);
    vpHomogeneousMatrix wMc;
    for (unsigned int i = 0; i < 3; ++i) {
      wMc[i][0] = x(i);
      wMc[i][1] = y(i);
      wMc[i][2] = z(i);
      wMc[i][3] = wC(i);
    }
    return wMc;
  };
  const vpHomogeneousMatrix wMl = lookAt(wMid - Eigen::Vector3d(0.5 * baseline, 0.0, 0.0));
  const vpHomogeneousMatrix wMr = lookAt(wMid + Eigen::Vector3d(0.5 * baseline, 0.0, 0.0));
  return vpSimulatorStereoRig(cam, cam, wMr.inverse() * wMl, wMl, width, height);
}

vpSimulatorStereoRig vpSimulatorStereoRig::paperRig(const vpColVector &fixation, double distance)
{
  return vergingRig(fixation, distance, 0.20, paperCameraParameters(), 640, 480);
}

vpMatrix vpSimulatorStereoRig::getLeftMetricProjection() const
{
  vpProjectiveStereoRig::Projection P = vpProjectiveStereoRig::Projection::Zero();
  P.leftCols<3>() = toEigenUnchecked<3, 3>(m_camLeft.get_K());
  return toVisp(P);
}

vpMatrix vpSimulatorStereoRig::getRightMetricProjection() const
{
  const Eigen::Matrix4d rMl = toEigenUnchecked<4, 4>(m_rMl);
  const vpProjectiveStereoRig::Projection P = toEigenUnchecked<3, 3>(m_camRight.get_K()) * rMl.topRows<3>();
  return toVisp(P);
}

vpMatrix vpSimulatorStereoRig::getFundamentalMatrix() const
{
  const Eigen::Matrix4d rMl = toEigenUnchecked<4, 4>(m_rMl);
  const Eigen::Matrix3d R = rMl.topLeftCorner<3, 3>();
  const Eigen::Vector3d t = rMl.topRightCorner<3, 1>();
  const Eigen::Matrix3d F = toEigenUnchecked<3, 3>(m_camRight.get_K()).inverse().transpose() * vpMetricTwist::skew(t) *
                            R * toEigenUnchecked<3, 3>(m_camLeft.get_K()).inverse();
  return toVisp(F / F.norm());
}

vpMatrix vpSimulatorStereoRig::toCameraFrame(const vpMatrix &wT) const
{
  if (wT.getRows() != 4 || wT.getCols() != 4) {
    std::ostringstream os;
    os << "vpSimulatorStereoRig::toCameraFrame(): the displacement must be 4x4, got " << wT.getRows() << "x"
       << wT.getCols();
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  if (!finiteValue(wT)) {
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                "vpSimulatorStereoRig::toCameraFrame(): the displacement contains NaN or infinity");
  }
  const Eigen::Matrix4d lT = toEigenUnchecked<4, 4>(m_lMw) * toEigenUnchecked<4, 4>(wT) * toEigenUnchecked<4, 4>(m_wMl);
  return toVisp(lT);
}

bool vpSimulatorStereoRig::imageOf(const vpColVector &wX, vpImagePoint &ipLeft, vpImagePoint &ipRight, double margin,
                                   double minDepth) const
{
  const Eigen::Vector3d X = worldPoint(wX, "vpSimulatorStereoRig::project()");
  const Eigen::Matrix4d lMw = toEigenUnchecked<4, 4>(m_lMw);
  const Eigen::Matrix4d rMl = toEigenUnchecked<4, 4>(m_rMl);
  const Eigen::Vector3d lX = lMw.topLeftCorner<3, 3>() * X + lMw.topRightCorner<3, 1>();
  const Eigen::Vector3d rX = rMl.topLeftCorner<3, 3>() * lX + rMl.topRightCorner<3, 1>();

  bool visible = true;
  const vpCameraParameters *cams[2] = {&m_camLeft, &m_camRight};
  const Eigen::Vector3d *points[2] = {&lX, &rX};
  vpImagePoint *ips[2] = {&ipLeft, &ipRight};
  for (int k = 0; k < 2; ++k) {
    const Eigen::Vector3d &cX = *points[k];
    if (cX(2) <= minDepth) {
      visible = false;
    }
    if (std::fabs(cX(2)) <= 1e-12) {
      continue; // On the focal plane: no image; the image point is left unchanged.
    }
    const double u = cams[k]->get_u0() + cams[k]->get_px() * cX(0) / cX(2);
    const double v = cams[k]->get_v0() + cams[k]->get_py() * cX(1) / cX(2);
    ips[k]->set_uv(u, v);
    if (!vpProjectiveInternal::vpImageWindow(m_width, m_height, margin).contains(u, v)) {
      visible = false;
    }
  }
  return visible;
}

bool vpSimulatorStereoRig::project(const vpColVector &wX, vpImagePoint &ipLeft, vpImagePoint &ipRight) const
{
  return imageOf(wX, ipLeft, ipRight, 0.0, 0.0);
}

bool vpSimulatorStereoRig::project(const vpColVector &wX, vpImagePoint &ipLeft, vpImagePoint &ipRight, double sigma,
                                   vpGaussRand &noise) const
{
  if (!finiteValue(sigma) || sigma < 0.0) {
    std::ostringstream os;
    os << "vpSimulatorStereoRig::project(): the noise standard deviation sigma = " << sigma
       << " px must be finite and non-negative";
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
  const bool visible = imageOf(wX, ipLeft, ipRight, 0.0, 0.0);
  if (sigma > 0.0) {
    // Only the generator's random stream is used: sigma is the one given here.
    noise.setSigmaMean(1.0, 0.0);
    const double du = sigma * noise();
    const double dv = sigma * noise();
    const double dup = sigma * noise();
    const double dvp = sigma * noise();
    ipLeft.set_uv(ipLeft.get_u() + du, ipLeft.get_v() + dv);
    ipRight.set_uv(ipRight.get_u() + dup, ipRight.get_v() + dvp);
  }
  return visible;
}

bool vpSimulatorStereoRig::project(const std::vector<vpColVector> &wX, std::vector<vpImagePoint> &left,
                                   std::vector<vpImagePoint> &right, double sigma, vpGaussRand &noise) const
{
  left.assign(wX.size(), vpImagePoint());
  right.assign(wX.size(), vpImagePoint());
  bool all = true;
  for (size_t k = 0; k < wX.size(); ++k) {
    all = project(wX[k], left[k], right[k], sigma, noise) && all;
  }
  return all;
}

bool vpSimulatorStereoRig::isVisible(const vpColVector &wX, double margin, double minDepth) const
{
  if (!finiteValue(margin) || !finiteValue(minDepth)) {
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                "vpSimulatorStereoRig::isVisible(): the margin or the minimal depth is not finite");
  }
  vpImagePoint ipLeft, ipRight;
  return imageOf(wX, ipLeft, ipRight, margin, minDepth);
}

std::vector<vpColVector> vpSimulatorStereoRig::transform(const vpHomogeneousMatrix &wT,
                                                         const std::vector<vpColVector> &wX)
{
  if (!finiteValue(wT)) {
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                "vpSimulatorStereoRig::transform(): the displacement contains NaN or infinity");
  }
  std::vector<vpColVector> out;
  out.reserve(wX.size());
  for (size_t k = 0; k < wX.size(); ++k) {
    const vpColVector &X = wX[k];
    if (X.getRows() != 3 && X.getRows() != 4) {
      std::ostringstream os;
      os << "vpSimulatorStereoRig::transform(): point " << k << " must be 3x1 or 4x1 (homogeneous), got " << X.getRows()
         << "x" << X.getCols();
      throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
    }
    if (!finiteValue(X)) {
      std::ostringstream os;
      os << "vpSimulatorStereoRig::transform(): point " << k << " contains NaN or infinity";
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
    }
    const double w = (X.getRows() == 4) ? X[3] : 1.0;
    vpColVector Y(X.getRows());
    for (unsigned int i = 0; i < 3; ++i) {
      Y[i] = wT[i][0] * X[0] + wT[i][1] * X[1] + wT[i][2] * X[2] + wT[i][3] * w;
    }
    if (X.getRows() == 4) {
      Y[3] = w;
    }
    out.push_back(Y);
  }
  return out;
}

vpHomogeneousMatrix vpSimulatorStereoRig::rotationAbout(const vpColVector &point, const vpColVector &axis, double theta)
{
  const char *where = "vpSimulatorStereoRig::rotationAbout()";
  checkVector3(point, where, "the point on the axis");
  checkVector3(axis, where, "the axis direction");
  if (!finiteValue(theta)) {
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                std::string(where) + ": the angle is not finite");
  }
  const double n = axis.frobeniusNorm();
  if (n < 1e-12) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                std::string(where) + ": the axis direction is zero; give a non-zero 3x1 direction");
  }
  const vpThetaUVector tu(theta * axis[0] / n, theta * axis[1] / n, theta * axis[2] / n);
  const vpRotationMatrix R(tu);
  const vpTranslationVector p(point[0], point[1], point[2]);
  const vpTranslationVector t = p - R * p;
  return vpHomogeneousMatrix(t, R);
}

vpHomogeneousMatrix vpSimulatorStereoRig::translationAlong(const vpColVector &direction, double tau)
{
  const char *where = "vpSimulatorStereoRig::translationAlong()";
  checkVector3(direction, where, "the direction");
  if (!finiteValue(tau)) {
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                std::string(where) + ": the translation length is not finite");
  }
  const double n = direction.frobeniusNorm();
  if (n < 1e-12) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                std::string(where) + ": the direction is zero; give a non-zero 3x1 direction");
  }
  vpHomogeneousMatrix T;
  for (unsigned int i = 0; i < 3; ++i) {
    T[i][3] = tau * direction[i] / n;
  }
  return T;
}
