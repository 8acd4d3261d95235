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
  The robust estimation of a p-displacement from stereo images with mismatched correspondences (5-point hypotheses,
  local optimisation, MSAC, rigidity test): see the documentation of vpProjectiveDisplacement::estimateRobust().
*/

#include <visp3/projective/vpProjectiveDisplacement.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#include "rig/vpDisplacementAdjustment.h"
#include "rig/vpDisplacementHypothesis.h"
#include "core/vpProjection.h"
#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
// Largest rigidity statistic (DisplacementAdjustment::rigidityStatistic()) of a robust estimate.
const double kRigidityBound = 8.0;
const vpErrorSite at("vpProjectiveDisplacement");

//! The squared errors d_j^2 of every point under H (mean over the four images, see the header) and, optionally, the
//! best-fitting points.
void pointErrors(const DisplacementData &data, const Eigen::Matrix4d &H, std::vector<double> &d2,
                 std::vector<Eigen::Vector4d> *points = nullptr)
{
  vpProjectiveStereoRig::Projection P, Pp;
  data.rig->getLeftProjection(P);
  data.rig->getRightProjection(Pp);
  GoldStandardPoint gold;
  gold.setDisplacement(P, Pp, H);
  d2.resize(data.size());
  std::vector<int> side(data.size());
  int votes = 0;
  for (size_t j = 0; j < data.size(); ++j) {
    Eigen::Vector4d M = data.M0[j];
    d2[j] = 0.25 * gold.squaredError(data.s[j], M);
    side[j] = gold.cheirality(M);
    votes += std::isfinite(d2[j]) ? side[j] : 0;
    if (points) {
      (*points)[j] = M;
    }
  }
  // A point on the other side of the cameras than most (it reached its images through infinity) does not move with H.
  const int sign = votes < 0 ? -1 : 1;
  for (size_t j = 0; j < data.size(); ++j) {
    if (side[j] != sign) {
      d2[j] = std::numeric_limits<double>::infinity();
    }
  }
}
//! Truncated quadratic cost sum_j min(d_j^2, t^2) (MSAC) and the support #{d_j <= t}.
struct RobustScore {
  double cost = std::numeric_limits<double>::infinity();
  size_t support = 0;
};

//! A fit of the robust estimation: its score, the homography, the points' squared errors and best-fitting points,
//! and the points it was fitted to (empty for a 5-point hypothesis).
struct RobustFit {
  RobustScore score;
  Eigen::Matrix4d H = Eigen::Matrix4d::Zero();
  std::vector<double> errors;
  std::vector<Eigen::Vector4d> points;
  std::vector<bool> fitted;
};

RobustScore msac(const std::vector<double> &d2, double threshold)
{
  const double t2 = threshold * threshold;
  RobustScore score;
  score.cost = 0.0;
  for (double e : d2) {
    score.cost += std::min(e, t2);
    score.support += e <= t2 ? 1 : 0;
  }
  return score;
}

