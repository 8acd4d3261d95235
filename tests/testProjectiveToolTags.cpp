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
  \file testProjectiveToolTags.cpp
  \brief visp-projective on sessions of a rendered tag cell, end to end: the images are PNGs of printed AprilTags
  (vpSimulatorStereoCell, addToolTags(): 12 corners, 1 grey level of noise), the readings absolute encoder values with a
  non-zero reference (vpSimulatorRobotArm::setEncoderOffset()), the tool's own detector finds the markers.
  - `calibrate` turns the 13-frame session of the Viper850 and of the R-R-P-R-R-R arm into a model whose prediction
    of the tag corners at 20 random configurations in view is within 0.3 px RMS of the truth;
  - `check` passes a later session of the same cell and names the camera bumped by 2 deg and 1 cm;
  - `record` writes the rendered cell's acquisition session, which `calibrate`, `check` and `report --plots` take.
*/

#include <cmath>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>
#include <visp3/projective/vpSimulatorStereoCell.h>

#include "vpProjectiveSessionTestTools.h"
#include "vpProjectiveToolTestTools.h"

using namespace vpProjectiveTest;

namespace
{
//! The cell of \e s with its rig moved by \e lBump (left camera) or \e rBump (right camera).
vpSimulatorStereoCell makeCell(const ArmSetup &s, const vpHomogeneousMatrix &lBump = vpHomogeneousMatrix(),
                               const vpHomogeneousMatrix &rBump = vpHomogeneousMatrix())
{
  // The left camera moving alone: wMl' = wMl lBump and rMl' = rMl lBump (wMr unchanged); the right one: rMl' = rBump^-1
  // rMl.
  const vpSimulatorStereoRig rig(s.camLeft, s.camRight, rBump.inverse() * s.rMl * lBump, s.wMl * lBump, s.width,
                                 s.height);
  vpSimulatorStereoCell cell(s.arm, rig, s.qRef, 17);
  cell.addToolTags(0.03);
  vpColVector offset(s.n());
  for (unsigned int i = 0; i < s.n(); ++i) {
    offset[i] = 0.1 * (i + 1); // an absolute encoder's reference
  }
  cell.getRobot().setEncoderOffset(offset);
  cell.getRobot().setConstantSamplingTimeMode(true);
  return cell;
}

//! Moves the cell's arm to arm joints \e qArm; true if the 12 tag corners are inside both images.
bool moveTo(vpSimulatorStereoCell &cell, const vpColVector &qArm)
{
  cell.getRobot().setPosition(vpRobot::ARTICULAR_FRAME, qArm + cell.getRobot().getEncoderOffset());
  std::vector<int> ids;
  std::vector<vpImagePoint> l, r;
  return cell.getTrueCorners(ids, l, r) == 12;
}

//! Adds the frame of the cell's current pose to \e writer (its readings, the rendered images).
void record(vpSimulatorStereoCell &cell, vpProjectiveSessionWriter &writer, vpProjectiveSession::vpFrameRole role)
{
  vpImage<unsigned char> Il, Ir;
  cell.acquire(Il, Ir);
  vpColVector q;
  cell.getRobot().getPosition(vpRobot::ARTICULAR_FRAME, q);
  writer.addFrame(role, q, cell.getRobot().getTime(), Il, Ir);
}

//! The calibration session: the zero frame, each joint alone both ways (halved until the tags stay in view).
void recordCalibration(const ArmSetup &s, const std::string &folder)
{
  vpSimulatorStereoCell cell = makeCell(s);
  vpProjectiveSessionWriter writer(folder, s.jointTypes());
  ASSERT_TRUE(moveTo(cell, s.qRef));
  record(cell, writer, vpProjectiveSession::ZERO);
  for (unsigned int i = 0; i < s.n(); ++i) {
    for (int sign = -1; sign <= 1; sign += 2) {
      vpColVector q = s.qRef;
      double amount = s.trialAmounts[i];
      q[i] = s.qRef[i] + sign * amount;
      while (!moveTo(cell, q)) {
        amount /= 2.0;
        q[i] = s.qRef[i] + sign * amount;
      }
      record(cell, writer, vpProjectiveSession::TRIAL);
    }
  }
}

//! Random arm joints within the trial amounts of the zero reference with the tags in view.
vpColVector randomPose(const ArmSetup &s, vpSimulatorStereoCell &cell, vpUniRand &rng)
{
  for (int attempt = 0; attempt < 1000; ++attempt) {
    vpColVector q = s.qRef;
    for (unsigned int i = 0; i < s.n(); ++i) {
      q[i] += rng.uniform(-s.trialAmounts[i], s.trialAmounts[i]);
    }
    if (moveTo(cell, q)) {
      return q;
    }
  }
  return vpColVector();
}

//! RMS per coordinate of the model's prediction of the 12 corners at 20 random configurations, against the truth.
double predictionError(const ArmSetup &s, const std::string &modelFile)
{
  std::vector<int> ids;
  const vpProjectiveArmModel model = vpProjectiveModelFile::load(modelFile, nullptr, nullptr, &ids);
  EXPECT_EQ(ids.size(), 12u);
  vpSimulatorStereoCell cell = makeCell(s);
  vpUniRand rng(5);
  double sum = 0.0;
  unsigned int coordinates = 0;
  for (int c = 0; c < 20; ++c) {
    const vpColVector q = randomPose(s, cell, rng);
    EXPECT_EQ(q.getRows(), s.n());
    vpColVector readings;
    cell.getRobot().getPosition(vpRobot::ARTICULAR_FRAME, readings);
    vpProjectiveArmModel::JointVector v(s.n());
    for (unsigned int i = 0; i < s.n(); ++i) {
      v(i) = readings[i];
    }
    const Eigen::Matrix4d H = model.displacement(v);
    std::vector<int> trueIds;
    std::vector<vpImagePoint> l, r;
    cell.getTrueCorners(trueIds, l, r);
    for (size_t j = 0; j < ids.size() && trueIds == ids; ++j) {
      Eigen::Vector4d predicted;
      EXPECT_TRUE(model.predictMarker(static_cast<unsigned int>(j), H, predicted));
      sum += (predicted - Eigen::Vector4d(l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v())).squaredNorm();
      coordinates += 4;
    }
  }
  return coordinates > 0 ? std::sqrt(sum / coordinates) : 1e9;
}

void expectCalibrated(const ArmSetup &s)
{
  TemporaryFolder tmp;
  recordCalibration(s, tmp / "session");
  const ToolRun run = runTool(tmp, "calibrate '" + (tmp / "session") + "' --output '" + (tmp / "model.json") + "'");
  ASSERT_EQ(run.status, 0) << run.err;
  const double error = predictionError(s, tmp / "model.json");
  EXPECT_LE(error, 0.3) << s.name;
  ::testing::Test::RecordProperty("prediction_error_px", std::to_string(error));
}
} // namespace

