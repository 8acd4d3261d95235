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

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
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

tutorial::ImagesAt trueImagesAt(const World &world)
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
