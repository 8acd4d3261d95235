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
  \file vpProjectiveSessionWriter.h
  \brief Records a session: stereo frames with their encoder readings, time and role, written as they come.
*/

#ifndef _vpProjectiveSessionWriter_h_
#define _vpProjectiveSessionWriter_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/projective/vpProjectiveSession.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveSessionWriter
  \ingroup group_projective
  \brief Writes a session (see vpProjectiveSession for the format) frame by frame, so that an acquisition or a servo
  run can be replayed, calibrated and checked offline.

  The constructor creates the folder (and its parents), \c left/ and \c right/; each addFrame() writes the two images
  as PNG (\c left/000000.png, ...) and rewrites \c session.json. Every file is written to a temporary name in its
  folder and then renamed: a session interrupted at any point (a crash, a full disk) is the complete session of the
  frames added so far. The frames are checked as vpProjectiveSession::read() checks them (readings, one zero frame,
  trials of one joint each), so a writer never records a session that the reader refuses.

  Attaching it to the acquisition procedure: vpProjectiveSessionCalibration::markerSource() makes the procedure's
  image source from a vpStereoImageSource and a marker extraction function, and records every stereo pair the
  procedure uses with the robot's readings (addAcquisitionFrame()).
  \code
  vpProjectiveSessionWriter writer("cell-2026-11-27", types);
  vpProjectiveAcquisitionProcedure procedure(
      vpProjectiveSessionCalibration::markerSource(cameras, extractor, robot, &writer), width, height);
  \endcode
  A servo loop adds its frames with the role vpProjectiveSession::SERVO (and the images of its target with TARGET).
*/
class VISP_EXPORT vpProjectiveSessionWriter
{
public:
  //! Joint kinds.
  typedef vpProjectiveJoint::vpJointType vpJointType;

  /*!
    A writer of a new session in \e folder, for joints of the kinds \e types (base to tip).
    \exception vpProjectiveException (dimensionError) for no joints or more than vpProjectiveArmModel::maxJoints;
    (fileError) if the folder cannot be created or written, or already holds a session.json (a recording is never
    overwritten: record into a new folder).
  */
  vpProjectiveSessionWriter(const std::string &folder, const std::vector<vpJointType> &types);

  /*!
    Records a frame: its \e role, the encoder readings \e q (n x 1, as read: radians, metres), the time \e t (seconds;
    NaN: no time) and the grey images. Returns the frame's index.
    \exception vpProjectiveException (fileError) if the frame is invalid (q of the wrong length or not finite, a
    second zero frame, a trial before the zero frame or moving no joint or several: nothing is written then), an image
    is empty, or a file cannot be written.
  */
  unsigned int addFrame(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t,
                        const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright);
  //! The same with colour images (written as RGB PNG).
  unsigned int addFrame(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t,
                        const vpImage<vpRGBa> &Ileft, const vpImage<vpRGBa> &Iright);
  /*!
    A frame of an acquisition, its role found from the readings: ZERO for the first frame, TRIAL if exactly one joint
    differs from the zero frame's readings by 1e-3 (rad or m) or more (the others within 1 % of its motion),
    OBSERVATION otherwise (a motion of several joints, e.g. the procedure's mounting check, or the arm back at the zero
    reference within its encoders' noise). Returns the role given.
    \exception vpProjectiveException as addFrame().
  */
  vpProjectiveSession::vpFrameRole addAcquisitionFrame(const vpColVector &q, double t,
                                                       const vpImage<unsigned char> &Ileft,
                                                       const vpImage<unsigned char> &Iright);

  //! The session as recorded so far (the content of session.json).
  const vpProjectiveSession &getSession() const { return m_session; }
  //! The session folder.
  const std::string &getFolder() const { return m_session.getFolder(); }

private:
  template <typename Type>
  unsigned int add(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t, const vpImage<Type> &Ileft,
                   const vpImage<Type> &Iright);

  vpProjectiveSession m_session;
};

END_VISP_NAMESPACE

#endif
