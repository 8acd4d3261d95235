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

#include <visp3/projective/vpServoProjective.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "vpProjectiveInternal.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

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

/*!
  Distance (pixels) of a point to the line \e l of an image, from the epipolar residual \f$ r = |m'^T F m| \f$ that
  every such distance shares. A line with a null normal is the epipolar line of an epipole: the distance is 0 if the
  residual is, infinite otherwise.
*/
double lineDistance(double residual, const Eigen::Vector3d &l)
{
  const double normal = l.head<2>().norm();
  if (normal > 0.0) {
    return residual / normal;
  }
  return residual == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
}

//! vpServo's default pseudo-inverse threshold: singular values below it times the largest count as zero.
const double kPseudoInverseThreshold = 1e-6;

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
      m_lambdaUsed(0.0), m_saturated(false), m_states(), m_tracked(), m_M0(), m_hasM0(), m_epipolarDistance(),
      m_predictionDistance(), m_width(0), m_height(0), m_border(0.0), m_outlierThreshold(0.0), m_rankTolerance(1e-6),
      m_status(SERVO_RUNNING), m_nbActive(0), m_ratioValid(true), m_ratio(0.0), m_b(), m_errorNorm(0.0),
      m_jointLimits(false), m_qmin(), m_qmax(), m_rho(0.1), m_rho1(0.3), m_lambdaTune(0.7), m_e0(0.1), m_e1(0.7),
      m_qdot2()
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

void vpServoProjective::setImageSize(unsigned int width, unsigned int height, double border)
{
  const std::string where = std::string(kClass) + "::setImageSize()";
  requireFinite(border, where, "the border");
  if ((width == 0) != (height == 0)) {
    std::ostringstream os;
    os << "the image size " << width << " x " << height << " has one zero side; give both sides, or 0 x 0 to "
       << "disable the image check";
    fail(vpProjectiveException::invalidValueError, where, os.str());
  }
  if (border < 0.0) {
    fail(vpProjectiveException::invalidValueError, where, "the border must be non-negative (pixels)");
  }
  if (width > 0 && (2.0 * border > width - 1.0 || 2.0 * border > height - 1.0)) {
    std::ostringstream os;
    os << "a border of " << border << " px leaves no pixel of a " << width << " x " << height << " image";
    fail(vpProjectiveException::invalidValueError, where, os.str());
  }
  m_width = width;
  m_height = height;
  m_border = border;
}

