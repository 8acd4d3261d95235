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
  Python bindings of the servo: the stereo point feature (FeatureStereoPoint), the task (ServoProjective), the report
  of its last call (ServoProjectiveReport) and the settings of its path planner (ProjectivePathPlanner).

  As in C++, the task keeps references to its robot and features: the Python objects stay alive as long as the task
  (keep_alive), and the loop updates the features with buildFrom(). The methods named by DESIGN.md's contract are
  bound in bindServoContract(); every other public method in bindServoMore(): the one place to adapt when
  vpServoProjective's public methods change (issue 32).
*/

#include "module.h"

#include <sstream>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectivePathPlanner.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpServoProjectiveReport.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
typedef py::class_<vpServoProjective> TaskClass;

void bindFeature(py::module_ &m)
{
  py::class_<vpFeatureStereoPoint>(
      m, "FeatureStereoPoint", "The stereo point s = (u, v, u', v') as a ViSP visual feature (vpFeatureStereoPoint).")
      .def(py::init<>())
      .def("buildFrom", py::overload_cast<const vpImagePoint &, const vpImagePoint &>(&vpFeatureStereoPoint::buildFrom),
           py::arg("ipLeft"), py::arg("ipRight"), "s from the left (u, v) and right (u', v') pixels.")
      .def("buildFrom", py::overload_cast<double, double, double, double>(&vpFeatureStereoPoint::buildFrom),
           py::arg("u"), py::arg("v"), py::arg("up"), py::arg("vp"))
      .def("buildFrom", py::overload_cast<const Pixels &, const Pixels &>(&vpFeatureStereoPoint::buildFrom),
           py::arg("ipLeft"), py::arg("ipRight"), "s as the mean of several frames' pixels, (N, 2) arrays.")
      .def("getLeft", &vpFeatureStereoPoint::getLeft)
      .def("getRight", &vpFeatureStereoPoint::getRight)
      .def("get_u", &vpFeatureStereoPoint::get_u)
      .def("get_v", &vpFeatureStereoPoint::get_v)
      .def("get_up", &vpFeatureStereoPoint::get_up)
      .def("get_vp", &vpFeatureStereoPoint::get_vp)
      .def(
          "get_s", [](const vpFeatureStereoPoint &s) { return s.get_s(); }, "s = (u, v, u', v'), a (4,) array.")
      .def("setStereoRig", &vpFeatureStereoPoint::setStereoRig, py::arg("rig"), py::keep_alive<1, 2>(),
           "The rig of interaction() (kept by reference).")
      .def(
          "error", [](vpFeatureStereoPoint &s, const vpFeatureStereoPoint &s_star) { return s.error(s_star); },
          py::arg("s_star"), "s - s* (4,).")
      .def(
          "interaction", [](vpFeatureStereoPoint &s) { return s.interaction(); },
          "L_s = ds/dM (4x4) at the point triangulated from s (needs setStereoRig()).");
}

void bindReport(py::module_ &m)
{
  py::class_<vpServoProjectiveReport> report(m, "ServoProjectiveReport",
                                             "What the last computeControlLaw() did (vpServoProjectiveReport).");
  bindEnum<vpServoProjectiveReport::vpServoStatus>(
      report, "ServoStatus",
      {{"SERVO_RUNNING", vpServoProjectiveReport::SERVO_RUNNING},
       {"SERVO_REDUCED", vpServoProjectiveReport::SERVO_REDUCED},
       {"SERVO_STOPPED", vpServoProjectiveReport::SERVO_STOPPED},
       {"SERVO_NO_PLAN", vpServoProjectiveReport::SERVO_NO_PLAN},
       {"SERVO_MODEL_MISMATCH", vpServoProjectiveReport::SERVO_MODEL_MISMATCH},
       {"SERVO_OPEN_LOOP", vpServoProjectiveReport::SERVO_OPEN_LOOP},
       {"SERVO_ARM_NOT_FOLLOWING", vpServoProjectiveReport::SERVO_ARM_NOT_FOLLOWING}});
  bindEnum<vpServoFeatureHealth::vpFeatureState>(report, "FeatureState",
                                                 {{"FEATURE_ACTIVE", vpServoFeatureHealth::FEATURE_ACTIVE},
                                                  {"FEATURE_NOT_TRACKED", vpServoFeatureHealth::FEATURE_NOT_TRACKED},
                                                  {"FEATURE_OUT_OF_IMAGE", vpServoFeatureHealth::FEATURE_OUT_OF_IMAGE},
                                                  {"FEATURE_NOT_FINITE", vpServoFeatureHealth::FEATURE_NOT_FINITE},
                                                  {"FEATURE_OUTLIER", vpServoFeatureHealth::FEATURE_OUTLIER}});
  report.def("getStatus", &vpServoProjectiveReport::getStatus)
      .def("getNumberOfFeatures", &vpServoProjectiveReport::getNumberOfFeatures)
      .def("getFeatureState", &vpServoProjectiveReport::getFeatureState, py::arg("i"))
      .def("getNumberOfActiveFeatures", &vpServoProjectiveReport::getNumberOfActiveFeatures)
      .def("isFollowingPath", &vpServoProjectiveReport::isFollowingPath)
      .def("getOpenLoopCalls", &vpServoProjectiveReport::getOpenLoopCalls)
      .def("getLambda", &vpServoProjectiveReport::getLambda)
      .def("getDamping", &vpServoProjectiveReport::getDamping)
      .def("isSaturated", &vpServoProjectiveReport::isSaturated)
      .def("getJointLimitVelocity", &vpServoProjectiveReport::getJointLimitVelocity)
      .def("getLargeProjectionOperator", &vpServoProjectiveReport::getLargeProjectionOperator)
      .def("getError", &vpServoProjectiveReport::getError)
      .def("getTaskJacobian", &vpServoProjectiveReport::getTaskJacobian)
      .def("getTaskSingularValues", &vpServoProjectiveReport::getTaskSingularValues)
      .def("getConditionNumber", &vpServoProjectiveReport::getConditionNumber)
      .def("getSingularValueRatio", &vpServoProjectiveReport::getSingularValueRatio)
      .def("getErrorScale", &vpServoProjectiveReport::getErrorScale);
}

