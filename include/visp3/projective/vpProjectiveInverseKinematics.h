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
};

END_VISP_NAMESPACE

#endif
