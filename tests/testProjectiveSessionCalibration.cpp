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
  The calibration of an arm from a recorded session and the check of a model against another session
  (vpProjectiveSessionCalibration, what visp-projective calibrate and check run): sessions recorded by
  vpProjectiveSessionWriter from simulated cells (ViSP's Viper850 and an R-R-P-R-R-R arm, absolute encoder readings
  with a non-zero zero reference), the markers given by a test extraction (the simulator's projections with seeded
  noise).
*/

#include <cmath>
#include <memory>
#include <sstream>

#include <gtest/gtest.h>

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveModelFile.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "vpProjectiveSessionTestTools.h"

using namespace vpProjectiveTest;

namespace
{
const double kSigma = 0.1; // pixel noise of the recorded markers (an AprilTag corner's, roughly)

/*!
  RMS per coordinate (px) of the model's prediction of the noise-free marker images at \e count random
  configurations in view within the trial amounts of \e s (absolute readings).
*/
double predictionError(const ArmSetup &s, const vpProjectiveArmModel &model, unsigned int count, long seed)
{
  vpUniRand rng(seed);
  double sum = 0.0;
  unsigned int coordinates = 0;
  for (unsigned int c = 0; c < count; ++c) {
    const vpColVector q = s.randomVisibleJoints(rng, s.trialAmounts);
    EXPECT_EQ(q.getRows(), s.n());
    if (q.getRows() != s.n()) {
      return 1e9;
    }
    const vpColVector qArm = s.armJoints(q);
    vpProjectiveArmModel::JointVector v(s.n());
    for (unsigned int i = 0; i < s.n(); ++i) {
      v(i) = qArm[i];
    }
    const Eigen::Matrix4d H = model.displacement(v);
    for (size_t j = 0; j < s.numberOfMarkers(); ++j) {
      Eigen::Vector4d predicted;
      EXPECT_TRUE(model.predictMarker(static_cast<unsigned int>(j), H, predicted));
      sum += (predicted - s.imageOf(qArm, j)).squaredNorm();
      coordinates += 4;
    }
  }
  return std::sqrt(sum / coordinates);
}

//! Records the calibration session of \e s, calibrates it and writes the model; returns the model read back.
vpProjectiveArmModel calibrateSetup(const ArmSetup &s, const TemporaryFolder &tmp, std::shared_ptr<Recording> &rec,
                                    std::string &modelFile, std::string &progress)
{
  rec = std::make_shared<Recording>();
  EXPECT_TRUE(recordCalibrationSession(s, tmp / "acquisition", *rec, kSigma, 1))
      << s.name << ": a marker left the view";
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "acquisition");
  EXPECT_EQ(session.getNumberOfFrames(vpProjectiveSession::TRIAL), 2 * s.n());
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  std::ostringstream os;
  calibration.setOutput(&os);
  calibration.calibrate(session);
  modelFile = tmp / "model.json";
  calibration.saveModel(modelFile);
  progress = os.str();
  std::vector<int> ids;
  const vpProjectiveArmModel model = vpProjectiveModelFile::load(modelFile, nullptr, nullptr, &ids);
  EXPECT_EQ(ids, rec->ids);
  return model;
}

void expectCalibrated(const ArmSetup &s)
{
  TemporaryFolder tmp;
  std::shared_ptr<Recording> rec;
  std::string modelFile, progress;
  const vpProjectiveArmModel model = calibrateSetup(s, tmp, rec, modelFile, progress);
  const double error = predictionError(s, model, 30, 7);
  EXPECT_LE(error, 0.3) << s.name << ": prediction error at random configurations";
  ::testing::Test::RecordProperty("prediction_error_px", std::to_string(error));
  // One progress line per frame used (1 zero, 12 trials, 2 observations) and one per joint.
  for (unsigned int k = 1; k <= 15; ++k) {
    EXPECT_NE(progress.find("frame " + std::to_string(k) + "/15 "), std::string::npos) << progress;
  }
  for (unsigned int i = 0; i < s.n(); ++i) {
    EXPECT_NE(progress.find("joint " + std::to_string(i) + " ("), std::string::npos) << progress;
  }
  // The facade reads the model and takes the session's absolute readings.
  vpProjectiveRobot robot;
  robot.loadModel(modelFile);
  const vpMatrix H0 = robot.getDisplacement(s.qRef);
  for (unsigned int i = 0; i < 4; ++i) {
    for (unsigned int j = 0; j < 4; ++j) {
      EXPECT_NEAR(H0[i][j], i == j ? 1.0 : 0.0, 1e-12);
    }
  }
}
} // namespace