void vpServoProjective::checkFeatureIndex(unsigned int i, const char *method) const
{
  if (i >= m_features.size()) {
    std::ostringstream os;
    os << "feature index " << i << " is out of range; the task has " << m_features.size()
       << " features (indices in addFeature() order, from 0)";
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
}

void vpServoProjective::setFeatureTracked(unsigned int i, bool tracked)
{
  checkFeatureIndex(i, "setFeatureTracked()");
  m_tracked[i] = tracked ? 1 : 0;
}

bool vpServoProjective::isFeatureTracked(unsigned int i) const
{
  checkFeatureIndex(i, "isFeatureTracked()");
  return m_tracked[i] != 0;
}

void vpServoProjective::setOutlierThreshold(double pixels)
{
  const std::string where = std::string(kClass) + "::setOutlierThreshold()";
  requireFinite(pixels, where, "the outlier threshold");
  if (pixels < 0.0) {
    fail(vpProjectiveException::invalidValueError, where,
         "the outlier threshold must be non-negative (pixels; 0 disables the outlier rejection)");
  }
  m_outlierThreshold = pixels;
}

void vpServoProjective::setRankTolerance(double tolerance)
{
  const std::string where = std::string(kClass) + "::setRankTolerance()";
  requireFinite(tolerance, where, "the rank tolerance");
  if (!(tolerance > 0.0) || !(tolerance < 1.0)) {
    fail(vpProjectiveException::invalidValueError, where,
         "the rank tolerance is a ratio of singular values and must be in (0, 1), e.g. 1e-6");
  }
  m_rankTolerance = tolerance;
  m_ratioValid = false;
}

void vpServoProjective::setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double rho, double rho1,
                                       double lambdaTune)
{
  const char *const method = "setJointLimits()";
  const std::string where = at(method);
  if (qmin.getRows() != qmax.getRows()) {
    std::ostringstream os;
    os << "qmin has " << qmin.getRows() << " entries and qmax " << qmax.getRows() << "; give one limit per joint";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  const unsigned int n = qmin.getRows();
  if (n == 0 || n > vpProjectiveRobot::maxJoints) {
    std::ostringstream os;
    os << "qmin and qmax have " << n << " entries; a chain has 1 to " << vpProjectiveRobot::maxJoints << " joints";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (m_robot != nullptr && n != m_robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << "qmin and qmax have " << n << " entries but the robot has " << m_robot->getNumberOfJoints() << " joints";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  for (unsigned int i = 0; i < n; ++i) {
    requireFinite(qmin[i], where, "qmin");
    requireFinite(qmax[i], where, "qmax");
    if (!(qmin[i] < qmax[i])) {
      std::ostringstream os;
      os << "joint " << i << ": qmin (" << qmin[i] << ") must be below qmax (" << qmax[i] << ")";
      fail(vpProjectiveException::invalidValueError, where, os.str());
    }
  }
  requireFinite(rho, where, "rho");
  requireFinite(rho1, where, "rho1");
  requireFinite(lambdaTune, where, "lambdaTune");
  if (!(rho > 0.0) || rho > 0.5) {
    fail(vpProjectiveException::invalidValueError, where,
         "rho must be in (0, 1/2]: the activation band is a fraction of the range at each end, and the bands of "
         "both ends must not overlap");
  }
  if (!(rho1 > 0.0) || rho1 > 1.0) {
    fail(vpProjectiveException::invalidValueError, where, "rho1 must be in (0, 1]");
  }
  if (lambdaTune < 0.0 || lambdaTune > 1.0) {
    fail(vpProjectiveException::invalidValueError, where, "lambdaTune must be in [0, 1]");
  }
  m_qmin.resize(n);
  m_qmax.resize(n);
  for (unsigned int i = 0; i < n; ++i) {
    m_qmin(i) = qmin[i];
    m_qmax(i) = qmax[i];
  }
  m_rho = rho;
  m_rho1 = rho1;
  m_lambdaTune = lambdaTune;
  m_jointLimits = true;
}

void vpServoProjective::setLargeProjectionThresholds(double e0, double e1)
{
  const std::string where = at("setLargeProjectionThresholds()");
  requireFinite(e0, where, "e0");
  requireFinite(e1, where, "e1");
  if (!(e0 >= 0.0) || !(e1 > e0)) {
    fail(vpProjectiveException::invalidValueError, where, "the thresholds must satisfy 0 <= e0 < e1 (pixels)");
  }
  m_e0 = e0;
  m_e1 = e1;
}

void vpServoProjective::clearJointLimits()
{
  m_jointLimits = false;
}

void vpServoProjective::checkJointLimitSize(unsigned int n, const char *method) const
{
  if (m_jointLimits && static_cast<unsigned int>(m_qmin.size()) != n) {
    std::ostringstream os;
    os << "the joint limits have " << m_qmin.size() << " entries but the robot has " << n
       << " joints; call setJointLimits() again";
    fail(vpProjectiveException::dimensionError, at(method), os.str());
  }
}

void vpServoProjective::addFeature(vpFeatureStereoPoint &s, vpFeatureStereoPoint &s_star)
{
  m_features.push_back(&s);
  m_desired.push_back(&s_star);
  m_states.push_back(FEATURE_ACTIVE);
  m_tracked.push_back(1);
  m_M0.push_back(Eigen::Vector4d::Zero());
  m_hasM0.push_back(0);
  m_epipolarDistance.push_back(-1.0);
  m_predictionDistance.push_back(-1.0);
}

void vpServoProjective::clearFeatures()
{
  m_features.clear();
  m_desired.clear();
  m_states.clear();
  m_tracked.clear();
  m_M0.clear();
  m_hasM0.clear();
  m_epipolarDistance.clear();
  m_predictionDistance.clear();
  m_status = SERVO_RUNNING;
  m_nbActive = 0;
}

vpServoProjective::vpFeatureState vpServoProjective::getFeatureState(unsigned int i) const
{
  checkFeatureIndex(i, "getFeatureState()");
  return m_states[i];
}

double vpServoProjective::getEpipolarDistance(unsigned int i) const
{
  checkFeatureIndex(i, "getEpipolarDistance()");
  return m_epipolarDistance[i];
}

double vpServoProjective::getPredictionDistance(unsigned int i) const
{
  checkFeatureIndex(i, "getPredictionDistance()");
  return m_predictionDistance[i];
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

void vpServoProjective::computeSingularValueRatio() const
{
  // sigma(J D^-1)^2 are the eigenvalues of D^-1 J^T J D^-1, D = diag(||J_k||): the Gram matrix with unit diagonal.
  const Eigen::Index n = m_JtJ.rows();
  m_ratioValid = true;
  m_ratio = 0.0;
  vpProjectiveRobot::JointVector d(n);
  for (Eigen::Index k = 0; k < n; ++k) {
    d(k) = std::sqrt(std::max(0.0, m_JtJ(k, k)));
  }
  const double dMax = n > 0 ? d.maxCoeff() : 0.0;
  if (!(dMax > 0.0) || !(d.minCoeff() > m_rankTolerance * dMax)) {
    return; // a joint that moves no active feature, or too little to tell
  }
  JointMatrix C(n, n);
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = 0; r < n; ++r) {
      C(r, c) = m_JtJ(r, c) / (d(r) * d(c));
    }
  }
  Eigen::SelfAdjointEigenSolver<JointMatrix> eig(C, Eigen::EigenvaluesOnly);
  const double lambdaMax = eig.eigenvalues()(n - 1);
  if (lambdaMax > 0.0) {
    m_ratio = std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / lambdaMax);
  }
}

double vpServoProjective::getSingularValueRatio() const
{
  if (!m_ratioValid) {
    computeSingularValueRatio();
  }
  return m_ratio;
}

void vpServoProjective::largeProjectionOperator(JointMatrix &P) const
{
  // P = sig P_e + (1 - sig) (I - J^+ J), vpServo::computeProjectionOperators() with its thresholds on ||e||.
  const Eigen::Index n = m_JtJ.rows();
  double sig = 0.0;
  if (m_errorNorm > m_e1) {
    sig = 1.0;
  } else if (m_errorNorm >= m_e0) {
    sig = 1.0 / (1.0 + std::exp(-12.0 * (m_errorNorm - m_e0) / (m_e1 - m_e0) + 6.0));
  }
  const double pp = m_b.squaredNorm(); // e^T J J^T e
  if (!(pp > 0.0)) {
    sig = 0.0; // J^T e = 0: P_e is undefined (vpServo would divide by zero)
  }
  P.setIdentity(n, n);
  if (sig > 0.0) {
    P.noalias() -= (m_b / pp) * m_b.transpose();
    P *= sig;
  } else {
    P.setZero(n, n);
  }
  if (sig < 1.0) {
    // I - J^+ J: the eigenvectors of J^T J whose singular value is below vpServo's threshold.
    Eigen::SelfAdjointEigenSolver<JointMatrix> eig(m_JtJ, Eigen::ComputeEigenvectors);
    const double lambdaMax = eig.eigenvalues()(n - 1);
    const double zero = kPseudoInverseThreshold * kPseudoInverseThreshold * std::max(0.0, lambdaMax);
    for (Eigen::Index k = 0; k < n; ++k) {
      if (eig.eigenvalues()(k) <= zero) {
        P.noalias() += (1.0 - sig) * eig.eigenvectors().col(k) * eig.eigenvectors().col(k).transpose();
      }
    }
  }
}

void vpServoProjective::jointLimitAvoidance(const vpProjectiveRobot::JointVector &q,
                                            const vpProjectiveRobot::JointVector &dq,
                                            vpProjectiveRobot::JointVector &q2) const
{
  // vpServo::secondaryTaskJointLimitAvoidance() with the large projection operator, dq the primary velocity.
  const Eigen::Index n = q.size();
  q2.setZero(n);
  JointMatrix P;
  bool haveP = false;
  for (Eigen::Index i = 0; i < n; ++i) {
    const double range = m_qmax(i) - m_qmin(i);
    const double l0min = m_qmin(i) + m_rho * range;
    const double l0max = m_qmax(i) - m_rho * range;
    double g = 0.0;
    if (q(i) < l0min) {
      g = -1.0;
    } else if (q(i) > l0max) {
      g = 1.0;
    }
    if (g == 0.0) {
      continue; // inside the free interval (on its boundary vpServo's b is infinite: no action either)
    }
    if (!haveP) {
      largeProjectionOperator(P);
      haveP = true;
    }
    // (P g_i)_i = g P_ii, P_ii >= 0.
    const double Pii = std::abs(P(i, i));
    if (!(Pii > 0.0)) {
      continue;
    }
    const double b = std::abs(dq(i)) / Pii;
    if (!(b < 1.0)) {
      continue; // vpServo: a large ratio does not activate the avoidance of this joint
    }
    const double l1min = l0min - m_rho * m_rho1 * range;
    const double l1max = l0max + m_rho * m_rho1 * range;
    double lambdaL = 1.0;
    if (q(i) >= l0max && q(i) <= l1max) {
      lambdaL = 1.0 / (1.0 + std::exp(-12.0 * (q(i) - l0max) / (l1max - l0max) + 6.0));
    } else if (q(i) >= l1min && q(i) <= l0min) {
      lambdaL = 1.0 / (1.0 + std::exp(-12.0 * (q(i) - l0min) / (l1min - l0min) + 6.0));
    }
    q2.noalias() -= (lambdaL * (1.0 + m_lambdaTune) * b * g) * P.col(i);
  }
}

vpMatrix vpServoProjective::getLargeProjectionOperator() const
{
  if (m_JtJ.rows() == 0) {
    fail(vpProjectiveException::notInitializedError, at("getLargeProjectionOperator()"),
         "no task Jacobian yet; call computeControlLaw() first");
  }
  JointMatrix P;
  largeProjectionOperator(P);
  return toVisp(P);
}

vpColVector vpServoProjective::getJointLimitVelocity() const
{
  return toVispVector(m_qdot2);
}

vpServoProjective::vpFeatureState vpServoProjective::classify(size_t i, const Eigen::Vector4d &s,
                                                              const Eigen::Vector4d &sStar, bool predict,
                                                              const Eigen::Matrix4d &H)
{
  m_epipolarDistance[i] = -1.0;
  m_predictionDistance[i] = -1.0;
  if (!m_tracked[i]) {
    return FEATURE_NOT_TRACKED;
  }
  if (!s.allFinite() || !sStar.allFinite()) {
    return FEATURE_NOT_FINITE;
  }
  if (m_width > 0) {
    const double uMax = m_width - 1.0 - m_border;
    const double vMax = m_height - 1.0 - m_border;
    if (s(0) < m_border || s(0) > uMax || s(1) < m_border || s(1) > vMax || s(2) < m_border || s(2) > uMax ||
        s(3) < m_border || s(3) > vMax) {
      return FEATURE_OUT_OF_IMAGE;
    }
  }
  if (m_outlierThreshold > 0.0) {
    const vpProjectiveStereoRig &rig = m_robot->getStereoRig();
    const Eigen::Matrix3d &F = rig.fundamentalMatrix();
    const Eigen::Vector3d m(s(0), s(1), 1.0);
    const Eigen::Vector3d mp(s(2), s(3), 1.0);
    const Eigen::Vector3d lp = F * m;             // epipolar line of m in the right image
    const Eigen::Vector3d l = F.transpose() * mp; // epipolar line of m' in the left image
    const double residual = std::abs(mp.dot(lp));
    const double dF = std::max(lineDistance(residual, l), lineDistance(residual, lp));
    m_epipolarDistance[i] = dF;
    if (!(dF <= m_outlierThreshold)) {
      return FEATURE_OUTLIER;
    }
    if (predict && m_hasM0[i]) {
      Eigen::Vector4d sHat;
      if (rig.project(H * m_M0[i], sHat)) {
        const double dP = std::max((sHat.head<2>() - s.head<2>()).norm(), (sHat.tail<2>() - s.tail<2>()).norm());
        m_predictionDistance[i] = dP;
        if (!(dP <= m_outlierThreshold)) {
          return FEATURE_OUTLIER;
        }
      }
    }
  }
  return FEATURE_ACTIVE;
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
  checkJointLimitSize(static_cast<unsigned int>(n), method);
  if (m_J.rows() != rows || m_J.cols() != n) {
    m_J.resize(rows, n);
    m_e.resize(rows);
  }

  // Task Jacobian, eq. (46) stacked over the active points, at the current q and triangulated points; the rows of
  // the features set aside are zero.
  Eigen::Matrix4d HhatKq[vpProjectiveRobot::maxJoints];
  m_robot->jointMotions(q, HhatKq);
  const vpProjectiveStereoRig &rig = m_robot->getStereoRig();
  // Outlier rejection predicts each feature from its last acceptance: H(q) and its LU, for M(0) = H(q)^-1 M.
  const bool predict = m_outlierThreshold > 0.0;
  Eigen::Matrix4d H = Eigen::Matrix4d::Identity();
  Eigen::PartialPivLU<Eigen::Matrix4d> Hlu;
  if (predict) {
    H = m_robot->displacement(q);
    Hlu.compute(H);
  }
  vpProjectiveRobot::PointJacobian Ji;
  unsigned int active = 0;
  for (size_t i = 0; i < m_features.size(); ++i) {
    const Eigen::Vector4d s = m_features[i]->getFeature();
    const Eigen::Vector4d sStar = m_desired[i]->getFeature();
    const Eigen::Index r = 4 * static_cast<Eigen::Index>(i);
    m_states[i] = classify(i, s, sStar, predict, H);
    if (m_states[i] != FEATURE_ACTIVE) {
      m_J.middleRows(r, 4).setZero();
      m_e.segment<4>(r).setZero();
      continue;
    }
    const Eigen::Vector4d M = rig.triangulateLinear(s.head<2>(), s.tail<2>());
    if (!m_robot->imageJacobian(HhatKq, M, Ji)) {
      std::ostringstream os;
      os << "feature " << i << " triangulates onto a camera's focal plane; check that it is matched correctly";
      fail(vpProjectiveException::pointAtInfinityError, at(method), os.str());
    }
    m_J.middleRows(r, 4) = Ji;
    m_e.segment<4>(r) = s - sStar;
    if (predict) {
      m_M0[i] = Hlu.solve(M).normalized(); // H(q_l)^-1 M_l, for the next predictions
      m_hasM0[i] = 1;
    }
    ++active;
  }
  m_nbActive = active;

  // Damped least squares: qdot = -lambda (J^T J + mu^2 I)^-1 J^T e.
  // J^T J by column dot products, its lower triangle mirrored: cheaper than a matrix product kernel at these sizes.
  m_JtJ.resize(n, n);
  m_b.resize(n);
  vpProjectiveRobot::JointVector &b = m_b;
  for (Eigen::Index c = 0; c < n; ++c) {
    for (Eigen::Index r = c; r < n; ++r) {
      m_JtJ(r, c) = m_J.col(r).dot(m_J.col(c));
    }
    for (Eigen::Index r = 0; r < c; ++r) {
      m_JtJ(r, c) = m_JtJ(c, r);
    }
    b(c) = m_J.col(c).dot(m_e);
  }
  m_errorNorm = m_e.norm();
  m_spectrumValid = false;
  m_ratioValid = false;

  // Status. With every feature active the task is the user's: a rank loss is left to the damping, as before. With
  // features set aside, the remaining ones must constrain every joint: a stereo point gives at most 3 independent
  // equations, then the scale-aware rank test on J D^-1.
  if (active == m_features.size()) {
    m_status = SERVO_RUNNING;
  } else {
    bool stopped = 3 * static_cast<Eigen::Index>(active) < n;
    if (!stopped) {
      computeSingularValueRatio();
      stopped = !(m_ratio >= m_rankTolerance);
    }
    m_status = stopped ? SERVO_STOPPED : SERVO_REDUCED;
  }
  m_qdot2.setZero(n);
  if (m_status == SERVO_STOPPED) {
    qdot.setZero(n);
    m_damping = 0.0;
    m_lambdaUsed = 0.0;
    m_saturated = false;
    return;
  }
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
  // Primary velocity, saturated: the motion the arm really makes, hence the dq of the joint-limit avoidance.
  qdot = -m_lambdaUsed * x;
  double largest = qdot.cwiseAbs().maxCoeff();
  m_saturated = m_qdotMax > 0.0 && largest > m_qdotMax;
  if (m_saturated) {
    qdot *= m_qdotMax / largest;
  }
  if (m_jointLimits) {
    jointLimitAvoidance(q, qdot, m_qdot2);
    qdot += m_qdot2;
    largest = qdot.cwiseAbs().maxCoeff();
    if (m_qdotMax > 0.0 && largest > m_qdotMax) {
      qdot *= m_qdotMax / largest;
      m_saturated = true;
    }
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
