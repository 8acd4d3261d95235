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
  Helpers of the mistakes study (testUserMistakes; header only, not a test itself): a mistaken acquisition refused with
  its cause, a servo task run by a user program with a mistake (vpServoArmFollowingTestTools.h's loop) and what it
  showed, and the row of page_mistakes' table each case prints when the tests are verbose.
*/

#ifndef _vpUserMistakesTestTools_h_
#define _vpUserMistakesTestTools_h_

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveModelCheck.h>
#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoArmFollowing.h>

#include "vpModelCheckTestTools.h"
#include "vpProjectiveAcquisitionProcedureTestTools.h"
#include "vpProjectiveSessionTestTools.h"
#include "vpServoArmFollowingTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
//! The three arms of the study.
const ArmCase kMistakeArms[] = {{"PUMA", pumaEyeToHand}, {"Viper850", viperEyeToHand}, {"RRPRRR", rrprrrEyeToHand}};
const double kPeriod = 0.05;                                              // s per servo call
const unsigned int kCallsIn3s = static_cast<unsigned int>(3.0 / kPeriod); // 60

//! One row of the table of page_mistakes, printed only when the tests are verbose.
inline void row(const std::string &mistake, const std::string &arm, const std::string &outcome,
                const std::string &message)
{
  const std::string line = message.substr(0, message.find('\n'));
  testLog() << "| " << mistake << " | " << arm << " | " << outcome << " | "
            << (line.size() > 150 ? line.substr(0, 150) + "..." : line) << " |" << std::endl;
}

/*
  An acquisition with a mistake (acquireWithMistakes()'s hooks) refused by calibrate(): modelRejectedError, the
  likeliest cause \e cause, its finding holding \e words; the row printed.
*/
inline void expectRefused(const char *mistake, const ArmCase &arm,
                          const std::vector<vpProjectiveRobot::vpJointType> &types,
                          vpProjectiveModelCheck::vpCause cause, const std::string &words,
                          const std::function<void(unsigned int, UserTrial &)> &before,
                          const std::function<void(unsigned int, UserTrial &)> &after = nullptr)
{
  const ArmSetup s = arm.make();
  vpProjectiveRobot robot(types);
  ASSERT_TRUE(acquireWithMistakes(s, robot, 0.3, 7, before, after)) << arm.label;
  std::string message;
  EXPECT_EQ(codeOf([&]() { robot.calibrate(); }, message), vpProjectiveException::modelRejectedError)
      << mistake << ", " << arm.label << ": " << message;
  EXPECT_FALSE(robot.isCalibrated());
  const std::vector<vpProjectiveModelCheck::vpDiagnosis> &causes = robot.getAcquisition().getModelCheck().getCauses();
  ASSERT_FALSE(causes.empty()) << mistake << ", " << arm.label;
  EXPECT_EQ(causes.front().cause, cause) << mistake << ", " << arm.label << ": " << message;
  EXPECT_NE(causes.front().finding.find(words), std::string::npos) << causes.front().finding;
  row(mistake, arm.label, "refused (modelRejectedError)", causes.front().finding);
}

//! What a run of vpProjectiveAcquisitionProcedure showed.
struct ProcedureRun {
  vpProjectiveRobot model;
  int code = -1;        //!< the vpProjectiveException's code (-1: none)
  std::string message;  //!< its message
  std::string progress; //!< the progress lines
  std::vector<vpProjectiveAcquisitionProcedure::vpJointReport> reports;
};

/*
  The procedure run as a user runs it on the arm of setup \e s (the library's simulated robot, readings of the model's
  joints), the rig's true F given, its image source the setup's images at 0.3 px drawn from \e seed passed through
  \e view (the user's camera program: it may swap them, or say that a marker is lost by returning false).
*/
inline ProcedureRun runProcedure(const ArmSetup &s, long seed,
                                 const std::function<bool(const vpColVector &qArm, std::vector<vpImagePoint> &left,
                                                          std::vector<vpImagePoint> &right)> &view)
{
  vpArmRobot robot(s.arm, s.qRef);
  robot.setEncoderOffset(-1.0 * s.qRef); // readings of the model's joints, zero at the zero reference
  vpGaussRand noise(1.0, 0.0, seed);
  vpProjectiveAcquisitionProcedure procedure(
      [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        const vpColVector qArm = robot.q();
        return s.images(qArm, left, right, 0.3, noise, 0.0) && view(qArm, left, right);
      },
      s.width, s.height);
  std::ostringstream progress;
  procedure.setOutput(&progress);
  ProcedureRun r{vpProjectiveRobot(s.jointTypes())};
  r.model.setStereoRig(s.rig());
  r.code = codeOf([&]() { procedure.run(robot, r.model); }, r.message);
  r.progress = progress.str();
  r.reports = procedure.getReports();
  return r;
}

/*
  A task's start and target in view, each joint within 10 deg (3 cm for a slide) of a centre that keeps it out of the
  task's joint-limit avoidance band (the outer 10 % of the arm's range at each end): the zero reference where it is
  inside, else 20 % of the range from the nearer limit (the R-R-P-R-R-R arm's slide, whose zero reference is 5 cm
  below its upper limit: a target there is one the task does not reach, whatever the mistake).
*/
inline void drawTask(const ArmSetup &s, vpUniRand &rng, vpColVector &qStart, vpColVector &qTarget)
{
  const vpColVector qmin = s.arm.getJointMin() - s.qRef, qmax = s.arm.getJointMax() - s.qRef;
  std::vector<double> centre(s.n()), range(s.n());
  for (unsigned int i = 0; i < s.n(); ++i) {
    const double band = 0.2 * (qmax[i] - qmin[i]);
    centre[i] = std::min(std::max(0.0, qmin[i] + band), qmax[i] - band);
    range[i] = s.jointTypes()[i] == vpProjectiveRobot::REVOLUTE ? vpMath::rad(10.0) : 0.03;
  }
  for (int attempt = 0; attempt < 10000; ++attempt) {
    qTarget.resize(s.n());
    qStart.resize(s.n());
    for (unsigned int i = 0; i < s.n(); ++i) {
      qTarget[i] = centre[i] + rng.uniform(-range[i], range[i]);
      qStart[i] = centre[i] + rng.uniform(-range[i], range[i]);
    }
    if (s.visible(s.armJoints(qTarget), 20.0) && s.visible(s.armJoints(qStart), 20.0)) {
      return;
    }
  }
  ADD_FAILURE() << s.name << ": no task in view";
}

//! The arm-following cause's enumerator name.
inline const char *causeName(vpServoArmFollowing::vpFollowingCause cause)
{
  static const char *const names[] = {"ARM_FOLLOWING", "ARM_NOT_MOVING", "ARM_SLOWER", "ARM_JOINTS_LAGGING",
                                      "ARM_OTHER_DIRECTION"};
  return names[cause];
}

//! What a servo run with a mistake showed: the loop's result and the task's line on std::cerr.
struct ServoOutcome {
  LoopResult r;
  std::string err;
  int stoppedAt() const { return r.notFollowingAt >= 0 ? r.notFollowingAt : r.mismatchAt; }
};

/*
  A task of the setup from a start to a target drawn from \e seed, with the model \e model and the user's program
  \e settings (its read/send hooks, a fault from \e faultAt): the notices on, as a drop-in program has them.
*/
inline ServoOutcome servoWithMistake(const ArmSetup &s, const vpProjectiveRobot &model, const LoopSettings &settings,
                                     long seed, ArmFault fault = NO_FAULT, unsigned int faultAt = 0,
                                     const ArmSetup *moved = nullptr)
{
  vpUniRand rng(seed);
  vpColVector qStart, qTarget;
  drawTask(s, rng, qStart, qTarget);
  const NoticesSetting on(true);
  vpProjectiveNotices::reset();
  ServoOutcome o;
  {
    CapturedStreams streams;
    o.r = runLoop(s, model, {0, 1, 2}, qStart, qTarget, settings, seed, 300, fault, faultAt, moved, 3, 0.5);
    o.err = streams.err.str();
  }
  return o;
}

/*
  The servo-time outcome: stopped within 3 s of its first faulty call on one of \e statuses, qdot = 0 from then on,
  and the task's line on std::cerr holding \e words (what a program that never reads the status shows its user).
*/
inline void expectStopped(const char *mistake, const char *arm, const ServoOutcome &o, unsigned int faultAt,
                          const std::vector<std::string> &statuses, const std::string &words)
{
  EXPECT_GE(o.stoppedAt(), static_cast<int>(faultAt)) << mistake << ", " << arm << ": final " << o.r.finalRms << " px";
  EXPECT_LE(o.stoppedAt(), static_cast<int>(faultAt + kCallsIn3s)) << mistake << ", " << arm;
  EXPECT_TRUE(o.r.qdotZeroAfter) << mistake << ", " << arm;
  const std::string prefix = "Warning: vpServoProjective: ";
  const size_t line = o.err.find(prefix);
  ASSERT_NE(line, std::string::npos) << mistake << ", " << arm << ": no line on std::cerr";
  const std::string said = o.err.substr(line + prefix.size(), o.err.find('\n', line) - line - prefix.size());
  const std::string status = said.substr(0, said.find(' '));
  EXPECT_NE(std::find(statuses.begin(), statuses.end(), status), statuses.end())
      << mistake << ", " << arm << ": " << said;
  EXPECT_NE(said.find(words), std::string::npos) << mistake << ", " << arm << ": " << said;
  const double seconds = (o.stoppedAt() - static_cast<int>(faultAt) + 1) * kPeriod;
  const std::string cause = o.r.notFollowingAt >= 0 ? std::string(" (") + causeName(o.r.cause) + ")" : "";
  const size_t detail = said.find("): ");
  row(mistake, arm, status + cause + " after " + std::to_string(seconds).substr(0, 4) + " s, qdot = 0",
      detail == std::string::npos ? said : said.substr(detail + 3));
}

//! The servo task of the ordinary user program (period given, noise 0.5 px).
inline LoopSettings userLoop()
{
  LoopSettings user;
  user.period = kPeriod;
  return user;
}

/*!
  The user's program on one arm of kMistakeArms: the arm's setup, the model its acquisition gave (0.3 px of image
  noise, seed 2), and its servo loop, userLoop() until a test puts its mistake in (loop.read, loop.send, ...).
*/
struct UserProgram {
  explicit UserProgram(const ArmCase &arm) : s(arm.make()), model(calibratedRobot(s, 0.3, 2)), loop(userLoop()) {}
  //! A task drawn from \e seed, run by this program (servoWithMistake()).
  ServoOutcome servo(long seed, ArmFault fault = NO_FAULT, unsigned int faultAt = 0,
                     const ArmSetup *moved = nullptr) const
  {
    return servoWithMistake(s, model, loop, seed, fault, faultAt, moved);
  }

  const ArmSetup s;
  const vpProjectiveRobot model;
  LoopSettings loop;
};
} // namespace vpProjectiveTest

#endif
