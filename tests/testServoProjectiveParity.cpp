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

/*!
  \file testServoProjectiveParity.cpp
  \brief What a vpServo program expects of the task, checked against ViSP itself:
  - vpFeatureStereoPoint::buildFrom(vpPoint, two cameras) gives the pixels of vpPoint::track() and
    vpMeterPixelConversion, and refuses a point behind a camera without changing the feature;
  - with setAdaptiveGainInput(GAIN_INPUT_JOINT_VELOCITY) a vpAdaptiveGain gets, at every iteration of a simulated
    servo run, the gain that ViSP's vpServo computes on the same error with the arm's true Jacobian (it evaluates the
    gain on J^+ e), and the same velocity; on the error's norm, in pixels or normalised, it does not;
  - with setErrorUnit(ERROR_NORMALIZED, f) the error is vpServo's normalised error (x - x*, from vpFeaturePoint); a
    constant gain's law does not change; the focal length estimated from the model's self-calibration is the
    simulator's;
  - computeControlLaw() after setJointPositions(q) is computeControlLaw(q), and refuses to run twice on the same q;
  - print() has vpServo::print()'s sections in vpServo's order.
*/

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMeterPixelConversion.h>
#include <visp3/core/vpPixelMeterConversion.h>
#include <visp3/core/vpPoint.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/visual_features/vpFeaturePoint.h>
#include <visp3/vs/vpAdaptiveGain.h>
#include <visp3/visual_features/vpGenericFeature.h>
#include <visp3/vs/vpServo.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpServoProjective.h>

#include "vpProjectiveArmTestTools.h"

using namespace vpProjectiveTest;

TEST(FeatureStereoPointBuilder, KnownPointsGiveThePixelsOfViSPsProjection)
{
  const vpCameraParameters camL(800.0, 810.0, 320.0, 240.0);
  vpCameraParameters camR;
  camR.initPersProjWithDistortion(1200.0, 1190.0, 330.0, 250.0, -0.1, 0.1);
  const vpHomogeneousMatrix cLMo(0.02, -0.01, 1.0, 0.1, -0.2, 0.3);
  const vpHomogeneousMatrix cRMo = vpHomogeneousMatrix(-0.1, 0.0, 0.0, 0.0, 0.15, 0.0) * cLMo;

  // On the optical axis: the principal point; then a point of known normalised coordinates.
  vpFeatureStereoPoint s;
  s.buildFrom(vpPoint(0.0, 0.0, 1.0), camL, vpHomogeneousMatrix(), camL, vpHomogeneousMatrix());
  EXPECT_DOUBLE_EQ(s.get_u(), 320.0);
  EXPECT_DOUBLE_EQ(s.get_v(), 240.0);
  s.buildFrom(vpPoint(0.1, -0.05, 2.0), camL, vpHomogeneousMatrix(), camL, vpHomogeneousMatrix());
  EXPECT_NEAR(s.get_u(), 320.0 + 800.0 * 0.05, 1e-12);
  EXPECT_NEAR(s.get_v(), 240.0 - 810.0 * 0.025, 1e-12);

  // Random points against vpPoint::track() and vpMeterPixelConversion (with distortion on the right).
  vpUniRand rng(7);
  for (int k = 0; k < 50; ++k) {
    const double Z = rng.uniform(-0.2, 0.2); // drawn last to first: see point3(), vpProjectiveTestTools.h
    const double Y = rng.uniform(-0.2, 0.2);
    const double X = rng.uniform(-0.2, 0.2);
    vpPoint P(X, Y, Z);
    s.buildFrom(P, camL, cLMo, camR, cRMo);
    double u, v, up, vp;
    P.track(cLMo);
    vpMeterPixelConversion::convertPoint(camL, P.get_x(), P.get_y(), u, v);
    P.track(cRMo);
    vpMeterPixelConversion::convertPoint(camR, P.get_x(), P.get_y(), up, vp);
    EXPECT_NEAR(s.get_u(), u, 1e-9);
    EXPECT_NEAR(s.get_v(), v, 1e-9);
    EXPECT_NEAR(s.get_up(), up, 1e-9);
    EXPECT_NEAR(s.get_vp(), vp, 1e-9);
  }

  // Behind the right camera: refused, s unchanged.
  const Eigen::Vector4d before = s.getFeature();
  const vpHomogeneousMatrix behind(0.0, 0.0, -1.0, 0.0, 0.0, 0.0);
  EXPECT_THROW(s.buildFrom(vpPoint(0.0, 0.0, 0.0), camL, cLMo, camR, behind), vpProjectiveException);
  EXPECT_EQ(s.getFeature(), before);
  try {
    s.buildFrom(vpPoint(0.0, 0.0, 0.0), camL, cLMo, camR, behind);
  } catch (const vpProjectiveException &e) {
    EXPECT_NE(e.getStringMessage().find("right camera"), std::string::npos) << e.getStringMessage();
  }
}

