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
  \file vpSimulatorMarkerRenderer.cpp
  \brief Stereo images of lit spherical markers: exact silhouettes, supersampling, blur, noise.
*/

#include <visp3/projective/vpSimulatorMarkerRenderer.h>

#include <algorithm>
#include <cmath>
#include <sstream>
#include <string>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpImageFilter.h>

#include <visp3/projective/vpProjectiveException.h>

#include "simulation/vpGaussianKernel.h"

namespace
{
void checkRange(double value, double low, double high, const char *what, const char *advice)
{
  if (!std::isfinite(value) || value < low || value > high) {
    std::ostringstream os;
    os << "vpSimulatorMarkerRenderer: " << what << " " << value << " is out of [" << low << ", " << high << "]; "
       << advice;
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
}

} // namespace

vpSimulatorMarkerRenderer::vpSimulatorMarkerRenderer(const vpSimulatorStereoRig &rig, long seed)
    : m_rig(rig), m_radius(0.003), m_background(30.0), m_marker(220.0), m_blur(0.8), m_noise(4.0), m_supersampling(8),
      m_seed(seed),
      m_kernel(vpProjectiveInternal::halfKernel(0.8)), m_cameras{{rig, false, m_background}, {rig, true, m_background}},
      m_imageNoise(m_noise, seed)
{
  resetNoise();
}

void vpSimulatorMarkerRenderer::setMarkerRadius(double radius)
{
  checkRange(radius, 1e-6, 1e3, "the marker radius (m)", "give a positive radius in metres.");
  m_radius = radius;
}

void vpSimulatorMarkerRenderer::setGrayLevels(double background, double marker)
{
  checkRange(background, 0.0, 255.0, "the background grey level", "grey levels are 8-bit values.");
  checkRange(marker, 0.0, 255.0, "the marker grey level", "grey levels are 8-bit values.");
  m_background = background;
  m_marker = marker;
  resetBuffers();
  resetNoise();
}

void vpSimulatorMarkerRenderer::setBlur(double sigma)
{
  checkRange(sigma, 0.0, 10.0, "the blur (px)", "give the standard deviation of the optics' blur in pixels.");
  m_kernel = vpProjectiveInternal::halfKernel(sigma);
  m_blur = sigma;
}

void vpSimulatorMarkerRenderer::setNoise(double sigma)
{
  checkRange(sigma, 0.0, 100.0, "the sensor noise (grey levels)", "give a standard deviation in grey levels.");
  m_noise = sigma;
  resetNoise();
}

void vpSimulatorMarkerRenderer::setSupersampling(unsigned int rays)
{
  checkRange(rays, 1.0, 32.0, "the number of rays per pixel and axis", "use 1 (no anti-aliasing) to 32.");
  m_supersampling = rays;
}

void vpSimulatorMarkerRenderer::setSeed(long seed)
{
  m_seed = seed;
  resetNoise();
}

double vpSimulatorMarkerRenderer::getImageRadius(double depth) const
{
  if (!(depth > 2.0 * m_radius)) {
    return 0.0;
  }
  return m_rig.getLeftCameraParameters().get_px() * m_radius / std::sqrt(depth * depth - m_radius * m_radius);
}

void vpSimulatorMarkerRenderer::resetBuffers()
{
  for (vpSimulatorCameraBuffers &c : m_cameras) {
    c.reset(m_background);
  }
}

void vpSimulatorMarkerRenderer::resetNoise()
{
  m_imageNoise.reset(m_noise, m_seed);
}

void vpSimulatorMarkerRenderer::render(const std::vector<vpColVector> &wX, vpImage<unsigned char> &Ileft,
                                       vpImage<unsigned char> &Iright)
{
  for (size_t k = 0; k < wX.size(); ++k) {
    const vpColVector &X = wX[k];
    if (X.size() != 3 && !(X.size() == 4 && X[3] == 1.0)) {
      std::ostringstream os;
      os << "vpSimulatorMarkerRenderer::render(): point " << k << " has " << X.size()
         << " entries; give world points as 3x1 vectors (or 4x1 with last entry 1).";
      throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
    }
    if (!std::isfinite(X[0]) || !std::isfinite(X[1]) || !std::isfinite(X[2])) {
      std::ostringstream os;
      os << "vpSimulatorMarkerRenderer::render(): point " << k << " is not finite; check the marker positions.";
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
    }
  }
  renderCamera(m_cameras[0], wX, Ileft);
  renderCamera(m_cameras[1], wX, Iright);
}

void vpSimulatorMarkerRenderer::renderCamera(vpSimulatorCameraBuffers &camera, const std::vector<vpColVector> &wX,
                                             vpImage<unsigned char> &I)
{
  const int width = static_cast<int>(m_rig.getWidth()), height = static_cast<int>(m_rig.getHeight());
  const int h = static_cast<int>(m_kernel.size()) - 1;
  const double R = m_radius;
  const double px = camera.cam.get_px(), py = camera.cam.get_py(), u0 = camera.cam.get_u0(), v0 = camera.cam.get_v0();
  const vpHomogeneousMatrix &cMw = camera.cMw;

  // Where each ball is: its centre in the camera frame and a pixel box holding its silhouette.
  std::vector<Ball> balls;
  for (const vpColVector &X : wX) {
    Ball b;
    b.x = cMw[0][0] * X[0] + cMw[0][1] * X[1] + cMw[0][2] * X[2] + cMw[0][3];
    b.y = cMw[1][0] * X[0] + cMw[1][1] * X[1] + cMw[1][2] * X[2] + cMw[1][3];
    b.z = cMw[2][0] * X[0] + cMw[2][1] * X[1] + cMw[2][2] * X[2] + cMw[2][3];
    if (b.z <= 2.0 * R) {
      continue; // behind the camera, or too close to it: not imaged
    }
    b.c2 = b.x * b.x + b.y * b.y + b.z * b.z - R * R;
    // The silhouette is an ellipse of semi-axes rho and rho / cos(angle off the optical axis), 3% longer at the
    // image corners, centred within 0.01 px of the image of the ball's centre: pixels whose centre is farther than
    // 1.2 rho + 0.75 px (half a pixel diagonal) from there do not see the ball.
    const double rho = px * R / std::sqrt(b.z * b.z - R * R);
    b.u = u0 + px * b.x / b.z;
    b.v = v0 + py * b.y / b.z;
    b.reach = 1.2 * rho + 0.75;
    b.jmin = std::max(0, static_cast<int>(std::floor(b.u - b.reach)));
    b.jmax = std::min(width - 1, static_cast<int>(std::ceil(b.u + b.reach)));
    b.imin = std::max(0, static_cast<int>(std::floor(b.v - b.reach)));
    b.imax = std::min(height - 1, static_cast<int>(std::ceil(b.v + b.reach)));
    if (b.jmin <= b.jmax && b.imin <= b.imax) {
      balls.push_back(b);
    }
  }

  // Supersampled silhouettes: the fraction of a pixel's rays that hit a ball. A silhouette is convex, so a pixel
  // whose four corners see the same ball is covered: only the pixels on a silhouette's edge need the S x S rays.
  const unsigned int S = m_supersampling;
  const double contrast = m_marker - m_background;
  const auto hit = [&](const Ball &b, double u, double v) {
    const double dx = (u - u0) / px, dy = (v - v0) / py, dc = dx * b.x + dy * b.y + b.z;
    return dc > 0.0 && dc * dc >= (dx * dx + dy * dy + 1.0) * b.c2;
  };
  ++camera.frame;
  std::vector<const Ball *> near;
  for (const Ball &box : balls) {
    for (int i = box.imin; i <= box.imax; ++i) {
      for (int j = box.jmin; j <= box.jmax; ++j) {
        if (camera.stamp[i][j] == camera.frame) {
          continue; // already done for an overlapping box
        }
        camera.stamp[i][j] = camera.frame;
        near.clear();
        for (const Ball &b : balls) {
          if ((j - b.u) * (j - b.u) + (i - b.v) * (i - b.v) < b.reach * b.reach) {
            near.push_back(&b);
          }
        }
        unsigned int hits = 0;
        for (const Ball *b : near) {
          if (hit(*b, j - 0.5, i - 0.5) && hit(*b, j + 0.5, i - 0.5) && hit(*b, j - 0.5, i + 0.5) &&
              hit(*b, j + 0.5, i + 0.5)) {
            hits = S * S;
            break;
          }
        }
        for (unsigned int a = 0; a < S && hits < S * S && !near.empty(); ++a) {
          for (unsigned int c = 0; c < S; ++c) {
            for (const Ball *b : near) {
              if (hit(*b, j - 0.5 + (c + 0.5) / S, i - 0.5 + (a + 0.5) / S)) {
                ++hits;
                break;
              }
            }
          }
        }
        camera.ideal[i][j] = m_background + contrast * hits / (S * S);
      }
    }
  }

  // Separable Gaussian blur (vpImageFilter's kernel) around the balls, edges replicated.
  for (const Ball &b : balls) {
    const int j0 = std::max(0, b.jmin - h), j1 = std::min(width - 1, b.jmax + h);
    for (int i = std::max(0, b.imin - 2 * h); i <= std::min(height - 1, b.imax + 2 * h); ++i) {
      for (int j = j0; j <= j1; ++j) {
        double sum = m_kernel[0] * camera.ideal[i][j];
        for (int k = 1; k <= h; ++k) {
          sum += m_kernel[k] * (camera.ideal[i][std::max(0, j - k)] + camera.ideal[i][std::min(width - 1, j + k)]);
        }
        camera.horizontal[i][j] = sum;
      }
    }
  }
  for (const Ball &b : balls) {
    const int j0 = std::max(0, b.jmin - h), j1 = std::min(width - 1, b.jmax + h);
    for (int i = std::max(0, b.imin - h); i <= std::min(height - 1, b.imax + h); ++i) {
      for (int j = j0; j <= j1; ++j) {
        double sum = m_kernel[0] * camera.horizontal[i][j];
        for (int k = 1; k <= h; ++k) {
          sum += m_kernel[k] *
                 (camera.horizontal[std::max(0, i - k)][j] + camera.horizontal[std::min(height - 1, i + k)][j]);
        }
        camera.blurred[i][j] = sum;
      }
    }
  }

  // Sensor noise on every pixel, and 8-bit quantisation: the background, then again around the balls.
  I.resize(static_cast<unsigned int>(height), static_cast<unsigned int>(width));
  for (unsigned int k = 0; k < I.getSize(); ++k) {
    I.bitmap[k] = m_imageNoise.flat(m_background);
  }
  for (const Ball &b : balls) {
    for (int i = std::max(0, b.imin - h); i <= std::min(height - 1, b.imax + h); ++i) {
      for (int j = std::max(0, b.jmin - h); j <= std::min(width - 1, b.jmax + h); ++j) {
        I[i][j] = m_imageNoise.noisy(camera.blurred[i][j]);
      }
    }
  }

  // Back to the uniform background for the next image.
  for (const Ball &b : balls) {
    for (int i = std::max(0, b.imin - 2 * h); i <= std::min(height - 1, b.imax + 2 * h); ++i) {
      for (int j = std::max(0, b.jmin - h); j <= std::min(width - 1, b.jmax + h); ++j) {
        camera.ideal[i][j] = camera.horizontal[i][j] = camera.blurred[i][j] = m_background;
      }
    }
  }
}
