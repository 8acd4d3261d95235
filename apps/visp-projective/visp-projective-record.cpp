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
  \file visp-projective-record.cpp
  \brief The rendered cell's acquisition session (`visp-projective record`).
*/

#include "visp-projective-record.h"

#include <cmath>
#include <cstdlib>
#include <memory>
#include <sstream>
#include <vector>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>
#include <visp3/projective/vpSimulatorStereoCell.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
unsigned int recordRenderedCell(const std::string &folder, double noise, double blur, unsigned int observations,
                                long seed, std::ostream &os)
{
  vpSimulatorStereoCell cell(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()),
                             vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0), vpColVector(), seed);
  cell.addToolTags(0.03);
  cell.getRenderer().setNoise(noise);
  cell.getRenderer().setBlur(blur);
  vpSimulatorRobotArm &robot = cell.getRobot();
  robot.setSamplingTime(0.04);
  const unsigned int n = robot.getNumberOfJoints();
  std::vector<vpProjectiveRobot::vpJointType> types;
  for (unsigned int i = 0; i < n; ++i) {
    types.push_back(robot.getArm().getJointType(i) == vpProjectiveJoint::PRISMATIC ? vpProjectiveRobot::PRISMATIC
                                                                                   : vpProjectiveRobot::REVOLUTE);
  }
  vpProjectiveSessionWriter writer(folder, types);
  vpProjectiveAcquisitionProcedure procedure(
      vpProjectiveSessionCalibration::markerSource(cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"),
                                                   robot, &writer),
      cell.getWidth(), cell.getHeight());
  procedure.setOutput(&os);
  vpProjectiveRobot model(types);
  procedure.run(robot, model);

  // Observation frames: views of several joints moved together, for the mounting and for check.
  vpUniRand rng(seed);
  const vpColVector qRef = robot.getArmJoints();
  vpImage<unsigned char> Il, Ir;
  for (unsigned int k = 0, attempts = 0; k < observations && attempts < 1000; ++attempts) {
    vpColVector q = qRef;
    for (unsigned int i = 0; i < n; ++i) {
      q[i] += vpMath::rad(rng.uniform(-15.0, 15.0));
    }
    robot.setPosition(vpRobot::ARTICULAR_FRAME, q + robot.getEncoderOffset());
    std::vector<int> ids;
    std::vector<vpImagePoint> l, r;
    if (cell.getTrueCorners(ids, l, r) < 12) {
      continue;
    }
    cell.acquire(Il, Ir);
    vpColVector readings;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, readings);
    writer.addFrame(vpProjectiveSession::OBSERVATION, readings, robot.getTime(), Il, Ir);
    ++k;
  }
  writer.close(); // session.json with every frame (the writer saves at intervals while it records)
  os << "recorded " << writer.getSession().getNumberOfFrames() << " frames in " << folder << " (model residual "
     << procedure.getCalibrationResidual() << " px RMS)" << std::endl;
  return writer.getSession().getNumberOfFrames();
}

std::vector<vpProjectiveJoint::vpJointType> jointTypesOf(const std::string &text)
{
  std::vector<vpProjectiveJoint::vpJointType> types;
  for (char c : text) {
    if (c != 'r' && c != 'p' && c != 'R' && c != 'P') {
      throw vpException(vpException::badValue, "the joint types '" + text +
                                                   "' must be one letter per joint, r (revolute) or p (prismatic), "
                                                   "e.g. rrprrr");
    }
    types.push_back(c == 'r' || c == 'R' ? vpProjectiveJoint::REVOLUTE : vpProjectiveJoint::PRISMATIC);
  }
  if (types.empty()) {
    throw vpException(vpException::badValue, "no joint types: give one letter per joint, e.g. --joint-types rrrrrr");
  }
  return types;
}

unsigned int recordFromReadings(const std::string &folder, vpStereoImageSource &images,
                                const std::vector<vpProjectiveJoint::vpJointType> &types, std::istream &joints,
                                unsigned int discard, bool interactive, std::ostream &os)
{
  const char *const roles[] = {"zero", "trial", "observation", "target", "servo"};
  std::unique_ptr<vpProjectiveSessionWriter> writer;
  std::string line;
  vpImage<unsigned char> Il, Ir;
  for (unsigned int number = 1; std::getline(joints, line); ++number) {
    for (char &c : line) {
      c = (c == ',' || c == '\t' || c == '\r') ? ' ' : c;
    }
    std::istringstream words(line);
    std::string first;
    if (!(words >> first) || first[0] == '#') {
      continue;
    }
    int role = -1; // told by the readings
    for (int r = 0; r < 5; ++r) {
      role = first == roles[r] ? r : role;
    }
    std::vector<double> readings;
    std::string word = role < 0 ? first : std::string();
    do {
      if (word.empty()) {
        continue;
      }
      char *end = nullptr;
      const double v = std::strtod(word.c_str(), &end);
      if (end == nullptr || *end != '\0' || !std::isfinite(v)) {
        throw vpException(vpException::badValue,
                          "line " + std::to_string(number) + " of the joint readings: '" + word +
                              "' is neither a role (zero, trial, observation, target, servo) nor a finite reading; "
                              "write the role (optional) then one reading per joint, radians and metres");
      }
      readings.push_back(v);
    } while (words >> word);
    if (!writer) { // at the first frame: the joints' kinds given, or one revolute joint per reading
      writer.reset(new vpProjectiveSessionWriter(
          folder, types.empty()
                      ? std::vector<vpProjectiveJoint::vpJointType>(readings.size(), vpProjectiveJoint::REVOLUTE)
                      : types));
      if (interactive) {
        writer->setSaveInterval(1, 1.0); // a session on disk after every frame typed in
      }
      writer->setCameras(images); // which camera is left, for later checks
    }
    if (readings.size() != writer->getSession().getNumberOfJoints()) {
      throw vpException(vpException::dimensionError, "line " + std::to_string(number) + " of the joint readings has " +
                                                         std::to_string(readings.size()) + " readings, the arm has " +
                                                         std::to_string(writer->getSession().getNumberOfJoints()) +
                                                         " joints; give one per joint");
    }
    bool taken = true;
    for (unsigned int d = 0; d < discard && taken; ++d) {
      taken = images.acquire(Il, Ir);
    }
    if (!taken || !images.acquire(Il, Ir)) {
      throw vpException(vpException::ioError, "the cameras gave no image for line " + std::to_string(number));
    }
    const vpColVector q(readings);
    const double t = static_cast<double>(number);
    vpProjectiveSession::vpFrameRole given;
    if (role < 0) {
      given = writer->addAcquisitionFrame(q, t, Il, Ir);
    } else {
      given = static_cast<vpProjectiveSession::vpFrameRole>(role);
      writer->addFrame(given, q, t, Il, Ir);
    }
    os << "frame " << writer->getSession().getNumberOfFrames() << " (line " << number
       << "): " << vpProjectiveSession::toString(given) << std::endl;
  }
  if (!writer) {
    throw vpException(vpException::badValue, "the joint readings have no frame line; write one line of readings per "
                                             "frame (see 'visp-projective record --help')");
  }
  writer->close();
  os << "recorded " << writer->getSession().getNumberOfFrames() << " frames in " << folder << std::endl;
  return writer->getSession().getNumberOfFrames();
}
} // namespace vispProjective
