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

//! \example tutorial-projective-port-viper850-4pts.cpp
/*!
  ViSP's example servoSimuViper850FourPoints2DCamVelocity.cpp (ViSP 3.5: a simulated Viper850 servoed by vpServo on
  the 4 corners of a plate, eye-in-hand) ported to vpServoProjective, as explained line by line in
  \ref page_porting. The camera of the simulated arm becomes the left camera of a stereo pair on the hand, whose
  calibration the plugin never sees; the plate gets 4 more markers off its plane for the acquisition of the arm's
  projective model (vpProjectiveAcquisitionProcedure with its defaults); then the example's 500 iterations of the
  control law.

  Usage: tutorial-projective-port-viper850-4pts [-c] [-d] [-n ITERATIONS] [-t PIXELS] [-h]
  -c: no mouse click; -d: no display (as in the original); -n: iterations of the servo loop (default 500, the
  original's); -t: the exit code is 0 only if the final image error is below PIXELS RMS (default 1.1).
  Added to the original's windows: both cameras' features (white images: the right camera exists only here) with s*
  in red, s and its path in green, and a vpPlot of the error and the joints (vpStereoServoDisplay).
*/

#include <cmath>
#include <cstdlib>
#include <iostream>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpTime.h>
#include <visp3/gui/vpDisplayX.h>
#include <visp3/robot/vpSimulatorViper850.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main(int argc, char **argv)
{
#if defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_PTHREAD)
  bool opt_click_allowed = true, opt_display = true;
  unsigned int opt_iterations = 500;
  double opt_threshold = 1.1;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "-c") {
      opt_click_allowed = false;
    } else if (arg == "-d") {
      opt_display = false;
    } else if (arg == "-n" && i + 1 < argc) {
      opt_iterations = static_cast<unsigned int>(std::atoi(argv[++i]));
    } else if (arg == "-t" && i + 1 < argc) {
      opt_threshold = std::atof(argv[++i]);
    } else {
      std::cout << "Usage: " << argv[0] << " [-c] [-d] [-n ITERATIONS] [-t PIXELS] [-h]" << std::endl;
      return arg == "-h" ? EXIT_SUCCESS : EXIT_FAILURE;
    }
  }
#if !defined(VISP_HAVE_X11)
  opt_display = false;
