/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

#include <visp3/projective/vpServoProjective.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "vpProjectiveInternal.h"

using namespace vpProjectiveInternal;

namespace
{
const char *const kClass = "vpServoProjective";

//! "vpServoProjective::method": built only when an error is thrown, never on the control loop's path.
std::string at(const char *method)
{
  return std::string(kClass) + "::" + method;
}

/*!
  In-place Cholesky factorisation \f$ A = L L^T \f$ of a symmetric positive definite matrix (lower triangle read,
  overwritten by L); false if A is not numerically positive definite (a pivot is not positive, or is NaN). Plain loops:
  for the few joints of an arm they are several times faster than Eigen's dynamic-size LLT and LDLT, which dispatch
  every column to matrix-vector kernels.
*/
template <typename Matrix> bool choleskyInPlace(Matrix &A)
{
  const Eigen::Index n = A.rows();
  for (Eigen::Index j = 0; j < n; ++j) {
    double d = A(j, j);
    for (Eigen::Index k = 0; k < j; ++k) {
      d -= A(j, k) * A(j, k);
    }
    if (!(d > 0.0)) {
      return false;
    }
    const double ljj = std::sqrt(d);
    A(j, j) = ljj;
    for (Eigen::Index i = j + 1; i < n; ++i) {
      double x = A(i, j);
      for (Eigen::Index k = 0; k < j; ++k) {
        x -= A(i, k) * A(j, k);
      }
      A(i, j) = x / ljj;
    }
  }
  return true;
}

//! Solves \f$ L L^T x = b \f$ in place (x holds b on entry), L from choleskyInPlace().
template <typename Matrix, typename Vector> void choleskySolveInPlace(const Matrix &L, Vector &x)
{
  const Eigen::Index n = L.rows();
  for (Eigen::Index i = 0; i < n; ++i) {
    double y = x(i);
    for (Eigen::Index k = 0; k < i; ++k) {
      y -= L(i, k) * x(k);
    }
    x(i) = y / L(i, i);
  }
  for (Eigen::Index i = n - 1; i >= 0; --i) {
    double y = x(i);
    for (Eigen::Index k = i + 1; k < n; ++k) {
      y -= L(k, i) * x(k);
    }
    x(i) = y / L(i, i);
  }
}
} // namespace

vpServoProjective::vpServoProjective()
    : m_robot(nullptr), m_features(), m_desired(), m_lambda(0.5), m_sigmaThreshold(1.0), m_maxDamping(10.0),
      m_qdotMax(0.0), m_J(), m_e(), m_JtJ(), m_spectrumValid(true), m_sigmaMin(0.0), m_condition(0.0), m_damping(0.0),
      m_lambdaUsed(0.0), m_saturated(false)
{
}

void vpServoProjective::setRobot(const vpProjectiveRobot &robot)
{
  if (!robot.isCalibrated()) {
    fail(vpProjectiveException::notInitializedError, std::string(kClass) + "::setRobot()",
         "the robot model is not acquired; call calibrate() or loadModel() on it first");
  }
  m_robot = &robot;
}

void vpServoProjective::setLambda(double lambda)
{
  const std::string where = std::string(kClass) + "::setLambda()";
  requireFinite(lambda, where, "the gain");
  if (!(lambda > 0.0)) {
    fail(vpProjectiveException::invalidValueError, where, "the gain must be positive");
  }
  m_lambda.initFromConstant(lambda);
}

void vpServoProjective::setLambda(const vpAdaptiveGain &lambda)
{
  m_lambda = lambda;
}

void vpServoProjective::setLambda(double gainAtZero, double gainAtInfinity, double slopeAtZero)
{
  const std::string where = std::string(kClass) + "::setLambda()";
  requireFinite(gainAtZero, where, "the gain at zero");
  requireFinite(gainAtInfinity, where, "the gain at infinity");
  requireFinite(slopeAtZero, where, "the slope at zero");
  if (!(gainAtZero > 0.0) || !(gainAtInfinity > 0.0) || !(gainAtZero >= gainAtInfinity) || slopeAtZero < 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "an adaptive gain needs gainAtZero >= gainAtInfinity > 0 and a non-negative slope");
  }
  m_lambda.initStandard(gainAtZero, gainAtInfinity, slopeAtZero);
}

