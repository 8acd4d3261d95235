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
  \file visp-projective-servo.cpp
  \brief `visp-projective servo`: the command line of vpProjectiveCell, with its cameras and arm.
*/

#include "visp-projective-servo.h"

#include <cstdlib>
#include <fstream>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveCell.h>
#include <visp3/projective/vpSimulatorStereoCell.h>
#include <visp3/projective/vpStereoGrabberSource.h>
#if defined(VISP_HAVE_FRANKA)
#include <visp3/robot/vpRobotFranka.h>
#endif
#if defined(VISP_HAVE_VIPER850)
#include <visp3/robot/vpRobotViper850.h>
#endif
#if defined(VISP_HAVE_AFMA6)
#include <visp3/robot/vpRobotAfma6.h>
#endif

#include "visp-projective-markers.h"
#include "visp-projective-options.h"
#include "visp-projective-record.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
const char *const kServoUsage =
    "Usage: visp-projective servo SESSION --robot KIND [--left DEV --right DEV] [OPTIONS]\n"
    "A real cell end to end, the arm stopped on every exit path (an error, Ctrl-C, SIGTERM, a lost tag, a status to\n"
    "stop on): the acquisition of the arm's model (each joint moved alone from where the arm stands, the tags in\n"
    "view), s* taught by showing (bring the arm to the target with its pendant, by hand, or by typed 'move Q0 ... Qn'\n"
    "(rad, m) or 'jog JOINT DELTA' lines, then Enter), the start pose the same way, then the planned servo. Every\n"
    "frame used is recorded in the new session SESSION: check it with 'visp-projective check MODEL SESSION'.\n"
    "\n"
    "Robots (--robot):\n"
    "  rendered                       the rendered cell (vpSimulatorStereoCell: the paper's PUMA-like arm and rig,\n"
    "                                 three 36h11 tags on the tool), which is also the cameras\n"
    "  franka:ADDRESS                 vpRobotFranka (when this ViSP has libfranka)\n"
    "  viper850, afma6                Inria's arms (when this ViSP has their drivers)\n"
    "  Another arm: write a vpProjectiveCellArm adapter (five calls) and run vpProjectiveCell in your program\n"
    "  (tutorial-projective-real-cell.cpp).\n"
    "\n"
    "Cameras: --left DEV, --right DEV (V4L2, e.g. /dev/video0 and /dev/video2), --scale N (subsampling, default 1).\n"
    "\n"
    "Safety (every motion; joint values in encoder readings, rad for revolute joints, m for prismatic ones):\n"
    "  --qmin Q0,...,Qn  --qmax ...   joint limits; default: the robot's own. An arm whose limits are unknown is\n"
    "                                 refused unless given them or --no-joint-limits\n"
    "  --no-joint-limits              the arm has no joint limits (says so explicitly)\n"
    "  --margin-deg D                 kept from a revolute joint's limits (default 5)\n"
    "  --margin-m M                   kept from a prismatic joint's limits (default 0.02)\n"
    "  --speed-deg D                  largest revolute joint speed, deg/s (default 15)\n"
    "  --speed-m M                    largest prismatic joint speed, m/s (default 0.03)\n"
    "Acquisition:\n"
    "  --amount-deg D, --amount-m M   largest trial of a joint each way (default 15 deg, 0.05 m)\n"
    "  --step-deg D, --step-m M       step of the trials (default 2 deg, 0.01 m)\n"
    "  --image-margin PX              margin the markers keep from the image border (default 20)\n"
    "  --tolerance T                  smallest arrival tolerance, rad or m (default 1e-5; raised to 4 times the\n"
    "                                 encoders' noise measured at rest)\n"
    "  --move-timeout S               longest move (default 0: 2 s plus 4 times the move's duration)\n"
    "  --settle S                     stamped images: taken this long after the arm stopped (default 0.1)\n"
    "  --discard N                    images without stamps dropped after the arm stopped (default 3)\n"
    "  --model MODEL.json             the model of an earlier acquisition instead of acquiring again\n"
    "  --save-model MODEL.json        write the model acquired\n"
    "  --family NAME                  AprilTag family (default 36h11)\n"
    "Teaching and servo:\n"
    "  --commands FILE                the teaching lines from FILE instead of the standard input\n"
    "  --target-frames N              frames averaged into s* (default 10)\n"
    "  --tags ID,...                  the tags whose corners are servoed (default: all seen at the target)\n"
    "  --gain G                       gain of the task, 1/s (default 0.5)\n"
    "  --timeout S                    longest servo (default 60)\n"
    "  --converged PX                 image error (RMS) of convergence (default 0.5), --converged-frames N (10)\n"
    "  --max-lost S                   longest time with too few corners seen before the arm stops (default 0.5)\n"
    "  --period S                     control period until measured (default 0.04)\n"
    "  --max-skew S, --max-latency S  frames whose right image is further from the left, or older than the readings,\n"
    "                                 are not used (default 0.04, 0.2; docs: the timing study)\n"
    "  --min-fps HZ                   a frame later than 1/HZ after the last is not used (default 4)\n"
    "  --no-planning                  law (47) alone, no path planning\n"
    "  --no-latency-compensation      use the features as seen, not predicted to the joint readings' time\n"
    "Rendered cell only: --fps HZ (default 25), --latency S (0), --skew S (0), --drop P (0), --encoder-noise RAD\n"
    "  (0), --noise GREY (1), --seed S (1): the timing of a real cell (vpSimulatorStereoCell::setTiming()).\n"
    "Exit status: 0 converged, 1 error, 2 usage, 4 the servo ended without converging (timeout, tags lost, a "
    "status).\n";

