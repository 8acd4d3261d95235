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
  \file tutorial-projective-common.h
  \brief What tutorial-projective-servo.cpp, tutorial-projective-servo-images.cpp and tutorial-projective-study.cpp
  share: the acquisition of the projective model by trial motions of one joint at a time, the check of the model's
  prediction at random configurations, the true image Jacobian and its noise floor, and small statistics helpers.

  The functions know nothing of the simulator: what differs between the tutorials, how the marker images at a joint
  configuration q are obtained (noisy projections, noise-free projections, tracked centres), is given as an ImagesAt.
*/

#ifndef _tutorial_projective_common_h_
#define _tutorial_projective_common_h_

#include <algorithm>
#include <cmath>
#include <functional>
#include <iostream>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace tutorial
{
/*!
  The marker images at the joint values \e q (rad): fills \e left and \e right, one image point per marker, and
  returns true if every marker is in view of both cameras.
*/
typedef std::function<bool(const vpColVector &q, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)>
    ImagesAt;

/*!
  The simulator's noise-free images of the markers \e indices of \e arm (all its markers if \e indices is empty)
  seen by \e rig, as an ImagesAt. Both are captured by reference: they must outlive the result.
*/
inline ImagesAt trueMarkerImages(const vpSimulatorStereoRig &rig, const vpSimulatorArm &arm,
                                 const std::vector<unsigned int> &indices = std::vector<unsigned int>())
{
  return
      [&rig, &arm, indices](const vpColVector &q, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
        const std::vector<vpColVector> markers = arm.getMarkers(q);
        const size_t count = indices.empty() ? markers.size() : indices.size();
        left.assign(count, vpImagePoint());
        right.assign(count, vpImagePoint());
        bool visible = true;
        for (size_t k = 0; k < count; ++k) {
          visible = rig.project(markers[indices.empty() ? k : indices[k]], left[k], right[k]) && visible;
        }
        return visible;
      };
}

//! Joint values in degrees as a vpColVector in radians.
inline vpColVector degToRad(const std::vector<double> &deg)
{
  vpColVector q(static_cast<unsigned int>(deg.size()));
  for (unsigned int i = 0; i < q.size(); ++i) {
    q[i] = vpMath::rad(deg[i]);
  }
  return q;
}

//! Mean of \e x; 0 for an empty set.
inline double mean(const std::vector<double> &x)
{
  double m = 0.0;
  for (double v : x) {
    m += v;
  }
  return x.empty() ? 0.0 : m / x.size();
}

//! Largest element of \e x; 0 for an empty set.
inline double maxOf(const std::vector<double> &x)
{
  return x.empty() ? 0.0 : *std::max_element(x.begin(), x.end());
}

//! One trial motion of the acquisition: joint \e joint alone moved by \e amount (rad) from the zero reference, and the
//! marker images there.
struct TrialMotion {
  unsigned int joint;
  double amount;
  std::vector<vpImagePoint> left, right;
};

/*!
  The projective model from the acquisition images (paper section 6): the fundamental matrix from all the marker
  matches (zero reference, then every trial in order) with inliers within \e inlierThreshold px of their epipolar
  line, then the generators of the \e n joints (revolute) calibrated by vpProjectiveRobot::calibrate().
*/
inline vpProjectiveRobot calibrateFromTrials(unsigned int n, const std::vector<vpImagePoint> &left0,
                                             const std::vector<vpImagePoint> &right0,
                                             const std::vector<TrialMotion> &trials, double inlierThreshold)
{
  std::vector<vpImagePoint> allLeft = left0, allRight = right0;
  for (const TrialMotion &t : trials) {
    allLeft.insert(allLeft.end(), t.left.begin(), t.left.end());
    allRight.insert(allRight.end(), t.right.begin(), t.right.end());
  }
  vpProjectiveStereoRig rig;
  rig.estimate(allLeft, allRight, inlierThreshold);

  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(n, vpProjectiveRobot::REVOLUTE));
  robot.setStereoRig(rig);
  robot.setZeroReference(left0, right0);
  for (const TrialMotion &t : trials) {
    robot.addTrialMotion(t.joint, t.amount, t.left, t.right);
  }
  robot.calibrate();
  return robot;
}