TEST(ProjectiveSessionCalibration, Viper850SessionPredictsRandomConfigurationsWithinAThirdOfAPixel)
{
  expectCalibrated(viperEyeToHand());
}

TEST(ProjectiveSessionCalibration, PrismaticArmSessionPredictsRandomConfigurationsWithinAThirdOfAPixel)
{
  expectCalibrated(rrprrrEyeToHand());
}

/*
  The observation and servo frames join the metric self-calibration: the model file holds every frame (1 zero, 12
  trials, 2 observations, 5 servo frames but one that shows no marker, which is left out with a progress line), the
  robot that loads it takes them as calibration frames, and its self-calibration is over all of them.
*/
TEST(ProjectiveSessionCalibration, ServoFramesJoinTheSelfCalibration)
{
  TemporaryFolder tmp;
  const ArmSetup s = viperEyeToHand();
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "session", *rec, kSigma, 3, 2, 5));
  rec->keep.back() = 0; // the last servo frame's tags were lost
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  std::ostringstream os;
  calibration.setOutput(&os);
  calibration.calibrate(vpProjectiveSession::read(tmp / "session"));
  calibration.saveModel(tmp / "model.json");
  EXPECT_NE(os.str().find("left out of the metric self-calibration"), std::string::npos) << os.str();
  EXPECT_NE(os.str().find("metric self-calibration: 19 frames (6 observation, target and servo frames)"),
            std::string::npos)
      << os.str();
  std::vector<vpProjectiveArmAcquisition::vpFrame> frames;
  const vpProjectiveArmModel model =
      vpProjectiveModelFile::load(tmp / "model.json", nullptr, nullptr, nullptr, &frames);
  ASSERT_EQ(frames.size(), 19u);
  vpProjectiveRobot robot;
  robot.loadModel(tmp / "model.json");
  EXPECT_EQ(robot.getAcquisition().getNumberOfCalibrationFrames(), 19u);
  const vpProjectiveSelfCalibration selfCalibration(model, frames);
  EXPECT_EQ(selfCalibration.getNumberOfFrames(), 19u);
  EXPECT_NEAR(selfCalibration.getNoiseLevel(), kSigma, 0.2 * kSigma);
}

