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
  Private: the servo task's notices (vpProjectiveNotices) for programs that never read its status. Not installed.
*/

#ifndef _vpServoProjectiveNotices_h_
#define _vpServoProjectiveNotices_h_

#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpServoModelMismatch.h>
#include <visp3/projective/vpServoProjectiveReport.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  After each computeControlLaw(): the first time in the process that a call ends in a status other than
  SERVO_RUNNING (the task stopped, degraded or left the user's plan), one line on std::cerr names the status, what
  it means and the fix (vpServoProjectiveReport::toString()), with the arm-following check's diagnosis, the planner's
  description or the model-mismatch check's finding of exchanged images when they say more. Nothing is built
  otherwise.
*/
void noticeServoStatus(const vpServoProjectiveReport &report, const vpProjectivePathPlanner &planner,
                       const vpServoModelMismatch &mismatch);
} // namespace vpProjectiveInternal

#endif
