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
  Linked into every test program (tests/CMakeLists.txt), not a test itself: what the library prints on its own is not
  printed unless the tests are asked to print (VISP_PROJECTIVE_TEST_VERBOSE, vpProjectiveTest::verboseTests()):
  - Ceres' own glog warnings (when glog comes as a CMake target). The library already runs Ceres with logging_type
    SILENT; what remains are Ceres' internal warnings such as "Linear solver failure. Failed to compute a step" when a
    Levenberg-Marquardt step fails and is retried with more damping (seen in the noisy calibration and robust rig
    estimation suites), which the tests assert the outcome of anyway;
  - the servo task's notices (vpProjectiveNotices: one line on stderr the first time a task stops or degrades): the
    suites provoke those statuses on purpose and assert them; testServoArmFollowing turns the notices on to test them.
*/

#ifdef VISP_PROJECTIVE_TEST_GLOG
#include <glog/logging.h>
#endif

#include <visp3/projective/vpProjectiveNotices.h>

#include "vpProjectiveTestTools.h"

namespace
{
//! Set once, before main(): glog's flags are defined (and read from GLOG_* variables) by the shared library first.
const bool kQuietLibrary = [] {
  if (!vpProjectiveTest::verboseTests()) {
#ifdef VISP_PROJECTIVE_TEST_GLOG
    FLAGS_minloglevel = google::GLOG_ERROR;
#endif
    vpProjectiveNotices::setEnabled(false);
  }
  return true;
}();
} // namespace