namespace
{
//! Noise-free stereo features of markers \e tracked at model joints q.
void setFeatures(const ArmSetup &s, const vpColVector &q, const std::vector<unsigned int> &tracked,
                 std::vector<vpFeatureStereoPoint> &features)
{
  for (size_t k = 0; k < tracked.size(); ++k) {
    const Eigen::Vector4d sk = s.imageOf(s.armJoints(q), tracked[k]);
    features[k].buildFrom(sk(0), sk(1), sk(2), sk(3));
  }
}

/*!
  A vpServo program's features for the same images: one vpFeaturePoint per camera and marker, x = (u - u0)/px from the
  pixels by vpPixelMeterConversion (Z = 1: only the error is compared).
*/
void setPointFeatures(const ArmSetup &s, const std::vector<vpFeatureStereoPoint> &stereo,
                      std::vector<vpFeaturePoint> &points)
{
  for (size_t k = 0; k < stereo.size(); ++k) {
    double x, y;
    vpPixelMeterConversion::convertPoint(s.camLeft, stereo[k].get_u(), stereo[k].get_v(), x, y);
    points[2 * k].buildFrom(x, y, 1.0);
    vpPixelMeterConversion::convertPoint(s.camRight, stereo[k].get_up(), stereo[k].get_vp(), x, y);
    points[2 * k + 1].buildFrom(x, y, 1.0);
  }
}

/*!
  The true image Jacobian (4N x n, pixels per joint unit) of the markers \e tracked at model joints q, by central
  differences of the simulator's projections: what a calibrated joint-space vpServo program would use.
*/
vpMatrix trueJacobian(const ArmSetup &s, const vpColVector &q, const std::vector<unsigned int> &tracked)
{
  const double h = 1e-6;
  vpMatrix J(4 * static_cast<unsigned int>(tracked.size()), s.n());
  for (unsigned int j = 0; j < s.n(); ++j) {
    vpColVector qp = q, qm = q;
    qp[j] += h;
    qm[j] -= h;
    for (size_t k = 0; k < tracked.size(); ++k) {
      const Eigen::Vector4d d =
          (s.imageOf(s.armJoints(qp), tracked[k]) - s.imageOf(s.armJoints(qm), tracked[k])) / (2 * h);
      for (unsigned int r = 0; r < 4; ++r) {
        J[4 * static_cast<unsigned int>(k) + r][j] = d(r);
      }
    }
  }
  return J;
}
} // namespace

class ServoProjectiveParity : public ::testing::Test
{
protected:
  const ArmSetup s = pumaEyeToHand(); // the paper's cameras: square pixels, px = py = f in both
  const vpProjectiveRobot robot = calibratedRobot(s);
  const std::vector<unsigned int> tracked = {0, 1, 2, 3};
  std::vector<vpFeatureStereoPoint> sv, svStar;
  vpServoProjective task;

