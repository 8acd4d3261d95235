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
  A robot cell servoed on printed AprilTags by two cameras nobody calibrated, in one main(). On real hardware run
  `visp-projective servo` (docs/robot.dox): the same steps, with safe limits and the arm stopped on every exit path.
  1. The cell: a PUMA-like arm behind vpRobot (joint velocity control, 25 Hz), three 3 cm tags (36h11, ids 0-2) on
     its tool, two cameras rendering them with noise, blur and a lighting that changes during the run.
  2. The acquisition (vpProjectiveAcquisitionProcedure): the tag corners at the zero reference, then each joint moved
     alone by velocity (corners identified by tag id); the stereo rig and the arm's model come from the same images.
  3. s* taught by showing: the arm at the target, 16 frames of the middle tag's 4 corners averaged.
  4. The planned servo from a start 25-40 deg away per joint, detection near the last corners, until the image error
     settles. Shown while it runs (vpStereoServoDisplay; -d: not): both images with the tags, s* (red), the corners
     and their paths (green), a vpPlot of the error and the joints; the first and last pictures go to --output.
  --record DIR writes each stereo frame used and its encoders to a session (visp-projective calibrate, check read it).
  Usage: tutorial-projective-servo-apriltag [-c] [-d] [--blur SIGMA] [--output DIR] [--record DIR] [--help]
  The exit code is 0 if the task converged (image error within 1 px RMS); with a window it waits for a click (-c: not).
