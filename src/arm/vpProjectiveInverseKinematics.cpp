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

#include <visp3/projective/vpProjectiveInverseKinematics.h>

#include <visp3/projective/vpProjectiveArmData.h>

#include <algorithm>
#include <cmath>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/core/vpUniRand.h>

#include "core/vpLevenbergMarquardt.h"
#include "core/vpProjectiveErrors.h"
#include "core/vpProjectiveNumerics.h"
#include "core/vpProjection.h"

using namespace vpProjectiveInternal;

namespace
{
//! The largest step of a revolute joint per Levenberg-Marquardt iteration of solve() (rad): 20 deg.
const double kMaxRevoluteStep = 0.35;

/*!
  The normal equations of the pixel error at \e q: \f$ J^T J \f$ (n x n), \f$ J^T r \f$ and the cost \f$ r^T r \f$,
  accumulated marker by marker (4 rows of \f$ J \f$, eq. (46), at a time: nothing is allocated), plus the prior's
  \f$ w^2 \| q - q_p \|^2 \f$ if \e prior is not null (\e pixelCost: the pixel part alone). False if a marker is on a
  camera's focal plane at \e q. \e data, the caller's for all its evaluations, keeps the generators' squares.
*/
bool normalEquations(const vpProjectiveArmModel &model, vpProjectiveArmData &data,
                     const std::vector<Eigen::Vector4d> &s, const std::vector<Eigen::Vector4d> &points,
                     const vpProjectiveArmModel::JointVector &q, const vpProjectiveArmModel::JointVector *prior,
                     double weight, vpProjectiveArmModel::JointMatrix &JtJ, vpProjectiveArmModel::JointVector &Jtr,
                     double &cost, double &pixelCost)
{
  const Eigen::Index n = static_cast<Eigen::Index>(model.getNumberOfJoints());
  vpProjectiveKinematics::forwardKinematics(model, data, q);
  JtJ.setZero(n, n);
  Jtr.setZero(n);
  cost = 0.0;
  vpProjectiveArmModel::PointJacobian J;
  for (size_t k = 0; k < s.size(); ++k) {
    Eigen::Vector4d sM;
    if (!vpProjectiveKinematics::pointImages(model, data, points[k], sM, &J)) {
      return false;
    }
    const Eigen::Vector4d r = sM - s[k];
    JtJ.noalias() += J.transpose() * J;
    Jtr.noalias() += J.transpose() * r;
    cost += r.squaredNorm();
  }
  pixelCost = cost;
  if (prior != nullptr) {
    const double w2 = weight * weight;
    JtJ.diagonal().array() += w2;
    Jtr.noalias() += w2 * (q - *prior);
    cost += w2 * (q - *prior).squaredNorm();
  }
  return std::isfinite(cost);
}
} // namespace

vpProjectiveArmModel::JointVector vpProjectiveInverseKinematics::solve(const vpProjectiveArmModel &model,
                                                                       const std::vector<Eigen::Vector4d> &s,
                                                                       const std::vector<unsigned int> &indices,
                                                                       const vpProjectiveArmModel::JointVector &q0,
                                                                       double *residual)
{
  std::vector<Eigen::Vector4d> points(indices.size());
  for (size_t k = 0; k < indices.size(); ++k) {
    points[k] = model.markers()[indices[k]];
  }
  return solve(model, s, points, q0, residual);
}

