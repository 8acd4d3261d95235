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

#include <visp3/projective/vpFeatureStereoPoint.h>

#include <iostream>
#include <sstream>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpFeatureStereoPoint");
const char *const kNames[4] = {"u", "v", "u'", "v'"};
} // namespace

vpFeatureStereoPoint::vpFeatureStereoPoint() : m_rig(nullptr)
{
  init();
}

void vpFeatureStereoPoint::init()
{
  dim_s = 4;
  nbParameters = 4;
  s.resize(dim_s);
  if (flags == nullptr) {
    flags = new bool[nbParameters];
  }
  for (unsigned int i = 0; i < nbParameters; ++i) {
    flags[i] = false;
  }
}

void vpFeatureStereoPoint::buildFrom(double u, double v, double up, double vp)
{
  const std::string where = at("buildFrom()");
  const double values[4] = {u, v, up, vp};
  for (unsigned int i = 0; i < 4; ++i) {
    requireFinite(values[i], where, std::string("the coordinate ") + kNames[i]);
  }
  for (unsigned int i = 0; i < 4; ++i) {
    s[i] = values[i];
    flags[i] = true;
  }
}

void vpFeatureStereoPoint::buildFrom(const vpImagePoint &ipLeft, const vpImagePoint &ipRight)
{
  buildFrom(ipLeft.get_u(), ipLeft.get_v(), ipRight.get_u(), ipRight.get_v());
}