*/

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <memory>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorStereoCell.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main([[maybe_unused]] int argc, [[maybe_unused]] char **argv)
{
#if defined(VISP_HAVE_APRILTAG)
  double blur = 0.5;                     // optical blur of the cameras (px)
  std::string output = "apriltag-servo"; // where the figures go
  std::string record;                    // where to record the session (empty: no recording)
  bool opt_display = true, opt_click_allowed = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-d" || arg == "--no-display" || arg == "-c" || arg == "--no-click") {
      (arg == "-d" || arg == "--no-display" ? opt_display : opt_click_allowed) = false;
    } else if (arg == "--blur" && i + 1 < argc) {
      blur = std::atof(argv[++i]);
    } else if ((arg == "--output" || arg == "--record") && i + 1 < argc) {
      (arg == "--output" ? output : record) = argv[++i];
    } else {
      std::cout << "Usage: " << argv[0] << " [-c] [-d] [--blur SIGMA (px)] [--output DIR] [--record DIR]\n";
      return arg == "--help" || arg == "-h" ? EXIT_SUCCESS : EXIT_FAILURE;
    }
  }

  try {
    //! [Cell]
    // The rendered cell: a simulated arm behind vpRobot and two rendered cameras (vpStereoImageSource).
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
    const std::vector<vpProjectiveRobot::vpJointType> types(n, vpProjectiveRobot::REVOLUTE);
    std::unique_ptr<vpProjectiveSessionWriter> writer(record.empty() ? nullptr
                                                                     : new vpProjectiveSessionWriter(record, types));
    vpStereoAprilTagDetector tags(vpDetectorAprilTag::TAG_36h11);
    vpStereoServoDisplay display(cell.getWidth(), cell.getHeight(), opt_display && vpStereoServoDisplay::hasDisplay());
    // A stereo frame, its tags, the encoders; --record writes it (role -1: acquisition, if it shows 5 corners).
    auto see = [&](int role) {
      cell.acquire(Ileft, Iright);
      tags.detect(Ileft, Iright);
      display.display(Ileft, Iright); // the frame and its tags: the caller adds the rest and flushes
      display.displayTags(tags.getIds(), tags.getLeftPoints(), tags.getRightPoints());
      vpColVector q;
      robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
      if (writer && role < 0 && tags.getIds().size() >= 5) {
        writer->addAcquisitionFrame(q, robot.getTime(), Ileft, Iright);
      } else if (writer && role >= 0) {
        writer->addFrame(static_cast<vpProjectiveSession::vpFrameRole>(role), q, robot.getTime(), Ileft, Iright);
      }
      return q;
    };
    //! [Cell]

    //! [Acquisition]
    // The tags' corners, identified by 4 * tag id + corner index, are the acquisition's markers.
    auto corners = [&](std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      see(-1);
      display.flush(); // the acquisition's frame and its tags
      ids = tags.getIds();
      left = tags.getLeftPoints();
      right = tags.getRightPoints();
      return true;
    };
    vpProjectiveAcquisitionProcedure acquisition(corners, cell.getWidth(), cell.getHeight());
    acquisition.setOutput(&std::cout);
    vpProjectiveRobot model(types);
    acquisition.run(robot, model); // moves the arm: keep a hand on the emergency stop of a real one
    std::cout << "Model: residual " << acquisition.getCalibrationResidual() << " px RMS" << std::endl;
    //! [Acquisition]

    //! [Teach]
    // s*: the arm shown the target, the 4 corners of tag 1 (ids 4 to 7) averaged over 16 frames.
    vpColVector qTarget({10, -8, 12, 15, -12, 20}), qStart({-25, 20, -25, 40, 30, -35}); // deg, then rad:
    for (unsigned int i = 0; i < n; ++i) {
      qTarget[i] = vpMath::rad(qTarget[i]);
      qStart[i] = vpMath::rad(qStart[i]);
    }
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qTarget);
    auto find = [&](unsigned int k) { // index of corner k of tag 1 (id 4 + k) in the last detection, -1 if not seen
      const auto it = std::find(tags.getIds().begin(), tags.getIds().end(), static_cast<int>(4 + k));
      return it == tags.getIds().end() ? -1 : static_cast<int>(it - tags.getIds().begin());
    };
    std::vector<std::vector<vpImagePoint>> starLeft(4), starRight(4);
    for (unsigned int frame = 0; frame < 16; ++frame) {
      see(vpProjectiveSession::TARGET);
      display.flush();
      for (unsigned int k = 0; k < 4; ++k) {
        const int j = find(k);
        if (j >= 0) {
          starLeft[k].push_back(tags.getLeftPoints()[static_cast<size_t>(j)]);
          starRight[k].push_back(tags.getRightPoints()[static_cast<size_t>(j)]);
        }
      }
    }
    //! [Teach]

    //! [Task]
    vpFeatureStereoPoint s[4], s_star[4];
    vpServoProjective task;
    task.setRobot(model);
    task.setControlPeriod(robot.getSamplingTime()); // one call per camera frame: qdot is sent as a velocity
    task.setLambda(1.0);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(30.0));
    task.setJointLimits(robot.getJointMin(), robot.getJointMax());
    task.setImageSize(cell.getWidth(), cell.getHeight(), 10.0);
    task.setPathPlanning(true); // rehearse law (47) on the model, plan a path if it would fail
    task.getPathPlanner().setPlanarGroups({{0, 1, 2, 3}}); // one tag's corners: a path keeps it facing the cameras
    task.setSettling(true); // once converged, average rather than chase each frame's noise
    for (unsigned int k = 0; k < 4; ++k) {
      s_star[k].buildFrom(starLeft[k], starRight[k]); // s*: the mean of the frames where corner k was seen
      task.addFeature(s[k], s_star[k]);
      std::cout << "s*[" << k << "] (i, j): left " << s_star[k].getLeft() << ", right " << s_star[k].getRight() << "\n";
    }
    //! [Task]

    //! [Loop]
    robot.setPosition(vpRobot::ARTICULAR_FRAME, qStart);
    robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
    double errorRms = 0.0;
    unsigned int it = 0, lost = 0; // lost: consecutive frames without the servo tag
    for (; it < 300; ++it) {
      const vpColVector q = see(vpProjectiveSession::SERVO); // tags near the last corners, else in the whole images
      if (it == 100) {
        cell.getRenderer().setLighting(0.7, 20.0, 0.3, 0.0); // a cloud from the next frame: darker, a gradient
      }
      vpColVector e; // s - s*: the final target, whatever intermediate features a planned path aims at
      for (unsigned int k = 0; k < 4; ++k) {
        const int j = find(k);
        if (j >= 0) {
          s[k].buildFrom(tags.getLeftPoints()[static_cast<size_t>(j)], tags.getRightPoints()[static_cast<size_t>(j)]);
        }
        task.setFeatureTracked(k, j >= 0); // a corner out of view is set aside for this iteration
        e.stack(s[k].error(s_star[k]));
        display.displayFeature(k, s[k], s_star[k], j >= 0); // s* in red, s and its path in green
      }
      errorRms = std::sqrt(e.sumSquare() / e.size());
      display.displayText("iteration " + std::to_string(it) + ": error " + std::to_string(errorRms) + " px RMS");
      display.flush();
      if (find(0) >= 0 && find(1) >= 0 && find(2) >= 0 && find(3) >= 0) { // the whole servo tag seen
        tags.setPredictedRegions(tags.getIds(), tags.getLeftPoints(), tags.getRightPoints()); // next: search there
      }
      const vpColVector qdot = task.computeControlLaw(q);
      lost = task.getStatus() == vpServoProjective::SERVO_STOPPED ? lost + 1 : 0; // this frame: qdot = 0
      if (lost > 25 || task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH ||
          task.getStatus() == vpServoProjective::SERVO_NO_PLAN) {
        std::cout << "Stopped at call " << it << ": " << vpServoProjectiveReport::toString(task.getStatus()) << "\n";
        break;
      }
      robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
      display.plot(e, q);
      if (it == 0) {
        display.write(output + "/stereo-start.png");
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
    if (writer) {
      writer->close(); // session.json naming every frame (the writer saves at intervals while recording)
    }
    //! [Loop]

    display.write(output + "/stereo-end.png"); // what the window shows (the same picture without a display)
    display.writePlot(output + "/plot.png");   // if the plot window is open
    std::cout << "Figures: " << output << "/stereo-start.png, " << output << "/stereo-end.png\n";

    // The simulator's truth, which a real cell does not have: how far the tool is from where it was shown s*.
    const vpHomogeneousMatrix tMt =
        robot.getArm().get_wMt(qTarget).inverse() * robot.getArm().get_wMt(robot.getArmJoints());
    std::cout << "After " << it << " iterations: image error " << errorRms << " px RMS; the tool is "
              << 1000.0 * tMt.getTranslationVector().frobeniusNorm() << " mm and "
              << vpMath::deg(vpThetaUVector(tMt.getRotationMatrix()).getTheta()) << " deg from its target pose\n";
    if (display.isOpen() && opt_click_allowed) {
      std::cout << "Click in the window to quit" << std::endl;
      display.getClick();
    }
    return errorRms < 1.0 ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
#else
  std::cout << "This tutorial needs ViSP's AprilTag detector (ViSP built with WITH_APRILTAG, the default)" << std::endl;
  return EXIT_SUCCESS;
#endif
}
