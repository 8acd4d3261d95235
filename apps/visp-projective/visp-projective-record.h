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
  \file visp-projective-record.h
  \brief `visp-projective record`: the acquisition session of the rendered tag cell, recorded as a real cell's would be.
*/

#ifndef _visp_projective_record_h_
#define _visp_projective_record_h_

#include <ostream>
#include <string>

namespace vispProjective
{
/*!
  Records in \e folder the acquisition of the rendered cell (vpSimulatorStereoCell: the paper's PUMA-like arm and rig,
  the three tool tags of addToolTags(), image noise \e noise grey levels and blur \e blur px): the frames that
  vpProjectiveAcquisitionProcedure takes while it moves the arm by velocity, as vpProjectiveSessionCalibration::
  markerSource() records them, then \e observations frames at random configurations within 15 deg of the zero
  reference (seeded by \e seed) with every tag corner in view. Progress on \e os. Returns the number of frames.
  \exception vpException if the folder exists or cannot be written, or the acquisition fails.
*/
unsigned int recordRenderedCell(const std::string &folder, double noise, double blur, unsigned int observations,
                                long seed, std::ostream &os);
} // namespace vispProjective

#endif
