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
  \file vpProjectiveDisplacement.h
  \brief Projective displacements: rigid motions seen in the projective frame of a weakly calibrated rig.
*/

#ifndef _vpProjectiveDisplacement_h_
#define _vpProjectiveDisplacement_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>

BEGIN_VISP_NAMESPACE

class vpProjectiveStereoRig;
template <typename Derived> class vpProjectiveJointSubgroup;

/*!
  \class vpProjectiveDisplacement
  \ingroup group_projective
  \brief A p-displacement \f$ H \in PSE(3) \f$: the 4x4 homography of \f$ \mathbb{P}^3 \f$ by which the projective
  points of a rigid body move (Ruf & Horaud, section 4.1).

  Points on a rigid body move as \f$ M(t) \simeq H\, M(0) \f$ (10), and \f$ H = H_{PE}^{-1}\, T\, H_{PE} \f$ (11)
  with \f$ T \in SE(3) \f$ the metric displacement and \f$ H_{PE} \f$ (4x4) the unknown projective-to-Euclidean link
  of the rig. The matrix is kept normalised by eq. (12):
  \f[ H \leftarrow H / \gamma, \qquad \gamma = \mathrm{sign}(\mathrm{trace}\, H)\, |\det H|^{1/4}, \f]
  so that it equals \f$ H_{PE}^{-1} T H_{PE} \f$ exactly, not only up to scale.

  The eigenvalues of \f$ H \f$ are those of \f$ T \f$: \f$ e^{\pm i\theta}, 1, 1 \f$. Hence
  \f$ \cos\theta = (\mathrm{trace}\, H - 2)/2 \f$ (21), and the rank of \f$ H - I \f$ classifies the motion:
  0 identity, 1 translation, 2 rotation about a fixed axis, 3 general screw motion.

  The matrix is matrix(), an Eigen matrix, as Sophus and manif give their groups' (one name per getter). A ViSP
  program that wants a vpMatrix converts it with ViSP's \c visp3/core/vpEigenConversion.h:
  <tt>vpMatrix M; vp::eigen2visp(Eigen::MatrixXd(H.matrix()), M);</tt> (namespace \c vp in ViSP 3.5 and 3.6,
  \c visp from ViSP 3.7).
*/
class VISP_EXPORT vpProjectiveDisplacement
{
public:
  //! Kind of rigid motion, read off the rank of \f$ H - I \f$.
  enum vpMotionType {
    IDENTITY,    //!< \f$ H = I \f$.
    TRANSLATION, //!< Pure translation, rank\f$(H - I) = 1\f$, \f$ (H - I)^2 = 0 \f$.
    ROTATION,    //!< Rotation about a fixed axis, rank\f$(H - I) = 2\f$.
    GENERAL      //!< Screw motion, rank\f$(H - I) = 3\f$.
  };

  //! Identity displacement.
  vpProjectiveDisplacement();
  /*!
    Wraps a 4x4 homography and normalises it with eq. (12).
    \exception vpProjectiveException if H is not 4x4, not finite or singular.
  */
  explicit vpProjectiveDisplacement(const vpMatrix &H);
  //! \overload
  explicit vpProjectiveDisplacement(const Eigen::Matrix4d &H);

  /*!
    Estimates \f$ H \f$ with \f$ M_1^{(j)} \simeq H M_0^{(j)} \f$ from at least 5 pairs of projective points (4x1) in
    general position (no 4 coplanar): the direct linear transform on whitened points (no division by a last
    coordinate), then eq. (12).
    \exception vpProjectiveException on fewer than 5 pairs, a size mismatch, a non-finite value, or a degenerate
    configuration (4 coplanar points among 5, all points coplanar, repeated points).
  */
  static vpProjectiveDisplacement estimate(const std::vector<vpColVector> &M0, const std::vector<vpColVector> &M1);

  /*!
    Estimates \f$ H \f$ from the images of at least 5 rigid points before and after the motion, seen by a weakly
    calibrated rig: triangulation, linear estimate, then minimisation of the reprojection error of all four point
    sets over \f$ H \f$ and the points \f$ M_0^{(j)} \f$ (the maximum-likelihood estimate under Gaussian pixel
    noise), by the plugin's one Levenberg-Marquardt for this cost (see estimateFromImages()).
    \exception vpProjectiveException as for the other overload, or if the rig has no fundamental matrix.
  */
  static vpProjectiveDisplacement estimate(const vpProjectiveStereoRig &rig, const std::vector<vpImagePoint> &left0,
                                           const std::vector<vpImagePoint> &right0,
                                           const std::vector<vpImagePoint> &left1,
                                           const std::vector<vpImagePoint> &right1);

