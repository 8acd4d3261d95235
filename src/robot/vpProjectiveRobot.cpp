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

#include <visp3/projective/vpProjectiveRobot.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <visp3/projective/vpProjectiveArmData.h>
#include <visp3/projective/vpProjectiveInverseKinematics.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

const vpErrorSite at("vpProjectiveRobot");

vpProjectiveRobot::vpProjectiveRobot() : m_acquisition(), m_model(), m_calibrated(false), m_rigUpdate(), m_listeners()
{
}

vpProjectiveRobot::vpListeners::~vpListeners()
{
  const std::vector<vpListener *> listeners = list; // a listener may detach itself
  for (vpListener *l : listeners) {
    l->robotDestroyed();
  }
}

void vpProjectiveRobot::vpListeners::notify(bool rigOnly) const
{
  for (vpListener *l : list) {
    l->robotModelChanged(rigOnly);
  }
}

void vpProjectiveRobot::attach(vpListener &listener) const
{
  if (std::find(m_listeners.list.begin(), m_listeners.list.end(), &listener) == m_listeners.list.end()) {
    m_listeners.list.push_back(&listener);
  }
}

void vpProjectiveRobot::detach(vpListener &listener) const
{
  m_listeners.list.erase(std::remove(m_listeners.list.begin(), m_listeners.list.end(), &listener),
                         m_listeners.list.end());
}

vpProjectiveRobot::vpProjectiveRobot(const std::vector<vpJointType> &joints) : vpProjectiveRobot()
{
  m_acquisition = vpProjectiveArmAcquisition(joints);
}

vpProjectiveRobot::vpProjectiveRobot(unsigned int n) : vpProjectiveRobot()
{
  m_acquisition = vpProjectiveArmAcquisition(n);
}

