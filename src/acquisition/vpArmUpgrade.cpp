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
  The algebraic generators of an arm's acquisition and the choice of their metric start: the start of the bundle
  adjustment of vpProjectiveArmAcquisition::calibrate() (the paper's section 6, and DESIGN.md's acquisition that
  reaches the noise floor). The upgrade itself is in vpArmMetricUpgrade.cpp.
*/

#include "acquisition/vpArmCalibration.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>

#include <Eigen/Dense>

#include <visp3/projective/vpProjectiveDisplacement.h>

#include "core/vpProjectiveErrors.h"
#include "core/vpProjectiveNumerics.h"

namespace vpProjectiveInternal
{

void accumulateTrialError(const ArmCalibrationData &data, unsigned int i, const Eigen::Matrix4d &Hhat,
                          const std::vector<Eigen::Vector4d> &M0, double &sum, size_t &count)
{
  // A prediction with no image (on a camera's focal plane) counts as an error of one image diagonal per coordinate.
  const double noImage = 1e6;
  // With an outlier threshold t, an error counts at most as 3 t (RMS over the two images): a mismatch the consensus
  // missed cannot outweigh the markers that agree.
  const double cap = data.outlierThreshold > 0.0 ? 2.0 * 9.0 * data.outlierThreshold * data.outlierThreshold
                                                 : std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < data.trials.size(); ++k) {
    const ArmTrial &trial = data.trials[k];
    if (trial.joint != i) {
      continue;
    }
    const Eigen::Matrix4d H = vpProjectiveJoint::exp(data.types[i], Hhat, trial.amount);
    for (size_t j = 0; j < M0.size(); ++j) {
      if (!data.inlier[k][j]) {
        continue;
      }
      Eigen::Vector4d s;
      const double e2 =
          data.rig.project(Eigen::Vector4d(H * M0[j]), s) ? (s - trial.s[j]).squaredNorm() : 4.0 * noImage * noImage;
      sum += std::min(e2, cap);
      count += 4;
    }
  }
}

