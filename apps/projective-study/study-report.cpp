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
  \file study-report.cpp
  \brief The study's report: its markdown tables and the report itself (the verdicts in study-summary.cpp, the data
  files and figures in study-files.cpp).
*/

#include "study-report.h"

#include "study-methods.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iomanip>
#include <map>
#include <sstream>

#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
namespace
{
//! The header of a table of distributions: a quantity's percentiles 5, 50 and 95.
const char *const kPercentileHeader = "| quantity | 5 % | median | 95 % |\n|---|---|---|---|\n";

//! One row of a table of distributions: \e name, the percentiles 5, 50 and 95 of \e x with \e digits decimals.
void percentileRow(std::ostream &os, const std::string &name, const std::vector<double> &x, int digits)
{
  os << "| " << name << " | " << fixed(percentile(x, 0.05), digits) << " | " << fixed(percentile(x, 0.5), digits)
     << " | " << fixed(percentile(x, 0.95), digits) << " |\n";
}
} // namespace

std::string verdict(const Cell &a, const Cell &b, unsigned int &onlyA, unsigned int &onlyB)
{
  onlyA = onlyB = 0;
  for (size_t t = 0; t < a.successes.size() && t < b.successes.size(); ++t) {
    onlyA += a.successes[t] && !b.successes[t];
    onlyB += !a.successes[t] && b.successes[t];
  }
  const double d = static_cast<double>(onlyA) - static_cast<double>(onlyB);
  if (std::abs(d) <= 2.0 * std::sqrt(static_cast<double>(onlyA + onlyB))) {
    return "ties with";
  }
  return d > 0 ? "wins against" : "loses to";
}

std::string tableHeader(const std::string &first)
{
  return "| " + first +
         " | method | success | acquisition failed | lost view | joint limit | not converged | other | median it. | "
         "95 % it. | joint error / floor | straightness | joint path / line | excursion median / max (deg) | no plan | "
         "other branch | extra moves |\n"
         "|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|---|\n";
}

std::string tableRow(const std::string &first, const Cell &c)
{
  std::ostringstream os;
  const unsigned int other = c.count("exception") + c.count("exploration");
  os << "| " << first << " | " << c.name() << " | " << fixed(c.successRate(), 1) << " % | "
     << (c.method.compare(0, 10, "projective") == 0 ? std::to_string(c.count("acquisition")) : std::string("-"))
     << " | " << c.count("lost view") << " | " << c.count("joint limit") << " | " << c.count("not converged") << " | "
     << other << " | " << fixed(percentile(c.iterations, 0.5), 0) << " | " << fixed(percentile(c.iterations, 0.95), 0)
     << " | " << fixed(percentile(c.errorOverFloor, 0.5), 2) << " | " << fixed(percentile(c.straightness, 0.5), 3)
     << " | " << fixed(percentile(c.jointPathRatio, 0.5), 2) << " | " << fixed(percentile(c.excursionDeg, 0.5), 1)
     << " / " << fixed(percentile(c.excursionDeg, 1.0), 1) << " | "
     << (c.method == "planned" ? std::to_string(c.noPlan) : std::string("-")) << " | "
     << (c.method == "planned" ? std::to_string(c.otherBranch) + " of " + std::to_string(c.planned) : std::string("-"))
     << " | " << fixed(percentile(c.moves, 0.5), 0) << " |\n";
  return os.str();
}

