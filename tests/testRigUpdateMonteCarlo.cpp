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

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <ostream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "vpProjectiveSessionTestTools.h" // rrprrrEyeToHand()
#include "vpRigUpdateTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! A positive integer from the environment variable \e name, or \e fallback (the study's larger runs).
long fromEnvironment(const char *name, long fallback)
{
  const char *value = std::getenv(name);
  if (value == nullptr || *value == '\0') {
    return fallback;
  }
  const long v = std::strtol(value, nullptr, 10);
  return v > 0 ? v : fallback;
}
} // namespace

/*
  Monte-Carlo of 120 seeded bumps at 0.5 px (one camera or the whole rig, 1-3 deg and 0.5-2 cm): the figures of
  issue 12 with loose bounds, and issue 18's (point 5): after updateRig() from 3 observation poses the task refines the
  rig with its own frames (vpServoRigRefinement::setRefinement(), on by default) and reaches its original target as
  often as from 10 poses (the measured values are printed). VISP_PROJECTIVE_BUMP_CASES and VISP_PROJECTIVE_BUMP_SEED
  (first seed, default 1000) run other cases; VISP_PROJECTIVE_BUMP_WITHOUT=1 adds the runs from 3 poses without the
  refinement, for comparison.
*/
TEST(RigUpdate, MonteCarloOfBumps)
{
  const ArmSetup s = pumaEyeToHand();
  const int cases = static_cast<int>(fromEnvironment("VISP_PROJECTIVE_BUMP_CASES", 120));
  const long seed0 = fromEnvironment("VISP_PROJECTIVE_BUMP_SEED", 1000);
  const bool without = fromEnvironment("VISP_PROJECTIVE_BUMP_WITHOUT", 0) > 0;
  int detected = 0, falseAlarms = 0, reached3 = 0, reached10 = 0, reached3Alone = 0, userUnchanged = 0,
      unbumpedReached = 0, reached3OfThose = 0, refinements = 0, failedRefinements = 0;
  std::vector<double> ratio3, ratio10, ratio3General, deg3, mm3, deg10, mm10, unbumpedDeg, unbumpedMm;
  for (int k = 0; k < cases; ++k) {
    const BumpKind kind = static_cast<BumpKind>(k % 3);
    BumpOptions options;
    options.withoutRefinement = without;
    const BumpCase c = runBumpCase(s, seed0 + k, kind, options);
    detected += c.detectedAfter >= 1 && c.detectedAfter <= 2 ? 1 : 0;
    falseAlarms += c.falseAlarms;
    reached3 += c.from3.reached() ? 1 : 0;
    reached10 += c.from10.reached() ? 1 : 0;
    reached3Alone += without && c.from3Alone.reached() ? 1 : 0;
    const bool unbumped = c.unbumpedDeg <= 2.0 && c.unbumpedMetres <= 0.002;
    unbumpedReached += unbumped ? 1 : 0;
    reached3OfThose += unbumped && c.from3.reached() ? 1 : 0;
    userUnchanged += c.from3.userStarUnchanged && c.from10.userStarUnchanged ? 1 : 0;
    refinements += static_cast<int>(c.from3.refinements + c.from10.refinements);
    failedRefinements += static_cast<int>(c.from3.failedRefinements + c.from10.failedRefinements);
    ratio3.push_back(c.ratio3);
    ratio10.push_back(c.ratio10);
    ratio3General.push_back(c.ratio3General);
    deg3.push_back(c.from3.deg);
    mm3.push_back(1000.0 * c.from3.metres);
    deg10.push_back(c.from10.deg);
    mm10.push_back(1000.0 * c.from10.metres);
    unbumpedDeg.push_back(c.unbumpedDeg);
    unbumpedMm.push_back(1000.0 * c.unbumpedMetres);
    if (c.detectedAfter < 1 || c.detectedAfter > 2 || !c.from3.reached() || !c.from10.reached()) {
      testLog() << "[ measured ] case " << k << " seed " << seed0 + k << " (" << bumpName(kind) << "): detected after "
                << c.detectedAfter << ", final from 3 poses " << c.from3.deg << " deg " << 1000.0 * c.from3.metres
                << " mm (" << c.from3.refinements << " refinements, " << c.from3.failedRefinements
                << " failed), from 10 " << c.from10.deg << " deg " << 1000.0 * c.from10.metres << " mm (unbumped "
                << c.unbumpedDeg << " deg " << 1000.0 * c.unbumpedMetres << " mm), ratio from 3 " << c.ratio3
                << std::endl;
    }
  }
  const double n = static_cast<double>(cases);
  testLog() << "[ measured ] " << cases << " bumps at 0.5 px (seeds " << seed0 << "-" << seed0 + cases - 1
            << "): detected within 2 iterations " << detected / n << ", false alarms " << falseAlarms
            << " (unbumped runs at 0.5 and 1 px and before the bumps), median ratio of the re-registered prediction "
            << "error to the pre-bump one: " << median(ratio3) << " from 3 observations (90 % quantile "
            << quantile(ratio3, 0.9) << "), " << median(ratio10) << " from 10 (90 %: " << quantile(ratio10, 0.9)
            << "); plain 11-parameter resection from 3: " << median(ratio3General)
            << " (90 %: " << quantile(ratio3General, 0.9) << ")" << std::endl;
  testLog() << "[ measured ] task at its original target within 2 deg / 2 mm, refining the rig with its own frames: "
            << reached3 / n << " from 3 observation poses (median " << median(deg3) << " deg, " << median(mm3)
            << " mm; 90 %: " << quantile(deg3, 0.9) << " deg, " << quantile(mm3, 0.9) << " mm), " << reached10 / n
            << " from 10 (median " << median(deg10) << " deg, " << median(mm10) << " mm; 90 %: " << quantile(deg10, 0.9)
            << " deg, " << quantile(mm10, 0.9) << " mm)";
  if (without) {
    testLog() << ", from 3 without the refinement " << reached3Alone / n;
  }
  testLog() << "; " << refinements << " refinements, " << failedRefinements << " failed; unbumped runs: median "
            << median(unbumpedDeg) << " deg, " << median(unbumpedMm) << " mm, 90 %: " << quantile(unbumpedDeg, 0.9)
            << " deg, " << quantile(unbumpedMm, 0.9) << " mm; the unbumped task itself ends within 2 deg / 2 mm in "
            << unbumpedReached << " cases, of which the bumped one from 3 poses in " << reached3OfThose << std::endl;
  EXPECT_EQ(detected, cases); // every bump, within 2 calls (1000, 2000 and 5000 + 0-119; and the study on every arm)
  EXPECT_EQ(falseAlarms, 0);
  EXPECT_LE(median(ratio3), 2.0);
  EXPECT_LE(median(ratio10), 1.2);
  // Issue 18, point 5: from 3 observation poses, the task refining the rig itself, at its target about as often as from
  // 10, and in at least 89 % of the cases. The frames' points are the features' triangulations through the rig before
  // the bump, the frame of the re-expressed s* (vpServoModelMismatch::getTriangulatedMemory()), averaged with the
  // acquired marker's point for a feature recognised as one (issue 30). Measured over four sets of 120 seeds, from 3
  // and from 10 poses: 97.5 % and 95.0 % on these (1000-1119); 96.7 % and 97.5 % over 2000-2119; 90.8 % and 93.3 %
  // over 5000-5119; 98.3 % and 95.0 % over 7000-7119 (95.8 % and 95.2 % of all 480; the unbumped task 96.7 %, the
  // bumped one from 3 poses in 95.7 % of those). The bounds are below the worst set's, not this one's: from 3 within
  // 3.5 % of the cases of from 10 (5000-5119: 3 cases of 120), at least 89 % of the cases (5000-5119: 109), and 89 %
  // of those where the unbumped task, whose s* has its own noise, ends at the target (5000-5119: 107 of 118). What
  // keeps the rate below 100 % is the noise of s* and of the triangulations before the bump (docs/servo.dox,
  // servo_meas_mismatch).
  EXPECT_GE(reached3 + static_cast<int>(std::ceil(0.035 * n)), reached10);
  EXPECT_GE(reached3, static_cast<int>(std::ceil(0.89 * n)));
  EXPECT_GE(reached3OfThose, static_cast<int>(std::ceil(0.89 * unbumpedReached)));
  EXPECT_EQ(userUnchanged, cases);
}

