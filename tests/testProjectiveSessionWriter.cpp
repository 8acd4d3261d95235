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
  vpProjectiveSessionWriter's save points (issue 21): session.json on disk is at every moment a complete session of
  the frames up to the last save point, the save points come at a constant amount of text per frame, and close() or
  the destructor saves the rest; recorded markers (a frame's "recorded_markers" entry) are written and read back bit for
  bit, refused when malformed, and calibrate a session exactly as the extraction they were measured by.
*/

#include <cmath>
#include <filesystem>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "vpProjectiveSessionTestTools.h"

using namespace vpProjectiveTest;

namespace
{
const std::vector<vpProjectiveJoint::vpJointType> kTypes(2, vpProjectiveJoint::REVOLUTE);
const double kNoTimeBound = std::numeric_limits<double>::infinity();

vpColVector servoJoints(unsigned int k)
{
  vpColVector q(2);
  q[0] = 0.1 + 1e-3 * k;
  q[1] = -0.2 + 2e-3 * k;
  return q;
}

//! Number of frames of the session on disk in \e folder (what a reader after a crash would get); -1 if unreadable.
int framesOnDisk(const std::string &folder)
{
  try {
    return static_cast<int>(vpProjectiveSession::read(folder, false).getNumberOfFrames());
  } catch (const vpProjectiveException &) {
    return -1;
  }
}
} // namespace

TEST(ProjectiveSessionWriter, SessionJsonHoldsTheFramesUpToTheLastSavePoint)
{
  TemporaryFolder tmp;
  const std::string folder = tmp / "s";
  vpProjectiveSessionWriter writer(folder, kTypes);
  writer.setSaveInterval(4, kNoTimeBound);
  EXPECT_EQ(framesOnDisk(folder), -1); // no frame yet: an empty session is not a session
  vpColVector lastWritten;
  for (unsigned int k = 0; k < 10; ++k) {
    lastWritten = servoJoints(k);
    writer.addFrame(k == 0 ? vpProjectiveSession::ZERO : vpProjectiveSession::SERVO, lastWritten, 0.04 * k, keyImage(k),
                    keyImage(k));
    const int expected = k + 1 >= 8 ? 8 : (k + 1 >= 4 ? 4 : -1);
    EXPECT_EQ(framesOnDisk(folder), expected) << "after frame " << k; // a crash now leaves this session
    EXPECT_EQ(writer.getNumberOfSavedFrames(), static_cast<unsigned int>(std::max(expected, 0))) << k;
    EXPECT_EQ(writer.getSession().getNumberOfFrames(), k + 1);
  }
  writer.close();
  const vpProjectiveSession session = vpProjectiveSession::read(folder);
  ASSERT_EQ(session.getNumberOfFrames(), 10u);
  // Bit-identical readings: against the reading written, not a second evaluation of servoJoints(9), which clang++-14
  // folds at compile time one unit in the last place away from the value the loop computed at run time.
  EXPECT_EQ(session.getFrame(9).q[1], lastWritten[1]);
  EXPECT_EQ(session.getFrame(9).t, 0.04 * 9);
  writer.close(); // again: nothing
  EXPECT_THROW(writer.addFrame(vpProjectiveSession::SERVO, servoJoints(10), 0.4, keyImage(10), keyImage(10)),
               vpProjectiveException);
  EXPECT_EQ(framesOnDisk(folder), 10);
  EXPECT_THROW(writer.setSaveInterval(0, 1.0), vpProjectiveException);
  EXPECT_THROW(writer.setSaveInterval(5, 0.0), vpProjectiveException);
  EXPECT_THROW(writer.setSaveInterval(5, std::nan("")), vpProjectiveException);
}

TEST(ProjectiveSessionWriter, TheDestructorSavesTheRest)
{
  TemporaryFolder tmp;
  {
    vpProjectiveSessionWriter writer(tmp / "s", kTypes);
    writer.setSaveInterval(100, kNoTimeBound);
    for (unsigned int k = 0; k < 7; ++k) {
      writer.addFrame(k == 0 ? vpProjectiveSession::ZERO : vpProjectiveSession::SERVO, servoJoints(k), 0.04 * k,
                      keyImage(k), keyImage(k));
    }
    EXPECT_EQ(framesOnDisk(tmp / "s"), -1);
    writer.save();
    EXPECT_EQ(framesOnDisk(tmp / "s"), 7);
    writer.addFrame(vpProjectiveSession::SERVO, servoJoints(7), 0.28, keyImage(7), keyImage(7));
  }
  EXPECT_EQ(framesOnDisk(tmp / "s"), 8);
  for (const auto &entry : std::filesystem::directory_iterator(tmp.path() + "/s")) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << entry.path();
  }
}