TEST_F(ProjectiveTool, TagSessionOfTheViper850CalibratesWithinAThirdOfAPixel)
{
  expectCalibrated(viperEyeToHand());
}

TEST_F(ProjectiveTool, TagSessionOfThePrismaticArmCalibratesWithinAThirdOfAPixel)
{
  expectCalibrated(rrprrrEyeToHand());
}

TEST_F(ProjectiveTool, CheckPassesTheSameCellAndNamesTheBumpedCamera)
{
  const ArmSetup s = viperEyeToHand();
  TemporaryFolder tmp;
  recordCalibration(s, tmp / "session");
  ASSERT_EQ(runTool(tmp, "calibrate '" + (tmp / "session") + "' --output '" + (tmp / "model.json") + "'").status, 0);
  const vpHomogeneousMatrix bump(0.01, 0.0, 0.0, 0.0, vpMath::rad(2.0), 0.0); // 1 cm and 2 deg
  const char *names[3] = {"unmoved", "left", "right"};
  for (int c = 0; c < 3; ++c) {
    vpSimulatorStereoCell cell =
        makeCell(s, c == 1 ? bump : vpHomogeneousMatrix(), c == 2 ? bump : vpHomogeneousMatrix());
    const std::string folder = tmp / names[c];
    {
      vpProjectiveSessionWriter writer(folder, s.jointTypes());
      ASSERT_TRUE(moveTo(cell, s.qRef));
      record(cell, writer, vpProjectiveSession::ZERO);
      vpUniRand rng(31 + c);
      for (int k = 0; k < 4; ++k) {
        ASSERT_EQ(randomPose(s, cell, rng).getRows(), s.n());
        record(cell, writer, vpProjectiveSession::OBSERVATION);
      }
    }
    const ToolRun check = runTool(tmp, "check '" + (tmp / "model.json") + "' '" + folder + "'");
    if (c == 0) {
      EXPECT_EQ(check.status, 0) << check.out << check.err;
    } else {
      EXPECT_EQ(check.status, 3) << names[c] << ": " << check.out << check.err;
      EXPECT_NE(check.out.find(std::string(names[c]) + " camera"), std::string::npos) << check.out;
    }
  }
}

