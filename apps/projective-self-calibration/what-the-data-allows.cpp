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
  \file what-the-data-allows.cpp
  \brief The study "what the data allows": the self-calibration's errors and stated deviations beside the
  Cramer-Rao bound of the same frames, of the same frames with parameters known, and of other frames.
*/

#include <array>
#include <cmath>
#include <iomanip>
#include <iostream>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>

#include "information-bound.h"
#include "paper-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
namespace
{
typedef std::vector<vpProjectiveArmAcquisition::vpFrame> Frames;
typedef std::array<double, PARAMETERS> Figures;

//! Issue 34's bounds on the errors, in the table's units (%, px, deg); no bound on the skew.
const Figures kBounds = {0.5, 5.0, std::numeric_limits<double>::infinity(), 0.2, 0.5, 0.5};

//! A row of the table: its figures per seed; with \e frames > 0, the bound on that many frames (not the issue's).
struct Row {
  std::string label;
  std::vector<Figures> seeds;
  unsigned int frames = 0;
};

Figures tableUnits(const double (&x)[PARAMETERS])
{
  Figures f;
  for (int p = 0; p < PARAMETERS; ++p) {
    f[p] = scaleOf(Parameter(p)) * x[p];
  }
  return f;
}

double worstOf(const Row &row, int p)
{
  double worst = 0.0;
  for (const Figures &f : row.seeds) {
    worst = std::max(worst, f[p]);
  }
  return worst;
}

//! The readings' bounds +-\e spread deg about the zero reference (prismatic: 2 mm per deg).
void boundsOf(const StudyArm &arm, double spread, vpColVector &qmin, vpColVector &qmax)
{
  qmin = arm.qRef;
  qmax = arm.qRef;
  for (unsigned int i = 0; i < qmin.size(); ++i) {
    const double d = arm.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? 0.002 * spread : vpMath::rad(spread);
    qmin[i] -= d;
    qmax[i] += d;
  }
}

/*!
  suggestConfigurations() among 500 candidates (of which few keep the markers in view at +-90 deg); none when none
  does.
*/
std::vector<vpColVector> suggestions(const vpProjectiveSelfCalibration &calibration, unsigned int count,
                                     const vpColVector &qmin, const vpColVector &qmax, const SkewedRig &rig,
                                     unsigned int seed)
{
  try {
    return calibration.suggestConfigurations(count, qmin, qmax, rig.width, rig.height, nullptr, 500, seed);
  } catch (const vpProjectiveException &e) {
    if (e.getCode() != vpProjectiveException::degenerateConfigurationError) {
      throw;
    }
    return {};
  }
}

//! The frame of the images \e left, \e right at readings \e q.
vpProjectiveArmAcquisition::vpFrame frameOf(const vpColVector &q, const std::vector<vpImagePoint> &left,
                                            const std::vector<vpImagePoint> &right)
{
  vpProjectiveArmAcquisition::vpFrame f{Eigen::Map<const Eigen::VectorXd>(q.data, q.size()),
                                        std::vector<Eigen::Vector4d>(), std::vector<bool>(left.size(), true)};
  for (size_t j = 0; j < left.size(); ++j) {
    f.s.emplace_back(left[j].get_u(), left[j].get_v(), right[j].get_u(), right[j].get_v());
  }
  return f;
}

/*!
  As a user would: suggestConfigurations() by rounds of 10 within +-\e spread deg, each from the self-calibration of
  the frames so far, the arm moved there and imaged at \e sigma px (a configuration whose markers leave the view is
  lost), until \e total frames beyond \e acquisition; \e kept receives how many of the suggested were in view.
*/
Frames suggestedInRounds(const vpProjectiveRobot &robot, const StudyArm &arm, const SkewedRig &rig,
                         const Frames &acquisition, double spread, unsigned int total, double sigma, vpGaussRand &noise,
                         unsigned int seed, double &kept)
{
  vpColVector qmin, qmax;
  boundsOf(arm, spread, qmin, qmax);
  Frames frames = acquisition;
  unsigned int suggested = 0;
  for (unsigned int round = 0; frames.size() < acquisition.size() + total && round < 3 * total / 10; ++round) {
    const vpProjectiveSelfCalibration calibration = selfCalibration(robot, arm, frames);
    for (const vpColVector &q : suggestions(calibration, 10, qmin, qmax, rig, seed + round)) {
      std::vector<vpImagePoint> left, right;
      ++suggested;
      if (rig.images(arm.arm.getMarkers(q), sigma, noise, left, right) && frames.size() < acquisition.size() + total) {
        frames.push_back(frameOf(q, left, right));
      }
    }
  }
  kept = static_cast<double>(frames.size() - acquisition.size()) / suggested;
  return frames;
}

//! The largest difference (px) between \e model's pixels of \e frames and the world's own projection.
double modelMismatch(const MetricModel &model, const StudyArm &arm, const SkewedRig &rig, const Frames &frames)
{
  const Eigen::VectorXd s = predict(model, frames);
  double worst = 0.0;
  Eigen::Index r = 0;
  for (const vpProjectiveArmAcquisition::vpFrame &f : frames) {
    vpColVector q(static_cast<unsigned int>(f.q.size()));
    for (unsigned int i = 0; i < q.size(); ++i) {
      q[i] = f.q(i);
    }
    for (const vpColVector &wX : arm.arm.getMarkers(q)) {
      vpImagePoint l, rr;
      rig.project(wX, l, rr, -1e9);
      const Eigen::Vector4d truth(l.get_u(), l.get_v(), rr.get_u(), rr.get_v());
      worst = std::max(worst, (s.segment<4>(r) - truth).cwiseAbs().maxCoeff());
      r += 4;
    }
  }
  return worst;
}

void printTable(const std::vector<Row> &rows)
{
  std::cout << "| data | focal length (%) | principal point (px) | skew (px) | rig rotation (deg) | baseline direction "
               "(deg) | baseline length (%) |\n|---|---|---|---|---|---|---|\n| issue 34's bound (every seed) |";
  for (int p = 0; p < PARAMETERS; ++p) {
    std::cout << " " << (std::isinf(kBounds[p]) ? std::string("-") : std::to_string(kBounds[p]).substr(0, 3)) << " |";
  }
  std::cout << "\n";
  for (const Row &row : rows) {
    std::cout << "| " << row.label << " |";
    for (int p = 0; p < PARAMETERS; ++p) {
      std::vector<double> x;
      for (const Figures &f : row.seeds) {
        x.push_back(f[p]);
      }
      std::cout << " " << app::median(x) << " / " << app::maxOf(x) << " |";
    }
    std::cout << "\n";
  }
}

/*!
  Per bound, whether the issue's frames allow it on every seed (3 times the worst CRB deviation within it), the
  fewest frames among the other rows that do, and how many frames like those of the row \e most would (its worst
  deviation scaled by one over the square root of the number of frames: the information of independent frames adds).
*/
void printVerdict(const std::vector<Row> &rows, size_t issue, const Row &most, const std::vector<Figures> &chance)
{
  for (int p = 0; p < PARAMETERS; ++p) {
    if (std::isinf(kBounds[p])) {
      continue;
    }
    std::cout << "  " << nameOf(Parameter(p)) << " within " << kBounds[p] << " " << unitOf(Parameter(p))
              << ": 3 x the worst CRB " << 3.0 * worstOf(rows[issue], p) << " on the issue's frames, "
              << (3.0 * worstOf(rows[issue], p) <= kBounds[p] ? "attainable" : "NOT attainable");
    std::vector<double> x;
    double all = 1.0;
    for (const Figures &f : chance) {
      x.push_back(f[p]);
      all *= f[p];
    }
    std::cout << " (an efficient estimator within it with probability " << app::median(x) << " in the median world, "
              << *std::min_element(x.begin(), x.end()) << " in the worst, " << all << " on all " << x.size()
              << "); reached by ";
    const Row *fewest = nullptr;
    for (const Row &row : rows) {
      if (row.frames > 0 && 3.0 * worstOf(row, p) <= kBounds[p] && (fewest == nullptr || row.frames < fewest->frames)) {
        fewest = &row;
      }
    }
    const double ratio = 3.0 * worstOf(most, p) / kBounds[p];
    std::cout << (fewest == nullptr ? std::string("none of the rows") : fewest->label);
    if (ratio > 1.0) {
      std::cout << "; about " << std::ceil(most.frames * ratio * ratio) << " frames as in '" << most.label << "'";
    }
    std::cout << "\n";
  }
}
} // namespace

