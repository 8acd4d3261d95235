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
  The recordings of the tutorial and of the main job (issue 21, point 5): each program run with --record into a
  temporary folder gives the same results as without, its session is calibrated and checked offline by
  visp-projective, and its figure is made again from the recording alone: the tutorial's last picture (both images
  with the tags, s*, the corners and their paths: vpStereoServoDisplay), pixel for pixel, and its final image error; the
  main job's trajectory and target CSV (the data of Fig. 2, 4 and 5), byte for byte. And `visp-projective record` from
  cameras and typed-in readings (recordFromReadings(), here on a replayed session as the cameras): one frame per line,
  the readings bit for bit, the roles given or told by the readings, malformed lines refused naming the line; a missing
  camera is refused before any folder is made.
*/

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/io/vpImageIo.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveSessionSource.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#include "visp-projective-record.h"
#include "vpProjectiveToolTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveTest;

namespace
{
//! Runs \e program with \e arguments (already quoted), its output in \e name.out / .err in \e tmp.
ToolRun runProgram(const TemporaryFolder &tmp, const std::string &program, const std::string &arguments,
                   const std::string &name)
{
  ToolRun run;
  const std::string out = tmp / (name + ".out"), err = tmp / (name + ".err");
  const int raw = std::system(("'" + program + "' " + arguments + " > '" + out + "' 2> '" + err + "'").c_str());
  run.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : -1;
  run.out = readText(out);
  run.err = readText(err);
  return run;
}

//! The line of \e text that starts with \e start (empty if none).
std::string lineStarting(const std::string &text, const std::string &start)
{
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.compare(0, start.size(), start) == 0) {
      return line;
    }
  }
  return std::string();
}
} // namespace

TEST(ProjectiveToolRecordings, TheTutorialsRecordingCalibratesChecksAndGivesItsFigureAgain)
{
#if defined(VISP_HAVE_APRILTAG)
  TemporaryFolder tmp;
  const ToolRun plain =
      runProgram(tmp, VISP_PROJECTIVE_TUTORIAL_APRILTAG, "-d --output '" + (tmp / "plain") + "'", "plain");
  ASSERT_EQ(plain.status, 0) << plain.out << plain.err;
  const ToolRun recorded =
      runProgram(tmp, VISP_PROJECTIVE_TUTORIAL_APRILTAG,
                 "-d --output '" + (tmp / "figures") + "' --record '" + (tmp / "session") + "'", "recorded");
  ASSERT_EQ(recorded.status, 0) << recorded.out << recorded.err;
  // Recording changes nothing: the same final line, the same figure.
  const std::string after = lineStarting(recorded.out, "After ");
  ASSERT_FALSE(after.empty()) << recorded.out;
  EXPECT_EQ(after, lineStarting(plain.out, "After "));
  vpImage<vpRGBa> plainEnd, end;
  vpImageIo::read(plainEnd, tmp / "plain/stereo-end.png");
  vpImageIo::read(end, tmp / "figures/stereo-end.png");
  EXPECT_TRUE(plainEnd == end);

  // Offline: the tool calibrates the session and finds that every frame fits the model.
  const ToolRun calibrate =
      runTool(tmp, "calibrate '" + (tmp / "session") + "' --output '" + (tmp / "model.json") + "' --quiet");
  ASSERT_EQ(calibrate.status, 0) << calibrate.err;
  const ToolRun check = runTool(tmp, "check '" + (tmp / "model.json") + "' '" + (tmp / "session") + "' --quiet");
  EXPECT_EQ(check.status, 0) << check.out << check.err;
  EXPECT_NE(check.out.find("the model fits"), std::string::npos) << check.out;

  // The figure again from the recording alone: s* from the target frames, the tags, the corners and their paths from
  // the servo frames (detected as the tutorial does, near the last corners) shown as the tutorial shows them.
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "session", false);
  EXPECT_EQ(session.getNumberOfFrames(vpProjectiveSession::TARGET), 16u);
  vpStereoAprilTagDetector tags(vpDetectorAprilTag::TAG_36h11);
  std::vector<std::vector<vpImagePoint>> starLeft(4), starRight(4);
  vpFeatureStereoPoint s[4], s_star[4];
  vpImage<unsigned char> Ileft, Iright;
  vpStereoServoDisplay display(640, 480, false); // the tutorial's cameras' images, without a window
  double errorRms = 0.0;
  unsigned int servoFrames = 0;
  for (vpProjectiveSession::vpFrameRole role : {vpProjectiveSession::TARGET, vpProjectiveSession::SERVO}) {
    for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
      if (session.getFrame(k).role != role) {
        continue;
      }
      session.getImages(k, Ileft, Iright);
      tags.detect(Ileft, Iright);
      const std::vector<int> &ids = tags.getIds();
      unsigned int seen = 0;
      vpColVector e;
      display.display(Ileft, Iright);
      display.displayTags(ids, tags.getLeftPoints(), tags.getRightPoints());
      for (unsigned int c = 0; c < 4; ++c) {
        const size_t j = static_cast<size_t>(std::find(ids.begin(), ids.end(), static_cast<int>(4 + c)) - ids.begin());
        if (j < ids.size() && role == vpProjectiveSession::TARGET) {
          starLeft[c].push_back(tags.getLeftPoints()[j]);
          starRight[c].push_back(tags.getRightPoints()[j]);
        } else if (j < ids.size()) {
          s[c].buildFrom(tags.getLeftPoints()[j], tags.getRightPoints()[j]);
          ++seen;
        }
        if (role == vpProjectiveSession::SERVO) {
          e.stack(s[c].error(s_star[c]));
          display.displayFeature(c, s[c], s_star[c], j < ids.size());
        }
      }
      if (role == vpProjectiveSession::SERVO) {
        errorRms = std::sqrt(e.sumSquare() / e.size());
        display.displayText("iteration " + std::to_string(servoFrames++) + ": error " + std::to_string(errorRms) +
                            " px RMS");
        display.flush();
        if (seen == 4) {
          tags.setPredictedRegions(tags.getIds(), tags.getLeftPoints(), tags.getRightPoints());
        }
      }
    }
    for (unsigned int c = 0; c < 4 && role == vpProjectiveSession::TARGET; ++c) {
      s_star[c].buildFrom(starLeft[c], starRight[c]);
    }
  }
  std::ostringstream expected;
  expected << "After " << servoFrames - 1 << " iterations: image error " << errorRms << " px RMS;";
  EXPECT_EQ(after.find(expected.str()), 0u) << after << " vs " << expected.str();
  vpImage<vpRGBa> replayed = display.getPicture();
  EXPECT_TRUE(replayed == end) << "the figure made from the recording differs from the run's";
