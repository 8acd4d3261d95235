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
  The joint types of the model check (vpProjectiveModelCheck): what each joint's trials show (the rotation angle of
  their displacements against the readings), and the refits that compare the two types of a joint whose type is in
  doubt: the identification of unknown types, the contradiction of declared ones.
*/

#include "acquisition/vpArmModelCheck.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace vpProjectiveInternal
{
namespace
{
const double kNaN = std::numeric_limits<double>::quiet_NaN();

//! What a joint's trials show: their displacements' mean rotation angle, their readings' mean absolute change (as
//! read, and folded into [0, pi] as a revolute joint's angle).
struct JointMotion {
  double turn = kNaN;
  double reading = 0.0;
  double angle = 0.0;
};

std::vector<JointMotion> jointMotions(const ArmCheckInput &in)
{
  const size_t n = in.data.types.size();
  std::vector<JointMotion> motion(n);
  std::vector<double> turnSum(n, 0.0);
  std::vector<unsigned int> turns(n, 0), trials(n, 0);
  for (size_t k = 0; k < in.data.trials.size(); ++k) {
    const ArmTrial &trial = in.data.trials[k];
    const double turn = turnAngle(in.displacements[k]);
    if (!std::isnan(turn)) {
      turnSum[trial.joint] += turn;
      ++turns[trial.joint];
    }
    motion[trial.joint].reading += std::abs(trial.amount);
    motion[trial.joint].angle += std::abs(std::remainder(trial.amount, 2.0 * M_PI));
    ++trials[trial.joint];
  }
  for (size_t i = 0; i < n; ++i) {
    if (turns[i] > 0) {
      motion[i].turn = turnSum[i] / turns[i];
    }
    if (trials[i] > 0) {
      motion[i].reading /= trials[i];
      motion[i].angle /= trials[i];
    }
  }
  return motion;
}

/*!
  The trials turn the markers by more than the noise of the turn can fake (at 1 px of image noise the displacements
  of a prismatic joint turn by up to 0.12 rad): by their readings and 0.2 rad, or by 0.3 rad whatever the readings say
  (readings in other units: a revolute joint all the same). No need to try the other type.
*/
bool clearlyTurns(const JointMotion &m)
{
  return m.turn >= 0.3 || (m.turn >= 0.2 && std::abs(m.turn - m.angle) <= 0.25 * m.angle + 0.05);
}

//! The first guess of an unknown type: the turn nearer the reading's angle than zero.
vpProjectiveJoint::vpJointType guessType(const JointMotion &m)
{
  return std::isnan(m.turn) || m.turn >= 0.5 * m.angle ? vpProjectiveJoint::REVOLUTE : vpProjectiveJoint::PRISMATIC;
}

std::vector<vpProjectiveJoint::vpJointType> flipped(std::vector<vpProjectiveJoint::vpJointType> types,
                                                    const std::vector<unsigned int> &joints)
{
  for (unsigned int i : joints) {
    types[i] = otherType(types[i]);
  }
  return types;
}

//! A fit that replaces declared types: better by 16 sigma^2 of squared error and by 10 %.
bool decisivelyBetter(const ArmFit &other, const ArmFit &declared, double sigma)
{
  return declared.squaredError - other.squaredError > 16.0 * sigma * sigma &&
         other.squaredError < 0.9 * declared.squaredError;
}

//! The better of two fits (the lower squared error; \e a on a tie).
const ArmFit &better(const ArmFit &a, const ArmFit &b)
{
  return b.squaredError < a.squaredError ? b : a;
}

/*!
  The fit with the joints \e joints changed from \e base's types: from scratch, and for several joints also from the
  best single change \e start: the better.
*/
ArmFit combined(const ArmCheckInput &in, const ArmFit &base, const ArmFit &start,
                const std::vector<unsigned int> &joints)
{
  ArmCalibrationData data = in.data;
  data.types = flipped(base.data.types, joints);
  const ArmFit scratch = fitHypothesis(in, data);
  if (joints.size() < 2) {
    return better(scratch, start);
  }
  return better(scratch, refitHypothesis(in, start, data.types));
}
} // namespace

void settleJointTypes(const ArmCheckInput &in, ArmCheck &check)
{
  const size_t n = in.data.types.size();
  const std::vector<JointMotion> motion = jointMotions(in);
  const double sigma = std::max(check.noise, 0.05); // px: the scale of the evidence, finite without noise
  ArmCalibrationData start = in.data;
  if (in.identify) {
    for (size_t i = 0; i < n; ++i) {
      start.types[i] = guessType(motion[i]);
    }
  }
  ArmFit base = fitHypothesis(in, start);
  for (unsigned int i = 0; in.identify && !base.ok && i < n; ++i) {
    base = fitHypothesis(in, [&]() {
      ArmCalibrationData d = start;
      d.types[i] = otherType(d.types[i]);
      return d;
    }());
  }
  // The joints whose type is in doubt.
  bool refused = !base.ok || base.residual > check.limit;
  for (unsigned int i = 0; i < n && !refused; ++i) {
    refused = base.jointResidual(i) > check.limit;
  }
  std::vector<bool> test(n, false);
  for (unsigned int i = 0; i < n; ++i) {
    const JointMotion &m = motion[i];
    if (clearlyTurns(m) && base.data.types[i] == vpProjectiveJoint::REVOLUTE) {
      continue; // a prismatic joint does not turn its markers
    }
    const double r = base.jointResidual(i);
    const bool looksOther = base.data.types[i] == vpProjectiveJoint::REVOLUTE ? !(m.turn >= 0.5 * m.angle) // it slides
                                                                              : m.turn >= 0.2;             // it turns
    // Its trials fit worse than the noise or the other joints' trials (above 0.05 px: not noise-free images).
    const bool worse = r > 0.05 && (r > 1.25 * check.noise || r > 1.25 * base.otherJointsResidual(i));
    test[i] = in.identify || refused || looksOther || worse;
  }
  // Rounds: each doubtful joint fitted with the other type against the current types; the joints whose other type fits
  // better (unknown types), or decisively better (declared ones: by 16 sigma^2 and 10 %), change together; again
  // against the new types, until no joint changes (several wrong types spoil each other's single changes).
  std::vector<ArmFit> other(n);
  std::vector<unsigned int> changed;
  ArmFit current = base;
  for (size_t round = 0; round < n; ++round) {
    std::vector<unsigned int> improving;
    const ArmFit *bestSingle = &current;
    for (unsigned int i = 0; i < n; ++i) {
      if (!test[i]) {
        continue;
      }
      other[i] = refitHypothesis(in, current, flipped(current.data.types, {i}));
      const bool changes =
          in.identify ? other[i].squaredError < current.squaredError : decisivelyBetter(other[i], current, sigma);
      if (changes) {
        improving.push_back(i);
        bestSingle = &better(*bestSingle, other[i]);
      }
    }
    if (improving.empty()) {
      break;
    }
    current = better(*bestSingle, combined(in, current, *bestSingle, improving));
    for (unsigned int i : improving) {
      const std::vector<unsigned int>::iterator it = std::find(changed.begin(), changed.end(), i);
      if (it == changed.end()) {
        changed.push_back(i);
      } else {
        changed.erase(it); // changed back
      }
    }
    for (unsigned int i = 0; i < n; ++i) {
      other[i] = ArmFit(); // of the previous types
    }
  }
  // The other type of each doubtful joint against the types kept, for the report.
  for (unsigned int i = 0; i < n; ++i) {
    if (test[i] && !other[i].ok && current.ok) {
      other[i] = refitHypothesis(in, current, flipped(current.data.types, {i}));
    }
  }
  std::sort(changed.begin(), changed.end());
  if (in.identify && current.quick) {
    current = refitData(current, current.data, false); // the model kept: a full adjustment
  }
  ArmFit kept = in.identify ? current : base;
  if (!in.identify && !changed.empty()) {
    check.contradicted = changed;
    check.typesFixed = current;
  }
  check.fit = kept;
  check.joints.resize(n);
  for (unsigned int i = 0; i < n; ++i) {
    vpProjectiveModelCheck::vpJointTypeFit &joint = check.joints[i];
    joint.type = kept.data.types[i];
    joint.declared = !in.identify;
    joint.contradicted = std::find(check.contradicted.begin(), check.contradicted.end(), i) != check.contradicted.end();
    joint.turn = motion[i].turn;
    joint.reading = motion[i].reading;
    joint.residual = kept.ok ? kept.jointResidual(i) : kNaN;
    // The other type: the types fixed for a contradicted joint, else the refit with this joint changed.
    const ArmFit &otherFit = joint.contradicted ? check.typesFixed : other[i];
    const double otherResidual = otherFit.ok ? otherFit.jointResidual(i) : kNaN;
    joint.residualRevolute = joint.type == vpProjectiveJoint::REVOLUTE ? joint.residual : otherResidual;
    joint.residualPrismatic = joint.type == vpProjectiveJoint::PRISMATIC ? joint.residual : otherResidual;
    joint.evidence =
        test[i] && (kept.ok || otherFit.ok) ? (otherFit.squaredError - kept.squaredError) / (sigma * sigma) : kNaN;
  }
}
} // namespace vpProjectiveInternal
