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
  Helpers for the suites of vpProjectiveAcquisitionProcedure on vpSimulatorRobotArm (PUMA, the paper's rig),
  instrumented by the test (header only, not a test itself). The suites: testProjectiveAcquisitionProcedureModel,
  testProjectiveAcquisitionProcedureMotion and testProjectiveAcquisitionProcedureFailures. Seeded noise.
*/

#ifndef _vpProjectiveAcquisitionProcedureTestTools_h_
#define _vpProjectiveAcquisitionProcedureTestTools_h_

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <sstream>
#include <thread>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorRobotArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
/*!
  The library's vpSimulatorRobotArm (constant sampling time: each setVelocity() moves the joints by one step of 10 ms)
  with what the tests check: the calls it received, every position reached (commands), a setPosition() that can be
  made to block, and a joint that velocity commands do not move.
*/
class vpArmRobot : public vpSimulatorRobotArm
{
public:
  explicit vpArmRobot(const vpSimulatorArm &arm, const vpColVector &q0 = vpColVector())
      : vpSimulatorRobotArm(arm, q0), commands(), positionCalls(0), velocityCalls(0), blockInSetPosition(false),
        stuckJoint(-1), lastVelocity(arm.getNumberOfJoints(), 0.0)
  {
  }
  void setPosition(const vpRobot::vpControlFrameType frame, const vpColVector &qIn) override
  {
    ++positionCalls;
    if (blockInSetPosition) {
      // A controller that never reports the move done (ViSP's setPosition() has no timeout): "forever" is 30 s
      // here, so that a procedure that calls it fails the test instead of hanging the suite.
      std::this_thread::sleep_for(std::chrono::seconds(30));
      return;
    }
    vpSimulatorRobotArm::setPosition(frame, qIn);
    commands.push_back(getArmJoints());
  }
  void setVelocity(const vpRobot::vpControlFrameType frame, const vpColVector &qdot) override
  {
    ++velocityCalls;
    lastVelocity = qdot;
    vpColVector v = qdot;
    if (stuckJoint >= 0 && static_cast<unsigned int>(stuckJoint) < v.size()) {
      v[static_cast<unsigned int>(stuckJoint)] = 0.0;
    }
    vpSimulatorRobotArm::setVelocity(frame, v);
    commands.push_back(getArmJoints());
  }
  //! The arm's joints now.
  vpColVector q() { return getArmJoints(); }

  std::vector<vpColVector> commands;
  unsigned int positionCalls, velocityCalls;
  bool blockInSetPosition; //!< setPosition() blocks (30 s)
  int stuckJoint;          //!< a joint that velocity commands do not move (-1: none)
  vpColVector lastVelocity;
};

struct AcquisitionSetup {
  vpSimulatorArm arm;
  vpSimulatorStereoRig sim;
  vpArmRobot robot;
  vpGaussRand noise;
  double sigma;

  AcquisitionSetup()
      : arm(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose())),
        sim(vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0)), robot(arm), noise(1.0, 0.0, 12), sigma(0.5)
  {
  }

  vpProjectiveAcquisitionProcedure::vpImageSource source()
  {
    return [this](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
      return sim.project(arm.getMarkers(robot.q()), left, right, sigma, noise);
    };
  }

  vpProjectiveArmAcquisition acquisition() const
  {
    std::vector<vpProjectiveJoint::vpJointType> types(6, vpProjectiveJoint::REVOLUTE);
    vpProjectiveArmAcquisition acq(types);
    vpProjectiveStereoRig rig;
    rig.setFundamentalMatrix(sim.getFundamentalMatrix());
    acq.setStereoRig(rig);
    return acq;
  }

  //! Largest distance (px) of a marker to the image border, over both images, at joints q (noise-free).
  double borderDistance(const vpColVector &q) const
  {
    double d = 1e9;
    for (const vpColVector &X : arm.getMarkers(q)) {
      vpImagePoint l, r;
      sim.project(X, l, r);
      for (const vpImagePoint &p : {l, r}) {
        d = std::min({d, p.get_u(), p.get_v(), sim.getWidth() - 1.0 - p.get_u(), sim.getHeight() - 1.0 - p.get_v()});
      }
    }
    return d;
  }
};

/*!
  RMS error (px) of the model's marker predictions against the true images at 100 random configurations inside half
  the explored box with all markers 10 px inside the images; fails the test if fewer than 20 such configurations.
*/
inline double predictionRms(const AcquisitionSetup &s, const vpProjectiveAcquisitionProcedure &procedure,
                            const vpProjectiveArmModel &model)
{
  vpUniRand rng(7);
  double sum = 0.0;
  unsigned int count = 0;
  for (int k = 0; k < 100; ++k) {
    vpColVector q(6);
    vpProjectiveArmModel::JointVector qm(6);
    for (unsigned int i = 0; i < 6; ++i) {
      const vpProjectiveAcquisitionProcedure::vpJointReport &r = procedure.getReports()[i];
      q[i] = rng.uniform(-0.5 * r.amountNegative, 0.5 * r.amountPositive);
      qm[i] = q[i];
    }
    if (s.borderDistance(q) < 10.0) {
      continue;
    }
    const Eigen::Matrix4d H = model.displacement(qm);
    const std::vector<vpColVector> X = s.arm.getMarkers(q);
    for (unsigned int j = 0; j < X.size(); ++j) {
      Eigen::Vector4d p;
      EXPECT_TRUE(model.predictMarker(j, H, p));
      vpImagePoint l, r;
      s.sim.project(X[j], l, r);
      sum += (p - Eigen::Vector4d(l.get_u(), l.get_v(), r.get_u(), r.get_v())).squaredNorm();
      count += 4;
    }
  }
  EXPECT_GT(count, 4u * 7u * 20u);
  return count == 0 ? 1e9 : std::sqrt(sum / count);
}

inline std::string messageOf(const std::function<void()> &f, int &code)
{
  try {
    f();
  } catch (const vpProjectiveException &e) {
    code = e.getCode();
    return e.getStringMessage();
  }
  code = -1;
  return "";
}

inline bool contains(const std::string &text, const std::string &word)
{
  return text.find(word) != std::string::npos;
}

//! Markers given in the tool frame (3x1, metres), seen on the PUMA of the setup.
inline vpProjectiveAcquisitionProcedure::vpImageSource toolMarkersSource(AcquisitionSetup &s,
                                                                         const std::vector<vpColVector> &tMarkers)
{
  return [&s, tMarkers](std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
    return s.sim.project(vpSimulatorStereoRig::transform(s.arm.get_wMt(s.robot.q()), tMarkers), left, right, s.sigma,
                         s.noise);
  };
}

inline std::vector<vpColVector> planarMarkers(unsigned int count)
{
  const double xy[6][2] = {{-0.04, -0.03}, {0.04, -0.03}, {0.04, 0.03}, {-0.04, 0.03}, {0.0, 0.05}, {0.02, -0.01}};
  std::vector<vpColVector> m;
  for (unsigned int j = 0; j < count; ++j) {
    m.push_back(vpProjectiveTest::point3(xy[j][0], xy[j][1], 0.0));
  }
  return m;
}
} // namespace vpProjectiveTest

#endif
