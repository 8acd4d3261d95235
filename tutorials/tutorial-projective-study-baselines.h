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

/*!
  \file tutorial-projective-study-baselines.h
  \brief The two baselines of tutorial-projective-study.cpp: calibrated joint-space stereo IBVS written with ViSP's
  metric features, and uncalibrated Broyden servoing. Both use the control law of vpServoProjective (same gain,
  damping rule and velocity saturation), so that only the Jacobian differs between the methods.
*/

#ifndef _tutorial_projective_study_baselines_h_
#define _tutorial_projective_study_baselines_h_

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/visual_features/vpFeatureBuilder.h>
#include <visp3/visual_features/vpFeaturePoint.h>

#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Control settings]
/*!
  The control settings every method shares, those of the main tutorial's projective task: gain 0.5, joint steps
  limited to 15 deg per iteration (the whole velocity scaled down, keeping its direction), and damped least squares
  \f$ \dot q = -\lambda (J^T J + \mu^2 I)^{-1} J^T e \f$ with \f$ \mu^2 = \mu_{max}^2 (1 - (\sigma_{min} /
  \sigma_0)^2) \f$ when the smallest singular value \f$ \sigma_{min} \f$ of J (pixels per radian) is below
  \f$ \sigma_0 \f$, 0 otherwise (vpServoProjective::setDamping(30, 30)).
*/
struct ControlSettings {
  double lambda = 0.5;
  double qdotMax = vpMath::rad(15.0); // rad per iteration
  double sigmaThreshold = 30.0;       // sigma_0, px/rad
  double maxDamping = 30.0;           // mu_max, px/rad
};

//! The control law of vpServoProjective::computeControlLaw() on a given Jacobian J (px/rad) and error e (px).
inline vpColVector dampedLeastSquares(const vpMatrix &J, const vpColVector &e, const ControlSettings &settings)
{
  const vpMatrix JtJ = J.AtA();
  const vpColVector b = J.t() * e;
  const vpColVector eigenvalues = JtJ.eigenValues(); // symmetric: real, ascending
  const double sigmaMin = std::sqrt(std::max(0.0, eigenvalues[0]));
  double mu2 = 0.0;
  if (sigmaMin < settings.sigmaThreshold) {
    const double ratio = sigmaMin / settings.sigmaThreshold;
    mu2 = settings.maxDamping * settings.maxDamping * (1.0 - ratio * ratio);
  }
  vpMatrix A = JtJ;
  for (unsigned int i = 0; i < A.getRows(); ++i) {
    A[i][i] += mu2;
  }
  vpColVector qdot = A.solveBySVD(b) * (-settings.lambda);
  const double largest = qdot.getMaxValue() > -qdot.getMinValue() ? qdot.getMaxValue() : -qdot.getMinValue();
  if (largest > settings.qdotMax) {
    qdot *= settings.qdotMax / largest;
  }
  return qdot;
}
//! [Control settings]

//! A controller driven by the study's loop: image measurements of the tracked stereo points in, joint velocity out.
class Controller
{
public:
  virtual ~Controller() {}
  /*!
    Called once at the start configuration \e q0 before the servo loop. \e moveAndMeasure(q, left, right) moves the
    arm to q and returns false if a tracked point is then out of an image or q is beyond a joint limit (the arm
    does not move then). Returns false if the controller cannot start; \e moves counts the extra configurations
    visited.
  */
  virtual bool prepare(const vpColVector &q0,
                       const std::function<bool(const vpColVector &, std::vector<vpImagePoint> &,
                                                std::vector<vpImagePoint> &)> &moveAndMeasure,
                       unsigned int &moves)
  {
    (void)q0;
    (void)moveAndMeasure;
    moves = 0;
    return true;
  }
  /*!
    Joint velocity (rad per iteration) at joint values \e q from the measured stereo points; \e tracked[k] is false
    for a point the tracker lost at this iteration (its measurement is then meaningless).
  */
  virtual vpColVector velocity(const vpColVector &q, const std::vector<vpImagePoint> &left,
                               const std::vector<vpImagePoint> &right, const std::vector<bool> &tracked) = 0;
  //! The points the controller itself rejected as outliers at the last velocity() (none by default).
  virtual void rejected(std::vector<bool> &flags) const { flags.clear(); }
};

