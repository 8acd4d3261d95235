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

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <thread>

#include <Eigen/Dense>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/robot/vpAfma4.h>
#include <visp3/robot/vpAfma6.h>
#include <visp3/robot/vpViper.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
std::string at(const char *method)
{
  return std::string("vpProjectiveAcquisitionProcedure::") + method;
}

void checkPerJoint(const vpColVector &v, bool allowZero, const char *method, const char *name)
{
  for (unsigned int i = 0; i < v.size(); ++i) {
    if (!std::isfinite(v[i])) {
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                  at(method) + ": " + name + " has a non-finite value: give finite values.");
    }
    if (v[i] < 0.0 || (!allowZero && v[i] == 0.0)) {
      throw vpProjectiveException(
          vpProjectiveException::invalidValueError,
          at(method) + ": " + name + "[" + std::to_string(i) + "] = " + std::to_string(v[i]) +
              (allowZero ? " is negative: give values >= 0." : " is not positive: give values > 0."));
    }
  }
}

void checkScalar(double x, const char *method, const char *name)
{
  if (!std::isfinite(x) || x < 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at(method) + ": " + name + " must be finite and >= 0.");
  }
}

void checkPositive(double x, const char *method, const char *name)
{
  if (!std::isfinite(x) || x <= 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at(method) + ": " + name + " must be finite and > 0.");
  }
}

double seconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

void sleepSeconds(double s)
{
  std::this_thread::sleep_for(std::chrono::duration<double>(s));
}

const char *mountingName(vpProjectiveArmModel::vpRigMounting m)
{
  return m == vpProjectiveArmModel::EYE_TO_HAND ? "EYE_TO_HAND" : "EYE_IN_HAND";
}

typedef vpProjectiveStereoRig::Projection Projection;

//! The centre of a camera \e P: its right null vector.
Eigen::Vector4d centreOf(const Projection &P)
{
  Eigen::JacobiSVD<Eigen::Matrix4d> svd((Eigen::Matrix4d() << P, Eigen::RowVector4d::Zero()).finished(),
                                        Eigen::ComputeFullV);
  return svd.matrixV().col(3);
}

bool pixelOf(const Projection &P, const Eigen::Vector4d &X, Eigen::Vector2d &m)
{
  const Eigen::Vector3d x = P * X;
  if (!(std::abs(x(2)) > 1e-12 * x.norm())) {
    return false;
  }
  m = x.head<2>() / x(2);
  return true;
}

/*!
  Plane parallax (pixels) of the point \e X to the plane \e plane: in each image, the distance between the image of
  X and that of the point where the other camera's line of sight through X meets the plane (along the epipolar
  line); the larger of the two. Zero when X is on the plane, whatever the projective frame.
*/
double planeParallax(const Projection &P, const Projection &Pp, const Eigen::Vector4d &centre,
                     const Eigen::Vector4d &centrep, const Eigen::Vector4d &plane, const Eigen::Vector4d &X)
{
  double parallax = 0.0;
  for (int camera = 0; camera < 2; ++camera) {
    const Eigen::Vector4d &c = camera == 0 ? centre : centrep; // the line of sight's camera
    const Projection &Q = camera == 0 ? Pp : P;                // the image where the parallax shows
    const Eigen::Vector4d Y = plane.dot(c) * X - plane.dot(X) * c;
    Eigen::Vector2d x, y;
    if (pixelOf(Q, X, x) && pixelOf(Q, Y, y)) {
      parallax = std::max(parallax, (x - y).norm());
    }
  }
  return parallax;
}

/*!
  How far 4 points (unit 4-vectors) are from coplanar, in pixels: the RMS plane parallax of the 4 to the plane that
  fits them best (the least singular vector of their 4 x 4 matrix). Noise of sigma per image coordinate gives about
  sigma; 4 points spanning a few centimetres in depth give tens of pixels.
*/
double coplanarity(const Projection &P, const Projection &Pp, const Eigen::Vector4d &centre,
                   const Eigen::Vector4d &centrep, const Eigen::Vector4d &A, const Eigen::Vector4d &B,
                   const Eigen::Vector4d &C, const Eigen::Vector4d &D)
{
  Eigen::Matrix4d T;
  T << A.transpose(), B.transpose(), C.transpose(), D.transpose();
  Eigen::JacobiSVD<Eigen::Matrix4d> svd(T, Eigen::ComputeFullV);
  const Eigen::Vector4d plane = svd.matrixV().col(3);
  double sum = 0.0;
  for (const Eigen::Vector4d *X : {&A, &B, &C, &D}) {
    const double p = planeParallax(P, Pp, centre, centrep, plane, *X);
    sum += p * p;
  }
  return std::sqrt(sum / 4.0);
}

/*!
  The general-position margin of the points \e X (pixels): over the sets of 5 points, the largest of the smallest
  coplanarity() of 4 points of the set; \e best receives that set. At most the first 24
  points are examined (a lower bound for more).
*/
double generalPositionParallax(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &X,
                               std::vector<unsigned int> &best)
{
  const Projection &P = rig.leftProjection(), &Pp = rig.rightProjection();
  const Eigen::Vector4d c = centreOf(P), cp = centreOf(Pp);
  const unsigned int K = static_cast<unsigned int>(std::min<size_t>(X.size(), 24));
  std::vector<double> c4(static_cast<size_t>(K) * K * K * K, 0.0);
  auto index = [K](unsigned int a, unsigned int b, unsigned int d, unsigned int e) {
    return ((static_cast<size_t>(a) * K + b) * K + d) * K + e;
  };
  for (unsigned int a = 0; a < K; ++a) {
    for (unsigned int b = a + 1; b < K; ++b) {
      for (unsigned int d = b + 1; d < K; ++d) {
        for (unsigned int e = d + 1; e < K; ++e) {
          c4[index(a, b, d, e)] = coplanarity(P, Pp, c, cp, X[a], X[b], X[d], X[e]);
        }
      }
    }
  }
  double margin = 0.0;
  best.clear();
  for (unsigned int a = 0; a < K; ++a) {
    for (unsigned int b = a + 1; b < K; ++b) {
      for (unsigned int d = b + 1; d < K; ++d) {
        for (unsigned int e = d + 1; e < K; ++e) {
          for (unsigned int f = e + 1; f < K; ++f) {
            const double g = std::min({c4[index(b, d, e, f)], c4[index(a, d, e, f)], c4[index(a, b, e, f)],
                                       c4[index(a, b, d, f)], c4[index(a, b, d, e)]});
            if (g > margin) {
              margin = g;
              best = {a, b, d, e, f};
            }
          }
        }
      }
    }
  }
  return margin;
}

