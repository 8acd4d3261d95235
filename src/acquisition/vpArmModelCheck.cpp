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
  The model check of vpProjectiveArmAcquisition::calibrate() (vpProjectiveModelCheck): the hypotheses' fits and their
  errors, the image noise of the acquisition's images, and the gate.
*/

#include "acquisition/vpArmModelCheck.h"

#include <algorithm>
#include <cmath>
#include <complex>
#include <iomanip>
#include <limits>
#include <sstream>

#include <Eigen/Eigenvalues>

#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveException.h>

namespace vpProjectiveInternal
{
namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();
const double kInfinity = std::numeric_limits<double>::infinity();
//! The limit's floor (px): a model within half a pixel is never refused.
const double kLimitFloor = 0.5;

//! RMS per coordinate of the finite errors of \e e that \e use selects (NaN if none).
template <typename Select> double rmsOf(const ObservationErrors &e, const ArmCalibrationData &data, Select use)
{
  double sum = 0.0;
  size_t count = 0;
  for (size_t k = 0; k < e.trial.size(); ++k) {
    if (!use(data.trials[k].joint, k)) {
      continue;
    }
    for (double e2 : e.trial[k]) {
      if (!std::isnan(e2)) {
        sum += e2;
        count += 4;
      }
    }
  }
  return count > 0 ? std::sqrt(sum / static_cast<double>(count)) : kNaN;
}

//! The squared errors' sum and coordinates of \e fit, from its model.
void measure(ArmFit &fit)
{
  fit.errors = observationErrors(fit.model, fit.data);
  fit.squaredError = 0.0;
  fit.coordinates = 0;
  for (double e2 : fit.errors.zero) {
    fit.squaredError += e2;
    fit.coordinates += 4;
  }
  for (const std::vector<double> &trial : fit.errors.trial) {
    for (double e2 : trial) {
      if (!std::isnan(e2)) {
        fit.squaredError += e2;
        fit.coordinates += 4;
      }
    }
  }
}

//! Runs \e fitting into \e fit: a failure of the estimation is recorded in \e fit, another error is thrown.
template <typename Fitting> void attempt(ArmFit &fit, Fitting fitting)
{
  try {
    fitting();
    fit.ok = true;
    measure(fit);
  } catch (const vpProjectiveException &e) {
    if (e.getCode() != vpProjectiveException::estimationFailedError &&
        e.getCode() != vpProjectiveException::degenerateConfigurationError) {
      throw;
    }
    fit.ok = false;
    fit.failure = e.getStringMessage();
    fit.failureCode = e.getCode();
    fit.squaredError = kInfinity;
    fit.residual = kInfinity;
  }
}
} // namespace

double ArmFit::jointResidual(unsigned int i) const
{
  return rmsOf(errors, data, [i](unsigned int joint, size_t) { return joint == i; });
}

double ArmFit::trialResidual(size_t k) const
{
  return rmsOf(errors, data, [k](unsigned int, size_t trial) { return trial == k; });
}

double ArmFit::otherJointsResidual(unsigned int i) const
{
  return rmsOf(errors, data, [i](unsigned int joint, size_t) { return joint != i; });
}

ArmFit fitHypothesis(const ArmCheckInput &in, const ArmCalibrationData &data)
{
  ArmFit fit;
  fit.data = data;
  attempt(fit, [&]() {
    fit.model = fitArmModel(fit.data, in.M0, in.displacements, in.qRef, fit.residual, fit.algebraicResidual);
  });
  return fit;
}

ArmFit refitHypothesis(const ArmCheckInput &in, const ArmFit &from,
                       const std::vector<vpProjectiveJoint::vpJointType> &types)
{
  if (!from.ok) {
    ArmCalibrationData data = in.data;
    data.types = types;
    return fitHypothesis(in, data);
  }
  ArmCalibrationData data = from.data;
  data.types = types;
  return refitData(from, data);
}

ArmFit refitData(const ArmFit &from, const ArmCalibrationData &data, bool quick)
{
  ArmFit fit;
  fit.data = data;
  fit.quick = quick;
  fit.algebraicResidual = from.algebraicResidual;
  attempt(fit, [&]() {
    fit.model = refitArmModel(fit.data, from.model, fit.residual, quick);
    fit.data.rig = fit.model.getStereoRig();
  });
  return fit;
}

double epipolarGap(const vpProjectiveStereoRig &rig, const Eigen::Vector4d &s)
{
  Eigen::Vector4d p;
  const Eigen::Vector4d M = rig.triangulate(Eigen::Vector2d(s.head<2>()), Eigen::Vector2d(s.tail<2>()));
  return rig.project(M, p) ? (p - s).squaredNorm() : kInfinity;
}

