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
  Python bindings of what acquires an arm in a cell: the AprilTag detector on numpy images (StereoAprilTagDetector)
  and the acquisition procedure (ProjectiveAcquisitionProcedure) on a robot that is either ViSP's (a bound vpRobot
  such as SimulatorRobotArm) or a Python object (PythonRobot below).

  The procedure's image source, step callback and progress output are Python callables or files: the procedure runs
  with the GIL released and takes it at each of their calls.
*/

#include "module.h"

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>
#include <visp3/robot/vpRobotException.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
/*!
  A vpRobot whose joint-space calls go to a Python object, for vpProjectiveAcquisitionProcedure::run(): the calls
  the procedure makes, with vpRobot's names and arguments,
  - getPosition(frame) -> the joint readings, a 1-D array (rad or m): required;
  - setVelocity(frame, qdot): required with the default VELOCITY_CONTROL (each call moves the joints at qdot until
    the next; a simulated arm may move one sampling period per call, as vpSimulatorRobotArm's constant sampling mode);
  - setPosition(frame, q): required with POSITION_CONTROL (returns once there);
  - setRobotState(state), getMaxRotationVelocity(), getMaxTranslationVelocity(): optional (without the getters,
    ViSP's defaults 0.7 rad/s and 0.2 m/s bound the velocities; setSpeed() of the procedure sets this adapter's).
  frame is Robot.ARTICULAR_FRAME, state a Robot.RobotStateType. Each call takes the GIL (the procedure runs without
  it); a Python exception in a call stops the run (the procedure sends the arm back to the zero reference) and is
  raised again by run(). The object is created and destroyed with the GIL held.
*/
class PythonRobot : public vpRobot
{
public:
  explicit PythonRobot(py::object robot) : m_robot(std::move(robot))
  {
    if (!py::hasattr(m_robot, "getPosition") || !py::hasattr(m_robot, "setVelocity")) {
      throw py::type_error("the robot given to ProjectiveAcquisitionProcedure.run() is neither a visp_projective.Robot "
                           "nor a Python object with vpRobot's getPosition(frame) and setVelocity(frame, qdot) "
                           "(and setPosition(frame, q) for POSITION_CONTROL): give it these methods.");
    }
    if (py::hasattr(m_robot, "getMaxRotationVelocity")) {
      setMaxRotationVelocity(m_robot.attr("getMaxRotationVelocity")().cast<double>());
    }
    if (py::hasattr(m_robot, "getMaxTranslationVelocity")) {
      setMaxTranslationVelocity(m_robot.attr("getMaxTranslationVelocity")().cast<double>());
    }
  }
  void init() override {}
  void getPosition(const vpRobot::vpControlFrameType frame, vpColVector &q) override
  {
    py::gil_scoped_acquire gil;
    py::object reading = m_robot.attr("getPosition")(frame);
    try {
      q = reading.cast<vpColVector>();
    } catch (const py::cast_error &) {
      throw py::type_error("getPosition(frame) of the Python robot returned " +
                           std::string(py::str(reading.get_type())) +
                           ": return the joint readings as a 1-D array of floats (rad or m).");
    }
  }
  void setPosition(const vpRobot::vpControlFrameType frame, const vpColVector &q) override
  {
    py::gil_scoped_acquire gil;
    m_robot.attr("setPosition")(frame, q);
  }
  void setVelocity(const vpRobot::vpControlFrameType frame, const vpColVector &qdot) override
  {
    py::gil_scoped_acquire gil;
    m_robot.attr("setVelocity")(frame, qdot);
  }
  vpRobotStateType setRobotState(const vpRobot::vpRobotStateType state) override
  {
    py::gil_scoped_acquire gil;
    if (py::hasattr(m_robot, "setRobotState")) {
      m_robot.attr("setRobotState")(state);
    }
    return vpRobot::setRobotState(state);
  }
  // Not called by the procedure.
  void get_eJe(vpMatrix &) override { unsupported("get_eJe()"); }
  void get_fJe(vpMatrix &) override { unsupported("get_fJe()"); }
  void getDisplacement(const vpRobot::vpControlFrameType, vpColVector &) override { unsupported("getDisplacement()"); }

private:
  static void unsupported(const std::string &what)
  {
    throw vpRobotException(vpRobotException::functionNotImplementedError,
                           "a Python robot has no " + what + " (it forwards vpRobot's joint-space calls only)");
  }

  py::object m_robot;
};

typedef WithOutput<vpProjectiveAcquisitionProcedure> Procedure;

