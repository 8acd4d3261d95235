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
  \file vpSimulatorStereoCell.cpp
  \brief The rendered cell: tags moved with the tool (or the scene with the rig), rendered by vpSimulatorTagRenderer.
*/

#include <visp3/projective/vpSimulatorStereoCell.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <sstream>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpTranslationVector.h>

#include "core/vpProjectiveErrors.h"

vpSimulatorStereoCell::vpSimulatorStereoCell(const vpSimulatorArm &arm, const vpSimulatorStereoRig &rig,
                                             const vpColVector &q0, long seed)
    : m_robot(arm, q0), m_rig0(rig), m_renderer(rig, seed), m_rig(rig), m_toolTags(), m_sceneTags(), m_eyeInHand(false),
      m_eMw0(), m_frameRate(0.0), m_latency(0.0), m_skew(0.0), m_dropRate(0.0), m_timingSeed(1),
      m_lastFrame(std::numeric_limits<long>::min()), m_stampLeft(std::numeric_limits<double>::quiet_NaN()),
      m_stampRight(std::numeric_limits<double>::quiet_NaN()), m_scratch()
{
}

unsigned int vpSimulatorStereoCell::addToolTag(int id, double size, const vpHomogeneousMatrix &tMg)
{
  const vpColVector q = m_robot.getArmJoints();
  const unsigned int index = m_renderer.addTag(id, size, m_robot.getArm().get_wMt(q) * tMg);
  m_toolTags.push_back({index, tMg});
  m_sceneTags.push_back(vpHomogeneousMatrix());
  update(m_robot.getArmJoints());
  return index;
}

void vpSimulatorStereoCell::addToolTags(double size, int firstId)
{
  // The holder's tags face -y_t (the gripper's face towards the rig): a tag's z (into the print) is +y_t, its x
  // along x_t, its y = z x x = -z_t. The outer two are turned by 55 deg about z_t and moved aside so that their quiet
  // zones (10/8 of the side) do not overlap the middle one's.
  const vpRotationMatrix tRg(-M_PI / 2.0, 0.0, 0.0); // theta-u: -90 deg about x_t
  const double front = -0.03 - 0.5 * size;           // in front of the gripper's face (y_t = -2 cm)
  const double turn = vpMath::rad(55.0);
  const double halfWidth = 0.65 * size; // half the quiet zone's side (10/16 of the side), and a small gap
  for (int k = -1; k <= 1; k++) {
    // A convex tent seen from -y_t: the outer facets hinge on the middle one's edges and recede by 55 deg (at 35 deg,
    // 12 corners seen from 1 m were within 1.5 px of one homography: too flat for the acquisition).
    const vpRotationMatrix tRturn(0.0, 0.0, k * turn);
    const vpTranslationVector t(k * halfWidth * (1.0 + std::cos(turn)),
                                front + std::abs(k) * halfWidth * std::sin(turn), 0.0);
    addToolTag(firstId + k + 1, size, vpHomogeneousMatrix(t, tRturn * tRg));
  }
}

unsigned int vpSimulatorStereoCell::addSceneTag(int id, double size, const vpHomogeneousMatrix &wMg)
{
  const unsigned int index = m_renderer.addTag(id, size, wMg);
  m_sceneTags.push_back(wMg);
  update(m_robot.getArmJoints());
  return index;
}

void vpSimulatorStereoCell::setEyeInHand()
{
  m_eMw0 = m_robot.getArm().get_wMe(m_robot.getArmJoints()).inverse();
  m_eyeInHand = true;
  update(m_robot.getArmJoints());
}

void vpSimulatorStereoCell::update(const vpColVector &q)
{
  // The renderer's rig stays where it was given (m_rig0). Eye-in-hand, the world moves instead by the inverse of the
  // last link's motion A(q) = wMe(q) eMw0 since setEyeInHand(): what the moved cameras see of a tag at wMg is what the
  // fixed ones see of a tag at A^-1 wMg.
  vpHomogeneousMatrix A;
  if (m_eyeInHand) {
    A = m_robot.getArm().get_wMe(q) * m_eMw0;
  }
  const vpHomogeneousMatrix Ainv = A.inverse();
  const vpHomogeneousMatrix wMt = m_robot.getArm().get_wMt(q);
  std::vector<bool> isTool(m_renderer.getNbTags(), false);
  for (const ToolTag &tag : m_toolTags) {
    isTool[tag.index] = true;
    m_renderer.setTagPose(tag.index, Ainv * wMt * tag.tMg);
  }
  for (unsigned int i = 0; i < m_renderer.getNbTags(); i++) {
    if (!isTool[i]) {
      m_renderer.setTagPose(i, Ainv * m_sceneTags[i]);
    }
  }
  m_rig = m_eyeInHand
              ? vpSimulatorStereoRig(m_rig0.getLeftCameraParameters(), m_rig0.getRightCameraParameters(),
                                     m_rig0.get_rMl(), A * m_rig0.get_wMl(), m_rig0.getWidth(), m_rig0.getHeight())
              : m_rig0;
}

