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
  Helpers for the suites of the projective robot, its stereo feature and its servo (header only, not a test itself):
  simulated arm-and-rig setups with their ground truth, in both mountings.

  An ArmSetup is a vpSimulatorArm, a metric stereo rig and a zero reference qRef (arm joint values). The projective
  model's joint values are q = qArm - qRef. Eye-to-hand: the rig is fixed (wMl), the markers are on the tool.
  Eye-in-hand: the rig rides on the tool (wMl(q) = wMt(q) tMl), the markers are static in the world; each
  configuration then has its own vpSimulatorStereoRig, all with the same K, K', rMl, hence the same F and H_PE.

  Ground truth, independent of the plugin's models: the metric twist of joint i at qRef in the world frame is read off
  the Denavit-Hartenberg frame reached after rows 0..i-1 at qRef (axis z, through the origin of that frame; written
  again in dhTransform(), not taken from the simulator), its 4x4 matrix made by vpMetricTwist's hats, which
  GroundTruthIsConsistent (testProjectiveRobotModel) checks against the simulated motions with the independent
  expm(); in the left camera frame it is lMw Tw wMl (eye-to-hand) or -lMw(qRef) Tw wMl(qRef) (eye-in-hand: the camera
  moves, the scene moves the other way). The true motion of the scene in the left camera frame from qRef to qRef + q is
  lMw wMt(qArm) wMt(qRef)^-1 wMl (eye-to-hand) or wMl(qArm)^-1 wMl(qRef) (eye-in-hand). In both cases the
  projective displacement is H_PE^-1 T H_PE, the generator H_PE^-1 That H_PE.
*/

