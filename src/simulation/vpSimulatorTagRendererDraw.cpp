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
  \file vpSimulatorTagRendererDraw.cpp
  \brief The drawing of vpSimulatorTagRenderer: each tag's view, the grey level of a pixel, blur, lighting, noise.
*/

#include <visp3/projective/vpSimulatorTagRenderer.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

bool vpSimulatorTagRenderer::view(const vpSimulatorCameraBuffers &camera, const Tag &tag, View &v) const
{
  const vpHomogeneousMatrix cMt = camera.cMw * m_wMb * tag.bMt;
  const double px = camera.cam.get_px(), py = camera.cam.get_py(), u0 = camera.cam.get_u0(), v0 = camera.cam.get_v0();
  // Printed side (-z) towards the camera: the tag's origin lies ahead along its z axis.
  const double facing = cMt[0][2] * cMt[0][3] + cMt[1][2] * cMt[1][3] + cMt[2][2] * cMt[2][3];
  if (!(facing > 1e-9)) {
    return false;
  }
  // A = K [r1 r2 t]: tag (X, Y, 1) -> Z (u, v, 1); H = G A^-1 with G: (X, Y) -> cells (X 8 / s + 5, Y 8 / s + 5).
  double A[9];
  for (int c = 0; c < 3; ++c) {
    const int col = c == 2 ? 3 : c;
    A[c] = px * cMt[0][col] + u0 * cMt[2][col];
    A[3 + c] = py * cMt[1][col] + v0 * cMt[2][col];
    A[6 + c] = cMt[2][col];
  }
  const double det =
      A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) + A[2] * (A[3] * A[7] - A[4] * A[6]);
  if (!(std::fabs(det) > 0.0)) {
    return false;
  }
  const double inv[9] = {
      (A[4] * A[8] - A[5] * A[7]) / det, (A[2] * A[7] - A[1] * A[8]) / det, (A[1] * A[5] - A[2] * A[4]) / det,
      (A[5] * A[6] - A[3] * A[8]) / det, (A[0] * A[8] - A[2] * A[6]) / det, (A[2] * A[3] - A[0] * A[5]) / det,
      (A[3] * A[7] - A[4] * A[6]) / det, (A[1] * A[6] - A[0] * A[7]) / det, (A[0] * A[4] - A[1] * A[3]) / det};
  const double g = 8.0 / tag.size;
  for (int c = 0; c < 3; ++c) {
    v.H[c] = g * inv[c] + 5.0 * inv[6 + c];
    v.H[3 + c] = g * inv[3 + c] + 5.0 * inv[6 + c];
    v.H[6 + c] = inv[6 + c];
  }
  // Pixel box of the quiet zone, whose corners must all be in front of the camera.
  const double q = 0.625 * tag.size;
  double umin = 1e300, umax = -1e300, vmin = 1e300, vmax = -1e300;
  for (int k = 0; k < 4; ++k) {
    const double X = (k == 1 || k == 2) ? q : -q, Y = k < 2 ? q : -q;
    const double x = cMt[0][0] * X + cMt[0][1] * Y + cMt[0][3], y = cMt[1][0] * X + cMt[1][1] * Y + cMt[1][3],
                 z = cMt[2][0] * X + cMt[2][1] * Y + cMt[2][3];
    if (!(z > 1e-3)) {
      return false;
    }
    umin = std::min(umin, u0 + px * x / z);
    umax = std::max(umax, u0 + px * x / z);
    vmin = std::min(vmin, v0 + py * y / z);
    vmax = std::max(vmax, v0 + py * y / z);
  }
  const double W = m_rig.getWidth(), Hh = m_rig.getHeight();
  if (umax < -1.0 || vmax < -1.0 || umin > W || vmin > Hh) {
    return false;
  }
  v.jmin = std::max(0, static_cast<int>(std::floor(umin)) - 1);
  v.jmax = std::min(static_cast<int>(W) - 1, static_cast<int>(std::ceil(umax)) + 1);
  v.imin = std::max(0, static_cast<int>(std::floor(vmin)) - 1);
  v.imax = std::min(static_cast<int>(Hh) - 1, static_cast<int>(std::ceil(vmax)) + 1);
  v.tag = &tag;
  return true;
}

