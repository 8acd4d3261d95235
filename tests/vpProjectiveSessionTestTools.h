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
  Helpers of the session suites (header only): recording sessions of a simulated cell with vpProjectiveSessionWriter,
  and a marker extraction that gives the simulator's projections of the recorded frame.

  The images of a recorded frame are small grey images that carry the frame's key in their first pixels; the
  extraction reads the key back and returns the markers' pixels recorded under it (the simulator's exact projections
  plus the seeded noise of the recording). The whole pipeline of a session (writer, PNG files, reader, replay,
  calibration, check) thus runs as it does on a real cell, with a ground truth, and fast.
*/

#ifndef _vpProjectiveSessionTestTools_h_
#define _vpProjectiveSessionTestTools_h_

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>

#include "vpProjectiveArmTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
//! The JSON of session.json, as the session suites read and edit it.
using json = nlohmann::json;

//! A fresh temporary folder, removed with the object.
class TemporaryFolder
{
public:
  TemporaryFolder()
  {
    char pattern[] = "/tmp/visp-projective-session-XXXXXX";
    const char *made = mkdtemp(pattern);
    m_path = made != nullptr ? made : "";
  }
  ~TemporaryFolder()
  {
    std::error_code ignored;
    if (!m_path.empty()) {
      std::filesystem::remove_all(m_path, ignored);
    }
  }
  const std::string &path() const { return m_path; }
  std::string operator/(const std::string &name) const { return m_path + "/" + name; }

private:
  std::string m_path;
};

//! The markers' pixels recorded per frame key, and their identifiers.
struct Recording {
  std::vector<int> ids;                            //!< one per marker, ascending
  std::vector<std::vector<Eigen::Vector4d>> truth; //!< per key: (u, v, u', v') of each marker
  std::vector<unsigned int> keep;                  //!< per key: how many markers the extraction gives (all: -1)
  bool recordMarkers = false; //!< also write each frame's markers in session.json (recorded_markers), for the tool
};

//! A small grey image carrying \e key in its first two pixels.
inline vpImage<unsigned char> keyImage(unsigned int key)
{
  vpImage<unsigned char> I(6, 8, 128);
  I[0][0] = static_cast<unsigned char>(key & 255);
  I[0][1] = static_cast<unsigned char>(key >> 8);
  return I;
}

//! The extraction of a recording: the markers recorded under the images' key.
inline vpProjectiveSessionCalibration::vpMarkerExtractor recordedMarkers(const std::shared_ptr<Recording> &rec)
{
  return [rec](const vpImage<unsigned char> &Il, const vpImage<unsigned char> &, std::vector<int> &ids,
               std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) -> unsigned int {
    const unsigned int key = Il[0][0] + 256u * Il[0][1];
    ids.clear();
    left.clear();
    right.clear();
    if (key >= rec->truth.size()) {
      return 0;
    }
    const std::vector<Eigen::Vector4d> &s = rec->truth[key];
    const size_t n = std::min<size_t>(s.size(), rec->keep[key]);
    for (size_t j = 0; j < n; ++j) {
      ids.push_back(rec->ids[j]);
      left.push_back(vpImagePoint(s[j](1), s[j](0)));
      right.push_back(vpImagePoint(s[j](3), s[j](2)));
    }
    return static_cast<unsigned int>(n);
  };
}

/*!
  Records the frame of \e role at arm joints \e qArm (absolute encoder readings) of the setup \e s with pixel noise
  \e sigma; false if a marker is out of view (nothing recorded then).
*/
inline bool recordFrame(const ArmSetup &s, vpProjectiveSessionWriter &writer, Recording &rec,
                        vpProjectiveSession::vpFrameRole role, const vpColVector &qArm, double sigma,
                        vpGaussRand &noise, const vpColVector &readings = vpColVector())
{
  std::vector<vpImagePoint> l, r;
  if (!s.images(qArm, l, r, sigma, noise)) {
    return false;
  }
  std::vector<Eigen::Vector4d> truth;
  for (size_t j = 0; j < l.size(); ++j) {
    truth.push_back(Eigen::Vector4d(l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v()));
  }
  if (rec.ids.empty()) {
    for (size_t j = 0; j < l.size(); ++j) {
      rec.ids.push_back(static_cast<int>(4 * j + 1));
    }
  }
  const unsigned int key = static_cast<unsigned int>(rec.truth.size());
  rec.truth.push_back(truth);
  rec.keep.push_back(static_cast<unsigned int>(-1));
  const vpColVector &q = readings.getRows() > 0 ? readings : qArm;
  const double t = 0.5 * writer.getSession().getNumberOfFrames();
  if (rec.recordMarkers) {
    writer.addFrame(role, q, t, keyImage(key), keyImage(key), rec.ids, l, r);
  } else {
    writer.addFrame(role, q, t, keyImage(key), keyImage(key));
  }
  return true;
}

