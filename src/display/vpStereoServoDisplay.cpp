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
  \file vpStereoServoDisplay.cpp
  \brief vpStereoServoDisplay: the picture of both images with the overlay, its window and the plot window.
*/

#include <visp3/projective/vpStereoServoDisplay.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <map>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpDisplayException.h>
#include <visp3/core/vpFont.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpIoTools.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>

// The window: the first display this ViSP has, in the order of ViSP 3.5's examples (vpPlot uses the same one).
#if defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_X11)
#include <visp3/gui/vpDisplayX.h>
#define VP_STEREO_SERVO_WINDOW vpDisplayX
#elif defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_GDI)
#include <visp3/gui/vpDisplayGDI.h>
#define VP_STEREO_SERVO_WINDOW vpDisplayGDI
#elif defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_OPENCV) &&                                                    \
    (VISP_VERSION_INT < VP_VERSION_INT(3, 6, 0) || defined(HAVE_OPENCV_HIGHGUI))
#include <visp3/gui/vpDisplayOpenCV.h>
#define VP_STEREO_SERVO_WINDOW vpDisplayOpenCV
#elif defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_GTK)
#include <visp3/gui/vpDisplayGTK.h>
#define VP_STEREO_SERVO_WINDOW vpDisplayGTK
#endif
#if defined(VP_STEREO_SERVO_WINDOW)
#include <visp3/gui/vpPlot.h>
#endif
#if defined(VISP_HAVE_MODULE_IO)
#include <visp3/io/vpImageIo.h>
#endif

#include "core/vpProjectiveErrors.h"

using vpProjectiveInternal::fail;

namespace
{
const vpProjectiveInternal::vpErrorSite at("vpStereoServoDisplay");

const unsigned int gap = 10;              // dark columns between the two images
const unsigned int desiredCrossSize = 15; // s*: red
const unsigned int currentCrossSize = 9;  // s: green, smaller, so that s* shows around it at convergence
const unsigned int markerRadius = 6;
const vpRGBa gapColour(40, 40, 40);

//! The pixel where \e p is drawn: its rounded coordinates, kept within 10^4 px of the image so that vpImageDraw's
//! integer arithmetic (products of two coordinates) cannot overflow for a point far outside.
vpImagePoint pixelOf(const vpImagePoint &p)
{
  const double limit = 1.0e4;
  return vpImagePoint(std::round(std::min(std::max(p.get_i(), -limit), limit)),
                      std::round(std::min(std::max(p.get_j(), -limit), limit)));
}

void requireFinitePoint(const vpImagePoint &p, const char *method, const std::string &what)
{
  if (!std::isfinite(p.get_u()) || !std::isfinite(p.get_v())) {
    fail(vpProjectiveException::nonFiniteValueError, at(method), what + " is not finite (NaN or infinity)");
  }
}

void requireStereoPoints(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                         const char *method)
{
  if (left.size() != right.size()) {
    fail(vpProjectiveException::dimensionError, at(method),
         std::to_string(left.size()) + " left points but " + std::to_string(right.size()) +
             " right points: give one left and one right image per marker");
  }
  for (size_t k = 0; k < left.size(); ++k) {
    requireFinitePoint(left[k], method, "left point " + std::to_string(k));
    requireFinitePoint(right[k], method, "right point " + std::to_string(k));
  }
}
} // namespace

vpStereoServoDisplay::vpStereoServoDisplay()
    : m_captionLines(0), m_plotted(0), m_plotPoints(0), m_plotJoints(0), m_x(0), m_y(0),
      m_font(new vpFont(16, vpFont::GENERIC_MONOSPACE))
{
}

vpStereoServoDisplay::vpStereoServoDisplay(unsigned int width, unsigned int height, bool window, int x, int y,
                                           const std::string &title)
    : vpStereoServoDisplay()
{
  init(width, height, window, x, y, title);
}

vpStereoServoDisplay::~vpStereoServoDisplay() = default;

