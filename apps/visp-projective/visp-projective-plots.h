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
  \file visp-projective-plots.h
  \brief `visp-projective report --plots DIR`: the paths the model predicts for its markers when each joint moves
  alone, drawn as PNG images.
*/

#ifndef _visp_projective_plots_h_
#define _visp_projective_plots_h_

#include <string>
#include <vector>

#include <visp3/projective/vpProjectiveArmModel.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
/*!
  Writes \e folder/joint-paths-left.png and \e folder/joint-paths-right.png (640 x 480): for each joint alone moved
  from the zero reference by -\e range to +\e range (degrees for a revolute joint, \e travel metres for a prismatic
  one), the image path of every marker that the model predicts, one colour per joint, the zero reference's images as
  black crosses; the view is the bounding box of the paths. Returns the files written.
  \exception vpException (ioError) if a file cannot be written.
*/
std::vector<std::string> writeJointPathPlots(const vpProjectiveArmModel &model, double range, double travel,
                                             const std::string &folder);
} // namespace vispProjective

#endif
