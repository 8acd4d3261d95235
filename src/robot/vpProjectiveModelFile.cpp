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

#include <visp3/projective/vpProjectiveModelFile.h>

#include <algorithm>
#include <climits>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <limits>
#include <sstream>

#include <nlohmann/json.hpp>

#include "robot/vpCameraIdentityJson.h"
#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
using json = nlohmann::json;

const char *const kFormat = "visp_projective_robot_model";

//! FNV-1a 64 of \e text, as "fnv1a64:" and 16 hexadecimal digits.
std::string checksumOf(const std::string &text)
{
  unsigned long long h = 14695981039346656037ULL;
  for (unsigned char c : text) {
    h ^= c;
    h *= 1099511628211ULL;
  }
  char digits[17];
  std::snprintf(digits, sizeof(digits), "%016llx", h);
  return std::string("fnv1a64:") + digits;
}

template <typename Derived> json matrixToJson(const Eigen::MatrixBase<Derived> &A)
{
  json rows = json::array();
  for (Eigen::Index i = 0; i < A.rows(); ++i) {
    json row = json::array();
    for (Eigen::Index j = 0; j < A.cols(); ++j) {
      row.push_back(A(i, j));
    }
    rows.push_back(row);
  }
  return rows;
}

template <typename Derived> json vectorToJson(const Eigen::MatrixBase<Derived> &x)
{
  json values = json::array();
  for (Eigen::Index i = 0; i < x.size(); ++i) {
    values.push_back(x(i));
  }
  return values;
}

//! Reads the entries of a model file, each error a fileError naming the file and the entry.
class Reader
{
public:
  explicit Reader(const std::string &name) : m_name(name) {}

  [[noreturn]] void bad(const std::string &what) const
  {
    fail(vpProjectiveException::fileError, "vpProjectiveModelFile::load()",
         "cannot read the model file '" + m_name + "': " + what);
  }

  const json &member(const json &object, const char *key) const
  {
    if (!object.is_object() || !object.contains(key)) {
      bad(std::string("the entry '") + key + "' is missing");
    }
    return object[key];
  }

  double number(const json &value, const std::string &what) const
  {
    if (!value.is_number()) {
      bad(what + " is not a number (or is a non-finite value)");
    }
    const double x = value.get<double>();
    if (!std::isfinite(x)) {
      bad(what + " has a non-finite value");
    }
    return x;
  }

  template <int R, int C> Eigen::Matrix<double, R, C> matrix(const json &value, const std::string &what) const
  {
    if (!value.is_array() || value.size() != static_cast<size_t>(R)) {
      bad(what + " must be an array of " + std::to_string(R) + " rows");
    }
    Eigen::Matrix<double, R, C> A;
    for (int i = 0; i < R; ++i) {
      const json &row = value[static_cast<size_t>(i)];
      if (!row.is_array() || row.size() != static_cast<size_t>(C)) {
        bad(what + " must have rows of " + std::to_string(C) + " values");
      }
      for (int j = 0; j < C; ++j) {
        A(i, j) = number(row[static_cast<size_t>(j)], what);
      }
    }
    return A;
  }

  template <int N> Eigen::Matrix<double, N, 1> vector(const json &value, const std::string &what) const
  {
    if (!value.is_array() || value.size() != static_cast<size_t>(N)) {
      bad(what + " must be an array of " + std::to_string(N) + " values");
    }
    Eigen::Matrix<double, N, 1> x;
    for (int i = 0; i < N; ++i) {
      x(i) = number(value[static_cast<size_t>(i)], what);
    }
    return x;
  }

  const json &array(const json &value, const std::string &what, size_t minSize, size_t maxSize) const
  {
    if (!value.is_array() || value.size() < minSize || value.size() > maxSize) {
      bad(what + " must be an array of " + std::to_string(minSize) + " to " + std::to_string(maxSize) + " entries");
    }
    return value;
  }