bool vpStereoServoDisplay::hasDisplay()
{
#if !defined(VP_STEREO_SERVO_WINDOW)
  return false;
#elif defined(_WIN32) || (defined(__APPLE__) && !defined(VISP_HAVE_X11))
  return true; // GDI or OpenCV's own windows: no X server involved
#else
  const char *server = std::getenv("DISPLAY");
  return server != nullptr && server[0] != '\0';
#endif
}

void vpStereoServoDisplay::init(unsigned int width, unsigned int height, bool window, int x, int y,
                                const std::string &title)
{
  if (width == 0 || height == 0) {
    fail(vpProjectiveException::invalidValueError, at("init()"),
         "the images are " + std::to_string(width) + " x " + std::to_string(height) +
             " pixels: give the size of the cameras' images");
  }
  m_plot.reset();
  m_window.reset();
  for (unsigned int c = 0; c < 2; ++c) {
    m_side[c].I.resize(height, width, vpRGBa(255, 255, 255));
    m_side[c].shift = c * (width + gap);
    m_paths[c].clear();
  }
  m_picture.resize(height, 2 * width + gap, gapColour);
  m_captionLines = 0;
  m_plotted = m_plotPoints = m_plotJoints = 0;
  m_x = x;
  m_y = y;
#if defined(VP_STEREO_SERVO_WINDOW)
  if (window && hasDisplay()) {
    try {
      m_window.reset(new VP_STEREO_SERVO_WINDOW(m_picture, x, y, title));
    } catch (const vpDisplayException &e) {
      const char *server = std::getenv("DISPLAY");
      fail(vpProjectiveException::notInitializedError, at("init()"),
           "cannot open a window on the display '" + std::string(server == nullptr ? "" : server) + "' (" +
               e.getStringMessage() + "): run without a display (ViSP's -d)");
    }
  }
#else
  (void)window;
  (void)title;
#endif
}

void vpStereoServoDisplay::requireInit(const char *method) const
{
  if (m_picture.getSize() == 0) {
    fail(vpProjectiveException::notInitializedError, at(method), "call init(width, height) first");
  }
}

void vpStereoServoDisplay::display(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright)
{
  requireInit("display()");
  const vpImage<unsigned char> *images[2] = {&Ileft, &Iright};
  for (unsigned int c = 0; c < 2; ++c) {
    const vpImage<unsigned char> &G = *images[c];
    if (G.getWidth() != m_side[c].I.getWidth() || G.getHeight() != m_side[c].I.getHeight()) {
      fail(vpProjectiveException::dimensionError, at("display()"),
           std::string(c == 0 ? "the left" : "the right") + " image is " + std::to_string(G.getWidth()) + " x " +
               std::to_string(G.getHeight()) + " pixels, not the " + std::to_string(m_side[c].I.getWidth()) + " x " +
               std::to_string(m_side[c].I.getHeight()) + " given to init()");
    }
  }
  for (unsigned int c = 0; c < 2; ++c) {
    const unsigned char *g = images[c]->bitmap;
    vpRGBa *rgba = m_side[c].I.bitmap;
    for (unsigned int k = 0; k < m_side[c].I.getSize(); ++k) {
      rgba[k] = vpRGBa(g[k], g[k], g[k]);
    }
  }
  m_captionLines = 0;
}

void vpStereoServoDisplay::display()
{
  requireInit("display()");
  for (unsigned int c = 0; c < 2; ++c) {
    m_side[c].I = vpRGBa(255, 255, 255);
  }
  m_captionLines = 0;
}

