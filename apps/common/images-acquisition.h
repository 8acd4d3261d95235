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
  \file images-acquisition.h
  \brief The image apps' steps on a Session (images.h): the acquisition from tracked images
  (the main job's trials, or vpProjectiveAcquisitionProcedure on the session's arm as a vpRobot), the prediction
  error of the tracked markers, and the target taught by showing.
*/

#ifndef _app_projective_images_acquisition_h_
#define _app_projective_images_acquisition_h_

#include <iostream>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>

#include <visp3/core/vpMatrix.h>
#include <visp3/robot/vpRobot.h>

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpStereoDotTracker.h>

#include "paper-world.h"
#include "images-view.h"
#include "images.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
/*!
  The start of an acquisition from images: the arm at the zero reference with every marker lit, the user's clicks on
  the 7 markers, the tracker's state there kept in \e zeroState.
*/
inline void clickAtZeroReference(Session &session, TrackingAccuracy &accuracy, vpStereoDotTracker &zeroState,
                                 bool verbose)
{
  std::vector<unsigned int> all(session.world.arm.getToolMarkers().size());
  std::iota(all.begin(), all.end(), 0u);
  session.q = vpColVector(session.world.arm.getNumberOfJoints(), 0.0);
  session.lit = all;
  session.caption = "acquisition: zero reference";
  session.grab();
  session.click(all);
  accuracy.add(session.world, session.q, session.tracker, session.markers);
  zeroState = session.tracker;
  if (verbose) {
    std::cout << "    markers 0-6 clicked once at the zero reference (simulated clicks, refined by vpDot2)\n";
  }
}

//! [Acquisition]
/*!
  Acquisition from images (projective-images.cpp, with the main job's trials): the user clicks the 7
  markers at the zero reference; each trial motion is then tracked from there, and ends at its last good frame if the
  tracker loses a marker. Between trials the arm drives back to the zero reference, where the tracker restarts from
  its zero-reference state (\e zeroState).
*/
inline vpProjectiveRobot acquireFromImages(Session &session, TrackingAccuracy &accuracy, vpStereoDotTracker &zeroState,
                                           bool verbose)
{
  const unsigned int n = session.world.arm.getNumberOfJoints();
  clickAtZeroReference(session, accuracy, zeroState, verbose);
  std::vector<TrialMotion> trials;
  session.accuracy = &accuracy;
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      const double planned = sign * vpMath::rad(session.world.trialDeg[i]);
      session.caption = "acquisition: joint " + std::to_string(i);
      session.q = vpColVector(n, 0.0); // back at the zero reference: a new frame, tracked from there
      session.tracker = zeroState;
      session.grab();
      if (!session.tracker.track(session.Ileft, session.Iright, 0.0)) {
        throw vpException(vpException::fatalError, "acquisition at the zero reference: " + session.tracker.getReport());
      }
      vpColVector qTrial(n, 0.0);
      qTrial[i] = planned;
      const MoveResult r = session.move(qTrial);
      const double amount = session.q[i];
      if (amount == 0.0) {
        throw vpException(vpException::fatalError, "joint " + std::to_string(i) + " could not move: " + r.failure);
      }
      if (verbose) {
        std::ostringstream os;
        os << std::fixed << std::setprecision(1) << std::showpos << "    joint " << i << ": " << vpMath::deg(amount)
           << " deg in " << std::noshowpos << r.frames << " frames";
        if (!r.complete) {
          os << ", reduced from " << std::showpos << vpMath::deg(planned) << " deg: " << r.failure;
        }
        std::cout << os.str() << "\n";
      }
      trials.push_back({i, amount, session.tracker.getLeftPoints(), session.tracker.getRightPoints()});
    }
  }
  session.accuracy = nullptr;
  // As in the main job, with tracked centres for noisy projections: F with inliers within 1 px, calibrate().
  return calibrateFromTrials(n, zeroState.getLeftPoints(), zeroState.getRightPoints(), trials, 1.0);
}
//! [Acquisition]

