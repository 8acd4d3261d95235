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
  (whether a camera moved; the diagnosis of frames that do not fit is in vpProjectiveSessionDiagnosis.cpp).
*/

#include <visp3/projective/vpProjectiveSessionCalibration.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <unistd.h>

#include <visp3/projective/vpProjectiveModelFile.h>

#include "core/vpProjectiveErrors.h"
#include "session/vpProjectiveSessionInternal.h"

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
  vpProjectiveSessionInternal::writeAtomically(filename,
                                               vpProjectiveModelFile::toString(m_model, m_residual, m_algebraicResidual,
                                                                               m_ids, m_frames, nullptr,
                                                                               &m_fingerprint),
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
  case BOTH_CAMERAS_MOVED:
    return "both cameras moved since the model was made (both images are off, a re-registered rig fits them): "
           "re-register the rig (vpProjectiveRobot::updateRig()) or calibrate again";
  case CAMERAS_SWAPPED:
    return "the left and right images are exchanged (the model fits them exchanged): exchange the cameras and record "
           "again";
  case MARKERS_MOVED:
    return "the markers moved on the tool since the model was made (the rig did not change): calibrate again";
  case OTHER_READINGS:
    return "the readings are not the model's encoders (another arm, the joints in another order, other units or "
           "zero): record the model's encoders, or calibrate this arm";
  default:
    return "the session is of another cell than the model's: check it against its own cell's model, or calibrate "
           "this cell";
  }
}

std::string vpProjectiveSessionCalibration::getDiagnosisMessage() const
{
  if (m_diagnosis.empty()) {
    return toString(m_state);
  }
  std::string likely, ruledOut;
  for (size_t c = 0; c < m_diagnosis.size(); ++c) {
    const vpCheckDiagnosis &d = m_diagnosis[c];
    if (c == 0) {
      likely = d.finding + ": " + d.fix;
    } else if (d.likely) {
      likely += (c == 1 ? ". Also possible: " : "; ") + d.finding;
    } else {
      // The residual with the fix where it shows why (some fixes fit and are ruled out by a simpler one that fits).
      const std::string residual = d.residualIfFixed > m_mismatch ? " (" + pixels(d.residualIfFixed) + ")" : "";
      ruledOut += (ruledOut.empty() ? ". Ruled out: " : ", ") + causeName(d.cause) + residual;
    }
  }
  return likely + ruledOut;
}

std::vector<vpProjectiveSessionCalibration::vpFrameCheck>
vpProjectiveSessionCalibration::check(const vpProjectiveArmModel &model, const std::vector<int> &ids,
                                      const vpProjectiveSession &session, const vpProjectiveCellFingerprint &cell)
{
  const std::string where = calibrationAt("check()");
  if (model.getNumberOfJoints() == 0) {
    fail(vpProjectiveException::notInitializedError, where, "the model is empty; load one first");
  }
  const std::string otherArm =
      vpProjectiveCellFingerprint::jointTypesMismatch(model.jointTypes(), session.getJointTypes());
  if (!otherArm.empty()) {
    fail(vpProjectiveException::dimensionError, where,
         "the session is of another arm: " + otherArm +
             " (its joint_types); check a session of the arm the model was made for");
  }
  if (ids.size() != model.markers().size()) {
    fail(vpProjectiveException::dimensionError, where,
         "the model has " + std::to_string(model.markers().size()) + " markers and " + std::to_string(ids.size()) +
             " marker identifiers; use a model calibrated from a session (visp-projective calibrate)");
  }
  std::vector<vpFrameCheck> checks;
  MismatchInput in{model, ids, session, cell, std::vector<CheckedFrame>(), m_mismatch, 0, 0, 0.0, 0.0, 0, 0};
  double sumLeft = 0.0, sumRight = 0.0;
  unsigned int total = 0;
  std::set<int> seen, others;
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    const FrameMarkers markers = extract(session, k, m_extractor, m_recorded, where);
    std::vector<std::pair<unsigned int, Eigen::Vector4d>> pairs;
    for (size_t j = 0; j < ids.size(); ++j) {
      const int f = markers.find(ids[j]);
      if (f >= 0) {
        pairs.push_back(std::make_pair(static_cast<unsigned int>(j), markers.s[static_cast<size_t>(f)]));
        seen.insert(ids[j]);
      }
    }
    for (int id : markers.ids) {
      if (std::find(ids.begin(), ids.end(), id) == ids.end()) {
        others.insert(id);
      }
    }
    if (pairs.empty()) {
      fail(vpProjectiveException::notEnoughPointsError, where,
           frameLabel(session, k) + ": none of the model's " + std::to_string(ids.size()) +
               " markers is seen in both images, " + std::to_string(markers.ids.size()) + " others are (identifiers " +
               std::to_string(markers.ids.front()) + " to " + std::to_string(markers.ids.back()) + ", the model's " +
               std::to_string(*std::min_element(ids.begin(), ids.end())) + " to " +
               std::to_string(*std::max_element(ids.begin(), ids.end())) +
               "): the session is of another cell, or the tags face away; check the session against its own cell's "
               "model, or remove the frame from session.json");
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
    in.leftOff += c.left > m_mismatch ? 1 : 0;
    in.rightOff += c.right > m_mismatch ? 1 : 0;
    sumLeft += l;
    sumRight += r;
    total += count;
    checks.push_back(c);
    in.frames.push_back(CheckedFrame{session.getFrame(k).q, jointsOf(session.getFrame(k).q), pairs});
    std::ostringstream os;
    os << frameLabel(session, k) << ": " << count << " markers, left " << pixels(c.left) << ", right "
       << pixels(c.right) << (c.fits ? ": fits" : ": DOES NOT FIT");
    progress(os.str());
  }
  in.leftResidual = rms(sumLeft, 2 * total);
  in.rightResidual = rms(sumRight, 2 * total);
  in.modelIdsSeen = seen.size();
  in.otherIds = others.size();
  std::vector<vpCheckDiagnosis> diagnosis;
  if (in.leftOff > 0 || in.rightOff > 0) {
    diagnosis = diagnoseMismatch(in);
  }
  m_leftResidual = in.leftResidual;
  m_rightResidual = in.rightResidual;
  m_diagnosis = diagnosis;
  m_state = m_diagnosis.empty() ? RIG_UNCHANGED : m_diagnosis.front().cause;
  return checks;
}
