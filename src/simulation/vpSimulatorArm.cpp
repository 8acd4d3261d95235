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
  \file vpSimulatorArm.cpp
  \brief Metric serial arm simulator: Denavit-Hartenberg chain, markers, twists at the zero reference.
*/

#include <visp3/projective/vpSimulatorArm.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/robot/vpViper850.h>

#include <visp3/projective/vpProjectiveException.h>

#include "core/vpProjectiveConversions.h"
#include "simulation/vpSimulatorArmInternal.h"

using namespace vpProjectiveInternal;

namespace
{
//! \f$ R_z(\theta) T_z(d) T_x(a) R_x(\alpha) \f$.
Eigen::Matrix4d dhTransform(double theta, double d, double a, double alpha)
{
  const double ct = std::cos(theta), st = std::sin(theta);
  const double ca = std::cos(alpha), sa = std::sin(alpha);
  Eigen::Matrix4d T;
  T << ct, -st * ca, st * sa, a * ct, st, ct * ca, -ct * sa, a * st, 0.0, sa, ca, d, 0.0, 0.0, 0.0, 1.0;
  return T;
}

vpColVector point3(double x, double y, double z)
{
  vpColVector p(3);
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

// Zero reference of puma() (theta offsets, degrees) and orientation of paperBasePose() (degrees).
// Found by a search maximising the joint range over which all 7 markers stay 10 px inside both images of
// vpSimulatorStereoRig::paperRig((0, 0, 0), 1.0), with no link (5 cm radius) on a line of sight, the elbow bent by at
// least 30 deg and the wrist by 20 to 100 deg.
const double s_pumaOffsetsDeg[6] = {0.0, 74.0, -60.0, 0.0, -40.0, 86.0};
const double s_pumaBaseTiltDeg = -7.0;
const double s_pumaBaseYawDeg = -86.0;

//! Gives access to the protected Denavit-Hartenberg parameters and joint limits of vpViper850.
class vpViper850Parameters : public vpViper850
{
public:
  double getA1() const { return a1; }
  double getD1() const { return d1; }
  double getA2() const { return a2; }
  double getA3() const { return a3; }
  double getD4() const { return d4; }
  double getD6() const { return d6; }
};
} // namespace

Eigen::Matrix4d vpProjectiveInternal::linkTransform(const vpSimulatorArm::vpDHRow &row, double q)
{
  if (row.type == vpProjectiveJoint::REVOLUTE) {
    return dhTransform(row.theta + q, row.d, row.a, row.alpha);
  }
  return dhTransform(row.theta, row.d + q, row.a, row.alpha);
}

vpSimulatorArm::vpSimulatorArm(const std::vector<vpDHRow> &dh, const vpHomogeneousMatrix &eMt,
                               const std::vector<vpColVector> &tMarkers, const vpHomogeneousMatrix &wMb)
    : m_dh(dh), m_eMt(eMt), m_tMarkers(tMarkers), m_wMb(wMb), m_qmin(), m_qmax()
{
  if (dh.empty()) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                "vpSimulatorArm: the Denavit-Hartenberg table is empty; give one row per joint");
  }
  for (size_t i = 0; i < dh.size(); ++i) {
    const vpDHRow &r = dh[i];
    if (!std::isfinite(r.theta) || !std::isfinite(r.d) || !std::isfinite(r.a) || !std::isfinite(r.alpha)) {
      std::ostringstream os;
      os << "vpSimulatorArm: Denavit-Hartenberg row " << i << " contains NaN or infinity";
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
    }
    if (r.type != vpProjectiveJoint::REVOLUTE && r.type != vpProjectiveJoint::PRISMATIC) {
      std::ostringstream os;
      os << "vpSimulatorArm: Denavit-Hartenberg row " << i << " has an unknown joint kind; use REVOLUTE or PRISMATIC";
      throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
    }
  }
  const vpHomogeneousMatrix *poses[2] = {&eMt, &wMb};
  const char *names[2] = {"eMt", "wMb"};
  for (int k = 0; k < 2; ++k) {
    if (!allFinite(*poses[k])) {
      std::ostringstream os;
      os << "vpSimulatorArm: " << names[k] << " contains NaN or infinity; give a finite rigid transformation";
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
    }
    if (!poses[k]->isAnHomogeneousMatrix(1e-6)) {
      std::ostringstream os;
      os << "vpSimulatorArm: " << names[k]
         << " is not a rigid transformation (rotation not orthonormal with determinant 1, or last row not [0 0 0 1])";
      throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
    }
  }
  for (size_t k = 0; k < tMarkers.size(); ++k) {
    if (tMarkers[k].getRows() != 3 || tMarkers[k].getCols() != 1) {
      std::ostringstream os;
      os << "vpSimulatorArm: marker " << k << " must be a 3x1 point in the tool frame, got " << tMarkers[k].getRows()
         << "x" << tMarkers[k].getCols();
      throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
    }
    if (!allFinite(tMarkers[k])) {
      std::ostringstream os;
      os << "vpSimulatorArm: marker " << k << " contains NaN or infinity";
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
    }
  }
  const unsigned int n = static_cast<unsigned int>(dh.size());
  m_qmin.resize(n);
  m_qmax.resize(n);
  for (unsigned int i = 0; i < n; ++i) {
    const double limit = (dh[i].type == vpProjectiveJoint::REVOLUTE) ? vpMath::rad(170.0) : 0.5;
    m_qmin[i] = -limit;
    m_qmax[i] = limit;
  }
}