  //! The self-calibration's frames of a model of \e n joints and \e K markers.
  std::vector<vpProjectiveArmAcquisition::vpFrame> frames(const json &value, size_t n, size_t K) const
  {
    std::vector<vpProjectiveArmAcquisition::vpFrame> list;
    for (const json &f : array(value, "the frames", 0, 10000000)) {
      const std::string what = "frame " + std::to_string(list.size());
      vpProjectiveArmAcquisition::vpFrame frame;
      const json &q = array(member(f, "q"), what + "'s readings", n, n);
      frame.q.resize(static_cast<Eigen::Index>(n));
      for (size_t i = 0; i < n; ++i) {
        frame.q(static_cast<Eigen::Index>(i)) = number(q[i], what + "'s readings");
      }
      for (const json &s : array(member(f, "s"), what + "'s marker images", K, K)) {
        frame.seen.push_back(!s.is_null());
        frame.s.push_back(s.is_null() ? Eigen::Vector4d::Constant(std::numeric_limits<double>::quiet_NaN())
                                      : vector<4>(s, what + "'s marker images"));
      }
      list.push_back(std::move(frame));
    }
    return list;
  }

private:
  std::string m_name;
};

//! The frames as JSON, checked against \e model's joints and markers.
json framesToJson(const vpProjectiveArmModel &model, const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames)
{
  json list = json::array();
  for (const vpProjectiveArmAcquisition::vpFrame &frame : frames) {
    if (frame.q.size() != static_cast<Eigen::Index>(model.getNumberOfJoints()) ||
        frame.s.size() != model.markers().size() || frame.seen.size() != model.markers().size()) {
      fail(vpProjectiveException::dimensionError, "vpProjectiveModelFile::save()",
           "a frame has not the model's joints and markers; give each frame n readings and one image per marker");
    }
    json images = json::array();
    for (size_t j = 0; j < frame.s.size(); ++j) {
      if (frame.seen[j] && !frame.s[j].allFinite()) {
        fail(vpProjectiveException::invalidValueError, "vpProjectiveModelFile::save()",
             "a frame's marker image is not finite; mark the marker not seen");
      }
      images.push_back(frame.seen[j] ? vectorToJson(frame.s[j]) : json());
    }
    list.push_back(json{{"q", vectorToJson(frame.q)}, {"s", images}});
  }
  return list;
}

//! The fingerprint of a "cell" entry \e c, checked.
vpProjectiveCellFingerprint cellFromJson(const Reader &reader, const json &c)
{
  vpProjectiveCellFingerprint cell;
  if (!c.is_object()) {
    reader.bad("the cell entry is not an object");
  }
  if (c.contains("image_size")) {
    const json &size = reader.array(c["image_size"], "the cell's image_size", 2, 2);
    if (!size[0].is_number_unsigned() || !size[1].is_number_unsigned() || size[0].get<unsigned long long>() > 100000 ||
        size[1].get<unsigned long long>() > 100000) {
      reader.bad("the cell's image_size must be two image dimensions in pixels");
    }
    cell.setImageSize(size[0].get<unsigned int>(), size[1].get<unsigned int>());
  }
  const json &layout = reader.member(c, "camera_layout");
  if (layout != "left-right" && layout != "any") {
    reader.bad("the cell's camera_layout is neither \"left-right\" nor \"any\"");
  }
  cell.setCameraLayout(layout == "any" ? vpProjectiveCellFingerprint::LAYOUT_ANY
                                       : vpProjectiveCellFingerprint::LAYOUT_LEFT_RIGHT);
  const int found = cameraSideOf(reader.member(c, "right_camera"));
  if (found < 0) {
    reader.bad("the cell's right_camera is not one of \"unknown\", \"right\", \"left\", \"above-below\"");
  }
  const Eigen::Vector3d direction = reader.vector<3>(reader.member(c, "baseline_direction"), "the baseline direction");
  try {
    cell.setCameraSide(static_cast<vpProjectiveCellFingerprint::vpCameraSide>(found), direction);
  } catch (const vpException &e) {
    reader.bad(e.getStringMessage());
  }
  if (c.contains("cameras")) {
    vpStereoImageSource::vpCameraIdentity left, right;
    if (!camerasFromJson(c["cameras"], left, right)) {
      reader.bad("the cell's cameras must be {\"left\": {...}, \"right\": {...}}, each field a string");
    }
    cell.setCameras(left, right);
  }
  return cell;
}
} // namespace

