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
  \file study-tags.h
  \brief The study on rendered AprilTags (--tags): the world's arm in a vpSimulatorStereoCell with the three tags of
  vpSimulatorStereoCell::addToolTags(), acquired by vpProjectiveAcquisitionProcedure from the detected corners
  (vpStereoAprilTagDetector), then random tasks servoed on the middle tag's 4 corners as
  tutorial-projective-servo-apriltag.cpp does: s* taught from 16 frames at the target, a 25 Hz velocity loop
  (setControlPeriod()), path planning and settling, detection in the regions of the last corners.
*/

#ifndef _study_tags_h_
#define _study_tags_h_

#include <ostream>
#include <string>

#include "study-world.h"

namespace study
{
//! Settings of the tag study.
struct TagStudySettings {
  unsigned int tasks = 100;    // tasks drawn (start and target with the servo tag 20 px inside both images)
  unsigned int seed = 1;       // task k uses seed + k; the images' noise uses seed
  double tagSize = 0.03;       // black-square side (m)
  double noise = 1.0;          // image noise (grey levels)
  double blur = 0.0;           // optical blur (px)
  bool lighting = false;       // a lighting change (darker, less contrast, a gradient) at call 50 of each task
  double period = 0.04;        // the loop's period (s): a 25 Hz camera
  unsigned int maxCalls = 400; // 16 s of the arm
  double successPx = 0.5;      // success: the final RMS image error of the 4 corners to s* below this
  std::string output = ".";    // where tag-study-<world>.csv goes
};

/*!
  Runs the tag study on \e world (its arm, rig, trials and task box) and prints its summary on \e os; returns the
  percentage of tasks that reached their target.
*/
double runTagStudy(const World &world, const TagStudySettings &settings, std::ostream &os);
} // namespace study

#endif
