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
  Python bindings of ViSP's robot interface (Robot: vpRobot's joint-space calls and enumerations) and of the simulated
  cell: the metric arm (SimulatorArm), the metric rig (SimulatorStereoRig), the arm as a vpRobot (SimulatorRobotArm),
  the AprilTag renderer (SimulatorTagRenderer) and the cell that ties them (SimulatorStereoCell).
*/

#include "module.h"

#include <visp3/core/vpGaussRand.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorRobotArm.h>
#include <visp3/projective/vpSimulatorStereoCell.h>
#include <visp3/projective/vpSimulatorStereoRig.h>
#include <visp3/projective/vpSimulatorTagRenderer.h>
#include <visp3/robot/vpRobot.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
void bindRobotInterface(py::module_ &m)
{
  py::class_<vpRobot> robot(m, "Robot",
                            "ViSP's robot interface (vpRobot), its joint-space calls: what the acquisition procedure "
                            "drives. SimulatorRobotArm is one; a Python class with the same methods is another.");
  bindEnum<vpRobot::vpRobotStateType>(robot, "RobotStateType",
                                      {{"STATE_STOP", vpRobot::STATE_STOP},
                                       {"STATE_VELOCITY_CONTROL", vpRobot::STATE_VELOCITY_CONTROL},
                                       {"STATE_POSITION_CONTROL", vpRobot::STATE_POSITION_CONTROL},
                                       {"STATE_ACCELERATION_CONTROL", vpRobot::STATE_ACCELERATION_CONTROL}});
  bindEnum<vpRobot::vpControlFrameType>(robot, "ControlFrameType",
                                        {{"REFERENCE_FRAME", vpRobot::REFERENCE_FRAME},
                                         {"ARTICULAR_FRAME", vpRobot::ARTICULAR_FRAME},
                                         {"JOINT_STATE", vpRobot::JOINT_STATE},
                                         {"END_EFFECTOR_FRAME", vpRobot::END_EFFECTOR_FRAME},
                                         {"CAMERA_FRAME", vpRobot::CAMERA_FRAME},
                                         {"TOOL_FRAME", vpRobot::TOOL_FRAME},
                                         {"MIXT_FRAME", vpRobot::MIXT_FRAME}});
  robot
      .def(
          "getPosition",
          [](vpRobot &r, vpRobot::vpControlFrameType frame) {
            vpColVector q;
            r.getPosition(frame, q);
            return q;
          },
          py::arg("frame"))
      .def("setPosition", &vpRobot::setPosition, py::arg("frame"), py::arg("q"), ReleaseGil())
      .def("setVelocity", &vpRobot::setVelocity, py::arg("frame"), py::arg("vel"), ReleaseGil())
      .def("setRobotState", &vpRobot::setRobotState, py::arg("newState"))
      .def("getRobotState", &vpRobot::getRobotState)
      .def("getMaxRotationVelocity", &vpRobot::getMaxRotationVelocity)
      .def("setMaxRotationVelocity", &vpRobot::setMaxRotationVelocity, py::arg("maxVr"))
      .def("getMaxTranslationVelocity", &vpRobot::getMaxTranslationVelocity)
      .def("setMaxTranslationVelocity", &vpRobot::setMaxTranslationVelocity, py::arg("maxVt"));
}

