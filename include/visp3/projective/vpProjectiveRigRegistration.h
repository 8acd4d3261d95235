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
  \file vpProjectiveRigRegistration.h
  \brief Re-registration of a moved stereo rig in the projective frame of an acquired arm model (camera resection).
*/

#ifndef _vpProjectiveRigRegistration_h_
#define _vpProjectiveRigRegistration_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveRigRegistration
  \ingroup group_projective
  \brief Re-estimates both cameras of a stereo rig that moved (a bumped camera, a moved rig) in the projective frame
  \f$ \mathcal{P} \f$ of an acquired vpProjectiveArmModel, from the images of its markers at a few joint
  configurations: the arm model is kept, only the camera pair changes.

  <b>Data.</b> Observation \f$ k \f$ is the joint values \f$ q_k \f$ (n x 1, the model's) and the images
  \f$ s_{kj} = (u, v, u', v') \f$ (pixels) of every marker \f$ j \f$ of the model, in the model's order. The model
  predicts the projective points \f$ X_{kj} = H(q_k) M_j(0) \f$ (4x1, eq. (34)), so each camera is a resection
  problem: find \f$ P \f$ (3x4) with \f$ (u, v, 1)^T \simeq P X_{kj} \f$.

  <b>Fixed intrinsics (default).</b> A bumped camera keeps its intrinsics. With \f$ G \f$ the model's metric upgrade
  (\f$ H_{PE} \f$ up to a similarity), the old camera is \f$ P_0 G^{-1} \simeq K [R_0 | t_0] \f$, and the moved one
  \f$ P = P_0 G^{-1} T(\omega, t)\, G \f$ with \f$ T(\omega, t) = [R(\omega)\; t; 0\; 1] \f$ a rigid motion of the
  metric frame (6 parameters: the angle-axis \f$ \omega \f$ in radians and \f$ t \f$ in the unit of \f$ G \f$'s
  frame). Start: the better (lower cost) of \f$ T = I \f$ and the rigid motion closest to a linear resection (DLT on
  Hartley-normalised pixels and whitened points); then Ceres minimises the pixel reprojection error over
  \f$ (\omega, t) \f$. registerRig() then decides which cameras moved: the left one, the right one, the whole rig
  (one \f$ T \f$ shared by both cameras, refitted on both images) or each its own, by the lowest Bayesian information
  criterion \f$ N \ln(\mathrm{SSE}/N) + p \ln N \f$ (\f$ N \f$ pixel coordinates, \f$ p \f$ = 6, 6, 6 or 12
  parameters). A camera that did not move keeps its acquired projection exactly: the disparities, hence the depths,
  keep the acquisition's accuracy instead of that of a few noisy observations.

  <b>Refining with the servo's frames.</b> The frames of a running task are observations too: a vpServoProjective
  task refines the rig itself after updateRig() (vpServoProjective::getRigRefinement(), on by default), through
  vpProjectiveRobot::refineRig() and the overload of registerRig() from given points. With the first observation
  poses and the frames seen where the task ends, the new cameras predict the features best where the re-expressed
  \f$ s^* \f$ matters (measured: \ref servo_meas_mismatch).

  <b>General (11 parameters).</b> DLT, then Ceres on the reprojection error over \f$ P \f$ (unit Frobenius norm).
  Needs more observations to reach the same accuracy; kept for a camera whose intrinsics changed (zoom, refocus).

  No projective point is divided by its last coordinate.
*/
class VISP_EXPORT vpProjectiveRigRegistration
{
public:
  //! What may change in a camera.
  enum vpRegistrationMode {
    FIXED_INTRINSICS, //!< The cameras moved rigidly: 6 parameters each (default).
    GENERAL           //!< Any camera: 11 parameters each.
  };

  //! Largest RMS reprojection error (pixels) of a camera accepted by registerRig(): above, the data is inconsistent.
  static constexpr double maxResidual = 10.0;

  /*!
    Resection of one camera.
    \param Pold : the camera before the move (3x4, model frame).
    \param G : the model's projective-to-metric matrix (4x4, invertible), used by FIXED_INTRINSICS.
    \param X : projective points (4x1 each, model frame, any scale).
    \param uv : their pixels (2x1 each), same order.
    \param mode : FIXED_INTRINSICS or GENERAL.
    \param rms : if not null, receives the RMS reprojection error per coordinate (pixels).
    \return the camera (3x4, unit Frobenius norm).
    \exception vpProjectiveException (dimensionError) if the sizes differ; (notEnoughPointsError) below 6 points;
    (degenerateConfigurationError) if the points are (nearly) coplanar or the linear resection is undetermined;
    (estimationFailedError) if the refinement gives no finite camera.
  */
  static vpProjectiveStereoRig::Projection resect(const vpProjectiveStereoRig::Projection &Pold,
                                                  const Eigen::Matrix4d &G, const std::vector<Eigen::Vector4d> &X,
                                                  const std::vector<Eigen::Vector2d> &uv,
                                                  vpRegistrationMode mode = FIXED_INTRINSICS, double *rms = nullptr);

  /*!
    Both cameras of \e model's rig re-estimated from the observations (see the class documentation).
    \param model : the acquired model (its rig gives the cameras before the move).
    \param q : joint values of each observation (n x 1 each).
    \param images : per observation, \f$ (u, v, u', v') \f$ (pixels) of every marker of the model, in its order.
    \param mode : FIXED_INTRINSICS or GENERAL.
    \param rms : if not null, receives the RMS reprojection error per coordinate of the new pair (pixels).
    \return the new rig: a general camera pair (vpProjectiveStereoRig::setProjections()) in the model's frame.
    \exception vpProjectiveException as resect(), (notEnoughPointsError) below 3 observations, (dimensionError) on
    sizes that disagree, (estimationFailedError) if a camera's RMS error exceeds maxResidual (the arm model does not
    explain the images: slipped markers, wrong marker order).
  */
  static vpProjectiveStereoRig registerRig(const vpProjectiveArmModel &model,
                                           const std::vector<vpProjectiveArmModel::JointVector> &q,
                                           const std::vector<std::vector<Eigen::Vector4d>> &images,
                                           vpRegistrationMode mode = FIXED_INTRINSICS, double *rms = nullptr);

  /*!
    Both cameras of the rig \e old re-estimated from given points (see the class documentation): the same as the
    other overload, whose markers moved by \f$ H(q_k) \f$ are such points, for points that are not the model's
    markers (e.g. a servo task's features, whose zero-reference points the task remembers: the refinement of
    vpServoProjective::getRigRefinement()).
    \param old : the rig before the move, in the model's frame.
    \param G : the model's projective-to-metric matrix (4x4, invertible), used by FIXED_INTRINSICS.
    \param points : projective points (4x1 each, model frame, any scale) where they were seen, e.g.
    \f$ H(q_k) M_j(0) \f$.
    \param images : their images \f$ (u, v, u', v') \f$ (pixels), same order.
    \param mode : FIXED_INTRINSICS or GENERAL.
    \param rms : if not null, receives the RMS reprojection error per coordinate of the new pair (pixels).
    \return the new rig: a general camera pair in the model's frame.
    \exception vpProjectiveException (dimensionError) if the sizes differ; (nonFiniteValueError) on a non-finite or
    zero point or a non-finite pixel; those of resect(); (estimationFailedError) if a camera's RMS error exceeds
    maxResidual.
  */
  static vpProjectiveStereoRig registerRig(const vpProjectiveStereoRig &old, const Eigen::Matrix4d &G,
                                           const std::vector<Eigen::Vector4d> &points,
                                           const std::vector<Eigen::Vector4d> &images,
                                           vpRegistrationMode mode = FIXED_INTRINSICS, double *rms = nullptr);
};

END_VISP_NAMESPACE

#endif
