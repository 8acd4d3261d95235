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
  \file vpFeatureStereoPoint.h
  \brief A point seen by both cameras of a stereo rig, as a ViSP visual feature.
*/

#ifndef _vpFeatureStereoPoint_h_
#define _vpFeatureStereoPoint_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColor.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/visual_features/vpBasicFeature.h>

BEGIN_VISP_NAMESPACE

class vpProjectiveStereoRig;

/*!
  \class vpFeatureStereoPoint
  \ingroup group_projective
  \brief Non-metric stereo point feature \f$ s = (u, v, u', v') \f$: the pixel coordinates of one point in the left
  and in the right image (Ruf & Horaud, section 6).

  Unlike vpFeaturePoint, it needs no intrinsics and no depth. Its interaction matrix is taken with respect to the
  velocity \f$ \dot M \f$ of the projective point \f$ M \f$ (4x1) of the rig's frame, eq. (45):
  \f[ \dot s = L_s \dot M, \qquad L_s = \begin{bmatrix} J_C(P M)\, P \\ J_C(P' M)\, P' \end{bmatrix} \quad (4 \times 4),
  \f] with \f$ M \f$ triangulated from \f$ s \f$. Multiplied by the point Jacobian \f$ J_H(q, M) \f$ of
  vpProjectiveRobot it gives the joint-space image Jacobian (46); vpServoProjective does exactly that.

  \code
  vpFeatureStereoPoint s, s_star;
  s_star.buildFrom(ipLeftDesired, ipRightDesired);
  s.buildFrom(ipLeft, ipRight);   // updated at every iteration of the loop
  vpColVector e = s.error(s_star); // s - s*
  \endcode
*/
class VISP_EXPORT vpFeatureStereoPoint : public vpBasicFeature
{
public:
  vpFeatureStereoPoint();

  //! Resets \f$ s \f$ to zero (4 rows, all selected); called by the constructor.
  void init();
  /*!
    Sets \f$ s \f$ from the pixels of the point in the left and right images.
    \exception vpProjectiveException if a coordinate is not finite.
  */
  void buildFrom(const vpImagePoint &ipLeft, const vpImagePoint &ipRight);
  //! Sets \f$ s = (u, v, u', v') \f$ directly.
  void buildFrom(double u, double v, double up, double vp);
  /*!
    Teaching \f$ s^* \f$ from several frames: sets \f$ s \f$ to the mean of the F observations of the point
    \f$ (u_f, v_f, u'_f, v'_f) \f$, \e ipLeft[f] and \e ipRight[f] (pixels), taken with the arm and the target at rest.
    Each frame's noise, \f$ \sigma \f$ px per coordinate, becomes \f$ \sigma / \sqrt F \f$ (the mean of
    independent observations of one point, and its maximum-likelihood estimate under Gaussian noise): a target taught
    from one frame keeps that frame's noise for the whole servo, which then ends at that floor whatever it averages
    (vpServoProjective::setSettling()). The mean of matched observations of one point is itself a matched
    observation (the epipolar constraint holds for the true point, and the noise is averaged in each coordinate).
    \code
    std::vector<vpImagePoint> left, right; // one per frame, the arm at the target
    for (unsigned int f = 0; f < 16; ++f) {
      // ... grab and track, then
      left.push_back(ipLeft); right.push_back(ipRight);
    }
    s_star.buildFrom(left, right);
    \endcode
    \exception vpProjectiveException (dimensionError) if the lists are empty or of different sizes;
    (nonFiniteValueError) if a coordinate is not finite. \f$ s \f$ is then unchanged.
  */
  void buildFrom(const std::vector<vpImagePoint> &ipLeft, const std::vector<vpImagePoint> &ipRight);
  /*!
    For simulations, what vpFeatureBuilder::create(vpFeaturePoint &, const vpPoint &) is to vpFeaturePoint: sets
    \f$ s \f$ from the images of the 3D point \e P (its object-frame coordinates, vpPoint::setWorldCoordinates())
    through two known cameras: \f$ {}^{c}P = {}^{c}M_o\, {}^{o}P \f$ in each camera, \f$ x = X/Z \f$, \f$ y = Y/Z
    \f$, then the pixels of vpMeterPixelConversion::convertPoint() with the camera's model (its distortion included).
    \e P is not changed (unlike vpPoint::track()).
    \code
    vpPoint point(0.045, -0.045, 0.0);            // object frame, metres
    vpHomogeneousMatrix cRightMcLeft(0.1, 0, 0, 0, -0.13, 0);
    s.buildFrom(point, cam, cMo, cam, cRightMcLeft * cMo); // the left camera at cMo, the right one 10 cm beside it
    \endcode
    A real rig has no such calibration: its features come from the images (buildFrom(ipLeft, ipRight)).
    \param P : the point; only its object-frame coordinates are used.
    \param camLeft, camRight : the intrinsics of the left and right cameras.
    \param cLeftMo, cRightMo : the object frame in the left and right camera frames.
    \exception vpProjectiveException (nonFiniteValueError) if a coordinate or a pose is not finite;
    (pointAtInfinityError) if the point is not in front of both cameras (Z <= 0). \f$ s \f$ is then unchanged.
  */
  void buildFrom(const vpPoint &P, const vpCameraParameters &camLeft, const vpHomogeneousMatrix &cLeftMo,
                 const vpCameraParameters &camRight, const vpHomogeneousMatrix &cRightMo);

