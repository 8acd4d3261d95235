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
  \file vpStereoDotTracker.cpp
  \brief vpDot2 markers in both images of a stereo rig: settings, prediction, checks, recovery (the initialisation is
  in vpStereoDotTrackerInit.cpp, the getters and display in vpStereoDotTrackerState.cpp).
*/

#include <visp3/projective/vpStereoDotTracker.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <numeric>
#include <sstream>

#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpRect.h>

#include <visp3/projective/vpProjectiveException.h>

#include "core/vpImageWindow.h"
#include "tracking/vpStereoDotTrackerInternal.h"

using namespace vpStereoDotTrackerInternal;

namespace
{
void addFailure(std::string &failure, const std::string &reason)
{
  failure += (failure.empty() ? "" : "; ") + reason;
}
} // namespace

vpStereoDotTracker::vpStereoDotTracker()
    : m_markers(), m_robot(nullptr), m_robotMarkers(), m_F(Eigen::Matrix3d::Zero()), m_hasF(false),
      m_epipolarThreshold(2.0), m_minimumGap(3.0), m_searchRadius(10.0), m_largestMotion(0.0), m_width(0), m_height(0)
{
}

void vpStereoDotTracker::setStereoRig(const vpProjectiveStereoRig &rig)
{
  if (!rig.isInitialized()) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                "vpStereoDotTracker::setStereoRig(): the rig has no fundamental matrix yet; call its "
                                "estimate() or setFundamentalMatrix() first.");
  }
  rig.getFundamentalMatrix(m_F);
  m_hasF = true;
}

void vpStereoDotTracker::setRobot(const vpProjectiveRobot &robot, const std::vector<unsigned int> &markers)
{
  if (!robot.isCalibrated()) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                "vpStereoDotTracker::setRobot(): the robot has no model; calibrate() it or "
                                "loadModel() first.");
  }
  const unsigned int nbModel = static_cast<unsigned int>(robot.getModel().markers().size());
  std::vector<unsigned int> indices = markers;
  if (indices.empty()) {
    indices.resize(m_markers.empty() ? nbModel : m_markers.size());
    std::iota(indices.begin(), indices.end(), 0u);
  }
  for (unsigned int index : indices) {
    if (index >= nbModel) {
      std::ostringstream os;
      os << "vpStereoDotTracker::setRobot(): marker " << index << " is not one of the model's " << nbModel
         << " markers; give indices of its zero-reference markers.";
      throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
    }
  }
  if (!m_markers.empty() && indices.size() != m_markers.size()) {
    std::ostringstream os;
    os << "vpStereoDotTracker::setRobot(): " << indices.size() << " model markers for " << m_markers.size()
       << " tracked ones; give one model marker per tracked marker.";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  m_robot = &robot;
  m_robotMarkers = indices;
  robot.getStereoRig().getFundamentalMatrix(m_F);
  m_hasF = true;
  for (size_t k = 0; k < m_markers.size(); ++k) {
    m_markers[k].index = indices[k];
    m_markers[k].blob[0].hasOffset = m_markers[k].blob[1].hasOffset = false;
  }
}

void vpStereoDotTracker::setEpipolarThreshold(double pixels)
{
  if (!std::isfinite(pixels) || pixels <= 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                "vpStereoDotTracker::setEpipolarThreshold(): give a positive number of pixels.");
  }
  m_epipolarThreshold = pixels;
}

void vpStereoDotTracker::setMinimumGap(double pixels)
{
  if (!std::isfinite(pixels) || pixels < 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                "vpStereoDotTracker::setMinimumGap(): give a non-negative number of pixels.");
  }
  m_minimumGap = pixels;
}

void vpStereoDotTracker::setSearchRadius(double pixels)
{
  if (!std::isfinite(pixels) || pixels <= 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                "vpStereoDotTracker::setSearchRadius(): give a positive number of pixels.");
  }
  m_searchRadius = pixels;
}