TEST(ProjectiveSessionWriter, SavePointsCostAConstantAmountOfTextPerFrame)
{
  // With a save interval of one frame, a save still waits for an eighth of the frames already saved: over n frames
  // the text written is a constant times n (not n^2 / 2 frames' worth), and no save point leaves more than an eighth
  // (or the interval) unsaved.
  TemporaryFolder tmp;
  vpProjectiveSessionWriter writer(tmp / "s", kTypes);
  writer.setSaveInterval(1, kNoTimeBound);
  const unsigned int n = 400;
  unsigned long framesWritten = 0; // frames' worth of text written to session.json
  unsigned int saves = 0, saved = 0;
  for (unsigned int k = 0; k < n; ++k) {
    writer.addFrame(k == 0 ? vpProjectiveSession::ZERO : vpProjectiveSession::SERVO, servoJoints(k), 0.04 * k,
                    keyImage(k), keyImage(k));
    if (writer.getNumberOfSavedFrames() != saved) {
      saved = writer.getNumberOfSavedFrames();
      EXPECT_EQ(saved, k + 1);
      framesWritten += saved;
      ++saves;
    }
    EXPECT_LE(k + 1 - saved, std::max(1u, saved / 8)) << k;
  }
  EXPECT_LE(framesWritten, 10ul * n);
  EXPECT_LT(saves, 50u);
  writer.close();
  EXPECT_EQ(framesOnDisk(tmp / "s"), static_cast<int>(n));
}

TEST(ProjectiveSessionWriter, RecordedMarkersAreReadBackBitForBitAndCheckedLikeTheRest)
{
  TemporaryFolder tmp;
  const std::vector<int> ids = {0, 3, 7};
  const std::vector<vpImagePoint> left = {vpImagePoint(10.125, 20.0 / 3.0), vpImagePoint(0.1, 1e-7),
                                          vpImagePoint(479.5, 639.25)};
  const std::vector<vpImagePoint> right = {vpImagePoint(11.0, 19.0), vpImagePoint(-3.5, 2.0 / 7.0),
                                           vpImagePoint(470.0, 600.0)};
  {
    vpProjectiveSessionWriter writer(tmp / "s", kTypes);
    writer.addFrame(vpProjectiveSession::ZERO, servoJoints(0), 0.0, keyImage(0), keyImage(0), ids, left, right);
    writer.addFrame(vpProjectiveSession::SERVO, servoJoints(1), 0.04, keyImage(1), keyImage(1));
    // Malformed markers are refused and record nothing.
    EXPECT_THROW(writer.addFrame(vpProjectiveSession::SERVO, servoJoints(2), 0.0, keyImage(2), keyImage(2), {3, 0, 7},
                                 left, right),
                 vpProjectiveException);
    EXPECT_THROW(
        writer.addFrame(vpProjectiveSession::SERVO, servoJoints(2), 0.0, keyImage(2), keyImage(2), {0, 3}, left, right),
        vpProjectiveException);
    std::vector<vpImagePoint> bad = right;
    bad[1].set_u(std::nan(""));
    EXPECT_THROW(
        writer.addFrame(vpProjectiveSession::SERVO, servoJoints(2), 0.0, keyImage(2), keyImage(2), ids, left, bad),
        vpProjectiveException);
    EXPECT_EQ(writer.getSession().getNumberOfFrames(), 2u);
    writer.close();
  }
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "s");
  ASSERT_EQ(session.getNumberOfFrames(), 2u);
  const vpProjectiveSession::vpFrame &f = session.getFrame(0);
  EXPECT_EQ(f.markerIds, ids);
  ASSERT_EQ(f.markerLeft.size(), 3u);
  for (size_t j = 0; j < 3; ++j) {
    EXPECT_EQ(f.markerLeft[j], left[j]) << j;
    EXPECT_EQ(f.markerRight[j], right[j]) << j;
  }
  EXPECT_TRUE(session.getFrame(1).markerIds.empty());
  EXPECT_EQ(vpProjectiveSession::fromString(session.toString(), "again").toString(), session.toString());

  // The reader refuses malformed entries with one line naming the frame.
  const std::string text = readText(tmp / "s/session.json");
  const std::vector<std::function<void(json &)>> edits = {
      [](json &m) { m["ids"] = {3, 0, 7}; },   [](json &m) { m["ids"] = {0, 0, 7}; },
      [](json &m) { m["left"].erase(1); },     [](json &m) { m["right"][2] = {1.0}; },
      [](json &m) { m["right"][2][0] = "x"; }, [](json &m) { m.erase("ids"); },
      [](json &m) { m = json::array(); },      [](json &m) { m["ids"][0] = -1; }};
  for (size_t e = 0; e < edits.size(); ++e) {
    json file = json::parse(text);
    edits[e](file["frames"][0]["recorded_markers"]);
    try {
      vpProjectiveSession::fromString(file.dump(), "edited");
      ADD_FAILURE() << "edit " << e << " accepted";
    } catch (const vpProjectiveException &x) {
      const std::string message = x.getStringMessage();
      EXPECT_NE(message.find("frame 1/"), std::string::npos) << e << ": " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << e;
    }
  }
}

