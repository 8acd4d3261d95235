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
  \file stereo-picture.h
  \brief What the tracker sees, without a display: the left and right images side by side in one PNG, with the
  tracked markers and the model's predicted images of them drawn on it (vpImageDraw), for the image apps'
  --output.
*/

#ifndef _app_projective_stereo_picture_h_
#define _app_projective_stereo_picture_h_

#include <cmath>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/io/vpImageIo.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpStereoDotTracker.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
//! [Stereo picture]
/*!
  Writes \e file (PNG): the left image, a 10 px gap, the right image, both in grey, and on them each tracked marker
  (green circle around its centre; a red circle if the tracker lost it), the image of that marker (the model's
  zero-reference marker \e markers[k]) that \e robot predicts at the joint values \e q (yellow cross; none if \e robot
  is null or not calibrated), a line from the prediction to the measurement, and \e caption in the top left corner. Says
  so on std::cout.
*/
inline void writeStereoPicture(const std::string &file, const vpImage<unsigned char> &Ileft,
                               const vpImage<unsigned char> &Iright, const vpStereoDotTracker &tracker,
                               const std::vector<unsigned int> &markers, const vpProjectiveRobot *robot,
                               const vpColVector &q, const std::string &caption)
{
  const unsigned int w = Ileft.getWidth(), h = Ileft.getHeight(), gap = 10;
  vpImage<vpRGBa> I(h, 2 * w + gap, vpRGBa(40, 40, 40));
  for (unsigned int c = 0; c < 2; ++c) {
    const vpImage<unsigned char> &G = c == 0 ? Ileft : Iright;
    for (unsigned int v = 0; v < h; ++v) {
      for (unsigned int u = 0; u < w; ++u) {
        const unsigned char g = G[v][u];
        I[v][u + c * (w + gap)] = vpRGBa(g, g, g);
      }
    }
  }
  for (unsigned int k = 0; k < tracker.getNumberOfMarkers(); ++k) {
    vpImagePoint predicted[2];
    const bool withPrediction = robot != nullptr && robot->isCalibrated();
    if (withPrediction) {
      robot->getModel().projectMarker(markers[k], q, predicted[0], predicted[1]);
    }
    const bool lost = tracker.getState(k) == vpStereoDotTracker::MARKER_LOST;
    for (unsigned int c = 0; c < 2; ++c) {
      const vpImagePoint shift(0.0, c * (w + gap));
      const vpImagePoint measured = (c == 0 ? tracker.getLeftPoint(k) : tracker.getRightPoint(k)) + shift;
      vpImageDraw::drawCircle(I, measured, 9, lost ? vpColor::red : vpColor::green, 2);
      if (withPrediction) {
        const vpImagePoint p = predicted[c] + shift;
        if (std::isfinite(p.get_u()) && std::isfinite(p.get_v())) {
          vpImageDraw::drawLine(I, p, measured, vpColor::orange, 1);
          vpImageDraw::drawCross(I, p, 14, vpColor::yellow, 2);
        }
      }
    }
  }
  const vpFont font(16, vpFont::GENERIC_MONOSPACE); // ViSP's built-in font: no font file needed
  font.drawText(I, "left: " + caption, vpImagePoint(8, 8), vpColor::white, vpColor::black);
  font.drawText(I, "right", vpImagePoint(8, w + gap + 8), vpColor::white, vpColor::black);
  font.drawText(I, "green: tracked, yellow: model's prediction", vpImagePoint(h - 24, 8), vpColor::white,
                vpColor::black);
  vpImageIo::write(I, file);
  std::cout << "    image written: " << file << " (" << caption << ")\n";
}
//! [Stereo picture]
} // namespace app

#endif
