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
  Tests of vpStereoDotTracker on images rendered by vpSimulatorMarkerRenderer (seeded): tracking accuracy against the
  rig's projections under noise and blur, an occluded marker that reappears, two blobs that cross, the projective
  model's prediction, automatic initialisation, and misuse.
*/

#include <cmath>
#include <iostream>
#include <vector>

#include <gtest/gtest.h>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorMarkerRenderer.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/projective/vpStereoDotTracker.h>

#include "vpProjectiveTestTools.h"

namespace
{
using vpProjectiveTest::point3;
using vpProjectiveTest::testLog;
using vpProjectiveTest::throwsProjective;

//! The paper's world: rig, PUMA-like arm with 7 gripper markers, a renderer, and the rig of the true F.
struct World {
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  vpProjectiveStereoRig trueRig;
  vpImage<unsigned char> Il, Ir;
  World() { trueRig.setFundamentalMatrix(rig.getFundamentalMatrix()); }

  void truth(const std::vector<vpColVector> &X, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)
  {
    left.resize(X.size());
    right.resize(X.size());
    for (size_t k = 0; k < X.size(); ++k) {
      rig.project(X[k], left[k], right[k]);
    }
  }
  //! Renders the arm's markers at joints \e q into Il, Ir and gives their true pixels; returns the markers (world).
  std::vector<vpColVector> renderArm(vpSimulatorMarkerRenderer &renderer, const vpColVector &q,
                                     std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)
  {
    const std::vector<vpColVector> X = arm.getMarkers(q);
    renderer.render(X, Il, Ir);
    truth(X, left, right);
    return X;
  }
};

//! The world with the arm at q = 0 rendered by a renderer seeded with \e seed: images in w.Il, w.Ir, true pixels.
struct RenderedAtZero {
  explicit RenderedAtZero(long seed) : w(), renderer(w.rig, seed), left(), right()
  {
    w.renderArm(renderer, vpColVector(6, 0.0), left, right);
  }
  World w;
  vpSimulatorMarkerRenderer renderer;
  std::vector<vpImagePoint> left, right;
};

//! Joint values along a smooth path: q(t) = t * qEnd (deg), t in [0, 1].
vpColVector along(double t)
{
  const double qEnd[6] = {12, 6, -8, 15, 20, 25};
  vpColVector q(6);
  for (unsigned int i = 0; i < 6; ++i) {
    q[i] = vpMath::rad(t * qEnd[i]);
  }
  return q;
}

//! Errors (px) of the found markers of \e tracker against the truth, accumulated in \e sum2 and \e largest.
void accumulate(const vpStereoDotTracker &tracker, const std::vector<vpImagePoint> &left,
                const std::vector<vpImagePoint> &right, double &sum2, unsigned int &count, double &largest)
{
  for (unsigned int k = 0; k < tracker.getNumberOfMarkers(); ++k) {
    if (tracker.getState(k) == vpStereoDotTracker::MARKER_LOST) {
      continue;
    }
    const unsigned int m = tracker.getMarkerIndices()[k];
    const vpImagePoint dl = tracker.getLeftPoint(k) - left[m], dr = tracker.getRightPoint(k) - right[m];
    for (double e : {dl.get_u(), dl.get_v(), dr.get_u(), dr.get_v()}) {
      sum2 += e * e;
      largest = std::max(largest, std::abs(e));
      ++count;
    }
  }
}

//! Tracks the 7 markers along the smooth path, clicks 1.5 px off at the start; returns the RMS error (px).
double trackPath(vpSimulatorMarkerRenderer &renderer, double &largest)
{
  World w;
  std::vector<vpImagePoint> left, right;
  w.truth(w.arm.getMarkers(along(0)), left, right);
  renderer.render(w.arm.getMarkers(along(0)), w.Il, w.Ir);
  std::vector<vpImagePoint> clickLeft, clickRight;
  for (size_t k = 0; k < left.size(); ++k) {
    clickLeft.push_back(left[k] + vpImagePoint(1.5, -1.0));
    clickRight.push_back(right[k] + vpImagePoint(-1.0, 1.5));
  }
  vpStereoDotTracker tracker;
  tracker.setStereoRig(w.trueRig);
  tracker.initTracking(w.Il, w.Ir, clickLeft, clickRight);
  double sum2 = 0.0;
  unsigned int count = 0;
  largest = 0.0;
  for (unsigned int f = 1; f <= 60; ++f) {
    const std::vector<vpColVector> X = w.arm.getMarkers(along(f / 60.0));
    renderer.render(X, w.Il, w.Ir);
    EXPECT_TRUE(tracker.track(w.Il, w.Ir)) << "frame " << f << ": " << tracker.getReport();
    w.truth(X, left, right);
    accumulate(tracker, left, right, sum2, count, largest);
  }
  return std::sqrt(sum2 / count);
}

/*!
  A calibrated model of the PUMA from noise-free projections (zero reference and the paper's trials both ways), in
  the frame of the true F.
*/
vpProjectiveRobot calibratedModel(World &w)
{
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  robot.setStereoRig(w.trueRig);
  std::vector<vpImagePoint> left, right;
  w.truth(w.arm.getMarkers(vpColVector(6, 0.0)), left, right);
  robot.setZeroReference(left, right);
  const double trialDeg[6] = {30, 20, 30, 40, 60, 60};
  for (unsigned int i = 0; i < 6; ++i) {
    for (double sign : {0.5, -0.5}) {
      vpColVector q(6, 0.0);
      q[i] = vpMath::rad(sign * trialDeg[i]);
      w.truth(w.arm.getMarkers(q), left, right);
      robot.addTrialMotion(i, q[i], left, right);
    }
  }
  robot.calibrate();
  return robot;
}
} // namespace

