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
  \file study-tags.cpp
  \brief The study on rendered AprilTags (--tags): the cell of the world as a user's program sees real hardware.
*/

#include "study-tags.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iostream>
#include <vector>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTime.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorStereoCell.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
namespace
{
const int kServoTag = 1; // the middle tag of vpSimulatorStereoCell::addToolTags(): its 4 corners are the features

//! The servo tag's 4 corners in the detector's last result; false unless all 4 were found.
bool servoCorners(const vpStereoAprilTagDetector &tags, std::vector<vpImagePoint> &left,
                  std::vector<vpImagePoint> &right)
{
  left.assign(4, vpImagePoint());
  right.assign(4, vpImagePoint());
  unsigned int found = 0;
  for (size_t j = 0; j < tags.getIds().size(); ++j) {
    const int corner = tags.getIds()[j] - 4 * kServoTag;
    if (corner >= 0 && corner < 4) {
      left[corner] = tags.getLeftPoints()[j];
      right[corner] = tags.getRightPoints()[j];
      ++found;
    }
  }
  return found == 4;
}

//! Whether the servo tag's true corners are at least \e margin px inside both images at the robot's joints.
bool servoTagInView(vpSimulatorStereoCell &cell, double margin)
{
  std::vector<int> ids;
  std::vector<vpImagePoint> l, r;
  cell.getTrueCorners(ids, l, r);
  unsigned int inside = 0;
  for (size_t j = 0; j < ids.size(); ++j) {
    if (ids[j] / 4 != kServoTag) {
      continue;
    }
    for (const vpImagePoint &p : {l[j], r[j]}) {
      inside += p.get_u() >= margin && p.get_u() <= cell.getWidth() - 1 - margin && p.get_v() >= margin &&
                p.get_v() <= cell.getHeight() - 1 - margin;
    }
  }
  return inside == 8;
}
//! Whether the detector finds the servo tag's 4 corners in the images of the cell now.
bool servoTagDetected(vpSimulatorStereoCell &cell, vpStereoAprilTagDetector &tags, vpImage<unsigned char> &Il,
                      vpImage<unsigned char> &Ir)
{
  cell.acquire(Il, Ir);
  tags.detect(Il, Ir);
  std::vector<vpImagePoint> l, r;
  return servoCorners(tags, l, r);
}
} // namespace

