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
  Tests of vpSimulatorArm, the metric arm of the simulator (helpers in vpSimulatorTestTools.h): the product of
  exponentials (PUMA, Viper850, a prismatic joint), twists about the joint axes, marker displacements, the Viper850
  against ViSP's model, the gripper's markers, the paper's setup in view, the integration clamped to the joint limits,
  and the bad inputs of the simulator's classes named in their messages.
*/

#include <gtest/gtest.h>
#include <visp3/core/vpThetaUVector.h>

#include "vpSimulatorTestTools.h"

using namespace vpProjectiveTest;

TEST(SimulatorArm, ProductOfExponentialsPuma)
{
  vpUniRand rng(42);
  expectProductOfExponentials(paperArm(), rng, 50);
  // With another base pose.
  const vpHomogeneousMatrix wMb(0.3, -0.2, 0.5, 0.1, -0.4, 0.7);
  expectProductOfExponentials(vpSimulatorArm::puma(wMb), rng, 20);
}

TEST(SimulatorArm, ProductOfExponentialsViper850)
{
  vpUniRand rng(43);
  expectProductOfExponentials(vpSimulatorArm::viper850(vpHomogeneousMatrix(0.1, 0.2, 0.3, 0.0, 0.5, 0.0)), rng, 50);
}

TEST(SimulatorArm, ProductOfExponentialsWithPrismaticJoint)
{
  // A SCARA-like R R P R chain.
  std::vector<vpSimulatorArm::vpDHRow> dh(4);
  dh[0] = {vpProjectiveJoint::REVOLUTE, 0.2, 0.4, 0.35, 0.0};
  dh[1] = {vpProjectiveJoint::REVOLUTE, -0.3, 0.0, 0.25, M_PI};
  dh[2] = {vpProjectiveJoint::PRISMATIC, 0.0, 0.1, 0.0, 0.0};
  dh[3] = {vpProjectiveJoint::REVOLUTE, 0.5, 0.05, 0.0, 0.0};
  const vpSimulatorArm arm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                           vpHomogeneousMatrix(0.0, 0.0, 1.0, 0.3, 0.0, 0.0));
  EXPECT_EQ(arm.getJointType(2), vpProjectiveJoint::PRISMATIC);
  EXPECT_NEAR(arm.getJointMax()[2], 0.5, 1e-15);
  EXPECT_NEAR(arm.getJointMax()[0], vpMath::rad(170.0), 1e-15);
  vpUniRand rng(44);
  expectProductOfExponentials(arm, rng, 50);
  // The prismatic twist is a unit translation, the revolute ones unit rotations about lines.
  const Eigen::Matrix4d Tp = toEigen<4, 4>(arm.getTwist(2));
  const Eigen::Matrix3d Wp = Tp.topLeftCorner<3, 3>();
  const Eigen::Vector3d vp = Tp.topRightCorner<3, 1>();
  EXPECT_LT(Wp.norm(), 1e-15);
  EXPECT_NEAR(vp.norm(), 1.0, 1e-12);
}

TEST(SimulatorArm, StanfordTableSlidesAlongItsThirdAxis)
{
  const vpSimulatorArm arm(vpSimulatorArm::stanfordTable(), vpSimulatorArm::gripperMount(),
                           vpSimulatorArm::gripperMarkers(), vpHomogeneousMatrix(0.1, 0.0, 0.5, 0.0, 0.3, 0.0));
  ASSERT_EQ(arm.getNumberOfJoints(), 6u);
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_EQ(arm.getJointType(i), i == 2 ? vpProjectiveJoint::PRISMATIC : vpProjectiveJoint::REVOLUTE);
  }
  vpUniRand rng(45);
  expectProductOfExponentials(arm, rng, 50);
  // Moving the slide alone moves the tool by the same distance without turning it (the wrist is spherical).
  vpColVector q(6, 0.0);
  q[1] = 0.6;
  q[2] = 0.45;
  const vpHomogeneousMatrix wMt0 = arm.get_wMt(q);
  q[2] += 0.05;
  const vpHomogeneousMatrix t0Mt1 = wMt0.inverse() * arm.get_wMt(q);
  EXPECT_NEAR(t0Mt1.getTranslationVector().frobeniusNorm(), 0.05, 1e-12);
  EXPECT_LT(std::sqrt(vpThetaUVector(t0Mt1.getRotationMatrix()).sumSquare()), 1e-12);
}

