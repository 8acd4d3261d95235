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
  \file images-view.h
  \brief What the image apps show and measure besides the servo: the tracking accuracy against the ground truth
  (only reported, never used) and the live view of both cameras.
*/

#ifndef _app_projective_images_view_h_
#define _app_projective_images_view_h_

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpStereoDotTracker.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#include "paper-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
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
/*!
  Both images live (seed 1, with a display: vpStereoServoDisplay): the tracked blobs (yellow circles; red if lost),
  the taught target s* (red crosses), the servo's features and their paths (green), and a vpPlot of the servo's error
  and joints.
*/
class Viewer
{
public:
  //! A window for \e width x \e height images.
  Viewer(unsigned int width, unsigned int height) : m_display(width, height, true) {}
  //! Shows the last stereo frame with \e caption.
  void show(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
            const vpStereoDotTracker &tracker, const std::string &caption)
  {
    m_display.display(Ileft, Iright);
    std::vector<vpImagePoint> left[2], right[2]; // tracked, lost
    for (unsigned int k = 0; k < tracker.getNumberOfMarkers(); ++k) {
      const unsigned int lost = tracker.getState(k) == vpStereoDotTracker::MARKER_LOST ? 1 : 0;
      left[lost].push_back(tracker.getLeftPoint(k));
      right[lost].push_back(tracker.getRightPoint(k));
    }
    m_display.displayMarkers(left[0], right[0], vpColor::yellow);
    m_display.displayMarkers(left[1], right[1], vpColor::red);
    for (unsigned int k = 0; k < features[0].size() && k < target[0].size(); ++k) {
      vpFeatureStereoPoint s, s_star;
      s.buildFrom(features[0][k], features[1][k]);
      s_star.buildFrom(target[0][k], target[1][k]);
      m_display.displayFeature(k, s, s_star);
    }
    m_display.displayText(caption);
    m_display.flush();
  }
  //! Plots a servo iteration's error \e e (s - s*) and joints \e q.
  void plot(const vpColVector &e, const vpColVector &q) { m_display.plot(e, q); }
  //! Waits for a click in the window.
  void waitForClick()
  {
    std::cout << "Click in the window to quit" << std::endl;
    m_display.getClick();
  }
  std::vector<vpImagePoint> target[2];   //!< s* in each image
  std::vector<vpImagePoint> features[2]; //!< the servo's last features in each image

private:
  vpStereoServoDisplay m_display;
};
//! [Viewer]
} // namespace app

#endif
