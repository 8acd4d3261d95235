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
  The Monte-Carlo study of the acquisition's model check (ctest label "study"; the cheap version is
  testAcquisitionModelCheck), on the four arms of vpModelCheckTestTools.h at 0.1, 0.3, 0.5 and 1 px, seeded:
  - the gate refuses no right acquisition: kRightCases per arm and noise with the declared types;
  - the joint types are identified from the joint count alone: kTypeCases per arm and noise;
  - a declared type of the other kind (joint k mod n in case k) is named as the likeliest cause: kTypeCases per arm
    and noise. Prismatic joints moved by 4-5 cm are the hard case: a rotation by 0.04-0.05 rad about an axis 1 m away
    moves the markers almost as the slide does.
  VISP_PROJECTIVE_TEST_VERBOSE=1 prints the table (docs/model_check.dox gives it).
*/

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include <visp3/projective/vpProjectiveModelCheck.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "vpModelCheckTestTools.h"

using namespace vpProjectiveTest;

namespace
{
const double kNoise[] = {0.1, 0.3, 0.5, 1.0};
const unsigned int kRightCases = 25; // per arm and noise: 100 per arm
const unsigned int kTypeCases = 6;   // per arm and noise: 24 per arm, each way, every joint once per noise level

struct Tally {
  unsigned int cases = 0, passed = 0;
  double worstRatio = 0.0;                                         // residual / limit of the right models
  double smallestMargin = std::numeric_limits<double>::infinity(); // evidence of the identified types
  unsigned int identified = 0;
  // A wrong declared type, [0]: a slide declared revolute, [1]: a revolute joint declared prismatic.
  unsigned int named[2] = {0, 0}, wrongCases[2] = {0, 0};
  double wrongResidual[2] = {0.0, 0.0}, rightResidual[2] = {0.0, 0.0}; // the wrong joint's trials: RMS, summed
};
} // namespace

TEST(AcquisitionModelCheckStudy, GateAndJointTypesOnFourArms)
{
  unsigned int refusedRight = 0, rightTotal = 0;
  for (const ArmCase &arm : kCheckArms) {
    const ArmSetup s = arm.make();
    for (unsigned int level = 0; level < 4; ++level) {
      const double sigma = kNoise[level];
      Tally t;
      for (unsigned int c = 0; c < kRightCases; ++c) {
        const long seed = static_cast<long>(1000 + 97 * c);
        vpProjectiveRobot robot(s.jointTypes());
        ASSERT_TRUE(acquireWithMistakes(s, robot, sigma, seed)) << arm.label;
        ++t.cases;
        try {
          robot.calibrate();
          ++t.passed;
          const vpProjectiveModelCheck &check = robot.getAcquisition().getModelCheck();
          t.worstRatio = std::max(t.worstRatio, check.getResidual() / check.getLimit());
        } catch (const vpProjectiveException &e) {
          ADD_FAILURE() << arm.label << " at " << sigma << " px, seed " << seed
                        << ": a right model refused: " << e.getStringMessage();
        }
      }
      for (unsigned int c = 0; c < kTypeCases; ++c) {
        const long seed = static_cast<long>(5000 + 89 * c);
        // From the joint count alone.
        vpProjectiveRobot unknown(s.n());
        ASSERT_TRUE(acquireWithMistakes(s, unknown, sigma, seed)) << arm.label;
        try {
          unknown.calibrate();
          bool right = true;
          for (unsigned int i = 0; i < s.n(); ++i) {
            right = right && unknown.getJointType(i) == s.jointTypes()[i];
            const double evidence = unknown.getAcquisition().getModelCheck().getJoints()[i].evidence;
            t.smallestMargin = std::isnan(evidence) ? t.smallestMargin : std::min(t.smallestMargin, evidence);
          }
          t.identified += right ? 1 : 0;
        } catch (const vpProjectiveException &) {
        }
        // One joint declared of the other type.
        const unsigned int wrong = (c + level) % s.n();
        const int kind = s.jointTypes()[wrong] == vpProjectiveRobot::PRISMATIC ? 0 : 1;
        vpProjectiveRobot declared(withOtherType(s, wrong));
        ASSERT_TRUE(acquireWithMistakes(s, declared, sigma, seed)) << arm.label;
        ++t.wrongCases[kind];
        try {
          declared.calibrate();
        } catch (const vpProjectiveException &) {
          const vpProjectiveModelCheck &check = declared.getAcquisition().getModelCheck();
          const bool first = !check.getCauses().empty() &&
                             check.getCauses().front().cause == vpProjectiveModelCheck::CAUSE_JOINT_TYPE &&
                             check.getCauses().front().joint == static_cast<int>(wrong);
          t.named[kind] += first ? 1 : 0;
        }
        const vpProjectiveModelCheck::vpJointTypeFit &j = declared.getAcquisition().getModelCheck().getJoints()[wrong];
        const bool declaredRevolute = j.type == vpProjectiveJoint::REVOLUTE;
        t.wrongResidual[kind] += declaredRevolute ? j.residualRevolute : j.residualPrismatic;
        t.rightResidual[kind] += declaredRevolute ? j.residualPrismatic : j.residualRevolute;
      }
      refusedRight += t.cases - t.passed;
      rightTotal += t.cases;
      testLog() << "[ measured ] " << arm.label << " at " << sigma << " px: right models passed " << t.passed << "/"
                << t.cases << " (worst residual / limit " << t.worstRatio << "); types identified from the joint count "
                << t.identified << "/" << kTypeCases << " (smallest margin " << t.smallestMargin << " sigma^2)";
      const char *kinds[2] = {"a slide declared revolute", "a revolute joint declared prismatic"};
      for (int kind = 0; kind < 2; ++kind) {
        if (t.wrongCases[kind] > 0) {
          testLog() << "; " << kinds[kind] << " named first " << t.named[kind] << "/" << t.wrongCases[kind]
                    << " (its trials: " << t.wrongResidual[kind] / t.wrongCases[kind] << " px as declared, "
                    << t.rightResidual[kind] / t.wrongCases[kind] << " px with the right type, mean)";
        }
      }
      testLog() << std::endl;
      // Identification and naming at every level (measured: no miss; the 1 px margin of the R-R-P-R-R-R slide, 28
      // sigma^2 at the smallest, is near the 16 sigma^2 of a contradiction: one miss per level is allowed).
      EXPECT_GE(t.identified, kTypeCases - 1) << arm.label << " at " << sigma << " px";
      EXPECT_GE(t.named[0] + t.named[1], t.wrongCases[0] + t.wrongCases[1] - 1)
          << arm.label << " at " << sigma << " px";
    }
  }
  testLog() << "[ measured ] right models refused: " << refusedRight << " of " << rightTotal << std::endl;
  EXPECT_EQ(refusedRight, 0u);
}