void vpProjectiveRobot::checkJoint(unsigned int i, const char *method) const
{
  if (i >= getNumberOfJoints()) {
    std::ostringstream os;
    os << "joint index " << i << " is out of range; the chain has " << getNumberOfJoints() << " joints";
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
}

vpProjectiveRobot::vpJointType vpProjectiveRobot::getJointType(unsigned int i) const
{
  checkJoint(i, "getJointType()");
  if (!m_calibrated && !m_acquisition.hasDeclaredJointTypes()) {
    fail(vpProjectiveException::notInitializedError, at("getJointType()"),
         "the robot was constructed from its joint count: calibrate() identifies the joint types from the trials");
  }
  return m_acquisition.getJointTypes()[i];
}

void vpProjectiveRobot::setRigMounting(vpRigMounting mounting)
{
  if (m_calibrated && mounting != m_model.getRigMounting()) {
    m_calibrated = false; // the model was acquired with the other mounting: calibrate() again
  }
  m_acquisition.setRigMounting(mounting);
}

void vpProjectiveRobot::setStereoRig(const vpProjectiveStereoRig &rig)
{
  m_acquisition.setStereoRig(rig);
  m_calibrated = false;
}

const vpProjectiveStereoRig &vpProjectiveRobot::getStereoRig() const
{
  return m_calibrated ? m_model.getStereoRig() : m_acquisition.getStereoRig();
}

void vpProjectiveRobot::setZeroReference(const std::vector<vpImagePoint> &left0,
                                         const std::vector<vpImagePoint> &right0)
{
  m_acquisition.setZeroReference(left0, right0);
  m_calibrated = false;
}

void vpProjectiveRobot::setZeroReference(const vpColVector &qRef, const std::vector<vpImagePoint> &left0,
                                         const std::vector<vpImagePoint> &right0)
{
  m_acquisition.setZeroReference(qRef, left0, right0);
  m_calibrated = false;
}

void vpProjectiveRobot::addTrialMotion(unsigned int i, double amount, const std::vector<vpImagePoint> &left,
                                       const std::vector<vpImagePoint> &right)
{
  m_acquisition.addTrialMotion(i, amount, left, right);
  m_calibrated = false;
}

void vpProjectiveRobot::addTrialMotion(const vpColVector &q, const std::vector<vpImagePoint> &left,
                                       const std::vector<vpImagePoint> &right)
{
  m_acquisition.addTrialMotion(q, left, right);
  m_calibrated = false;
}

void vpProjectiveRobot::addCalibrationFrame(const vpColVector &q, const std::vector<vpImagePoint> &left,
                                            const std::vector<vpImagePoint> &right)
{
  m_acquisition.addCalibrationFrame(q, left, right);
}

void vpProjectiveRobot::calibrate()
{
  const vpProjectiveArmModel model = m_acquisition.calibrate(); // throws before anything changes
  adopt(m_acquisition, model, m_acquisition.getCalibrationResidual(), m_acquisition.getAlgebraicResidual());
}

void vpProjectiveRobot::setCalibration(const vpProjectiveArmAcquisition &acquisition, const vpProjectiveArmModel &model,
                                       double residual)
{
  const std::string where = at("setCalibration()");
  // A robot of a joint count alone takes the types identified by the acquisition.
  const bool sameJoints = m_acquisition.hasDeclaredJointTypes()
                              ? model.jointTypes() == m_acquisition.getJointTypes()
                              : model.getNumberOfJoints() == m_acquisition.getNumberOfJoints();
  if (model.jointTypes() != acquisition.getJointTypes() || !sameJoints) {
    fail(vpProjectiveException::dimensionError, where,
         "the model, the acquisition and the robot have different joints; calibrate from an acquisition of this "
         "robot's joints (getAcquisition())");
  }
  if (!std::isfinite(residual) || residual < 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the residual is the RMS pixel error of the model's refinement: finite and not negative");
  }
  adopt(acquisition, model, residual, acquisition.getAlgebraicResidual());
}

void vpProjectiveRobot::adopt(const vpProjectiveArmAcquisition &acquisition, const vpProjectiveArmModel &model,
                              double residual, double algebraicResidual)
{
  m_acquisition = acquisition;
  m_acquisition.m_residual = residual;
  m_acquisition.m_algebraicResidual = algebraicResidual;
  m_model = model;
  m_calibrated = true;
  m_rigUpdate.restart();     // rig observations and the last re-registration belong to the previous model
  m_listeners.notify(false); // the tasks on this robot take their desired features anew
}

void vpProjectiveRobot::setOutlierThreshold(double pixels)
{
  m_acquisition.setOutlierThreshold(pixels);
  m_calibrated = false;
}

const vpProjectiveArmModel &vpProjectiveRobot::getModel() const
{
  if (!m_calibrated) {
    fail(vpProjectiveException::notInitializedError, at("getModel()"),
         "the robot model is not acquired yet; call calibrate() after the acquisition, or loadModel()");
  }
  return m_model;
}

vpProjectiveRobot::JointVector vpProjectiveRobot::toJointVector(const vpColVector &q, const char *method) const
{
  return toEigenVector<JointVector>(q, getNumberOfJoints(), at(method), "q");
}

vpMatrix vpProjectiveRobot::getGenerator(unsigned int i) const
{
  const vpProjectiveArmModel &model = getModel();
  checkJoint(i, "getGenerator()");
  return toVisp(model.generator(i));
}

vpMatrix vpProjectiveRobot::getDisplacement(const vpColVector &q) const
{
  const vpProjectiveArmModel &model = getModel();
  return toVisp(model.displacement(toJointVector(q, "getDisplacement()")));
}

vpMatrix vpProjectiveRobot::getImageJacobian(const vpColVector &q, const vpColVector &M) const
{
  const std::string where = at("getImageJacobian()");
  const vpProjectiveArmModel &model = getModel();
  const JointVector qe = toJointVector(q, "getImageJacobian()");
  const Eigen::Vector4d Me = toEigen<4>(M, where, "the point M");
  if (Me.norm() == 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "M is the zero vector, which is no projective point");
  }
  vpProjectiveArmData data;
  vpProjectiveKinematics::forwardKinematics(model, data, qe);
  PointJacobian J;
  if (!vpProjectiveKinematics::imageJacobian(model, data, Me, J)) {
    fail(vpProjectiveException::pointAtInfinityError, where,
         "M lies on the focal plane of a camera: its image and image Jacobian are undefined");
  }
  return toVisp(J);
}