void vpServoProjective::setDamping(double sigmaThreshold, double maxDamping)
{
  const std::string where = std::string(kClass) + "::setDamping()";
  requireFinite(sigmaThreshold, where, "the singular value threshold");
  requireFinite(maxDamping, where, "the maximum damping");
  if (sigmaThreshold < 0.0 || maxDamping < 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "the threshold and the damping must be non-negative");
  }
  m_sigmaThreshold = sigmaThreshold;
  m_maxDamping = maxDamping;
}

void vpServoProjective::setMaxJointVelocity(double qdotMax)
{
  const std::string where = std::string(kClass) + "::setMaxJointVelocity()";
  requireFinite(qdotMax, where, "the maximum joint velocity");
  if (qdotMax < 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "the maximum joint velocity must be positive (0 disables)");
  }
  m_qdotMax = qdotMax;
}

void vpServoProjective::addFeature(vpFeatureStereoPoint &s, vpFeatureStereoPoint &s_star)
{
  m_features.push_back(&s);
  m_desired.push_back(&s_star);
}

void vpServoProjective::clearFeatures()
{
  m_features.clear();
  m_desired.clear();
}

void vpServoProjective::check(const char *method) const
{
  if (m_robot == nullptr) {
    fail(vpProjectiveException::notInitializedError, at(method), "no robot model; call setRobot() first");
  }
  if (m_features.empty()) {
    fail(vpProjectiveException::notInitializedError, at(method), "no feature; call addFeature(s, s_star) first");
  }
  if (4 * m_features.size() < m_robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << m_features.size() << " stereo points give " << 4 * m_features.size() << " equations for "
       << m_robot->getNumberOfJoints() << " joints; add features";
    fail(vpProjectiveException::notEnoughPointsError, at(method), os.str());
  }
}

void vpServoProjective::computeSpectrum() const
{
  const Eigen::Index n = m_JtJ.rows();
  Eigen::SelfAdjointEigenSolver<JointMatrix> eig(m_JtJ, Eigen::EigenvaluesOnly);
  m_sigmaMin = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
  const double sigmaMax = std::sqrt(std::max(0.0, eig.eigenvalues()(n - 1)));
  m_condition = m_sigmaMin > 0.0 ? sigmaMax / m_sigmaMin : std::numeric_limits<double>::infinity();
  m_spectrumValid = true;
}

double vpServoProjective::getConditionNumber() const
{
  if (!m_spectrumValid) {
    computeSpectrum();
  }
  return m_condition;
}

