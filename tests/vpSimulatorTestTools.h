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
  Helpers for the suites of the metric simulator (vpSimulatorStereoRig, vpSimulatorArm), the ground truth every other
  suite and the tutorials rely on (header only, not a test itself). The suites: testSimulatorStereoRig,
  testSimulatorProjectiveToEuclidean and testSimulatorArm. Every random number comes from a seeded vpUniRand or
  vpGaussRand.
*/

#ifndef _vpSimulatorTestTools_h_
#define _vpSimulatorTestTools_h_

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/robot/vpViper850.h>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
using vpProjectiveTest::expm; // independent reference: a scaled and squared Taylor series
using vpProjectiveTest::pixel;
using vpProjectiveTest::point3;
using vpProjectiveTest::toEigen; // checks the size of the ViSP array

const double kTrialDeg[6] = {30.0, 20.0, 30.0, 40.0, 60.0, 60.0}; // the paper's trial motions

//! A world point drawn uniformly in a box around the fixation point, visible in both images of \e sim.
inline vpColVector visiblePoint(const vpSimulatorStereoRig &sim, vpUniRand &rng)
{
  for (;;) {
    const double z = rng.uniform(-0.2, 0.2); // drawn last to first: see point3(), vpProjectiveTestTools.h
    const double y = rng.uniform(-0.12, 0.12);
    const double x = rng.uniform(-0.15, 0.15);
    const vpColVector X = point3(x, y, z);
    if (sim.isVisible(X, 5.0)) {
      return X;
    }
  }
}

//! Left-camera homogeneous coordinates N = (lX, 1) of a world point.
inline Eigen::Vector4d leftCameraPoint(const vpSimulatorStereoRig &sim, const vpColVector &wX)
{
  return toEigen<4, 4>(sim.get_wMl().inverse()) * toEigen<3, 1>(wX).homogeneous();
}

//! Random joint values within the arm's limits.
inline vpColVector randomJoints(const vpSimulatorArm &arm, vpUniRand &rng)
{
  vpColVector q(arm.getNumberOfJoints());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    q[i] = rng.uniform(arm.getJointMin()[i], arm.getJointMax()[i]);
  }
  return q;
}

//! Checks the product of exponentials (35): wMt(q) = exp(q0 T0) ... exp(q_{n-1} T_{n-1}) wMt(0).
inline void expectProductOfExponentials(const vpSimulatorArm &arm, vpUniRand &rng, int trials)
{
  const unsigned int n = arm.getNumberOfJoints();
  const Eigen::Matrix4d wMt0 = toEigen<4, 4>(arm.get_wMt(vpColVector(n, 0.0)));
  for (int k = 0; k < trials; ++k) {
    const vpColVector q = randomJoints(arm, rng);
    Eigen::Matrix4d poe = Eigen::Matrix4d::Identity();
    for (unsigned int i = 0; i < n; ++i) {
      poe = poe * expm(q[i] * toEigen<4, 4>(arm.getTwist(i)));
    }
    poe = poe * wMt0;
    const Eigen::Matrix4d wMt = toEigen<4, 4>(arm.get_wMt(q));
    EXPECT_LT((poe - wMt).cwiseAbs().maxCoeff(), 1e-12) << "q = " << q.t();
  }
}

template <typename F> void expectThrowsCode(F f, int code)
{
  try {
    f();
    ADD_FAILURE() << "no vpProjectiveException thrown";
  } catch (const vpProjectiveException &e) {
    EXPECT_EQ(e.getCode(), code) << e.getStringMessage();
    EXPECT_FALSE(e.getStringMessage().empty());
  }
}

inline vpSimulatorArm paperArm()
{
  return vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
}

inline vpSimulatorStereoRig paperRig()
{
  return vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
}
} // namespace vpProjectiveTest

#endif
