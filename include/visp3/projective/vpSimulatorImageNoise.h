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

/*!
  \file vpSimulatorImageNoise.h
  \brief Seeded Gaussian sensor noise of the simulated cameras, at a nanosecond per pixel.
*/

#ifndef _vpSimulatorImageNoise_h_
#define _vpSimulatorImageNoise_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <cstdint>
#include <vector>

BEGIN_VISP_NAMESPACE

/*!
  \class vpSimulatorImageNoise
  \ingroup group_projective_simulator
  \brief Independent Gaussian grey-level noise for every pixel of a rendered image, seeded, shared by
  vpSimulatorMarkerRenderer and vpSimulatorTagRenderer.

  65536 draws of a seeded vpGaussRand of standard deviation \f$ \sigma \f$ are tabulated once; each pixel then takes
  the entry at a pseudo-random 16-bit index (xorshift64*, Vigna 2016, seeded through splitmix64: another stream than
  the table's; four indices per 64-bit draw). The pixels' noise is thus Gaussian with the table's variance, and the
  same seed gives the same images. A grey level is quantised to 8 bits after the noise is added (noisy()); a flat
  region uses a table of the quantised noisy level (flat()), rebuilt only when the level changes.
*/
class VISP_EXPORT vpSimulatorImageNoise
{
public:
  //! Noise of standard deviation \e sigma grey levels (>= 0; 0: none) from \e seed.
  explicit vpSimulatorImageNoise(double sigma = 0.0, long seed = 0);

  //! Restarts the noise from a new table of standard deviation \e sigma (>= 0, grey levels) and \e seed.
  void reset(double sigma, long seed);
  //! Standard deviation of the noise (grey levels).
  double getSigma() const { return m_sigma; }

  //! The 8-bit grey level of \e level plus the next pixel's noise, clamped to [0, 255] and rounded.
  unsigned char noisy(double level) { return quantise(level + m_table[nextIndex()]); }
  //! The same as noisy(\e level) for a flat region of grey level \e level, by one look-up.
  unsigned char flat(double level)
  {
    if (m_flatTable.empty() || m_flatLevel != level) {
      buildFlatTable(level);
    }
    return m_flatTable[nextIndex()];
  }
  //! Clamps \e g to [0, 255] and rounds it to the nearest 8-bit grey level.
  static unsigned char quantise(double g)
  {
    return static_cast<unsigned char>((g < 0.0 ? 0.0 : (g > 255.0 ? 255.0 : g)) + 0.5);
  }

private:
  unsigned int nextIndex()
  {
    if (m_left == 0) {
      m_state ^= m_state >> 12;
      m_state ^= m_state << 25;
      m_state ^= m_state >> 27;
      m_bits = m_state * 0x2545F4914F6CDD1DULL;
      m_left = 4;
    }
    --m_left;
    const unsigned int index = static_cast<unsigned int>(m_bits & 0xFFFFu);
    m_bits >>= 16;
    return index;
  }
  void buildFlatTable(double level);

  double m_sigma;
  std::vector<double> m_table;
  std::vector<unsigned char> m_flatTable;
  double m_flatLevel;
  uint64_t m_state, m_bits;
  unsigned int m_left;
};

END_VISP_NAMESPACE

#endif