TEST(ProjectiveSessionCalibration, CheckPassesTheUnmovedRigAndNamesTheBumpedCamera)
{
  const ArmSetup s = viperEyeToHand();
  TemporaryFolder tmp;
  std::shared_ptr<Recording> rec;
  std::string modelFile, progress;
  const vpProjectiveArmModel model = calibrateSetup(s, tmp, rec, modelFile, progress);

  // 2 deg and 1 cm: the bump of the issue.
  const vpHomogeneousMatrix bump(0.01, 0.0, 0.0, 0.0, vpMath::rad(2.0), 0.0);
  const char *names[3] = {"unmoved", "left-bumped", "right-bumped"};
  const vpProjectiveSessionCalibration::vpRigState expected[3] = {vpProjectiveSessionCalibration::RIG_UNCHANGED,
                                                                  vpProjectiveSessionCalibration::LEFT_CAMERA_MOVED,
                                                                  vpProjectiveSessionCalibration::RIGHT_CAMERA_MOVED};
  for (int c = 0; c < 3; ++c) {
    ArmSetup cell = s;
    if (c == 1) { // the left camera moves, the right one stays: wMr = wMl rMl^-1 unchanged
      cell.wMl = s.wMl * bump;
      cell.rMl = s.rMl * bump;
    } else if (c == 2) { // the right camera moves: wMr' = wMr bump
      cell.rMl = bump.inverse() * s.rMl;
    }
    const std::string folder = tmp / names[c];
    {
      vpProjectiveSessionWriter writer(folder, cell.jointTypes());
      vpGaussRand noise(1.0, 0.0, 11 + c);
      vpUniRand rng(23 + c);
      ASSERT_TRUE(recordFrame(cell, writer, *rec, vpProjectiveSession::ZERO, cell.qRef, kSigma, noise));
      for (unsigned int k = 0; k < 6;) {
        const vpColVector q = s.randomVisibleJoints(rng, s.trialAmounts);
        ASSERT_EQ(q.getRows(), s.n());
        k +=
            recordFrame(cell, writer, *rec, vpProjectiveSession::OBSERVATION, cell.armJoints(q), kSigma, noise) ? 1 : 0;
      }
    }
    vpProjectiveSessionCalibration checker(recordedMarkers(rec));
    std::vector<int> ids;
    const vpProjectiveArmModel loaded = vpProjectiveModelFile::load(modelFile, nullptr, nullptr, &ids);
    const std::vector<vpProjectiveSessionCalibration::vpFrameCheck> checks =
        checker.check(loaded, ids, vpProjectiveSession::read(folder));
    ASSERT_EQ(checks.size(), 7u);
    RecordProperty(std::string(names[c]) + "_left_px", std::to_string(checker.getLeftResidual()));
    RecordProperty(std::string(names[c]) + "_right_px", std::to_string(checker.getRightResidual()));
    EXPECT_EQ(checker.getRigState(), expected[c])
        << names[c] << ": left " << checker.getLeftResidual() << " px, right " << checker.getRightResidual() << " px";
    for (const auto &frame : checks) {
      EXPECT_EQ(frame.markers, s.numberOfMarkers());
      EXPECT_EQ(frame.fits, c == 0) << names[c] << " frame " << frame.frame << ": " << frame.left << " / "
                                    << frame.right;
    }
    if (c == 0) {
      EXPECT_LT(std::max(checker.getLeftResidual(), checker.getRightResidual()), 0.5);
    }
  }
}

TEST(ProjectiveSessionCalibration, EyeInHandMountingIsToldByTheObservationFrames)
{
  const ArmSetup s = mixedEyeInHand();
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "session", *rec, kSigma, 3, 3));
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  const vpProjectiveArmModel model = calibration.calibrate(vpProjectiveSession::read(tmp / "session"));
  EXPECT_EQ(model.getRigMounting(), vpProjectiveArmModel::EYE_IN_HAND);
  EXPECT_LE(predictionError(s, model, 20, 5), 0.3);
}

TEST(ProjectiveSessionCalibration, BadSessionsAreRefusedWithOneLineNamingTheFrame)
{
  const ArmSetup s = viperEyeToHand();
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "session", *rec, kSigma, 1, 0));
  const vpProjectiveSession session = vpProjectiveSession::read(tmp / "session");
  auto expectRefused = [&](const std::string &what, const std::string &needle) {
    vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
    try {
      calibration.calibrate(session);
      ADD_FAILURE() << what << ": accepted";
    } catch (const vpProjectiveException &e) {
      const std::string message = e.getStringMessage();
      EXPECT_NE(message.find(needle), std::string::npos) << what << ": " << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << what << ": " << message;
    }
    EXPECT_THROW(calibration.saveModel(tmp / "never.json"), vpProjectiveException) << what;
    EXPECT_FALSE(std::filesystem::exists(tmp / "never.json")) << what;
  };
  // A frame with no tag.
  rec->keep[4] = 0;
  expectRefused("no tag", "frame 5/13 ('left/000004.png', trial): no marker found");
  // Too few markers.
  rec->keep.assign(rec->keep.size(), 4);
  expectRefused("too few markers", "only 4 markers are seen in frame 1/13");
  rec->keep.assign(rec->keep.size(), static_cast<unsigned int>(-1));
  // The default extraction (AprilTag 36h11) on images without tags: the frame named, what to check.
  {
    vpProjectiveSessionCalibration calibration;
    try {
      calibration.calibrate(session);
      ADD_FAILURE() << "the default extraction found tags in images without any";
    } catch (const vpProjectiveException &e) {
      EXPECT_NE(e.getStringMessage().find("frame 1/13 ('left/000000.png', zero): no marker found in both images"),
                std::string::npos)
          << e.getStringMessage();
    }
  }
  // An AprilTag family that ViSP does not have.
  EXPECT_THROW(vpProjectiveSessionCalibration::aprilTagMarkers("37h12"), vpProjectiveException);
  // An output path that cannot be written.
  EXPECT_THROW(vpProjectiveSessionCalibration::checkWritable(tmp / "missing-folder/model.json"), vpProjectiveException);
  EXPECT_NO_THROW(vpProjectiveSessionCalibration::checkWritable(tmp / "model.json"));
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  calibration.calibrate(session);
  EXPECT_THROW(calibration.saveModel(tmp / "missing-folder/model.json"), vpProjectiveException);
  EXPECT_FALSE(std::filesystem::exists(tmp / "missing-folder"));
  for (const auto &entry : std::filesystem::directory_iterator(tmp.path())) {
    EXPECT_EQ(entry.path().filename().string().find(".tmp"), std::string::npos) << "left behind: " << entry.path();
  }
}