  /*!
    The maximum-likelihood estimate of the image overload on Eigen types: \e s0[j] and \e s1[j] are the pixels
    \f$ (u, v, u', v') \f$ of point j before and after the motion (same sizes, at least 5, finite: unchecked). Returns
    the normalised matrix (12). \e maxIterations caps the Levenberg-Marquardt iterations (a starting point for a
    larger adjustment needs few). The minimisation works in frames whitened by each point set, with \f$ H \f$ (16
    entries) and each point (4) on its unit sphere, and eliminates the points by the Schur complement of the normal
    equations; if it cannot lower the cost, the linear estimate is returned.
  */
  static Eigen::Matrix4d estimateFromImages(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                                            const std::vector<Eigen::Vector4d> &s1, int maxIterations = 100);
  //! Linear (DLT) estimate on Eigen types; same checks as estimate().
  static Eigen::Matrix4d estimateLinear(const std::vector<Eigen::Vector4d> &M0, const std::vector<Eigen::Vector4d> &M1);

  /*! \name Robust estimation (mismatched correspondences)
    A mismatched marker (a wrong blob tracked after the motion, two markers swapped) moves by no common H and drags the
    least-squares estimates arbitrarily far. The robust estimates below hypothesise H from minimal sets of 5 points
    (eq. (10) gives 3 constraints per point, H has 15 degrees of freedom), keep the hypothesis that the most points
    agree with, and refit it on those points only by the maximum-likelihood estimate of estimateFromImages() (the
    same cost and the same Levenberg-Marquardt).

    <b>Error of a point.</b> Both observations of point j are noisy: \f$ s_0 = (u, v, u', v') \f$ before and
    \f$ s_1 \f$ after the motion. Its error under a candidate \f$ H \f$ is its gold-standard reprojection error
    \f[ d_j(H) = \min_{M} \sqrt{\tfrac{1}{4}\left( \|\pi(P M) - m_0\|^2 + \|\pi(P' M) - m'_0\|^2 +
         \|\pi(P H M) - m_1\|^2 + \|\pi(P' H M) - m'_1\|^2 \right)}, \f]
    the RMS distance in pixels over the four images between the observed pixels and those of the rigid point that
    fits them best (the residual that estimateFromImages() minimises, per point). Transferring the triangulated
    \f$ M_0 \f$ by \f$ H \f$ and comparing with \f$ s_1 \f$ alone would charge the noise of \f$ s_0 \f$,
    amplified by the triangulation, to \f$ s_1 \f$, and would not be symmetric in the two views; \f$ d_j \f$
    is symmetric (\f$ d_j(H) \f$ with the views exchanged is \f$ d_j(H^{-1}) \f$) and also catches a point whose
    left and right images do not match. It is evaluated by two Gauss-Newton steps from the triangulated
    \f$ M_0 \f$. For the true H and Gaussian noise \f$ \sigma \f$ per coordinate, \f$ 4 d_j^2 / \sigma^2 \f$ is
    chi-square with 5 degrees of freedom (8 measurements, 3 for the point): mean \f$ d_j \approx 1.06\,\sigma \f$,
    and \f$ d_j > 2\,\sigma \f$ (\f$ 3\,\sigma \f$) for 0.7 % (1e-6) of the correct points; a mismatch that
    moves both image points after the motion by D pixels gives \f$ d_j \approx D / 2 \f$ (the best-fitting point
    splits the discrepancy between the views). A threshold t of \f$ 3\,\sigma \f$ is a good default. A point that
    the candidate puts behind the cameras (its images reached through infinity) has an infinite error: with
    \f$ H = \lambda H_{PE}^{-1} T H_{PE} \f$ the depths \f$ (P M)_3 \f$ and \f$ (P H M)_3 \f$ (likewise with
    \f$ P' \f$) have the sign of \f$ \lambda \f$ for every point in front of the rig.

    <b>Hypotheses.</b> When \f$ \binom{n}{5} \f$ does not exceed \e maxIterations (n <= 8 at the default 100;
    7 markers give 21 sets), every 5-point subset is tried, in a fixed order; otherwise \e maxIterations subsets
    are drawn by a generator with a fixed seed (so equal inputs give equal outputs), stopping early once a set free
    of mismatches has been drawn with probability 0.9999 given the best support so far. Subsets with 4 coplanar
    points (or repeated ones) among their 5 in either view are skipped, as are those whose homography reverses
    orientation (\f$ \det H = \det T > 0 \f$ for a displacement, eq. (11)). A 5-point fit amplifies the noise (on
    a 20 cm object 1 m away it may predict the other markers 10 to 100 px off), so each promising hypothesis is
    locally optimised (LO-RANSAC, Chum, Matas and Kittler 2003): refitted by maximum likelihood on the points within
    4 t of it (at least the 6 it predicts best), then on those within t of that fit, until stable. Hypotheses are
    ranked by the truncated quadratic cost \f$ \sum_j \min(d_j^2, t^2) \f$ (MSAC: the support, then the accuracy).

    <b>Rigidity.</b> With few points a homography may fit a mismatched set within the threshold by distorting
    space. The characteristic polynomial of a displacement normalised by (12) is
    \f$ (x - 1)^2 (x^2 - 2 x \cos\theta + 1) \f$ for every rotation, screw or translation, so its coefficients
    satisfy \f$ e_3 = e_1 \f$ and \f$ e_2 = 2 e_1 - 2 \f$; a fit whose deviation from these exceeds 8 times its
    spread under the noise (sampled from the covariance of the fit) is rejected.

    <b>Failure.</b> Any 5 points in general position are fitted exactly by a 3D homography, so 5 agreeing points
    prove nothing: with n >= 6 points a displacement must be supported by at least 6 (a point beyond its minimal set
    confirms it). estimationFailedError is thrown when fewer points agree, when the best fit is no rigid
    displacement, or when two different sets of as many points each agree with a rigid displacement, not with one
    another, and neither fits 1000 times more likely (the data are ambiguous). Use 7 points or more: with 6 points of
    which 1 is mismatched, some configurations admit a rigid-looking fit of all 6 (only 3 constraints are redundant).
    With exactly n = 5 points no mismatch between the views can be detected, only a point whose left and right images
    disagree. The measured rates are on the page \ref page_estimation_accuracy.

    <b>Point-set version.</b> There is no robust overload of estimate(M0, M1): an inlier threshold needs a distance,
    and distances between projective points depend on the arbitrary projective frame fixed by F (any
    \f$ G \in PGL(4) \f$ is as valid a frame as the identity); the meaningful distances are the pixel distances in
    the images, which need the rig, hence the image overloads below.
  */
  //@{
  /*!
    Robust estimate from images: minimal 5-point sets, inliers within inlierThreshold pixels, ML refit on the
    inliers (see estimateRobust() for the criterion).
    \param rig : the weakly calibrated rig.
    \param left0, right0, left1, right1 : images of the points before (0) and after (1) the motion, same sizes,
    at least 5.
    \param inlierThreshold : largest error \f$ d_j \f$ (pixels, RMS over the four images) of an inlier, e.g.
    \f$ 3\,\sigma \f$ (1.5 px at 0.5 px noise).
    \param inliers : resized to the number of points; inliers[j] tells whether point j was used.
    \exception vpProjectiveException: notInitializedError (rig without F), dimensionError (sizes differ),
    notEnoughPointsError (fewer than 5 points), nonFiniteValueError (a coordinate or the threshold),
    invalidValueError (threshold <= 0), degenerateConfigurationError (no 5 points in general position),
    estimationFailedError (too many mismatches: see above).
  */
  static vpProjectiveDisplacement estimate(const vpProjectiveStereoRig &rig, const std::vector<vpImagePoint> &left0,
                                           const std::vector<vpImagePoint> &right0,
                                           const std::vector<vpImagePoint> &left1,
                                           const std::vector<vpImagePoint> &right1, double inlierThreshold,
                                           std::vector<bool> &inliers);

