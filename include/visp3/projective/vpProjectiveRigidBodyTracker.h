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
  \file vpProjectiveRigidBodyTracker.h
  \brief Frame-by-frame p-displacement and velocity of a rigid marker set seen by an uncalibrated stereo rig.
*/

#ifndef _vpProjectiveRigidBodyTracker_h_
#define _vpProjectiveRigidBodyTracker_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveBodyVelocity.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveRigidBodyTracker
  \ingroup group_projective
  \brief Rigid-body tracking in the projective frame (the seed's "tracking" use of projective kinematics): the
  p-displacement \f$ H(t) \f$ (10) of a rigid set of \f$ K \ge 5 \f$ markers from their reference images, at every
  frame of a stereo sequence, and its body velocity (13).

  init() triangulates the markers' projective points \f$ M_j \f$ (4x1) at the reference. At each frame, track()
  minimises the pixel error \f$ \sum_j \| s_j(t) - \pi(H M_j) \|^2 \f$ of the visible markers over \f$ H \f$ (16
  entries on their unit sphere, in the frame whitened by the reference points, by Levenberg-Marquardt), warm-started
  at the previous frame's \f$ H \f$: with the points fixed it needs 4 markers in general position. A homography has 15
  degrees of freedom where a rigid motion has 6, so with a few markers on a small object the projective estimate is
  noisy; when the metric upgrade \f$ G \f$ of the rig is known (setProjectiveToMetric(), for instance
  vpProjectiveArmModel::projectiveToMetric() of an arm acquired with the same rig), the tracker estimates the rigid
  motion itself, \f$ H = G^{-1} T G \f$ with \f$ T \in SE(3) \f$ (6 degrees of freedom, 3 markers suffice). A marker the
  tracker lost (flagged not visible, or with non-finite pixels) is left out of that frame. If the warm start does not
  converge (the first frame, a jump), the maximum-likelihood estimate from the images (vpProjectiveDisplacement) of at
  least 5 visible markers starts it. The velocity is the least-squares slope of the logarithms over the last frames
  (vpProjectiveBodyVelocity::fromSequence(), one-sided at the newest frame).
*/
class VISP_EXPORT vpProjectiveRigidBodyTracker
{
public:
  vpProjectiveRigidBodyTracker();

  /*!
    The reference: the weakly calibrated rig and the markers' images (pixels) at time \e t0 (seconds or any unit).
    Clears the history.
    \exception vpProjectiveException if the rig has no F (notInitializedError), the sizes differ (dimensionError),
    fewer than 5 markers are given (notEnoughPointsError), or a coordinate is not finite (nonFiniteValueError).
  */
  void init(const vpProjectiveStereoRig &rig, const std::vector<vpImagePoint> &left0,
            const std::vector<vpImagePoint> &right0, double t0 = 0.0);
  /*!
    The metric upgrade \f$ G \f$ (4x4) of the rig's projective frame (\f$ H_{PE} \f$ up to a similarity, e.g.
    vpProjectiveArmModel::projectiveToMetric()): from the next frame on, the displacements are rigid,
    \f$ H = G^{-1} T G \f$, \f$ T \in SE(3) \f$. An empty matrix returns to projective tracking.
    \exception vpProjectiveException if \e G is not 4x4 (or empty), not finite or singular.
  */
  void setProjectiveToMetric(const vpMatrix &G);
  //! True once init() succeeded.
  bool isInitialized() const { return !m_M.empty(); }

  /*!
    One frame at time \e t (after the previous frame's): the images of the same markers in the same order; a marker
    whose \e visible flag is false (all visible if \e visible is empty) or whose pixels are not finite is ignored.
    Returns \f$ H(t) \f$, the displacement from the reference.
    \exception vpProjectiveException (notInitializedError) before init(); (dimensionError) on sizes that differ from
    the reference; (invalidValueError) if \e t is not after the previous frame; (notEnoughPointsError) if fewer than
    4 markers are visible (3 in rigid tracking; 5 when the warm start fails); (estimationFailedError) if no displacement
    explains them. Nothing changes on failure.
  */
  vpProjectiveDisplacement track(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                 double t, const std::vector<bool> &visible = std::vector<bool>());
  /*!
    track() on Eigen types: \e s[j] the pixels \f$ (u, v, u', v') \f$ of marker j (non-finite: lost). Allocates
    nothing once the history is full.
  */
  const Eigen::Matrix4d &track(const std::vector<Eigen::Vector4d> &s, double t);

  //! \f$ H(t) \f$ of the last frame (the identity before the first).
  const vpProjectiveDisplacement &getDisplacement() const { return m_H; }
  /*!
    Body velocity at the last frame: the least-squares slope over the last \f$ w + 1 \f$ frames (setVelocityWindow()).
    \exception vpProjectiveException (notInitializedError) before the first frame.
  */
  vpProjectiveBodyVelocity getVelocity() const;
  /*!
    Number \f$ w \ge 1 \f$ of past frames the velocity is fitted over (default 4). Larger windows smooth more and lag
    more.
    \exception vpProjectiveException (invalidValueError) if \e frames is 0.
  */
  void setVelocityWindow(unsigned int frames);
  //! RMS pixel error per coordinate of the last frame's visible markers.
  double getResidual() const { return m_residual; }
  //! Number of markers used by the last frame.
  unsigned int getNumberOfTrackedMarkers() const { return m_tracked; }
  //! The markers' projective points at the reference (4x1, unit norm).
  const std::vector<Eigen::Vector4d> &getReferencePoints() const { return m_M; }

private:
  bool refine(const std::vector<Eigen::Vector4d> &s, Eigen::Matrix4d &H, double &cost, unsigned int &used) const;
  bool refineRigid(const std::vector<Eigen::Vector4d> &s, Eigen::Matrix4d &T, double &cost, unsigned int &used) const;

  vpProjectiveStereoRig m_rig;
  std::vector<Eigen::Vector4d> m_M; // reference points, unit norm
  Eigen::Matrix4d m_T, m_Tinv;      // whitening of the reference points
  bool m_rigid;                     // H = G^-1 T G with T rigid
  Eigen::Matrix4d m_G, m_Ginv;
  vpProjectiveDisplacement m_H;
  std::vector<vpProjectiveDisplacement> m_history;
  std::vector<double> m_times;
  unsigned int m_window;
  double m_residual;
  unsigned int m_tracked;
};

END_VISP_NAMESPACE

#endif
