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
  \file vpStereoDotTrackerInit.cpp
  \brief vpStereoDotTracker's initialisation: markers given by pixels, by clicks, or detected as the bright blobs the
  epipolar geometry pairs (and the robot's model names).
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

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#include "tracking/vpStereoDotTrackerInternal.h"

using namespace vpStereoDotTrackerInternal;

namespace
{
//! A bright connected blob found by detectBlobs().
struct Candidate {
  vpImagePoint brightest; // its brightest pixel: where vpDot2 starts
  vpImagePoint centroid;  // mean of its pixels
  unsigned int area;      // pixels
};

/*!
  The bright blobs of \e I: 8-connected pixels at least halfway between the median grey level (the scene) and the
  brightest one, 4 pixels to 2 % of the image each, in raster order of their centroids. None if the brightest pixel
  is not 40 grey levels above the median.
*/
std::vector<Candidate> detectBlobs(const vpImage<unsigned char> &I)
{
  std::vector<unsigned int> histogram(256, 0);
  const unsigned int size = I.getSize();
  for (unsigned int k = 0; k < size; ++k) {
    ++histogram[I.bitmap[k]];
  }
  unsigned int median = 0, cumulated = 0, brightest = 0;
  for (unsigned int g = 0; g < 256; ++g) {
    if (cumulated < size / 2) {
      median = g;
    }
    cumulated += histogram[g];
    if (histogram[g] > 0) {
      brightest = g;
    }
  }
  std::vector<Candidate> blobs;
  if (brightest < median + 40) {
    return blobs;
  }
  const unsigned char threshold = static_cast<unsigned char>(median + (brightest - median) / 2);
  const int width = static_cast<int>(I.getWidth()), height = static_cast<int>(I.getHeight());
  std::vector<unsigned char> visited(size, 0);
  std::vector<int> stack;
  for (int start = 0; start < static_cast<int>(size); ++start) {
    if (visited[start] || I.bitmap[start] < threshold) {
      continue;
    }
    Candidate c{vpImagePoint(), vpImagePoint(), 0};
    double su = 0.0, sv = 0.0;
    unsigned char best = 0;
    stack.assign(1, start);
    visited[start] = 1;
    while (!stack.empty()) {
      const int p = stack.back();
      stack.pop_back();
      const int i = p / width, j = p % width;
      ++c.area;
      su += j;
      sv += i;
      if (I.bitmap[p] > best) {
        best = I.bitmap[p];
        c.brightest.set_ij(i, j);
      }
      for (int di = -1; di <= 1; ++di) {
        for (int dj = -1; dj <= 1; ++dj) {
          const int ni = i + di, nj = j + dj;
          if (ni >= 0 && ni < height && nj >= 0 && nj < width) {
            const int q = ni * width + nj;
            if (!visited[q] && I.bitmap[q] >= threshold) {
              visited[q] = 1;
              stack.push_back(q);
            }
          }
        }
      }
    }
    if (c.area >= 4 && c.area <= size / 50) {
      c.centroid.set_uv(su / c.area, sv / c.area);
      blobs.push_back(c);
    }
  }
  std::sort(blobs.begin(), blobs.end(), [](const Candidate &a, const Candidate &b) {
    return a.centroid.get_v() < b.centroid.get_v() ||
           (a.centroid.get_v() == b.centroid.get_v() && a.centroid.get_u() < b.centroid.get_u());
  });
  return blobs;
}

std::string pixel(const vpImagePoint &ip)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(1) << "(" << ip.get_u() << ", " << ip.get_v() << ")";
  return os.str();
}
} // namespace

