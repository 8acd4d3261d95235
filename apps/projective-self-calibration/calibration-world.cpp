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
  \file calibration-world.cpp
  \brief The self-calibration study's worlds: arms, random rigs with skewed cameras, the acquisition and the frames.
*/

#include "calibration-world.h"

#include <algorithm>
#include <cmath>

#include <Eigen/Geometry>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
Eigen::Matrix4d eigenOf(const vpHomogeneousMatrix &M)
{
  Eigen::Matrix4d E;
  for (unsigned int i = 0; i < 4; ++i) {
    for (unsigned int j = 0; j < 4; ++j) {
      E(i, j) = M[i][j];
    }
  }
  return E;
}

namespace
{
vpHomogeneousMatrix homogeneousOf(const Eigen::Matrix4d &E)
{
  vpHomogeneousMatrix M;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 4; ++j) {
      M[i][j] = E(i, j);
    }
  }
  return M;
}

//! A camera's intrinsics drawn around the focal length \e focal for an image \e width x \e height.
Eigen::Matrix3d randomIntrinsics(double focal, unsigned int width, unsigned int height, vpUniRand &rng)
{
  const double fx = focal * (1.0 + rng.uniform(-0.03, 0.03));
  const double fy = fx * (1.0 + rng.uniform(-0.02, 0.02));
  const double skew = fx * rng.uniform(-0.01, 0.01);
  const double u0 = width * (0.5 + rng.uniform(-0.05, 0.05)), v0 = height * (0.5 + rng.uniform(-0.05, 0.05));
  Eigen::Matrix3d K;
  K << fx, skew, u0, 0.0, fy, v0, 0.0, 0.0, 1.0;
  return K;
}
} // namespace

bool SkewedRig::project(const vpColVector &wX, vpImagePoint &left, vpImagePoint &right, double margin) const
{
  const Eigen::Vector4d X(wX[0], wX[1], wX[2], 1.0);
  const Eigen::Matrix4d lMw = eigenOf(wMl).inverse();
  const Eigen::Vector4d Xl = lMw * X, Xr = eigenOf(rMl) * Xl;
  const Eigen::Vector3d ml = Kl * Xl.head<3>(), mr = Kr * Xr.head<3>();
  left.set_uv(ml(0) / ml(2), ml(1) / ml(2));
  right.set_uv(mr(0) / mr(2), mr(1) / mr(2));
  auto inside = [&](const vpImagePoint &ip) {
    return ip.get_u() >= margin && ip.get_u() <= width - 1.0 - margin && ip.get_v() >= margin &&
           ip.get_v() <= height - 1.0 - margin;
  };
  return Xl(2) > 0.05 && Xr(2) > 0.05 && inside(left) && inside(right);
}

bool SkewedRig::images(const std::vector<vpColVector> &wX, double sigma, vpGaussRand &noise,
                       std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right, double margin) const
{
  left.assign(wX.size(), vpImagePoint());
  right.assign(wX.size(), vpImagePoint());
  noise.setSigmaMean(1.0, 0.0);
  bool visible = true;
  for (size_t j = 0; j < wX.size(); ++j) {
    visible = project(wX[j], left[j], right[j], margin) && visible;
    const double du = sigma * noise(), dv = sigma * noise(), dup = sigma * noise(), dvp = sigma * noise();
    left[j].set_uv(left[j].get_u() + du, left[j].get_v() + dv);
    right[j].set_uv(right[j].get_u() + dup, right[j].get_v() + dvp);
  }
  return visible;
}

