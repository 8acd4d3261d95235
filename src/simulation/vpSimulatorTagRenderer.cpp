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
  \file vpSimulatorTagRenderer.cpp
  \brief Stereo images of printed AprilTags: exact perspective, supersampling, blur, lighting, noise, occluder.
*/

#include <visp3/projective/vpSimulatorTagRenderer.h>

#include <algorithm>
#include <cmath>
#include <numeric>
#include <sstream>
#include <string>

#include "simulation/vpAprilTag36h11.h"
#include "simulation/vpGaussianKernel.h"
#include "core/vpProjectiveErrors.h"

using vpProjectiveInternal::fail;

namespace
{
const vpProjectiveInternal::vpErrorSite at("vpSimulatorTagRenderer");

void checkRange(double value, double low, double high, const char *method, const std::string &what,
                const std::string &advice)
{
  if (!std::isfinite(value) || value < low || value > high) {
    std::ostringstream os;
    os << what << " " << value << " is out of [" << low << ", " << high << "]; " << advice;
    fail(vpProjectiveException::invalidValueError, at(method), os.str());
  }
}

void checkPose(const vpHomogeneousMatrix &M, const char *method)
{
  if (!vpProjectiveInternal::allFinite(M)) {
    fail(vpProjectiveException::nonFiniteValueError, at(method), "the pose is not finite; check it");
  }
}
} // namespace

vpSimulatorTagRenderer::vpSimulatorTagRenderer(const vpSimulatorStereoRig &rig, long seed)
    : m_rig(rig), m_tags(), m_wMb(), m_background(128.0), m_black(30.0), m_white(220.0), m_blur(0.0), m_noise(1.0),
      m_supersampling(4), m_gain(1.0), m_offset(0.0), m_gradientU(0.0), m_gradientV(0.0), m_occluder(3, 0.0),
      m_occluderRadius(0.0), m_occluderLevel(15.0), m_seed(seed),
      m_kernel(vpProjectiveInternal::halfKernel(0.0)), m_cameras{{rig, false, m_background}, {rig, true, m_background}},
      m_imageNoise(m_noise, seed), m_labels(), m_views(), m_near()
{
  resetNoise();
}

unsigned int vpSimulatorTagRenderer::addTag(int id, double size, const vpHomogeneousMatrix &bMt)
{
  checkRange(id, 0, maxTagId, "addTag()", "the tag id", "the renderer holds the 36h11 codes 0 to 31.");
  checkRange(size, 1e-4, 10.0, "addTag()", "the tag size (m)", "give the side of the black square in metres.");
  checkPose(bMt, "addTag()");
  Tag tag;
  tag.id = id;
  tag.size = size;
  tag.bMt = bMt;
  for (int y = 0; y < 10; ++y) {
    for (int x = 0; x < 10; ++x) {
      tag.cells[10 * y + x] = (x == 0 || y == 0 || x == 9 || y == 9) ? 1 : 0; // quiet zone white, the rest black
    }
  }
  for (int b = 0; b < 36; ++b) {
    if ((vpProjectiveInternal::kCodes36h11[id] >> (35 - b)) & 1u) {
      tag.cells[10 * (vpProjectiveInternal::kBitY[b] + 1) + vpProjectiveInternal::kBitX[b] + 1] = 1;
    }
  }
  m_tags.push_back(tag);
  return static_cast<unsigned int>(m_tags.size() - 1);
}

const vpSimulatorTagRenderer::Tag &vpSimulatorTagRenderer::tag(unsigned int index, const char *method) const
{
  if (index >= m_tags.size()) {
    std::ostringstream os;
    os << "no tag " << index << " (there are " << m_tags.size() << "); use the index addTag() returned";
    fail(vpProjectiveException::invalidValueError, at(method), os.str());
  }
  return m_tags[index];
}

void vpSimulatorTagRenderer::setTagPose(unsigned int index, const vpHomogeneousMatrix &bMt)
{
  tag(index, "setTagPose()"); // throws on a bad index
  checkPose(bMt, "setTagPose()");
  m_tags[index].bMt = bMt;
}

void vpSimulatorTagRenderer::setBodyPose(const vpHomogeneousMatrix &wMb)
{
  checkPose(wMb, "setBodyPose()");
  m_wMb = wMb;
}

std::vector<vpColVector> vpSimulatorTagRenderer::getCorners(unsigned int index) const
{
  const Tag &t = tag(index, "getCorners()");
  const vpHomogeneousMatrix wMt = m_wMb * t.bMt;
  const double h = t.size / 2.0;
  const double xs[4] = {-h, h, h, -h}, ys[4] = {h, h, -h, -h};
  std::vector<vpColVector> corners;
  for (int k = 0; k < 4; ++k) {
    vpColVector X(3);
    for (unsigned int r = 0; r < 3; ++r) {
      X[r] = wMt[r][0] * xs[k] + wMt[r][1] * ys[k] + wMt[r][3];
    }
    corners.push_back(X);
  }
  return corners;
}

