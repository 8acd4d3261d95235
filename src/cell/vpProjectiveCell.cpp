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
  \file vpProjectiveCell.cpp
  \brief The real-cell program: its settings and safety range, the images it takes, the acquisition, the moves.
*/

#include <visp3/projective/vpProjectiveCell.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <exception>
#include <sstream>
#include <thread>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveCellFingerprint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveModelFile.h>

#include "cell/vpProjectiveCellInternal.h"

using namespace vpProjectiveInternal;
using vpProjectiveCellInternal::at;

namespace
{
void requirePositive(double x, const char *name)
{
  if (!std::isfinite(x) || !(x > 0.0)) {
    std::ostringstream os;
    os << "the setting " << name << " must be finite and > 0, not " << x;
    fail(vpProjectiveException::invalidValueError, at("vpProjectiveCell()"), os.str());
  }
}
} // namespace

vpProjectiveCell::vpSettings::vpSettings()
    : qmin(), qmax(), limitMarginRotation(vpMath::rad(5.0)), maxRotationSpeed(vpMath::rad(15.0)),
      amountRotation(vpMath::rad(15.0)), stepRotation(vpMath::rad(2.0))
{
}

vpProjectiveCell::vpSettings::vpSettings(const vpSettings &other) : vpSettings()
{
  *this = other;
}

vpProjectiveCell::vpProjectiveCell(vpProjectiveCellArm &arm, vpStereoImageSource &cameras,
                                   const vpProjectiveSessionCalibration::vpMarkerExtractor &markers,
                                   const vpSettings &settings)
    : m_arm(arm), m_cameras(cameras), m_markers(markers), m_settings(settings), m_types(arm.getJointTypes()), m_lower(),
      m_upper(), m_robot(), m_model(m_types), m_markerIds(), m_targetIds(), m_targetLeft(), m_targetRight(), m_writer(),
      m_recording(), m_os(nullptr), m_Ileft(), m_Iright(), m_history()
{
  const unsigned int n = static_cast<unsigned int>(m_types.size());
  if (!m_markers) {
    fail(vpProjectiveException::invalidValueError, at("vpProjectiveCell()"), "the marker extraction is empty");
  }
  const vpSettings &s = settings;
  for (const auto &setting :
       {std::make_pair(s.limitMarginRotation, "limitMarginRotation"),
        std::make_pair(s.limitMarginTranslation, "limitMarginTranslation"),
        std::make_pair(s.maxRotationSpeed, "maxRotationSpeed"),
        std::make_pair(s.maxTranslationSpeed, "maxTranslationSpeed"),
        std::make_pair(s.amountRotation, "amountRotation"), std::make_pair(s.amountTranslation, "amountTranslation"),
        std::make_pair(s.stepRotation, "stepRotation"), std::make_pair(s.stepTranslation, "stepTranslation"),
        std::make_pair(s.arrivalTolerance, "arrivalTolerance"), std::make_pair(s.gain, "gain"),
        std::make_pair(s.period, "period"), std::make_pair(s.timeout, "timeout"),
        std::make_pair(s.convergedError, "convergedError"), std::make_pair(s.maxLostTime, "maxLostTime"),
        std::make_pair(s.maxSkew, "maxSkew"), std::make_pair(s.maxLatency, "maxLatency"),
        std::make_pair(s.minFrameRate, "minFrameRate")}) {
    requirePositive(setting.first, setting.second);
  }
  for (const double x : {s.imageMargin, s.imageBorder, s.moveTimeout, s.settleTime}) {
    if (!std::isfinite(x) || x < 0.0) {
      fail(vpProjectiveException::invalidValueError, at("vpProjectiveCell()"),
           "the image margin and border, the move timeout and the settle time must be finite and >= 0");
    }
  }
  if (s.targetFrames == 0 || s.convergedFrames == 0) {
    fail(vpProjectiveException::invalidValueError, at("vpProjectiveCell()"),
         "targetFrames and convergedFrames must be at least 1");
  }
  // The speeds: the settings', below the arm's own.
  const vpColVector armSpeeds = arm.getMaxJointVelocities();
  if (armSpeeds.size() != n) {
    fail(vpProjectiveException::dimensionError, at("vpProjectiveCell()"),
         "the arm gives " + std::to_string(armSpeeds.size()) + " largest speeds for " + std::to_string(n) +
             " joints: check the adapter's getMaxJointVelocities()");
  }
  vpColVector speeds(n);
  for (unsigned int i = 0; i < n; ++i) {
    const double mine = m_types[i] == vpProjectiveJoint::REVOLUTE ? s.maxRotationSpeed : s.maxTranslationSpeed;
    speeds[i] = armSpeeds[i] > 0.0 ? std::min(mine, armSpeeds[i]) : mine;
  }
  // The limits: the user's, else the arm's; none only when the user says so.
  vpColVector qmin, qmax; // assigned, not copy-constructed: ViSP 3.5 copies an empty vector by memcpy from null
  qmin = s.qmin;
  qmax = s.qmax;
  std::string from = "the settings";
  if (qmin.size() == 0 && qmax.size() == 0) {
    from = "the arm";
    if (!arm.getJointLimits(qmin, qmax)) {
      qmin = qmax = vpColVector();
      if (!s.noJointLimits) {
        fail(vpProjectiveException::invalidValueError, at("vpProjectiveCell()"),
             "the arm knows no joint limits: give them (vpSettings::qmin and qmax; visp-projective servo --qmin "
             "and --qmax), or say that the arm has none (vpSettings::noJointLimits; --no-joint-limits). Nothing "
             "moved");
      }
    }
  }
  if (qmin.size() != 0 || qmax.size() != 0) {
    if (qmin.size() != n || qmax.size() != n) {
      fail(vpProjectiveException::dimensionError, at("vpProjectiveCell()"),
           "the joint limits of " + from + " have " + std::to_string(qmin.size()) + " and " +
               std::to_string(qmax.size()) + " values for " + std::to_string(n) + " joints: give one per joint");
    }
    m_lower = qmin;
    m_upper = qmax;
    for (unsigned int i = 0; i < n; ++i) {
      const double margin =
          m_types[i] == vpProjectiveJoint::REVOLUTE ? s.limitMarginRotation : s.limitMarginTranslation;
      m_lower[i] += margin;
      m_upper[i] -= margin;
    }
  }
  m_robot.reset(new vpProjectiveCellRobot(arm, m_lower, m_upper, speeds)); // checks the range
}

