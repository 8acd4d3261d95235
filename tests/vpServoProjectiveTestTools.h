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
  Helpers for the suites of vpServoProjective, the non-metric stereo servo of eq. (47) (header only, not a test
  itself): tasks on the markers of an arm whose model is acquired noise-free from the metric simulator
  (vpProjectiveArmTestTools.h), the closed loop, the settings of the convergence tests, and the fixture on the
  PUMA-like arm watched by the paper's rig. The suites: testServoProjectiveConvergence, testServoProjectiveLaw,
  testServoProjectiveReducedTask, testServoProjectiveOutliers, testServoProjectiveJointLimits and
  testServoProjectiveInterface.

  Settings of the convergence tests: lambda = 0.5, dt = 1, damping (sigma_0, mu_max) = (1, 10) px/rad (the library's
  default since commit 6e8f9d6), saturation 10 deg per step. Measured: 24-36 iterations for all 20 pairs. With the
  former default damping (30, 30) the same pairs need up to 223 iterations or stall (2 of 10 PUMA and 4 of 10 Viper
  pairs above 300 iterations): three tracked markers 8 cm apart seen from 1 m give sigma_min of 1 to 50 px/rad in
  healthy configurations, so that threshold damped the last, small steps too. Without damping and saturation one Viper
  pair crosses a near-singularity (condition 2700) and ends in another local minimum.
  Bounds: noise free, qdot must match the closed forms to rounding (1e-9 relative); the final joint error is bounded
  by the image error over sigma_min: 3.5e-6 px / 0.9 px/rad < 1e-5 rad. Every random number is seeded.
*/

#ifndef _vpServoProjectiveTestTools_h_
#define _vpServoProjectiveTestTools_h_

#include <cmath>
#include <cstdint>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/visual_features/vpGenericFeature.h>
#include <visp3/vs/vpAdaptiveGain.h>
#include <visp3/vs/vpServo.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
/*!
  A stereo feature written as a tracker that lost its point may write it: NaN and infinity allowed
  (vpFeatureStereoPoint::buildFrom() refuses them), for the tests of FEATURE_NOT_FINITE.
*/
class vpRawStereoPoint : public vpFeatureStereoPoint
{
public:
  void setRaw(double u, double v, double up, double vp)
  {
    s[0] = u;
    s[1] = v;
    s[2] = up;
    s[3] = vp;
  }
};

//! Noise-free features of the markers \e tracked at model joints q.
template <typename Feature>
inline void setFeatures(const ArmSetup &s, const vpColVector &q, const std::vector<unsigned int> &tracked,
                        std::vector<Feature> &features)
{
  for (size_t k = 0; k < tracked.size(); ++k) {
    const Eigen::Vector4d sk = s.imageOf(s.armJoints(q), tracked[k]);
    features[k].buildFrom(sk(0), sk(1), sk(2), sk(3));
  }
}

//! A task on \e tracked markers, current features at q, desired ones at qStar.
struct Task {
  std::vector<vpRawStereoPoint> s, sStar;
  vpServoProjective task;

  Task(const ArmSetup &setup, const vpProjectiveRobot &robot, const std::vector<unsigned int> &tracked,
       const vpColVector &q, const vpColVector &qStar)
      : s(tracked.size()), sStar(tracked.size()), task()
  {
    setFeatures(setup, qStar, tracked, sStar);
    setFeatures(setup, q, tracked, s);
    task.setRobot(robot);
    for (size_t k = 0; k < tracked.size(); ++k) {
      task.addFeature(s[k], sStar[k]);
    }
  }
};

inline Eigen::VectorXd singularValues(const Eigen::MatrixXd &J)
{
  return Eigen::JacobiSVD<Eigen::MatrixXd>(J).singularValues();
}

//! A pair (start, target) of model joints: target within +-targetRange, start within +-startRange of it, both in view.
inline void randomPair(const ArmSetup &s, vpUniRand &rng, double targetRange, double startRange, vpColVector &qStart,
                       vpColVector &qTarget)
{
  for (int attempt = 0; attempt < 100000; ++attempt) {
    qTarget.resize(s.n());
    for (unsigned int i = 0; i < s.n(); ++i) {
      qTarget[i] = rng.uniform(-targetRange, targetRange);
    }
    qStart = qTarget;
    for (unsigned int i = 0; i < s.n(); ++i) {
      qStart[i] += rng.uniform(-startRange, startRange);
    }
    if (s.visible(s.armJoints(qTarget)) && s.visible(s.armJoints(qStart))) {
      return;
    }
  }
  ADD_FAILURE() << s.name << ": no start/target pair in view";
}

