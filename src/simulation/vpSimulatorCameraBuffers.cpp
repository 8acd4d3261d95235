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

#include <visp3/projective/vpSimulatorCameraBuffers.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

vpSimulatorCameraBuffers::vpSimulatorCameraBuffers(const vpSimulatorStereoRig &rig, bool right, double background)
    : cam(right ? rig.getRightCameraParameters() : rig.getLeftCameraParameters()),
      cMw(right ? rig.get_rMl() * rig.get_wMl().inverse() : rig.get_wMl().inverse()),
      ideal(rig.getHeight(), rig.getWidth()), horizontal(rig.getHeight(), rig.getWidth()),
      blurred(rig.getHeight(), rig.getWidth()), stamp(rig.getHeight(), rig.getWidth())
{
  reset(background);
}

void vpSimulatorCameraBuffers::reset(double background)
{
  ideal = background;
  horizontal = background;
  blurred = background;
  stamp = 0;
  frame = 0;
}
