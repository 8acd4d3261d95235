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
  The command-line tool visp-projective run as a user runs it (its path given by CMake): --help on every command,
  usage mistakes, report on a model calibrated from a recorded session, check without a detector. Skipped when the
  apps are not built. Malformed sessions: testProjectiveToolBadInput.
*/

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "vpProjectiveToolTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

TEST_F(ProjectiveTool, EveryCommandHasHelpAndUsageMistakesExitWithStatus2)
{
  TemporaryFolder tmp;
  for (const std::string command : {"calibrate", "check", "report"}) {
    for (const std::string help : {command == "report" ? "-h" : "--help"}) {
      const ToolRun run = runTool(tmp, command + " " + help);
      EXPECT_EQ(run.status, 0) << command;
      EXPECT_EQ(run.out.find("Usage: visp-projective " + command), 0u) << run.out;
      EXPECT_TRUE(run.err.empty()) << run.err;
    }
  }
  EXPECT_EQ(runTool(tmp, "--help").status, 0);
  for (const std::string arguments : {"", "frobnicate", "calibrate session", "check model.json"}) {
    const ToolRun run = runTool(tmp, arguments);
    EXPECT_EQ(run.status, 2) << "'" << arguments << "': " << run.err;
    EXPECT_LE(lines(run.err), 1u) << run.err;
  }
  const ToolRun run = runTool(tmp, "calibrate s --output=m --bogus");
  EXPECT_EQ(run.err, "visp-projective calibrate: unknown option '--bogus'; see 'visp-projective calibrate --help'\n");
}

TEST_F(ProjectiveTool, ReportAndCheckOfAModelCalibratedFromASession)
{
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(rrprrrEyeToHand(), tmp / "session", *rec, 0.1, 1, 0));
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  calibration.calibrate(vpProjectiveSession::read(tmp / "session"));
  calibration.saveModel(tmp / "model.json");

  const ToolRun report = runTool(tmp, "report '" + (tmp / "model.json") + "'");
  EXPECT_EQ(report.status, 0) << report.err;
  EXPECT_TRUE(report.err.empty()) << report.err;
  for (const std::string needle : {"6 joints, eye-to-hand, 7 markers", "joint 2 (prismatic)", "joint 5 (revolute)",
                                   "residuals: bundle adjustment", "metric self-calibration", "left K:", "right K:",
                                   "baseline", "prismatic joints' unit", "+-", "largest uncertainty"}) {
    EXPECT_NE(report.out.find(needle), std::string::npos) << needle << " not in:\n" << report.out;
  }
  // check needs the markers of the session's images: these have no tags, refused clearly (the frame named).
  const ToolRun check = runTool(tmp, "check '" + (tmp / "model.json") + "' '" + (tmp / "session") + "'");
  EXPECT_EQ(check.status, 1);
  EXPECT_EQ(lines(check.err), 1u) << check.err;
  EXPECT_NE(check.err.find("no marker found in both images"), std::string::npos) << check.err;
  // A model file that is not one.
  writeText(tmp / "broken.json", "{\"format\": \"visp_projective_robot_model\"");
  const ToolRun broken = runTool(tmp, "report '" + (tmp / "broken.json") + "'");
  EXPECT_EQ(broken.status, 1);
  EXPECT_EQ(lines(broken.err), 1u) << broken.err;
  EXPECT_NE(broken.err.find("broken.json"), std::string::npos) << broken.err;
}
