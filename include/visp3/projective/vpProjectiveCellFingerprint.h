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
  \file vpProjectiveCellFingerprint.h
  \brief What tells a cell from another, and its left camera from its right one: kept with a model, compared with
  later sessions and images.
*/

#ifndef _vpProjectiveCellFingerprint_h_
#define _vpProjectiveCellFingerprint_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpStereoImageSource.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveCellFingerprint
  \ingroup group_projective
  \brief The fingerprint of a cell: with its model (joint types, markers and their identifiers, the rig's fundamental
  matrix and epipoles), what the model alone does not hold: the left camera's image size, which camera was left
  (vpStereoImageSource::vpCameraIdentity: device, name, bus, serial), how the cameras are laid out, and where the
  right camera sits in the left camera's frame. vpProjectiveSessionCalibration makes it when it calibrates a session,
  the model file keeps it (vpProjectiveModelFile, its "cell" entry), and vpProjectiveSessionCalibration::check()
  compares it with a later session (\ref page_sessions_checks).

  <b>Which camera is left.</b> A projective model does not care which image is the left one: a session whose left
  and right images were exchanged calibrates to the same residuals. The metric self-calibration does
  (vpProjectiveSelfCalibration::metricStereoRig(): intrinsics with positive focal lengths, the markers in front of
  both cameras, a right-handed frame): it gives the right camera's centre in the left camera's frame, whose unit
  direction \f$ b \f$ is the baseline. Upright cameras with the left one on the left (seen from behind them, as the
  images are) have \f$ b_x > 0 \f$, whatever their vergence; exchanged images give \f$ b_x < 0 \f$. cameraSide()
  says SIDE_RIGHT for \f$ b_x \ge \cos 45^\circ \f$, SIDE_LEFT for \f$ b_x \le -\cos 45^\circ \f$, else
  SIDE_ABOVE_BELOW (cameras stacked vertically, or one behind the other: the images alone do not tell left from
  right then). Measured on random rigs (\ref page_sessions_checks): \f$ |b_x| \f$ is within 0.05 of the true
  \f$ \cos \varphi \f$, \f$ \varphi \f$ the direction of the right camera seen from behind the rig, so that the 45 deg
  margin never misnames a rig. The test assumes upright cameras: a camera mounted upside down (rolled by 180 deg) or
  seen through a mirror has its x axis the other way, and a rig whose left camera is the one on the right on purpose
  says so by LAYOUT_ANY, which turns the test off.
*/
class VISP_EXPORT vpProjectiveCellFingerprint
{
public:
  //! How the cameras are laid out: what the test of which camera is left assumes.
  enum vpCameraLayout {
    LAYOUT_LEFT_RIGHT, //!< Upright cameras, the left one on the left seen from behind them (default; side test on).
    LAYOUT_ANY         //!< Any layout (a camera upside down, a mirror): the side test is off.
  };

  //! Where the right camera sits in the left camera's frame (cameraSide()).
  enum vpCameraSide {
    SIDE_UNKNOWN,    //!< Not told: no metric self-calibration (or a model file without a fingerprint).
    SIDE_RIGHT,      //!< Within 45 deg of the left camera's +x axis: the cameras are as named.
    SIDE_LEFT,       //!< Within 45 deg of its -x axis: the left and right images are exchanged.
    SIDE_ABOVE_BELOW //!< Neither: cameras stacked vertically or one behind the other; the images do not tell.
  };

  //! An empty fingerprint: nothing known (a model file without one reads as this).
  vpProjectiveCellFingerprint();

  /*!
    Where the right camera of \e model sits in its left camera's frame, by the metric self-calibration (see the class
    documentation); \e direction receives the baseline's unit direction \f$ b \f$ (zero for SIDE_UNKNOWN, when the
    self-calibration fails: e.g. a model of prismatic joints only).
  */
  static vpCameraSide cameraSide(const vpProjectiveArmModel &model, Eigen::Vector3d &direction);

