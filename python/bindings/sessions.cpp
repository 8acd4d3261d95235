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
  Python bindings of recorded sessions (DESIGN.md section 3: a folder with session.json and its images): the reader
  (ProjectiveSession), the writer (ProjectiveSessionWriter, also a context manager that closes the recording), the
  replay as an image source (ProjectiveSessionSource) and the offline calibration (ProjectiveSessionCalibration).
*/

#include "module.h"

#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>
#include <visp3/projective/vpProjectiveSessionSource.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
typedef vpProjectiveSession::vpFrameRole Role;

void bindSession(py::module_ &m)
{
  py::class_<vpProjectiveSession> session(m, "ProjectiveSession",
                                          "A recorded session: session.json and the images it names "
                                          "(vpProjectiveSession).");
  session.attr("JointType") = m.attr("ProjectiveRobot").attr("JointType");
  bindEnum<Role>(session, "FrameRole",
                 {{"ZERO", vpProjectiveSession::ZERO},
                  {"TRIAL", vpProjectiveSession::TRIAL},
                  {"OBSERVATION", vpProjectiveSession::OBSERVATION},
                  {"TARGET", vpProjectiveSession::TARGET},
                  {"SERVO", vpProjectiveSession::SERVO}});
  typedef vpProjectiveSession::vpFrame Frame;
  py::class_<Frame>(session, "Frame", "One stereo frame as recorded.")
      .def_readonly("role", &Frame::role)
      .def_readonly("q", &Frame::q)
      .def_readonly("hasTime", &Frame::hasTime)
      .def_readonly("t", &Frame::t)
      .def_readonly("left", &Frame::left)
      .def_readonly("right", &Frame::right)
      .def_readonly("markerIds", &Frame::markerIds)
      .def_readonly("markerLeft", &Frame::markerLeft)
      .def_readonly("markerRight", &Frame::markerRight);
  session.def(py::init<>())
      .def_static("read", &vpProjectiveSession::read, py::arg("folder"), py::arg("checkImages") = true, ReleaseGil())
      .def_static("fromString", &vpProjectiveSession::fromString, py::arg("text"), py::arg("name"))
      .def("toString", py::overload_cast<>(&vpProjectiveSession::toString, py::const_))
      .def("getFolder", &vpProjectiveSession::getFolder)
      .def("getNumberOfJoints", &vpProjectiveSession::getNumberOfJoints)
      .def("getJointTypes", &vpProjectiveSession::getJointTypes)
      .def("getNumberOfFrames", py::overload_cast<>(&vpProjectiveSession::getNumberOfFrames, py::const_))
      .def("getNumberOfFrames", py::overload_cast<Role>(&vpProjectiveSession::getNumberOfFrames, py::const_),
           py::arg("role"))
      .def("getFrame", &vpProjectiveSession::getFrame, py::arg("k"), py::return_value_policy::copy)
      .def("getZeroFrame", &vpProjectiveSession::getZeroFrame)
      .def("getTrialJoint", &vpProjectiveSession::getTrialJoint, py::arg("k"))
      .def("getImagePath", &vpProjectiveSession::getImagePath, py::arg("k"), py::arg("left"))
      .def(
          "getImages",
          [](const vpProjectiveSession &s, unsigned int k) {
            return stereoPair([&](vpImage<unsigned char> &left, vpImage<unsigned char> &right) {
              s.getImages(k, left, right);
              return true;
            });
          },
          py::arg("k"), "(left, right): the grey images of frame k, 2-D uint8 arrays.")
      .def("getWidth", &vpProjectiveSession::getWidth)
      .def("getHeight", &vpProjectiveSession::getHeight);
}

void bindWriter(py::module_ &m)
{
  typedef vpProjectiveSessionWriter W;
  py::class_<W>(m, "ProjectiveSessionWriter",
                "Records a session into a new folder, frame by frame (vpProjectiveSessionWriter); as a context "
                "manager, closes it at the end of the block.")
      .def(py::init<const std::string &, const std::vector<vpProjectiveJoint::vpJointType> &>(), py::arg("folder"),
           py::arg("types"))
      .def("addFrame",
           py::overload_cast<Role, const vpColVector &, double, const vpImage<unsigned char> &,
                             const vpImage<unsigned char> &>(&W::addFrame),
           py::arg("role"), py::arg("q"), py::arg("t"), py::arg("Ileft"), py::arg("Iright"), ReleaseGil())
      .def("addFrame",
           py::overload_cast<Role, const vpColVector &, double, const vpImage<unsigned char> &,
                             const vpImage<unsigned char> &, const std::vector<int> &, const Pixels &, const Pixels &>(
               &W::addFrame),
           py::arg("role"), py::arg("q"), py::arg("t"), py::arg("Ileft"), py::arg("Iright"), py::arg("ids"),
           py::arg("left"), py::arg("right"), ReleaseGil(), "A frame with the markers the program measured in it.")
      .def("addAcquisitionFrame", &W::addAcquisitionFrame, py::arg("q"), py::arg("t"), py::arg("Ileft"),
           py::arg("Iright"), ReleaseGil())
      .def("setSaveInterval", &W::setSaveInterval, py::arg("frames"), py::arg("seconds"))
      .def("save", &W::save)
      .def("close", &W::close)
      .def("isClosed", &W::isClosed)
      .def("getSession", &W::getSession, py::return_value_policy::copy)
      .def("getNumberOfSavedFrames", &W::getNumberOfSavedFrames)
      .def("getFolder", &W::getFolder)
      .def(
          "__enter__", [](W &w) -> W & { return w; }, py::return_value_policy::reference)
      .def("__exit__", [](W &w, py::object, py::object, py::object) { w.close(); });
}

