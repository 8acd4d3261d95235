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

#include <visp3/projective/vpProjectiveRigidBodyTracker.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include <visp3/projective/vpMetricTwist.h>

#include "core/vpLevenbergMarquardt.h"
#include "core/vpProjection.h"
#include "core/vpProjectiveConversions.h"
#include "core/vpProjectiveNumerics.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveRigidBodyTracker");

/*
  Cost and normal equations (N = A^T A, g = A^T r, A the 4-row Jacobian of the residuals r) of the reprojection error
  of the finite observations s_j = (u, v, u', v') of points Z_j(x) in both cameras: point(j, Z, dZ) gives Z_j (4x1)
  and, when dZ is not null, its 4 x D derivative in x. N and g null: the cost only. False if a point lies on a
  camera's focal plane.
*/
template <int D, typename Point>
bool reprojectionNormalEquations(const vpProjectiveStereoRig::Projection (&cameras)[2],
                                 const std::vector<Eigen::Vector4d> &s, const Point &point,
                                 Eigen::Matrix<double, D, D> *N, Eigen::Matrix<double, D, 1> *g, double &cost,
                                 unsigned int &used)
{
  cost = 0.0;
  used = 0;
  if (N != nullptr) {
    N->setZero();
    g->setZero();
  }
  Eigen::Vector2d uv;
  Eigen::Matrix<double, 2, 4> Jc;
  Eigen::Vector4d Z;
  Eigen::Matrix<double, 4, D> dZ;
  for (size_t j = 0; j < s.size(); ++j) {
    if (!s[j].allFinite()) {
      continue;
    }
    point(j, Z, N != nullptr ? &dZ : nullptr);
    for (int k = 0; k < 2; ++k) {
      if (!projectPoint(cameras[k], Z, uv, N != nullptr ? &Jc : nullptr)) {
        return false;
      }
      const Eigen::Vector2d r = uv - s[j].segment<2>(2 * k);
      cost += r.squaredNorm();
      if (N != nullptr) {
        const Eigen::Matrix<double, 2, D> A = Jc * dZ;
        N->noalias() += A.transpose() * A;
        g->noalias() += A.transpose() * r;
      }
    }
    ++used;
  }
  return std::isfinite(cost);
}

//! Beyond this RMS pixel error per coordinate, a warm-started fit is taken for a wrong minimum (a jump).
const double kWarmStartResidual = 5.0;

