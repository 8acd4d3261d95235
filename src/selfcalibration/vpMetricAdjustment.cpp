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

#include "selfcalibration/vpMetricAdjustment.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

#include <Eigen/Eigenvalues>

#include <ceres/ceres.h>
#include <ceres/rotation.h>

#include "core/vpProjection.h"
#include "core/vpProjectiveErrors.h"
#include "core/vpProjectiveCeres.h"

namespace vpProjectiveInternal
{
namespace
{
typedef vpProjectiveArmModel::JointVector JointVector;
const unsigned int kMaxJoints = vpProjectiveArmModel::maxJoints;

//! \f$ K \f$ (3x4, \f$ [K | 0] \f$) of the intrinsics fx, fy, skew, u0, v0.
template <typename T> Eigen::Matrix<T, 3, 4> cameraOf(const T *k)
{
  Eigen::Matrix<T, 3, 4> P = Eigen::Matrix<T, 3, 4>::Zero();
  P(0, 0) = k[0];
  P(0, 1) = k[2];
  P(0, 2) = k[3];
  P(1, 1) = k[1];
  P(1, 2) = k[4];
  P(2, 2) = T(1.0);
  return P;
}

/*!
  The motion \f$ T(\delta q) \f$ (4x4) of the markers in the left camera's frame: the product of the joints'
  exponentials in vpProjectiveArmModel's order, each joint's twist from its unit direction and point.
*/
template <typename T>
Eigen::Matrix<T, 4, 4> chainMotion(const MetricChain &chain, const Eigen::Matrix<T, 3, 1> *axis,
                                   const Eigen::Matrix<T, 3, 1> *point, const JointVector &dq)
{
  const unsigned int n = static_cast<unsigned int>(chain.types.size());
  Eigen::Matrix<T, 4, 4> H = Eigen::Matrix<T, 4, 4>::Identity();
  for (unsigned int k = 0; k < n; ++k) {
    const unsigned int i = chain.mounting == vpProjectiveArmModel::EYE_TO_HAND ? k : n - 1 - k;
    H = H *
        vpProjectiveJoint::exp(chain.types[i], vpProjectiveJoint::twist(chain.types[i], axis[i], point[i]), T(dq(i)));
  }
  return H;
}

//! Both cameras: \f$ [K_l | 0] \f$ and \f$ K_r [{}^rR_l | -{}^rR_l b] \f$.
template <typename T>
void cameras(const T *left, const T *right, const Eigen::Matrix<T, 3, 3> &lRr, const Eigen::Matrix<T, 3, 1> &b,
             Eigen::Matrix<T, 3, 4> &Pl, Eigen::Matrix<T, 3, 4> &Pr)
{
  Pl = cameraOf(left);
  Eigen::Matrix<T, 4, 4> rMl = Eigen::Matrix<T, 4, 4>::Identity();
  rMl.template topLeftCorner<3, 3>() = lRr.transpose();
  rMl.template topRightCorner<3, 1>() = -(lRr.transpose() * b);
  Pr = cameraOf(right) * rMl;
}

//! What the cost functors share with the problem: the chain, the rotation's base and the charts of the axes' points.
struct Shared {
  MetricChain chain;
  Eigen::Matrix3d lRr0;
  // A revolute axis' point is p0 + c(0) e1 + c(1) e2, its 2 coordinates c in the plane through p0 normal to the
  // start's axis: a line has 4 degrees of freedom, not 6.
  std::vector<Eigen::Vector3d> p0, e1, e2;
};

/*!
  Pixel errors (u, v, u', v') of the observed markers of one frame. Parameters: left (5), right (5), phi (3), b (3),
  per joint its direction (3) and, revolute, its point's chart (2), then each observed marker (3).
*/
class FrameObservationError
{
public:
  FrameObservationError(const Shared *shared, const JointVector &dq, const std::vector<Eigen::Vector4d> &s)
      : m_shared(shared), m_dq(dq), m_s(s)
  {
  }