vpProjectiveArmModel::JointVector
vpProjectiveInverseKinematics::solve(const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
                                     const std::vector<Eigen::Vector4d> &points,
                                     const vpProjectiveArmModel::JointVector &q0, double *residual,
                                     const vpProjectiveArmModel::JointVector *prior, double priorWeight)
{
  // Levenberg-Marquardt on the normal equations, damping relative to their diagonal (Marquardt's scaling, so that
  // radians and length units mix): a few iterations from a nearby start (motion capture), more from afar.
  typedef vpProjectiveArmModel::JointMatrix JointMatrix;
  typedef vpProjectiveArmModel::JointVector JointVector;
  JointMatrix JtJ, A;
  JointVector Jtr, q = q0, qNew, step;
  double cost = 0.0, pixelCost = 0.0;
  vpProjectiveArmData data;
  if (!normalEquations(model, data, s, points, q, prior, priorWeight, JtJ, Jtr, cost, pixelCost)) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveInverseKinematics::solve()",
         "a marker lies on a camera's focal plane at the starting joint values; start closer to the solution (q0)");
  }
  double lambda = 1e-3;
  for (int evaluation = 0; evaluation < 100; ++evaluation) {
    A = JtJ;
    A.diagonal() += lambda * JtJ.diagonal().cwiseMax(1e-12 * JtJ.diagonal().maxCoeff());
    step = A.ldlt().solve(-Jtr);
    // From afar a (nearly) Gauss-Newton step can leap into another branch's basin: at most kMaxRevoluteStep on any
    // revolute joint, the direction kept (still a descent direction).
    double largest = 0.0;
    for (Eigen::Index i = 0; i < step.size(); ++i) {
      if (model.jointType(static_cast<unsigned int>(i)) == vpProjectiveJoint::REVOLUTE) {
        largest = std::max(largest, std::abs(step(i)));
      }
    }
    if (largest > kMaxRevoluteStep) {
      step *= kMaxRevoluteStep / largest;
    }
    // The decrease the local quadratic model promises: below the rounding of the cost, the minimum is reached (this
    // saves the evaluations that would only find it out).
    const double promised = -Jtr.dot(step) - 0.5 * step.dot(JtJ * step);
    if (!step.allFinite() || !(promised > 1e-15 * cost) || step.norm() <= 1e-14 * (1.0 + q.norm())) {
      break;
    }
    qNew = q + step;
    JointMatrix JtJNew;
    JointVector JtrNew;
    double costNew = 0.0, pixelCostNew = 0.0;
    if (normalEquations(model, data, s, points, qNew, prior, priorWeight, JtJNew, JtrNew, costNew, pixelCostNew) &&
        costNew < cost) {
      q = qNew;
      JtJ = JtJNew;
      Jtr = JtrNew;
      cost = costNew;
      pixelCost = pixelCostNew;
      lambda = std::max(lambda / 10.0, 1e-12);
    } else {
      lambda *= 10.0;
      if (lambda > 1e12) {
        break; // no step lowers the cost: a minimum to working precision
      }
    }
  }
  if (!q.allFinite()) {
    fail(vpProjectiveException::estimationFailedError, "vpProjectiveInverseKinematics::solve()",
         "the inverse kinematics did not converge; start closer to the solution (q0) or check the marker images");
  }
  if (residual != nullptr) {
    *residual = std::sqrt(pixelCost / static_cast<double>(4 * s.size()));
  }
  return q;
}

