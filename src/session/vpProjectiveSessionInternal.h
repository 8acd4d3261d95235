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

/*
  Private: what the session's reader, writer and tools share. Not installed.
*/

#ifndef _vpProjectiveSessionInternal_h_
#define _vpProjectiveSessionInternal_h_

#include <algorithm>
#include <string>
#include <utility>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpRGBa.h>
#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>

#include "core/vpProjectiveErrors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveSessionInternal
{
/*!
  Checks that \e path is an 8-bit grey or RGB PNG by its header (signature, IHDR) and that its chunks are complete up
  to IEND (a truncated file), and gives its size; returns what is wrong ("is missing or cannot be opened", ...), empty
  if nothing. The pixels are not decoded.
*/
std::string checkPngFile(const std::string &path, unsigned int &width, unsigned int &height);

/*!
  The joint that readings \e q moved from the zero frame's \e q0 (same sizes), or -1 with \e why saying what is wrong:
  no joint moved, or another joint moved by more than 1 % of the largest motion.
*/
int trialJoint(const vpColVector &q0, const vpColVector &q, std::string &why);

/*!
  How every message and progress line names frame \e k (its index in session.json, from 0) of a session of \e total
  frames: counted from 1, "frame 3/13 ('left/000002.png', trial)", or "frame 3 (...)" when \e total is 0 (not known
  yet: a recording); the parenthesis holds \e left and \e role, those given.
*/
std::string frameName(unsigned int k, unsigned int total, const std::string &left = std::string(),
                      const std::string &role = std::string());

/*!
  Appends the JSON text of \e frame (one line) to \e frames, the text of a session's frame list: what
  sessionText() puts between the brackets of "frames". Each frame is serialised once (the writer keeps the text).
*/
void appendFrame(std::string &frames, const vpProjectiveSession::vpFrame &frame);

/*!
  The text of the session.json of \e session (its joints, cameras and layout) with the frame list \e frames
  (appendFrame()'s): a JSON object, one line per frame.
*/
std::string sessionText(const vpProjectiveSession &session, const std::string &frames);

/*!
  Reads the image file \e path into \e I (vpImageIo); returns what is wrong on one line (ViSP's message, an empty
  image, a ViSP without the io module), empty if nothing.
*/
std::string readImage(const std::string &path, vpImage<unsigned char> &I);

//! Writes \e I to the image file \e path (vpImageIo, the format by the extension); returns what is wrong, empty if
//! nothing.
std::string writeImage(const std::string &path, const vpImage<unsigned char> &I);
std::string writeImage(const std::string &path, const vpImage<vpRGBa> &I);

/*!
  Writes \e text to \e path atomically: to a temporary file in the same folder, then renamed over \e path, so that
  \e path is either as before or complete. Throws vpProjectiveException (fileError) naming \e path, \e where.
*/
void writeAtomically(const std::string &path, const std::string &text, const std::string &where);

// What the calibration and the check of a session share (vpProjectiveSessionMarkers.cpp).

//! The error site of vpProjectiveSessionCalibration, whose sources are vpProjectiveSessionCalibration.cpp,
//! vpProjectiveSessionMarkers.cpp and vpProjectiveSessionCheck.cpp.
const vpProjectiveInternal::vpErrorSite calibrationAt("vpProjectiveSessionCalibration");

//! The markers of one frame: identifiers (ascending) and pixels (u, v, u', v').
struct FrameMarkers {
  std::vector<int> ids;
  std::vector<Eigen::Vector4d> s;
  //! Index of marker \e id in this frame, -1 if absent.
  int find(int id) const
  {
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    return it != ids.end() && *it == id ? static_cast<int>(it - ids.begin()) : -1;
  }
};

//! How messages and progress lines name frame \e k of \e session: frameName() with its left image and role.
std::string frameLabel(const vpProjectiveSession &session, unsigned int k);

//! The markers of frame \e k by the extraction function, checked. Throws (naming \e where and the frame) if it fails or
//! gives bad markers.
FrameMarkers extract(const vpProjectiveSession &session, unsigned int k,
                     const vpProjectiveSessionCalibration::vpMarkerExtractor &extractor, bool recorded,
                     const std::string &where);

//! Readings of a frame as the model's joint vector.
vpProjectiveArmModel::JointVector jointsOf(const vpColVector &q);

/*!
  Squared prediction errors of \e model at readings \e q for the pairs (model marker j, measured s): adds the left
  and right squared errors and the number of markers. A marker on a camera's focal plane counts as 1e6 px.
*/
void predictionError(const vpProjectiveArmModel &model, const vpColVector &q,
                     const std::vector<std::pair<unsigned int, Eigen::Vector4d>> &pairs, double &left, double &right,
                     unsigned int &count);

//! Root mean square of \e coordinates coordinates whose squares sum to \e sumSquares (0 for none).
double rms(double sumSquares, unsigned int coordinates);

//! \e px as "1.23 px".
std::string pixels(double px);

// What check() gives its diagnosis (vpProjectiveSessionDiagnosis.cpp).

//! A frame of a check: its readings and the model's markers seen in it (model marker index, measured pixels).
struct CheckedFrame {
  vpColVector q;                            //!< the readings
  vpProjectiveArmModel::JointVector joints; //!< the same as the model's joint vector
  std::vector<std::pair<unsigned int, Eigen::Vector4d>> pairs;
};

//! What check() measured: the frames, the errors, and what the session shows of the model's markers.
struct MismatchInput {
  const vpProjectiveArmModel &model;
  const std::vector<int> &ids;
  const vpProjectiveSession &session;
  const vpProjectiveCellFingerprint &cell;
  std::vector<CheckedFrame> frames;
  double threshold;                   //!< the mismatch threshold (px)
  unsigned int leftOff, rightOff;     //!< frames whose left (right) images are off
  double leftResidual, rightResidual; //!< RMS per coordinate over the frames (px)
  size_t modelIdsSeen;                //!< the model's markers seen in some frame
  size_t otherIds;                    //!< markers seen that the model does not have
};

/*!
  The probable causes of frames that do not fit, ranked likeliest first (see vpProjectiveSessionCalibration::check());
  \e in has at least one frame off.
*/
std::vector<vpProjectiveSessionCalibration::vpCheckDiagnosis> diagnoseMismatch(const MismatchInput &in);

//! A cause in a few words ("exchanged images", "the left camera moved", ...).
std::string causeName(vpProjectiveSessionCalibration::vpRigState cause);
} // namespace vpProjectiveSessionInternal

#endif
