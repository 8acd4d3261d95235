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

#include <visp3/projective/vpProjectivePathPlanner.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveInverseKinematics.h>

#include "core/vpProjectiveErrors.h"
#include "servo/vpProjectivePathPlannerInternal.h"

using namespace vpProjectiveInternal;

namespace
{

//! Number of configurations drawn in the search of a waypoint.
const unsigned int kWaypointDraws = 200;
//! Factor of the inverse kinematics' starts in its second round, when no path leads to a branch of the first.
const unsigned int kMoreStarts = 8;
//! Largest pixel motion of a feature per step of the tracking of the inverse kinematics toward s*.
const double kTrackingPixels = 25.0;
//! Bounds of the number of steps of that tracking.
const int kTrackingMinSteps = 4, kTrackingMaxSteps = 32;

/*
  The inverse kinematics tracked along straight image lines from the features at q to s* (each step warm-started at
  the previous one): a configuration in the branch that the motion from q meets first, the natural target, which the
  uniform starts of solveAll() in a wide joint box can all miss (the Viper850's sixth joint spans 720 deg). Jumps are
  allowed here: only the end matters, as a start of the inverse kinematics. Returns false if the tracking failed.
*/
bool trackToDesired(const vpProjectiveArmModel &model, const vpProjectiveArmModel::JointVector &q,
                    const std::vector<Eigen::Vector4d> &points, const std::vector<Eigen::Vector4d> &sStar,
                    vpProjectiveArmModel::JointVector &end)
{
  const Eigen::Matrix4d H = model.displacement(q);
  std::vector<Eigen::Vector4d> s0(points.size()), s(points.size());
  double largest = 0.0;
  for (size_t k = 0; k < points.size(); ++k) {
    if (!model.getStereoRig().project(Eigen::Vector4d(H * points[k]), s0[k])) {
      return false;
    }
    largest = std::max(largest, (sStar[k] - s0[k]).cwiseAbs().maxCoeff());
  }
  const int steps =
      std::min(kTrackingMaxSteps, std::max(kTrackingMinSteps, static_cast<int>(std::ceil(largest / kTrackingPixels))));
  end = q;
  try {
    for (int j = 1; j <= steps; ++j) {
      const double t = static_cast<double>(j) / steps;
      for (size_t k = 0; k < points.size(); ++k) {
        s[k] = (1.0 - t) * s0[k] + t * sStar[k];
      }
      end = vpProjectiveInverseKinematics::solve(model, s, points, end);
    }
  } catch (const vpProjectiveException &) {
    return false;
  }
  return end.allFinite();
}
} // namespace

vpProjectivePathPlanner::JointVector vpProjectivePathPlanner::nearestRepresentative(const vpProjectiveArmModel &model,
                                                                                    const JointVector &branch,
                                                                                    const JointVector &q)
{
  JointVector t = branch;
  for (Eigen::Index i = 0; i < q.size(); ++i) {
    if (model.jointType(static_cast<unsigned int>(i)) == vpProjectiveJoint::REVOLUTE) {
      t(i) = q(i) + std::remainder(t(i) - q(i), 2.0 * M_PI);
    }
  }
  return t;
}