void bindArm(py::module_ &m)
{
  py::class_<vpSimulatorArm> arm(m, "SimulatorArm",
                                 "A metric serial arm with markers on its tool: the simulator's ground truth "
                                 "(vpSimulatorArm).");
  arm.attr("JointType") = m.attr("ProjectiveRobot").attr("JointType");
  py::class_<vpSimulatorArm::vpDHRow>(arm, "DHRow", "One Denavit-Hartenberg row R_z(theta) T_z(d) T_x(a) R_x(alpha).")
      .def(py::init([](vpProjectiveJoint::vpJointType type, double theta, double d, double a, double alpha) {
             return vpSimulatorArm::vpDHRow{type, theta, d, a, alpha};
           }),
           py::arg("type"), py::arg("theta"), py::arg("d"), py::arg("a"), py::arg("alpha"))
      .def_readwrite("type", &vpSimulatorArm::vpDHRow::type)
      .def_readwrite("theta", &vpSimulatorArm::vpDHRow::theta)
      .def_readwrite("d", &vpSimulatorArm::vpDHRow::d)
      .def_readwrite("a", &vpSimulatorArm::vpDHRow::a)
      .def_readwrite("alpha", &vpSimulatorArm::vpDHRow::alpha);
  arm.def(py::init<const std::vector<vpSimulatorArm::vpDHRow> &, const vpHomogeneousMatrix &,
                   const std::vector<vpColVector> &, const vpHomogeneousMatrix &>(),
          py::arg("dh"), py::arg("eMt"), py::arg("tMarkers"), py::arg("wMb"))
      .def_static("puma", &vpSimulatorArm::puma, py::arg("wMb"))
      .def_static("viper850", &vpSimulatorArm::viper850, py::arg("wMb"))
      .def_static("pumaTable", &vpSimulatorArm::pumaTable)
      .def_static("stanfordTable", &vpSimulatorArm::stanfordTable)
      .def_static("gripperMarkers", &vpSimulatorArm::gripperMarkers)
      .def_static("gripperMount", &vpSimulatorArm::gripperMount)
      .def_static("paperBasePose", &vpSimulatorArm::paperBasePose)
      .def("getNumberOfJoints", &vpSimulatorArm::getNumberOfJoints)
      .def("getJointType", &vpSimulatorArm::getJointType, py::arg("i"))
      .def("get_wMt", &vpSimulatorArm::get_wMt, py::arg("q"))
      .def("get_wMe", &vpSimulatorArm::get_wMe, py::arg("q"))
      .def("get_wMb", &vpSimulatorArm::get_wMb)
      .def("get_eMt", &vpSimulatorArm::get_eMt)
      .def("getDHTable", &vpSimulatorArm::getDHTable)
      .def("getMarkers", &vpSimulatorArm::getMarkers, py::arg("q"), "The markers' world points (N, 3) at q.")
      .def("getToolMarkers", &vpSimulatorArm::getToolMarkers)
      .def("getTwist", &vpSimulatorArm::getTwist, py::arg("i"))
      .def("getDisplacement", &vpSimulatorArm::getDisplacement, py::arg("q"))
      .def("getJointMin", &vpSimulatorArm::getJointMin)
      .def("getJointMax", &vpSimulatorArm::getJointMax)
      .def("setJointLimits", &vpSimulatorArm::setJointLimits, py::arg("qmin"), py::arg("qmax"))
      .def("integrate", &vpSimulatorArm::integrate, py::arg("q"), py::arg("qdot"), py::arg("dt"));
}

void bindRig(py::module_ &m)
{
  py::class_<vpSimulatorStereoRig>(m, "SimulatorStereoRig",
                                   "A metric stereo rig: the simulator's cameras and its ground truth "
                                   "(vpSimulatorStereoRig).")
      .def_static("paperRig", &vpSimulatorStereoRig::paperRig, py::arg("fixation"), py::arg("distance") = 1.0)
      .def_static(
          "vergingRig",
          [](const vpColVector &fixation, double distance, double baseline) {
            return vpSimulatorStereoRig::vergingRig(fixation, distance, baseline);
          },
          py::arg("fixation"), py::arg("distance"), py::arg("baseline"), "A verging rig of the paper's cameras.")
      .def("getWidth", &vpSimulatorStereoRig::getWidth)
      .def("getHeight", &vpSimulatorStereoRig::getHeight)
      .def("get_rMl", &vpSimulatorStereoRig::get_rMl)
      .def("get_wMl", &vpSimulatorStereoRig::get_wMl)
      .def("getLeftMetricProjection", &vpSimulatorStereoRig::getLeftMetricProjection)
      .def("getRightMetricProjection", &vpSimulatorStereoRig::getRightMetricProjection)
      .def("getFundamentalMatrix", &vpSimulatorStereoRig::getFundamentalMatrix)
      .def(
          "getProjectiveToEuclidean",
          [](const vpSimulatorStereoRig &r, const vpProjectiveStereoRig &rig) {
            return r.getProjectiveToEuclidean(rig);
          },
          py::arg("rig"))
      .def(
          "project",
          [](const vpSimulatorStereoRig &r, const vpColVector &wX) {
            vpImagePoint left, right;
            const bool visible = r.project(wX, left, right);
            return py::make_tuple(visible, left, right);
          },
          py::arg("wX"), "(visible, left (u, v), right (u', v')) of the world point wX (3,), noise-free.")
      .def(
          "project",
          [](const vpSimulatorStereoRig &r, const std::vector<vpColVector> &wX) {
            std::vector<vpImagePoint> left, right;
            vpGaussRand unused;
            const bool visible = r.project(wX, left, right, 0.0, unused);
            return py::make_tuple(visible, left, right);
          },
          py::arg("wX"), "(all visible, left (N, 2), right (N, 2)) of the world points wX (N, 3), noise-free.")
      .def("isVisible", &vpSimulatorStereoRig::isVisible, py::arg("wX"), py::arg("margin") = 0.0,
           py::arg("minDepth") = 0.05);
}

