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

#include "arm/vpJointExponentialPair.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
/*!
  vpProjectiveArmModel::jointMotions() (its expressions, hence its bits) and, from the same joint exponentials,
  \f$ H(q) = A_{n-1} \f$ (displacement(q) to rounding: the same products of the exponentials (26), (31)) and
  \f$ H(q)^{-1} = A_{n-1}^{-1} \f$ (the exponentials of the opposite joint values): one pass for the iteration.
  (To move into vpProjectiveArmModel with its next header change.)
*/
void jointMotionsAndDisplacement(const vpProjectiveArmModel &model, const vpProjectiveArmModel::JointVector &q,
                                 const Eigen::Matrix4d *Hhat2s, Eigen::Matrix4d *HhatKq, Eigen::Matrix4d &A,
                                 Eigen::Matrix4d &Ainv)
{
  const unsigned int n = model.getNumberOfJoints();
  const bool reversed =
      model.getRigMounting() != vpProjectiveArmModel::EYE_TO_HAND; // vpProjectiveArmModel::chainJoint()
  const vpProjectiveArmModel::JointVector &qRef = model.zeroReferenceJoints();
  Eigen::Matrix4d AH, E, Einv;
  for (unsigned int k = 0; k < n; ++k) {
    const unsigned int i = reversed ? n - 1 - k : k;
    const Eigen::Matrix4d &Hhat = model.generator(i);
    if (k == 0) {
      HhatKq[i] = Hhat;
    } else {
      AH.noalias() = A * Hhat;
      HhatKq[i].noalias() = AH * Ainv;
    }
    const double dq = q(i) - qRef(i);
    // Hhat2s[i] is Hhat * Hhat, as jointMotions() computes it: the same motions to the bit.
    vpProjectiveInternal::jointExponentialPair(model.jointTypes()[i], dq, Hhat, Hhat2s[i], E, Einv);
    vpProjectiveInternal::chainExponentialPair(k == 0, E, Einv, A, Ainv);
  }
}
} // namespace

vpServoProjectiveData::vpServoProjectiveData()
    : m_q(), m_H(Eigen::Matrix4d::Identity()), m_Hinv(Eigen::Matrix4d::Identity()), m_rig(nullptr), m_HhatKq(),
      m_Hhat(), m_Hhat2(), m_nbGenerators(0), m_displacementCount(0), m_nbFeatures(0), m_s(), m_M(), m_M0(),
      m_hasPoint(), m_J(), m_e(), m_JtJ(), m_Jte(), m_errorNorm(0.0), m_nbActive(0)
{
}

void vpServoProjectiveData::computeKinematics(const vpProjectiveArmModel &model, const JointVector &q,
                                              unsigned int features)
{
  m_q = q;
  m_displacementCount = 0;
  // The squares of the generators (constants of the model, recomputed only when a generator differs from the one
  // they were computed from: any model, any change of it).
  const unsigned int n = model.getNumberOfJoints();
  for (unsigned int i = 0; i < n; ++i) {
    if (i >= m_nbGenerators || !(model.generator(i) == m_Hhat[i])) {
      m_Hhat[i] = model.generator(i);
      m_Hhat2[i].noalias() = m_Hhat[i] * m_Hhat[i];
    }
  }
  m_nbGenerators = n;
  m_rig = &model.getStereoRig();
  jointMotionsAndDisplacement(model, q, m_Hhat2, m_HhatKq, m_H, m_Hinv); // the iteration's only H(q), and the motions
  ++m_displacementCount;
  if (m_s.size() != features) { // allocates only when the number of features changes
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
    m_M0[i] = (m_Hinv * m_M[i]).normalized();
  } else {
    m_M[i].setZero();
    m_M0[i].setZero();
  }
}

bool vpServoProjectiveData::predict(const Eigen::Vector4d &X, Eigen::Vector4d &s) const
{
  return m_rig != nullptr && m_rig->project(Eigen::Vector4d(m_H * X), s);
}