void bindPlanner(py::module_ &m)
{
  py::class_<vpProjectivePathPlanner>(m, "ProjectivePathPlanner",
                                      "The settings and last plan of a task's path planner (vpProjectivePathPlanner): "
                                      "ServoProjective.getPathPlanner() gives the task's own.")
      .def("setMaxJointStep", &vpProjectivePathPlanner::setMaxJointStep, py::arg("step"))
      .def("getMaxJointStep", &vpProjectivePathPlanner::getMaxJointStep)
      .def("setMaxExcursion", &vpProjectivePathPlanner::setMaxExcursion, py::arg("excursion"))
      .def("getMaxExcursion", &vpProjectivePathPlanner::getMaxExcursion)
      .def("setJointLimitMargin", &vpProjectivePathPlanner::setJointLimitMargin, py::arg("fraction"))
      .def("setPlanarGroups", &vpProjectivePathPlanner::setPlanarGroups, py::arg("groups"))
      .def("getPlanarGroups", &vpProjectivePathPlanner::getPlanarGroups)
      .def("setMinGroupArea", &vpProjectivePathPlanner::setMinGroupArea, py::arg("fraction"))
      .def("setNumberOfStarts", &vpProjectivePathPlanner::setNumberOfStarts, py::arg("starts"))
      .def("setMaxResidual", &vpProjectivePathPlanner::setMaxResidual, py::arg("pixels"))
      .def("getDescription", &vpProjectivePathPlanner::getDescription);
}

//! The names of DESIGN.md section 3 (fixed).
void bindServoContract(TaskClass &task)
{
  task.def(py::init<>())
      .def("setRobot", py::overload_cast<vpProjectiveRobot &>(&vpServoProjective::setRobot), py::arg("robot"),
           py::keep_alive<1, 2>(), "The acquired robot (kept by reference; the task may refine its re-registered rig).")
      .def("setLambda", py::overload_cast<double>(&vpServoProjective::setLambda), py::arg("lambda_"))
      .def("setLambda", py::overload_cast<double, double, double>(&vpServoProjective::setLambda), py::arg("gainAtZero"),
           py::arg("gainAtInfinity"), py::arg("slopeAtZero"), "An adaptive gain.")
      .def("addFeature", &vpServoProjective::addFeature, py::arg("s"), py::arg("s_star"), py::keep_alive<1, 2>(),
           py::keep_alive<1, 3>(), "Adds s and s* (kept by reference, like vpServo: the loop updates s).")
      .def("computeControlLaw", py::overload_cast<const vpColVector &>(&vpServoProjective::computeControlLaw),
           py::arg("q"), ReleaseGil(), "The joint velocities (n,) at the joints q (planning inside, once per target).")
      .def("getError", &vpServoProjective::getError)
      .def("setJointLimits", &vpServoProjective::setJointLimits, py::arg("qmin"), py::arg("qmax"), py::arg("rho") = 0.1,
           py::arg("rho1") = 0.3, py::arg("lambdaTune") = 0.7)
      .def("setImageSize", &vpServoProjective::setImageSize, py::arg("width"), py::arg("height"),
           py::arg("border") = 0.0)
      .def("setPathPlanning", &vpServoProjective::setPathPlanning, py::arg("planning"))
      .def("getPlannedTarget", &vpServoProjective::getPlannedTarget)
      .def("getStatus", &vpServoProjective::getStatus)
      .def("setSettling", &vpServoProjective::setSettling, py::arg("settling"));
}

