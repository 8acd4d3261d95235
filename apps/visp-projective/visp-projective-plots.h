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
  alone, drawn by gnuplot over the zero frame's images when the model's session is given.
*/

#ifndef _visp_projective_plots_h_
#define _visp_projective_plots_h_

#include <ostream>
#include <string>
#include <vector>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
/*!
  Writes \e folder/joint-paths-left.png and \e folder/joint-paths-right.png through gnuplot (and, beside them, the
  data files and the script): for each joint alone moved from the zero reference, the image path of every marker
  (ids \e ids, the model's order) that the model predicts, one colour and one legend entry per joint, axes in pixels.
  With the model's \e session (not null): drawn over the zero frame's images, with the image border; solid within the
  range the session's trials acquired, dashed beyond (to 1.5 times that range, or \e range deg / \e travel m either
  way when these are > 0); and the markers measured in each trial frame (its recorded markers, else those of
  \e extractor) as circles beside the model's prediction at the frame's readings (crosses). Without a session: the
  paths to \e range deg (30 if 0) or \e travel m (0.05 if 0) either way, the view their bounding box. Returns the
  figures written.
  \exception vpException (ioError) if a file cannot be written or gnuplot fails (install gnuplot-nox: the data
  and the script are left in \e folder).
*/
std::vector<std::string> writeJointPathPlots(const vpProjectiveArmModel &model, const std::vector<int> &ids,
                                             double range, double travel, const std::string &folder,
                                             const vpProjectiveSession *session,
                                             const vpProjectiveSessionCalibration::vpMarkerExtractor &extractor);
} // namespace vispProjective

#endif
