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
  \file tutorial-projective-images.h
  \brief The camera side of tutorial-projective-servo-images.cpp: one seed's session (the arm at q, the rendered
  stereo frames of its lit markers, the vpStereoDotTracker that follows them, the simulated user's clicks), the
  motion of the arm imaged frame by frame, the tracking accuracy against the ground truth, and the live view.
*/

#ifndef _tutorial_projective_images_h_
#define _tutorial_projective_images_h_

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <iostream>
#include <numeric>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/gui/vpDisplayX.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorMarkerRenderer.h>
#include <visp3/projective/vpStereoDotTracker.h>

#include "tutorial-projective-common.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace tutorial
{
//! [Image model]
//! How the cameras grab frames while the arm moves, and how the servo is judged on the images. What they see is
//! vpSimulatorMarkerRenderer's default: 6 mm lit balls, blur 0.8 px, sensor noise 4 grey levels, 8 x 8 rays per pixel.
struct ImageModel {
  double pixelsPerFrame = 8.0;       // the frame rate: blobs move by about this much between frames
  double firstStepDeg = 0.05;        // joint step of a motion's first frame, before any image velocity is known
  double convergenceThreshold = 0.2; // px: RMS(s - s*) for convergence, the main job's 2 sigma at 0.1 px
};
//! [Image model]

//! RMS of the tracked centres minus the true projections (px per coordinate): only reported, never used.
struct TrackingAccuracy {
  double sumSquares = 0.0, largest = 0.0;
  unsigned int coordinates = 0;
  //! Accounts one stereo frame of the markers \e markers at \e q; returns its errors (u, v, u', v' per marker).
  vpColVector add(const PaperWorld &world, const vpColVector &q, const vpStereoDotTracker &tracker,
                  const std::vector<unsigned int> &markers)
  {
    const std::vector<vpColVector> X = world.arm.getMarkers(q);
    vpColVector errors(4 * tracker.getNumberOfMarkers());
    for (unsigned int k = 0; k < tracker.getNumberOfMarkers(); ++k) {
      vpImagePoint l, r;
      world.rig.project(X[markers[k]], l, r);
      const vpImagePoint dl = tracker.getLeftPoint(k) - l, dr = tracker.getRightPoint(k) - r;
      errors[4 * k] = dl.get_u();
      errors[4 * k + 1] = dl.get_v();
      errors[4 * k + 2] = dr.get_u();
      errors[4 * k + 3] = dr.get_v();
    }
    sumSquares += errors.sumSquare();
    coordinates += errors.size();
    largest = std::max(largest, std::max(errors.getMaxValue(), -errors.getMinValue()));
    return errors;
  }
  //! Accounts another accuracy.
  void add(const TrackingAccuracy &other)
  {
    sumSquares += other.sumSquares;
    coordinates += other.coordinates;
    largest = std::max(largest, other.largest);
  }
  //! RMS error (px).
  double rms() const { return coordinates > 0 ? std::sqrt(sumSquares / coordinates) : 0.0; }
};

//! [Viewer]
//! Both images live (seed 1, with an X display): the tracked blobs, the taught target and the servo's trajectory.
class Viewer
{
public:
  Viewer(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright)
#if defined(VISP_HAVE_X11)
      : m_left(Ileft, 0, 0, "Left camera"), m_right(Iright, static_cast<int>(Ileft.getWidth()) + 20, 0, "Right camera")
#endif
  {
    (void)Iright;
  }
  //! Shows the last stereo frame with \e caption.
  void show(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
            const vpStereoDotTracker &tracker, const std::string &caption)
  {
    for (unsigned int c = 0; c < 2; ++c) {
      const vpImage<unsigned char> &I = c == 0 ? Ileft : Iright;
      vpDisplay::display(I);
      vpDisplay::displayText(I, 20, 20, caption, vpColor::yellow);
      for (const vpImagePoint &ip : target[c]) {
        vpDisplay::displayCross(I, ip, 14, vpColor::red, 2);
      }
      for (const std::vector<vpImagePoint> &points : trail[c]) {
        for (const vpImagePoint &ip : points) {
          vpDisplay::displayPoint(I, ip, vpColor::cyan, 2);
        }
      }
    }
    tracker.display(Ileft, Iright);
    vpDisplay::flush(Ileft);
    vpDisplay::flush(Iright);
  }
  std::vector<vpImagePoint> target[2];             //!< s* in each image
  std::vector<std::vector<vpImagePoint>> trail[2]; //!< the servo's trajectory in each image

private:
#if defined(VISP_HAVE_X11)
  vpDisplayX m_left, m_right;
#endif
};
//! [Viewer]

//! [Bump]
/*!
  \e rig with camera \e camera (0 left, 1 right) moved by \e d, expressed in that camera's frame (a knock of 2 deg
  and 1 cm, say): the other camera stays where it was.
*/
inline vpSimulatorStereoRig bumpedRig(const vpSimulatorStereoRig &rig, unsigned int camera,
                                      const vpHomogeneousMatrix &d)
{
  vpHomogeneousMatrix wMl = rig.get_wMl(), rMl = rig.get_rMl();
  if (camera == 0) {
    wMl = wMl * d; // wMr = wMl rMl^-1 unchanged
    rMl = rMl * d;
  } else {
    rMl = d.inverse() * rMl; // wMr <- wMr d
  }
  return vpSimulatorStereoRig(rig.getLeftCameraParameters(), rig.getRightCameraParameters(), rMl, wMl, rig.getWidth(),
                              rig.getHeight());
}
//! [Bump]

//! How a motion imaged frame by frame ended.
struct MoveResult {
  bool complete = true; // reached the end of the segment
  std::string failure;  // otherwise, why the tracking stopped
  unsigned int frames = 0;
};

//! [Session]
/*!
  One seed's run of the experiment: the arm at joint values q, the rig's cameras (vpSimulatorMarkerRenderer, noise
  seeded by the seed), the seed's simulated clicks, the lit markers, the last images and the tracker.
*/
struct Session {
  Session(const PaperWorld &w, const ImageModel &m, unsigned int seed)
      : world(w), model(m), renderer(w.rig, static_cast<long>(seed)), clicks(static_cast<uint64_t>(seed), 2),
        seed(static_cast<long>(seed)), Ileft(w.rig.getHeight(), w.rig.getWidth(), 0),
        Iright(w.rig.getHeight(), w.rig.getWidth(), 0), q(w.arm.getNumberOfJoints(), 0.0)
  {
  }

  //! Grabs a stereo frame of the arm at q: the images of its lit markers.
  void grab()
  {
    const std::vector<vpColVector> markers = world.arm.getMarkers(q);
    std::vector<vpColVector> X;
    for (unsigned int k : lit) {
      X.push_back(markers[k]);
    }
    renderer.render(X, Ileft, Iright);
    ++frames;
  }

  //! [Click]
  /*!
    The one use of the ground truth for image measurements, standing for a user who clicks each marker of \e indices
    once in both images (vpStereoDotTracker::initTrackingByClick() with a display): a click up to 2 px off the
    marker's true image (seeded), inside the blob, that the tracker's vpDot2 refines. The new tracker has no model
    (withModel is left to the caller).
  */
  void click(const std::vector<unsigned int> &indices)
  {
    const std::vector<vpColVector> X = world.arm.getMarkers(q);
    std::vector<vpImagePoint> clickLeft, clickRight;
    for (unsigned int k : indices) {
      vpImagePoint l, r;
      renderer.getStereoRig().project(X[k], l, r); // the cameras as they are now (see bump())
      clickLeft.push_back(l + vpImagePoint(clicks.uniform(-2.0, 2.0), clicks.uniform(-2.0, 2.0)));
      clickRight.push_back(r + vpImagePoint(clicks.uniform(-2.0, 2.0), clicks.uniform(-2.0, 2.0)));
    }
    tracker = vpStereoDotTracker();
    tracker.initTracking(Ileft, Iright, clickLeft, clickRight);
    markers = indices;
  }
  //! [Click]

  /*!
    A knock on camera \e camera (0 left, 1 right): from the next grab() on, the cameras are bumpedRig() of the
    present ones by \e d. The world, which the rest of the program sees, is not changed: the truth moved, not the
    arm.
  */
  void bump(unsigned int camera, const vpHomogeneousMatrix &d)
  {
    renderer = vpSimulatorMarkerRenderer(bumpedRig(renderer.getStereoRig(), camera, d), seed + 1000);
  }

  //! Shows s* in the live view, if any.
  void showTarget(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
  {
    if (viewer != nullptr) {
      viewer->target[0] = left;
      viewer->target[1] = right;
    }
  }
  //! Adds an iteration's features to the servo's trajectory in the live view, if any.
  void showTrail(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
  {
    if (viewer != nullptr) {
      viewer->trail[0].push_back(left);
      viewer->trail[1].push_back(right);
    }
  }

  //! [Move]
  /*!
    Drives the arm along the joint-space segment from q to \e qTo while the cameras grab frames and the tracker
    follows the blobs: predicted by the model where the tracker has one (vpStereoDotTracker::setRobot()), else at
    constant image velocity. The joint step starts at ImageModel::firstStepDeg and adapts so that the blobs move by
    about ImageModel::pixelsPerFrame between frames. The last frame is at \e qTo. If the tracker loses a marker, the
    arm stops at the last good frame: q and the tracker are those of that frame.
  */
  MoveResult move(const vpColVector &qTo)
  {
    MoveResult result;
    const vpColVector qFrom = q, dq = qTo - qFrom;
    double span = 0.0;
    for (unsigned int i = 0; i < dq.size(); ++i) {
      span = std::max(span, std::abs(dq[i]));
    }
    double s = 0.0, step = span > 0.0 ? std::min(1.0, vpMath::rad(model.firstStepDeg) / span) : 1.0;
    double previousStep = 0.0;
    while (s < 1.0) {
      const double next = std::min(1.0, s + step);
      const vpStereoDotTracker lastGood = tracker;
      q = qFrom + dq * next;
      grab();
      ++result.frames;
      const bool tracked = withModel
                               ? tracker.track(Ileft, Iright, q)
                               : tracker.track(Ileft, Iright, previousStep > 0.0 ? (next - s) / previousStep : 0.0);
      if (!tracked) {
        const std::string report = tracker.getReport();
        result.failure = report.substr(0, report.find('\n')); // the first marker lost says why
        tracker = lastGood;
        q = qFrom + dq * s;
        result.complete = false;
        return result;
      }
      if (accuracy != nullptr) {
        accuracy->add(world, q, tracker, markers);
      }
      if (viewer != nullptr) {
        viewer->show(Ileft, Iright, tracker, caption);
      }
      previousStep = next - s;
      s = next;
      // Next step: as large as keeps the blobs within pixelsPerFrame, growing at most twofold.
      step = previousStep * std::min(2.0, model.pixelsPerFrame / std::max(tracker.getLargestMotion(), 1e-3));
    }
    return result;
  }
  //! [Move]

  const PaperWorld &world;
  ImageModel model;
  vpSimulatorMarkerRenderer renderer;
  vpUniRand clicks;
  long seed;
  vpImage<unsigned char> Ileft, Iright;
  vpColVector q;
  std::vector<unsigned int> lit;        // the markers switched on
  vpStereoDotTracker tracker;           // the markers clicked, then followed
  std::vector<unsigned int> markers;    // the simulator's marker of each tracked marker (for the accuracy only)
  bool withModel = false;               // the tracker has the model: it predicts the blobs from it
  TrackingAccuracy *accuracy = nullptr; // where to account the frames, if anywhere
  Viewer *viewer = nullptr;
  std::string caption;
  unsigned int frames = 0;
};
//! [Session]

//! [Acquisition]
/*!
  Acquisition from images (tutorial-projective-servo-images.cpp and tutorial-projective-bumped-camera.cpp): the user
  clicks the 7 markers at the zero reference; each trial motion is then tracked
  from there, and ends at its last good frame if the tracker loses a marker. Between trials the arm drives back to the
  zero reference, where the tracker restarts from its zero-reference state (\e zeroState).
*/
inline vpProjectiveRobot acquireFromImages(Session &session, TrackingAccuracy &accuracy, vpStereoDotTracker &zeroState,
                                           bool verbose)
{
  const unsigned int n = session.world.arm.getNumberOfJoints();
  std::vector<unsigned int> all(session.world.arm.getToolMarkers().size());
  std::iota(all.begin(), all.end(), 0u);
  session.q = vpColVector(n, 0.0);
  session.lit = all;
  session.caption = "acquisition: zero reference";
  session.grab();
  session.click(all);
  accuracy.add(session.world, session.q, session.tracker, session.markers);
  zeroState = session.tracker;
  if (verbose) {
    std::cout << "    markers 0-6 clicked once at the zero reference (simulated clicks, refined by vpDot2)\n";
  }
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
  // As in the main tutorial, with tracked centres for noisy projections: F with inliers within 1 px, calibrate().
  return calibrateFromTrials(n, zeroState.getLeftPoints(), zeroState.getRightPoints(), trials, 1.0);
}
//! [Acquisition]

//! RMS per coordinate of the tracked markers minus the model's predictions at q (getPredictionError() on a subset).
inline double trackedPredictionError(const vpProjectiveRobot &robot, const Session &session)
{
  double sum = 0.0;
  for (unsigned int k = 0; k < session.tracker.getNumberOfMarkers(); ++k) {
    vpImagePoint l, r;
    robot.projectMarker(session.markers[k], session.q, l, r);
    sum += vpImagePoint::sqrDistance(l, session.tracker.getLeftPoint(k)) +
           vpImagePoint::sqrDistance(r, session.tracker.getRightPoint(k));
  }
  return std::sqrt(sum / (4.0 * session.tracker.getNumberOfMarkers()));
}

//! A knock of \e deg degrees about a random axis and \e mm millimetres along a random direction (seeded).
inline vpHomogeneousMatrix randomBump(double deg, double mm, unsigned int seed)
{
  vpUniRand rng(seed + 100);
  vpColVector axis(3), direction(3);
  for (unsigned int a = 0; a < 3; ++a) {
    axis[a] = rng.uniform(-1.0, 1.0);
    direction[a] = rng.uniform(-1.0, 1.0);
  }
  axis *= vpMath::rad(deg) / axis.frobeniusNorm();
  direction *= 0.001 * mm / direction.frobeniusNorm();
  return vpHomogeneousMatrix(vpTranslationVector(direction[0], direction[1], direction[2]),
                             vpThetaUVector(axis[0], axis[1], axis[2]));
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
} // namespace tutorial

#endif
