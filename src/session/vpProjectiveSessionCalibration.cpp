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
  vpProjectiveSessionCalibration: its settings and calibrate() (the arm acquired from a recorded session). The marker
  extraction is in vpProjectiveSessionMarkers.cpp, the check of a model and the model file in
  vpProjectiveSessionCheck.cpp.
*/

#include <visp3/projective/vpProjectiveSessionCalibration.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <sstream>
#include <utility>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpTime.h>
#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#include "acquisition/vpProjectiveAcquisitionInternal.h"
#include "core/vpProjectiveErrors.h"
#include "session/vpProjectiveSessionInternal.h"

using namespace vpProjectiveInternal;
using namespace vpProjectiveSessionInternal;

namespace
{

std::string amountText(vpProjectiveJoint::vpJointType type, double amount)
{
  std::ostringstream os;
  os << std::showpos << std::fixed;
  if (type == vpProjectiveJoint::REVOLUTE) {
    os << std::setprecision(2) << vpMath::deg(amount) << " deg";
  } else {
    os << std::setprecision(4) << amount << " m";
  }
  return os.str();
}
} // namespace

vpProjectiveSessionCalibration::vpProjectiveSessionCalibration(const vpMarkerExtractor &extractor)
    : m_extractor(extractor ? extractor : aprilTagMarkers("36h11")), m_os(nullptr), m_mounting(MOUNTING_AUTO),
      m_epipolar(2.0), m_outlier(0.0), m_coplanarity(2.0), m_mismatch(2.0), m_calibrated(false), m_model(), m_ids(),
      m_residual(0.0), m_algebraicResidual(0.0), m_joints(), m_state(RIG_UNCHANGED), m_leftResidual(0.0),
      m_rightResidual(0.0), m_recorded(false), m_layout(vpProjectiveCellFingerprint::LAYOUT_LEFT_RIGHT),
      m_fingerprint(), m_diagnosis()
{
}

void vpProjectiveSessionCalibration::setMarkerExtractor(const vpMarkerExtractor &extractor)
{
  if (!extractor) {
    fail(vpProjectiveException::invalidValueError, calibrationAt("setMarkerExtractor()"),
         "the extraction function is empty");
  }
  m_extractor = extractor;
}

void vpProjectiveSessionCalibration::setEpipolarThreshold(double pixels)
{
  m_epipolar = positive(pixels, calibrationAt("setEpipolarThreshold()"), "the epipolar threshold", "pixels");
}

void vpProjectiveSessionCalibration::setOutlierThreshold(double pixels)
{
  m_outlier = nonNegative(pixels, calibrationAt("setOutlierThreshold()"), "the outlier threshold",
                          "pixels; 0 keeps every observation");
}

void vpProjectiveSessionCalibration::setCoplanarityThreshold(double pixels)
{
  m_coplanarity = positive(pixels, calibrationAt("setCoplanarityThreshold()"), "the coplanarity threshold", "pixels");
}

void vpProjectiveSessionCalibration::setMismatchThreshold(double pixels)
{
  m_mismatch = positive(pixels, calibrationAt("setMismatchThreshold()"), "the mismatch threshold", "pixels");
}

void vpProjectiveSessionCalibration::progress(const std::string &line) const
{
  if (m_os != nullptr) {
    *m_os << line << std::endl;
  }
}

