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
 * libFuzzer target on the model loader vpProjectiveRobot::loadModel() (tests/fuzz/run-fuzz.sh builds and runs it).
 *
 * loadModel() reads a file path, so every input is written to a fixed temporary file (/tmp/fuzzModelLoader-<pid>.yml)
 * and loaded from there. The first input byte selects the mode and is not part of the file:
 *  - odd  (the seeds use 'c'): the rest is a model body; the harness appends a valid checksum line to it (the same
 *    FNV-1a 64-bit hash as saveModel(), written as "checksum <hex>\n" after the body), so that the mutations reach
 *    the parser behind the checksum;
 *  - even (the seeds use 'r'): the rest is written as is (checksum validation, truncation, raw garbage).
 * Any vpException is an expected outcome (the loader rejected the file); a crash, a sanitizer report, or any other
 * exception escaping loadModel() is a finding. A model that loads is used once (forward kinematics, a generator).
 * The temporary file is removed after each input.
 */
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>

#include <unistd.h>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include "../vpModelFileChecksum.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
using vpProjectiveTest::fnv1a;

const std::string &modelPath()
{
  static const std::string path = "/tmp/fuzzModelLoader-" + std::to_string(static_cast<long>(getpid())) + ".yml";
  return path;
}

// Removes the temporary model file when an input is done (libFuzzer may end the process without running destructors
// of static objects).
struct RemoveModelFile {
  ~RemoveModelFile() { std::remove(modelPath().c_str()); }
};
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  if (size == 0) {
    return 0;
  }
  std::string text(reinterpret_cast<const char *>(data + 1), size - 1);
  if (data[0] & 1) {
    if (!text.empty() && text.back() != '\n') {
      text += '\n'; // loadModel() wants the checksum line at the start of a line
    }
    std::ostringstream checksum;
    checksum << "checksum " << std::hex << fnv1a(text) << '\n';
    text += checksum.str();
  }
  const RemoveModelFile removeModelFile;
  {
    std::ofstream file(modelPath().c_str(), std::ios::binary | std::ios::trunc);
    file.write(text.data(), static_cast<std::streamsize>(text.size()));
    if (!file) {
      std::fprintf(stderr, "fuzzModelLoader: cannot write %s\n", modelPath().c_str());
      std::abort();
    }
  }
  vpProjectiveRobot robot;
  try {
    robot.loadModel(modelPath());
  } catch (const vpException &) {
    return 0; // rejected: the expected outcome for almost every input
  }
  // A model that loads must be usable: forward kinematics at two configurations and one generator.
  try {
    const unsigned int n = robot.getNumberOfJoints();
    vpMatrix H = robot.getDisplacement(vpColVector(n, 0.0));
    H = robot.getDisplacement(vpColVector(n, 0.1));
    H = robot.getGenerator(n - 1);
    (void)H;
  } catch (const vpException &) {
  }
  return 0;
}