TEST(SimulatorArm, TwistsAreRotationsAboutJointAxes)
{
  const vpSimulatorArm arm = paperArm();
  const vpColVector q0(6, 0.0);
  for (unsigned int i = 0; i < 6; ++i) {
    const Eigen::Matrix4d T = toEigen<4, 4>(arm.getTwist(i));
    const Eigen::Matrix3d W = T.topLeftCorner<3, 3>();
    EXPECT_LT((W + W.transpose()).norm(), 1e-15); // skew
    EXPECT_LT(T.bottomRows<1>().norm(), 1e-15);
    const Eigen::Vector3d w(W(2, 1), W(0, 2), W(1, 0));
    const Eigen::Vector3d v = T.block<3, 1>(0, 3);
    EXPECT_NEAR(w.norm(), 1.0, 1e-12);
    EXPECT_NEAR(w.dot(v), 0.0, 1e-12); // a pure rotation (zero pitch)
    // Moving joint i alone rotates the tool about that line: the displacement's rotation axis is w.
    vpColVector q(6, 0.0);
    q[i] = 0.3;
    const vpHomogeneousMatrix D = arm.getDisplacement(q);
    const vpThetaUVector tu(D.getRotationMatrix());
    EXPECT_NEAR(tu.getTheta(), 0.3, 1e-12);
    EXPECT_LT((Eigen::Vector3d(tu[0], tu[1], tu[2]) / 0.3 - w).norm(), 1e-12);
  }
  // Joint 0 of puma() turns about the base's z axis.
  const vpHomogeneousMatrix wMb = arm.get_wMb();
  const Eigen::Matrix4d T0 = toEigen<4, 4>(arm.getTwist(0));
  EXPECT_LT((Eigen::Vector3d(T0(2, 1), T0(0, 2), T0(1, 0)) - Eigen::Vector3d(wMb[0][2], wMb[1][2], wMb[2][2])).norm(),
            1e-12);
}

TEST(SimulatorArm, DisplacementMovesMarkers)
{
  const vpSimulatorArm arm = paperArm();
  vpUniRand rng(8);
  const std::vector<vpColVector> m0 = arm.getMarkers(vpColVector(6, 0.0));
  ASSERT_EQ(m0.size(), 7u);
  for (int k = 0; k < 10; ++k) {
    const vpColVector q = randomJoints(arm, rng);
    const std::vector<vpColVector> moved = vpSimulatorStereoRig::transform(arm.getDisplacement(q), m0);
    const std::vector<vpColVector> mq = arm.getMarkers(q);
    for (size_t j = 0; j < m0.size(); ++j) {
      EXPECT_LT((toEigen<3, 1>(moved[j]) - toEigen<3, 1>(mq[j])).norm(), 1e-12);
    }
    // Markers are rigidly attached: wMt(q) tX.
    const Eigen::Matrix4d wMt = toEigen<4, 4>(arm.get_wMt(q));
    const vpColVector &tX = arm.getToolMarkers()[3];
    EXPECT_LT(
        (wMt.topLeftCorner<3, 3>() * toEigen<3, 1>(tX) + wMt.topRightCorner<3, 1>() - toEigen<3, 1>(mq[3])).norm(),
        1e-12);
  }
}

TEST(SimulatorArm, Viper850MatchesVispModel)
{
  // vpViper::get_fMe() ignores the joint 5-6 coupling (it applies to motor positions only), so the comparison holds
  // for every q, including q5 != 0.
  const vpSimulatorArm arm = vpSimulatorArm::viper850(vpHomogeneousMatrix());
  vpViper850 viper;
  EXPECT_LT((toEigen<6, 1>(arm.getJointMin()) - toEigen<6, 1>(viper.getJointMin())).norm(), 1e-15);
  EXPECT_LT((toEigen<6, 1>(arm.getJointMax()) - toEigen<6, 1>(viper.getJointMax())).norm(), 1e-15);
  vpUniRand rng(850);
  for (int k = 0; k < 100; ++k) {
    const vpColVector q = randomJoints(arm, rng);
    vpHomogeneousMatrix fMe;
    viper.get_fMe(q, fMe);
    EXPECT_LT((toEigen<4, 4>(arm.get_wMe(q)) - toEigen<4, 4>(fMe)).cwiseAbs().maxCoeff(), 1e-12) << "q = " << q.t();
  }
  // With a base pose and the gripper mount.
  const vpHomogeneousMatrix wMb(0.5, 0.0, -0.2, 0.0, 0.0, 1.0);
  const vpSimulatorArm placed = vpSimulatorArm::viper850(wMb);
  const vpColVector q = randomJoints(placed, rng);
  vpHomogeneousMatrix fMe;
  viper.get_fMe(q, fMe);
  EXPECT_LT((toEigen<4, 4>(placed.get_wMt(q)) - toEigen<4, 4>(wMb * fMe * vpSimulatorArm::gripperMount()))
                .cwiseAbs()
                .maxCoeff(),
            1e-12);
}