void vpSimulatorStereoCell::setTiming(double frameRate, double latency, double skew, double dropRate, long seed)
{
  const vpProjectiveInternal::vpErrorSite at("vpSimulatorStereoCell");
  if (!std::isfinite(frameRate) || frameRate < 0.0 || !std::isfinite(latency) || latency < 0.0 ||
      !std::isfinite(skew) || !(dropRate >= 0.0 && dropRate <= 0.9)) {
    std::ostringstream os;
    os << "give a frame rate >= 0 (Hz), a latency >= 0 (s), a finite skew (s) and a drop rate in [0, 0.9], not "
       << frameRate << ", " << latency << ", " << skew << ", " << dropRate;
    vpProjectiveInternal::fail(vpProjectiveException::invalidValueError, at("setTiming()"), os.str());
  }
  m_frameRate = frameRate;
  m_latency = latency;
  m_skew = skew;
  m_dropRate = dropRate;
  m_timingSeed = seed;
  m_lastFrame = std::numeric_limits<long>::min();
}

bool vpSimulatorStereoCell::dropped(long frame) const
{
  // SplitMix64 of (seed, frame): each frame's fate is fixed, whatever order the frames are asked in.
  uint64_t z = static_cast<uint64_t>(m_timingSeed) * 0x9E3779B97F4A7C15ULL + static_cast<uint64_t>(frame);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ULL;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBULL;
  z ^= z >> 31;
  return static_cast<double>(z >> 11) * (1.0 / 9007199254740992.0) < m_dropRate;
}

bool vpSimulatorStereoCell::acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright)
{
  if (m_frameRate <= 0.0) {
    m_stampLeft = m_stampRight = m_robot.getTime();
    update(m_robot.getArmJoints());
    m_renderer.render(Ileft, Iright);
    return true;
  }
  // Frame k: left at k T, right at k T + skew, delivered at the later of the two plus the latency.
  const double T = 1.0 / m_frameRate, delay = std::max(0.0, m_skew) + m_latency;
  const double now = m_robot.getTime();
  long k = static_cast<long>(std::floor((now - delay) / T + 1e-9));
  while (k > m_lastFrame && dropped(k)) {
    --k;
  }
  if (k <= m_lastFrame) { // nothing new: wait for the next frame that is not lost
    k = std::max(m_lastFrame + 1, static_cast<long>(std::floor((now - delay) / T + 1e-9)) + 1);
    while (dropped(k)) {
      ++k;
    }
    m_robot.wait(std::max(0.0, k * T + delay - now));
  }
  m_lastFrame = k;
  m_stampLeft = k * T;
  m_stampRight = k * T + m_skew;
  update(m_robot.getArmJointsAt(m_stampLeft));
  if (m_skew == 0.0) {
    m_renderer.render(Ileft, Iright);
  } else {
    m_renderer.render(Ileft, m_scratch);
    update(m_robot.getArmJointsAt(m_stampRight));
    m_renderer.render(m_scratch, Iright);
  }
  update(m_robot.getArmJoints());
  return true;
}

bool vpSimulatorStereoCell::getTimestamps(double &left, double &right) const
{
  if (std::isnan(m_stampLeft)) {
    return false;
  }
  left = m_stampLeft;
  right = m_stampRight;
  return true;
}

unsigned int vpSimulatorStereoCell::getTrueCorners(std::vector<int> &ids, std::vector<vpImagePoint> &left,
                                                   std::vector<vpImagePoint> &right)
{
  update(m_robot.getArmJoints());
  std::vector<int> allIds;
  std::vector<vpImagePoint> allLeft, allRight;
  for (unsigned int i = 0; i < m_renderer.getNbTags(); i++) {
    std::vector<vpImagePoint> l, r;
    if (m_renderer.getImageCorners(i, l, r)) {
      for (unsigned int c = 0; c < 4; c++) {
        allIds.push_back(4 * m_renderer.getTagId(i) + static_cast<int>(c));
        allLeft.push_back(l[c]);
        allRight.push_back(r[c]);
      }
    }
  }
  std::vector<size_t> order(allIds.size());
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&allIds](size_t a, size_t b) { return allIds[a] < allIds[b]; });
  ids.clear();
  left.clear();
  right.clear();
  for (size_t k : order) {
    ids.push_back(allIds[k]);
    left.push_back(allLeft[k]);
    right.push_back(allRight[k]);
  }
  return static_cast<unsigned int>(ids.size());
}