/*!
  RMS distance (pixels) between the right images and the left ones mapped by the least-squares homography of all
  the pairs (DLT on Hartley-normalised points): at the noise level when the markers are all on one plane.
*/
double homographyTransferError(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
{
  const size_t K = left.size();
  auto normaliser = [K](const std::vector<vpImagePoint> &p) {
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const vpImagePoint &q : p) {
      mean += Eigen::Vector2d(q.get_u(), q.get_v()) / static_cast<double>(K);
    }
    double spread = 0.0;
    for (const vpImagePoint &q : p) {
      spread += (Eigen::Vector2d(q.get_u(), q.get_v()) - mean).norm() / static_cast<double>(K);
    }
    const double scale = spread > 0.0 ? std::sqrt(2.0) / spread : 1.0;
    Eigen::Matrix3d T;
    T << scale, 0.0, -scale * mean(0), 0.0, scale, -scale * mean(1), 0.0, 0.0, 1.0;
    return T;
  };
  const Eigen::Matrix3d T = normaliser(left), Tp = normaliser(right);
  Eigen::MatrixXd A(2 * K, 9);
  for (size_t j = 0; j < K; ++j) {
    const Eigen::Vector3d x = T * Eigen::Vector3d(left[j].get_u(), left[j].get_v(), 1.0);
    const Eigen::Vector3d xp = Tp * Eigen::Vector3d(right[j].get_u(), right[j].get_v(), 1.0);
    A.row(2 * j) << 0.0, 0.0, 0.0, -xp(2) * x.transpose(), xp(1) * x.transpose();
    A.row(2 * j + 1) << xp(2) * x.transpose(), 0.0, 0.0, 0.0, -xp(0) * x.transpose();
  }
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A, Eigen::ComputeFullV);
  const Eigen::VectorXd h = svd.matrixV().col(8);
  Eigen::Matrix3d Hn;
  Hn << h(0), h(1), h(2), h(3), h(4), h(5), h(6), h(7), h(8);
  const Eigen::Matrix3d H = Tp.inverse() * Hn * T;
  double sum = 0.0;
  for (size_t j = 0; j < K; ++j) {
    const Eigen::Vector3d m = H * Eigen::Vector3d(left[j].get_u(), left[j].get_v(), 1.0);
    sum += std::abs(m(2)) > 0.0
               ? (m.head<2>() / m(2) - Eigen::Vector2d(right[j].get_u(), right[j].get_v())).squaredNorm()
               : std::numeric_limits<double>::infinity();
  }
  return std::sqrt(sum / static_cast<double>(K));
}

/*!
  A marker that moved, between the images \e prev and \e cur, to where another marker was: its index (and the
  other's in \e other), or -1. The markers' common image motion (their mean displacement, which a swap of two
  markers leaves unchanged) is taken out first; a marker must then be four times nearer another marker's previous
  images than its own.
*/
int orderChange(const std::vector<vpImagePoint> &prevL, const std::vector<vpImagePoint> &prevR,
                const std::vector<vpImagePoint> &l, const std::vector<vpImagePoint> &r, int &other, double &dOwn,
                double &dOther)
{
  const size_t K = l.size();
  std::vector<Eigen::Vector4d> p(K), c(K);
  Eigen::Vector4d mean = Eigen::Vector4d::Zero();
  for (size_t j = 0; j < K; ++j) {
    p[j] << prevL[j].get_u(), prevL[j].get_v(), prevR[j].get_u(), prevR[j].get_v();
    c[j] << l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v();
    mean += (c[j] - p[j]) / static_cast<double>(K);
  }
  for (size_t j = 0; j < K; ++j) {
    const double own = (c[j] - mean - p[j]).norm();
    for (size_t k = 0; k < K; ++k) {
      const double d = (c[j] - mean - p[k]).norm();
      if (k != j && d < 0.25 * own) {
        other = static_cast<int>(k);
        dOwn = own;
        dOther = d;
        return static_cast<int>(j);
      }
    }
  }
  return -1;
}

std::string jointValue(double v, bool revolute)
{
  std::ostringstream os;
  os << std::setprecision(6) << (revolute ? vpMath::deg(v) : v) << (revolute ? " deg" : " m");
  return os.str();
}
} // namespace

vpProjectiveAcquisitionProcedure::vpProjectiveAcquisitionProcedure(const vpImageSource &source, unsigned int width,
                                                                   unsigned int height)
    : m_source(source), m_width(width), m_height(height), m_maxAmounts(), m_steps(), m_minAmounts(), m_qmin(), m_qmax(),
      m_limitMargin(0.0), m_imageMargin(10.0), m_rotationSpeed(0.0), m_translationSpeed(0.0), m_epipolarThreshold(2.0),
      m_control(VELOCITY_CONTROL), m_moveTimeout(0.0), m_tolerance(1e-5), m_coplanarity(2.0), m_detectMounting(true),
      m_os(nullptr), m_callback(), m_motion(), m_reports(), m_mountingReport(), m_residual(0.0), m_parallax(-1.0),
      m_commandPeriod(0.0), m_wallPeriod(0.0), m_types(), m_lower(), m_upper()
{
  if (!m_source) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("constructor") +
                                    ": the image source is empty: give a function returning the images.");
  }
  setImageSize(width, height);
  m_mountingReport.checked = false;
  m_mountingReport.set = m_mountingReport.kept = vpProjectiveArmModel::EYE_TO_HAND;
  m_mountingReport.residual = m_mountingReport.otherResidual = -1.0;
  m_mountingReport.separation = 0.0;
}

void vpProjectiveAcquisitionProcedure::setMaxAmounts(const vpColVector &amounts)
{
  checkPerJoint(amounts, false, "setMaxAmounts", "amounts");
  m_maxAmounts = amounts;
}

void vpProjectiveAcquisitionProcedure::setSteps(const vpColVector &steps)
{
  checkPerJoint(steps, false, "setSteps", "steps");
  m_steps = steps;
}

void vpProjectiveAcquisitionProcedure::setMinAmounts(const vpColVector &amounts)
{
  checkPerJoint(amounts, true, "setMinAmounts", "amounts");
  m_minAmounts = amounts;
}

