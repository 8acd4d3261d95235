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
  Private: the maximum-likelihood estimate of a p-displacement from stereo images, the one such estimator of the
  plugin (vpProjectiveDisplacement::estimateFromImages() and the robust estimator both use it). Not installed.
*/

#ifndef _vpDisplacementAdjustment_h_
#define _vpDisplacementAdjustment_h_

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  The pixels \f$ (u, v, u', v') \f$ of each point before (\e s0) and after (\e s1) the motion from the four image
  lists of the vpImagePoint overloads; throws (dimensionError, nonFiniteValueError, naming \e where) if the lists
  differ in size or a coordinate is not finite.
*/
void stackImagePairs(const std::vector<vpImagePoint> &left0, const std::vector<vpImagePoint> &right0,
                     const std::vector<vpImagePoint> &left1, const std::vector<vpImagePoint> &right1,
                     const std::string &where, std::vector<Eigen::Vector4d> &s0, std::vector<Eigen::Vector4d> &s1);

/*!
  The data of a displacement estimated from images: the stacked pixels \f$ s_j = (s_{0,j}, s_{1,j}) \f$ (8x1:
  \f$ (u, v, u', v') \f$ before, then after the motion), the triangulated points \f$ M_{0,j}, M_{1,j} \f$ (unit),
  the whitenings \f$ T_0, T_1 \f$ of each set and the whitened unit points \f$ X_j = T_0 M_{0,j} \f$,
  \f$ Y_j = T_1 M_{1,j} \f$.
*/
struct DisplacementData {
  //! Triangulates and whitens the pixels \e s0[j], \e s1[j] (same sizes, finite: unchecked) seen by \e rig.
  DisplacementData(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                   const std::vector<Eigen::Vector4d> &s1);

  const vpProjectiveStereoRig *rig;
  std::vector<Eigen::Matrix<double, 8, 1>> s;
  std::vector<Eigen::Vector4d> M0, M1, X, Y;
  Eigen::Matrix4d T0, T0inv, T1, T1inv;

  size_t size() const { return s.size(); }
  //! H in the rig's frame of a homography Hw between the whitened points.
  Eigen::Matrix4d unwhiten(const Eigen::Matrix4d &Hw) const { return T1inv * Hw * T0; }
};

/*
  The maximum-likelihood refit of estimateFromImages() (the same cost: the pixel error of the four images over H and
  the points), solved by a dedicated Levenberg-Marquardt with the points eliminated by the Schur complement: the
  robust estimator refits a few times per call and the robot's acquisition calls it a dozen times, where a generic
  solver's set-up costs more than the solve. It works in the whitened frames (view 0: X = T0 M, view 1: T1 H M, so
  Hw = T1 H T0^-1), where H and the points are well conditioned; each of Hw (16 entries) and the points X (4) lives on
  its unit sphere, the scale gauge being removed by a term along the current value (the residuals do not depend on
  it: J h = 0, J X = 0).
*/
class DisplacementAdjustment
{
public:
  explicit DisplacementAdjustment(const DisplacementData &data);

  /*
    Refines H (rig frame, any scale; returned normalised by (12)) and points[j] (rig frame, unit) on the flagged
    points, until an accepted step lowers the cost by less than \e tolerance times it, or after \e maxIterations.
    Returns false, leaving H and the points unchanged, if no step lowered the cost, a point left the image, or the
    result is singular or reverses orientation (no displacement).
  */
  bool refine(const std::vector<bool> &flags, Eigen::Matrix4d &H, std::vector<Eigen::Vector4d> &points,
              int maxIterations, double tolerance = 1e-12) const;

  /*
    Rigidity statistic of H fitted to the flagged points at their fitted positions \e points: max_k |c_k| / s_k, c
    the rigidity residual of H (rigidityResidual()) and s_k the RMS change of c_k over draws of H from its covariance
    sigma^2 S^-1 (S the Schur complement of the normal equations at the fit, in the whitened frame; sigma the RMS
    residual per coordinate over 5 m - 15 degrees of freedom for m points, at least \e sigmaFloor). Measured on the
    correct data of the tests (275 fits of 7 to 30 points): median 0.6, largest 3.3, and no rejection at the bound 8
    over 1600 correct 7-marker motions of every kind; homographies that absorbed mismatches: 16 and more, or det H <= 0
    (infinity). 0 when the noise alone leaves H undetermined (no rejection).
  */
  double rigidityStatistic(const std::vector<bool> &flags, const Eigen::Matrix4d &H,
                           const std::vector<Eigen::Vector4d> &points, double sigmaFloor) const;

private:
  typedef Eigen::Matrix<double, 4, 4, Eigen::RowMajor> RowMajor4;

  /*
    The flagged points' indices, and H (rig frame) and their points in the whitened frames, each on its unit sphere:
    Hw = T1 H T0^-1, X = T0 M.
  */
  void whiten(const std::vector<bool> &flags, const Eigen::Matrix4d &H, const std::vector<Eigen::Vector4d> &points,
              std::vector<size_t> &index, RowMajor4 &Hw, std::vector<Eigen::Vector4d> &X) const;
  /*
    Residuals r (8 pixels) of the flagged points and, if asked, their Jacobians: A (4x16, view-1 rows, with respect to
    the row-major entries of Hw) and B (8x4, with respect to X). False if a point is on a camera's focal plane.
  */
  bool evaluate(const std::vector<size_t> &index, const RowMajor4 &Hw, const std::vector<Eigen::Vector4d> &X,
                std::vector<Eigen::Matrix<double, 8, 1>> &r, std::vector<Eigen::Matrix<double, 4, 16>> *A,
                std::vector<Eigen::Matrix<double, 8, 4>> *B, double &cost) const;

  const DisplacementData &m_data;
  vpProjectiveStereoRig::Projection m_P0, m_Pp0, m_P1, m_Pp1; // the rig's cameras in the whitened frames
};
} // namespace vpProjectiveInternal

#endif
