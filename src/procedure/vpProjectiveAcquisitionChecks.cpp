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
  vpProjectiveAcquisitionProcedure's checks of the markers: at the zero reference (count, inside the images, not
  coplanar) and in general position (5 markers of which no 4 are coplanar), with their geometry.
*/

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <visp3/projective/vpProjectiveException.h>

#include "core/vpImageWindow.h"
#include "acquisition/vpProjectiveAcquisitionInternal.h"

using namespace vpProjectiveAcquisitionInternal;

namespace
{
typedef vpProjectiveStereoRig::Projection Projection;

//! The centre of a camera \e P: its right null vector.
Eigen::Vector4d centreOf(const Projection &P)
{
  Eigen::JacobiSVD<Eigen::Matrix4d> svd((Eigen::Matrix4d() << P, Eigen::RowVector4d::Zero()).finished(),
                                        Eigen::ComputeFullV);
  return svd.matrixV().col(3);
}

bool pixelOf(const Projection &P, const Eigen::Vector4d &X, Eigen::Vector2d &m)
{
  const Eigen::Vector3d x = P * X;
  if (!(std::abs(x(2)) > 1e-12 * x.norm())) {
    return false;
  }
  m = x.head<2>() / x(2);
  return true;
}

/*!
  Plane parallax (pixels) of the point \e X to the plane \e plane: in each image, the distance between the image of
  X and that of the point where the other camera's line of sight through X meets the plane (along the epipolar
  line); the larger of the two. Zero when X is on the plane, whatever the projective frame.
*/
double planeParallax(const Projection &P, const Projection &Pp, const Eigen::Vector4d &centre,
                     const Eigen::Vector4d &centrep, const Eigen::Vector4d &plane, const Eigen::Vector4d &X)
{
  double parallax = 0.0;
  for (int camera = 0; camera < 2; ++camera) {
    const Eigen::Vector4d &c = camera == 0 ? centre : centrep; // the line of sight's camera
    const Projection &Q = camera == 0 ? Pp : P;                // the image where the parallax shows
    const Eigen::Vector4d Y = plane.dot(c) * X - plane.dot(X) * c;
    Eigen::Vector2d x, y;
    if (pixelOf(Q, X, x) && pixelOf(Q, Y, y)) {
      parallax = std::max(parallax, (x - y).norm());
    }
  }
  return parallax;
}

/*!
  How far 4 points (unit 4-vectors) are from coplanar, in pixels: the RMS plane parallax of the 4 to the plane that
  fits them best (the least singular vector of their 4 x 4 matrix). Noise of sigma per image coordinate gives about
  sigma; 4 points spanning a few centimetres in depth give tens of pixels.
*/
double coplanarity(const Projection &P, const Projection &Pp, const Eigen::Vector4d &centre,
                   const Eigen::Vector4d &centrep, const Eigen::Vector4d &A, const Eigen::Vector4d &B,
                   const Eigen::Vector4d &C, const Eigen::Vector4d &D)
{
  Eigen::Matrix4d T;
  T << A.transpose(), B.transpose(), C.transpose(), D.transpose();
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(T, Eigen::ComputeFullV);
  const Eigen::Vector4d plane = svd.matrixV().col(3);
  double sum = 0.0;
  for (const Eigen::Vector4d *X : {&A, &B, &C, &D}) {
    const double p = planeParallax(P, Pp, centre, centrep, plane, *X);
    sum += p * p;
  }
  return std::sqrt(sum / 4.0);
}

} // namespace

