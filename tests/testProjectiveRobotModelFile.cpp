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
  Tests of vpProjectiveRobot's model file (its round trip on the five setups: testProjectiveRobotModel): a missing,
  truncated, corrupted or other-version file throws.
*/

#include <algorithm>

#include <gtest/gtest.h>

#include "vpProjectiveRobotTestTools.h"

using namespace vpProjectiveTest;

TEST(ProjectiveRobot, ModelFileErrors)
{
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
  const std::string path = tempFile("errors_source");
  robot.saveModel(path);
  const std::string text = readFile(path);
  ASSERT_GT(text.size(), 100u);
  const nlohmann::json file = nlohmann::json::parse(text);
  const std::string bad = tempFile("errors_bad");
  const int code = vpProjectiveException::fileError;
  vpProjectiveRobot target = calibratedRobot(s);
  const Eigen::Matrix4d before = toEigen<4, 4>(target.getGenerator(0));

  // Missing file.
  std::remove(bad.c_str());
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "cannot open"));

  // Truncated: at the start, inside values, inside the markers, inside the checksum, before the last brace.
  const size_t checksumAt = text.rfind("\"checksum\"");
  ASSERT_NE(checksumAt, std::string::npos);
  std::vector<size_t> cuts = {0,
                              1,
                              10,
                              text.size() / 4,
                              text.size() / 2,
                              text.find("\"markers\"") + 1,
                              text.find("\"calibration_residual\"") + 5,
                              checksumAt,
                              checksumAt + 15,
                              text.size() - 2};
  for (size_t cut : cuts) {
    writeFile(bad, text.substr(0, cut));
    EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "truncated")) << "cut at " << cut;
  }

  // One byte changed (about 1200 positions spread over the file, every third one in a file without frames; every
  // byte of the checksum line but its final newline): the JSON syntax, an entry's check or the checksum catch it,
  // unless the change leaves every value as it was (a 17th significant digit that reads back to the same double):
  // then the model loaded is bit-identical to the one saved.
  int caught = 0, tried = 0, harmless = 0;
  const size_t checksumEnd = text.find('\n', checksumAt);
  const size_t step = std::max<size_t>(3, text.size() / 1200) | 1; // odd: every kind of character is hit
  for (size_t k = 0; k + 2 < text.size(); k += (k >= checksumAt && k < checksumEnd ? 1 : step)) {
    std::string edited = text;
    edited[k] = static_cast<char>(edited[k] ^ 0x01);
    writeFile(bad, edited);
    ++tried;
    if (throwsProjective([&] { target.loadModel(bad); }, code, "model file")) {
      ++caught;
      continue;
    }
    vpProjectiveRobot reloaded;
    reloaded.loadModel(bad);
    bool identical = reloaded.getModel().projectiveToMetric() == robot.getModel().projectiveToMetric();
    for (unsigned int i = 0; i < s.n(); ++i) {
      identical = identical && toEigen<4, 4>(reloaded.getGenerator(i)) == toEigen<4, 4>(robot.getGenerator(i));
    }
    for (size_t j = 0; j < robot.getModel().markers().size(); ++j) {
      identical = identical && reloaded.getModel().markers()[j] == robot.getModel().markers()[j];
    }
    if (identical) {
      ++harmless;
    } else {
      ADD_FAILURE() << "byte " << k << " ('" << text[k] << "') changed the model undetected";
    }
  }
  EXPECT_EQ(caught + harmless, tried);
  EXPECT_GT(caught, 9 * tried / 10);
  testLog() << "[ measured ] one byte changed: " << caught << " of " << tried << " caught, " << harmless
            << " left every value as it was" << std::endl;

  // A value edited without re-signing fails the checksum; another version is named.
  nlohmann::json edited = file;
  edited["model"]["G"][0][0] = edited["model"]["G"][0][0].get<double>() * 1.001;
  writeFile(bad, edited.dump(2));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "checksum"));
  nlohmann::json version = file;
  version["version"] = 4;
  writeFile(bad, version.dump(2));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "version 4"));

  // Re-signed but inconsistent content: another format, a non-finite value, a joint type, too few markers, a missing
  // entry, a singular G.
  nlohmann::json other = file;
  other["format"] = "some_other_model";
  writeFile(bad, resigned(other));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "visp_projective_robot_model"));
  nlohmann::json nonFinite = file;
  nonFinite["model"]["G"][0][0] = std::numeric_limits<double>::quiet_NaN(); // written as null
  writeFile(bad, resigned(nonFinite));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "non-finite"));
  nlohmann::json joints = file;
  joints["model"]["joints"][2] = "screw";
  writeFile(bad, resigned(joints));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "joint type"));
  nlohmann::json markers = file;
  markers["model"]["markers"].erase(3);
  markers["model"]["markers"].erase(3);
  markers["model"]["markers"].erase(3);
  writeFile(bad, resigned(markers));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "markers"));
  nlohmann::json missing = file;
  missing["model"].erase("twists");
  writeFile(bad, resigned(missing));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "twists"));
  nlohmann::json singular = file;
  singular["model"]["G"][1] = singular["model"]["G"][0];
  writeFile(bad, resigned(singular));
  EXPECT_TRUE(throwsProjective([&] { target.loadModel(bad); }, code, "singular"));
  // The re-signed original loads: the checksum recomputation above is the library's.
  writeFile(bad, resigned(file));
  EXPECT_NO_THROW(target.loadModel(bad));

  // A failed load leaves the robot as it was.
  writeFile(bad, text.substr(0, text.size() / 2));
  EXPECT_THROW(target.loadModel(bad), vpException);
  EXPECT_TRUE(target.isCalibrated());
  EXPECT_LT(relativeError(toEigen<4, 4>(target.getGenerator(0)), before), 1e-12);

  // Saving before calibration, or to an impossible path.
  vpProjectiveRobot empty(s.jointTypes());
  EXPECT_TRUE(
      throwsProjective([&] { empty.saveModel(bad); }, vpProjectiveException::notInitializedError, "not acquired"));
  EXPECT_TRUE(
      throwsProjective([&] { robot.saveModel("/nonexistent_dir_visp_projective/model.json"); }, code, "cannot open"));
  std::remove(path.c_str());
  std::remove(bad.c_str());
}