/*!
  Acquisition (paper section 6, Fig. 3): the marker images at the zero reference q = 0, then joint i alone moved by
  +trialDeg[i] and -trialDeg[i] deg, each trial halved until every marker stays in view; then calibrateFromTrials().
  The fundamental matrix is estimated from the same images, so nothing but pixels and encoder values enters the
  model.
  \param trialDeg : the trial amount of every joint (deg); its size is the number of joints.
  \param imagesAt : the marker images at q, called in the order of the motions (q = 0 first).
  \param inlierThreshold : see calibrateFromTrials().
  \param verbose : if true, says on std::cout which trials were reduced.
*/
inline vpProjectiveRobot acquireByTrials(const std::vector<double> &trialDeg, const ImagesAt &imagesAt,
                                         double inlierThreshold, bool verbose)
{
  const unsigned int n = static_cast<unsigned int>(trialDeg.size());
  std::vector<vpImagePoint> left0, right0;
  imagesAt(vpColVector(n, 0.0), left0, right0);

  std::vector<TrialMotion> trials;
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      TrialMotion t{i, sign * vpMath::rad(trialDeg[i]), {}, {}};
      vpColVector q(n, 0.0);
      q[i] = t.amount;
      while (!imagesAt(q, t.left, t.right)) {
        t.amount /= 2.0; // the markers left the view: a smaller trial
        q[i] = t.amount;
      }
      if (verbose && std::abs(t.amount) < vpMath::rad(trialDeg[i])) {
        std::cout << "    joint " << i << ": trial reduced to " << vpMath::deg(t.amount) << " deg to stay in view\n";
      }
      trials.push_back(t);
    }
  }
  return calibrateFromTrials(n, left0, right0, trials, inlierThreshold);
}

/*!
  RMS pixel error of the markers predicted by the model, rig.project(H(q) M(0)), at 100 random q within +-30 deg
  (uniform, seeded by \e seed); only the configurations where the true markers are all in view count.
  \param trueImages : the true (noise-free) images of all the markers at q, in the order of the zero reference.
*/
inline double predictionError(const vpProjectiveRobot &robot, const ImagesAt &trueImages, unsigned int seed)
{
  const unsigned int n = robot.getNumberOfJoints();
  const std::vector<vpColVector> M0 = robot.getZeroReferencePoints();
  vpUniRand uniform(seed);
  double sum = 0.0;
  unsigned int count = 0;
  for (unsigned int k = 0; k < 100; ++k) {
    vpColVector q(n);
    for (unsigned int i = 0; i < n; ++i) {
      q[i] = vpMath::rad(uniform.uniform(-30.0, 30.0));
    }
    std::vector<vpImagePoint> left, right;
    if (!trueImages(q, left, right)) {
      continue; // only configurations where the truth is visible
    }
    const vpMatrix H = robot.getDisplacement(q);
    for (size_t j = 0; j < M0.size(); ++j) {
      vpImagePoint l, r;
      robot.getStereoRig().project(H * M0[j], l, r);
      sum += vpImagePoint::sqrDistance(l, left[j]) + vpImagePoint::sqrDistance(r, right[j]);
      count += 4;
    }
  }
  return std::sqrt(sum / count);
}

/*!
  The true stacked image Jacobian at \e q by central differences of step \e h (rad): 4 rows (u, v, u', v') per
  point given by \e trueImages, one column per joint.
*/
inline vpMatrix imageJacobian(const ImagesAt &trueImages, const vpColVector &q, double h = 1e-6)
{
  const unsigned int n = q.size();
  vpMatrix J;
  for (unsigned int i = 0; i < n; ++i) {
    vpColVector qp = q, qm = q;
    qp[i] += h;
    qm[i] -= h;
    std::vector<vpImagePoint> lp, rp, lm, rm;
    trueImages(qp, lp, rp);
    trueImages(qm, lm, rm);
    if (i == 0) {
      J.resize(4 * static_cast<unsigned int>(lp.size()), n);
    }
    for (unsigned int k = 0; k < lp.size(); ++k) {
      J[4 * k][i] = (lp[k].get_u() - lm[k].get_u()) / (2 * h);
      J[4 * k + 1][i] = (lp[k].get_v() - lm[k].get_v()) / (2 * h);
      J[4 * k + 2][i] = (rp[k].get_u() - rm[k].get_u()) / (2 * h);
      J[4 * k + 3][i] = (rp[k].get_v() - rm[k].get_v()) / (2 * h);
    }
  }
  return J;
}

//! The noise floor sqrt(diag(sigma^2 (J^T J)^-1)) of the joint values servoed on image features with Jacobian \e J.
inline vpColVector noiseFloor(const vpMatrix &J, double sigma)
{
  const vpMatrix covariance = (J.t() * J).inverseByLU() * (sigma * sigma);
  vpColVector floor(J.getCols());
  for (unsigned int i = 0; i < floor.size(); ++i) {
    floor[i] = std::sqrt(covariance[i][i]);
  }
  return floor;
}
} // namespace tutorial

#endif