namespace vpProjectiveAcquisitionInternal
{
/*!
  The general-position margin of the points \e X (pixels): over the sets of 5 points, the largest of the smallest
  coplanarity() of 4 points of the set; \e best receives that set. At most the first 24
  points are examined (a lower bound for more).
*/
double generalPositionParallax(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &X,
                               std::vector<unsigned int> &best)
{
  Projection P, Pp;
  rig.getLeftProjection(P);
  rig.getRightProjection(Pp);
  const Eigen::Vector4d c = centreOf(P), cp = centreOf(Pp);
  const unsigned int K = static_cast<unsigned int>(std::min<size_t>(X.size(), 24));
  std::vector<double> c4(static_cast<size_t>(K) * K * K * K, 0.0);
  auto index = [K](unsigned int a, unsigned int b, unsigned int d, unsigned int e) {
    return ((static_cast<size_t>(a) * K + b) * K + d) * K + e;
  };
  for (unsigned int a = 0; a < K; ++a) {
    for (unsigned int b = a + 1; b < K; ++b) {
      for (unsigned int d = b + 1; d < K; ++d) {
        for (unsigned int e = d + 1; e < K; ++e) {
          c4[index(a, b, d, e)] = coplanarity(P, Pp, c, cp, X[a], X[b], X[d], X[e]);
        }
      }
    }
  }
  double margin = 0.0;
  best.clear();
  for (unsigned int a = 0; a < K; ++a) {
    for (unsigned int b = a + 1; b < K; ++b) {
      for (unsigned int d = b + 1; d < K; ++d) {
        for (unsigned int e = d + 1; e < K; ++e) {
          for (unsigned int f = e + 1; f < K; ++f) {
            const double g = std::min({c4[index(b, d, e, f)], c4[index(a, d, e, f)], c4[index(a, b, e, f)],
                                       c4[index(a, b, d, f)], c4[index(a, b, d, e)]});
            if (g > margin) {
              margin = g;
              best = {a, b, d, e, f};
            }
          }
        }
      }
    }
  }
  return margin;
}

/*!
  RMS distance (pixels) between the right images and the left ones mapped by the least-squares homography of all
  the pairs (DLT on Hartley-normalised points): at the noise level when the markers are all on one plane.
*/
double homographyTransferError(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
{
  const size_t K = left.size();
  auto normaliser = [K](const std::vector<vpImagePoint> &p) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const vpImagePoint &q : p) {
      mean += Eigen::Vector2d(q.get_u(), q.get_v()) / static_cast<double>(K);
    }
    double spread = 0.0;
    for (const vpImagePoint &q : p) {
      spread += (Eigen::Vector2d(q.get_u(), q.get_v()) - mean).norm() / static_cast<double>(K);
    }
    const double scale = spread > 0.0 ? std::sqrt(2.0) / spread : 1.0;
    Eigen::Matrix3d T;
    T << scale, 0.0, -scale * mean(0), 0.0, scale, -scale * mean(1), 0.0, 0.0, 1.0;
    return T;
  };
  const Eigen::Matrix3d T = normaliser(left), Tp = normaliser(right);
  Eigen::MatrixXd A(2 * K, 9);
  for (size_t j = 0; j < K; ++j) {
    const Eigen::Vector3d x = T * Eigen::Vector3d(left[j].get_u(), left[j].get_v(), 1.0);
    const Eigen::Vector3d xp = Tp * Eigen::Vector3d(right[j].get_u(), right[j].get_v(), 1.0);
    A.row(2 * j) << 0.0, 0.0, 0.0, -xp(2) * x.transpose(), xp(1) * x.transpose();
    A.row(2 * j + 1) << xp(2) * x.transpose(), 0.0, 0.0, 0.0, -xp(0) * x.transpose();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd h = svd.matrixV().col(8);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  const Eigen::Matrix3d H = Tp.inverse() * Hn * T;
  double sum = 0.0;
  for (size_t j = 0; j < K; ++j) {
    const Eigen::Vector3d m = H * Eigen::Vector3d(left[j].get_u(), left[j].get_v(), 1.0);
    sum += std::abs(m(2)) > 0.0
               ? (m.head<2>() / m(2) - Eigen::Vector2d(right[j].get_u(), right[j].get_v())).squaredNorm()
               : std::numeric_limits<double>::infinity();
  }
  return std::sqrt(sum / static_cast<double>(K));
}
} // namespace vpProjectiveAcquisitionInternal