StudyArm makeArm(const std::string &name)
{
  StudyArm s{name, vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()), vpColVector(6, 0.0), {}};
  std::vector<double> deg;
  if (name == "puma") {
    deg = {30, 20, 30, 40, 60, 60};
  } else if (name == "viper850") {
    s.arm = vpSimulatorArm::viper850(vpHomogeneousMatrix());
    s.qRef[1] = vpMath::rad(-150.0);
    s.qRef[2] = vpMath::rad(190.0);
    s.qRef[4] = vpMath::rad(-75.0);
    deg = {30, 8, 12, 30, 30, 60};
  } else if (name == "prismatic") {
    s.arm = vpSimulatorArm(vpSimulatorArm::stanfordTable(), vpSimulatorArm::gripperMount(),
                           vpSimulatorArm::gripperMarkers(), vpHomogeneousMatrix());
    s.qRef[1] = vpMath::rad(60.0);
    s.qRef[2] = 0.45;
    s.qRef[4] = vpMath::rad(-50.0);
    deg = {20, 10, 0, 40, 40, 60};
  } else {
    throw vpException(vpException::badValue, "unknown arm '" + name + "'; use puma, viper850 or prismatic");
  }
  for (unsigned int i = 0; i < 6; ++i) {
    s.trials.push_back(s.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? 0.04 : vpMath::rad(deg[i]));
  }
  return s;
}

SkewedRig randomRig(const StudyArm &arm, vpUniRand &rng)
{
  const std::vector<vpColVector> markers = arm.arm.getMarkers(arm.qRef);
  const Eigen::Matrix4d wMt = eigenOf(arm.arm.get_wMt(arm.qRef));
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  for (const vpColVector &X : markers) {
    centre += Eigen::Vector3d(X[0], X[1], X[2]) / static_cast<double>(markers.size());
  }
  const unsigned int sizes[4][2] = {{640, 480}, {800, 600}, {1024, 768}, {1280, 960}};
  for (int draw = 0; draw < 1000; ++draw) {
    const double distance = rng.uniform(0.8, 1.3);
    const double baseline = 2.0 * distance * std::tan(vpMath::rad(rng.uniform(10.0, 30.0)) / 2.0);
    const unsigned int s = std::min(3u, static_cast<unsigned int>(rng.uniform(0.0, 4.0)));
    SkewedRig rig;
    rig.width = sizes[s][0];
    rig.height = sizes[s][1];
    const double focal = rig.width * distance / rng.uniform(0.30, 0.50);
    rig.Kl = randomIntrinsics(focal, rig.width, rig.height, rng);
    rig.Kr = randomIntrinsics(focal, rig.width, rig.height, rng);
    // The rig's frame: looking at the gripper's front face (its outward normal is the tool's -y), the images' up
    // along the tool's z, turned about the gripper and rolled.
    const Eigen::Matrix3d wRt = wMt.topLeftCorner<3, 3>();
    const double azimuth = rng.uniform(-20.0, 20.0), elevation = rng.uniform(-20.0, 20.0),
                 roll = rng.uniform(-10.0, 10.0);
    const Eigen::Matrix3d turn = Eigen::AngleAxisd(vpMath::rad(azimuth), wRt.col(2)).toRotationMatrix() *
                                 Eigen::AngleAxisd(vpMath::rad(elevation), wRt.col(0)).toRotationMatrix();
    Eigen::Matrix3d wRv;
    wRv.col(2) = turn * wRt.col(1);    // viewing direction
    wRv.col(1) = -(turn * wRt.col(2)); // image down
    wRv.col(0) = wRv.col(1).cross(wRv.col(2));
    wRv = wRv * Eigen::AngleAxisd(vpMath::rad(roll), Eigen::Vector3d::UnitZ()).toRotationMatrix();
    Eigen::Matrix4d wMv = Eigen::Matrix4d::Identity();
    wMv.topLeftCorner<3, 3>() = wRv;
    wMv.topRightCorner<3, 1>() = centre;
    // vergingRig() in the view's frame (fixation at its origin, looking along +Z, image down along +Y).
    vpCameraParameters unused;
    const vpSimulatorStereoRig verged =
        vpSimulatorStereoRig::vergingRig(vpColVector(3, 0.0), distance, baseline, unused, rig.width, rig.height);
    rig.wMl = homogeneousOf(wMv * eigenOf(verged.get_wMl()));
    rig.rMl = verged.get_rMl();
    bool visible = true;
    vpImagePoint l, r;
    for (const vpColVector &X : markers) {
      visible = visible && rig.project(X, l, r, 20.0);
    }
    if (visible) {
      return rig;
    }
  }
  throw vpException(vpException::fatalError, "no random rig sees the markers within 1000 draws");
}