  template <typename T> bool operator()(T const *const *p, T *r) const
  {
    const MetricChain &chain = m_shared->chain;
    const size_t n = chain.types.size();
    T R[9];
    ceres::AngleAxisToRotationMatrix(p[2], R); // column-major
    const Eigen::Matrix<T, 3, 3> lRr = Eigen::Map<const Eigen::Matrix<T, 3, 3>>(R) * m_shared->lRr0.cast<T>();
    Eigen::Matrix<T, 3, 4> Pl, Pr;
    cameras(p[0], p[1], lRr, Eigen::Matrix<T, 3, 1>(p[3][0], p[3][1], p[3][2]), Pl, Pr);
    std::array<Eigen::Matrix<T, 3, 1>, kMaxJoints> axis, point;
    int block = 4;
    for (size_t i = 0; i < n; ++i, ++block) {
      axis[i] = Eigen::Matrix<T, 3, 1>(p[block][0], p[block][1], p[block][2]).normalized();
      point[i] = m_shared->p0[i].cast<T>();
      if (chain.types[i] == vpProjectiveJoint::REVOLUTE) {
        ++block;
        point[i] += p[block][0] * m_shared->e1[i].cast<T>() + p[block][1] * m_shared->e2[i].cast<T>();
      }
    }
    const Eigen::Matrix<T, 4, 4> H = chainMotion<T>(chain, axis.data(), point.data(), m_dq);
    for (size_t j = 0; j < m_s.size(); ++j, ++block) {
      const Eigen::Matrix<T, 4, 1> X(p[block][0], p[block][1], p[block][2], T(1.0));
      Eigen::Matrix<T, 4, 1> s;
      if (!projectStereo(Pl, Pr, Eigen::Matrix<T, 4, 1>(H * X), s)) {
        return false;
      }
      for (int c = 0; c < 4; ++c) {
        r[4 * j + c] = s(c) - T(m_s[j](c));
      }
    }
    return true;
  }

private:
  const Shared *m_shared;
  JointVector m_dq;
  std::vector<Eigen::Vector4d> m_s; // observed markers, in the order of their parameter blocks
};

//! Any unit vector normal to \e w.
Eigen::Vector3d normalTo(const Eigen::Vector3d &w)
{
  const Eigen::Vector3d a = std::abs(w(0)) < 0.9 ? Eigen::Vector3d::UnitX() : Eigen::Vector3d::UnitY();
  return w.cross(a).normalized();
}
} // namespace

bool MetricChain::hasPrismatic() const
{
  for (vpProjectiveJoint::vpJointType t : types) {
    if (t == vpProjectiveJoint::PRISMATIC) {
      return true;
    }
  }
  return false;
}

void checkMarkerDistance(unsigned int markerA, unsigned int markerB, double distance, size_t markers,
                         const std::string &where)
{
  if (markerA >= markers || markerB >= markers || markerA == markerB) {
    std::ostringstream os;
    os << "markers " << markerA << " and " << markerB << " are not two distinct markers of the model's " << markers;
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!std::isfinite(distance) || !(distance > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where, "the marker distance must be positive and finite");
  }
}

double largestDeviation(const Eigen::Matrix3d &S)
{
  const double lambda = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S, Eigen::EigenvaluesOnly).eigenvalues()(2);
  return std::sqrt(std::max(0.0, lambda));
}

double directionDeviation(const Eigen::Vector3d &d, const Eigen::Matrix3d &S, double length)
{
  const Eigen::Matrix3d P = Eigen::Matrix3d::Identity() - d * d.transpose();
  return largestDeviation(P * S * P.transpose()) / length;
}

bool predictFrame(const MetricChain &chain, const MetricArm &arm, const JointVector &q, std::vector<Eigen::Vector4d> &s)
{
  Eigen::Matrix<double, 3, 4> Pl, Pr;
  cameras(arm.left.data(), arm.right.data(), arm.lRr, arm.b, Pl, Pr);
  const Eigen::Matrix4d H = chainMotion<double>(chain, arm.axis.data(), arm.point.data(), q - chain.qRef);
  s.resize(arm.X.size());
  for (size_t j = 0; j < arm.X.size(); ++j) {
    const Eigen::Vector4d X = H * arm.X[j].homogeneous();
    if (!(Pl.row(2).dot(X) > 0.0 && Pr.row(2).dot(X) > 0.0) || !projectStereo(Pl, Pr, X, s[j])) {
      return false;
    }
  }
  return true;
}

struct MetricProblem::Data {
  Shared shared;
  Eigen::Matrix<double, 5, 1> left, right;
  Eigen::Vector3d phi, b;
  std::vector<Eigen::Vector3d> axis, X;
  std::vector<Eigen::Vector2d> chart;
  std::vector<bool> used; // markers observed by some frame: their blocks are in the problem
  unsigned int residuals = 0;
  ceres::Problem problem; // last: destroyed first, before the blocks it points to

