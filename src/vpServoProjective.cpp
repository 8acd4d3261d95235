/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

#include <visp3/projective/vpServoProjective.h>

#include <cmath>
#include <limits>
#include <sstream>

#include <Eigen/Dense>

#include "vpProjectiveInternal.h"

using namespace vpProjectiveInternal;

namespace
{
const char *const kClass = "vpServoProjective";
}

vpServoProjective::vpServoProjective()
  : m_robot(nullptr), m_features(), m_desired(), m_lambda(0.5), m_sigmaThreshold(30.0), m_maxDamping(30.0),
    m_qdotMax(0.0), m_J(), m_e(), m_condition(0.0), m_damping(0.0), m_lambdaUsed(0.0), m_saturated(false)
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

void vpServoProjective::setLambda(const vpAdaptiveGain &lambda) { m_lambda = lambda; }

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

void vpServoProjective::check(const std::string &where) const
{
  if (m_robot == nullptr) {
    fail(vpProjectiveException::notInitializedError, where, "no robot model; call setRobot() first");
  }
  if (m_features.empty()) {
    fail(vpProjectiveException::notInitializedError, where, "no feature; call addFeature(s, s_star) first");
  }
  if (4 * m_features.size() < m_robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << m_features.size() << " stereo points give " << 4 * m_features.size() << " equations for "
       << m_robot->getNumberOfJoints() << " joints; add features";
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
}

void vpServoProjective::computeControlLaw(const vpProjectiveRobot::JointVector &q, vpProjectiveRobot::JointVector &qdot)
{
  const std::string where = std::string(kClass) + "::computeControlLaw()";
  check(where);
  const Eigen::Index n = static_cast<Eigen::Index>(m_robot->getNumberOfJoints());
  const Eigen::Index rows = 4 * static_cast<Eigen::Index>(m_features.size());
  if (q.size() != n) {
    std::ostringstream os;
    os << "q must have " << n << " entries, got " << q.size();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (!q.allFinite()) {
    fail(vpProjectiveException::nonFiniteValueError, where, "q has a NaN or infinite entry");
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
      fail(vpProjectiveException::pointAtInfinityError, where, os.str());
    }
    const Eigen::Index r = 4 * static_cast<Eigen::Index>(i);
    m_J.middleRows(r, 4) = Ji;
    m_e.segment<4>(r) = s - sStar;
  }

  // Damped least squares: qdot = -lambda (J^T J + mu^2 I)^-1 J^T e.
  typedef Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, vpProjectiveRobot::maxJoints,
                        vpProjectiveRobot::maxJoints>
      JointMatrix;
  JointMatrix A = m_J.transpose() * m_J;
  const vpProjectiveRobot::JointVector b = m_J.transpose() * m_e;
  Eigen::SelfAdjointEigenSolver<JointMatrix> eig(A, Eigen::EigenvaluesOnly);
  const double sigmaMin = std::sqrt(std::max(0.0, eig.eigenvalues()(0)));
  const double sigmaMax = std::sqrt(std::max(0.0, eig.eigenvalues()(n - 1)));
  m_condition = sigmaMin > 0.0 ? sigmaMax / sigmaMin : std::numeric_limits<double>::infinity();
  double mu2 = 0.0;
  if (sigmaMin < m_sigmaThreshold) {
    const double ratio = sigmaMin / m_sigmaThreshold;
    mu2 = m_maxDamping * m_maxDamping * (1.0 - ratio * ratio);
  }
  m_damping = std::sqrt(mu2);
  A.diagonal().array() += mu2;
  m_lambdaUsed = m_lambda(m_e.cwiseAbs().maxCoeff());
  qdot = -m_lambdaUsed * A.ldlt().solve(b);
  const double largest = qdot.cwiseAbs().maxCoeff();
  m_saturated = m_qdotMax > 0.0 && largest > m_qdotMax;
  if (m_saturated) {
    qdot *= m_qdotMax / largest;
  }
  if (!qdot.allFinite()) {
    fail(vpProjectiveException::estimationFailedError, where,
         "the control law gave a non-finite velocity (singular task Jacobian); increase the damping");
  }
}

vpColVector vpServoProjective::computeControlLaw(const vpColVector &q)
{
  const std::string where = std::string(kClass) + "::computeControlLaw()";
  check(where);
  if (q.getRows() != m_robot->getNumberOfJoints()) {
    std::ostringstream os;
    os << "q must have " << m_robot->getNumberOfJoints() << " entries, got " << q.getRows();
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  vpProjectiveRobot::JointVector qe(q.getRows()), qdot(q.getRows());
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    qe(i) = q[i];
  }
  computeControlLaw(qe, qdot);
  return toVispVector(qdot);
}

vpColVector vpServoProjective::getError() const { return toVispVector(m_e); }

vpMatrix vpServoProjective::getTaskJacobian() const { return toVisp(m_J); }
