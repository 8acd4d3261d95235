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
  \file vpStereoAprilTagDetector.cpp
  \brief AprilTag corners in a stereo pair: detection, sub-pixel refinement, pairing, epipolar check, tracking.
*/

#include <visp3/projective/vpStereoAprilTagDetector.h>

#if defined(VISP_HAVE_APRILTAG)

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpProjectiveErrors.h"

using vpProjectiveInternal::fail;

namespace
{
const vpProjectiveInternal::vpErrorSite at("vpStereoAprilTagDetector");
const double kSpacing = 2.0; // pixels between the points relocated along an edge
const int kIterations = 2;   // relocations of the edges at most; the second if a corner moved by 0.1 px or more

//! Bilinear grey level at (u, v) (ViSP's convention); false outside the image.
inline bool bilinear(const vpImage<unsigned char> &I, double u, double v, double &g)
{
  const double fu = std::floor(u), fv = std::floor(v);
  const int j = static_cast<int>(fu), i = static_cast<int>(fv);
  if (j < 0 || i < 0 || j + 1 >= static_cast<int>(I.getWidth()) || i + 1 >= static_cast<int>(I.getHeight())) {
    return false;
  }
  const double a = u - fu, b = v - fv;
  const unsigned char *r0 = I[i] + j, *r1 = I[i + 1] + j;
  g = (1.0 - b) * ((1.0 - a) * r0[0] + a * r0[1]) + b * ((1.0 - a) * r1[0] + a * r1[1]);
  return true;
}

//! Total least-squares line n . x = c through points (n unit); false if fewer than 4 points.
bool fitLine(const std::vector<Eigen::Vector2d> &points, Eigen::Vector2d &n, double &c)
{
  if (points.size() < 4) {
    return false;
  }
  Eigen::Vector2d mean = Eigen::Vector2d::Zero();
  for (const Eigen::Vector2d &p : points) {
    mean += p;
  }
  mean /= static_cast<double>(points.size());
  double sxx = 0.0, sxy = 0.0, syy = 0.0;
  for (const Eigen::Vector2d &p : points) {
    const Eigen::Vector2d d = p - mean;
    sxx += d.x() * d.x();
    sxy += d.x() * d.y();
    syy += d.y() * d.y();
  }
  // The normal is the eigenvector of the smaller eigenvalue of the 2x2 scatter matrix.
  const double theta = 0.5 * std::atan2(2.0 * sxy, sxx - syy); // direction of the larger eigenvalue
  n = Eigen::Vector2d(-std::sin(theta), std::cos(theta));
  c = n.dot(mean);
  return true;
}
} // namespace

vpStereoAprilTagDetector::vpStereoAprilTagDetector(vpDetectorAprilTag::vpAprilTagFamily family)
    : m_detector(family), m_F(), m_useRig(false), m_epipolarThreshold(2.0), m_refine(true), m_margin(10.0),
      m_decimation(1.5), m_predicted(), m_predictedBox(), m_crop(), m_ids(), m_left(), m_right(), m_rejected(0)
{
  m_detector.setAprilTagNbThreads(1);
  m_detector.setAprilTagRefineEdges(false);                             // the refinement below replaces it
  m_detector.setAprilTagQuadDecimate(static_cast<float>(m_decimation)); // the refinement works at full resolution
}

void vpStereoAprilTagDetector::setStereoRig(const vpProjectiveStereoRig &rig)
{
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, at("setStereoRig()"),
         "the rig has no fundamental matrix yet; estimate() or setFundamentalMatrix() it first");
  }
  m_F = rig.getFundamentalMatrix();
  m_useRig = true;
}

void vpStereoAprilTagDetector::setEpipolarThreshold(double pixels)
{
  m_epipolarThreshold = vpProjectiveInternal::positive(pixels, at("setEpipolarThreshold()"), "the epipolar threshold",
                                                       "pixels; clearStereoRig() disables the check");
}

void vpStereoAprilTagDetector::setDecimation(double decimation)
{
  if (!std::isfinite(decimation) || decimation < 1.0 || decimation > 8.0) {
    fail(vpProjectiveException::invalidValueError, at("setDecimation()"),
         "the decimation must be in [1, 8] (1: full resolution, for tags under 25 px; 1.5 is about 10 times faster)");
  }
  m_detector.setAprilTagQuadDecimate(static_cast<float>(decimation));
  m_decimation = decimation;
}

void vpStereoAprilTagDetector::setNbThreads(unsigned int threads)
{
  if (threads < 1 || threads > 64) {
    fail(vpProjectiveException::invalidValueError, at("setNbThreads()"), "give 1 to 64 threads");
  }
  m_detector.setAprilTagNbThreads(static_cast<int>(threads));
}