// record writes the rendered cell's acquisition session; calibrate turns it into a model that check finds in agreement
// with the same session; report --plots draws the model's marker paths.
TEST_F(ProjectiveTool, RecordCalibrateCheckAndReportTheRenderedCell)
{
  TemporaryFolder tmp;
  const ToolRun record = runTool(tmp, "record '" + (tmp / "cell") + "' --observations 2");
  ASSERT_EQ(record.status, 0) << record.err;
  EXPECT_NE(record.out.find("recorded "), std::string::npos) << record.out;
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "cell");
  EXPECT_EQ(session.getNumberOfFrames(vpProjectiveSession::ZERO), 1u);
  EXPECT_GE(session.getNumberOfFrames(vpProjectiveSession::TRIAL), 12u);
  EXPECT_GE(session.getNumberOfFrames(vpProjectiveSession::OBSERVATION), 2u);
  const ToolRun calibrate = runTool(tmp, "calibrate '" + (tmp / "cell") + "' --output '" + (tmp / "model.json") + "'");
  ASSERT_EQ(calibrate.status, 0) << calibrate.err;
  const ToolRun check = runTool(tmp, "check '" + (tmp / "model.json") + "' '" + (tmp / "cell") + "'");
  EXPECT_EQ(check.status, 0) << check.out << check.err;
  // The plots (gnuplot): without the session the paths alone; with it, over the zero frame's images (a 640 x 480
  // grey picture in the figure: many more pixels drawn), with the acquired ranges in the legend.
  unsigned int drawn[2][2] = {{0, 0}, {0, 0}}; // [session][side]: pixels that are not the white background
  for (int withSession = 0; withSession < 2; ++withSession) {
    const std::string folder = tmp / (withSession ? "plots-session" : "plots");
    const ToolRun report = runTool(tmp, "report '" + (tmp / "model.json") + "' --plots '" + folder + "'" +
                                            (withSession ? " --session '" + (tmp / "cell") + "'" : std::string()));
    ASSERT_EQ(report.status, 0) << report.err;
    for (int side = 0; side < 2; ++side) {
      vpImage<vpRGBa> I;
      vpImageIo::read(I, folder + "/joint-paths-" + (side == 0 ? "left" : "right") + ".png");
      EXPECT_EQ(I.getWidth(), 1200u);
      for (unsigned int k = 0; k < I.getSize(); ++k) {
        drawn[withSession][side] += I.bitmap[k] == vpRGBa(255, 255, 255) ? 0 : 1;
      }
      EXPECT_GT(drawn[withSession][side], 1000u) << side;
    }
    std::ifstream script((folder + "/joint-paths-left.gnuplot").c_str());
    const std::string text((std::istreambuf_iterator<char>(script)), std::istreambuf_iterator<char>());
    EXPECT_EQ(text.find("joint 0: acquired") != std::string::npos, withSession == 1) << text;
    EXPECT_EQ(text.find("measured (o)") != std::string::npos, withSession == 1) << text;
  }
  EXPECT_GT(drawn[1][0], drawn[0][0] + 640u * 480u / 2);
  // A folder that already holds a session is never overwritten.
  EXPECT_EQ(runTool(tmp, "record '" + (tmp / "cell") + "'").status, 1);
}