SkewedRig withoutSkew(const SkewedRig &rig)
{
  SkewedRig natural = rig;
  natural.Kl(0, 1) = 0.0;
  natural.Kr(0, 1) = 0.0;
  return natural;
}

vpProjectiveRobot acquire(const StudyArm &arm, const SkewedRig &rig, double sigma, unsigned int frames, double rangeDeg,
                          vpGaussRand &noise, vpUniRand &rng)
{
  const unsigned int n = arm.arm.getNumberOfJoints();
  std::vector<vpColVector> q;
  std::vector<std::vector<vpImagePoint>> left, right;
  const auto view = [&](const vpColVector &qk) {
    std::vector<vpImagePoint> l, r;
    if (!rig.images(arm.arm.getMarkers(qk), sigma, noise, l, r)) {
      return false;
    }
    q.push_back(qk);
    left.push_back(l);
    right.push_back(r);
    return true;
  };
  if (!view(arm.qRef)) {
    throw vpException(vpException::fatalError, "the markers are not in view at the zero reference");
  }
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      double amount = sign * arm.trials[i];
      vpColVector qk = arm.qRef;
      qk[i] += amount;
      while (!view(qk)) { // the markers left the view: a smaller trial
        amount /= 2.0;
        qk[i] = arm.qRef[i] + amount;
      }
    }
  }
  const size_t trials = q.size();
  for (unsigned int k = 0, attempts = 0; k < frames; ++attempts) {
    if (attempts > 100000) {
      throw vpException(vpException::fatalError, "no visible random configuration within 100000 draws");
    }
    vpColVector qk = arm.qRef;
    for (unsigned int i = 0; i < n; ++i) {
      const bool prismatic = arm.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC;
      qk[i] += prismatic ? 0.002 * rng.uniform(-rangeDeg, rangeDeg) : vpMath::rad(rng.uniform(-rangeDeg, rangeDeg));
    }
    k += view(qk) ? 1 : 0;
  }
  // The fundamental matrix from the acquisition's matches, as a user estimates it.
  std::vector<vpImagePoint> allLeft, allRight;
  for (size_t k = 0; k < trials; ++k) {
    allLeft.insert(allLeft.end(), left[k].begin(), left[k].end());
    allRight.insert(allRight.end(), right[k].begin(), right[k].end());
  }
  vpProjectiveStereoRig stereo;
  stereo.estimate(allLeft, allRight, std::max(1.0, 4.0 * sigma));
  std::vector<vpProjectiveRobot::vpJointType> types;
  for (unsigned int i = 0; i < n; ++i) {
    types.push_back(arm.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? vpProjectiveRobot::PRISMATIC
                                                                            : vpProjectiveRobot::REVOLUTE);
  }
  vpProjectiveRobot robot(types);
  robot.setStereoRig(stereo);
  robot.setZeroReference(q[0], left[0], right[0]);
  for (size_t k = 1; k < trials; ++k) {
    robot.addTrialMotion(q[k], left[k], right[k]);
  }
  robot.calibrate();
  for (size_t k = trials; k < q.size(); ++k) {
    robot.addCalibrationFrame(q[k], left[k], right[k]);
  }
  return robot;
}

WorldStreams::WorldStreams(unsigned int seed, size_t a)
    : rig(1000003ul * seed + a), view(2000003ul * seed + a), grid(3000017ul * seed + a),
      noise(1.0, 0.0, static_cast<long>(4000037ul * seed + a))
{
}

vpProjectiveSelfCalibration selfCalibration(const vpProjectiveRobot &robot, const StudyArm &arm,
                                            const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames)
{
  vpProjectiveSelfCalibration calibration(robot.getModel(), frames);
  if (arm.name != "prismatic") { // two markers whose distance was measured with a ruler
    const std::vector<vpColVector> X = arm.arm.getMarkers(arm.qRef);
    calibration.setScale(vpProjectiveSelfCalibration::SCALE_MARKER_DISTANCE, 0, 1, (X[0] - X[1]).frobeniusNorm());
  }
  return calibration;
}
} // namespace selfcal
