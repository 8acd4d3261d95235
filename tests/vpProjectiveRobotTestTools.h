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
  Helpers for the suites of vpProjectiveRobot (Ruf & Horaud, sections 5 and 6) against the metric simulator (header
  only, not a test itself): the five setups of the parametrised tests (see vpProjectiveArmTestTools.h): the paper's
  PUMA eye-to-hand, a revolute-prismatic-revolute chain eye-to-hand, both again eye-in-hand (rig on the tool, static
  markers) and the Viper850 eye-to-hand. The suites: testProjectiveRobotModel, testProjectiveRobotAcquisition,
  testProjectiveRobotModelFile and testProjectiveRobotBadInput.

  Bounds. Noise-free, the bundle adjustment ends at ~1e-12 px and every model quantity agrees with the ground truth to
  1e-13..5e-12 relative (measured); the bounds 1e-9 (generators, displacements, eq. (39)) leave three orders of
  magnitude for other platforms yet catch any modelling error (a wrong sign, order or frame gives errors of order 1).
  Numeric derivatives are vpNumericJacobian.h's Richardson extrapolation of central differences, h = 1e-3 (rad or m):
  truncation error ~h^4 |f^(5)| / 480 ~ 1e-13 relative, rounding ~1e-16 * |s| / h ~ 1e-11; the bounds 1e-8 (image
  Jacobian against the simulator) and 1e-7 (point Jacobian and joint motions against the model) sit above both. Noisy
  bounds are derived at the tests. Every random number comes from a seeded vpUniRand / vpGaussRand.
*/

#ifndef _vpProjectiveRobotTestTools_h_
#define _vpProjectiveRobotTestTools_h_

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpModelFileChecksum.h"
#include "vpNumericJacobian.h"
#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
//! RMS and worst pixel error of the model's marker images P H(q) M_j(0) against the true noise-free ones, over 50
//! random configurations within +-range (per joint) of the zero reference with every marker in view.
inline double predictionRms(const ArmSetup &s, const vpProjectiveRobot &robot, const std::vector<double> &range,
                            long seed, double &worst)
{
  const vpProjectiveStereoRig &rig = robot.getStereoRig();
  const std::vector<Eigen::Vector4d> &M0 = robot.getModel().markers();
  vpUniRand rng(seed);
  double sum = 0.0;
  size_t count = 0;
  worst = 0.0;
  for (int t = 0; t < 50; ++t) {
    const vpColVector q = s.randomVisibleJoints(rng, range);
    EXPECT_EQ(q.getRows(), s.jointTypes().size());
    const Eigen::Matrix4d H = toEigen<4, 4>(robot.getDisplacement(q));
    for (size_t j = 0; j < M0.size(); ++j) {
      vpImagePoint l, r;
      rig.project(toVispVector(Eigen::Vector4d(H * M0[j])), l, r);
      const Eigen::Vector4d e =
          Eigen::Vector4d(l.get_u(), l.get_v(), r.get_u(), r.get_v()) - s.imageOf(s.armJoints(q), j);
      sum += e.squaredNorm();
      count += 4;
      worst = std::max(worst, e.cwiseAbs().maxCoeff());
    }
  }
  return std::sqrt(sum / static_cast<double>(count));
}

//! Random model joints within the trial amounts of the setup, all markers in view.
inline vpColVector randomJoints(const ArmSetup &s, vpUniRand &rng, double fraction = 1.0)
{
  std::vector<double> range(s.n());
  for (unsigned int i = 0; i < s.n(); ++i) {
    range[i] = fraction * s.trialAmounts[i];
  }
  const vpColVector q = s.randomVisibleJoints(rng, range);
  EXPECT_EQ(q.getRows(), s.n()) << s.name << ": no visible configuration found";
  return q;
}