void vpServoProjective::computeControlLaw(const vpProjectiveRobot::JointVector &q, vpProjectiveRobot::JointVector &qdot)
{
  // No allocation once the sizes are known: messages are built only when throwing.
  const char *const method = "computeControlLaw()";
  check(method);
  const Eigen::Index n = static_cast<Eigen::Index>(m_robot->getNumberOfJoints());
  const Eigen::Index rows = 4 * static_cast<Eigen::Index>(m_features.size());
  if (q.size() != n) {
    std::ostringstream os;
    os << "q must have " << n << " entries, got " << q.size();
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
  if (!q.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, at(method), "q has a NaN or infinite entry");
  }
  if (m_J.rows() != rows || m_J.cols() != n) {
    m_J.resize(rows, n);
    m_e.resize(rows);
  }

  // Task Jacobian, eq. (46) stacked over the points, at the current q and triangulated points.
  Eigen::Matrix4d HhatKq[vpProjectiveRobot::maxJoints];
  m_robot->jointMotions(q, HhatKq);
  const vpProjectiveStereoRig &rig = m_robot->getStereoRig();
  vpProjectiveRobot::PointJacobian Ji;
  for (size_t i = 0; i < m_features.size(); ++i) {
    const Eigen::Vector4d s = m_features[i]->getFeature();
    const Eigen::Vector4d sStar = m_desired[i]->getFeature();
    const Eigen::Vector4d M = rig.triangulateLinear(s.head<2>(), s.tail<2>());
    if (!m_robot->imageJacobian(HhatKq, M, Ji)) {
      std::ostringstream os;
      os << "feature " << i << " triangulates onto a camera's focal plane; check that it is matched correctly";
      fail(vpProjectiveException::pointAtInfinityError, at(method), os.str());
    }
    const Eigen::Index r = 4 * static_cast<Eigen::Index>(i);
    m_J.middleRows(r, 4) = Ji;
    m_e.segment<4>(r) = s - sStar;
  }

  // Damped least squares: qdot = -lambda (J^T J + mu^2 I)^-1 J^T e.
  // J^T J by column dot products, its lower triangle mirrored: cheaper than a matrix product kernel at these sizes.
  m_JtJ.resize(n, n);
  vpProjectiveRobot::JointVector b(n);
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = c; r < n; ++r) {
      m_JtJ(r, c) = m_J.col(r).dot(m_J.col(c));
    }
    for (Eigen::Index r = 0; r < c; ++r) {
      m_JtJ(r, c) = m_JtJ(c, r);
    }
    b(c) = m_J.col(c).dot(m_e);
  }
  m_spectrumValid = false;
  // mu > 0 only if sigma_min < sigma_0. Away from singularities a Cholesky factorisation of J^T J - sigma_0^2 I
  // proves sigma_min > sigma_0 at a fraction of the cost of the eigenvalues, which are then left to
  // getConditionNumber(); otherwise the eigenvalues decide, as documented.
  double mu2 = 0.0;
  bool positiveDefinite = false; // proven: sigma_min > sigma_0 > 0, or mu > 0
  if (m_sigmaThreshold > 0.0) {
    JointMatrix shifted = m_JtJ;
    shifted.diagonal().array() -= m_sigmaThreshold * m_sigmaThreshold;
    positiveDefinite = choleskyInPlace(shifted);
    if (!positiveDefinite) {
      computeSpectrum();
      if (m_sigmaMin < m_sigmaThreshold) {
        const double ratio = m_sigmaMin / m_sigmaThreshold;
        mu2 = m_maxDamping * m_maxDamping * (1.0 - ratio * ratio);
      }
    }
  }
  m_damping = std::sqrt(mu2);
  JointMatrix A = m_JtJ;
  A.diagonal().array() += mu2;
  m_lambdaUsed = m_lambda(m_e.cwiseAbs().maxCoeff());
  // Cholesky where J^T J + mu^2 I is known to be positive definite; elsewhere (no damping configured, J possibly rank
  // deficient) the pivoting LDLT, which gives what it can of a singular system.
  positiveDefinite = positiveDefinite || mu2 > 0.0;
  vpProjectiveRobot::JointVector x = b;
  if (positiveDefinite && choleskyInPlace(A)) {
    choleskySolveInPlace(A, x);
  } else {
    A = m_JtJ;
    A.diagonal().array() += mu2;
    x = A.ldlt().solve(b);
  }
  qdot = -m_lambdaUsed * x;
  const double largest = qdot.cwiseAbs().maxCoeff();
  m_saturated = m_qdotMax > 0.0 && largest > m_qdotMax;
  if (m_saturated) {
    qdot *= m_qdotMax / largest;
  }
  if (!qdot.allFinite()) {
    fail(vpProjectiveException::estimationFailedError, at(method),
         "the control law gave a non-finite velocity (singular task Jacobian); increase the damping");
  }
}

vpColVector vpServoProjective::computeControlLaw(const vpColVector &q)
{
  check("computeControlLaw()");
  if (q.getRows() != m_robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << "q must have " << m_robot->getNumberOfJoints() << " entries, got " << q.getRows();
    fail(vpProjectiveException::dimensionError, at("computeControlLaw()"), os.str());
  }
  vpProjectiveRobot::JointVector qe(q.getRows()), qdot(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    qe(i) = q[i];
  }
  computeControlLaw(qe, qdot);
  return toVispVector(qdot);
}

vpColVector vpServoProjective::getError() const
{
  return toVispVector(m_e);
}

vpMatrix vpServoProjective::getTaskJacobian() const
{
  return toVisp(m_J);
}
