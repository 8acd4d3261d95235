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
  Private: the pieces of the robust p-displacement estimation (vpProjectiveDisplacementRobust.cpp): the 5-point
  hypothesis and the gold-standard error of one point under a hypothesis. Not installed.
*/

#ifndef _vpDisplacementHypothesis_h_
#define _vpDisplacementHypothesis_h_

#include <limits>

#include <Eigen/Cholesky>
#include <Eigen/Core>

#include <visp3/projective/vpProjectiveStereoRig.h>

#include "core/vpProjection.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*
  The homography of P^3 that maps 5 points X (unit, whitened) onto 5 points Y, in closed form: with
  X[0..3] diag(a) = A, a = [X0 X1 X2 X3]^-1 X4, A maps the standard frame (e_1..e_4, e_1 + .. + e_4) onto the X's, and
  likewise B onto the Y's, so Hw = B A^-1. Degenerate when 4 of the 5 points of either set are coplanar (or repeated):
  the determinant of the 4 others, a_i det[X0..X3] for the set without X_i, vanishes. Reversed when Hw reverses
  orientation: no displacement does (det H = det T > 0, eq. (11); the whitenings have positive determinants).
*/
enum MinimalResult { MinimalValid, MinimalDegenerate, MinimalReversed };
MinimalResult minimalHomography(const Eigen::Vector4d *const X[5], const Eigen::Vector4d *const Y[5],
                                Eigen::Matrix4d &Hw);

/*
  The gold-standard error of one rigid point under a candidate H (any scale): the four cameras P, P', P H, P' H
  in \e cameras and their observations s = (s0, s1) (8 pixels). Writes the 8 residuals of M (unit) and their
  Jacobian (8x4); false if M is on a camera's focal plane.
*/
struct GoldStandardPoint {
  vpProjectiveStereoRig::Projection cameras[4]; // P, P', P H, P' H (H of unit norm)

  void setDisplacement(const vpProjectiveStereoRig::Projection &P, const vpProjectiveStereoRig::Projection &Pp,
                       const Eigen::Matrix4d &H)
  {
    const Eigen::Matrix4d Hs = H / H.norm();
    cameras[0] = P;
    cameras[1] = Pp;
    cameras[2] = P * Hs;
    cameras[3] = Pp * Hs;
  }

  bool residuals(const Eigen::Matrix<double, 8, 1> &s, const Eigen::Vector4d &M, Eigen::Matrix<double, 8, 1> &r,
                 Eigen::Matrix<double, 8, 4> &J) const
  {
    Eigen::Vector2d uv;
    Eigen::Matrix<double, 2, 4> Jk;
    for (int k = 0; k < 4; ++k) {
      if (!projectPoint(cameras[k], M, uv, &Jk)) {
        return false;
      }
      r.segment<2>(2 * k) = uv - s.segment<2>(2 * k);
      J.block<2, 4>(2 * k, 0) = Jk;
    }
    return r.allFinite();
  }

  /*
    min over M of the squared residual, by at most two Gauss-Newton steps on the unit sphere from \e M (updated): an
    upper bound of the minimum, reached to first order for a correct point. Infinity if M has no image.
  */
  double squaredError(const Eigen::Matrix<double, 8, 1> &s, Eigen::Vector4d &M) const
  {
    Eigen::Matrix<double, 8, 1> r;
    Eigen::Matrix<double, 8, 4> J;
    if (!residuals(s, M, r, J)) {
      return std::numeric_limits<double>::infinity();
    }
    double cost = r.squaredNorm();
    for (int iteration = 0; iteration < 2; ++iteration) {
      // J M = 0 (a projection ignores the scale of M): the term M M^T fixes the step orthogonal to M.
      Eigen::Matrix4d N = J.transpose() * J;
      const double scale = N.trace();
      if (!(scale > 0.0)) {
        break;
      }
      N += (0.25 * scale) * M * M.transpose();
      const Eigen::Vector4d delta = N.llt().solve(-J.transpose() * r);
      const Eigen::Vector4d Mnew = (M + delta).normalized();
      Eigen::Matrix<double, 8, 1> rNew;
      Eigen::Matrix<double, 8, 4> JNew;
      if (!Mnew.allFinite() || !residuals(s, Mnew, rNew, JNew)) {
        break;
      }
      const double costNew = rNew.squaredNorm();
      if (!(costNew < cost)) {
        break;
      }
      const bool converged = cost - costNew <= 1e-6 * cost;
      M = Mnew;
      r = rNew;
      J = JNew;
      cost = costNew;
      if (converged) {
        break;
      }
    }
    return cost;
  }

  /*
    Cheirality of a point M under H: a point in front of both cameras stays so after a rigid motion, and with H = lambda
    H_PE^-1 T H_PE the depths (P M)_3 and (P H M)_3 (likewise with P') have the sign of lambda for every point, whatever
    the scale and sign of M. Returns that sign (+1 or -1), or 0 if the two cameras disagree.
  */
  int cheirality(const Eigen::Vector4d &M) const
  {
    const double left = cameras[0].row(2).dot(M) * cameras[2].row(2).dot(M);
    const double right = cameras[1].row(2).dot(M) * cameras[3].row(2).dot(M);
    if (left > 0.0 && right > 0.0) {
      return 1;
    }
    return left < 0.0 && right < 0.0 ? -1 : 0;
  }
};
} // namespace vpProjectiveInternal

#endif