//! The rigid motion nearest to a 4x4 matrix of the metric frame: its rotation block projected on SO(3) (polar part).
Eigen::Matrix4d nearestRigid(const Eigen::Matrix4d &A)
{
  const Eigen::Matrix4d B = A / A(3, 3);
  Eigen::JacobiSVD<Eigen::Matrix3d> svd(B.topLeftCorner<3, 3>(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d D = Eigen::Matrix3d::Identity();
  D(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  Eigen::Matrix4d T = Eigen::Matrix4d::Identity();
  T.topLeftCorner<3, 3>() = svd.matrixU() * D * svd.matrixV().transpose();
  T.topRightCorner<3, 1>() = B.topRightCorner<3, 1>();
  return T;
}
} // namespace

vpProjectiveRigidBodyTracker::vpProjectiveRigidBodyTracker()
    : m_rig(), m_M(), m_T(Eigen::Matrix4d::Identity()), m_Tinv(Eigen::Matrix4d::Identity()), m_rigid(false),
      m_G(Eigen::Matrix4d::Identity()), m_Ginv(Eigen::Matrix4d::Identity()), m_H(), m_history(), m_times(), m_window(4),
      m_residual(0.0), m_tracked(0)
{
}

void vpProjectiveRigidBodyTracker::init(const vpProjectiveStereoRig &rig, const std::vector<vpImagePoint> &left0,
                                        const std::vector<vpImagePoint> &right0, double t0)
{
  const std::string where = at("init()");
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where, "the rig has no fundamental matrix; estimate it first");
  }
  requireFinite(t0, where, "the reference time");
  const std::vector<Eigen::Vector4d> s = stackStereoImages(left0, right0, where);
  if (s.size() < 5) {
    std::ostringstream os;
    os << "needs the images of at least 5 markers (no 4 coplanar), got " << s.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  std::vector<Eigen::Vector4d> M(s.size());
  for (size_t j = 0; j < s.size(); ++j) {
    M[j] = rig.triangulate(Eigen::Vector2d(s[j].head<2>()), Eigen::Vector2d(s[j].tail<2>()));
  }
  m_rig = rig;
  m_M = M;
  m_T = whitening(M);
  m_Tinv = m_T.inverse();
  m_H = vpProjectiveDisplacement();
  m_history.assign(1, m_H);
  m_times.assign(1, t0);
  m_residual = 0.0;
  m_tracked = static_cast<unsigned int>(s.size());
}

void vpProjectiveRigidBodyTracker::setProjectiveToMetric(const vpMatrix &G)
{
  const std::string where = at("setProjectiveToMetric()");
  if (G.getRows() == 0 && G.getCols() == 0) {
    m_rigid = false;
    return;
  }
  const Eigen::Matrix4d Ge = toEigen<4, 4>(G, where, "G");
  const Eigen::FullPivLU<Eigen::Matrix4d> lu(Ge);
  if (!lu.isInvertible()) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "G is singular; it must map the projective frame onto a metric one");
  }
  m_G = Ge;
  m_Ginv = lu.inverse();
  m_rigid = true;
}

void vpProjectiveRigidBodyTracker::setVelocityWindow(unsigned int frames)
{
  m_window = atLeastOne(frames, at("setVelocityWindow()"), "the velocity is fitted over at least 1 past frame");
}

bool vpProjectiveRigidBodyTracker::refine(const std::vector<Eigen::Vector4d> &s, Eigen::Matrix4d &H, double &cost,
                                          unsigned int &used) const
{
  // In the frame whitened by the reference points: Hw = T H T^-1, X_j = T M_j, cameras P T^-1, P' T^-1.
  typedef Eigen::Matrix<double, 4, 4, Eigen::RowMajor> RowMajor4;
  vpProjectiveStereoRig::Projection P, Pp;
  m_rig.getLeftProjection(P);
  m_rig.getRightProjection(Pp);
  const vpProjectiveStereoRig::Projection cameras[2] = {P * m_Tinv, Pp * m_Tinv};
  auto evaluate = [&](const RowMajor4 &Hw, Eigen::Matrix<double, 16, 16> *N, Eigen::Matrix<double, 16, 1> *g,
                      double &c) {
    auto point = [&](size_t j, Eigen::Vector4d &Z, Eigen::Matrix<double, 4, 16> *dZ) {
      const Eigen::Vector4d X = (m_T * m_M[j]).normalized();
      Z = Hw * X;
      if (dZ != nullptr) {
        dZ->setZero();
        for (int row = 0; row < 4; ++row) { // d(Hw X)_row / dHw(row, col) = X(col), Hw stored row by row
          dZ->block<1, 4>(row, 4 * row) = X.transpose();
        }
      }
    };
    return reprojectionNormalEquations<16>(cameras, s, point, N, g, c, used);
  };
  RowMajor4 Hw = m_T * H * m_Tinv;
  Hw /= Hw.norm();
  // The residuals ignore the scale of Hw (J h = 0): a term along h fixes the step on its unit sphere.
  auto update = [](const RowMajor4 &Hc, Eigen::Matrix<double, 16, 16> &S, const Eigen::Matrix<double, 16, 1> &g,
                   RowMajor4 &HNew) {
    const Eigen::Map<const Eigen::Matrix<double, 16, 1>> h(Hc.data());
    S.noalias() += std::max(S.trace() / 16.0, 1e-300) * h * h.transpose();
    const Eigen::Matrix<double, 16, 1> step = S.ldlt().solve(-g);
    HNew = Hc;
    Eigen::Map<Eigen::Matrix<double, 16, 1>>(HNew.data()) += step;
    HNew /= HNew.norm();
    return step.allFinite();
  };
  if (!levenbergMarquardt<16>(Hw, cost, evaluate, update)) {
    return false;
  }
  H = m_Tinv * Eigen::Matrix4d(Hw) * m_T;
  return H.allFinite() && used >= 4;
}