inline double vpSimulatorTagRenderer::level(const vpSimulatorCameraBuffers &camera,
                                            const std::vector<const View *> &views, double u, double v,
                                            int &label) const
{
  label = -1;
  double value = m_background, nearest = 0.0;
  for (const View *view : views) {
    const View &w = *view;
    if (u < w.jmin - 1 || u > w.jmax + 1 || v < w.imin - 1 || v > w.imax + 1) {
      continue;
    }
    if (w.tag == nullptr) { // the occluder: ray/ball test, drawn over the tags
      const double dx = (u - camera.cam.get_u0()) / camera.cam.get_px(),
                   dy = (v - camera.cam.get_v0()) / camera.cam.get_py(), dc = dx * w.H[0] + dy * w.H[1] + w.H[2];
      if (dc > 0.0 && dc * dc >= (dx * dx + dy * dy + 1.0) * w.H[3]) {
        label = -2;
        return m_occluderLevel;
      }
      continue;
    }
    const double iz = w.H[6] * u + w.H[7] * v + w.H[8]; // 1 / depth
    if (!(iz > nearest)) {
      continue;
    }
    const double z = 1.0 / iz, gx = (w.H[0] * u + w.H[1] * v + w.H[2]) * z, gy = (w.H[3] * u + w.H[4] * v + w.H[5]) * z;
    if (gx >= 0.0 && gy >= 0.0 && gx < 10.0 && gy < 10.0) {
      const int cell = 10 * static_cast<int>(gy) + static_cast<int>(gx);
      nearest = iz;
      label = (static_cast<int>(w.tag - m_tags.data()) << 8) | cell;
      value = w.tag->cells[cell] ? m_white : m_black;
    }
  }
  return value;
}

void vpSimulatorTagRenderer::render(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright)
{
  renderCamera(m_cameras[0], Ileft);
  renderCamera(m_cameras[1], Iright);
}

