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
  Which camera is left, and what the check of a model says first (issue 30, point 6): sessions recorded by
  vpProjectiveSessionWriter from simulated cells (ViSP's Viper850 and an R-R-P-R-R-R arm, the paper's rig or random
  rigs), the markers given by the test extraction (the simulator's projections with seeded noise).
  - A session whose left and right images are exchanged is refused by calibrate(), unless the layout says any; the
    right one calibrates; random rigs side by side, stacked or toed in are never called exchanged (more rigs with
    VISP_PROJECTIVE_CAMERA_RIGS=N, N per layout and arm).
  - check() names the likeliest cause first: exchanged images, a moved camera, a moved rig, moved markers, readings in
    another joint order, another cell.
  - The session's cameras and layout and the model's fingerprint are written and read back; older files still read.
*/

#include <cmath>
#include <cstdlib>
#include <memory>
#include <sstream>

#include <gtest/gtest.h>

#include <visp3/projective/vpProjectiveCellFingerprint.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveSessionSource.h>

#include "vpModelFileChecksum.h"
#include "vpProjectiveSessionTestTools.h"

using namespace vpProjectiveTest;

namespace
{
const double kSigma = 0.1; // pixel noise of the recorded markers (an AprilTag corner's, roughly)
typedef vpProjectiveSessionCalibration Calibration;
typedef vpProjectiveCellFingerprint Fingerprint;

//! A camera's identity as V4L2 gives it.
vpStereoImageSource::vpCameraIdentity camera(const std::string &device, const std::string &serial)
{
  vpStereoImageSource::vpCameraIdentity c;
  c.device = device;
  c.name = "HD Webcam C920";
  c.bus = "usb-0000:00:14.0-" + device.substr(device.size() - 1);
  c.serial = serial;
  return c;
}

//! A writer preparation that records the cameras \e left and \e right.
std::function<void(vpProjectiveSessionWriter &)> withCameras(const vpStereoImageSource::vpCameraIdentity &left,
                                                             const vpStereoImageSource::vpCameraIdentity &right)
{
  return [left, right](vpProjectiveSessionWriter &writer) { writer.setCameras(left, right); };
}

//! The message of \e e after its site ("vpProjectiveSessionCalibration::calibrate(): ").
std::string what(const vpException &e)
{
  const std::string m = e.getStringMessage();
  const size_t colon = m.find("(): ");
  return colon == std::string::npos ? m : m.substr(colon + 4);
}

//! A positive integer from the environment variable \e name, or \e fallback.
long fromEnvironment(const char *name, long fallback)
{
  const char *value = std::getenv(name);
  const long v = value != nullptr ? std::strtol(value, nullptr, 10) : 0;
  return v > 0 ? v : fallback;
}
} // namespace

TEST(ProjectiveSessionCameras, ExchangedImagesAreRefusedAndTheRightOnesCalibrate)
{
  for (const ArmSetup &s : {viperEyeToHand(), rrprrrEyeToHand()}) {
    TemporaryFolder tmp;
    auto rec = std::make_shared<Recording>();
    ASSERT_TRUE(recordCalibrationSession(s, tmp / "right", *rec, kSigma, 1, 0));
    Calibration calibration(recordedMarkers(rec));
    calibration.calibrate(vpProjectiveSession::read(tmp / "right"));
    EXPECT_EQ(calibration.getFingerprint().getCameraSide(), Fingerprint::SIDE_RIGHT) << s.name;
    EXPECT_GT(calibration.getFingerprint().getBaselineDirection()(0), 0.9) << s.name;
    const double residual = calibration.getCalibrationResidual();

    ASSERT_TRUE(recordCalibrationSession(swappedCameras(s), tmp / "exchanged", *rec, kSigma, 1, 0));
    const vpProjectiveSession exchanged = vpProjectiveSession::read(tmp / "exchanged");
    try {
      calibration.calibrate(exchanged);
      ADD_FAILURE() << s.name << ": a session with exchanged images was calibrated";
    } catch (const vpException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::invalidValueError);
      EXPECT_EQ(what(e).find("the left and right images are exchanged"), 0u) << e.getStringMessage();
      EXPECT_NE(what(e).find("--camera-layout any"), std::string::npos) << e.getStringMessage();
    }
    // A failed calibrate() leaves the calibration as it was.
    EXPECT_EQ(calibration.getFingerprint().getCameraSide(), Fingerprint::SIDE_RIGHT);
    EXPECT_EQ(calibration.getCalibrationResidual(), residual);

    // The layout says any (a camera upside down): calibrated, the side recorded.
    calibration.setCameraLayout(Fingerprint::LAYOUT_ANY);
    calibration.calibrate(exchanged);
    EXPECT_EQ(calibration.getFingerprint().getCameraSide(), Fingerprint::SIDE_LEFT);
    EXPECT_EQ(calibration.getFingerprint().getCameraLayout(), Fingerprint::LAYOUT_ANY);
    // ... or the session says it.
    ASSERT_TRUE(
        recordCalibrationSession(swappedCameras(s), tmp / "any", *rec, kSigma, 1, 0, 0,
                                 [](vpProjectiveSessionWriter &w) { w.setCameraLayout(Fingerprint::LAYOUT_ANY); }));
    Calibration fresh(recordedMarkers(rec));
    EXPECT_NO_THROW(fresh.calibrate(vpProjectiveSession::read(tmp / "any")));
  }
}

