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
  Helpers for the suites of a camera or the whole rig moved (issue 12, points 3, 4 and 6) (header only, not a test
  itself): observations of the arm by a moved rig, servo runs through a bump, the bump cases. The suites:
  testRigUpdateCameraPair (the general camera pair, the re-registration, the model file, the bad inputs),
  testRigUpdateBump (SERVO_MODEL_MISMATCH, the task's re-expressed s*) and testRigUpdateMonteCarlo.
*/

#ifndef _vpRigUpdateTestTools_h_
#define _vpRigUpdateTestTools_h_

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <functional>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTranslationVector.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRigRegistration.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpModelFileChecksum.h"
#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
const double kSigma = 0.5; // pixels

//! True if \e f throws a vpProjectiveException of \e code whose message contains \e text.
template <typename F> bool throwsWith(F f, int code, const std::string &text)
{
  try {
    f();
  } catch (const vpProjectiveException &e) {
    const bool ok = e.getCode() == code && e.getStringMessage().find(text) != std::string::npos;
    if (!ok) {
      std::cout << "unexpected error " << e.getCode() << ": " << e.getStringMessage() << std::endl;
    }
    return ok;
  } catch (...) {
    return false;
  }
  return false;
}

enum BumpKind { BUMP_LEFT, BUMP_RIGHT, BUMP_RIG };

inline const char *bumpName(BumpKind kind)
{
  return kind == BUMP_LEFT ? "left camera" : (kind == BUMP_RIGHT ? "right camera" : "whole rig");
}

/*!
  \e s with a camera (or the rig) moved by 1-3 deg about a random axis and 0.5-2 cm along a random direction, in the
  moved camera's frame (the rig's left camera for the whole rig).
*/
inline ArmSetup bumped(const ArmSetup &s, BumpKind kind, vpUniRand &rng)
{
  const double angle = vpMath::rad(rng.uniform(1.0, 3.0));
  const double length = rng.uniform(0.005, 0.02);
  const vpColVector axis = randomDirection(rng), direction = randomDirection(rng);
  const vpHomogeneousMatrix d(vpTranslationVector(length * direction[0], length * direction[1], length * direction[2]),
                              vpThetaUVector(angle * axis[0], angle * axis[1], angle * axis[2]));
  ArmSetup b = s;
  if (kind == BUMP_LEFT) {
    b.wMl = s.wMl * d; // the right camera stays: wMr = wMl rMl^-1 unchanged
    b.rMl = s.rMl * d;
  } else if (kind == BUMP_RIGHT) {
    b.rMl = d.inverse() * s.rMl; // wMr <- wMr d
  } else {
    b.wMl = s.wMl * d;
  }
  return b;
}

//! True if the arm joints of model joints \e q are within the arm's joint limits.
inline bool withinLimits(const ArmSetup &s, const vpColVector &q)
{
  const vpColVector qArm = s.armJoints(q);
  for (unsigned int i = 0; i < s.n(); ++i) {
    if (qArm[i] < s.arm.getJointMin()[i] || qArm[i] > s.arm.getJointMax()[i]) {
      return false;
    }
  }
  return true;
}

/*!
  Model joints drawn by \e draw until they are within the joint limits and every marker is in view in all \e setups
  (\e fallback if none in 100000 draws).
*/
inline vpColVector drawInView(const std::vector<const ArmSetup *> &setups, const std::function<vpColVector()> &draw,
                              const vpColVector &fallback)
{
  for (int attempt = 0; attempt < 100000; ++attempt) {
    const vpColVector q = draw();
    bool ok = withinLimits(*setups[0], q);
    for (const ArmSetup *setup : setups) {
      ok = ok && setup->visible(setup->armJoints(q), 20.0);
    }
    if (ok) {
      return q;
    }
  }
  ADD_FAILURE() << "no configuration in view";
  return fallback;
}

//! Random model joints (within 0.6 times the trial amounts) with every marker in view in all \e setups.
inline vpColVector visibleJoints(const std::vector<const ArmSetup *> &setups, vpUniRand &rng)
{
  const ArmSetup &s = *setups[0];
  return drawInView(
      setups,
      [&] {
        vpColVector q(s.n());
        for (unsigned int i = 0; i < s.n(); ++i) {
          q[i] = rng.uniform(-0.6 * s.trialAmounts[i], 0.6 * s.trialAmounts[i]);
        }
        return q;
      },
      vpColVector(s.n(), 0.0));
}

//! Model joints within +-range[i] of \e center (joint i) with every marker in view in all \e setups.
inline vpColVector jointsNear(const std::vector<const ArmSetup *> &setups, vpUniRand &rng, const vpColVector &center,
                              const vpColVector &range)
{
  return drawInView(
      setups,
      [&] {
        vpColVector q = center;
        for (unsigned int i = 0; i < q.getRows(); ++i) {
          q[i] += rng.uniform(-range[i], range[i]);
        }
        return q;
      },
      center);
}

/*!
  A box of +-degrees about every joint of \e s, a prismatic joint's side 2 mm per degree (20 deg: 4 cm, the
  R-R-P-R-R-R arm's trial on its slide).
*/
inline vpColVector jointBox(const ArmSetup &s, double degrees)
{
  vpColVector range(s.n());
  for (unsigned int i = 0; i < s.n(); ++i) {
    range[i] = s.jointTypes()[i] == vpProjectiveRobot::PRISMATIC ? 0.002 * degrees : vpMath::rad(degrees);
  }
  return range;
}

//! Model joints within jointBox(degrees) of \e center with every marker in view in all \e setups.
inline vpColVector jointsNear(const std::vector<const ArmSetup *> &setups, vpUniRand &rng, const vpColVector &center,
                              double degrees)
{
  return jointsNear(setups, rng, center, jointBox(*setups[0], degrees));
}

inline vpProjectiveRobot acquiredRobot(const ArmSetup &s, vpGaussRand &noise, double sigma = kSigma)
{
  vpProjectiveRobot robot(s.jointTypes());
  EXPECT_TRUE(s.acquire(robot, sigma, noise)) << s.name;
  robot.calibrate();
  return robot;
}

//! RMS over the configurations \e q of the robot's prediction error on noisy images of \e s.
inline double predictionError(const vpProjectiveRobot &robot, const ArmSetup &s, const std::vector<vpColVector> &q,
                              vpGaussRand &noise, double sigma = kSigma)
{
  double sum = 0.0;
  for (const vpColVector &qk : q) {
    std::vector<vpImagePoint> left, right;
    s.images(s.armJoints(qk), left, right, sigma, noise, -1e9);
    const double e = robot.getPredictionError(qk, left, right);
    sum += e * e;
  }
  return std::sqrt(sum / static_cast<double>(q.size()));
}

/*!
  Adds \e count observations of \e s at random configurations in view (around \e center within jointBox(degrees) if
  given, else within 0.6 times the trial amounts of the zero reference) and updates the rig.
*/
struct Observation {
  vpColVector q;
  std::vector<vpImagePoint> left, right;
};

inline std::vector<Observation> reRegister(vpProjectiveRobot &robot, const ArmSetup &s, unsigned int count,
                                           vpUniRand &rng, vpGaussRand &noise,
                                           const vpColVector &center = vpColVector(), double degrees = 0.0)
{
  std::vector<Observation> observations(count);
  for (Observation &o : observations) {
    o.q = center.getRows() > 0 ? jointsNear({&s}, rng, center, degrees) : visibleJoints({&s}, rng);
    s.images(s.armJoints(o.q), o.left, o.right, kSigma, noise, -1e9);
    robot.addRigObservation(o.q, o.left, o.right);
  }
  robot.updateRig();
  return observations;
}

//! Tool pose error (rotation in degrees, translation in metres) between model joints qa and qb of \e s.
inline void toolPoseError(const ArmSetup &s, const vpColVector &qa, const vpColVector &qb, double &deg, double &metres)
{
  const vpHomogeneousMatrix d = s.arm.get_wMt(s.armJoints(qa)).inverse() * s.arm.get_wMt(s.armJoints(qb));
  deg = vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta());
  metres = d.getTranslationVector().frobeniusNorm();
}