vpProjectiveCell::~vpProjectiveCell()
{
  if (m_robot) {
    m_robot->stop();
  }
  if (m_writer) {
    try {
      m_writer->close();
    } catch (...) {
    }
  }
}

void vpProjectiveCell::progress(const std::string &line) const
{
  if (m_os != nullptr) {
    *m_os << line << std::endl;
  }
}

void vpProjectiveCell::setRecording(const std::string &folder)
{
  std::unique_ptr<vpProjectiveSessionWriter> writer(new vpProjectiveSessionWriter(folder, m_types));
  writer->setCameras(m_cameras); // which camera is left, so that check and loadModel() tell exchanged ones
  m_writer = std::move(writer);
  m_recording = folder;
}

void vpProjectiveCell::record(int role, const vpColVector &q, double t)
{
  if (!m_writer || m_writer->isClosed()) {
    return;
  }
  if (role < 0) {
    m_writer->addAcquisitionFrame(q, t, m_Ileft, m_Iright);
  } else {
    m_writer->addFrame(static_cast<vpProjectiveSession::vpFrameRole>(role), q, t, m_Ileft, m_Iright);
  }
}

void vpProjectiveCell::remember(double t, const vpColVector &q)
{
  if (!m_history.empty() && !(t > m_history.back().first)) {
    m_history.back().second = q;
    return;
  }
  m_history.emplace_back(t, q);
  while (m_history.size() > 2 && m_history[1].first < t - 2.0) {
    m_history.pop_front();
  }
}

vpColVector vpProjectiveCell::jointsAt(double t) const
{
  if (m_history.empty()) {
    return vpColVector();
  }
  if (!(t > m_history.front().first)) {
    return m_history.front().second;
  }
  for (size_t k = 1; k < m_history.size(); ++k) {
    if (t <= m_history[k].first) {
      const double a = (t - m_history[k - 1].first) / (m_history[k].first - m_history[k - 1].first);
      return m_history[k - 1].second + a * (m_history[k].second - m_history[k - 1].second);
    }
  }
  return m_history.back().second;
}