#else
  GTEST_SKIP() << "ViSP without AprilTag: the tutorial records nothing";
#endif
}

TEST(ProjectiveToolRecordings, TheMainJobsRecordingReplaysItsFiguresAndCalibratesFromItsMarkers)
{
  TemporaryFolder tmp;
  const std::string common = "--seeds 1 --no-display --output ";
  const ToolRun plain = runProgram(tmp, VISP_PROJECTIVE_PAPER, common + "'" + (tmp / "plain") + "'", "plain");
  ASSERT_EQ(plain.status, 0) << plain.err;
  const ToolRun recorded = runProgram(tmp, VISP_PROJECTIVE_PAPER,
                                      common + "'" + (tmp / "run") + "' --record '" + (tmp / "session") + "'", "run");
  ASSERT_EQ(recorded.status, 0) << recorded.err;
  const ToolRun replay =
      runProgram(tmp, VISP_PROJECTIVE_PAPER,
                 "--no-display --output '" + (tmp / "replay") + "' --replay '" + (tmp / "session") + "'", "replay");
  ASSERT_EQ(replay.status, 0) << replay.out << replay.err;
  EXPECT_NE(replay.out.find("law's: 0 rad"), std::string::npos) << replay.out; // every recorded step is the law's
  for (const char *data : {"/projective-servo-trajectory.csv", "/projective-servo-target.csv"}) {
    const std::string run = readText(tmp / "run" + data);
    EXPECT_FALSE(run.empty()) << data;
    EXPECT_EQ(run, readText(tmp / "plain" + data)) << data << ": recording changed the run";
    EXPECT_EQ(run, readText(tmp / "replay" + data)) << data << ": the replay differs from the run";
  }
  EXPECT_EQ(lineStarting(replay.out, "Seed 1 servo:"), lineStarting(recorded.out, "Seed 1 servo:"));

  // The session: the zero frame, 12 trials, the target, 41 servo frames; the tool calibrates and checks it from the
  // recorded markers (its images are rendered balls, which no tag detector finds).
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "session");
  EXPECT_EQ(session.getNumberOfFrames(vpProjectiveSession::TRIAL), 12u);
  EXPECT_EQ(session.getNumberOfFrames(vpProjectiveSession::TARGET), 1u);
  EXPECT_EQ(session.getNumberOfFrames(vpProjectiveSession::SERVO), 41u);
  const ToolRun calibrate = runTool(tmp, "calibrate '" + (tmp / "session") + "' --recorded-markers --output '" +
                                             (tmp / "model.json") + "' --quiet");
  ASSERT_EQ(calibrate.status, 0) << calibrate.err;
  const ToolRun check =
      runTool(tmp, "check '" + (tmp / "model.json") + "' '" + (tmp / "session") + "' --recorded-markers --quiet");
  EXPECT_EQ(check.status, 0) << check.out << check.err;
  const ToolRun tags = runTool(tmp, "calibrate '" + (tmp / "session") + "' --output '" + (tmp / "tags.json") + "'");
  EXPECT_EQ(tags.status, 1) << "tags found in the rendered balls?";
}

