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

#include "visp-projective-markers.h"

#include <visp3/core/vpException.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
vpProjectiveSessionCalibration::vpMarkerExtractor markerExtractor(const std::string &family)
{
  // The families of ViSP's vpDetectorAprilTag (TAG_36h11, ...), as --family spells them.
  const char *const families[] = {"36h11",      "36h10",       "25h9",        "25h7",          "16h5",
                                  "Circle21h7", "Circle49h12", "Custom48h12", "Standard41h12", "Standard52h13"};
  bool known = false;
  for (const char *name : families) {
    known = known || family == name;
  }
  if (!known) {
    throw vpException(vpException::badValue, "unknown AprilTag family '" + family +
                                                 "'; use 36h11, 36h10, 25h9, 25h7, 16h5, Circle21h7, Circle49h12, "
                                                 "Custom48h12, Standard41h12 or Standard52h13");
  }
  /*
    The AprilTag detector plugs in here once merged (vpStereoAprilTagDetector, DESIGN.md section 3):
      auto tags = std::make_shared<vpStereoAprilTagDetector>(vpDetectorAprilTag::TAG_36h11); // from family
      return [tags](const vpImage<unsigned char> &Il, const vpImage<unsigned char> &Ir, std::vector<int> &ids,
                    std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        const unsigned int n = tags->detect(Il, Ir);
        ids = tags->getIds();
        left = tags->getLeftPoints();
        right = tags->getRightPoints();
        return n;
      };
  */
  return vpProjectiveSessionCalibration::noDetector(family);
}
} // namespace vispProjective
