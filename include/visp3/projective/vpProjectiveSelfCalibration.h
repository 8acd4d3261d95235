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
  \file vpProjectiveSelfCalibration.h
  \brief Metric self-calibration of a stereo rig and an arm from the projective model acquired with them.
*/

#ifndef _vpProjectiveSelfCalibration_h_
#define _vpProjectiveSelfCalibration_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveSelfCalibration
  \ingroup group_projective
  \brief The metric stereo rig and the arm's joint axes that a vpProjectiveArmModel holds without anybody having
  calibrated anything.

  The acquisition's bundle adjustment shares one \f$ G \f$ between all generators, \f$ \hat H_i = G^{-1} \hat T_i G
  \f$ with metric twists \f$ \hat T_i \f$: \f$ G \f$ is \f$ H_{PE} \f$ up to a similarity, so it maps the projective
  frame to a metric frame \f$ E' \f$ that differs from the left camera's frame by a rotation, a translation and a
  scale. In that frame the two cameras are
  \f[ P G^{-1} \simeq K_l [R_l \,|\, t_l], \qquad P' G^{-1} \simeq K_r [R_r \,|\, t_r], \f]
  and an RQ decomposition of each left 3x3 block gives the intrinsics \f$ K \f$ (upper triangular with the skew,
  \f$ K_{33} = 1 \f$, positive focal lengths) and the rotations; the sign of each camera matrix is the one that puts
  the markers in front of it, and a mirrored \f$ E' \f$ (an improper \f$ R \f$) is turned into a right-handed one. The
  right camera's pose in the left one is then
  \f[ {}^l M_r = \begin{bmatrix} R_l R_r^T & t_l - R_l R_r^T t_r \\ 0 & 1 \end{bmatrix}, \qquad X_l = {}^l M_r X_r,
  \f]
  its translation known up to the scale of \f$ E' \f$, which a prismatic joint's encoder fixes (its twist is the
  motion per encoder unit: the translation comes out in encoder units, least squares over the prismatic joints), or
  a known distance between two markers, or else the baseline is given unit length.

  The accuracy is that of \f$ G \f$, hence of the acquisition: the trials' amplitudes and the spread of the markers
  fix how well the plane at infinity and the metric conic are determined (see the page \ref page_self_calibration).
*/
class VISP_EXPORT vpProjectiveSelfCalibration
{
public:
  //! How the metric scale of the translations is fixed.
  enum vpScale {
    SCALE_FROM_PRISMATIC_JOINTS, //!< Encoder units of the prismatic joints (least squares over them).
    SCALE_UNIT_BASELINE,         //!< The baseline has length 1.
    SCALE_MARKER_DISTANCE        //!< Two markers a known distance apart.
  };

  /*!
    The metric rig of \e model.
    \param model : an acquired model.
    \param Kl, Kr : intrinsics of the left and right cameras (3x3, pixels, skew included, \f$ K_{33} = 1 \f$).
    \param lMr : pose of the right camera in the left camera's frame (4x4 rigid, \f$ X_l = {}^l M_r X_r \f$).
    \param scale : how the translation's unit is fixed; SCALE_FROM_PRISMATIC_JOINTS falls back to a unit baseline
    when the arm has no prismatic joint.
    \param markerA, markerB, distance : with SCALE_MARKER_DISTANCE, two marker indices of the model and their
    distance (any positive length unit, which the translation then takes).
    \return the scale applied: lengths of the metric frame of \e model (vpProjectiveArmModel::projectiveToMetric())
    times this value are in the unit of \e lMr.
    \exception vpProjectiveException (notInitializedError) for an empty model; (invalidValueError, dimensionError)
    for a bad marker index or distance; (degenerateConfigurationError) if a camera matrix is singular in the metric
    frame or the baseline is zero.
  */
  static double metricStereoRig(const vpProjectiveArmModel &model, Eigen::Matrix3d &Kl, Eigen::Matrix3d &Kr,
                                Eigen::Matrix4d &lMr, vpScale scale = SCALE_FROM_PRISMATIC_JOINTS,
                                unsigned int markerA = 0, unsigned int markerB = 1, double distance = 0.0);

  /*!
    The joints' axes in the left camera's frame: for each joint a unit direction (3x1: a revolute joint's axis, or a
    prismatic joint's direction of motion) and a point (3x1: on a revolute joint's axis, in the unit of
    metricStereoRig() with the same scale arguments; the origin for a prismatic joint).
    \exception vpProjectiveException as metricStereoRig().
  */
  static void jointAxes(const vpProjectiveArmModel &model, std::vector<Eigen::Vector3d> &direction,
                        std::vector<Eigen::Vector3d> &point, vpScale scale = SCALE_FROM_PRISMATIC_JOINTS,
                        unsigned int markerA = 0, unsigned int markerB = 1, double distance = 0.0);
};

END_VISP_NAMESPACE

#endif