std::vector<bool> within(const std::vector<double> &d2, double threshold)
{
  std::vector<bool> flags(d2.size());
  for (size_t j = 0; j < d2.size(); ++j) {
    flags[j] = d2[j] <= threshold * threshold;
  }
  return flags;
}
/*
  Local optimisation of a hypothesis (LO-RANSAC, Chum, Matas and Kittler 2003): a 5-point hypothesis predicts the
  other points far less accurately than a fit on all of its inliers (an exact fit amplifies the noise), so it is
  refitted by maximum likelihood on the points \e rough, then on those within \e threshold of that fit, until the
  inliers are stable; a fit that is no rigid displacement (rigidityStatistic()) ends it. \e fit holds the hypothesis
  (H, errors, points) and gets the best fit by the MSAC cost at \e threshold (or the hypothesis itself, with empty
  fitted points).
*/
void localOptimisation(const DisplacementData &data, const DisplacementAdjustment &adjustment, double threshold,
                       const std::vector<bool> &rough, RobustFit &fit)
{
  fit.score = msac(fit.errors, threshold);
  fit.fitted.clear();
  std::vector<bool> flags = rough;
  Eigen::Matrix4d Hcurrent = fit.H;
  std::vector<Eigen::Vector4d> current = fit.points;
  for (int round = 0; round < 3 && std::count(flags.begin(), flags.end(), true) >= 5; ++round) {
    if (!adjustment.refine(flags, Hcurrent, current, 15, 1e-6)) {
      break;
    }
    std::vector<double> e2;
    pointErrors(data, Hcurrent, e2, &current);
    const RobustScore score = msac(e2, threshold);
    if (score.cost < fit.score.cost) {
      if (!(adjustment.rigidityStatistic(flags, Hcurrent, current, 0.1 * threshold) <= kRigidityBound)) {
        break; // a homography that absorbed mismatches, not a displacement
      }
      fit.score = score;
      fit.H = Hcurrent;
      fit.errors = e2;
      fit.points = current;
      fit.fitted = flags;
    }
    const std::vector<bool> next = within(e2, threshold);
    if (next == flags) {
      break;
    }
    flags = next;
  }
}
//! Adds to \e flags the points of smallest finite error until at least \e count are flagged.
void nearestFirst(const std::vector<double> &d2, size_t count, std::vector<bool> &flags)
{
  std::vector<size_t> order(d2.size());
  for (size_t j = 0; j < order.size(); ++j) {
    order[j] = j;
  }
  std::sort(order.begin(), order.end(), [&d2](size_t a, size_t b) { return d2[a] < d2[b]; });
  size_t flagged = static_cast<size_t>(std::count(flags.begin(), flags.end(), true));
  for (size_t k = 0; k < order.size() && flagged < count && std::isfinite(d2[order[k]]); ++k) {
    if (!flags[order[k]]) {
      flags[order[k]] = true;
      ++flagged;
    }
  }
}
// C(n, k), saturated at cap + 1.
size_t binomialCapped(size_t n, size_t k, size_t cap)
{
  double c = 1.0;
  for (size_t i = 0; i < k; ++i) {
    c = c * static_cast<double>(n - i) / static_cast<double>(i + 1);
  }
  return c > static_cast<double>(cap) ? cap + 1 : static_cast<size_t>(std::llround(c));
}
} // namespace