double predictionResidual(const ArmCalibrationData &data, const std::vector<Eigen::Matrix4d> &Hhat,
                          const std::vector<Eigen::Vector4d> &M0)
{
  double sum = 0.0;
  size_t count = 0;
  for (unsigned int i = 0; i < data.types.size(); ++i) {
    accumulateTrialError(data, i, Hhat[i], M0, sum, count);
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : 0.0;
}

std::vector<Eigen::Matrix4d> trialDisplacements(ArmCalibrationData &data)
{
  const std::string where = "vpProjectiveArmAcquisition::calibrate()";
  std::vector<Eigen::Matrix4d> displacements(data.trials.size(),
                                             Eigen::Matrix4d::Constant(std::numeric_limits<double>::quiet_NaN()));
  for (size_t k = 0; k < data.trials.size(); ++k) {
    const ArmTrial &trial = data.trials[k];
    // A blocked joint or a tiny trial leaves the markers where they were: H = I has no logarithm to speak of.
    double motion = 0.0;
    std::vector<Eigen::Vector4d> s0, s1; // the markers the trial shows (all, unless identified markers are missing)
    for (size_t j = 0; j < trial.s.size(); ++j) {
      if (trial.seen[j]) {
        motion += (trial.s[j] - data.zeroImages[j]).squaredNorm();
        s0.push_back(data.zeroImages[j]);
        s1.push_back(trial.s[j]);
      }
    }
    const bool all = s1.size() == trial.s.size();
    motion = std::sqrt(motion / (2.0 * static_cast<double>(s1.size())));
    if (motion < 1.0) {
      std::ostringstream os;
      os << "the trial of joint " << trial.joint << " by " << trial.amount << " moved the markers by only " << motion
         << " px RMS; the joint may be blocked or the trial too small to observe (use 20 to 60 deg)";
      fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
    }
    // Maximum-likelihood displacement: the linear one from 7 noisy markers is too poor a start for the upgrade. 12
    // Levenberg-Marquardt iterations (of about 25 to full convergence) are enough for a start: the bundle adjustment
    // refines everything, and at 1 px noise no acquisition of 300 failed with 12 (one failed with 8).
    try {
      // With an outlier threshold, mismatched markers are found by the 5-point consensus of estimateRobust() and
      // left out of everything that follows (the candidates' scores, the rigid motions, the bundle adjustment).
      if (data.outlierThreshold > 0.0) {
        std::vector<bool> inlier;
        displacements[k] = vpProjectiveDisplacement::estimateRobust(data.rig, all ? data.zeroImages : s0,
                                                                    all ? trial.s : s1, data.outlierThreshold, inlier);
        for (size_t j = 0, m = 0; j < trial.s.size(); ++j) {
          data.inlier[k][j] = trial.seen[j] && inlier[m++];
        }
      } else {
        displacements[k] =
            vpProjectiveDisplacement::estimateFromImages(data.rig, all ? data.zeroImages : s0, all ? trial.s : s1, 12);
      }
    } catch (const vpProjectiveException &) {
      // A noisy homography so far off that it is singular gives no candidate; the joint's other trials, or the rigid
      // motions of its markers in the metric frame (initialTwists()), still do. A trial where too few markers agree on
      // one displacement stays out of the initial model: the model of the other trials decides which of its
      // observations to keep.
      if (data.outlierThreshold > 0.0) {
        data.inlier[k].assign(data.inlier[k].size(), false);
      }
    }
  }
  return displacements;
}

void algebraicGenerators(const ArmCalibrationData &data, const std::vector<Eigen::Vector4d> &M0,
                         const std::vector<Eigen::Matrix4d> &displacements, std::vector<Eigen::Matrix4d> &Hhat)
{
  const std::string where = "vpProjectiveArmAcquisition::calibrate()";
  const size_t n = data.types.size();
  // Candidate generators of each joint: the logarithm of each of its trials, and their projected mean.
  std::vector<std::vector<Eigen::Matrix4d>> candidates(n);
  std::vector<unsigned int> trialCount(n, 0);
  for (size_t k = 0; k < data.trials.size(); ++k) {
    const ArmTrial &trial = data.trials[k];
    ++trialCount[trial.joint];
    if (!displacements[k].allFinite()) {
      continue; // no displacement: no candidate
    }
    try {
      candidates[trial.joint].push_back(
          vpProjectiveJoint::log(data.types[trial.joint], vpProjectiveDisplacement(displacements[k]), trial.amount));
    } catch (const vpProjectiveException &) {
      // A displacement without a logarithm of this joint's kind gives no candidate.
    }
  }
  // A single trial's homography occasionally lands far off (a small marker set gives a poorly conditioned 15-dof
  // fit), which spoils the mean: keep the candidate that best predicts all the trials of its joint.
  Hhat.assign(n, Eigen::Matrix4d::Zero());
  for (size_t i = 0; i < n; ++i) {
    if (trialCount[i] == 0) {
      std::ostringstream os;
      os << "joint " << i << " has no trial motion; call addTrialMotion(" << i << ", amount, left, right) first";
      fail(vpProjectiveException::notInitializedError, where, os.str());
    }
    if (candidates[i].empty()) {
      continue; // Hhat_i = 0: the upgrade leaves joint i out
    }
    Eigen::Matrix4d mean = Eigen::Matrix4d::Zero();
    for (const Eigen::Matrix4d &G : candidates[i]) {
      if (G.allFinite()) {
        mean += G / static_cast<double>(candidates[i].size());
      }
    }
    candidates[i].push_back(vpProjectiveJoint::project(data.types[i], mean));
    double best = std::numeric_limits<double>::quiet_NaN();
    for (const Eigen::Matrix4d &G : candidates[i]) {
      if (!G.allFinite()) {
        continue; // the projection of a degenerate logarithm
      }
      double sum = 0.0;
      size_t count = 0;
      accumulateTrialError(data, static_cast<unsigned int>(i), G, M0, sum, count);
      const double error = sum / static_cast<double>(count);
      if (!(error >= best)) { // the first finite candidate, then any better one
        best = error;
        Hhat[i] = G;
      }
    }
  }
}

std::vector<MetricModel> initialMetricModels(const ArmCalibrationData &data, const std::vector<Eigen::Matrix4d> &Hhat,
                                             const std::vector<Eigen::Vector4d> &M0)
{
  const size_t n = data.types.size();
  std::vector<std::vector<Eigen::Vector4d>> trialPoints(data.trials.size());
  for (size_t k = 0; k < data.trials.size(); ++k) {
    for (size_t j = 0; j < data.trials[k].s.size(); ++j) {
      const Eigen::Vector4d &s = data.trials[k].s[j];
      trialPoints[k].push_back(data.trials[k].seen[j]
                                   ? data.rig.triangulate(Eigen::Vector2d(s.head<2>()), Eigen::Vector2d(s.tail<2>()))
                                   : Eigen::Vector4d::Zero());
    }
  }
  // The upgrade from every joint's generator, then leaving one or two joints out in turn: a joint whose axis is far
  // from a small marker set (the shoulder of an arm) can have a generator too poor for the common plane at infinity
  // and metric conic (at 1 px noise, 6 PUMA acquisitions of 300 failed with every joint in). The candidate that
  // predicts all the trials best starts the bundle adjustment.
  std::vector<std::pair<double, MetricModel>> candidates;
  std::vector<std::vector<bool>> subsets(1, std::vector<bool>(n, true));
  for (size_t a = 0; n >= 3 && a < n; ++a) {
    for (size_t b = a; b < n && (b == a || n >= 4); ++b) {
      std::vector<bool> use(n, true);
      use[a] = false;
      use[b] = false; // b == a: one joint left out
      subsets.push_back(use);
    }
  }
  for (const std::vector<bool> &use : subsets) {
    Eigen::Matrix4d Gc;
    std::vector<Eigen::Vector3d> axisC, pointC;
    if (!metricUpgrade(data, Hhat, use, M0, Gc) || !initialTwists(data, Gc, Hhat, M0, trialPoints, axisC, pointC)) {
      continue;
    }
    const Eigen::Matrix4d GcInv = Gc.inverse();
    std::vector<Eigen::Matrix4d> HhatC(n);
    for (size_t i = 0; i < n; ++i) {
      HhatC[i] = GcInv * vpProjectiveJoint::twist(data.types[i], axisC[i], pointC[i]) * Gc;
    }
    MetricModel candidate;
    candidate.G = Gc;
    candidate.axis = axisC;
    candidate.point = pointC;
    const double residual = predictionResidual(data, HhatC, M0);
    candidates.emplace_back(std::isnan(residual) ? std::numeric_limits<double>::infinity() : residual, candidate);
  }
  if (candidates.empty()) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveArmAcquisition::calibrate()",
         "the affine and metric upgrade of the generators failed; check that the trial motions are large enough and "
         "that the markers are matched in the same order in every image");
  }
  std::stable_sort(candidates.begin(), candidates.end(),
                   [](const std::pair<double, MetricModel> &a, const std::pair<double, MetricModel> &b) {
                     return a.first < b.first;
                   });
  std::vector<MetricModel> starts;
  for (const std::pair<double, MetricModel> &c : candidates) {
    starts.push_back(c.second);
  }
  return starts;
}
} // namespace vpProjectiveInternal
