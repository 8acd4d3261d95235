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

#include <visp3/projective/vpProjectiveSession.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveArmModel.h>

#include "robot/vpCameraIdentityJson.h"
#include "core/vpProjectiveErrors.h"
#include "session/vpProjectiveSessionInternal.h"

using namespace vpProjectiveInternal;
using vpProjectiveSessionInternal::frameName;

const char *const vpProjectiveSession::formatName = "visp-projective-session";

namespace
{
using json = nlohmann::json;

const vpErrorSite at("vpProjectiveSession");

const char *const kRoles[] = {"zero", "trial", "observation", "target", "servo"};

//! Reads the entries of session.json, each error a fileError naming the file.
class Reader
{
public:
  explicit Reader(const std::string &name) : m_name(name) {}

  [[noreturn]] void bad(const std::string &what) const
  {
    fail(vpProjectiveException::fileError, at("read()"), "cannot read the session '" + m_name + "': " + what);
  }

  const json &member(const json &object, const char *key, const std::string &owner) const
  {
    if (!object.is_object() || !object.contains(key)) {
      bad(owner + " has no '" + key +
          "' entry; add it (see the session format in vpProjectiveSession's documentation)");
    }
    return object[key];
  }

  const std::string &name() const { return m_name; }

private:
  std::string m_name;
};

//! The optional "recorded_markers" entry of a frame: {"ids": [...], "left": [[u, v], ...], "right": [[u, v], ...]}.
void readMarkers(const Reader &reader, const json &m, const std::string &label, vpProjectiveSession::vpFrame &frame)
{
  const std::string what = label + ": 'recorded_markers' must be {\"ids\": [...], \"left\": [[u, v], ...], \"right\": "
                                   "[[u, v], ...]} with one identifier and one finite pixel per image for each marker";
  if (!m.is_object() || !m.contains("ids") || !m.contains("left") || !m.contains("right") || !m["ids"].is_array() ||
      !m["left"].is_array() || !m["right"].is_array() || m["left"].size() != m["ids"].size() ||
      m["right"].size() != m["ids"].size()) {
    reader.bad(what);
  }
  for (size_t j = 0; j < m["ids"].size(); ++j) {
    const json &id = m["ids"][j];
    if (!id.is_number_integer() || id.get<long long>() < 0 || id.get<long long>() > 1000000000LL) {
      reader.bad(what);
    }
    frame.markerIds.push_back(static_cast<int>(id.get<long long>()));
    for (int side = 0; side < 2; ++side) {
      const json &p = m[side == 0 ? "left" : "right"][j];
      if (!p.is_array() || p.size() != 2 || !p[0].is_number() || !p[1].is_number()) {
        reader.bad(what);
      }
      (side == 0 ? frame.markerLeft : frame.markerRight)
          .push_back(vpImagePoint(p[1].get<double>(), p[0].get<double>()));
    }
  }
}

//! True if \e path is relative and stays inside the folder (no "..", no absolute path, no empty component).
bool insideFolder(const std::string &path)
{
  if (path.empty() || path[0] == '/' || path.find('\\') != std::string::npos || path.find('\0') != std::string::npos) {
    return false;
  }
  std::istringstream parts(path);
  std::string part;
  while (std::getline(parts, part, '/')) {
    if (part.empty() || part == "..") {
      return false;
    }
  }
  return path.back() != '/';
}
} // namespace

vpProjectiveSession::vpProjectiveSession()
    : m_folder(), m_types(), m_frames(), m_trialJoint(), m_zero(-1), m_width(0), m_height(0), m_cameras(),
      m_layout(vpProjectiveCellFingerprint::LAYOUT_LEFT_RIGHT)
{
}

std::string vpProjectiveSession::toString(vpFrameRole role)
{
  return kRoles[static_cast<int>(role)];
}

