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
  \file vpSimulatorStereoRig.h
  \brief A metric stereo rig with pixel noise: the ground truth behind tutorials and tests.
*/

#ifndef _vpSimulatorStereoRig_h_
#define _vpSimulatorStereoRig_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>

BEGIN_VISP_NAMESPACE

class vpProjectiveStereoRig;

/*!
  \class vpSimulatorStereoRig
  \ingroup group_projective_simulator
  \brief Two metric pinhole cameras rigidly linked, as in eq. (2) of Ruf & Horaud:
  \f$ m \simeq K [I | 0] N \f$, \f$ m' \simeq K' [R' | t'] N \f$, \f$ N \f$ in the left camera frame \f$ E \f$.

  Frames: \c w the world, \c l the left camera (the metric frame \f$ E \f$ of the paper), \c r the right camera.
  \c wMl is the left camera's pose in the world and \c rMl = \f$ [R' | t'] \f$ maps left-camera coordinates to
  right-camera ones. Points passed to the methods are 3D world points (3x1, or 4x1 homogeneous with last entry 1).

  It knows what the plugin never does: the intrinsics, the rig geometry, and hence the projective-to-Euclidean link
  \f$ H_{PE} \f$ (4) of any vpProjectiveStereoRig frame, \f$ N \simeq H_{PE} M \f$. Tests compare estimates with it.
*/
class VISP_EXPORT vpSimulatorStereoRig
{
public:
  /*!
    A rig from its metric parameters.
    \param camLeft, camRight : intrinsics (px, py, u0, v0), no distortion.
    \param rMl : left-to-right camera transform \f$ [R' | t'] \f$.
    \param wMl : pose of the left camera in the world.
    \param width, height : image size in pixels (for visibility).
  */
  vpSimulatorStereoRig(const vpCameraParameters &camLeft, const vpCameraParameters &camRight,
                       const vpHomogeneousMatrix &rMl, const vpHomogeneousMatrix &wMl, unsigned int width,
                       unsigned int height);

  /*!
    The paper's rig (section 6): 20 cm baseline, verging cameras, 12.5 mm lenses on a 1/3 inch CCD (4.8 x 3.6 mm,
    640 x 480 pixels of 7.5 um, hence px = py = 1666.7), principal point at the image centre. The left camera is
    placed in the world so that the vergence point lies \e distance metres in front of the rig's midpoint, at the
    world point \e fixation.

    World placement (see vergingRig()): the rig's midpoint is at \e fixation - (0, 0, \e distance), the cameras are
    at -/+ 10 cm along the world X axis from it, both optical axes pass through \e fixation (so it images at the
    principal point, (320, 240), in both images), and both cameras' y axes are the world +Y axis. The rig thus looks
    along the world +Z axis, world X is to the right in the images and world Y downwards.

    The paper's 20 cm baseline, 20 deg vergence and 1 m distance cannot all hold with the optical axes crossing at
    \e fixation; the baseline and the vergence point are kept: each camera is toed in by atan(0.1 / \e distance), so
    the vergence angle is the paper's 20 deg at \e distance = 0.567 m and 11.4 deg at the default 1 m (20 deg at 1 m
    needs a 35 cm baseline: vergingRig(fixation, 1.0, 0.3527)). At 1 m each camera sees 38 x 29 cm.
  */
  static vpSimulatorStereoRig paperRig(const vpColVector &fixation, double distance = 1.0);

  /*!
    A symmetric verging rig of two identical cameras \e cam (images \e width x \e height): the camera centres are
    at \e fixation - (-/+ \e baseline / 2, 0, \e distance) in the world, each optical axis passes through the world
    point \e fixation (3x1) and each camera's y axis is the world +Y axis.
    \exception vpProjectiveException if \e fixation is not 3x1 or a value is not finite or not positive.
  */
  static vpSimulatorStereoRig vergingRig(const vpColVector &fixation, double distance, double baseline,
                                         const vpCameraParameters &cam = paperCameraParameters(),
                                         unsigned int width = 640, unsigned int height = 480);

  //! The paper's cameras: px = py = 12.5 mm / 7.5 um = 1666.67, (u0, v0) = (320, 240), 640 x 480, no distortion.
  static vpCameraParameters paperCameraParameters();