std::vector<vpColVector> vpSimulatorArm::gripperMarkers()
{
  // Tool frame t: origin at the gripper's centre, z the approach direction (the last link's z axis). The gripper is
  // 8 x 4 x 10 cm: a palm (z in [-5, -1] cm) carrying two fingers (x in -/+ [2, 4] cm, z in [-1, 5] cm); its broad
  // faces are y = -/+ 2 cm. Markers 0-2 lie on the front face y = -2 cm (outward normal -y; a 30 cm^2 triangle), the
  // face that looks at the rig at the zero reference of puma() with paperBasePose(). Markers 3-6 are on the right
  // finger tip, the left side of the palm, the back of the right finger and the back of the left finger. No 4 of the
  // 7 are coplanar: every marker is at least 8.5 mm away from the plane through any other three.
  std::vector<vpColVector> tMarkers;
  tMarkers.push_back(point3(-0.040, -0.020, -0.040));
  tMarkers.push_back(point3(-0.040, -0.020, 0.035));
  tMarkers.push_back(point3(0.040, -0.020, 0.035));
  tMarkers.push_back(point3(0.030, 0.005, 0.050));
  tMarkers.push_back(point3(-0.040, 0.015, -0.025));
  tMarkers.push_back(point3(0.025, 0.020, -0.005));
  tMarkers.push_back(point3(-0.030, 0.020, 0.040));
  return tMarkers;
}

std::vector<vpSimulatorArm::vpDHRow> vpSimulatorArm::pumaTable()
{
  // Standard DH, PUMA 560 structure (Corke's table) with the paper's link lengths and no shoulder or elbow offsets.
  // theta holds the zero-reference offsets: q = 0 is the bent-elbow "ready" pose documented in the header.
  const double deg = M_PI / 180.0;
  std::vector<vpDHRow> dh(6);
  dh[0] = {vpProjectiveJoint::REVOLUTE, s_pumaOffsetsDeg[0] * deg, 0.36, 0.0, M_PI / 2};
  dh[1] = {vpProjectiveJoint::REVOLUTE, s_pumaOffsetsDeg[1] * deg, 0.0, 0.48, 0.0};
  dh[2] = {vpProjectiveJoint::REVOLUTE, s_pumaOffsetsDeg[2] * deg, 0.0, 0.0, -M_PI / 2};
  dh[3] = {vpProjectiveJoint::REVOLUTE, s_pumaOffsetsDeg[3] * deg, 0.40, 0.0, M_PI / 2};
  dh[4] = {vpProjectiveJoint::REVOLUTE, s_pumaOffsetsDeg[4] * deg, 0.0, 0.0, -M_PI / 2};
  dh[5] = {vpProjectiveJoint::REVOLUTE, s_pumaOffsetsDeg[5] * deg, 0.05, 0.0, 0.0};
  return dh;
}

std::vector<vpSimulatorArm::vpDHRow> vpSimulatorArm::stanfordTable()
{
  std::vector<vpDHRow> dh(6);
  dh[0] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.41, 0.0, -M_PI / 2};
  dh[1] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.15, 0.0, M_PI / 2};
  dh[2] = {vpProjectiveJoint::PRISMATIC, 0.0, 0.0, 0.0, 0.0};
  dh[3] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.0, 0.0, -M_PI / 2};
  dh[4] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.0, 0.0, M_PI / 2};
  dh[5] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.10, 0.0, 0.0};
  return dh;
}

