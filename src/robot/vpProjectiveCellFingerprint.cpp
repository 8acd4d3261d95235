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

#include <visp3/projective/vpProjectiveCellFingerprint.h>

#include <cmath>

#include <visp3/core/vpException.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveCellFingerprint");

//! cos 45 deg: the cone around the left camera's x axis in which the right camera is said to be on one side.
const double kSideCone = std::sqrt(0.5);
} // namespace

vpProjectiveCellFingerprint::vpProjectiveCellFingerprint()
    : m_width(0), m_height(0), m_left(), m_right(), m_layout(LAYOUT_LEFT_RIGHT), m_side(SIDE_UNKNOWN),
      m_baseline(Eigen::Vector3d::Zero())
{
}

vpProjectiveCellFingerprint::vpCameraSide vpProjectiveCellFingerprint::cameraSide(const vpProjectiveArmModel &model,
                                                                                  Eigen::Vector3d &direction)
{
  direction.setZero();
  Eigen::Matrix3d Kl, Kr;
  Eigen::Matrix4d lMr;
  try {
    vpProjectiveSelfCalibration::metricStereoRig(model, Kl, Kr, lMr, vpProjectiveSelfCalibration::SCALE_UNIT_BASELINE);
  } catch (const vpException &) {
    return SIDE_UNKNOWN; // no metric frame: nothing tells which camera is left
  }
  const Eigen::Vector3d t = lMr.block<3, 1>(0, 3);
  if (!t.allFinite() || !(t.norm() > 0.0)) {
    return SIDE_UNKNOWN;
  }
  direction = t.normalized();
  return direction(0) >= kSideCone ? SIDE_RIGHT : direction(0) <= -kSideCone ? SIDE_LEFT : SIDE_ABOVE_BELOW;
}

void vpProjectiveCellFingerprint::setImageSize(unsigned int width, unsigned int height)
{
  m_width = width;
  m_height = height;
}

void vpProjectiveCellFingerprint::setCameras(const vpStereoImageSource::vpCameraIdentity &left,
                                             const vpStereoImageSource::vpCameraIdentity &right)
{
  m_left = left;
  m_right = right;
}

void vpProjectiveCellFingerprint::setCameraSide(vpCameraSide side, const Eigen::Vector3d &direction)
{
  if (!direction.allFinite() || (direction.norm() != 0.0 && std::fabs(direction.norm() - 1.0) > 1e-6)) {
    fail(vpProjectiveException::invalidValueError, at("setCameraSide()"),
         "the baseline direction must be a finite unit vector, or zero when not known");
  }
  m_side = side;
  m_baseline = direction;
}

bool vpProjectiveCellFingerprint::isKnown(const vpStereoImageSource::vpCameraIdentity &camera)
{
  return !camera.device.empty() || !camera.name.empty() || !camera.bus.empty() || !camera.serial.empty();
}

int vpProjectiveCellFingerprint::sameCamera(const vpStereoImageSource::vpCameraIdentity &a,
                                            const vpStereoImageSource::vpCameraIdentity &b)
{
  if (!a.serial.empty() && !b.serial.empty()) {
    return a.serial == b.serial ? 1 : 0;
  }
  if (!a.bus.empty() && !b.bus.empty() && !a.name.empty() && !b.name.empty()) {
    return a.bus == b.bus && a.name == b.name ? 1 : 0;
  }
  if (!a.device.empty() && !b.device.empty()) {
    // A name present on both sides must agree too; the device alone tells when neither has one.
    if (!a.name.empty() && !b.name.empty() && a.name != b.name) {
      return 0;
    }
    return a.device == b.device ? 1 : 0;
  }
  return -1;
}

std::string vpProjectiveCellFingerprint::cameraMismatch(const vpStereoImageSource::vpCameraIdentity &left,
                                                        const vpStereoImageSource::vpCameraIdentity &right) const
{
  if (sameCamera(left, m_right) == 1 && sameCamera(right, m_left) == 1) {
    return "the left and right cameras are exchanged: the left one, " + toString(left) +
           ", is the model's right camera; exchange the cameras (their devices or cables) or give them in the "
           "model's order";
  }
  if (sameCamera(left, m_left) == 0 || sameCamera(right, m_right) == 0) {
    return "the cameras are not the model's: " + toString(left) + " and " + toString(right) + ", the model's " +
           toString(m_left) + " and " + toString(m_right) +
           "; give the cameras of the model's cell, or acquire a "
           "model of these";
  }
  return std::string();
}

std::string vpProjectiveCellFingerprint::imageSizeMismatch(unsigned int width, unsigned int height) const
{
  if (m_width == 0 || width == 0 || (width == m_width && height == m_height)) {
    return std::string();
  }
  return "the left images are " + std::to_string(width) + " x " + std::to_string(height) + " pixels, the model's " +
         std::to_string(m_width) + " x " + std::to_string(m_height);
}

std::string vpProjectiveCellFingerprint::jointTypesMismatch(const std::vector<vpProjectiveJoint::vpJointType> &model,
                                                            const std::vector<vpProjectiveJoint::vpJointType> &arm)
{
  if (arm.size() != model.size()) {
    return "it has " + std::to_string(arm.size()) + " joints, the model " + std::to_string(model.size());
  }
  for (size_t i = 0; i < arm.size(); ++i) {
    if (arm[i] != model[i]) {
      return "its joint " + std::to_string(i) + " is " + vpProjectiveJoint::name(arm[i]) + ", the model's " +
             vpProjectiveJoint::name(model[i]);
    }
  }
  return std::string();
}

std::string vpProjectiveCellFingerprint::toString(const vpStereoImageSource::vpCameraIdentity &camera)
{
  if (!isKnown(camera)) {
    return "an unknown camera";
  }
  std::string details;
  auto add = [&details](const std::string &what) { details += (details.empty() ? "" : ", ") + what; };
  if (!camera.name.empty()) {
    add(camera.name);
  }
  if (!camera.serial.empty()) {
    add("serial " + camera.serial);
  }
  if (!camera.bus.empty() && camera.serial.empty()) {
    add("on " + camera.bus);
  }
  const std::string device = camera.device.empty() ? "a camera" : "'" + camera.device + "'";
  return details.empty() ? device : device + " (" + details + ")";
}

std::string vpProjectiveCellFingerprint::toString(vpCameraSide side)
{
  switch (side) {
  case SIDE_RIGHT:
    return "to the right of the left camera";
  case SIDE_LEFT:
    return "to the LEFT of the left camera";
  case SIDE_ABOVE_BELOW:
    return "above, below, before or behind the left camera (the images do not tell left from right)";
  default:
    return "not known (no metric self-calibration)";
  }
}

std::string vpProjectiveCellFingerprint::toString(vpCameraLayout layout)
{
  return layout == LAYOUT_ANY ? "any" : "left-right";
}