/*
  Random rigs (randomRig(): baselines 10-40 cm, 0.7-1.4 m away, cameras toed in or out by up to 15 deg more than
  looking at the markers' centre, rolled by up to 5 deg, intrinsics of each its own): side by side (the right camera
  within 30 deg of the left one's right), stacked (within 20 deg of straight below or above), exchanged (within 30 deg
  of its left). The layout is set to any so that every rig is calibrated and its side read.
*/
TEST(ProjectiveSessionCameras, RandomRigsAreNeverMisnamed)
{
  const int perLayout = static_cast<int>(fromEnvironment("VISP_PROJECTIVE_CAMERA_RIGS", 2));
  const char *layouts[3] = {"side by side", "stacked", "exchanged"};
  int calibrated[3] = {0, 0, 0}, named[3] = {0, 0, 0}, refused = 0;
  double worst = 0.0; // largest |b_x - true x| of the baseline's direction
  for (const ArmSetup &s : {viperEyeToHand(), rrprrrEyeToHand()}) {
    vpUniRand draws(static_cast<long>(s.n() * 1000 + s.arm.getDHTable()[2].type));
    for (int l = 0; l < 3; ++l) {
      for (int k = 0, attempts = 0; k < perLayout && attempts < 20 * perLayout; ++attempts) {
        const double spread = l == 1 ? 20.0 : 30.0;
        const double stack = (l == 0   ? 0.0
                              : l == 1 ? (draws.uniform(0.0, 1.0) < 0.5 ? 90.0 : 270.0)
                                       : 180.0) +
                             draws.uniform(-spread, spread);
        RigDraw draw;
        const ArmSetup r = randomRig(s, draws, stack, 15.0, draw);
        ASSERT_FALSE(r.name.empty()) << "no random rig sees the markers";
        TemporaryFolder tmp;
        auto rec = std::make_shared<Recording>();
        const long seed = 100 * l + attempts;
        if (!recordCalibrationSession(r, tmp / "s", *rec, 0.3, seed, 0)) {
          continue;
        }
        Calibration calibration(recordedMarkers(rec));
        calibration.setCameraLayout(Fingerprint::LAYOUT_ANY);
        try {
          calibration.calibrate(vpProjectiveSession::read(tmp / "s"));
        } catch (const vpException &e) {
          // Markers too close to coplanar in a far, narrow view: a rig this calibration refuses anyway.
          EXPECT_EQ(e.getCode(), vpProjectiveException::degenerateConfigurationError) << e.getStringMessage();
          ++refused;
          continue;
        }
        ++k;
        ++calibrated[l];
        const Fingerprint::vpCameraSide side = calibration.getFingerprint().getCameraSide();
        const Fingerprint::vpCameraSide expected = l == 0   ? Fingerprint::SIDE_RIGHT
                                                   : l == 1 ? Fingerprint::SIDE_ABOVE_BELOW
                                                            : Fingerprint::SIDE_LEFT;
        named[l] += side == expected ? 1 : 0;
        EXPECT_EQ(side, expected) << r.name << ", " << layouts[l] << " at " << stack << " deg, baseline "
                                  << draw.baseline << " m, toe-in " << draw.toeInDeg << " deg";
        const vpTranslationVector t = r.rMl.inverse().getTranslationVector();
        worst = std::max(worst,
                         std::fabs(calibration.getFingerprint().getBaselineDirection()(0) - t[0] / t.frobeniusNorm()));
      }
    }
  }
  for (int l = 0; l < 3; ++l) {
    EXPECT_EQ(calibrated[l], 2 * perLayout) << layouts[l] << ": too many rigs refused as coplanar";
    testLog() << layouts[l] << ": " << named[l] << " of " << calibrated[l] << " named as they are" << std::endl;
  }
  EXPECT_LT(worst, 0.1); // 0.0497 over 300 rigs (VISP_PROJECTIVE_CAMERA_RIGS=50)
  testLog() << "largest error of the baseline direction's x: " << worst << "; " << refused
            << " rigs refused as seeing coplanar markers" << std::endl;
  RecordProperty("largest_baseline_x_error", std::to_string(worst));
}