int vpProjectiveSession::checkFrame(const vpFrame &frame, const std::string &where, const std::string &what) const
{
  const std::string name = what;
  if (static_cast<int>(frame.role) < static_cast<int>(ZERO) || static_cast<int>(frame.role) > static_cast<int>(SERVO)) {
    fail(vpProjectiveException::fileError, where, name + " has an unknown role; use one of vpFrameRole's values");
  }
  if (frame.q.getRows() != m_types.size()) {
    fail(vpProjectiveException::fileError, where,
         name + " has " + std::to_string(frame.q.getRows()) + " readings in 'q', the session has " +
             std::to_string(m_types.size()) + " joints (joint_types); give one encoder reading per joint");
  }
  for (unsigned int i = 0; i < frame.q.getRows(); ++i) {
    if (!std::isfinite(frame.q[i])) {
      fail(vpProjectiveException::fileError, where,
           name + ": reading " + std::to_string(i) + " of 'q' is not finite; record the encoders again");
    }
  }
  if (frame.hasTime && !std::isfinite(frame.t)) {
    fail(vpProjectiveException::fileError, where, name + ": its time 't' is not finite; fix or remove it");
  }
  if (!insideFolder(frame.left) || !insideFolder(frame.right)) {
    fail(vpProjectiveException::fileError, where,
         name + ": its image paths must be relative paths inside the session folder (no '..', no absolute path)");
  }
  if (frame.markerLeft.size() != frame.markerIds.size() || frame.markerRight.size() != frame.markerIds.size()) {
    fail(vpProjectiveException::fileError, where,
         name + " has " + std::to_string(frame.markerIds.size()) + " recorded marker identifiers, " +
             std::to_string(frame.markerLeft.size()) + " left and " + std::to_string(frame.markerRight.size()) +
             " right pixels; give one of each per marker");
  }
  for (size_t j = 0; j < frame.markerIds.size(); ++j) {
    if (frame.markerIds[j] < 0 || (j > 0 && frame.markerIds[j] <= frame.markerIds[j - 1])) {
      fail(vpProjectiveException::fileError, where,
           name + ": the recorded markers' identifiers must be non-negative, ascending and distinct");
    }
    const vpImagePoint &l = frame.markerLeft[j], &r = frame.markerRight[j];
    if (!std::isfinite(l.get_u()) || !std::isfinite(l.get_v()) || !std::isfinite(r.get_u()) ||
        !std::isfinite(r.get_v())) {
      fail(vpProjectiveException::fileError, where,
           name + ": recorded marker " + std::to_string(frame.markerIds[j]) + " has a non-finite pixel");
    }
  }
  if (frame.role == ZERO && m_zero >= 0) {
    fail(vpProjectiveException::fileError, where,
         name + " is a second zero frame (" +
             frameName(static_cast<unsigned int>(m_zero), 0, m_frames[static_cast<size_t>(m_zero)].left) +
             " is the first); a session has exactly one: give the others the role 'observation'");
  }
  if (frame.role != TRIAL) {
    return -1;
  }
  if (m_zero < 0) {
    fail(vpProjectiveException::fileError, where,
         name + " is a trial, but the session has no zero frame; add the zero reference's frame with the role 'zero'");
  }
  std::string why;
  const int joint = vpProjectiveSessionInternal::trialJoint(m_frames[static_cast<size_t>(m_zero)].q, frame.q, why);
  if (joint < 0) {
    fail(vpProjectiveException::fileError, where, name + " is a trial, but " + why);
  }
  return joint;
}