  //! The parameter blocks (data, size) of a frame observing the markers \e seen, in FrameObservationError's order.
  std::vector<std::pair<double *, int>> blocks(const std::vector<bool> &seen)
  {
    std::vector<std::pair<double *, int>> list = {{left.data(), 5}, {right.data(), 5}, {phi.data(), 3}, {b.data(), 3}};
    for (size_t i = 0; i < axis.size(); ++i) {
      list.emplace_back(axis[i].data(), 3);
      if (shared.chain.types[i] == vpProjectiveJoint::REVOLUTE) {
        list.emplace_back(chart[i].data(), 2);
      }
    }
    for (size_t j = 0; j < X.size(); ++j) {
      if (seen[j]) {
        list.emplace_back(X[j].data(), 3);
      }
    }
    return list;
  }
  //! Adds the residual block of the markers \e seen of pixels \e s at readings \e q.
  ceres::ResidualBlockId add(const JointVector &q, const std::vector<Eigen::Vector4d> &s, const std::vector<bool> &seen)
  {
    std::vector<Eigen::Vector4d> observed;
    for (size_t j = 0; j < s.size(); ++j) {
      if (seen[j]) {
        observed.push_back(s[j]);
      }
    }
    // 16 derivatives per pass: the 60 to 100 parameters of a frame in 4 to 7 passes over its chain.
    auto *cost = new ceres::DynamicAutoDiffCostFunction<FrameObservationError, 16>(
        new FrameObservationError(&shared, q - shared.chain.qRef, observed));
    std::vector<double *> pointers;
    for (const std::pair<double *, int> &block : blocks(seen)) {
      cost->AddParameterBlock(block.second);
      pointers.push_back(block.first);
    }
    cost->SetNumResiduals(static_cast<int>(4 * observed.size()));
    return problem.AddResidualBlock(cost, nullptr, pointers);
  }
};

MetricProblem::MetricProblem(const MetricChain &chain, const MetricArm &start) : m(new Data)
{
  m->shared.chain = chain;
  m->shared.lRr0 = start.lRr;
  m->left = start.left;
  m->right = start.right;
  m->phi.setZero();
  m->b = start.b;
  m->X = start.X;
  m->used.assign(start.X.size(), false);
  for (size_t i = 0; i < chain.types.size(); ++i) {
    const Eigen::Vector3d w = start.axis[i].normalized();
    m->axis.push_back(w);
    const Eigen::Vector3d p = start.point[i] - w * w.dot(start.point[i]); // the axis' point nearest the origin
    m->shared.p0.push_back(chain.types[i] == vpProjectiveJoint::REVOLUTE ? p : Eigen::Vector3d::Zero());
    m->shared.e1.push_back(normalTo(w));
    m->shared.e2.push_back(w.cross(m->shared.e1.back()));
    m->chart.push_back(Eigen::Vector2d::Zero());
  }
}

MetricProblem::~MetricProblem() = default;

void MetricProblem::addFrame(const MetricFrame &frame)
{
  unsigned int observed = 0;
  for (size_t j = 0; j < frame.seen.size(); ++j) {
    observed += frame.seen[j] ? 1u : 0u;
  }
  if (observed == 0) {
    return;
  }
  m->add(frame.q, frame.s, frame.seen);
  for (size_t j = 0; j < frame.seen.size(); ++j) {
    m->used[j] = m->used[j] || frame.seen[j];
  }
  m->residuals += 4 * observed;
  for (size_t i = 0; i < m->axis.size(); ++i) {
    if (!m->problem.HasManifold(m->axis[i].data())) {
      m->problem.SetManifold(m->axis[i].data(), new ceres::SphereManifold<3>());
    }
  }
  if (!m->shared.chain.hasPrismatic() && !m->problem.HasManifold(m->b.data())) {
    m->problem.SetManifold(m->b.data(), new ceres::SphereManifold<3>()); // the scale: a unit baseline
  }
}

bool MetricProblem::solve()
{
  if (m->residuals == 0) {
    return false;
  }
  const ceres::Solver::Summary summary = solveLeastSquares(m->problem, ceres::DENSE_NORMAL_CHOLESKY, 100, 1e-10);
  if (!summary.IsSolutionUsable()) {
    return false;
  }
  // The rotation's perturbation back to zero around the solution: the covariance of phi is then that of the
  // rotation itself, in the left camera's axes.
  double R[9];
  ceres::AngleAxisToRotationMatrix(m->phi.data(), R);
  m->shared.lRr0 = Eigen::Map<const Eigen::Matrix3d>(R) * m->shared.lRr0;
  m->phi.setZero();
  return true;
}

MetricArm MetricProblem::estimate() const
{
  MetricArm arm;
  arm.left = m->left;
  arm.right = m->right;
  double R[9];
  ceres::AngleAxisToRotationMatrix(m->phi.data(), R);
  arm.lRr = Eigen::Map<const Eigen::Matrix3d>(R) * m->shared.lRr0;
  arm.b = m->b;
  for (size_t i = 0; i < m->axis.size(); ++i) {
    arm.axis.push_back(m->axis[i].normalized());
    arm.point.push_back(m->shared.p0[i] + m->chart[i](0) * m->shared.e1[i] + m->chart[i](1) * m->shared.e2[i]);
    if (m->shared.chain.types[i] == vpProjectiveJoint::PRISMATIC) {
      arm.point.back().setZero();
    }
  }
  arm.X = m->X;
  return arm;
}