namespace
{
//! \e s with its tool's markers moved on the tool by 1 cm and 5 deg (eye-to-hand).
ArmSetup markersMoved(const ArmSetup &s)
{
  const vpSimulatorArm arm(s.arm.getDHTable(), s.arm.get_eMt(),
                           vpSimulatorStereoRig::transform(
                               vpHomogeneousMatrix(0.01, 0.0, 0.0, vpMath::rad(5.0), 0.0, 0.0), s.arm.getToolMarkers()),
                           s.arm.get_wMb());
  ArmSetup moved(s.name + " with its markers moved", arm, s.qRef, s.simAt(s.qRef));
  moved.trialAmounts = s.trialAmounts;
  return moved;
}

//! One mistake of a check: the cell as it is at the check, the readings recorded, the cameras, the cause expected.
struct Mistake {
  std::string name;
  ArmSetup cell;
  std::function<vpColVector(const vpColVector &)> readingsOf;
  vpStereoImageSource::vpCameraIdentity left, right;
  Calibration::vpRigState expected;
  std::string opening; // how the diagnosis message starts
};
} // namespace

/*
  A model calibrated from a session whose cameras are recorded (A left, B right), checked against 7-frame sessions of
  the same cell (fits), and of each mistake: the likeliest cause comes first, named in the first words of the message.
*/
TEST(ProjectiveSessionCameras, CheckNamesTheLikeliestCauseFirst)
{
  const vpStereoImageSource::vpCameraIdentity A = camera("/dev/video0", "8A3F1C2E"),
                                              B = camera("/dev/video2", "5D09B7A1"),
                                              C = camera("/dev/video0", "11112222"),
                                              D = camera("/dev/video2", "33334444");
  const vpHomogeneousMatrix bump(0.01, 0.0, 0.0, 0.0, vpMath::rad(2.0), 0.0); // 1 cm and 2 deg
  for (const ArmSetup &s : {viperEyeToHand(), rrprrrEyeToHand()}) {
    TemporaryFolder tmp;
    auto rec = std::make_shared<Recording>();
    ASSERT_TRUE(recordCalibrationSession(s, tmp / "acquisition", *rec, kSigma, 1, 2, 0, withCameras(A, B)));
    Calibration calibration(recordedMarkers(rec));
    calibration.calibrate(vpProjectiveSession::read(tmp / "acquisition"));
    calibration.saveModel(tmp / "model.json");
    std::vector<int> ids;
    Fingerprint cell;
    const vpProjectiveArmModel model =
        vpProjectiveModelFile::load(tmp / "model.json", nullptr, nullptr, &ids, nullptr, &cell);
    EXPECT_EQ(Fingerprint::sameCamera(cell.getLeftCamera(), A), 1);

    ArmSetup leftBumped = s, rigMoved = s;
    leftBumped.wMl = s.wMl * bump; // the left camera moves, the right one stays
    leftBumped.rMl = s.rMl * bump;
    rigMoved.wMl = s.wMl * bump; // both cameras move together
    vpUniRand rng(7);
    const ArmSetup other = anotherCell(s, rng);
    ASSERT_FALSE(other.name.empty());
    auto jointsExchanged = [](const vpColVector &q) {
      vpColVector r = q;
      std::swap(r[1], r[2]);
      return r;
    };
    const std::vector<Mistake> mistakes = {
        {"the same cell", s, nullptr, A, B, Calibration::RIG_UNCHANGED, "the model fits"},
        {"exchanged cameras", swappedCameras(s), nullptr, B, A, Calibration::CAMERAS_SWAPPED,
         "the left and right images are exchanged"},
        {"exchanged images, cameras not recorded",
         swappedCameras(s),
         nullptr,
         {},
         {},
         Calibration::CAMERAS_SWAPPED,
         "the left and right images are exchanged"},
        {"the left camera bumped", leftBumped, nullptr, A, B, Calibration::LEFT_CAMERA_MOVED, "the left camera moved"},
        {"the rig moved", rigMoved, nullptr, A, B, Calibration::BOTH_CAMERAS_MOVED, "both cameras moved"},
        {"markers moved on the tool", markersMoved(s), nullptr, A, B, Calibration::MARKERS_MOVED,
         "the markers moved on the tool"},
        {"joints 1 and 2 in the other order", s, jointsExchanged, A, B, Calibration::OTHER_READINGS,
         "the readings are not the model's encoders"},
        {"another cell", other, nullptr, C, D, Calibration::OTHER_CELL, "the session is of another cell"},
        {"another cell, cameras not recorded",
         other,
         nullptr,
         {},
         {},
         Calibration::OTHER_CELL,
         "the session is of another cell"}};
    long seed = 40;
    for (const Mistake &mistake : mistakes) {
      const std::string folder = tmp / ("check-" + std::to_string(seed));
      const bool known = Fingerprint::isKnown(mistake.left);
      ASSERT_TRUE(recordCheckSession(mistake.cell, folder, *rec, kSigma, ++seed, 7, mistake.readingsOf,
                                     known ? withCameras(mistake.left, mistake.right)
                                           : std::function<void(vpProjectiveSessionWriter &)>()))
          << mistake.name;
      Calibration checker(recordedMarkers(rec));
      checker.check(model, ids, vpProjectiveSession::read(folder), cell);
      EXPECT_EQ(checker.getRigState(), mistake.expected)
          << s.name << ", " << mistake.name << ": " << checker.getDiagnosisMessage();
      EXPECT_EQ(checker.getDiagnosisMessage().find(mistake.opening), 0u)
          << s.name << ", " << mistake.name << ": " << checker.getDiagnosisMessage();
      EXPECT_EQ(checker.getDiagnosis().empty(), mistake.expected == Calibration::RIG_UNCHANGED);
      if (!checker.getDiagnosis().empty()) {
        EXPECT_TRUE(checker.getDiagnosis().front().likely);
      }
      testLog() << s.name << ", " << mistake.name << ": " << checker.getDiagnosisMessage() << std::endl;
    }
    // A session of an arm with a joint of another kind: refused before any frame, the joint named.
    const std::string same = tmp / "check-40";
    json edited = json::parse(readText(same + "/session.json"));
    const bool revolute = edited["joint_types"][2] == "revolute";
    edited["joint_types"][2] = revolute ? "prismatic" : "revolute";
    writeText(same + "/session.json", edited.dump());
    try {
      Calibration(recordedMarkers(rec)).check(model, ids, vpProjectiveSession::read(same), cell);
      ADD_FAILURE() << s.name << ": a session of another arm was checked";
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::dimensionError);
      EXPECT_NE(what(e).find(std::string("the session is of another arm: its joint 2 is ") +
                             (revolute ? "prismatic, the model's revolute" : "revolute, the model's prismatic")),
                std::string::npos)
          << e.getStringMessage();
    }
  }
}

