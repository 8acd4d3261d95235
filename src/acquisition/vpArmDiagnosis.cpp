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
  The diagnosis of a model that the check of vpProjectiveArmAcquisition::calibrate() refuses (vpProjectiveModelCheck):
  each probable cause tried on the acquisition's images where they allow it (the model refitted with the fix), ranked
  by its diagnostic, and the message.
*/

#include "acquisition/vpArmModelCheck.h"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <utility>

#include <visp3/core/vpMath.h>

#include "acquisition/vpProjectiveAcquisitionInternal.h"

using vpProjectiveAcquisitionInternal::jointValue;

namespace vpProjectiveInternal
{
namespace
{
typedef vpProjectiveModelCheck::vpDiagnosis vpDiagnosis;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string number(double x, int precision = 3)
{
  std::ostringstream os;
  os << std::setprecision(precision) << x;
  return os.str();
}

std::string trialName(const ArmCalibrationData &data, int k)
{
  if (k < 0) {
    return "the zero reference";
  }
  const ArmTrial &t = data.trials[static_cast<size_t>(k)];
  return "trial " + std::to_string(k) + " (joint " + std::to_string(t.joint) + " by " +
         jointValue(t.amount, data.types[t.joint] == vpProjectiveJoint::REVOLUTE) + ")";
}

//! The model's residual with the errors of trial \e k replaced by \e trialSquaredError over \e trialCoordinates.
double residualWith(const ArmFit &without, double trialSquaredError, size_t trialCoordinates)
{
  return std::sqrt((without.squaredError + trialSquaredError) /
                   static_cast<double>(without.coordinates + trialCoordinates));
}

vpDiagnosis jointTypeCause(const ArmCheckInput &in, const ArmCheck &check)
{
  vpDiagnosis d = diagnosis(vpProjectiveModelCheck::CAUSE_JOINT_TYPE);
  std::ostringstream finding, fix;
  if (check.contradicted.empty()) {
    finding << (in.identify ? "the types were identified from the images (each joint the type that fits its trials "
                              "better)"
                            : "no joint's trials fit the other type decisively better");
    d.fix = "";
  } else {
    const ArmFit &fixed = check.typesFixed;
    d.joint = static_cast<int>(check.contradicted.front());
    d.residualIfFixed = fixed.ok ? fixed.residual : kNaN;
    d.likely = fixed.ok && (fixed.residual <= check.limit || fixed.residual < 0.5 * check.fit.residual);
    d.evidence = (check.fit.squaredError - fixed.squaredError) / std::pow(std::max(check.noise, 0.05), 2);
    fix << "declare";
    for (size_t c = 0; c < check.contradicted.size(); ++c) {
      const unsigned int i = check.contradicted[c];
      const vpProjectiveModelCheck::vpJointTypeFit &j = check.joints[i];
      const bool slides = j.type == vpProjectiveJoint::REVOLUTE;
      finding << (c > 0 ? "; " : "") << "joint " << i << " (declared " << vpProjectiveJoint::name(j.type) << ") "
              << (slides ? "slides" : "turns") << ": its trials turn the markers by " << number(vpMath::deg(j.turn))
              << " deg while its readings changed by " << jointValue(j.reading, !slides) << ", and fit at "
              << pixelsText(slides ? j.residualPrismatic : j.residualRevolute) << " as "
              << (slides ? "prismatic" : "revolute") << ", " << pixelsText(j.residual) << " as declared";
      fix << (c > 0 ? ", " : " ") << "joint " << i << (slides ? " PRISMATIC" : " REVOLUTE");
    }
    finding << " (with " << (check.contradicted.size() > 1 ? "these types" : "this type") << " changed: model at "
            << pixelsText(d.residualIfFixed) << ")";
    fix << ", or construct the robot or acquisition from the joint count alone (vpProjectiveRobot(n)) to identify the "
           "types from the images";
    d.fix = fix.str();
  }
  d.finding = finding.str();
  return d;
}

vpDiagnosis unitsCause(const ArmCheckInput &in, const ArmCheck &check)
{
  vpDiagnosis d = diagnosis(vpProjectiveModelCheck::CAUSE_READING_UNITS);
  ArmCalibrationData data = in.data;
  data.types = check.fit.data.types;
  std::ostringstream finding;
  bool any = false;
  double worst = 1.0;
  for (unsigned int i = 0; i < check.joints.size(); ++i) {
    const vpProjectiveModelCheck::vpJointTypeFit &j = check.joints[i];
    // A prismatic joint's turn is noise (up to 0.12 rad at 1 px): only a clear turn has a unit.
    if (!(j.turn >= 0.15)) {
      continue;
    }
    const double ratio = j.reading / j.turn;
    worst = std::abs(std::log(ratio)) > std::abs(std::log(worst)) ? ratio : worst;
    if (ratio > 0.6 && ratio < 1.6) {
      continue;
    }
    const bool degrees = ratio > 30.0 && ratio < 120.0;
    const double scale = degrees ? M_PI / 180.0 : 1.0 / ratio;
    for (ArmTrial &t : data.trials) {
      t.amount *= t.joint == i ? scale : 1.0;
    }
    data.types[i] = vpProjectiveJoint::REVOLUTE;
    finding << (any ? "; " : "") << "joint " << i << "'s readings changed by " << number(j.reading, 4)
            << " while its trials turn the markers by " << number(j.turn) << " rad (" << number(vpMath::deg(j.turn))
            << " deg): " << (degrees ? "degrees" : "not radians") << " (" << number(ratio) << " per radian)";
    d.joint = any ? d.joint : static_cast<int>(i);
    any = true;
  }
  d.evidence = worst;
  if (!any) {
    d.finding = "every turning joint's readings agree with its trials' turn, reading / turn " + number(worst);
    return d;
  }
  const ArmFit fixed = fitHypothesis(in, data);
  d.residualIfFixed = fixed.ok ? fixed.residual : kNaN;
  d.likely = fixed.ok && (fixed.residual <= check.limit || fixed.residual < 0.5 * check.fit.residual);
  d.finding = finding.str() + " (readings converted: model at " + pixelsText(d.residualIfFixed) + ")";
  d.fix = "give the joints' readings in radians (vpMath::rad()) and metres, as "
          "vpRobot::getPosition(vpRobot::ARTICULAR_FRAME) does";
  return d;
}

//! \e fit refitted without trial \e k.
ArmFit leaveOut(const ArmFit &fit, size_t k)
{
  ArmCalibrationData data = fit.data;
  data.trials.erase(data.trials.begin() + static_cast<long>(k));
  data.inlier.erase(data.inlier.begin() + static_cast<long>(k));
  return refitData(fit, data);
}

/*!
  The trial that stands out, if any (-1 otherwise), and the model of the other trials (\e without): among the three
  trials that fit worst, above the limit, the one whose leaving out lets the others fit best. (The trial that fits worst
  is not always the culprit: its joint's generator, bent by a wrong trial, misses the joint's right trials too.)
*/
int standingOutTrial(const ArmCheck &check, ArmFit &without)
{
  std::vector<std::pair<double, size_t>> worst;
  for (size_t k = 0; check.fit.ok && k < check.fit.data.trials.size(); ++k) {
    const double r = check.fit.trialResidual(k);
    if (r > check.limit) {
      worst.push_back(std::make_pair(-r, k));
    }
  }
  std::sort(worst.begin(), worst.end());
  int kept = -1;
  for (size_t c = 0; c < worst.size() && c < 3; ++c) {
    ArmFit candidate = leaveOut(check.fit, worst[c].second);
    if (candidate.ok && (kept < 0 || candidate.residual < without.residual)) {
      without = candidate;
      kept = static_cast<int>(worst[c].second);
    }
  }
  return kept;
}

//! Squared error of trial \e k's observations predicted by \e model at readings \e q, and their coordinates.
double trialError(const vpProjectiveArmModel &model, const ArmTrial &trial, const std::vector<bool> &use,
                  const vpProjectiveArmModel::JointVector &q, size_t &coordinates, const std::vector<int> &order)
{
  const Eigen::Matrix4d H = model.displacement(q);
  double sum = 0.0;
  coordinates = 0;
  for (size_t j = 0; j < trial.s.size(); ++j) {
    if (!use[j]) {
      continue;
    }
    Eigen::Vector4d s;
    sum += model.predictMarker(static_cast<unsigned int>(order[j]), H, s) ? (s - trial.s[j]).squaredNorm() : 1e12;
    coordinates += 4;
  }
  return sum;
}

//! The minimum of \e f over [-range, range]: a grid of 41 values, then golden sections around the best.
template <typename F> double minimise(F f, double range, double &best)
{
  double xBest = 0.0;
  best = f(0.0);
  for (int g = -20; g <= 20; ++g) {
    const double x = range * g / 20.0, v = f(x);
    if (v < best) {
      best = v;
      xBest = x;
    }
  }
  double a = xBest - range / 20.0, b = xBest + range / 20.0;
  const double r = 0.5 * (std::sqrt(5.0) - 1.0);
  for (int it = 0; it < 40; ++it) {
    const double c = b - r * (b - a), d = a + r * (b - a);
    if (f(c) < f(d)) {
      b = d;
    } else {
      a = c;
    }
  }
  const double x = 0.5 * (a + b), v = f(x);
  if (v < best) {
    best = v;
    xBest = x;
  }
  return xBest;
}

vpDiagnosis secondJointCause(const ArmCheck &check, int k, const ArmFit &without)
{
  vpDiagnosis d = diagnosis(vpProjectiveModelCheck::CAUSE_SECOND_JOINT);
  if (k < 0 || !without.ok) {
    d.finding = k < 0 ? "no trial stands out: each fits within the limit or as badly as the others"
                      : "the model of the other trials cannot be fitted";
    return d;
  }
  const ArmCalibrationData &data = check.fit.data;
  const ArmTrial &trial = data.trials[static_cast<size_t>(k)];
  const vpProjectiveArmModel &model = without.model;
  const std::vector<bool> &use = data.inlier[static_cast<size_t>(k)];
  std::vector<int> order(trial.s.size());
  for (size_t j = 0; j < order.size(); ++j) {
    order[j] = static_cast<int>(j);
  }
  const vpProjectiveArmModel::JointVector qRef = model.zeroReferenceJoints();
  size_t coordinates = 0;
  double bestError = trialError(model, trial, use,
                                qRef + trial.amount * vpProjectiveArmModel::JointVector::Unit(qRef.size(), trial.joint),
                                coordinates, order);
  const double recorded = std::sqrt(bestError / static_cast<double>(coordinates));
  double bestAmount = 0.0;
  bool alone = false;
  for (unsigned int j = 0; j < model.getNumberOfJoints(); ++j) {
    if (j == trial.joint) {
      continue;
    }
    double range = 0.0;
    for (const ArmTrial &t : data.trials) {
      range = std::max(range, t.joint == j ? 2.0 * std::abs(t.amount) : 0.0);
    }
    for (int withTrialJoint = 1; withTrialJoint >= 0; --withTrialJoint) {
      auto error = [&](double b) {
        vpProjectiveArmModel::JointVector q = qRef;
        q(trial.joint) += withTrialJoint ? trial.amount : 0.0;
        q(j) += b;
        size_t c = 0;
        return trialError(model, trial, use, q, c, order);
      };
      double e = 0.0;
      const double b = minimise(error, range > 0.0 ? range : 1.0, e);
      if (e < bestError) {
        bestError = e;
        bestAmount = b;
        alone = !withTrialJoint;
        d.other = static_cast<int>(j);
      }
    }
  }
  const double r = std::sqrt(bestError / static_cast<double>(coordinates));
  d.trial = k;
  d.joint = static_cast<int>(trial.joint);
  d.evidence = recorded / r;
  if (d.other < 0) {
    d.finding = trialName(data, k) + " fits worst (" + pixelsText(recorded) +
                "), and no motion of a second joint explains it better";
    return d;
  }
  d.residualIfFixed = residualWith(without, bestError, coordinates);
  d.likely = r <= check.limit && d.residualIfFixed <= check.limit;
  const bool revolute = data.types[static_cast<size_t>(d.other)] == vpProjectiveJoint::REVOLUTE;
  d.finding = trialName(data, k) + " fits at " + pixelsText(recorded) + " as recorded, at " + pixelsText(r) +
              (alone ? " if it was joint " + std::to_string(d.other) + " that moved, by "
                     : " if joint " + std::to_string(d.other) + " also moved, by ") +
              jointValue(bestAmount, revolute) + " (the model of the other trials: " + pixelsText(without.residual) +
              ")";
  d.fix = "move one joint alone in each trial, give the trial the joint that moved, and take the readings of every "
          "joint after the motion";
  return d;
}

vpDiagnosis swapCause(const ArmCheckInput &in, const ArmCheck &check, int k, const ArmFit &without)
{
  vpDiagnosis d = diagnosis(vpProjectiveModelCheck::CAUSE_MARKERS_SWAPPED);
  // Left and right images of one marker that no 3D point explains: not the same marker.
  double gap = 0.0;
  for (size_t j = 0; j < in.data.zeroImages.size(); ++j) {
    const double g = std::sqrt(epipolarGap(in.data.rig, in.data.zeroImages[j]));
    if (g > gap) {
      gap = g;
      d.trial = -2;
      d.marker = static_cast<int>(j);
    }
  }
  for (size_t t = 0; t < in.data.trials.size(); ++t) {
    for (size_t j = 0; j < in.data.trials[t].s.size(); ++j) {
      const double g = in.data.trials[t].seen[j] ? std::sqrt(epipolarGap(in.data.rig, in.data.trials[t].s[j])) : 0.0;
      if (g > gap) {
        gap = g;
        d.trial = static_cast<int>(t);
        d.marker = static_cast<int>(j);
      }
    }
  }
  d.evidence = gap / std::max(check.noise, 1e-12);
  std::ostringstream finding;
  finding << "the worst pair of left and right images, marker " << d.marker << " in "
          << trialName(in.data, d.trial == -2 ? -1 : d.trial) << ", is " << pixelsText(gap)
          << " off the epipolar geometry (" << number(d.evidence) << " times the noise)";
  if (d.evidence > 6.0 && gap > 1.0) {
    d.likely = true;
    d.fix = "match each marker's left and right images (the same order in both images), or identify the markers "
            "(tag ids)";
  }
  // Two markers exchanged in the worst trial: their predictions by the model of the other trials, crossed.
  if (k >= 0 && without.ok) {
    const ArmTrial &trial = check.fit.data.trials[static_cast<size_t>(k)];
    const std::vector<bool> &use = check.fit.data.inlier[static_cast<size_t>(k)];
    std::vector<int> order(trial.s.size());
    for (size_t j = 0; j < order.size(); ++j) {
      order[j] = static_cast<int>(j);
    }
    vpProjectiveArmModel::JointVector q = without.model.zeroReferenceJoints();
    q(trial.joint) += trial.amount;
    size_t coordinates = 0;
    const double recorded = trialError(without.model, trial, use, q, coordinates, order);
    double best = recorded;
    for (size_t a = 0; a < order.size(); ++a) {
      for (size_t b = a + 1; b < order.size(); ++b) {
        std::swap(order[a], order[b]);
        size_t c = 0;
        const double e = use[a] && use[b] ? trialError(without.model, trial, use, q, c, order) : recorded;
        if (e < best) {
          best = e;
          d.marker = static_cast<int>(a);
          d.other = static_cast<int>(b);
        }
        std::swap(order[a], order[b]);
      }
    }
    const double r = std::sqrt(best / static_cast<double>(coordinates));
    if (d.other >= 0 && r < 0.5 * std::sqrt(recorded / static_cast<double>(coordinates))) {
      d.trial = k;
      d.residualIfFixed = residualWith(without, best, coordinates);
      d.likely = r <= check.limit;
      d.evidence = std::sqrt(recorded / best);
      finding.str("");
      finding << "markers " << d.marker << " and " << d.other << " are exchanged in " << trialName(in.data, k)
              << ": it fits at " << pixelsText(r) << " with them exchanged, "
              << pixelsText(std::sqrt(recorded / static_cast<double>(coordinates))) << " as given";
      d.fix = "give the markers in the same order in every frame (track each one from frame to frame, or identify "
              "them: tag ids)";
    }
  }
  d.finding = finding.str();
  return d;
}

vpDiagnosis imageErrorsCause(const ArmCheckInput &in, const ArmCheck &check)
{
  vpDiagnosis d = diagnosis(vpProjectiveModelCheck::CAUSE_IMAGE_ERRORS);
  std::ostringstream finding;
  finding << "the images meet the rig's epipolar geometry within " << pixelsText(check.epipolarNoise) << " RMS";
  if (in.givenNoise > 0.0) {
    d.evidence = check.epipolarNoise / in.givenNoise;
    d.likely = d.evidence > 2.0;
    finding << ", " << number(d.evidence) << " times the noise given (" << pixelsText(in.givenNoise) << ")";
  }
  d.finding = finding.str();
  d.fix = "undistort the images (lens distortion is not in the model), check the tracker's accuracy, keep the "
          "cameras still during the acquisition; or raise vpProjectiveArmAcquisition::setResidualTolerance() if "
          "this residual is good enough";
  return d;
}

//! The causes' order: those the diagnostic points at first, then the others, each group by its residual if fixed.
int rank(const vpDiagnosis &d)
{
  if (d.likely) {
    return std::isnan(d.residualIfFixed) ? 1 : 0;
  }
  return std::isnan(d.residualIfFixed) ? 3 : 2;
}
} // namespace

void diagnoseRefusal(const ArmCheckInput &in, ArmCheck &check)
{
  std::vector<vpDiagnosis> causes;
  causes.push_back(jointTypeCause(in, check));
  causes.push_back(unitsCause(in, check));
  ArmFit without;
  const int k = standingOutTrial(check, without);
  causes.push_back(secondJointCause(check, k, without));
  causes.push_back(swapCause(in, check, k, without));
  vpDiagnosis mounting = diagnosis(vpProjectiveModelCheck::CAUSE_MOUNTING);
  mounting.finding = "trials of one joint look the same with the rig on the arm or in the workspace: the mounting "
                     "does not change this residual";
  mounting.fix = "set the mounting (EYE_IN_HAND when the cameras ride on the arm); vpProjectiveAcquisitionProcedure "
                 "tells it by a motion of two joints";
  causes.push_back(mounting);
  causes.push_back(imageErrorsCause(in, check));
  std::stable_sort(causes.begin(), causes.end(), [](const vpDiagnosis &a, const vpDiagnosis &b) {
    return rank(a) < rank(b) || (rank(a) == rank(b) && a.residualIfFixed < b.residualIfFixed);
  });
  check.causes = causes;

  std::ostringstream os;
  os << "the model is refused: ";
  if (check.fit.ok) {
    os << "its residual is " << pixelsText(check.fit.residual) << " RMS";
    for (const vpProjectiveModelCheck::vpJointTypeFit &j : check.joints) {
      if (j.residual > check.limit && !(check.fit.residual > check.limit)) {
        os << ", joint " << (&j - &check.joints[0]) << "'s trials " << pixelsText(j.residual);
      }
    }
  } else {
    os << "no model of the declared joint types fits the images (" << check.fit.failure << ")";
  }
  os << ", and the limit is " << pixelsText(check.limit) << " (" << number(in.tolerance) << " times the image noise, "
     << pixelsText(check.noise)
     << (in.givenNoise > check.epipolarNoise ? " as given"
                                             : " measured against the rig's "
                                               "epipolar geometry")
     << ", at least 0.5 px). Probable causes, likeliest first:";
  int rankNumber = 0;
  for (const vpDiagnosis &d : causes) {
    if (d.likely) {
      os << " (" << ++rankNumber << ") " << vpProjectiveModelCheck::toString(d.cause) << ": " << d.finding
         << (d.fix.empty() ? "" : "; fix: " + d.fix) << ".";
    }
  }
  if (rankNumber == 0) {
    os << " none stands out.";
  }
  os << " Ruled out or untested:";
  for (const vpDiagnosis &d : causes) {
    if (!d.likely) {
      os << " " << vpProjectiveModelCheck::toString(d.cause) << " (" << d.finding << ");";
    }
  }
  check.message = os.str();
}
} // namespace vpProjectiveInternal
