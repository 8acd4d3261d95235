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
  visp-projective: the command-line tool of the plugin, on recorded sessions (vpProjectiveSession) and model files.

    visp-projective calibrate SESSION --output MODEL.json [--family 36h11] [options]
    visp-projective check MODEL.json SESSION [--family 36h11] [--threshold PX]
    visp-projective report MODEL.json
    visp-projective servo SESSION --robot KIND [--left DEV --right DEV] [options]

  Exit status: 0 on success (check: the model fits every frame), 1 on bad input or any error (one line on stderr
  that says what was wrong and what to do; calibrate then leaves no model file), 2 on a usage mistake, 3 when check
  finds that the model does not fit the session (its likeliest cause first on stderr).
*/

#include <chrono>
#include <fstream>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>
#include <visp3/projective/vpStereoGrabberSource.h>

#include "visp-projective-cell.h"
#include "visp-projective-markers.h"
#include "visp-projective-options.h"
#include "visp-projective-plots.h"
#include "visp-projective-record.h"
#include "visp-projective-servo.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
const int kUsageError = 2;
const int kMismatch = 3;

const char *const kMainUsage =
    "Usage: visp-projective COMMAND [ARGUMENTS] [OPTIONS]\n"
    "Non-metric stereo visual servoing (ViSP plugin visp_projective): calibrate an arm from a recorded session,\n"
    "check a model against another session, report what a model says about the cell.\n"
    "\n"
    "Commands:\n"
    "  calibrate SESSION --output MODEL.json   markers of every frame, rig, arm acquisition -> model file\n"
    "  check MODEL.json SESSION                prediction error of the model on each frame: did a camera move?\n"
    "  report MODEL.json                       joints, residuals, the metric self-calibration K, R, t\n"
    "  record SESSION                          a session from two cameras and typed-in joint readings, or the\n"
    "                                          acquisition of the rendered tag cell (no camera needed)\n"
    "  servo SESSION --robot KIND              a real cell end to end: acquisition, s* taught by showing, the\n"
    "                                          planned servo, the session recorded; the arm stopped on every exit "
    "path\n"
    "\n"
    "'visp-projective COMMAND --help' describes each command. A SESSION is a folder holding session.json\n"
    "(format visp-projective-session, version 1) and its PNG images.\n"
    "Exit status: 0 success, 1 bad input or error (one line on stderr), 2 usage, 3 check: the model does not fit,\n"
    "4 servo: not converged (the arm stopped).\n";

const char *const kRecordUsage =
    "Usage: visp-projective record SESSION --left DEV --right DEV --joints FILE [--joint-types TYPES] [--scale N]\n"
    "                              [--discard N]\n"
    "       visp-projective record SESSION [--noise GREY] [--blur PX] [--observations N] [--seed S]\n"
    "With --left and --right, records in the new folder SESSION one stereo frame of two V4L2 cameras\n"
    "(vpStereoGrabberSource) per line of FILE ('-': standard input), once the line is read: a line is the encoder\n"
    "readings of the arm standing still (radians, metres, separated by spaces or commas), optionally preceded by a\n"
    "role (zero, trial, observation, target, servo); without a role the readings tell it: the first frame is the zero\n"
    "reference, a frame moving one joint from it a trial, any other an observation. Type the readings of your\n"
    "controller, or pipe them in; '#' starts a comment line. On standard input session.json is written after every\n"
    "frame. Then 'visp-projective calibrate SESSION' calibrates the cell.\n"
    "Without cameras, records the acquisition of the rendered cell (vpSimulatorStereoCell: the paper's PUMA-like arm\n"
    "and rig, three 36h11 tags on the tool): the frames vpProjectiveAcquisitionProcedure takes while it moves the\n"
    "arm, then N observation frames at random configurations. A live cell driven by a program records from it\n"
    "(vpProjectiveSessionCalibration::markerSource() with a vpProjectiveSessionWriter).\n"
    "\n"
    "Options:\n"
    "  --left DEV, --right DEV        the two cameras (e.g. /dev/video0 and /dev/video2)\n"
    "  --joints FILE                  the readings, one frame per line ('-': standard input)\n"
    "  --joint-types TYPES            one letter per joint, r revolute or p prismatic (default: r for each reading\n"
    "                                 of the first line)\n"
    "  --scale N                      camera subsampling (default 1: full resolution)\n"
    "  --discard N                    image pairs dropped before each recorded one (default 4: a V4L2 camera\n"
    "                                 queues images taken while the arm was moving)\n"
    "  --noise GREY                   rendered cell: image noise in grey levels (default 1)\n"
    "  --blur PX                      rendered cell: optical blur in pixels (default 0.5)\n"
    "  --observations N               rendered cell: observation frames (default 4)\n"
    "  --seed S                       rendered cell: seed of the noise and of the observation poses (default 1)\n"
    "  -h, --help                     this help\n";

