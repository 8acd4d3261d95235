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
  Python bindings of the projective robot (ProjectiveRobot: acquisition, model, kinematics, rig re-registration, model
  file) and of the model it holds (ProjectiveArmModel, opaque: what a session calibration returns).

  The methods named by DESIGN.md's contract are bound in bindRobotContract(); every other public method in
  bindRobotMore(): the one place to adapt when vpProjectiveRobot's public methods change (issue 32). The model's
  kinematics, the acquisition's residuals and the rig-registration state are bound on their own classes.
*/

#include "module.h"

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveRigRegistration.h>
#include <visp3/projective/vpProjectiveRigUpdate.h>
#include <visp3/projective/vpProjectiveRobot.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
typedef py::class_<vpProjectiveRobot> RobotClass;

//! An Eigen matrix as a vpMatrix (a numpy array in Python).
template <typename Derived> vpMatrix toVispMatrix(const Eigen::MatrixBase<Derived> &E)
{
  vpMatrix A(static_cast<unsigned int>(E.rows()), static_cast<unsigned int>(E.cols()));
  for (Eigen::Index r = 0; r < E.rows(); ++r) {
    for (Eigen::Index c = 0; c < E.cols(); ++c) {
      A[static_cast<unsigned int>(r)][static_cast<unsigned int>(c)] = E(r, c);
    }
  }
  return A;
}

//! An Eigen column vector as a vpColVector.
template <typename Derived> vpColVector toVispColumn(const Eigen::MatrixBase<Derived> &E)
{
  vpColVector v(static_cast<unsigned int>(E.rows()));
  for (Eigen::Index r = 0; r < E.rows(); ++r) {
    v[static_cast<unsigned int>(r)] = E(r);
  }
  return v;
}

//! \e i if the model has joint \e i (the model's Eigen accessors do not check).
unsigned int checkedJoint(const vpProjectiveArmModel &model, unsigned int i)
{
  if (i >= model.getNumberOfJoints()) {
    throw py::index_error("joint index out of range: the model has " + std::to_string(model.getNumberOfJoints()) +
                          " joints");
  }
  return i;
}

//! The names of DESIGN.md section 3 (fixed).
void bindRobotContract(RobotClass &robot)
{
  robot.def(py::init<>())
      .def(py::init<const std::vector<vpProjectiveRobot::vpJointType> &>(), py::arg("joints"),
           "A chain of joints of the given types (JointType), base to tip.")
      .def(py::init<const vpProjectiveRobot &>(), py::arg("other"), "A copy of another robot and its model.")
      .def("setStereoRig", &vpProjectiveRobot::setStereoRig, py::arg("rig"))
      .def("setZeroReference", py::overload_cast<const Pixels &, const Pixels &>(&vpProjectiveRobot::setZeroReference),
           py::arg("left0"), py::arg("right0"))
      .def("setZeroReference",
           py::overload_cast<const vpColVector &, const Pixels &, const Pixels &>(&vpProjectiveRobot::setZeroReference),
           py::arg("qRef"), py::arg("left0"), py::arg("right0"))
      .def("addTrialMotion",
           py::overload_cast<unsigned int, double, const Pixels &, const Pixels &>(&vpProjectiveRobot::addTrialMotion),
           py::arg("i"), py::arg("amount"), py::arg("left"), py::arg("right"))
      .def("addTrialMotion",
           py::overload_cast<const vpColVector &, const Pixels &, const Pixels &>(&vpProjectiveRobot::addTrialMotion),
           py::arg("q"), py::arg("left"), py::arg("right"))
      .def("calibrate", &vpProjectiveRobot::calibrate, ReleaseGil())
      .def("getGenerator", &vpProjectiveRobot::getGenerator, py::arg("i"))
      .def("getDisplacement", &vpProjectiveRobot::getDisplacement, py::arg("q"))
      .def("getImageJacobian", &vpProjectiveRobot::getImageJacobian, py::arg("q"), py::arg("M"))
      .def("saveModel", &vpProjectiveRobot::saveModel, py::arg("filename"))
      .def("loadModel", &vpProjectiveRobot::loadModel, py::arg("filename"))
      .def("addCalibrationFrame", &vpProjectiveRobot::addCalibrationFrame, py::arg("q"), py::arg("left"),
           py::arg("right"), "A frame at any configuration for the metric self-calibration (getMetricStereoRig()).")
      .def("addRigObservation", &vpProjectiveRobot::addRigObservation, py::arg("q"), py::arg("left"), py::arg("right"))
      .def("updateRig", &vpProjectiveRobot::updateRig, ReleaseGil())
      .def("getPredictionError", &vpProjectiveRobot::getPredictionError, py::arg("q"), py::arg("left"),
           py::arg("right"))
      .def(
          "inverseKinematics",
          [](const vpProjectiveRobot &r, const Pixels &left, const Pixels &right, const vpColVector &qPrev,
             const std::vector<unsigned int> &indices) { return r.inverseKinematics(left, right, qPrev, indices); },
          py::arg("left"), py::arg("right"), py::arg("qPrev") = vpColVector(),
          py::arg("indices") = std::vector<unsigned int>(), ReleaseGil(),
          "The joints that best explain the images of the markers `indices` (all if empty), from qPrev.")
      .def(
          "getMetricStereoRig",
          [](const vpProjectiveRobot &r) {
            vpMatrix Kl, Kr;
            vpHomogeneousMatrix lMr;
            r.getMetricStereoRig(Kl, Kr, lMr);
            return py::make_tuple(Kl, Kr, lMr);
          },
          "(Kl, Kr, lMr): both cameras' intrinsics (3x3) and the right camera's pose in the left camera's frame.");
}

