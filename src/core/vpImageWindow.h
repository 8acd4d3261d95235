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
  Private: the one test of "this pixel is inside the image, a margin away from its border", shared by the acquisition,
  the planner, the feature health, the trackers and the simulators. Not installed.
*/

#ifndef _vpImageWindow_h_
#define _vpImageWindow_h_

#include <cmath>

#include <Eigen/Core>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpImagePoint.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  The pixels (u, v) with margin <= u <= width - 1 - margin and margin <= v <= height - 1 - margin (u the column, v the
  row, pixel centres at integers). A window of width 0 is unset: it contains every finite pixel (the callers whose
  image size is optional). A non-finite pixel is never inside.
*/
class vpImageWindow
{
public:
  vpImageWindow(double width, double height, double margin) : m_width(width), m_height(height), m_margin(margin) {}

  bool contains(double u, double v) const
  {
    if (!std::isfinite(u) || !std::isfinite(v)) {
      return false;
    }
    return m_width <= 0.0 ||
           (u >= m_margin && v >= m_margin && u <= m_width - 1.0 - m_margin && v <= m_height - 1.0 - m_margin);
  }
  bool contains(const vpImagePoint &p) const { return contains(p.get_u(), p.get_v()); }
  //! Both pixels of a stereo feature (u, v, u', v') inside the window (the same size for both cameras).
  bool containsStereo(const Eigen::Vector4d &s) const { return contains(s(0), s(1)) && contains(s(2), s(3)); }

private:
  double m_width, m_height, m_margin;
};
} // namespace vpProjectiveInternal

#endif
