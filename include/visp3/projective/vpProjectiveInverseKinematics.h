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
  \file vpProjectiveInverseKinematics.h
  \brief Inverse kinematics of a projective arm model: the joint values that explain observed marker images.
*/

#ifndef _vpProjectiveInverseKinematics_h_
#define _vpProjectiveInverseKinematics_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveInverseKinematics
  \ingroup group_projective
  \brief Inverse kinematics on a vpProjectiveArmModel (the paper's motion-capture use): the joint values \f$ q \f$
  (n x 1, encoder readings) that minimise the pixel error
  \f[ \sum_k \| s_k - \pi(H(q) M_{j_k}(0)) \|^2 \f]
  of observed markers \f$ j_k \f$ with pixels \f$ s_k = (u, v, u', v') \f$, \f$ \pi \f$ the projection by the rig's
  \f$ P, P' \f$, \f$ H(q) \f$ the displacement (34). The residuals' Jacobian is the stereo image Jacobian (46) of each
  predicted marker. Each marker gives 4 equations but constrains at most 3 degrees of freedom of the chain.
*/
class VISP_EXPORT vpProjectiveInverseKinematics
{
public:
  /*!
    Minimises the pixel error by Levenberg-Marquardt from \e q0 (at most 100 iterations), on the normal equations
    accumulated marker by marker: nothing is allocated, so that motion capture can call it at every frame, warm-started
    at the previous frame's joint values (a few microseconds per iteration for 6 joints and 7 markers).
    \param model : the arm's model.
    \param s : pixels \f$ (u, v, u', v') \f$ of the observed markers (finite: unchecked).
    \param indices : index of each observed marker among the model's markers (same size as \e s, valid: unchecked).
    \param q0 : starting joint values (n x 1).
    \param residual : if not null, receives the final RMS pixel error per coordinate.
    \return the joint values (n x 1).
    \exception vpProjectiveException (estimationFailedError) if a marker is on a camera's focal plane at \e q0 or the
    minimisation gives no finite solution.
  */
  static vpProjectiveArmModel::JointVector solve(const vpProjectiveArmModel &model,
                                                 const std::vector<Eigen::Vector4d> &s,
                                                 const std::vector<unsigned int> &indices,
                                                 const vpProjectiveArmModel::JointVector &q0,
                                                 double *residual = nullptr);
  /*!
    The same for any points \e points of the moving end (4x1 projective points at the zero reference, such as a servo
    task's features carried there by \f$ H(q)^{-1} \f$), \e s[k] the observed pixels of points[k]; with a \e prior
    (n x 1, not null) the cost gains \f$ w^2 \| q - q_p \|^2 \f$ (\e priorWeight \f$ w \f$ in pixels per joint unit),
    which settles the joints the pixels leave free (fewer than 3 points, a singular configuration) and keeps a
    tracked path from jumping there. \e residual is that of the pixels alone.
  */
  static vpProjectiveArmModel::JointVector
  solve(const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
        const std::vector<Eigen::Vector4d> &points, const vpProjectiveArmModel::JointVector &q0,
        double *residual = nullptr, const vpProjectiveArmModel::JointVector *prior = nullptr, double priorWeight = 0.0);
  /*!
    Every branch of the inverse kinematics it can find (multi-start): the minimisation of solve() from \e q0 and from
    \e starts configurations drawn uniformly between \e qmin and \e qmax (n x 1 each, with a fixed seed: equal
    inputs give equal outputs). Two minima are one branch when every joint agrees within 1e-3 (revolute joints modulo
    a turn). A branch explains the pixels: its RMS residual per coordinate is at most the larger of 1 px and twice the
    best one found (a wrong local minimum leaves them far off). Returns the branches sorted by residual (the best
    first), their residuals in \e residuals if not null; none if no start converged.
  */
  static std::vector<vpProjectiveArmModel::JointVector>
  solveAll(const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
           const std::vector<Eigen::Vector4d> &points, const vpProjectiveArmModel::JointVector &q0,
           const vpProjectiveArmModel::JointVector &qmin, const vpProjectiveArmModel::JointVector &qmax,
           unsigned int starts, std::vector<double> *residuals = nullptr);
};

END_VISP_NAMESPACE

#endif