//! Every other public method (see the file's comment).
void bindServoMore(TaskClass &task)
{
  // The Python names of the settings that moved to the task's parts (getControlLaw(), getFeatureHealth(),
  // getModelMismatch(), getRigRefinement(), getPathPlanner()) stay on ServoProjective.
  typedef vpServoProjective T;
  task.def(
          "setAdaptiveGainInput",
          [](T &t, vpServoControlLaw::vpGainInput i) { t.getControlLaw().setAdaptiveGainInput(i); }, py::arg("input"))
      .def("getAdaptiveGainInput", [](T &t) { return t.getControlLaw().getAdaptiveGainInput(); })
      .def("setErrorUnit", &vpServoProjective::setErrorUnit, py::arg("unit"), py::arg("focalLength") = 0.0)
      .def("getErrorScale", [](T &t) { return t.getControlLaw().getErrorScale(); })
      .def(
          "setDamping", [](T &t, double s0, double mu) { t.getControlLaw().setDamping(s0, mu); },
          py::arg("sigmaThreshold"), py::arg("maxDamping"))
      .def(
          "setMaxJointVelocity", [](T &t, double v) { t.getControlLaw().setMaxJointVelocity(v); }, py::arg("qdotMax"))
      .def("setControlPeriod", &vpServoProjective::setControlPeriod, py::arg("seconds"))
      .def("getControlPeriod", [](T &t) { return t.getControlLaw().getControlPeriod(); })
      .def(
          "setPseudoInverseThreshold", [](T &t, double x) { t.getControlLaw().setPseudoInverseThreshold(x); },
          py::arg("threshold"))
      .def(
          "setRankTolerance", [](T &t, double x) { t.getFeatureHealth().setRankTolerance(x); }, py::arg("tolerance"))
      .def("setFeatureTracked", &vpServoProjective::setFeatureTracked, py::arg("i"), py::arg("tracked"))
      .def(
          "setOutlierThreshold", [](T &t, double px) { t.getFeatureHealth().setOutlierThreshold(px); },
          py::arg("pixels"))
      .def(
          "setModelMismatchThreshold", [](T &t, double px) { t.getModelMismatch().setThreshold(px); },
          py::arg("pixels"))
      .def("getDesiredFeature", &vpServoProjective::getDesiredFeature, py::arg("i"))
      .def(
          "setRigRefinement",
          [](T &t, bool refine, unsigned int period, unsigned int n) {
            t.getRigRefinement().setRefinement(refine, period, n);
          },
          py::arg("refine"), py::arg("period") = 40, py::arg("refinements") = 3)
      .def("clearJointLimits", [](T &t) { t.getControlLaw().getJointLimitAvoidance().clearJointLimits(); })
      .def("clearFeatures", &vpServoProjective::clearFeatures)
      .def("getNumberOfFeatures", [](T &t) { return t.getFeatureHealth().getNumberOfFeatures(); })
      .def("getDimension", [](T &t) { return 4 * t.getFeatureHealth().getNumberOfFeatures(); })
      .def("setJointPositions", &vpServoProjective::setJointPositions, py::arg("q"))
      .def("computeControlLaw", py::overload_cast<>(&vpServoProjective::computeControlLaw), ReleaseGil())
      .def_static("toString", &vpServoProjectiveReport::toString, py::arg("status"))
      .def("getReport", &vpServoProjective::getReport, py::return_value_policy::copy,
           "A copy of the report of the last computeControlLaw().")
      .def(
          "setPathFollowingGain", [](T &t, double g) { t.getPathPlanner().setPathFollowingGain(g); }, py::arg("gain"))
      .def(
          "setMaxOpenLoopTime", [](T &t, double s) { t.getPathPlanner().setMaxOpenLoopTime(s); }, py::arg("seconds"))
      .def("getMaxOpenLoopTime", [](T &t) { return t.getPathPlanner().getMaxOpenLoopTime(); })
      .def("getPathPlanner", py::overload_cast<>(&vpServoProjective::getPathPlanner),
           py::return_value_policy::reference_internal, "The task's planner: change its settings before the loop.")
      .def("__str__", [](const vpServoProjective &t) {
        std::ostringstream os;
        t.print(os);
        return os.str();
      });
}
} // namespace

void bindServo(py::module_ &m)
{
  bindFeature(m);
  bindReport(m);
  bindPlanner(m);
  TaskClass task(m, "ServoProjective",
                 "The non-metric joint-space visual servo of Ruf & Horaud: qdot = -lambda J^+ (s - s*) through the "
                 "projective model of the arm (vpServoProjective).");
  // The task's enumerations: its own, and the report's, reachable from the task as in C++.
  bindEnum<vpServoProjective::vpErrorUnit>(
      task, "ErrorUnit",
      {{"ERROR_PIXELS", vpServoProjective::ERROR_PIXELS}, {"ERROR_NORMALIZED", vpServoProjective::ERROR_NORMALIZED}});
  bindEnum<vpServoControlLaw::vpGainInput>(
      task, "GainInput",
      {{"GAIN_INPUT_ERROR", vpServoControlLaw::GAIN_INPUT_ERROR},
       {"GAIN_INPUT_JOINT_VELOCITY", vpServoControlLaw::GAIN_INPUT_JOINT_VELOCITY}});
  py::object report = m.attr("ServoProjectiveReport");
  for (const char *name : {"ServoStatus", "FeatureState"}) {
    py::object type = report.attr(name);
    task.attr(name) = type;
    for (const auto &value : type.attr("__members__").cast<py::dict>()) {
      task.attr(value.first) = value.second;
    }
  }
  bindServoContract(task);
  bindServoMore(task);
}
} // namespace vpPython
