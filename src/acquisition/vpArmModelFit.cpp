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
  The calibration of vpProjectiveArmAcquisition::calibrate() as one step (the algebraic generators, the metric start
  and the bundle adjustment with its outlier rounds), the adjustment started from another model (the hypotheses of
  the joint-type check) and the errors of a model on every observation.
*/

#include "acquisition/vpArmCalibration.h"
#include "acquisition/vpArmModelCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Dense>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveException.h>

namespace vpProjectiveInternal
{
namespace
{
/*!
  Flags the trial observations of \e data that \e model places within the outlier threshold (RMS over the two
  images); true if a flag changed.
*/
bool classifyTrialObservations(const vpProjectiveArmModel &model, ArmCalibrationData &data)
{
  bool changed = false;
  for (size_t k = 0; k < data.trials.size(); ++k) {
    const ArmTrial &trial = data.trials[k];
    const Eigen::Matrix4d H = model.jointExp(trial.joint, trial.amount);
    for (unsigned int j = 0; j < model.markers().size(); ++j) {
      if (!trial.seen[j]) {
        continue; // no observation
      }
      Eigen::Vector4d s;
      const double d = model.predictMarker(j, H, s) ? std::sqrt(0.5 * (s - trial.s[j]).squaredNorm())
                                                    : std::numeric_limits<double>::infinity();
      const bool inlier = d <= data.outlierThreshold;
      changed = changed || inlier != data.inlier[k][j];
      data.inlier[k][j] = inlier;
    }
  }
  return changed;
}

/*!
  The bundle adjustment of \e data from \e start and, with an outlier threshold, its rounds of outlier classification
  (fitArmModel()); \e quick adjustments (bundleAdjust()) compare starts.
*/
vpProjectiveArmModel adjustFrom(ArmCalibrationData &data, const std::vector<Eigen::Vector4d> &M0,
                                const MetricModel &start, const vpProjectiveArmModel::JointVector &qRef,
                                double &residual, bool quick)
{
  if (!(data.outlierThreshold > 0.0)) {
    return bundleAdjust(data, M0, start, false, qRef, residual, quick);
  }
  // Every trial observation, mismatches down-weighted by a robust loss; then least squares on exactly those the model
  // accepts, until that set no longer changes (at most 3 rounds). Each adjustment refines the rig too: the next one
  // starts from its frame.
  vpProjectiveArmModel model = bundleAdjust(data, M0, start, true, qRef, residual, quick);
  data.rig = model.getStereoRig();
  classifyTrialObservations(model, data);
  model = bundleAdjust(data, model.markers(), metricModelOf(model), false, qRef, residual, quick);
  data.rig = model.getStereoRig();
  for (int round = 0; round < 2 && classifyTrialObservations(model, data); ++round) {
    model = bundleAdjust(data, model.markers(), metricModelOf(model), false, qRef, residual, quick);
    data.rig = model.getStereoRig();
  }
  return model;
}
} // namespace

MetricModel metricModelOf(const vpProjectiveArmModel &model)
{
  MetricModel m;
  m.G = model.projectiveToMetric();
  for (unsigned int i = 0; i < model.getNumberOfJoints(); ++i) {
    m.axis.push_back(model.axis(i));
    m.point.push_back(model.point(i));
  }
  return m;
}

vpProjectiveArmModel fitArmModel(ArmCalibrationData &data, const std::vector<Eigen::Vector4d> &M0,
                                 const std::vector<Eigen::Matrix4d> &displacements,
                                 const vpProjectiveArmModel::JointVector &qRef, double &residual,
                                 double &algebraicResidual)
{
  std::vector<Eigen::Matrix4d> Hhat;
  algebraicGenerators(data, M0, displacements, Hhat);
  algebraicResidual = predictionResidual(data, Hhat, M0);
  const std::vector<MetricModel> starts = initialMetricModels(data, Hhat, M0);
  ArmCalibrationData kept = data;
  vpProjectiveArmModel model = adjustFrom(kept, M0, starts[0], qRef, residual, false);
  // The start that predicts the trials best can lead the adjustment to a local minimum pixels off the images: from a
  // PUMA eye-in-hand acquisition of 4-8 deg trials at 0.3 px noise, 2.24 px from the best of 22 starts, 0.27 px from
  // the 8th. A residual that the noise does not explain (a right model ends near the noise, below 1.05 times it in the
  // model-check study) tries the others (quick adjustments, until one ends within 1.3 times the noise); the best of
  // them is adjusted fully, and the lower residual is kept. Fits from scratch get this search (the model check's
  // hypotheses of fitHypothesis()); refits from another hypothesis's model (refitArmModel()) do not.
  const double expected = 1.3 * std::max(epipolarNoise(data), 0.05);
  if (residual > expected) {
    size_t best = 0;
    double bestResidual = residual;
    for (size_t c = 1; c < starts.size() && bestResidual > expected; ++c) {
      ArmCalibrationData other = data;
      double r = std::numeric_limits<double>::infinity();
      try {
        adjustFrom(other, M0, starts[c], qRef, r, true);
      } catch (const vpProjectiveException &) {
        continue; // no model from this start
      }
      if (r < bestResidual) {
        best = c;
        bestResidual = r;
      }
    }
    if (best > 0) {
      ArmCalibrationData other = data;
      double r = std::numeric_limits<double>::infinity();
      try {
        const vpProjectiveArmModel alternative = adjustFrom(other, M0, starts[best], qRef, r, false);
        if (r < residual) {
          model = alternative;
          residual = r;
          kept = other;
        }
      } catch (const vpProjectiveException &) {
        // the full adjustment failed where the quick one did not: the first model stands
      }
    }
  }
  data = kept;
  return model;
}

vpProjectiveArmModel refitArmModel(const ArmCalibrationData &data, const vpProjectiveArmModel &from, double &residual,
                                   bool quick)
{
  MetricModel start = metricModelOf(from);
  // The markers' centroid and the left camera's centre in the metric frame of G, where points are finite (w != 0).
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector4d &M : from.markers()) {
    const Eigen::Vector4d N = start.G * M;
    centroid += N.head<3>() / (N(3) * static_cast<double>(from.markers().size()));
  }
  // The left camera's centre: the null vector of its projection ((0, 0, 0, 1) for the canonical [I | 0]).
  vpProjectiveStereoRig::Projection P;
  from.getStereoRig().getLeftProjection(P);
  const Eigen::JacobiSVD<Eigen::Matrix<double, 3, 4>> svd(P, Eigen::ComputeFullV);
  const Eigen::Vector4d C = start.G * svd.matrixV().col(3);
  const Eigen::Vector3d sight = (centroid - C.head<3>() / C(3)).normalized();
  for (unsigned int i = 0; i < from.getNumberOfJoints(); ++i) {
    if (data.types[i] == from.jointType(i)) {
      continue;
    }
    if (data.types[i] == vpProjectiveJoint::PRISMATIC) {
      // The revolute motion of the centroid per unit of the reading: w x (c - p).
      start.axis[i] = from.axis(i).cross(centroid - from.point(i));
      start.point[i] = Eigen::Vector3d::Zero();
    } else {
      // A revolute axis w perpendicular to the motion t and to the line of sight, through p = c - |t| (t^ x w): then
      // w x (c - p) = t, the same motion of the centroid per unit of the reading.
      const Eigen::Vector3d t = from.axis(i);
      Eigen::Vector3d w = t.cross(sight);
      if (!(w.norm() > 1e-9 * t.norm())) {
        w = t.unitOrthogonal();
      }
      w.normalize();
      start.axis[i] = w;
      start.point[i] = centroid - t.norm() * t.normalized().cross(w);
    }
  }
  ArmCalibrationData refit = data;
  refit.rig = from.getStereoRig();
  return bundleAdjust(refit, from.markers(), start, false, from.zeroReferenceJoints(), residual, quick);
}

ObservationErrors observationErrors(const vpProjectiveArmModel &model, const ArmCalibrationData &data)
{
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  ObservationErrors e;
  const Eigen::Matrix4d I = Eigen::Matrix4d::Identity();
  for (unsigned int j = 0; j < data.zeroImages.size(); ++j) {
    Eigen::Vector4d s;
    e.zero.push_back(model.predictMarker(j, I, s) ? (s - data.zeroImages[j]).squaredNorm() : inf);
  }
  for (size_t k = 0; k < data.trials.size(); ++k) {
    const ArmTrial &trial = data.trials[k];
    const Eigen::Matrix4d H = model.jointExp(trial.joint, trial.amount);
    e.trial.emplace_back(trial.s.size(), nan);
    for (unsigned int j = 0; j < trial.s.size(); ++j) {
      Eigen::Vector4d s;
      if (data.inlier[k][j]) {
        e.trial[k][j] = model.predictMarker(j, H, s) ? (s - trial.s[j]).squaredNorm() : inf;
      }
    }
  }
  return e;
}
} // namespace vpProjectiveInternal