//! [Believed calibration]
/*!
  What the calibrated baseline believes: the intrinsics of both cameras, the rig's left-to-right transform, the pose
  of the rig with respect to the arm (here the left camera's pose in the world, the arm's base pose being part of the
  arm), and the arm's Denavit-Hartenberg table with its tool mount.
*/
struct BelievedCalibration {
  vpCameraParameters camLeft, camRight;
  vpHomogeneousMatrix rMl; // left-camera to right-camera
  vpHomogeneousMatrix lMw; // world (arm side) to left camera
  vpSimulatorArm arm;
};

/*!
  A direction of calibration error, drawn once per task: a sign per intrinsic parameter (px, py, u0, v0 of each
  camera), a rotation axis for the rig, a rotation axis and a translation direction for the base-to-rig transform,
  and a sign per link length (the non-zero d and a of the DH table and the tool mount's length).
*/
struct CalibrationErrorDirection {
  std::vector<double> intrinsicSigns; // 8
  vpColVector rigAxis;                // 3, unit
  vpColVector baseAxis;               // 3, unit
  vpColVector baseDirection;          // 3, unit
  std::vector<double> linkSigns;      // one per non-zero DH length, then the tool mount

  //! Uniform unit vector on the sphere.
  static vpColVector unitVector(vpUniRand &rng)
  {
    const double z = rng.uniform(-1.0, 1.0), phi = rng.uniform(0.0, 2.0 * M_PI), r = std::sqrt(1.0 - z * z);
    vpColVector u(3);
    u[0] = r * std::cos(phi);
    u[1] = r * std::sin(phi);
    u[2] = z;
    return u;
  }

  static CalibrationErrorDirection draw(vpUniRand &rng, unsigned int nbLinkLengths)
  {
    CalibrationErrorDirection d;
    for (unsigned int i = 0; i < 8; ++i) {
      d.intrinsicSigns.push_back(rng.uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0);
    }
    d.rigAxis = unitVector(rng);
    d.baseAxis = unitVector(rng);
    d.baseDirection = unitVector(rng);
    for (unsigned int i = 0; i < nbLinkLengths + 1; ++i) {
      d.linkSigns.push_back(rng.uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0);
    }
    return d;
  }
};

//! Magnitudes of the unit calibration error ("1x"): intrinsics 5 %, rig rotation 2 deg, base-to-rig 5 deg and 5 cm,
//! link lengths 2 %.
struct CalibrationErrorMagnitude {
  double intrinsics = 0.05;
  double rigRotation = vpMath::rad(2.0);
  double baseRotation = vpMath::rad(5.0);
  double baseTranslation = 0.05;
  double linkLengths = 0.02;
};

//! Number of non-zero lengths (d and a) in a DH table.
inline unsigned int countLinkLengths(const std::vector<vpSimulatorArm::vpDHRow> &dh)
{
  unsigned int count = 0;
  for (const vpSimulatorArm::vpDHRow &row : dh) {
    count += (row.d != 0.0) + (row.a != 0.0);
  }
  return count;
}

