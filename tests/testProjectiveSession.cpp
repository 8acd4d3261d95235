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
  Sessions on disk (vpProjectiveSession, vpProjectiveSessionWriter, vpProjectiveSessionSource) and the stereo image
  sources (vpStereoGrabberSource): what the writer records the reader reads back bit for bit, replay is
  deterministic, and every malformed session of issue 21 is refused with one line that names the file or the frame.
*/

#include <cmath>
#include <filesystem>
#include <functional>
#include <limits>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <visp3/core/vpFrameGrabber.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/projective/vpProjectiveSessionSource.h>
#include <visp3/projective/vpStereoGrabberSource.h>

#include "vpProjectiveSessionTestTools.h"

using namespace vpProjectiveTest;

namespace
{
typedef std::vector<vpProjectiveJoint::vpJointType> Types;

const Types kTypes = {vpProjectiveJoint::REVOLUTE, vpProjectiveJoint::REVOLUTE, vpProjectiveJoint::PRISMATIC};

vpColVector joints(double a, double b, double c)
{
  return vpColVector({a, b, c});
}

//! A grey image whose pixels depend on \e seed.
vpImage<unsigned char> pattern(unsigned int seed, unsigned int height = 12, unsigned int width = 16)
{
  vpImage<unsigned char> I(height, width);
  for (unsigned int i = 0; i < height; ++i) {
    for (unsigned int j = 0; j < width; ++j) {
      I[i][j] = static_cast<unsigned char>((seed * 37 + i * 11 + j * 5) & 255);
    }
  }
  return I;
}

/*!
  A small valid session in \e folder: zero at a non-zero reference, a trial of each joint, an observation, a
  target and a servo frame (7 frames).
*/
void writeSession(const std::string &folder)
{
  vpProjectiveSessionWriter writer(folder, kTypes);
  const vpColVector q0 = joints(0.1, -0.2, 0.05);
  writer.addFrame(vpProjectiveSession::ZERO, q0, 0.0, pattern(0), pattern(100));
  writer.addFrame(vpProjectiveSession::TRIAL, joints(0.6, -0.2, 0.05), 1.5, pattern(1), pattern(101));
  writer.addFrame(vpProjectiveSession::TRIAL, joints(0.1, -0.5, 0.05), 3.0, pattern(2), pattern(102));
  writer.addFrame(vpProjectiveSession::TRIAL, joints(0.1, -0.2, 0.01), 4.5, pattern(3), pattern(103));
  writer.addFrame(vpProjectiveSession::OBSERVATION, joints(0.3, 0.1, 0.07), 6.0, pattern(4), pattern(104));
  writer.addFrame(vpProjectiveSession::TARGET, joints(0.2, 0.0, 0.06), std::numeric_limits<double>::quiet_NaN(),
                  pattern(5), pattern(105));
  writer.addFrame(vpProjectiveSession::SERVO, joints(0.2, 0.0, 0.06), 9.0, pattern(6), pattern(106));
}

bool sameImage(const vpImage<unsigned char> &A, const vpImage<unsigned char> &B)
{
  if (A.getHeight() != B.getHeight() || A.getWidth() != B.getWidth()) {
    return false;
  }
  for (unsigned int i = 0; i < A.getSize(); ++i) {
    if (A.bitmap[i] != B.bitmap[i]) {
      return false;
    }
  }
  return true;
}

//! Expects read(\e folder) to throw one line containing every string of \e needles.
void expectRefused(const std::string &folder, const std::vector<std::string> &needles, const std::string &what)
{
  try {
    vpProjectiveSession::read(folder);
    ADD_FAILURE() << what << ": accepted";
  } catch (const vpProjectiveException &e) {
    const std::string message = e.getStringMessage();
    EXPECT_EQ(e.getCode(), vpProjectiveException::fileError) << what;
    EXPECT_EQ(message.find('\n'), std::string::npos) << what << ": " << message;
    for (const std::string &needle : needles) {
      EXPECT_NE(message.find(needle), std::string::npos) << what << ": '" << needle << "' not in: " << message;
    }
  }
}

//! A copy of the valid session with its session.json edited by \e edit.
std::string editedSession(const TemporaryFolder &tmp, const std::string &name, const std::function<void(json &)> &edit)
{
  const std::string folder = tmp / name;
  writeSession(folder);
  json file = json::parse(readText(folder + "/session.json"));
  edit(file);
  writeText(folder + "/session.json", file.dump(1));
  return folder;
}

//! A grabber of fixed images (width x height), counting its acquisitions.
class FixedGrabber : public vpFrameGrabber
{
public:
  FixedGrabber(unsigned int w, unsigned int h, unsigned char value) : m_value(value), acquisitions(0)
  {
    width = w;
    height = h;
    init = true;
  }
  void open(vpImage<unsigned char> &I) override { I.resize(height, width, m_value); }
  void open(vpImage<vpRGBa> &I) override { I.resize(height, width); }
  void acquire(vpImage<unsigned char> &I) override
  {
    I.resize(height, width, m_value);
    ++acquisitions;
  }
  void acquire(vpImage<vpRGBa> &I) override { I.resize(height, width); }
  void close() override {}

private:
  unsigned char m_value;

public:
  unsigned int acquisitions;
};
} // namespace

