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
  vpProjectiveSessionCalibration: the model file and check(), the prediction error of a model on a later session
  (whether a camera moved).
*/

#include <visp3/projective/vpProjectiveSessionCalibration.h>

#include <cstdio>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <visp3/projective/vpProjectiveModelFile.h>

#include "core/vpProjectiveErrors.h"
#include "session/vpProjectiveSessionInternal.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

using namespace vpProjectiveInternal;
using namespace vpProjectiveSessionInternal;

void vpProjectiveSessionCalibration::checkWritable(const std::string &filename)
{
  const size_t slash = filename.find_last_of('/');
  const std::string folder = slash == std::string::npos ? std::string() : filename.substr(0, slash + 1);
  const std::string probe = folder + ".tmp-" + std::to_string(static_cast<long>(getpid())) + "-probe";
  std::FILE *file = filename.empty() ? nullptr : std::fopen(probe.c_str(), "wb");
  if (file == nullptr) {
    fail(vpProjectiveException::fileError, calibrationAt("checkWritable()"),
         "cannot write the model file '" + filename +
             "': its folder does not exist or is not writable; choose another output path");
  }
  std::fclose(file);
  std::remove(probe.c_str());
}

void vpProjectiveSessionCalibration::saveModel(const std::string &filename) const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, calibrationAt("saveModel()"),
         "no model yet; call calibrate() first");
  }
  vpProjectiveSessionInternal::writeAtomically(
      filename, vpProjectiveModelFile::toString(m_model, m_residual, m_algebraicResidual, m_ids, m_frames),
      calibrationAt("saveModel()"));
}

std::string vpProjectiveSessionCalibration::toString(vpRigState state)
{
  switch (state) {
  case RIG_UNCHANGED:
    return "the model fits: the rig has not moved since the model was made";
  case LEFT_CAMERA_MOVED:
    return "the left camera moved since the model was made (its images are off, the right ones fit): calibrate again, "
           "or re-register the rig (vpProjectiveRobot::updateRig())";
  case RIGHT_CAMERA_MOVED:
    return "the right camera moved since the model was made (its images are off, the left ones fit): calibrate again, "
           "or re-register the rig (vpProjectiveRobot::updateRig())";
  default:
    return "both images are off: both cameras moved, or the markers moved on the tool, or the readings are not the "
           "model's encoders; calibrate again";
  }
}

std::vector<vpProjectiveSessionCalibration::vpFrameCheck>
vpProjectiveSessionCalibration::check(const vpProjectiveArmModel &model, const std::vector<int> &ids,
                                      const vpProjectiveSession &session)
{
  const std::string where = calibrationAt("check()");
  if (model.getNumberOfJoints() == 0) {
    fail(vpProjectiveException::notInitializedError, where, "the model is empty; load one first");
  }
  if (session.getJointTypes() != model.jointTypes()) {
    fail(vpProjectiveException::dimensionError, where,
         "the session's joints (" + std::to_string(session.getNumberOfJoints()) +
             ", joint_types) are not the model's (" + std::to_string(model.getNumberOfJoints()) +
             "); check a session of the arm the model was made for");
  }
  if (ids.size() != model.markers().size()) {
    fail(vpProjectiveException::dimensionError, where,
         "the model has " + std::to_string(model.markers().size()) + " markers and " + std::to_string(ids.size()) +
             " marker identifiers; use a model calibrated from a session (visp-projective calibrate)");
  }
  std::vector<vpFrameCheck> checks;
  double sumLeft = 0.0, sumRight = 0.0;
  unsigned int total = 0, leftOff = 0, rightOff = 0;
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    const FrameMarkers markers = extract(session, k, m_extractor, m_recorded, where);
    std::vector<std::pair<unsigned int, Eigen::Vector4d>> pairs;
    for (size_t j = 0; j < ids.size(); ++j) {
      const int f = markers.find(ids[j]);
      if (f >= 0) {
        pairs.push_back(std::make_pair(static_cast<unsigned int>(j), markers.s[static_cast<size_t>(f)]));
      }
    }
    if (pairs.empty()) {
      fail(vpProjectiveException::notEnoughPointsError, where,
           frameLabel(session, k) + ": none of the model's markers is seen in both images; check that the tags face "
                                    "both cameras, or remove the frame from session.json");
    }
    double l = 0.0, r = 0.0;
    unsigned int count = 0;
    predictionError(model, session.getFrame(k).q, pairs, l, r, count);
    vpFrameCheck c;
    c.frame = k;
    c.role = session.getFrame(k).role;
    c.markers = count;
    c.left = rms(l, 2 * count);
    c.right = rms(r, 2 * count);
    c.rms = rms(l + r, 4 * count);
    c.fits = c.left <= m_mismatch && c.right <= m_mismatch;
    leftOff += c.left > m_mismatch ? 1 : 0;
    rightOff += c.right > m_mismatch ? 1 : 0;
    sumLeft += l;
    sumRight += r;
    total += count;
    checks.push_back(c);
    std::ostringstream os;
    os << "frame " << (k + 1) << "/" << session.getNumberOfFrames() << " (" << session.getFrame(k).left << ", "
       << vpProjectiveSession::toString(c.role) << "): " << count << " markers, left " << pixels(c.left) << ", right "
       << pixels(c.right) << (c.fits ? ": fits" : ": DOES NOT FIT");
    progress(os.str());
  }
  m_leftResidual = rms(sumLeft, 2 * total);
  m_rightResidual = rms(sumRight, 2 * total);
  m_state = leftOff == 0 && rightOff == 0 ? RIG_UNCHANGED
            : rightOff == 0               ? LEFT_CAMERA_MOVED
            : leftOff == 0                ? RIGHT_CAMERA_MOVED
                                          : BOTH_CAMERAS_MOVED;
  return checks;
}