vpColVector vpProjectiveRobot::inverseKinematics(const std::vector<vpImagePoint> &left,
                                                 const std::vector<vpImagePoint> &right, const vpColVector &q0,
                                                 const std::vector<unsigned int> &indices, double *residual) const
{
  const std::string where = at("inverseKinematics()");
  const vpProjectiveArmModel &model = getModel();
  const std::vector<Eigen::Vector4d> s = stackStereoImages(left, right, where);
  const size_t K = model.markers().size();
  std::vector<unsigned int> which = indices;
  if (indices.empty()) {
    if (s.size() != K) {
      std::ostringstream os;
      os << "got the images of " << s.size() << " markers but the model has " << K
         << "; pass all markers in order, or their indices";
      fail(vpProjectiveException::dimensionError, where, os.str());
    }
    for (unsigned int j = 0; j < K; ++j) {
      which.push_back(j);
    }
  } else {
    if (indices.size() != s.size()) {
      fail(vpProjectiveException::dimensionError, where, "there must be one marker index per image point pair");
    }
    for (unsigned int j : indices) {
      if (j >= K) {
        std::ostringstream os;
        os << "marker index " << j << " is out of range; the model has " << K << " markers";
        fail(vpProjectiveException::dimensionError, where, os.str());
      }
    }
  }
  const unsigned int n = model.getNumberOfJoints();
  if (2 * s.size() < n) {
    std::ostringstream os;
    os << s.size() << " markers give " << 4 * s.size() << " equations for " << n
       << " joints, but each marker constrains at most 2 degrees of freedom of the chain; observe more markers";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  const JointVector start = q0.getRows() == 0 ? model.zeroReferenceJoints() : toJointVector(q0, "inverseKinematics()");
  return toVispVector(vpProjectiveInverseKinematics::solve(model, s, which, start, residual));
}

std::vector<vpProjectiveArmAcquisition::vpFrame> vpProjectiveRobot::selfCalibrationFrames() const
{
  std::vector<vpProjectiveArmAcquisition::vpFrame> frames = m_acquisition.getFrames();
  if (m_rigUpdate.getUpdateCount() >
      0) { // the acquisition's images show the rig before it moved: only the frames added since
    frames.erase(frames.begin(), frames.end() - m_acquisition.getNumberOfCalibrationFrames());
  }
  return frames;
}

void vpProjectiveRobot::getMetricStereoRig(vpMatrix &Kl, vpMatrix &Kr, vpHomogeneousMatrix &lMr) const
{
  Eigen::Matrix3d Kle, Kre;
  Eigen::Matrix4d lMre;
  vpProjectiveSelfCalibration(getModel(), selfCalibrationFrames()).getMetricStereoRig(Kle, Kre, lMre);
  Kl = toVisp(Kle);
  Kr = toVisp(Kre);
  lMr = toHomogeneous(lMre);
}

void vpProjectiveRobot::saveModel(const std::string &filename) const
{
  // The check of the model's own calibration (not of a later, refused one).
  const vpProjectiveModelCheck &check = m_acquisition.getModelCheck();
  vpProjectiveModelFile::save(filename, getModel(), m_acquisition.getCalibrationResidual(),
                              m_acquisition.getAlgebraicResidual(), std::vector<int>(), selfCalibrationFrames(),
                              check.isAccepted() ? &check : nullptr);
}

void vpProjectiveRobot::loadModel(const std::string &filename)
{
  double residual = 0.0, algebraicResidual = 0.0;
  std::vector<vpProjectiveArmAcquisition::vpFrame> frames;
  const vpProjectiveArmModel model =
      vpProjectiveModelFile::load(filename, &residual, &algebraicResidual, nullptr, &frames);
  vpProjectiveArmAcquisition acquisition(model);
  acquisition.setOutlierThreshold(m_acquisition.getOutlierThreshold());
  for (const vpProjectiveArmAcquisition::vpFrame &frame : frames) {
    std::vector<int> ids;
    std::vector<vpImagePoint> left, right;
    for (size_t j = 0; j < frame.s.size(); ++j) {
      if (frame.seen[j]) {
        ids.push_back(static_cast<int>(j));
        left.emplace_back(frame.s[j](1), frame.s[j](0));
        right.emplace_back(frame.s[j](3), frame.s[j](2));
      }
    }
    if (!ids.empty()) {
      acquisition.addCalibrationFrame(toVispVector(frame.q), ids, left, right);
    }
  }
  adopt(acquisition, model, residual, algebraicResidual);
}
