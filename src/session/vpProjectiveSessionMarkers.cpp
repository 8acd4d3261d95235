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

/*
  vpProjectiveSessionCalibration: the marker extractors (AprilTag corners, a live source's markers) and what the
  calibration and the check share: the markers of a frame, the prediction error of a model.
*/

#include <visp3/projective/vpProjectiveSessionCalibration.h>

#include <cmath>
#include <iomanip>
#include <memory>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <visp3/core/vpTime.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>

#include "core/vpProjectiveErrors.h"
#include "session/vpProjectiveSessionInternal.h"

using namespace vpProjectiveInternal;
using namespace vpProjectiveSessionInternal;

namespace vpProjectiveSessionInternal
{
std::string frameLabel(const vpProjectiveSession &session, unsigned int k)
{
  const vpProjectiveSession::vpFrame &frame = session.getFrame(k);
  return frameName(k, session.getNumberOfFrames(), frame.left, vpProjectiveSession::toString(frame.role));
}

FrameMarkers extract(const vpProjectiveSession &session, unsigned int k,
                     const vpProjectiveSessionCalibration::vpMarkerExtractor &extractor, bool recorded,
                     const std::string &where)
{
  const std::string label = frameLabel(session, k);
  std::vector<int> ids;
  std::vector<vpImagePoint> left, right;
  unsigned int n = 0;
  if (recorded) { // the markers the recording program measured (vpProjectiveSession::vpFrame::markerIds)
    const vpProjectiveSession::vpFrame &frame = session.getFrame(k);
    if (frame.markerIds.empty()) {
      fail(vpProjectiveException::notEnoughPointsError, where,
           label +
               " has no recorded markers (no 'recorded_markers' entry); extract them from the images instead (a marker "
               "extraction function; visp-projective: without --recorded-markers)");
    }
    ids = frame.markerIds;
    left = frame.markerLeft;
    right = frame.markerRight;
    n = static_cast<unsigned int>(ids.size());
  } else {
    vpImage<unsigned char> Il, Ir;
    session.getImages(k, Il, Ir);
    n = extractor(Il, Ir, ids, left, right);
  }
  if (n != ids.size() || n != left.size() || n != right.size()) {
    fail(vpProjectiveException::dimensionError, where,
         label + ": the marker extraction returned " + std::to_string(n) + " markers with " +
             std::to_string(ids.size()) + " identifiers, " + std::to_string(left.size()) + " left and " +
             std::to_string(right.size()) + " right points; it must give one of each per marker");
  }
  FrameMarkers markers;
  markers.ids = ids;
  for (size_t j = 0; j < n; ++j) {
    if (j > 0 && ids[j] <= ids[j - 1]) {
      fail(vpProjectiveException::invalidValueError, where,
           label + ": the marker extraction's identifiers are not ascending and distinct; fix the extraction");
    }
    const Eigen::Vector4d s(left[j].get_u(), left[j].get_v(), right[j].get_u(), right[j].get_v());
    if (!s.allFinite()) {
      fail(vpProjectiveException::nonFiniteValueError, where,
           label + ": the marker extraction gave a non-finite pixel for marker " + std::to_string(ids[j]));
    }
    markers.s.push_back(s);
  }
  if (n == 0 && !session.getFrame(k).markerIds.empty()) {
    // The likeliest cause first: a session of a program whose markers are not tags (balls, projected points).
    fail(vpProjectiveException::notEnoughPointsError, where,
         label + ": no marker found in its images, but the frame carries the " +
             std::to_string(session.getFrame(k).markerIds.size()) +
             " markers its recording program measured (recorded_markers): use them (visp-projective: "
             "--recorded-markers; setRecordedMarkers(true)), or give the extraction that finds them in the images");
  }
  if (n == 0) {
    fail(vpProjectiveException::notEnoughPointsError, where,
         label + ": no marker found in both images; check that the tags face both cameras, the exposure and the "
                 "focus, or remove the frame from session.json");
  }
  return markers;
}

vpProjectiveArmModel::JointVector jointsOf(const vpColVector &q)
{
  vpProjectiveArmModel::JointVector v(static_cast<Eigen::Index>(q.getRows()));
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    v(i) = q[i];
  }
  return v;
}

void predictionError(const vpProjectiveArmModel &model, const vpColVector &q,
                     const std::vector<std::pair<unsigned int, Eigen::Vector4d>> &pairs, double &left, double &right,
                     unsigned int &count)
{
  const Eigen::Matrix4d H = model.displacement(jointsOf(q));
  for (const auto &pair : pairs) {
    Eigen::Vector4d s;
    if (!model.predictMarker(pair.first, H, s)) {
      left += 1e12;
      right += 1e12;
    } else {
      left += (s.head<2>() - pair.second.head<2>()).squaredNorm();
      right += (s.tail<2>() - pair.second.tail<2>()).squaredNorm();
    }
    ++count;
  }
}