//! Every other public method (see the file's comment).
void bindRobotMore(RobotClass &robot)
{
  robot.def("getNumberOfJoints", &vpProjectiveRobot::getNumberOfJoints)
      .def("getJointType", &vpProjectiveRobot::getJointType, py::arg("i"))
      .def("setRigMounting", &vpProjectiveRobot::setRigMounting, py::arg("mounting"))
      .def("getRigMounting", &vpProjectiveRobot::getRigMounting)
      .def("getStereoRig", &vpProjectiveRobot::getStereoRig, py::return_value_policy::copy)
      .def("isCalibrated", &vpProjectiveRobot::isCalibrated)
      .def("setOutlierThreshold", &vpProjectiveRobot::setOutlierThreshold, py::arg("pixels"))
      .def("getAcquisition", &vpProjectiveRobot::getAcquisition, py::return_value_policy::reference_internal)
      .def("getModel", &vpProjectiveRobot::getModel, py::return_value_policy::copy)
      .def("getRigUpdate", py::overload_cast<>(&vpProjectiveRobot::getRigUpdate),
           py::return_value_policy::reference_internal);
}

//! The robot's acquisition (its residuals and zero reference) and rig-registration state.
void bindRobotParts(py::module_ &m)
{
  py::class_<vpProjectiveArmAcquisition>(m, "ProjectiveArmAcquisition",
                                         "The acquisition of a ProjectiveRobot (vpProjectiveArmAcquisition, read-only "
                                         "here): the model's residuals and the zero reference's joint values.")
      .def("getNumberOfJoints", &vpProjectiveArmAcquisition::getNumberOfJoints)
      .def("getNumberOfTrials", &vpProjectiveArmAcquisition::getNumberOfTrials)
      .def("getCalibrationResidual", &vpProjectiveArmAcquisition::getCalibrationResidual)
      .def("getAlgebraicResidual", &vpProjectiveArmAcquisition::getAlgebraicResidual)
      .def("getZeroReferenceJoints", &vpProjectiveArmAcquisition::getZeroReferenceJoints);

  typedef vpProjectiveRigUpdate U;
  py::class_<U>(m, "ProjectiveRigUpdate",
                "The rig-registration state of a ProjectiveRobot (vpProjectiveRigUpdate): observations, mode, "
                "residual and counters.")
      .def("setRegistrationMode", &U::setRegistrationMode, py::arg("mode"))
      .def("getRegistrationMode", &U::getRegistrationMode)
      .def("getNumberOfObservations", &U::getNumberOfObservations)
      .def("clearObservations", &U::clearObservations)
      .def("hasRegistration", &U::hasRegistration)
      .def("getResidual", &U::getResidual)
      .def("getGeneration", &U::getGeneration)
      .def("getUpdateCount", &U::getUpdateCount)
      .def("getModelGeneration", &U::getModelGeneration);
}