/*!
  A session of \e s to check a model against (\e frames frames: the zero reference, then random configurations in
  view within the trial amounts, all with the role observation but the first), its readings those of the arm, or
  \e readingsOf them (a mistake made on purpose); \e prepare, if given, is called on the writer before the first frame
  (e.g. to record the cameras). False if a frame is out of view.
*/
inline bool recordCheckSession(const ArmSetup &s, const std::string &folder, Recording &rec, double sigma, long seed,
                               unsigned int frames,
                               const std::function<vpColVector(const vpColVector &)> &readingsOf = nullptr,
                               const std::function<void(vpProjectiveSessionWriter &)> &prepare = nullptr)
{
  vpProjectiveSessionWriter writer(folder, s.jointTypes());
  if (prepare) {
    prepare(writer);
  }
  vpGaussRand noise(1.0, 0.0, seed);
  vpUniRand rng(static_cast<long>(seed + 29));
  for (unsigned int k = 0; k < frames; ++k) {
    vpColVector qArm = s.qRef;
    if (k > 0) {
      const vpColVector q = s.randomVisibleJoints(rng, s.trialAmounts);
      if (q.getRows() != s.n()) {
        return false;
      }
      qArm = s.armJoints(q);
    }
    if (!recordFrame(s, writer, rec, k == 0 ? vpProjectiveSession::ZERO : vpProjectiveSession::OBSERVATION, qArm, sigma,
                     noise, readingsOf ? readingsOf(qArm) : vpColVector())) {
      return false;
    }
  }
  return true;
}

/*!
  The acquisition session of \e s in \e folder: the zero frame at its zero reference, each joint's trial both ways
  (13 frames for 6 joints), then \e observations frames and \e servo servo frames at random configurations in view.
  False if a frame is out of view.
*/
inline bool recordCalibrationSession(const ArmSetup &s, const std::string &folder, Recording &rec, double sigma,
                                     long seed, unsigned int observations = 2, unsigned int servo = 0,
                                     const std::function<void(vpProjectiveSessionWriter &)> &prepare = nullptr)
{
  vpProjectiveSessionWriter writer(folder, s.jointTypes());
  if (prepare) {
    prepare(writer);
  }
  vpGaussRand noise(1.0, 0.0, seed);
  if (!recordFrame(s, writer, rec, vpProjectiveSession::ZERO, s.qRef, sigma, noise)) {
    return false;
  }
  for (unsigned int i = 0; i < s.n(); ++i) {
    for (int sign = -1; sign <= 1; sign += 2) {
      vpColVector q = s.qRef;
      q[i] += sign * s.trialAmounts[i];
      if (!recordFrame(s, writer, rec, vpProjectiveSession::TRIAL, q, sigma, noise)) {
        return false;
      }
    }
  }
  vpUniRand rng(static_cast<long>(seed + 17));
  for (unsigned int k = 0; k < observations + servo; ++k) {
    const vpColVector q = s.randomVisibleJoints(rng, s.trialAmounts);
    const vpProjectiveSession::vpFrameRole role =
        k < observations ? vpProjectiveSession::OBSERVATION : vpProjectiveSession::SERVO;
    if (q.getRows() != s.n() || !recordFrame(s, writer, rec, role, s.armJoints(q), sigma, noise)) {
      return false;
    }
  }
  return true;
}