void vpStereoDotTracker::startMarkers(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                                      const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                      const std::vector<unsigned int> &indices, const char *method)
{
  const std::string where = std::string("vpStereoDotTracker::") + method + "(): ";
  if (left.empty() || left.size() != right.size()) {
    std::ostringstream os;
    os << where << left.size() << " left and " << right.size()
       << " right points; give one point per marker in each image, at least one.";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  if (Ileft.getSize() == 0 || Ileft.getWidth() != Iright.getWidth() || Ileft.getHeight() != Iright.getHeight()) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                where + "the images are empty or of different sizes; give the rig's two images.");
  }
  std::vector<unsigned int> modelIndices = indices;
  if (m_robot != nullptr && modelIndices.empty()) {
    modelIndices = m_robotMarkers;
  }
  if (m_robot != nullptr && modelIndices.size() != left.size()) {
    std::ostringstream os;
    os << where << left.size() << " markers for the " << modelIndices.size()
       << " model markers of setRobot(); give as many, or call setRobot() again after initialising.";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  std::vector<Marker> markers(left.size());
  const vpImage<unsigned char> *I[2] = {&Ileft, &Iright};
  for (unsigned int c = 0; c < 2; ++c) {
    for (size_t k = 0; k < markers.size(); ++k) {
      Blob &b = markers[k].blob[c];
      const vpImagePoint &ip = c == 0 ? left[k] : right[k];
      b.dot.setGraphics(false);
      bool ok = ip.get_i() >= 0 && ip.get_j() >= 0 && ip.get_i() <= I[c]->getHeight() - 1 &&
                ip.get_j() <= I[c]->getWidth() - 1;
      if (ok) {
        try {
          // vpDot2 takes its grey levels from the pixel under the point; a first track() on the same image adapts
          // them to the blob's mean level, so that its area does not jump at the next frame.
          b.dot.initTracking(*I[c], ip);
          b.dot.track(*I[c]);
          ok = b.dot.getArea() <= I[c]->getSize() / 50.0; // not the background
        } catch (const vpException &) {
          ok = false;
        }
      }
      if (!ok) {
        std::ostringstream os;
        os << where << "point " << k << " " << pixel(ip) << " of the " << kImageName[c]
           << " image is not on a blob; give a point inside each marker's blob.";
        throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
      }
      b.cog = b.dot.getCog();
      b.area = b.dot.getArea();
      b.grayMin = b.dot.getGrayLevelMin();
      b.grayMax = b.dot.getGrayLevelMax();
      b.found = true;
    }
    for (size_t k = 0; k < markers.size(); ++k) {
      for (size_t l = k + 1; l < markers.size(); ++l) {
        const Blob &a = markers[k].blob[c], &b = markers[l].blob[c];
        const double gap = vpImagePoint::distance(a.cog, b.cog) - radiusOf(a.area) - radiusOf(b.area);
        if (gap < m_minimumGap) {
          std::ostringstream os;
          os << where << "markers " << k << " and " << l << " are " << std::fixed << std::setprecision(1) << gap
             << " px apart in the " << kImageName[c]
             << " image (the same blob, or touching ones); give points on separate blobs.";
          throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
        }
      }
    }
  }
  for (size_t k = 0; k < markers.size(); ++k) {
    markers[k].index = modelIndices.empty() ? static_cast<unsigned int>(k) : modelIndices[k];
    markers[k].state = MARKER_TRACKED;
    if (m_hasF) {
      const double d = epipolarDistance(markers[k].blob[0].cog, markers[k].blob[1].cog);
      if (d > m_epipolarThreshold) {
        std::ostringstream os;
        os << where << "marker " << k << " " << pixel(markers[k].blob[0].cog) << ", " << pixel(markers[k].blob[1].cog)
           << " is " << std::fixed << std::setprecision(1) << d
           << " px from its epipolar lines; the two points are not images of one marker (check their order).";
        throw vpProjectiveException(vpProjectiveException::estimationFailedError, os.str());
      }
    }
  }
  m_markers.swap(markers);
  if (m_robot != nullptr) {
    m_robotMarkers = modelIndices;
  }
  m_width = Ileft.getWidth();
  m_height = Ileft.getHeight();
  m_largestMotion = 0.0;
}