void vpProjectiveAcquisitionProcedure::setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double margin)
{
  if (qmin.size() != qmax.size()) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                at("setJointLimits") +
                                    ": qmin and qmax have different sizes: give one value per joint.");
  }
  checkScalar(margin, "setJointLimits", "margin");
  for (unsigned int i = 0; i < qmin.size(); ++i) {
    if (!std::isfinite(qmin[i]) || !std::isfinite(qmax[i])) {
      throw vpProjectiveException(vpProjectiveException::nonFiniteValueError,
                                  at("setJointLimits") + ": a limit is not finite: give finite limits.");
    }
    if (qmin[i] + 2.0 * margin >= qmax[i]) {
      throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                  at("setJointLimits") + ": joint " + std::to_string(i) +
                                      " has qmin + 2 margin >= qmax: give qmin < qmax and a smaller margin.");
    }
  }
  m_qmin = qmin;
  m_qmax = qmax;
  m_limitMargin = margin;
}

void vpProjectiveAcquisitionProcedure::setImageMargin(double pixels)
{
  checkScalar(pixels, "setImageMargin", "the margin");
  m_imageMargin = pixels;
}

void vpProjectiveAcquisitionProcedure::setImageSize(unsigned int width, unsigned int height)
{
  if (width == 0 || height == 0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("setImageSize") + ": an image size is 0: give the cameras' size in pixels.");
  }
  m_width = width;
  m_height = height;
}

void vpProjectiveAcquisitionProcedure::setSpeed(double rotation, double translation)
{
  checkScalar(rotation, "setSpeed", "the rotation speed");
  checkScalar(translation, "setSpeed", "the translation speed");
  m_rotationSpeed = rotation;
  m_translationSpeed = translation;
}

void vpProjectiveAcquisitionProcedure::setEpipolarThreshold(double pixels)
{
  if (!std::isfinite(pixels) || pixels <= 0.0) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("setEpipolarThreshold") + ": the threshold must be finite and > 0 (pixels).");
  }
  m_epipolarThreshold = pixels;
}

void vpProjectiveAcquisitionProcedure::setMotionControl(vpMotionControl control)
{
  if (control != VELOCITY_CONTROL && control != POSITION_CONTROL) {
    throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                at("setMotionControl") + ": give VELOCITY_CONTROL or POSITION_CONTROL.");
  }
  m_control = control;
}

void vpProjectiveAcquisitionProcedure::setMoveTimeout(double secondsAllowed)
{
  checkScalar(secondsAllowed, "setMoveTimeout", "the timeout (0: automatic)");
  m_moveTimeout = secondsAllowed;
}

void vpProjectiveAcquisitionProcedure::setArrivalTolerance(double tolerance)
{
  checkPositive(tolerance, "setArrivalTolerance", "the tolerance (rad or m)");
  m_tolerance = tolerance;
}

void vpProjectiveAcquisitionProcedure::setCoplanarityThreshold(double pixels)
{
  checkPositive(pixels, "setCoplanarityThreshold", "the threshold (pixels)");
  m_coplanarity = pixels;
}

std::string vpProjectiveAcquisitionProcedure::toString(vpStopReason reason)
{
  switch (reason) {
  case AMOUNT_REACHED:
    return "amount";
  case IMAGE_BORDER:
    return "image border";
  case MARKER_LOST:
    return "marker lost";
  default:
    return "joint limit";
  }
}

bool vpProjectiveAcquisitionProcedure::inside(const std::vector<vpImagePoint> &left,
                                              const std::vector<vpImagePoint> &right) const
{
  for (const std::vector<vpImagePoint> *image : {&left, &right}) {
    for (const vpImagePoint &p : *image) {
      if (!std::isfinite(p.get_u()) || !std::isfinite(p.get_v()) || p.get_u() < m_imageMargin ||
          p.get_v() < m_imageMargin || p.get_u() > m_width - 1.0 - m_imageMargin ||
          p.get_v() > m_height - 1.0 - m_imageMargin) {
        return false;
      }
    }
  }
  return true;
}

double vpProjectiveAcquisitionProcedure::amountOf(const vpColVector &v, unsigned int i, double fallback) const
{
  return v.size() == 0 ? fallback : v[i];
}

double vpProjectiveAcquisitionProcedure::stepOf(unsigned int i) const
{
  return amountOf(m_steps, i, m_types[i] == vpProjectiveJoint::REVOLUTE ? vpMath::rad(2.0) : 0.01);
}

void vpProjectiveAcquisitionProcedure::progress(const std::string &line) const
{
  if (m_os) {
    *m_os << line << std::endl; // flushed: a run whose output goes to a file shows where it is
  }
}

void vpProjectiveAcquisitionProcedure::stopRobot(vpRobot &robot) const
{
  if (!m_motion && m_control == VELOCITY_CONTROL && !m_types.empty()) {
    robot.setVelocity(vpRobot::ARTICULAR_FRAME, vpColVector(static_cast<unsigned int>(m_types.size()), 0.0));
  }
}

void vpProjectiveAcquisitionProcedure::checkArrival(vpRobot &robot, const vpColVector &q, double tolerance,
                                                    const char *how) const
{
  vpColVector reading;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, reading);
  for (unsigned int k = 0; k < q.size(); ++k) {
    const bool revolute = m_types[k] == vpProjectiveJoint::REVOLUTE;
    const double allowed = std::max(tolerance, 0.1 * stepOf(k));
    if (reading.size() != q.size() || !(std::abs(reading[k] - q[k]) <= allowed)) {
      std::ostringstream os;
      os << at("run") << ": joint " << k << " did not arrive: commanded " << jointValue(q[k], revolute) << ", read "
         << (reading.size() == q.size() ? jointValue(reading[k], revolute) : std::string("nothing")) << " after " << how
         << " (allowed " << jointValue(allowed, revolute)
         << "): check the robot (joint limit, state, controller), or use setMotionControl(VELOCITY_CONTROL).";
      throw vpProjectiveException(vpProjectiveException::robotMotionError, os.str());
    }
  }
}

