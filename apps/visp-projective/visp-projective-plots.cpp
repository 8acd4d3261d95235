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
  \file visp-projective-plots.cpp
  \brief The predicted marker paths of `visp-projective report --plots`.
*/

#include "visp-projective-plots.h"

#include <algorithm>
#include <limits>

#include <visp3/core/vpColor.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/projective/vpProjectiveJoint.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
std::vector<std::string> writeJointPathPlots(const vpProjectiveArmModel &model, double range, double travel,
                                             const std::string &folder)
{
  // paths[i][j]: the predicted (u, v, u', v') of marker j along joint i's motion; zero: at the zero reference.
  const unsigned int n = model.getNumberOfJoints(), m = static_cast<unsigned int>(model.markers().size());
  const int samples = 41;
  std::vector<std::vector<std::vector<Eigen::Vector4d>>> paths(n, std::vector<std::vector<Eigen::Vector4d>>(m));
  std::vector<Eigen::Vector4d> zero(m);
  Eigen::Vector4d lo = Eigen::Vector4d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  const vpProjectiveArmModel::JointVector qRef = model.zeroReferenceJoints();
  for (unsigned int j = 0; j < m; ++j) {
    model.predictMarker(j, model.displacement(qRef), zero[j]);
  }
  for (unsigned int i = 0; i < n; ++i) {
    const double amount =
        model.jointType(i) == vpProjectiveJoint::REVOLUTE ? vpMath::rad(range) : travel; // either way from qRef
    for (int k = 0; k < samples; ++k) {
      vpProjectiveArmModel::JointVector q = qRef;
      q(i) += amount * (2.0 * k / (samples - 1) - 1.0);
      const Eigen::Matrix4d H = model.displacement(q);
      for (unsigned int j = 0; j < m; ++j) {
        Eigen::Vector4d s;
        if (model.predictMarker(j, H, s) && s.allFinite()) {
          paths[i][j].push_back(s);
          lo = lo.cwiseMin(s);
          hi = hi.cwiseMax(s);
        }
      }
    }
  }
  vpIoTools::makeDirectory(folder);
  const vpColor colours[] = {vpColor::red,    vpColor::green, vpColor::blue,      vpColor::orange,
                             vpColor::purple, vpColor::cyan,  vpColor::darkGreen, vpColor::darkRed};
  const unsigned int width = 640, height = 480, margin = 20;
  std::vector<std::string> files;
  for (int c = 0; c < 2; ++c) { // left image (u, v), right image (u', v')
    const double u0 = lo(2 * c), v0 = lo(2 * c + 1);
    const double spanU = std::max(1e-9, hi(2 * c) - u0), spanV = std::max(1e-9, hi(2 * c + 1) - v0);
    const double scale = std::min((width - 2.0 * margin) / spanU, (height - 2.0 * margin) / spanV);
    const auto pixel = [&](const Eigen::Vector4d &s) {
      return vpImagePoint(margin + (s(2 * c + 1) - v0) * scale, margin + (s(2 * c) - u0) * scale);
    };
    vpImage<vpRGBa> I(height, width, vpRGBa(255, 255, 255));
    for (unsigned int i = 0; i < n; ++i) {
      for (unsigned int j = 0; j < m; ++j) {
        for (size_t k = 1; k < paths[i][j].size(); ++k) {
          vpImageDraw::drawLine(I, pixel(paths[i][j][k - 1]), pixel(paths[i][j][k]), colours[i % 8], 1);
        }
      }
    }
    for (unsigned int j = 0; j < m; ++j) {
      vpImageDraw::drawCross(I, pixel(zero[j]), 7, vpColor::black, 1);
    }
    const std::string file = folder + (c == 0 ? "/joint-paths-left.png" : "/joint-paths-right.png");
    vpImageIo::write(I, file);
    files.push_back(file);
  }
  return files;
}
} // namespace vispProjective
