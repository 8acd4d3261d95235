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
  \file vpStereoDotTrackerState.cpp
  \brief vpStereoDotTracker: what it tracks (markers, states, failures, points, areas) and its display.
*/

#include <visp3/projective/vpStereoDotTracker.h>

#include <sstream>

#include <visp3/core/vpDisplay.h>

#include <visp3/projective/vpProjectiveException.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#include "tracking/vpStereoDotTrackerInternal.h"

using namespace vpStereoDotTrackerInternal;

std::vector<unsigned int> vpStereoDotTracker::getMarkerIndices() const
{
  std::vector<unsigned int> indices;
  for (const Marker &m : m_markers) {
    indices.push_back(m.index);
  }
  return indices;
}

vpStereoDotTracker::vpMarkerState vpStereoDotTracker::getState(unsigned int k) const
{
  checkMarker(k, "getState");
  return m_markers[k].state;
}

std::string vpStereoDotTracker::getFailure(unsigned int k) const
{
  checkMarker(k, "getFailure");
  return m_markers[k].failure;
}

std::string vpStereoDotTracker::getReport() const
{
  std::ostringstream os;
  for (const Marker &m : m_markers) {
    if (m.state == MARKER_LOST) {
      os << (os.str().empty() ? "" : "\n") << "marker " << m.index << ": " << m.failure;
    }
  }
  return os.str();
}

bool vpStereoDotTracker::isTracked() const
{
  for (const Marker &m : m_markers) {
    if (m.state == MARKER_LOST) {
      return false;
    }
  }
  return !m_markers.empty();
}

vpImagePoint vpStereoDotTracker::getLeftPoint(unsigned int k) const
{
  checkMarker(k, "getLeftPoint");
  return m_markers[k].blob[0].cog;
}

vpImagePoint vpStereoDotTracker::getRightPoint(unsigned int k) const
{
  checkMarker(k, "getRightPoint");
  return m_markers[k].blob[1].cog;
}

std::vector<vpImagePoint> vpStereoDotTracker::getLeftPoints() const
{
  std::vector<vpImagePoint> points;
  for (const Marker &m : m_markers) {
    points.push_back(m.blob[0].cog);
  }
  return points;
}

std::vector<vpImagePoint> vpStereoDotTracker::getRightPoints() const
{
  std::vector<vpImagePoint> points;
  for (const Marker &m : m_markers) {
    points.push_back(m.blob[1].cog);
  }
  return points;
}

double vpStereoDotTracker::getArea(unsigned int k, unsigned int camera) const
{
  checkMarker(k, "getArea");
  if (camera > 1) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                "vpStereoDotTracker::getArea(): camera 0 is the left one, 1 the right one.");
  }
  return m_markers[k].blob[camera].area;
}

void vpStereoDotTracker::display(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                                 const vpColor &color) const
{
  for (const Marker &m : m_markers) {
    for (unsigned int c = 0; c < 2; ++c) {
      const vpImage<unsigned char> &I = c == 0 ? Ileft : Iright;
      if (m.blob[c].found) {
        m.blob[c].dot.display(I, color);
      } else {
        vpDisplay::displayCross(I, m.blob[c].cog, 12, vpColor::red, 2);
      }
    }
  }
}
