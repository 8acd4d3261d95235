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

#include <visp3/projective/vpSimulatorImageNoise.h>

#include <cmath>
#include <sstream>

#include <visp3/core/vpGaussRand.h>

#include "core/vpProjectiveErrors.h"

namespace
{
const unsigned int kTableSize = 65536; // the 16-bit indices of nextIndex()
}

vpSimulatorImageNoise::vpSimulatorImageNoise(double sigma, long seed)
    : m_sigma(0.0), m_table(), m_flatTable(), m_flatLevel(0.0), m_state(1), m_bits(0), m_left(0)
{
  reset(sigma, seed);
}

void vpSimulatorImageNoise::reset(double sigma, long seed)
{
  if (!std::isfinite(sigma) || sigma < 0.0) {
    std::ostringstream os;
    os << "the noise's standard deviation " << sigma << " must be finite and >= 0 (grey levels; 0: no noise)";
    vpProjectiveInternal::fail(vpProjectiveException::invalidValueError, "vpSimulatorImageNoise::reset()", os.str());
  }
  m_sigma = sigma;
  vpGaussRand gauss(sigma, 0.0, seed);
  m_table.resize(kTableSize);
  for (unsigned int k = 0; k < kTableSize; ++k) {
    m_table[k] = sigma > 0.0 ? gauss() : 0.0;
  }
  m_flatTable.clear();
  uint64_t z = static_cast<uint64_t>(seed) + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  m_state = (z ^ (z >> 31)) | 1u;
  m_bits = 0;
  m_left = 0;
}

void vpSimulatorImageNoise::buildFlatTable(double level)
{
  m_flatTable.resize(kTableSize);
  for (unsigned int k = 0; k < kTableSize; ++k) {
    m_flatTable[k] = quantise(level + m_table[k]);
  }
  m_flatLevel = level;
}
