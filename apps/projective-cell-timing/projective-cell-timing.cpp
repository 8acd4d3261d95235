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
  projective-cell-timing: how the real-cell program (vpProjectiveCell) degrades with the timing of a real cell, on
  the rendered cell (vpSimulatorStereoCell::setTiming()): the right image taken after the left (skew), images older
  than the encoder readings (latency), a low frame rate, dropped frames, noisy encoders. For each condition and seed:
  the acquisition's residual (with the cameras' time stamps, and for the latency rows also without them: images
  dropped a fixed number of times after each stop; the latency and frame-rate rows, which the acquisition sees), then
  the planned servo (on a model acquired once per seed at the reference timing) from a start 5-10 deg away per joint,
  with and without the features predicted to the readings' time (vpSettings::latencyCompensation): converged or
  not, its final image error and its duration. docs/cell-timing.dox gives the table and the limits it sets.

    projective-cell-timing [--seeds N] [--gain G] [--speed-deg D] [--quick]

  Exit status 0 when it ran to its table (it checks nothing: the figures are the study's).
*/

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <visp3/core/vpMath.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/projective/vpProjectiveCell.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpSimulatorStereoCell.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
struct Condition {
  const char *group;
  double fps, latency, skew, drop;
};

//! The rendered cameras, their time stamps hidden (a camera that gives none).
class Unstamped : public vpStereoImageSource
{
public:
  explicit Unstamped(vpSimulatorStereoCell &cell) : m_cell(cell) {}
  bool acquire(vpImage<unsigned char> &Il, vpImage<unsigned char> &Ir) override { return m_cell.acquire(Il, Ir); }
  unsigned int getWidth() const override { return m_cell.getWidth(); }
  unsigned int getHeight() const override { return m_cell.getHeight(); }

private:
  vpSimulatorStereoCell &m_cell;
};

struct Cell {
  vpSimulatorStereoCell cell;
  std::vector<vpProjectiveJoint::vpJointType> types;
  vpProjectiveCellViSPArm arm;
  Cell(const Condition &c, long seed)
      : cell(vpSimulatorArm::puma(vpSimulatorArm::paperBasePose()),
             vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0), vpColVector(), seed),
        types(6, vpProjectiveJoint::REVOLUTE), arm(cell.getRobot(), types)
  {
    cell.addToolTags(0.03);
    cell.getRenderer().setNoise(1.0);
    cell.getRenderer().setBlur(0.5);
    cell.getRobot().setSamplingTime(0.01); // the controller's period: the camera sets the loop's
    cell.getRobot().setEncoderNoise(2e-5, seed + 100);
    cell.setTiming(c.fps, c.latency, c.skew, c.drop, seed);
  }
};
} // namespace