  //! The task on the tracked markers, s seen at joints \e q and s* at \e qStar.
  void makeTask(const vpColVector &q, const vpColVector &qStar)
  {
    sv.resize(tracked.size());
    svStar.resize(tracked.size());
    setFeatures(s, qStar, tracked, svStar);
    setFeatures(s, q, tracked, sv);
    task.setRobot(robot);
    for (size_t k = 0; k < tracked.size(); ++k) {
      task.addFeature(sv[k], svStar[k]);
    }
  }
};

TEST_F(ServoProjectiveParity, AnAdaptiveGainGetsVpServosValueAtEveryIteration)
{
  // A gain tuned on a vpServo program: 4 at zero, 0.4 far away, slope 30 at zero.
  const vpAdaptiveGain gain(4.0, 0.4, 30.0);
  const unsigned int nb = static_cast<unsigned int>(tracked.size());
  const double f = s.camLeft.get_px();
  const char *const names[3] = {"||J^+ e||_inf (vpServo's)", "||e||_inf in pixels", "||e||_inf normalised"};
  for (int mode = 0; mode < 3; ++mode) {
    vpColVector q(6, 0.0), qStar(6, 0.0);
    q[0] = vpMath::rad(12.0);
    q[1] = vpMath::rad(-8.0);
    q[2] = vpMath::rad(10.0);
    q[4] = vpMath::rad(15.0);
    qStar[3] = vpMath::rad(5.0);
    std::vector<vpFeatureStereoPoint> modeFeatures(nb), modeStar(nb);
    setFeatures(s, qStar, tracked, modeStar);
    vpServoProjective modeTask;
    modeTask.setRobot(robot);
    for (unsigned int k = 0; k < nb; ++k) {
      modeTask.addFeature(modeFeatures[k], modeStar[k]);
    }
    modeTask.setLambda(gain);
    modeTask.getControlLaw().setAdaptiveGainInput(mode == 0 ? vpServoControlLaw::GAIN_INPUT_JOINT_VELOCITY
                                                            : vpServoControlLaw::GAIN_INPUT_ERROR);
    modeTask.setErrorUnit(mode == 2 ? vpServoProjective::ERROR_NORMALIZED : vpServoProjective::ERROR_PIXELS, f);

    // The vpServo program: the same stereo error with the true Jacobian of the arm, through ViSP's own
    // computeControlLaw() (a vpGenericFeature with L = J, s = e and s* = 0; EYEINHAND_CAMERA makes J1 = L).
    vpGenericFeature feature(4 * nb), featureStar(4 * nb);
    featureStar.set_s(vpColVector(4 * nb, 0.0));
    vpServo vs;
    vs.setServo(vpServo::EYEINHAND_CAMERA);
    vs.setInteractionMatrixType(vpServo::CURRENT);
    vs.setLambda(gain);
    vs.addFeature(feature, featureStar);

    double worst = 1.0;
    int iterations = 0;
    for (int it = 0; it < 200; ++it, ++iterations) {
      setFeatures(s, q, tracked, modeFeatures);
      const vpColVector qdot = modeTask.computeControlLaw(q);
      feature.setInteractionMatrix(trueJacobian(s, q, tracked));
      feature.set_s(modeTask.getError());
      const vpColVector qdotViSP = vs.computeControlLaw();
      const double ratio = modeTask.getReport().getLambda() / vs.lambda.getLastValue();
      worst = std::max(worst, std::max(ratio, 1.0 / ratio));
      if (mode == 0) {
        EXPECT_NEAR(ratio, 1.0, 1e-5) << "iteration " << it;
        EXPECT_LT((qdot - qdotViSP).frobeniusNorm(), 1e-4 * qdotViSP.frobeniusNorm()) << "iteration " << it;
      }
      if (std::sqrt(modeTask.getError().sumSquare() / (4 * nb)) * modeTask.getControlLaw().getErrorScale() < 1e-3) {
        break; // converged: 1e-3 px RMS
      }
      q = s.arm.integrate(s.armJoints(q), qdot, 0.1) - s.qRef; // a velocity (1/s) applied for 0.1 s
    }
    testLog() << "[ measured ] adaptive gain of " << names[mode] << ": " << iterations
              << " iterations to 1e-3 px, gains up to " << worst << " times vpServo's" << std::endl;
    if (mode == 1) {
      EXPECT_GT(worst, 2.0) << names[mode]; // pixels: a slope per normalised unit acts a thousand times too early
    }
    if (mode == 2) {
      // Normalised, the error's norm is of the order of J^+ e in radians (an angle seen from the camera), not equal.
      EXPECT_LT(worst, 1.5) << names[mode];
      EXPECT_GT(worst, 1.0 + 1e-3) << names[mode];
    }
  }
}