void bindCell(py::module_ &m)
{
  py::class_<vpSimulatorRobotArm, vpRobot>(m, "SimulatorRobotArm",
                                           "A SimulatorArm behind ViSP's vpRobot interface: joint velocity and "
                                           "position control, encoder readings (vpSimulatorRobotArm).")
      .def(py::init<const vpSimulatorArm &, const vpColVector &>(), py::arg("arm"), py::arg("q0") = vpColVector())
      .def("getVelocity", py::overload_cast<const vpRobot::vpControlFrameType>(&vpSimulatorRobotArm::getVelocity),
           py::arg("frame"))
      .def("setConstantSamplingTimeMode", &vpSimulatorRobotArm::setConstantSamplingTimeMode, py::arg("constant"))
      .def("getConstantSamplingTimeMode", &vpSimulatorRobotArm::getConstantSamplingTimeMode)
      .def("setSamplingTime", &vpSimulatorRobotArm::setSamplingTime, py::arg("seconds"))
      .def("getSamplingTime", &vpSimulatorRobotArm::getSamplingTime)
      .def("setEncoderOffset", &vpSimulatorRobotArm::setEncoderOffset, py::arg("offset"))
      .def("getEncoderOffset", &vpSimulatorRobotArm::getEncoderOffset)
      .def("getJointMin", &vpSimulatorRobotArm::getJointMin)
      .def("getJointMax", &vpSimulatorRobotArm::getJointMax)
      .def("setJointLimits", &vpSimulatorRobotArm::setJointLimits, py::arg("qmin"), py::arg("qmax"))
      .def("getNumberOfJoints", &vpSimulatorRobotArm::getNumberOfJoints)
      .def("getArm", &vpSimulatorRobotArm::getArm, py::return_value_policy::reference_internal)
      .def("getArmJoints", &vpSimulatorRobotArm::getArmJoints)
      .def("getTime", &vpSimulatorRobotArm::getTime);

  py::class_<vpSimulatorTagRenderer>(m, "SimulatorTagRenderer",
                                     "Renders printed AprilTags (36h11) in both cameras of a SimulatorStereoRig "
                                     "(vpSimulatorTagRenderer).")
      .def(py::init<const vpSimulatorStereoRig &, long>(), py::arg("rig"), py::arg("seed") = 1)
      .def("addTag", &vpSimulatorTagRenderer::addTag, py::arg("id"), py::arg("size"), py::arg("bMt"))
      .def("setTagPose", &vpSimulatorTagRenderer::setTagPose, py::arg("index"), py::arg("bMt"))
      .def("setBodyPose", &vpSimulatorTagRenderer::setBodyPose, py::arg("wMb"))
      .def("getNbTags", &vpSimulatorTagRenderer::getNbTags)
      .def("getCorners", &vpSimulatorTagRenderer::getCorners, py::arg("index"))
      .def(
          "getImageCorners",
          [](const vpSimulatorTagRenderer &r, unsigned int index) {
            std::vector<vpImagePoint> left, right;
            const bool visible = r.getImageCorners(index, left, right);
            return py::make_tuple(visible, left, right);
          },
          py::arg("index"), "(visible, left (4, 2), right (4, 2)): the true corners of tag `index`.")
      .def("setGrayLevels", &vpSimulatorTagRenderer::setGrayLevels, py::arg("background"), py::arg("black"),
           py::arg("white"))
      .def("setBlur", &vpSimulatorTagRenderer::setBlur, py::arg("sigma"))
      .def("setNoise", &vpSimulatorTagRenderer::setNoise, py::arg("sigma"))
      .def("setLighting", &vpSimulatorTagRenderer::setLighting, py::arg("gain"), py::arg("offset"),
           py::arg("gradientU") = 0.0, py::arg("gradientV") = 0.0)
      .def("setOccluder", &vpSimulatorTagRenderer::setOccluder, py::arg("wC"), py::arg("radius"),
           py::arg("level") = 15.0)
      .def("clearOccluder", &vpSimulatorTagRenderer::clearOccluder)
      .def("setSeed", &vpSimulatorTagRenderer::setSeed, py::arg("seed"))
      .def(
          "render",
          [](vpSimulatorTagRenderer &r) {
            return stereoPair([&](vpImage<unsigned char> &left, vpImage<unsigned char> &right) {
              r.render(left, right);
              return true;
            });
          },
          "(left, right): both cameras' images, 2-D uint8 arrays.");

  py::class_<vpSimulatorStereoCell>(m, "SimulatorStereoCell",
                                    "A robot cell as a program sees real hardware: an arm behind vpRobot and two "
                                    "cameras rendering its AprilTags (vpSimulatorStereoCell).")
      .def(py::init<const vpSimulatorArm &, const vpSimulatorStereoRig &, const vpColVector &, long>(), py::arg("arm"),
           py::arg("rig"), py::arg("q0") = vpColVector(), py::arg("seed") = 1)
      .def("addToolTag", &vpSimulatorStereoCell::addToolTag, py::arg("id"), py::arg("size"), py::arg("tMg"))
      .def("addToolTags", &vpSimulatorStereoCell::addToolTags, py::arg("size"), py::arg("firstId") = 0)
      .def("addSceneTag", &vpSimulatorStereoCell::addSceneTag, py::arg("id"), py::arg("size"), py::arg("wMg"))
      .def("setEyeInHand", &vpSimulatorStereoCell::setEyeInHand)
      .def("isEyeInHand", &vpSimulatorStereoCell::isEyeInHand)
      .def("getRobot", &vpSimulatorStereoCell::getRobot, py::return_value_policy::reference_internal)
      .def("getRenderer", &vpSimulatorStereoCell::getRenderer, py::return_value_policy::reference_internal)
      .def("getStereoRig", &vpSimulatorStereoCell::getStereoRig, py::return_value_policy::copy)
      .def(
          "acquire",
          [](vpSimulatorStereoCell &cell) {
            return stereoPair([&](vpImage<unsigned char> &left, vpImage<unsigned char> &right) {
              return cell.acquire(left, right); // always true: a rendered cell never runs out of images
            });
          },
          "(left, right): the two cameras' images at the arm's current joints, 2-D uint8 arrays.")
      .def("getWidth", &vpSimulatorStereoCell::getWidth)
      .def("getHeight", &vpSimulatorStereoCell::getHeight)
      .def(
          "getTrueCorners",
          [](vpSimulatorStereoCell &cell) {
            std::vector<int> ids;
            std::vector<vpImagePoint> left, right;
            cell.getTrueCorners(ids, left, right);
            return py::make_tuple(ids, left, right);
          },
          "(ids, left (N, 2), right (N, 2)): the true images of the tag corners seen in both images.");
}
} // namespace

void bindSimulation(py::module_ &m)
{
  bindRobotInterface(m);
  bindArm(m);
  bindRig(m);
  bindCell(m);
}
} // namespace vpPython