vpProjectiveSession vpProjectiveSession::fromString(const std::string &text, const std::string &name)
{
  const Reader reader(name);
  json file;
  try {
    file = json::parse(text);
  } catch (const json::exception &e) {
    reader.bad(std::string("it is not valid JSON (truncated or damaged file?): ") + e.what());
  }
  if (!file.is_object()) {
    reader.bad("it is not a JSON object; a session.json starts with { \"format\": \"visp-projective-session\", ...");
  }
  const json &format = reader.member(file, "format", "the file");
  if (!format.is_string() || format.get<std::string>() != formatName) {
    reader.bad(std::string("its format is ") + format.dump() + ", not \"" + formatName + "\"; it is not a session");
  }
  const json &v = reader.member(file, "version", "the file");
  if (!v.is_number_integer() || v.get<long long>() != version) {
    reader.bad("it has version " + v.dump() + ", this build reads version " + std::to_string(version) +
               "; read it with the build that recorded it, or record it again");
  }
  const json &types = reader.member(file, "joint_types", "the file");
  if (!types.is_array() || types.empty() || types.size() > vpProjectiveArmModel::maxJoints) {
    reader.bad("'joint_types' must be an array of 1 to " + std::to_string(vpProjectiveArmModel::maxJoints) +
               " joint types (\"revolute\" or \"prismatic\")");
  }
  vpProjectiveSession session;
  for (size_t i = 0; i < types.size(); ++i) {
    if (types[i] == vpProjectiveJoint::name(vpProjectiveJoint::REVOLUTE)) {
      session.m_types.push_back(vpProjectiveJoint::REVOLUTE);
    } else if (types[i] == vpProjectiveJoint::name(vpProjectiveJoint::PRISMATIC)) {
      session.m_types.push_back(vpProjectiveJoint::PRISMATIC);
    } else {
      reader.bad("joint " + std::to_string(i) + " has the type " + types[i].dump() +
                 "; use \"revolute\" or \"prismatic\"");
    }
  }
  if (file.contains("cameras") && !camerasFromJson(file["cameras"], session.m_cameras[0], session.m_cameras[1])) {
    reader.bad("'cameras' must be {\"left\": {...}, \"right\": {...}}, each camera's device, name, bus and serial "
               "a string (those not known left out)");
  }
  if (file.contains("camera_layout")) {
    const json &layout = file["camera_layout"];
    if (layout != "left-right" && layout != "any") {
      reader.bad("'camera_layout' is " + layout.dump() +
                 "; use \"left-right\" (upright cameras, the left one on the left) or \"any\"");
    }
    session.m_layout =
        layout == "any" ? vpProjectiveCellFingerprint::LAYOUT_ANY : vpProjectiveCellFingerprint::LAYOUT_LEFT_RIGHT;
  }
  const json &frames = reader.member(file, "frames", "the file");
  if (!frames.is_array() || frames.empty()) {
    reader.bad("'frames' must be a non-empty array of frames (at least the zero frame)");
  }
  // First pass: each frame on its own; the zero frame found.
  std::vector<vpFrame> parsed(frames.size());
  const unsigned int count = static_cast<unsigned int>(frames.size());
  int zero = -1;
  for (size_t k = 0; k < frames.size(); ++k) {
    const json &f = frames[k];
    const unsigned int index = static_cast<unsigned int>(k);
    std::string label = frameName(index, count);
    if (!f.is_object()) {
      reader.bad(label + " is not a JSON object");
    }
    const json &left = reader.member(f, "left", label);
    const json &right = reader.member(f, "right", label);
    if (!left.is_string() || !right.is_string()) {
      reader.bad(label + ": 'left' and 'right' must be image paths (strings) relative to the session folder");
    }
    vpFrame &frame = parsed[k];
    frame.left = left.get<std::string>();
    frame.right = right.get<std::string>();
    label = frameName(index, count, frame.left);
    const json &role = reader.member(f, "role", label);
    bool known = false;
    for (int r = 0; r < 5 && role.is_string(); ++r) {
      if (role == kRoles[r]) {
        frame.role = static_cast<vpFrameRole>(r);
        known = true;
      }
    }
    if (!known) {
      reader.bad(label + " has the role " + role.dump() +
                 "; use \"zero\", \"trial\", \"observation\", \"target\" or \"servo\"");
    }
    const json &q = reader.member(f, "q", label);
    if (!q.is_array()) {
      reader.bad(label + ": 'q' must be an array of encoder readings, one per joint");
    }
    frame.q.resize(static_cast<unsigned int>(std::min<size_t>(q.size(), 1000)));
    for (unsigned int i = 0; i < frame.q.getRows(); ++i) {
      if (!q[i].is_number()) {
        reader.bad(label + ": reading " + std::to_string(i) + " of 'q' is " + q[i].dump() +
                   ", not a finite number; record the encoders again");
      }
      frame.q[i] = q[i].get<double>();
    }
    if (q.size() > 1000) {
      frame.q.resize(1001, false); // the length check below names the mismatch
    }
    frame.hasTime = f.contains("t");
    frame.t = 0.0;
    if (frame.hasTime) {
      if (!f["t"].is_number()) {
        reader.bad(label + ": its time 't' must be a number of seconds (or be left out)");
      }
      frame.t = f["t"].get<double>();
    }
    if (f.contains("recorded_markers")) {
      readMarkers(reader, f["recorded_markers"], label, frame);
    }
    if (frame.role == ZERO) {
      if (zero >= 0) {
        reader.bad(label + " is a second zero frame (" +
                   frameName(static_cast<unsigned int>(zero), count, parsed[static_cast<size_t>(zero)].left) +
                   " is the first); a session has exactly one: give the others the role 'observation'");
      }
      zero = static_cast<int>(k);
    }
  }
  if (zero < 0) {
    reader.bad("it has no zero frame (role \"zero\"); a session has exactly one: the frame at the zero reference");
  }
  // Second pass: each frame against the session, the zero frame first.
  const std::string where = at("read()");
  const std::string prefix = "cannot read the session '" + name + "': ";
  const size_t z = static_cast<size_t>(zero);
  session.checkFrame(parsed[z], where, prefix + frameName(static_cast<unsigned int>(z), count, parsed[z].left));
  session.m_frames = parsed;
  session.m_zero = zero;
  for (size_t k = 0; k < parsed.size(); ++k) {
    const int joint = k == z
                          ? -1
                          : session.checkFrame(parsed[k], where,
                                               prefix + frameName(static_cast<unsigned int>(k), count, parsed[k].left));
    session.m_trialJoint.push_back(joint);
  }
  return session;
}