std::string vpProjectiveModelFile::toString(const vpProjectiveArmModel &model, double calibrationResidual,
                                            double algebraicResidual, const std::vector<int> &markerIds,
                                            const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames,
                                            const vpProjectiveModelCheck *check,
                                            const vpProjectiveCellFingerprint *cell)
{
  if (model.getNumberOfJoints() == 0) {
    fail(vpProjectiveException::notInitializedError, "vpProjectiveModelFile::save()",
         "the model is empty; acquire or load one first");
  }
  json m;
  m["mounting"] = model.getRigMounting() == vpProjectiveArmModel::EYE_TO_HAND ? "eye-to-hand" : "eye-in-hand";
  json joints = json::array(), twists = json::array(), markers = json::array();
  for (unsigned int i = 0; i < model.getNumberOfJoints(); ++i) {
    joints.push_back(vpProjectiveJoint::name(model.jointType(i)));
    twists.push_back(json{{"axis", vectorToJson(model.axis(i))}, {"point", vectorToJson(model.point(i))}});
  }
  for (const Eigen::Vector4d &M : model.markers()) {
    markers.push_back(vectorToJson(M));
  }
  m["joints"] = joints;
  m["zero_reference_joints"] = vectorToJson(model.zeroReferenceJoints());
  const vpProjectiveStereoRig &rig = model.getStereoRig();
  Eigen::Matrix3d F;
  rig.getFundamentalMatrix(F);
  if (rig.isCanonical()) {
    m["rig"] = json{{"camera_pair", "canonical"}, {"fundamental_matrix", matrixToJson(F)}};
  } else {
    vpProjectiveStereoRig::Projection P, Pp;
    rig.getLeftProjection(P);
    rig.getRightProjection(Pp);
    m["rig"] = json{{"camera_pair", "general"},
                    {"fundamental_matrix", matrixToJson(F)},
                    {"left_projection", matrixToJson(P)},
                    {"right_projection", matrixToJson(Pp)}};
  }
  m["G"] = matrixToJson(model.projectiveToMetric());
  m["twists"] = twists;
  m["markers"] = markers;
  m["calibration_residual"] = calibrationResidual;
  m["algebraic_residual"] = algebraicResidual;
  if (!markerIds.empty()) {
    if (markerIds.size() != model.markers().size()) {
      fail(vpProjectiveException::dimensionError, "vpProjectiveModelFile::save()",
           "got " + std::to_string(markerIds.size()) + " marker identifiers for " +
               std::to_string(model.markers().size()) + " markers; give one per marker, or none");
    }
    std::vector<int> sorted(markerIds);
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      fail(vpProjectiveException::invalidValueError, "vpProjectiveModelFile::save()",
           "two markers have the same identifier; give each marker its own");
    }
    m["marker_ids"] = markerIds;
  }
  if (check != nullptr && check->isChecked()) {
    json joints = json::array();
    bool identified = false;
    for (const vpProjectiveModelCheck::vpJointTypeFit &j : check->getJoints()) {
      auto finite = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
      joints.push_back(json{{"turn", finite(j.turn)},
                            {"residual_revolute", finite(j.residualRevolute)},
                            {"residual_prismatic", finite(j.residualPrismatic)}});
      identified = identified || !j.declared;
    }
    m["model_check"] =
        json{{"joint_types", identified ? "identified" : "declared"},
             {"image_noise", check->getNoise()},
             {"residual_limit", std::isfinite(check->getLimit()) ? json(check->getLimit()) : json(nullptr)},
             {"joints", joints}};
  }
  if (!frames.empty()) {
    m["frames"] = framesToJson(model, frames);
  }
  if (cell != nullptr) {
    m["cell"] = cellToJson(*cell);
  }
  json file;
  file["format"] = kFormat;
  file["version"] = version;
  file["model"] = m;
  file["checksum"] = checksumOf(m.dump());
  return file.dump(2) + "\n";
}

void vpProjectiveModelFile::save(const std::string &filename, const vpProjectiveArmModel &model,
                                 double calibrationResidual, double algebraicResidual)
{
  save(filename, model, calibrationResidual, algebraicResidual, std::vector<int>());
}