  /*!
    The same on Eigen types: \e s0[j] and \e s1[j] are the pixels \f$ (u, v, u', v') \f$ of point j before and after
    the motion. Returns the normalised \f$ H \f$ (12), fills \e inliers (the points within \e inlierThreshold of
    the returned H, which it was fitted to). \e maxIterations is the number of 5-point subsets drawn at most when
    they are not all enumerated (see above); the ML refit runs at most 100 Levenberg-Marquardt iterations. Allocates;
    (timings: benchmark program tests/benchmark/benchmarkServo, page \ref page_estimation_accuracy).
    \exception vpProjectiveException as the vpImagePoint overload, and invalidValueError if maxIterations < 1;
    estimationFailedError when fewer than 6 points (5 when n = 5) agree with one rigid displacement (see above).
  */
  static Eigen::Matrix4d estimateRobust(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                                        const std::vector<Eigen::Vector4d> &s1, double inlierThreshold,
                                        std::vector<bool> &inliers, int maxIterations = 100);
  //@}

  /*!
    Normalisation of eq. (12): \f$ H / (\mathrm{sign}(\mathrm{trace} H) |\det H|^{1/4}) \f$.
    \exception vpProjectiveException if H is singular or not finite.
  */
  static Eigen::Matrix4d normalize(const Eigen::Matrix4d &H);

