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
  \file visp-projective-markers.h
  \brief The one place where visp-projective gets its marker extraction function (AprilTag corners in both images).
*/

#ifndef _visp_projective_markers_h_
#define _visp_projective_markers_h_

#include <string>

#include <visp3/projective/vpProjectiveSessionCalibration.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
/*!
  The marker extraction of the AprilTag family \e family (as the --family option spells it, e.g. "36h11"): each tag's
  4 corners found in both images by vpStereoAprilTagDetector, identifier 4 * tag id + corner index:
  vpProjectiveSessionCalibration::aprilTagMarkers().
*/
vpProjectiveSessionCalibration::vpMarkerExtractor markerExtractor(const std::string &family);
} // namespace vispProjective

#endif
