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

#include <visp3/projective/vpProjectiveSessionWriter.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>

#include <unistd.h>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpTime.h>
#include <visp3/projective/vpProjectiveArmModel.h>

#include "core/vpProjectiveErrors.h"
#include "session/vpProjectiveSessionInternal.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveSessionWriter");

//! A temporary name beside \e path, ending like it (vpImageIo chooses the format by the extension).
std::string temporaryName(const std::string &path)
{
  const size_t slash = path.find_last_of('/');
  const std::string folder = slash == std::string::npos ? std::string() : path.substr(0, slash + 1);
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  return folder + ".tmp-" + std::to_string(static_cast<long>(getpid())) + "-" + base;
}

void renameOver(const std::string &from, const std::string &to, const std::string &where)
{
  if (std::rename(from.c_str(), to.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(from.c_str());
    fail(vpProjectiveException::fileError, where, "cannot write '" + to + "' (" + reason + ")");
  }
}
} // namespace

namespace vpProjectiveSessionInternal
{
void writeAtomically(const std::string &path, const std::string &text, const std::string &where)
{
  const std::string tmp = temporaryName(path);
  {
    std::ofstream file(tmp.c_str(), std::ios::binary | std::ios::trunc);
    if (!file) {
      fail(vpProjectiveException::fileError, where,
           "cannot write '" + path + "' (" + std::strerror(errno) +
               "); check that its folder exists and that you may write there");
    }
    file << text;
    file.flush();
    if (!file) {
      file.close();
      std::remove(tmp.c_str());
      fail(vpProjectiveException::fileError, where, "writing '" + path + "' failed (disk full?); nothing was written");
    }
  }
  renameOver(tmp, path, where);
}
} // namespace vpProjectiveSessionInternal

vpProjectiveSessionWriter::vpProjectiveSessionWriter(const std::string &folder,
                                                     const std::vector<vpProjectiveJoint::vpJointType> &types)
    : m_session(), m_frames(), m_saved(0), m_interval(25), m_seconds(1.0), m_lastSave(0.0), m_closed(false)
{
  const std::string where = at("vpProjectiveSessionWriter()");
  if (types.empty() || types.size() > vpProjectiveArmModel::maxJoints) {
    fail(vpProjectiveException::dimensionError, where,
         "a session needs 1 to " + std::to_string(vpProjectiveArmModel::maxJoints) + " joints, got " +
             std::to_string(types.size()));
  }
  for (vpProjectiveJoint::vpJointType type : types) {
    if (type != vpProjectiveJoint::REVOLUTE && type != vpProjectiveJoint::PRISMATIC) {
      fail(vpProjectiveException::invalidValueError, where, "a joint type is neither REVOLUTE nor PRISMATIC");
    }
  }
  if (folder.empty()) {
    fail(vpProjectiveException::fileError, where, "the session folder's name is empty");
  }
  std::error_code error;
  if (std::filesystem::exists(folder + "/session.json", error)) {
    fail(vpProjectiveException::fileError, where,
         "'" + folder +
             "' already holds a session (session.json); record into a new folder (a recording is never "
             "overwritten)");
  }
  for (const char *sub : {"", "/left", "/right"}) {
    const std::string path = folder + sub;
    std::filesystem::create_directories(path, error);
    if (error || !std::filesystem::is_directory(path)) {
      fail(vpProjectiveException::fileError, where,
           "cannot create the folder '" + path + "' (" + (error ? error.message() : std::string("not a folder")) +
               "); check the path and that you may write there");
    }
  }
  m_session.m_folder = folder;
  m_session.m_types = types;
  // An empty session.json at once: an unwritable folder is reported now, not at the first frame.
  vpProjectiveSessionInternal::writeAtomically(folder + "/session.json", m_session.toString(), where);
  m_lastSave = vpTime::measureTimeSecond();
}

vpProjectiveSessionWriter::~vpProjectiveSessionWriter()
{
  if (!m_closed && m_saved != m_session.getNumberOfFrames()) {
    try {
      save();
    } catch (...) {
      // A destructor does not throw: close() reports the error.
    }
  }
}

void vpProjectiveSessionWriter::setSaveInterval(unsigned int frames, double seconds)
{
  if (frames == 0 || !(seconds > 0.0)) {
    fail(vpProjectiveException::invalidValueError, at("setSaveInterval()"),
         "the save interval needs at least 1 frame and a positive time (infinity: no time bound)");
  }
  m_interval = frames;
  m_seconds = seconds;
}

void vpProjectiveSessionWriter::save()
{
  vpProjectiveSessionInternal::writeAtomically(m_session.getFolder() + "/session.json",
                                               vpProjectiveSessionInternal::sessionText(m_session, m_frames),
                                               at("save()"));
  m_saved = m_session.getNumberOfFrames();
  m_lastSave = vpTime::measureTimeSecond();
}

bool vpProjectiveSessionWriter::setCameras(const vpStereoImageSource &images)
{
  vpStereoImageSource::vpCameraIdentity left, right;
  if (!images.getCameraIdentities(left, right)) {
    return false;
  }
  setCameras(left, right);
  return true;
}

void vpProjectiveSessionWriter::setCameras(const vpStereoImageSource::vpCameraIdentity &left,
                                           const vpStereoImageSource::vpCameraIdentity &right)
{
  if (m_closed) {
    fail(vpProjectiveException::fileError, at("setCameras()"),
         "the session '" + m_session.getFolder() + "' was closed; set the cameras before closing it");
  }
  const vpStereoImageSource::vpCameraIdentity before[2] = {m_session.m_cameras[0], m_session.m_cameras[1]};
  m_session.m_cameras[0] = left;
  m_session.m_cameras[1] = right;
  try {
    save();
  } catch (...) {
    m_session.m_cameras[0] = before[0];
    m_session.m_cameras[1] = before[1];
    throw;
  }
}