void vpStereoServoDisplay::displayTags(const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                                       const std::vector<vpImagePoint> &right)
{
  requireInit("displayTags()");
  requireStereoPoints(left, right, "displayTags()");
  if (ids.size() != left.size()) {
    fail(vpProjectiveException::dimensionError, at("displayTags()"),
         std::to_string(ids.size()) + " ids for " + std::to_string(left.size()) +
             " corners: give one id (4 x tag id + corner index) per corner");
  }
  std::map<int, std::vector<size_t>> tags; // tag id -> the index in ids of its corners 0 to 3 (or ids.size())
  for (size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] < 0) {
      fail(vpProjectiveException::invalidValueError, at("displayTags()"),
           "id " + std::to_string(ids[k]) + " is negative: ids are 4 x tag id + corner index");
    }
    std::vector<size_t> &corners = tags[ids[k] / 4];
    corners.resize(4, ids.size());
    corners[static_cast<size_t>(ids[k] % 4)] = k;
  }
  const std::vector<vpImagePoint> *points[2] = {&left, &right};
  for (const auto &tag : tags) {
    for (unsigned int c = 0; c < 2; ++c) {
      vpImagePoint top(1.0e9, 0.0); // where the id goes: above the highest corner
      for (size_t corner = 0; corner < 4; ++corner) {
        const size_t a = tag.second[corner], b = tag.second[(corner + 1) % 4];
        if (a == ids.size()) {
          continue;
        }
        const vpImagePoint p = pixelOf((*points[c])[a]);
        top = p.get_i() < top.get_i() ? p : top;
        if (b != ids.size()) {
          vpImageDraw::drawLine(m_side[c].I, p, pixelOf((*points[c])[b]), vpColor::yellow, 1);
        }
      }
      const vpImagePoint text(std::max(0.0, top.get_i() - 20.0), std::max(0.0, top.get_j() - 4.0));
      m_font->drawText(m_side[c].I, std::to_string(tag.first), text, vpColor::yellow);
    }
  }
}

void vpStereoServoDisplay::displayMarkers(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                          const vpColor &color)
{
  requireInit("displayMarkers()");
  requireStereoPoints(left, right, "displayMarkers()");
  for (size_t k = 0; k < left.size(); ++k) {
    vpImageDraw::drawCircle(m_side[0].I, pixelOf(left[k]), markerRadius, color, 1);
    vpImageDraw::drawCircle(m_side[1].I, pixelOf(right[k]), markerRadius, color, 1);
  }
}

void vpStereoServoDisplay::displayFeature(unsigned int i, const vpFeatureStereoPoint &s,
                                          const vpFeatureStereoPoint &s_star, bool seen)
{
  requireInit("displayFeature()");
  const vpImagePoint desired[2] = {s_star.getLeft(), s_star.getRight()};
  const vpImagePoint current[2] = {s.getLeft(), s.getRight()}; // finite: vpFeatureStereoPoint::buildFrom() checks
  for (unsigned int c = 0; c < 2; ++c) {
    if (m_paths[c].size() <= i) {
      m_paths[c].resize(i + 1);
    }
    std::vector<vpImagePoint> &path = m_paths[c][i];
    if (seen && (path.empty() || path.back() != current[c])) {
      path.push_back(current[c]);
    }
    for (size_t k = 1; k < path.size(); ++k) {
      vpImageDraw::drawLine(m_side[c].I, pixelOf(path[k - 1]), pixelOf(path[k]), vpColor::green, 1);
    }
    vpImageDraw::drawCross(m_side[c].I, pixelOf(desired[c]), desiredCrossSize, vpColor::red, 1);
    if (seen) {
      vpImageDraw::drawCross(m_side[c].I, pixelOf(current[c]), currentCrossSize, vpColor::green, 1);
    }
  }
}

void vpStereoServoDisplay::displayText(const std::string &text)
{
  requireInit("displayText()");
  const vpImagePoint position(6.0 + 20.0 * m_captionLines++, 6.0);
  m_font->drawText(m_side[0].I, text, position, vpColor::white, vpColor::black);
}

void vpStereoServoDisplay::flush()
{
  requireInit("flush()");
  const unsigned int width = m_side[0].I.getWidth();
  for (unsigned int c = 0; c < 2; ++c) {
    for (unsigned int v = 0; v < m_picture.getHeight(); ++v) {
      std::copy(m_side[c].I[v], m_side[c].I[v] + width, m_picture[v] + m_side[c].shift);
    }
  }
  if (m_window) {
    vpDisplay::display(m_picture);
    vpDisplay::flush(m_picture);
  }
}