const std::vector<unsigned int> kTracked = {0, 1, 2, 3, 4, 5, 6};

//! A servo task on the markers kTracked, features from noisy images; s* taught at qTarget through \e s.
struct ServoRun {
  std::vector<vpFeatureStereoPoint> s, sStar;
  vpServoProjective task;

  ServoRun(const ArmSetup &setup, const vpProjectiveRobot &robot, const vpColVector &qTarget, double sigma,
           vpGaussRand &noise)
      : s(kTracked.size()), sStar(kTracked.size()), task()
  {
    measure(setup, qTarget, sigma, noise, sStar);
    s = sStar;
    task.setRobot(robot);
    task.setLambda(0.5);
    task.getControlLaw().setMaxJointVelocity(vpMath::rad(10.0));
    task.setPathPlanning(true); // plans from the model: no task ends in another branch (issue 11)
    for (size_t k = 0; k < kTracked.size(); ++k) {
      task.addFeature(s[k], sStar[k]);
    }
  }

  static void measure(const ArmSetup &setup, const vpColVector &q, double sigma, vpGaussRand &noise,
                      std::vector<vpFeatureStereoPoint> &features, Observation *frame = nullptr)
  {
    std::vector<vpImagePoint> left, right;
    setup.images(setup.armJoints(q), left, right, sigma, noise, -1e9);
    if (frame != nullptr) {
      *frame = Observation{q, left, right};
    }
    for (size_t k = 0; k < kTracked.size(); ++k) {
      features[k].buildFrom(left[kTracked[k]], right[kTracked[k]]);
    }
  }