//! The model: its kinematics in ViSP types (numpy arrays here).
void bindArmModel(py::module_ &m)
{
  typedef vpProjectiveArmModel A;
  py::class_<A>(m, "ProjectiveArmModel",
                "An acquired model (vpProjectiveArmModel): what calibrations return and ProjectiveRobot.getModel() "
                "gives; a ProjectiveRobot reads its file (loadModel()).")
      .def("getNumberOfJoints", &A::getNumberOfJoints)
      .def("getRigMounting", &A::getRigMounting)
      .def("getStereoRig", &A::getStereoRig, py::return_value_policy::copy)
      .def(
          "projectiveToMetric", [](const A &a) { return toVispMatrix(a.projectiveToMetric()); },
          "G (4x4): maps projective points to a metric frame.")
      .def(
          "twist", [](const A &a, unsigned int i) { return toVispMatrix(a.twist(checkedJoint(a, i))); }, py::arg("i"),
          "The metric twist (4x4 se(3) matrix) of joint i.")
      .def(
          "markers",
          [](const A &a) {
            std::vector<vpColVector> M;
            for (const Eigen::Vector4d &Mj : a.markers()) {
              M.push_back(toVispColumn(Mj));
            }
            return M;
          },
          "The markers' projective points M_j(0) at the zero reference, (K, 4).")
      .def(
          "zeroReferenceJoints", [](const A &a) { return toVispColumn(a.zeroReferenceJoints()); },
          "The joint values at the zero reference.")
      .def(
          "projectMarker",
          [](const A &a, unsigned int j, const vpColVector &q) {
            vpImagePoint left, right;
            a.projectMarker(j, q, left, right);
            return py::make_tuple(left, right);
          },
          py::arg("j"), py::arg("q"), "The predicted (u, v) of marker j in both images at the joint values q.");
}
} // namespace

void bindRobot(py::module_ &m)
{
  RobotClass robot(m, "ProjectiveRobot",
                   "A serial arm modelled in the projective frame of an uncalibrated stereo rig: acquisition, "
                   "kinematics, inverse kinematics, rig re-registration and model file (vpProjectiveRobot).");
  bindEnum<vpProjectiveRobot::vpJointType>(
      robot, "JointType", {{"REVOLUTE", vpProjectiveRobot::REVOLUTE}, {"PRISMATIC", vpProjectiveRobot::PRISMATIC}});
  bindEnum<vpProjectiveRobot::vpRigMounting>(
      robot, "RigMounting",
      {{"EYE_TO_HAND", vpProjectiveRobot::EYE_TO_HAND}, {"EYE_IN_HAND", vpProjectiveRobot::EYE_IN_HAND}});
  py::class_<vpProjectiveRigRegistration> registration(m, "ProjectiveRigRegistration");
  bindEnum<vpProjectiveRigRegistration::vpRegistrationMode>(
      registration, "RegistrationMode",
      {{"FIXED_INTRINSICS", vpProjectiveRigRegistration::FIXED_INTRINSICS},
       {"GENERAL", vpProjectiveRigRegistration::GENERAL}});
  bindRobotContract(robot);
  bindRobotMore(robot);
  bindRobotParts(m);
  bindArmModel(m);
}
} // namespace vpPython
