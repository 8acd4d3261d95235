/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

/*
  The model file's checksum, re-implemented independently of src/robot/vpProjectiveModelFile.cpp so that tests and the
  fuzzer can forge files that pass it: FNV-1a 64 of the "model" member written compactly, as "fnv1a64:" and 16
  hexadecimal digits in the "checksum" member.
*/

#ifndef _vpModelFileChecksum_h_
#define _vpModelFileChecksum_h_

#include <cstdio>
#include <string>

#include <nlohmann/json.hpp>

namespace vpProjectiveTest
{
inline unsigned long long fnv1a(const std::string &text)
{
  unsigned long long h = 14695981039346656037ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  return h;
}

//! \e file with its "checksum" member recomputed from its "model" member (which must exist), as JSON text.
inline std::string resigned(nlohmann::json file)
{
  char digits[17];
  std::snprintf(digits, sizeof(digits), "%016llx", fnv1a(file["model"].dump()));
  file["checksum"] = std::string("fnv1a64:") + digits;
  return file.dump(2) + "\n";
}
} // namespace vpProjectiveTest

#endif