//! Noise-free images of marker j at arm joints qArm, and the projective point triangulated from them.
inline vpColVector currentPoint(const ArmSetup &s, const vpProjectiveStereoRig &rig, const vpColVector &qArm, size_t j)
{
  const Eigen::Vector4d sj = s.imageOf(qArm, j);
  vpImagePoint l, r;
  l.set_uv(sj(0), sj(1));
  r.set_uv(sj(2), sj(3));
  return rig.triangulate(l, r);
}

//! Product of exponentials in chain order (base of the chain first), with an independent matrix exponential.
inline Eigen::Matrix4d chainProduct(const vpProjectiveRobot &robot, const vpColVector &q, unsigned int upTo)
{
  const unsigned int n = robot.getNumberOfJoints();
  Eigen::Matrix4d A = Eigen::Matrix4d::Identity();
  for (unsigned int k = 0; k < upTo; ++k) {
    const unsigned int i = robot.getRigMounting() == vpProjectiveRobot::EYE_TO_HAND ? k : n - 1 - k;
    A = A * expm(q[i] * toEigen<4, 4>(robot.getGenerator(i)));
  }
  return A;
}

//! A file name of this process only: other build trees may run the same suite at the same time.
inline std::string tempFile(const std::string &name)
{
  return ::testing::TempDir() + "visp_projective_" + std::to_string(static_cast<long>(getpid())) + "_" + name + ".json";
}

inline std::string readFile(const std::string &path)
{
  std::ifstream f(path.c_str(), std::ios::binary);
  std::ostringstream os;
  os << f.rdbuf();
  return os.str();
}

inline void writeFile(const std::string &path, const std::string &text)
{
  std::ofstream f(path.c_str(), std::ios::binary);
  f << text;
}

// ---------------------------------------------------------------------------------------------------------------
// Parametrised over the five setups.

struct SetupCase {
  const char *label;
  ArmSetup (*make)();
};

//! Names the setup in GoogleTest's output instead of dumping its bytes.
inline void PrintTo(const SetupCase &setup, std::ostream *os)
{
  *os << setup.label;
}

const SetupCase kSetups[] = {{"PumaEyeToHand", pumaEyeToHand},
                             {"MixedEyeToHand", mixedEyeToHand},
                             {"PumaEyeInHand", pumaEyeInHand},
                             {"MixedEyeInHand", mixedEyeInHand},
                             {"Viper850EyeToHand", viperEyeToHand}};

class ProjectiveRobotSetup : public ::testing::TestWithParam<SetupCase>
{
};

/*
  Child process of the death test below: the PUMA acquisition where joint 3's only trial shows no motion (a blocked
  joint: its images are those of the zero reference). Exit code 0 if calibrate() throws a vpProjectiveException of
  code degenerateConfigurationError or estimationFailedError whose message names joint 3, 1 if it calibrates, 2 on
  another exception, 3 on a message that does not name the joint. A crash gives a signal instead.
*/
inline void calibrateWithBlockedJoint()
{
  const ArmSetup s = pumaEyeToHand();
  vpProjectiveRobot robot(s.jointTypes());
  robot.setStereoRig(s.rig());
  std::vector<vpImagePoint> left0, right0, left, right;
  s.images(s.qRef, left0, right0);
  robot.setZeroReference(left0, right0);
  for (unsigned int i = 0; i < 6; ++i) {
    vpColVector q(6, 0.0);
    q[i] = s.trialAmounts[i];
    s.images(s.armJoints(q), left, right);
    robot.addTrialMotion(i, q[i], i == 3 ? left0 : left, i == 3 ? right0 : right);
  }
  try {
    robot.calibrate();
  } catch (const vpProjectiveException &e) {
    std::cerr << "calibrate() threw code " << e.getCode() << ": " << e.getStringMessage() << std::endl;
    if (e.getCode() != vpProjectiveException::degenerateConfigurationError &&
        e.getCode() != vpProjectiveException::estimationFailedError) {
      std::exit(2);
    }
    std::exit(e.getStringMessage().find("joint 3") == std::string::npos ? 3 : 0);
  } catch (...) {
    std::exit(2);
  }
  std::exit(1);
}
} // namespace vpProjectiveTest

#endif