  //! The normalised 4x4 matrix (no allocation); as a vpMatrix: see the class description.
  const Eigen::Matrix4d &matrix() const { return m_H; }

  //! Rotation angle \f$ \theta \in [0, \pi] \f$ of eq. (21), \f$ \cos\theta = (\mathrm{trace} H - 2)/2 \f$, clamped.
  double getRotationAngle() const;

  /*!
    Classifies the motion by the numerical rank of \f$ H - I \f$: a singular value \f$ \sigma_k \f$ counts when
    \f$ \sigma_k > \mathrm{tolerance} \cdot \max(1, \sigma_1) \f$. With noisy estimates, pass a tolerance above the
    noise level of \f$ H \f$.
  */
  vpMotionType classify(double tolerance = 1e-6) const;

  /*! \name Group operations
    One API with vpProjectiveRotation and vpProjectiveTranslation, one name per operation (\ref page_groups): the
    kernels exp(Hhat, q) and act(Hhat, q, M) (static, Eigen, templated on the scalar), log(H, amount), and for the
    element inverse(), operator*() (compose) and act(M).
  */
  //@{
  /*!
    Principal logarithm \f$ \hat H \in pse(3) \f$ (4x4) of any p-displacement (rotation, translation, screw,
    identity): \f$ \exp(\hat H) = H \f$ and, for \f$ H = H_{PE}^{-1} T H_{PE} \f$, \f$ \hat H = H_{PE}^{-1} \log(T)
    H_{PE} \f$ with \f$ \log(T) \in se(3) \f$ of rotation angle \f$ \theta \in [0, \pi) \f$ (eq. (21)). Since the
    minimal polynomial of \f$ D = H - I \f$ divides \f$ x^2 (x^2 - 2 (\cos\theta - 1) x + 2 - 2 \cos\theta) \f$, the
    logarithm is the cubic
    \f[ \hat H = D + b_2 D^2 + b_3 D^3, \qquad
        b_2 = 1 - \frac{\theta}{2} \left( \cot\frac{\theta}{2} + \cot\theta \right), \qquad
        b_3 = \frac{\sin\theta - \theta \cos\theta}{2 (1 - \cos\theta) \sin\theta}, \f]
    the Hermite interpolant of \f$ \log \f$ at the eigenvalues \f$ 1, 1, e^{\pm i\theta} \f$ (\f$ b_2 \to -1/2 \f$,
    \f$ b_3 \to 1/3 \f$ as \f$ \theta \to 0 \f$: the series of \f$ \log(I + D) \f$). A scaled or negated \f$ H \f$
    gives the same result (the matrix is kept normalised by eq. (12)). ViSP-typed form of log(H).
    \exception vpProjectiveException (degenerateConfigurationError) if the rotation angle is \f$ \pi \f$ (within
    1e-6 rad): the logarithm is not unique there.
  */
  vpMatrix log() const;
  /*!
    The generator \f$ \hat H \f$ (4x4) with \f$ H = \exp(\mathrm{amount}\, \hat H) \f$: the principal logarithm of log()
    divided by \e amount (default 1: the logarithm itself), on Eigen types, no allocation. Same signature as
    vpProjectiveRotation::log() and vpProjectiveTranslation::log().
    \exception vpProjectiveException as log(); nonFiniteValueError or invalidValueError if \e amount is not finite or
    is zero.
  */
  static Eigen::Matrix4d log(const vpProjectiveDisplacement &H, double amount = 1.0);

  /*!
    The p-displacement \f$ \exp(\hat H) \f$ of an element \e Hhat (4x4) of pse(3), such as log() gives or a body
    velocity times a duration: the kernel exp(Hhat, 1).
    \exception vpProjectiveException (nonFiniteValueError, dimensionError) if \e Hhat is not finite or not 4x4.
  */
  static vpProjectiveDisplacement exp(const vpMatrix &Hhat);
  //! \overload
  static vpProjectiveDisplacement exp(const Eigen::Matrix4d &Hhat);