std::string taskDistribution(const World &world, const std::vector<Task> &tasks)
{
  const unsigned int n = world.arm.getNumberOfJoints();
  std::vector<std::vector<double>> dq(n);
  std::vector<double> translation, rotation, rms, floor, draws;
  std::map<std::string, unsigned int> branches;
  for (const Task &task : tasks) {
    for (unsigned int i = 0; i < n; ++i) {
      const double dqi = std::abs(task.qTarget[i] - task.qStart[i]);
      dq[i].push_back(world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? 100.0 * dqi : vpMath::deg(dqi));
    }
    const vpHomogeneousMatrix d = world.arm.get_wMt(task.qStart).inverse() * world.arm.get_wMt(task.qTarget);
    translation.push_back(100.0 * d.getTranslationVector().frobeniusNorm());
    rotation.push_back(vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta()));
    double sum = 0.0;
    for (unsigned int k = 0; k < world.nbPoints(); ++k) {
      sum += vpImagePoint::sqrDistance(task.leftStart[k], task.leftTarget[k]) +
             vpImagePoint::sqrDistance(task.rightStart[k], task.rightTarget[k]);
    }
    rms.push_back(std::sqrt(sum / (4.0 * world.nbPoints())));
    floor.push_back(vpMath::deg(0.5 * task.unitFloor.getMaxValue()));
    draws.push_back(task.drawnStart + task.drawnTarget);
    if (!world.pumaBranches) {
      continue;
    }
    const Branch b = branchOf(world.arm, task.qStart);
    std::string label = std::string(b.shoulder > 0 ? "+" : "-") + (b.elbow > 0 ? "+" : "-") + (b.wrist > 0 ? "+" : "-");
    ++branches[label];
  }
  std::ostringstream os;
  os << kPercentileHeader;
  auto row = [&](const std::string &name, const std::vector<double> &x, int digits) {
    percentileRow(os, name, x, digits);
  };
  for (unsigned int i = 0; i < n; ++i) {
    row("abs(q*_" + std::to_string(i) + " - q0_" + std::to_string(i) + ") (" +
            (world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? "cm" : "deg") + ")",
        dq[i], 1);
  }
  row("tool translation (cm)", translation, 1);
  row("tool rotation (deg)", rotation, 1);
  row("initial image error, RMS (px)", rms, 1);
  row("largest joint noise floor at 0.5 px (deg)", floor, 3);
  row("configurations drawn per task (start + target)", draws, 0);
  if (world.pumaBranches) {
    os << "\nBranches (shoulder, elbow, wrist signs) of the start and target:";
    for (const auto &kv : branches) {
      os << " " << kv.first << " " << kv.second;
    }
    os << "\n";
  }
  return os.str();
}

std::string rotationBreakdown(const World &world, const Results &results)
{
  const double edges[5] = {0, 45, 90, 135, 180};
  std::vector<int> bin;
  std::vector<unsigned int> count(4, 0);
  for (const Task &task : results.tasks) {
    const vpHomogeneousMatrix d = world.arm.get_wMt(task.qStart).inverse() * world.arm.get_wMt(task.qTarget);
    const double rotation = vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta());
    int b = 0;
    while (b < 3 && rotation >= edges[b + 1]) {
      ++b;
    }
    bin.push_back(b);
    ++count[b];
  }
  std::ostringstream os;
  os << "| noise (px) | method";
  for (int b = 0; b < 4; ++b) {
    os << " | " << edges[b] << "-" << edges[b + 1] << " deg (" << count[b] << " tasks)";
  }
  os << " |\n|---|---|---|---|---|---|\n";
  for (double sigma : world.sigmas) {
    for (const Cell *c : results.select("nominal", sigma)) {
      std::vector<unsigned int> ok(4, 0);
      for (size_t t = 0; t < c->successes.size(); ++t) {
        ok[bin[t]] += c->successes[t];
      }
      os << "| " << sigma << " | " << c->name();
      for (int b = 0; b < 4; ++b) {
        os << " | " << (count[b] ? fixed(100.0 * ok[b] / count[b], 1) + " %" : std::string("-"));
      }
      os << " |\n";
    }
  }
  return os.str();
}