/*!
  An R-R-P-R-R-R arm (the Stanford arm's structure: a telescoping third joint, spherical wrist, 10 cm wrist to
  flange), its zero reference at (0, 60 deg, 0.45 m, 0, -50 deg, 0) with the gripper at the PUMA's zero-reference tool
  pose facing the paper rig (the study's "prismatic" world). Trials 20, 10 deg, 4 cm, 40, 40, 60 deg.
*/
inline ArmSetup rrprrrEyeToHand()
{
  const std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::stanfordTable();
  vpColVector qRef(6, 0.0);
  qRef[1] = vpMath::rad(60.0);
  qRef[2] = 0.45;
  qRef[4] = vpMath::rad(-50.0);
  const vpSimulatorArm arm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                           basePoseFor(dh, qRef, paperToolPose()));
  ArmSetup s("R-R-P-R-R-R eye-to-hand", arm, qRef, paperRigAtOrigin());
  s.trialAmounts = {vpMath::rad(20.0), vpMath::rad(10.0), 0.04,
                    vpMath::rad(40.0), vpMath::rad(40.0), vpMath::rad(60.0)};
  return s;
}

/*!
  A camera at world point \e centre looking at \e target, upright (its y axis as close to the world +Y axis, downwards
  in the paper rig's images, as the optical axis allows), then rolled by \e rollDeg about its optical axis.
*/
inline vpHomogeneousMatrix lookAt(const vpColVector &centre, const vpColVector &target, double rollDeg)
{
  Eigen::Vector3d c(centre[0], centre[1], centre[2]), p(target[0], target[1], target[2]);
  const Eigen::Vector3d z = (p - c).normalized();
  const Eigen::Vector3d x = Eigen::Vector3d::UnitY().cross(z).normalized();
  const Eigen::Vector3d y = z.cross(x);
  Eigen::Matrix3d R;
  R << x, y, z;
  vpHomogeneousMatrix wMc;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      wMc[i][j] = R(i, j);
    }
    wMc[i][3] = c(i);
  }
  return wMc * vpHomogeneousMatrix(0.0, 0.0, 0.0, 0.0, 0.0, vpMath::rad(rollDeg));
}

//! What randomRig() drew.
struct RigDraw {
  double stackDeg; //!< direction of the right camera from the left one, seen from behind the rig: 0 right, 90 below
  double baseline; //!< metres
  double distance; //!< metres from the rig's midpoint to the markers
  double toeInDeg; //!< each camera's toe-in beyond looking at the markers' centre
};

