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
  vpProjectivePathPlanner: the candidate paths (the joint line, straight image lines, law (47) rehearsed on the model)
  and their checks (joint limits, the image window, the features in front of both cameras).
*/

#include <visp3/projective/vpProjectivePathPlanner.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveArmData.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveInverseKinematics.h>

#include "core/vpImageWindow.h"
#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
//! Weight of the joint-space line in the tracking of straight image lines (pixels per radian).
const double kPriorWeight = 30.0;
} // namespace

bool vpProjectivePathPlanner::inside(const JointVector &q) const
{
  return !m_hasLimits || ((q.array() >= m_qmin.array()).all() && (q.array() <= m_qmax.array()).all());
}

bool vpProjectivePathPlanner::visible(const vpProjectiveArmModel &model, const JointVector &q,
                                      const std::vector<Eigen::Vector4d> &points, std::vector<Eigen::Vector4d> &s) const
{
  const Eigen::Matrix4d H = model.displacement(q);
  const vpProjectiveStereoRig &rig = model.getStereoRig();
  vpProjectiveStereoRig::Projection P, Pp;
  rig.getLeftProjection(P);
  rig.getRightProjection(Pp);
  s.resize(points.size());
  const vpImageWindow window(m_width, m_height, m_border);
  for (size_t k = 0; k < points.size(); ++k) {
    const Eigen::Vector4d M = H * points[k];
    // In front of both cameras: the depths keep the signs they have where the points are seen (a projective camera
    // also images the points behind it; H(q) is continuous in q, so a sign change means the point went behind).
    if (!rig.project(M, s[k]) || !(P.row(2).dot(M) * m_front[k](0) > 0.0) ||
        !(Pp.row(2).dot(M) * m_front[k](1) > 0.0)) {
      return false;
    }
    if (!window.containsStereo(s[k])) {
      return false;
    }
  }
  return groupsFacing(s);
}

namespace
{
//! Twice the signed area of the polygon of the points \e group of \e s, in the left (offset 0) or right (2) image.
double polygonArea(const std::vector<Eigen::Vector4d> &s, const std::vector<unsigned int> &group, int offset)
{
  double area = 0.0;
  for (size_t k = 0; k < group.size(); ++k) {
    const Eigen::Vector4d &a = s[group[k]], &b = s[group[(k + 1) % group.size()]];
    area += a(offset) * b(offset + 1) - b(offset) * a(offset + 1);
  }
  return area;
}
} // namespace

bool vpProjectivePathPlanner::groupsFacing(const std::vector<Eigen::Vector4d> &s) const
{
  // Each planar group faces both cameras: its image area keeps the sign and a fraction of the size it has at the ends.
  for (size_t g = 0; m_groupsOn && g < m_groupArea.size(); ++g) {
    for (int c = 0; c < 2; ++c) {
      const double reference = m_groupArea[g](c);
      if (reference != 0.0 &&
          !(polygonArea(s, m_groups[g], 2 * c) * reference >= m_minGroupArea * reference * reference)) {
        return false;
      }
    }
  }
  return true;
}

void vpProjectivePathPlanner::computeGroupAreas(const std::vector<Eigen::Vector4d> &atStart,
                                                const std::vector<Eigen::Vector4d> &sStar)
{
  m_groupArea.assign(m_groups.size(), Eigen::Vector2d::Zero());
  for (size_t g = 0; g < m_groups.size(); ++g) {
    for (int c = 0; c < 2; ++c) {
      const double a = polygonArea(atStart, m_groups[g], 2 * c), b = polygonArea(sStar, m_groups[g], 2 * c);
      // The sign where the marker is seen at both ends (a polygon seen from behind at one end is not checked).
      m_groupArea[g](c) = a * b > 0.0 ? (a > 0.0 ? 1.0 : -1.0) * std::min(std::abs(a), std::abs(b)) : 0.0;
    }
  }
}

bool vpProjectivePathPlanner::feasible(const vpProjectiveArmModel &model, const std::vector<JointVector> &path,
                                       const std::vector<Eigen::Vector4d> &points,
                                       std::vector<std::vector<Eigen::Vector4d>> &features) const
{
  features.resize(path.size());
  for (size_t j = 0; j < path.size(); ++j) {
    if (!inside(path[j]) || !visible(model, path[j], points, features[j])) {
      return false;
    }
  }
  return true;
}

