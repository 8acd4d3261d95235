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
  Helpers for the suites of the acquisition's model check (vpProjectiveModelCheck; header only, not a test itself):
  the four arms (the PUMA-like arm of the paper, ViSP's Viper850, the R-R-P-R-R-R arm of the stanfordTable(), an
  Afma6-like gantry of 3 slides and a spherical wrist) with the paper's rig, and a user's acquisition with mistakes
  (readings in degrees, a second joint moving, markers swapped), each trial's readings and images editable. The
  suites: testAcquisitionModelCheck and testAcquisitionModelCheckStudy. Seeded noise.
*/

#ifndef _vpModelCheckTestTools_h_
#define _vpModelCheckTestTools_h_

#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorArm.h>

#include "vpProjectiveArmTestTools.h"
#include "vpProjectiveSessionTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
/*!
  An Afma6-like gantry: three orthogonal slides (joints 0-2, d of the standard DH rows) then a spherical wrist with a
  10 cm wrist-to-flange distance (joints 3-5, as stanfordTable()'s).
*/
inline std::vector<vpSimulatorArm::vpDHRow> gantryTable()
{
  std::vector<vpSimulatorArm::vpDHRow> dh(6);
  dh[0] = {vpProjectiveJoint::PRISMATIC, 0.0, 0.0, 0.0, -M_PI / 2};
  dh[1] = {vpProjectiveJoint::PRISMATIC, -M_PI / 2, 0.0, 0.0, -M_PI / 2};
  dh[2] = {vpProjectiveJoint::PRISMATIC, M_PI / 2, 0.0, 0.0, -M_PI / 2};
  dh[3] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.0, 0.0, -M_PI / 2};
  dh[4] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.0, 0.0, M_PI / 2};
  dh[5] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.10, 0.0, 0.0};
  return dh;
}

/*!
  The gantry with its zero reference at slides (0.3, 0.3, 0.3) m and the wrist at (0, -50, 0) deg (off its
  singularity), the gripper at the PUMA's zero-reference tool pose facing the paper rig. Trials: 5 cm per slide, 30,
  30, 60 deg.
*/
inline ArmSetup gantryEyeToHand()
{
  const std::vector<vpSimulatorArm::vpDHRow> dh = gantryTable();
  vpColVector qRef(6, 0.0);
  qRef[0] = qRef[1] = qRef[2] = 0.3;
  qRef[4] = vpMath::rad(-50.0);
  const vpSimulatorArm arm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                           basePoseFor(dh, qRef, paperToolPose()));
  ArmSetup s("gantry eye-to-hand", arm, qRef, paperRigAtOrigin());
  s.trialAmounts = {0.05, 0.05, 0.05, vpMath::rad(30.0), vpMath::rad(30.0), vpMath::rad(60.0)};
  return s;
}

//! The four arms of the model check's suites.
struct ArmCase {
  const char *label;
  ArmSetup (*make)();
};
const ArmCase kCheckArms[] = {
    {"PUMA", pumaEyeToHand}, {"Viper850", viperEyeToHand}, {"RRPRRR", rrprrrEyeToHand}, {"gantry", gantryEyeToHand}};

//! One trial as the user gives it: the joint moved and its reading, the true model joints of its images, the images.
struct UserTrial {
  unsigned int joint;
  double amount;     //!< the reading given to addTrialMotion()
  vpColVector qTrue; //!< the model joints where the images are taken
  std::vector<vpImagePoint> left, right;
};

/*!
  The setup's acquisition into \e robot (rig with the true F, mounting, zero reference, one trial per joint and sign)
  at pixel noise \e sigma drawn from \e seed. \e before(k, trial) may change trial k's reading or true joints before
  its images are taken, \e after(k, trial) its images. False if a marker left the view.
*/
inline bool acquireWithMistakes(const ArmSetup &s, vpProjectiveRobot &robot, double sigma, long seed,
                                const std::function<void(unsigned int, UserTrial &)> &before = nullptr,
                                const std::function<void(unsigned int, UserTrial &)> &after = nullptr)
{
  vpGaussRand noise(1.0, 0.0, seed);
  robot.setStereoRig(s.rig());
  robot.setRigMounting(s.mounting);
  std::vector<vpImagePoint> left, right;
  bool ok = s.images(s.qRef, left, right, sigma, noise);
  robot.setZeroReference(left, right);
  unsigned int k = 0;
  for (unsigned int i = 0; i < s.n(); ++i) {
    for (int sign = -1; sign <= 1; sign += 2, ++k) {
      UserTrial t;
      t.joint = i;
      t.amount = sign * s.trialAmounts[i];
      t.qTrue = vpColVector(s.n(), 0.0);
      t.qTrue[i] = t.amount;
      if (before) {
        before(k, t);
      }
      ok = s.images(s.armJoints(t.qTrue), t.left, t.right, sigma, noise) && ok;
      if (after) {
        after(k, t);
      }
      robot.addTrialMotion(t.joint, t.amount, t.left, t.right);
    }
  }
  return ok;
}

//! The types of \e s with joint \e i changed to the other type.
inline std::vector<vpProjectiveRobot::vpJointType> withOtherType(const ArmSetup &s, unsigned int i)
{
  std::vector<vpProjectiveRobot::vpJointType> types = s.jointTypes();
  types[i] = types[i] == vpProjectiveRobot::REVOLUTE ? vpProjectiveRobot::PRISMATIC : vpProjectiveRobot::REVOLUTE;
  return types;
}

//! The code of the vpProjectiveException \e f throws (-1: none, -2: another exception); \e message its message.
inline int codeOf(const std::function<void()> &f, std::string &message)
{
  try {
    f();
  } catch (const vpProjectiveException &e) {
    message = e.getStringMessage();
    return e.getCode();
  } catch (...) {
    return -2;
  }
  message.clear();
  return -1;
}
} // namespace vpProjectiveTest

#endif