const char *const kCalibrateUsage =
    "Usage: visp-projective calibrate SESSION --output MODEL.json [--family 36h11 | --recorded-markers] [OPTIONS]\n"
    "Extracts the markers (AprilTag corners) of the zero, trial and observation frames of SESSION, estimates the\n"
    "rig, acquires and bundle-adjusts the arm, and writes the model (read by vpProjectiveRobot::loadModel(); it takes\n"
    "the session's absolute encoder readings). A progress line per frame, a summary per joint. On any error no\n"
    "model file is written (the file is written to a temporary name and renamed).\n"
    "\n"
    "Options:\n"
    "  --output FILE                  the model file to write (required)\n"
    "  --family NAME                  AprilTag family (default 36h11)\n"
    "  --mounting MODE                auto, eye-to-hand or eye-in-hand (default auto: told by the observation\n"
    "                                 frames if any, else eye-to-hand)\n"
    "  --epipolar-threshold PX        inlier threshold of the rig's estimation (default 2)\n"
    "  --outlier-threshold PX         leave out trial observations farther than PX from the model (default 0: none)\n"
    "  --coplanarity-threshold PX     plane parallax below which markers count as coplanar (default 2)\n"
    "  --camera-layout LAYOUT         left-right (default: upright cameras, the left one on the left; a session\n"
    "                                 whose right camera sits to the left of the left one is refused as one with\n"
    "                                 exchanged images) or any (a camera upside down or seen in a mirror)\n"
    "  --recorded-markers             take each frame's recorded markers (its recorded_markers entry: sessions of\n"
    "                                 programs whose markers are not tags, e.g. projective-paper --record) instead\n"
    "                                 of detecting tags in its images\n"
    "  --quiet                        no progress lines\n"
    "  -h, --help                     this help\n";

const char *const kCheckUsage =
    "Usage: visp-projective check MODEL.json SESSION [--family 36h11 | --recorded-markers] [--threshold PX]\n"
    "Predicts, at each frame's encoder readings, the markers of the model seen in the frame and prints the RMS error\n"
    "of the left and right images; says whether the rig moved since the model was made, and which camera. When\n"
    "frames do not fit, the probable causes are tried and ranked, the likeliest first (a camera moved, the left and\n"
    "right images exchanged, the markers moved on the tool, readings of other encoders, a session of another cell),\n"
    "in one line on the standard output and the standard error.\n"
    "Exit status 0 if every frame fits, 3 if not, 1 on bad input.\n"
    "\n"
    "Options:\n"
    "  --family NAME                  AprilTag family (default 36h11)\n"
    "  --threshold PX                 RMS per coordinate above which a frame does not fit (default 2)\n"
    "  --recorded-markers             take each frame's recorded markers instead of detecting tags (see calibrate)\n"
    "  --quiet                        no line per frame\n"
    "  -h, --help                     this help\n";

const char *const kReportUsage =
    "Usage: visp-projective report MODEL.json [--plots DIR [--session SESSION] [--range DEG] [--travel M]]\n"
    "Prints what the model says about the cell: the joints, the residuals of its calibration, its markers, and the\n"
    "metric self-calibration over the frames the model file holds (the acquisition's, and the observation, target\n"
    "and servo frames of its session): intrinsics K of both cameras, the right camera's pose R, t in the left one (t\n"
    "in the prismatic joints' unit, or a unit baseline without one), the joints' axes in the left camera's frame,\n"
    "each with its standard deviation, and the largest uncertainty; and its cameras (which was left, on which side\n"
    "the right one sits).\n"
    "\n"
    "Options:\n"
    "  --plots DIR                    write DIR/joint-paths-left.png and -right.png (gnuplot): the marker paths the\n"
    "                                 model predicts when each joint moves alone, one colour and legend per joint,\n"
    "                                 axes in pixels\n"
    "  --session SESSION              the model's session: the paths over its zero frame's images and their border,\n"
    "                                 solid within the range its trials acquired, dashed beyond, and the markers\n"
    "                                 measured in each trial beside the model's prediction there\n"
    "  --range DEG                    a revolute joint's motion either way (default: 1.5 times the acquired range\n"
    "                                 with --session, else 30)\n"
    "  --travel M                     a prismatic joint's motion either way (default: 1.5 times the acquired range\n"
    "                                 with --session, else 0.05)\n"
    "  --family NAME                  AprilTag family of the session's markers (default 36h11; a frame's recorded\n"
    "                                 markers are used when it has them)\n"
    "  -h, --help                     this help\n";

