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
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpRGBa.h>
#include <visp3/projective/vpProjectiveSession.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveSessionWriter
  \ingroup group_projective
  \brief Writes a session (see vpProjectiveSession for the format) frame by frame, so that an acquisition or a servo
  run can be replayed, calibrated and checked offline.

  The constructor creates the folder (and its parents), \c left/ and \c right/ and an empty \c session.json; each
  addFrame() writes the two images as PNG (\c left/000000.png, ...) at once, and the frame list is written to
  \c session.json at save points:
  - when the frames added since the last save reach the save interval: max(setSaveInterval()'s frames, default 25,
    one eighth of the frames already saved), so that the text written over a recording is a constant amount per
    frame (appending a frame costs O(1) amortised: each frame is serialised once, and the file is rewritten after
    a number of frames proportional to its length);
  - when setSaveInterval()'s seconds (default 1 s) have passed since the last save, whatever the count, so that a
    slow recording is on disk within a second;
  - at save(), close(), and in the destructor (which swallows errors: call close() to hear of them).
  Every file is written to a temporary name in its folder and then renamed: at any moment (a crash, a full disk, a
  kill between two frames) \c session.json is a complete session of the frames up to the last save point, readable by
  vpProjectiveSession::read(); the frames added since are lost from it (their images stay in \c left/ and \c right/,
  unnamed, and are ignored). Close the writer before reading the session it records. The frames are checked as
  vpProjectiveSession::read() checks them (readings, one zero frame, trials of one joint each, recorded markers), so a
  writer never records a session that the reader refuses (except one without a zero frame yet).

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
  /*!
    A writer of a new session in \e folder, for joints of the kinds \e types (base to tip).
    \exception vpProjectiveException (dimensionError) for no joints or more than vpProjectiveArmModel::maxJoints;
    (fileError) if the folder cannot be created or written, or already holds a session.json (a recording is never
    overwritten: record into a new folder).
  */
  vpProjectiveSessionWriter(const std::string &folder, const std::vector<vpProjectiveJoint::vpJointType> &types);

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
    A frame with the markers that the recording program measured in it (\e ids ascending and distinct, one left and
    one right pixel each), saved in the frame's \c recorded_markers entry (see vpProjectiveSession): for a program whose
    markers are not extracted from its images by the plugin, so that the session calibrates offline from exactly what
    the program used.
    \exception vpProjectiveException as addFrame(), and (fileError) if the markers are not as described.
  */
  unsigned int addFrame(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t,
                        const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                        const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                        const std::vector<vpImagePoint> &right);
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

  /*!
    Which cameras take the left and the right images (the session's \c cameras entry), e.g. those of
    vpStereoImageSource::getCameraIdentities() (vpProjectiveSessionCalibration::markerSource() sets them so); written
    to session.json at once.
    \exception vpProjectiveException (fileError) as save().
  */
  void setCameras(const vpStereoImageSource::vpCameraIdentity &left,
                  const vpStereoImageSource::vpCameraIdentity &right);
  /*!
    The cameras of \e images (vpStereoImageSource::getCameraIdentities()) when it knows them, as setCameras(); nothing
    otherwise. Returns whether it knew them.
    \exception vpProjectiveException (fileError) as save().
  */
  bool setCameras(const vpStereoImageSource &images);
  /*!
    The cameras' layout (the session's \c camera_layout entry; default LAYOUT_LEFT_RIGHT): LAYOUT_ANY for a rig whose
    cameras are not upright side by side with the left one on the left (see vpProjectiveCellFingerprint). Written to
    session.json at once.
    \exception vpProjectiveException (fileError) as save().
  */
  void setCameraLayout(vpProjectiveCellFingerprint::vpCameraLayout layout);

  /*!
    Save points (see the class documentation): session.json is written when \e frames frames (>= 1; at least an
    eighth of those already saved) were added since the last save, or when \e seconds (> 0; infinity: no time bound)
    have passed since it and a frame is added.
    \exception vpProjectiveException (invalidValueError) on a zero count or a non-positive or NaN time.
  */
  void setSaveInterval(unsigned int frames, double seconds);
  /*!
    Writes session.json now with every frame added (atomically).
    \exception vpProjectiveException (fileError) if it cannot be written (the previous session.json is kept).
  */
  void save();
  /*!
    Saves and ends the recording: addFrame() is refused afterwards. Calling it again does nothing.
    \exception vpProjectiveException (fileError) as save().
  */
  void close();
  //! True after close().
  bool isClosed() const { return m_closed; }
  //! Saves if not closed, ignoring errors (close() reports them).
  ~vpProjectiveSessionWriter();

  //! The session as recorded so far (every frame added; session.json holds those up to the last save point).
  const vpProjectiveSession &getSession() const { return m_session; }
  //! Number of frames in session.json on disk (at the last save point).
  unsigned int getNumberOfSavedFrames() const { return m_saved; }
  //! The session folder.
  const std::string &getFolder() const { return m_session.getFolder(); }

private:
  template <typename Type>
  unsigned int add(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t, const vpImage<Type> &Ileft,
                   const vpImage<Type> &Iright, const std::vector<int> &ids = std::vector<int>(),
                   const std::vector<vpImagePoint> &left = std::vector<vpImagePoint>(),
                   const std::vector<vpImagePoint> &right = std::vector<vpImagePoint>());

  vpProjectiveSessionWriter(const vpProjectiveSessionWriter &) = delete;
  vpProjectiveSessionWriter &operator=(const vpProjectiveSessionWriter &) = delete;

  vpProjectiveSession m_session;
  std::string m_frames;    // the JSON text of the frame list, each frame serialised once
  unsigned int m_saved;    // frames in session.json
  unsigned int m_interval; // save after this many frames (at least m_saved / 8)
  double m_seconds;        // or after this many seconds
  double m_lastSave;       // vpTime::measureTimeSecond() of the last save
  bool m_closed;
};

END_VISP_NAMESPACE

#endif