vpProjectiveDisplacement vpProjectiveDisplacement::estimate(const vpProjectiveStereoRig &rig,
                                                            const std::vector<vpImagePoint> &left0,
                                                            const std::vector<vpImagePoint> &right0,
                                                            const std::vector<vpImagePoint> &left1,
                                                            const std::vector<vpImagePoint> &right1,
                                                            double inlierThreshold, std::vector<bool> &inliers)
{
  const std::string where = at("estimate()");
  std::vector<Eigen::Vector4d> s0, s1;
  stackImagePairs(left0, right0, left1, right1, where, s0, s1);
  return vpProjectiveDisplacement(estimateRobust(rig, s0, s1, inlierThreshold, inliers));
}
Eigen::Matrix4d vpProjectiveDisplacement::estimateRobust(const vpProjectiveStereoRig &rig,
                                                         const std::vector<Eigen::Vector4d> &s0,
                                                         const std::vector<Eigen::Vector4d> &s1, double inlierThreshold,
                                                         std::vector<bool> &inliers, int maxIterations)
{
  const std::string where = at("estimateRobust()");
  if (!rig.isInitialized()) {
    fail(vpProjectiveException::notInitializedError, where,
         "the stereo rig has no fundamental matrix; estimate it or set it before estimating displacements");
  }
  const size_t n = s0.size();
  if (s1.size() != n) {
    std::ostringstream os;
    os << "got " << n << " points before the motion but " << s1.size() << " after; pass the same points in the same "
       << "order";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  if (n < 5) {
    std::ostringstream os;
    os << "needs at least 5 points seen before and after the motion, got " << n;
    fail(vpProjectiveException::notEnoughPointsError, where, os.str());
  }
  for (size_t j = 0; j < n; ++j) {
    if (!s0[j].allFinite() || !s1[j].allFinite()) {
      fail(vpProjectiveException::nonFiniteValueError, where, "an image point is not finite (NaN or infinity)");
    }
  }
  positive(inlierThreshold, where, "the inlier threshold", "pixels, e.g. 3 times the image noise");
  if (maxIterations < 1) {
    fail(vpProjectiveException::invalidValueError, where, "maxIterations (the number of 5-point sets) must be >= 1");
  }

  // Projective points, and the whitened unit points the minimal solver works on.
  const DisplacementData data(rig, s0, s1);
  const DisplacementAdjustment adjustment(data);

  // Hypotheses from minimal sets: all of them in lexicographic order when they are few, else seeded random draws
  // with adaptive stopping. A hypothesis that more points roughly agree with (within the loose threshold) than the
  // best so far agree with precisely is locally optimised.
  const double loose = 4.0 * inlierThreshold;
  const size_t budget = static_cast<size_t>(maxIterations);
  const bool enumerate = binomialCapped(n, 5, budget) <= budget;
  vpUniRand rng(0x5eedULL);
  size_t subset[5] = {0, 1, 2, 3, 4};
  size_t needed = budget;
  RobustFit best;
  std::vector<std::vector<bool>> tried; // the rough inlier sets already locally optimised
  struct Rival {
    std::vector<bool> inliers;
    double cost; // MSAC cost
  };
  std::vector<Rival> rivals; // the rigid fits found by the local optimisation
  const size_t required = n >= 6 ? 6 : 5;
  bool found = false, reversed = false;
  for (size_t iteration = 0; iteration < needed; ++iteration) {
    if (enumerate) {
      if (iteration > 0) { // next 5-combination of {0..n-1}
        int k = 4;
        while (k >= 0 && subset[k] == n - 5 + static_cast<size_t>(k)) {
          --k;
        }
        if (k < 0) {
          break;
        }
        ++subset[k];
        for (int l = k + 1; l < 5; ++l) {
          subset[l] = subset[l - 1] + 1;
        }
      }
    } else {
      for (int k = 0; k < 5; ++k) {
        do {
          subset[k] = static_cast<size_t>(rng.uniform(0, static_cast<int>(n)));
        } while (std::find(subset, subset + k, subset[k]) != subset + k);
      }
    }
    const Eigen::Vector4d *x[5], *y[5];
    for (int k = 0; k < 5; ++k) {
      x[k] = &data.X[subset[k]];
      y[k] = &data.Y[subset[k]];
    }
    Eigen::Matrix4d Hw;
    const MinimalResult minimal = minimalHomography(x, y, Hw);
    if (minimal != MinimalValid) {
      reversed = reversed || minimal == MinimalReversed;
      continue; // 4 coplanar (or repeated) points among the 5 in one view, or no displacement
    }
    RobustFit fit;
    fit.H = data.unwhiten(Hw);
    fit.points.resize(n);
    pointErrors(data, fit.H, fit.errors, &fit.points);
    fit.score = msac(fit.errors, inlierThreshold);
    // The points to refit on: those within the loose threshold, and at least the `required` best predicted (with few
    // points a 5-point fit may predict every other one far beyond it).
    std::vector<bool> rough = within(fit.errors, loose);
    nearestFirst(fit.errors, required, rough);
    const size_t roughSupport = static_cast<size_t>(std::count(rough.begin(), rough.end(), true));
    if (n > 5 && roughSupport >= best.score.support) {
      // Skip rough sets already optimised, and those within the inliers of the best fit (nothing to gain).
      bool news = !found;
      for (size_t j = 0; j < n && !news; ++j) {
        news = rough[j] && !(best.errors[j] <= inlierThreshold * inlierThreshold);
      }
      if (news && std::find(tried.begin(), tried.end(), rough) == tried.end()) {
        tried.push_back(rough);
        localOptimisation(data, adjustment, inlierThreshold, rough, fit);
        if (!fit.fitted.empty()) {
          rivals.push_back(Rival{within(fit.errors, inlierThreshold), fit.score.cost});
        }
      }
    }
    if (fit.score.cost < best.score.cost) {
      best = std::move(fit);
      found = true;
      if (!enumerate) {
        // Draws needed to pick a set of inliers only with probability 0.9999, at the best inlier ratio so far.
        const double clean = std::pow(static_cast<double>(best.score.support) / static_cast<double>(n), 5.0);
        if (clean >= 1.0) {
          needed = iteration + 1;
        } else if (clean > 0.0) {
          const double draws = std::ceil(std::log(1e-4) / std::log1p(-clean));
          needed = std::min(budget, std::max(iteration + 1, static_cast<size_t>(std::min(draws, 1e9))));
        }
      }
    }
  }
  if (!found && reversed) {
    std::ostringstream os;
    os << "no 5 of the " << n << " points move by one rigid displacement (the homography of every 5 of them reverses "
       << "orientation): too many correspondences are mismatched; check the point tracking or add points";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }
  if (!found) {
    std::ostringstream os;
    os << "no 5 of the " << n << " points are in general position (every set of 5 has 4 coplanar or repeated points "
       << "in one view); a 3D homography needs points spanning 3D space";
    fail(vpProjectiveException::degenerateConfigurationError, where, os.str());
  }

  // Too few points agree with every hypothesis: one more local optimisation, from all the points.
  if (best.score.support < required) {
    RobustFit all = best;
    localOptimisation(data, adjustment, inlierThreshold, std::vector<bool>(n, true), all);
    if (!all.fitted.empty()) {
      best = std::move(all);
    }
  }

  // Another rigid fit supported by as many points, but other ones: both sets cannot be right. If their union is
  // consistent, it is the answer (two correct points near the threshold). Otherwise the better fit wins if it is
  // 1000 times more likely (its MSAC cost, in squared pixels per image point, is lower by 2 ln(1000) sigma^2 / 4,
  // sigma = t / 3 the noise the threshold is meant for); else the data are ambiguous.
  std::vector<bool> bestFlags = within(best.errors, inlierThreshold);
  const double sigma2 = inlierThreshold * inlierThreshold / 9.0;
  for (const Rival &rival : rivals) {
    if (std::count(rival.inliers.begin(), rival.inliers.end(), true) <
            static_cast<long>(std::max(best.score.support, required)) ||
        rival.inliers == bestFlags || 4.0 * (rival.cost - best.score.cost) >= 2.0 * std::log(1000.0) * sigma2) {
      continue;
    }
    std::vector<bool> both(n);
    for (size_t j = 0; j < n; ++j) {
      both[j] = rival.inliers[j] || bestFlags[j];
    }
    RobustFit joint = best;
    localOptimisation(data, adjustment, inlierThreshold, both, joint);
    const std::vector<bool> flagsBoth = within(joint.errors, inlierThreshold);
    bool covers = !joint.fitted.empty();
    for (size_t j = 0; j < n && covers; ++j) {
      covers = !both[j] || flagsBoth[j];
    }
    if (!covers) {
      std::ostringstream os;
      os << "two different sets of " << best.score.support << " of the " << n << " points each agree with a rigid "
         << "displacement within " << inlierThreshold << " px, and not with one another: the mismatched points "
         << "cannot be told from the others; check the point tracking or add points";
      fail(vpProjectiveException::estimationFailedError, where, os.str());
    }
    best = std::move(joint);
    bestFlags = flagsBoth;
  }

  // Maximum-likelihood refit on the inliers, from their best-fitting points, until the inliers are stable (the
  // local optimisation has usually done it, with a capped number of iterations: this converges it).
  Eigen::Matrix4d H = best.H;
  std::vector<bool> flags = within(best.errors, inlierThreshold);
  std::vector<Eigen::Vector4d> points = best.points;
  for (int round = 0; round < 3 && (round == 0 || flags != best.fitted) && best.score.support >= 5; ++round) {
    if (!adjustment.refine(flags, H, points, 100)) {
      break;
    }
    best.fitted = flags;
    std::vector<double> d2;
    pointErrors(data, H, d2, &points);
    flags = within(d2, inlierThreshold);
  }

  // Any 5 points fit a homography: a sixth must confirm it (when there is one).
  const size_t support = static_cast<size_t>(std::count(flags.begin(), flags.end(), true));
  if (support < required) {
    std::ostringstream os;
    os << "only " << support << " of the " << n << " points agree with one rigid displacement within "
       << inlierThreshold << " px (" << required << " needed: any 5 points are fitted exactly by a 3D homography, so a "
       << "sixth must confirm it); too many correspondences are mismatched: check the point tracking, add points, or "
       << "raise the threshold in proportion to the image noise";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }
  // A homography may fit a mismatched set within the threshold by distorting space (few points leave it the freedom):
  // then it is no rigid displacement.
  const double rigidity = adjustment.rigidityStatistic(best.fitted, H, points, 0.1 * inlierThreshold);
  if (!(rigidity <= kRigidityBound)) {
    std::ostringstream os;
    os << "the " << support << " of " << n << " points that agree within " << inlierThreshold << " px are fitted by a "
       << "homography that is no rigid displacement (its characteristic polynomial differs from that of a rotation, "
       << "(x - 1)^2 (x^2 - 2 x cos(theta) + 1), by " << rigidity << " times its noise, more than " << kRigidityBound
       << "), so some of them are mismatched; check the point tracking or add points";
    fail(vpProjectiveException::estimationFailedError, where, os.str());
  }
  inliers = flags;
  return normalize(H);
}