/*!
  The believed calibration at \e factor times the unit error magnitude in the direction \e dir (factor 0: the truth).
  Rotations of the rig and of the base-to-rig transform are applied about the camera centres (\c rMl becomes
  \f$ \delta_r\, {}^rM_l \f$ and \c lMw becomes \f$ \delta_b\, {}^lM_w \f$), the base translation in the left camera
  frame.
*/
inline BelievedCalibration believedCalibration(const vpSimulatorStereoRig &rig, const vpSimulatorArm &arm,
                                               const CalibrationErrorDirection &dir, double factor,
                                               const CalibrationErrorMagnitude &magnitude = CalibrationErrorMagnitude())
{
  const vpCameraParameters &cl = rig.getLeftCameraParameters(), &cr = rig.getRightCameraParameters();
  const double k = factor * magnitude.intrinsics;
  const std::vector<double> &s = dir.intrinsicSigns;
  vpCameraParameters camLeft, camRight;
  camLeft.initPersProjWithoutDistortion(cl.get_px() * (1 + k * s[0]), cl.get_py() * (1 + k * s[1]),
                                        cl.get_u0() * (1 + k * s[2]), cl.get_v0() * (1 + k * s[3]));
  camRight.initPersProjWithoutDistortion(cr.get_px() * (1 + k * s[4]), cr.get_py() * (1 + k * s[5]),
                                         cr.get_u0() * (1 + k * s[6]), cr.get_v0() * (1 + k * s[7]));

  const vpThetaUVector rigTu(dir.rigAxis[0] * factor * magnitude.rigRotation,
                             dir.rigAxis[1] * factor * magnitude.rigRotation,
                             dir.rigAxis[2] * factor * magnitude.rigRotation);
  const vpHomogeneousMatrix rigDelta(vpTranslationVector(0, 0, 0), rigTu);
  const vpThetaUVector baseTu(dir.baseAxis[0] * factor * magnitude.baseRotation,
                              dir.baseAxis[1] * factor * magnitude.baseRotation,
                              dir.baseAxis[2] * factor * magnitude.baseRotation);
  const double t = factor * magnitude.baseTranslation;
  const vpHomogeneousMatrix baseDelta(
      vpTranslationVector(dir.baseDirection[0] * t, dir.baseDirection[1] * t, dir.baseDirection[2] * t), baseTu);

  std::vector<vpSimulatorArm::vpDHRow> dh = arm.getDHTable();
  unsigned int j = 0;
  const double l = factor * magnitude.linkLengths;
  for (vpSimulatorArm::vpDHRow &row : dh) {
    if (row.d != 0.0) {
      row.d *= 1 + l * dir.linkSigns[j++];
    }
    if (row.a != 0.0) {
      row.a *= 1 + l * dir.linkSigns[j++];
    }
  }
  vpHomogeneousMatrix eMt = arm.get_eMt();
  for (unsigned int i = 0; i < 3; ++i) {
    eMt[i][3] *= 1 + l * dir.linkSigns[j];
  }
  return BelievedCalibration{camLeft, camRight, rigDelta * rig.get_rMl(), baseDelta * rig.get_wMl().inverse(),
                             vpSimulatorArm(dh, eMt, arm.getToolMarkers(), arm.get_wMb())};
}
//! [Believed calibration]

//! [Robot Jacobian]
/*!
  Spatial Jacobian of an arm (6 x n) from its twists at q = 0 (world frame) by the product of exponentials: column i
  is \f$ \mathrm{Ad}_{g_{i-1}(q)} \xi_i \f$, \f$ g_{i-1}(q) = \exp(q_0 \hat\xi_0) \cdots \exp(q_{i-1} \hat\xi_{i-1})
  \f$, as a velocity twist \f$ (v, \omega) \f$ of the last link expressed in the world frame at the world origin.
  vpVelocityTwistMatrix(g) is the adjoint \f$ \mathrm{Ad}_g \f$ and vpExponentialMap::direct() the exponential of
  se(3).
*/
class ArmJacobian
{
public:
  explicit ArmJacobian(const vpSimulatorArm &arm) : m_xi()
  {
    for (unsigned int i = 0; i < arm.getNumberOfJoints(); ++i) {
      const vpMatrix T = arm.getTwist(i);
      vpColVector xi(6);
      xi[0] = T[0][3];
      xi[1] = T[1][3];
      xi[2] = T[2][3];
      xi[3] = T[2][1];
      xi[4] = T[0][2];
      xi[5] = T[1][0];
      m_xi.push_back(xi);
    }
  }
  vpMatrix spatial(const vpColVector &q) const
  {
    const unsigned int n = static_cast<unsigned int>(m_xi.size());
    vpMatrix wJ(6, n);
    vpHomogeneousMatrix g;
    for (unsigned int i = 0; i < n; ++i) {
      const vpColVector column = vpVelocityTwistMatrix(g) * m_xi[i];
      for (unsigned int r = 0; r < 6; ++r) {
        wJ[r][i] = column[r];
      }
      g = g * vpExponentialMap::direct(m_xi[i] * q[i]);
    }
    return wJ;
  }

private:
  std::vector<vpColVector> m_xi;
};
//! [Robot Jacobian]

