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
  vpProjectiveRobot after the acquisition, its rig: the model's prediction error on measured images, the observations
  and the re-registration of a moved rig (updateRig()), and its refinement with given points (refineRig()).
*/

#include <visp3/projective/vpProjectiveRobot.h>

#include <sstream>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveRobot");

//! The marker images of every model marker, checked.
std::vector<Eigen::Vector4d> allMarkerImages(const vpProjectiveArmModel &model, const std::vector<vpImagePoint> &left,
                                             const std::vector<vpImagePoint> &right, const std::string &where)
{
  const std::vector<Eigen::Vector4d> s = stackStereoImages(left, right, where);
  if (s.size() != model.markers().size()) {
    std::ostringstream os;
    os << "got the images of " << s.size() << " markers but the model has " << model.markers().size()
       << "; pass the images of every zero-reference marker, in the zero reference's order";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  return s;
}
} // namespace

double vpProjectiveRobot::getPredictionError(const vpColVector &q, const std::vector<vpImagePoint> &left,
                                             const std::vector<vpImagePoint> &right) const
{
  const std::string where = at("getPredictionError()");
  const vpProjectiveArmModel &model = getModel();
  const JointVector qe = toJointVector(q, "getPredictionError()");
  const std::vector<Eigen::Vector4d> s = allMarkerImages(model, left, right, where);
  const Eigen::Matrix4d H = model.displacement(qe);
  double sum = 0.0;
  for (unsigned int j = 0; j < s.size(); ++j) {
    Eigen::Vector4d sHat;
    if (!model.predictMarker(j, H, sHat)) {
      fail(vpProjectiveException::pointAtInfinityError, where,
           "a marker's prediction lies on a camera's focal plane at this q; check q");
    }
    sum += (sHat - s[j]).squaredNorm();
  }
  return std::sqrt(sum / (4.0 * static_cast<double>(s.size())));
}

void vpProjectiveRobot::addRigObservation(const vpColVector &q, const std::vector<vpImagePoint> &left,
                                          const std::vector<vpImagePoint> &right)
{
  const std::string where = at("addRigObservation()");
  const vpProjectiveArmModel &model = getModel();
  const JointVector qe = toJointVector(q, "addRigObservation()");
  std::vector<Eigen::Vector4d> s = allMarkerImages(model, left, right, where);
  for (const JointVector &qk : m_rigUpdate.m_joints) {
    if ((qk - qe).cwiseAbs().maxCoeff() <= 1e-6) {
      fail(vpProjectiveException::degenerateConfigurationError, where,
           "these joints equal those of an observation already recorded, which adds nothing; move the arm to "
           "another configuration (spread the markers over the images) before the next observation");
    }
  }
  m_rigUpdate.m_joints.push_back(qe);
  m_rigUpdate.m_images.push_back(std::move(s));
}

void vpProjectiveRobot::updateRig()
{
  const std::string where = at("updateRig()");
  const vpProjectiveArmModel &model = getModel();
  vpProjectiveRigUpdate &u = m_rigUpdate;
  if (u.m_joints.size() < 3) {
    std::ostringstream os;
    os << "needs at least 3 observations (addRigObservation()) since the last update, got " << u.m_joints.size()
       << "; observe the markers at more joint configurations";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  double rms = 0.0;
  const vpProjectiveStereoRig rig = vpProjectiveRigRegistration::registerRig(model, u.m_joints, u.m_images, u.m_mode,
                                                                             &rms); // throws before anything changes
  vpProjectiveRigUpdate::vpRegistration
      registration; // what refineRig() starts from: this update's observations and the rig before it
  registration.rigBefore = model.getStereoRig();
  registration.joints = u.m_joints;
  registration.images = u.m_images;
  registration.valid = true;
  adoptRig(rig, rms);
  u.m_registration = std::move(registration);
  ++u.m_updates;
  u.clearObservations();
  m_acquisition.clearCalibrationFrames(); // they show the rig before it moved
  m_listeners.notify(true);               // the tasks on this robot re-express their desired features in the new rig
}

void vpProjectiveRobot::adoptRig(const vpProjectiveStereoRig &rig, double rms)
{
  const vpProjectiveArmModel &model = m_model;
  std::vector<Eigen::Vector3d> axis, point;
  for (unsigned int i = 0; i < model.getNumberOfJoints(); ++i) {
    axis.push_back(model.axis(i));
    point.push_back(model.point(i));
  }
  vpProjectiveArmModel updated(model.jointTypes(), model.getRigMounting(), rig, model.projectiveToMetric(), axis, point,
                               model.markers(), model.zeroReferenceJoints());
  m_model = std::move(updated);
  m_rigUpdate.m_residual = rms;
  ++m_rigUpdate.m_generation;
}

void vpProjectiveRobot::refineRig(const std::vector<Eigen::Vector4d> &points,
                                  const std::vector<Eigen::Vector4d> &images)
{
  const std::string where = at("refineRig()");
  const vpProjectiveArmModel &model = getModel();
  const vpProjectiveRigUpdate::vpRegistration &registration = m_rigUpdate.m_registration;
  if (!registration.valid) {
    fail(vpProjectiveException::notInitializedError, where,
         "there is no re-registration to refine (none since the model was computed or loaded); call updateRig() "
         "first: the refinement starts from its observations");
  }
  if (points.size() != images.size()) {
    std::ostringstream os;
    os << "got " << points.size() << " points but " << images.size() << " stereo images; pass one per point";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const size_t K = model.markers().size();
  std::vector<Eigen::Vector4d> X, s;
  X.reserve(registration.joints.size() * K + points.size());
  s.reserve(X.capacity());
  for (size_t k = 0; k < registration.joints.size(); ++k) {
    const Eigen::Matrix4d H = model.displacement(registration.joints[k]);
    for (size_t j = 0; j < K; ++j) {
      X.push_back(H * model.markers()[j]);
      s.push_back(registration.images[k][j]);
    }
  }
  X.insert(X.end(), points.begin(), points.end());
  s.insert(s.end(), images.begin(), images.end());
  double rms = 0.0;
  const vpProjectiveStereoRig rig =
      vpProjectiveRigRegistration::registerRig(registration.rigBefore, model.projectiveToMetric(), X, s,
                                               m_rigUpdate.m_mode, &rms); // throws before anything changes
  adoptRig(rig, rms);
  m_listeners.notify(true); // the tasks re-express their desired features in the refined rig
}
