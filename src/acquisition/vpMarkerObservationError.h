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

/*
  Private: the Ceres cost functor of the arm's bundle adjustment. They use the plugin's own exponentials
  (vpProjectiveJoint), twists (vpMetricTwist) and projection (vpProjection.h), templated on the scalar, so that what
  Ceres differentiates is exactly what the model computes. Not installed.
*/

#ifndef _vpMarkerObservationError_h_
#define _vpMarkerObservationError_h_

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpProjection.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  Pixel error (4 residuals: u, v, u', v') of one marker observation of an arm's acquisition. Parameters: \f$ G^{-1}
  \f$ (16, row-major), the right camera \f$ P' \f$ (12, row-major; the left one \f$ P \f$ is fixed), the marker's
  metric point \f$ N \f$ (4, homogeneous) and, for a trial, the joint's twist: the axis (3; normalised here, so that a
  revolute axis is a direction) and a point of it (3) for a revolute joint, the motion per joint unit (3) for a
  prismatic one. The predicted point is \f$ G^{-1} \exp(q \hat T) N \f$ seen by \f$ P, P' \f$.
*/
class MarkerObservationError
{
public:
  //! An observation \e s at the zero reference (no joint moved).
  MarkerObservationError(const vpProjectiveStereoRig::Projection &P, const Eigen::Vector4d &s)
      : m_P(P), m_s(s), m_type(vpProjectiveJoint::REVOLUTE), m_q(0.0)
  {
  }
  //! An observation \e s after a joint of kind \e type alone moved by \e q.
  MarkerObservationError(const vpProjectiveStereoRig::Projection &P, const Eigen::Vector4d &s,
                         vpProjectiveJoint::vpJointType type, double q)
      : m_P(P), m_s(s), m_type(type), m_q(q)
  {
  }

  //! Zero reference: parameters G^-1, P', N.
  template <typename T> bool operator()(const T *Ginv, const T *Pp, const T *N, T *r) const
  {
    return residual(Ginv, Pp, Eigen::Matrix<T, 4, 1>(N[0], N[1], N[2], N[3]), r);
  }
  //! Prismatic trial: parameters G^-1, P', N, d.
  template <typename T> bool operator()(const T *Ginv, const T *Pp, const T *N, const T *d, T *r) const
  {
    const Eigen::Matrix<T, 4, 4> That = vpMetricTwist::prismatic(Eigen::Matrix<T, 3, 1>(d[0], d[1], d[2]));
    return residual(Ginv, Pp,
                    vpProjectiveJoint::act(m_type, That, T(m_q), Eigen::Matrix<T, 4, 1>(N[0], N[1], N[2], N[3])), r);
  }
  //! Revolute trial: parameters G^-1, P', N, axis w, point p.
  template <typename T> bool operator()(const T *Ginv, const T *Pp, const T *N, const T *w, const T *p, T *r) const
  {
    const Eigen::Matrix<T, 3, 1> axis = Eigen::Matrix<T, 3, 1>(w[0], w[1], w[2]).normalized();
    const Eigen::Matrix<T, 4, 4> That = vpMetricTwist::revolute(axis, Eigen::Matrix<T, 3, 1>(p[0], p[1], p[2]));
    return residual(Ginv, Pp,
                    vpProjectiveJoint::act(m_type, That, T(m_q), Eigen::Matrix<T, 4, 1>(N[0], N[1], N[2], N[3])), r);
  }

private:
  template <typename T> bool residual(const T *Ginv, const T *Pp, const Eigen::Matrix<T, 4, 1> &N, T *r) const
  {
    const Eigen::Matrix<T, 4, 1> M = Eigen::Map<const Eigen::Matrix<T, 4, 4, Eigen::RowMajor>>(Ginv) * N;
    Eigen::Matrix<T, 4, 1> s;
    if (!projectStereo(m_P, Eigen::Map<const Eigen::Matrix<T, 3, 4, Eigen::RowMajor>>(Pp), M, s)) {
      return false;
    }
    for (int k = 0; k < 4; ++k) {
      r[k] = s(k) - T(m_s(k));
    }
    return true;
  }

  vpProjectiveStereoRig::Projection m_P; // the left camera, fixed (the frame's gauge)
  Eigen::Vector4d m_s;
  vpProjectiveJoint::vpJointType m_type;
  double m_q;
};

} // namespace vpProjectiveInternal

#endif