std::vector<std::pair<vpProjectivePathPlanner::JointVector, unsigned int>>
vpProjectivePathPlanner::targetCandidates(const vpProjectiveArmModel &model, const JointVector &q,
                                          const std::vector<Eigen::Vector4d> &points, bool &anyInside) const
{
  // Each branch's representative nearest to q (revolute joints modulo a turn; another turn if the nearest is outside
  // the limits and that one inside); those inside the limits with the features in view, the ones with every joint
  // out of the margins first, each group by its distance to q. All of them: when no path leads to the nearest (a
  // feature would leave the view on the way), another branch of the same pose may have one.
  std::vector<std::pair<double, std::pair<JointVector, unsigned int>>> ranked;
  std::vector<Eigen::Vector4d> s;
  anyInside = false;
  // The branch the images refused (setRefusedTarget()): the one nearest to where the law stalled, if near.
  size_t refused = m_branches.size();
  double nearest = m_refusedRadius;
  for (size_t b = 0; m_refused.size() == q.size() && b < m_branches.size(); ++b) {
    const double d = (nearestRepresentative(model, m_branches[b], m_refused) - m_refused).cwiseAbs().maxCoeff();
    if (d < nearest) {
      nearest = d;
      refused = b;
    }
  }
  for (size_t b = 0; b < m_branches.size(); ++b) {
    if (b == refused) {
      continue;
    }
    JointVector t = nearestRepresentative(model, m_branches[b], q);
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      if (model.jointType(static_cast<unsigned int>(i)) != vpProjectiveJoint::REVOLUTE) {
        continue;
      }
      for (double turn : {-2.0 * M_PI, 2.0 * M_PI}) {
        if (m_hasLimits && (t(i) < m_qmin(i) || t(i) > m_qmax(i)) && t(i) + turn >= m_qmin(i) &&
            t(i) + turn <= m_qmax(i)) {
          t(i) += turn;
        }
      }
    }
    if (!inside(t)) {
      continue;
    }
    anyInside = true;
    if (!visible(model, t, points, s)) {
      continue;
    }
    bool inMargin = false;
    for (Eigen::Index i = 0; m_hasLimits && i < q.size(); ++i) {
      const double margin = m_limitMargin * (m_qmax(i) - m_qmin(i));
      inMargin = inMargin || t(i) < m_qmin(i) + margin || t(i) > m_qmax(i) - margin;
    }
    // The margin ranks first: a branch in it comes after every branch out of it.
    const double rank = (t - q).norm() + (inMargin ? 1e6 : 0.0);
    ranked.emplace_back(rank, std::make_pair(t, static_cast<unsigned int>(b)));
  }
  std::stable_sort(ranked.begin(), ranked.end(),
                   [](const std::pair<double, std::pair<JointVector, unsigned int>> &a,
                      const std::pair<double, std::pair<JointVector, unsigned int>> &b) { return a.first < b.first; });
  std::vector<std::pair<JointVector, unsigned int>> candidates;
  for (const auto &r : ranked) {
    candidates.push_back(r.second);
  }
  return candidates;
}

bool vpProjectivePathPlanner::planPath(const vpProjectiveArmModel &model, const JointVector &q,
                                       const JointVector &target, const std::vector<JointVector> &rehearsed,
                                       const std::vector<Eigen::Vector4d> &points, const JointVector &qmin,
                                       const JointVector &qmax, std::vector<JointVector> &path,
                                       std::vector<std::vector<Eigen::Vector4d>> &features, vpPathKind &kind,
                                       bool corners) const
{
  if (corners) {
    // A path of several corners: where no single corner turns the joint-space line around the view's and the limits'
    // obstacles (a wide task whose three close markers leave the window on every one-corner detour).
    kind = PATH_WAYPOINT;
    return connectPath(model, q, target, points, qmin, qmax, path, features);
  }
  if (imagePath(model, q, target, points, path) && feasible(model, path, points, features)) {
    kind = PATH_IMAGE_LINE;
    return true;
  }
  if (feasible(model, path = jointLine(q, target), points, features)) {
    kind = PATH_JOINT_LINE;
    return true;
  }
  // A waypoint among configurations inside the limits with the features in view: the shortest feasible. Drawn about
  // the middle of the joint-space line, in a box that grows from nothing to the whole of the limits over the draws:
  // the short detours are tried densely before the long ones.
  vpUniRand uniform(0x5eedULL);
  double shortest = std::numeric_limits<double>::infinity();
  std::vector<Eigen::Vector4d> s;
  const JointVector middle = 0.5 * (q + target);
  for (unsigned int draw = 0; draw < kWaypointDraws; ++draw) {
    const double spread = (draw + 1.0) / kWaypointDraws;
    JointVector w(q.size());
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      w(i) = middle(i) + spread * uniform.uniform(qmin(i) - middle(i), qmax(i) - middle(i));
    }
    const double length = (w - q).norm() + (target - w).norm();
    if (!(length < shortest) || !inside(w) || !visible(model, w, points, s)) {
      continue;
    }
    std::vector<JointVector> candidate = jointLine(q, w), second = jointLine(w, target);
    candidate.insert(candidate.end(), second.begin() + 1, second.end());
    std::vector<std::vector<Eigen::Vector4d>> candidateFeatures;
    if (feasible(model, candidate, points, candidateFeatures)) {
      shortest = length;
      path = candidate;
      features = candidateFeatures;
    }
  }
  kind = PATH_WAYPOINT;
  if (shortest < std::numeric_limits<double>::infinity()) {
    return true;
  }
  // Law (47)'s rehearsal as the way there: its configurations are inside the limits with the features in view, and
  // where the law stalls (a local minimum of three points, a slow law) or leaves the view, the target is often a
  // straight joint-space line away. From its last configuration back, the first from which that line is feasible,
  // the rehearsal's steps resampled to the path's step before it.
  for (size_t j = rehearsed.size(); j-- > 1;) {
    std::vector<std::vector<Eigen::Vector4d>> candidateFeatures;
    std::vector<JointVector> candidate = jointLine(rehearsed[j], target);
    if (!feasible(model, candidate, points, candidateFeatures)) {
      continue;
    }
    std::vector<JointVector> prefix(1, q);
    for (size_t m = 1; m <= j; ++m) {
      const std::vector<JointVector> step = jointLine(rehearsed[m - 1], rehearsed[m]);
      prefix.insert(prefix.end(), step.begin() + 1, step.end());
    }
    prefix.insert(prefix.end(), candidate.begin() + 1, candidate.end());
    if (feasible(model, prefix, points, candidateFeatures)) {
      path = prefix;
      features = candidateFeatures;
      return true;
    }
  }
  return false;
}

