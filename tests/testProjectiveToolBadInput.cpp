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
  The command-line tool on malformed sessions (issue 21.4): each refused by visp-projective calibrate with exit status
  1, one line on stderr naming the file or frame, and no model file (nor a temporary one) left. Skipped when the apps
  are not built. The library's reader is tested on more cases in testProjectiveSession.
*/

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "vpProjectiveToolTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

TEST_F(ProjectiveTool, MalformedSessionsExitWithStatus1OneLineAndNoModelFile)
{
  TemporaryFolder tmp;
  expectBadInput(tmp, tmp / "missing", "missing/session.json", "missing session");
  {
    const std::string folder = tmp / "truncated";
    recordViperSession(folder);
    const std::string text = readText(folder + "/session.json");
    writeText(folder + "/session.json", text.substr(0, text.size() / 3));
    expectBadInput(tmp, folder, "not valid JSON", "truncated session.json");
  }
  expectBadInput(tmp, edited(tmp, "version", [](json &f) { f["version"] = 7; }), "version 7", "wrong version");
  expectBadInput(tmp, edited(tmp, "length", [](json &f) { f["frames"][3]["q"].erase(0); }), "frame 4/13",
                 "readings of the wrong length");
  expectBadInput(tmp, edited(tmp, "nan", [](json &f) { f["frames"][3]["q"][0] = "nan"; }), "not a finite number",
                 "a non-finite reading");
  expectBadInput(tmp, edited(tmp, "two", [](json &f) { f["frames"][5]["q"][0] = 0.5; }), "moves joints",
                 "a trial of two joints");
  expectBadInput(tmp, edited(tmp, "nozero", [](json &f) { f["frames"][0]["role"] = "target"; }), "no zero frame",
                 "no zero frame");
  expectBadInput(tmp, edited(tmp, "zeros", [](json &f) { f["frames"][6]["role"] = "zero"; }), "second zero frame",
                 "two zero frames");
  {
    const std::string folder = edited(tmp, "image", [](json &) {});
    std::filesystem::remove(folder + "/left/000007.png");
    expectBadInput(tmp, folder, "left/000007.png", "a missing image");
    writeText(folder + "/left/000007.png", "garbage garbage garbage garbage garbage garbage");
    expectBadInput(tmp, folder, "not a PNG", "an unreadable image");
  }
  // A valid session whose images have no tag: refused clearly (the frame named), nothing written.
  recordViperSession(tmp / "valid");
  expectBadInput(tmp, tmp / "valid", "no marker found in both images", "a frame with no tag");
  // An output path that cannot be written: refused before any work.
  const ToolRun run =
      runTool(tmp, "calibrate '" + (tmp / "valid") + "' --output '" + (tmp / "no/such/folder.json") + "'");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(lines(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find("cannot write the model file"), std::string::npos) << run.err;
}