double vpStereoDotTracker::epipolarDistance(const vpImagePoint &left, const vpImagePoint &right) const
{
  const Eigen::Vector3d m(left.get_u(), left.get_v(), 1.0), mp(right.get_u(), right.get_v(), 1.0);
  const Eigen::Vector3d l = m_F * m, lp = m_F.transpose() * mp;
  const double r = std::abs(mp.dot(l));
  return 0.5 * (r / std::hypot(l(0), l(1)) + r / std::hypot(lp(0), lp(1)));
}

void vpStereoDotTracker::checkInitialised(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                                          const char *method) const
{
  if (m_markers.empty()) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                std::string("vpStereoDotTracker::") + method +
                                    "(): no marker is tracked; call initTracking(), initTrackingByClick() or "
                                    "initTrackingByDetection() first.");
  }
  for (const vpImage<unsigned char> *I : {&Ileft, &Iright}) {
    if (I->getWidth() != m_width || I->getHeight() != m_height) {
      std::ostringstream os;
      os << "vpStereoDotTracker::" << method << "(): a " << I->getWidth() << " x " << I->getHeight()
         << " image where the markers were initialised in " << m_width << " x " << m_height
         << " images; give the rig's images.";
      throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
    }
  }
}

void vpStereoDotTracker::checkMarker(unsigned int k, const char *method) const
{
  if (k >= m_markers.size()) {
    std::ostringstream os;
    os << "vpStereoDotTracker::" << method << "(): marker " << k << " does not exist; " << m_markers.size()
       << " markers are tracked.";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
}

void vpStereoDotTracker::checkJoints(const vpColVector &q, const char *method) const
{
  if (m_robot == nullptr) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                std::string("vpStereoDotTracker::") + method +
                                    "(): joint values need a model to predict the markers; call setRobot() first.");
  }
  bool finite = true;
  for (unsigned int i = 0; i < q.size(); ++i) {
    finite = finite && std::isfinite(q[i]);
  }
  if (q.size() != m_robot->getNumberOfJoints() || !finite) {
    std::ostringstream os;
    os << "vpStereoDotTracker::" << method << "(): " << q.size() << " joint values for a "
       << m_robot->getNumberOfJoints()
       << "-joint model, or a non-finite one; give the encoder readings of every joint.";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
}

bool vpStereoDotTracker::track(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                               double motionRatio)
{
  checkInitialised(Ileft, Iright, "track");
  if (!std::isfinite(motionRatio) || motionRatio < 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                "vpStereoDotTracker::track(): the motion ratio must be non-negative (1: constant "
                                "image velocity).");
  }
  std::vector<vpImagePoint> predicted[2];
  for (unsigned int c = 0; c < 2; ++c) {
    for (const Marker &m : m_markers) {
      predicted[c].push_back(m.blob[c].cog + m.blob[c].motion * motionRatio);
    }
  }
  const vpImage<unsigned char> *I[2] = {&Ileft, &Iright};
  return trackFrame(I, predicted, nullptr);
}

bool vpStereoDotTracker::track(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                               const vpColVector &q)
{
  checkInitialised(Ileft, Iright, "track");
  checkJoints(q, "track");
  std::vector<vpImagePoint> model[2], predicted[2];
  for (const Marker &m : m_markers) {
    vpImagePoint ip[2];
    m_robot->getModel().projectMarker(m.index, q, ip[0], ip[1]);
    for (unsigned int c = 0; c < 2; ++c) {
      model[c].push_back(ip[c]);
      predicted[c].push_back(m.blob[c].hasOffset ? ip[c] + m.blob[c].offset : ip[c]);
    }
  }
  const vpImage<unsigned char> *I[2] = {&Ileft, &Iright};
  return trackFrame(I, predicted, model);
}

