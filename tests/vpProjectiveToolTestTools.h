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
  Helpers of the suites of the command-line tool (header only): run visp-projective (its path given by CMake as
  VISP_PROJECTIVE_TOOL) with its output captured, and the suites' fixture (these suites are built with the tool only).
*/

#ifndef _vpProjectiveToolTestTools_h_
#define _vpProjectiveToolTestTools_h_

#include <sys/wait.h>

#include <cstdlib>
#include <filesystem>
#include <functional>
#include <string>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "vpProjectiveSessionTestTools.h"

namespace vpProjectiveTest
{
struct ToolRun {
  int status;
  std::string out, err;
};

//! Runs visp-projective with \e arguments (already quoted), in \e tmp for its output files.
inline ToolRun runTool(const TemporaryFolder &tmp, const std::string &arguments)
{
  ToolRun run;
  const std::string command = std::string("'") + VISP_PROJECTIVE_TOOL + "' " + arguments + " > '" + (tmp / "out.txt") +
                              "' 2> '" + (tmp / "err.txt") + "'";
  const int raw = std::system(command.c_str());
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = readText(tmp / "out.txt");
  run.err = readText(tmp / "err.txt");
  return run;
}

inline size_t lines(const std::string &text)
{
  size_t n = 0;
  for (char c : text) {
    n += c == '\n' ? 1 : 0;
  }
  return n;
}

//! A recorded Viper850 acquisition session in \e folder (13 frames).
inline void recordViperSession(const std::string &folder)
{
  Recording rec;
  ASSERT_TRUE(recordCalibrationSession(viperEyeToHand(), folder, rec, 0.1, 1, 0));
}

inline void expectBadInput(const TemporaryFolder &tmp, const std::string &folder, const std::string &needle,
                           const std::string &what)
{
  const std::string model = tmp / "model.json";
  const ToolRun run = runTool(tmp, "calibrate '" + folder + "' --output '" + model + "'");
  EXPECT_EQ(run.status, 1) << what << ": " << run.err;
  EXPECT_EQ(lines(run.err), 1u) << what << ": " << run.err;
  EXPECT_EQ(run.err.find("visp-projective calibrate: "), 0u) << what << ": " << run.err;
  EXPECT_NE(run.err.find(needle), std::string::npos) << what << ": '" << needle << "' not in " << run.err;
  EXPECT_FALSE(std::filesystem::exists(model)) << what;
  for (const auto &entry : std::filesystem::directory_iterator(tmp.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << what << ": " << entry.path();
  }
}

inline std::string edited(const TemporaryFolder &tmp, const std::string &name,
                          const std::function<void(nlohmann::json &)> &edit)
{
  const std::string folder = tmp / name;
  recordViperSession(folder);
  nlohmann::json file = nlohmann::json::parse(readText(folder + "/session.json"));
  edit(file);
  writeText(folder + "/session.json", file.dump(1));
  return folder;
}

//! The suites of the command-line tool (built only with it: tests/CMakeLists.txt gives its path).
class ProjectiveTool : public ::testing::Test
{
};

} // namespace vpProjectiveTest

#endif