bool vpSimulatorTagRenderer::getImageCorners(unsigned int index, std::vector<vpImagePoint> &left,
                                             std::vector<vpImagePoint> &right) const
{
  const std::vector<vpColVector> wX = getCorners(index);
  bool visible = true;
  for (int c = 0; c < 2; ++c) {
    View v;
    visible = view(m_cameras[c], m_tags[index], v) && visible;
    std::vector<vpImagePoint> &out = c == 0 ? left : right;
    out.clear();
    const vpHomogeneousMatrix &cMw = m_cameras[c].cMw;
    const vpCameraParameters &cam = m_cameras[c].cam;
    for (const vpColVector &X : wX) {
      double p[3];
      for (unsigned int r = 0; r < 3; ++r) {
        p[r] = cMw[r][0] * X[0] + cMw[r][1] * X[1] + cMw[r][2] * X[2] + cMw[r][3];
      }
      const double u = cam.get_u0() + cam.get_px() * p[0] / p[2], w = cam.get_v0() + cam.get_py() * p[1] / p[2];
      out.push_back(vpImagePoint(w, u));
      visible = visible && u >= 0.0 && w >= 0.0 && u <= m_rig.getWidth() - 1.0 && w <= m_rig.getHeight() - 1.0;
    }
  }
  return visible;
}

void vpSimulatorTagRenderer::setGrayLevels(double background, double black, double white)
{
  checkRange(background, 0.0, 255.0, "setGrayLevels()", "the background grey level", "grey levels are 8-bit.");
  checkRange(black, 0.0, 255.0, "setGrayLevels()", "the black grey level", "grey levels are 8-bit.");
  checkRange(white, 0.0, 255.0, "setGrayLevels()", "the white grey level", "grey levels are 8-bit.");
  m_background = background;
  m_black = black;
  m_white = white;
}

void vpSimulatorTagRenderer::setBlur(double sigma)
{
  checkRange(sigma, 0.0, 10.0, "setBlur()", "the blur (px)", "give the standard deviation of the optics' blur.");
  m_kernel = vpProjectiveInternal::halfKernel(sigma);
  m_blur = sigma;
}

void vpSimulatorTagRenderer::setNoise(double sigma)
{
  checkRange(sigma, 0.0, 100.0, "setNoise()", "the sensor noise (grey levels)", "give a standard deviation.");
  m_noise = sigma;
  resetNoise();
}

void vpSimulatorTagRenderer::setSupersampling(unsigned int rays)
{
  checkRange(rays, 1.0, 32.0, "setSupersampling()", "the number of rays per pixel and axis",
             "use 1 (no anti-aliasing) to 32.");
  m_supersampling = rays;
}

void vpSimulatorTagRenderer::setLighting(double gain, double offset, double gradientU, double gradientV)
{
  checkRange(gain, 0.0, 10.0, "setLighting()", "the gain", "1 leaves the grey levels unchanged.");
  checkRange(offset, -255.0, 255.0, "setLighting()", "the offset", "0 leaves the grey levels unchanged.");
  checkRange(gradientU, -1.0, 1.0, "setLighting()", "the horizontal gradient", "a relative gain change.");
  checkRange(gradientV, -1.0, 1.0, "setLighting()", "the vertical gradient", "a relative gain change.");
  m_gain = gain;
  m_offset = offset;
  m_gradientU = gradientU;
  m_gradientV = gradientV;
}

void vpSimulatorTagRenderer::setOccluder(const vpColVector &wC, double radius, double level)
{
  if (wC.size() != 3 || !vpProjectiveInternal::allFinite(wC)) {
    fail(vpProjectiveException::dimensionError, at("setOccluder()"),
         "the occluder's centre must be a finite world point (3x1)");
  }
  checkRange(radius, 1e-6, 10.0, "setOccluder()", "the occluder's radius (m)", "give a positive radius in metres.");
  checkRange(level, 0.0, 255.0, "setOccluder()", "the occluder's grey level", "grey levels are 8-bit.");
  m_occluder = wC;
  m_occluderRadius = radius;
  m_occluderLevel = level;
}

void vpSimulatorTagRenderer::setSeed(long seed)
{
  m_seed = seed;
  resetNoise();
}

void vpSimulatorTagRenderer::resetNoise()
{
  m_imageNoise.reset(m_noise, m_seed);
}