TEST(StereoDotTracker, TracksRenderedMarkersAccurately)
{
  World w;
  vpSimulatorMarkerRenderer renderer(w.rig, 1); // 6 mm balls, blur 0.8 px, noise 4 grey levels
  double largest = 0.0;
  const double rms = trackPath(renderer, largest);
  testLog() << "tracking accuracy, default rendering: " << rms << " px RMS, largest " << largest << " px\n";
  EXPECT_LT(rms, 0.12);
  EXPECT_LT(largest, 0.5);
}

TEST(StereoDotTracker, ToleratesStrongNoiseAndBlur)
{
  World w;
  vpSimulatorMarkerRenderer renderer(w.rig, 2);
  renderer.setNoise(12.0);
  renderer.setBlur(1.5);
  double largest = 0.0;
  const double rms = trackPath(renderer, largest);
  testLog() << "tracking accuracy, noise 12 grey levels and blur 1.5 px: " << rms << " px RMS, largest " << largest
            << " px\n";
  EXPECT_LT(rms, 0.3);
  EXPECT_LT(largest, 1.2);
}

TEST(StereoDotTracker, OccludedMarkerIsLostThenRedetected)
{
  World w;
  vpSimulatorMarkerRenderer renderer(w.rig, 3);
  std::vector<vpImagePoint> left, right;
  w.truth(w.arm.getMarkers(along(0)), left, right);
  renderer.render(w.arm.getMarkers(along(0)), w.Il, w.Ir);
  vpStereoDotTracker tracker;
  tracker.setStereoRig(w.trueRig);
  tracker.initTracking(w.Il, w.Ir, left, right);
  bool redetected = false;
  double sum2 = 0.0, largest = 0.0;
  unsigned int count = 0;
  for (unsigned int f = 1; f <= 40; ++f) {
    std::vector<vpColVector> X = w.arm.getMarkers(along(f / 60.0));
    w.truth(X, left, right);
    const bool hidden = f >= 10 && f <= 16;
    if (hidden) {
      X.erase(X.begin() + 3); // marker 3 occluded
    }
    renderer.render(X, w.Il, w.Ir);
    tracker.track(w.Il, w.Ir);
    for (unsigned int k = 0; k < 7; ++k) {
      if (k != 3) {
        ASSERT_NE(tracker.getState(k), vpStereoDotTracker::MARKER_LOST) << "frame " << f << ": " << tracker.getReport();
      }
    }
    if (hidden) {
      EXPECT_EQ(tracker.getState(3), vpStereoDotTracker::MARKER_LOST) << "frame " << f;
      EXPECT_FALSE(tracker.getFailure(3).empty());
    } else if (f > 16) {
      redetected = redetected || tracker.getState(3) == vpStereoDotTracker::MARKER_REDETECTED;
      EXPECT_NE(tracker.getState(3), vpStereoDotTracker::MARKER_LOST) << "frame " << f << ": " << tracker.getReport();
    }
    accumulate(tracker, left, right, sum2, count, largest);
  }
  EXPECT_TRUE(redetected);
  EXPECT_LT(std::sqrt(sum2 / count), 0.15);
  EXPECT_LT(largest, 0.5); // no wrong measurement of the occluded marker
}