void vpProjectiveAcquisitionProcedure::moveByVelocity(vpRobot &robot, const vpColVector &target, double tolerance)
{
  const unsigned int n = target.size();
  vpColVector q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  std::vector<double> vmax(n);
  double travel = 0.0;
  for (unsigned int k = 0; k < n; ++k) {
    vmax[k] =
        m_types[k] == vpProjectiveJoint::REVOLUTE ? robot.getMaxRotationVelocity() : robot.getMaxTranslationVelocity();
    if (!(vmax[k] > 0.0)) {
      throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                  at("run") + ": the robot's largest joint velocity is not positive: give one "
                                              "(setSpeed(), or vpRobot::setMaxRotationVelocity()).");
    }
    travel = std::max(travel, std::abs(target[k] - q[k]) / vmax[k]);
  }
  const double timeout = m_moveTimeout > 0.0 ? m_moveTimeout : 2.0 + 4.0 * travel;
  const double t0 = seconds();
  vpColVector v(n, 0.0);
  auto fail = [&](const char *what) {
    stopRobot(robot);
    unsigned int worst = 0;
    for (unsigned int k = 1; k < n; ++k) {
      if (std::abs(target[k] - q[k]) * vmax[worst] > std::abs(target[worst] - q[worst]) * vmax[k]) {
        worst = k;
      }
    }
    const bool revolute = m_types[worst] == vpProjectiveJoint::REVOLUTE;
    std::ostringstream os;
    os << at("run") << ": joint " << worst << " did not arrive within " << timeout << " s (" << what << "): commanded "
       << jointValue(target[worst], revolute) << ", read " << jointValue(q[worst], revolute) << ", velocity "
       << v[worst] << (revolute ? " rad/s" : " m/s")
       << "; the robot was stopped. Check that setVelocity(ARTICULAR_FRAME) moves this joint (robot state, joint "
          "limit, emergency stop), or raise setMoveTimeout(), or use setMotionControl(POSITION_CONTROL).";
    throw vpProjectiveException(vpProjectiveException::robotMotionError, os.str());
  };
  for (;;) {
    bool arrived = true;
    for (unsigned int k = 0; k < n; ++k) {
      arrived = arrived && std::abs(target[k] - q[k]) <= tolerance;
    }
    if (arrived) {
      // Stop, then read again once a command period has passed: the joint must stay within the tolerance.
      v = 0.0;
      robot.setVelocity(vpRobot::ARTICULAR_FRAME, v);
      sleepSeconds(std::min(0.1, std::max(0.001, 1.5 * m_wallPeriod)));
      robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
      bool still = true;
      for (unsigned int k = 0; k < n; ++k) {
        still = still && std::abs(target[k] - q[k]) <= tolerance;
      }
      if (still) {
        return;
      }
      if (seconds() - t0 > timeout) {
        fail("it moved off the target after the stop");
      }
      continue;
    }
    const double dt = m_commandPeriod > 0.0 ? m_commandPeriod : 0.05;
    unsigned int fastest = 0;
    for (unsigned int k = 0; k < n; ++k) {
      const double e = target[k] - q[k];
      v[k] = std::abs(e) <= tolerance ? 0.0 : std::max(-vmax[k], std::min(vmax[k], e / dt));
      if (std::abs(v[k]) * vmax[fastest] > std::abs(v[fastest]) * vmax[k]) {
        fastest = k;
      }
    }
    robot.setVelocity(vpRobot::ARTICULAR_FRAME, v);
    // Wait for the reading to change: one command period of a real-time controller, or the one step a simulator
    // in its constant sampling time mode makes per command. No change within 0.1 s: command again.
    const double tc = seconds();
    vpColVector next = q;
    bool changed = false;
    while (!changed && seconds() - tc < 0.1) {
      sleepSeconds(0.0002);
      robot.getPosition(vpRobot::ARTICULAR_FRAME, next);
      for (unsigned int k = 0; k < n && !changed; ++k) {
        changed = next[k] != q[k];
      }
      if (seconds() - t0 > timeout) {
        fail("the joint readings did not reach the target");
      }
    }
    if (changed) {
      m_wallPeriod = seconds() - tc;
    }
    if (changed && v[fastest] != 0.0) {
      const double observed = (next[fastest] - q[fastest]) / v[fastest];
      if (observed > 1e-4 && observed < 0.5 && std::abs(next[fastest] - q[fastest]) > 1e-9) {
        m_commandPeriod = observed;
      }
    }
    q = next;
    if (seconds() - t0 > timeout) {
      fail("the joint readings did not reach the target");
    }
  }
}

void vpProjectiveAcquisitionProcedure::moveTo(vpRobot &robot, const vpColVector &q, double tolerance, bool check)
{
  if (m_motion) {
    m_motion(robot, q);
    if (check) {
      checkArrival(robot, q, tolerance, "the motion of setMotion()");
    }
  } else if (m_control == POSITION_CONTROL) {
    robot.setPosition(vpRobot::ARTICULAR_FRAME, q);
    if (check) {
      checkArrival(robot, q, tolerance, "setPosition()");
    }
  } else {
    moveByVelocity(robot, q, tolerance);
  }
}