namespace
{
//! An arm of the bump study on every arm (issue 30, point 5).
struct BumpArm {
  const char *label;
  ArmSetup (*make)();
};
const BumpArm kBumpArms[] = {{"PUMA", pumaEyeToHand}, {"Viper850", viperEyeToHand}, {"RRPRRR", rrprrrEyeToHand}};

//! The arm's label in gtest's messages, instead of the bytes of the struct.
void PrintTo(const BumpArm &arm, std::ostream *os)
{
  *os << arm.label;
}

class RigUpdateOnEveryArm : public ::testing::TestWithParam<BumpArm>
{
};
} // namespace

/*
  Issue 30, point 5: the bump study of MonteCarloOfBumps on each arm (the PUMA-like arm, ViSP's Viper850, the
  R-R-P-R-R-R arm), 120 seeded cases per arm (left camera, right camera, whole rig in turn), each task run unbumped and
  bumped, re-registered from 3 observation poses, the task refining the rig. Asserted: no false alarm, detection within
  2 calls of the bump in every case, and the bumped task at its original target in at least 90 % of the cases where
  the unbumped one is. Over seeds 30000, 40000, 90000, 70000, 50000 and 110000 (+0-119; docs/servo.dox,
  servo_meas_mismatch) every bump of every arm is detected within 2 calls since the detector tests the features
  together against the noise it learned (18 of the 2160 were missed when only the 5 px threshold decided: they moved
  the features by 1-5 px), and the worst set of an arm reached 94.96 % (113 of 119; the noise of the triangulations
  before the bump, which the refined rig inherits): the bound is below the worst set, not at this one. The median tool
  error printed is over the cases the unbumped task reaches, bumped and unbumped. VISP_PROJECTIVE_BUMP_CASES and
  VISP_PROJECTIVE_BUMP_SEED (first seed, default 30000) run other cases.
*/
TEST_P(RigUpdateOnEveryArm, BumpStudy)
{
  const ArmSetup s = GetParam().make();
  const int cases = static_cast<int>(fromEnvironment("VISP_PROJECTIVE_BUMP_CASES", 120));
  const long seed0 = fromEnvironment("VISP_PROJECTIVE_BUMP_SEED", 30000);
  BumpOptions options;
  options.ratios = false;
  options.from10 = false;
  int detected = 0, falseAlarms = 0, reached = 0, unbumpedReached = 0, reachedOfThose = 0;
  std::vector<int> latency(6, 0);           // cases detected after 1-4 calls; [0]: not in 4, [5]: unused
  std::vector<double> bumpedMm, unbumpedMm; // tool position error where the tasks rest (the cases the unbumped reaches)
  for (int k = 0; k < cases; ++k) {
    const BumpKind kind = static_cast<BumpKind>(k % 3);
    const BumpCase c = runBumpCase(s, seed0 + k, kind, options);
    const bool inTime = c.detectedAfter >= 1 && c.detectedAfter <= 2;
    detected += inTime ? 1 : 0;
    ++latency[static_cast<size_t>(std::max(0, c.detectedAfter))];
    falseAlarms += c.falseAlarms;
    const bool unbumped = c.unbumpedDeg <= 2.0 && c.unbumpedMetres <= 0.002;
    reached += c.from3.reached() ? 1 : 0;
    unbumpedReached += unbumped ? 1 : 0;
    reachedOfThose += unbumped && c.from3.reached() ? 1 : 0;
    if (unbumped) {
      bumpedMm.push_back(1000.0 * c.from3.metres);
      unbumpedMm.push_back(1000.0 * c.unbumpedMetres);
    }
    if (!inTime || c.falseAlarms > 0 || (unbumped && !c.from3.reached())) {
      testLog() << "[ measured ] " << GetParam().label << " seed " << seed0 + k << " (" << bumpName(kind)
                << "): detected after " << c.detectedAfter << ", false alarms " << c.falseAlarms << ", bumped "
                << c.from3.deg << " deg " << 1000.0 * c.from3.metres << " mm (" << c.from3.refinements
                << " refinements, " << c.from3.failedRefinements << " failed), unbumped " << c.unbumpedDeg << " deg "
                << 1000.0 * c.unbumpedMetres << " mm" << std::endl;
    }
  }
  testLog() << "[ measured ] " << GetParam().label << ", " << cases << " bumps (seeds " << seed0 << "-"
            << seed0 + cases - 1 << "): detected within 2 calls " << detected << " (after 1: " << latency[1]
            << ", 2: " << latency[2] << ", 3: " << latency[3] << ", 4: " << latency[4] << ", not in 4: " << latency[0]
            << "), false alarms " << falseAlarms << "; at the original target from 3 poses " << reached
            << ", the unbumped task " << unbumpedReached << ", the bumped one among those " << reachedOfThose << " ("
            << 100.0 * reachedOfThose / std::max(1, unbumpedReached) << " %); among those, the bumped task ends "
            << median(bumpedMm) << " mm from the target (median; 90 %: " << quantile(bumpedMm, 0.9)
            << "), the unbumped " << median(unbumpedMm) << " mm (90 %: " << quantile(unbumpedMm, 0.9) << ")"
            << std::endl;
  EXPECT_EQ(detected, cases);
  EXPECT_EQ(falseAlarms, 0);
  EXPECT_GE(reachedOfThose, static_cast<int>(std::ceil(0.90 * unbumpedReached)));
  EXPECT_GE(unbumpedReached, static_cast<int>(std::ceil(0.9 * cases))); // the tasks are ones the arm reaches
}

INSTANTIATE_TEST_SUITE_P(RigUpdate, RigUpdateOnEveryArm, ::testing::ValuesIn(kBumpArms),
                         [](const ::testing::TestParamInfo<BumpArm> &info) { return std::string(info.param.label); });
