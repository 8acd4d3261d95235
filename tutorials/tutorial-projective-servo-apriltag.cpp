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

//! \example tutorial-projective-servo-apriltag.cpp
/*!
  A robot cell servoed on printed AprilTags by two cameras nobody calibrated, in one main() to copy into a real
  cell: replace the rendered cell (vpSimulatorStereoCell) by your vpRobot and your two grabbers, and keep the rest.

  1. The cell: a PUMA-like arm behind vpRobot (joint velocity control, 25 Hz), three 3 cm tags (36h11, ids 0-2) on
     its tool, two cameras rendering them with noise, blur and a lighting that changes during the run.
  2. The acquisition (vpProjectiveAcquisitionProcedure): the tag corners at the zero reference, then each joint moved
     alone by velocity; corners are identified by tag id, so a corner lost in some frames does no harm. The stereo
     rig and the arm's projective model come from the same images.
  3. s* taught by showing: the arm at the target, 16 frames of the middle tag's 4 corners averaged.
  4. The planned servo from a start 25-40 deg away per joint, detection restricted to the regions around the last
     corners, until the image error settles; the final images are written with the corners' paths.

  Usage: tutorial-projective-servo-apriltag [--blur SIGMA] [--output DIR] [--help]
  The exit code is 0 if the task converged (image error within 1 px RMS).
*/

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/io/vpImageIo.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorStereoCell.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main(int argc, char **argv)
{
#if defined(VISP_HAVE_APRILTAG)
  double blur = 0.5;                     // optical blur of the cameras (px)
  std::string output = "apriltag-servo"; // where the figures go
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--blur" && i + 1 < argc) {
      blur = std::atof(argv[++i]);
    } else if (arg == "--output" && i + 1 < argc) {
      output = argv[++i];
    } else {
      std::cout << "Usage: " << argv[0] << " [--blur SIGMA (px, default 0.5)] [--output DIR] [--help]\n";
      return arg == "--help" || arg == "-h" ? EXIT_SUCCESS : EXIT_FAILURE;
    }
  }

  try {
    //! [Cell]
    // The rendered cell: replace it by your robot and two grabbers (vpStereoImageSource).
    vpSimulatorStereoCell cell(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()),
                               vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0));
    cell.addToolTags(0.03); // tags 0, 1, 2 on three faces of a holder on the tool
    cell.getRenderer().setNoise(1.0);
    cell.getRenderer().setBlur(blur);
    vpSimulatorRobotArm &robot = cell.getRobot();
    robot.setConstantSamplingTimeMode(true); // each setVelocity() moves the arm for one period
    robot.setSamplingTime(0.04);             // a 25 Hz camera
    robot.setMaxRotationVelocity(vpMath::rad(30.0));
    const unsigned int n = robot.getNumberOfJoints();
    vpImage<unsigned char> Ileft(cell.getHeight(), cell.getWidth()), Iright(cell.getHeight(), cell.getWidth());
    //! [Cell]

    //! [Acquisition]
    // The tags' corners, identified by 4 * tag id + corner index, are the acquisition's markers.
    vpStereoAprilTagDetector tags(vpDetectorAprilTag::TAG_36h11);
    auto corners = [&](std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      cell.acquire(Ileft, Iright);
      tags.detect(Ileft, Iright);
      ids = tags.getIds();
      left = tags.getLeftPoints();
      right = tags.getRightPoints();
      return true;
    };
    vpProjectiveAcquisitionProcedure acquisition(corners, cell.getWidth(), cell.getHeight());
    acquisition.setOutput(&std::cout);
    vpProjectiveRobot model(std::vector<vpProjectiveRobot::vpJointType>(n, vpProjectiveRobot::REVOLUTE));
    acquisition.run(robot, model); // moves the arm: keep a hand on the emergency stop of a real one
    std::cout << "Model: residual " << acquisition.getCalibrationResidual() << " px RMS" << std::endl;
    //! [Acquisition]

    //! [Teach]
    // s*: the arm shown the target, the 4 corners of tag 1 (ids 4 to 7) averaged over 16 frames.
    const double targetDeg[6] = {10, -8, 12, 15, -12, 20}, startDeg[6] = {-25, 20, -25, 40, 30, -35};
    vpColVector qTarget(n), qStart(n);
    for (unsigned int i = 0; i < n; ++i) {
      qTarget[i] = vpMath::rad(targetDeg[i]);
      qStart[i] = vpMath::rad(startDeg[i]);
    }
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qTarget);
    const std::vector<int> servoIds = {4, 5, 6, 7};
    std::vector<std::vector<vpImagePoint>> starLeft(4), starRight(4);
    for (unsigned int frame = 0; frame < 16; ++frame) {
      cell.acquire(Ileft, Iright);
      tags.detect(Ileft, Iright);
      for (unsigned int k = 0; k < 4; ++k) {
        for (size_t j = 0; j < tags.getIds().size(); ++j) {
          if (tags.getIds()[j] == servoIds[k]) {
            starLeft[k].push_back(tags.getLeftPoints()[j]);
            starRight[k].push_back(tags.getRightPoints()[j]);
          }
        }
      }
    }
    vpFeatureStereoPoint s[4], s_star[4];
    for (unsigned int k = 0; k < 4; ++k) {
      s_star[k].buildFrom(starLeft[k], starRight[k]); // the mean of the frames where corner k was seen
    }
    //! [Teach]

    //! [Task]
    vpServoProjective task;
    task.setRobot(model);
    task.setControlPeriod(robot.getSamplingTime()); // one call per camera frame: qdot is sent as a velocity
    task.setLambda(1.0);
    task.setMaxJointVelocity(vpMath::rad(30.0));
    task.setJointLimits(robot.getJointMin(), robot.getJointMax());
    task.setImageSize(cell.getWidth(), cell.getHeight(), 10.0);
    task.setPathPlanning(true); // rehearse law (47) on the model, plan a path if it would fail
    task.setSettling(true);     // once converged, average rather than chase each frame's noise
    for (unsigned int k = 0; k < 4; ++k) {
      task.addFeature(s[k], s_star[k]);
    }
    //! [Task]

    //! [Loop]
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qStart);
    robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
    std::vector<std::vector<vpImagePoint>> path(4);
    vpImage<unsigned char> Istart;
    double errorRms = 0.0;
    unsigned int it = 0, lost = 0; // lost: consecutive frames without the servo tag
    for (; it < 300; ++it) {
      cell.acquire(Ileft, Iright);
      if (it == 100) {
        cell.getRenderer().setLighting(0.7, 20.0, 0.3, 0.0); // a cloud: darker, less contrast, a gradient
      }
      tags.detect(Ileft, Iright); // near the last corners; a tag not found there is searched for in the whole images
      unsigned int seenCorners = 0;
      for (unsigned int k = 0; k < 4; ++k) {
        bool seen = false;
        for (size_t j = 0; j < tags.getIds().size(); ++j) {
          if (tags.getIds()[j] == servoIds[k]) {
            s[k].buildFrom(tags.getLeftPoints()[j], tags.getRightPoints()[j]);
            path[k].push_back(tags.getLeftPoints()[j]);
            seen = true;
          }
        }
        task.setFeatureTracked(k, seen); // a corner out of view is set aside for this iteration
        seenCorners += seen ? 1 : 0;
      }
      if (seenCorners == 4) {
        tags.setPredictedRegions(tags.getIds(), tags.getLeftPoints(), tags.getRightPoints()); // next: search there
      }
      if (it == 0) {
        Istart = Ileft;
      }
      vpColVector q;
      robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
      const vpColVector qdot = task.computeControlLaw(q);
      lost = task.getStatus() == vpServoProjective::SERVO_STOPPED ? lost + 1 : 0; // this frame: qdot = 0
      if (lost > 25 || task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH ||
          task.getStatus() == vpServoProjective::SERVO_NO_PLAN) {
        std::cout << "Stopped at iteration " << it << ": " << vpServoProjective::toString(task.getStatus()) << "\n";
        break;
      }
      robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
      vpColVector e; // s - s*: the final target, whatever intermediate features a planned path aims at
      for (unsigned int k = 0; k < 4; ++k) {
        e.stack(s[k].error(s_star[k]));
      }
      errorRms = std::sqrt(e.sumSquare() / e.size());
      if (it == 0) {
        std::cout << "Plan: " << task.getPathPlanner().getDescription() << "\n";
      }
      if (it % 20 == 0) {
        std::cout << "iteration " << it << ": image error " << errorRms << " px RMS, " << tags.getIds().size()
                  << " corners seen\n";
      }
      if (it > 20 && errorRms < 0.3 && qdot.frobeniusNorm() < vpMath::rad(0.05)) {
        break; // settled
      }
    }
    robot.setRobotState(vpRobot::STATE_STOP);
    //! [Loop]

    //! [Figures]
    // The left image at the start and at the end, the corners' paths in green and s* in red.
    vpIoTools::makeDirectory(output);
    vpImage<vpRGBa> start, end;
    vpImageConvert::convert(Istart, start);
    vpImageConvert::convert(Ileft, end);
    for (unsigned int k = 0; k < 4; ++k) {
      for (size_t j = 1; j < path[k].size(); ++j) {
        vpImageDraw::drawLine(start, path[k][j - 1], path[k][j], vpColor::green, 1);
        vpImageDraw::drawLine(end, path[k][j - 1], path[k][j], vpColor::green, 1);
      }
      vpImageDraw::drawCross(start, vpImagePoint(s_star[k].get_v(), s_star[k].get_u()), 9, vpColor::red, 1);
      vpImageDraw::drawCross(end, vpImagePoint(s_star[k].get_v(), s_star[k].get_u()), 9, vpColor::red, 1);
    }
    vpImageIo::write(start, output + "/left-start.png");
    vpImageIo::write(end, output + "/left-end.png");
    std::cout << "Figures: " << output << "/left-start.png, " << output << "/left-end.png\n";
    //! [Figures]

    // The simulator's truth, which a real cell does not have: how far the tool is from where it was shown s*.
    const vpHomogeneousMatrix tMt =
        robot.getArm().get_wMt(qTarget).inverse() * robot.getArm().get_wMt(robot.getArmJoints());
    std::cout << "After " << it << " iterations: image error " << errorRms << " px RMS; the tool is "
              << 1000.0 * tMt.getTranslationVector().frobeniusNorm() << " mm and "
              << vpMath::deg(vpThetaUVector(tMt.getRotationMatrix()).getTheta()) << " deg from its pose at the target"
              << std::endl;
    return errorRms < 1.0 ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
#else
  (void)argc;
  (void)argv;
  std::cout << "This tutorial needs ViSP's AprilTag detector (ViSP built with WITH_APRILTAG, the default)" << std::endl;
  return EXIT_SUCCESS;
#endif
}