vpProjectivePathPlanner::vpPlanStatus vpProjectivePathPlanner::plan(const vpProjectiveArmModel &model,
                                                                    const JointVector &q,
                                                                    const std::vector<Eigen::Vector4d> &points,
                                                                    const std::vector<Eigen::Vector4d> &sStar)
{
  for (size_t g = 0; g < m_groups.size(); ++g) {
    for (unsigned int k : m_groups[g]) {
      if (k >= points.size()) {
        std::ostringstream os;
        os << "planar group " << g << " names point " << k << " but plan() was given " << points.size()
           << " points; setPlanarGroups() takes indices in the order of plan()'s points";
        fail(vpProjectiveException::dimensionError, plannerAt("plan()"), os.str());
      }
    }
  }
  // With the planar groups facing the cameras; if no plan does, without (the task's open loop then carries the arm
  // past where a marker is lost).
  m_groupsOn = true;
  const vpPlanStatus status = planOnce(model, q, points, sStar);
  if (status == PLAN_FOUND || m_groups.empty()) {
    return status;
  }
  m_groupsOn = false;
  const std::string why = m_description;
  planOnce(model, q, points, sStar);
  m_groupsOn = true;
  if (m_status == PLAN_FOUND) {
    m_description =
        "no plan keeps every planar group facing the cameras (" + why + "); without that check: " + m_description;
  } else {
    m_description = why;
    m_status = status;
  }
  return m_status;
}