void vpSimulatorTagRenderer::renderCamera(vpSimulatorCameraBuffers &camera, vpImage<unsigned char> &I)
{
  const int width = static_cast<int>(m_rig.getWidth()), height = static_cast<int>(m_rig.getHeight());
  const int h = static_cast<int>(m_kernel.size()) - 1;

  m_views.clear();
  for (const Tag &tag : m_tags) {
    View v;
    if (view(camera, tag, v)) {
      m_views.push_back(v);
    }
  }
  if (m_occluderRadius > 0.0) {
    const vpHomogeneousMatrix &M = camera.cMw;
    const double R = m_occluderRadius;
    View v;
    for (unsigned int r = 0; r < 3; ++r) {
      v.H[r] = M[r][0] * m_occluder[0] + M[r][1] * m_occluder[1] + M[r][2] * m_occluder[2] + M[r][3];
    }
    if (v.H[2] > 2.0 * R) {
      v.H[3] = v.H[0] * v.H[0] + v.H[1] * v.H[1] + v.H[2] * v.H[2] - R * R;
      const double rho = camera.cam.get_px() * R / std::sqrt(v.H[2] * v.H[2] - R * R);
      const double u = camera.cam.get_u0() + camera.cam.get_px() * v.H[0] / v.H[2],
                   w = camera.cam.get_v0() + camera.cam.get_py() * v.H[1] / v.H[2], reach = 1.2 * rho + 0.75;
      v.jmin = std::max(0, static_cast<int>(std::floor(u - reach)));
      v.jmax = std::min(width - 1, static_cast<int>(std::ceil(u + reach)));
      v.imin = std::max(0, static_cast<int>(std::floor(w - reach)));
      v.imax = std::min(height - 1, static_cast<int>(std::ceil(w + reach)));
      v.tag = nullptr;
      if (v.jmin <= v.jmax && v.imin <= v.imax) {
        m_views.push_back(v);
      }
    }
  }

  // Ideal image (no blur) on each box grown by twice the kernel's half-width: labels of the pixels' corners (tag
  // index * 256 + cell, -1 the scene, -2 the occluder), then a pixel whose 4 corners fall in one cell, or in a block
  // of 2 x 2 cells of one colour (convex as well), has that colour; the others average S x S rays.
  const auto uniform = [this](int a, int b, int c, int d) {
    if (a == b && a == c && a == d) {
      return true;
    }
    if (a < 0 || b < 0 || c < 0 || d < 0 || (a >> 8) != (b >> 8) || (a >> 8) != (c >> 8) || (a >> 8) != (d >> 8)) {
      return false;
    }
    const int cells[4] = {a & 255, b & 255, c & 255, d & 255};
    int x0 = 9, x1 = 0, y0 = 9, y1 = 0;
    for (int cell : cells) {
      x0 = std::min(x0, cell % 10);
      x1 = std::max(x1, cell % 10);
      y0 = std::min(y0, cell / 10);
      y1 = std::max(y1, cell / 10);
    }
    if (x1 - x0 > 1 || y1 - y0 > 1) {
      return false;
    }
    const uint8_t *pattern = m_tags[static_cast<size_t>(a >> 8)].cells;
    const uint8_t colour = pattern[10 * y0 + x0];
    return pattern[10 * y0 + x1] == colour && pattern[10 * y1 + x0] == colour && pattern[10 * y1 + x1] == colour;
  };
  const auto colour = [this](int label) {
    return label == -1
               ? m_background
               : (label == -2 ? m_occluderLevel
                              : (m_tags[static_cast<size_t>(label >> 8)].cells[label & 255] ? m_white : m_black));
  };
  ++camera.frame;
  // The S x S rays of an edge pixel: a rank-1 lattice, ray k at ((k + 1/2) / N, ((g k mod N) + 1/2) / N), N = S^2,
  // g coprime with N near N / 1.618 (Fibonacci-like): every ray on its own row and column, so that a near-horizontal
  // or near-vertical edge is resolved to 1 / N px (a square grid resolves it to 1 / S px).
  const unsigned int N = m_supersampling * m_supersampling;
  unsigned int generator = std::max(1u, static_cast<unsigned int>(std::lround(N / 1.618)));
  while (std::gcd(generator, N) != 1) {
    ++generator;
  }
  for (const View &box : m_views) {
    const int i0 = std::max(0, box.imin - 2 * h), i1 = std::min(height - 1, box.imax + 2 * h);
    const int j0 = std::max(0, box.jmin - 2 * h), j1 = std::min(width - 1, box.jmax + 2 * h);
    m_near.clear(); // the views that may be seen in this box
    for (const View &other : m_views) {
      if (other.jmin - 1 <= j1 + 1 && other.jmax + 1 >= j0 - 1 && other.imin - 1 <= i1 + 1 &&
          other.imax + 1 >= i0 - 1) {
        m_near.push_back(&other);
      }
    }
    // The same as level(), shorter when a single tag may be seen in the box (the usual case).
    const View *only = m_near.size() == 1 && m_near[0]->tag != nullptr ? m_near[0] : nullptr;
    const int base = only == nullptr ? 0 : static_cast<int>(only->tag - m_tags.data()) << 8;
    const auto sample = [&](double u, double v, int &label) {
      if (only == nullptr) {
        return level(camera, m_near, u, v, label);
      }
      const double *H = only->H;
      const double iz = H[6] * u + H[7] * v + H[8];
      label = -1;
      if (iz > 0.0) {
        const double z = 1.0 / iz, gx = (H[0] * u + H[1] * v + H[2]) * z, gy = (H[3] * u + H[4] * v + H[5]) * z;
        if (gx >= 0.0 && gy >= 0.0 && gx < 10.0 && gy < 10.0) {
          const int cell = 10 * static_cast<int>(gy) + static_cast<int>(gx);
          label = base | cell;
          return only->tag->cells[cell] ? m_white : m_black;
        }
      }
      return m_background;
    };
    const int cols = j1 - j0 + 2;
    m_labels.resize(static_cast<size_t>((i1 - i0 + 2) * cols));
    for (int i = i0; i <= i1 + 1; ++i) {
      for (int j = j0; j <= j1 + 1; ++j) {
        sample(j - 0.5, i - 0.5, m_labels[(i - i0) * cols + (j - j0)]);
      }
    }
    for (int i = i0; i <= i1; ++i) {
      for (int j = j0; j <= j1; ++j) {
        if (camera.stamp[i][j] >= camera.frame) {
          continue; // done for an overlapping box
        }
        camera.stamp[i][j] = h == 0 ? camera.frame + 1 : camera.frame; // without blur, the ideal is the image
        const int *l = &m_labels[(i - i0) * cols + (j - j0)];
        int label;
        if (uniform(l[0], l[1], l[cols], l[cols + 1])) {
          camera.ideal[i][j] = colour(l[0]); // every corner (and cell between them) has this colour
          continue;
        }
        double sum = 0.0;
        for (unsigned int k = 0; k < N; ++k) {
          sum += sample(j - 0.5 + (k + 0.5) / N, i - 0.5 + ((k * generator) % N + 0.5) / N, label);
        }
        camera.ideal[i][j] = sum / N;
      }
    }
  }

  // Separable Gaussian blur (vpImageFilter's kernel) on each box grown by the kernel's half-width, edges replicated.
  for (const View &box : m_views) {
    if (h == 0) {
      break; // no blur: the final pass reads the ideal image
    }
    const int j0 = std::max(0, box.jmin - h), j1 = std::min(width - 1, box.jmax + h);
    const int jl = std::max(0, box.jmin - 2 * h), jr = std::min(width - 1, box.jmax + 2 * h); // the ideal's box
    for (int i = std::max(0, box.imin - 2 * h); i <= std::min(height - 1, box.imax + 2 * h); ++i) {
      for (int j = j0; j <= j1; ++j) {
        double sum = m_kernel[0] * camera.ideal[i][j];
        for (int k = 1; k <= h; ++k) {
          sum += m_kernel[k] * (camera.ideal[i][std::max(jl, j - k)] + camera.ideal[i][std::min(jr, j + k)]);
        }
        camera.horizontal[i][j] = sum;
      }
    }
  }
  for (const View &box : m_views) {
    if (h == 0) {
      break;
    }
    const int j0 = std::max(0, box.jmin - h), j1 = std::min(width - 1, box.jmax + h);
    const int i0 = std::max(0, box.imin - h), i1 = std::min(height - 1, box.imax + h);
    const int il = std::max(0, box.imin - 2 * h), ir = std::min(height - 1, box.imax + 2 * h);
    for (int i = i0; i <= i1; ++i) {
      for (int j = j0; j <= j1; ++j) {
        double sum = m_kernel[0] * camera.horizontal[i][j];
        for (int k = 1; k <= h; ++k) {
          sum += m_kernel[k] * (camera.horizontal[std::max(il, i - k)][j] + camera.horizontal[std::min(ir, i + k)][j]);
        }
        camera.blurred[i][j] = sum;
        camera.stamp[i][j] = camera.frame + 1; // blurred value valid in this frame
      }
    }
  }

  // Lighting, sensor noise, 8-bit quantisation on every pixel (the uniform background outside the boxes).
  I.resize(static_cast<unsigned int>(height), static_cast<unsigned int>(width));
  const double su = m_gain * m_gradientU / width, sv = m_gain * m_gradientV / height;
  const unsigned int valid = camera.frame + 1;
  const bool flat = m_gradientU == 0.0 && m_gradientV == 0.0;
  const double lit = m_offset + m_gain * m_background; // the lit background: one look-up per pixel when flat
  for (int i = 0; i < height; ++i) {
    const double rowGain = m_gain + sv * (i - 0.5 * height) - su * 0.5 * width;
    const unsigned int *stamp = camera.stamp[i];
    const double *blurred = h == 0 ? camera.ideal[i] : camera.blurred[i];
    unsigned char *out = I[i];
    for (int j = 0; j < width; ++j) {
      if (flat && stamp[j] != valid) {
        out[j] = m_imageNoise.flat(lit);
        continue;
      }
      const double g = stamp[j] == valid ? blurred[j] : m_background;
      out[j] = m_imageNoise.noisy(m_offset + (rowGain + su * j) * g);
    }
  }
  ++camera.frame; // the next frame's stamps are beyond this one's two
}