vpProjectiveArmModel::JointVector vpProjectiveInverseKinematics::solveWithPoints(
    const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s, const std::vector<Eigen::Vector4d> &seen,
    const vpProjectiveArmModel::JointVector &q0, const vpProjectiveArmModel::JointVector &q,
    std::vector<Eigen::Vector4d> &points, double *residual)
{
  // The state: the joint values at the target and the points on their unit spheres; a step moves q additively and
  // each free point (seen pixels finite) in its tangent space (3 parameters), the parameters ordered (q, free points).
  struct State {
    vpProjectiveArmModel::JointVector q;
    std::vector<Eigen::Vector4d> M;
  };
  typedef Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic> Matrix;
  typedef Eigen::Matrix<double, Eigen::Dynamic, 1> Vector;
  const char *const where = "vpProjectiveInverseKinematics::solveWithPoints()";
  const Eigen::Index n = static_cast<Eigen::Index>(model.getNumberOfJoints()), N = static_cast<Eigen::Index>(s.size());
  if (seen.size() != s.size() || points.size() != s.size() || q0.size() != n || q.size() != n) {
    std::ostringstream os;
    os << s.size() << " desired pixels, " << seen.size() << " seen pixels and " << points.size() << " points (one each)"
       << ", joint vectors of " << q0.size() << " and " << q.size() << " entries for " << n << " joints";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  bool finite = q0.allFinite() && q.allFinite();
  for (Eigen::Index k = 0; k < N; ++k) {
    finite = finite && s[k].allFinite() && points[k].allFinite() && points[k].norm() > 0.0;
  }
  if (!finite) {
    fail(vpProjectiveException::nonFiniteValueError, where,
         "a desired pixel, a point or a joint value is not finite, or a point is zero: track every point");
  }
  // Column of each free point's 3 parameters (-1: a fixed point).
  std::vector<Eigen::Index> column(static_cast<size_t>(N), -1);
  Eigen::Index D = n;
  for (size_t k = 0; k < column.size(); ++k) {
    if (seen[k].allFinite()) {
      column[k] = D;
      D += 3;
    }
  }
  const Eigen::Matrix4d H0 = model.displacement(q0);
  vpProjectiveStereoRig::Projection P, Pp;
  model.getStereoRig().getLeftProjection(P);
  model.getStereoRig().getRightProjection(Pp);
  vpProjectiveArmData data;
  auto evaluate = [&](const State &x, Matrix *A, Vector *g, double &cost) {
    vpProjectiveKinematics::forwardKinematics(model, data, x.q);
    const Eigen::Matrix4d &H = data.getDisplacement();
    if (A != nullptr) {
      A->setZero(D, D);
      g->setZero(D);
    }
    cost = 0.0;
    vpProjectiveArmModel::PointJacobian Jq;
    Eigen::Vector4d sM;
    Eigen::Matrix4d L;
    for (Eigen::Index k = 0; k < N; ++k) {
      const Eigen::Index c = column[static_cast<size_t>(k)];
      const Eigen::Matrix<double, 4, 3> B = c >= 0 ? sphereTangentBasis(x.M[k]) : Eigen::Matrix<double, 4, 3>::Zero();
      // The view at q0 (free points): only the point moves its image.
      if (c >= 0) {
        if (!projectStereo(P, Pp, Eigen::Vector4d(H0 * x.M[k]), sM, &L)) {
          return false;
        }
        const Eigen::Vector4d r0 = sM - seen[k];
        cost += r0.squaredNorm();
        if (A != nullptr) {
          const Eigen::Matrix<double, 4, 3> Jm = L * H0 * B;
          A->block(c, c, 3, 3).noalias() += Jm.transpose() * Jm;
          g->segment(c, 3).noalias() += Jm.transpose() * r0;
        }
      }
      // The view at the target: the joints and the point.
      const Eigen::Vector4d M = H * x.M[k];
      if (!projectStereo(P, Pp, M, sM, &L) ||
          (A != nullptr && !vpProjectiveKinematics::imageJacobian(model, data, M, Jq))) {
        return false;
      }
      const Eigen::Vector4d r = sM - s[k];
      cost += r.squaredNorm();
      if (A != nullptr) {
        A->topLeftCorner(n, n).noalias() += Jq.transpose() * Jq;
        g->head(n).noalias() += Jq.transpose() * r;
        if (c >= 0) {
          const Eigen::Matrix<double, 4, 3> Jm = L * H * B;
          A->block(0, c, n, 3).noalias() += Jq.transpose() * Jm;
          A->block(c, c, 3, 3).noalias() += Jm.transpose() * Jm;
          g->segment(c, 3).noalias() += Jm.transpose() * r;
        }
      }
    }
    if (A != nullptr) {
      A->bottomLeftCorner(D - n, n) = A->topRightCorner(n, D - n).transpose();
    }
    return std::isfinite(cost);
  };
  auto update = [&](const State &x, Matrix &S, const Vector &g, State &xNew) {
    S.diagonal() = S.diagonal().cwiseMax(1e-12 * S.diagonal().maxCoeff()); // a joint the pixels do not see
    const Vector step = S.ldlt().solve(-g);
    xNew.q = x.q + step.head(n);
    xNew.M.resize(static_cast<size_t>(N));
    for (Eigen::Index k = 0; k < N; ++k) {
      const Eigen::Index c = column[static_cast<size_t>(k)];
      xNew.M[k] = c >= 0 ? (x.M[k] + sphereTangentBasis(x.M[k]) * step.segment<3>(c)).normalized() : x.M[k];
    }
    return step.allFinite();
  };
  State x{q, points};
  for (Eigen::Vector4d &M : x.M) {
    M.normalize();
  }
  double cost = 0.0;
  if (!levenbergMarquardt<Eigen::Dynamic>(x, cost, evaluate, update) || !x.q.allFinite()) {
    fail(vpProjectiveException::estimationFailedError, where,
         "a point lies on a camera's focal plane at q0 or q; start closer to the solution (q)");
  }
  points = x.M;
  if (residual != nullptr) {
    *residual = std::sqrt(cost / static_cast<double>(4 * N + 4 * (D - n) / 3));
  }
  return x.q;
}

std::vector<vpProjectiveArmModel::JointVector> vpProjectiveInverseKinematics::solveAll(
    const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
    const std::vector<Eigen::Vector4d> &points, const vpProjectiveArmModel::JointVector &q0,
    const vpProjectiveArmModel::JointVector &qmin, const vpProjectiveArmModel::JointVector &qmax, unsigned int starts,
    std::vector<double> *residuals, const std::vector<Eigen::Vector4d> *seen,
    const std::vector<vpProjectiveArmModel::JointVector> *extraStarts)
{
  if (seen != nullptr && seen->size() != points.size()) {
    fail(vpProjectiveException::dimensionError, "vpProjectiveInverseKinematics::solveAll()",
         "the seen pixels must be one per point");
  }
  typedef vpProjectiveArmModel::JointVector JointVector;
  const Eigen::Index n = static_cast<Eigen::Index>(model.getNumberOfJoints());
  const size_t extra = extraStarts != nullptr ? extraStarts->size() : 0;
  for (size_t e = 0; e < extra; ++e) {
    if ((*extraStarts)[e].size() != q0.size()) {
      fail(vpProjectiveException::dimensionError, "vpProjectiveInverseKinematics::solveAll()",
           "every extra start must have as many joint values as q0");
    }
  }
  // Two joint vectors are the same configuration when every joint agrees, revolute ones modulo a turn.
  const auto distance = [&](const JointVector &a, const JointVector &b) {
    double d = 0.0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double di = model.jointType(static_cast<unsigned int>(i)) == vpProjectiveJoint::REVOLUTE
                            ? std::remainder(a(i) - b(i), 2.0 * M_PI)
                            : a(i) - b(i);
      d = std::max(d, std::abs(di));
    }
    return d;
  };
  // Adds a minimum to the list, or keeps the lower residual of the one it meets.
  const auto keep = [&](std::vector<JointVector> &minima, std::vector<double> &residual, const JointVector &q,
                        double rms) {
    size_t same = minima.size();
    for (size_t b = 0; b < minima.size() && same == minima.size(); ++b) {
      same = distance(minima[b], q) < 1e-3 ? b : same;
    }
    if (same == minima.size()) {
      minima.push_back(q);
      residual.push_back(rms);
    } else if (rms < residual[same]) {
      minima[same] = q;
      residual[same] = rms;
    }
  };
  std::vector<JointVector> found;
  std::vector<double> cost;
  vpUniRand uniform(0x5eedULL);
  for (size_t k = 0; k <= starts + extra; ++k) {
    // q0, the extra starts, then the random ones (drawn as before: the same sequence with or without extra starts).
    JointVector start = (k > 0 && k <= extra) ? (*extraStarts)[k - 1] : q0;
    for (Eigen::Index i = 0; k > extra && i < n; ++i) {
      start(i) = uniform.uniform(qmin(i), qmax(i));
    }
    double rms = 0.0;
    JointVector q;
    try {
      q = solve(model, s, points, start, &rms);
    } catch (const vpProjectiveException &) {
      continue; // a start from which a point is on a focal plane
    }
    keep(found, cost, q, rms);
  }
  if (seen != nullptr) {
    // Each minimum with the points refined by their two views; minima that meet are one.
    std::vector<JointVector> refined;
    std::vector<double> refinedCost;
    for (size_t b = 0; b < found.size(); ++b) {
      std::vector<Eigen::Vector4d> M = points;
      double rms = 0.0;
      JointVector q;
      try {
        q = solveWithPoints(model, s, *seen, q0, found[b], M, &rms);
      } catch (const vpProjectiveException &) {
        continue;
      }
      keep(refined, refinedCost, q, rms);
    }
    found.swap(refined);
    cost.swap(refinedCost);
  }
  // The branches: the minima that explain the images nearly as well as the best, sorted by their residual. The points
  // fixed, a wrong local minimum leaves pixels far off, but so may the true one, the points' depth errors turned
  // sideways: hence 1 px or twice the best. Refined with both views, the branches of the true pose share its residual
  // at the noise, and another pose that the points nearly explain (three points) leaves more: within 1.5 times the
  // best (and 0.01 px, the working precision of noise-free pixels).
  const double best = cost.empty() ? 0.0 : *std::min_element(cost.begin(), cost.end());
  std::vector<size_t> order;
  for (size_t b = 0; b < found.size(); ++b) {
    if (seen != nullptr ? cost[b] <= 1.5 * best + 0.01 : cost[b] <= std::max(1.0, 2.0 * best)) {
      order.push_back(b);
    }
  }
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return cost[a] < cost[b]; });
  std::vector<JointVector> branches;
  if (residuals != nullptr) {
    residuals->clear();
  }
  for (size_t b : order) {
    branches.push_back(found[b]);
    if (residuals != nullptr) {
      residuals->push_back(cost[b]);
    }
  }
  return branches;
}