void vpProjectiveAcquisitionProcedure::checkGeneralPosition(const vpProjectiveStereoRig &rig,
                                                            const std::vector<vpImagePoint> &left,
                                                            const std::vector<vpImagePoint> &right, const char *when)
{
  std::vector<Eigen::Vector4d> X(left.size());
  for (size_t j = 0; j < left.size(); ++j) {
    X[j] = rig.triangulate(Eigen::Vector2d(left[j].get_u(), left[j].get_v()),
                           Eigen::Vector2d(right[j].get_u(), right[j].get_v()));
  }
  std::vector<unsigned int> best;
  m_parallax = generalPositionParallax(rig, X, best);
  if (!(m_parallax >= m_coplanarity)) {
    std::ostringstream os;
    os << at("run") << ": the " << left.size() << " markers are too close to coplanar (" << when
       << "): every set of 5 markers has 4 within " << m_parallax
       << " px RMS of plane parallax of a plane (setCoplanarityThreshold(): " << m_coplanarity
       << " px). A rigid motion is only determined by 5 markers of which no 4 are coplanar (a planar target, or "
          "points on a plane and one more, leaves a family of motions that fit the images): add markers off the plane "
          "of the others, a few centimetres in depth (on the tool eye-to-hand, in the scene eye-in-hand).";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  std::ostringstream os;
  os << "  markers in general position: markers " << best[0] << ", " << best[1] << ", " << best[2] << ", " << best[3]
     << ", " << best[4] << " have no 4 within " << m_parallax << " px RMS of plane parallax of a plane (" << when
     << ")";
  progress(os.str());
}

void vpProjectiveAcquisitionProcedure::checkZeroReference(const vpProjectiveArmAcquisition &acquisition,
                                                          const std::vector<vpImagePoint> &left,
                                                          const std::vector<vpImagePoint> &right)
{
  // "Markers" in both mountings: the points the rig tracks, wherever they are.
  const std::string where = acquisition.getRigMounting() == vpProjectiveArmModel::EYE_IN_HAND
                                ? " (static in the scene, seen by the cameras on the hand)"
                                : " (on the tool, seen by the rig; static in the scene if the cameras ride on the arm)";
  if (left.size() != right.size()) {
    std::ostringstream os;
    os << at("run") << ": the image source gave " << left.size() << " left and " << right.size()
       << " right images of the markers" << where << " at the zero reference: give both images of every marker, in "
       << "the same order.";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  if (left.size() < 5) {
    std::ostringstream os;
    os << at("run") << ": " << left.size() << " markers at the zero reference" << where
       << "; the arm's motion is read off the images of at least 5 markers, 5 of them with no "
          "4 coplanar (a projective displacement has 15 degrees of freedom, each marker gives 3). ViSP's 4-point "
          "target cannot work: add at least one marker off its plane, a few centimetres in depth. Nothing moved.";
    throw vpProjectiveException(vpProjectiveException::notEnoughPointsError, os.str());
  }
  for (size_t j = 0; j < left.size(); ++j) {
    for (int image = 0; image < 2; ++image) {
      const vpImagePoint &p = image == 0 ? left[j] : right[j];
      if (!vpProjectiveInternal::vpImageWindow(m_width, m_height, m_imageMargin).contains(p)) {
        std::ostringstream os;
        os << at("run") << ": marker " << j << " is at (" << p.get_u() << ", " << p.get_v() << ") in the "
           << (image == 0 ? "left" : "right") << " image at the zero reference, not " << m_imageMargin
           << " px inside its " << m_width << " x " << m_height
           << " pixels (setImageMargin(), setImageSize()): place the arm so that every marker is well inside both "
              "images, then run again. Nothing moved.";
        throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
      }
    }
  }
  // All on one plane: a homography maps the left images onto the right ones. Needs no rig.
  const double transfer = homographyTransferError(left, right);
  if (transfer < m_coplanarity) {
    std::ostringstream os;
    os << at("run") << ": the " << left.size() << " markers are coplanar" << where
       << ": one homography maps their left images onto the right ones within " << transfer
       << " px RMS (setCoplanarityThreshold(): " << m_coplanarity
       << " px). A planar target cannot give the arm's motion, which needs 5 markers of which no 4 are coplanar: "
          "add markers off the plane, a few centimetres in depth. Nothing moved.";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  std::ostringstream os;
  os << "zero reference: " << left.size() << " markers inside both images, not all coplanar (" << transfer
     << " px RMS off the best homography)";
  progress(os.str());
  if (acquisition.getStereoRig().isInitialized()) {
    checkGeneralPosition(acquisition.getStereoRig(), left, right, "zero reference, known rig");
  }
}

double vpProjectiveAcquisitionProcedure::noiseAtRest(const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                                                     const std::vector<vpImagePoint> &right)
{
  std::vector<int> ids2;
  std::vector<vpImagePoint> left2, right2;
  if (!acquire(ids2, left2, right2)) {
    progress("image noise at rest: a marker was lost in the second frame; the calibration estimates the noise from "
             "the images");
    return 0.0;
  }
  // Two frames of the same markers without motion: each coordinate differs by sqrt(2) sigma RMS.
  double sum = 0.0;
  size_t coordinates = 0;
  for (size_t j = 0, m = 0; j < ids.size(); ++j) {
    while (m < ids2.size() && ids2[m] < ids[j]) {
      ++m; // ids ascending in both
    }
    if (m < ids2.size() && ids2[m] == ids[j] && m < left2.size() && m < right2.size()) {
      sum += vpImagePoint::sqrDistance(left[j], left2[m]) + vpImagePoint::sqrDistance(right[j], right2[m]);
      coordinates += 4;
    }
  }
  const double noise = coordinates > 0 ? std::sqrt(sum / (2.0 * static_cast<double>(coordinates))) : 0.0;
  std::ostringstream os;
  os << "image noise at rest: " << noise << " px RMS per coordinate (two frames without motion)";
  if (!(noise > 0.0)) {
    os << "; identical frames: the calibration estimates the noise from the images";
  }
  progress(os.str());
  return noise;
}