void MetricProblem::cost(double &sum, unsigned int &residuals, unsigned int &parameters) const
{
  double half = 0.0;
  m->problem.Evaluate(ceres::Problem::EvaluateOptions(), &half, nullptr, nullptr, nullptr);
  sum = 2.0 * half;
  residuals = m->residuals;
  parameters = 0;
  for (const std::pair<double *, int> &block : m->blocks(m->used)) {
    parameters += static_cast<unsigned int>(m->problem.ParameterBlockTangentSize(block.first));
  }
}

bool MetricProblem::covariance(Eigen::MatrixXd &tangent, Eigen::MatrixXd &L)
{
  const unsigned int n = static_cast<unsigned int>(m->axis.size()), K = static_cast<unsigned int>(m->X.size());
  std::vector<const double *> blocks;
  int dimension = 0;
  for (const std::pair<double *, int> &block : m->blocks(m->used)) {
    blocks.push_back(block.first);
    dimension += m->problem.ParameterBlockTangentSize(block.first);
  }
  ceres::Covariance::Options options;
#if defined(CERES_NO_SUITESPARSE) && !defined(CERES_USE_EIGEN_SPARSE)
  options.algorithm_type = ceres::DENSE_SVD; // no sparse QR in this Ceres
#else
  options.algorithm_type = ceres::SPARSE_QR; // fails on a rank-deficient Jacobian: an undetermined parameter
#endif
  options.num_threads = 1;
  ceres::Covariance covariance(options);
  if (!covariance.Compute(blocks, &m->problem)) {
    return false;
  }
  Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> C(dimension, dimension);
  if (!covariance.GetCovarianceMatrixInTangentSpace(blocks, C.data())) {
    return false;
  }
  tangent = C;
  // The map from the tangent spaces to the ambient layout: the manifolds' Plus Jacobians, the charts' planes.
  L = Eigen::MatrixXd::Zero(MetricLayout::size(n, K), dimension);
  int column = 0;
  auto place = [&](int row, const double *block, int size) {
    const int t = m->problem.ParameterBlockTangentSize(block);
    const ceres::Manifold *manifold = m->problem.GetManifold(block);
    if (manifold == nullptr) {
      L.block(row, column, size, t).setIdentity();
    } else {
      Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor> J(size, t);
      manifold->PlusJacobian(block, J.data());
      L.block(row, column, size, t) = J;
    }
    column += t;
  };
  place(MetricLayout::kLeft, m->left.data(), 5);
  place(MetricLayout::kRight, m->right.data(), 5);
  place(MetricLayout::kRotation, m->phi.data(), 3);
  place(MetricLayout::kBaseline, m->b.data(), 3);
  for (unsigned int i = 0; i < n; ++i) {
    place(MetricLayout::joint(i), m->axis[i].data(), 3);
    if (m->shared.chain.types[i] == vpProjectiveJoint::REVOLUTE) {
      L.block<3, 1>(MetricLayout::joint(i) + 3, column) = m->shared.e1[i];
      L.block<3, 1>(MetricLayout::joint(i) + 3, column + 1) = m->shared.e2[i];
      column += 2;
    }
  }
  for (unsigned int j = 0; j < K; ++j) {
    if (m->used[j]) {
      place(MetricLayout::marker(n, j), m->X[j].data(), 3);
    }
  }
  return tangent.allFinite();
}

Eigen::MatrixXd MetricProblem::frameJacobian(const JointVector &q)
{
  const ceres::ResidualBlockId id =
      m->add(q, std::vector<Eigen::Vector4d>(m->X.size(), Eigen::Vector4d::Zero()), m->used);
  ceres::Problem::EvaluateOptions options;
  options.residual_blocks = {id};
  for (const std::pair<double *, int> &block : m->blocks(m->used)) {
    options.parameter_blocks.push_back(block.first);
  }
  ceres::CRSMatrix crs;
  const bool ok = m->problem.Evaluate(options, nullptr, nullptr, nullptr, &crs);
  m->problem.RemoveResidualBlock(id);
  Eigen::MatrixXd J = Eigen::MatrixXd::Zero(crs.num_rows, crs.num_cols);
  for (int r = 0; ok && r < crs.num_rows; ++r) {
    for (int k = crs.rows[static_cast<size_t>(r)]; k < crs.rows[static_cast<size_t>(r) + 1]; ++k) {
      J(r, crs.cols[static_cast<size_t>(k)]) = crs.values[static_cast<size_t>(k)];
    }
  }
  return ok ? J : Eigen::MatrixXd();
}
} // namespace vpProjectiveInternal
