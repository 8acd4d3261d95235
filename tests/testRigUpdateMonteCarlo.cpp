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
  A seeded Monte-Carlo of bumps at 0.5 px (issue 12; helpers in vpRigUpdateTestTools.h) whose figures are printed as
  "[ measured ]" lines when VISP_PROJECTIVE_TEST_VERBOSE=1.
*/

#include <gtest/gtest.h>

#include "vpRigUpdateTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

/*
  Monte-Carlo of 120 seeded bumps at 0.5 px (one camera or the whole rig, 1-3 deg and 0.5-2 cm): the figures of
  issue 12 with loose bounds (the measured values are printed).
*/
TEST(RigUpdate, MonteCarloOfBumps)
{
  const ArmSetup s = pumaEyeToHand();
  const int cases = 120;
  int detected = 0, falseAlarms = 0, finished = 0, userUnchanged = 0, unbumpedFinishedCount = 0, finishedOfThose = 0;
  std::vector<double> ratio3, ratio10, ratio3General, finalDeg, finalMm, unbumpedDeg, unbumpedMm;
  for (int k = 0; k < cases; ++k) {
    const BumpKind kind = static_cast<BumpKind>(k % 3);
    const BumpCase c = runBumpCase(s, 1000 + k, kind);
    detected += c.detectedAfter >= 1 && c.detectedAfter <= 2 ? 1 : 0;
    falseAlarms += c.falseAlarms;
    finished += c.finalDeg <= 2.0 && c.finalMetres <= 0.002 ? 1 : 0;
    const bool unbumpedFinished = c.unbumpedDeg <= 2.0 && c.unbumpedMetres <= 0.002;
    unbumpedFinishedCount += unbumpedFinished ? 1 : 0;
    finishedOfThose += unbumpedFinished && c.finalDeg <= 2.0 && c.finalMetres <= 0.002 ? 1 : 0;
    userUnchanged += c.userStarUnchanged ? 1 : 0;
    ratio3.push_back(c.ratio3);
    ratio10.push_back(c.ratio10);
    ratio3General.push_back(c.ratio3General);
    finalDeg.push_back(c.finalDeg);
    finalMm.push_back(1000.0 * c.finalMetres);
    unbumpedDeg.push_back(c.unbumpedDeg);
    unbumpedMm.push_back(1000.0 * c.unbumpedMetres);
    if (c.detectedAfter < 1 || c.detectedAfter > 2 || c.finalDeg > 2.0 || c.finalMetres > 0.002) {
      testLog() << "[ measured ] case " << k << " (" << bumpName(kind) << "): detected after " << c.detectedAfter
                << ", final " << c.finalDeg << " deg " << 1000.0 * c.finalMetres << " mm (unbumped " << c.unbumpedDeg
                << " deg " << 1000.0 * c.unbumpedMetres << " mm), ratio from 3 " << c.ratio3 << std::endl;
    }
  }
  const double n = static_cast<double>(cases);
  testLog() << "[ measured ] " << cases << " bumps at 0.5 px: detected within 2 iterations " << detected / n
            << ", false alarms " << falseAlarms << " (unbumped runs at 0.5 and 1 px and before the bumps), median "
            << "ratio of the re-registered prediction error to the pre-bump one: " << median(ratio3)
            << " from 3 observations (90 % quantile " << quantile(ratio3, 0.9) << "), " << median(ratio10)
            << " from 10 (90 %: " << quantile(ratio10, 0.9)
            << "); plain 11-parameter resection from 3: " << median(ratio3General)
            << " (90 %: " << quantile(ratio3General, 0.9) << "); task at its target within "
            << "2 deg / 2 mm: " << finished / n << " (median " << median(finalDeg) << " deg, " << median(finalMm)
            << " mm; unbumped runs: median " << median(unbumpedDeg) << " deg, " << median(unbumpedMm)
            << " mm, 90 %: " << quantile(unbumpedDeg, 0.9) << " deg, " << quantile(unbumpedMm, 0.9)
            << " mm; the unbumped task itself ends within 2 deg / 2 mm in " << unbumpedFinishedCount
            << " cases, of which the bumped one in " << finishedOfThose << ")" << std::endl;
  EXPECT_GE(detected, static_cast<int>(0.95 * n));
  EXPECT_EQ(falseAlarms, 0);
  EXPECT_LE(median(ratio3), 2.0);
  EXPECT_LE(median(ratio10), 1.2);
  // The 95 %: the unbumped runs themselves rest up to 1.3 mm from the target (90 % quantile) at 0.5 px, and
  // the re-expressed target inherits the model's error at the target (see the printed figures).
  EXPECT_GE(finished, static_cast<int>(std::ceil(0.95 * n)));
  EXPECT_GE(finishedOfThose, static_cast<int>(std::ceil(0.95 * unbumpedFinishedCount)));
  EXPECT_EQ(userUnchanged, cases);
}
