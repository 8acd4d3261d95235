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
  \file vpProjectiveStereoRig.h
  \brief Weakly calibrated stereo rig: fundamental matrix, canonical camera pair, projective triangulation.
*/

#ifndef _vpProjectiveStereoRig_h_
#define _vpProjectiveStereoRig_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveStereoRig
  \ingroup group_projective
  \brief A stereo rig known only through its epipolar geometry (Ruf & Horaud, ICCV'99, section 2).

  Pixels are \f$ m = (u, v, 1)^T \f$ in the left image and \f$ m' = (u', v', 1)^T \f$ in the right one, with
  \f$ u \f$ = vpImagePoint::get_u() (column) and \f$ v \f$ = vpImagePoint::get_v() (row). The fundamental matrix
  \f$ F \f$ (3x3) satisfies \f$ m'^T F m = 0 \f$.

  \f$ F \f$ fixes one projective frame \f$ \mathcal{P} \f$ through the canonical camera pair (3)
  \f[ P = [I \,|\, 0], \qquad P' = [\, [e']_\times F + e' a^T \,|\, e' \,] \f]
  with \f$ F \f$ scaled to unit Frobenius norm, the right epipole \f$ e' \f$ (\f$ e'^T F = 0 \f$) of unit norm, both
  with their largest-magnitude entry positive, and \f$ a = e' \f$, which keeps the left 3x3 block of \f$ P' \f$
  invertible. Any \f$ F \f$ proportional to another gives the same frame, so models acquired with this rig stay valid.

  A projective point \f$ M \f$ is a homogeneous 4-vector of unit norm with \f$ m \simeq P M \f$, \f$ m' \simeq P' M
  \f$. Its last coordinate may be zero inside the workspace: it is never divided by.

  Each value has one name with two forms, ViSP's idiom: getFundamentalMatrix(), getLeftProjection() and
  getRightProjection() return a vpMatrix, and their overloads with an output argument write the fixed-size Eigen
  matrix (no allocation) for hot paths, e.g. \c Eigen::Matrix3d \c F; \c rig.getFundamentalMatrix(F);.

  \code
  vpProjectiveStereoRig rig;
  rig.estimate(left, right);                      // >= 8 matches: RANSAC, then Ceres on the geometric error
  vpColVector M = rig.triangulate(ipLeft, ipRight); // 4x1, unit norm
  vpImagePoint l, r;
  rig.project(M, l, r);
  \endcode
*/
class VISP_EXPORT vpProjectiveStereoRig
{
public:
  //! A 3x4 camera matrix.
  typedef Eigen::Matrix<double, 3, 4> Projection;

  vpProjectiveStereoRig();

  /*!
    Estimates \f$ F \f$ from pixel matches: OpenCV's RANSAC on Hartley-normalised points selects the inliers (from 15
    matches), linear refits on the consensus set are kept while they lower the truncated quadratic cost
    \f$ \sum_i \min(d_i^2, t^2) \f$ over all matches (\f$ d_i \f$ the epipolar distance below, t the threshold),
    then Ceres minimises the geometric (Sampson-free, gold standard) reprojection error of the inliers over \f$ F \f$
    and their projective points, repeated on the inliers of the refined geometry until they are the matches it was
    fitted to. Needs at least 8 matches in general position.

    Wrong pairings within the threshold of their true epipolar line cannot be told from correct ones (measured
    robustness: page \ref page_estimation_accuracy).
    Below 15 matches there is no robust selection (OpenCV's RANSAC needs 15, and F's 7 degrees of freedom leave
    little redundancy): all the matches are fitted, those beyond the threshold of the refined geometry dropped and
    the rest refitted: one wrong match among fewer than 15 may be absorbed by F without a trace in
    getEstimationResidual(): use 15 matches or more when wrong ones are possible.
    \param left, right : matched image points, left[i] seen as right[i].
    \param inlierThreshold : maximum distance in pixels of an inlier to its epipolar lines (the larger of the two
    images' distances). The default, 2 px, keeps about 99 % of the correct matches at 0.5 px Gaussian noise per
    coordinate (the distance to the line then has a standard deviation of about 0.7 px); raise it in proportion to
    the noise.
    \exception vpProjectiveException when there are fewer than 8 matches, the sizes differ, a coordinate or the
    threshold is not finite, the threshold is not positive, the matches are degenerate (for instance all on one line),
    or fewer than 8 of them agree with one epipolar geometry (estimationFailedError).
  */
  void estimate(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                double inlierThreshold = 2.0);