  //! One iteration at q seen through \e setup; moves q; returns the status.
  vpServoProjective::vpServoStatus step(const ArmSetup &setup, vpColVector &q, double sigma, vpGaussRand &noise,
                                        Observation *frame = nullptr)
  {
    measure(setup, q, sigma, noise, s, frame);
    const vpColVector qdot = task.computeControlLaw(q);
    q = setup.arm.integrate(setup.armJoints(q), qdot, 1.0) - setup.qRef;
    return task.getStatus();
  }
};

//! The end of one bumped run: where the task rests and how its rig was refined.
struct BumpedRun {
  int detectedAfter = -1;         // iterations after the bump until SERVO_MODEL_MISMATCH (-1: never)
  int falseAlarms = 0;            // SERVO_MODEL_MISMATCH before the bump
  double deg = 0.0, metres = 0.0; // tool pose error where the arm rests: its mean joints over the last 30 of 150
                                  // iterations after updateRig() (the law jittering with the noise)
  unsigned int refinements = 0;   // the task's own refinements of the rig (setRigRefinement())
  unsigned int failedRefinements = 0;
  bool userStarUnchanged = true;
  bool reached() const { return deg <= 2.0 && metres <= 0.002; } // the target reached: within 2 deg / 2 mm
};

/*!
  The bumped run of a task from qStart to qTarget through \e s: 6 iterations, the bump to \e b, detection, \e poses
  observation poses within 20 deg of where the arm stopped (spreading the markers), updateRig(), then 150 iterations
  back to the target, the task refining the rig with its own frames if \e refine (setRigRefinement(), its defaults:
  every 40 calls, 3 times). Seeded apart (\e seed), so that the variants of a case see the same poses and noise.
*/
inline BumpedRun runBumped(const ArmSetup &s, const ArmSetup &b, const vpProjectiveRobot &acquired,
                           const vpColVector &qTarget, const vpColVector &qStart, unsigned int poses, bool refine,
                           long seed)
{
  BumpedRun r;
  vpUniRand rng(seed);
  vpGaussRand noise(1.0, 0.0, seed);
  vpProjectiveRobot robot = acquired;
  ServoRun run(s, robot, qTarget, kSigma, noise);
  run.task.setRobot(robot); // modifiable: the task may refine the robot's rig
  run.task.getRigRefinement().setRefinement(refine);
  const std::vector<vpFeatureStereoPoint> userStar = run.sStar;
  vpColVector q = qStart;
  for (int it = 0; it < 6; ++it) {
    if (run.step(s, q, kSigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH) {
      ++r.falseAlarms;
    }
  }
  for (int it = 1; it <= 4 && r.detectedAfter < 0; ++it) {
    if (run.step(b, q, kSigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH) {
      r.detectedAfter = it;
    }
  }
  reRegister(robot, b, poses, rng, noise, q, 20.0);
  vpColVector qRest(s.n(), 0.0);
  for (int it = 0; it < 150; ++it) {
    run.step(b, q, kSigma, noise);
    if (it >= 120) {
      qRest += q / 30.0;
    }
  }
  toolPoseError(s, qRest, qTarget, r.deg, r.metres);
  r.refinements = run.task.getRigRefinement().getNumberOfRefinements();
  r.failedRefinements = run.task.getRigRefinement().getNumberOfFailures();
  for (size_t k = 0; k < userStar.size(); ++k) {
    r.userStarUnchanged = r.userStarUnchanged && userStar[k].get_s() == run.sStar[k].get_s();
  }
  return r;
}

//! The figures of one bump case.
struct BumpCase {
  int detectedAfter = -1;     // iterations after the bump until SERVO_MODEL_MISMATCH (1 or 2 wanted; -1: never)
  int falseAlarms = 0;        // SERVO_MODEL_MISMATCH in the unbumped runs (0.5 and 1 px) and before the bump
  double preError = 0.0;      // prediction error before the bump (px)
  double ratio3 = 0.0;        // after updateRig() from 3 observations, over preError
  double ratio10 = 0.0;       // from 10
  double ratio3General = 0.0; // from 3, plain 11-parameter resection
  BumpedRun from3;            // the task after updateRig() from 3 observation poses, refining the rig itself
  BumpedRun from10;           // from 10 poses, refining
  BumpedRun from3Alone;       // from 3 poses, no refinement (setRigRefinement(false)); only if asked
  double unbumpedDeg = 0.0;   // the same for the unbumped run at 0.5 px
  double unbumpedMetres = 0.0;
};

//! What runBumpCase() runs besides the unbumped task and the bumped one from 3 observation poses.
struct BumpOptions {
  bool ratios = true;             // the re-registered prediction errors (ratio3, ratio10, ratio3General)
  bool from10 = true;             // the bumped task from 10 observation poses
  bool withoutRefinement = false; // the bumped task from 3 poses without the task's refinement
};

/*!
  One bump case of \e s, seeded: the acquisition at 0.5 px, the bump (\e kind), a task whose target is within 20 deg
  of the zero reference and start within 15 deg of the target (a slide: jointBox()), joints within the arm's limits,
  run unbumped at 0.5 and 1 px and bumped six calls after its start (runBumped()), and what \e options asks.
*/
inline BumpCase runBumpCase(const ArmSetup &s, long seed, BumpKind kind, const BumpOptions &options = BumpOptions())
{
  BumpCase c;
  vpUniRand rng(seed);
  vpGaussRand noise(1.0, 0.0, seed);
  const vpProjectiveRobot acquired = acquiredRobot(s, noise);
  const ArmSetup b = bumped(s, kind, rng);

  // Prediction error before the bump, and after re-registration from 3 and 10 observations (same test poses).
  std::vector<vpColVector> testPoses;
  for (int k = 0; k < 10; ++k) {
    testPoses.push_back(visibleJoints({&s, &b}, rng));
  }
  c.preError = predictionError(acquired, s, testPoses, noise);
  if (options.ratios) {
    vpProjectiveRobot robot = acquired;
    reRegister(robot, b, 3, rng, noise);
    c.ratio3 = predictionError(robot, b, testPoses, noise) / c.preError;
  }
  if (options.ratios) {
    vpProjectiveRobot robot = acquired;
    reRegister(robot, b, 10, rng, noise);
    c.ratio10 = predictionError(robot, b, testPoses, noise) / c.preError;
  }
  if (options.ratios) {
    vpProjectiveRobot robot = acquired;
    robot.getRigUpdate().setRegistrationMode(vpProjectiveRigRegistration::GENERAL);
    reRegister(robot, b, 3, rng, noise);
    c.ratio3General = predictionError(robot, b, testPoses, noise) / c.preError;
  }

  // A task of the servo tests' kind: target within 20 deg of the zero reference, start within 15 deg of it.
  const vpColVector qTarget = jointsNear({&s, &b}, rng, vpColVector(s.n(), 0.0), 20.0);
  const vpColVector qStart = jointsNear({&s, &b}, rng, qTarget, 15.0);

  // No false alarm in unbumped runs to the target, at 0.5 and 1 px.
  for (double sigma : {0.5, 1.0}) {
    ServoRun run(s, acquired, qTarget, sigma, noise);
    vpColVector q = qStart, qRest(s.n(), 0.0);
    for (int it = 0; it < 150; ++it) {
      if (run.step(s, q, sigma, noise) == vpServoProjective::SERVO_MODEL_MISMATCH) {
        ++c.falseAlarms;
      }
      if (it >= 120) {
        qRest += q / 30.0;
      }
    }
    if (sigma == kSigma) {
      toolPoseError(s, qRest, qTarget, c.unbumpedDeg, c.unbumpedMetres);
    }
  }

  // The bumped runs, their poses and noise seeded by the case: from 3 poses (with and, if asked, without the task's
  // refinement, the same poses) and from 10.
  c.from3 = runBumped(s, b, acquired, qTarget, qStart, 3, true, 7 * seed + 1);
  if (options.from10) {
    c.from10 = runBumped(s, b, acquired, qTarget, qStart, 10, true, 7 * seed + 2);
  }
  if (options.withoutRefinement) {
    c.from3Alone = runBumped(s, b, acquired, qTarget, qStart, 3, false, 7 * seed + 1);
  }
  c.detectedAfter = c.from3.detectedAfter;
  c.falseAlarms += c.from3.falseAlarms + c.from10.falseAlarms;
  return c;
}

inline double quantile(std::vector<double> x, double p)
{
  std::sort(x.begin(), x.end());
  return x[std::min(x.size() - 1, static_cast<size_t>(p * static_cast<double>(x.size())))];
}

//! A noise-free model of the PUMA, its rig then bumped (\e kind) and a target in view of both rigs; seeded.
struct NoiseFreeBump {
  NoiseFreeBump(long seed, BumpKind kind)
      : s(pumaEyeToHand()), rng(seed), noise(1.0, 0.0, seed), robot(acquiredRobot(s, noise, 0.0)),
        b(bumped(s, kind, rng)), qTarget(jointsNear({&s, &b}, rng, vpColVector(s.n(), 0.0), 20.0))
  {
  }
  const ArmSetup s;
  vpUniRand rng;
  vpGaussRand noise;
  vpProjectiveRobot robot;
  const ArmSetup b;
  const vpColVector qTarget;
};
} // namespace vpProjectiveTest

#endif