//! [Stereo IBVS]
/*!
  Calibrated joint-space stereo IBVS with ViSP's metric features. For each tracked point and camera c (left l,
  right r), a vpFeaturePoint is built from the measured pixels through the believed intrinsics (vpFeatureBuilder)
  with the depth Z of the point in the believed geometry (believed arm, tool and base-to-rig transform), and its
  interaction matrix \f$ L \f$ maps the camera's velocity twist to the point's image motion. The rig is fixed and the
  point moves with the last link, whose twist at joint velocities \f$ \dot q \f$ is \f$ {}^wJ(q) \dot q \f$ in the
  world frame: in camera c it is \f$ {}^cV_w\, {}^wJ \dot q \f$ (vpVelocityTwistMatrix), and the point's image moves
  as if the camera moved by the opposite twist, hence the eye-to-hand Jacobian \f$ -L\, {}^cV_w\, {}^wJ \f$ (vpServo's
  EYETOHAND_L_cVf_fJe). Rows are scaled by the believed focal lengths, so that error and Jacobian are in pixels as in
  the projective task (the error \f$ p_x (x - x^*) \f$ is exactly the pixel error \f$ u - u^* \f$) and the damping
  threshold means the same; both cameras are stacked, 4 rows per point.
*/
class StereoIbvs : public Controller
{
public:
  StereoIbvs(const BelievedCalibration &believed, const std::vector<unsigned int> &markers,
             const std::vector<vpImagePoint> &leftTarget, const std::vector<vpImagePoint> &rightTarget,
             const ControlSettings &settings)
      : m_believed(believed), m_jacobian(believed.arm), m_markers(markers), m_settings(settings), m_lVw(), m_rVw(),
        m_sStarLeft(), m_sStarRight()
  {
    m_lVw.buildFrom(believed.lMw);
    m_rVw.buildFrom(believed.rMl * believed.lMw);
    for (size_t k = 0; k < markers.size(); ++k) {
      vpFeaturePoint sl, sr;
      vpFeatureBuilder::create(sl, believed.camLeft, leftTarget[k]);
      vpFeatureBuilder::create(sr, believed.camRight, rightTarget[k]);
      m_sStarLeft.push_back(sl);
      m_sStarRight.push_back(sr);
    }
  }

