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
  \file vpProjectiveSession.h
  \brief A recorded session on disk (folder with session.json and PNG images): reading with full validation.
*/

#ifndef _vpProjectiveSession_h_
#define _vpProjectiveSession_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpProjectiveCellFingerprint.h>
#include <visp3/projective/vpProjectiveJoint.h>

BEGIN_VISP_NAMESPACE

class vpProjectiveSessionWriter;

/*!
  \class vpProjectiveSession
  \ingroup group_projective
  \brief A recorded session: the stereo frames of a cell (images, encoder readings, time, role) in a folder, so that
  an acquisition is recorded once and calibrated, checked and replayed later, on any machine.

  A session is a folder holding \c session.json and the images it names:
  \code{.json}
  { "format": "visp-projective-session", "version": 1,
    "joint_types": ["revolute", "revolute", "prismatic", "revolute", "revolute", "revolute"],
    "frames": [
      { "role": "zero",  "q": [0.1, -0.2, 0.05, 0, 0, 0], "t": 0.0, "left": "left/000000.png", "right":
  "right/000000.png" }, { "role": "trial", "q": [0.6, -0.2, 0.05, 0, 0, 0], "t": 1.5, "left": "left/000001.png",
  "right": "right/000001.png" } ] } \endcode
  - \c q: the encoder readings as read (radians, metres), one per joint;
  - \c role: \c "zero" (exactly one: the zero reference), \c "trial" (exactly one joint differs from the zero frame's
    readings; any number of trials per joint, both ways), \c "observation" (a view for re-registering the rig, or
    any other configuration), \c "target" (the images that teach s*), \c "servo" (a frame of a servo run);
  - \c left, \c right: paths relative to the folder, inside it, of 8-bit grey or RGB PNG images;
  - \c t: seconds, optional. Keys that the reader does not know are ignored.
  - \c recorded_markers: optional, the markers as the recording program measured them in the frame's images:
    \c {"ids": [0, 1, ...], "left": [[u, v], ...], "right": [[u, v], ...]} (identifiers ascending and distinct, one
    left and one right pixel each, ViSP's convention (u, v) = (j, i)). A program whose markers are not found in its
    images by an image-processing step of this plugin (the paper's experiment: projected points) records them here,
    so that calibrating the session (vpProjectiveSessionCalibration::setRecordedMarkers(), \c visp-projective
    \c calibrate \c --recorded-markers) uses exactly what the program used; readers of version 1 that do not know
    the key ignore it.
  - \c cameras: optional, which cameras took the left and the right images, as the recording knew them
    (vpStereoImageSource::getCameraIdentities(): vpStereoGrabberSource on V4L2 devices, \c visp-projective \c record):
    \code{.json}
    "cameras": { "left":  { "device": "/dev/video0", "name": "HD Webcam C920", "bus": "usb-0000:00:14.0-1",
                            "serial": "8A3F1C2E" },
                 "right": { "device": "/dev/video2", "name": "HD Webcam C920", "bus": "usb-0000:00:14.0-2" } }
    \endcode
    (each field a string, those not known left out). The model calibrated from the session keeps them, and checking
    it against a later session names cameras exchanged or replaced (vpProjectiveSessionCalibration::check()).
  - \c camera_layout: optional, \c "left-right" (the default: upright cameras, the left one on the left seen from
    behind them) or \c "any" (a camera mounted upside down or seen through a mirror): whether calibrating the session
    may refuse it as one whose left and right images are exchanged (vpProjectiveCellFingerprint::cameraSide()).
  Both keys are top-level, beside \c joint_types; sessions without them (older ones) read as before, and a reader of
  version 1 that does not know them ignores them.

  read() validates everything and throws a vpProjectiveException (fileError) whose one-line message names the file
  or the frame, what is wrong and what to do: a missing or unreadable session.json, text that is not JSON, another
  format name or version, unknown joint types, a frame without a known role, readings of the wrong length or not
  finite, no zero frame or several, a trial that moves no joint or several (the joint that moved most and the other
  that moved are named; a trial's other readings may differ by at most 1 % of its motion, encoder noise), an image
  path outside the folder, recorded markers whose identifiers are not ascending and distinct or whose pixels are
  not one finite (u, v) pair per identifier, a missing image, one that is not an 8-bit grey or RGB PNG or cannot be
  decoded, and images whose size differs from the first frame's. Frames are kept in the file's order, which replay
  follows (vpProjectiveSessionSource): the same session always gives the same images and readings.

  vpProjectiveSessionWriter records a session; vpProjectiveSessionCalibration calibrates an arm from one.
*/
class VISP_EXPORT vpProjectiveSession
{
public:
  //! What a frame is for.
  enum vpFrameRole {
    ZERO,        //!< The zero reference ("zero"): exactly one per session.
    TRIAL,       //!< One joint alone moved from the zero reference ("trial").
    OBSERVATION, //!< Any configuration, e.g. a view for re-registering the rig ("observation").
    TARGET,      //!< The images that teach the desired features s* ("target").
    SERVO        //!< A frame of a servo run ("servo").
  };

