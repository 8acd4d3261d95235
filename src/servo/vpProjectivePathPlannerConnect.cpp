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
  vpProjectivePathPlanner's path of several corners, where no straight joint-space line nor a single waypoint keeps
  the features in view: two trees of feasible joint-space lines grown from the start and from the target toward the
  same random configurations (RRT-Connect), then shortcuts.
*/

#include <visp3/projective/vpProjectivePathPlanner.h>

#include <algorithm>
#include <cmath>
#include <limits>

#include <visp3/core/vpUniRand.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
//! Configurations drawn in the search of a path of several corners, and the longest edge in path steps.
const unsigned int kConnectDraws = 1000;
const double kConnectEdgeSteps = 4.0;
} // namespace

bool vpProjectivePathPlanner::connectPath(const vpProjectiveArmModel &model, const JointVector &q,
                                          const JointVector &target, const std::vector<Eigen::Vector4d> &points,
                                          const JointVector &qmin, const JointVector &qmax,
                                          std::vector<JointVector> &path,
                                          std::vector<std::vector<Eigen::Vector4d>> &features) const
{
  // Two trees of feasible joint-space lines (RRT-Connect), one grown from q and one from the target, each toward
  // configurations drawn over the joint limits in turn, the other tree trying to reach each new node by as many
  // feasible edges as it takes; the joined branches, then shortened where a straight feasible line skips nodes. The
  // configurations where the markers stay in view are a thin set of the joint space that draws over the whole box
  // rarely hit, whereas edges grown from feasible nodes stay near it.
  struct Node {
    JointVector q;
    int parent;
  };
  std::vector<Node> trees[2] = {{{q, -1}}, {{target, -1}}};
  const double edge = kConnectEdgeSteps * getMaxJointStep();
  vpUniRand uniform(0xc0ec7ULL);
  std::vector<std::vector<Eigen::Vector4d>> lineFeatures;
  auto nearest = [](const std::vector<Node> &tree, const JointVector &r) {
    size_t best = 0;
    double distance = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < tree.size(); ++k) {
      const double d = (tree[k].q - r).cwiseAbs().maxCoeff();
      if (d < distance) {
        distance = d;
        best = k;
      }
    }
    return best;
  };
  // One edge from the tree's node nearest to r toward r (at most edge rad per joint): its index, or -1 if blocked.
  auto extend = [&](std::vector<Node> &tree, const JointVector &r) {
    const size_t from = nearest(tree, r);
    const JointVector d = r - tree[from].q;
    const double largest = d.cwiseAbs().maxCoeff();
    const JointVector to = largest > edge ? JointVector(tree[from].q + (edge / largest) * d) : r;
    if (!feasible(model, jointLine(tree[from].q, to), points, lineFeatures)) {
      return -1;
    }
    tree.push_back(Node{to, static_cast<int>(from)});
    return static_cast<int>(tree.size() - 1);
  };
  int a = 0;
  for (unsigned int draw = 0; draw < kConnectDraws; ++draw, a = 1 - a) {
    JointVector r(q.size());
    for (Eigen::Index i = 0; i < q.size(); ++i) {
      r(i) = uniform.uniform(qmin(i), qmax(i));
    }
    const int added = extend(trees[a], r);
    if (added < 0) {
      continue;
    }
    const JointVector goal = trees[a][static_cast<size_t>(added)].q;
    int reached = -1;
    for (int grown = 0; (reached = extend(trees[1 - a], goal)) >= 0; ++grown) {
      if ((trees[1 - a][static_cast<size_t>(reached)].q - goal).cwiseAbs().maxCoeff() < 1e-12) {
        break;
      }
    }
    if (reached < 0) {
      continue;
    }
    // Joined: q's branch to the meeting node, then the target's branch back to the target.
    std::vector<JointVector> nodes;
    const int meet[2] = {a == 0 ? added : reached, a == 0 ? reached : added};
    for (int k = meet[0]; k >= 0; k = trees[0][static_cast<size_t>(k)].parent) {
      nodes.push_back(trees[0][static_cast<size_t>(k)].q);
    }
    std::reverse(nodes.begin(), nodes.end());
    for (int k = trees[1][static_cast<size_t>(meet[1])].parent; k >= 0; k = trees[1][static_cast<size_t>(k)].parent) {
      nodes.push_back(trees[1][static_cast<size_t>(k)].q);
    }
    // Shortcuts: from each kept node, the farthest node a feasible straight line reaches.
    std::vector<JointVector> candidate(1, q);
    for (size_t k = 0; k + 1 < nodes.size();) {
      size_t far = nodes.size() - 1;
      while (far > k + 1 && !feasible(model, jointLine(nodes[k], nodes[far]), points, lineFeatures)) {
        --far;
      }
      const std::vector<JointVector> line = jointLine(nodes[k], nodes[far]);
      candidate.insert(candidate.end(), line.begin() + 1, line.end());
      k = far;
    }
    return feasible(model, path = candidate, points, features);
  }
  return false;
}