TEST(ProjectiveSession, WhatTheWriterRecordsTheReaderReadsBack)
{
  TemporaryFolder tmp;
  writeSession(tmp / "s");
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "s");
  ASSERT_EQ(session.getNumberOfFrames(), 7u);
  EXPECT_EQ(session.getJointTypes(), kTypes);
  EXPECT_EQ(session.getZeroFrame(), 0u);
  EXPECT_EQ(session.getTrialJoint(1), 0);
  EXPECT_EQ(session.getTrialJoint(2), 1);
  EXPECT_EQ(session.getTrialJoint(3), 2);
  EXPECT_EQ(session.getTrialJoint(4), -1);
  EXPECT_EQ(session.getNumberOfFrames(vpProjectiveSession::TRIAL), 3u);
  EXPECT_EQ(session.getWidth(), 16u);
  EXPECT_EQ(session.getHeight(), 12u);
  EXPECT_EQ(session.getFrame(4).role, vpProjectiveSession::OBSERVATION);
  EXPECT_EQ(session.getFrame(5).role, vpProjectiveSession::TARGET);
  EXPECT_FALSE(session.getFrame(5).hasTime);
  EXPECT_TRUE(session.getFrame(6).hasTime);
  EXPECT_EQ(session.getFrame(6).t, 9.0);
  EXPECT_EQ(session.getFrame(1).q[0], 0.6); // bit-identical readings
  EXPECT_EQ(session.getFrame(3).q[2], 0.01);
  EXPECT_EQ(session.getFrame(2).left, "left/000002.png");
  for (unsigned int k = 0; k < 7; ++k) {
    vpImage<unsigned char> Il, Ir;
    session.getImages(k, Il, Ir);
    EXPECT_TRUE(sameImage(Il, pattern(k))) << k;
    EXPECT_TRUE(sameImage(Ir, pattern(100 + k))) << k;
  }
  // Nothing temporary is left.
  for (const char *sub : {"", "/left", "/right"}) {
    for (const auto &entry : std::filesystem::directory_iterator(tmp / "s" + sub)) {
      EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
    }
  }
}

TEST(ProjectiveSession, ColourImagesAreRecordedAsRgbAndReadAsGrey)
{
  TemporaryFolder tmp;
  vpProjectiveSessionWriter writer(tmp / "s", kTypes);
  vpImage<vpRGBa> colour(10, 14, vpRGBa(200, 100, 50));
  writer.addFrame(vpProjectiveSession::ZERO, joints(0, 0, 0), 0.0, colour, colour);
  writer.close();
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "s");
  vpImage<unsigned char> Il, Ir;
  session.getImages(0, Il, Ir);
  ASSERT_EQ(Il.getWidth(), 14u);
  vpImage<unsigned char> grey;
  vpImageConvert::convert(colour, grey);
  EXPECT_NEAR(Il[3][3], grey[3][3], 1.0);
}

