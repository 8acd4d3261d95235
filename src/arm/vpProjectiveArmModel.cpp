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

#include <visp3/projective/vpProjectiveArmModel.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const char *const kWhere = "vpProjectiveArmModel()";

void requireFiniteVector(const Eigen::Ref<const Eigen::VectorXd> &x, const std::string &what)
{
  if (!x.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, kWhere, what + " has a NaN or infinite entry");
  }
}
} // namespace

vpProjectiveArmModel::vpProjectiveArmModel()
    : m_types(), m_mounting(EYE_TO_HAND), m_rig(), m_G(Eigen::Matrix4d::Identity()),
      m_Ginv(Eigen::Matrix4d::Identity()), m_axis(), m_point(), m_Hhat(), m_M0(), m_qRef()
{
}

vpProjectiveArmModel::vpProjectiveArmModel(const std::vector<vpProjectiveJoint::vpJointType> &types,
                                           vpRigMounting mounting, const vpProjectiveStereoRig &rig,
                                           const Eigen::Matrix4d &G, const std::vector<Eigen::Vector3d> &axis,
                                           const std::vector<Eigen::Vector3d> &point,
                                           const std::vector<Eigen::Vector4d> &markers, const JointVector &qRef)
    : vpProjectiveArmModel()
{
  const size_t n = types.size();
  if (n == 0 || n > maxJoints) {
    std::ostringstream os;
    os << "a chain needs between 1 and " << maxJoints << " joints, got " << n;
    fail(vpProjectiveException::dimensionError, kWhere, os.str());
  }
  if (axis.size() != n || point.size() != n || (qRef.size() != 0 && static_cast<size_t>(qRef.size()) != n)) {
    std::ostringstream os;
    os << "the model has " << n << " joints but " << axis.size() << " axes, " << point.size() << " axis points and "
       << qRef.size() << " zero-reference joint values";
    fail(vpProjectiveException::dimensionError, kWhere, os.str());
  }
  if (mounting != EYE_TO_HAND && mounting != EYE_IN_HAND) {
    fail(vpProjectiveException::invalidValueError, kWhere, "the rig mounting is neither EYE_TO_HAND nor EYE_IN_HAND");
  }
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, kWhere, "the rig has no fundamental matrix");
  }
  requireFiniteVector(Eigen::Map<const Eigen::Matrix<double, 16, 1>>(G.data()), "G");
  if (!(std::abs(G.determinant()) > 1e-12 * std::pow(G.norm(), 4))) {
    fail(vpProjectiveException::degenerateConfigurationError, kWhere,
         "G is singular; it must map the projective frame onto a metric one");
  }
  for (size_t i = 0; i < n; ++i) {
    if (types[i] != vpProjectiveJoint::REVOLUTE && types[i] != vpProjectiveJoint::PRISMATIC) {
      fail(vpProjectiveException::invalidValueError, kWhere, "a joint type is neither REVOLUTE nor PRISMATIC");
    }
    requireFiniteVector(axis[i], "an axis");
    requireFiniteVector(point[i], "an axis point");
    if (types[i] == vpProjectiveJoint::REVOLUTE && std::abs(axis[i].norm() - 1.0) > 1e-9) {
      std::ostringstream os;
      os << "the axis of revolute joint " << i << " is not a unit vector (norm " << axis[i].norm() << ")";
      fail(vpProjectiveException::invalidValueError, kWhere, os.str());
    }
  }
  if (markers.empty()) {
    fail(vpProjectiveException::notEnoughPointsError, kWhere, "the model has no marker");
  }
  for (const Eigen::Vector4d &M : markers) {
    requireFiniteVector(M, "a marker");
    if (M.norm() == 0.0) {
      fail(vpProjectiveException::invalidValueError, kWhere,
           "a marker is the zero vector, which is no projective point");
    }
  }
  requireFiniteVector(qRef, "the zero-reference joint values");

  m_types = types;
  m_mounting = mounting;
  m_rig = rig;
  m_G = G;
  m_Ginv = G.inverse();
  m_axis = axis;
  m_point = point;
  m_M0 = markers;
  m_qRef = qRef.size() == 0 ? JointVector::Zero(static_cast<Eigen::Index>(n)) : qRef;
  m_Hhat.resize(n);
  for (unsigned int i = 0; i < n; ++i) {
    m_Hhat[i] = m_Ginv * twist(i) * m_G;
  }
}

Eigen::Matrix4d vpProjectiveArmModel::twist(unsigned int i) const
{
  return vpProjectiveJoint::twist(m_types[i], m_axis[i], m_point[i]);
}

Eigen::Matrix4d vpProjectiveArmModel::jointExp(unsigned int i, double delta) const
{
  return vpProjectiveJoint::exp(m_types[i], m_Hhat[i], delta);
}

Eigen::Matrix4d vpProjectiveArmModel::displacement(const JointVector &q) const
{
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  for (unsigned int k = 0; k < m_types.size(); ++k) {
    const unsigned int i = chainJoint(k);
    H = H * jointExp(i, q(i) - m_qRef(i));
  }
  return H;
}

bool vpProjectiveArmModel::predictMarker(unsigned int j, const Eigen::Matrix4d &H, Eigen::Vector4d &s) const
{
  return m_rig.project(Eigen::Vector4d(H * m_M0[j]), s);
}

void vpProjectiveArmModel::projectMarker(unsigned int j, const vpColVector &q, vpImagePoint &ipLeft,
                                         vpImagePoint &ipRight) const
{
  const std::string where = "vpProjectiveArmModel::projectMarker()";
  if (j >= m_M0.size()) {
    std::ostringstream os;
    os << "marker index " << j << " is out of range; the model has " << m_M0.size() << " markers";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const JointVector qe = toEigenVector<JointVector>(q, m_types.size(), where, "q");
  Eigen::Vector4d s;
  if (!predictMarker(j, displacement(qe), s)) {
    fail(vpProjectiveException::pointAtInfinityError, where, "the marker lies on a camera's focal plane at this q");
  }
  ipLeft.set_uv(s(0), s(1));
  ipRight.set_uv(s(2), s(3));
}

int vpProjectiveArmModel::matchMarker(const Eigen::Matrix4d &H, const Eigen::Vector4d &s, double pixels) const
{
  int nearest = -1;
  double d1 = std::numeric_limits<double>::infinity(), d2 = d1; // the two smallest RMS pixel distances
  for (size_t j = 0; j < m_M0.size(); ++j) {
    Eigen::Vector4d m;
    if (!m_rig.project(H * m_M0[j], m)) {
      continue;
    }
    const double d = std::sqrt((m - s).squaredNorm() / 4.0);
    if (d < d1) {
      d2 = d1;
      d1 = d;
      nearest = static_cast<int>(j);
    } else if (d < d2) {
      d2 = d;
    }
  }
  return d1 <= pixels && d2 > 2.0 * pixels ? nearest : -1;
}
