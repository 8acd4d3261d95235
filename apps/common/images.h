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
  \file images.h
  \brief The camera side of the image apps: one seed's session (the arm at q, the rendered stereo frames of its
  lit markers, the vpStereoDotTracker that follows them, the simulated user's clicks), the motion of the arm imaged
  frame by frame, and the knocks of a bumped camera. The steps on a session are in
  images-acquisition.h, the accuracy and the live view in images-view.h.
*/

#ifndef _app_projective_images_h_
#define _app_projective_images_h_

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
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorMarkerRenderer.h>
#include <visp3/projective/vpStereoDotTracker.h>

#include "paper-world.h"
#include "images-view.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
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
      // The clicks drawn j then i: the order g++ evaluated them in as the arguments of one call (C++ leaves it
      // unspecified; the documented figures were measured with g++).
      const double lj = clicks.uniform(-2.0, 2.0);
      const double li = clicks.uniform(-2.0, 2.0);
      clickLeft.push_back(l + vpImagePoint(li, lj));
      const double rj = clicks.uniform(-2.0, 2.0);
      const double ri = clicks.uniform(-2.0, 2.0);
      clickRight.push_back(r + vpImagePoint(ri, rj));
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
  //! Shows a servo iteration in the live view, if any: its features, the tracked centres (and their paths), and,
  //! plotted, its error \e e = s - s* and the joints q.
  void showServo(const vpColVector &e)
  {
    if (viewer != nullptr) {
      viewer->features[0] = tracker.getLeftPoints();
      viewer->features[1] = tracker.getRightPoints();
      viewer->plot(e, q);
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
} // namespace app
#endif