  /*!
    Sets \f$ F \f$ (3x3, rank 2, pixel coordinates, \f$ m'^T F m = 0 \f$) and the frame it defines. A rank-3 input is
    projected on the closest rank-2 matrix.
  */
  void setFundamentalMatrix(const vpMatrix &F);

  /*!
    Sets a general camera pair \f$ P \f$, \f$ P' \f$ (3x4 each, rank 3, any non-zero scale), as left by a
    re-registration of the cameras in a model's projective frame (vpProjectiveRigRegistration): the frame is then that
    of the model, no longer the canonical frame of \f$ F \f$. With \f$ C \f$, \f$ C' \f$ the camera centres
    (\f$ P C = 0 \f$, \f$ P' C' = 0 \f$), the epipoles are \f$ e = P C' \f$, \f$ e' = P' C \f$ and
    \f$ F = [e']_\times P' P^+ \f$ (then unit Frobenius norm and canonical sign, as setFundamentalMatrix()).
    Triangulation and projection use \f$ P \f$ and \f$ P' \f$ as given (scaled to unit Frobenius norm).
    \exception vpProjectiveException (dimensionError, nonFiniteValueError) on a wrong size or a non-finite entry;
    (degenerateConfigurationError) if a matrix has rank below 3 or both centres coincide (no baseline). Nothing is
    changed then.
  */
  void setProjections(const vpMatrix &P, const vpMatrix &Pp);
  //! The same with Eigen types (see the other overload).
  void setProjections(const Projection &P, const Projection &Pp);
  /*!
    True if the pair is the canonical pair of \f$ F \f$ (estimate(), setFundamentalMatrix()); false after
    setProjections().
  */
  bool isCanonical() const { return m_canonical; }

  /*! \name Fundamental matrix and cameras
    One name per value, in two forms as in ViSP (vpHomogeneousMatrix getPose() beside void getPose(cMo)): the ViSP
    type returned, and an overload writing the Eigen type into its argument (fixed size: no allocation, for hot
    paths). Both are copies of the same stored values.
  */
  //@{
  /*!
    \f$ F \f$ of unit Frobenius norm (3x3, pixel coordinates, \f$ m'^T F m = 0 \f$).
    \exception vpProjectiveException if the rig has no \f$ F \f$ yet.
  */
  vpMatrix getFundamentalMatrix() const;
  /*!
    \overload
    Writes \f$ F \f$ (3x3, unit Frobenius norm) into \e F. Unchecked (hot path): zero before the rig is
    initialized.
  */
  void getFundamentalMatrix(Eigen::Matrix3d &F) const { F = m_F; }
  /*!
    \f$ P \f$ (3x4, from the rig's projective frame to homogeneous left pixels): \f$ [I | 0] \f$ for the canonical
    pair, else the one of setProjections() (unit Frobenius norm).
    \exception vpProjectiveException if the rig has no \f$ F \f$ yet.
  */
  vpMatrix getLeftProjection() const;
  /*!
    \overload
    Writes \f$ P \f$ (3x4, projective frame to left pixels) into \e P. Unchecked (hot path): zero before the rig is
    initialized.
  */
  void getLeftProjection(Projection &P) const { P = m_P; }
  /*!
    \f$ P' \f$ (3x4, from the rig's projective frame to homogeneous right pixels):
    \f$ [[e']_\times F + e' e'^T | e'] \f$ for the canonical pair, else that of setProjections() (unit Frobenius norm).
    \exception vpProjectiveException if the rig has no \f$ F \f$ yet.
  */
  vpMatrix getRightProjection() const;
  /*!
    \overload
    Writes \f$ P' \f$ (3x4, projective frame to right pixels) into \e Pp. Unchecked (hot path): zero before the rig
    is initialized.
  */
  void getRightProjection(Projection &Pp) const { Pp = m_Pp; }
  //@}
  //! Left epipole \f$ e \f$, \f$ F e = 0 \f$, unit norm (3x1, homogeneous pixels).
  vpColVector getLeftEpipole() const;
  //! Right epipole \f$ e' \f$, \f$ e'^T F = 0 \f$, unit norm (3x1, homogeneous pixels).
  vpColVector getRightEpipole() const;

