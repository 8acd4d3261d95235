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
  \file vpProjectiveMotionCapture.h
  \brief Articulated motion capture: the joint values and velocities of an arm from its marker images, frame by frame.
*/

#ifndef _vpProjectiveMotionCapture_h_
#define _vpProjectiveMotionCapture_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpProjectiveArmModel.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveMotionCapture
  \ingroup group_projective
  \brief Motion capture of an arm that moves on its own (teleoperated, or a passive mechanism) with the projective
  model acquired from it (the seed's "motion capture" use): at every frame, the joint values \f$ q(t) \f$ that
  explain the observed marker images (vpProjectiveInverseKinematics, warm-started at the previous frame's values), and
  the joint velocities, the least-squares slope of \f$ q \f$ over the last frames.

  With Gaussian pixel noise \f$ \sigma \f$ the estimate at a frame is the maximum-likelihood one: its covariance is
  the floor \f$ \sigma^2 (J^T J)^{-1} \f$ of the stacked image Jacobian (46) of the observed markers, which no
  estimator from one frame beats. A marker flagged not visible (or with non-finite pixels) is left out of its frame;
  the frame needs enough markers to constrain every joint (each constrains at most 3 of them, and 2 may leave a
  rotation about the line through them free).

  \code
  vpProjectiveMotionCapture capture(robot.getModel());
  capture.setInitialJoints(q0);           // near the first frame's pose (the zero reference's if not set)
  for (each frame) {
    capture.capture(t, left, right);       // images of the model's markers, in order
    vpColVector q = capture.getJoints(), qdot = capture.getJointVelocities();
  }
  \endcode
*/
class VISP_EXPORT vpProjectiveMotionCapture
{
public:
  /*!
    Captures the arm of \e model (kept by reference: it must outlive the capture), observing the markers \e indices
    of the model (all if empty).
    \exception vpProjectiveException (notInitializedError) for an empty model, (dimensionError) for a bad index.
  */
  explicit vpProjectiveMotionCapture(const vpProjectiveArmModel &model,
                                     const std::vector<unsigned int> &indices = std::vector<unsigned int>());

  /*!
    The joint values (n x 1) the first frame starts from; the zero reference's by default. Clears the history.
    \exception vpProjectiveException if \e q0 has not n finite entries.
  */
  void setInitialJoints(const vpColVector &q0);
  /*!
    Number \f$ w \ge 1 \f$ of past frames the velocity is fitted over (default 4).
    \exception vpProjectiveException (invalidValueError) if \e frames is 0.
  */
  void setVelocityWindow(unsigned int frames);

  /*!
    One frame at time \e t: the images of the observed markers (in the order of the constructor's \e indices);
    a marker whose \e visible flag is false (all visible if empty) or whose pixels are not finite is left out.
    \exception vpProjectiveException (dimensionError) on sizes that differ; (invalidValueError) if \e t is not after
    the previous frame's; (notEnoughPointsError) if the visible markers cannot constrain every joint
    (\f$ 2 K < n \f$); (estimationFailedError) if the minimisation fails. Nothing changes on failure.
  */
  void capture(double t, const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
               const std::vector<bool> &visible = std::vector<bool>());
  /*!
    capture() on Eigen types, \e s[k] the pixels \f$ (u, v, u', v') \f$ of observed marker k (non-finite: lost).
    Allocates nothing once the history is full and the visibility of the markers does not change. Returns the joint
    values.
  */
  const vpProjectiveArmModel::JointVector &capture(double t, const std::vector<Eigen::Vector4d> &s);

  //! The joint values (n x 1) of the last frame (the starting values before the first).
  vpColVector getJoints() const;
  /*!
    The joint velocities (n x 1, per time unit) at the last frame: the least-squares slope of the joint values over
    the last \f$ w + 1 \f$ frames (one-sided: no future frame is waited for).
    \exception vpProjectiveException (notInitializedError) before the second frame.
  */
  vpColVector getJointVelocities() const;
  //! RMS pixel error per coordinate of the last frame.
  double getResidual() const { return m_residual; }
  //! Number of markers used by the last frame.
  unsigned int getNumberOfTrackedMarkers() const { return static_cast<unsigned int>(m_visibleIndices.size()); }

private:
  const vpProjectiveArmModel &m_model;
  std::vector<unsigned int> m_indices;
  vpProjectiveArmModel::JointVector m_q;
  std::vector<vpProjectiveArmModel::JointVector> m_history;
  std::vector<double> m_times;
  unsigned int m_window;
  double m_residual;
  std::vector<Eigen::Vector4d> m_visible;     // the visible markers' pixels of the current frame
  std::vector<unsigned int> m_visibleIndices; // and their model indices
};

END_VISP_NAMESPACE

#endif