double rms(double sumSquares, unsigned int coordinates)
{
  return coordinates > 0 ? std::sqrt(sumSquares / coordinates) : 0.0;
}

std::string pixels(double px)
{
  std::ostringstream os;
  os << std::setprecision(3) << px << " px";
  return os.str();
}
} // namespace vpProjectiveSessionInternal

vpProjectiveSessionCalibration::vpMarkerExtractor
vpProjectiveSessionCalibration::aprilTagMarkers(const std::string &family)
{
#if defined(VISP_HAVE_APRILTAG)
  // The families every ViSP from 3.5 on detects (the deprecated 36h10, 25h7 and ARToolKit ones are left out).
  const std::vector<std::pair<std::string, vpDetectorAprilTag::vpAprilTagFamily>> families = {
    {"36h11", vpDetectorAprilTag::TAG_36h11},
    {"25h9", vpDetectorAprilTag::TAG_25h9},
    {"16h5", vpDetectorAprilTag::TAG_16h5},
    {"Circle21h7", vpDetectorAprilTag::TAG_CIRCLE21h7},
#if defined(VISP_HAVE_APRILTAG_BIG_FAMILY)
    {"Circle49h12", vpDetectorAprilTag::TAG_CIRCLE49h12},
    {"Custom48h12", vpDetectorAprilTag::TAG_CUSTOM48h12},
    {"Standard41h12", vpDetectorAprilTag::TAG_STANDARD41h12},
    {"Standard52h13", vpDetectorAprilTag::TAG_STANDARD52h13},
#endif
  };
  std::string names;
  for (const auto &f : families) {
    if (f.first == family) {
      // Shared: the extraction function is copied with the calibration, the detector's settings go with it.
      auto tags = std::make_shared<vpStereoAprilTagDetector>(f.second);
      return [tags](const vpImage<unsigned char> &Il, const vpImage<unsigned char> &Ir, std::vector<int> &ids,
                    std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        const unsigned int n = tags->detect(Il, Ir);
        ids = tags->getIds();
        left = tags->getLeftPoints();
        right = tags->getRightPoints();
        return n;
      };
    }
    names += (names.empty() ? "" : ", ") + f.first;
  }
  fail(vpProjectiveException::invalidValueError, calibrationAt("aprilTagMarkers()"),
       "unknown AprilTag family '" + family + "'; use " + names);
#else
  return [family](const vpImage<unsigned char> &, const vpImage<unsigned char> &, std::vector<int> &,
                  std::vector<vpImagePoint> &, std::vector<vpImagePoint> &) -> unsigned int {
    fail(vpProjectiveException::notImplementedError, "vpProjectiveSessionCalibration",
         "no detector for the AprilTag family " + family +
             ": this ViSP was built without AprilTag (WITH_APRILTAG); give a marker extraction function");
  };
#endif
}

vpProjectiveAcquisitionProcedure::vpImageSource
vpProjectiveSessionCalibration::markerSource(vpStereoImageSource &images, const vpMarkerExtractor &extractor,
                                             vpRobot &robot, vpProjectiveSessionWriter *writer)
{
  if (!extractor) {
    fail(vpProjectiveException::invalidValueError, calibrationAt("markerSource()"), "the extraction function is empty");
  }
  struct State {
    bool started = false;
    double t0 = 0.0;
    std::vector<int> ids; // the zero reference's markers
    vpImage<unsigned char> Il, Ir;
  };
  auto state = std::make_shared<State>();
  return
      [state, &images, extractor, &robot, writer](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        if (!images.acquire(state->Il, state->Ir)) {
          return false;
        }
        vpColVector q;
        robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
        const double now = vpTime::measureTimeSecond();
        if (!state->started) {
          state->t0 = now;
        }
        std::vector<int> ids;
        std::vector<vpImagePoint> l, r;
        const unsigned int n = extractor(state->Il, state->Ir, ids, l, r);
        if (n != ids.size() || n != l.size() || n != r.size()) {
          fail(vpProjectiveException::dimensionError, calibrationAt("markerSource()"),
               "the marker extraction must give one identifier, one left and one right point per marker");
        }
        if (!state->started) {
          state->ids = ids;
          state->started = true;
        }
        left.clear();
        right.clear();
        for (int id : state->ids) {
          const auto it = std::find(ids.begin(), ids.end(), id);
          if (it == ids.end()) {
            return false; // a marker of the zero reference is lost
          }
          left.push_back(l[static_cast<size_t>(it - ids.begin())]);
          right.push_back(r[static_cast<size_t>(it - ids.begin())]);
        }
        // Recorded once the markers are all seen: the session holds the frames that the procedure used, and which
        // camera took which images when the source knows.
        if (writer != nullptr && writer->getSession().getNumberOfFrames() == 0) {
          writer->setCameras(images);
        }
        if (writer != nullptr) {
          writer->addAcquisitionFrame(q, now - state->t0, state->Il, state->Ir);
        }
        return true;
      };
}