#ifndef _vpProjectiveArmTestTools_h_
#define _vpProjectiveArmTestTools_h_

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveArmData.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "vpProjectiveTestTools.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveTest
{
//! The paper's trial motions (degrees), joints 0-5.
const double kPaperTrialDeg[6] = {30.0, 20.0, 30.0, 40.0, 60.0, 60.0};

//! \f$ R_z(\theta) T_z(d) T_x(a) R_x(\alpha) \f$, written again here so that the ground truth does not reuse the
//! simulator's code.
inline Eigen::Matrix4d dhTransform(const vpSimulatorArm::vpDHRow &row, double q)
{
  const double theta = row.theta + (row.type == vpProjectiveJoint::REVOLUTE ? q : 0.0);
  const double d = row.d + (row.type == vpProjectiveJoint::PRISMATIC ? q : 0.0);
  const double ct = std::cos(theta), st = std::sin(theta);
  const double ca = std::cos(row.alpha), sa = std::sin(row.alpha);
  Eigen::Matrix4d T;
  T << ct, -st * ca, st * sa, row.a * ct, st, ct * ca, -ct * sa, row.a * st, 0.0, sa, ca, d, 0.0, 0.0, 0.0, 1.0;
  return T;
}

/*!
  A simulated arm, a metric stereo rig mounted eye-to-hand or eye-in-hand, a zero reference and trial amounts.
*/
struct ArmSetup {
  std::string name;
  vpSimulatorArm arm;
  vpColVector qRef; //!< arm joint values of the model's zero reference
  vpProjectiveRobot::vpRigMounting mounting;
  vpCameraParameters camLeft, camRight;
  vpHomogeneousMatrix rMl;
  vpHomogeneousMatrix wMl;               //!< eye-to-hand: the fixed left camera
  vpHomogeneousMatrix tMl;               //!< eye-in-hand: the left camera on the tool
  std::vector<vpColVector> worldMarkers; //!< eye-in-hand: static markers (world, 3x1)
  std::vector<double> trialAmounts;      //!< one per joint (rad or m), used with both signs
  unsigned int width, height;

  ArmSetup(const std::string &setupName, const vpSimulatorArm &simArm, const vpColVector &zeroReference,
           const vpSimulatorStereoRig &sim)
      : name(setupName), arm(simArm), qRef(zeroReference), mounting(vpProjectiveRobot::EYE_TO_HAND),
        camLeft(sim.getLeftCameraParameters()), camRight(sim.getRightCameraParameters()), rMl(sim.get_rMl()),
        wMl(sim.get_wMl()), tMl(), worldMarkers(), trialAmounts(), width(sim.getWidth()), height(sim.getHeight())
  {
  }

  unsigned int n() const { return arm.getNumberOfJoints(); }
  vpColVector armJoints(const vpColVector &qModel) const { return qRef + qModel; }

  std::vector<vpProjectiveRobot::vpJointType> jointTypes() const
  {
    std::vector<vpProjectiveRobot::vpJointType> types(n());
    for (unsigned int i = 0; i < n(); ++i) {
      types[i] = arm.getJointType(i) == vpProjectiveJoint::REVOLUTE ? vpProjectiveRobot::REVOLUTE
                                                                    : vpProjectiveRobot::PRISMATIC;
    }
    return types;
  }

  //! Pose of the left camera at arm joints qArm.
  vpHomogeneousMatrix leftPose(const vpColVector &qArm) const
  {
    return mounting == vpProjectiveRobot::EYE_TO_HAND ? wMl : arm.get_wMt(qArm) * tMl;
  }

  //! The metric rig at arm joints qArm.
  vpSimulatorStereoRig simAt(const vpColVector &qArm) const
  {
    return vpSimulatorStereoRig(camLeft, camRight, rMl, leftPose(qArm), width, height);
  }

  //! The markers (world, 3x1) at arm joints qArm.
  std::vector<vpColVector> markersAt(const vpColVector &qArm) const
  {
    return mounting == vpProjectiveRobot::EYE_TO_HAND ? arm.getMarkers(qArm) : worldMarkers;
  }

  size_t numberOfMarkers() const { return markersAt(qRef).size(); }

  //! Images of all markers at arm joints qArm (noise sigma from \e noise); true if all are \e margin px inside.
  bool images(const vpColVector &qArm, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right, double sigma,
              vpGaussRand &noise, double margin = 10.0) const
  {
    const vpSimulatorStereoRig sim = simAt(qArm);
    const std::vector<vpColVector> X = markersAt(qArm);
    sim.project(X, left, right, sigma, noise);
    for (size_t j = 0; j < X.size(); ++j) {
      if (!sim.isVisible(X[j], margin)) {
        return false;
      }
    }
    return true;
  }

  bool images(const vpColVector &qArm, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right,
              double margin = 10.0) const
  {
    vpGaussRand unused(1.0, 0.0, 1);
    return images(qArm, left, right, 0.0, unused, margin);
  }

  bool visible(const vpColVector &qArm, double margin = 10.0) const
  {
    std::vector<vpImagePoint> left, right;
    return images(qArm, left, right, margin);
  }

  //! Noise-free (u, v, u', v') of marker j at arm joints qArm.
  Eigen::Vector4d imageOf(const vpColVector &qArm, size_t j) const
  {
    vpImagePoint l, r;
    simAt(qArm).project(markersAt(qArm)[j], l, r);
    return Eigen::Vector4d(l.get_u(), l.get_v(), r.get_u(), r.get_v());
  }

  //! A projective rig holding the true F.
  vpProjectiveStereoRig rig() const
  {
    vpProjectiveStereoRig r;
    r.setFundamentalMatrix(simAt(qRef).getFundamentalMatrix());
    return r;
  }

  //! H_PE of \e rig's frame (the same for every configuration: it only depends on K, K', rMl).
  Eigen::Matrix4d Hpe(const vpProjectiveStereoRig &r) const
  {
    return toEigen<4, 4>(simAt(qRef).getProjectiveToEuclidean(r));
  }

  //! World twist of joint i at arm joints qArm, from the Denavit-Hartenberg frames.
  Eigen::Matrix4d worldTwist(unsigned int i, const vpColVector &qArm) const
  {
    const std::vector<vpSimulatorArm::vpDHRow> &dh = arm.getDHTable();
    Eigen::Matrix4d wMi = toEigen<4, 4>(arm.get_wMb());
    for (unsigned int k = 0; k < i; ++k) {
      wMi = wMi * dhTransform(dh[k], qArm[k]);
    }
    const Eigen::Vector3d z = wMi.block<3, 1>(0, 2);
    const Eigen::Vector3d p = wMi.block<3, 1>(0, 3);
    // The plugin's hats (vpMetricTwist): GroundTruthIsConsistent checks them against the simulated motions with the
    // independent expm().
    return dh[i].type == vpProjectiveJoint::REVOLUTE ? vpMetricTwist::revolute(z, p) : vpMetricTwist::prismatic(z);
  }

  //! The metric twist That_i of joint i at the zero reference, in the left camera frame (see the file comment).
  Eigen::Matrix4d cameraTwist(unsigned int i) const
  {
    const Eigen::Matrix4d wMl0 = toEigen<4, 4>(leftPose(qRef));
    const Eigen::Matrix4d T = wMl0.inverse() * worldTwist(i, qRef) * wMl0;
    return mounting == vpProjectiveRobot::EYE_TO_HAND ? T : Eigen::Matrix4d(-T);
  }

  //! The true motion of the markers in the left camera frame from the zero reference to model joints qModel.
  Eigen::Matrix4d cameraMotion(const vpColVector &qModel) const
  {
    const vpColVector qArm = armJoints(qModel);
    if (mounting == vpProjectiveRobot::EYE_TO_HAND) {
      const Eigen::Matrix4d D = toEigen<4, 4>(arm.get_wMt(qArm) * arm.get_wMt(qRef).inverse());
      const Eigen::Matrix4d W = toEigen<4, 4>(wMl);
      return W.inverse() * D * W;
    }
    return toEigen<4, 4>(leftPose(qArm).inverse() * leftPose(qRef));
  }

  //! The true generator H_PE^-1 That_i H_PE of joint i.
  Eigen::Matrix4d trueGenerator(unsigned int i, const Eigen::Matrix4d &H) const
  {
    return H.inverse() * cameraTwist(i) * H;
  }

  /*!
    Acquisition as the plugin's user does it: rig with the true F, mounting, zero-reference images, then one trial
    per joint and sign with trialAmounts (images with Gaussian noise sigma). Returns false if a marker left the view.
    \e corruptTrial, if given, may alter the images of trial k (numbered as addTrialMotion() sees them) before they
    are added, to simulate mismatches.
  */
  bool acquire(vpProjectiveRobot &robot, double sigma, vpGaussRand &noise,
               const std::function<void(unsigned int, std::vector<vpImagePoint> &, std::vector<vpImagePoint> &)>
                   &corruptTrial = nullptr) const
  {
    robot.setStereoRig(rig());
    robot.setRigMounting(mounting);
    std::vector<vpImagePoint> left, right;
    bool ok = images(qRef, left, right, sigma, noise);
    robot.setZeroReference(left, right);
    for (unsigned int i = 0; i < n(); ++i) {
      for (int sign = -1; sign <= 1; sign += 2) {
        vpColVector qModel(n(), 0.0);
        qModel[i] = sign * trialAmounts[i];
        ok = images(armJoints(qModel), left, right, sigma, noise) && ok;
        if (corruptTrial) {
          corruptTrial(2 * i + (sign > 0 ? 1 : 0), left, right);
        }
        robot.addTrialMotion(i, qModel[i], left, right);
      }
    }
    return ok;
  }

  //! Random model joints uniformly within +-range (per joint) of the zero reference with all markers in view.
  vpColVector randomVisibleJoints(vpUniRand &rng, const std::vector<double> &range, double margin = 10.0) const
  {
    for (int attempt = 0; attempt < 100000; ++attempt) {
      vpColVector q(n());
      for (unsigned int i = 0; i < n(); ++i) {
        q[i] = rng.uniform(-range[i], range[i]);
      }
      if (visible(armJoints(q), margin)) {
        return q;
      }
    }
    return vpColVector(); // the caller asserts the size
  }
};

//! Tool pose of the PUMA of the paper at its zero reference: at the world origin, front face towards the paper rig.
inline vpHomogeneousMatrix paperToolPose()
{
  return vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()).get_wMt(vpColVector(6, 0.0));
}