vpProjectivePathPlanner::vpPlanStatus vpProjectivePathPlanner::planOnce(const vpProjectiveArmModel &model,
                                                                        const JointVector &q,
                                                                        const std::vector<Eigen::Vector4d> &points,
                                                                        const std::vector<Eigen::Vector4d> &sStar)
{
  const std::string where = plannerAt("plan()");
  const Eigen::Index n = static_cast<Eigen::Index>(model.getNumberOfJoints());
  if (q.size() != n || (m_hasLimits && m_qmin.size() != n) || points.size() != sStar.size()) {
    std::ostringstream os;
    os << "q has " << q.size() << " entries and the limits " << m_qmin.size() << " for " << n << " joints; "
       << points.size() << " points for " << sStar.size() << " desired features";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (points.size() < 2) {
    fail(vpProjectiveException::notEnoughPointsError, where, "a task needs at least 2 points");
  }
  for (size_t k = 0; k < points.size(); ++k) {
    if (!points[k].allFinite() || !sStar[k].allFinite() || !q.allFinite()) {
      fail(vpProjectiveException::nonFiniteValueError, where, "a point, a desired feature or q is not finite");
    }
  }
  // 1. Every branch of the inverse kinematics.
  JointVector qmin = m_qmin, qmax = m_qmax;
  if (!m_hasLimits) {
    qmin.resize(n);
    qmax.resize(n);
    for (Eigen::Index i = 0; i < n; ++i) {
      const double range = model.jointType(static_cast<unsigned int>(i)) == vpProjectiveJoint::REVOLUTE ? M_PI : 0.5;
      qmin(i) = q(i) - range;
      qmax(i) = q(i) + range;
    }
  }
  // The points' images at q (the features they were triangulated from, less their epipolar error) are the second view
  // of the two-view refinement of every minimum. A point whose images at q are those the model predicts for one of its
  // acquired markers, and for no other, is that marker: the bundle adjustment placed it from every acquisition image,
  // far better than one stereo pair, so it replaces the triangulation and stays fixed (its seen pixels not finite).
  std::vector<Eigen::Vector4d> X = points, seen(points.size());
  const Eigen::Matrix4d Hq = model.displacement(q);
  for (size_t k = 0; k < X.size(); ++k) {
    if (!model.getStereoRig().project(Hq * X[k], seen[k])) {
      fail(vpProjectiveException::invalidValueError, where, "a point lies on a camera's focal plane at q");
    }
  }
  computeGroupAreas(seen, sStar); // the planar groups' image areas at q and at s*: the references of facing
  unsigned int matched = 0;
  std::vector<bool> taken(model.markers().size(), false);
  for (size_t k = 0; k < X.size(); ++k) {
    const int j = model.matchMarker(Hq, seen[k]);
    if (j >= 0 && !taken[static_cast<size_t>(j)]) {
      taken[static_cast<size_t>(j)] = true;
      X[k] = model.markers()[static_cast<size_t>(j)].normalized();
      seen[k].setConstant(std::numeric_limits<double>::quiet_NaN());
      ++matched;
    }
  }
  std::vector<JointVector> extraStarts(1);
  if (!trackToDesired(model, q, X, sStar, extraStarts[0])) {
    extraStarts.clear();
  }
  m_branches = vpProjectiveInverseKinematics::solveAll(model, sStar, X, q, qmin, qmax, m_starts, &m_residuals, &seen,
                                                       &extraStarts);
  m_path.clear();
  m_features.clear();
  m_rehearsalOk = false;
  m_rehearsalIterations = 0;
  m_rehearsalResidual = -1.0;
  std::ostringstream os;
  // The depth signs where the points are seen, at q: the reference of "in front of the cameras".
  m_front.resize(X.size());
  vpProjectiveStereoRig::Projection P, Pp;
  model.getStereoRig().getLeftProjection(P);
  model.getStereoRig().getRightProjection(Pp);
  for (size_t k = 0; k < X.size(); ++k) {
    const Eigen::Vector4d M = Hq * X[k];
    m_front[k] << P.row(2).dot(M), Pp.row(2).dot(M);
  }
  bool explained = !m_branches.empty() && m_residuals.front() <= m_maxResidual;
  if (!explained) {
    os << "no joint values explain the desired features (";
    if (m_branches.empty()) {
      os << "the inverse kinematics failed from every start)";
    } else {
      os << "the best leaves " << m_residuals.front() << " px RMS, more than " << m_maxResidual << " px)";
    }
    m_branches.clear();
    m_residuals.clear();
  }
  // 2. Law (47) alone, rehearsed on the model: never worse than the law (which may get there where the inverse
  // kinematics of a model that is off by a few pixels does not).
  os << (explained ? "" : "; ") << matched << " of " << X.size() << " points are acquired markers; "
     << m_branches.size() << " inverse-kinematic branch" << (m_branches.size() > 1 ? "es" : "") << " found";
  std::vector<JointVector> lawPath;
  std::vector<std::vector<Eigen::Vector4d>> lawFeatures;
  m_rehearsalOk = m_hasLaw && m_rehearsalBudget > 0 && rehearseLaw(model, q, X, sStar, lawPath, lawFeatures);
  if (m_hasLaw && m_rehearsalBudget > 0) {
    os << "; law (47) alone " << (m_rehearsalOk ? "solves the task" : "fails") << " in its rehearsal ("
       << m_rehearsalIterations << " iterations, " << m_rehearsalResidual << " px RMS)";
  }
  // 3. The target, and 4. a path keeping the features in view and the joints within their limits: the preferred
  // target first, the nearest if no path leads to the preferred one. 5. Of the law and the path, both predicted to
  // solve the task, the faster: the path's samples and 3 iterations of the law after them, against the law's
  // rehearsed iterations.
  // If no path leads to any branch found (or none explains s*), the inverse kinematics again from kMoreStarts times
  // as many starts (the first ones among them): the uniform starts in a wide joint box can all miss the basin of the
  // branch that a path reaches (a prismatic joint's, a wrist's), and the branches already tried are not tried again.
  bool anyInside = false, found = false;
  std::vector<std::pair<JointVector, unsigned int>> candidates;
  std::vector<JointVector> tried[2], path;
  std::vector<std::vector<Eigen::Vector4d>> features;
  vpPathKind kind = PATH_JOINT_LINE;
  size_t c = 0;
  for (int round = 0; round < 2 && !found; ++round) {
    if (round == 1) {
      std::vector<double> residuals;
      std::vector<JointVector> more = vpProjectiveInverseKinematics::solveAll(
          model, sStar, X, q, qmin, qmax, kMoreStarts * m_starts, &residuals, &seen, &extraStarts);
      if (more.empty() || !(residuals.front() <= m_maxResidual)) {
        break;
      }
      os << (explained ? "; " : "; then ") << more.size() << " branches from " << kMoreStarts * m_starts << " starts";
      m_branches = more;
      m_residuals = residuals;
      explained = true;
    }
    if (!explained) {
      continue;
    }
    candidates = targetCandidates(model, q, X, anyInside);
    // The short paths (lines, one corner, the law's course) to every branch before the costly paths of several
    // corners to any: planning stays a few milliseconds whenever a short path leads to some branch.
    for (int corners = 0; corners < 2 && !found; ++corners) {
      for (c = 0; c < candidates.size(); ++c) {
        bool before = false;
        for (const JointVector &t : tried[corners]) {
          before = before || (t - candidates[c].first).cwiseAbs().maxCoeff() < 1e-3;
        }
        if (before) {
          continue;
        }
        tried[corners].push_back(candidates[c].first);
        if (planPath(model, q, candidates[c].first, lawPath, X, qmin, qmax, path, features, kind, corners == 1)) {
          found = true;
          break;
        }
      }
    }
  }
  if (!explained) {
    return m_rehearsalOk ? adoptLaw(model, lawPath, lawFeatures, os) : failWith(PLAN_NO_INVERSE_KINEMATICS, os);
  }
  if (candidates.empty()) {
    os << (anyInside ? "; at every one inside the joint limits a feature is out of the image window or behind a camera"
                     : ", none inside the joint limits");
    return m_rehearsalOk ? adoptLaw(model, lawPath, lawFeatures, os)
                         : failWith(anyInside ? PLAN_NO_VISIBLE_PATH : PLAN_OUTSIDE_JOINT_LIMITS, os);
  }
  if (!found) {
    os << "; no path keeps the features in view within the joint limits";
    // A law that its rehearsal found slow, not lost (inside the limits, in view, still moving at the budget), is
    // better than no motion: law (47) it is (the task re-plans from where it stalls, if it does).
    if (!m_rehearsalOk && m_rehearsalSlow) {
      os << "; law (47) is slow but keeps the view";
    }
    return m_rehearsalOk || m_rehearsalSlow ? adoptLaw(model, lawPath, lawFeatures, os)
                                            : failWith(PLAN_NO_VISIBLE_PATH, os);
  }
  const char *const kinds[] = {"straight image lines", "the straight joint-space line", "through a waypoint"};
  os << "; target: branch " << candidates[c].second << ", "
     << vpMath::deg((candidates[c].first - q).cwiseAbs().maxCoeff()) << " deg away at most per joint"
     << (c > 0 ? " (no path to a nearer branch)" : "") << "; path: " << kinds[kind] << " in " << path.size() - 1
     << " steps";
  if (m_rehearsalOk && path.size() - 1 + 3 >= m_rehearsalIterations) {
    return adoptLaw(model, lawPath, lawFeatures, os);
  }
  m_target = candidates[c].first;
  m_branch = candidates[c].second;
  m_kind = kind;
  m_path = path;
  m_features = features;
  m_status = PLAN_FOUND;
  m_description = os.str();
  return m_status;
}

vpProjectivePathPlanner::vpPlanStatus vpProjectivePathPlanner::failWith(vpPlanStatus status, std::ostringstream &os)
{
  m_status = status;
  m_description = os.str();
  return m_status;
}

vpProjectivePathPlanner::vpPlanStatus
vpProjectivePathPlanner::adoptLaw(const vpProjectiveArmModel &model, const std::vector<JointVector> &path,
                                  const std::vector<std::vector<Eigen::Vector4d>> &features, std::ostringstream &os)
{
  // The law ends in the branch whose basin it reached: the target is that branch's representative there (the last
  // rehearsed configuration without branches).
  m_target = path.back();
  m_branch = 0;
  double nearest = std::numeric_limits<double>::infinity();
  for (size_t b = 0; b < m_branches.size(); ++b) {
    const JointVector t = nearestRepresentative(model, m_branches[b], path.back());
    if ((t - path.back()).cwiseAbs().maxCoeff() < nearest) {
      nearest = (t - path.back()).cwiseAbs().maxCoeff();
      m_branch = static_cast<unsigned int>(b);
      m_target = t;
    }
  }
  m_kind = PATH_LAW;
  m_path = path;
  m_features = features;
  m_status = PLAN_FOUND;
  os << "; plan: law (47) alone" << (m_branches.empty() ? "" : ", to branch ");
  if (!m_branches.empty()) {
    os << m_branch;
  }
  m_description = os.str();
  return m_status;
}