bool vpProjectiveRigidBodyTracker::refineRigid(const std::vector<Eigen::Vector4d> &s, Eigen::Matrix4d &T, double &cost,
                                               unsigned int &used) const
{
  // H = G^-1 T G, T updated by left increments exp(xi^) T, xi = (v, w) (6): d(H M)/d xi_k = G^-1 E_k T G M.
  vpProjectiveStereoRig::Projection P, Pp;
  m_rig.getLeftProjection(P);
  m_rig.getRightProjection(Pp);
  const vpProjectiveStereoRig::Projection cameras[2] = {P * m_Ginv, Pp * m_Ginv};
  auto evaluate = [&](const Eigen::Matrix4d &Tc, Eigen::Matrix<double, 6, 6> *N, Eigen::Matrix<double, 6, 1> *g,
                      double &c) {
    auto point = [&](size_t j, Eigen::Vector4d &Z, Eigen::Matrix<double, 4, 6> *dZ) {
      Z = Tc * (m_G * m_M[j]); // the marker in the metric frame, moved
      if (dZ != nullptr) {
        dZ->row(3).setZero();
        for (int i = 0; i < 3; ++i) {
          dZ->block<3, 1>(0, i) = Z(3) * Eigen::Vector3d::Unit(i);                 // translations
          dZ->block<3, 1>(0, 3 + i) = Eigen::Vector3d::Unit(i).cross(Z.head<3>()); // rotations
        }
      }
    };
    return reprojectionNormalEquations<6>(cameras, s, point, N, g, c, used);
  };
  // Left increments on SE(3): T <- exp(xi^) T.
  auto update = [](const Eigen::Matrix4d &Tc, Eigen::Matrix<double, 6, 6> &S, const Eigen::Matrix<double, 6, 1> &g,
                   Eigen::Matrix4d &TNew) {
    const Eigen::Matrix<double, 6, 1> xi = S.ldlt().solve(-g);
    TNew =
        vpProjectiveDisplacement::exp(vpMetricTwist::hat(Eigen::Vector3d(xi.head<3>()), Eigen::Vector3d(xi.tail<3>())))
            .matrix() *
        Tc;
    return xi.allFinite();
  };
  if (!levenbergMarquardt<6>(T, cost, evaluate, update)) {
    return false;
  }
  return T.allFinite() && used >= 3;
}

