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
  The session format's pieces that the reader (vpProjectiveSession.cpp) and the writer share: the PNG header check,
  the image files, a frame's JSON text, the session.json text, the joint a trial moved.
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
#ifdef VISP_HAVE_MODULE_IO
#include <visp3/io/vpImageIo.h>
#endif

#include "robot/vpCameraIdentityJson.h"
#include "core/vpProjectiveErrors.h"
#include "session/vpProjectiveSessionInternal.h"

using namespace vpProjectiveInternal;

namespace vpProjectiveSessionInternal
{
using json = nlohmann::json;

namespace
{
//! vpImageIo's call \e io; what it threw, on one line, or that this ViSP has no io module.
template <typename Io> std::string imageProblem(Io io)
{
  std::string problem;
#ifdef VISP_HAVE_MODULE_IO
  try {
    io();
  } catch (const vpException &e) {
    problem = e.getStringMessage();
  } catch (const std::exception &e) {
    problem = e.what();
  }
#else
  (void)io;
  problem = "this ViSP has no io module (vpImageIo)";
#endif
  for (char &c : problem) {
    c = (c == '\n' || c == '\r') ? ' ' : c;
  }
  return problem;
}

template <typename Type> std::string writeImageOf(const std::string &path, const vpImage<Type> &I)
{
#ifdef VISP_HAVE_MODULE_IO
  return imageProblem([&] { vpImageIo::write(I, path); });
#else
  (void)path;
  (void)I;
  return imageProblem(0);
#endif
}
} // namespace

std::string readImage(const std::string &path, vpImage<unsigned char> &I)
{
#ifdef VISP_HAVE_MODULE_IO
  const std::string problem = imageProblem([&] { vpImageIo::read(I, path); });
#else
  (void)path;
  const std::string problem = imageProblem(0);
#endif
  return problem.empty() && I.getSize() == 0 ? std::string("empty image") : problem;
}

std::string writeImage(const std::string &path, const vpImage<unsigned char> &I)
{
  return writeImageOf(path, I);
}

std::string writeImage(const std::string &path, const vpImage<vpRGBa> &I)
{
  return writeImageOf(path, I);
}

std::string checkPngFile(const std::string &path, unsigned int &width, unsigned int &height)
{
  std::ifstream file(path.c_str(), std::ios::binary);
  if (!file) {
    return "is missing or cannot be opened";
  }
  unsigned char h[33];
  file.read(reinterpret_cast<char *>(h), sizeof(h));
  if (file.gcount() != static_cast<std::streamsize>(sizeof(h))) {
    return "is too short to be a PNG image (empty or truncated file)";
  }
  const unsigned char signature[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1a, '\n'};
  for (int i = 0; i < 8; ++i) {
    if (h[i] != signature[i]) {
      return "is not a PNG image";
    }
  }
  if (h[12] != 'I' || h[13] != 'H' || h[14] != 'D' || h[15] != 'R') {
    return "is a damaged PNG image (no IHDR header)";
  }
  auto be32 = [&h](int i) {
    return (static_cast<unsigned int>(h[i]) << 24) | (static_cast<unsigned int>(h[i + 1]) << 16) |
           (static_cast<unsigned int>(h[i + 2]) << 8) | static_cast<unsigned int>(h[i + 3]);
  };
  width = be32(16);
  height = be32(20);
  const unsigned int depth = h[24], colour = h[25];
  if (width == 0 || height == 0 || width > 100000 || height > 100000) {
    return "is a PNG image of an invalid size";
  }
  if (depth != 8 || (colour != 0 && colour != 2)) {
    return "is a PNG image of bit depth " + std::to_string(depth) + " and colour type " + std::to_string(colour) +
           ", not 8-bit grey or RGB; save it as an 8-bit grey or RGB PNG";
  }
  // The chunks up to IEND fit in the file: a truncated image is named here, before the PNG decoder meets its end
  // (libpng would print its own "Read Error" on the standard error).
  file.clear();
  file.seekg(0, std::ios::end);
  const std::streamoff size = file.tellg();
  std::streamoff chunk = 8; // after the signature
  while (true) {
    unsigned char c[8];
    file.seekg(chunk);
    file.read(reinterpret_cast<char *>(c), sizeof(c));
    if (file.gcount() != static_cast<std::streamsize>(sizeof(c))) {
      return "is a truncated PNG image (it ends before its end marker IEND); record or copy it again";
    }
    const std::streamoff length = (static_cast<std::streamoff>(c[0]) << 24) |
                                  (static_cast<std::streamoff>(c[1]) << 16) | (static_cast<std::streamoff>(c[2]) << 8) |
                                  static_cast<std::streamoff>(c[3]);
    chunk += 12 + length; // length, type, data, CRC
    if (chunk > size) {
      return "is a truncated PNG image (a chunk runs past the end of the file); record or copy it again";
    }
    if (c[4] == 'I' && c[5] == 'E' && c[6] == 'N' && c[7] == 'D') {
      return std::string();
    }
  }
}

std::string frameName(unsigned int k, unsigned int total, const std::string &left, const std::string &role)
{
  std::string name = "frame " + std::to_string(k + 1) + (total > 0 ? "/" + std::to_string(total) : std::string());
  const std::string image = left.empty() ? std::string() : "'" + left + "'";
  const std::string details = image + (!image.empty() && !role.empty() ? ", " : "") + role;
  return details.empty() ? name : name + " (" + details + ")";
}

void appendFrame(std::string &frames, const vpProjectiveSession::vpFrame &frame)
{
  json f;
  f["role"] = vpProjectiveSession::toString(frame.role);
  json q = json::array();
  for (unsigned int i = 0; i < frame.q.getRows(); ++i) {
    q.push_back(frame.q[i]);
  }
  f["q"] = q;
  if (frame.hasTime) {
    f["t"] = frame.t;
  }
  f["left"] = frame.left;
  f["right"] = frame.right;
  if (!frame.markerIds.empty()) {
    json ids = json::array(), left = json::array(), right = json::array();
    for (size_t j = 0; j < frame.markerIds.size(); ++j) {
      ids.push_back(frame.markerIds[j]);
      left.push_back({frame.markerLeft[j].get_u(), frame.markerLeft[j].get_v()});
      right.push_back({frame.markerRight[j].get_u(), frame.markerRight[j].get_v()});
    }
    f["recorded_markers"] = {{"ids", ids}, {"left", left}, {"right", right}};
  }
  frames += (frames.empty() ? "\n  " : ",\n  ") + f.dump();
}

std::string sessionText(const vpProjectiveSession &session, const std::string &frames)
{
  json typeNames = json::array();
  for (vpProjectiveJoint::vpJointType type : session.getJointTypes()) {
    typeNames.push_back(vpProjectiveJoint::name(type));
  }
  std::string cameras;
  if (session.hasCameras()) {
    cameras += ",\n \"cameras\": " + camerasToJson(session.getLeftCamera(), session.getRightCamera()).dump();
  }
  if (session.getCameraLayout() != vpProjectiveCellFingerprint::LAYOUT_LEFT_RIGHT) {
    cameras += ", \"camera_layout\": " + json(vpProjectiveCellFingerprint::toString(session.getCameraLayout())).dump();
  }
  return std::string("{\"format\": ") + json(vpProjectiveSession::formatName).dump() +
         ", \"version\": " + std::to_string(vpProjectiveSession::version) + ", \"joint_types\": " + typeNames.dump() +
         cameras + ",\n \"frames\": [" + frames + "\n]}\n";
}

int trialJoint(const vpColVector &q0, const vpColVector &q, std::string &why)
{
  unsigned int moved = 0;
  double largest = 0.0;
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    if (std::fabs(q[i] - q0[i]) > largest) {
      largest = std::fabs(q[i] - q0[i]);
      moved = i;
    }
  }
  if (!(largest > 0.0)) {
    why = "it moves no joint (its readings are the zero frame's); give it the role 'observation' or remove it";
    return -1;
  }
  for (unsigned int i = 0; i < q.getRows(); ++i) {
    if (i != moved && std::fabs(q[i] - q0[i]) > 0.01 * largest) {
      why = "it moves joints " + std::to_string(moved) + " and " + std::to_string(i) +
            " (a trial moves one joint alone from the zero frame's readings); give it the role 'observation' or "
            "record the trial again";
      return -1;
    }
  }
  return static_cast<int>(moved);
}
} // namespace vpProjectiveSessionInternal
