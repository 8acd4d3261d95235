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
  Private: what the sources of vpProjectiveCell share. Not installed.
*/

#ifndef _vpProjectiveCellInternal_h_
#define _vpProjectiveCellInternal_h_

#include <exception>

#include <visp3/projective/vpProjectiveCellRobot.h>

#include "core/vpProjectiveErrors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveCellInternal
{
//! Where vpProjectiveCell's errors come from.
const vpProjectiveInternal::vpErrorSite at("vpProjectiveCell");
} // namespace vpProjectiveCellInternal

/*!
  Stops the arm when a public call of vpProjectiveCell ends, whatever the way: returned, or left by an exception
  (then the robot is halted: a program that failed does not move the arm again).
*/
class vpStopGuard
{
public:
  explicit vpStopGuard(vpProjectiveCellRobot &robot) : m_robot(robot), m_exceptions(std::uncaught_exceptions()) {}
  ~vpStopGuard()
  {
    if (std::uncaught_exceptions() > m_exceptions) {
      m_robot.halt("an error ended the program's step");
    } else {
      m_robot.stop();
    }
  }

private:
  vpStopGuard(const vpStopGuard &) = delete;
  vpStopGuard &operator=(const vpStopGuard &) = delete;
  vpProjectiveCellRobot &m_robot;
  int m_exceptions;
};

#endif