//! Base pose that puts the tool of \e dh (gripper mount) at wMt when the joints are qArm.
inline vpHomogeneousMatrix basePoseFor(const std::vector<vpSimulatorArm::vpDHRow> &dh, const vpColVector &qArm,
                                       const vpHomogeneousMatrix &wMt)
{
  const vpSimulatorArm unplaced(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                                vpHomogeneousMatrix());
  return wMt * unplaced.get_wMt(qArm).inverse();
}

//! Joint values in radians from the 6 values \e deg in degrees.
inline vpColVector radiansOf(const double (&deg)[6])
{
  vpColVector q(6);
  for (unsigned int i = 0; i < 6; ++i) {
    q[i] = vpMath::rad(deg[i]);
  }
  return q;
}

//! The main job's task (apps/projective-paper, 82 cm and 88 deg): its start joint values (rad) on the paper's arm.
inline vpColVector paperTaskStart()
{
  const double deg[6] = {15.4461, 54.9087, -48.3752, 62.3954, 29.0729, 1.7330};
  return radiansOf(deg);
}

//! The main job's task: its target joint values (rad).
inline vpColVector paperTaskTarget()
{
  const double deg[6] = {8.1330, 7.0830, -56.4826, 90.4984, 76.3260, 57.1987};
  return radiansOf(deg);
}