  vpColVector velocity(const vpColVector &q, const std::vector<vpImagePoint> &left,
                       const std::vector<vpImagePoint> &right, const std::vector<bool> &tracked) override
  {
    const vpMatrix wJ = m_jacobian.spatial(q);
    const vpMatrix lJ = m_lVw * wJ, rJ = m_rVw * wJ;
    const vpHomogeneousMatrix lMt = m_believed.lMw * m_believed.arm.get_wMt(q);
    const std::vector<vpColVector> &tX = m_believed.arm.getToolMarkers();
    unsigned int rows = 0;
    for (size_t k = 0; k < m_markers.size(); ++k) {
      rows += tracked[k] ? 4 : 0;
    }
    const unsigned int n = q.size();
    vpMatrix J(rows, n);
    vpColVector e(rows);
    unsigned int r = 0;
    for (size_t k = 0; k < m_markers.size(); ++k) {
      if (!tracked[k]) {
        continue;
      }
      // Depth of the point in both cameras from the believed geometry.
      const vpColVector &X = tX[m_markers[k]];
      vpColVector tXh(4, 1.0);
      tXh[0] = X[0];
      tXh[1] = X[1];
      tXh[2] = X[2];
      const vpColVector lX = lMt * tXh;
      const vpColVector rX = m_believed.rMl * lX;
      for (int camera = 0; camera < 2; ++camera) {
        const vpCameraParameters &cam = camera == 0 ? m_believed.camLeft : m_believed.camRight;
        vpFeaturePoint s;
        vpFeatureBuilder::create(s, cam, camera == 0 ? left[k] : right[k]);
        s.set_Z(camera == 0 ? lX[2] : rX[2]);
        const vpMatrix L = s.interaction();
        const vpColVector error = s.error(camera == 0 ? m_sStarLeft[k] : m_sStarRight[k]);
        const vpMatrix Jc = L * (camera == 0 ? lJ : rJ) * (-1.0);
        const double scale[2] = {cam.get_px(), cam.get_py()};
        for (unsigned int i = 0; i < 2; ++i, ++r) {
          for (unsigned int j = 0; j < n; ++j) {
            J[r][j] = scale[i] * Jc[i][j];
          }
          e[r] = scale[i] * error[i];
        }
      }
    }
    m_lastJ = J;
    return dampedLeastSquares(J, e, m_settings);
  }

  //! Task Jacobian (px/rad) of the last velocity().
  const vpMatrix &getTaskJacobian() const { return m_lastJ; }

private:
  BelievedCalibration m_believed;
  ArmJacobian m_jacobian;
  std::vector<unsigned int> m_markers;
  ControlSettings m_settings;
  vpVelocityTwistMatrix m_lVw, m_rVw;
  std::vector<vpFeaturePoint> m_sStarLeft, m_sStarRight;
  vpMatrix m_lastJ;
};
//! [Stereo IBVS]

//! [Broyden]
/*!
  Uncalibrated servoing with a Broyden-estimated image Jacobian (Jagersand-style). prepare() initialises J by one
  small exploratory motion per joint at the start configuration (\e delta, tried the other way if the first one
  leaves an image or a joint range; the arm returns to the start after each): column i is the measured image motion
  divided by the joint motion. In the loop, each iteration's measured image change \f$ \Delta s \f$ and encoder
  change \f$ \Delta q \f$ give the rank-one update \f$ J \leftarrow J + (\Delta s - J \Delta q) \Delta q^T /
  (\Delta q^T \Delta q) \f$ on the rows tracked at both iterations. An update is made only if the step is measurable:
  the motion it predicts, \f$ \|J \Delta q\| \f$, must exceed 3 times the noise of \f$ \Delta s \f$ (\f$ \sqrt{2}
  \sigma \f$ per coordinate, so \f$ 3 \sqrt{2 m} \sigma \f$ for m rows); below it the update would only fit noise
  (its size grows as \f$ \sigma / \|\Delta q\| \f$ while the arm settles).
*/
class BroydenServo : public Controller
{
public:
  BroydenServo(unsigned int nbJoints, double delta, double sigma, const std::vector<vpImagePoint> &leftTarget,
               const std::vector<vpImagePoint> &rightTarget, const ControlSettings &settings)
      : m_n(nbJoints), m_delta(delta), m_sigma(sigma), m_target(targetVector(leftTarget, rightTarget)),
        m_settings(settings), m_J(), m_previousS(), m_previousQ(), m_previousTracked(), m_hasPrevious(false),
        m_updates(0), m_skipped(0)
  {
  }