void vpProjectiveCell::grab(bool atRest, vpFrame &frame)
{
  // At rest, an image must show the arm still: taken settleTime after it stopped, or not before the joints were
  // last read (a camera without latency), by its stamps; without stamps, after discardFrames images (a camera queues
  // a few, taken while the arm moved).
  for (unsigned int attempt = 0;; ++attempt) {
    if (!m_cameras.acquire(m_Ileft, m_Iright)) {
      fail(vpProjectiveException::notEnoughPointsError, at("grab()"),
           "the cameras gave no more images: check that they are running");
    }
    frame.stamped = m_cameras.getTimestamps(frame.tLeft, frame.tRight);
    if (!atRest) {
      break;
    }
    vpColVector q;
    double now = 0.0;
    m_robot->getJoints(q, now);
    if (frame.stamped
            ? std::min(frame.tLeft, frame.tRight) >= std::min(m_robot->getRestTime() + m_settings.settleTime, now)
            : attempt >= m_settings.discardFrames) {
      break;
    }
    if (attempt >= 1000) {
      fail(vpProjectiveException::estimationFailedError, at("grab()"),
           "1000 images in a row were taken before the arm stopped, by their time stamps: the cameras' time stamps "
           "are not on the clock of the arm's readings (vpStereoImageSource::getTimestamps())");
    }
  }
  const unsigned int found = m_markers(m_Ileft, m_Iright, frame.ids, frame.left, frame.right);
  if (found != frame.ids.size() || found != frame.left.size() || found != frame.right.size()) {
    fail(vpProjectiveException::dimensionError, at("grab()"),
         "the marker extraction must give one identifier, one left and one right point per marker");
  }
}

void vpProjectiveCell::acquire()
{
  vpStopGuard guard(*m_robot);
  const unsigned int n = static_cast<unsigned int>(m_types.size());
  auto source = [this](std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
    vpFrame frame;
    grab(true, frame);
    vpColVector q;
    double t = 0.0;
    m_robot->getJoints(q, t);
    if (frame.ids.size() >= 5) {
      record(-1, q, t);
    }
    ids = frame.ids;
    left = frame.left;
    right = frame.right;
    return true;
  };
  vpProjectiveAcquisitionProcedure procedure(source, m_cameras.getWidth(), m_cameras.getHeight());
  vpColVector amounts(n), steps(n), minimum(n);
  for (unsigned int i = 0; i < n; ++i) {
    const bool revolute = m_types[i] == vpProjectiveJoint::REVOLUTE;
    amounts[i] = revolute ? m_settings.amountRotation : m_settings.amountTranslation;
    steps[i] = std::min(amounts[i], revolute ? m_settings.stepRotation : m_settings.stepTranslation);
    minimum[i] = std::min(amounts[i], revolute ? vpMath::rad(5.0) : 0.01); // the procedure's defaults, or less
  }
  procedure.setMaxAmounts(amounts);
  procedure.setSteps(steps);
  procedure.setMinAmounts(minimum);
  if (m_lower.size() != 0) {
    procedure.setJointLimits(m_lower, m_upper, 0.0); // the safe range already keeps its margin
  }
  procedure.setImageMargin(m_settings.imageMargin);
  procedure.setSpeed(m_settings.maxRotationSpeed, m_settings.maxTranslationSpeed);
  procedure.setMoveTimeout(m_settings.moveTimeout);
  procedure.setArrivalTolerance(m_settings.arrivalTolerance);
  procedure.setOutput(m_os);
  vpProjectiveRobot model(m_types);
  procedure.run(*m_robot, model);
  m_model = model;
  m_markerIds = model.getAcquisition().getMarkerIds();
  if (m_writer) {
    m_writer->save();
  }
  std::ostringstream os;
  os << "model: residual " << procedure.getCalibrationResidual() << " px RMS, encoder noise "
     << (procedure.getEncoderNoise().size() ? procedure.getEncoderNoise().getMaxValue() : 0.0) << " (rad or m)";
  progress(os.str());
}

void vpProjectiveCell::loadModel(const std::string &file)
{
  vpProjectiveRobot model(m_types);
  model.loadModel(file);
  if (model.getNumberOfJoints() != m_types.size()) {
    fail(vpProjectiveException::dimensionError, at("loadModel()"),
         "the model '" + file + "' has " + std::to_string(model.getNumberOfJoints()) + " joints, the arm " +
             std::to_string(m_types.size()) + ": give the model of this arm");
  }
  std::vector<int> ids;
  vpProjectiveCellFingerprint cell;
  vpProjectiveModelFile::load(file, nullptr, nullptr, &ids, nullptr, &cell);
  // The fingerprint of the model's cell against this one, the likeliest mistake first: the cameras exchanged or
  // others, the arm's joint kinds, the images' size (the model's matrices are in its pixels).
  std::string mismatch;
  vpStereoImageSource::vpCameraIdentity left, right;
  if (m_cameras.getCameraIdentities(left, right)) {
    mismatch = cell.cameraMismatch(left, right);
  }
  const std::string otherArm = vpProjectiveCellFingerprint::jointTypesMismatch(model.getModel().jointTypes(), m_types);
  if (mismatch.empty() && !otherArm.empty()) {
    mismatch = "the arm is not the model's: " + otherArm +
               "; give the model of this arm, or declare its joints' kinds as they are (vpProjectiveCellArm::"
               "getJointTypes())";
  }
  const std::string otherSize = cell.imageSizeMismatch(m_cameras.getWidth(), m_cameras.getHeight());
  if (mismatch.empty() && !otherSize.empty()) {
    mismatch = "the cameras are not set as the model's: " + otherSize +
               "; give the cameras the model's resolution, or acquire a model at this one";
  }
  if (!mismatch.empty()) {
    fail(vpProjectiveException::invalidValueError, at("loadModel()"), "the model '" + file + "': " + mismatch);
  }
  m_markerIds = ids;
  m_model = model;
}

