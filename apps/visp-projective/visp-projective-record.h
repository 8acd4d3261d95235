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

#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpStereoImageSource.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

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

/*!
  Records in \e folder, from the live (or any) stereo source \e images, one frame per line of \e joints: the
  encoder readings of a real cell, typed in or written by the robot's controller, as the arm stands still. A line is
  the readings (numbers separated by spaces or commas, radians and metres, one per joint of \e types), optionally
  preceded by a role ("zero", "trial", "observation", "target", "servo"); \e types empty: one revolute joint per
  reading of the first frame line. Without a role, the readings tell it
  (vpProjectiveSessionWriter::addAcquisitionFrame(): the first frame is the zero reference, then trials of one
  joint, else observations). Blank lines and lines starting with '#' are skipped. For each frame line a stereo pair
  is taken from \e images after the line was read (after \e discard pairs are dropped: a live V4L2 camera queues a
  few images, taken while the arm was still moving), and recorded with the readings; a line per frame on \e os.
  session.json is complete after each frame when \e joints is interactive (save interval of one frame), and at
  the end otherwise. Returns the number of frames.
  \exception vpException if a line is malformed (naming its number and what to write), its readings are refused by
  the writer (wrong count, a trial of two joints...), the source has no more images, or the folder exists.
*/
unsigned int recordFromReadings(const std::string &folder, vpStereoImageSource &images,
                                const std::vector<vpProjectiveJoint::vpJointType> &types, std::istream &joints,
                                unsigned int discard, bool interactive, std::ostream &os);

/*!
  The joint kinds of \e text, one letter per joint base to tip: 'r' revolute, 'p' prismatic (e.g. "rrprrr").
  \exception vpException on another letter or an empty text.
*/
std::vector<vpProjectiveJoint::vpJointType> jointTypesOf(const std::string &text);
} // namespace vispProjective

#endif