TEST(ProjectiveSession, ReplayIsDeterministicAndFollowsTheRoles)
{
  TemporaryFolder tmp;
  writeSession(tmp / "s");
  vpProjectiveSessionSource replay(vpProjectiveSession::read(tmp / "s"));
  EXPECT_EQ(replay.getWidth(), 16u);
  EXPECT_EQ(replay.getHeight(), 12u);
  EXPECT_THROW(replay.getJoints(), vpProjectiveException);
  vpStereoImageSource &source = replay;
  vpImage<unsigned char> Il, Ir;
  for (int pass = 0; pass < 2; ++pass) {
    for (unsigned int k = 0; k < 7; ++k) {
      ASSERT_TRUE(source.acquire(Il, Ir));
      EXPECT_EQ(replay.getFrameIndex(), static_cast<int>(k));
      EXPECT_TRUE(sameImage(Il, pattern(k)) && sameImage(Ir, pattern(100 + k))) << pass << " " << k;
      EXPECT_EQ(replay.getJoints(), replay.getSession().getFrame(k).q);
    }
    EXPECT_FALSE(source.acquire(Il, Ir));
    EXPECT_TRUE(sameImage(Il, pattern(6)));
    replay.rewind();
  }
  vpProjectiveSessionSource trials(vpProjectiveSession::read(tmp / "s"), {vpProjectiveSession::TRIAL});
  std::vector<int> seen;
  while (trials.acquire(Il, Ir)) {
    seen.push_back(trials.getFrameIndex());
  }
  EXPECT_EQ(seen, std::vector<int>({1, 2, 3}));
  EXPECT_THROW(vpProjectiveSessionSource(vpProjectiveSession::fromString(readText(tmp / "s/session.json"), "text")),
               vpProjectiveException);
}

TEST(ProjectiveSession, AcquisitionFramesGetTheirRoleFromTheReadings)
{
  TemporaryFolder tmp;
  vpProjectiveSessionWriter writer(tmp / "s", kTypes);
  EXPECT_EQ(writer.addAcquisitionFrame(joints(0.1, 0.2, 0.3), 0.0, pattern(0), pattern(1)), vpProjectiveSession::ZERO);
  EXPECT_EQ(writer.addAcquisitionFrame(joints(0.1, 0.25, 0.3), 1.0, pattern(0), pattern(1)),
            vpProjectiveSession::TRIAL);
  EXPECT_EQ(writer.addAcquisitionFrame(joints(0.1 + 1e-6, 0.2, 0.2), 1.0, pattern(0), pattern(1)),
            vpProjectiveSession::TRIAL); // encoder noise on joint 0: 1 % of the motion
  EXPECT_EQ(writer.addAcquisitionFrame(joints(0.2, 0.25, 0.3), 2.0, pattern(0), pattern(1)),
            vpProjectiveSession::OBSERVATION);
  EXPECT_EQ(writer.addAcquisitionFrame(joints(0.1, 0.2, 0.3), 3.0, pattern(0), pattern(1)),
            vpProjectiveSession::OBSERVATION);
  EXPECT_EQ(writer.addAcquisitionFrame(joints(0.1, 0.2 + 1e-5, 0.3), 3.0, pattern(0), pattern(1)),
            vpProjectiveSession::OBSERVATION); // back at the zero reference within the encoders' noise
  writer.close();
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "s");
  EXPECT_EQ(session.getTrialJoint(1), 1);
  EXPECT_EQ(session.getTrialJoint(2), 2);
}

TEST(ProjectiveSession, TheWriterRecordsNoFrameTheReaderWouldRefuse)
{
  TemporaryFolder tmp;
  vpProjectiveSessionWriter writer(tmp / "s", kTypes);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::TRIAL, joints(0.5, 0, 0), 0.0, pattern(0), pattern(1)),
               vpProjectiveException); // a trial before the zero frame
  writer.addFrame(vpProjectiveSession::ZERO, joints(0, 0, 0), 0.0, pattern(0), pattern(1));
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::ZERO, joints(0, 0, 0), 0.0, pattern(0), pattern(1)),
               vpProjectiveException);
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::TRIAL, joints(0.5, 0.5, 0), 0.0, pattern(0), pattern(1)),
               vpProjectiveException);
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::TRIAL, joints(0, 0, 0), 0.0, pattern(0), pattern(1)),
               vpProjectiveException);
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::SERVO, joints(nan, 0, 0), 0.0, pattern(0), pattern(1)),
               vpProjectiveException);
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::SERVO, vpColVector(2, 0.0), 0.0, pattern(0), pattern(1)),
               vpProjectiveException);
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::SERVO, joints(0, 0, 0), 0.0, vpImage<unsigned char>(), pattern(1)),
               vpProjectiveException);
  EXPECT_EQ(writer.getSession().getNumberOfFrames(), 1u);
  writer.save();
  EXPECT_EQ(vpProjectiveSession::read(tmp / "s").getNumberOfFrames(), 1u);
  EXPECT_FALSE(std::filesystem::exists(tmp / "s/left/000001.png"));
  // A recording is never overwritten; a folder that cannot be created is reported at once.
  EXPECT_THROW(vpProjectiveSessionWriter(tmp / "s", kTypes), vpProjectiveException);
  writeText(tmp / "file", "x");
  EXPECT_THROW(vpProjectiveSessionWriter(tmp / "file/s", kTypes), vpProjectiveException);
  EXPECT_THROW(vpProjectiveSessionWriter(tmp / "t", Types()), vpProjectiveException);
}