void vpProjectiveSessionWriter::setCameraLayout(vpProjectiveCellFingerprint::vpCameraLayout layout)
{
  if (m_closed) {
    fail(vpProjectiveException::fileError, at("setCameraLayout()"),
         "the session '" + m_session.getFolder() + "' was closed; set the layout before closing it");
  }
  const vpProjectiveCellFingerprint::vpCameraLayout before = m_session.m_layout;
  m_session.m_layout = layout;
  try {
    save();
  } catch (...) {
    m_session.m_layout = before;
    throw;
  }
}

void vpProjectiveSessionWriter::close()
{
  if (!m_closed) {
    save();
    m_closed = true;
  }
}

template <typename Type>
unsigned int vpProjectiveSessionWriter::add(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t,
                                            const vpImage<Type> &Ileft, const vpImage<Type> &Iright,
                                            const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                                            const std::vector<vpImagePoint> &right)
{
  const std::string where = at("addFrame()");
  const unsigned int k = m_session.getNumberOfFrames();
  if (m_closed) {
    fail(vpProjectiveException::fileError, where,
         "the session '" + m_session.getFolder() + "' was closed; record into a new writer");
  }
  char name[32];
  std::snprintf(name, sizeof(name), "%06u.png", k);
  vpProjectiveSession::vpFrame frame;
  frame.role = role;
  frame.q = q;
  frame.hasTime = !std::isnan(t);
  frame.t = frame.hasTime ? t : 0.0;
  frame.left = std::string("left/") + name;
  frame.right = std::string("right/") + name;
  frame.markerIds = ids;
  frame.markerLeft = left;
  frame.markerRight = right;
  const int joint = m_session.checkFrame(frame, where, vpProjectiveSessionInternal::frameName(k, 0, frame.left));
  if (Ileft.getSize() == 0 || Iright.getSize() == 0) {
    fail(vpProjectiveException::fileError, where,
         vpProjectiveSessionInternal::frameName(k, 0, frame.left) + ": an image is empty; nothing written");
  }
  for (int side = 0; side < 2; ++side) {
    const std::string path = m_session.getFolder() + "/" + (side == 0 ? frame.left : frame.right);
    const std::string tmp = temporaryName(path);
    const std::string problem = vpProjectiveSessionInternal::writeImage(tmp, side == 0 ? Ileft : Iright);
    if (!problem.empty()) {
      std::remove(tmp.c_str());
      fail(vpProjectiveException::fileError, where,
           "cannot write the image '" + path + "' (" + problem + "); check the disk and permissions");
    }
    renameOver(tmp, path, where);
  }
  const size_t framesLength = m_frames.size();
  m_session.m_frames.push_back(frame);
  m_session.m_trialJoint.push_back(joint);
  if (role == vpProjectiveSession::ZERO) {
    m_session.m_zero = static_cast<int>(k);
  }
  vpProjectiveSessionInternal::appendFrame(m_frames, frame);
  const unsigned int pending = k + 1 - m_saved;
  if (pending >= std::max(m_interval, m_saved / 8) || vpTime::measureTimeSecond() - m_lastSave >= m_seconds) {
    try {
      save();
    } catch (...) {
      m_session.m_frames.pop_back(); // the images stay, unnamed by session.json
      m_session.m_trialJoint.pop_back();
      m_frames.resize(framesLength);
      if (role == vpProjectiveSession::ZERO) {
        m_session.m_zero = -1;
      }
      throw;
    }
  }
  if (k == 0) {
    m_session.m_width = Ileft.getWidth();
    m_session.m_height = Ileft.getHeight();
  }
  return k;
}

unsigned int vpProjectiveSessionWriter::addFrame(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t,
                                                 const vpImage<unsigned char> &Ileft,
                                                 const vpImage<unsigned char> &Iright)
{
  return add(role, q, t, Ileft, Iright);
}

unsigned int vpProjectiveSessionWriter::addFrame(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t,
                                                 const vpImage<vpRGBa> &Ileft, const vpImage<vpRGBa> &Iright)
{
  return add(role, q, t, Ileft, Iright);
}

unsigned int vpProjectiveSessionWriter::addFrame(vpProjectiveSession::vpFrameRole role, const vpColVector &q, double t,
                                                 const vpImage<unsigned char> &Ileft,
                                                 const vpImage<unsigned char> &Iright, const std::vector<int> &ids,
                                                 const std::vector<vpImagePoint> &left,
                                                 const std::vector<vpImagePoint> &right)
{
  return add(role, q, t, Ileft, Iright, ids, left, right);
}

vpProjectiveSession::vpFrameRole vpProjectiveSessionWriter::addAcquisitionFrame(const vpColVector &q, double t,
                                                                                const vpImage<unsigned char> &Ileft,
                                                                                const vpImage<unsigned char> &Iright)
{
  vpProjectiveSession::vpFrameRole role = vpProjectiveSession::ZERO;
  if (m_session.m_zero >= 0) {
    role = vpProjectiveSession::OBSERVATION;
    const vpColVector &q0 = m_session.m_frames[static_cast<size_t>(m_session.m_zero)].q;
    std::string why;
    const int joint = q.getRows() == q0.getRows() ? vpProjectiveSessionInternal::trialJoint(q0, q, why) : -1;
    // A motion below 1e-3 (rad or m) is the arm back at the zero reference within its encoders' noise, not a trial.
    if (joint >= 0 && std::fabs(q[static_cast<unsigned int>(joint)] - q0[static_cast<unsigned int>(joint)]) >= 1e-3) {
      role = vpProjectiveSession::TRIAL;
    }
  }
  add(role, q, t, Ileft, Iright);
  return role;
}