std::vector<vpProjectivePathPlanner::JointVector> vpProjectivePathPlanner::jointLine(const JointVector &from,
                                                                                     const JointVector &to) const
{
  const double largest = (to - from).cwiseAbs().maxCoeff();
  const int samples = std::max(1, static_cast<int>(std::ceil(largest / getMaxJointStep())));
  std::vector<JointVector> path;
  for (int j = 0; j <= samples; ++j) {
    path.push_back(from + (static_cast<double>(j) / samples) * (to - from));
  }
  return path;
}

bool vpProjectivePathPlanner::imagePath(const vpProjectiveArmModel &model, const JointVector &q,
                                        const JointVector &target, const std::vector<Eigen::Vector4d> &points,
                                        std::vector<JointVector> &path) const
{
  // s_k(t) = (1 - t) s_k(q) + t s_k(q*) for every point, tracked by the inverse kinematics warm-started at the previous
  // sample, with the joint-space line as a weak prior: it settles what the pixels leave free (a singular wrist, two
  // points) and costs as much as one pixel for 1/kPriorWeight rad off the line.
  const Eigen::Matrix4d H0 = model.displacement(q), Hstar = model.displacement(target);
  std::vector<Eigen::Vector4d> s0(points.size()), s1(points.size()), s(points.size());
  for (size_t k = 0; k < points.size(); ++k) {
    if (!model.getStereoRig().project(Eigen::Vector4d(H0 * points[k]), s0[k]) ||
        !model.getStereoRig().project(Eigen::Vector4d(Hstar * points[k]), s1[k])) {
      return false;
    }
  }
  // Tracked in steps four times finer than the path's, then thinned to steps of at most setMaxJointStep(). A fine step
  // in which a joint moves by more than setMaxJointStep() is tracked again in 2, 4 and 8 sub-steps: a joint that turns
  // fast (a wrist near a singular configuration) is then followed continuously, while a jump to another branch stays a
  // jump and rejects the path.
  const size_t samples = 4 * (jointLine(q, target).size() - 1);
  const double step = getMaxJointStep();
  const double excursion = getMaxExcursion();
  const JointVector lowest = q.cwiseMin(target), highest = q.cwiseMax(target);
  std::vector<JointVector> tracked(1, q);
  for (size_t j = 1; j <= samples; ++j) {
    const double t0 = static_cast<double>(j - 1) / samples, t1 = static_cast<double>(j) / samples;
    std::vector<JointVector> steps;
    for (int split = 1; split <= 8 && steps.empty(); split *= 2) {
      for (int m = 1; m <= split; ++m) {
        const double t = t0 + (t1 - t0) * m / split;
        for (size_t k = 0; k < points.size(); ++k) {
          s[k] = (1.0 - t) * s0[k] + t * s1[k];
        }
        const JointVector line = q + t * (target - q);
        const JointVector from = steps.empty() ? tracked.back() : steps.back(); // a copy: push_back() reallocates
        try {
          steps.push_back(vpProjectiveInverseKinematics::solve(model, s, points, from, nullptr, &line, kPriorWeight));
        } catch (const vpProjectiveException &) {
          return false;
        }
        if ((steps.back() - from).cwiseAbs().maxCoeff() > step) {
          steps.clear();
          break;
        }
      }
    }
    if (steps.empty()) {
      return false; // a jump: the tracked joints left the branch
    }
    // No joint beyond its [start, target] interval by more than setMaxExcursion() (a wrist spinning near a singular
    // configuration reaches the same pose the long way): checked as it goes, to give up early.
    for (const JointVector &step : steps) {
      if (((step - lowest).array() < -excursion).any() || ((step - highest).array() > excursion).any()) {
        return false;
      }
      tracked.push_back(step);
    }
  }
  // It must end at the target.
  if ((tracked.back() - target).cwiseAbs().maxCoeff() > 1e-3) {
    return false;
  }
  tracked.back() = target; // the same configuration up to the inverse kinematics' convergence
  path.assign(1, q);
  for (size_t j = 1; j < tracked.size(); ++j) {
    if (j + 1 == tracked.size() || (tracked[j + 1] - path.back()).cwiseAbs().maxCoeff() > step) {
      path.push_back(tracked[j]);
    }
  }
  return true;
}

double vpProjectivePathPlanner::residual(const vpProjectiveArmModel &model, const JointVector &q,
                                         const std::vector<Eigen::Vector4d> &points,
                                         const std::vector<Eigen::Vector4d> &sStar)
{
  const Eigen::Matrix4d H = model.displacement(q);
  double sum = 0.0;
  Eigen::Vector4d s;
  for (size_t k = 0; k < points.size(); ++k) {
    if (!model.getStereoRig().project(Eigen::Vector4d(H * points[k]), s)) {
      return std::numeric_limits<double>::infinity();
    }
    sum += (s - sStar[k]).squaredNorm();
  }
  return std::sqrt(sum / (4.0 * points.size()));
}

