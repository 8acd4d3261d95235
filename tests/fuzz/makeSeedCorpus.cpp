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
 * re-signed by the harness ('c' + file), plus truncated, corrupted and edited variants.
 *   makeSeedCorpus <corpus directory>
 */
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "../vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

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
} // namespace

int main(int argc, char **argv)
{
  if (argc != 2) {
    std::cerr << "usage: " << argv[0] << " <corpus directory>" << std::endl;
    return 2;
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
  }
  std::cout << "seed corpus written to " << dir << std::endl;
  return 0;
}