void vpFeatureStereoPoint::buildFrom(const std::vector<vpImagePoint> &ipLeft, const std::vector<vpImagePoint> &ipRight)
{
  const std::string where = at("buildFrom()");
  if (ipLeft.empty() || ipLeft.size() != ipRight.size()) {
    std::ostringstream os;
    os << "got " << ipLeft.size() << " left and " << ipRight.size()
       << " right observations; give the point's image in both cameras for each frame, at least one frame";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  double sum[4] = {0.0, 0.0, 0.0, 0.0};
  for (size_t f = 0; f < ipLeft.size(); ++f) {
    const double values[4] = {ipLeft[f].get_u(), ipLeft[f].get_v(), ipRight[f].get_u(), ipRight[f].get_v()};
    for (unsigned int i = 0; i < 4; ++i) {
      requireFinite(values[i], where, std::string("the coordinate ") + kNames[i]);
      sum[i] += values[i];
    }
  }
  const double count = static_cast<double>(ipLeft.size());
  buildFrom(sum[0] / count, sum[1] / count, sum[2] / count, sum[3] / count);
}

void vpFeatureStereoPoint::buildFrom(const vpPoint &P, const vpCameraParameters &camLeft,
                                     const vpHomogeneousMatrix &cLeftMo, const vpCameraParameters &camRight,
                                     const vpHomogeneousMatrix &cRightMo)
{
  const std::string where = at("buildFrom()");
  const double oP[3] = {P.get_oX(), P.get_oY(), P.get_oZ()};
  for (unsigned int k = 0; k < 3; ++k) {
    requireFinite(oP[k], where, "the point's object-frame coordinates");
  }
  const vpHomogeneousMatrix *poses[2] = {&cLeftMo, &cRightMo};
  const vpCameraParameters *cams[2] = {&camLeft, &camRight};
  const char *const names[2] = {"left", "right"};
  double uv[4];
  for (unsigned int c = 0; c < 2; ++c) {
    const vpHomogeneousMatrix &cMo = *poses[c];
    double cP[3];
    for (unsigned int i = 0; i < 3; ++i) {
      cP[i] = cMo[i][0] * oP[0] + cMo[i][1] * oP[1] + cMo[i][2] * oP[2] + cMo[i][3];
      requireFinite(cP[i], where, std::string("the point in the ") + names[c] + " camera (check the pose)");
    }
    if (!(cP[2] > 0.0)) {
      std::ostringstream os;
      os << "the point (" << oP[0] << ", " << oP[1] << ", " << oP[2] << ") is not in front of the " << names[c]
         << " camera (Z = " << cP[2] << " m); check the pose given for that camera";
      fail(vpProjectiveException::pointAtInfinityError, where, os.str());
    }
    vpMeterPixelConversion::convertPoint(*cams[c], cP[0] / cP[2], cP[1] / cP[2], uv[2 * c], uv[2 * c + 1]);
  }
  buildFrom(uv[0], uv[1], uv[2], uv[3]);
}

vpImagePoint vpFeatureStereoPoint::getLeft() const
{
  vpImagePoint ip;
  ip.set_uv(s[0], s[1]);
  return ip;
}

vpImagePoint vpFeatureStereoPoint::getRight() const
{
  vpImagePoint ip;
  ip.set_uv(s[2], s[3]);
  return ip;
}

vpColVector vpFeatureStereoPoint::error(const vpBasicFeature &s_star, unsigned int select)
{
  const vpFeatureStereoPoint *desired = dynamic_cast<const vpFeatureStereoPoint *>(&s_star);
  if (desired == nullptr) {
    fail(vpProjectiveException::invalidValueError, at("error()"), "the desired feature is not a vpFeatureStereoPoint");
  }
  vpColVector e(getDimension(select));
  unsigned int row = 0;
  for (unsigned int i = 0; i < 4; ++i) {
    if (FEATURE_LINE[i] & select) {
      e[row++] = s[i] - desired->s[i];
    }
  }
  return e;
}

vpMatrix vpFeatureStereoPoint::interaction(unsigned int select)
{
  const std::string where = at("interaction()");
  if (m_rig == nullptr || !m_rig->isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where,
         "the interaction matrix needs the weakly calibrated rig; call setStereoRig() first");
  }
  const Eigen::Vector4d M = m_rig->triangulate(Eigen::Vector2d(s[0], s[1]), Eigen::Vector2d(s[2], s[3]));
  Eigen::Vector4d sM;
  Eigen::Matrix4d L; // J_C(P M) P and J_C(P' M) P', eq. (45)
  if (!m_rig->project(M, sM, &L)) {
    fail(vpProjectiveException::pointAtInfinityError, where, "the point lies on a camera's focal plane");
  }
  vpMatrix Ls(getDimension(select), 4);
  unsigned int row = 0;
  for (unsigned int i = 0; i < 4; ++i) {
    if (FEATURE_LINE[i] & select) {
      for (unsigned int j = 0; j < 4; ++j) {
        Ls[row][j] = L(i, j);
      }
      ++row;
    }
  }
  return Ls;
}

void vpFeatureStereoPoint::print(unsigned int select) const
{
  std::cout << "StereoPoint:";
  for (unsigned int i = 0; i < 4; ++i) {
    if (FEATURE_LINE[i] & select) {
      std::cout << " " << kNames[i] << "=" << s[i];
    }
  }
  std::cout << std::endl;
}

vpFeatureStereoPoint *vpFeatureStereoPoint::duplicate() const
{
  return new vpFeatureStereoPoint(*this);
}

void vpFeatureStereoPoint::display(const vpCameraParameters &, const vpImage<unsigned char> &I, const vpColor &color,
                                   unsigned int thickness) const
{
  vpDisplay::displayCross(I, getLeft(), 10, color, thickness);
}

void vpFeatureStereoPoint::display(const vpCameraParameters &, const vpImage<vpRGBa> &I, const vpColor &color,
                                   unsigned int thickness) const
{
  vpDisplay::displayCross(I, getLeft(), 10, color, thickness);
}

void vpFeatureStereoPoint::display(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                                   const vpColor &color, unsigned int thickness) const
{
  vpDisplay::displayCross(Ileft, getLeft(), 10, color, thickness);
  vpDisplay::displayCross(Iright, getRight(), 10, color, thickness);
}
