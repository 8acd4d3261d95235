/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

#include <visp3/projective/vpProjectiveDisplacement.h>

#include <cmath>
#include <sstream>

#include <Eigen/Dense>
#include <ceres/ceres.h>

#include <visp3/projective/vpProjectiveStereoRig.h>

#include "vpProjectiveCeres.h"
#include "vpProjectiveInternal.h"

using namespace vpProjectiveInternal;

namespace
{
const char *const kClass = "vpProjectiveDisplacement";

// Pixel reprojection error of a rigid point M0 (unit 4-vector) seen before (M0) and after (H M0) the motion.
struct DisplacementReprojectionError {
  DisplacementReprojectionError(const vpProjectiveStereoRig::Projection &P, const vpProjectiveStereoRig::Projection &Pp,
                                const Eigen::Vector4d &s0, const Eigen::Vector4d &s1)
      : m_P(P), m_Pp(Pp), m_s0(s0), m_s1(s1)
  {
  }

  template <typename T> static void project(const Eigen::Matrix<double, 3, 4> &P, const T *X, T *uv)
  {
    T m[3];
    for (int r = 0; r < 3; ++r) {
      m[r] = T(P(r, 0)) * X[0] + T(P(r, 1)) * X[1] + T(P(r, 2)) * X[2] + T(P(r, 3)) * X[3];
    }
    uv[0] = m[0] / m[2];
    uv[1] = m[1] / m[2];
  }

  template <typename T> bool operator()(const T *const H, const T *const M0, T *residual) const
  {
    T M1[4];
    for (int r = 0; r < 4; ++r) {
      M1[r] = H[4 * r] * M0[0] + H[4 * r + 1] * M0[1] + H[4 * r + 2] * M0[2] + H[4 * r + 3] * M0[3];
    }
    T uv[2];
    const Eigen::Vector4d *obs[2] = {&m_s0, &m_s1};
    const T *points[2] = {M0, M1};
    for (int k = 0; k < 2; ++k) {
      project(m_P, points[k], uv);
      residual[4 * k] = uv[0] - T((*obs[k])(0));
      residual[4 * k + 1] = uv[1] - T((*obs[k])(1));
      project(m_Pp, points[k], uv);
      residual[4 * k + 2] = uv[0] - T((*obs[k])(2));
      residual[4 * k + 3] = uv[1] - T((*obs[k])(3));
    }
    return true;
  }

  Eigen::Matrix<double, 3, 4> m_P, m_Pp;
  Eigen::Vector4d m_s0, m_s1;
};

// Rejects point sets that cannot determine a homography of P^3: all coplanar, or 4 coplanar among a minimal 5.
void checkGeneralPosition(const std::vector<Eigen::Vector4d> &M, const std::string &where, const char *which)
{
  const size_t n = M.size();
  Eigen::Matrix<double, 4, Eigen::Dynamic> U(4, n);
  for (size_t j = 0; j < n; ++j) {
    const double norm = M[j].norm();
    if (norm == 0.0) {
      fail(vpProjectiveException::invalidValueError, where,
           std::string("a point of ") + which + " is the zero vector, which is no projective point");
    }
    U.col(static_cast<Eigen::Index>(j)) = M[j] / norm;
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(U);
  if (svd.singularValues()(3) < 1e-10 * svd.singularValues()(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         std::string("the points of ") + which + " are coplanar; a 3D homography needs points spanning 3D space");
  }
  if (n == 5) {
    // Whitened first: the points of a small object are nearly parallel 4-vectors in the rig's frame, so an absolute
    // threshold on raw determinants would reject valid sets. Whitening preserves coplanarity.
    const Eigen::Matrix4d T = whitening(M);
    for (size_t skip = 0; skip < 5; ++skip) {
      Eigen::Matrix4d S;
      for (size_t j = 0, c = 0; j < 5; ++j) {
        if (j != skip) {
          S.col(static_cast<Eigen::Index>(c++)) = (T * U.col(static_cast<Eigen::Index>(j))).normalized();
        }
      }
      if (std::abs(S.determinant()) < 1e-9) {
        fail(vpProjectiveException::degenerateConfigurationError, where,
             std::string("4 of the 5 points of ") + which +
                 " are coplanar (or repeated); 5 points determine a 3D homography only if no 4 are coplanar");
      }
    }
  }
}

std::vector<Eigen::Vector4d> toEigenPoints(const std::vector<vpColVector> &M, const std::string &where,
                                           const char *which)
{
  std::vector<Eigen::Vector4d> E(M.size());
  for (size_t j = 0; j < M.size(); ++j) {
    E[j] = toEigen<4>(M[j], where, std::string("a point of ") + which);
  }
  return E;
}
} // namespace

vpProjectiveDisplacement::vpProjectiveDisplacement() : m_H(Eigen::Matrix4d::Identity()) {}

vpProjectiveDisplacement::vpProjectiveDisplacement(const vpMatrix &H)
    : m_H(normalize(toEigen<4, 4>(H, std::string(kClass) + "()", "H")))
{
}

vpProjectiveDisplacement::vpProjectiveDisplacement(const Eigen::Matrix4d &H) : m_H(normalize(H)) {}

Eigen::Matrix4d vpProjectiveDisplacement::normalize(const Eigen::Matrix4d &H)
{
  const std::string where = std::string(kClass) + "::normalize()";
  if (!H.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, where, "H has a NaN or infinite entry");
  }
  const double scale = H.norm();
  if (scale == 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "H is the zero matrix");
  }
  const Eigen::Matrix4d Hs = H / scale; // avoids overflow of det for large entries
  const double det = Hs.determinant();
  if (!(std::abs(det) > 1e-14)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "H is singular; a projective displacement is an invertible 4x4 homography");
  }
  const double trace = Hs.trace();
  const double gamma = (trace < 0.0 ? -1.0 : 1.0) * std::pow(std::abs(det), 0.25);
  return Hs / gamma;
}