double epipolarNoise(const ArmCalibrationData &data, bool exchanged)
{
  std::vector<double> gaps;
  const auto gap = [&](const Eigen::Vector4d &s) {
    return epipolarGap(data.rig, exchanged ? Eigen::Vector4d(s(2), s(3), s(0), s(1)) : s);
  };
  for (const Eigen::Vector4d &s : data.zeroImages) {
    gaps.push_back(gap(s));
  }
  for (const ArmTrial &trial : data.trials) {
    for (size_t j = 0; j < trial.s.size(); ++j) {
      if (trial.seen[j]) {
        gaps.push_back(gap(trial.s[j]));
      }
    }
  }
  if (gaps.size() < 5) {
    return 0.0;
  }
  // The mean of chi^2_1 over its smallest 90 %: P(chi^2_3 < q90) / 0.9 with q90 = 2.7055 the 90th percentile of
  // chi^2_1 (E[X; X < q] = P(chi^2_3 < q) for X ~ chi^2_1).
  const double trimmedMean = 0.6233;
  std::sort(gaps.begin(), gaps.end());
  const size_t kept = std::max<size_t>(1, (gaps.size() * 9) / 10);
  double sum = 0.0;
  for (size_t m = 0; m < kept; ++m) {
    sum += gaps[m];
  }
  return std::sqrt(sum / (static_cast<double>(kept) * trimmedMean));
}

double turnAngle(const Eigen::Matrix4d &H)
{
  if (!H.allFinite()) {
    return kNaN;
  }
  const Eigen::EigenSolver<Eigen::Matrix4d> eig(H, false);
  if (eig.info() != Eigen::Success) {
    return kNaN;
  }
  double angle = 0.0;
  for (int k = 0; k < 4; ++k) {
    angle = std::max(angle, std::abs(std::arg(eig.eigenvalues()(k))));
  }
  return angle;
}

std::string pixelsText(double px)
{
  std::ostringstream os;
  os << std::setprecision(3) << px << " px";
  return os.str();
}

vpProjectiveModelCheck::vpDiagnosis diagnosis(vpProjectiveModelCheck::vpCause cause)
{
  vpProjectiveModelCheck::vpDiagnosis d;
  d.cause = cause;
  d.likely = false;
  d.residualIfFixed = kNaN;
  d.evidence = kNaN;
  d.joint = d.trial = d.marker = d.other = -1;
  return d;
}

bool refuseExchangedImages(const ArmCheckInput &in, ArmCheck &check)
{
  const double exchanged = epipolarNoise(in.data, true);
  if (!(exchanged < 0.5 * check.epipolarNoise)) {
    return false;
  }
  vpProjectiveModelCheck::vpDiagnosis d = diagnosis(vpProjectiveModelCheck::CAUSE_IMAGES_EXCHANGED);
  d.likely = true;
  d.evidence = check.epipolarNoise / exchanged;
  std::ostringstream finding;
  finding << "the images meet the rig's epipolar geometry within " << pixelsText(exchanged)
          << " RMS with left and right exchanged, " << pixelsText(check.epipolarNoise) << " as given";
  d.finding = finding.str();
  d.fix = "give each frame's left camera image first, in the order of the rig's fundamental matrix (m'^T F m = 0, m "
          "in the left image), or estimate the rig from images in the acquisition's order";
  check.exchanged = true;
  check.accepted = false;
  check.causes.assign(1, d);
  check.message = "the model is refused: left and right images are swapped against the rig (" + d.finding +
                  "); fix: " + d.fix + ".";
  return true;
}

ArmCheck checkArmModel(const ArmCheckInput &in)
{
  ArmCheck check;
  check.epipolarNoise = epipolarNoise(in.data);
  check.noise = std::max(check.epipolarNoise, in.givenNoise);
  check.limit = in.tolerance > 0.0 ? std::max(in.tolerance * check.noise, kLimitFloor) : kInfinity;
  if (in.tolerance > 0.0 && refuseExchangedImages(in, check)) {
    return check; // a model of the exchanged cameras would fit them, and mislead the servo: refused before any fit
  }
  settleJointTypes(in, check);
  bool within = check.fit.ok && check.fit.residual <= check.limit;
  for (const vpProjectiveModelCheck::vpJointTypeFit &joint : check.joints) {
    within = within && !(joint.residual > check.limit);
  }
  check.accepted = within && (check.contradicted.empty() || !(in.tolerance > 0.0));
  if (check.accepted) {
    std::ostringstream os;
    os << "model accepted: residual " << pixelsText(check.fit.residual) << " RMS within the limit "
       << pixelsText(check.limit) << " (image noise " << pixelsText(check.noise) << "); joint types "
       << (in.identify ? "identified from the images" : "as declared (no trial contradicts them)");
    check.message = os.str();
  } else {
    diagnoseRefusal(in, check);
  }
  return check;
}
} // namespace vpProjectiveInternal