TEST(ProjectiveSessionCameras, CamerasLayoutAndFingerprintAreWrittenAndReadBack)
{
  const vpStereoImageSource::vpCameraIdentity A = camera("/dev/video0", "8A3F1C2E"), B = camera("/dev/video2", "");
  const ArmSetup s = viperEyeToHand();
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "old", *rec, kSigma, 1, 0));
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "new", *rec, kSigma, 1, 0, 0, [&](vpProjectiveSessionWriter &w) {
    w.setCameras(A, B);
    w.setCameraLayout(Fingerprint::LAYOUT_ANY);
  }));
  // A session without the keys (as every older one) reads as before.
  const vpProjectiveSession old = vpProjectiveSession::read(tmp / "old");
  EXPECT_FALSE(old.hasCameras());
  EXPECT_EQ(old.getCameraLayout(), Fingerprint::LAYOUT_LEFT_RIGHT);
  EXPECT_EQ(readText(tmp / "old/session.json").find("cameras"), std::string::npos);
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "new");
  ASSERT_TRUE(session.hasCameras());
  EXPECT_EQ(session.getLeftCamera().serial, A.serial);
  EXPECT_EQ(session.getLeftCamera().bus, A.bus);
  EXPECT_EQ(Fingerprint::sameCamera(session.getRightCamera(), B), 1);
  EXPECT_EQ(Fingerprint::sameCamera(session.getRightCamera(), A), 0);
  EXPECT_EQ(session.getCameraLayout(), Fingerprint::LAYOUT_ANY);
  vpStereoImageSource::vpCameraIdentity l, r;
  EXPECT_TRUE(vpProjectiveSessionSource(session).getCameraIdentities(l, r));
  EXPECT_EQ(r.device, B.device);
  EXPECT_FALSE(vpProjectiveSessionSource(old).getCameraIdentities(l, r));
  // Malformed keys are refused with one line naming them.
  const json file = json::parse(readText(tmp / "new/session.json"));
  for (const auto &edit : std::vector<std::pair<std::string, std::function<void(json &)>>>{
           {"'cameras'", [](json &f) { f["cameras"]["left"] = 3; }},
           {"'cameras'", [](json &f) { f["cameras"]["right"]["serial"] = 42; }},
           {"'camera_layout'", [](json &f) { f["camera_layout"] = "sideways"; }}}) {
    json edited = file;
    edit.second(edited);
    try {
      vpProjectiveSession::fromString(edited.dump(), "edited");
      ADD_FAILURE() << edited.dump();
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::fileError);
      EXPECT_NE(e.getStringMessage().find(edit.first), std::string::npos) << e.getStringMessage();
    }
  }

  // The model keeps the fingerprint, bit for bit; a model file without one reads as an empty fingerprint.
  Calibration calibration(recordedMarkers(rec));
  calibration.calibrate(session);
  calibration.saveModel(tmp / "model.json");
  Fingerprint cell;
  vpProjectiveModelFile::load(tmp / "model.json", nullptr, nullptr, nullptr, nullptr, &cell);
  const Fingerprint &made = calibration.getFingerprint();
  EXPECT_EQ(cell.getWidth(), session.getWidth());
  EXPECT_EQ(cell.getHeight(), session.getHeight());
  EXPECT_EQ(cell.getCameraLayout(), Fingerprint::LAYOUT_ANY);
  EXPECT_EQ(cell.getCameraSide(), Fingerprint::SIDE_RIGHT);
  EXPECT_EQ(cell.getBaselineDirection(), made.getBaselineDirection());
  EXPECT_EQ(cell.getLeftCamera().name, A.name);
  EXPECT_EQ(cell.getRightCamera().serial, "");
  const vpProjectiveArmModel model = vpProjectiveModelFile::load(tmp / "model.json");
  vpProjectiveModelFile::fromString(vpProjectiveModelFile::toString(model, 0.1, 1.0), "plain", nullptr, nullptr,
                                    nullptr, nullptr, &cell);
  EXPECT_EQ(cell.getCameraSide(), Fingerprint::SIDE_UNKNOWN);
  EXPECT_EQ(cell.getWidth(), 0u);
  EXPECT_FALSE(Fingerprint::isKnown(cell.getLeftCamera()));
  // A damaged fingerprint is refused (the checksum made again, as after a careless edit).
  const json saved = json::parse(readText(tmp / "model.json"));
  for (const auto &edit : std::vector<std::function<void(json &)>>{[](json &c) { c["right_camera"] = "behind"; },
                                                                   [](json &c) {
                                                                     c["baseline_direction"] = {3.0, 0.0, 0.0};
                                                                   },
                                                                   [](json &c) { c["image_size"] = {640}; },
                                                                   [](json &c) { c["cameras"]["left"]["device"] = 0; },
                                                                   [](json &c) { c.erase("camera_layout"); }}) {
    json edited = saved;
    edit(edited["model"]["cell"]);
    try {
      vpProjectiveModelFile::fromString(resigned(edited), "edited.json");
      ADD_FAILURE() << edited["model"]["cell"].dump();
    } catch (const vpProjectiveException &e) {
      EXPECT_EQ(e.getCode(), vpProjectiveException::fileError);
      EXPECT_NE(e.getStringMessage().find("edited.json"), std::string::npos) << e.getStringMessage();
    }
  }
}