Eigen::Matrix4d vpProjectiveDisplacement::estimateLinear(const std::vector<Eigen::Vector4d> &M0,
                                                         const std::vector<Eigen::Vector4d> &M1)
{
  const std::string where = std::string(kClass) + "::estimate()";
  if (M0.size() != M1.size()) {
    std::ostringstream os;
    os << "got " << M0.size() << " points before the motion but " << M1.size() << " after; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (M0.size() < 5) {
    std::ostringstream os;
    os << "needs at least 5 point pairs to estimate a 3D homography (15 degrees of freedom), got " << M0.size();
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  for (size_t j = 0; j < M0.size(); ++j) {
    if (!M0[j].allFinite() || !M1[j].allFinite()) {
      fail(vpProjectiveException::nonFiniteValueError, where, "a point has a NaN or infinite coordinate");
    }
  }
  checkGeneralPosition(M0, where, "the first set");
  checkGeneralPosition(M1, where, "the second set");

  // DLT on whitened points: Y ~ H' X with X = T0 M0, Y = T1 M1, then H = T1^-1 H' T0.
  const Eigen::Matrix4d T0 = whitening(M0);
  const Eigen::Matrix4d T1 = whitening(M1);
  const size_t n = M0.size();
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6 * static_cast<Eigen::Index>(n), 16);
  static const int pairs[6][2] = {{0, 1}, {0, 2}, {0, 3}, {1, 2}, {1, 3}, {2, 3}};
  for (size_t j = 0; j < n; ++j) {
    const Eigen::Vector4d X = (T0 * M0[j]).normalized();
    const Eigen::Vector4d Y = (T1 * M1[j]).normalized();
    for (int p = 0; p < 6; ++p) {
      const int a = pairs[p][0], b = pairs[p][1];
      const Eigen::Index row = 6 * static_cast<Eigen::Index>(j) + p;
      // Y_a (H X)_b - Y_b (H X)_a = 0
      for (int c = 0; c < 4; ++c) {
        A(row, 4 * b + c) += Y(a) * X(c);
        A(row, 4 * a + c) -= Y(b) * X(c);
      }
    }
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd sigma = svd.singularValues();
  if (sigma(14) < 1e-9 * sigma(0)) {
    fail(vpProjectiveException::degenerateConfigurationError, where,
         "the point pairs do not determine a unique 3D homography (critical configuration); add points in general "
         "position");
  }
  const Eigen::VectorXd h = svd.matrixV().col(15);
  Eigen::Matrix4d Hw;
  for (int r = 0; r < 4; ++r) {
    Hw.row(r) = h.segment<4>(4 * r).transpose();
  }
  return normalize(T1.inverse() * Hw * T0);
}

vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const std::vector<vpColVector> &M0,
                                                            const std::vector<vpColVector> &M1)
{
  const std::string where = std::string(kClass) + "::estimate()";
  return vpProjectiveDisplacement(
      estimateLinear(toEigenPoints(M0, where, "the first set"), toEigenPoints(M1, where, "the second set")));
}

vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const vpProjectiveStereoRig &rig,
                                                            const std::vector<vpImagePoint> &left0,
                                                            const std::vector<vpImagePoint> &right0,
                                                            const std::vector<vpImagePoint> &left1,
                                                            const std::vector<vpImagePoint> &right1)
{
  const std::string where = std::string(kClass) + "::estimate()";
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where,
         "the stereo rig has no fundamental matrix; estimate it or set it before estimating displacements");
  }
  const size_t n = left0.size();
  if (right0.size() != n || left1.size() != n || right1.size() != n) {
    std::ostringstream os;
    os << "the four image point lists must have the same size, got " << left0.size() << ", " << right0.size() << ", "
       << left1.size() << ", " << right1.size();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (n < 5) {
    std::ostringstream os;
    os << "needs at least 5 points seen before and after the motion, got " << n;
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  std::vector<Eigen::Vector4d> s0(n), s1(n);
  for (size_t j = 0; j < n; ++j) {
    s0[j] << toEigen(left0[j], where, "a left image point before the motion"),
        toEigen(right0[j], where, "a right image point before the motion");
    s1[j] << toEigen(left1[j], where, "a left image point after the motion"),
        toEigen(right1[j], where, "a right image point after the motion");
  }
  return vpProjectiveDisplacement(estimateFromImages(rig, s0, s1));
}

Eigen::Matrix4d vpProjectiveDisplacement::estimateFromImages(const vpProjectiveStereoRig &rig,
                                                             const std::vector<Eigen::Vector4d> &s0,
                                                             const std::vector<Eigen::Vector4d> &s1, int maxIterations)
{
  const size_t n = s0.size();
  std::vector<Eigen::Vector4d> M0(n), M1(n);
  for (size_t j = 0; j < n; ++j) {
    M0[j] = rig.triangulate(Eigen::Vector2d(s0[j].head<2>()), Eigen::Vector2d(s0[j].tail<2>()));
    M1[j] = rig.triangulate(Eigen::Vector2d(s1[j].head<2>()), Eigen::Vector2d(s1[j].tail<2>()));
  }
  const Eigen::Matrix4d Hlin = estimateLinear(M0, M1);

  // Maximum-likelihood refinement: H (unit sphere in R^16, a gauge for its scale) and the points M0 (unit sphere).
  Eigen::Matrix<double, 4, 4, Eigen::RowMajor> H = Hlin / Hlin.norm();
  ceres::Problem problem;
  for (size_t j = 0; j < n; ++j) {
    auto *cost = new ceres::AutoDiffCostFunction<DisplacementReprojectionError, 8, 16, 4>(
        new DisplacementReprojectionError(rig.leftProjection(), rig.rightProjection(), s0[j], s1[j]));
    problem.AddResidualBlock(cost, nullptr, H.data(), M0[j].data());
    problem.SetManifold(M0[j].data(), new ceres::SphereManifold<4>());
  }
  problem.SetManifold(H.data(), new ceres::SphereManifold<16>());
  const ceres::Solver::Summary summary = solveLeastSquares(problem, ceres::DENSE_SCHUR, maxIterations);
  const Eigen::Matrix4d Hrefined = H;
  if (!Hrefined.allFinite() || summary.final_cost > summary.initial_cost) {
    return Hlin;
  }
  return normalize(Hrefined);
}

vpMatrix vpProjectiveDisplacement::getMatrix() const
{
  return toVisp(m_H);
}

double vpProjectiveDisplacement::getRotationAngle() const
{
  const double c = 0.5 * (m_H.trace() - 2.0);
  return std::acos(std::max(-1.0, std::min(1.0, c)));
}

vpProjectiveDisplacement::vpMotionType vpProjectiveDisplacement::classify(double tolerance) const
{
  const Eigen::Matrix4d D = m_H - Eigen::Matrix4d::Identity();
  if (D.norm() <= tolerance * m_H.norm()) {
    return IDENTITY;
  }
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(D);
  const Eigen::Vector4d sigma = svd.singularValues();
  int rank = 0;
  for (int k = 0; k < 4; ++k) {
    rank += sigma(k) > tolerance * sigma(0) ? 1 : 0;
  }
  if (rank == 1) {
    return TRANSLATION;
  }
  if (rank == 2) {
    return ROTATION;
  }
  return GENERAL;
}

vpProjectiveDisplacement vpProjectiveDisplacement::operator*(const vpProjectiveDisplacement &other) const
{
  return vpProjectiveDisplacement(Eigen::Matrix4d(m_H * other.m_H));
}

vpProjectiveDisplacement vpProjectiveDisplacement::inverse() const
{
  return vpProjectiveDisplacement(Eigen::Matrix4d(m_H.inverse()));
}