vpProjectiveSession vpProjectiveSession::read(const std::string &folder, bool checkImages)
{
  const std::string path = folder + "/session.json";
  std::ifstream file(path.c_str(), std::ios::binary);
  if (!file) {
    fail(vpProjectiveException::fileError, at("read()"),
         "cannot open '" + path + "'; check that '" + folder + "' is a session folder (it holds session.json)");
  }
  std::ostringstream text;
  text << file.rdbuf();
  if (!file.good() && !file.eof()) {
    fail(vpProjectiveException::fileError, at("read()"), "cannot read '" + path + "' (an I/O error)");
  }
  vpProjectiveSession session = fromString(text.str(), path);
  session.m_folder = folder;
  unsigned int size[2][2] = {{0, 0}, {0, 0}};
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    for (int side = 0; side < 2; ++side) {
      const std::string &relative = side == 0 ? session.m_frames[k].left : session.m_frames[k].right;
      const std::string image = folder + "/" + relative;
      unsigned int w = 0, h = 0;
      const std::string problem = vpProjectiveSessionInternal::checkPngFile(image, w, h);
      if (!problem.empty()) {
        fail(vpProjectiveException::fileError, at("read()"),
             "cannot read the session '" + path +
                 "': " + frameName(k, session.getNumberOfFrames(), session.m_frames[k].left) + ": the " +
                 (side == 0 ? "left" : "right") + " image '" + image + "' " + problem +
                 "; record the frame again or remove it from session.json");
      }
      if (k == 0) {
        size[side][0] = w;
        size[side][1] = h;
      } else if (w != size[side][0] || h != size[side][1]) {
        fail(vpProjectiveException::fileError, at("read()"),
             "cannot read the session '" + path +
                 "': " + frameName(k, session.getNumberOfFrames(), session.m_frames[k].left) + ": the " +
                 (side == 0 ? "left" : "right") + " image '" + image + "' is " + std::to_string(w) + " x " +
                 std::to_string(h) + " pixels, the first frame's is " + std::to_string(size[side][0]) + " x " +
                 std::to_string(size[side][1]) + "; every frame of a camera must have the same size");
      }
    }
    if (checkImages) {
      vpImage<unsigned char> Il, Ir;
      session.getImages(k, Il, Ir);
    }
  }
  session.m_width = size[0][0];
  session.m_height = size[0][1];
  return session;
}

std::string vpProjectiveSession::toString() const
{
  std::string frames;
  for (const vpFrame &frame : m_frames) {
    vpProjectiveSessionInternal::appendFrame(frames, frame);
  }
  return vpProjectiveSessionInternal::sessionText(*this, frames);
}

const vpProjectiveSession::vpFrame &vpProjectiveSession::getFrame(unsigned int k) const
{
  if (k >= m_frames.size()) {
    fail(vpProjectiveException::dimensionError, at("getFrame()"),
         "frame " + std::to_string(k) + " does not exist: the session has " + std::to_string(m_frames.size()));
  }
  return m_frames[k];
}

unsigned int vpProjectiveSession::getZeroFrame() const
{
  if (m_zero < 0) {
    fail(vpProjectiveException::notInitializedError, at("getZeroFrame()"),
         "the session has no zero frame; read a session or add the zero frame first");
  }
  return static_cast<unsigned int>(m_zero);
}

int vpProjectiveSession::getTrialJoint(unsigned int k) const
{
  return k < m_trialJoint.size() ? m_trialJoint[k] : -1;
}

unsigned int vpProjectiveSession::getNumberOfFrames(vpFrameRole role) const
{
  unsigned int count = 0;
  for (const vpFrame &frame : m_frames) {
    count += frame.role == role ? 1 : 0;
  }
  return count;
}

std::string vpProjectiveSession::getImagePath(unsigned int k, bool left) const
{
  const vpFrame &frame = getFrame(k);
  return (m_folder.empty() ? std::string() : m_folder + "/") + (left ? frame.left : frame.right);
}

void vpProjectiveSession::getImages(unsigned int k, vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright) const
{
  const vpFrame &frame = getFrame(k);
  for (int side = 0; side < 2; ++side) {
    const std::string path = getImagePath(k, side == 0);
    const std::string problem = vpProjectiveSessionInternal::readImage(path, side == 0 ? Ileft : Iright);
    if (!problem.empty()) {
      fail(vpProjectiveException::fileError, at("getImages()"),
           "cannot read the " + std::string(side == 0 ? "left" : "right") + " image '" + path + "' of " +
               frameName(k, getNumberOfFrames(), frame.left) + " (" + problem +
               "); record the frame again or remove it from session.json");
    }
  }
}