vpHomogeneousMatrix vpSimulatorArm::gripperMount()
{
  vpHomogeneousMatrix eMt;
  eMt[2][3] = 0.05; // the 10 cm gripper starts at the flange: its centre is 5 cm further along z
  return eMt;
}

vpSimulatorArm vpSimulatorArm::puma(const vpHomogeneousMatrix &wMb)
{
  return vpSimulatorArm(pumaTable(), gripperMount(), gripperMarkers(), wMb);
}

vpHomogeneousMatrix vpSimulatorArm::paperBasePose()
{
  // Orientation of the base: its z axis (up) along world -Y, rotated as documented in the header; then the base is
  // translated so that the gripper's centre (tool frame origin) lies at the world origin at q = 0.
  const double deg = M_PI / 180.0;
  const Eigen::Matrix3d wRb0 = (Eigen::Matrix3d() << 1, 0, 0, 0, 0, -1, 0, 1, 0).finished();
  const Eigen::Matrix3d wRb = Eigen::AngleAxisd(s_pumaBaseTiltDeg * deg, Eigen::Vector3d::UnitX()).toRotationMatrix() *
                              wRb0 *
                              Eigen::AngleAxisd(s_pumaBaseYawDeg * deg, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Eigen::Matrix4d wMb0 = Eigen::Matrix4d::Identity();
  wMb0.topLeftCorner<3, 3>() = wRb;
  const vpSimulatorArm arm = puma(toHomogeneous(wMb0));
  const vpHomogeneousMatrix wMt0 = arm.get_wMt(vpColVector(6, 0.0));
  for (unsigned int i = 0; i < 3; ++i) {
    wMb0(i, 3) = -wMt0[i][3];
  }
  return toHomogeneous(wMb0);
}

vpSimulatorArm vpSimulatorArm::viper850(const vpHomogeneousMatrix &wMb)
{
  // vpViper::get_fMe() is the standard DH chain of vpViper850's documentation:
  //   1: a1, d1, -pi/2, q1        2: a2, 0, 0, q2           3: a3, 0, -pi/2, q3 - pi
  //   4: 0, d4, pi/2, q4          5: 0, 0, -pi/2, q5        6: 0, d6, 0, q6 - pi   (d6: wrist to flange)
  // get_fMe() ignores the joint 5-6 coupling c56 (it only relates motor to joint positions), and so does this model.
  const vpViper850Parameters viper;
  std::vector<vpDHRow> dh(6);
  dh[0] = {vpProjectiveJoint::REVOLUTE, 0.0, viper.getD1(), viper.getA1(), -M_PI / 2};
  dh[1] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.0, viper.getA2(), 0.0};
  dh[2] = {vpProjectiveJoint::REVOLUTE, -M_PI, 0.0, viper.getA3(), -M_PI / 2};
  dh[3] = {vpProjectiveJoint::REVOLUTE, 0.0, viper.getD4(), 0.0, M_PI / 2};
  dh[4] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.0, 0.0, -M_PI / 2};
  dh[5] = {vpProjectiveJoint::REVOLUTE, -M_PI, viper.getD6(), 0.0, 0.0};
  vpSimulatorArm arm(dh, gripperMount(), gripperMarkers(), wMb);
  arm.m_qmin = viper.getJointMin();
  arm.m_qmax = viper.getJointMax();
  return arm;
}

