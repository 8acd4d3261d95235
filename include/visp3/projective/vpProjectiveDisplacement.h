/*
 * visp_projective: non-metric stereo visual servoing for ViSP.
 */

/*!
  \file vpProjectiveDisplacement.h
  \brief Projective displacements: rigid motions seen in the projective frame of a weakly calibrated rig.
*/

#ifndef _vpProjectiveDisplacement_h_
#define _vpProjectiveDisplacement_h_

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>

class vpProjectiveStereoRig;

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
    calibrated rig: triangulation, linear estimate, then Ceres minimisation of the reprojection error of all four
    point sets over \f$ H \f$ and the points \f$ M_0^{(j)} \f$ (the maximum-likelihood estimate under Gaussian pixel
    noise).
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
    larger adjustment needs few).
  */
  static Eigen::Matrix4d estimateFromImages(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &s0,
                                            const std::vector<Eigen::Vector4d> &s1, int maxIterations = 100);
  //! Linear (DLT) estimate on Eigen types; same checks as estimate().
  static Eigen::Matrix4d estimateLinear(const std::vector<Eigen::Vector4d> &M0, const std::vector<Eigen::Vector4d> &M1);

  /*!
    Normalisation of eq. (12): \f$ H / (\mathrm{sign}(\mathrm{trace} H) |\det H|^{1/4}) \f$.
    \exception vpProjectiveException if H is singular or not finite.
  */
  static Eigen::Matrix4d normalize(const Eigen::Matrix4d &H);

  //! The normalised 4x4 matrix.
  vpMatrix getMatrix() const;
  //! The normalised 4x4 matrix (Eigen, no allocation).
  const Eigen::Matrix4d &matrix() const { return m_H; }

  //! Rotation angle \f$ \theta \in [0, \pi] \f$ of eq. (21), \f$ \cos\theta = (\mathrm{trace} H - 2)/2 \f$, clamped.
  double getRotationAngle() const;

  /*!
    Classifies the motion by the numerical rank of \f$ H - I \f$: a singular value \f$ \sigma_k \f$ counts when
    \f$ \sigma_k > \mathrm{tolerance} \cdot \max(1, \sigma_1) \f$. With noisy estimates, pass a tolerance above the
    noise level of \f$ H \f$.
  */
  vpMotionType classify(double tolerance = 1e-6) const;

  //! Composition: points move by \f$ H_2 H_1 \f$ when they move by \f$ H_1 \f$, then \f$ H_2 \f$.
  vpProjectiveDisplacement operator*(const vpProjectiveDisplacement &other) const;
  //! Inverse displacement.
  vpProjectiveDisplacement inverse() const;

private:
  Eigen::Matrix4d m_H;
};

#endif