//! "a,b,c" as numbers; false on a word that is not a finite number.
bool numbers(const std::string &text, vpColVector &v)
{
  std::vector<double> values;
  std::string word;
  std::istringstream in(text);
  while (std::getline(in, word, ',')) {
    char *end = nullptr;
    const double x = std::strtod(word.c_str(), &end);
    if (word.empty() || end == nullptr || *end != '\0' || !std::isfinite(x)) {
      return false;
    }
    values.push_back(x);
  }
  v = vpColVector(values);
  return !values.empty();
}

int usage(const std::string &error)
{
  std::cerr << "visp-projective servo: " << error << std::endl;
  return 2;
}

//! The rendered cell as a real one: the simulated arm behind the ViSP adapter, its cameras with a real cell's timing.
struct Rendered {
  vpSimulatorStereoCell cell;
  std::unique_ptr<vpProjectiveCellViSPArm> arm;
  explicit Rendered(long seed)
      : cell(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()),
             vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0), vpColVector(), seed)
  {
    cell.addToolTags(0.03);
    cell.getRobot().setSamplingTime(0.04);
  }
};
} // namespace

namespace vispProjective
{
int servoCommand(int argc, char **argv)
{
  Arguments args(
      "visp-projective servo", {"SESSION"},
      {"--robot",         "--left",       "--right",    "--scale",         "--joint-types", "--qmin",
       "--qmax",          "--margin-deg", "--margin-m", "--speed-deg",     "--speed-m",     "--amount-deg",
       "--amount-m",      "--step-deg",   "--step-m",   "--image-margin",  "--tolerance",   "--move-timeout",
       "--settle",        "--discard",    "--model",    "--save-model",    "--family",      "--commands",
       "--target-frames", "--tags",       "--gain",     "--timeout",       "--converged",   "--converged-frames",
       "--max-lost",      "--period",     "--max-skew", "--max-latency",   "--min-fps",     "--fps",
       "--latency",       "--skew",       "--drop",     "--encoder-noise", "--noise",       "--seed"},
      {"--no-joint-limits", "--no-planning", "--no-latency-compensation"});
  bool help = false;
  std::string error;
  if (!args.parse(argc, argv, 2, help, error)) {
    if (help) {
      std::cout << kServoUsage;
      return EXIT_SUCCESS;
    }
    return usage(error);
  }
  vpProjectiveCell::vpSettings s;
  double marginDeg = 5, speedDeg = 15, amountDeg = 15, stepDeg = 2, discard = 3, frames = 10, convergedFrames = 10;
  double fps = 25, latency = 0, skew = 0, drop = 0, encoderNoise = 0, noise = 1, seed = 1, scale = 1;
  if (!args.number("--margin-deg", 5, 0, marginDeg, error) ||
      !args.number("--margin-m", 0.02, 0, s.limitMarginTranslation, error) ||
      !args.number("--speed-deg", 15, 1e-6, speedDeg, error) ||
      !args.number("--speed-m", 0.03, 1e-9, s.maxTranslationSpeed, error) ||
      !args.number("--amount-deg", 15, 1e-6, amountDeg, error) ||
      !args.number("--amount-m", 0.05, 1e-9, s.amountTranslation, error) ||
      !args.number("--step-deg", 2, 1e-6, stepDeg, error) ||
      !args.number("--step-m", 0.01, 1e-9, s.stepTranslation, error) ||
      !args.number("--image-margin", 20, 0, s.imageMargin, error) ||
      !args.number("--tolerance", 1e-5, 1e-12, s.arrivalTolerance, error) ||
      !args.number("--move-timeout", 0, 0, s.moveTimeout, error) ||
      !args.number("--settle", 0.1, 0, s.settleTime, error) || !args.number("--discard", 3, 0, discard, error) ||
      !args.number("--target-frames", 10, 1, frames, error) || !args.number("--gain", 0.5, 1e-9, s.gain, error) ||
      !args.number("--timeout", 60, 1e-3, s.timeout, error) ||
      !args.number("--converged", 0.5, 1e-9, s.convergedError, error) ||
      !args.number("--converged-frames", 10, 1, convergedFrames, error) ||
      !args.number("--max-lost", 0.5, 1e-3, s.maxLostTime, error) ||
      !args.number("--period", 0.04, 1e-4, s.period, error) ||
      !args.number("--max-skew", s.maxSkew, 1e-6, s.maxSkew, error) ||
      !args.number("--max-latency", s.maxLatency, 1e-6, s.maxLatency, error) ||
      !args.number("--min-fps", s.minFrameRate, 1e-6, s.minFrameRate, error) ||
      !args.number("--fps", 25, 0, fps, error) || !args.number("--latency", 0, 0, latency, error) ||
      !args.number("--skew", -10, -10, skew, error) || !args.number("--drop", 0, 0, drop, error) ||
      !args.number("--encoder-noise", 0, 0, encoderNoise, error) || !args.number("--noise", 1, 0, noise, error) ||
      !args.number("--seed", 1, 0, seed, error) || !args.number("--scale", 1, 1, scale, error)) {
    return usage(error);
  }
  skew = args.has("--skew") ? skew : 0.0;
  s.limitMarginRotation = vpMath::rad(marginDeg);
  s.maxRotationSpeed = vpMath::rad(speedDeg);
  s.amountRotation = vpMath::rad(amountDeg);
  s.stepRotation = vpMath::rad(stepDeg);
  s.discardFrames = static_cast<unsigned int>(discard);
  s.targetFrames = static_cast<unsigned int>(frames);
  s.convergedFrames = static_cast<unsigned int>(convergedFrames);
  s.noJointLimits = args.has("--no-joint-limits");
  s.planning = !args.has("--no-planning");
  s.latencyCompensation = !args.has("--no-latency-compensation");
  if ((args.has("--qmin") && !numbers(args.value("--qmin"), s.qmin)) ||
      (args.has("--qmax") && !numbers(args.value("--qmax"), s.qmax))) {
    return usage("--qmin and --qmax take one number per joint, separated by commas (rad, m)");
  }
  if (args.has("--tags")) {
    vpColVector tags;
    if (!numbers(args.value("--tags"), tags)) {
      return usage("--tags takes tag ids separated by commas");
    }
    for (unsigned int i = 0; i < tags.size(); ++i) {
      s.tags.push_back(static_cast<int>(tags[i]));
    }
  }
  const std::string robot = args.value("--robot");
  if (robot.empty()) {
    return usage("--robot KIND is required (rendered, franka:ADDRESS, viper850, afma6); see --help");
  }

  // The arm and the cameras.
  std::unique_ptr<Rendered> rendered;
  std::unique_ptr<vpRobot> driver;
  std::unique_ptr<vpProjectiveCellArm> arm;
  std::unique_ptr<vpStereoImageSource> grabbers;
  vpStereoImageSource *cameras = nullptr;
  std::vector<vpProjectiveJoint::vpJointType> types =
      args.has("--joint-types") ? jointTypesOf(args.value("--joint-types"))
                                : std::vector<vpProjectiveJoint::vpJointType>(6, vpProjectiveJoint::REVOLUTE);
  if (robot == "rendered") {
    rendered.reset(new Rendered(static_cast<long>(seed)));
    rendered->cell.getRenderer().setNoise(noise);
    rendered->cell.setTiming(fps, latency, skew, drop, static_cast<long>(seed));
    rendered->cell.getRobot().setEncoderNoise(encoderNoise, static_cast<long>(seed) + 1);
    types.assign(6, vpProjectiveJoint::REVOLUTE);
    arm.reset(new vpProjectiveCellViSPArm(rendered->cell.getRobot(), types));
    cameras = &rendered->cell;
  } else {
    if (!args.has("--left") || !args.has("--right")) {
      return usage("a real arm needs its cameras: --left DEV --right DEV");
    }
#if defined(VISP_HAVE_FRANKA)
    if (robot.rfind("franka:", 0) == 0) {
      vpRobotFranka *franka = new vpRobotFranka();
      driver.reset(franka);
      franka->connect(robot.substr(7));
      types.assign(7, vpProjectiveJoint::REVOLUTE);
    }
#endif
#if defined(VISP_HAVE_VIPER850)
    if (robot == "viper850") {
      driver.reset(new vpRobotViper850());
      types.assign(6, vpProjectiveJoint::REVOLUTE);
    }
#endif
#if defined(VISP_HAVE_AFMA6)
    if (robot == "afma6") {
      driver.reset(new vpRobotAfma6());
      types = jointTypesOf("ppprrr");
    }
#endif
    if (!driver) {
      throw vpException(vpException::badValue,
                        "--robot " + robot +
                            ": not a robot of this ViSP build (rendered; franka:ADDRESS with libfranka, viper850 and "
                            "afma6 with their drivers): for another arm, write a vpProjectiveCellArm adapter and run "
                            "vpProjectiveCell in your program (see tutorial-projective-real-cell.cpp)");
    }
    arm.reset(new vpProjectiveCellViSPArm(*driver, types));
    grabbers.reset(
        new vpStereoGrabberSource(args.value("--left"), args.value("--right"), static_cast<unsigned int>(scale)));
    cameras = grabbers.get();
  }

  std::ifstream file;
  if (args.has("--commands")) {
    file.open(args.value("--commands").c_str());
    if (!file) {
      throw vpException(vpException::ioError, "cannot read the commands '" + args.value("--commands") + "'");
    }
  }
  vpProjectiveCellRobot::installSignalHandlers(); // Ctrl-C and SIGTERM stop the arm
  vpProjectiveCell cell(*arm, *cameras, markerExtractor(args.value("--family", "36h11")), s);
  cell.setOutput(&std::cout);
  cell.setRecording(args.positional(0));
  if (args.has("--model")) {
    cell.loadModel(args.value("--model"));
    std::cout << "model read from " << args.value("--model") << std::endl;
  } else {
    std::cout << "acquisition: the arm moves each joint alone from where it stands (a hand on the emergency stop)"
              << std::endl;
    cell.acquire();
  }
  if (args.has("--save-model")) {
    cell.saveModel(args.value("--save-model"));
  }
  cell.teach(args.has("--commands") ? static_cast<std::istream &>(file) : std::cin, std::cout);
  const vpProjectiveCell::vpServoResult result = cell.servo();
  std::cout << "servo " << vpProjectiveCell::toString(result.end) << " after " << result.seconds << " s, "
            << result.frames << " frames; session recorded in " << args.positional(0) << std::endl;
  return result.end == vpProjectiveCell::SERVO_CONVERGED ? EXIT_SUCCESS : 4;
}
} // namespace vispProjective