std::string worldDescription(const World &world)
{
  std::ostringstream os;
  os << "`--world " << world.name << " --rig " << world.rigName << "`: ";
  os << (world.name == "puma"       ? "the main job's PUMA-like arm"
         : world.name == "viper850" ? "ViSP's Viper850 (vpSimulatorArm::viper850(), its true joint limits), zero "
                                      "reference (0, -150, 190, 0, -75, 0) deg"
                                    : "an R-R-P-R-R-R arm (Stanford-arm structure, a prismatic joint 2 in metres), "
                                      "zero reference (0, 60 deg, 0.45 m, 0, -50 deg, 0)");
  os << ", the gripper's markers facing the rig at the zero reference; "
     << (world.rigName == "random" ? "a random verged rig per task (see Random rigs)"
                                   : "the paper's rig (20 deg vergence at 1 m, 640 x 480)")
     << "; trials";
  for (unsigned int i = 0; i < world.trials.size(); ++i) {
    const bool prismatic = world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC;
    os << (i ? ", " : " ") << fixed(prismatic ? 100.0 * world.trials[i] : vpMath::deg(world.trials[i]), 0)
       << (prismatic ? " cm" : " deg");
  }
  os << ".";
  return os.str();
}

std::string plannedAgainstLaw(const World &world, const Results &results)
{
  std::ostringstream os;
  for (double sigma : world.sigmas) {
    const Cell &law = results.get("nominal", "projective", sigma), &planned = results.get("nominal", "planned", sigma);
    unsigned int lawOnly = 0, plannedOnly = 0, lawSolved = 0, both = 0;
    std::vector<unsigned int> seeds;
    for (size_t t = 0; t < law.successes.size() && t < planned.successes.size() && t < results.tasks.size(); ++t) {
      lawSolved += law.successes[t];
      both += law.successes[t] && planned.successes[t];
      plannedOnly += planned.successes[t] && !law.successes[t];
      if (law.successes[t] && !planned.successes[t]) {
        ++lawOnly;
        if (seeds.size() < 10) {
          seeds.push_back(results.tasks[t].seed);
        }
      }
    }
    os << "Planned against law (47) at " << fixed(sigma, 1) << " px, the same tasks and models: " << lawOnly
       << " tasks solved by law (47) and not by the planned servo";
    for (size_t k = 0; k < seeds.size(); ++k) {
      os << (k ? ", " : " (seeds ") << seeds[k]
         << (k + 1 == seeds.size() ? (lawOnly > seeds.size() ? ", ...)" : ")") : "");
    }
    os << ", " << plannedOnly << " by the planned servo only; among the " << lawSolved
       << " tasks law (47) solves, the planned servo solves " << fixed(lawSolved ? 100.0 * both / lawSolved : 0.0, 1)
       << " %.\n";
  }
  return os.str();
}

std::string rigDistribution(const std::vector<RigDraw> &draws)
{
  std::vector<double> distance, baseline, vergence, focal, azimuth, elevation, attempts;
  std::map<std::string, unsigned int> sizes;
  for (const RigDraw &d : draws) {
    distance.push_back(100.0 * d.distance);
    baseline.push_back(100.0 * d.baseline);
    vergence.push_back(d.vergenceDeg);
    focal.push_back(d.focal);
    azimuth.push_back(d.azimuthDeg);
    elevation.push_back(d.elevationDeg);
    attempts.push_back(d.draws);
    ++sizes[std::to_string(d.width) + " x " + std::to_string(d.height)];
  }
  std::ostringstream os;
  os << kPercentileHeader;
  auto row = [&](const std::string &name, const std::vector<double> &x, int digits) {
    percentileRow(os, name, x, digits);
  };
  row("distance to the fixation point (cm)", distance, 0);
  row("baseline (cm)", baseline, 0);
  row("vergence (deg)", vergence, 1);
  row("focal length (px)", focal, 0);
  row("azimuth (deg)", azimuth, 1);
  row("elevation (deg)", elevation, 1);
  row("rigs drawn per task (until the markers are in view)", attempts, 0);
  os << "\nImage sizes:";
  for (const auto &kv : sizes) {
    os << " " << kv.first << " (" << kv.second << " tasks);";
  }
  os << "\n";
  return os.str();
}

