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
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/gui/vpDisplayX.h>

#include <visp3/projective/vpStereoDotTracker.h>

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
} // namespace app

#endif