TEST(ProjectiveSession, MalformedSessionsAreRefusedWithOneLineNamingTheFileOrFrame)
{
  TemporaryFolder tmp;
  expectRefused(tmp / "nothing", {"nothing/session.json", "session folder"}, "missing folder");
  {
    const std::string folder = tmp / "truncated";
    writeSession(folder);
    const std::string text = readText(folder + "/session.json");
    writeText(folder + "/session.json", text.substr(0, text.size() / 2));
    expectRefused(folder, {"truncated/session.json", "not valid JSON"}, "truncated JSON");
    writeText(folder + "/session.json", "");
    expectRefused(folder, {"not valid JSON"}, "empty session.json");
    writeText(folder + "/session.json", "[1, 2]");
    expectRefused(folder, {"not a JSON object"}, "an array");
  }
  expectRefused(editedSession(tmp, "format", [](json &f) { f["format"] = "visp_projective_robot_model"; }),
                {"format", "not \"visp-projective-session\""}, "wrong format name");
  expectRefused(editedSession(tmp, "version", [](json &f) { f["version"] = 2; }), {"version 2", "version 1"},
                "wrong version");
  expectRefused(editedSession(tmp, "noversion", [](json &f) { f.erase("version"); }), {"'version'"}, "no version");
  expectRefused(editedSession(tmp, "jointtype", [](json &f) { f["joint_types"][1] = "spherical"; }),
                {"joint 1", "spherical"}, "unknown joint type");
  expectRefused(editedSession(tmp, "short", [](json &f) { f["frames"][2]["q"].erase(2); }),
                {"frame 3/7 ('left/000002.png')", "2 readings", "3 joints"}, "readings of the wrong length");
  expectRefused(editedSession(tmp, "long", [](json &f) { f["frames"][5]["q"].push_back(0.0); }),
                {"frame 6/7", "4 readings"}, "readings of the wrong length");
  expectRefused(editedSession(tmp, "nan", [](json &f) { f["frames"][4]["q"][1] = "NaN"; }),
                {"frame 5/7", "reading 1", "not a finite number"}, "a non-finite reading");
  expectRefused(editedSession(tmp, "null", [](json &f) { f["frames"][4]["q"][0] = nullptr; }),
                {"frame 5/7", "reading 0"}, "a null reading");
  expectRefused(editedSession(tmp, "twojoints", [](json &f) { f["frames"][2]["q"][0] = 0.3; }),
                {"frame 3/7 ('left/000002.png')", "moves joints 1 and 0", "observation"}, "a trial moving two joints");
  expectRefused(editedSession(tmp, "nomotion", [](json &f) { f["frames"][1]["q"][0] = 0.1; }),
                {"frame 2/7", "moves no joint"}, "a trial moving no joint");
  expectRefused(editedSession(tmp, "nozero", [](json &f) { f["frames"][0]["role"] = "observation"; }),
                {"no zero frame"}, "no zero frame");
  expectRefused(editedSession(tmp, "twozeros", [](json &f) { f["frames"][4]["role"] = "zero"; }),
                {"frame 5/7", "second zero frame", "frame 1/7"}, "two zero frames");
  expectRefused(editedSession(tmp, "role", [](json &f) { f["frames"][3]["role"] = "trail"; }),
                {"frame 4/7", "\"trail\""}, "unknown role");
  expectRefused(editedSession(tmp, "norole", [](json &f) { f["frames"][3].erase("role"); }), {"frame 4/7", "'role'"},
                "no role");
  expectRefused(editedSession(tmp, "outside", [](json &f) { f["frames"][1]["right"] = "../outside/000001.png"; }),
                {"frame 2/7", "inside the session folder"}, "an image outside the folder");
  expectRefused(editedSession(tmp, "time", [](json &f) { f["frames"][1]["t"] = "noon"; }), {"frame 2/7", "'t'"},
                "a time that is not a number");
  expectRefused(editedSession(tmp, "noframes", [](json &f) { f["frames"] = json::array(); }), {"'frames'"},
                "no frames");
  {
    const std::string folder = editedSession(tmp, "missing", [](json &) {});
    std::filesystem::remove(folder + "/right/000003.png");
    expectRefused(folder, {"frame 4/7 ('left/000003.png')", "right image", "right/000003.png", "is missing"},
                  "a missing image");
  }
  {
    const std::string folder = editedSession(tmp, "notpng", [](json &) {});
    writeText(folder + "/left/000002.png", "this is no image, only a text of more than 33 characters");
    expectRefused(folder, {"frame 3/7", "left/000002.png", "not a PNG"}, "an image that is not a PNG");
  }
  {
    const std::string folder = editedSession(tmp, "cut", [](json &) {});
    const std::string png = readText(folder + "/left/000005.png");
    writeText(folder + "/left/000005.png", png.substr(0, 40));
    expectRefused(folder, {"frame 6/7", "left/000005.png"}, "a truncated PNG");
  }
  {
    const std::string folder = editedSession(tmp, "depth", [](json &) {});
    std::string png = readText(folder + "/right/000001.png");
    png[24] = 16; // bit depth 16 in the IHDR header
    writeText(folder + "/right/000001.png", png);
    expectRefused(folder, {"frame 2/7", "right/000001.png", "bit depth 16", "8-bit grey or RGB"}, "a 16-bit PNG");
  }
  {
    const std::string folder = editedSession(tmp, "size", [](json &) {});
    vpImageIo::write(pattern(4, 10, 16), folder + "/left/000004.png");
    expectRefused(folder, {"frame 5/7", "16 x 10", "16 x 12"}, "an image of another size");
  }
}