std::string jointLimits(const World &world)
{
  std::ostringstream os;
  os << "relative to the zero reference:";
  for (unsigned int i = 0; i < world.arm.getNumberOfJoints(); ++i) {
    const bool prismatic = world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC;
    const double k = prismatic ? 100.0 : 180.0 / M_PI;
    os << (i ? ", " : " ") << "[" << fixed(k * world.arm.getJointMin()[i], 0) << ", "
       << fixed(k * world.arm.getJointMax()[i], 0) << "]" << (prismatic ? " cm" : " deg");
  }
  return os.str();
}

std::string markdownReport(const World &world, const Results &results, unsigned int nbTasks, unsigned int seed)
{
  std::ostringstream md;
  md << "# Servo study: projective servo, calibrated stereo IBVS, Broyden\n\n"
     << "World: " << worldDescription(world) << "\n\n"
     << nbTasks << " random tasks (seeds " << seed << " to " << seed + nbTasks - 1
     << "), the same for every method and noise level; budget " << world.budget << " iterations; tasks within +-"
     << world.boxDeg
     << " deg of the zero reference on every joint; success: image "
        "RMS error below max(2 sigma, 1e-6) px within the budget, the "
     << world.tracked.size()
     << " tracked markers in view of both cameras throughout, no joint limit hit. Every method: gain "
     << world.control.lambda << ", joint steps at most " << vpMath::deg(world.control.qdotMax)
     << " deg, damped least squares (sigma_0 = " << world.control.sigmaThreshold
     << " px/rad, mu_max = " << world.control.maxDamping
     << " px/rad). Iterations: median and 95th percentile of the successes; joint error / floor: median over the "
        "successes of the mean over joints of |q - q*| / sqrt(diag(sigma^2 (J^T J)^-1)) at the end of the budget; "
        "straightness: median of the image path length over the straight distance (1 = straight; noise-free "
        "images of the servo phase up to convergence); joint path / line: median over the successes of the joint "
        "path length up to convergence over |q* - q_0|; excursion: the largest motion of a joint beyond the "
        "interval of its start and target values, median and maximum over the runs; no plan: planned runs where "
        "the planner found none (SERVO_NO_PLAN); other branch: plans whose target joints are in another "
        "inverse-kinematic branch than the true target's; extra moves: "
        "Broyden's exploratory configurations per task (the projective servo's acquisition, 12 trial motions per "
        "arm, is not counted).\n\n";
  md << "Self-check: the exact-calibration IBVS Jacobian equals the true image Jacobian to " << std::scientific
     << std::setprecision(1) << checkIbvsJacobian(world, results.tasks.front()) << std::defaultfloat
     << std::setprecision(6) << " (relative).\n\n";

  md << "## Tasks\n\nStart and target drawn uniformly in |q_i| <= " << world.boxDeg << " deg";
  for (unsigned int i = 0; i < world.arm.getNumberOfJoints(); ++i) {
    if (world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC) {
      md << " (prismatic joint " << i << ": +-" << 100.0 * world.prismaticPerDeg * world.boxDeg << " cm)";
    }
  }
  md << " of the zero reference, clipped to the joint limits (" << jointLimits(world)
     << "), kept when the tracked markers are " << world.marginPx << " px inside both images at both ends"
     << (world.anyBranch ? " (--any-branch: the target in any inverse-kinematic branch).\n\n"
         : !world.pumaBranches
             ? " (the " + world.name +
                   " arm has no closed-form branch test: the target in any inverse-kinematic branch, as with "
                   "--any-branch; \"other branch\" counts the plans whose target leads Gauss-Newton inverse kinematics "
                   "of "
                   "the true target's tool pose to another solution than the true target).\n\n"
             : std::string(" and the target has the start's inverse-kinematic branch (signs of the shoulder reach, "
                           "cos(theta_2) and sin(theta_4)).\n\n"))
     << taskDistribution(world, results.tasks) << "\n";

  md << "## Nominal: Gaussian noise\n\n" << tableHeader("noise (px)");
  for (double sigma : world.sigmas) {
    for (const Cell *c : results.select("nominal", sigma)) {
      md << tableRow(fixed(sigma, 1), *c);
    }
  }
  md << "\n" << plannedAgainstLaw(world, results);
  md << "\nSuccess by the tool rotation of the task:\n\n" << rotationBreakdown(world, results);

  if (!world.robustness) {
    md << "\n(--nominal-only: no robustness cases.)\n";
  } else {
    md << "\n## Robustness at " << world.robustnessSigma << " px\n\n"
       << "(a) each stereo measurement replaced with probability " << world.outlierProbability
       << " per iteration by a gross error (" << world.outlierMinPx << "-" << world.outlierMaxPx
       << " px in a random direction, in one image); (b) feature " << world.occludedFeature
       << " not tracked at iterations " << world.occludedFirst << "-" << world.occludedLast
       << "; (c) start with q_4 within " << world.nearSingularDeg << " deg of " << world.wristSingularDeg
       << " deg, where the axes of joints 3 and 5 align (theta_4 = 0 in the DH table), other tasks drawn as above. "
          "(a) and (b) use the nominal tasks and the nominal 0.5 px models; (c) its own tasks and fresh acquisitions. "
          "The baselines and the plain projective servo drop the rows of an occluded point and have no other "
          "protection; the robustness API adds setFeatureTracked(), setImageSize(), setOutlierThreshold("
       << world.outlierThresholdPx << " px) and setJointLimits().\n\n"
       << tableHeader("case");
    for (const char *scenario : {"outliers", "occlusion", "singular start"}) {
      for (const Cell *c : results.select(scenario, world.robustnessSigma)) {
        md << tableRow(scenario, *c);
      }
    }
    const Cell &robustOutliers = results.get("outliers", "projective (robust)", world.robustnessSigma);
    const Cell &robustOcclusion = results.get("occlusion", "projective (robust)", world.robustnessSigma);
    const size_t remaining = world.tracked.size() - 1;
    md << "\nWhile feature " << world.occludedFeature << " is occluded, " << remaining << " points remain ("
       << (remaining >= 3
               ? "enough to constrain 6 joints"
               : "they cannot constrain 6 joints: a rotation about the line through two points moves neither")
       << "): the robustness API stopped the task (SERVO_STOPPED, zero velocity) for "
       << robustOcclusion.stoppedIterations << " iterations over " << robustOcclusion.tasks
       << " tasks, where the others go on with the damped " << 4 * remaining << " x 6 task.\n";
    md << "\nOutlier rejection of the robustness API: " << robustOutliers.outliersRejected << " of "
       << robustOutliers.outliersSeen << " gross errors rejected ("
       << fixed(100.0 * robustOutliers.outliersRejected / std::max(1u, robustOutliers.outliersSeen), 1) << " %), "
       << robustOutliers.cleanRejected << " of " << robustOutliers.cleanSeen << " clean measurements rejected ("
       << fixed(100.0 * robustOutliers.cleanRejected / std::max(1u, robustOutliers.cleanSeen), 2) << " %).\n";
    if (!results.singularTasks.empty()) {
      md << "\nSingular-start tasks:\n\n" << taskDistribution(world, results.singularTasks);
    }
  }

  md << "\n## Verdicts\n\n" << summary(world, results);
  md << "\n## Failures of the projective servo (first seeds; rerun one with --seed S --tasks 1)\n\n";
  for (const Cell &c : results.cells) {
    if (c.method.compare(0, 10, "projective") != 0) {
      continue;
    }
    for (const auto &kv : c.seeds) {
      if (!kv.second.empty()) {
        md << "- " << c.scenario << ", " << c.name() << ", " << c.sigma << " px, " << kv.first << " ("
           << c.count(kv.first) << "): seeds " << seedList(kv.second) << "\n";
      }
    }
  }
  return md.str();
}
} // namespace study