void vpStereoServoDisplay::plot(const vpColVector &e, const vpColVector &q)
{
  requireInit("plot()");
  if (e.size() == 0 || e.size() % 4 != 0) {
    fail(vpProjectiveException::dimensionError, at("plot()"),
         "the error has " + std::to_string(e.size()) + " rows: give s - s*, 4 rows (u, v, u', v') per stereo point");
  }
  if (m_plotted > 0 && (e.size() != 4 * m_plotPoints || q.size() != m_plotJoints)) {
    fail(vpProjectiveException::dimensionError, at("plot()"),
         "the error has " + std::to_string(e.size()) + " rows and q " + std::to_string(q.size()) +
             " joints, the first plot() had " + std::to_string(4 * m_plotPoints) + " and " +
             std::to_string(m_plotJoints) + ": init() again for another task");
  }
  if (!vpProjectiveInternal::allFinite(e) || !vpProjectiveInternal::allFinite(q)) {
    fail(vpProjectiveException::nonFiniteValueError, at("plot()"), "the error or q is not finite (NaN or infinity)");
  }
  m_plotPoints = e.size() / 4;
  m_plotJoints = q.size();
  const double x = m_plotted++;
#if defined(VP_STEREO_SERVO_WINDOW)
  if (m_window && !m_plot) {
    const unsigned int graphs = m_plotJoints > 0 ? 2 : 1;
    m_plot.reset(new vpPlot(graphs, 250 * graphs, m_picture.getWidth(), m_x,
                            m_y + static_cast<int>(m_picture.getHeight()) + 30, "Image error and joints"));
    m_plot->initGraph(0, m_plotPoints);
    m_plot->setTitle(0, "Image error of each point: RMS of (u, v, u', v') - s*");
    for (unsigned int k = 0; k < m_plotPoints; ++k) {
      m_plot->setLegend(0, k, "point " + std::to_string(k));
    }
    if (graphs == 2) {
      m_plot->initGraph(1, m_plotJoints);
      m_plot->setTitle(1, "Joints q");
      for (unsigned int j = 0; j < m_plotJoints; ++j) {
        m_plot->setLegend(1, j, "q" + std::to_string(j + 1));
      }
    }
  }
  if (m_plot) {
    vpColVector rms(m_plotPoints);
    for (unsigned int k = 0; k < m_plotPoints; ++k) {
      rms[k] = std::sqrt(e.extract(4 * k, 4).sumSquare() / 4.0);
    }
    m_plot->plot(0, x, rms);
    if (m_plotJoints > 0) {
      m_plot->plot(1, x, q);
    }
  }
#else
  (void)x;
#endif
}

bool vpStereoServoDisplay::getClick(bool blocking)
{
  return m_window ? vpDisplay::getClick(m_picture, blocking) : false;
}

void vpStereoServoDisplay::getWindowImage(vpImage<vpRGBa> &I) const
{
  if (!m_window) {
    fail(vpProjectiveException::notInitializedError, at("getWindowImage()"),
         "no window is open: init() with a display (hasDisplay()), or getPicture()");
  }
  vpDisplay::getImage(m_picture, I);
}

namespace
{
void writeImage(const vpImage<vpRGBa> &I, const std::string &file)
{
#if defined(VISP_HAVE_MODULE_IO)
  try {
    const std::string folder = vpIoTools::getParent(file);
    if (!folder.empty() && !vpIoTools::checkDirectory(folder)) {
      vpIoTools::makeDirectory(folder);
    }
    vpImageIo::write(I, file);
  } catch (const vpException &e) {
    fail(vpProjectiveException::fileError, at("write()"),
         "cannot write '" + file + "' (" + e.getStringMessage() + "): check the folder and the extension");
  }
#else
  (void)I;
  fail(vpProjectiveException::fileError, at("write()"), "cannot write '" + file + "': this ViSP has no io module");
#endif
}
} // namespace

void vpStereoServoDisplay::write(const std::string &file) const
{
  requireInit("write()");
  if (m_window) {
    vpImage<vpRGBa> I;
    getWindowImage(I);
    writeImage(I, file);
  } else {
    writeImage(m_picture, file);
  }
}

bool vpStereoServoDisplay::writePlot(const std::string &file) const
{
#if defined(VP_STEREO_SERVO_WINDOW)
  if (m_plot) {
    vpImage<vpRGBa> I;
    vpDisplay::getImage(m_plot->I, I);
    writeImage(I, file);
    return true;
  }
#else
  (void)file;
#endif
  return false;
}
