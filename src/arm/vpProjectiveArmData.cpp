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

#include <visp3/projective/vpProjectiveArmData.h>

#include "arm/vpJointExponentialPair.h"

namespace
{
//! \f$ J(q, M) \f$ column by column, eq. (46): \e L (rows \f$ J_C(m) P \f$ and \f$ J_C(m') P' \f$, eq. (45)) times
//! each joint's motion of \e M.
void imageColumns(const Eigen::Matrix4d &L, const Eigen::Matrix4d *HhatKq, const Eigen::Vector4d &M, unsigned int n,
                  vpProjectiveArmModel::PointJacobian &J)
{
  J.resize(4, static_cast<Eigen::Index>(n));
  for (unsigned int k = 0; k < n; ++k) {
    J.col(k) = L * (HhatKq[k] * M);
  }
}
} // namespace

vpProjectiveArmData::vpProjectiveArmData()
    : m_q(), m_H(Eigen::Matrix4d::Identity()), m_Hinv(Eigen::Matrix4d::Identity()), m_HhatKq(), m_Hhat(), m_Hhat2(),
      m_nbGenerators(0), m_passCount(0)
{
}

void vpProjectiveKinematics::forwardKinematics(const vpProjectiveArmModel &model, vpProjectiveArmData &data,
                                               const vpProjectiveArmModel::JointVector &q)
{
  const unsigned int n = model.getNumberOfJoints();
  for (unsigned int i = 0; i < n; ++i) {
    if (i >= data.m_nbGenerators || !(model.generator(i) == data.m_Hhat[i])) {
      data.m_Hhat[i] = model.generator(i);
      data.m_Hhat2[i].noalias() = data.m_Hhat[i] * data.m_Hhat[i];
    }
  }
  data.m_nbGenerators = n;
  data.m_q = q;
  // Along the chain (base = the rig's end), A_k = A_{k-1} exp(dq_k Hhat_k) and A_k^-1 = exp(-dq_k Hhat_k) A_{k-1}^-1:
  // the motion of joint k needs A_{k-1} and its inverse, the displacement is A_{n-1}. The two exponentials of a
  // joint share their terms (vpJointExponentialPair.h).
  const bool reversed = model.getRigMounting() != vpProjectiveArmModel::EYE_TO_HAND;
  const vpProjectiveArmModel::JointVector &qRef = model.zeroReferenceJoints();
  Eigen::Matrix4d &A = data.m_H, &Ainv = data.m_Hinv;
  Eigen::Matrix4d AH, E, Einv;
  if (n == 0) {
    A.setIdentity();
    Ainv.setIdentity();
  }
  for (unsigned int k = 0; k < n; ++k) {
    const unsigned int i = reversed ? n - 1 - k : k;
    const Eigen::Matrix4d &Hhat = data.m_Hhat[i];
    if (k == 0) {
      data.m_HhatKq[i] = Hhat;
    } else {
      AH.noalias() = A * Hhat;
      data.m_HhatKq[i].noalias() = AH * Ainv;
    }
    vpProjectiveInternal::jointExponentialPair(model.jointTypes()[i], q(i) - qRef(i), Hhat, data.m_Hhat2[i], E, Einv);
    vpProjectiveInternal::chainExponentialPair(k == 0, E, Einv, A, Ainv);
  }
  ++data.m_passCount;
}

void vpProjectiveKinematics::pointJacobian(const vpProjectiveArmModel &model, const vpProjectiveArmData &data,
                                           const Eigen::Vector4d &M, vpProjectiveArmModel::PointJacobian &JH)
{
  const unsigned int n = model.getNumberOfJoints();
  JH.resize(4, static_cast<Eigen::Index>(n));
  for (unsigned int k = 0; k < n; ++k) {
    JH.col(k).noalias() = data.getJointMotions()[k] * M;
  }
}

bool vpProjectiveKinematics::imageJacobian(const vpProjectiveArmModel &model, const vpProjectiveArmData &data,
                                           const Eigen::Vector4d &M, vpProjectiveArmModel::PointJacobian &J)
{
  Eigen::Vector4d s;
  Eigen::Matrix4d L;
  if (!model.getStereoRig().project(M, s, &L)) {
    return false;
  }
  imageColumns(L, data.getJointMotions(), M, model.getNumberOfJoints(), J);
  return true;
}

bool vpProjectiveKinematics::pointImages(const vpProjectiveArmModel &model, const vpProjectiveArmData &data,
                                         const Eigen::Vector4d &X, Eigen::Vector4d &s,
                                         vpProjectiveArmModel::PointJacobian *J)
{
  const Eigen::Vector4d M = data.getDisplacement() * X;
  Eigen::Matrix4d L;
  if (!model.getStereoRig().project(M, s, J != nullptr ? &L : nullptr)) {
    return false;
  }
  if (J != nullptr) {
    imageColumns(L, data.getJointMotions(), M, model.getNumberOfJoints(), *J);
  }
  return true;
}
