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
 * Writes the seed corpus of fuzzModelLoader (tests/fuzz/run-fuzz.sh): model files saved by saveModel() from small
 * calibrated models (noise-free acquisitions of the test setups), each as a raw file ('r' + file) and as a file to be
 * re-signed by the harness ('c' + file), plus truncated, corrupted and edited variants; and, given a second directory,
 * that of fuzzSessionReader: session.json texts (the format's example, a 13-frame acquisition session, a servo
 * session) and malformed variants.
 *   makeSeedCorpus <model corpus directory> [<session corpus directory>]
 */
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

namespace
{
std::string readAll(const std::string &path)
{
  std::ifstream in(path.c_str(), std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

void writeSeed(const std::string &dir, const std::string &name, char mode, const std::string &content)
{
  std::ofstream out((dir + "/" + name).c_str(), std::ios::binary);
  out << mode << content;
  if (!out) {
    std::cerr << "cannot write " << dir << "/" << name << std::endl;
    std::exit(1);
  }
}
void writeText(const std::string &dir, const std::string &name, const std::string &content)
{
  std::ofstream out((dir + "/" + name).c_str(), std::ios::binary);
  out << content;
  if (!out) {
    std::cerr << "cannot write " << dir << "/" << name << std::endl;
    std::exit(1);
  }
}

//! A session.json of \e frames (role, q) for joints \e types.
nlohmann::json sessionJson(const std::vector<std::string> &types,
                           const std::vector<std::pair<std::string, std::vector<double>>> &frames)
{
  nlohmann::json file;
  file["format"] = "visp-projective-session";
  file["version"] = 1;
  file["joint_types"] = types;
  file["frames"] = nlohmann::json::array();
  for (size_t k = 0; k < frames.size(); ++k) {
    char name[32];
    std::snprintf(name, sizeof(name), "%06u.png", static_cast<unsigned int>(k));
    file["frames"].push_back({{"role", frames[k].first},
                              {"q", frames[k].second},
                              {"t", 0.5 * k},
                              {"left", std::string("left/") + name},
                              {"right", std::string("right/") + name}});
  }
  return file;
}

void writeSessionSeeds(const std::string &dir)
{
  const std::vector<std::string> rrprrr = {"revolute", "revolute", "prismatic", "revolute", "revolute", "revolute"};
  // The format's example (DESIGN.md).
  const nlohmann::json example =
      sessionJson(rrprrr, {{"zero", {0.1, -0.2, 0.05, 0, 0, 0}}, {"trial", {0.6, -0.2, 0.05, 0, 0, 0}}});
  writeText(dir, "example.json", example.dump(1));
  // An acquisition: zero, each joint both ways, two observations, a target, servo frames.
  std::vector<std::pair<std::string, std::vector<double>>> frames = {{"zero", {0.0, 1.05, 0.45, 0.0, -0.87, 0.0}}};
  for (size_t i = 0; i < 6; ++i) {
    for (int sign = -1; sign <= 1; sign += 2) {
      std::vector<double> q = frames[0].second;
      q[i] += sign * (i == 2 ? 0.04 : 0.3);
      frames.push_back({"trial", q});
    }
  }
  frames.push_back({"observation", {0.1, 1.0, 0.47, 0.2, -0.8, 0.1}});
  frames.push_back({"target", {0.2, 1.1, 0.44, 0.1, -0.9, 0.3}});
  frames.push_back({"servo", {0.15, 1.05, 0.45, 0.15, -0.85, 0.2}});
  const nlohmann::json acquisition = sessionJson(rrprrr, frames);
  const std::string text = acquisition.dump(1);
  writeText(dir, "acquisition.json", text);
  writeText(dir, "acquisition-compact.json", acquisition.dump());
  writeText(dir, "acquisition-truncated.json", text.substr(0, text.size() / 2));
  nlohmann::json edited = acquisition;
  edited["frames"][3]["q"][0] = 0.2;
  writeText(dir, "two-joints.json", edited.dump(1));
  edited = acquisition;
  edited["frames"][5]["role"] = "zero";
  writeText(dir, "two-zeros.json", edited.dump(1));
  edited = acquisition;
  edited["frames"][0]["role"] = "servo";
  writeText(dir, "no-zero.json", edited.dump(1));
  edited = acquisition;
  edited["frames"][2]["q"].erase(1);
  writeText(dir, "short-q.json", edited.dump(1));
  edited = acquisition;
  edited["frames"][2]["left"] = "../left/000002.png";
  writeText(dir, "outside.json", edited.dump(1));
  edited = acquisition;
  edited["version"] = 2;
  writeText(dir, "version2.json", edited.dump(1));
  edited = acquisition;
  edited["comment"] = {{"nested", {1, 2, 3}}};
  edited["frames"][1]["exposure"] = 8;
  writeText(dir, "unknown-keys.json", edited.dump(1));
}
} // namespace

int main(int argc, char **argv)
{
  if (argc != 2 && argc != 3) {
    std::cerr << "usage: " << argv[0] << " <model corpus directory> [<session corpus directory>]" << std::endl;
    return 2;
  }
  if (argc == 3) {
    writeSessionSeeds(argv[2]);
  }
  const std::string dir = argv[1];
  const std::vector<std::pair<std::string, ArmSetup>> setups = {{"puma", pumaEyeToHand()},
                                                                {"mixed-in-hand", mixedEyeInHand()}};
  for (const auto &named : setups) {
    const ArmSetup &s = named.second;
    vpProjectiveRobot robot(s.jointTypes());
    vpGaussRand noise(1.0, 0.0, 1);
    if (!s.acquire(robot, 0.0, noise)) {
      std::cerr << s.name << ": a marker left the view during the acquisition" << std::endl;
      return 1;
    }
    robot.calibrate();
    const std::string path = dir + "/.saved-" + named.first + ".json";
    robot.saveModel(path);
    const std::string file = readAll(path);
    std::remove(path.c_str());
    const nlohmann::json json = nlohmann::json::parse(file);
    const std::string p = named.first;
    writeSeed(dir, p + "-valid", 'r', file);
    writeSeed(dir, p + "-resigned", 'c', file);
    writeSeed(dir, p + "-truncated-half", 'r', file.substr(0, file.size() / 2));
    writeSeed(dir, p + "-resigned-truncated-half", 'c', file.substr(0, file.size() / 2));
    std::string flipped = file;
    flipped[flipped.size() / 3] ^= 0x10;
    writeSeed(dir, p + "-corrupted", 'r', flipped);
    nlohmann::json nan = json;
    nan["model"]["G"][0][0] = nullptr;
    writeSeed(dir, p + "-resigned-null", 'c', nan.dump(2));
    nlohmann::json version = json;
    version["version"] = 1;
    writeSeed(dir, p + "-resigned-version1", 'c', version.dump(2));
    nlohmann::json joints = json;
    joints["model"]["joints"].push_back("revolute");
    writeSeed(dir, p + "-resigned-extra-joint", 'c', joints.dump(2));
    nlohmann::json ids = json;
    ids["model"]["marker_ids"] = nlohmann::json::array();
    for (size_t j = 0; j < json["model"]["markers"].size(); ++j) {
      ids["model"]["marker_ids"].push_back(4 * j + 1);
    }
    writeSeed(dir, p + "-resigned-marker-ids", 'c', ids.dump(2));
    ids["model"]["marker_ids"][1] = 1;
    writeSeed(dir, p + "-resigned-marker-ids-repeated", 'c', ids.dump(2));
  }
  std::cout << "seed corpus written to " << dir << std::endl;
  return 0;
}
