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
  vpProjectiveArmAcquisition::calibrate() and its model check (vpProjectiveModelCheck): the acquisition of unknown
  joint types, the noise and the tolerance of the gate. The data and the trials are in vpProjectiveArmAcquisition.cpp.
*/

#include <visp3/projective/vpProjectiveArmAcquisition.h>

#include <cmath>
#include <limits>
#include <sstream>

#include "acquisition/vpArmModelCheck.h"
#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveArmAcquisition");
}

vpProjectiveArmAcquisition::vpProjectiveArmAcquisition(unsigned int n) : vpProjectiveArmAcquisition()
{
  if (n == 0 || n > vpProjectiveArmModel::maxJoints) {
    std::ostringstream os;
    os << "a chain has 1 to " << vpProjectiveArmModel::maxJoints << " joints, got " << n;
    fail(vpProjectiveException::dimensionError, at("constructor"), os.str());
  }
  m_types.assign(n, vpProjectiveJoint::REVOLUTE); // until calibrate() identifies them
  m_declared = false;
}

void vpProjectiveArmAcquisition::setImageNoise(double pixels)
{
  m_imageNoise = nonNegative(pixels, at("setImageNoise()"), "the image noise",
                             "pixels per coordinate; 0: estimated from the images");
}

void vpProjectiveArmAcquisition::setResidualTolerance(double factor)
{
  m_tolerance = nonNegative(factor, at("setResidualTolerance()"), "the residual tolerance",
                            "a factor of the image noise; 0 accepts any model");
}

vpProjectiveArmModel vpProjectiveArmAcquisition::calibrate()
{
  const std::string where = at("calibrate()");
  if (m_types.empty()) {
    fail(vpProjectiveException::notInitializedError, where, "the robot has no joints; construct it with joint types");
  }
  if (m_zeroImages.empty()) {
    fail(vpProjectiveException::notInitializedError, where,
         "no zero reference; call setStereoRig(), setZeroReference() and addTrialMotion() for every joint first");
  }
  ArmCheckInput in;
  ArmCalibrationData &data = in.data;
  data.types = m_types;
  data.mounting = m_mounting;
  data.rig = m_rig;
  data.zeroImages = m_zeroImages;
  std::vector<unsigned int> trials(m_types.size(), 0);
  for (const vpTrial &t : m_trials) {
    data.trials.push_back(ArmTrial{t.joint, t.amount, t.s, t.seen});
    data.inlier.push_back(t.seen); // a missing marker is no observation: never an inlier
    ++trials[t.joint];
  }
  for (size_t i = 0; i < trials.size(); ++i) {
    if (trials[i] == 0) {
      std::ostringstream os;
      os << "joint " << i << " has no trial motion; call addTrialMotion(" << i << ", amount, left, right) first";
      fail(vpProjectiveException::notInitializedError, where, os.str());
    }
  }
  data.outlierThreshold = m_outlierThreshold;
  const size_t K = m_zeroImages.size();
  in.M0.resize(K);
  for (size_t j = 0; j < K; ++j) {
    in.M0[j] =
        m_rig.triangulate(Eigen::Vector2d(m_zeroImages[j].head<2>()), Eigen::Vector2d(m_zeroImages[j].tail<2>()));
  }
  if (m_outlierThreshold > 0.0) {
    // The zero reference defines which marker is which: a marker whose two images there do not meet (a left-right
    // mismatch) cannot be repaired, only reported.
    for (size_t j = 0; j < K; ++j) {
      Eigen::Vector4d s;
      const double d = m_rig.project(in.M0[j], s) ? std::sqrt(0.5 * (s - m_zeroImages[j]).squaredNorm())
                                                  : std::numeric_limits<double>::infinity();
      if (!(d <= m_outlierThreshold)) {
        std::ostringstream os;
        os << "the left and right images of marker " << j << " at the zero reference are " << d
           << " px away from any 3D point (outlier threshold " << m_outlierThreshold
           << " px): they are not the same marker; fix the matching of the zero-reference images";
        fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
      }
    }
  }
  in.displacements = trialDisplacements(data);
  in.qRef = m_qRef;
  in.identify = !m_declared;
  in.givenNoise = m_imageNoise;
  in.tolerance = m_tolerance;
  const ArmCheck check = checkArmModel(in);

  vpProjectiveModelCheck result;
  result.m_checked = check.fit.ok || !check.causes.empty();
  result.m_accepted = check.accepted;
  result.m_residual = check.fit.ok ? check.fit.residual : std::numeric_limits<double>::infinity();
  result.m_noise = check.noise;
  result.m_epipolarNoise = check.epipolarNoise;
  result.m_givenNoise = m_imageNoise;
  result.m_limit = check.limit;
  result.m_joints = check.joints;
  result.m_causes = check.causes;
  result.m_message = check.message;
  if (!check.fit.ok && check.contradicted.empty() && !check.exchanged) {
    throw vpProjectiveException(check.fit.failureCode, check.fit.failure); // no model of any type: the fit's error
  }
  m_check = result;
  if (!check.accepted) {
    fail(vpProjectiveException::modelRejectedError, where, check.message);
  }
  m_types = check.fit.data.types;
  m_inlier = check.fit.data.inlier;
  m_residual = check.fit.residual;
  m_algebraicResidual = check.fit.algebraicResidual;
  return check.fit.model;
}