int whatTheDataAllows(const std::vector<std::string> &arms, unsigned int seeds, unsigned int first, double sigma,
                      unsigned int frames, double range)
{
  std::cout << std::defaultfloat << std::setprecision(3) << "What the data allows at " << sigma
            << " px: the self-calibration's errors and stated deviations on "
            << "the acquisition and " << frames << " frames within +-" << range
            << " deg, and the Cramer-Rao bound (CRB, one standard deviation; focal length and intrinsics: the worst "
               "component of both cameras, rig rotation: rms angle, baseline direction: its least determined axis)\n";
  double mismatch = 0.0;
  const unsigned int spreads[3] = {30, 60, 90}, counts[4] = {30, 60, 120, 480}, rounds[2] = {30, 120};
  for (size_t a = 0; a < arms.size(); ++a) {
    const StudyArm arm = makeArm(arms[a]);
    const bool prismatic = arm.name == "prismatic";
    const std::string issue =
        "acquisition + " + std::to_string(frames) + " frames within +-" + std::to_string(static_cast<int>(range));
    std::vector<Row> rows = {{"errors: " + issue, {}},           {"stated deviations", {}},
                             {"CRB, the same frames", {}},       {"CRB, skew known", {}},
                             {"CRB, markers known", {}},         {"CRB, joint axes known", {}},
                             {"CRB, markers and axes known", {}}};
    const size_t kIssue = 2;
    size_t most = 0; // the row of the most frames, the widest spread
    for (unsigned int n : counts) {
      for (unsigned int s : spreads) {
        most = rows.size();
        rows.push_back({"CRB, " + std::to_string(n) + " random frames within +-" + std::to_string(s), {}, n});
      }
    }
    for (unsigned int s : spreads) {
      rows.push_back(
          {"CRB, " + std::to_string(frames) + " suggested at once after the acquisition within +-" + std::to_string(s),
           {},
           frames});
    }
    for (unsigned int n : rounds) {
      for (unsigned int s : spreads) {
        rows.push_back(
            {"CRB, " + std::to_string(n) + " suggested (rounds of 10) within +-" + std::to_string(s), {}, n});
      }
    }
    std::vector<Figures> chance; // per seed, the probability of an efficient estimator's errors within the bounds
    std::vector<double> kept, atOnce[3]; // the share of suggested configurations whose markers stayed in view
    for (unsigned int seed = first; seed < first + seeds; ++seed) {
      WorldStreams streams(seed, a);
      const SkewedRig rig = randomRig(arm, streams.rig);
      const vpProjectiveRobot robot = acquire(arm, rig, sigma, frames, range, streams.noise, streams.view);
      const Frames all = robot.getAcquisition().getFrames();
      const Frames acquisition(all.begin(), all.end() - robot.getAcquisition().getNumberOfCalibrationFrames());
      const vpProjectiveSelfCalibration calibration = selfCalibration(robot, arm, all);
      Eigen::Matrix3d Kl, Kr;
      Eigen::Matrix4d lMr;
      calibration.getMetricStereoRig(Kl, Kr, lMr);
      size_t r = 0;
      rows[r++].seeds.push_back(tableUnits(compare(Kl, Kr, lMr, rig, true).error));
      double x[PARAMETERS];
      statedDeviations(calibration.getUncertainty(), Kl, Kr, lMr.topRightCorner<3, 1>(), x);
      rows[r++].seeds.push_back(tableUnits(x));
      const MetricModel truth = trueModel(arm, rig);
      mismatch = std::max(mismatch, modelMismatch(truth, arm, rig, all));
      // The scale's gauge as the adjustment's: the prismatic joint, or a unit baseline; known markers or axes (their
      // lengths in metres) fix the scale themselves, the baseline's length is then free.
      const MetricParameters gauge(truth, !prismatic), metric(truth, false);
      const Eigen::MatrixXd J = pixelJacobian(gauge, all), Jm = prismatic ? J : pixelJacobian(metric, all);
      double bounds[PARAMETERS], within[PARAMETERS];
      for (int p = 0; p < PARAMETERS; ++p) {
        bounds[p] = kBounds[p] / scaleOf(Parameter(p));
      }
      withinBounds(gauge, J, sigma, bounds, within);
      chance.emplace_back();
      std::copy(std::begin(within), std::end(within), chance.back().begin());
      for (unsigned int known : {unsigned(NOTHING_KNOWN), unsigned(SKEW_KNOWN)}) {
        informationBound(gauge, J, sigma, known, x);
        rows[r++].seeds.push_back(tableUnits(x));
      }
      for (unsigned int known : {unsigned(MARKERS_KNOWN), unsigned(AXES_KNOWN), unsigned(MARKERS_KNOWN | AXES_KNOWN)}) {
        informationBound(metric, Jm, sigma, known, x);
        rows[r++].seeds.push_back(tableUnits(x));
      }
      // Other frames in the same world: the same acquisition (it draws nothing), frames from streams of their own.
      for (unsigned int n : counts) {
        for (unsigned int s : spreads) {
          WorldStreams other(seed + 7919u * (s + n), a);
          const vpProjectiveRobot more = acquire(arm, rig, sigma, n, s, other.noise, other.view);
          informationBound(gauge, pixelJacobian(gauge, more.getAcquisition().getFrames()), sigma, NOTHING_KNOWN, x);
          rows[r++].seeds.push_back(tableUnits(x));
        }
      }
      // suggestConfigurations() called once after the acquisition, as its model and covariance are then.
      const vpProjectiveSelfCalibration start = selfCalibration(robot, arm, acquisition);
      for (size_t k = 0; k < 3; ++k) {
        const unsigned int s = spreads[k];
        vpColVector qmin, qmax;
        boundsOf(arm, s, qmin, qmax);
        WorldStreams other(seed + 7919u * s + 1u, a);
        Frames f = acquisition;
        for (const vpColVector &q : suggestions(start, frames, qmin, qmax, rig, seed)) {
          std::vector<vpImagePoint> left, right;
          if (rig.images(arm.arm.getMarkers(q), sigma, other.noise, left, right)) {
            f.push_back(frameOf(q, left, right));
          }
        }
        atOnce[k].push_back(static_cast<double>(f.size() - acquisition.size()) / frames);
        informationBound(gauge, pixelJacobian(gauge, f), sigma, NOTHING_KNOWN, x);
        rows[r++].seeds.push_back(tableUnits(x));
      }
      std::vector<Frames> suggested;
      for (unsigned int s : spreads) {
        WorldStreams other(seed + 7919u * s, a);
        double share = 0.0;
        suggested.push_back(
            suggestedInRounds(robot, arm, rig, acquisition, s, rounds[1], sigma, other.noise, seed, share));
        kept.push_back(share);
      }
      for (unsigned int n : rounds) {
        for (const Frames &f : suggested) {
          const Frames some(f.begin(), f.begin() + static_cast<long>(std::min(f.size(), acquisition.size() + n)));
          informationBound(gauge, pixelJacobian(gauge, some), sigma, NOTHING_KNOWN, x);
          rows[r++].seeds.push_back(tableUnits(x));
        }
      }
      std::cerr << arm.name << " seed " << seed << " done\n";
    }
    std::cout << "\n" << arm.name << " (median / worst over " << seeds << " seeds from " << first << "):\n";
    printTable(rows);
    std::cout << "suggested configurations whose markers stayed in view (median, least):";
    for (size_t k = 0; k < 3; ++k) {
      std::cout << " at once within +-" << spreads[k] << " " << 100.0 * app::median(atOnce[k]) << " %, "
                << 100.0 * *std::min_element(atOnce[k].begin(), atOnce[k].end()) << " %;";
    }
    std::cout << " by rounds " << 100.0 * app::median(kept) << " %, "
              << 100.0 * *std::min_element(kept.begin(), kept.end()) << " %\n";
    printVerdict(rows, kIssue, rows[most], chance);
  }
  std::cout << "\nlargest difference between the true model's pixels and the worlds' projection: " << mismatch
            << " px\n";
  return mismatch < 1e-6 ? 0 : 1;
}
} // namespace selfcal