inline vpSimulatorStereoRig paperRigAtOrigin()
{
  return vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
}

//! The paper's setup: PUMA with paperBasePose(), paperRig((0, 0, 0), 1), q_ref = 0, the paper's trials.
inline ArmSetup pumaEyeToHand()
{
  ArmSetup s("PUMA eye-to-hand", vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()), vpColVector(6, 0.0),
             paperRigAtOrigin());
  for (unsigned int i = 0; i < 6; ++i) {
    s.trialAmounts.push_back(vpMath::rad(kPaperTrialDeg[i]));
  }
  return s;
}

/*!
  A revolute-prismatic-revolute chain (R about a vertical axis 45 cm from the tool, a 20 cm-offset prismatic slide,
  R about the last link's axis), its zero reference at non-zero joint values, the tool at the world origin facing
  the paper rig. Trials: 12 deg, 4 cm, 40 deg.
*/
inline std::vector<vpSimulatorArm::vpDHRow> mixedTable()
{
  std::vector<vpSimulatorArm::vpDHRow> dh(3);
  dh[0] = {vpProjectiveJoint::REVOLUTE, 0.0, 0.30, 0.25, M_PI / 2};
  dh[1] = {vpProjectiveJoint::PRISMATIC, M_PI / 2, 0.20, 0.0, M_PI / 2};
  dh[2] = {vpProjectiveJoint::REVOLUTE, 0.3, 0.10, 0.0, 0.0};
  return dh;
}

inline vpColVector mixedZeroReference()
{
  vpColVector q(3);
  q[0] = vpMath::rad(10.0);
  q[1] = 0.05;
  q[2] = vpMath::rad(-20.0);
  return q;
}

inline ArmSetup mixedEyeToHand()
{
  const vpColVector qRef = mixedZeroReference();
  const vpSimulatorArm arm(mixedTable(), vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                           basePoseFor(mixedTable(), qRef, paperToolPose()));
  ArmSetup s("RPR eye-to-hand", arm, qRef, paperRigAtOrigin());
  s.trialAmounts.push_back(vpMath::rad(12.0));
  s.trialAmounts.push_back(0.04);
  s.trialAmounts.push_back(vpMath::rad(40.0));
  return s;
}

/*!
  Eye-in-hand: the paper's cameras on a 20 cm verging rig whose midpoint is 10 cm in front of the tool centre at the
  zero reference, looking at 7 static markers (the gripper's marker layout) around the vergence point 60 cm away.
*/
inline void mountEyeInHand(ArmSetup &s)
{
  const vpColVector fixation = point3(0.0, -0.05, 1.10);
  const vpSimulatorStereoRig rig = vpSimulatorStereoRig::vergingRig(fixation, 1.0, 0.20);
  s.mounting = vpProjectiveRobot::EYE_IN_HAND;
  s.camLeft = rig.getLeftCameraParameters();
  s.camRight = rig.getRightCameraParameters();
  s.rMl = rig.get_rMl();
  s.tMl = s.arm.get_wMt(s.qRef).inverse() * rig.get_wMl();
  vpHomogeneousMatrix wMo(fixation[0], fixation[1], fixation[2], 0.3, 0.2, 0.1); // the marker object
  s.worldMarkers = vpSimulatorStereoRig::transform(wMo, vpSimulatorArm::gripperMarkers());
}