int main(int argc, char **argv)
{
  unsigned int seeds = 2;
  double gain = 0.5, speedDeg = 15.0;
  bool quick = false;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seeds" && i + 1 < argc) {
      seeds = static_cast<unsigned int>(std::atoi(argv[++i]));
    } else if (arg == "--gain" && i + 1 < argc) {
      gain = std::atof(argv[++i]);
    } else if (arg == "--speed-deg" && i + 1 < argc) {
      speedDeg = std::atof(argv[++i]);
    } else if (arg == "--quick") {
      quick = true;
    } else {
      std::cout << "Usage: " << argv[0] << " [--seeds N (2)] [--gain G (0.5)] [--speed-deg D (15)] [--quick]\n";
      return arg == "--help" || arg == "-h" ? EXIT_SUCCESS : EXIT_FAILURE;
    }
  }
  std::vector<Condition> conditions = {
      {"reference", 25, 0, 0, 0},       {"skew", 25, 0, 0.02, 0},    {"skew", 25, 0, 0.04, 0},
      {"skew", 25, 0, 0.08, 0},         {"skew", 25, 0, 0.16, 0},    {"latency", 25, 0.08, 0, 0},
      {"latency", 25, 0.16, 0, 0},      {"latency", 25, 0.32, 0, 0}, {"latency", 25, 0.64, 0, 0},
      {"frame rate", 10, 0, 0, 0},      {"frame rate", 5, 0, 0, 0},  {"frame rate", 2, 0, 0, 0},
      {"frame rate", 1, 0, 0, 0},       {"drops", 25, 0, 0, 0.3},    {"drops", 25, 0, 0, 0.6},
      {"combined", 15, 0.08, 0.02, 0.1}};
  if (quick) {
    conditions = {{"reference", 25, 0, 0, 0}, {"combined", 15, 0.08, 0.02, 0.1}};
  }
  std::cout << "gain " << gain << " /s, joint speed " << speedDeg << " deg/s, " << seeds
            << " seeds; servo from 5-10 deg per joint, converged: 0.5 px RMS for 10 frames within 30 s\n";
  std::cout << "| condition | fps | latency ms | skew ms | drops | acquisition px (stamped / unstamped) | servo "
               "compensated: converged, final joint error deg, s | servo as seen: converged, final deg, s |\n";
  std::cout << "|---|---|---|---|---|---|---|---|\n";
  const vpColVector target(
      {vpMath::rad(10), vpMath::rad(-8), vpMath::rad(12), vpMath::rad(15), vpMath::rad(-12), vpMath::rad(20)});
  vpProjectiveCell::vpSettings settings;
  settings.gain = gain;
  settings.maxRotationSpeed = vpMath::rad(speedDeg);
  settings.stepRotation = vpMath::rad(5.0);
  settings.timeout = 30.0;
  settings.maxLostTime = 1.0;
  settings.maxSkew = settings.maxLatency = 1e9; // no timing limit: the study measures where they should be
  settings.minFrameRate = 1e-9;
  // The servo's model: one acquisition per seed with the reference timing (the servo rows do not change it).
  std::vector<std::string> models(seeds + 1);
  for (unsigned int s = 1; s <= seeds; ++s) {
    Cell cell(conditions[0], static_cast<long>(s));
    vpProjectiveCell run(cell.arm, cell.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
    run.acquire();
    models[s] = (std::filesystem::temp_directory_path() /
                 ("projective-cell-timing-" + std::to_string(static_cast<long>(::getpid())) + "-" + std::to_string(s) +
                  ".json"))
                    .string();
    run.saveModel(models[s]);
  }
  for (const Condition &c : conditions) {
    double residual[2] = {0, 0};
    unsigned int acquired[2] = {0, 0};
    unsigned int converged[2] = {0, 0};
    double finalError[2] = {0, 0}, seconds[2] = {0, 0};
    const std::string group = c.group;
    const bool acquire = group == "latency" || group == "frame rate" || group == "combined" || group == "reference";
    const bool unstamped = group == "latency" || group == "reference";
    for (unsigned int s = 1; s <= seeds; ++s) {
      vpUniRand rng(static_cast<long>(s));
      vpColVector start = target;
      for (unsigned int i = 0; i < 6; ++i) {
        start[i] += vpMath::rad((rng.uniform(0.0, 1.0) < 0.5 ? -1.0 : 1.0) * rng.uniform(5.0, 10.0));
      }
      for (int stamps = 0; acquire && stamps < (unstamped ? 2 : 1); ++stamps) { // with and without stamps
        Cell cell(c, static_cast<long>(s));
        Unstamped hidden(cell.cell);
        vpProjectiveCell run(cell.arm, stamps == 0 ? static_cast<vpStereoImageSource &>(cell.cell) : hidden,
                             vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
        try {
          run.acquire();
          residual[stamps] += run.getModel().getAcquisition().getCalibrationResidual();
          ++acquired[stamps];
        } catch (const vpException &e) {
          std::cerr << group << " seed " << s << (stamps ? " unstamped" : "") << ": " << e.getStringMessage() << "\n";
        }
      }
      for (int compensate = 0; compensate < 2; ++compensate) {
        Cell cell(c, static_cast<long>(s));
        settings.latencyCompensation = compensate == 0;
        vpProjectiveCell run(cell.arm, cell.cell, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
        try {
          run.loadModel(models[s]);
          run.moveTo(target);
          run.teachHere();
          run.moveTo(start);
          const vpProjectiveCell::vpServoResult r = run.servo();
          if (r.end == vpProjectiveCell::SERVO_CONVERGED) {
            ++converged[compensate];
            // The truth: how far the joints ended from those s* was taught at (the image error is the task's own).
            const vpColVector e = r.q - target;
            finalError[compensate] += vpMath::deg(std::max(e.getMaxValue(), -e.getMinValue()));
            seconds[compensate] += r.seconds;
          } else {
            std::cerr << group << " seed " << s << (compensate ? " as seen" : " compensated") << ": " << r.message
                      << "\n";
          }
        } catch (const vpException &e) {
          std::cerr << group << " seed " << s << ": " << e.getStringMessage() << "\n";
        }
      }
    }
    std::ostringstream row;
    row << std::fixed << std::setprecision(3) << "| " << group << " | " << c.fps << " | " << 1000 * c.latency << " | "
        << 1000 * c.skew << " | " << c.drop << " | ";
    if (acquire) {
      row << (acquired[0] ? residual[0] / acquired[0] : -1.0) << " (" << acquired[0] << "/" << seeds << ") / ";
      if (unstamped) {
        row << (acquired[1] ? residual[1] / acquired[1] : -1.0) << " (" << acquired[1] << "/" << seeds << ")";
      } else {
        row << "-";
      }
    } else {
      row << "as the reference";
    }
    for (int k = 0; k < 2; ++k) {
      row << " | " << converged[k] << "/" << seeds;
      if (converged[k] > 0) {
        row << ", " << finalError[k] / converged[k] << ", " << std::setprecision(1) << seconds[k] / converged[k]
            << std::setprecision(3);
      }
    }
    std::cout << row.str() << " |" << std::endl;
  }
  for (const std::string &model : models) {
    if (!model.empty()) {
      std::filesystem::remove(model);
    }
  }
  return EXIT_SUCCESS;
}
