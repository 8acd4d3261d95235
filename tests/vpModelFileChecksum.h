/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

/*
  The model file's checksum, re-implemented independently of src/vpProjectiveRobot.cpp so that tests and the fuzzer
  can forge files that pass it: FNV-1a 64 of the body, written as "checksum <hex>" on the last line.
*/

#ifndef _vpModelFileChecksum_h_
#define _vpModelFileChecksum_h_

#include <string>

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
} // namespace vpProjectiveTest

#endif