double runTagStudy(const World &world, const TagStudySettings &settings, std::ostream &os)
{
#if !defined(VISP_HAVE_APRILTAG)
  throw vpException(vpException::notImplementedError, "--tags needs ViSP's AprilTag detector (WITH_APRILTAG)");
#else
  const double start = vpTime::measureTimeMs();
  vpSimulatorStereoCell cell(world.arm, world.rig, vpColVector(), settings.seed);
  cell.addToolTags(settings.tagSize);
  cell.getRenderer().setNoise(settings.noise);
  cell.getRenderer().setBlur(settings.blur);
  vpSimulatorRobotArm &robot = cell.getRobot();
  robot.setConstantSamplingTimeMode(true);
  robot.setSamplingTime(settings.period);
  const unsigned int n = robot.getNumberOfJoints();
  vpImage<unsigned char> Il, Ir;

  // The acquisition, as the tutorial runs it: tag corners identified by id.
  vpStereoAprilTagDetector tags;
  vpProjectiveAcquisitionProcedure acquisition(
      [&](std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        cell.acquire(Il, Ir);
        tags.detect(Il, Ir);
        ids = tags.getIds();
        left = tags.getLeftPoints();
        right = tags.getRightPoints();
        return true;
      },
      cell.getWidth(), cell.getHeight());
  vpColVector amounts(n);
  for (unsigned int i = 0; i < n; ++i) {
    amounts[i] = world.trials[i];
  }
  acquisition.setMaxAmounts(amounts);
  acquisition.setOutput(nullptr); // the study prints its tables, not each case's progress
  std::vector<vpProjectiveRobot::vpJointType> types;
  for (unsigned int i = 0; i < n; ++i) {
    types.push_back(world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? vpProjectiveRobot::PRISMATIC
                                                                              : vpProjectiveRobot::REVOLUTE);
  }
  vpProjectiveRobot model(types);
  acquisition.run(robot, model);
  os << "Tag study, world " << world.name << ": " << settings.tasks << " tasks within +-" << world.boxDeg
     << " deg, tag corners at " << settings.noise << " grey levels of noise, blur " << settings.blur << " px"
     << (settings.lighting ? ", a lighting change at call 50" : "") << "; model residual "
     << acquisition.getCalibrationResidual() << " px RMS\n";

  std::ofstream csv((settings.output + "/tag-study-" + world.name + ".csv").c_str());
  csv << "seed,success,calls,final_image_rms_px,tool_position_error_mm,tool_rotation_error_deg,status\n";
  unsigned int successes = 0, drawn = 0;
  std::vector<double> calls, positionErrors;
  for (unsigned int t = 0; drawn < settings.tasks && t < 100 * settings.tasks; ++t) {
    // A task: start and target uniform in the box, the servo tag 20 px inside both images at both.
    vpUniRand rng(settings.seed + t);
    vpColVector qStart(n), qTarget(n);
    for (unsigned int i = 0; i < n; ++i) {
      double lower, upper;
      world.box(i, lower, upper);
      const double unit = world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? 1.0 : M_PI / 180.0;
      qStart[i] = rng.uniform(lower, upper) * unit;
      qTarget[i] = rng.uniform(lower, upper) * unit;
    }
    // A task a user could give: the servo tag detected at both ends (a tag seen too obliquely or too small is not).
    tags.clearPredictedRegions();
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qTarget);
    if (!servoTagInView(cell, 20.0) || !servoTagDetected(cell, tags, Il, Ir)) {
      continue;
    }
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qStart);
    if (!servoTagInView(cell, 20.0) || !servoTagDetected(cell, tags, Il, Ir)) {
      continue;
    }
    ++drawn;
    // Where the loop's first detection looks: the corners found at the start.
    const std::vector<int> startIds = tags.getIds();
    const std::vector<vpImagePoint> startLeft = tags.getLeftPoints(), startRight = tags.getRightPoints();

    // s* taught by showing: 16 frames at the target, averaged.
    cell.getRenderer().setLighting(1.0, 0.0);
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qTarget);
    std::vector<std::vector<vpImagePoint>> starLeft(4), starRight(4);
    tags.clearPredictedRegions();
    for (unsigned int f = 0; f < 16; ++f) {
      cell.acquire(Il, Ir);
      tags.detect(Il, Ir);
      std::vector<vpImagePoint> l, r;
      if (servoCorners(tags, l, r)) {
        for (unsigned int k = 0; k < 4; ++k) {
          starLeft[k].push_back(l[k]);
          starRight[k].push_back(r[k]);
        }
      }
    }
    const vpHomogeneousMatrix wMtTarget = world.arm.get_wMt(robot.getArmJoints());
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qStart);
    robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);

    vpFeatureStereoPoint s[4], s_star[4];
    vpServoProjective task;
    task.setRobot(model);
    task.setControlPeriod(settings.period);
    task.setLambda(1.0);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(30.0));
    task.getControlLaw().setDamping(30.0, 30.0);
    task.setJointLimits(robot.getJointMin(), robot.getJointMax());
    task.setImageSize(cell.getWidth(), cell.getHeight(), 10.0);
    task.setPathPlanning(true);
    task.setSettling(true);
    task.getPathPlanner().setPlanarGroups({{0, 1, 2, 3}}); // the servo tag's corners, in order around it
    bool taught = !starLeft[0].empty();
    for (unsigned int k = 0; taught && k < 4; ++k) {
      s_star[k].buildFrom(starLeft[k], starRight[k]);
      task.addFeature(s[k], s_star[k]);
    }
    double errorRms = -1.0;
    unsigned int call = 0, quiet = 0, stopped = 0;
    vpServoProjective::vpServoStatus status = vpServoProjective::SERVO_RUNNING;
    tags.setPredictedRegions(startIds, startLeft, startRight);
    for (; taught && call < settings.maxCalls; ++call) {
      if (settings.lighting && call == 50) {
        cell.getRenderer().setLighting(0.7, 20.0, 0.3, 0.0);
      }
      cell.acquire(Il, Ir);
      tags.detect(Il, Ir);
      std::vector<vpImagePoint> l, r;
      const bool seen = servoCorners(tags, l, r);
      if (seen) { // else the last regions again: a tag not found there is searched for in the whole images
        tags.setPredictedRegions(tags.getIds(), tags.getLeftPoints(), tags.getRightPoints());
      }
      double sum = 0.0;
      for (unsigned int k = 0; k < 4; ++k) {
        if (seen) {
          s[k].buildFrom(l[k], r[k]);
        }
        task.setFeatureTracked(k, seen);
        sum += s[k].error(s_star[k]).sumSquare();
      }
      errorRms = std::sqrt(sum / 16.0);
      vpColVector q;
      robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
      const vpColVector qdot = task.computeControlLaw(q);
      status = task.getStatus();
      // The tag missing from frames: the plan followed on the model for up to 2 s (SERVO_OPEN_LOOP), then the task
      // stops (qdot = 0); a second stopped without it ends the task.
      stopped = status == vpServoProjective::SERVO_STOPPED ? stopped + 1 : 0;
      if (stopped > 25 || status == vpServoProjective::SERVO_NO_PLAN ||
          status == vpServoProjective::SERVO_MODEL_MISMATCH) {
        break;
      }
      robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
      quiet = seen && errorRms < settings.successPx && !task.getReport().isFollowingPath() ? quiet + 1 : 0;
      if (quiet >= 25) {
        break; // converged, and settled for a second
      }
    }
    robot.setRobotState(vpRobot::STATE_STOP);
    const vpHomogeneousMatrix tMt = wMtTarget.inverse() * world.arm.get_wMt(robot.getArmJoints());
    const double positionMm = 1000.0 * tMt.getTranslationVector().frobeniusNorm();
    const double rotationDeg = vpMath::deg(vpThetaUVector(tMt.getRotationMatrix()).getTheta());
    const bool success = taught && errorRms >= 0.0 && errorRms < settings.successPx;
    successes += success;
    calls.push_back(call);
    positionErrors.push_back(positionMm);
    csv << settings.seed + t << "," << success << "," << call << "," << errorRms << "," << positionMm << ","
        << rotationDeg << "," << vpServoProjectiveReport::toString(status) << "\n";
  }
  const double rate = drawn > 0 ? 100.0 * successes / drawn : 0.0;
  auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  os << "  " << successes << " of " << drawn << " tasks reached their target (" << rate
     << " %: final image error below " << settings.successPx << " px RMS); median " << median(calls) << " calls of "
     << settings.period * 1000.0 << " ms, median tool position error " << median(positionErrors) << " mm; "
     << (vpTime::measureTimeMs() - start) / 1000.0 << " s\n";
  return rate;
#endif
}
} // namespace study
