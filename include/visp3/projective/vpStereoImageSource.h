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
  \file vpStereoImageSource.h
  \brief A source of stereo image pairs: two live cameras, a rendered cell, or a recorded session being replayed.
*/

#ifndef _vpStereoImageSource_h_
#define _vpStereoImageSource_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>

#include <visp3/core/vpImage.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpStereoImageSource
  \ingroup group_projective
  \brief The one small interface behind which the acquisition procedure's and the servo loops' images come: a pair
  of grey images per call, left and right, taken at the same instant.

  Implementations: vpStereoGrabberSource (two live ViSP grabbers), vpProjectiveSessionSource (a recorded session
  replayed frame by frame, deterministically). A rendered cell implements it the same way.
  \code
  vpImage<unsigned char> Il, Ir;
  while (source.acquire(Il, Ir)) {
    // detect the markers, read the joints, servo...
  }
  \endcode
*/
class VISP_EXPORT vpStereoImageSource
{
public:
  //! What identifies one camera of the pair, so that a later run tells its left camera from its right one.
  struct vpCameraIdentity {
    std::string device; //!< The device it was opened as (e.g. "/dev/video0"); empty if not known.
    std::string name;   //!< The driver's name of the camera (V4L2: its card name, e.g. "HD Pro Webcam C920").
    std::string bus;    //!< Where it is plugged (V4L2: its bus_info, e.g. "usb-0000:00:14.0-2").
    std::string serial; //!< Its serial number where the driver gives one (a USB camera's iSerial), else empty.
  };

  virtual ~vpStereoImageSource() {}
  /*!
    The identities of the left and right cameras, when the source knows them (vpStereoGrabberSource on V4L2 devices,
    a replayed session that recorded them); false (the default) otherwise. A session records them
    (vpProjectiveSessionWriter::setCameras()) and its model keeps them, so that a later session with the cameras
    exchanged is named as such.
  */
  virtual bool getCameraIdentities(vpCameraIdentity &left, vpCameraIdentity &right) const
  {
    (void)left;
    (void)right;
    return false;
  }
  /*!
    Takes the next pair of images (8-bit grey; colour images are converted) into \e Ileft and \e Iright. Returns
    false when the source has no more images (the end of a replayed session); a live source waits for its cameras.
    \exception vpProjectiveException if the images cannot be taken (a camera lost, an unreadable file): the message
    names the device or the file.
  */
  virtual bool acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright) = 0;
  //! Width of the images (pixels; both cameras of a pair have the same size unless the source says otherwise).
  virtual unsigned int getWidth() const = 0;
  //! Height of the images (pixels).
  virtual unsigned int getHeight() const = 0;
  /*!
    The instants (seconds) the images of the last acquire() were taken, left and right, on the clock of the robot's
    encoder readings (vpProjectiveCellArm::getJoints(): CLOCK_MONOTONIC, std::chrono::steady_clock, for a real cell;
    the simulated time for a rendered one); false if the source does not know them (the default). A servo loop aligns
    each image's features to the time of the readings with them (vpProjectiveCell), and an acquisition waits for
    images taken after the arm stopped.
  */
  virtual bool getTimestamps(double &left, double &right) const
  {
    (void)left;
    (void)right;
    return false;
  }
};

END_VISP_NAMESPACE

#endif