  //! One stereo frame as recorded.
  struct vpFrame {
    vpFrameRole role;                      //!< What the frame is for.
    vpColVector q;                         //!< Encoder readings (n x 1: radians, metres), as read.
    bool hasTime;                          //!< True if the frame has a time.
    double t;                              //!< Seconds (0 if hasTime is false).
    std::string left;                      //!< Left image, relative to the session folder.
    std::string right;                     //!< Right image, relative to the session folder.
    std::vector<int> markerIds;            //!< Recorded markers' identifiers (ascending; empty: none recorded).
    std::vector<vpImagePoint> markerLeft;  //!< Their left pixels (one per identifier).
    std::vector<vpImagePoint> markerRight; //!< Their right pixels (one per identifier).
  };

  //! The format name of session.json.
  static const char *const formatName;
  //! The format version this build reads and writes.
  static constexpr int version = 1;

  //! An empty session (no joints, no frames).
  vpProjectiveSession();

  /*!
    Reads and validates the session in \e folder (see the class documentation). With \e checkImages (default) every
    image is also decoded (vpImageIo) and its size compared with the first frame's; with false only the PNG headers
    are checked (faster on long servo recordings; getImages() still reports a damaged image).
    \exception vpProjectiveException (fileError) on any invalid content, with a one-line message.
  */
  static vpProjectiveSession read(const std::string &folder, bool checkImages = true);
  /*!
    The session of the JSON text \e text (the content of a session.json; images not checked); \e name is quoted in
    the error messages. The parser behind read().
    \exception vpProjectiveException (fileError) as read(), except for the images.
  */
  static vpProjectiveSession fromString(const std::string &text, const std::string &name);
  //! The JSON text of the session (what vpProjectiveSessionWriter writes to session.json).
  std::string toString() const;

  //! The folder read (empty for fromString()).
  const std::string &getFolder() const { return m_folder; }
  //! Number of joints \e n.
  unsigned int getNumberOfJoints() const { return static_cast<unsigned int>(m_types.size()); }
  //! The kinds of the joints, base to tip.
  const std::vector<vpProjectiveJoint::vpJointType> &getJointTypes() const { return m_types; }
  //! Number of frames.
  unsigned int getNumberOfFrames() const { return static_cast<unsigned int>(m_frames.size()); }
  /*!
    Frame \e k, in the file's order.
    \exception vpProjectiveException (dimensionError) if there is no such frame.
  */
  const vpFrame &getFrame(unsigned int k) const;
  /*!
    Index of the zero frame.
    \exception vpProjectiveException (notInitializedError) if the session has none (an empty session).
  */
  unsigned int getZeroFrame() const;
  //! The joint that trial frame \e k moved; -1 if frame \e k is not a trial (or does not exist).
  int getTrialJoint(unsigned int k) const;
  //! Number of frames of role \e role.
  unsigned int getNumberOfFrames(vpFrameRole role) const;
  /*!
    Full path of the left (\e left true) or right image of frame \e k.
    \exception vpProjectiveException (dimensionError) if there is no such frame.
  */
  std::string getImagePath(unsigned int k, bool left) const;
  /*!
    The images of frame \e k, as 8-bit grey (RGB images are converted).
    \exception vpProjectiveException (dimensionError) if there is no such frame; (fileError) if an image cannot be
    read, naming the frame and the file.
  */
  void getImages(unsigned int k, vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright) const;
  //! Width of the left images (pixels; 0 if not known: fromString(), or read() without images checked and no frame).
  unsigned int getWidth() const { return m_width; }
  //! Height of the left images (pixels; 0 if not known).
  unsigned int getHeight() const { return m_height; }
  //! True if the session recorded which cameras took its images (its \c cameras entry).
  bool hasCameras() const
  {
    return vpProjectiveCellFingerprint::isKnown(m_cameras[0]) || vpProjectiveCellFingerprint::isKnown(m_cameras[1]);
  }
  //! The camera that took the left images (empty fields: not recorded).
  const vpStereoImageSource::vpCameraIdentity &getLeftCamera() const { return m_cameras[0]; }
  //! The camera that took the right images (empty fields: not recorded).
  const vpStereoImageSource::vpCameraIdentity &getRightCamera() const { return m_cameras[1]; }
  //! The cameras' layout (its \c camera_layout entry; LAYOUT_LEFT_RIGHT if it has none).
  vpProjectiveCellFingerprint::vpCameraLayout getCameraLayout() const { return m_layout; }

  //! The role's name in session.json ("zero", "trial", "observation", "target", "servo").
  static std::string toString(vpFrameRole role);

private:
  friend class vpProjectiveSessionWriter;

  /*!
    Checks \e frame against the session (readings, role: a second zero frame, a trial that moves no joint or
    several) and returns the trial's joint (-1 for another role); \e what names the frame in the messages.
  */
  int checkFrame(const vpFrame &frame, const std::string &where, const std::string &what) const;

  std::string m_folder;
  std::vector<vpProjectiveJoint::vpJointType> m_types;
  std::vector<vpFrame> m_frames;
  std::vector<int> m_trialJoint; // per frame: the joint a trial moved, -1 otherwise
  int m_zero;                    // index of the zero frame, -1 if none yet
  unsigned int m_width, m_height;
  vpStereoImageSource::vpCameraIdentity m_cameras[2]; // left, right
  vpProjectiveCellFingerprint::vpCameraLayout m_layout;
};

END_VISP_NAMESPACE

#endif