void vpStereoDotTracker::initTracking(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                                      const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
{
  startMarkers(Ileft, Iright, left, right, std::vector<unsigned int>(), "initTracking");
}

void vpStereoDotTracker::initTrackingByClick(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                                             unsigned int nbMarkers)
{
  if (Ileft.display == nullptr || Iright.display == nullptr || nbMarkers == 0) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                "vpStereoDotTracker::initTrackingByClick(): attach a vpDisplay to both images and ask "
                                "for at least one marker (without a display use initTracking() or "
                                "initTrackingByDetection()).");
  }
  std::vector<vpImagePoint> left(nbMarkers), right(nbMarkers);
  for (unsigned int k = 0; k < nbMarkers; ++k) {
    for (unsigned int c = 0; c < 2; ++c) {
      const vpImage<unsigned char> &I = c == 0 ? Ileft : Iright;
      std::ostringstream os;
      os << "Click marker " << k << " in the " << kImageName[c] << " image";
      vpDisplay::display(I);
      vpDisplay::displayText(I, 20, 20, os.str(), vpColor::red);
      for (unsigned int j = 0; j < k; ++j) {
        vpDisplay::displayCross(I, c == 0 ? left[j] : right[j], 10, vpColor::green, 2);
      }
      vpDisplay::flush(I);
      vpDisplay::getClick(I, c == 0 ? left[k] : right[k]);
    }
  }
  startMarkers(Ileft, Iright, left, right, std::vector<unsigned int>(), "initTrackingByClick");
}

void vpStereoDotTracker::initTrackingByDetection(const vpImage<unsigned char> &Ileft,
                                                 const vpImage<unsigned char> &Iright, unsigned int nbMarkers)
{
  const std::string where = "vpStereoDotTracker::initTrackingByDetection(): ";
  if (!m_hasF) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                where + "the blobs are paired by the epipolar geometry: call setStereoRig() or "
                                        "setRobot() first, or initialise by clicks.");
  }
  const std::vector<Candidate> blobs[2] = {detectBlobs(Ileft), detectBlobs(Iright)};
  for (unsigned int c = 0; c < 2; ++c) {
    if (blobs[c].size() != nbMarkers || nbMarkers == 0) {
      std::ostringstream os;
      os << where << blobs[c].size() << " bright blobs in the " << kImageName[c] << " image, " << nbMarkers
         << " markers expected; light exactly the markers to track (or initialise by clicks).";
      throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
    }
  }
  // The pairing of least total epipolar distance (every permutation up to 8 markers, greedy beyond), and the next
  // best one: too close to it, the pairing is ambiguous.
  const unsigned int n = nbMarkers;
  std::vector<std::vector<double>> d(n, std::vector<double>(n));
  for (unsigned int i = 0; i < n; ++i) {
    for (unsigned int j = 0; j < n; ++j) {
      d[i][j] = epipolarDistance(blobs[0][i].centroid, blobs[1][j].centroid);
    }
  }
  std::vector<unsigned int> perm(n), best(n);
  std::iota(perm.begin(), perm.end(), 0u);
  double bestCost = std::numeric_limits<double>::max(), secondCost = std::numeric_limits<double>::max();
  if (n <= 8) {
    do {
      double cost = 0.0;
      for (unsigned int i = 0; i < n; ++i) {
        cost += d[i][perm[i]];
      }
      if (cost < bestCost) {
        secondCost = bestCost;
        bestCost = cost;
        best = perm;
      } else if (cost < secondCost) {
        secondCost = cost;
      }
    } while (std::next_permutation(perm.begin(), perm.end()));
  } else {
    std::vector<bool> used(n, false);
    for (unsigned int i = 0; i < n; ++i) {
      unsigned int jBest = 0;
      double dBest = std::numeric_limits<double>::max();
      for (unsigned int j = 0; j < n; ++j) {
        if (!used[j] && d[i][j] < dBest) {
          dBest = d[i][j];
          jBest = j;
        }
      }
      used[jBest] = true;
      best[i] = jBest;
    }
  }
  if (n > 1 && n <= 8 && secondCost - bestCost <= m_epipolarThreshold) {
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError,
                                where + "two markers lie on nearly the same epipolar line, so that their left-right "
                                        "pairing is ambiguous; move them, or initialise by clicks or with the model.");
  }
  std::vector<vpImagePoint> left(n), right(n);
  for (unsigned int i = 0; i < n; ++i) {
    left[i] = blobs[0][i].brightest;
    right[i] = blobs[1][best[i]].brightest;
  }
  startMarkers(Ileft, Iright, left, right, std::vector<unsigned int>(), "initTrackingByDetection");
}