  /*! \name Ground truth */
  //@{
  //! Intrinsics of the left camera.
  const vpCameraParameters &getLeftCameraParameters() const { return m_camLeft; }
  //! Intrinsics of the right camera.
  const vpCameraParameters &getRightCameraParameters() const { return m_camRight; }
  //! \f$ [R' | t'] \f$: left-camera to right-camera coordinates.
  const vpHomogeneousMatrix &get_rMl() const { return m_rMl; }
  //! Pose of the left camera in the world.
  const vpHomogeneousMatrix &get_wMl() const { return m_wMl; }
  //! Image width (pixels).
  unsigned int getWidth() const { return m_width; }
  //! Image height (pixels).
  unsigned int getHeight() const { return m_height; }
  //! Metric projection matrices \f$ K[I|0] \f$ and \f$ K'[R'|t'] \f$ (3x4), acting on left-camera coordinates.
  vpMatrix getLeftMetricProjection() const;
  //! \f$ K'[R'|t'] \f$ (3x4), acting on left-camera coordinates.
  vpMatrix getRightMetricProjection() const;
  //! The true fundamental matrix (3x3, unit Frobenius norm, pixel coordinates): \f$ m'^T F m = 0 \f$.
  vpMatrix getFundamentalMatrix() const;
  /*!
    \f$ H_{PE} \f$ (4x4) of the projective frame of \e rig (which must hold a fundamental matrix of this rig): the
    homography with \f$ N \simeq H_{PE} M \f$, \f$ N \f$ homogeneous left-camera coordinates, \f$ M \f$ projective
    coordinates in \e rig's frame. Scaled so that \f$ \det H_{PE} = \pm 1 \f$, with the sign that makes
    \f$ K[I|0] H_{PE} \f$ a positive multiple of \f$ P \f$ (points in front of the cameras have \f$ (P M)_3 > 0 \f$
    when \f$ N = ({}^lX, 1) \f$).
    \exception vpProjectiveException if \e rig has no \f$ F \f$ yet, or if its frame is not one of this rig's (its
    \f$ F \f$ differs: see the residual below).
  */
  vpMatrix getProjectiveToEuclidean(const vpProjectiveStereoRig &rig) const;
  /*!
    The same, also returning the \e residual in pixels. The left cameras are matched exactly
    (\f$ P H_{PE}^{-1} = K[I|0] \f$); the remaining 4 degrees of freedom are fitted so that the right camera of the
    frame, \f$ P' H_{PE}^{-1} \f$, images sample points filling the common field of view (7 x 7 left pixels at 0.6 to
    1.6 times the vergence distance) where \f$ K'[R'|t'] \f$ does; \e residual is the RMS distance of those right
    images. It is about 1e-11 px for a rig given this simulator's getFundamentalMatrix(), of the order of the image
    noise for an \f$ F \f$ estimated from this rig's images (the result is then the best-fitting homography), and
    above getMaxProjectiveToEuclideanResidual() an exception declares the frame foreign.
  */
  vpMatrix getProjectiveToEuclidean(const vpProjectiveStereoRig &rig, double &residual) const;
  //! Largest residual accepted by getProjectiveToEuclidean(): 2% of the image diagonal (16 px for 640 x 480).
  double getMaxProjectiveToEuclideanResidual() const;
  //! The metric 4x4 displacement \f$ {}^w T \f$ expressed in the left camera frame: \f$ {}^lM_w\, T\, {}^wM_l \f$.
  vpMatrix toCameraFrame(const vpMatrix &wT) const;
  //@}

  /*! \name Imaging */
  //@{
  /*!
    Noise-free pixel images of the world point \e wX (3x1 or 4x1).
    \return true if the point is in front of both cameras and inside both images (0 <= u <= width - 1,
    0 <= v <= height - 1). A point on a camera's focal plane leaves that image point unchanged.
  */
  bool project(const vpColVector &wX, vpImagePoint &ipLeft, vpImagePoint &ipRight) const;
  /*!
    The same with independent Gaussian noise of standard deviation \e sigma pixels on each coordinate, drawn from
    \e noise (seed it for reproducible runs). Only the generator's random stream is used: its own standard deviation
    and mean are reset to 1 and 0 (setSigmaMean(1, 0)) and each draw is scaled by \e sigma; four draws per point, in
    the order u, v, u', v'. The returned visibility is that of the noise-free point.
    \exception vpProjectiveException if \e sigma is negative or not finite, or \e wX is not 3x1 / 4x1 or not finite.
  */
  bool project(const vpColVector &wX, vpImagePoint &ipLeft, vpImagePoint &ipRight, double sigma,
               vpGaussRand &noise) const;
  //! Images of a point set; returns true if all points are visible in both images.
  bool project(const std::vector<vpColVector> &wX, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right,
               double sigma, vpGaussRand &noise) const;
  //! True if \e wX is in front of both cameras (depth > \e minDepth metres) and inside both images by \e margin px.
  bool isVisible(const vpColVector &wX, double margin = 0.0, double minDepth = 0.05) const;
  //@}

  /*! \name Rigid and single-axis motions of point sets (world frame) */
  //@{
  //! \f$ {}^wT\, X \f$ for every point.
  static std::vector<vpColVector> transform(const vpHomogeneousMatrix &wT, const std::vector<vpColVector> &wX);
  /*!
    Rotation by \e theta radians about the axis through \e point with direction \e axis (world frame, 3x1),
    as a 4x4 metric displacement.
  */
  static vpHomogeneousMatrix rotationAbout(const vpColVector &point, const vpColVector &axis, double theta);
  //! Translation by \e tau metres along the unit \e direction.
  static vpHomogeneousMatrix translationAlong(const vpColVector &direction, double tau);
  //@}

private:
  //! Metric points (homogeneous, left camera) filling the common field of view around the vergence distance.
  std::vector<Eigen::Vector4d> samplePoints() const;
  bool imageOf(const vpColVector &wX, vpImagePoint &ipLeft, vpImagePoint &ipRight, double margin,
               double minDepth) const;

  vpCameraParameters m_camLeft;
  vpCameraParameters m_camRight;
  vpHomogeneousMatrix m_rMl;
  vpHomogeneousMatrix m_wMl;
  vpHomogeneousMatrix m_lMw;
  unsigned int m_width;
  unsigned int m_height;
};

END_VISP_NAMESPACE

#endif