vpProjectiveArmModel vpProjectiveSessionCalibration::calibrate(const vpProjectiveSession &session)
{
  const std::string where = calibrationAt("calibrate()");
  const unsigned int n = session.getNumberOfJoints();
  const unsigned int zero = session.getZeroFrame();
  const std::vector<vpProjectiveJoint::vpJointType> &types = session.getJointTypes();

  // The frames used, in the file's order, and a trial per joint.
  std::vector<unsigned int> used;
  std::vector<unsigned int> trialsOf(n, 0);
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    const vpProjectiveSession::vpFrameRole role = session.getFrame(k).role;
    if (role == vpProjectiveSession::ZERO || role == vpProjectiveSession::TRIAL ||
        role == vpProjectiveSession::OBSERVATION) {
      used.push_back(k);
    }
    if (role == vpProjectiveSession::TRIAL) {
      ++trialsOf[static_cast<size_t>(session.getTrialJoint(k))];
    }
  }
  for (unsigned int i = 0; i < n; ++i) {
    if (trialsOf[i] == 0) {
      fail(vpProjectiveException::notInitializedError, where,
           "joint " + std::to_string(i) +
               " has no trial frame in the session; record trials of every joint (each "
               "joint alone, both ways from the zero reference)");
    }
  }
  {
    std::ostringstream os;
    os << "session '" << session.getFolder() << "': " << session.getNumberOfFrames() << " frames, " << n
       << " joints; using the zero frame, " << session.getNumberOfFrames(vpProjectiveSession::TRIAL) << " trials and "
       << session.getNumberOfFrames(vpProjectiveSession::OBSERVATION) << " observations";
    progress(os.str());
  }

  // Markers of every frame used.
  std::map<unsigned int, FrameMarkers> markers;
  for (unsigned int k : used) {
    markers[k] = extract(session, k, m_extractor, m_recorded, where);
    std::string role = vpProjectiveSession::toString(session.getFrame(k).role);
    const int joint = session.getTrialJoint(k);
    if (joint >= 0) {
      const double amount = session.getFrame(k).q[static_cast<unsigned int>(joint)] -
                            session.getFrame(zero).q[static_cast<unsigned int>(joint)];
      role += " of joint " + std::to_string(joint) + " by " + amountText(types[static_cast<size_t>(joint)], amount);
    }
    progress(frameName(k, session.getNumberOfFrames(), session.getFrame(k).left, role) + ": " +
             std::to_string(markers[k].ids.size()) + " markers");
  }

  // The markers of the model: those of the zero frame. A trial may miss some (identified markers: matched by id),
  // as long as it shows 5 of them.
  const std::vector<int> ids = markers[zero].ids;
  if (ids.size() < 5) {
    fail(vpProjectiveException::notEnoughPointsError, where,
         "only " + std::to_string(ids.size()) + " markers are seen in " + frameLabel(session, zero) +
             "; the arm's motion needs at least 5, 5 of them with no 4 coplanar: keep more tags in view of both "
             "cameras at the zero reference, or record it again");
  }
  for (unsigned int k : used) {
    if (session.getFrame(k).role != vpProjectiveSession::TRIAL) {
      continue;
    }
    size_t common = 0;
    for (int id : ids) {
      common += markers[k].find(id) >= 0 ? 1 : 0;
    }
    if (common < 5) {
      fail(vpProjectiveException::notEnoughPointsError, where,
           frameLabel(session, k) + " shows only " + std::to_string(common) + " of the " + std::to_string(ids.size()) +
               " markers of the zero frame; a trial needs 5 of them, with no 4 "
               "coplanar: record the trial again with a smaller motion, or remove it");
    }
  }
  std::vector<vpImagePoint> l0, r0;
  for (int id : ids) {
    const Eigen::Vector4d &s = markers[zero].s[static_cast<size_t>(markers[zero].find(id))];
    l0.push_back(vpImagePoint(s(1), s(0)));
    r0.push_back(vpImagePoint(s(3), s(2)));
  }
  const double transfer = vpProjectiveAcquisitionInternal::homographyTransferError(l0, r0);
  if (!(transfer >= m_coplanarity)) {
    std::ostringstream os;
    os << "the " << ids.size() << " markers of " << frameLabel(session, zero)
       << " are coplanar: one homography maps their left images onto the right ones within " << std::setprecision(3)
       << transfer << " px RMS (threshold " << m_coplanarity
       << " px); a rigid motion needs 5 markers of which no 4 are coplanar: add tags on another plane, a few "
          "centimetres in depth";
    fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
  }

  // The rig from every match of the frames used.
  std::vector<vpImagePoint> allLeft, allRight;
  for (unsigned int k : used) {
    for (const Eigen::Vector4d &s : markers[k].s) {
      allLeft.push_back(vpImagePoint(s(1), s(0)));
      allRight.push_back(vpImagePoint(s(3), s(2)));
    }
  }
  vpProjectiveStereoRig rig;
  try {
    rig.estimate(allLeft, allRight, m_epipolar);
  } catch (const vpException &e) {
    fail(vpProjectiveException::estimationFailedError, where,
         "the rig's epipolar geometry cannot be estimated from the " + std::to_string(allLeft.size()) +
             " marker matches of the session (" + e.getStringMessage() + ")");
  }
  {
    std::ostringstream os;
    os << "rig: fundamental matrix from " << allLeft.size() << " matches, " << std::setprecision(3)
       << rig.getEstimationResidual() << " px RMS epipolar residual";
    progress(os.str());
  }
  std::vector<Eigen::Vector4d> X;
  for (size_t j = 0; j < l0.size(); ++j) {
    X.push_back(
        rig.triangulate(Eigen::Vector2d(l0[j].get_u(), l0[j].get_v()), Eigen::Vector2d(r0[j].get_u(), r0[j].get_v())));
  }
  std::vector<unsigned int> best;
  const double parallax = vpProjectiveAcquisitionInternal::generalPositionParallax(rig, X, best);
  if (!(parallax >= m_coplanarity)) {
    std::ostringstream os;
    os << "the " << ids.size() << " markers of " << frameLabel(session, zero)
       << " are too close to coplanar: every set of 5 has 4 within " << std::setprecision(3) << parallax
       << " px RMS of plane parallax of a plane (threshold " << m_coplanarity
       << " px); add tags off the plane of the others, a few centimetres in depth";
    fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
  }

  // The acquisition.
  vpProjectiveArmAcquisition acquisition(types);
  std::vector<unsigned int> trialFrames;
  vpProjectiveArmModel model;
  try {
    acquisition.setStereoRig(rig);
    acquisition.setOutlierThreshold(m_outlier);
    acquisition.setZeroReference(session.getFrame(zero).q, ids, l0, r0);
    for (unsigned int k : used) {
      if (session.getFrame(k).role != vpProjectiveSession::TRIAL) {
        continue;
      }
      std::vector<int> seen;
      std::vector<vpImagePoint> l, r;
      for (int id : ids) {
        const int f = markers[k].find(id);
        if (f >= 0) {
          const Eigen::Vector4d &s = markers[k].s[static_cast<size_t>(f)];
          seen.push_back(id);
          l.push_back(vpImagePoint(s(1), s(0)));
          r.push_back(vpImagePoint(s(3), s(2)));
        }
      }
      acquisition.addTrialMotion(session.getFrame(k).q, seen, l, r);
      trialFrames.push_back(k);
    }
    model = acquisition.calibrate();
  } catch (const vpException &e) {
    // A model the check refused keeps its code: its message ranks the causes.
    fail(e.getCode() == vpProjectiveException::modelRejectedError ? e.getCode()
                                                                  : vpProjectiveException::estimationFailedError,
         where, "the arm cannot be calibrated from the session (" + e.getStringMessage() + ")");
  }

  const vpProjectiveCellFingerprint cell = cellOf(model, session);

  // The mounting.
  auto withMounting = [&model](vpProjectiveArmModel::vpRigMounting mounting) {
    std::vector<Eigen::Vector3d> axis, point;
    for (unsigned int i = 0; i < model.getNumberOfJoints(); ++i) {
      axis.push_back(model.axis(i));
      point.push_back(model.point(i));
    }
    return vpProjectiveArmModel(model.jointTypes(), mounting, model.getStereoRig(), model.projectiveToMetric(), axis,
                                point, model.markers(), model.zeroReferenceJoints());
  };
  auto pairsOf = [&ids, &markers](unsigned int k) {
    std::vector<std::pair<unsigned int, Eigen::Vector4d>> pairs;
    for (size_t j = 0; j < ids.size(); ++j) {
      const int f = markers[k].find(ids[j]);
      if (f >= 0) {
        pairs.push_back(std::make_pair(static_cast<unsigned int>(j), markers[k].s[static_cast<size_t>(f)]));
      }
    }
    return pairs;
  };
  const unsigned int observations = session.getNumberOfFrames(vpProjectiveSession::OBSERVATION);
  if (m_mounting != MOUNTING_AUTO) {
    model = withMounting(m_mounting == MOUNTING_EYE_IN_HAND ? vpProjectiveArmModel::EYE_IN_HAND
                                                            : vpProjectiveArmModel::EYE_TO_HAND);
    progress(std::string("mounting: ") + (m_mounting == MOUNTING_EYE_IN_HAND ? "eye-in-hand" : "eye-to-hand") +
             " (as set)");
  } else if (observations == 0) {
    model = withMounting(vpProjectiveArmModel::EYE_TO_HAND);
    progress("mounting: eye-to-hand (no observation frame tells it; set it if the cameras ride on the arm)");
  } else {
    double error[2] = {0.0, 0.0};
    vpProjectiveArmModel candidate[2] = {withMounting(vpProjectiveArmModel::EYE_TO_HAND),
                                         withMounting(vpProjectiveArmModel::EYE_IN_HAND)};
    for (int c = 0; c < 2; ++c) {
      double l = 0.0, r = 0.0;
      unsigned int count = 0;
      for (unsigned int k : used) {
        if (session.getFrame(k).role == vpProjectiveSession::OBSERVATION) {
          predictionError(candidate[c], session.getFrame(k).q, pairsOf(k), l, r, count);
        }
      }
      error[c] = rms(l + r, 4 * count);
    }
    const int kept = error[1] < error[0] ? 1 : 0;
    model = candidate[kept];
    progress(std::string("mounting: ") + (kept == 1 ? "eye-in-hand" : "eye-to-hand") + " (the " +
             std::to_string(observations) + " observation frames predicted within " + pixels(error[kept]) +
             " RMS; the other mounting: " + pixels(error[1 - kept]) + ")");
  }

  // The metric self-calibration's frames: the acquisition's, and the observation, target and servo frames (views of
  // the markers at known readings). One that shows none of the model's markers is left out, and said so.
  unsigned int views = 0;
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    const vpProjectiveSession::vpFrameRole role = session.getFrame(k).role;
    if (role != vpProjectiveSession::OBSERVATION && role != vpProjectiveSession::TARGET &&
        role != vpProjectiveSession::SERVO) {
      continue;
    }
    try {
      if (markers.find(k) == markers.end()) {
        markers[k] = extract(session, k, m_extractor, m_recorded, where);
      }
      std::vector<int> seen;
      std::vector<vpImagePoint> l, r;
      for (const std::pair<unsigned int, Eigen::Vector4d> &p : pairsOf(k)) {
        seen.push_back(ids[p.first]);
        l.push_back(vpImagePoint(p.second(1), p.second(0)));
        r.push_back(vpImagePoint(p.second(3), p.second(2)));
      }
      acquisition.addCalibrationFrame(session.getFrame(k).q, seen, l, r);
      ++views;
    } catch (const vpException &e) {
      progress(frameLabel(session, k) + ": left out of the metric self-calibration (" + e.getStringMessage() + ")");
    }
  }
  const std::vector<vpProjectiveArmAcquisition::vpFrame> frames = acquisition.getFrames();
  try {
    const vpProjectiveSelfCalibration selfCalibration(model, frames);
    std::string what;
    const double largest = selfCalibration.getLargestUncertainty(&what);
    std::ostringstream os;
    os << "metric self-calibration: " << selfCalibration.getNumberOfFrames() << " frames (" << views
       << " observation, target and servo frames), noise " << pixels(selfCalibration.getNoiseLevel())
       << ", largest uncertainty " << what << " (" << std::setprecision(3) << largest * 180.0 / M_PI << " deg)";
    progress(os.str());
  } catch (const vpException &e) {
    progress("metric self-calibration: not available (" + e.getStringMessage() + ")");
  }

  // Per-joint summary.
  std::vector<vpJointSummary> joints(n);
  std::vector<double> sums(n, 0.0);
  std::vector<unsigned int> counts(n, 0);
  for (unsigned int i = 0; i < n; ++i) {
    joints[i] = vpJointSummary{types[i], 0, 0.0, 0.0, 0.0};
  }
  for (unsigned int k : trialFrames) {
    const unsigned int i = static_cast<unsigned int>(session.getTrialJoint(k));
    const double amount = session.getFrame(k).q[i] - session.getFrame(zero).q[i];
    vpJointSummary &summary = joints[i];
    summary.smallest = summary.trials == 0 ? amount : std::min(summary.smallest, amount);
    summary.largest = summary.trials == 0 ? amount : std::max(summary.largest, amount);
    ++summary.trials;
    double l = 0.0, r = 0.0;
    predictionError(model, session.getFrame(k).q, pairsOf(k), l, r, counts[i]);
    sums[i] += l + r;
  }
  for (unsigned int i = 0; i < n; ++i) {
    joints[i].residual = rms(sums[i], 4 * counts[i]);
    std::ostringstream os;
    os << "joint " << i << " (" << vpProjectiveJoint::name(types[i]) << "): " << joints[i].trials << " trials from "
       << amountText(types[i], joints[i].smallest) << " to " << amountText(types[i], joints[i].largest)
       << ", prediction " << pixels(joints[i].residual) << " RMS";
    progress(os.str());
  }
  {
    std::ostringstream os;
    os << "model: " << ids.size() << " markers, bundle adjustment " << pixels(acquisition.getCalibrationResidual())
       << " RMS (algebraic generators: " << pixels(acquisition.getAlgebraicResidual()) << "), "
       << acquisition.getNumberOfOutliers() << " outliers left out";
    progress(os.str());
  }

  m_model = model;
  m_ids = ids;
  m_frames = frames;
  m_residual = acquisition.getCalibrationResidual();
  m_algebraicResidual = acquisition.getAlgebraicResidual();
  m_joints = joints;
  m_fingerprint = cell;
  m_calibrated = true;
  return model;
}

