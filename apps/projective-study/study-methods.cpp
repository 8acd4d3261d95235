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
  \file study-methods.cpp
  \brief Running every method of the study.
*/

#include "study-methods.h"

#include <algorithm>
#include <cmath>
#include <functional>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpTime.h>

#include "study-broyden.h"
#include "study-calibration.h"
#include "study-ibvs.h"
#include "study-projective.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
void writeRun(std::ofstream &csv, const World &world, const std::string &scenario, const std::string &method,
              double sigma, double factor, const Task &task, const RunResult &r)
{
  std::string message = r.message;
  std::replace(message.begin(), message.end(), '"', '\'');
  std::replace(message.begin(), message.end(), '\n', ' ');
  csv << task.seed << "," << scenario << "," << method << "," << sigma << "," << factor << "," << r.cause() << ","
      << r.convergedAt << "," << r.lastIteration << "," << r.finalImageRms << "," << r.errorOverFloor << ","
      << r.straightness << "," << r.moves << "," << r.modelErrorTarget << "," << r.outliersSeen << ","
      << r.outliersRejected << "," << r.cleanSeen << "," << r.cleanRejected << "," << r.jointPathRatio << ","
      << r.excursionDeg << "," << r.noPlan << "," << r.otherBranch << ",\"" << message << "\"," << world.name << ","
      << world.rigName << "\n";
}

void runMethods(const World &world, const Task &task, double sigma, const vpProjectiveRobot *robot,
                const std::string &acquisitionMessage, Scenario scenario, const std::string &scenarioName,
                const std::vector<double> &factors, bool robust, Results &results, std::ofstream &csv)
{
  std::vector<vpImagePoint> leftStar, rightStar;
  measuredTarget(task, sigma, leftStar, rightStar);

  // The projective servo on the acquired model, set up by \e configure; after the run, \e finish reads the servo.
  const auto runProjective = [&](const std::string &method, const std::function<void(ProjectiveServo &)> &configure,
                                 const std::function<void(const ProjectiveServo &, RunResult &)> &finish) {
    RunResult r;
    if (robot == nullptr) {
      r.acquisitionFailed = true;
      r.message = acquisitionMessage;
    } else {
      ProjectiveServo servo(*robot, leftStar, rightStar, world.control);
      configure(servo);
      r = runServo(world, task, sigma, servo, scenario);
      finish(servo, r);
      r.mismatchIterations = servo.getMismatchIterations();
      r.modelErrorTarget = modelPredictionError(world, *robot, task.qTarget);
    }
    results.cell(scenarioName, method, sigma).add(r, task.seed);
    writeRun(csv, world, scenarioName, method, sigma, -1, task, r);
  };

  const double t0 = vpTime::measureTimeMs();
  for (int variant = 0; variant < (robust ? 2 : 1); ++variant) {
    runProjective(
        variant == 0 ? "projective" : "projective (robust)",
        [&](ProjectiveServo &servo) {
          if (variant == 1) {
            servo.setRobust(world.rig.getWidth(), world.rig.getHeight(), world.outlierThresholdPx,
                            world.arm.getJointMin(), world.arm.getJointMax());
          }
        },
        [](const ProjectiveServo &servo, RunResult &r) { r.stoppedIterations = servo.getStoppedIterations(); });
  }
  const double tp = vpTime::measureTimeMs();
  results.timeMs["projective servo"] += tp - t0;

  if (scenario == NOMINAL) {
    // Global servoing: the same model, planned (its tasks are not filtered to the start's branch with --any-branch).
    runProjective(
        "planned",
        [&](ProjectiveServo &servo) {
          servo.setPlanned(world.rig.getWidth(), world.rig.getHeight(), world.planBorderPx,
                           vpMath::rad(world.planStepDeg), world.arm.getJointMin(), world.arm.getJointMax(),
                           world.rehearsal);
        },
        [&](const ProjectiveServo &servo, RunResult &r) {
          r.noPlan = servo.getNoPlan();
          if (servo.getPlannedTarget().size() == world.arm.getNumberOfJoints()) {
            r.otherBranch = otherBranch(world, servo.getPlannedTarget(), task.qTarget) ? 1 : 0;
          }
        });
  }
  const double t1 = vpTime::measureTimeMs();
  results.timeMs["planned servo"] += t1 - tp;

  for (double factor : factors) {
    const BelievedCalibration believed = believedCalibration(world.rig, world.arm, task.calibrationError, factor);
    StereoIbvs ibvs(believed, world.tracked, leftStar, rightStar, world.control);
    const RunResult r = runServo(world, task, sigma, ibvs, scenario);
    results.cell(scenarioName, "IBVS", sigma, factor).add(r, task.seed);
    writeRun(csv, world, scenarioName, "IBVS", sigma, factor, task, r);
  }
  const double t2 = vpTime::measureTimeMs();
  results.timeMs["IBVS"] += t2 - t1;

  BroydenServo broyden(world.arm.getNumberOfJoints(), world.exploration, sigma, leftStar, rightStar, world.control);
  const RunResult r = runServo(world, task, sigma, broyden, scenario);
  results.cell(scenarioName, "Broyden", sigma).add(r, task.seed);
  writeRun(csv, world, scenarioName, "Broyden", sigma, -1, task, r);
  results.timeMs["Broyden"] += vpTime::measureTimeMs() - t2;
}

std::unique_ptr<vpProjectiveRobot> acquireForTask(const World &world, const Task &task, double sigma,
                                                  unsigned int sigmaIndex, std::string &message, Results &results)
{
  const double t0 = vpTime::measureTimeMs();
  vpGaussRand noise(1.0, 0.0, streamSeed(task.seed, ACQUISITION_STREAM + sigmaIndex + (task.singularStart ? 100 : 0)));
  std::unique_ptr<vpProjectiveRobot> robot;
  try {
    robot.reset(new vpProjectiveRobot(acquire(world, sigma, noise)));
  } catch (const vpException &e) {
    message = e.getStringMessage();
  }
  results.timeMs["acquisition"] += vpTime::measureTimeMs() - t0;
  ++results.acquisitions;
  return robot;
}

double checkIbvsJacobian(const World &world, const Task &task)
{
  const BelievedCalibration exact = believedCalibration(world.rig, world.arm, task.calibrationError, 0.0);
  StereoIbvs ibvs(exact, world.tracked, task.leftTarget, task.rightTarget, world.control);
  std::vector<vpImagePoint> left, right;
  trueImages(world, task.qStart, left, right);
  ibvs.velocity(task.qStart, left, right, std::vector<bool>(world.nbPoints(), true));
  const vpMatrix &J = ibvs.getTaskJacobian();
  const vpMatrix truth = app::imageJacobian(trueImagesAt(world), task.qStart);
  double largest = 0.0, difference = 0.0;
  for (unsigned int i = 0; i < truth.getCols(); ++i) {
    for (unsigned int r = 0; r < truth.getRows(); ++r) {
      largest = std::max(largest, std::abs(truth[r][i]));
      difference = std::max(difference, std::abs(truth[r][i] - J[r][i]));
    }
  }
  return difference / largest;
}
} // namespace study