  //! Inliers kept by the last estimate(): inliers[i] tells whether match i was used.
  const std::vector<bool> &getInliers() const { return m_inliers; }
  //! RMS distance in pixels of the inliers to their refined reprojections after estimate().
  double getEstimationResidual() const { return m_residual; }

  /*!
    Projective reconstruction of one match, eq. (3): linear (DLT on conditioned equations), then refined by
    Gauss-Newton on the reprojection error in both images.
    \return \f$ M \f$ (4x1), unit norm.
    \exception vpProjectiveException if the rig has no \f$ F \f$ or a coordinate is not finite.
  */
  vpColVector triangulate(const vpImagePoint &ipLeft, const vpImagePoint &ipRight) const;
  /*!
    Projective reconstruction of matches, eq. (3): triangulate(ipLeft[i], ipRight[i]) for every i.
    \return the points \f$ M_i \f$ (4x1 each, unit norm), in the order of the matches.
    \exception vpProjectiveException if the rig has no \f$ F \f$, the lists differ in size, or a coordinate is not
    finite.
  */
  std::vector<vpColVector> triangulate(const std::vector<vpImagePoint> &ipLeft,
                                       const std::vector<vpImagePoint> &ipRight) const;

  /*!
    Projects \f$ M \f$ (4x1, any scale and sign) into both images: \f$ m \simeq P M \f$, \f$ m' \simeq P' M \f$.
    \exception vpProjectiveException if \f$ M \f$ is not 4x1 or not finite, or lies on a camera's focal plane.
  */
  void project(const vpColVector &M, vpImagePoint &ipLeft, vpImagePoint &ipRight) const;

  //! True once \f$ F \f$ is known (estimate() or setFundamentalMatrix()).
  bool isInitialized() const { return m_initialized; }

  /*! \name Eigen access for hot paths (no allocation) */
  //@{
  /*!
    Triangulates \f$ (u, v) \f$, \f$ (u', v') \f$ into the unit-norm 4-vector \f$ M \f$ (linear, then Gauss-Newton).
  */
  Eigen::Vector4d triangulate(const Eigen::Vector2d &left, const Eigen::Vector2d &right) const;
  /*!
    Linear triangulation only (no refinement): accurate enough where \f$ M \f$ only serves to evaluate a Jacobian,
    and several times cheaper.
  */
  Eigen::Vector4d triangulateLinear(const Eigen::Vector2d &left, const Eigen::Vector2d &right) const;
  /*!
    Writes \f$ s = (u, v, u', v') \f$ (pixels) of \f$ M \f$ (4x1, any scale and sign) and, if \e L is not null,
    \f$ L = \partial s / \partial M \f$ (4x4): the rows \f$ J_C(P M) P \f$ and \f$ J_C(P' M) P' \f$ of eq. (45) (the
    interaction matrix of vpFeatureStereoPoint). Returns false when \f$ M \f$ is on a camera's focal plane: its
    depth \f$ |P_3 M| \f$ is at most \f$ 10^{-12} \|P\|_F \|M\| \f$ (likewise for \f$ P' \f$), the one tolerance
    of the plugin.
  */
  bool project(const Eigen::Vector4d &M, Eigen::Vector4d &s, Eigen::Matrix4d *L = nullptr) const;
  //@}

private:
  void checkInitialized(const char *where) const;
  void updateFocalPlaneBounds();

  Eigen::Matrix3d m_F;
  Projection m_P;
  Projection m_Pp;
  double m_bound2P, m_bound2Pp; // the focal-plane bounds of P and P' squared, for project() (constants of the cameras)
  Eigen::Vector3d m_e;
  Eigen::Vector3d m_ep;
  std::vector<bool> m_inliers;
  double m_residual;
  bool m_initialized;
  bool m_canonical;
};

END_VISP_NAMESPACE

#endif