const Eigen::Matrix4d &vpProjectiveRigidBodyTracker::track(const std::vector<Eigen::Vector4d> &s, double t)
{
  const std::string where = at("track()");
  if (!isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where, "call init() with the reference images first");
  }
  if (s.size() != m_M.size()) {
    std::ostringstream os;
    os << "got the images of " << s.size() << " markers but the reference has " << m_M.size()
       << "; pass every marker in the reference's order, flagging the lost ones";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!std::isfinite(t) || !(t > m_times.back())) {
    std::ostringstream os;
    os << "the frame time " << t << " must be finite and after the previous frame's (" << m_times.back() << ")";
    fail(vpProjectiveException::invalidValueError, where, os.str());
  }
  unsigned int visible = 0;
  for (const Eigen::Vector4d &sj : s) {
    visible += sj.allFinite() ? 1 : 0;
  }
  const unsigned int needed = m_rigid ? 3 : 4;
  if (visible < needed) {
    std::ostringstream os;
    os << "only " << visible << " markers are visible; a " << (m_rigid ? "rigid motion" : "displacement")
       << " of known points needs " << needed << " in general position";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  // One fit: projective (15 degrees of freedom), or rigid in the metric frame of G (6).
  auto fit = [&](Eigen::Matrix4d &Hfit, double &c, unsigned int &u) {
    if (!m_rigid) {
      return refine(s, Hfit, c, u);
    }
    Eigen::Matrix4d T = nearestRigid(m_G * Hfit * m_Ginv);
    const bool converged = refineRigid(s, T, c, u);
    Hfit = m_Ginv * T * m_G;
    return converged;
  };
  Eigen::Matrix4d H = m_H.matrix();
  double cost = 0.0;
  unsigned int used = 0;
  bool ok = fit(H, cost, used);
  if (!ok || std::sqrt(cost / (4.0 * used)) > kWarmStartResidual) {
    // A jump, or a wrong minimum: the maximum-likelihood displacement of the visible markers from their reference.
    if (visible < 5) {
      fail(vpProjectiveException::notEnoughPointsError, where,
           "the warm-started fit failed and only 4 markers are visible; a fresh estimate needs 5");
    }
    std::vector<Eigen::Vector4d> s0, s1;
    for (size_t j = 0; j < s.size(); ++j) {
      if (s[j].allFinite()) {
        Eigen::Vector4d s0j;
        m_rig.project(m_M[j], s0j);
        s0.push_back(s0j);
        s1.push_back(s[j]);
      }
    }
    Eigen::Matrix4d Hfresh;
    try {
      Hfresh = vpProjectiveDisplacement::estimateFromImages(m_rig, s0, s1);
    } catch (const vpProjectiveException &e) {
      fail(vpProjectiveException::estimationFailedError, where,
           std::string("no displacement explains the markers: ") + e.getStringMessage());
    }
    double costFresh = 0.0;
    unsigned int usedFresh = 0;
    if (fit(Hfresh, costFresh, usedFresh) && (!ok || costFresh < cost)) {
      H = Hfresh;
      cost = costFresh;
      used = usedFresh;
      ok = true;
    }
  }
  if (!ok) {
    fail(vpProjectiveException::estimationFailedError, where,
         "no displacement explains the markers (on a camera's focal plane?)");
  }
  m_H = vpProjectiveDisplacement(H);
  if (m_history.size() > m_window) {
    m_history.erase(m_history.begin());
    m_times.erase(m_times.begin());
  }
  m_history.push_back(m_H);
  m_times.push_back(t);
  m_residual = std::sqrt(cost / (4.0 * used));
  m_tracked = used;
  return m_H.matrix();
}

vpProjectiveDisplacement vpProjectiveRigidBodyTracker::track(const std::vector<vpImagePoint> &left,
                                                             const std::vector<vpImagePoint> &right, double t,
                                                             const std::vector<bool> &visible)
{
  const std::string where = at("track()");
  if (left.size() != right.size() || (!visible.empty() && visible.size() != left.size())) {
    std::ostringstream os;
    os << "got " << left.size() << " left, " << right.size() << " right images and " << visible.size()
       << " visibility flags; pass one of each per marker";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  std::vector<Eigen::Vector4d> s(left.size());
  for (size_t j = 0; j < s.size(); ++j) {
    s[j] << left[j].get_u(), left[j].get_v(), right[j].get_u(), right[j].get_v();
    if (!visible.empty() && !visible[j]) {
      s[j].setConstant(std::numeric_limits<double>::quiet_NaN());
    }
  }
  track(s, t);
  return m_H;
}

vpProjectiveBodyVelocity vpProjectiveRigidBodyTracker::getVelocity() const
{
  if (m_history.size() < 2) {
    fail(vpProjectiveException::notInitializedError, at("getVelocity()"),
         "no frame tracked yet; call track() on a frame first");
  }
  return vpProjectiveBodyVelocity::fromSequence(m_history, m_times, m_history.size() - 1, m_window);
}