//! One line: a message with its line breaks replaced.
std::string oneLine(std::string text)
{
  for (char &c : text) {
    if (c == '\n' || c == '\r') {
      c = ' ';
    }
  }
  return text;
}

int usageError(const std::string &command, const std::string &error)
{
  std::cerr << "visp-projective " << command << ": " << oneLine(error) << std::endl;
  return kUsageError;
}

//! Parses a subcommand's arguments; returns -1 to go on, else the exit status.
int parseArguments(vispProjective::Arguments &args, int argc, char **argv, const std::string &command,
                   const char *usage)
{
  bool help = false;
  std::string error;
  if (!args.parse(argc, argv, 2, help, error)) {
    if (help) {
      std::cout << usage;
      return EXIT_SUCCESS;
    }
    return usageError(command, error);
  }
  return -1;
}

int calibrate(int argc, char **argv)
{
  vispProjective::Arguments args("visp-projective calibrate", {"SESSION"},
                                 {"--output", "-o", "--family", "--mounting", "--epipolar-threshold",
                                  "--outlier-threshold", "--coplanarity-threshold", "--camera-layout"},
                                 {"--quiet", "--recorded-markers"});
  const int parsed = parseArguments(args, argc, argv, "calibrate", kCalibrateUsage);
  if (parsed >= 0) {
    return parsed;
  }
  const std::string output = args.value("--output", args.value("-o"));
  if (output.empty()) {
    return usageError("calibrate", "--output MODEL.json is required; see 'visp-projective calibrate --help'");
  }
  double epipolar = 2.0, outlier = 0.0, coplanarity = 2.0;
  std::string error;
  if (!args.number("--epipolar-threshold", 2.0, 1e-9, epipolar, error) ||
      !args.number("--outlier-threshold", 0.0, 0.0, outlier, error) ||
      !args.number("--coplanarity-threshold", 2.0, 1e-9, coplanarity, error)) {
    return usageError("calibrate", error);
  }
  const std::string mounting = args.value("--mounting", "auto");
  if (mounting != "auto" && mounting != "eye-to-hand" && mounting != "eye-in-hand") {
    return usageError("calibrate", "--mounting takes auto, eye-to-hand or eye-in-hand, not '" + mounting + "'");
  }
  const std::string layout = args.value("--camera-layout", "left-right");
  if (layout != "left-right" && layout != "any") {
    return usageError("calibrate", "--camera-layout takes left-right or any, not '" + layout + "'");
  }
  const auto start = std::chrono::steady_clock::now();
  vpProjectiveSessionCalibration calibration(vispProjective::markerExtractor(args.value("--family", "36h11")));
  vpProjectiveSessionCalibration::checkWritable(output);
  const vpProjectiveSession session = vpProjectiveSession::read(args.positional(0));
  calibration.setOutput(args.has("--quiet") ? nullptr : &std::cout);
  calibration.setEpipolarThreshold(epipolar);
  calibration.setOutlierThreshold(outlier);
  calibration.setCoplanarityThreshold(coplanarity);
  calibration.setRecordedMarkers(args.has("--recorded-markers"));
  calibration.setMounting(mounting == "eye-to-hand"   ? vpProjectiveSessionCalibration::MOUNTING_EYE_TO_HAND
                          : mounting == "eye-in-hand" ? vpProjectiveSessionCalibration::MOUNTING_EYE_IN_HAND
                                                      : vpProjectiveSessionCalibration::MOUNTING_AUTO);
  calibration.setCameraLayout(layout == "any" ? vpProjectiveCellFingerprint::LAYOUT_ANY
                                              : vpProjectiveCellFingerprint::LAYOUT_LEFT_RIGHT);
  calibration.calibrate(session);
  calibration.saveModel(output);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  if (!args.has("--quiet")) {
    std::cout << "model written to '" << output << "' (" << std::fixed << std::setprecision(2) << seconds << " s)"
              << std::endl;
  }
  return EXIT_SUCCESS;
}