/*
  The frames named alike everywhere (counted from 1, as the progress lines count): a missing image, a frame without
  markers, the progress; a session of a program whose markers are not tags, calibrated with an extraction that finds
  none, is pointed at its recorded markers.
*/
TEST(ProjectiveSessionCameras, FramesAreNamedAlikeAndRecordedMarkersArePointedAt)
{
  const ArmSetup s = rrprrrEyeToHand();
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  rec->recordMarkers = true;
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "session", *rec, kSigma, 1, 0));
  Calibration calibration(recordedMarkers(rec));
  std::ostringstream progress;
  calibration.setOutput(&progress);
  calibration.calibrate(vpProjectiveSession::read(tmp / "session"));
  const std::string label = "frame 3/13 ('left/000002.png'";
  EXPECT_NE(progress.str().find(label + ", trial of joint 0 by +20.00 deg): 7 markers"), std::string::npos)
      << progress.str();
  std::filesystem::remove(tmp / "session/right/000002.png");
  try {
    vpProjectiveSession::read(tmp / "session");
    ADD_FAILURE() << "a session with a missing image was read";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find(label + ")"), std::string::npos) << e.getStringMessage();
  }
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "balls", *rec, kSigma, 1, 0));
  Calibration tags([](const vpImage<unsigned char> &, const vpImage<unsigned char> &, std::vector<int> &,
                      std::vector<vpImagePoint> &, std::vector<vpImagePoint> &) { return 0u; });
  try {
    tags.calibrate(vpProjectiveSession::read(tmp / "balls"));
    ADD_FAILURE() << "calibrated without markers";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("frame 1/13 ('left/000000.png', zero): no marker found in its images, but"),
              std::string::npos)
        << e.getStringMessage();
    EXPECT_NE(e.getStringMessage().find("recorded_markers"), std::string::npos) << e.getStringMessage();
    EXPECT_EQ(e.getStringMessage().find("exposure"), std::string::npos) << e.getStringMessage();
  }
}
