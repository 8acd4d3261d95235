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
  \file paper-world.h
  \brief What the servo apps (projective-paper, projective-study and the others) share: the paper's world, the
  acquisition of the projective model by trial motions of one joint at a time, the check of the model's prediction at
  random configurations, the true image Jacobian and its noise floor, and small statistics helpers.

  The functions know nothing of the simulator: what differs between the apps, how the marker images at a joint
  configuration q are obtained (noisy projections, noise-free projections, tracked centres, ViSP's simulated
  Viper850), is given as an ImagesAt.
*/

#ifndef _app_projective_common_h_
#define _app_projective_common_h_

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

namespace app
{
//! [World]
/*!
  The paper's world, which only the simulator knows: the metric rig, the PUMA-like arm, the trial motions and the
  servo task in its joint values (deg). The gripper translates by 82 cm and rotates by 88 deg; with a 38 x 29 cm field
  of view at 1 m, such a motion is mostly along the depth (0.7 to 1.5 m from the rig). The pair was found once by a
  seeded search over random configurations: 3 tracked markers in view of both cameras at both ends, the target away
  from singularities (noise floor below 1.5 deg at 0.5 px), in the same inverse-kinematic branch as the start (so that
  q* is the configuration the servo can reach), then moved to exactly 82 cm and 88 deg. The search checked
  convergence with 10 models acquired at seeds 1 to 6 (0.5 px) and 1 to 4 (0.1 px); the final pair was moved
  afterwards, and converges for every one of seeds 1 to 100 at both noise levels.
*/
struct PaperWorld {
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  std::vector<double> trialDeg = {30, 20, 30, 40, 60, 60}; // the paper's trial motions
  std::vector<unsigned int> tracked = {0, 1, 2};           // markers on the face that looks at the rig
  std::vector<double> startDeg = {15.4461, 54.9087, -48.3752, 62.3954, 29.0729, 1.7330};
  std::vector<double> targetDeg = {8.1330, 7.0830, -56.4826, 90.4984, 76.3260, 57.1987};
};
//! [World]

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
template <typename T> T maxOf(const std::vector<T> &x)
{
  return x.empty() ? T(0) : *std::max_element(x.begin(), x.end());
}

//! Upper median of \e x; 0 for an empty set.
template <typename T> T median(std::vector<T> x)
{
  std::sort(x.begin(), x.end());
  return x.empty() ? T(0) : x[x.size() / 2];
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
  line, then the generators of the \e n joints (revolute) calibrated by vpProjectiveRobot::calibrate(), with the rig
  where \e mounting says.
*/
inline vpProjectiveRobot calibrateFromTrials(unsigned int n, const std::vector<vpImagePoint> &left0,
                                             const std::vector<vpImagePoint> &right0,
                                             const std::vector<TrialMotion> &trials, double inlierThreshold,
                                             vpProjectiveRobot::vpRigMounting mounting = vpProjectiveRobot::EYE_TO_HAND)
{
  std::vector<vpImagePoint> allLeft = left0, allRight = right0;
  for (const TrialMotion &t : trials) {
    allLeft.insert(allLeft.end(), t.left.begin(), t.left.end());
    allRight.insert(allRight.end(), t.right.begin(), t.right.end());
  }
  vpProjectiveStereoRig rig;
  rig.estimate(allLeft, allRight, inlierThreshold);

  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(n, vpProjectiveRobot::REVOLUTE));
  robot.setRigMounting(mounting); // with the rig on the hand, the hand is the base of the chain
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
  \param inlierThreshold, mounting : see calibrateFromTrials().
  \param verbose : if true, says on std::cout which trials were reduced.
  \param moveTo : if set, drives a real arm to q and returns the joint values its encoders read there (relative to
  the zero reference), which the trial amounts then are; imagesAt() is called once the arm is there.
*/
inline vpProjectiveRobot acquireByTrials(const std::vector<double> &trialDeg, const ImagesAt &imagesAt,
                                         double inlierThreshold, bool verbose,
                                         vpProjectiveRobot::vpRigMounting mounting = vpProjectiveRobot::EYE_TO_HAND,
                                         const std::function<vpColVector(const vpColVector &)> &moveTo = nullptr)
{
  const unsigned int n = static_cast<unsigned int>(trialDeg.size());
  const auto reach = [&](const vpColVector &q) { return moveTo ? moveTo(q) : q; };
  std::vector<vpImagePoint> left0, right0;
  imagesAt(reach(vpColVector(n, 0.0)), left0, right0);

  std::vector<TrialMotion> trials;
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      TrialMotion t{i, sign * vpMath::rad(trialDeg[i]), {}, {}};
      vpColVector q(n, 0.0);
      q[i] = t.amount;
      vpColVector reached = reach(q);
      while (!imagesAt(reached, t.left, t.right)) {
        t.amount /= 2.0; // the markers left the view: a smaller trial
        q[i] = t.amount;
        reached = reach(q);
      }
      t.amount = reached[i]; // as read by the encoder
      if (verbose && std::abs(t.amount) < vpMath::rad(trialDeg[i]) - 1e-9) {
        std::cout << "    joint " << i << ": trial reduced to " << vpMath::deg(t.amount) << " deg to stay in view\n";
      }
      trials.push_back(t);
    }
  }
  return calibrateFromTrials(n, left0, right0, trials, inlierThreshold, mounting);
}

/*!
  RMS pixel error of the markers predicted by the model, rig.project(H(q_ref + q) M(0)), at 100 random offsets q
  from the zero reference's readings q_ref within +-\e rangeDeg (uniform, seeded by \e seed); only the
  configurations where the true markers are all in view count (0 if none).
  \param trueImages : the true (noise-free) images of all the markers at the offset q, in the order of the zero
  reference.
*/
inline double predictionError(const vpProjectiveRobot &robot, const ImagesAt &trueImages, unsigned int seed,
                              double rangeDeg = 30.0)
{
  const unsigned int n = robot.getNumberOfJoints();
  std::vector<vpColVector> M0; // the markers' points M_j(0)
  for (const Eigen::Vector4d &Mj : robot.getModel().markers()) {
    M0.emplace_back(4);
    for (unsigned int i = 0; i < 4; ++i) {
      M0.back()[i] = Mj(i);
    }
  }
  vpUniRand uniform(seed);
  double sum = 0.0;
  unsigned int count = 0;
  for (unsigned int k = 0; k < 100; ++k) {
    vpColVector q(n);
    for (unsigned int i = 0; i < n; ++i) {
      q[i] = vpMath::rad(uniform.uniform(-rangeDeg, rangeDeg));
    }
    std::vector<vpImagePoint> left, right;
    if (!trueImages(q, left, right)) {
      continue; // only configurations where the truth is visible
    }
    const vpMatrix H =
        robot.getDisplacement(robot.getAcquisition().getZeroReferenceJoints() + q); // q from the zero reference
    for (size_t j = 0; j < M0.size(); ++j) {
      vpImagePoint l, r;
      robot.getStereoRig().project(H * M0[j], l, r);
      sum += vpImagePoint::sqrDistance(l, left[j]) + vpImagePoint::sqrDistance(r, right[j]);
      count += 4;
    }
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
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
} // namespace app

#endif