int check(int argc, char **argv)
{
  vispProjective::Arguments args("visp-projective check", {"MODEL.json", "SESSION"}, {"--family", "--threshold"},
                                 {"--quiet", "--recorded-markers"});
  const int parsed = parseArguments(args, argc, argv, "check", kCheckUsage);
  if (parsed >= 0) {
    return parsed;
  }
  double threshold = 2.0;
  std::string error;
  if (!args.number("--threshold", 2.0, 1e-9, threshold, error)) {
    return usageError("check", error);
  }
  vpProjectiveSessionCalibration calibration(vispProjective::markerExtractor(args.value("--family", "36h11")));
  std::vector<int> ids;
  double residual = 0.0, algebraic = 0.0;
  vpProjectiveCellFingerprint cell;
  const vpProjectiveArmModel model =
      vpProjectiveModelFile::load(args.positional(0), &residual, &algebraic, &ids, nullptr, &cell);
  if (ids.empty()) {
    throw vpException(vpException::fatalError,
                      "the model '" + args.positional(0) +
                          "' has no marker identifiers (it was not calibrated from a session): calibrate it with "
                          "'visp-projective calibrate' to check it against sessions");
  }
  const vpProjectiveSession session = vpProjectiveSession::read(args.positional(1));
  calibration.setOutput(args.has("--quiet") ? nullptr : &std::cout);
  calibration.setMismatchThreshold(threshold);
  calibration.setRecordedMarkers(args.has("--recorded-markers"));
  const std::vector<vpProjectiveSessionCalibration::vpFrameCheck> checks = calibration.check(model, ids, session, cell);
  unsigned int off = 0;
  for (const auto &c : checks) {
    off += c.fits ? 0 : 1;
  }
  std::cout << std::setprecision(3) << "left images " << calibration.getLeftResidual() << " px RMS, right images "
            << calibration.getRightResidual() << " px RMS over " << checks.size() << " frames, " << off << " above "
            << threshold << " px (the model's calibration residual: " << residual << " px)" << std::endl;
  std::cout << calibration.getDiagnosisMessage() << std::endl;
  if (calibration.getRigState() == vpProjectiveSessionCalibration::RIG_UNCHANGED) {
    return EXIT_SUCCESS;
  }
  // The likeliest cause first, on the standard error too: a script that reads only it learns why.
  std::cerr << "visp-projective check: " << oneLine(calibration.getDiagnosisMessage()) << std::endl;
  return kMismatch;
}

int record(int argc, char **argv)
{
  vispProjective::Arguments args("visp-projective record", {"SESSION"},
                                 {"--noise", "--blur", "--observations", "--seed", "--left", "--right", "--joints",
                                  "--joint-types", "--scale", "--discard"},
                                 {});
  const int parsed = parseArguments(args, argc, argv, "record", kRecordUsage);
  if (parsed >= 0) {
    return parsed;
  }
  std::string error;
  if (args.has("--left") || args.has("--right") || args.has("--joints")) { // two live cameras
    if (!args.has("--left") || !args.has("--right") || !args.has("--joints")) {
      return usageError("record", "a live recording needs --left DEV, --right DEV and --joints FILE");
    }
    double scale = 1.0, discard = 4.0;
    if (!args.number("--scale", 1.0, 1.0, scale, error) || !args.number("--discard", 4.0, 0.0, discard, error)) {
      return usageError("record", error);
    }
    const std::string file = args.value("--joints");
    std::ifstream readings;
    if (file != "-") {
      readings.open(file.c_str());
      if (!readings) {
        throw vpException(vpException::ioError, "cannot open the joint readings '" + file + "'; check the path");
      }
    }
    std::istream &in = file == "-" ? std::cin : readings;
    const std::string types = args.value("--joint-types");
    if (std::ifstream((args.positional(0) + "/session.json").c_str())) {
      throw vpException(vpException::badValue,
                        "'" + args.positional(0) + "' already holds a session; record into a new folder");
    }
    const std::vector<vpProjectiveJoint::vpJointType> jointTypes =
        types.empty() ? std::vector<vpProjectiveJoint::vpJointType>() : vispProjective::jointTypesOf(types);
    vpStereoGrabberSource cameras(args.value("--left"), args.value("--right"), static_cast<unsigned int>(scale));
    vispProjective::recordFromReadings(args.positional(0), cameras, jointTypes, in, static_cast<unsigned int>(discard),
                                       file == "-", std::cout);
    return EXIT_SUCCESS;
  }
  double noise = 1.0, blur = 0.5, observations = 4.0, seed = 1.0;
  if (!args.number("--noise", 1.0, 0.0, noise, error) || !args.number("--blur", 0.5, 0.0, blur, error) ||
      !args.number("--observations", 4.0, 0.0, observations, error) || !args.number("--seed", 1.0, 0.0, seed, error)) {
    return usageError("record", error);
  }
  vispProjective::recordRenderedCell(args.positional(0), noise, blur, static_cast<unsigned int>(observations),
                                     static_cast<long>(seed), std::cout);
  return EXIT_SUCCESS;
}