void vpProjectiveAcquisitionProcedure::checkGeneralPosition(const vpProjectiveStereoRig &rig,
                                                            const std::vector<vpImagePoint> &left,
                                                            const std::vector<vpImagePoint> &right, const char *when)
{
  std::vector<Eigen::Vector4d> X(left.size());
  for (size_t j = 0; j < left.size(); ++j) {
    X[j] = rig.triangulate(Eigen::Vector2d(left[j].get_u(), left[j].get_v()),
                           Eigen::Vector2d(right[j].get_u(), right[j].get_v()));
  }
  std::vector<unsigned int> best;
  m_parallax = generalPositionParallax(rig, X, best);
  if (!(m_parallax >= m_coplanarity)) {
    std::ostringstream os;
    os << at("run") << ": the " << left.size() << " markers are too close to coplanar (" << when
       << "): every set of 5 markers has 4 within " << m_parallax
       << " px RMS of plane parallax of a plane (setCoplanarityThreshold(): " << m_coplanarity
       << " px). A rigid motion is only determined by 5 markers of which no 4 are coplanar (a planar target, or "
          "points on a plane and one more, leaves a family of motions that fit the images): add markers off the plane "
          "of the others, a few centimetres in depth (on the tool eye-to-hand, in the scene eye-in-hand).";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  std::ostringstream os;
  os << "  markers in general position: markers " << best[0] << ", " << best[1] << ", " << best[2] << ", " << best[3]
     << ", " << best[4] << " have no 4 within " << m_parallax << " px RMS of plane parallax of a plane (" << when
     << ")";
  progress(os.str());
}

void vpProjectiveAcquisitionProcedure::checkZeroReference(const vpProjectiveArmAcquisition &acquisition,
                                                          const std::vector<vpImagePoint> &left,
                                                          const std::vector<vpImagePoint> &right)
{
  // "Markers" in both mountings: the points the rig tracks, wherever they are.
  const std::string where = acquisition.getRigMounting() == vpProjectiveArmModel::EYE_IN_HAND
                                ? " (static in the scene, seen by the cameras on the hand)"
                                : " (on the tool, seen by the rig; static in the scene if the cameras ride on the arm)";
  if (left.size() != right.size()) {
    std::ostringstream os;
    os << at("run") << ": the image source gave " << left.size() << " left and " << right.size()
       << " right images of the markers" << where << " at the zero reference: give both images of every marker, in "
       << "the same order.";
    throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
  }
  if (left.size() < 5) {
    std::ostringstream os;
    os << at("run") << ": " << left.size() << " markers at the zero reference" << where
       << "; the arm's motion is read off the images of at least 5 markers, 5 of them with no "
          "4 coplanar (a projective displacement has 15 degrees of freedom, each marker gives 3). ViSP's 4-point "
          "target cannot work: add at least one marker off its plane, a few centimetres in depth. Nothing moved.";
    throw vpProjectiveException(vpProjectiveException::notEnoughPointsError, os.str());
  }
  for (size_t j = 0; j < left.size(); ++j) {
    for (int image = 0; image < 2; ++image) {
      const vpImagePoint &p = image == 0 ? left[j] : right[j];
      if (!std::isfinite(p.get_u()) || !std::isfinite(p.get_v()) || p.get_u() < m_imageMargin ||
          p.get_v() < m_imageMargin || p.get_u() > m_width - 1.0 - m_imageMargin ||
          p.get_v() > m_height - 1.0 - m_imageMargin) {
        std::ostringstream os;
        os << at("run") << ": marker " << j << " is at (" << p.get_u() << ", " << p.get_v() << ") in the "
           << (image == 0 ? "left" : "right") << " image at the zero reference, not " << m_imageMargin
           << " px inside its " << m_width << " x " << m_height
           << " pixels (setImageMargin(), setImageSize()): place the arm so that every marker is well inside both "
              "images, then run again. Nothing moved.";
        throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
      }
    }
  }
  // All on one plane: a homography maps the left images onto the right ones. Needs no rig.
  const double transfer = homographyTransferError(left, right);
  if (transfer < m_coplanarity) {
    std::ostringstream os;
    os << at("run") << ": the " << left.size() << " markers are coplanar" << where
       << ": one homography maps their left images onto the right ones within " << transfer
       << " px RMS (setCoplanarityThreshold(): " << m_coplanarity
       << " px). A planar target cannot give the arm's motion, which needs 5 markers of which no 4 are coplanar: "
          "add markers off the plane, a few centimetres in depth. Nothing moved.";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  std::ostringstream os;
  os << "zero reference: " << left.size() << " markers inside both images, not all coplanar (" << transfer
     << " px RMS off the best homography)";
  progress(os.str());
  if (acquisition.getStereoRig().isInitialized()) {
    checkGeneralPosition(acquisition.getStereoRig(), left, right, "zero reference, known rig");
  }
}

void vpProjectiveAcquisitionProcedure::moveJoint(vpRobot &robot, const vpColVector &qRef, unsigned int i, int sign,
                                                 double &amount, vpStopReason &reason, vpColVector &qReached,
                                                 std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right,
                                                 std::vector<vpImagePoint> &allLeft,
                                                 std::vector<vpImagePoint> &allRight)
{
  const bool revolute = m_types[i] == vpProjectiveJoint::REVOLUTE;
  const double maxAmount = amountOf(m_maxAmounts, i, revolute ? vpMath::rad(30.0) : 0.1);
  const double step = stepOf(i);
  amount = 0.0;
  reason = AMOUNT_REACHED;
  std::vector<vpImagePoint> l, r, prevL = left, prevR = right;
  while (amount < maxAmount) {
    const double next = std::min(maxAmount, amount + step);
    vpColVector q = qRef;
    q[i] = qRef[i] + sign * next;
    if (m_lower.size() != 0 && (q[i] < m_lower[i] || q[i] > m_upper[i])) {
      reason = JOINT_LIMIT;
      break;
    }
    // A position controller may stop short of a step where a marker is lost (a motion tracked frame by frame): the
    // lost marker stops the joint; a step that is used must have arrived.
    moveTo(robot, q, std::max(m_tolerance, 0.05 * step), false);
    vpColVector reading;
    robot.getPosition(vpRobot::ARTICULAR_FRAME, reading);
    if (!m_source(l, r)) {
      reason = MARKER_LOST;
      break;
    }
    if (m_motion || m_control == POSITION_CONTROL) {
      checkArrival(robot, q, std::max(m_tolerance, 0.05 * step),
                   m_motion ? "the motion of setMotion()" : "setPosition()");
    }
    if (m_callback) {
      m_callback(i, q, l, r);
    }
    if (l.size() != prevL.size() || r.size() != prevR.size()) {
      std::ostringstream os;
      os << at("run") << ": the image source gave " << l.size() << " left and " << r.size()
         << " right marker images at step " << jointValue(sign * next, revolute) << " of joint " << i << ", "
         << prevL.size() << " at the zero reference: give every marker, in the same order, or return false when "
         << "one is lost.";
      throw vpProjectiveException(vpProjectiveException::dimensionError, os.str());
    }
    int other = -1;
    double dOwn = 0.0, dOther = 0.0;
    const int jumped = orderChange(prevL, prevR, l, r, other, dOwn, dOther);
    if (jumped >= 0) {
      std::ostringstream os;
      os << at("run") << ": marker " << jumped << " jumped, at step " << jointValue(sign * next, revolute)
         << " of joint " << i << ", to where marker " << other << " was (" << dOther << " px from it, " << dOwn
         << " px from its own previous images, the markers' common motion taken out): the image source changed the "
            "markers' order. Return the markers in "
            "the same order in every frame (track each one, or identify it: tag ids), then run again.";
      throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
    }
    prevL = l;
    prevR = r;
    if (!inside(l, r)) {
      reason = IMAGE_BORDER;
      break;
    }
    amount = next;
    qReached = reading;
    left = l;
    right = r;
    allLeft.insert(allLeft.end(), l.begin(), l.end());
    allRight.insert(allRight.end(), r.begin(), r.end());
  }
}

vpProjectiveArmModel vpProjectiveAcquisitionProcedure::tellMounting(vpRobot &robot, const vpColVector &qRef,
                                                                    const vpProjectiveArmModel &model,
                                                                    const std::vector<vpJointReport> &reports)
{
  vpMountingReport report;
  report.checked = false;
  report.set = report.kept = model.getRigMounting();
  report.residual = report.otherResidual = -1.0;
  report.separation = 0.0;
  const unsigned int n = model.getNumberOfJoints();
  const vpProjectiveArmModel::vpRigMounting otherMounting = model.getRigMounting() == vpProjectiveArmModel::EYE_TO_HAND
                                                                ? vpProjectiveArmModel::EYE_IN_HAND
                                                                : vpProjectiveArmModel::EYE_TO_HAND;
  if (!m_detectMounting || n < 2) {
    m_mountingReport = report;
    progress(std::string("rig mounting: ") + mountingName(report.set) +
             (n < 2 ? " (one joint: the mounting makes no difference)" : " (as set; detection off)"));
    return model;
  }
  // The other mounting's model: the same generators, the product of exponentials (34) in the other order.
  std::vector<Eigen::Vector3d> axis, point;
  for (unsigned int i = 0; i < n; ++i) {
    axis.push_back(model.axis(i));
    point.push_back(model.point(i));
  }
  const vpProjectiveArmModel other(model.jointTypes(), otherMounting, model.getStereoRig(), model.projectiveToMetric(),
                                   axis, point, model.markers(), model.zeroReferenceJoints());
  const size_t K = model.markers().size();
  auto predict = [K](const vpProjectiveArmModel &m, const vpProjectiveArmModel::JointVector &q,
                     std::vector<Eigen::Vector4d> &s) {
    const Eigen::Matrix4d H = m.displacement(q);
    s.resize(K);
    for (size_t j = 0; j < K; ++j) {
      if (!m.predictMarker(static_cast<unsigned int>(j), H, s[j])) {
        return false;
      }
    }
    return true;
  };
  auto insideS = [this](const std::vector<Eigen::Vector4d> &s) {
    for (const Eigen::Vector4d &p : s) {
      if (!(p(0) >= m_imageMargin && p(1) >= m_imageMargin && p(2) >= m_imageMargin && p(3) >= m_imageMargin &&
            p(0) <= m_width - 1.0 - m_imageMargin && p(2) <= m_width - 1.0 - m_imageMargin &&
            p(1) <= m_height - 1.0 - m_imageMargin && p(3) <= m_height - 1.0 - m_imageMargin)) {
        return false;
      }
    }
    return true;
  };
  auto rms = [K](const std::vector<Eigen::Vector4d> &a, const std::vector<Eigen::Vector4d> &b) {
    double sum = 0.0;
    for (size_t j = 0; j < K; ++j) {
      sum += (a[j] - b[j]).squaredNorm();
    }
    return std::sqrt(sum / (4.0 * static_cast<double>(K)));
  };
  // The check configuration: two joints moved together within the explored ranges, every marker inside the margin
  // in both predictions, where the predictions differ most.
  double bestVisible = 0.0, bestAnywhere = 0.0;
  vpColVector qCheck;
  std::vector<Eigen::Vector4d> sA, sB;
  for (unsigned int i = 0; i < n; ++i) {
    for (unsigned int j = i + 1; j < n; ++j) {
      for (int si = -1; si <= 1; si += 2) {
        for (int sj = -1; sj <= 1; sj += 2) {
          for (double f : {1.0, 0.75, 0.5}) {
            const double ai = f * (si < 0 ? reports[i].amountNegative : reports[i].amountPositive);
            const double aj = f * (sj < 0 ? reports[j].amountNegative : reports[j].amountPositive);
            if (ai <= 0.0 || aj <= 0.0) {
              continue;
            }
            vpColVector q = qRef;
            q[i] += si * ai;
            q[j] += sj * aj;
            vpProjectiveArmModel::JointVector qe(n);
            for (unsigned int k = 0; k < n; ++k) {
              qe(k) = q[k];
            }
            if (!predict(model, qe, sA) || !predict(other, qe, sB)) {
              continue;
            }
            const double d = rms(sA, sB);
            bestAnywhere = std::max(bestAnywhere, d);
            if (d > bestVisible && insideS(sA) && insideS(sB)) {
              bestVisible = d;
              qCheck = q;
            }
          }
        }
      }
    }
  }
  // Two models whose predictions differ by 5 times the noise are told apart by one check at better than 1 in 1000.
  const double needed = std::max(1.0, 5.0 * m_residual);
  std::ostringstream os;
  if (bestVisible < needed) {
    if (bestAnywhere < needed) {
      report.separation = bestAnywhere;
      m_mountingReport = report;
      os << "rig mounting: " << mountingName(report.set) << " as set (both mountings predict the same images within "
         << bestAnywhere << " px in the explored joint ranges: the joints' motions commute there)";
      progress(os.str());
      return model;
    }
    os << at("run") << ": the rig mounting cannot be told from the images: the two mountings predict images up to "
       << bestAnywhere << " px apart in the explored joint ranges, but at most " << bestVisible
       << " px apart where every marker stays in view (needed: " << needed
       << " px). Set the mounting with setRigMounting() (EYE_IN_HAND: the cameras ride on the arm and the markers "
          "are static; EYE_TO_HAND: the rig is fixed and the markers are on the tool) and call "
          "setMountingDetection(false).";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  double smallestStep = std::numeric_limits<double>::infinity();
  for (unsigned int k = 0; k < n; ++k) {
    smallestStep = std::min(smallestStep, stepOf(k));
  }
  moveTo(robot, qCheck, std::max(m_tolerance, 0.05 * smallestStep), false);
  vpColVector reading;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, reading);
  std::vector<vpImagePoint> l, r;
  const bool seen = m_source(l, r) && l.size() == K && r.size() == K;
  if (seen && (m_motion || m_control == POSITION_CONTROL)) {
    checkArrival(robot, qCheck, std::max(m_tolerance, 0.05 * smallestStep),
                 m_motion ? "the motion of setMotion()" : "setPosition()");
  }
  moveTo(robot, qRef, m_tolerance);
  if (!seen) {
    os << at("run") << ": the image source lost a marker at the mounting's check motion, where both mountings "
       << "predicted every marker inside the images: the markers changed order, or the rig or the markers moved "
          "during the acquisition; run again.";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  vpProjectiveArmModel::JointVector qe(n);
  for (unsigned int k = 0; k < n; ++k) {
    qe(k) = reading[k];
  }
  std::vector<Eigen::Vector4d> measured(K);
  for (size_t j = 0; j < K; ++j) {
    measured[j] = Eigen::Vector4d(l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v());
  }
  const bool okA = predict(model, qe, sA), okB = predict(other, qe, sB);
  const double rA = okA ? rms(sA, measured) : std::numeric_limits<double>::infinity();
  const double rB = okB ? rms(sB, measured) : std::numeric_limits<double>::infinity();
  report.checked = true;
  report.q = reading;
  report.separation = okA && okB ? rms(sA, sB) : bestVisible;
  report.kept = rB < rA ? otherMounting : model.getRigMounting();
  report.residual = std::min(rA, rB);
  report.otherResidual = std::max(rA, rB);
  if (!(report.residual < 0.5 * report.separation)) {
    os << at("run") << ": neither mounting predicts the check motion (two joints moved together): "
       << mountingName(model.getRigMounting()) << " is off by " << rA << " px, " << mountingName(otherMounting)
       << " by " << rB << " px, for predictions " << report.separation
       << " px apart. The markers changed order, the rig or the markers moved during the acquisition, or a joint "
          "moved other than its reading says; run again.";
    throw vpProjectiveException(vpProjectiveException::estimationFailedError, os.str());
  }
  m_mountingReport = report;
  os << "rig mounting: " << mountingName(report.kept) << " (its model predicts a check motion of two joints within "
     << report.residual << " px; " << mountingName(report.kept == report.set ? otherMounting : report.set)
     << " would be off by " << report.otherResidual << " px)";
  if (report.kept != report.set) {
    os << "; the acquisition was set to " << mountingName(report.set) << ": the model uses "
       << mountingName(report.kept) << " (call setRigMounting(" << mountingName(report.kept) << ") to say so)";
  }
  progress(os.str());
  return report.kept == model.getRigMounting() ? model : other;
}

vpProjectiveArmModel vpProjectiveAcquisitionProcedure::run(vpRobot &robot, vpProjectiveArmAcquisition &acquisition)
{
  const double tStart = seconds();
  const double previousResidual = m_residual;
  m_types = acquisition.getJointTypes();
  m_parallax = -1.0;
  vpColVector qRef;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, qRef);
  const unsigned int n = qRef.size();
  for (const vpColVector *v : {&m_maxAmounts, &m_steps, &m_minAmounts, &m_qmin}) {
    if (v->size() != 0 && v->size() != n) {
      throw vpProjectiveException(vpProjectiveException::dimensionError,
                                  at("run") + ": a per-joint setting has " + std::to_string(v->size()) +
                                      " values, the robot has " + std::to_string(n) + " joints: give one per joint.");
    }
  }
  if (acquisition.getNumberOfJoints() != n) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                at("run") + ": the acquisition has " + std::to_string(acquisition.getNumberOfJoints()) +
                                    " joints, the robot " + std::to_string(n) + ": give the robot's joint types.");
  }
  // The joint range the trials stay in: the limits given, else those of ViSP's arms that know theirs (Viper650/850,
  // Afma4/6, real or simulated) less 2 deg or 1 cm, else none.
  m_lower = vpColVector();
  m_upper = vpColVector();
  std::string limitsFrom = "none";
  if (m_qmin.size() != 0) {
    m_lower = m_qmin + vpColVector(n, m_limitMargin);
    m_upper = m_qmax - vpColVector(n, m_limitMargin);
    limitsFrom = "setJointLimits()";
  } else {
    vpColVector qmin, qmax;
    if (const vpViper *viper = dynamic_cast<const vpViper *>(&robot)) {
      qmin = viper->getJointMin();
      qmax = viper->getJointMax();
    } else if (const vpAfma6 *afma6 = dynamic_cast<const vpAfma6 *>(&robot)) {
      qmin = afma6->getJointMin();
      qmax = afma6->getJointMax();
    } else if (const vpAfma4 *afma4 = dynamic_cast<const vpAfma4 *>(&robot)) {
      qmin = afma4->getJointMin();
      qmax = afma4->getJointMax();
    }
    if (qmin.size() == n && qmax.size() == n) {
      m_lower = qmin;
      m_upper = qmax;
      for (unsigned int k = 0; k < n; ++k) {
        const double margin = m_types[k] == vpProjectiveJoint::REVOLUTE ? vpMath::rad(2.0) : 0.01;
        m_lower[k] += margin;
        m_upper[k] -= margin;
      }
      limitsFrom = "the robot's own, less 2 deg or 1 cm";
    }
  }
  std::vector<vpImagePoint> left, right;
  if (!m_source(left, right)) {
    throw vpProjectiveException(vpProjectiveException::notEnoughPointsError,
                                at("run") + ": the image source lost a marker at the zero reference: place the arm so "
                                            "that every marker is tracked in both images, then run again. Nothing "
                                            "moved.");
  }
  checkZeroReference(acquisition, left, right); // before the arm moves
  progress("joint limits: " + limitsFrom);
  if (!m_motion) {
    robot.setRobotState(m_control == VELOCITY_CONTROL ? vpRobot::STATE_VELOCITY_CONTROL
                                                      : vpRobot::STATE_POSITION_CONTROL);
  }
  if (m_rotationSpeed > 0.0) {
    robot.setMaxRotationVelocity(m_rotationSpeed);
  }
  if (m_translationSpeed > 0.0) {
    robot.setMaxTranslationVelocity(m_translationSpeed);
  }
  // With a known rig the zero reference is checked before the arm moves; without one, once the rig is estimated.
  const bool rigKnown = acquisition.getStereoRig().isInitialized();
  vpProjectiveArmAcquisition work = acquisition;
  if (rigKnown) {
    work.setZeroReference(qRef, left, right);
  }
  struct Trial {
    vpColVector q;
    std::vector<vpImagePoint> left, right;
  };
  std::vector<Trial> trials;
  std::vector<vpImagePoint> allLeft = left, allRight = right; // every pair seen inside the margins, for the rig
  std::vector<vpJointReport> reports(n);
  try {
    for (unsigned int i = 0; i < n; ++i) {
      vpJointReport &report = reports[i];
      report.trials = 0;
      const bool revolute = m_types[i] == vpProjectiveJoint::REVOLUTE;
      for (int sign = -1; sign <= 1; sign += 2) {
        double amount = 0.0;
        vpStopReason reason = AMOUNT_REACHED;
        Trial trial;
        trial.left = left;
        trial.right = right;
        moveJoint(robot, qRef, i, sign, amount, reason, trial.q, trial.left, trial.right, allLeft, allRight);
        (sign < 0 ? report.amountNegative : report.amountPositive) = amount;
        (sign < 0 ? report.stopNegative : report.stopPositive) = reason;
        if (amount > 0.0) {
          trials.push_back(trial); // the encoders' readings, as the model will take them
          ++report.trials;
        }
        if (sign > 0) {
          moveTo(robot, qRef, m_tolerance); // from the negative side, the positive steps pass through it anyway
        }
        std::ostringstream os;
        os << "joint " << i << (sign < 0 ? " -" : " +") << ": " << jointValue(amount, revolute) << " ("
           << toString(reason) << ")" << (sign > 0 ? ", back at the zero reference" : "") << "; " << std::fixed
           << std::setprecision(1) << seconds() - tStart << " s";
        progress(os.str());
      }
      const double minAmount = amountOf(m_minAmounts, i, revolute ? vpMath::rad(5.0) : 0.01);
      if (std::max(report.amountNegative, report.amountPositive) < minAmount) {
        std::ostringstream os;
        os << at("run") << ": joint " << i << " moved only -" << jointValue(report.amountNegative, revolute) << " ("
           << toString(report.stopNegative) << ") and +" << jointValue(report.amountPositive, revolute) << " ("
           << toString(report.stopPositive) << "), less than the minimum " << jointValue(minAmount, revolute)
           << ": too small a motion to observe; move the arm so that the markers are nearer the image centre and "
           << "the joint away from its limits, or lower the image margin or the minimum amount.";
        throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
      }
    }
    if (!rigKnown) {
      vpProjectiveStereoRig rig;
      rig.estimate(allLeft, allRight, m_epipolarThreshold);
      work.setStereoRig(rig);
      work.setZeroReference(qRef, left, right);
      std::ostringstream os;
      os << "rig estimated from " << allLeft.size() << " matches, epipolar residual " << rig.getEstimationResidual()
         << " px";
      progress(os.str());
      checkGeneralPosition(rig, left, right, "zero reference, estimated rig");
    }
    for (const Trial &trial : trials) {
      work.addTrialMotion(trial.q, trial.left, trial.right);
    }
    vpProjectiveArmModel model;
    try {
      model = work.calibrate();
    } catch (const vpProjectiveException &e) {
      // Say what the run saw that makes a calibration fail: small image motions, markers nearly coplanar.
      std::ostringstream os;
      os << e.getStringMessage() << ". What the procedure saw:";
      double smallest = std::numeric_limits<double>::infinity();
      unsigned int which = 0;
      for (size_t k = 0; k < trials.size(); ++k) {
        double sum = 0.0;
        for (size_t j = 0; j < left.size(); ++j) {
          sum += vpImagePoint::sqrDistance(left[j], trials[k].left[j]) +
                 vpImagePoint::sqrDistance(right[j], trials[k].right[j]);
        }
        const double motion = std::sqrt(sum / (2.0 * static_cast<double>(left.size())));
        if (motion < smallest) {
          smallest = motion;
          which = static_cast<unsigned int>(k);
        }
      }
      if (!trials.empty()) {
        unsigned int joint = 0;
        vpColVector d = trials[which].q - qRef;
        for (unsigned int k = 1; k < n; ++k) {
          joint = std::abs(d[k]) > std::abs(d[joint]) ? k : joint;
        }
        os << " the smallest trial (joint " << joint << ") moved the markers by " << smallest << " px RMS"
           << (smallest < 20.0 ? ": too small a motion, raise setMaxAmounts() or start where the markers can move "
                                 "further"
                               : "");
      }
      os << "; markers' general-position margin " << m_parallax << " px of plane parallax"
         << (m_parallax >= 0.0 && m_parallax < 5.0 * m_coplanarity
                 ? ": nearly coplanar markers, add markers off their plane"
                 : "")
         << "; a marker order change would have stopped the run at the step where it happened.";
      throw vpProjectiveException(e.getCode(), os.str());
    }
    {
      std::ostringstream os;
      os << "calibrated: " << trials.size() << " trials, residual " << work.getCalibrationResidual() << " px RMS";
      progress(os.str());
    }
    m_residual = work.getCalibrationResidual();
    model = tellMounting(robot, qRef, model, reports);
    work.setRigMounting(model.getRigMounting());
    stopRobot(robot);
    acquisition = work;
    m_reports = reports;
    std::ostringstream os;
    os << "acquisition done in " << std::fixed << std::setprecision(1) << seconds() - tStart << " s";
    progress(os.str());
    return model;
  } catch (const vpProjectiveException &e) {
    m_residual = previousResidual;
    if (e.getCode() != vpProjectiveException::robotMotionError) {
      try {
        moveTo(robot, qRef, m_tolerance);
      } catch (...) {
      }
    }
    try {
      stopRobot(robot);
    } catch (...) {
    }
    throw;
  } catch (...) {
    m_residual = previousResidual;
    try {
      moveTo(robot, qRef, m_tolerance);
      stopRobot(robot);
    } catch (...) {
    }
    throw;
  }
}

void vpProjectiveAcquisitionProcedure::run(vpRobot &robot, vpProjectiveRobot &projectiveRobot)
{
  vpProjectiveArmAcquisition acquisition = projectiveRobot.m_acquisition;
  const vpProjectiveStereoRig &rig = projectiveRobot.getStereoRig(); // once calibrated, the model's (updateRig())
  if (rig.isInitialized()) {
    acquisition.setStereoRig(rig);
  }
  const vpProjectiveArmModel model = run(robot, acquisition);
  projectiveRobot.adopt(acquisition, model, m_residual, acquisition.getAlgebraicResidual());
}
