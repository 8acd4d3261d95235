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

#include <visp3/projective/vpProjectiveModelCheck.h>

#include <limits>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

vpProjectiveModelCheck::vpProjectiveModelCheck()
    : m_checked(false), m_accepted(false), m_residual(0.0), m_noise(0.0), m_epipolarNoise(0.0), m_givenNoise(0.0),
      m_limit(std::numeric_limits<double>::infinity()), m_joints(), m_causes(),
      m_message("no model checked yet: calibrate() checks the model it computes")
{
}

std::string vpProjectiveModelCheck::toString(vpCause cause)
{
  switch (cause) {
  case CAUSE_JOINT_TYPE:
    return "joint types";
  case CAUSE_SECOND_JOINT:
    return "a second joint moved";
  case CAUSE_READING_UNITS:
    return "readings in other units";
  case CAUSE_MARKERS_SWAPPED:
    return "markers swapped";
  case CAUSE_MOUNTING:
    return "the rig's mounting";
  case CAUSE_IMAGES_EXCHANGED:
    return "left and right images exchanged";
  default:
    return "image errors";
  }
}