//! The procedure on marker images from the Python callable \e source: source() -> (left, right) or None when a
//! marker is lost; with \e identified, source() -> (ids, left, right) or None when no image could be read.
Procedure *newProcedure(py::object source, unsigned int width, unsigned int height, bool identified)
{
  const Callable call(std::move(source));
  if (identified) {
    return new Procedure(
        [call](std::vector<int> &ids, Pixels &left, Pixels &right) {
          return call.call([&](py::object r) {
            if (r.is_none()) {
              return false;
            }
            try {
              std::tie(ids, left, right) = r.cast<std::tuple<std::vector<int>, Pixels, Pixels>>();
            } catch (const py::cast_error &) {
              throw py::type_error("the identified image source must return (ids, left, right): a list of int and two "
                                   "(N, 2) arrays of (u, v) pixels, or None when no image could be read");
            }
            return true;
          });
        },
        width, height);
  }
  return new Procedure(vpProjectiveAcquisitionProcedure::vpImageSource([call](Pixels &left, Pixels &right) {
                         return call.call([&](py::object r) {
                           if (r.is_none()) {
                             return false;
                           }
                           try {
                             std::tie(left, right) = r.cast<std::tuple<Pixels, Pixels>>();
                           } catch (const py::cast_error &) {
                             throw py::type_error(
                                 "the image source must return (left, right): two (N, 2) arrays of (u, v) pixels "
                                 "in the same marker order, or None when a marker is lost");
                           }
                           return true;
                         });
                       }),
                       width, height);
}

void bindProcedure(py::module_ &m)
{
  typedef vpProjectiveAcquisitionProcedure P;
  py::class_<Procedure> procedure(m, "ProjectiveAcquisitionProcedure",
                                  "Drives a robot through the acquisition of Ruf & Horaud (trial motions of each joint "
                                  "alone), calibrates the model and tells the rig's mounting "
                                  "(vpProjectiveAcquisitionProcedure).");
  bindEnum<P::vpMotionControl>(procedure, "MotionControl",
                               {{"VELOCITY_CONTROL", P::VELOCITY_CONTROL}, {"POSITION_CONTROL", P::POSITION_CONTROL}});
  bindEnum<P::vpStopReason>(procedure, "StopReason",
                            {{"AMOUNT_REACHED", P::AMOUNT_REACHED},
                             {"IMAGE_BORDER", P::IMAGE_BORDER},
                             {"MARKER_LOST", P::MARKER_LOST},
                             {"JOINT_LIMIT", P::JOINT_LIMIT}});
  py::class_<P::vpJointReport>(procedure, "JointReport")
      .def_readonly("amountNegative", &P::vpJointReport::amountNegative)
      .def_readonly("amountPositive", &P::vpJointReport::amountPositive)
      .def_readonly("stopNegative", &P::vpJointReport::stopNegative)
      .def_readonly("stopPositive", &P::vpJointReport::stopPositive)
      .def_readonly("trials", &P::vpJointReport::trials);
  py::class_<P::vpMountingReport>(procedure, "MountingReport")
      .def_readonly("checked", &P::vpMountingReport::checked)
      .def_readonly("set", &P::vpMountingReport::set)
      .def_readonly("kept", &P::vpMountingReport::kept)
      .def_readonly("residual", &P::vpMountingReport::residual)
      .def_readonly("otherResidual", &P::vpMountingReport::otherResidual)
      .def_readonly("separation", &P::vpMountingReport::separation)
      .def_readonly("q", &P::vpMountingReport::q);
  procedure
      .def(py::init(&newProcedure), py::arg("source"), py::arg("width"), py::arg("height"),
           py::arg("identified") = false,
           "A procedure on the marker images of source(): (left, right) (N, 2) arrays in a fixed marker order, or "
           "None when a marker is lost; with identified=True, (ids, left, right) with a marker's id beside its pixels.")
      .def("setMaxAmounts", &P::setMaxAmounts, py::arg("amounts"))
      .def("setSteps", &P::setSteps, py::arg("steps"))
      .def("setMinAmounts", &P::setMinAmounts, py::arg("amounts"))
      .def("setJointLimits", &P::setJointLimits, py::arg("qmin"), py::arg("qmax"), py::arg("margin"))
      .def("setImageMargin", &P::setImageMargin, py::arg("pixels"))
      .def("setImageSize", &P::setImageSize, py::arg("width"), py::arg("height"))
      .def("setSpeed", &P::setSpeed, py::arg("rotation"), py::arg("translation"))
      .def("setMotionControl", &P::setMotionControl, py::arg("control"))
      .def("getMotionControl", &P::getMotionControl)
      .def("setMoveTimeout", &P::setMoveTimeout, py::arg("seconds"))
      .def("setArrivalTolerance", &P::setArrivalTolerance, py::arg("tolerance"))
      .def("setCoplanarityThreshold", &P::setCoplanarityThreshold, py::arg("pixels"))
      .def("setMountingDetection", &P::setMountingDetection, py::arg("detect"))
      .def("setEpipolarThreshold", &P::setEpipolarThreshold, py::arg("pixels"))
      .def("setMinMarkerVisibility", &P::setMinMarkerVisibility, py::arg("fraction"))
      .def("getDroppedMarkers", &P::getDroppedMarkers)
      .def("setOutput", &Procedure::setPythonOutput, py::arg("file"),
           "Progress lines to the Python file `file` (e.g. sys.stdout); None: none.")
      .def(
          "setStepCallback",
          [](Procedure &p, py::object callback) {
            if (callback.is_none()) {
              p.setStepCallback(P::vpStepCallback());
              return;
            }
            const Callable call(std::move(callback));
            p.setStepCallback([call](unsigned int joint, const vpColVector &q, const Pixels &left,
                                     const Pixels &right) { call.call([](py::object) {}, joint, q, left, right); });
          },
          py::arg("callback"), "callback(joint, q, left, right) after each step; None: none.")
      .def(
          "run",
          [](Procedure &p, py::object robot, vpProjectiveRobot &projectiveRobot) {
            if (py::isinstance<vpRobot>(robot)) {
              vpRobot &visp = robot.cast<vpRobot &>();
              py::gil_scoped_release release;
              p.run(visp, projectiveRobot);
            } else {
              PythonRobot adapter(robot);
              py::gil_scoped_release release;
              p.run(adapter, projectiveRobot);
            }
          },
          py::arg("robot"), py::arg("projectiveRobot"),
          "Runs the acquisition on `robot` (a visp_projective.Robot, or a Python object with getPosition(frame) and "
          "setVelocity(frame, qdot)) and calibrates `projectiveRobot`.")
      .def("getReports", &P::getReports)
      .def("getMountingReport", &P::getMountingReport)
      .def("getCalibrationResidual", &P::getCalibrationResidual)
      .def("getGeneralPositionParallax", &P::getGeneralPositionParallax)
      .def_static("toString", &P::toString, py::arg("reason"));
}