  bool prepare(const vpColVector &q0,
               const std::function<bool(const vpColVector &, std::vector<vpImagePoint> &, std::vector<vpImagePoint> &)>
                   &moveAndMeasure,
               unsigned int &moves) override
  {
    moves = 0;
    std::vector<vpImagePoint> left0, right0;
    if (!moveAndMeasure(q0, left0, right0)) {
      return false;
    }
    const vpColVector s0 = targetVector(left0, right0);
    m_J.resize(s0.size(), m_n);
    for (unsigned int i = 0; i < m_n; ++i) {
      bool done = false;
      for (double sign : {1.0, -1.0}) {
        vpColVector q = q0;
        q[i] += sign * m_delta;
        std::vector<vpImagePoint> left, right;
        ++moves;
        if (moveAndMeasure(q, left, right)) {
          const vpColVector ds = targetVector(left, right) - s0;
          for (unsigned int r = 0; r < s0.size(); ++r) {
            m_J[r][i] = ds[r] / (sign * m_delta);
          }
          done = true;
          break;
        }
      }
      if (!done) {
        return false;
      }
    }
    return true;
  }

  vpColVector velocity(const vpColVector &q, const std::vector<vpImagePoint> &left,
                       const std::vector<vpImagePoint> &right, const std::vector<bool> &tracked) override
  {
    const vpColVector s = targetVector(left, right);
    if (m_hasPrevious) {
      update(q - m_previousQ, s - m_previousS, tracked);
    }
    m_previousS = s;
    m_previousQ = q;
    m_previousTracked = tracked;
    m_hasPrevious = true;

    unsigned int rows = 0;
    for (bool t : tracked) {
      rows += t ? 4 : 0;
    }
    vpMatrix J(rows, m_n);
    vpColVector e(rows);
    unsigned int r = 0;
    for (unsigned int row = 0; row < s.size(); ++row) {
      if (tracked[row / 4]) {
        for (unsigned int j = 0; j < m_n; ++j) {
          J[r][j] = m_J[row][j];
        }
        e[r++] = s[row] - m_target[row];
      }
    }
    return dampedLeastSquares(J, e, m_settings);
  }

  //! Numbers of rank-one updates made and skipped (step too small to be measured).
  unsigned int getUpdates() const { return m_updates; }
  unsigned int getSkippedUpdates() const { return m_skipped; }
  const vpMatrix &getJacobian() const { return m_J; }

  //! (u, v, u', v') of every point, stacked.
  static vpColVector targetVector(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
  {
    vpColVector s(4 * static_cast<unsigned int>(left.size()));
    for (unsigned int k = 0; k < left.size(); ++k) {
      s[4 * k] = left[k].get_u();
      s[4 * k + 1] = left[k].get_v();
      s[4 * k + 2] = right[k].get_u();
      s[4 * k + 3] = right[k].get_v();
    }
    return s;
  }

private:
  void update(const vpColVector &dq, const vpColVector &ds, const std::vector<bool> &tracked)
  {
    const double dq2 = dq.sumSquare();
    std::vector<unsigned int> rows;
    for (unsigned int row = 0; row < ds.size(); ++row) {
      if (tracked[row / 4] && m_previousTracked[row / 4]) {
        rows.push_back(row);
      }
    }
    if (rows.empty() || !(dq2 > 0.0)) {
      ++m_skipped;
      return;
    }
    double predicted2 = 0.0;
    std::vector<double> residual(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) {
      double Jdq = 0.0;
      for (unsigned int j = 0; j < m_n; ++j) {
        Jdq += m_J[rows[k]][j] * dq[j];
      }
      predicted2 += Jdq * Jdq;
      residual[k] = ds[rows[k]] - Jdq;
    }
    const double noise = 3.0 * std::sqrt(2.0 * rows.size()) * m_sigma;
    if (std::sqrt(predicted2) < noise) {
      ++m_skipped;
      return;
    }
    for (size_t k = 0; k < rows.size(); ++k) {
      for (unsigned int j = 0; j < m_n; ++j) {
        m_J[rows[k]][j] += residual[k] * dq[j] / dq2;
      }
    }
    ++m_updates;
  }

  unsigned int m_n;
  double m_delta;
  double m_sigma;
  vpColVector m_target;
  ControlSettings m_settings;
  vpMatrix m_J;
  vpColVector m_previousS, m_previousQ;
  std::vector<bool> m_previousTracked;
  bool m_hasPrevious;
  unsigned int m_updates, m_skipped;
};
//! [Broyden]
} // namespace study

#endif
