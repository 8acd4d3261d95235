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
    a turn). With \e seen (not null: the pixels at which \e points were seen at \e q0, see solveWithPoints()) each
    minimum is then refined with the points by both views, and a branch's residual is that of both views: at most 1.5
    times the best one plus 0.01 px (the branches of one pose tie; another pose that few points nearly explain leaves
    more). Without it the points are taken as exact, and a branch's residual is at most the larger of 1 px and twice
    the best one (a wrong local minimum leaves the pixels far off). Returns the branches sorted by residual (the best
    first), their residuals in \e residuals if not null; none if no start converged. \e extraStarts (if not null)
    are more starts, tried after \e q0 and before the random ones: configurations the caller expects near a branch
    (vpProjectivePathPlanner passes the end of the inverse kinematics tracked along straight image lines from
    \e q0 to \e s, the branch that the motion from \e q0 meets first, which uniform starts in a wide box can miss).
    \exception vpProjectiveException (dimensionError) if \e seen is not null and not of the size of \e points, or an
    extra start not of the size of \e q0.
  */
  static std::vector<vpProjectiveArmModel::JointVector>
  solveAll(const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
           const std::vector<Eigen::Vector4d> &points, const vpProjectiveArmModel::JointVector &q0,
           const vpProjectiveArmModel::JointVector &qmin, const vpProjectiveArmModel::JointVector &qmax,
           unsigned int starts, std::vector<double> *residuals = nullptr,
           const std::vector<Eigen::Vector4d> *seen = nullptr,
           const std::vector<vpProjectiveArmModel::JointVector> *extraStarts = nullptr);
  /*!
    The target's joint values and the points together, from two views: minimises
    \f[ \sum_k \| s_k - \pi(H(q) M_k) \|^2 + \sum_{k\ free} \| s^0_k - \pi(H(q_0) M_k) \|^2 \f]
    over \f$ q \f$ (n x 1) and the free points \f$ M_k \f$ (4x1 at the zero reference, each on its unit sphere),
    where \e seen holds the pixels \f$ s^0_k \f$ at which \e points were seen at \e q0 (the features they were
    triangulated from) and \e s the pixels wanted at \f$ q \f$. A point whose seen pixels are not finite is exact
    (e.g. a marker of the model's bundle adjustment) and stays fixed. The points triangulated at \e q0 alone carry
    the depth error of the stereo pair into the prediction at \f$ q \f$ when the motion turns it sideways; refined
    with both views, the residual of the true target falls to the image noise. Levenberg-Marquardt from \e q and
    \e points (replaced by the refined ones), on the dense normal equations (n + 3 unknowns per free point).
    \param model : the arm's model.
    \param s : pixels \f$ (u, v, u', v') \f$ wanted at \f$ q \f$, one per point.
    \param seen : pixels at which the points were seen at \e q0, one per point (not finite: the point is exact).
    \param q0 : the joint values (n x 1) where the points were seen.
    \param q : the starting joint values of the target (n x 1), e.g. a minimum of solve().
    \param points : the points (4x1, zero reference) in, the refined ones (unit norm) out.
    \param residual : if not null, receives the RMS pixel error per coordinate over both views (4 per desired pixel
    and 4 per free point's seen pixel).
    \exception vpProjectiveException (dimensionError) if \e s, \e seen and \e points differ in size or the joint
    vectors are not n x 1; (nonFiniteValueError) on a non-finite desired pixel, point or joint value;
    (estimationFailedError) if a point lies on a camera's focal plane at the start. \e points is left unchanged when
    it throws.
  */
  static vpProjectiveArmModel::JointVector
  solveWithPoints(const vpProjectiveArmModel &model, const std::vector<Eigen::Vector4d> &s,
                  const std::vector<Eigen::Vector4d> &seen, const vpProjectiveArmModel::JointVector &q0,
                  const vpProjectiveArmModel::JointVector &q, std::vector<Eigen::Vector4d> &points,
                  double *residual = nullptr);
};

END_VISP_NAMESPACE

#endif