  //! The left camera's image size (pixels; 0 x 0: not known).
  void setImageSize(unsigned int width, unsigned int height);
  //! Width of the left camera's images (pixels; 0: not known).
  unsigned int getWidth() const { return m_width; }
  //! Height of the left camera's images (pixels; 0: not known).
  unsigned int getHeight() const { return m_height; }
  //! The identities of the cameras that took the left and right images (empty fields: not known).
  void setCameras(const vpStereoImageSource::vpCameraIdentity &left,
                  const vpStereoImageSource::vpCameraIdentity &right);
  //! The left camera's identity.
  const vpStereoImageSource::vpCameraIdentity &getLeftCamera() const { return m_left; }
  //! The right camera's identity.
  const vpStereoImageSource::vpCameraIdentity &getRightCamera() const { return m_right; }
  //! The cameras' layout (default LAYOUT_LEFT_RIGHT).
  void setCameraLayout(vpCameraLayout layout) { m_layout = layout; }
  //! The cameras' layout.
  vpCameraLayout getCameraLayout() const { return m_layout; }
  /*!
    Where the right camera was found (cameraSide()) and the baseline's unit direction in the left camera's frame.
    \exception vpProjectiveException (invalidValueError) if \e direction is not finite or is neither unit nor zero.
  */
  void setCameraSide(vpCameraSide side, const Eigen::Vector3d &direction);
  //! Where the right camera was found.
  vpCameraSide getCameraSide() const { return m_side; }
  //! The baseline's unit direction in the left camera's frame (zero if not known).
  const Eigen::Vector3d &getBaselineDirection() const { return m_baseline; }

  /*!
    Whether \e a and \e b are the same camera: 1 if so, 0 if not, -1 if their identities do not tell (a field empty
    in either). Serial numbers decide when both have one; else the bus and the name together; else the device and the
    name.
  */
  static int sameCamera(const vpStereoImageSource::vpCameraIdentity &a, const vpStereoImageSource::vpCameraIdentity &b);
  //! True if the identity has a field (the camera is known).
  static bool isKnown(const vpStereoImageSource::vpCameraIdentity &camera);
  /*!
    What tells that the cameras \e left and \e right (as a source gives them: vpStereoImageSource::
    getCameraIdentities()) are not this fingerprint's, the likeliest first: the model's cameras exchanged, or other
    cameras; with what to do. Empty if they are the fingerprint's, or if the identities do not tell (sameCamera()).
  */
  std::string cameraMismatch(const vpStereoImageSource::vpCameraIdentity &left,
                             const vpStereoImageSource::vpCameraIdentity &right) const;
  /*!
    What tells that images of \e width x \e height pixels are not the model's ("the left images are 320 x 240 pixels,
    the model's 640 x 480": the rig's matrices are in the model's pixels); empty if they are, or if a size is not
    known (0).
  */
  std::string imageSizeMismatch(unsigned int width, unsigned int height) const;
  /*!
    What tells that an arm whose joints are of the kinds \e arm is not the one a model of joints \e model was made
    for: their numbers, or the first joint whose kind differs ("joint 2 is prismatic, the model's revolute"); empty if
    they are the same.
  */
  static std::string jointTypesMismatch(const std::vector<vpProjectiveJoint::vpJointType> &model,
                                        const std::vector<vpProjectiveJoint::vpJointType> &arm);
  //! A camera's identity in a few words ("'/dev/video0' (HD Webcam C920, serial 8A3F1C2E)"); "an unknown camera".
  static std::string toString(const vpStereoImageSource::vpCameraIdentity &camera);
  //! A side in a few words ("to the right of the left camera", ...).
  static std::string toString(vpCameraSide side);
  //! The layout's name in a session and a model file: "left-right" or "any".
  static std::string toString(vpCameraLayout layout);

private:
  unsigned int m_width, m_height;
  vpStereoImageSource::vpCameraIdentity m_left, m_right;
  vpCameraLayout m_layout;
  vpCameraSide m_side;
  Eigen::Vector3d m_baseline;
};

END_VISP_NAMESPACE

#endif
