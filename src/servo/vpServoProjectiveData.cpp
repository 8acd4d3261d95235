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

#include <visp3/projective/vpServoProjectiveData.h>

#include <cmath>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

vpServoProjectiveData::vpServoProjectiveData()
    : m_arm(), m_rig(nullptr), m_passesBefore(0), m_nbFeatures(0), m_s(), m_M(), m_M0(), m_hasPoint(), m_J(), m_e(),
      m_normal(), m_errorNorm(0.0), m_nbActive(0)
{
}

void vpServoProjectiveData::computeKinematics(const vpProjectiveArmModel &model, const JointVector &q,
                                              unsigned int features)
{
  m_rig = &model.getStereoRig();
  m_passesBefore = m_arm.getPassCount();
  vpProjectiveKinematics::forwardKinematics(model, m_arm, q); // the iteration's only H(q), and the joint motions
  if (m_s.size() != features) {                               // allocates only when the number of features changes
    m_s.resize(features);
    m_M.resize(features);
    m_M0.resize(features);
    m_hasPoint.resize(features);
  }
  m_nbFeatures = features;
}

void vpServoProjectiveData::computeFeature(const vpProjectiveArmModel &model, unsigned int i, const Eigen::Vector4d &s)
{
  m_s[i] = s;
  m_hasPoint[i] = s.allFinite() ? 1 : 0;
  if (m_hasPoint[i]) {
    m_M[i] = model.getStereoRig().triangulateLinear(s.head<2>(), s.tail<2>());
    m_M0[i] = (m_arm.getDisplacementInverse() * m_M[i]).normalized();
  } else {
    m_M[i].setZero();
    m_M0[i].setZero();
  }
}

bool vpServoProjectiveData::predict(const Eigen::Vector4d &X, Eigen::Vector4d &s) const
{
  return m_rig != nullptr && m_rig->project(Eigen::Vector4d(m_arm.getDisplacement() * X), s);
}
