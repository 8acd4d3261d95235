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

#include "paper-experiment.h"
#include "paper-record.h"

#include <algorithm>
#include <memory>

#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpServoProjective.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
//! [Acquisition]
vpProjectiveRobot acquire(const PaperWorld &world, double sigma, vpGaussRand &noise, bool verbose,
                          PaperRecorder *recorder)
{
  // The images at q: noisy projections of all the markers, in view of both cameras or not.
  bool first = true;
  const ImagesAt imagesAt = [&](const vpColVector &q, std::vector<vpImagePoint> &left,
                                std::vector<vpImagePoint> &right) {
    const bool inView = world.rig.project(world.arm.getMarkers(q), left, right, sigma, noise);
    if (recorder != nullptr && inView) { // the frames the acquisition uses: the zero reference, then the trials
      std::vector<unsigned int> all(left.size());
      for (unsigned int k = 0; k < all.size(); ++k) {
        all[k] = k;
      }
      recorder->add(first ? vpProjectiveSession::ZERO : vpProjectiveSession::TRIAL, q, all, left, right);
    }
    first = false;
    return inView;
  };
  return acquireByTrials(world.trialDeg, imagesAt, acquisitionThreshold(sigma), verbose);
}
//! [Acquisition]

void configureTask(vpServoProjective &task, const PaperWorld &world, const vpProjectiveRobot &robot,
                   double maxExcursionDeg, bool settling)
{
  task.setRobot(robot);
  task.setLambda(0.5);
  // The task starts 240 px away from its target: joint steps are limited to 15 deg and damped when the smallest
  // singular value of J falls below 30 px/rad, so that no step leaves the domain where J is a good linearisation.
  task.getControlLaw().setMaxJointVelocity(vpMath::rad(15.0));
  task.getControlLaw().setDamping(30.0, 30.0);
  // Global servoing: the model plans the task once (inverse kinematics of s*, a path inside the joint limits that
  // keeps the markers 10 px inside the images), the task follows it, and law (47) finishes.
  task.setJointLimits(world.arm.getJointMin(), world.arm.getJointMax());
  task.setImageSize(world.rig.getWidth(), world.rig.getHeight(), 10.0);
  task.setPathPlanning(true);
  // Path samples 10 deg apart; a path of straight image lines is kept if no joint goes farther than maxExcursionDeg
  // beyond its start and target values (this task's need 31 deg: by default its path is the joint-space line).
  task.getPathPlanner().setMaxJointStep(vpMath::rad(10.0));
  task.getPathPlanner().setMaxExcursion(vpMath::rad(maxExcursionDeg));
  task.setSettling(settling); // once converged, average the frames instead of chasing each one's noise
}

//! [Servo]
ServoRun servo(const PaperWorld &world, const vpProjectiveRobot &robot, double sigma, vpGaussRand &noise,
               unsigned int iterations, double maxExcursionDeg, unsigned int targetFrames, bool settling, long seed,
               PaperRecorder *recorder)
{
  ServoRun run;
  const vpColVector qTarget = degToRad(world.targetDeg);
  const unsigned int nbPoints = static_cast<unsigned int>(world.tracked.size());

  std::vector<vpFeatureStereoPoint> s(nbPoints), s_star(nbPoints);
  vpServoProjective task;
  configureTask(task, world, robot, maxExcursionDeg, settling);
  const std::vector<vpColVector> targetMarkers = world.arm.getMarkers(qTarget);
  vpGaussRand teachingNoise(1.0, 0.0, 1000 + seed);
  std::vector<std::vector<vpImagePoint>> leftFrames(nbPoints), rightFrames(nbPoints);
  for (unsigned int f = 0; f < targetFrames; ++f) {
    for (unsigned int k = 0; k < nbPoints; ++k) {
      vpImagePoint l, r;
      world.rig.project(targetMarkers[world.tracked[k]], l, r, sigma, f == 0 ? noise : teachingNoise);
      leftFrames[k].push_back(l);
      rightFrames[k].push_back(r);
    }
    if (recorder != nullptr) { // the frame that taught s*, with the tracked markers
      std::vector<vpImagePoint> l, r;
      for (unsigned int k = 0; k < nbPoints; ++k) {
        l.push_back(leftFrames[k].back());
        r.push_back(rightFrames[k].back());
      }
      recorder->add(vpProjectiveSession::TARGET, qTarget, world.tracked, l, r);
    }
  }
  for (unsigned int k = 0; k < nbPoints; ++k) {
    s_star[k].buildFrom(leftFrames[k], rightFrames[k]); // the mean of the frames
    run.leftTarget.push_back(s_star[k].getLeft());
    run.rightTarget.push_back(s_star[k].getRight());
    task.addFeature(s[k], s_star[k]);
  }

  vpColVector q = degToRad(world.startDeg);
  for (unsigned int it = 0; it <= iterations; ++it) {
    // Image processing stand-in: noisy images of the tracked markers at the current configuration.
    const std::vector<vpColVector> markers = world.arm.getMarkers(q);
    std::vector<vpImagePoint> left(nbPoints), right(nbPoints);
    for (unsigned int k = 0; k < nbPoints; ++k) {
      run.inView = world.rig.project(markers[world.tracked[k]], left[k], right[k], sigma, noise) && run.inView;
      s[k].buildFrom(left[k], right[k]);
    }
    if (!run.inView) {
      break;
    }
    if (recorder != nullptr) {
      recorder->add(vpProjectiveSession::SERVO, q, world.tracked, left, right);
    }
    const vpColVector qdot = task.computeControlLaw(q); // eq. (47), J from the model at q
    if (it == 0) {
      run.plan = task.getPathPlanner().getDescription();
    }
    vpColVector e; // s - s*, whatever intermediate features a planned path aims at
    for (unsigned int k = 0; k < nbPoints; ++k) {
      e.stack(s[k].error(s_star[k]));
    }
    run.record(it, q, left, right, e, std::max(2.0 * sigma, 1e-6));
    if (it < iterations) {
      q = world.arm.integrate(q, qdot, 1.0); // one control period
    }
  }
  run.finalJointError = q - qTarget;
  return run;
}
//! [Servo]

//! [Monte Carlo]
Study study(const PaperWorld &world, double sigma, const std::vector<double> &paperDeg, unsigned int seeds,
            double maxExcursionDeg)
{
  Study st;
  st.sigma = sigma;
  st.paperDeg = paperDeg;
  const ImagesAt trueTracked = trueMarkerImages(world.rig, world.arm, world.tracked);
  st.floor = noiseFloor(imageJacobian(trueTracked, degToRad(world.targetDeg)), sigma);
  st.settled = std::make_shared<Study>();
  st.settled->sigma = sigma;
  st.settled->floor = st.floor;
  for (unsigned int seed = 1; seed <= seeds; ++seed) {
    vpGaussRand noise(1.0, 0.0, static_cast<long>(seed));
    const vpProjectiveRobot robot = acquire(world, sigma, noise, false);
    const double prediction = predictionError(robot, trueMarkerImages(world.rig, world.arm), seed);
    vpGaussRand settledNoise = noise; // the same frames for the 16-frame s* and settling
    st.add(seed, servo(world, robot, sigma, noise, 40, maxExcursionDeg), robot, prediction);
    st.settled->add(seed, servo(world, robot, sigma, settledNoise, 40, maxExcursionDeg, 16, true, seed), robot,
                    prediction);
  }
  st.finish();
  st.settled->finish();
  return st;
}
//! [Monte Carlo]
} // namespace app