void vpProjectiveCell::saveModel(const std::string &file) const
{
  // With the markers' ids (AprilTag corners), so that visp-projective check compares it with recorded sessions, and
  // the fingerprint of the cell (its cameras, which is left), so that loadModel() and check compare it.
  vpProjectiveCellFingerprint cell;
  cell.setImageSize(m_cameras.getWidth(), m_cameras.getHeight());
  vpStereoImageSource::vpCameraIdentity left, right;
  if (m_cameras.getCameraIdentities(left, right)) {
    cell.setCameras(left, right);
  }
  Eigen::Vector3d direction;
  const vpProjectiveCellFingerprint::vpCameraSide side =
      vpProjectiveCellFingerprint::cameraSide(m_model.getModel(), direction);
  cell.setCameraSide(side, direction);
  vpProjectiveModelFile::save(file, m_model.getModel(), m_model.getAcquisition().getCalibrationResidual(),
                              m_model.getAcquisition().getAlgebraicResidual(), m_markerIds,
                              std::vector<vpProjectiveArmAcquisition::vpFrame>(), nullptr, &cell);
}

void vpProjectiveCell::moveTo(const vpColVector &target)
{
  vpStopGuard guard(*m_robot);
  const unsigned int n = static_cast<unsigned int>(m_types.size());
  if (target.size() != n) {
    fail(vpProjectiveException::dimensionError, at("moveTo()"),
         "give " + std::to_string(n) + " joint readings (rad, m), not " + std::to_string(target.size()));
  }
  double travel = 0.0;
  vpColVector q;
  double t0 = 0.0, t = 0.0;
  m_robot->getJoints(q, t0);
  for (unsigned int i = 0; i < n; ++i) {
    requireFinite(target[i], at("moveTo()"), "a joint reading");
    const bool revolute = m_types[i] == vpProjectiveJoint::REVOLUTE;
    if (m_lower.size() != 0 && (target[i] < m_lower[i] || target[i] > m_upper[i])) {
      std::ostringstream os;
      os << "joint " << i << " to " << target[i] << (revolute ? " rad" : " m") << " is outside the safe range ["
         << m_lower[i] << ", " << m_upper[i] << "] (the limits less their margin); nothing moved";
      fail(vpProjectiveException::invalidValueError, at("moveTo()"), os.str());
    }
    travel = std::max(travel, std::abs(target[i] - q[i]) /
                                  (revolute ? m_settings.maxRotationSpeed : m_settings.maxTranslationSpeed));
  }
  const double timeout = m_settings.moveTimeout > 0.0 ? m_settings.moveTimeout : 2.0 + 4.0 * travel;
  const auto wall0 = std::chrono::steady_clock::now();
  m_robot->setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  const double tolerance = std::max(m_settings.arrivalTolerance, 1e-3), tau = 0.25; // s: the approach's time constant
  for (t = t0;; m_robot->getJoints(q, t)) {
    const vpColVector e = target - q;
    if (e.getMaxValue() <= tolerance && -e.getMinValue() <= tolerance) {
      break;
    }
    const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - wall0).count();
    if (t - t0 > timeout || wall > timeout) {
      std::ostringstream os;
      os << "the arm did not reach the joints asked within " << timeout << " s (largest joint error "
         << std::max(e.getMaxValue(), -e.getMinValue()) << " rad or m): it was stopped; check the arm's state";
      fail(vpProjectiveException::robotMotionError, at("moveTo()"), os.str());
    }
    m_robot->setVelocity(vpRobot::ARTICULAR_FRAME, e / tau);
    remember(t, q);
    std::this_thread::sleep_for(std::chrono::microseconds(200)); // a real controller's readings need time to change
  }
  m_robot->setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector(n, 0.0)); // the rest time for the next images
}

std::string vpProjectiveCell::toString(vpServoEnd end)
{
  switch (end) {
  case SERVO_CONVERGED:
    return "converged";
  case SERVO_TIMEOUT:
    return "timeout";
  case SERVO_TAGS_LOST:
    return "tags lost";
  default:
    return "status";
  }
}