bool vpStereoDotTracker::trackFrame(const vpImage<unsigned char> *const I[2],
                                    const std::vector<vpImagePoint> predicted[2],
                                    const std::vector<vpImagePoint> *model)
{
  const size_t n = m_markers.size();
  std::vector<Blob> next[2];
  std::vector<bool> ok[2];
  std::vector<std::string> failure(n);
  for (unsigned int c = 0; c < 2; ++c) {
    const vpImage<unsigned char> &image = *I[c];
    const std::string in = std::string(" in the ") + kImageName[c] + " image";
    const std::vector<vpImagePoint> &p = predicted[c];
    ok[c].assign(n, true);
    next[c].resize(n);
    for (size_t k = 0; k < n; ++k) {
      next[c][k] = m_markers[k].blob[c];
    }
    auto fail = [&](size_t k, const std::string &reason) {
      if (ok[c][k]) {
        addFailure(failure[k], reason);
      }
      ok[c][k] = false;
    };
    // Predictions at the border, or closer to each other than the gap: vpDot2 would merge or cut those blobs.
    for (size_t k = 0; k < n; ++k) {
      const double margin = radiusOf(next[c][k].area) + m_minimumGap;
      if (!vpProjectiveInternal::vpImageWindow(m_width, m_height, margin).contains(p[k])) {
        fail(k, "predicted at the image border" + in + " (leaving the image)");
      }
    }
    for (size_t k = 0; k < n; ++k) {
      for (size_t l = k + 1; l < n; ++l) {
        const double gap = vpImagePoint::distance(p[k], p[l]) - radiusOf(next[c][k].area) - radiusOf(next[c][l].area);
        if (gap < m_minimumGap) {
          std::ostringstream os;
          os << std::fixed << std::setprecision(1) << "predicted " << gap << " px from marker " << m_markers[l].index
             << in << " (about to merge)";
          fail(k, os.str());
          os.str("");
          os << "predicted " << gap << " px from marker " << m_markers[k].index << in << " (about to merge)";
          fail(l, os.str());
        }
      }
    }
    // Blobs found in the last frame: vpDot2::track() from the prediction.
    for (size_t k = 0; k < n; ++k) {
      Blob &b = next[c][k];
      if (!ok[c][k] || !b.found) {
        continue;
      }
      b.dot.setCog(p[k]);
      try {
        b.dot.track(image);
      } catch (const vpException &e) {
        fail(k, "lost by vpDot2" + in + " (" + e.getStringMessage() + ")");
        continue;
      }
      const vpRect box = b.dot.getBBox();
      const double area = b.dot.getArea(), miss = vpImagePoint::distance(b.dot.getCog(), p[k]);
      std::ostringstream os;
      os << std::fixed << std::setprecision(1);
      if (box.getLeft() < 2 || box.getTop() < 2 || box.getRight() > m_width - 3 || box.getBottom() > m_height - 3) {
        os << "at the image border" << in << " (leaving the image)";
      } else if (std::abs(area - b.area) > 0.15 * b.area + 1.5 * std::sqrt(b.area)) {
        os << "blob area jumped from " << b.area << " to " << area << " px" << in
           << " (merged with another blob, or hidden by it)";
      } else if (miss > radiusOf(area) + 0.5 * m_minimumGap) {
        os << "found " << miss << " px from its predicted position" << in << " (the tracker may have jumped to "
           << "another blob)";
      }
      if (!os.str().empty()) {
        fail(k, os.str());
      }
    }
    // Blobs lost in the last frame: the brightest pixel near the prediction, away from the blobs just found.
    for (size_t k = 0; k < n; ++k) {
      Blob &b = next[c][k];
      if (!ok[c][k] || b.found) {
        continue;
      }
      const int r = static_cast<int>(std::ceil(m_searchRadius));
      const int i0 = static_cast<int>(std::round(p[k].get_i())), j0 = static_cast<int>(std::round(p[k].get_j()));
      int bestI = -1, bestJ = -1;
      unsigned char best = 0;
      for (int i = std::max(0, i0 - r); i <= std::min(static_cast<int>(m_height) - 1, i0 + r); ++i) {
        for (int j = std::max(0, j0 - r); j <= std::min(static_cast<int>(m_width) - 1, j0 + r); ++j) {
          const vpImagePoint ip(i, j);
          if (image[i][j] <= best || image[i][j] < b.grayMin || vpImagePoint::distance(ip, p[k]) > m_searchRadius) {
            continue;
          }
          bool free = true;
          for (size_t l = 0; l < n && free; ++l) {
            free =
                l == k || !ok[c][l] || !next[c][l].found ||
                vpImagePoint::distance(ip, next[c][l].dot.getCog()) > radiusOf(next[c][l].dot.getArea()) + m_minimumGap;
          }
          if (free) {
            best = image[i][j];
            bestI = i;
            bestJ = j;
          }
        }
      }
      bool found = bestI >= 0;
      if (found) {
        try {
          b.dot.initTracking(image, vpImagePoint(bestI, bestJ), b.grayMin, b.grayMax);
        } catch (const vpException &) {
          found = false;
        }
      }
      std::ostringstream os;
      os << std::fixed << std::setprecision(1);
      if (!found) {
        os << "no blob within " << m_searchRadius << " px of its predicted position" << in;
      } else {
        const vpRect box = b.dot.getBBox();
        const double area = b.dot.getArea(), miss = vpImagePoint::distance(b.dot.getCog(), p[k]);
        if (box.getLeft() < 2 || box.getTop() < 2 || box.getRight() > m_width - 3 || box.getBottom() > m_height - 3) {
          os << "found again at the image border" << in;
        } else if (std::abs(area - b.area) > 0.5 * b.area + 1.5 * std::sqrt(b.area)) {
          os << "a blob of " << area << " px near its prediction" << in << ", not its " << b.area << " px";
        } else if (miss > m_searchRadius) {
          os << "found again " << miss << " px from its predicted position" << in;
        }
      }
      if (!os.str().empty()) {
        fail(k, os.str());
      } else {
        b.found = true; // provisionally, for the checks below
      }
    }
    // Blobs found closer to each other than the gap: merging.
    for (size_t k = 0; k < n; ++k) {
      for (size_t l = k + 1; l < n; ++l) {
        if (!ok[c][k] || !ok[c][l]) {
          continue;
        }
        const Blob &a = next[c][k], &b = next[c][l];
        const double gap = vpImagePoint::distance(a.dot.getCog(), b.dot.getCog()) - radiusOf(a.dot.getArea()) -
                           radiusOf(b.dot.getArea());
        if (gap < m_minimumGap) {
          std::ostringstream os;
          os << std::fixed << std::setprecision(1) << "found " << gap << " px from marker " << m_markers[l].index << in
             << " (about to merge)";
          fail(k, os.str());
          os.str("");
          os << "found " << gap << " px from marker " << m_markers[k].index << in << " (about to merge)";
          fail(l, os.str());
        }
      }
    }
  }
  // Correspondences: the epipolar constraint.
  if (m_hasF) {
    for (size_t k = 0; k < n; ++k) {
      if (ok[0][k] && ok[1][k]) {
        const double d = epipolarDistance(next[0][k].dot.getCog(), next[1][k].dot.getCog());
        if (d > m_epipolarThreshold) {
          std::ostringstream os;
          os << std::fixed << std::setprecision(1) << "left and right blobs " << d
             << " px from their epipolar lines (not images of one marker)";
          addFailure(failure[k], os.str());
          ok[0][k] = ok[1][k] = false;
        }
      }
    }
  }
  // The new state: measurements where found, predictions elsewhere.
  m_largestMotion = 0.0;
  for (size_t k = 0; k < n; ++k) {
    Marker &m = m_markers[k];
    const bool both = ok[0][k] && ok[1][k];
    const bool wasFound = m.blob[0].found && m.blob[1].found && m.state != MARKER_LOST;
    for (unsigned int c = 0; c < 2; ++c) {
      Blob &b = next[c][k];
      if (ok[c][k]) {
        const vpImagePoint cog = b.dot.getCog();
        if (m.blob[c].found) {
          b.motion = cog - m.blob[c].cog;
          m_largestMotion = std::max(m_largestMotion, vpImagePoint::distance(cog, m.blob[c].cog));
        }
        b.cog = cog;
        b.area = b.dot.getArea();
        b.found = true;
        if (model != nullptr) {
          b.offset = cog - model[c][k];
          b.hasOffset = true;
        }
        m.blob[c] = b;
      } else {
        m.blob[c].cog = predicted[c][k]; // the dot itself stays as it was at its last detection
        m.blob[c].found = false;
      }
    }
    m.state = both ? (wasFound ? MARKER_TRACKED : MARKER_REDETECTED) : MARKER_LOST;
    m.failure = both ? std::string() : failure[k];
  }
  return isTracked();
}
