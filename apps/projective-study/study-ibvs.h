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
  \file study-ibvs.h
  \brief Calibrated joint-space stereo IBVS written with ViSP's metric features: the first baseline.
*/

#ifndef _study_study_ibvs_h_
#define _study_study_ibvs_h_

#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpVelocityTwistMatrix.h>
#include <visp3/visual_features/vpFeatureBuilder.h>
#include <visp3/visual_features/vpFeaturePoint.h>

#include <visp3/projective/vpSimulatorArm.h>

#include "study-calibration.h"
#include "study-control.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
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
} // namespace study

#endif