TEST(ProjectiveSessionCalibration, TrialsMissingSomeMarkersStillCalibrate)
{
  // Markers occluded in some trials (a tag turned away): matched by identifier, the others still used.
  const ArmSetup s = viperEyeToHand();
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "session", *rec, kSigma, 1, 0));
  rec->keep[3] = 6;
  rec->keep[8] = 5;
  rec->keep[11] = 6;
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  const vpProjectiveArmModel model = calibration.calibrate(vpProjectiveSession::read(tmp / "session"));
  EXPECT_EQ(model.markers().size(), 7u);
  EXPECT_EQ(calibration.getMarkerIds(), rec->ids);
  EXPECT_LE(predictionError(s, model, 30, 7), 0.3);
  // A trial with 4 of them is refused, naming it.
  rec->keep[8] = 4;
  try {
    calibration.calibrate(vpProjectiveSession::read(tmp / "session"));
    ADD_FAILURE() << "a trial with 4 markers accepted";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("frame 9/13 ('left/000008.png', trial) shows only 4 of the 7 markers"),
              std::string::npos)
        << e.getStringMessage();
  }
}

TEST(ProjectiveSessionCalibration, CoplanarMarkersAreRefused)
{
  // The Viper850 with its markers on one plane of the tool (a single flat target).
  const ArmSetup viper = viperEyeToHand();
  std::vector<vpColVector> planar;
  for (const vpColVector &X : vpSimulatorArm::gripperMarkers()) {
    vpColVector Y = X;
    Y[2] = 0.0;
    planar.push_back(Y);
  }
  const vpSimulatorArm arm(viper.arm.getDHTable(), viper.arm.get_eMt(), planar, viper.arm.get_wMb());
  ArmSetup s("Viper850 with a flat target", arm, viper.qRef, paperRigAtOrigin());
  s.trialAmounts = viper.trialAmounts;
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  ASSERT_TRUE(recordCalibrationSession(s, tmp / "session", *rec, kSigma, 1, 0));
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  try {
    calibration.calibrate(vpProjectiveSession::read(tmp / "session"));
    ADD_FAILURE() << "coplanar markers accepted";
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("coplanar"), std::string::npos) << e.getStringMessage();
  }
}

