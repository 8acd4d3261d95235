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
  Private: the JSON of a pair of camera identities, as a session (session.json) and a model file (its "cell" entry)
  write it: {"left": {"device": ..., "name": ..., "bus": ..., "serial": ...}, "right": {...}}, empty fields left out;
  and the model file's "cell" entry (vpProjectiveModelFile reads it back, checked). Not installed.
*/

#ifndef _vpCameraIdentityJson_h_
#define _vpCameraIdentityJson_h_

#include <string>

#include <nlohmann/json.hpp>

#include <visp3/projective/vpProjectiveCellFingerprint.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
//! The fields of an identity, in the JSON's names.
inline std::string *identityField(vpStereoImageSource::vpCameraIdentity &camera, int field, const char *&key)
{
  static const char *const keys[] = {"device", "name", "bus", "serial"};
  std::string *fields[] = {&camera.device, &camera.name, &camera.bus, &camera.serial};
  key = keys[field];
  return fields[field];
}

//! The JSON of the identities of the left and right cameras.
inline nlohmann::json camerasToJson(vpStereoImageSource::vpCameraIdentity left,
                                    vpStereoImageSource::vpCameraIdentity right)
{
  nlohmann::json cameras;
  for (int side = 0; side < 2; ++side) {
    nlohmann::json identity = nlohmann::json::object();
    for (int f = 0; f < 4; ++f) {
      const char *key = nullptr;
      const std::string *value = identityField(side == 0 ? left : right, f, key);
      if (!value->empty()) {
        identity[key] = *value;
      }
    }
    cameras[side == 0 ? "left" : "right"] = identity;
  }
  return cameras;
}

//! The identities of \e cameras (camerasToJson()'s); false if it is not such an object (the identities untouched).
inline bool camerasFromJson(const nlohmann::json &cameras, vpStereoImageSource::vpCameraIdentity &left,
                            vpStereoImageSource::vpCameraIdentity &right)
{
  vpStereoImageSource::vpCameraIdentity read[2];
  for (int side = 0; side < 2; ++side) {
    const char *name = side == 0 ? "left" : "right";
    if (!cameras.is_object() || !cameras.contains(name) || !cameras[name].is_object()) {
      return false;
    }
    for (int f = 0; f < 4; ++f) {
      const char *key = nullptr;
      std::string *value = identityField(read[side], f, key);
      if (cameras[name].contains(key)) {
        if (!cameras[name][key].is_string()) {
          return false;
        }
        *value = cameras[name][key].get<std::string>();
      }
    }
  }
  left = read[0];
  right = read[1];
  return true;
}
//! The names of vpProjectiveCellFingerprint::vpCameraSide in a model file's "cell" entry, in the enum's order.
inline const char *const *cameraSideNames()
{
  static const char *const names[] = {"unknown", "right", "left", "above-below"};
  return names;
}

//! The vpProjectiveCellFingerprint::vpCameraSide named \e name in a "cell" entry; -1 if it names none.
inline int cameraSideOf(const nlohmann::json &name)
{
  for (int k = 0; k < 4; ++k) {
    if (name == cameraSideNames()[k]) {
      return k;
    }
  }
  return -1;
}

//! The "cell" entry of a model file for \e cell.
inline nlohmann::json cellToJson(const vpProjectiveCellFingerprint &cell)
{
  nlohmann::json c;
  if (cell.getWidth() > 0 && cell.getHeight() > 0) {
    c["image_size"] = {cell.getWidth(), cell.getHeight()};
  }
  c["camera_layout"] = vpProjectiveCellFingerprint::toString(cell.getCameraLayout());
  c["right_camera"] = cameraSideNames()[static_cast<int>(cell.getCameraSide())];
  const Eigen::Vector3d &b = cell.getBaselineDirection();
  c["baseline_direction"] = {b(0), b(1), b(2)};
  if (vpProjectiveCellFingerprint::isKnown(cell.getLeftCamera()) ||
      vpProjectiveCellFingerprint::isKnown(cell.getRightCamera())) {
    c["cameras"] = camerasToJson(cell.getLeftCamera(), cell.getRightCamera());
  }
  return c;
}
} // namespace vpProjectiveInternal

#endif
