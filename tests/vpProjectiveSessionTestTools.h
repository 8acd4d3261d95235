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
                        vpGaussRand &noise)
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
  writer.addFrame(role, qArm, 0.5 * writer.getSession().getNumberOfFrames(), keyImage(key), keyImage(key));
  return true;
}

/*!
  The acquisition session of \e s in \e folder: the zero frame at its zero reference, each joint's trial both ways
  (13 frames for 6 joints), then \e observations frames and \e servo servo frames at random configurations in view.
  False if a frame is out of view.
*/
inline bool recordCalibrationSession(const ArmSetup &s, const std::string &folder, Recording &rec, double sigma,
                                     long seed, unsigned int observations = 2, unsigned int servo = 0)
{
  vpProjectiveSessionWriter writer(folder, s.jointTypes());
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