TEST(SimulatorArm, GripperMarkersNoFourCoplanar)
{
  const std::vector<vpColVector> m = vpSimulatorArm::gripperMarkers();
  ASSERT_EQ(m.size(), 7u);
  double minDet = std::numeric_limits<double>::infinity();
  double minDistance = std::numeric_limits<double>::infinity();
  int subsets = 0;
  for (int a = 0; a < 7; ++a) {
    for (int b = a + 1; b < 7; ++b) {
      for (int c = b + 1; c < 7; ++c) {
        for (int d = c + 1; d < 7; ++d) {
          const int id[4] = {a, b, c, d};
          Eigen::Matrix4d M;
          for (int k = 0; k < 4; ++k) {
            M.block<3, 1>(0, k) = toEigen<3, 1>(m[id[k]]);
            M(3, k) = 1.0;
          }
          minDet = std::min(minDet, std::fabs(M.determinant())); // 6 x tetrahedron volume, m^3
          for (int k = 0; k < 4; ++k) {
            Eigen::Vector3d p[3];
            int j = 0;
            for (int l = 0; l < 4; ++l) {
              if (l != k) {
                p[j++] = M.block<3, 1>(0, l);
              }
            }
            const Eigen::Vector3d n = (p[1] - p[0]).cross(p[2] - p[0]).normalized();
            minDistance = std::min(minDistance, std::fabs(n.dot(M.block<3, 1>(0, k) - p[0])));
          }
          ++subsets;
        }
      }
    }
  }
  EXPECT_EQ(subsets, 35);
  EXPECT_GT(minDet, 1e-5);
  EXPECT_GT(minDistance, 0.008); // every marker at least 8 mm off the plane of any other three
  // All within the 10 cm gripper.
  for (size_t k = 0; k < m.size(); ++k) {
    EXPECT_LE((toEigen<3, 1>(m[k])).cwiseAbs().maxCoeff(), 0.05 + 1e-12);
  }
  // Markers 0-2 share the front face y = -2 cm; all others are behind it.
  for (size_t k = 0; k < m.size(); ++k) {
    if (k < 3) {
      EXPECT_NEAR(m[k][1], -0.02, 1e-15);
    } else {
      EXPECT_GT(m[k][1], -0.02 + 1e-3);
    }
  }
}

TEST(SimulatorArm, PaperSetupZeroReferenceInView)
{
  const vpSimulatorArm arm = paperArm();
  const vpSimulatorStereoRig sim = paperRig();
  const vpColVector q0(6, 0.0);
  // The gripper's centre is the fixation point (world origin).
  const vpHomogeneousMatrix wMt0 = arm.get_wMt(q0);
  EXPECT_LT(wMt0.getTranslationVector().frobeniusNorm(), 1e-12);
  const std::vector<vpColVector> m = arm.getMarkers(q0);
  for (size_t k = 0; k < m.size(); ++k) {
    EXPECT_TRUE(sim.isVisible(m[k], 10.0)) << "marker " << k;
  }
  // The front face (markers 0-2) looks at both cameras: its outward normal points to each camera centre.
  const Eigen::Vector3d n = -Eigen::Vector3d(wMt0[0][1], wMt0[1][1], wMt0[2][1]);
  const vpHomogeneousMatrix wMr = sim.get_wMl() * sim.get_rMl().inverse();
  const Eigen::Vector3d centres[2] = {Eigen::Vector3d(sim.get_wMl()[0][3], sim.get_wMl()[1][3], sim.get_wMl()[2][3]),
                                      Eigen::Vector3d(wMr[0][3], wMr[1][3], wMr[2][3])};
  for (int c = 0; c < 2; ++c) {
    for (int k = 0; k < 3; ++k) {
      const Eigen::Vector3d toCamera = (centres[c] - toEigen<3, 1>(m[k])).normalized();
      EXPECT_GT(n.dot(toCamera), std::cos(vpMath::rad(35.0))) << "camera " << c << " marker " << k;
    }
  }
  // The base is below the gripper (world +Y is down) and the arm does not reach behind the rig.
  EXPECT_GT(arm.get_wMb()[1][3], 1.0);
  EXPECT_GT(arm.get_wMb()[2][3], -0.5);
}

