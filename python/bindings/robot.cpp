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
  bindRobotMore(): the one place to adapt when vpProjectiveRobot's public methods change (issue 32).
*/

#include "module.h"

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveRigRegistration.h>
#include <visp3/projective/vpProjectiveRobot.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
typedef py::class_<vpProjectiveRobot> RobotClass;
typedef std::vector<vpImagePoint> Pixels;

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
      .def("getCalibrationResidual", &vpProjectiveRobot::getCalibrationResidual)
      .def("getAlgebraicResidual", &vpProjectiveRobot::getAlgebraicResidual)
      .def("setOutlierThreshold", &vpProjectiveRobot::setOutlierThreshold, py::arg("pixels"))
      .def("getModel", &vpProjectiveRobot::getModel, py::return_value_policy::copy)
      .def("getProjectiveToMetric", &vpProjectiveRobot::getProjectiveToMetric)
      .def("getTwist", &vpProjectiveRobot::getTwist, py::arg("i"))
      .def("getZeroReferencePoints", &vpProjectiveRobot::getZeroReferencePoints)
      .def("getZeroReferenceJoints", &vpProjectiveRobot::getZeroReferenceJoints)
      .def(
          "getMetricStereoRig",
          [](const vpProjectiveRobot &r, unsigned int markerA, unsigned int markerB, double distance) {
            vpMatrix Kl, Kr;
            vpHomogeneousMatrix lMr;
            r.getMetricStereoRig(Kl, Kr, lMr, markerA, markerB, distance);
            return py::make_tuple(Kl, Kr, lMr);
          },
          py::arg("markerA"), py::arg("markerB"), py::arg("distance"))
      .def(
          "getMetricJointAxes",
          [](const vpProjectiveRobot &r) {
            std::vector<vpColVector> direction, point;
            r.getMetricJointAxes(direction, point);
            return py::make_tuple(direction, point);
          },
          "(directions, points): per joint a unit direction and a point of its axis, (n, 3) arrays.")
      .def("getJointMotion", &vpProjectiveRobot::getJointMotion, py::arg("k"), py::arg("q"))
      .def("getPointJacobian", &vpProjectiveRobot::getPointJacobian, py::arg("q"), py::arg("M"))
      .def(
          "projectMarker",
          [](const vpProjectiveRobot &r, unsigned int j, const vpColVector &q) {
            vpImagePoint left, right;
            r.projectMarker(j, q, left, right);
            return py::make_tuple(left, right);
          },
          py::arg("j"), py::arg("q"))
      .def(
          "predictMarkers",
          [](const vpProjectiveRobot &r, const std::vector<vpColVector> &trajectory,
             const std::vector<unsigned int> &indices) {
            std::vector<Pixels> left, right;
            r.predictMarkers(trajectory, left, right, indices);
            return py::make_tuple(left, right);
          },
          py::arg("trajectory"), py::arg("indices") = std::vector<unsigned int>(),
          "The predicted pixels of the markers along the joint trajectory (K, n): two lists of (N, 2) arrays.")
      .def("getNumberOfRigObservations", &vpProjectiveRobot::getNumberOfRigObservations)
      .def("clearRigObservations", &vpProjectiveRobot::clearRigObservations)
      .def("setRigRegistrationMode", &vpProjectiveRobot::setRigRegistrationMode, py::arg("mode"))
      .def("getRigRegistrationMode", &vpProjectiveRobot::getRigRegistrationMode)
      .def("getRigRegistrationResidual", &vpProjectiveRobot::getRigRegistrationResidual);
}
} // namespace

void bindRobot(py::module_ &m)
{
  RobotClass robot(m, "ProjectiveRobot",
                   "A serial arm modelled in the projective frame of an uncalibrated stereo rig: acquisition, "
                   "kinematics, inverse kinematics, rig re-registration and model file (vpProjectiveRobot).");
  py::enum_<vpProjectiveRobot::vpJointType>(robot, "JointType")
      .value("REVOLUTE", vpProjectiveRobot::REVOLUTE)
      .value("PRISMATIC", vpProjectiveRobot::PRISMATIC)
      .export_values();
  py::enum_<vpProjectiveRobot::vpRigMounting>(robot, "RigMounting")
      .value("EYE_TO_HAND", vpProjectiveRobot::EYE_TO_HAND)
      .value("EYE_IN_HAND", vpProjectiveRobot::EYE_IN_HAND)
      .export_values();
  py::class_<vpProjectiveRigRegistration> registration(m, "ProjectiveRigRegistration");
  py::enum_<vpProjectiveRigRegistration::vpRegistrationMode>(registration, "RegistrationMode")
      .value("FIXED_INTRINSICS", vpProjectiveRigRegistration::FIXED_INTRINSICS)
      .value("GENERAL", vpProjectiveRigRegistration::GENERAL)
      .export_values();
  bindRobotContract(robot);
  bindRobotMore(robot);

  py::class_<vpProjectiveArmModel>(m, "ProjectiveArmModel",
                                   "An acquired model (vpProjectiveArmModel): what calibrations return; a "
                                   "ProjectiveRobot reads its file (loadModel()).")
      .def("getNumberOfJoints", &vpProjectiveArmModel::getNumberOfJoints)
      .def("getRigMounting", &vpProjectiveArmModel::getRigMounting)
      .def("getStereoRig", &vpProjectiveArmModel::getStereoRig, py::return_value_policy::copy);
}
} // namespace vpPython