void bindSource(py::module_ &m)
{
  typedef vpProjectiveSessionSource S;
  py::class_<S>(m, "ProjectiveSessionSource", "Replays a session's images (vpProjectiveSessionSource).")
      .def(py::init<const vpProjectiveSession &, const std::vector<Role> &>(), py::arg("session"),
           py::arg("roles") = std::vector<Role>())
      .def(
          "acquire",
          [](S &s) {
            return stereoPair(
                [&](vpImage<unsigned char> &left, vpImage<unsigned char> &right) { return s.acquire(left, right); });
          },
          "(left, right) of the next frame, or None after the last one.")
      .def("getWidth", &S::getWidth)
      .def("getHeight", &S::getHeight)
      .def("getFrameIndex", &S::getFrameIndex)
      .def("getJoints", &S::getJoints)
      .def("getFrame", &S::getFrame, py::return_value_policy::copy)
      .def("rewind", &S::rewind);
}

void bindCalibration(py::module_ &m)
{
  typedef WithOutput<vpProjectiveSessionCalibration> C;
  typedef vpProjectiveSessionCalibration B;
  py::class_<C> calibration(m, "ProjectiveSessionCalibration",
                            "Calibrates an arm from a recorded session, and checks a model on one "
                            "(vpProjectiveSessionCalibration); markers: AprilTag corners of `family`.");
  bindEnum<B::vpMountingChoice>(calibration, "MountingChoice",
                                {{"MOUNTING_AUTO", B::MOUNTING_AUTO},
                                 {"MOUNTING_EYE_TO_HAND", B::MOUNTING_EYE_TO_HAND},
                                 {"MOUNTING_EYE_IN_HAND", B::MOUNTING_EYE_IN_HAND}});
  bindEnum<B::vpRigState>(calibration, "RigState",
                          {{"RIG_UNCHANGED", B::RIG_UNCHANGED},
                           {"LEFT_CAMERA_MOVED", B::LEFT_CAMERA_MOVED},
                           {"RIGHT_CAMERA_MOVED", B::RIGHT_CAMERA_MOVED},
                           {"BOTH_CAMERAS_MOVED", B::BOTH_CAMERAS_MOVED},
                           {"CAMERAS_SWAPPED", B::CAMERAS_SWAPPED},
                           {"MARKERS_MOVED", B::MARKERS_MOVED},
                           {"OTHER_READINGS", B::OTHER_READINGS},
                           {"OTHER_CELL", B::OTHER_CELL}});
  py::class_<B::vpJointSummary>(calibration, "JointSummary")
      .def_readonly("type", &B::vpJointSummary::type)
      .def_readonly("trials", &B::vpJointSummary::trials)
      .def_readonly("smallest", &B::vpJointSummary::smallest)
      .def_readonly("largest", &B::vpJointSummary::largest)
      .def_readonly("residual", &B::vpJointSummary::residual);
  py::class_<B::vpFrameCheck>(calibration, "FrameCheck")
      .def_readonly("frame", &B::vpFrameCheck::frame)
      .def_readonly("role", &B::vpFrameCheck::role)
      .def_readonly("markers", &B::vpFrameCheck::markers)
      .def_readonly("left", &B::vpFrameCheck::left)
      .def_readonly("right", &B::vpFrameCheck::right)
      .def_readonly("rms", &B::vpFrameCheck::rms)
      .def_readonly("fits", &B::vpFrameCheck::fits);
  calibration
      .def(py::init([](const std::string &family) { return new C(B::aprilTagMarkers(family)); }),
           py::arg("family") = "36h11")
      .def("setRecordedMarkers", &B::setRecordedMarkers, py::arg("recorded"))
      .def("getRecordedMarkers", &B::getRecordedMarkers)
      .def("setOutput", &C::setPythonOutput, py::arg("file"),
           "Progress lines to the Python file `file` (e.g. sys.stdout); None: none.")
      .def("setMounting", &B::setMounting, py::arg("mounting"))
      .def("setEpipolarThreshold", &B::setEpipolarThreshold, py::arg("pixels"))
      .def("setOutlierThreshold", &B::setOutlierThreshold, py::arg("pixels"))
      .def("setCoplanarityThreshold", &B::setCoplanarityThreshold, py::arg("pixels"))
      .def("setMismatchThreshold", &B::setMismatchThreshold, py::arg("pixels"))
      .def("calibrate", &B::calibrate, py::arg("session"), ReleaseGil())
      .def("getMarkerIds", &B::getMarkerIds)
      .def("getCalibrationResidual", &B::getCalibrationResidual)
      .def("getAlgebraicResidual", &B::getAlgebraicResidual)
      .def("getJointSummaries", &B::getJointSummaries)
      .def("saveModel", &B::saveModel, py::arg("filename"))
      .def_static("checkWritable", &B::checkWritable, py::arg("filename"))
      .def(
          "check",
          [](C &self, const vpProjectiveArmModel &model, const std::vector<int> &ids,
             const vpProjectiveSession &session) { return self.check(model, ids, session); },
          py::arg("model"), py::arg("ids"), py::arg("session"), ReleaseGil())
      .def("getRigState", &B::getRigState)
      .def("getDiagnosisMessage", &B::getDiagnosisMessage)
      .def("getLeftResidual", &B::getLeftResidual)
      .def("getRightResidual", &B::getRightResidual)
      .def_static("toString", &B::toString, py::arg("state"));
}
} // namespace

void bindSessions(py::module_ &m)
{
  bindSession(m);
  bindWriter(m);
  bindSource(m);
  bindCalibration(m);
}
} // namespace vpPython