TEST(ProjectiveSession, UnknownKeysAreIgnored)
{
  TemporaryFolder tmp;
  const std::string folder = editedSession(tmp, "extra", [](json &f) {
    f["recorded_by"] = "a test";
    f["frames"][1]["exposure_ms"] = 8;
    f["frames"][1]["markers"] = json::array({1, 2, 3});
  });
  const vpProjectiveSession session = vpProjectiveSession::read(folder);
  EXPECT_EQ(session.getNumberOfFrames(), 7u);
  EXPECT_EQ(session.getTrialJoint(1), 0);
}

TEST(ProjectiveSession, AMissingCameraDeviceGivesAClearError)
{
  const std::string device = "/dev/video-nonexistent-visp-projective-test";
  try {
    vpStereoGrabberSource cameras(device, device + "-right");
    ADD_FAILURE() << "a missing device opened";
  } catch (const vpProjectiveException &e) {
    const std::string message = e.getStringMessage();
    EXPECT_NE(message.find(device), std::string::npos) << message;
    EXPECT_NE(message.find("left camera"), std::string::npos) << message;
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
  }
  // A device that is not a camera: named, before ViSP's grabber (which would print its own lines) is opened.
  try {
    vpStereoGrabberSource cameras("/dev/null", "/dev/null");
    ADD_FAILURE() << "/dev/null opened as a camera";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("cannot open the left camera '/dev/null' (not a video capture device)"),
              std::string::npos)
        << e.getStringMessage();
  }
  // Two grabbers opened by the caller.
  FixedGrabber left(8, 6, 10), right(8, 6, 20);
  vpStereoGrabberSource pair(left, right);
  vpImage<unsigned char> Il, Ir;
  EXPECT_TRUE(pair.acquire(Il, Ir));
  EXPECT_EQ(pair.getWidth(), 8u);
  EXPECT_EQ(Il[0][0], 10);
  EXPECT_EQ(Ir[0][0], 20);
  EXPECT_EQ(left.acquisitions, 1u);
  double tLeft = -1.0, tRight = -1.0; // grabbers other than V4L2 give no stamps: the cell then waits and discards
  EXPECT_FALSE(pair.getTimestamps(tLeft, tRight));
  EXPECT_EQ(tLeft, -1.0);
  FixedGrabber unopened(0, 0, 0);
  EXPECT_THROW(vpStereoGrabberSource(left, unopened), vpProjectiveException);
}