TEST_F(ServoProjectiveParity, NormalisedErrorIsVpServosErrorOnTheSamePoints)
{
  const double f = s.camLeft.get_px();
  ASSERT_EQ(s.camLeft.get_py(), f); // the paper's cameras: square pixels, the same in both
  ASSERT_EQ(s.camRight.get_px(), f);
  const unsigned int nb = static_cast<unsigned int>(tracked.size());
  vpColVector q(6, 0.0), qStar(6, 0.0);
  q[0] = vpMath::rad(12.0);
  q[4] = vpMath::rad(-6.0);
  makeTask(q, qStar);
  task.setErrorUnit(vpServoProjective::ERROR_NORMALIZED, f);
  task.computeControlLaw(q);

  // vpServo's error on vpFeaturePoint built from the same pixels, x = (u - u0)/px: left x, y, right x, y per point.
  std::vector<vpFeaturePoint> p(2 * nb), pStar(2 * nb);
  setPointFeatures(s, sv, p);
  setPointFeatures(s, svStar, pStar);
  vpServo vs;
  vs.setServo(vpServo::EYEINHAND_CAMERA);
  vs.setInteractionMatrixType(vpServo::CURRENT);
  for (unsigned int k = 0; k < 2 * nb; ++k) {
    vs.addFeature(p[k], pStar[k]);
  }
  vs.computeControlLaw();
  const vpColVector e = task.getError(), ev = vs.getError();
  ASSERT_EQ(e.size(), ev.size());
  for (unsigned int r = 0; r < e.size(); ++r) {
    EXPECT_NEAR(e[r], ev[r], 1e-12) << "row " << r;
  }
}

TEST_F(ServoProjectiveParity, TheUnitChangesNeitherAConstantGainsLawNorThePixelSettings)
{
  vpColVector q(6, 0.0), qStar(6, 0.0);
  q[1] = vpMath::rad(6.0);
  q[5] = vpMath::rad(-9.0);
  makeTask(q, qStar);
  task.setLambda(0.7);
  const vpColVector qdotPixels = task.computeControlLaw(q);
  const vpColVector ePixels = task.getError();
  const vpMatrix JPixels = task.getReport().getTaskJacobian();
  const vpColVector svPixels = task.getReport().getTaskSingularValues();
  EXPECT_EQ(task.getControlLaw().getErrorScale(), 1.0);

  task.setErrorUnit(vpServoProjective::ERROR_NORMALIZED, 1000.0);
  const vpColVector qdot = task.computeControlLaw(q);
  EXPECT_LT((qdot - qdotPixels).frobeniusNorm(), 1e-12 * qdotPixels.frobeniusNorm());
  EXPECT_LT((task.getError() * 1000.0 - ePixels).frobeniusNorm(), 1e-12 * ePixels.frobeniusNorm());
  EXPECT_LT((task.getReport().getTaskJacobian() * 1000.0 - JPixels).frobeniusNorm(), 1e-12 * JPixels.frobeniusNorm());
  const vpColVector svNormalised = task.getReport().getTaskSingularValues();
  ASSERT_EQ(svNormalised.size(), svPixels.size());
  for (unsigned int k = 0; k < svPixels.size(); ++k) {
    EXPECT_NEAR(svNormalised[k] * 1000.0, svPixels[k], 1e-9 * svPixels[0]);
  }

  // Bad values are refused and change nothing.
  EXPECT_THROW(task.setErrorUnit(vpServoProjective::ERROR_NORMALIZED, -1.0), vpProjectiveException);
  EXPECT_THROW(task.setErrorUnit(vpServoProjective::ERROR_NORMALIZED, std::nan("")), vpProjectiveException);
  EXPECT_EQ(task.getControlLaw().getErrorScale(), 1000.0);

  // Estimated: the mean focal length of the model's metric self-calibration, the simulator's px = py here.
  task.setErrorUnit(vpServoProjective::ERROR_NORMALIZED);
  const double f = s.camLeft.get_px();
  testLog() << "[ measured ] estimated focal length " << task.getControlLaw().getErrorScale() << " px, true " << f
            << " px" << std::endl;
  EXPECT_NEAR(task.getControlLaw().getErrorScale(), f, 0.01 * f);
  // Chosen before the robot: estimated by setRobot().
  vpServoProjective later;
  later.setErrorUnit(vpServoProjective::ERROR_NORMALIZED);
  later.setRobot(robot);
  EXPECT_DOUBLE_EQ(later.getControlLaw().getErrorScale(), task.getControlLaw().getErrorScale());
}

