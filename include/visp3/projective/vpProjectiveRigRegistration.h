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

  //! One image, after the move, of a point that adjustRig() adjusts.
  struct vpTrackedImage {
    unsigned int point; //!< Index of the point in adjustRig()'s \e points.
    unsigned int frame; //!< Index of the frame in adjustRig()'s \e frames.
    Eigen::Vector4d s;  //!< Its image \f$ (u, v, u', v') \f$, pixels.
  };

  /*!
    Bundle adjustment of a re-registered rig (FIXED_INTRINSICS) together with points whose place is known only from
    images: a servo task's features, at the zero reference \f$ M_i \f$ (4x1, model frame, never divided by the last
    coordinate: unit norm, Ceres' sphere manifold). Minimised over the moved cameras' rigid motions (those of \e rig
    against \e before: a camera that did not move stays, a whole rig moved keeps one motion) and the points:
    \f[ \sum_k \| \pi'(X_k) - s_k \|^2 + \sum_{(i, k)} \| \pi'(H_k M_i) - s_{ik} \|^2
        + \sum_i w_i \| \pi(H_0 M_i) - \pi(H_0 \bar M_i) \|^2, \f]
    \f$ \pi' \f$ the moved rig's stereo image, \f$ \pi \f$ the rig's before the move (pixels, both cameras). The first
    sum: the points known without error of their own (the markers moved by \f$ H(q_k) \f$ at the observation poses);
    the second: the tracked images after the move, at frames of displacement \f$ H_k \f$; the third: the images
    before the move, summed up by the mean \f$ \bar M_i \f$ of the points triangulated from \f$ w_i \f$ stereo
    pairs through the rig before the move near the displacement \f$ H_0 \f$ (the reprojection errors of those pairs
    to first order). Those pairs' noise is what a rig fitted to \f$ \bar M_i \f$ held fixed takes in as an error
    common to the points; the frames after the move, at other displacements, tell it apart from a camera motion.
    \param before : the rig before the move.
    \param rig : the re-registered rig (registerRig(), FIXED_INTRINSICS): which cameras moved, and the start.
    \param G : the model's projective-to-metric matrix (4x4, invertible).
    \param fixedPoints, fixedImages : known points (4x1, model frame) and their images after the move, same order.
    \param H0 : where the points' priors were seen (4x4, the displacement of the last frames before the move).
    \param weights : per point, the number of stereo pairs its prior was triangulated from (> 0).
    \param frames : the displacements \f$ H_k \f$ of the frames after the move (4x4 each).
    \param images : the points' images in those frames.
    \param points : in: the priors \f$ \bar M_i \f$ (the start); out: the adjusted points (unit norm).
    \return the adjusted rig; its RMS error per coordinate (pixels) over the images after the move in \e rms.
    \exception vpProjectiveException (dimensionError) on sizes that disagree or an index out of range;
    (nonFiniteValueError) on a non-finite input, a zero point or a weight that is not positive;
    (estimationFailedError) if the adjustment gives no finite rig. \e points is then unchanged.
  */
  static vpProjectiveStereoRig adjustRig(const vpProjectiveStereoRig &before, const vpProjectiveStereoRig &rig,
                                         const Eigen::Matrix4d &G, const std::vector<Eigen::Vector4d> &fixedPoints,
                                         const std::vector<Eigen::Vector4d> &fixedImages, const Eigen::Matrix4d &H0,
                                         const std::vector<double> &weights, const std::vector<Eigen::Matrix4d> &frames,
                                         const std::vector<vpTrackedImage> &images,
                                         std::vector<Eigen::Vector4d> &points, double *rms = nullptr);
};

END_VISP_NAMESPACE

#endif