void vpStereoAprilTagDetector::setRegionMargin(double pixels)
{
  m_margin = vpProjectiveInternal::nonNegative(pixels, at("setRegionMargin()"), "the region margin",
                                               "pixels added around each predicted tag");
}

void vpStereoAprilTagDetector::setPredictedRegions(const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                                                   const std::vector<vpImagePoint> &right)
{
  if (ids.size() != left.size() || ids.size() != right.size()) {
    std::ostringstream os;
    os << "give one left and one right point per id (" << ids.size() << " ids, " << left.size() << " left, "
       << right.size() << " right points)";
    fail(vpProjectiveException::dimensionError, at("setPredictedRegions()"), os.str());
  }
  std::map<int, std::pair<Eigen::Vector4d, Eigen::Vector4d>> boxes; // tag id -> (umin, vmin, umax, vmax) per image
  for (size_t k = 0; k < ids.size(); ++k) {
    if (ids[k] < 0) {
      fail(vpProjectiveException::invalidValueError, at("setPredictedRegions()"),
           "an id is negative; give ids as getIds() returns them (4 * tag id + corner index)");
    }
    const vpImagePoint *p[2] = {&left[k], &right[k]};
    for (const vpImagePoint *q : p) {
      if (!std::isfinite(q->get_u()) || !std::isfinite(q->get_v())) {
        fail(vpProjectiveException::nonFiniteValueError, at("setPredictedRegions()"),
             "a predicted point is not finite; check the prediction");
      }
    }
    auto found = boxes.find(ids[k] / 4);
    if (found == boxes.end()) {
      const Eigen::Vector4d empty(1e300, 1e300, -1e300, -1e300);
      found = boxes.emplace(ids[k] / 4, std::make_pair(empty, empty)).first;
    }
    Eigen::Vector4d *b[2] = {&found->second.first, &found->second.second};
    for (int s = 0; s < 2; ++s) {
      (*b[s])[0] = std::min((*b[s])[0], p[s]->get_u());
      (*b[s])[1] = std::min((*b[s])[1], p[s]->get_v());
      (*b[s])[2] = std::max((*b[s])[2], p[s]->get_u());
      (*b[s])[3] = std::max((*b[s])[3], p[s]->get_v());
    }
  }
  m_predicted.clear();
  m_predictedBox[0].clear();
  m_predictedBox[1].clear();
  for (const auto &b : boxes) {
    m_predicted.push_back(b.first);
    m_predictedBox[0].push_back(vpImagePoint(b.second.first[1], b.second.first[0]));
    m_predictedBox[0].push_back(vpImagePoint(b.second.first[3], b.second.first[2]));
    m_predictedBox[1].push_back(vpImagePoint(b.second.second[1], b.second.second[0]));
    m_predictedBox[1].push_back(vpImagePoint(b.second.second[3], b.second.second[2]));
  }
}

void vpStereoAprilTagDetector::clearPredictedRegions()
{
  m_predicted.clear();
  m_predictedBox[0].clear();
  m_predictedBox[1].clear();
}

void vpStereoAprilTagDetector::detectIn(const vpImage<unsigned char> &I, const Box &box, std::vector<Tag> &tags)
{
  if (box.i1 - box.i0 < 8 || box.j1 - box.j0 < 8) {
    return; // a box (nearly) out of the image
  }
  const bool whole = box.i0 == 0 && box.j0 == 0 && box.i1 == static_cast<int>(I.getHeight()) - 1 &&
                     box.j1 == static_cast<int>(I.getWidth()) - 1;
  const vpImage<unsigned char> *image = &I;
  if (!whole) {
    m_crop.resize(static_cast<unsigned int>(box.i1 - box.i0 + 1), static_cast<unsigned int>(box.j1 - box.j0 + 1));
    for (int i = box.i0; i <= box.i1; ++i) {
      std::copy(I[i] + box.j0, I[i] + box.j1 + 1, m_crop[i - box.i0]);
    }
    image = &m_crop;
  }
  m_detector.detect(*image);
  const std::vector<std::vector<vpImagePoint>> corners = m_detector.getTagsCorners();
  const std::vector<int> ids = m_detector.getTagsId();
  for (size_t d = 0; d < ids.size() && d < corners.size(); ++d) {
    if (corners[d].size() != 4 || (box.id >= 0 && ids[d] != box.id)) {
      continue;
    }
    Tag tag;
    tag.id = ids[d];
    for (int k = 0; k < 4; ++k) { // AprilTag's pixel centres are at (j + 1/2, i + 1/2): back to ViSP's (j, i)
      tag.corners[k].set_uv(corners[d][k].get_u() - 0.5 + box.j0, corners[d][k].get_v() - 0.5 + box.i0);
    }
    tags.push_back(tag);
  }
}

