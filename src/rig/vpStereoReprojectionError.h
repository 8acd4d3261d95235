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
  Private: the Ceres cost functor of the rig's gold-standard estimation, on the plugin's projection (vpProjection.h)
  templated on the scalar. Not installed.
*/

#ifndef _vpStereoReprojectionError_h_
#define _vpStereoReprojectionError_h_

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpProjection.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  Reprojection error (4 residuals) of one match of the gold-standard fundamental matrix, in Hartley-normalised image
  coordinates weighted back to pixels: the left camera is \f$ [I | 0] \f$, the right camera \f$ P' \f$ (12,
  row-major) and the point \f$ M \f$ (4) are the parameters.
*/
class StereoReprojectionError
{
public:
  StereoReprojectionError(const Eigen::Vector2d &left, const Eigen::Vector2d &right, double leftScale,
                          double rightScale)
      : m_left(left), m_right(right), m_leftScale(leftScale), m_rightScale(rightScale)
  {
  }

  template <typename T> bool operator()(const T *Pp, const T *M, T *residual) const
  {
    const Eigen::Matrix<T, 4, 1> Me(M[0], M[1], M[2], M[3]);
    Eigen::Matrix<T, 2, 1> uv, uvp;
    if (!projectPoint(vpProjectiveStereoRig::Projection::Identity(), Me, uv) ||
        !projectPoint(Eigen::Map<const Eigen::Matrix<T, 3, 4, Eigen::RowMajor>>(Pp), Me, uvp)) {
      return false;
    }
    residual[0] = (uv(0) - T(m_left(0))) / T(m_leftScale);
    residual[1] = (uv(1) - T(m_left(1))) / T(m_leftScale);
    residual[2] = (uvp(0) - T(m_right(0))) / T(m_rightScale);
    residual[3] = (uvp(1) - T(m_right(1))) / T(m_rightScale);
    return true;
  }

private:
  Eigen::Vector2d m_left, m_right;
  double m_leftScale, m_rightScale;
};
} // namespace vpProjectiveInternal

#endif
