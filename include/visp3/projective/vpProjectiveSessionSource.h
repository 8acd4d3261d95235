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
  \file vpProjectiveSessionSource.h
  \brief A recorded session replayed as a stereo image source, frame by frame, deterministically.
*/

#ifndef _vpProjectiveSessionSource_h_
#define _vpProjectiveSessionSource_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImage.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpStereoImageSource.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveSessionSource
  \ingroup group_projective
  \brief Replays a vpProjectiveSession: each acquire() gives the images of the next frame (in the file's order,
  optionally only frames of some roles), and getJoints() the encoder readings recorded with them. The same session
  always gives the same sequence: a loop fed by it runs offline exactly as it ran on the cell.
  \code
  vpProjectiveSessionSource replay(vpProjectiveSession::read("cell-2026-11-27"));
  while (replay.acquire(Il, Ir)) {
    const vpColVector &q = replay.getJoints();
    // ...
  }
  \endcode
*/
class VISP_EXPORT vpProjectiveSessionSource : public vpStereoImageSource
{
public:
  /*!
    Replays \e session (read from its folder), all frames, or only those whose role is in \e roles (if not empty).
    \exception vpProjectiveException (notInitializedError) if the session was not read from a folder (no images).
  */
  explicit vpProjectiveSessionSource(
      const vpProjectiveSession &session,
      const std::vector<vpProjectiveSession::vpFrameRole> &roles = std::vector<vpProjectiveSession::vpFrameRole>());

  /*!
    The images of the next frame (grey); false, and the images untouched, after the last one.
    \exception vpProjectiveException (fileError) if an image cannot be read (naming the frame and the file).
  */
  bool acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright) override;
  //! The cameras the session recorded (vpProjectiveSession::getLeftCamera()); false if it recorded none.
  bool getCameraIdentities(vpCameraIdentity &left, vpCameraIdentity &right) const override
  {
    left = m_session.getLeftCamera();
    right = m_session.getRightCamera();
    return m_session.hasCameras();
  }
  //! Width of the session's left images (pixels).
  unsigned int getWidth() const override { return m_session.getWidth(); }
  //! Height of the session's left images (pixels).
  unsigned int getHeight() const override { return m_session.getHeight(); }

  //! Index in the session of the frame last acquired (-1 before the first acquire()).
  int getFrameIndex() const { return m_current; }
  /*!
    The encoder readings of the frame last acquired.
    \exception vpProjectiveException (notInitializedError) before the first acquire().
  */
  const vpColVector &getJoints() const;
  /*!
    The frame last acquired.
    \exception vpProjectiveException (notInitializedError) before the first acquire().
  */
  const vpProjectiveSession::vpFrame &getFrame() const;
  //! Starts again from the first frame.
  void rewind();
  //! The session replayed.
  const vpProjectiveSession &getSession() const { return m_session; }

private:
  vpProjectiveSession m_session;
  std::vector<unsigned int> m_order; // the frames replayed, in order
  size_t m_next;
  int m_current;
};

END_VISP_NAMESPACE

#endif