vpStereoAprilTagDetector::Box vpStereoAprilTagDetector::box(const vpImage<unsigned char> &I, int side, size_t t) const
{
  // The predicted tag's box, grown by the margin, by its quiet zone (an eighth of its size) and 2 px.
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());
  const vpImagePoint &lo = m_predictedBox[side][2 * t], &hi = m_predictedBox[side][2 * t + 1];
  const double grow = m_margin + 2.0 + std::max(hi.get_u() - lo.get_u(), hi.get_v() - lo.get_v()) / 8.0;
  return Box{std::max(0, static_cast<int>(std::floor(lo.get_v() - grow))),
             std::max(0, static_cast<int>(std::floor(lo.get_u() - grow))),
             std::min(H - 1, static_cast<int>(std::ceil(hi.get_v() + grow))),
             std::min(W - 1, static_cast<int>(std::ceil(hi.get_u() + grow))), m_predicted[t]};
}

void vpStereoAprilTagDetector::detectImage(const vpImage<unsigned char> &I, int side, std::vector<Tag> &tags)
{
  tags.clear();
  const int H = static_cast<int>(I.getHeight()), W = static_cast<int>(I.getWidth());
  if (m_predicted.empty()) {
    detectIn(I, Box{0, 0, H - 1, W - 1, -1}, tags);
  } else {
    // One box per predicted tag, grown by the margin, by its quiet zone (an eighth of its size) and 2 px; in each box,
    // only that tag is kept (a neighbour partly inside is found in its own box).
    for (size_t t = 0; t < m_predicted.size(); ++t) {
      detectIn(I, box(I, side, t), tags);
    }
    // A predicted tag not found in its box (a tag seen obliquely, too small for the decimation; a box too tight for a
    // fast motion): its box again at full resolution, then the whole image once for the tags still missing, so that
    // tracking loses no tag that detection finds.
    std::vector<int> missing;
    for (size_t t = 0; t < m_predicted.size(); ++t) {
      const int id = m_predicted[t];
      if (std::none_of(tags.begin(), tags.end(), [id](const Tag &tag) { return tag.id == id; })) {
        missing.push_back(id);
      }
    }
    if (!missing.empty() && m_decimation > 1.0) {
      m_detector.setAprilTagQuadDecimate(1.0f);
      for (size_t t = 0; t < m_predicted.size(); ++t) {
        if (std::find(missing.begin(), missing.end(), m_predicted[t]) != missing.end()) {
          const size_t before = tags.size();
          detectIn(I, box(I, side, t), tags);
          if (tags.size() > before) {
            missing.erase(std::find(missing.begin(), missing.end(), m_predicted[t]));
          }
        }
      }
      m_detector.setAprilTagQuadDecimate(static_cast<float>(m_decimation));
    }
    if (!missing.empty()) {
      std::vector<Tag> all;
      detectIn(I, Box{0, 0, H - 1, W - 1, -1}, all);
      for (const Tag &t : all) {
        if (std::find(missing.begin(), missing.end(), t.id) != missing.end()) {
          tags.push_back(t);
        }
      }
    }
  }
  if (m_refine) {
    for (Tag &tag : tags) {
      refine(I, tag);
    }
  }
}