namespace
{
//! A vpRobot whose joints jump to setPosition()'s target (POSITION_CONTROL), for the acquisition procedure.
class vpJumpingRobot : public vpRobot
{
public:
  explicit vpJumpingRobot(const vpColVector &q0) : q(q0) {}
  void get_eJe(vpMatrix &eJe) override { eJe.resize(6, q.size(), true); }
  void get_fJe(vpMatrix &fJe) override { fJe.resize(6, q.size(), true); }
  void getDisplacement(const vpRobot::vpControlFrameType, vpColVector &d) override { d.resize(q.size(), true); }
  void getPosition(const vpRobot::vpControlFrameType, vpColVector &qOut) override { qOut = q; }
  void init() override {}
  void setPosition(const vpRobot::vpControlFrameType, const vpColVector &qIn) override { q = qIn; }
  void setVelocity(const vpRobot::vpControlFrameType, const vpColVector &) override {}
  vpColVector q;
};

/*!
  The stereo images of a simulated cell as a vpStereoImageSource: key images of the markers' projections at the
  robot's joints (with seeded noise), markers out of view left out (the extraction then misses them).
*/
class vpCellImages : public vpStereoImageSource
{
public:
  vpCellImages(const ArmSetup &setup, vpRobot &robot, Recording &rec, long seed)
      : m_setup(setup), m_robot(robot), m_rec(rec), m_noise(1.0, 0.0, seed)
  {
  }
  bool acquire(vpImage<unsigned char> &Il, vpImage<unsigned char> &Ir) override
  {
    vpColVector q;
    m_robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    std::vector<vpImagePoint> l, r;
    const bool all = m_setup.images(q, l, r, kSigma, m_noise, 0.0);
    std::vector<Eigen::Vector4d> truth;
    for (size_t j = 0; j < l.size(); ++j) {
      truth.push_back(Eigen::Vector4d(l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v()));
    }
    if (m_rec.ids.empty()) {
      for (size_t j = 0; j < l.size(); ++j) {
        m_rec.ids.push_back(static_cast<int>(4 * j + 1));
      }
    }
    const unsigned int key = static_cast<unsigned int>(m_rec.truth.size());
    m_rec.truth.push_back(truth);
    m_rec.keep.push_back(all ? static_cast<unsigned int>(-1) : 0u); // a marker out of view: none extracted
    Il = keyImage(key);
    Ir = keyImage(key);
    return true;
  }
  unsigned int getWidth() const override { return m_setup.width; }
  unsigned int getHeight() const override { return m_setup.height; }

private:
  const ArmSetup &m_setup;
  vpRobot &m_robot;
  Recording &m_rec;
  vpGaussRand m_noise;
};
} // namespace

TEST(ProjectiveSessionCalibration, TheAcquisitionProcedureRecordsASessionThatCalibratesAsWell)
{
  // The writer attached to the procedure through markerSource(): every stereo pair the procedure sees is recorded with
  // the robot's readings, its role found from them; the recording then calibrates offline.
  const ArmSetup s = viperEyeToHand();
  TemporaryFolder tmp;
  auto rec = std::make_shared<Recording>();
  vpJumpingRobot robot(s.qRef);
  unsigned int roles[5] = {0, 0, 0, 0, 0};
  vpCellImages cell(s, robot, *rec, 5);
  {
    vpProjectiveSessionWriter writer(tmp / "recorded", s.jointTypes());
    vpProjectiveAcquisitionProcedure procedure(
        vpProjectiveSessionCalibration::markerSource(cell, recordedMarkers(rec), robot, &writer), s.width, s.height);
    procedure.setMotionControl(vpProjectiveAcquisitionProcedure::POSITION_CONTROL);
    vpProjectiveArmAcquisition acquisition(s.jointTypes());
    procedure.run(robot, acquisition);
    const vpProjectiveSession &recorded = writer.getSession();
    for (unsigned int k = 0; k < recorded.getNumberOfFrames(); ++k) {
      ++roles[recorded.getFrame(k).role];
    }
  }
  EXPECT_EQ(roles[vpProjectiveSession::ZERO], 1u);
  EXPECT_GE(roles[vpProjectiveSession::TRIAL], 24u);      // 2 deg steps, each joint both ways
  EXPECT_GE(roles[vpProjectiveSession::OBSERVATION], 1u); // the mounting check (and the returns to the reference)
  vpProjectiveSessionCalibration calibration(recordedMarkers(rec));
  const vpProjectiveArmModel model = calibration.calibrate(vpProjectiveSession::read(tmp / "recorded"));
  EXPECT_EQ(model.getRigMounting(), vpProjectiveArmModel::EYE_TO_HAND);
  const double error = predictionError(s, model, 30, 9);
  EXPECT_LE(error, 0.3);
  RecordProperty("procedure_session_prediction_error_px", std::to_string(error));
  RecordProperty("procedure_session_trials", std::to_string(roles[vpProjectiveSession::TRIAL]));
}