  /*!
    The kernel \f$ \exp(q \hat H) \f$ (4x4) for any \e Hhat of pse(3), templated on the scalar (double or a Ceres
    Jet), unchecked: with \f$ A = q \hat H \f$ and \f$ \theta^2 = -\mathrm{trace}(A^2) / 2 \f$,
    \f[ \exp(A) = I + A + \frac{1 - \cos\theta}{\theta^2} A^2 + \frac{\theta - \sin\theta}{\theta^3} A^3, \f]
    exact for \f$ \hat H = H_{PE}^{-1} \hat T H_{PE} \f$, \f$ \hat T \in se(3) \f$ (\f$ \hat T^4 = -\theta^2 \hat T^2
    \f$); the coefficients by their series below \f$ \theta = 10^{-3} \f$.
  */
  template <typename T> static Eigen::Matrix<T, 4, 4> exp(const Eigen::Matrix<T, 4, 4> &Hhat, const T &q)
  {
    const Eigen::Matrix<T, 4, 4> A = q * Hhat;
    const Eigen::Matrix<T, 4, 4> A2 = A * A;
    T a2, a3;
    expCoefficients(T(-0.5) * A2.trace(), a2, a3);
    return Eigen::Matrix<T, 4, 4>::Identity() + A + a2 * A2 + a3 * (A2 * A);
  }
  /*!
    The kernel \f$ \exp(q \hat H) M \f$ (4x1) from the same series, with three matrix-vector products instead of
    4x4 products; templated on the scalar, unchecked.
  */
  template <typename T>
  static Eigen::Matrix<T, 4, 1> act(const Eigen::Matrix<T, 4, 4> &Hhat, const T &q, const Eigen::Matrix<T, 4, 1> &M)
  {
    const Eigen::Matrix<T, 4, 1> AM = q * (Hhat * M);
    const Eigen::Matrix<T, 4, 1> A2M = q * (Hhat * AM);
    T a2, a3;
    expCoefficients(T(-0.5) * q * q * Hhat.cwiseProduct(Hhat.transpose()).sum(), a2, a3);
    return M + AM + a2 * A2M + a3 * (q * (Hhat * A2M));
  }
  //! The point \f$ H M \f$ (4x1) moved by this displacement (no division by a last coordinate).
  Eigen::Vector4d act(const Eigen::Vector4d &M) const { return m_H * M; }
  /*!
    \overload
    \exception vpProjectiveException (dimensionError, nonFiniteValueError) if \e M is not a finite 4-vector.
  */
  vpColVector act(const vpColVector &M) const;

  //! Composition: points move by \f$ H_2 H_1 \f$ when they move by \f$ H_1 \f$, then \f$ H_2 \f$.
  vpProjectiveDisplacement operator*(const vpProjectiveDisplacement &other) const;
  //! Inverse displacement.
  vpProjectiveDisplacement inverse() const;
  //@}

private:
  template <typename Derived> friend class vpProjectiveJointSubgroup; // exp(q) of the joints' subgroups
  //! Wraps \e H, normalised by construction (an exponential): no eq. (12), which would only add rounding.
  struct vpNormalized {
  };
  vpProjectiveDisplacement(const Eigen::Matrix4d &H, vpNormalized) : m_H(H) {}

  //! \f$ (1 - \cos\theta) / \theta^2 \f$ and \f$ (\theta - \sin\theta) / \theta^3 \f$ from \f$ \theta^2 \f$ (clamped at
  //! 0)
  template <typename T> static void expCoefficients(const T &theta2In, T &a2, T &a3)
  {
    using std::cos;
    using std::sin;
    using std::sqrt;
    const T theta2 = theta2In < T(0.0) ? T(0.0) : theta2In;
    if (theta2 < T(1e-6)) {
      a2 = T(0.5) - theta2 / T(24.0);
      a3 = T(1.0 / 6.0) - theta2 / T(120.0);
    } else {
      const T theta = sqrt(theta2);
      const T s = sin(T(0.5) * theta);
      a2 = T(2.0) * s * s / theta2;
      a3 = (theta - sin(theta)) / (theta2 * theta);
    }
  }

  Eigen::Matrix4d m_H;
};

END_VISP_NAMESPACE

#endif