vpProjectiveJoint::vpJointType vpSimulatorArm::getJointType(unsigned int i) const
{
  if (i >= m_dh.size()) {
    std::ostringstream os;
    os << "vpSimulatorArm::getJointType(): joint " << i << " does not exist; the arm has " << m_dh.size()
       << " joints, indexed from 0";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  return m_dh[i].type;
}

void vpSimulatorArm::checkJointVector(const vpColVector &q, const char *where, const char *name) const
{
  if (q.getRows() != m_dh.size() || q.getCols() != 1) {
    std::ostringstream os;
    os << where << ": " << name << " must be " << m_dh.size() << "x1 (one value per joint), got " << q.getRows() << "x"
       << q.getCols();
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  if (!allFinite(q)) {
    std::ostringstream os;
    os << where << ": " << name << " contains NaN or infinity";
    throw vpProjectiveException(vpProjectiveException::nonFiniteValueError, os.str());
  }
}

vpHomogeneousMatrix vpSimulatorArm::get_wMe(const vpColVector &q) const
{
  checkJointVector(q, "vpSimulatorArm::get_wMe()", "q");
  Eigen::Matrix4d wMe = toEigenUnchecked<4, 4>(m_wMb);
  for (unsigned int i = 0; i < m_dh.size(); ++i) {
    wMe = wMe * linkTransform(m_dh[i], q[i]);
  }
  return toHomogeneous(wMe);
}

vpHomogeneousMatrix vpSimulatorArm::get_wMt(const vpColVector &q) const
{
  checkJointVector(q, "vpSimulatorArm::get_wMt()", "q");
  return get_wMe(q) * m_eMt;
}

std::vector<vpColVector> vpSimulatorArm::getMarkers(const vpColVector &q) const
{
  checkJointVector(q, "vpSimulatorArm::getMarkers()", "q");
  const vpHomogeneousMatrix wMt = get_wMt(q);
  std::vector<vpColVector> wMarkers;
  wMarkers.reserve(m_tMarkers.size());
  for (size_t k = 0; k < m_tMarkers.size(); ++k) {
    const vpColVector &tX = m_tMarkers[k];
    vpColVector wX(3);
    for (unsigned int i = 0; i < 3; ++i) {
      wX[i] = wMt[i][0] * tX[0] + wMt[i][1] * tX[1] + wMt[i][2] * tX[2] + wMt[i][3];
    }
    wMarkers.push_back(wX);
  }
  return wMarkers;
}

vpMatrix vpSimulatorArm::getTwist(unsigned int i) const
{
  if (i >= m_dh.size()) {
    std::ostringstream os;
    os << "vpSimulatorArm::getTwist(): joint " << i << " does not exist; the arm has " << m_dh.size()
       << " joints, indexed from 0";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  // Joint i turns (or slides) about the z axis of the frame before its DH transform, at q = 0.
  Eigen::Matrix4d wMi = toEigenUnchecked<4, 4>(m_wMb);
  for (unsigned int k = 0; k < i; ++k) {
    wMi = wMi * linkTransform(m_dh[k], 0.0);
  }
  const Eigen::Vector3d z = wMi.block<3, 1>(0, 2);
  const Eigen::Vector3d p = wMi.block<3, 1>(0, 3);
  return toVisp(vpProjectiveJoint::twist(m_dh[i].type, z, p));
}

vpHomogeneousMatrix vpSimulatorArm::getDisplacement(const vpColVector &q) const
{
  checkJointVector(q, "vpSimulatorArm::getDisplacement()", "q");
  return get_wMt(q) * get_wMt(vpColVector(static_cast<unsigned int>(m_dh.size()), 0.0)).inverse();
}

void vpSimulatorArm::setJointLimits(const vpColVector &qmin, const vpColVector &qmax)
{
  checkJointVector(qmin, "vpSimulatorArm::setJointLimits()", "qmin");
  checkJointVector(qmax, "vpSimulatorArm::setJointLimits()", "qmax");
  for (unsigned int i = 0; i < qmin.getRows(); ++i) {
    if (qmin[i] > qmax[i]) {
      std::ostringstream os;
      os << "vpSimulatorArm::setJointLimits(): joint " << i << " has qmin = " << qmin[i] << " > qmax = " << qmax[i];
      throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
    }
  }
  m_qmin = qmin;
  m_qmax = qmax;
}

vpColVector vpSimulatorArm::integrate(const vpColVector &q, const vpColVector &qdot, double dt) const
{
  checkJointVector(q, "vpSimulatorArm::integrate()", "q");
  checkJointVector(qdot, "vpSimulatorArm::integrate()", "qdot");
  if (!std::isfinite(dt) || dt < 0.0) {
    std::ostringstream os;
    os << "vpSimulatorArm::integrate(): the time step dt = " << dt << " s must be finite and non-negative";
    throw vpProjectiveException(vpProjectiveException::invalidValueError, os.str());
  }
  vpColVector next(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    next[i] = std::min(std::max(q[i] + qdot[i] * dt, m_qmin[i]), m_qmax[i]);
  }
  return next;
}
