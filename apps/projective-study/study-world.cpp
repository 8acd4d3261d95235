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
  \file study-world.cpp
  \brief The study's world: random streams, branches, images.
*/

#include "study-world.h"

#include "study-ibvs.h"

#include <algorithm>
#include <cmath>

#include <visp3/core/vpException.h>
#include <visp3/core/vpExponentialMap.h>
#include <visp3/core/vpUniRand.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
namespace
{
//! Base pose that puts the tool of \e dh (gripper mount) at \e wMt when the joints are qArm.
vpHomogeneousMatrix basePoseFor(const std::vector<vpSimulatorArm::vpDHRow> &dh, const vpColVector &qArm,
                                const vpHomogeneousMatrix &wMt)
{
  const vpSimulatorArm unplaced(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                                vpHomogeneousMatrix());
  return wMt * unplaced.get_wMt(qArm).inverse();
}

vpColVector degrees(const std::vector<double> &values)
{
  vpColVector q(static_cast<unsigned int>(values.size()));
  for (unsigned int i = 0; i < q.size(); ++i) {
    q[i] = vpMath::rad(values[i]);
  }
  return q;
}

//! q_4 where the axes of joints 3 and 5 of a spherical wrist align (theta_4 = 0 mod pi), the one nearest q = 0 (deg).
double wristSingularity(const vpSimulatorArm &arm)
{
  double q4 = -vpMath::deg(arm.getDHTable()[4].theta);
  while (q4 > 90.0) {
    q4 -= 180.0;
  }
  while (q4 <= -90.0) {
    q4 += 180.0;
  }
  return q4;
}
} // namespace

void World::box(unsigned int i, double &lower, double &upper) const
{
  if (arm.getJointType(i) == vpProjectiveJoint::PRISMATIC) {
    lower = std::max(-prismaticPerDeg * boxDeg, arm.getJointMin()[i]);
    upper = std::min(prismaticPerDeg * boxDeg, arm.getJointMax()[i]);
  } else {
    lower = std::max(-boxDeg, vpMath::deg(arm.getJointMin()[i]));
    upper = std::min(boxDeg, vpMath::deg(arm.getJointMax()[i]));
  }
}

vpSimulatorArm shiftedArm(const vpSimulatorArm &arm, const vpColVector &qRef)
{
  std::vector<vpSimulatorArm::vpDHRow> dh = arm.getDHTable();
  for (unsigned int i = 0; i < dh.size(); ++i) {
    (dh[i].type == vpProjectiveJoint::REVOLUTE ? dh[i].theta : dh[i].d) += qRef[i];
  }
  vpSimulatorArm shifted(dh, arm.get_eMt(), arm.getToolMarkers(), arm.get_wMb());
  shifted.setJointLimits(arm.getJointMin() - qRef, arm.getJointMax() - qRef);
  return shifted;
}

World makeWorld(const std::string &armName)
{
  World world;
  const vpHomogeneousMatrix wMt = world.arm.get_wMt(vpColVector(6, 0.0)); // the PUMA's zero-reference tool pose
  if (armName == "puma") {
    return world;
  }
  world.name = armName;
  world.pumaBranches = false;
  if (armName == "viper850") {
    const vpColVector qRef = degrees({0, -150, 190, 0, -75, 0});
    const std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::viper850(vpHomogeneousMatrix()).getDHTable();
    world.arm = shiftedArm(vpSimulatorArm::viper850(basePoseFor(dh, qRef, wMt)), qRef);
    world.trials = {vpMath::rad(30), vpMath::rad(8),  vpMath::rad(12),
                    vpMath::rad(30), vpMath::rad(30), vpMath::rad(60)};
  } else if (armName == "prismatic") {
    vpColVector qRef = degrees({0, 60, 0, 0, -50, 0});
    qRef[2] = 0.45;
    const std::vector<vpSimulatorArm::vpDHRow> dh = vpSimulatorArm::stanfordTable();
    vpSimulatorArm arm(dh, vpSimulatorArm::gripperMount(), vpSimulatorArm::gripperMarkers(),
                       basePoseFor(dh, qRef, wMt));
    vpColVector qmin = degrees({-170, -170, 0, -170, -120, -170}), qmax = degrees({170, 170, 0, 170, 120, 170});
    qmin[2] = 0.25;
    qmax[2] = 0.75;
    arm.setJointLimits(qmin, qmax);
    world.arm = shiftedArm(arm, qRef);
    world.trials = {vpMath::rad(20), vpMath::rad(10), 0.04, vpMath::rad(40), vpMath::rad(40), vpMath::rad(60)};
  } else {
    throw vpException(vpException::badValue, "unknown world '" + armName + "'; use puma, viper850 or prismatic");
  }
  world.wristSingularDeg = wristSingularity(world.arm);
  return world;
}