inline ArmSetup pumaEyeInHand()
{
  ArmSetup s = pumaEyeToHand();
  s.name = "PUMA eye-in-hand";
  mountEyeInHand(s);
  s.trialAmounts.assign(6, vpMath::rad(4.0));
  return s;
}

inline ArmSetup mixedEyeInHand()
{
  ArmSetup s = mixedEyeToHand();
  s.name = "RPR eye-in-hand";
  mountEyeInHand(s);
  s.trialAmounts[0] = vpMath::rad(4.0);
  s.trialAmounts[1] = 0.04;
  s.trialAmounts[2] = vpMath::rad(4.0);
  return s;
}

/*!
  vpViper850 geometry with the gripper, its tool at paperToolPose() (world origin, markers facing the paper rig) at
  the zero reference qRef = (0, -150, 190, 0, -75, 0) deg, the base pose following from that. qRef was chosen by an
  offline grid search (q1 in [-150, 20], q2 in [0, 230] by 10 deg, q4 in [-90, 90] by 15 deg, |sin q4| >= 0.5 to
  stay off the wrist singularity, base at least 30 cm below the tool and not in front of the rig), maximising the
  smallest single-joint range that keeps the 7 markers 10 px inside both images, relative to the paper's amounts:
  from qRef, joints move within j0 [-90, 43], j1 [-10, 10], j2 [-14, 15], j3 [-90, 36], j4 [-34, 34], j5 [-90, 90] deg
  (the Viper's 18 cm wrist-to-flange distance and 77 cm reach make the view narrower than the PUMA's); 45 % of
  random configurations within +-20 deg of qRef keep all markers in view. Trials: 30, 8, 12, 30, 30, 60 deg.
*/
inline vpColVector viperZeroReference()
{
  vpColVector q(6, 0.0);
  q[1] = vpMath::rad(-150.0);
  q[2] = vpMath::rad(190.0);
  q[4] = vpMath::rad(-75.0);
  return q;
}

inline ArmSetup viperEyeToHand()
{
  const vpColVector qRef = viperZeroReference();
  const std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::viper850(vpHomogeneousMatrix()).getDHTable();
  ArmSetup s("Viper850 eye-to-hand", vpSimulatorArm::viper850(basePoseFor(dh, qRef, paperToolPose())), qRef,
             paperRigAtOrigin());
  const double trialDeg[6] = {30.0, 8.0, 12.0, 30.0, 30.0, 60.0};
  for (unsigned int i = 0; i < 6; ++i) {
    s.trialAmounts.push_back(vpMath::rad(trialDeg[i]));
  }
  return s;
}

/*!
  The setup's acquisition (its trials, both ways) at pixel noise \e sigma drawn from \e seed, then calibrate(): the
  robot every servo, capture and self-calibration test starts from. A marker leaving the view fails the test.
*/
inline vpProjectiveRobot calibratedRobot(const ArmSetup &s, double sigma = 0.0, long seed = 1)
{
  vpProjectiveRobot robot(s.jointTypes());
  vpGaussRand noise(1.0, 0.0, seed);
  EXPECT_TRUE(s.acquire(robot, sigma, noise)) << s.name << ": a marker left the view during the acquisition";
  robot.calibrate();
  return robot;
}

//! The model's joints' motions \f$ \hat H_{k,q} \f$ (eq. (39)) at the readings \e q (ViSP types), written to HhatKq.
inline void jointMotions(const vpProjectiveArmModel &model, const vpColVector &q, Eigen::Matrix4d *HhatKq)
{
  vpProjectiveArmData data;
  vpProjectiveKinematics::forwardKinematics(model, data, toEigenV(q));
  std::copy(data.getJointMotions(), data.getJointMotions() + model.getNumberOfJoints(), HhatKq);
}

//! The model's point Jacobian \f$ J_H(q, M) \f$ (4 x n, eqs. (42)-(44)) at the readings \e q for the point \e M.
inline Eigen::MatrixXd pointJacobian(const vpProjectiveArmModel &model, const vpColVector &q, const vpColVector &M)
{
  vpProjectiveArmData data;
  vpProjectiveKinematics::forwardKinematics(model, data, toEigenV(q));
  vpProjectiveArmModel::PointJacobian JH;
  vpProjectiveKinematics::pointJacobian(model, data, toEigen4(M), JH);
  return JH;
}

} // namespace vpProjectiveTest

#endif