  //! The point in the left image, \f$ (u, v) \f$.
  vpImagePoint getLeft() const;
  //! The point in the right image, \f$ (u', v') \f$.
  vpImagePoint getRight() const;
  //! Left column \f$ u \f$ (pixels).
  double get_u() const { return s[0]; }
  //! Left row \f$ v \f$ (pixels).
  double get_v() const { return s[1]; }
  //! Right column \f$ u' \f$ (pixels).
  double get_up() const { return s[2]; }
  //! Right row \f$ v' \f$ (pixels).
  double get_vp() const { return s[3]; }
  //! \f$ s \f$ as an Eigen vector (no allocation).
  Eigen::Vector4d getFeature() const { return Eigen::Vector4d(s[0], s[1], s[2], s[3]); }

  /*!
    The rig used by interaction() to triangulate \f$ M \f$ and form \f$ L_s \f$. The feature keeps a reference: the
    rig must outlive it.
  */
  void setStereoRig(const vpProjectiveStereoRig &rig) { m_rig = &rig; }

  /*!
    \f$ s - s^* \f$ for the selected rows.
    \exception vpProjectiveException if s_star is not a vpFeatureStereoPoint.
  */
  vpColVector error(const vpBasicFeature &s_star, unsigned int select = FEATURE_ALL);
  /*!
    \f$ L_s = \partial s / \partial M \f$ (rows selected, 4 columns), eq. (45).
    \exception vpProjectiveException if no rig was set or the point is on a camera's focal plane.
  */
  vpMatrix interaction(unsigned int select = FEATURE_ALL);
  //! Prints the selected rows of \f$ s \f$.
  void print(unsigned int select = FEATURE_ALL) const;
  //! A new feature of the same type (the caller deletes it), as vpBasicFeature requires.
  vpFeatureStereoPoint *duplicate() const;

  //! Draws the left image point (the camera parameters are not needed: \f$ s \f$ is in pixels).
  void display(const vpCameraParameters &cam, const vpImage<unsigned char> &I, const vpColor &color = vpColor::green,
               unsigned int thickness = 1) const;
  //! Draws the left image point in a color image (the camera parameters are not needed).
  void display(const vpCameraParameters &cam, const vpImage<vpRGBa> &I, const vpColor &color = vpColor::green,
               unsigned int thickness = 1) const;
  //! Draws the point in the left image \e Ileft and in the right image \e Iright.
  void display(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
               const vpColor &color = vpColor::green, unsigned int thickness = 1) const;

  //! Selection mask of \f$ u \f$, for error() and interaction().
  static unsigned int selectU() { return FEATURE_LINE[0]; }
  //! Selection mask of \f$ v \f$.
  static unsigned int selectV() { return FEATURE_LINE[1]; }
  //! Selection mask of \f$ u' \f$.
  static unsigned int selectUp() { return FEATURE_LINE[2]; }
  //! Selection mask of \f$ v' \f$.
  static unsigned int selectVp() { return FEATURE_LINE[3]; }

private:
  const vpProjectiveStereoRig *m_rig;
};

END_VISP_NAMESPACE

#endif