//! [Session robot]
//! The session's arm as a ViSP robot: its joints read by getPosition(), driven by setPosition() (Session::move()).
class SessionRobot : public vpRobot
{
public:
  explicit SessionRobot(Session &session) : m_session(session), m_lastMove() { nDof = session.q.size(); }
  void getPosition(const vpRobot::vpControlFrameType, vpColVector &q) override { q = m_session.q; }
  //! Drives the arm to \e q frame by frame; stops at the last frame where every marker was tracked.
  void setPosition(const vpRobot::vpControlFrameType, const vpColVector &q) override { m_lastMove = m_session.move(q); }
  //! Whether the last motion kept every marker tracked.
  bool tracked() const { return m_lastMove.complete; }
  void get_eJe(vpMatrix &eJe) override { eJe.resize(6, nDof, true); } // not used by the acquisition
  void get_fJe(vpMatrix &fJe) override { fJe.resize(6, nDof, true); }
  void getDisplacement(const vpRobot::vpControlFrameType, vpColVector &d) override { d.resize(nDof, true); }
  void init() override {}
  void setVelocity(const vpRobot::vpControlFrameType, const vpColVector &) override {}

private:
  Session &m_session;
  MoveResult m_lastMove;
};
//! [Session robot]

//! [Acquisition procedure]
/*!
  Acquisition from images by vpProjectiveAcquisitionProcedure (projective-bumped-camera.cpp): the user
  clicks the 7 markers at the zero reference; the procedure then moves each joint alone in 2 deg steps both ways,
  up to 45 deg, a tracked marker 10 px from an image border or a marker lost, the arm tracked frame by frame
  (SessionRobot); F from the tracked centres of every step (inliers within 1 px); the model calibrated. No trial
  amount is chosen by hand.
*/
inline vpProjectiveRobot acquireByProcedure(Session &session, TrackingAccuracy &accuracy, vpStereoDotTracker &zeroState,
                                            bool verbose)
{
  const unsigned int n = session.world.arm.getNumberOfJoints();
  clickAtZeroReference(session, accuracy, zeroState, verbose);
  SessionRobot arm(session);
  vpProjectiveAcquisitionProcedure procedure(
      [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        left = session.tracker.getLeftPoints();
        right = session.tracker.getRightPoints();
        return arm.tracked(); // the arm stopped short of the step: a marker was lost
      },
      session.world.rig.getWidth(), session.world.rig.getHeight());
  procedure.setMaxAmounts(vpColVector(n, vpMath::rad(45.0)));
  procedure.setSteps(vpColVector(n, vpMath::rad(2.0)));
  procedure.setEpipolarThreshold(1.0);
  // The session's arm moves by setPosition() (frame by frame, tracked), not by joint velocities.
  procedure.setMotionControl(vpProjectiveAcquisitionProcedure::POSITION_CONTROL);
  procedure.setOutput(verbose ? &std::cout : nullptr);
  session.accuracy = &accuracy;
  session.caption = "acquisition";
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(n, vpProjectiveRobot::REVOLUTE));
  procedure.run(arm, robot);
  session.accuracy = nullptr;
  return robot;
}
//! [Acquisition procedure]

//! RMS per coordinate of the tracked markers minus the model's predictions at q (getPredictionError() on a subset).
inline double trackedPredictionError(const vpProjectiveRobot &robot, const Session &session)
{
  double sum = 0.0;
  for (unsigned int k = 0; k < session.tracker.getNumberOfMarkers(); ++k) {
    vpImagePoint l, r;
    robot.getModel().projectMarker(session.markers[k], session.q, l, r);
    sum += vpImagePoint::sqrDistance(l, session.tracker.getLeftPoint(k)) +
           vpImagePoint::sqrDistance(r, session.tracker.getRightPoint(k));
  }
  return std::sqrt(sum / (4.0 * session.tracker.getNumberOfMarkers()));
}

//! [Teaching]
/*!
  Teaching by showing: the arm, at the zero reference with the servo's markers tracked with the model, is driven by
  the start to the target, where \e left, \e right (s*) are the tracked centres, then back to the start. Returns why
  it failed (empty if it did not).
*/
inline std::string teachTarget(Session &session, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)
{
  // The direct joint-space line from the zero reference to the target turns the face of markers 0-2 edge-on, and
  // markers 1 and 2 would cross in both images: the arm goes by the start.
  session.caption = "teaching: to the start, then the arm is shown the target";
  MoveResult r = session.move(degToRad(session.world.startDeg));
  if (r.complete) {
    r = session.move(degToRad(session.world.targetDeg));
  }
  if (!r.complete) {
    return "while showing the target: " + r.failure;
  }
  left = session.tracker.getLeftPoints();
  right = session.tracker.getRightPoints();
  session.showTarget(left, right);
  session.caption = "to the start";
  r = session.move(degToRad(session.world.startDeg));
  return r.complete ? std::string() : "while moving to the start: " + r.failure;
}
//! [Teaching]
} // namespace app

#endif
