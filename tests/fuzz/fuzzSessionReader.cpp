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
 * libFuzzer target on the session reader vpProjectiveSession::fromString(), the parser of session.json behind
 * vpProjectiveSession::read() (tests/fuzz/run-fuzz.sh builds and runs it; seeds from makeSeedCorpus).
 *
 * The input is the text of a session.json. Any vpException is an expected outcome (the reader refused it, with a
 * message that must be one line); a crash, a sanitizer report, any other exception escaping the reader, or a
 * property broken by a session that reads is a finding: its accessors agree with each other, every trial moves the
 * joint it names, and its text (toString()) reads back to the same text.
 */
#include <cstdint>
#include <cstdlib>
#include <string>

#include <visp3/core/vpException.h>
#include <visp3/projective/vpProjectiveSession.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *data, size_t size)
{
  const std::string text(reinterpret_cast<const char *>(data), size);
  vpProjectiveSession session;
  try {
    session = vpProjectiveSession::fromString(text, "fuzz input");
  } catch (const vpException &e) {
    if (e.getStringMessage().find('\n') != std::string::npos) {
      std::abort(); // every refusal is one line
    }
    return 0;
  }
  const unsigned int n = session.getNumberOfJoints();
  const unsigned int zero = session.getZeroFrame();
  unsigned int zeros = 0;
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    const vpProjectiveSession::vpFrame &frame = session.getFrame(k);
    if (frame.q.getRows() != n) {
      std::abort();
    }
    zeros += frame.role == vpProjectiveSession::ZERO ? 1 : 0;
    const int joint = session.getTrialJoint(k);
    if ((frame.role == vpProjectiveSession::TRIAL) != (joint >= 0)) {
      std::abort();
    }
    if (joint >= 0 &&
        !(frame.q[static_cast<unsigned int>(joint)] != session.getFrame(zero).q[static_cast<unsigned int>(joint)])) {
      std::abort();
    }
  }
  if (zeros != 1 || session.getFrame(zero).role != vpProjectiveSession::ZERO) {
    std::abort();
  }
  const std::string again = session.toString();
  if (vpProjectiveSession::fromString(again, "fuzz round trip").toString() != again) {
    std::abort();
  }
  return 0;
}