#endif
  if (std::getenv("DISPLAY") == nullptr || std::string(std::getenv("DISPLAY")).empty()) {
    opt_display = false; // headless (ctest)
  }

  try {
    //! [Display]
    vpImage<unsigned char> Iint(480, 640, 255);
#if defined(VISP_HAVE_X11)
    vpDisplayX displayInt;
    if (opt_display) {
      displayInt.init(Iint, 700, 0, "Internal view (left camera)");
    }
#endif
    vpStereoServoDisplay stereo(Iint.getWidth(), Iint.getHeight(), opt_display, 0, 520, "Both cameras' features");
    //! [Display]

    //! [Scene]
    // The original's initial and desired poses of the camera (now the left camera) and its 4 coplanar points.
    vpHomogeneousMatrix cMo(-0.05, -0.05, 0.7, vpMath::rad(10), vpMath::rad(10), vpMath::rad(-30));
    vpHomogeneousMatrix cdMo(0.0, 0.0, 0.8, vpMath::rad(0), vpMath::rad(0), vpMath::rad(0));
    std::vector<vpPoint> point(4);
    point[0].setWorldCoordinates(-0.045, -0.045, 0);
    point[3].setWorldCoordinates(-0.045, 0.045, 0);
    point[2].setWorldCoordinates(0.045, 0.045, 0);
    point[1].setWorldCoordinates(0.045, -0.045, 0);
    // Added: the acquisition needs >= 5 markers, no 4 of them coplanar: 4 posts 5 to 7 cm high on the plate, towards
    // the camera (each of the 8 markers is 5.5 mm or more from the plane through any 3 others, but the plate's 4).
    std::vector<vpPoint> markers = point;
    markers.push_back(vpPoint(0.034, -0.033, -0.055));
    markers.push_back(vpPoint(0.015, 0.011, -0.052));
    markers.push_back(vpPoint(-0.020, 0.034, -0.047));
    markers.push_back(vpPoint(-0.019, -0.014, -0.067));
    // Added: the right camera, 10 cm to the right of the left one on the hand, verging 75 cm ahead.
    const vpHomogeneousMatrix cLeftMcRight(vpTranslationVector(0.10, 0.0, 0.0),
                                           vpThetaUVector(0.0, -std::atan2(0.10, 0.75), 0.0));
    const vpHomogeneousMatrix cRightMcLeft = cLeftMcRight.inverse();
    //! [Scene]

    //! [Robot]
    vpSimulatorViper850 robot(opt_display);
    robot.init(vpViper850::TOOL_PTGREY_FLEA2_CAMERA, vpCameraParameters::perspectiveProjWithoutDistortion);
    robot.initScene(vpWireFrameSimulator::PLATE, vpWireFrameSimulator::D_STANDARD);
    robot.initialiseObjectRelativeToCamera(cMo);
    robot.setDesiredCameraPosition(cdMo);
    vpCameraParameters cam;
    robot.getCameraParameters(cam, Iint); // both cameras of the simulated pair: the plugin never reads it
    //! [Robot]

    //! [Acquisition]
    // The tracker of a real rig: here the markers projected in both cameras where the hand is now.
    auto images = [&](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      const vpHomogeneousMatrix cLeftMo = robot.get_cMo();
      left.resize(markers.size());
      right.resize(markers.size());
      vpFeatureStereoPoint m;
      for (size_t k = 0; k < markers.size(); ++k) {
        m.buildFrom(markers[k], cam, cLeftMo, cam, cRightMcLeft * cLeftMo);
        left[k] = m.getLeft();
        right[k] = m.getRight();
      }
      return true;
    };
    vpProjectiveAcquisitionProcedure procedure(images, Iint.getWidth(), Iint.getHeight());
    procedure.setOutput(&std::cout);
    vpProjectiveRobot model(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
    model.setRigMounting(vpProjectiveRobot::EYE_IN_HAND); // the rig rides on the hand, the markers are static
    const double t0 = vpTime::measureTimeMs();
    procedure.run(robot, model); // each joint alone, both ways; the robot ends where it started
    std::cout << "Acquisition: " << (vpTime::measureTimeMs() - t0) / 1000.0 << " s, model residual "
              << procedure.getCalibrationResidual() << " px" << std::endl;
    robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
    //! [Acquisition]

    //! [Features]
    std::vector<vpFeatureStereoPoint> p(4), pd(4);
    for (unsigned int i = 0; i < 4; i++) {
      p[i].buildFrom(point[i], cam, cMo, cam, cRightMcLeft * cMo);    // s at the initial pose
      pd[i].buildFrom(point[i], cam, cdMo, cam, cRightMcLeft * cdMo); // s* at the desired pose
    }
    //! [Features]

    //! [Task]
    vpServoProjective task;
    task.setRobot(model);
    task.setErrorUnit(vpServoProjective::ERROR_NORMALIZED); // |e| as vpServo's; f from the model's self-calibration
    for (unsigned int i = 0; i < 4; i++) {
      task.addFeature(p[i], pd[i]);
    }
    task.setLambda(0.8); // a vpAdaptiveGain tuned on vpServo would need setAdaptiveGainInput(GAIN_INPUT_JOINT_VELOCITY)
    std::cout << "Focal length from the model: " << task.getControlLaw().getErrorScale()
              << " px (simulated cameras: " << cam.get_px() << ")" << std::endl;
    //! [Task]

    if (opt_display) {
      vpDisplay::display(Iint);
      robot.getInternalView(Iint);
      vpDisplay::flush(Iint);
    }
    task.print();

    //! [Loop]
    double rms = 0.0, rmsStart = 0.0;
    const double tLoop = vpTime::measureTimeMs();
    unsigned int iter = 0;
    while (iter++ < opt_iterations) {
      std::cout << "---------------------------------------------" << iter << std::endl;
      double t = vpTime::measureTimeMs();
      vpColVector q;
      robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
      cMo = robot.get_cMo();
      if (iter == 1) {
        std::cout << "Initial robot position with respect to the object frame:\n";
        cMo.print();
        std::cout << std::endl;
      }
      for (unsigned int i = 0; i < 4; i++) {
        p[i].buildFrom(point[i], cam, cMo, cam, cRightMcLeft * cMo);
      }
      if (opt_display) {
        vpDisplay::display(Iint);
        robot.getInternalView(Iint);
        vpDisplay::flush(Iint);
      }
      if (opt_display && opt_click_allowed && iter == 1) {
        std::cout << "Click in the internal view window to continue..." << std::endl;
        vpDisplay::getClick(Iint);
      }
      task.setJointPositions(q);                   // vpServo: task.set_eJe(...) at each iteration
      vpColVector qdot = task.computeControlLaw(); // joint velocities (rad/s), not a camera velocity
      robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
      const vpColVector e = task.getError();
      if (opt_display) {
        stereo.display();
        for (unsigned int i = 0; i < 4; i++) {
          stereo.displayFeature(i, p[i], pd[i]);
        }
        stereo.flush();
        stereo.plot(e, q);
      }
      std::cout << "|| s - s* || " << e.sumSquare() << std::endl;
      rms = std::sqrt(e.sumSquare() / e.size()) * task.getControlLaw().getErrorScale(); // pixels
      if (iter == 1) {
        rmsStart = rms;
      }
      vpTime::wait(t, 10);
    }
    robot.setRobotState(vpRobot::STATE_STOP);
    //! [Loop]

    task.print();
    std::cout << "Final robot position with respect to the object frame:\n";
    cMo.print();
    std::cout << std::endl;
    std::cout << "Image error: " << rmsStart << " px RMS at the start, " << rms << " px RMS after " << opt_iterations
              << " iterations (" << (vpTime::measureTimeMs() - tLoop) / 1000.0 << " s)" << std::endl;
    if (opt_display && opt_click_allowed) {
      std::cout << "Click in the internal view window to end..." << std::endl;
      vpDisplay::getClick(Iint);
    }
    return rms < opt_threshold ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cout << "Catch a ViSP exception: " << e << std::endl;
    return EXIT_FAILURE;
  }
#else
  (void)argc;
  (void)argv;
  std::cout << "This tutorial needs ViSP's threaded robot simulator (ViSP's gui module and pthread)" << std::endl;
  return EXIT_SUCCESS;
#endif
}