unsigned int vpProjectivePathPlanner::guardStep(const vpProjectiveArmModel &model, const JointVector &q,
                                                JointVector &qdot) const
{
  if (m_status != PLAN_FOUND || q.size() != qdot.size() ||
      static_cast<unsigned int>(q.size()) != model.getNumberOfJoints()) {
    return 0;
  }
  return halveWhileRising(model, q, qdot);
}

unsigned int vpProjectivePathPlanner::halveWhileRising(const vpProjectiveArmModel &model, const JointVector &q,
                                                       JointVector &qdot) const
{
  const double now = residual(model, q, m_points, m_sStar);
  unsigned int halvings = 0;
  while (halvings < 5 && residual(model, JointVector(q + qdot), m_points, m_sStar) > now + 0.5) {
    qdot *= 0.5;
    ++halvings;
  }
  return halvings;
}

bool vpProjectivePathPlanner::rehearseLaw(const vpProjectiveArmModel &model, const JointVector &q,
                                          const std::vector<Eigen::Vector4d> &points,
                                          const std::vector<Eigen::Vector4d> &sStar, std::vector<JointVector> &path,
                                          std::vector<std::vector<Eigen::Vector4d>> &features)
{
  // Law (47) as the task runs it (vpServoControlLaw::computeStep(), the task's implementation), on the model's
  // predictions, one step q <- q + qdot per iteration. Planning time, not the loop's: the stacked J and e may allocate.
  const Eigen::Index n = q.size();
  const Eigen::Index rows = 4 * static_cast<Eigen::Index>(points.size());
  Eigen::MatrixXd J(rows, n);
  Eigen::VectorXd e(rows);
  vpServoNormalEquations normal;
  JointVector qdot, qdot2;
  vpProjectiveArmData data;
  vpProjectiveArmModel::PointJacobian Ji;
  JointVector qk = q;
  path.assign(1, q);
  features.clear();
  m_rehearsalIterations = 0;
  m_rehearsalResidual = -1.0;
  m_rehearsalSlow = false;
  // Solved when it reaches the global minimum: the residual of the best branch with the same points (the law
  // minimises that residual, so in the branch's basin it comes down to it; a local minimum of three points leaves
  // pixels), within 1.5 times plus 0.05 px.
  double best = std::numeric_limits<double>::infinity();
  for (const JointVector &b : m_branches) {
    best = std::min(best, residual(model, b, points, sStar));
  }
  const double solved = std::min(1.5 * best + 0.05, m_maxResidual);
  std::vector<Eigen::Vector4d> s;
  for (unsigned int it = 0;; ++it) {
    if (!inside(qk) || !visible(model, qk, points, s)) {
      return false; // a joint limit, or a feature out of the window or behind a camera: law (47) would lose it
    }
    features.push_back(s);
    vpProjectiveKinematics::forwardKinematics(model, data, qk);
    for (size_t k = 0; k < points.size(); ++k) {
      if (!vpProjectiveKinematics::imageJacobian(model, data, Eigen::Vector4d(data.getDisplacement() * points[k]),
                                                 Ji)) {
        return false;
      }
      const Eigen::Index r = 4 * static_cast<Eigen::Index>(k);
      J.middleRows(r, 4) = Ji;
      e.segment<4>(r) = s[k] - sStar[k];
    }
    m_rehearsalIterations = it;
    m_rehearsalResidual = std::sqrt(e.squaredNorm() / static_cast<double>(rows));
    if (m_rehearsalResidual <= solved) {
      return true;
    }
    if (it == m_rehearsalBudget || (it > 0 && (path[it] - path[it - 1]).cwiseAbs().maxCoeff() < 1e-7)) {
      m_rehearsalSlow = it == m_rehearsalBudget && it > 0 && (path[it] - path[it - 1]).cwiseAbs().maxCoeff() >= 1e-7;
      return false; // the budget, or a fixed point of the law that is not the solution
    }
    normal.compute(J, e);
    m_law.computeStep(qk, normal, e.cwiseAbs().maxCoeff(), e.norm() / m_law.getErrorScale(), qdot, qdot2);
    if (!qdot.allFinite()) {
      return false;
    }
    halveWhileRising(model, qk, qdot);
    qk += qdot;
    path.push_back(qk);
  }
}
