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
  \file visp-projective-cell.h
  \brief What visp-projective report says about the fingerprint of a model's cell: its cameras, which was left.
*/

#ifndef _visp_projective_cell_h_
#define _visp_projective_cell_h_

#include <ostream>

#include <visp3/projective/vpProjectiveCellFingerprint.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
/*!
  Prints the fingerprint \e cell of a model's cell on \e os: one line with the image size, the cameras (which took the
  left images), their layout and the side of the right camera; a model file without one says so.
*/
void printCell(const vpProjectiveCellFingerprint &cell, std::ostream &os);
} // namespace vispProjective

#endif