int report(int argc, char **argv)
{
  vispProjective::Arguments args("visp-projective report", {"MODEL.json"},
                                 {"--plots", "--range", "--travel", "--session", "--family"}, {});
  const int parsed = parseArguments(args, argc, argv, "report", kReportUsage);
  if (parsed >= 0) {
    return parsed;
  }
  double range = 0.0, travel = 0.0; // 0: told by the session's trials (or 30 deg, 5 cm)
  std::string error;
  if (!args.number("--range", 0.0, 1e-9, range, error) || !args.number("--travel", 0.0, 1e-9, travel, error)) {
    return usageError("report", error);
  }
  if (args.has("--session") && !args.has("--plots")) {
    return usageError("report", "--session is for the plots: give --plots DIR too");
  }
  std::vector<int> ids;
  double residual = 0.0, algebraic = 0.0;
  std::vector<vpProjectiveArmAcquisition::vpFrame> frames;
  vpProjectiveCellFingerprint cell;
  const vpProjectiveArmModel model =
      vpProjectiveModelFile::load(args.positional(0), &residual, &algebraic, &ids, &frames, &cell);
  if (args.has("--plots")) {
    std::unique_ptr<vpProjectiveSession> session;
    if (args.has("--session")) {
      session.reset(new vpProjectiveSession(vpProjectiveSession::read(args.value("--session"))));
      if (ids.size() != model.markers().size()) {
        throw vpException(vpException::badValue, "the model '" + args.positional(0) +
                                                     "' has no marker identifiers: its markers cannot be found in "
                                                     "the session; calibrate it with 'visp-projective calibrate'");
      }
    }
    for (const std::string &file :
         vispProjective::writeJointPathPlots(model, ids, range, travel, args.value("--plots"), session.get(),
                                             vispProjective::markerExtractor(args.value("--family", "36h11")))) {
      std::cout << "plot: " << file << std::endl;
    }
  }
  std::cout << "model '" << args.positional(0) << "': " << model.getNumberOfJoints() << " joints, "
            << (model.getRigMounting() == vpProjectiveArmModel::EYE_TO_HAND ? "eye-to-hand" : "eye-in-hand") << ", "
            << model.markers().size() << " markers" << (ids.empty() ? " (no identifiers)" : "") << ", "
            << (model.getStereoRig().isCanonical() ? "canonical camera pair" : "re-registered camera pair")
            << std::endl;
  std::cout << std::setprecision(3) << "residuals: bundle adjustment " << residual << " px RMS, algebraic generators "
            << algebraic << " px RMS" << std::endl;
  vispProjective::printCell(cell, std::cout);
  for (unsigned int i = 0; i < model.getNumberOfJoints(); ++i) {
    const bool revolute = model.jointType(i) == vpProjectiveJoint::REVOLUTE;
    std::cout << "joint " << i << " (" << vpProjectiveJoint::name(model.jointType(i)) << "), zero reference at "
              << std::setprecision(6)
              << (revolute ? vpMath::deg(model.zeroReferenceJoints()(i)) : model.zeroReferenceJoints()(i))
              << (revolute ? " deg" : " m") << std::endl;
  }
  try {
    // The metric bundle adjustment over the frames the model file holds (none in a file of an older version: the
    // read-out of the model's upgrade, without uncertainty).
    vpProjectiveSelfCalibration(model, frames).print(std::cout);
  } catch (const vpException &e) {
    std::cout << "metric self-calibration: not available (" << oneLine(e.getStringMessage()) << ")" << std::endl;
  }
  return EXIT_SUCCESS;
}
} // namespace

int main(int argc, char **argv)
{
  const std::string command = argc > 1 ? argv[1] : "";
  if (command.empty() || command == "--help" || command == "-h") {
    std::cout << kMainUsage;
    return command.empty() ? kUsageError : EXIT_SUCCESS;
  }
  try {
    if (command == "calibrate") {
      return calibrate(argc, argv);
    }
    if (command == "check") {
      return check(argc, argv);
    }
    if (command == "report") {
      return report(argc, argv);
    }
    if (command == "record") {
      return record(argc, argv);
    }
    if (command == "servo") {
      return vispProjective::servoCommand(argc, argv);
    }
  } catch (const vpException &e) {
    std::cerr << "visp-projective " << command << ": " << oneLine(e.getStringMessage()) << std::endl;
    return EXIT_FAILURE;
  } catch (const std::exception &e) {
    std::cerr << "visp-projective " << command << ": " << oneLine(e.what()) << std::endl;
    return EXIT_FAILURE;
  }
  std::cerr << "visp-projective: unknown command '" << command
            << "'; use calibrate, check, report, record or servo (see "
            << "'visp-projective --help')" << std::endl;
  return kUsageError;
}
