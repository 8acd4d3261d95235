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
  Private: what the sources of vpProjectivePathPlanner share (vpProjectivePathPlanner.cpp, its settings and its
  paths). Not installed.
*/

#ifndef _vpProjectivePathPlannerInternal_h_
#define _vpProjectivePathPlannerInternal_h_

#include "core/vpProjectiveErrors.h"

namespace vpProjectiveInternal
{
//! The error site of vpProjectivePathPlanner.
const vpErrorSite plannerAt("vpProjectivePathPlanner");
} // namespace vpProjectiveInternal

#endif