void vpStereoAprilTagDetector::refine(const vpImage<unsigned char> &I, Tag &tag) const
{
  Eigen::Vector2d c[4];
  for (int k = 0; k < 4; ++k) {
    c[k] = Eigen::Vector2d(tag.corners[k].get_u(), tag.corners[k].get_v());
  }
  const Eigen::Vector2d centre = 0.25 * (c[0] + c[1] + c[2] + c[3]);
  std::vector<Eigen::Vector2d> points;
  for (int iteration = 0; iteration < kIterations; ++iteration) {
    Eigen::Vector2d n[4];
    double d[4];
    for (int e = 0; e < 4; ++e) { // edge e: corner e to corner e + 1
      const Eigen::Vector2d a = c[e], b = c[(e + 1) % 4];
      const double length = (b - a).norm();
      if (!(length > 8.0)) {
        return; // too small to refine
      }
      const Eigen::Vector2d t = (b - a) / length;
      Eigen::Vector2d normal(-t.y(), t.x());
      if (normal.dot(0.5 * (a + b) - centre) < 0.0) {
        normal = -normal; // outwards: from the black border to the white quiet zone
      }
      // Half-width of the search across the edge: less than half a cell across it (the border is one cell, an eighth
      // of the two neighbouring edges: the shorter one, for a foreshortened tag).
      const double across = std::min((c[(e + 3) % 4] - a).norm(), (c[(e + 2) % 4] - b).norm());
      const double reach = std::min(3.0, std::max(1.0, 0.45 * across / 8.0));
      const int steps = static_cast<int>(std::floor(reach / 0.5));
      points.clear();
      for (double s = reach + 2.0; s <= length - reach - 2.0; s += kSpacing) {
        const Eigen::Vector2d p = a + s * t;
        double previous = 0.0, sum = 0.0, moment = 0.0;
        bool inside = true;
        for (int k = -steps; k <= steps && inside; ++k) {
          const Eigen::Vector2d q = p + (0.5 * k) * normal;
          double g = 0.0;
          inside = bilinear(I, q.x(), q.y(), g);
          if (k > -steps && g > previous) {
            sum += g - previous;
            moment += (g - previous) * 0.5 * (k - 0.5);
          }
          previous = g;
        }
        if (inside && sum > 10.0) { // a step of at least 10 grey levels
          points.push_back(p + (moment / sum) * normal);
        }
      }
      if (!fitLine(points, n[e], d[e])) {
        return;
      }
    }
    Eigen::Vector2d refined[4];
    for (int k = 0; k < 4; ++k) { // corner k: edges k - 1 and k
      const int e0 = (k + 3) % 4, e1 = k;
      const double det = n[e0].x() * n[e1].y() - n[e0].y() * n[e1].x();
      if (std::fabs(det) < 1e-6) {
        return;
      }
      refined[k] =
          Eigen::Vector2d((d[e0] * n[e1].y() - n[e0].y() * d[e1]) / det, (n[e0].x() * d[e1] - d[e0] * n[e1].x()) / det);
      if ((refined[k] - c[k]).norm() > 2.0) {
        return;
      }
    }
    double moved = 0.0;
    for (int k = 0; k < 4; ++k) {
      moved = std::max(moved, (refined[k] - c[k]).norm());
      c[k] = refined[k];
    }
    if (moved < 0.1) {
      break;
    }
  }
  for (int k = 0; k < 4; ++k) {
    tag.corners[k].set_uv(c[k].x(), c[k].y());
  }
}

unsigned int vpStereoAprilTagDetector::detect(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright)
{
  if (Ileft.getSize() == 0 || Iright.getSize() == 0) {
    fail(vpProjectiveException::dimensionError, at("detect()"),
         "an image is empty; pass the two grabbed images (8-bit grey)");
  }
  if (Ileft.getWidth() != Iright.getWidth() || Ileft.getHeight() != Iright.getHeight()) {
    std::ostringstream os;
    os << "the images differ in size (" << Ileft.getWidth() << " x " << Ileft.getHeight() << " and "
       << Iright.getWidth() << " x " << Iright.getHeight() << "); pass the left and right images of one stereo pair";
    fail(vpProjectiveException::dimensionError, at("detect()"), os.str());
  }
  std::vector<Tag> tags[2];
  detectImage(Ileft, 0, tags[0]);
  detectImage(Iright, 1, tags[1]);

  // Tags by id in each image; an id seen twice in an image is ambiguous.
  std::map<int, const Tag *> byId[2];
  for (int s = 0; s < 2; ++s) {
    std::map<int, int> count;
    for (const Tag &t : tags[s]) {
      ++count[t.id];
    }
    for (const Tag &t : tags[s]) {
      if (count[t.id] == 1) {
        byId[s][t.id] = &t;
      }
    }
  }
  std::vector<int> ids;
  std::vector<vpImagePoint> left, right;
  unsigned int rejected = 0;
  for (const auto &l : byId[0]) {
    const auto r = byId[1].find(l.first);
    if (r == byId[1].end()) {
      continue;
    }
    for (int k = 0; k < 4; ++k) {
      const vpImagePoint &pl = l.second->corners[k], &pr = r->second->corners[k];
      if (m_useRig) {
        const Eigen::Vector3d m(pl.get_u(), pl.get_v(), 1.0), mp(pr.get_u(), pr.get_v(), 1.0);
        Eigen::Vector3d Fm, Ftmp;
        for (int i = 0; i < 3; ++i) {
          Fm[i] = m_F[i][0] * m[0] + m_F[i][1] * m[1] + m_F[i][2] * m[2];
          Ftmp[i] = m_F[0][i] * mp[0] + m_F[1][i] * mp[1] + m_F[2][i] * mp[2];
        }
        const double residual = std::fabs(mp.dot(Fm));
        const double distance = std::max(residual / std::max(1e-300, Fm.head<2>().norm()),
                                         residual / std::max(1e-300, Ftmp.head<2>().norm()));
        if (!(distance <= m_epipolarThreshold)) {
          ++rejected;
          continue;
        }
      }
      ids.push_back(4 * l.first + k);
      left.push_back(pl);
      right.push_back(pr);
    }
  }
  m_ids.swap(ids);
  m_left.swap(left);
  m_right.swap(right);
  m_rejected = rejected;
  return static_cast<unsigned int>(m_ids.size());
}

#endif // VISP_HAVE_APRILTAG
