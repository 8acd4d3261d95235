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
  \file visp-projective-servo.h
  \brief `visp-projective servo`: a real cell end to end (vpProjectiveCell): two cameras and an arm, or the rendered
  cell behind the same adapter.
*/

#ifndef _visp_projective_servo_h_
#define _visp_projective_servo_h_

namespace vispProjective
{
/*!
  Runs `visp-projective servo` on argv[2..argc-1]; returns the exit status: 0 converged, 1 an error (the arm
  stopped; one line on stderr), 2 a usage mistake, 4 the servo ended without converging (timeout, tags lost, a
  status to stop on; the arm stopped).
*/
int servoCommand(int argc, char **argv);
} // namespace vispProjective

#endif
