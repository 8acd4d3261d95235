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
  Private: what the session's reader, writer and tools share. Not installed.
*/

#ifndef _vpProjectiveSessionInternal_h_
#define _vpProjectiveSessionInternal_h_

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/projective/vpProjectiveSession.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveSessionInternal
{
/*!
  Checks that \e path is an 8-bit grey or RGB PNG by its header (signature, IHDR) and gives its size; returns what is
  wrong ("is missing or cannot be opened", ...), empty if nothing.
*/
std::string checkPngHeader(const std::string &path, unsigned int &width, unsigned int &height);

/*!
  The joint that readings \e q moved from the zero frame's \e q0 (same sizes), or -1 with \e why saying what is wrong:
  no joint moved, or another joint moved by more than 1 % of the largest motion.
*/
int trialJoint(const vpColVector &q0, const vpColVector &q, std::string &why);

/*!
  Appends the JSON text of \e frame (one line) to \e frames, the text of a session's frame list: what
  sessionText() puts between the brackets of "frames". Each frame is serialised once (the writer keeps the text).
*/
void appendFrame(std::string &frames, const vpProjectiveSession::vpFrame &frame);

/*!
  The text of a session.json with joints \e types and the frame list \e frames (appendFrame()'s): a JSON object, one
  line per frame.
*/
std::string sessionText(const std::vector<vpProjectiveJoint::vpJointType> &types, const std::string &frames);

/*!
  Writes \e text to \e path atomically: to a temporary file in the same folder, then renamed over \e path, so that
  \e path is either as before or complete. Throws vpProjectiveException (fileError) naming \e path, \e where.
*/
void writeAtomically(const std::string &path, const std::string &text, const std::string &where);
} // namespace vpProjectiveSessionInternal

#endif