TEST_F(ServoProjectiveParity, ComputeControlLawWithoutArgumentUsesTheJointsSetForIt)
{
  vpColVector q(6, 0.0), qStar(6, 0.0);
  q[2] = vpMath::rad(-7.0);
  makeTask(q, qStar);
  EXPECT_THROW(task.computeControlLaw(), vpProjectiveException); // no joints yet
  const vpColVector expected = task.computeControlLaw(q);
  task.setJointPositions(q);
  const vpColVector qdot = task.computeControlLaw();
  EXPECT_EQ((qdot - expected).frobeniusNorm(), 0.0);
  // The same joints twice: refused (the arm has moved since), and the task is left as it was.
  const vpColVector e = task.getError();
  try {
    task.computeControlLaw();
    ADD_FAILURE() << "no exception";
  } catch (const vpProjectiveException &ex) {
    EXPECT_NE(ex.getStringMessage().find("setJointPositions(q)"), std::string::npos) << ex.getStringMessage();
  }
  EXPECT_EQ((task.getError() - e).frobeniusNorm(), 0.0);
  EXPECT_THROW(task.setJointPositions(vpColVector(5, 0.0)), vpProjectiveException);
  vpColVector bad(6, 0.0);
  bad[3] = std::nan("");
  EXPECT_THROW(task.setJointPositions(bad), vpProjectiveException);
  EXPECT_THROW(task.computeControlLaw(), vpProjectiveException); // the refused joints were not kept
}

TEST_F(ServoProjectiveParity, PrintHasVpServosSectionsInItsOrder)
{
  vpColVector q(6, 0.0), qStar(6, 0.0);
  q[0] = vpMath::rad(4.0);
  makeTask(q, qStar);
  for (int computed = 0; computed < 2; ++computed) {
    if (computed == 1) {
      task.computeControlLaw(q);
    }
    std::ostringstream os;
    task.print(os);
    const std::string out = os.str();
    size_t last = 0;
    for (const char *section :
         {"Visual servoing task:", "Type of control law", "Eye-to-hand configuration", "List of visual features : s",
          "List of desired visual features : s*", "Task Jacobian J", "Error vector (s-s*)", "Gain : "}) {
      const size_t at = out.find(section, last);
      EXPECT_NE(at, std::string::npos) << "no \"" << section << "\" after position " << last << " in\n" << out;
      last = at == std::string::npos ? last : at;
    }
    EXPECT_EQ(out.find("not yet computed") != std::string::npos, computed == 0) << out;
  }
}