void vpProjectiveModelFile::save(const std::string &filename, const vpProjectiveArmModel &model,
                                 double calibrationResidual, double algebraicResidual,
                                 const std::vector<int> &markerIds,
                                 const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames,
                                 const vpProjectiveModelCheck *check, const vpProjectiveCellFingerprint *cell)
{
  const std::string where = "vpProjectiveModelFile::save()";
  const std::string text = toString(model, calibrationResidual, algebraicResidual, markerIds, frames, check, cell);
  std::ofstream file(filename.c_str(), std::ios::binary);
  if (!file) {
    fail(vpProjectiveException::fileError, where, "cannot open '" + filename + "' for writing");
  }
  file << text;
  if (!file) {
    fail(vpProjectiveException::fileError, where, "writing '" + filename + "' failed (disk full?)");
  }
}

vpProjectiveArmModel vpProjectiveModelFile::load(const std::string &filename, double *calibrationResidual,
                                                 double *algebraicResidual, std::vector<int> *markerIds,
                                                 std::vector<vpProjectiveArmAcquisition::vpFrame> *frames,
                                                 vpProjectiveCellFingerprint *cell)
{
  std::ifstream file(filename.c_str(), std::ios::binary);
  if (!file) {
    fail(vpProjectiveException::fileError, "vpProjectiveModelFile::load()",
         "cannot open the model file '" + filename + "'; check the path, or acquire a model and save it first");
  }
  std::ostringstream text;
  text << file.rdbuf();
  return fromString(text.str(), filename, calibrationResidual, algebraicResidual, markerIds, frames, cell);
}