vpProjectiveCellFingerprint vpProjectiveSessionCalibration::cellOf(const vpProjectiveArmModel &model,
                                                                   const vpProjectiveSession &session) const
{
  vpProjectiveCellFingerprint cell;
  cell.setImageSize(session.getWidth(), session.getHeight());
  cell.setCameras(session.getLeftCamera(), session.getRightCamera());
  const bool anyLayout = m_layout == vpProjectiveCellFingerprint::LAYOUT_ANY ||
                         session.getCameraLayout() == vpProjectiveCellFingerprint::LAYOUT_ANY;
  cell.setCameraLayout(anyLayout ? vpProjectiveCellFingerprint::LAYOUT_ANY
                                 : vpProjectiveCellFingerprint::LAYOUT_LEFT_RIGHT);
  Eigen::Vector3d direction;
  const vpProjectiveCellFingerprint::vpCameraSide side = vpProjectiveCellFingerprint::cameraSide(model, direction);
  cell.setCameraSide(side, direction);
  std::ostringstream os;
  os << std::fixed << std::setprecision(2) << "(" << direction(0) << ", " << direction(1) << ", " << direction(2)
     << ")";
  if (side == vpProjectiveCellFingerprint::SIDE_LEFT && !anyLayout) {
    fail(vpProjectiveException::invalidValueError, calibrationAt("calibrate()"),
         "the left and right images are exchanged: the metric self-calibration puts the right camera to the LEFT of "
         "the left one (the baseline's direction " +
             os.str() +
             " in the left camera's frame; upright cameras named as seen from behind them have it along +x); "
             "exchange the left and right cameras (their devices or cables, or the session's left and right images) "
             "and record again, or, for a camera mounted upside down or seen through a mirror, say so "
             "(visp-projective calibrate --camera-layout any; the session's \"camera_layout\": \"any\"; "
             "setCameraLayout(LAYOUT_ANY))");
  }
  progress("cameras: the right camera is " + vpProjectiveCellFingerprint::toString(side) +
           (side == vpProjectiveCellFingerprint::SIDE_UNKNOWN ? std::string()
                                                              : " (the baseline's direction " + os.str() + ")") +
           (anyLayout ? "; any layout: not checked" : std::string()) +
           (session.hasCameras() ? "; left: " + vpProjectiveCellFingerprint::toString(session.getLeftCamera()) +
                                       ", right: " + vpProjectiveCellFingerprint::toString(session.getRightCamera())
                                 : std::string()));
  return cell;
}
