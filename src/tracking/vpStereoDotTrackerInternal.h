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
  Private: what the two sources of vpStereoDotTracker share (initialisation and tracking). Not installed.
*/

#ifndef _vpStereoDotTrackerInternal_h_
#define _vpStereoDotTrackerInternal_h_

#include <algorithm>
#include <cmath>

namespace vpStereoDotTrackerInternal
{
//! The cameras' names, for the messages.
const char *const kImageName[2] = {"left", "right"};

//! Radius (px) of a disc of area \e area.
inline double radiusOf(double area)
{
  return std::sqrt(std::max(0.0, area) / M_PI);
}
} // namespace vpStereoDotTrackerInternal

#endif