#if defined(VISP_HAVE_APRILTAG)
void bindDetector(py::module_ &m)
{
  py::class_<vpStereoAprilTagDetector> detector(m, "StereoAprilTagDetector",
                                                "AprilTag corners found in both images of a stereo pair "
                                                "(vpStereoAprilTagDetector).");
  bindEnum<vpDetectorAprilTag::vpAprilTagFamily>(detector, "AprilTagFamily",
                                                 {{"TAG_36h11", vpDetectorAprilTag::TAG_36h11},
                                                  {"TAG_25h9", vpDetectorAprilTag::TAG_25h9},
                                                  {"TAG_16h5", vpDetectorAprilTag::TAG_16h5},
                                                  {"TAG_CIRCLE21h7", vpDetectorAprilTag::TAG_CIRCLE21h7},
                                                  {"TAG_CIRCLE49h12", vpDetectorAprilTag::TAG_CIRCLE49h12},
                                                  {"TAG_CUSTOM48h12", vpDetectorAprilTag::TAG_CUSTOM48h12},
                                                  {"TAG_STANDARD41h12", vpDetectorAprilTag::TAG_STANDARD41h12},
                                                  {"TAG_STANDARD52h13", vpDetectorAprilTag::TAG_STANDARD52h13}});
  detector.def(py::init<vpDetectorAprilTag::vpAprilTagFamily>(), py::arg("family") = vpDetectorAprilTag::TAG_36h11)
      .def("setStereoRig", &vpStereoAprilTagDetector::setStereoRig, py::arg("rig"))
      .def("clearStereoRig", &vpStereoAprilTagDetector::clearStereoRig)
      .def("setEpipolarThreshold", &vpStereoAprilTagDetector::setEpipolarThreshold, py::arg("pixels"))
      .def("getEpipolarThreshold", &vpStereoAprilTagDetector::getEpipolarThreshold)
      .def("setDecimation", &vpStereoAprilTagDetector::setDecimation, py::arg("decimation"))
      .def("setRefinement", &vpStereoAprilTagDetector::setRefinement, py::arg("refine"))
      .def("setNbThreads", &vpStereoAprilTagDetector::setNbThreads, py::arg("threads"))
      .def("setPredictedRegions", &vpStereoAprilTagDetector::setPredictedRegions, py::arg("ids"), py::arg("left"),
           py::arg("right"))
      .def("clearPredictedRegions", &vpStereoAprilTagDetector::clearPredictedRegions)
      .def("setRegionMargin", &vpStereoAprilTagDetector::setRegionMargin, py::arg("pixels"))
      .def("hasPredictedRegions", &vpStereoAprilTagDetector::hasPredictedRegions)
      .def("detect", &vpStereoAprilTagDetector::detect, py::arg("Ileft"), py::arg("Iright"), ReleaseGil(),
           "Detects in two uint8 images; returns the number of corners found in both.")
      .def("getIds", &vpStereoAprilTagDetector::getIds, "4 * tag id + corner index, ascending.")
      .def("getLeftPoints", &vpStereoAprilTagDetector::getLeftPoints, "(N, 2) (u, v) in the order of getIds().")
      .def("getRightPoints", &vpStereoAprilTagDetector::getRightPoints)
      .def("getNbEpipolarRejections", &vpStereoAprilTagDetector::getNbEpipolarRejections);
}
#endif
} // namespace

void bindAcquisition(py::module_ &m)
{
  bindProcedure(m);
#if defined(VISP_HAVE_APRILTAG)
  bindDetector(m);
#endif
}
} // namespace vpPython