//! The same drawn from a generator of its own seeded with \e seed: a test's one pair, reproducible by its seed.
inline void randomPair(const ArmSetup &s, uint64_t seed, double targetRange, double startRange, vpColVector &qStart,
                       vpColVector &qTarget)
{
  vpUniRand rng(seed);
  randomPair(s, rng, targetRange, startRange, qStart, qTarget);
}

//! Runs the loop; returns the iterations to reach rmsGoal (or maxIterations + 1) and leaves q at the end.
inline int servo(const ArmSetup &s, const vpProjectiveRobot &robot, const std::vector<unsigned int> &tracked,
                 vpColVector &q, const vpColVector &qTarget, double rmsGoal, int maxIterations, double sigma0,
                 double &rms)
{
  Task t(s, robot, tracked, q, qTarget);
  t.task.setLambda(0.5);
  t.task.getControlLaw().setDamping(sigma0, 10.0);
  t.task.getControlLaw().setMaxJointVelocity(vpMath::rad(10.0));
  for (int it = 0; it <= maxIterations; ++it) {
    setFeatures(s, q, tracked, t.s); // the tracker: images of the true arm
    const vpColVector qdot = t.task.computeControlLaw(q);
    rms = t.task.getError().frobeniusNorm() / std::sqrt(static_cast<double>(4 * tracked.size()));
    if (rms < rmsGoal) {
      return it;
    }
    q = s.arm.integrate(s.armJoints(q), qdot, 1.0) - s.qRef;
  }
  return maxIterations + 1;
}

inline void expectConvergence(const ArmSetup &s, long seed, int pairs, double targetRange, double startRange,
                              double sigma0 = 1.0, const std::vector<unsigned int> &tracked = {0, 1, 2})
{
  const vpProjectiveRobot robot = calibratedRobot(s);
  vpUniRand rng(seed);
  int worst = 0;
  for (int p = 0; p < pairs; ++p) {
    vpColVector qStart, qTarget;
    randomPair(s, rng, targetRange, startRange, qStart, qTarget);
    vpColVector q = qStart;
    double rms = 0.0;
    const int iterations = servo(s, robot, tracked, q, qTarget, 1e-6, 200, sigma0, rms);
    worst = std::max(worst, iterations);
    EXPECT_LE(iterations, 200) << s.name << " pair " << p << ": RMS " << rms << " px";
    EXPECT_LT((toEigenV(q) - toEigenV(qTarget)).cwiseAbs().maxCoeff(), 1e-5) << s.name << " pair " << p;
    testLog() << "[ measured ] " << s.name << " pair " << p << ": " << iterations << " iterations, start error "
              << vpMath::deg((toEigenV(qStart) - toEigenV(qTarget)).cwiseAbs().maxCoeff()) << " deg, final RMS " << rms
              << " px, joint error " << (toEigenV(q) - toEigenV(qTarget)).cwiseAbs().maxCoeff() << " rad" << std::endl;
  }
}

//! The tests on the PUMA-like arm watched by the paper's rig: its model, acquired noise-free, for each test.
class ServoProjectivePuma : public ::testing::Test
{
protected:
  const ArmSetup s = pumaEyeToHand();
  const vpProjectiveRobot robot = calibratedRobot(s);
};

// ---------------------------------------------------------------------------------------------------------------
// Lost features, outliers, singularities and joint limits (issue 6, points 3 and 4).
// ---------------------------------------------------------------------------------------------------------------
//! The settings of the convergence tests above.
inline void configure(vpServoProjective &task)
{
  task.setLambda(0.5);
  task.getControlLaw().setDamping(1.0, 10.0);
  task.getControlLaw().setMaxJointVelocity(vpMath::rad(10.0));
}

//! RMS (px) of the error of the active features.
inline double activeRms(const vpServoProjective &task)
{
  const unsigned int active = task.getReport().getNumberOfActiveFeatures();
  return active == 0 ? 0.0 : task.getError().frobeniusNorm() / std::sqrt(4.0 * active);
}