TEST(StereoDotTracker, CrossingBlobsKeepTheirIdentity)
{
  World w;
  vpSimulatorMarkerRenderer renderer(w.rig, 4);
  // Two balls at 1 m move in opposite directions along the world x axis, 1.2 mm apart in y: their blobs (10 px wide)
  // overlap while they cross, in both images.
  const unsigned int frames = 60;
  auto points = [&](unsigned int f) {
    const double t = -0.05 + 0.1 * f / frames;
    return std::vector<vpColVector>{point3(t, 0.0, 0.0), point3(-t, 0.0012, 0.0)};
  };
  std::vector<vpImagePoint> left, right;
  w.truth(points(0), left, right);
  renderer.render(points(0), w.Il, w.Ir);
  vpStereoDotTracker tracker;
  tracker.setStereoRig(w.trueRig);
  tracker.initTracking(w.Il, w.Ir, left, right);
  unsigned int lostFrames = 0;
  double sum2 = 0.0, largest = 0.0;
  unsigned int count = 0;
  for (unsigned int f = 1; f <= frames; ++f) {
    renderer.render(points(f), w.Il, w.Ir);
    w.truth(points(f), left, right);
    tracker.track(w.Il, w.Ir);
    lostFrames += tracker.getState(0) == vpStereoDotTracker::MARKER_LOST;
    accumulate(tracker, left, right, sum2, count, largest); // whatever is reported as found is right
  }
  EXPECT_GT(lostFrames, 2u);  // lost while they overlap
  EXPECT_LT(lostFrames, 12u); // and found again afterwards
  EXPECT_TRUE(tracker.isTracked()) << tracker.getReport();
  EXPECT_LT(vpImagePoint::distance(tracker.getLeftPoint(0), left[0]), 0.3);
  EXPECT_LT(vpImagePoint::distance(tracker.getRightPoint(1), right[1]), 0.3);
  EXPECT_LT(largest, 0.5);
  testLog() << "crossing: lost for " << lostFrames << " frames, accuracy " << std::sqrt(sum2 / count)
            << " px RMS when found\n";
}