vpSimulatorStereoRig randomRig(const World &world, unsigned int seed, RigDraw &draw)
{
  vpUniRand rng(static_cast<uint64_t>(streamSeed(seed, RIG_STREAM)));
  const std::vector<vpColVector> markers = world.arm.getMarkers(vpColVector(world.arm.getNumberOfJoints(), 0.0));
  vpColVector fixation(3, 0.0);
  for (unsigned int k : world.tracked) {
    fixation += markers[k] * (1.0 / world.nbPoints());
  }
  const unsigned int sizes[4][2] = {{640, 480}, {800, 600}, {1024, 768}, {1280, 960}};
  vpColVector vertical(3, 0.0), horizontal(3, 0.0);
  vertical[1] = 1.0;
  horizontal[0] = 1.0;
  for (draw.draws = 1; draw.draws <= 1000; ++draw.draws) {
    draw.distance = rng.uniform(0.7, 1.4);
    draw.vergenceDeg = rng.uniform(10.0, 30.0);
    draw.baseline = 2.0 * draw.distance * std::tan(vpMath::rad(draw.vergenceDeg) / 2.0);
    const unsigned int s = std::min(3u, static_cast<unsigned int>(rng.uniform(0.0, 4.0)));
    draw.width = sizes[s][0];
    draw.height = sizes[s][1];
    const double field = rng.uniform(0.30, 0.55);
    draw.focal = draw.width * draw.distance / field;
    draw.azimuthDeg = rng.uniform(-20.0, 20.0);
    draw.elevationDeg = rng.uniform(-15.0, 15.0);
    vpCameraParameters cam;
    cam.initPersProjWithoutDistortion(draw.focal, draw.focal, draw.width / 2.0, draw.height / 2.0);
    const vpSimulatorStereoRig verged =
        vpSimulatorStereoRig::vergingRig(fixation, draw.distance, draw.baseline, cam, draw.width, draw.height);
    const vpHomogeneousMatrix turn =
        vpSimulatorStereoRig::rotationAbout(fixation, vertical, vpMath::rad(draw.azimuthDeg)) *
        vpSimulatorStereoRig::rotationAbout(fixation, horizontal, vpMath::rad(draw.elevationDeg));
    const vpSimulatorStereoRig rig(cam, cam, verged.get_rMl(), turn * verged.get_wMl(), draw.width, draw.height);
    bool visible = true;
    for (unsigned int k : world.tracked) {
      visible = visible && rig.isVisible(markers[k], world.marginPx);
    }
    if (visible) {
      return rig;
    }
  }
  throw vpException(vpException::fatalError,
                    "task " + std::to_string(seed) + ": no random rig sees the markers within 1000 draws");
}

bool otherBranch(const World &world, const vpColVector &qPlanned, const vpColVector &qTarget)
{
  if (world.pumaBranches) {
    return !(branchOf(world.arm, qPlanned) == branchOf(world.arm, qTarget));
  }
  // The inverse-kinematic solution of the true target's tool pose nearest the plan's target: Gauss-Newton on the
  // true arm from qPlanned (spatial Jacobian, the pose error as a twist).
  const ArmJacobian jacobian(world.arm);
  const vpHomogeneousMatrix wMt = world.arm.get_wMt(qTarget);
  vpColVector q = qPlanned;
  bool converged = false;
  for (unsigned int it = 0; it < 100 && !converged; ++it) {
    const vpColVector error = vpExponentialMap::inverse(wMt * world.arm.get_wMt(q).inverse());
    converged = error.frobeniusNorm() < 1e-10;
    q += jacobian.spatial(q).pseudoInverse(1e-9) * error;
  }
  if (!converged) {
    return true; // no solution near the plan's target: it was not on the true target's solution
  }
  for (unsigned int i = 0; i < q.size(); ++i) {
    double d = q[i] - qTarget[i];
    if (world.arm.getJointType(i) == vpProjectiveJoint::REVOLUTE) {
      d = std::remainder(d, 2.0 * M_PI);
    }
    if (std::abs(d) > 1e-6) {
      return true;
    }
  }
  return false;
}

long streamSeed(unsigned int seed, unsigned int stream)
{
  uint64_t z = (static_cast<uint64_t>(seed) << 16) + stream + 0x9E3779B97F4A7C15ULL;
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<long>(z >> 1);
}

Branch branchOf(const vpSimulatorArm &arm, const vpColVector &q)
{
  const std::vector<vpSimulatorArm::vpDHRow> &dh = arm.getDHTable();
  const double t1 = dh[1].theta + q[1], t2 = dh[2].theta + q[2], t4 = dh[4].theta + q[4];
  const double reach = dh[1].a * std::cos(t1) - dh[3].d * std::sin(t1 + t2);
  return Branch{reach > 0 ? 1 : -1, std::cos(t2) > 0 ? 1 : -1, std::sin(t4) > 0 ? 1 : -1};
}

bool trueImages(const World &world, const vpColVector &q, std::vector<vpImagePoint> &left,
                std::vector<vpImagePoint> &right)
{
  const std::vector<vpColVector> markers = world.arm.getMarkers(q);
  left.resize(world.nbPoints());
  right.resize(world.nbPoints());
  bool visible = true;
  for (unsigned int k = 0; k < world.nbPoints(); ++k) {
    visible = world.rig.project(markers[world.tracked[k]], left[k], right[k]) && visible;
  }
  return visible;
}

app::ImagesAt trueImagesAt(const World &world)
{
  return [&world](const vpColVector &q, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) {
    return trueImages(world, q, left, right);
  };
}

bool acceptable(const World &world, const vpColVector &q)
{
  for (unsigned int i = 0; i < q.size(); ++i) {
    if (q[i] < world.arm.getJointMin()[i] || q[i] > world.arm.getJointMax()[i]) {
      return false;
    }
  }
  const std::vector<vpColVector> markers = world.arm.getMarkers(q);
  for (unsigned int k : world.tracked) {
    if (!world.rig.isVisible(markers[k], world.marginPx)) {
      return false;
    }
  }
  return true;
}
} // namespace study