vpProjectiveArmModel vpProjectiveModelFile::fromString(const std::string &text, const std::string &name,
                                                       double *calibrationResidual, double *algebraicResidual,
                                                       std::vector<int> *markerIds,
                                                       std::vector<vpProjectiveArmAcquisition::vpFrame> *frames,
                                                       vpProjectiveCellFingerprint *cell)
{
  const Reader reader(name);
  json file;
  try {
    file = json::parse(text);
  } catch (const json::exception &e) {
    reader.bad(std::string("it is not complete JSON (truncated or damaged file?): ") + e.what());
  }
  const json &format = reader.member(file, "format");
  if (!format.is_string() || format.get<std::string>() != kFormat) {
    reader.bad(std::string("it is not a ") + kFormat + " file (its 'format' entry differs)");
  }
  const json &v = reader.member(file, "version");
  if (!v.is_number_integer() || (v.get<long long>() != version && v.get<long long>() != 2)) {
    reader.bad("it has format version " + v.dump() + ", this build reads versions 2 and " + std::to_string(version) +
               "; save the model again with the build that wrote it, or acquire it again");
  }
  const bool version2 = v.get<long long>() == 2; // before re-registration: always the canonical pair of F
  const json &m = reader.member(file, "model");
  const json &checksum = reader.member(file, "checksum");
  if (!checksum.is_string() || checksum.get<std::string>() != checksumOf(m.dump())) {
    reader.bad("its checksum does not match its content (corrupted or edited file)");
  }

  const json &mounting = reader.member(m, "mounting");
  if (!mounting.is_string() || (mounting != "eye-to-hand" && mounting != "eye-in-hand")) {
    reader.bad("the rig mounting is neither eye-to-hand nor eye-in-hand");
  }
  const json &joints = reader.array(reader.member(m, "joints"), "the joint list", 1, vpProjectiveArmModel::maxJoints);
  const size_t n = joints.size();
  std::vector<vpProjectiveJoint::vpJointType> types(n);
  for (size_t i = 0; i < n; ++i) {
    if (joints[i] == vpProjectiveJoint::name(vpProjectiveJoint::REVOLUTE)) {
      types[i] = vpProjectiveJoint::REVOLUTE;
    } else if (joints[i] == vpProjectiveJoint::name(vpProjectiveJoint::PRISMATIC)) {
      types[i] = vpProjectiveJoint::PRISMATIC;
    } else {
      reader.bad("joint " + std::to_string(i) + " has a joint type that is neither revolute nor prismatic");
    }
  }
  const json &qRefJson = reader.array(reader.member(m, "zero_reference_joints"), "zero_reference_joints", n, n);
  vpProjectiveArmModel::JointVector qRef(static_cast<Eigen::Index>(n));
  for (size_t i = 0; i < n; ++i) {
    qRef(static_cast<Eigen::Index>(i)) = reader.number(qRefJson[i], "zero_reference_joints");
  }
  const json &rigJson = reader.member(m, "rig");
  const Eigen::Matrix3d F = reader.matrix<3, 3>(reader.member(rigJson, "fundamental_matrix"), "the fundamental matrix");
  bool general = false;
  Eigen::Matrix<double, 3, 4> P, Pp;
  if (!version2) {
    const json &pair = reader.member(rigJson, "camera_pair");
    if (!pair.is_string() || (pair != "canonical" && pair != "general")) {
      reader.bad("the rig's camera_pair is neither canonical nor general");
    }
    general = pair == "general";
    if (general) {
      P = reader.matrix<3, 4>(reader.member(rigJson, "left_projection"), "the left projection");
      Pp = reader.matrix<3, 4>(reader.member(rigJson, "right_projection"), "the right projection");
    }
  }
  const Eigen::Matrix4d G = reader.matrix<4, 4>(reader.member(m, "G"), "G");
  const json &twists = reader.array(reader.member(m, "twists"), "the twist list", n, n);
  std::vector<Eigen::Vector3d> axis(n), point(n);
  for (size_t i = 0; i < n; ++i) {
    axis[i] = reader.vector<3>(reader.member(twists[i], "axis"), "the axis of joint " + std::to_string(i));
    point[i] = reader.vector<3>(reader.member(twists[i], "point"), "the axis point of joint " + std::to_string(i));
  }
  const json &markersJson = reader.array(reader.member(m, "markers"), "the markers", 5, 100000);
  std::vector<Eigen::Vector4d> markers(markersJson.size());
  for (size_t j = 0; j < markers.size(); ++j) {
    markers[j] = reader.vector<4>(markersJson[j], "marker " + std::to_string(j));
  }
  const double residual = reader.number(reader.member(m, "calibration_residual"), "calibration_residual");
  const double algebraic = reader.number(reader.member(m, "algebraic_residual"), "algebraic_residual");
  std::vector<int> ids;
  if (m.contains("marker_ids")) {
    const json &idsJson = reader.array(m["marker_ids"], "marker_ids", markers.size(), markers.size());
    for (const json &id : idsJson) {
      if (!id.is_number_integer() || id.get<long long>() < INT_MIN || id.get<long long>() > INT_MAX) {
        reader.bad("marker_ids must hold one integer per marker");
      }
      ids.push_back(id.get<int>());
    }
    std::vector<int> sorted(ids);
    std::sort(sorted.begin(), sorted.end());
    if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) {
      reader.bad("two markers have the same identifier in marker_ids");
    }
  }
  const vpProjectiveCellFingerprint fingerprint =
      m.contains("cell") ? cellFromJson(reader, m["cell"]) : vpProjectiveCellFingerprint();

  std::vector<vpProjectiveArmAcquisition::vpFrame> framesRead;
  if (m.contains("frames")) {
    framesRead = reader.frames(m["frames"], n, markers.size());
  }

  vpProjectiveArmModel model;
  try {
    vpProjectiveStereoRig rig;
    if (general) {
      rig.setProjections(P, Pp);
    } else {
      rig.setFundamentalMatrix(toVisp(F));
    }
    model = vpProjectiveArmModel(
        types, mounting == "eye-to-hand" ? vpProjectiveArmModel::EYE_TO_HAND : vpProjectiveArmModel::EYE_IN_HAND, rig,
        G, axis, point, markers, qRef);
  } catch (const vpException &e) {
    reader.bad(std::string("its model is invalid: ") + e.getStringMessage());
  }
  if (calibrationResidual != nullptr) {
    *calibrationResidual = residual;
  }
  if (algebraicResidual != nullptr) {
    *algebraicResidual = algebraic;
  }
  if (markerIds != nullptr) {
    *markerIds = ids;
  }
  if (frames != nullptr) {
    *frames = std::move(framesRead);
  }
  if (cell != nullptr) {
    *cell = fingerprint;
  }
  return model;
}