TEST(StereoDotTracker, ModelPredictionRecoversAMarkerAfterAnIrregularMotion)
{
  World w;
  const vpProjectiveRobot robot = calibratedModel(w);
  vpSimulatorMarkerRenderer renderer(w.rig, 5);
  const std::vector<unsigned int> servoMarkers = {0, 1, 2};
  auto lit = [&](const vpColVector &q, bool hide1) {
    const std::vector<vpColVector> X = w.arm.getMarkers(q);
    std::vector<vpColVector> out;
    for (unsigned int k : servoMarkers) {
      if (!(hide1 && k == 1)) {
        out.push_back(X[k]);
      }
    }
    return out;
  };
  vpStereoDotTracker tracker;
  tracker.setRobot(robot, servoMarkers);
  renderer.render(lit(along(0), false), w.Il, w.Ir);
  tracker.initTrackingByDetection(w.Il, w.Ir, along(0));
  std::vector<vpImagePoint> left, right;
  double sum2 = 0.0, largest = 0.0;
  unsigned int count = 0;
  // Forth for 20 frames, marker 1 hidden while the arm turns back: constant velocity would be 40 px off.
  for (unsigned int f = 1; f <= 40; ++f) {
    const double t = f <= 20 ? f / 40.0 : (40 - f) / 40.0;
    const bool hidden = f >= 15 && f <= 25;
    renderer.render(lit(along(t), hidden), w.Il, w.Ir);
    tracker.track(w.Il, w.Ir, along(t));
    w.truth(w.arm.getMarkers(along(t)), left, right);
    EXPECT_EQ(tracker.getState(1) == vpStereoDotTracker::MARKER_LOST, hidden) << "frame " << f;
    EXPECT_NE(tracker.getState(0), vpStereoDotTracker::MARKER_LOST) << tracker.getReport();
    accumulate(tracker, left, right, sum2, count, largest);
  }
  EXPECT_TRUE(tracker.isTracked());
  EXPECT_LT(std::sqrt(sum2 / count), 0.15);
  EXPECT_LT(largest, 0.5);
}

TEST(StereoDotTracker, DetectionPairsTheBlobsByTheEpipolarGeometry)
{
  RenderedAtZero z(6);
  World &w = z.w;
  const std::vector<vpImagePoint> &left = z.left, &right = z.right;
  vpStereoDotTracker tracker;
  tracker.setStereoRig(w.trueRig);
  tracker.initTrackingByDetection(w.Il, w.Ir, 7);
  ASSERT_EQ(tracker.getNumberOfMarkers(), 7u);
  for (unsigned int k = 0; k < 7; ++k) {
    // Marker k is one true marker in both images.
    unsigned int nearest = 0;
    for (unsigned int m = 1; m < 7; ++m) {
      if (vpImagePoint::distance(tracker.getLeftPoint(k), left[m]) <
          vpImagePoint::distance(tracker.getLeftPoint(k), left[nearest])) {
        nearest = m;
      }
    }
    EXPECT_LT(vpImagePoint::distance(tracker.getLeftPoint(k), left[nearest]), 0.3);
    EXPECT_LT(vpImagePoint::distance(tracker.getRightPoint(k), right[nearest]), 0.3);
    if (k > 0) {
      EXPECT_LE(tracker.getLeftPoint(k - 1).get_v(), tracker.getLeftPoint(k).get_v() + 1.0); // raster order
    }
  }
  EXPECT_TRUE(throwsProjective([&] { tracker.initTrackingByDetection(w.Il, w.Ir, 6); },
                               vpProjectiveException::degenerateConfigurationError, "7 bright blobs"));
  EXPECT_EQ(tracker.getNumberOfMarkers(), 7u); // unchanged
}

TEST(StereoDotTracker, DetectionWithTheModelNumbersTheMarkersAsTheModel)
{
  World w;
  const vpProjectiveRobot robot = calibratedModel(w);
  vpSimulatorMarkerRenderer renderer(w.rig, 8);
  const vpColVector q = along(0.7);
  std::vector<vpImagePoint> left, right;
  const std::vector<vpColVector> X = w.renderArm(renderer, q, left, right);
  vpStereoDotTracker tracker;
  tracker.setRobot(robot, {4, 0, 2});
  tracker.initTrackingByDetection(w.Il, w.Ir, q); // the 4 other lit markers are ignored
  ASSERT_EQ(tracker.getNumberOfMarkers(), 3u);
  const unsigned int expected[3] = {4, 0, 2};
  for (unsigned int k = 0; k < 3; ++k) {
    EXPECT_EQ(tracker.getMarkerIndices()[k], expected[k]);
    EXPECT_LT(vpImagePoint::distance(tracker.getLeftPoint(k), left[expected[k]]), 0.3);
    EXPECT_LT(vpImagePoint::distance(tracker.getRightPoint(k), right[expected[k]]), 0.3);
  }
  tracker.keepMarkers({2, 0});
  EXPECT_EQ(tracker.getMarkerIndices(), (std::vector<unsigned int>{2, 4}));
  EXPECT_TRUE(tracker.track(w.Il, w.Ir, q));
}

