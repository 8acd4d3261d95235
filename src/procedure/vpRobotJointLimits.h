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
  Private: the joint limits of the ViSP robots that know theirs, for the acquisition procedure and the real-cell
  adapter of a vpRobot. Not installed.
*/

#ifndef _vpRobotJointLimits_h_
#define _vpRobotJointLimits_h_

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/projective/vpSimulatorRobotArm.h>
#if VISP_VERSION_INT < VP_VERSION_INT(3, 7, 0) // ViSP 3.7.0 removed vpAfma4 and vpRobotAfma4
#include <visp3/robot/vpAfma4.h>
#endif
#include <visp3/robot/vpAfma6.h>
#include <visp3/robot/vpRobot.h>
#include <visp3/robot/vpViper.h>
#if defined(VISP_HAVE_FRANKA)
#include <visp3/robot/vpRobotFranka.h>
#endif

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  The joint limits (encoder readings: rad, m) of \e robot when its class knows them: ViSP's Viper650/850 and Afma4/6,
  real or simulated (vpViper, vpAfma4, vpAfma6), vpRobotFranka, and vpSimulatorRobotArm. False otherwise.
*/
inline bool robotJointLimits(const vpRobot &robot, vpColVector &qmin, vpColVector &qmax)
{
  if (const vpViper *viper = dynamic_cast<const vpViper *>(&robot)) {
    qmin = viper->getJointMin();
    qmax = viper->getJointMax();
  } else if (const vpAfma6 *afma6 = dynamic_cast<const vpAfma6 *>(&robot)) {
    qmin = afma6->getJointMin();
    qmax = afma6->getJointMax();
#if VISP_VERSION_INT < VP_VERSION_INT(3, 7, 0)
  } else if (const vpAfma4 *afma4 = dynamic_cast<const vpAfma4 *>(&robot)) {
    qmin = afma4->getJointMin();
    qmax = afma4->getJointMax();
#endif
  } else if (const vpSimulatorRobotArm *arm = dynamic_cast<const vpSimulatorRobotArm *>(&robot)) {
    qmin = arm->getJointMin(); // in encoder readings
    qmax = arm->getJointMax();
#if defined(VISP_HAVE_FRANKA)
  } else if (const vpRobotFranka *franka = dynamic_cast<const vpRobotFranka *>(&robot)) {
    qmin = franka->getJointMin();
    qmax = franka->getJointMax();
#endif
  } else {
    return false;
  }
  return true;
}
} // namespace vpProjectiveInternal

#endif
