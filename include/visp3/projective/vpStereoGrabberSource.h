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
  \file vpStereoGrabberSource.h
  \brief Stereo images from two live ViSP frame grabbers (two V4L2 cameras, or any two grabbers already opened).
*/

#ifndef _vpStereoGrabberSource_h_
#define _vpStereoGrabberSource_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <memory>
#include <string>

#include <visp3/core/vpFrameGrabber.h>
#include <visp3/core/vpImage.h>
#include <visp3/projective/vpStereoImageSource.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpStereoGrabberSource
  \ingroup group_projective
  \brief Two live cameras as a vpStereoImageSource: each acquire() takes one image from the left grabber, then one
  from the right.

  Two ways to build one:
  - from two Video4Linux2 device names (ViSP's vpV4l2Grabber, when this ViSP was built with V4L2): the grabbers are
    opened at once, and a device that cannot be opened (missing, busy, not a camera, no permission) makes the
    constructor throw a vpProjectiveException naming the device and what to check;
  - from two ViSP grabbers the caller has opened (vp1394TwoGrabber, vpOpenCVGrabber, vpRealSense2 through its
    grabber...), which must outlive this object.

  The two cameras are not synchronised by this class: take images of a still scene (the acquisition procedure stops
  the arm before each pair), or use cameras triggered together. V4L2 cameras stamp each image (the driver's buffer
  time, CLOCK_MONOTONIC for uvcvideo and most drivers): getTimestamps() gives both stamps, so that vpProjectiveCell
  aligns each image with the encoder readings and refuses pairs taken too far apart (vpProjectiveCell::vpSettings
  maxSkew, maxLatency). Other grabbers give no stamps.
  \code
  vpStereoGrabberSource cameras("/dev/video0", "/dev/video2");
  vpImage<unsigned char> Il, Ir;
  cameras.acquire(Il, Ir);
  \endcode
*/
class VISP_EXPORT vpStereoGrabberSource : public vpStereoImageSource
{
public:
  /*!
    Opens the V4L2 cameras \e leftDevice and \e rightDevice (e.g. "/dev/video0") with the subsampling \e scale
    (1: full resolution, 2: half...).
    \exception vpProjectiveException (fileError) if a device cannot be opened (the message names it), or if this ViSP
    has no V4L2 support (then open the cameras with another ViSP grabber and use the other constructor).
  */
  vpStereoGrabberSource(const std::string &leftDevice, const std::string &rightDevice, unsigned int scale = 1);
  /*!
    Two grabbers opened by the caller; they are not owned and must outlive this object.
    \exception vpProjectiveException (notInitializedError) if a grabber has not been opened (its size is 0).
  */
  vpStereoGrabberSource(vpFrameGrabber &left, vpFrameGrabber &right);
  ~vpStereoGrabberSource() override;

  /*!
    One image from each camera. Always true (a live source has no end).
    \exception vpProjectiveException (fileError) if a grabber fails, naming the camera.
  */
  bool acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright) override;
  /*!
    The instants (s, CLOCK_MONOTONIC) the last acquire()'s images were taken: true only if both cameras are V4L2
    devices whose driver stamped them on that clock (a stamp in the future or more than 10 s old, as the wall clock
    some drivers use gives, counts as none).
  */
  bool getTimestamps(double &left, double &right) const override;
  /*!
    The identities of the V4L2 cameras opened by the first constructor: the device names given, V4L2's card name and
    bus_info, and a USB camera's serial number (from sysfs) when it has one. False for grabbers given by the caller.
  */
  bool getCameraIdentities(vpCameraIdentity &left, vpCameraIdentity &right) const override;
  //! Width of the left camera's images (pixels).
  unsigned int getWidth() const override { return m_left->getWidth(); }
  //! Height of the left camera's images (pixels).
  unsigned int getHeight() const override { return m_left->getHeight(); }

private:
  vpStereoGrabberSource(const vpStereoGrabberSource &) = delete;
  vpStereoGrabberSource &operator=(const vpStereoGrabberSource &) = delete;

  std::unique_ptr<vpFrameGrabber> m_ownedLeft, m_ownedRight;
  vpFrameGrabber *m_left, *m_right;
  std::string m_leftName, m_rightName;
  double m_stamps[2];               // the last images' instants (s, CLOCK_MONOTONIC)
  bool m_stamped;                   // both stamps valid
  vpCameraIdentity m_identities[2]; // left, right: the V4L2 cameras opened by the first constructor
};

END_VISP_NAMESPACE

#endif
