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
  \file vpProjectiveCellArm.cpp
  \brief The adapter of a ViSP vpRobot to the real-cell program's arm.
*/

#include <visp3/projective/vpProjectiveCellArm.h>

#include <chrono>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpSimulatorRobotArm.h>

#include "procedure/vpRobotJointLimits.h"

vpProjectiveCellViSPArm::vpProjectiveCellViSPArm(vpRobot &robot,
                                                 const std::vector<vpProjectiveJoint::vpJointType> &types)
    : m_robot(robot), m_types(types), m_maxVelocities(static_cast<unsigned int>(types.size()))
{
  if (types.empty()) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                "vpProjectiveCellViSPArm: no joint types: give one per joint of the robot");
  }
  for (unsigned int i = 0; i < m_maxVelocities.size(); ++i) {
    m_maxVelocities[i] =
        types[i] == vpProjectiveJoint::REVOLUTE ? robot.getMaxRotationVelocity() : robot.getMaxTranslationVelocity();
  }
}

void vpProjectiveCellViSPArm::getJoints(vpColVector &q, double &t)
{
  m_robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  if (const vpSimulatorRobotArm *simulated = dynamic_cast<const vpSimulatorRobotArm *>(&m_robot)) {
    t = simulated->getTime(); // the clock of the rendered cell's images
  } else {
    t = std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
  }
}

void vpProjectiveCellViSPArm::setJointVelocities(const vpColVector &qdot)
{
  if (m_robot.getRobotState() != vpRobot::STATE_VELOCITY_CONTROL) {
    m_robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  }
  m_robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
}

void vpProjectiveCellViSPArm::stop()
{
  // A zero velocity first (a robot whose STATE_STOP only changes a flag keeps no command), then the stop state.
  if (m_robot.getRobotState() == vpRobot::STATE_VELOCITY_CONTROL) {
    m_robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector(static_cast<unsigned int>(m_types.size()), 0.0));
  }
  m_robot.setRobotState(vpRobot::STATE_STOP);
}

bool vpProjectiveCellViSPArm::getJointLimits(vpColVector &qmin, vpColVector &qmax)
{
  return vpProjectiveInternal::robotJointLimits(m_robot, qmin, qmax);
}