TEST(SimulatorArm, PaperTrialMotionsStayInView)
{
  // Each joint alone moves by the paper's trial amount both ways, continuously: all markers stay 10 px inside both
  // images. Just beyond the documented reach of joints 1 and 2 they leave, which shows that the check is tight.
  const vpSimulatorArm arm = paperArm();
  const vpSimulatorStereoRig sim = paperRig();
  auto allVisible = [&](const vpColVector &q) {
    const std::vector<vpColVector> m = arm.getMarkers(q);
    for (size_t k = 0; k < m.size(); ++k) {
      if (!sim.isVisible(m[k], 10.0)) {
        return false;
      }
    }
    return true;
  };
  for (unsigned int j = 0; j < 6; ++j) {
    for (int sign = -1; sign <= 1; sign += 2) {
      for (double a = 0.0; a <= kTrialDeg[j] + 1e-9; a += 0.5) {
        vpColVector q(6, 0.0);
        q[j] = sign * vpMath::rad(a);
        EXPECT_TRUE(allVisible(q)) << "joint " << j << " at " << sign * a << " deg";
      }
    }
  }
  const double beyond[4][2] = {{1, -23.0}, {1, 35.0}, {2, -48.0}, {2, 35.0}};
  for (int k = 0; k < 4; ++k) {
    vpColVector q(6, 0.0);
    q[static_cast<unsigned int>(beyond[k][0])] = vpMath::rad(beyond[k][1]);
    EXPECT_FALSE(allVisible(q)) << "joint " << beyond[k][0] << " at " << beyond[k][1] << " deg";
  }
}

TEST(SimulatorArm, IntegrateClampsToJointLimits)
{
  const vpSimulatorArm arm = paperArm();
  const double limit = vpMath::rad(170.0);
  vpColVector q(6, 0.0);
  q[0] = limit - 0.01;
  q[1] = -limit + 0.01;
  q[2] = 0.2;
  vpColVector qdot(6, 0.0);
  qdot[0] = 1.0;
  qdot[1] = -1.0;
  qdot[2] = -0.5;
  qdot[3] = 0.25;
  const vpColVector next = arm.integrate(q, qdot, 0.1);
  EXPECT_DOUBLE_EQ(next[0], limit);
  EXPECT_DOUBLE_EQ(next[1], -limit);
  EXPECT_NEAR(next[2], 0.15, 1e-15);
  EXPECT_NEAR(next[3], 0.025, 1e-15);
  EXPECT_DOUBLE_EQ(next[4], 0.0);
  // Viper850 limits come from vpViper850.
  const vpSimulatorArm viper = vpSimulatorArm::viper850(vpHomogeneousMatrix());
  const vpColVector fast(6, 100.0);
  const vpColVector top = viper.integrate(vpColVector(6, 0.0), fast, 1.0);
  const vpColVector bottom = viper.integrate(vpColVector(6, 0.0), -1.0 * fast, 1.0);
  for (unsigned int i = 0; i < 6; ++i) {
    EXPECT_DOUBLE_EQ(top[i], vpViper850().getJointMax()[i]);
    EXPECT_DOUBLE_EQ(bottom[i], vpViper850().getJointMin()[i]);
  }
  // Custom limits.
  vpSimulatorArm custom = arm;
  custom.setJointLimits(vpColVector(6, -0.1), vpColVector(6, 0.1));
  EXPECT_DOUBLE_EQ(custom.integrate(vpColVector(6, 0.0), fast, 1.0)[5], 0.1);
}