TEST(StereoDotTracker, MisuseThrowsAndLeavesTheTrackerAsItWas)
{
  RenderedAtZero z(9);
  World &w = z.w;
  const std::vector<vpImagePoint> &left = z.left, &right = z.right;
  vpStereoDotTracker tracker;
  EXPECT_TRUE(
      throwsProjective([&] { tracker.track(w.Il, w.Ir); }, vpProjectiveException::notInitializedError, "initTracking"));
  EXPECT_TRUE(throwsProjective([&] { tracker.initTrackingByClick(w.Il, w.Ir, 7); },
                               vpProjectiveException::notInitializedError, "display"));
  EXPECT_TRUE(throwsProjective([&] { tracker.initTrackingByDetection(w.Il, w.Ir, 7); },
                               vpProjectiveException::notInitializedError, "setStereoRig"));
  EXPECT_TRUE(throwsProjective([&] { tracker.setRobot(vpProjectiveRobot()); },
                               vpProjectiveException::notInitializedError, "calibrate"));
  EXPECT_TRUE(throwsProjective([&] { tracker.setEpipolarThreshold(0.0); }, vpProjectiveException::invalidValueError,
                               "positive"));
  tracker.setStereoRig(w.trueRig);
  tracker.initTracking(w.Il, w.Ir, left, right);
  const std::vector<vpImagePoint> before = tracker.getLeftPoints();

  std::vector<vpImagePoint> shortList(left.begin(), left.begin() + 3);
  EXPECT_TRUE(throwsProjective([&] { tracker.initTracking(w.Il, w.Ir, shortList, right); },
                               vpProjectiveException::dimensionError, "one point per marker"));
  std::vector<vpImagePoint> offBlob = left;
  offBlob[2] = vpImagePoint(10, 10);
  EXPECT_TRUE(throwsProjective([&] { tracker.initTracking(w.Il, w.Ir, offBlob, right); },
                               vpProjectiveException::degenerateConfigurationError, "not on a blob"));
  std::vector<vpImagePoint> twice = left, twiceRight = right;
  twice[1] = twice[0];
  twiceRight[1] = twiceRight[0];
  EXPECT_TRUE(throwsProjective([&] { tracker.initTracking(w.Il, w.Ir, twice, twiceRight); },
                               vpProjectiveException::degenerateConfigurationError, "separate blobs"));
  std::vector<vpImagePoint> swapped = right;
  std::swap(swapped[0], swapped[5]);
  EXPECT_TRUE(throwsProjective([&] { tracker.initTracking(w.Il, w.Ir, left, swapped); },
                               vpProjectiveException::estimationFailedError, "epipolar"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        tracker.keepMarkers({0, 9});
      },
      vpProjectiveException::dimensionError, "does not exist"));
  EXPECT_TRUE(throwsProjective([&] { tracker.track(w.Il, w.Ir, vpColVector(6, 0.0)); },
                               vpProjectiveException::notInitializedError, "setRobot"));
  vpImage<unsigned char> small(100, 100, 0);
  EXPECT_TRUE(
      throwsProjective([&] { tracker.track(small, w.Ir); }, vpProjectiveException::dimensionError, "100 x 100"));
  EXPECT_TRUE(
      throwsProjective([&] { tracker.track(w.Il, w.Ir, -1.0); }, vpProjectiveException::invalidValueError, "ratio"));
  EXPECT_TRUE(throwsProjective([&] { tracker.getState(7); }, vpProjectiveException::dimensionError, "7 markers"));

  ASSERT_EQ(tracker.getNumberOfMarkers(), 7u);
  for (unsigned int k = 0; k < 7; ++k) {
    EXPECT_EQ(tracker.getLeftPoints()[k], before[k]);
  }
  EXPECT_TRUE(tracker.track(w.Il, w.Ir)) << tracker.getReport();
}