void vpStereoDotTracker::initTrackingByDetection(const vpImage<unsigned char> &Ileft,
                                                 const vpImage<unsigned char> &Iright, const vpColVector &q)
{
  const std::string where = "vpStereoDotTracker::initTrackingByDetection(): ";
  if (m_robot == nullptr) {
    throw vpProjectiveException(vpProjectiveException::notInitializedError,
                                where + "the markers are found where the model predicts them: call setRobot() first.");
  }
  checkJoints(q, "initTrackingByDetection");
  const std::vector<Candidate> blobs[2] = {detectBlobs(Ileft), detectBlobs(Iright)};
  const size_t n = m_robotMarkers.size();
  std::vector<vpImagePoint> points[2] = {std::vector<vpImagePoint>(n), std::vector<vpImagePoint>(n)};
  for (unsigned int c = 0; c < 2; ++c) {
    std::vector<vpImagePoint> predicted(n);
    for (size_t k = 0; k < n; ++k) {
      vpImagePoint l, r;
      m_robot->getModel().projectMarker(m_robotMarkers[k], q, l, r);
      predicted[k] = c == 0 ? l : r;
    }
    // Greedy assignment: the closest (marker, blob) pair first, each blob used once.
    std::vector<std::pair<double, std::pair<size_t, size_t>>> pairs;
    for (size_t k = 0; k < n; ++k) {
      for (size_t b = 0; b < blobs[c].size(); ++b) {
        pairs.push_back(
            std::make_pair(vpImagePoint::distance(predicted[k], blobs[c][b].centroid), std::make_pair(k, b)));
      }
    }
    std::sort(pairs.begin(), pairs.end());
    std::vector<bool> markerDone(n, false), blobUsed(blobs[c].size(), false);
    for (const auto &p : pairs) {
      const size_t k = p.second.first, b = p.second.second;
      if (p.first <= m_searchRadius && !markerDone[k] && !blobUsed[b]) {
        markerDone[k] = blobUsed[b] = true;
        points[c][k] = blobs[c][b].brightest;
      }
    }
    for (size_t k = 0; k < n; ++k) {
      if (!markerDone[k]) {
        std::ostringstream os;
        os << where << "model marker " << m_robotMarkers[k] << " has no bright blob within " << m_searchRadius
           << " px of its predicted image " << pixel(predicted[k]) << " in the " << kImageName[c]
           << " image; check that it is lit and in view, or raise setSearchRadius().";
        throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
      }
    }
  }
  startMarkers(Ileft, Iright, points[0], points[1], m_robotMarkers, "initTrackingByDetection");
}

void vpStereoDotTracker::keepMarkers(const std::vector<unsigned int> &which)
{
  if (which.empty()) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                "vpStereoDotTracker::keepMarkers(): keep at least one marker.");
  }
  for (unsigned int k : which) {
    checkMarker(k, "keepMarkers");
  }
  std::vector<Marker> kept;
  for (unsigned int k : which) {
    kept.push_back(m_markers[k]);
  }
  m_markers.swap(kept);
  if (m_robot != nullptr) {
    m_robotMarkers = getMarkerIndices();
  }
}