TEST(SimulatorArm, BadInputsThrow)
{
  const vpSimulatorArm arm = paperArm();
  expectThrowsCode([&]() { arm.get_wMt(vpColVector(5, 0.0)); }, vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.getMarkers(vpColVector(7, 0.0)); }, vpProjectiveException::dimensionError);
  vpColVector nan(6, 0.0);
  nan[3] = std::numeric_limits<double>::quiet_NaN();
  expectThrowsCode([&]() { arm.get_wMt(nan); }, vpProjectiveException::nonFiniteValueError);
  expectThrowsCode([&]() { arm.getDisplacement(nan); }, vpProjectiveException::nonFiniteValueError);
  expectThrowsCode([&]() { arm.getTwist(6); }, vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.getJointType(6); }, vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), vpColVector(3, 0.0), 0.1); },
                   vpProjectiveException::dimensionError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), nan, 0.1); }, vpProjectiveException::nonFiniteValueError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), vpColVector(6, 0.0), -0.1); },
                   vpProjectiveException::invalidValueError);
  expectThrowsCode([&]() { arm.integrate(vpColVector(6, 0.0), vpColVector(6, 0.0), std::nan("")); },
                   vpProjectiveException::invalidValueError);
  vpSimulatorArm copy = arm;
  expectThrowsCode([&]() { copy.setJointLimits(vpColVector(6, 1.0), vpColVector(6, -1.0)); },
                   vpProjectiveException::invalidValueError);

  const std::vector<vpColVector> markers = vpSimulatorArm::gripperMarkers();
  const vpHomogeneousMatrix I;
  expectThrowsCode([&]() { vpSimulatorArm(std::vector<vpSimulatorArm::vpDHRow>(), I, markers, I); },
                   vpProjectiveException::dimensionError);
  std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::pumaTable();
  dh[2].a = std::numeric_limits<double>::infinity();
  expectThrowsCode([&]() { vpSimulatorArm(dh, I, markers, I); }, vpProjectiveException::nonFiniteValueError);
  std::vector<vpColVector> badMarkers = markers;
  badMarkers[4] = vpColVector(4, 1.0);
  expectThrowsCode([&]() { vpSimulatorArm(vpSimulatorArm::pumaTable(), I, badMarkers, I); },
                   vpProjectiveException::dimensionError);
  vpHomogeneousMatrix notRigid;
  notRigid[0][0] = 2.0;
  expectThrowsCode([&]() { vpSimulatorArm(vpSimulatorArm::pumaTable(), I, markers, notRigid); },
                   vpProjectiveException::invalidValueError);
}

TEST(Simulator, BadInputsNameTheProblem)
{
  // The ground-truth classes are public API too: beyond the codes checked above, the construction and the settings
  // reject bad input with a message naming the problem.
  using vpProjectiveTest::throwsProjective;
  const int dimension = vpProjectiveException::dimensionError, nonFinite = vpProjectiveException::nonFiniteValueError,
            invalid = vpProjectiveException::invalidValueError;
  const vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  vpColVector nan(6, 0.0);
  nan[2] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_TRUE(throwsProjective([&] { arm.getMarkers(nan); }, nonFinite, "contains NaN or infinity"));
  EXPECT_TRUE(
      throwsProjective([&] { arm.integrate(vpColVector(6, 0.0), vpColVector(6, 0.0), -1.0); }, invalid, "time step"));
  vpSimulatorArm limited = arm;
  vpColVector qmin(6, 0.0), qmax(6, 1.0);
  qmin[3] = 2.0;
  EXPECT_TRUE(throwsProjective([&] { limited.setJointLimits(qmin, qmax); }, invalid, "joint 3 has qmin"));
  std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::pumaTable();
  dh[1].a = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorArm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(), vpHomogeneousMatrix());
      },
      nonFinite, "Denavit-Hartenberg row 1"));
  std::vector<vpColVector> markers = vpSimulatorArm::gripperMarkers();
  markers[4] = vpColVector(2, 0.0);
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorArm(vpSimulatorArm::pumaTable(), vpSimulatorArm::gripperMount(), markers, vpHomogeneousMatrix());
      },
      dimension, "marker 4 must be a 3x1 point"));

  const vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpCameraParameters bad(-100.0, 100.0, 320.0, 240.0);
  EXPECT_TRUE(throwsProjective(
      [&] { vpSimulatorStereoRig(bad, rig.getRightCameraParameters(), rig.get_rMl(), rig.get_wMl(), 640, 480); },
      invalid, "focal lengths in pixels must be positive"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorStereoRig(rig.getLeftCameraParameters(), rig.getRightCameraParameters(), vpHomogeneousMatrix(),
                             rig.get_wMl(), 640, 480);
      },
      vpProjectiveException::degenerateConfigurationError, "non-zero baseline"));
  EXPECT_TRUE(throwsProjective(
      [&] {
        vpSimulatorStereoRig(rig.getLeftCameraParameters(), rig.getRightCameraParameters(), rig.get_rMl(),
                             rig.get_wMl(), 0, 480);
      },
      invalid, "image size is zero"));
}
