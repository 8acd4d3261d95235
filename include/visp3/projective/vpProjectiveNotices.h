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
  \file vpProjectiveNotices.h
  \brief One line on stderr the first time the plugin stops, degrades or changes a user's setting, for programs that
  never read a status.
*/

#ifndef _vpProjectiveNotices_h_
#define _vpProjectiveNotices_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveNotices
  \ingroup group_projective
  \brief The plugin's warnings for programs that never read a status: a program ported from ViSP runs its loop to the
  end whatever vpServoProjective::getStatus() says, so the first time a task stops (\f$ \dot q = 0 \f$), degrades or
  changes what the user set, one line on std::cerr names what happened and the fix, as ViSP's own warnings do:
  \verbatim
Warning: vpServoProjective: SERVO_ARM_NOT_FOLLOWING: ... (vpProjectiveNotices::setEnabled(false) silences these lines)
  \endverbatim

  <b>Once per kind and process.</b> Each kind of event (a small integer \e kind below 64: the servo task uses its
  vpServoProjectiveReport::vpServoStatus values, 0 to 15; 16 to 63 are free for the other parts of the plugin) is told
  once per process, however many calls or tasks meet it again: a study of 500 tasks prints a handful of lines, not
  one per task or call. reset() lets every kind be told again (a test that expects a line).

  <b>Silence.</b> setEnabled(false) silences every notice of the process (a program that reads the statuses itself,
  a test that provokes them). The state is global and thread-safe (atomics): tell() prints a line at most once per
  kind even when several threads meet it together. Nothing is allocated unless a line is printed.
*/
class VISP_EXPORT vpProjectiveNotices
{
public:
  //! Kinds are below this bound.
  static const unsigned int maxKinds = 64;

  //! On (default) or off for the whole process; off, nothing is printed and nothing is marked as told.
  static void setEnabled(bool enabled);
  //! True if notices are printed (setEnabled()).
  static bool isEnabled();
  //! Forgets which kinds were told: each may be told once more.
  static void reset();
  //! True if a line of \e kind would be printed now: notices on, \e kind below maxKinds and not told yet. What a caller
  //! checks before it builds the line (which allocates).
  static bool isPending(unsigned int kind);
  /*!
    Prints \e line on std::cerr, prefixed with "Warning: " and followed by the way to silence it, if \e kind is
    pending (isPending()), and marks \e kind as told. Returns true if it printed.
  */
  static bool tell(unsigned int kind, const std::string &line);
};

END_VISP_NAMESPACE

#endif
