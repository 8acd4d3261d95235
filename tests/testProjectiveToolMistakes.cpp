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
  The command-line tool on the mistakes of issue 30, point 6, as a new user makes them, on the Viper850 and the
  R-R-P-R-R-R arm: sessions recorded by the test tools with their markers (recorded_markers, so that the tool
  calibrates them with --recorded-markers, fast), the left and right images exchanged, a session of another cell, a
  session of markers that are not tags calibrated with the tag detector, a missing image. Each mistake ends with its
  exit status, the likeliest cause in the first words of the first line on stderr, and no model file; the right
  sessions calibrate and check with status 0.
*/

#include <filesystem>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "vpProjectiveToolTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
//! The first line of \e text.
std::string firstLine(const std::string &text)
{
  return text.substr(0, text.find('\n'));
}

//! Expects \e run to have ended with \e status, its first stderr line beginning with \e opening.
void expectNamed(const ToolRun &run, int status, const std::string &opening, const std::string &what)
{
  EXPECT_EQ(run.status, status) << what << ": " << run.out << run.err;
  EXPECT_EQ(firstLine(run.err).find(opening), 0u) << what << ": " << run.err;
}

//! True if \e folder holds no file whose name starts with ".tmp" (a model half-written).
bool noTemporaryFile(const std::string &folder)
{
  for (const auto &entry : std::filesystem::directory_iterator(folder)) {
    if (entry.path().filename().string().find(".tmp") == 0) {
      return false;
    }
  }
  return true;
}
} // namespace

TEST_F(ProjectiveTool, MistakesOfTheCellAreNamedFirstAndRightSessionsPass)
{
  for (const ArmSetup &s : {viperEyeToHand(), rrprrrEyeToHand()}) {
    TemporaryFolder tmp;
    auto rec = std::make_shared<Recording>();
    rec->recordMarkers = true;
    ASSERT_TRUE(recordCalibrationSession(s, tmp / "cell", *rec, 0.1, 1, 2));
    ASSERT_TRUE(recordCheckSession(s, tmp / "later", *rec, 0.1, 2, 6));
    ASSERT_TRUE(recordCalibrationSession(swappedCameras(s), tmp / "exchanged", *rec, 0.1, 3, 2));
    vpUniRand rng(11);
    const ArmSetup other = anotherCell(s, rng);
    ASSERT_FALSE(other.name.empty());
    ASSERT_TRUE(recordCheckSession(other, tmp / "other", *rec, 0.1, 4, 6));
    const std::string model = "'" + (tmp / "model.json") + "'";

    // The right session: calibrated and checked with status 0.
    const ToolRun calibrate = runTool(tmp, "calibrate '" + (tmp / "cell") + "' --recorded-markers --output " + model);
    ASSERT_EQ(calibrate.status, 0) << s.name << ": " << calibrate.err;
    EXPECT_NE(calibrate.out.find("cameras: the right camera is to the right of the left camera"), std::string::npos)
        << calibrate.out;
    const ToolRun later = runTool(tmp, "check " + model + " '" + (tmp / "later") + "' --recorded-markers");
    EXPECT_EQ(later.status, 0) << s.name << ": " << later.out << later.err;
    EXPECT_TRUE(later.err.empty()) << later.err;
    const ToolRun report = runTool(tmp, "report " + model);
    EXPECT_NE(report.out.find("the right camera to the right of the left camera"), std::string::npos) << report.out;

    // The left and right images exchanged: refused, no model written; with --camera-layout any, calibrated.
    const std::string refused = "'" + (tmp / "refused.json") + "'";
    expectNamed(runTool(tmp, "calibrate '" + (tmp / "exchanged") + "' --recorded-markers --output " + refused), 1,
                "visp-projective calibrate: vpProjectiveSessionCalibration::calibrate(): the left and right images "
                "are exchanged",
                s.name + ", exchanged images");
    EXPECT_FALSE(std::filesystem::exists(tmp / "refused.json"));
    EXPECT_TRUE(noTemporaryFile(tmp.path()));
    EXPECT_EQ(runTool(tmp, "calibrate '" + (tmp / "exchanged") + "' --recorded-markers --camera-layout any --output " +
                               refused)
                  .status,
              0);

    // check of the model against the exchanged session and against another cell's: status 3, the cause first.
    expectNamed(runTool(tmp, "check " + model + " '" + (tmp / "exchanged") + "' --recorded-markers"), 3,
                "visp-projective check: the left and right images are exchanged", s.name + ", check exchanged");
    expectNamed(runTool(tmp, "check " + model + " '" + (tmp / "other") + "' --recorded-markers"), 3,
                "visp-projective check: the session is of another cell", s.name + ", check another cell");

    // A session of markers that are not tags, calibrated with the tag detector: pointed at its recorded markers.
    const ToolRun tags = runTool(tmp, "calibrate '" + (tmp / "cell") + "' --output " + refused);
    expectNamed(tags, 1,
                "visp-projective calibrate: vpProjectiveSessionCalibration::calibrate(): frame 1/15 "
                "('left/000000.png', zero): no marker found in its images, but the frame carries the 7 markers",
                s.name + ", recorded markers");
    EXPECT_NE(tags.err.find("--recorded-markers"), std::string::npos) << tags.err;
    EXPECT_EQ(tags.err.find("exposure"), std::string::npos) << tags.err;

    // A missing image: named as the progress lines name it.
    EXPECT_NE(calibrate.out.find("frame 3/15 ('left/000002.png', trial"), std::string::npos) << calibrate.out;
    std::filesystem::remove(tmp / "cell/right/000002.png");
    const ToolRun missing = runTool(tmp, "calibrate '" + (tmp / "cell") + "' --recorded-markers --output " + refused);
    EXPECT_EQ(missing.status, 1);
    EXPECT_NE(missing.err.find("frame 3/15 ('left/000002.png')"), std::string::npos) << missing.err;
    EXPECT_EQ(lines(missing.err), 1u);
    EXPECT_TRUE(noTemporaryFile(tmp.path()));
  }
}