TEST(ProjectiveToolRecordings, RecordingFromCamerasAndTypedReadingsKeepsEveryLine)
{
  TemporaryFolder tmp;
  {
    vpProjectiveSessionWriter writer(tmp / "cameras", std::vector<vpProjectiveJoint::vpJointType>(3));
    for (unsigned int k = 0; k < 9; ++k) {
      writer.addFrame(k == 0 ? vpProjectiveSession::ZERO : vpProjectiveSession::SERVO, vpColVector(3, 0.01 * k), k,
                      keyImage(k), keyImage(100 + k));
    }
  }
  const std::string typed = "# readings of the controller\n"
                            "0.1 -0.2 0.05\n"
                            "0.6, -0.2, 0.05\n"
                            "\n"
                            "observation 0.3\t0.1 0.07\n"
                            "servo 0.2 0 0.06\n";
  {
    vpProjectiveSessionSource cameras(vpProjectiveSession::read(tmp / "cameras"));
    std::istringstream readings(typed);
    std::ostringstream progress;
    EXPECT_EQ(vispProjective::recordFromReadings(tmp / "live", cameras, {}, readings, 1, false, progress), 4u);
  }
  const vpProjectiveSession live = vpProjectiveSession::read(tmp / "live");
  ASSERT_EQ(live.getNumberOfFrames(), 4u);
  EXPECT_EQ(live.getNumberOfJoints(), 3u);
  const vpProjectiveSession::vpFrameRole roles[4] = {vpProjectiveSession::ZERO, vpProjectiveSession::TRIAL,
                                                     vpProjectiveSession::OBSERVATION, vpProjectiveSession::SERVO};
  const double q1[4] = {0.1, 0.6, 0.3, 0.2};
  for (unsigned int k = 0; k < 4; ++k) {
    EXPECT_EQ(live.getFrame(k).role, roles[k]) << k;
    EXPECT_EQ(live.getFrame(k).q[0], q1[k]) << k; // as typed, bit for bit
    vpImage<unsigned char> Il, Ir;
    live.getImages(k, Il, Ir);
    EXPECT_TRUE(Il == keyImage(2 * k + 1) && Ir == keyImage(101 + 2 * k)) << k; // one pair dropped before each
  }
  EXPECT_EQ(live.getTrialJoint(1), 0);
  EXPECT_EQ(live.getFrame(3).q[2], 0.06);

  // Malformed readings name their line; the cameras running out is an error too.
  const std::vector<std::pair<std::string, std::string>> bad = {{"0.1 x 0.3\n", "line 1"},
                                                                {"0.1 0.2\n0.1 0.2 0.3\n", "line 2"},
                                                                {"# nothing\n", "no frame line"},
                                                                {"0 0 0\n0 0 1\n0 0 2\n0 0 3\n0 0 4\n", "line 5"},
                                                                {"zero 0 0 nan\n", "line 1"}};
  for (size_t b = 0; b < bad.size(); ++b) {
    vpProjectiveSessionSource cameras(vpProjectiveSession::read(tmp / "cameras"));
    std::istringstream readings(bad[b].first);
    std::ostringstream progress;
    try {
      vispProjective::recordFromReadings(tmp / ("bad" + std::to_string(b)), cameras, {}, readings, 1, false, progress);
      ADD_FAILURE() << "accepted: " << bad[b].first;
    } catch (const vpException &e) {
      EXPECT_NE(e.getStringMessage().find(bad[b].second), std::string::npos) << b << ": " << e.getStringMessage();
    }
  }

  // The tool: a missing camera is one line naming it, and no session folder is made.
  writeText(tmp / "readings.txt", typed);
  const ToolRun run = runTool(tmp, "record '" + (tmp / "nothing") +
                                       "' --left /dev/visp-projective-none0 --right "
                                       "/dev/visp-projective-none1 --joints '" +
                                       (tmp / "readings.txt") + "'");
  EXPECT_EQ(run.status, 1);
  EXPECT_EQ(lines(run.err), 1u) << run.err;
  EXPECT_NE(run.err.find("/dev/visp-projective-none0"), std::string::npos) << run.err;
  EXPECT_FALSE(std::filesystem::exists(tmp / "nothing"));
}