inline double jointError(const vpColVector &q, const vpColVector &qTarget)
{
  return (toEigenV(q) - toEigenV(qTarget)).cwiseAbs().maxCoeff();
}

//! The rows of J that belong to the active features.
inline Eigen::MatrixXd activeRows(const vpServoProjective &task)
{
  const Eigen::MatrixXd J = toEigenX(task.getReport().getTaskJacobian());
  Eigen::MatrixXd Ja(4 * task.getReport().getNumberOfActiveFeatures(), J.cols());
  Eigen::Index r = 0;
  for (unsigned int i = 0; i < task.getReport().getNumberOfFeatures(); ++i) {
    if (task.getReport().getFeatureState(i) == vpServoProjective::FEATURE_ACTIVE) {
      Ja.middleRows(r, 4) = J.middleRows(4 * i, 4);
      r += 4;
    }
  }
  return Ja;
}

//! sigma_min / sigma_max of J D^-1, D the column norms, by an SVD (independent of the task's Gram matrix).
inline double equilibratedRatio(const Eigen::MatrixXd &J)
{
  Eigen::MatrixXd JD = J;
  for (Eigen::Index c = 0; c < J.cols(); ++c) {
    JD.col(c) /= J.col(c).norm();
  }
  const Eigen::VectorXd sv = singularValues(JD);
  return sv(sv.size() - 1) / sv(0);
}

inline bool allZero(const Eigen::VectorXd &v)
{
  for (Eigen::Index i = 0; i < v.size(); ++i) {
    if (v(i) != 0.0) {
      return false;
    }
  }
  return true;
}

//! One closed loop at control period dt (the velocities are per second), noise free, markers 0-2.
struct LimitedRun {
  int iterations = 0;          //!< to RMS < 1e-6 px, or maxIterations + 1
  double rms = 0.0;            //!< at the end (px)
  vpColVector qEnd;            //!< model joints at the end
  vpColVector lowest, highest; //!< joint extremes over the run
  bool inside = true;          //!< every joint within [qmin, qmax] at every iteration
};

inline LimitedRun runLimited(const ArmSetup &s, const vpProjectiveRobot &robot, const vpColVector &qStart,
                             const vpColVector &qTarget, const vpColVector *qmin, const vpColVector *qmax, double dt,
                             int maxIterations)
{
  const std::vector<unsigned int> tracked = {0, 1, 2};
  LimitedRun r;
  Task t(s, robot, tracked, qStart, qTarget);
  configure(t.task);
  if (qmin != nullptr) {
    t.task.setJointLimits(*qmin, *qmax);
  } else {
    // Unconstrained, the task may push a joint into the simulated arm's own limit, where integrate() holds it: the
    // arm-following check would stop the task there; off, the run shows how far the task alone goes.
    t.task.getArmFollowing().setEnabled(false);
  }
  vpColVector q = qStart;
  r.lowest = q;
  r.highest = q;
  r.iterations = maxIterations + 1;
  for (int it = 0; it <= maxIterations; ++it) {
    for (unsigned int i = 0; i < q.size(); ++i) {
      r.lowest[i] = std::min(r.lowest[i], q[i]);
      r.highest[i] = std::max(r.highest[i], q[i]);
      if (qmin != nullptr && (q[i] < (*qmin)[i] || q[i] > (*qmax)[i])) {
        r.inside = false;
      }
    }
    setFeatures(s, q, tracked, t.s);
    const vpColVector qdot = t.task.computeControlLaw(q);
    r.rms = activeRms(t.task);
    if (!toEigenV(qdot).allFinite()) {
      ADD_FAILURE() << "non-finite qdot";
      break;
    }
    if (r.rms < 1e-6) {
      r.iterations = it;
      break;
    }
    q = s.arm.integrate(s.armJoints(q), qdot, dt) - s.qRef;
  }
  r.qEnd = q;
  return r;
}

inline vpColVector toVispX(const Eigen::VectorXd &v)
{
  vpColVector r(static_cast<unsigned int>(v.size()));
  for (unsigned int i = 0; i < r.size(); ++i) {
    r[i] = v(i);
  }
  return r;
}
} // namespace vpProjectiveTest

#endif