TEST(ProjectiveSessionWriter, RecordedMarkersCalibrateAsTheExtractionTheyWereMeasuredBy)
{
  // A calibration session whose images carry a key to the markers (the test tools' extraction), copied into a second
  // session with each frame's markers recorded in it: the two calibrate into the same model.
  TemporaryFolder tmp;
  const ArmSetup s = pumaEyeToHand();
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "keyed", *rec, 0.3, 5));
  const vpProjectiveSession keyed = vpProjectiveSession::read(tmp / "keyed");
  {
    vpProjectiveSessionWriter writer(tmp / "markers", keyed.getJointTypes());
    const vpProjectiveSessionCalibration::vpMarkerExtractor extract = recordedMarkers(rec);
    for (unsigned int k = 0; k < keyed.getNumberOfFrames(); ++k) {
      vpImage<unsigned char> Il, Ir;
      keyed.getImages(k, Il, Ir);
      std::vector<int> ids;
      std::vector<vpImagePoint> l, r;
      extract(Il, Ir, ids, l, r);
      const vpProjectiveSession::vpFrame &f = keyed.getFrame(k);
      writer.addFrame(f.role, f.q, f.t, vpImage<unsigned char>(6, 8, 0), vpImage<unsigned char>(6, 8, 0), ids, l, r);
    }
    writer.close();
  }
  vpProjectiveSessionCalibration fromImages(recordedMarkers(rec)), fromRecorded(recordedMarkers(rec));
  fromRecorded.setRecordedMarkers(true);
  const vpProjectiveArmModel a = fromImages.calibrate(keyed);
  const vpProjectiveArmModel b = fromRecorded.calibrate(vpProjectiveSession::read(tmp / "markers"));
  EXPECT_EQ(fromImages.getCalibrationResidual(), fromRecorded.getCalibrationResidual());
  EXPECT_EQ(fromImages.getMarkerIds(), fromRecorded.getMarkerIds());
  ASSERT_EQ(a.markers().size(), b.markers().size());
  // Without recorded markers, the recorded-marker calibration names the frame.
  try {
    fromRecorded.calibrate(keyed);
    ADD_FAILURE() << "a session without recorded markers was calibrated from them";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("frame 1/"), std::string::npos) << e.getStringMessage();
    EXPECT_NE(e.getStringMessage().find("no recorded markers"), std::string::npos) << e.getStringMessage();
  }
}
