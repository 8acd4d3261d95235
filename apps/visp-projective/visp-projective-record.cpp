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

#include <vector>

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
    types.push_back(robot.getArm().getJointType(i) == vpSimulatorArm::PRISMATIC ? vpProjectiveRobot::PRISMATIC
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
} // namespace vispProjective