/*!
  \e s with a random rig looking at its markers at the zero reference: the right camera \e stackDeg (seen from behind
  the rig: 0 to the right of the left one, 90 below it, 180 to its left: a rig whose images are swapped) from the left
  one, baselines of 10 to 40 cm, 0.7 to 1.4 m from the markers' centre, each camera toed in by up to \e toeInDeg more
  (or out) and rolled by up to 5 deg, intrinsics of each its own (30 to 60 cm seen across the image at the markers,
  focal lengths 5 % apart at most, principal points within 20 px of the centre, 640 x 480 or 800 x 600 images). Redrawn
  until the trials of \e s keep the markers in view; \e draw receives what was drawn. Returns \e s unchanged (name
  empty) if no draw in 200 sees them.
*/
inline ArmSetup randomRig(const ArmSetup &s, vpUniRand &rng, double stackDeg, double toeInDeg, RigDraw &draw)
{
  const std::vector<vpColVector> markers = s.arm.getMarkers(s.qRef);
  vpColVector centre(3, 0.0);
  for (const vpColVector &X : markers) {
    centre += X * (1.0 / markers.size());
  }
  for (int attempt = 0; attempt < 200; ++attempt) {
    draw.stackDeg = stackDeg;
    draw.baseline = rng.uniform(0.10, 0.40);
    draw.distance = rng.uniform(0.7, 1.4);
    draw.toeInDeg = rng.uniform(-toeInDeg, toeInDeg);
    const bool large = rng.uniform(0.0, 1.0) < 0.5;
    const unsigned int width = large ? 800 : 640, height = large ? 600 : 480;
    vpCameraParameters cam[2];
    vpHomogeneousMatrix wMc[2];
    const double azimuth = vpMath::rad(rng.uniform(-20.0, 20.0)), elevation = vpMath::rad(rng.uniform(-15.0, 15.0));
    const Eigen::Vector3d back(std::sin(azimuth) * std::cos(elevation), std::sin(elevation),
                               -std::cos(azimuth) * std::cos(elevation));              // from the markers to the rig
    const Eigen::Vector3d across = Eigen::Vector3d::UnitY().cross(-back).normalized(); // the rig's right
    const Eigen::Vector3d down = (-back).cross(across);
    const double phi = vpMath::rad(stackDeg);
    const Eigen::Vector3d offset = 0.5 * draw.baseline * (std::cos(phi) * across + std::sin(phi) * down);
    const Eigen::Vector3d mid = Eigen::Vector3d(centre[0], centre[1], centre[2]) + draw.distance * back;
    const double field = rng.uniform(0.3, 0.6); // metres seen across the image at the markers
    for (int c = 0; c < 2; ++c) {
      const double f = width * draw.distance / field * rng.uniform(0.95, 1.05);
      cam[c].initPersProjWithoutDistortion(f * rng.uniform(0.98, 1.02), f, width / 2.0 + rng.uniform(-20.0, 20.0),
                                           height / 2.0 + rng.uniform(-20.0, 20.0));
      const Eigen::Vector3d position = mid + (c == 0 ? -offset : offset);
      // The aim point moves along the baseline: toed in (towards the other camera's side of the centre) or out.
      const Eigen::Vector3d aim =
          Eigen::Vector3d(centre[0], centre[1], centre[2]) +
          (c == 0 ? 1.0 : -1.0) * std::tan(vpMath::rad(draw.toeInDeg)) * draw.distance * offset.normalized();
      vpColVector pc(3), pa(3);
      for (unsigned int i = 0; i < 3; ++i) {
        pc[i] = position(i);
        pa[i] = aim(i);
      }
      wMc[c] = lookAt(pc, pa, rng.uniform(-5.0, 5.0));
    }
    const vpSimulatorStereoRig rig(cam[0], cam[1], wMc[1].inverse() * wMc[0], wMc[0], width, height);
    ArmSetup r(s.name + " on a random rig", s.arm, s.qRef, rig);
    r.trialAmounts = s.trialAmounts;
    bool visible = r.visible(r.qRef, 20.0);
    for (unsigned int i = 0; i < r.n() && visible; ++i) {
      for (int sign = -1; sign <= 1 && visible; sign += 2) {
        vpColVector q = r.qRef;
        q[i] += sign * r.trialAmounts[i];
        visible = r.visible(q, 20.0);
      }
    }
    if (visible) {
      return r;
    }
  }
  ArmSetup none = s;
  none.name.clear();
  return none;
}

/*!
  Another cell of the joint types of \e s (eye-to-hand): an arm whose links are 25 % longer, its tool at the same pose
  at the same zero reference (the base placed for it), seen by a random rig (randomRig(), side by side); its name is
  empty if no rig sees it.
*/
inline ArmSetup anotherCell(const ArmSetup &s, vpUniRand &rng)
{
  std::vector<vpSimulatorArm::vpDHRow> dh = s.arm.getDHTable();
  for (vpSimulatorArm::vpDHRow &row : dh) {
    row.d *= 1.25;
    row.a *= 1.25;
  }
  const vpSimulatorArm arm(dh, s.arm.get_eMt(), s.arm.getToolMarkers(), basePoseFor(dh, s.qRef, s.arm.get_wMt(s.qRef)));
  ArmSetup longer(s.name + ", links 25 % longer", arm, s.qRef, s.simAt(s.qRef));
  longer.trialAmounts = s.trialAmounts;
  RigDraw draw;
  return randomRig(longer, rng, rng.uniform(-20.0, 20.0), 10.0, draw);
}

//! \e s with its cameras exchanged: the left images are the right camera's and the right ones the left camera's.
inline ArmSetup swappedCameras(const ArmSetup &s)
{
  const vpSimulatorStereoRig rig(s.camRight, s.camLeft, s.rMl.inverse(), s.wMl * s.rMl.inverse(), s.width, s.height);
  ArmSetup r(s.name + " with its cameras swapped", s.arm, s.qRef, rig);
  r.trialAmounts = s.trialAmounts;
  return r;
}

inline std::string readText(const std::string &path)
{
  std::ifstream in(path.c_str(), std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

inline void writeText(const std::string &path, const std::string &text)
{
  std::ofstream out(path.c_str(), std::ios::binary | std::ios::trunc);
  out << text;
}
} // namespace vpProjectiveTest

#endif
