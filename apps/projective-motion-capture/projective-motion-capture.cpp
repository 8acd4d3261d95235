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
  Motion capture with projective kinematics (Ruf & Horaud's "motion capture" use): an arm moves on its own, along a
  joint trajectory the plugin does not know, and an uncalibrated stereo rig recovers its joint values and velocities
  from the marker images of every frame.

  1. The paper's world (projective-paper.cpp): the projective model of the PUMA-like arm is acquired once by
     its trial motions, with the same pixel noise as the frames, averaged over the 16 frames the arm stands still at
     each pose (--still-frames): a model 4 times more accurate than single frames leaves the capture at the floor
     of its frames.
  2. The arm then follows a smooth trajectory (two sines per joint, 25 Hz); at every frame vpProjectiveMotionCapture
     minimises the pixel error of the 7 markers over the joint values (vpProjectiveInverseKinematics, warm-started at
     the previous frame's), and fits the joint velocities over the last 12 frames. Two markers are hidden for a
     while: the capture goes on with 5.
  3. The captured joints are compared with the truth and with the per-frame accuracy floor
     sqrt(diag(sigma^2 (J^T J)^-1)) of the true image Jacobian of the visible markers: no estimator from one frame's
     pixels does better. The table prints each joint's error against its floor, frame by frame; the figures
     (motion-capture-joints.png, motion-capture-errors.png, with gnuplot) plot the captured joints over the true ones
     and the errors against +-floor.

  Usage: projective-motion-capture [--frames N] [--noise SIGMA] [--seed S] [--still-frames N] [--output DIR]
  [-d] [-c] [--help]
  With a display (and no -d) the capture is shown live at 25 Hz (vpStereoServoDisplay, white images): the markers
  measured (green, with their paths; hidden ones not drawn), the model's images of them at the captured joints (red),
  and a vpPlot of their difference and the captured joints; it then waits for a click (-c: not).
  Exits with 1 if a frame could not be captured or a joint's median error exceeds 1.25 times the floor's (the median
  |error| / floor exceeds 1.25 x 0.674).
*/

#include <cmath>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpTime.h>

#include <visp3/projective/vpProjectiveMotionCapture.h>
#include <visp3/projective/vpProjectiveRobot.h>

#include "command-line.h"
#include "paper-world.h"
#include "figures.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
/*!
  The trajectory the arm follows on its own (rad, relative to the zero reference): two sines per joint, smaller for
  the shoulder joints, whose long lever would take the markers out of the 38 x 29 cm view. Twice (near 0.8 s and
  8.3 s) it passes close to a configuration where joints 0, 3 and 5 move the markers alike: there the floor of those
  joints rises to tens of degrees, since no frame's pixels tell them apart.
*/
vpColVector trajectory(double t)
{
  const double amplitudeDeg[6] = {6, 5, 6, 20, 20, 30};
  vpColVector q(6);
  for (unsigned int i = 0; i < 6; ++i) {
    q[i] = vpMath::rad(amplitudeDeg[i]) * (0.6 * std::sin(0.7 * t + i) + 0.4 * std::sin(1.9 * t + 2.0 * i));
  }
  return q;
}

//! One captured frame: time, true and captured joints, velocity, floor (rad).
struct Frame {
  double t;
  vpColVector q, qCaptured, qdotCaptured, floor;
};

void writeFigures(const std::vector<Frame> &frames, const std::string &dir)
{
  const std::string csv = dir + "/motion-capture.csv";
  std::ofstream out(csv.c_str());
  out << std::setprecision(10);
  for (const Frame &f : frames) {
    out << f.t;
    for (unsigned int i = 0; i < 6; ++i) {
      out << ' ' << vpMath::deg(f.q[i]) << ' ' << vpMath::deg(f.qCaptured[i]) << ' ' << vpMath::deg(f.floor[i]);
    }
    out << '\n';
  }
  std::ostringstream gp;
  gp << "set terminal png size 1200,800\nset key top left\nset xlabel 't [s]'\n";
  gp << "set output '" << dir << "/motion-capture-joints.png'\nset multiplot layout 2,3 title 'captured (dots) "
     << "and true (lines) joint values'\n";
  for (unsigned int i = 0; i < 6; ++i) {
    gp << "set ylabel 'q" << i << " [deg]'\nplot '" << csv << "' using 1:" << 2 + 3 * i << " with lines lw 2 title "
       << "'true', '' using 1:" << 3 + 3 * i << " with points pt 7 ps 0.4 title 'captured'\n";
  }
  gp << "unset multiplot\nset output '" << dir << "/motion-capture-errors.png'\n"
     << "set multiplot layout 2,3 title 'capture error and the per-frame floor'\n";
  for (unsigned int i = 0; i < 6; ++i) {
    gp << "set ylabel 'error q" << i << " [deg]'\nplot '" << csv << "' using 1:($" << 3 + 3 * i << "-$" << 2 + 3 * i
       << ") with points pt 7 ps 0.4 title 'error', '' using 1:" << 4 + 3 * i << " with lines lc rgb 'black' title "
       << "'+-floor', '' using 1:(-$" << 4 + 3 * i << ") with lines lc rgb 'black' notitle\n";
  }
  gp << "unset multiplot\n";
  app::runGnuplot(gp.str(), dir + "/motion-capture.gp",
                  dir + "/motion-capture-joints.png, " + dir + "/motion-capture-errors.png", csv);
}
} // namespace

int main(int argc, char **argv)
{
  unsigned int frames = 250, seed = 1, stillFrames = 16;
  double sigma = 0.5;
  std::string output = ".";
  bool display = vpStereoServoDisplay::hasDisplay(), click = true;
  app::CommandLine cmd;
  cmd.add("--frames", frames, "N", "number of frames (25 Hz)", 20)
      .add("--noise", sigma, "SIGMA", "pixel noise (px, Gaussian, every image coordinate)", 0.0)
      .add("--seed", seed, "S", "seed of the noise", 1)
      .add("--still-frames", stillFrames, "N", "frames averaged at each pose of the acquisition", 1)
      .add("--output", output, "DIR", "where the CSV data and the figures are written")
      .displayOptions(display, click);
  int exitCode = 0;
  if (!cmd.parse(argc, argv, exitCode)) {
    return exitCode;
  }
  try {
    vpIoTools::makeDirectory(output);
    // 1. The model, acquired from images by the paper's trial motions. The arm stands still at each pose: the marker
    //    images are averaged over a few frames, so that the model is more accurate than one frame.
    const app::PaperWorld world;
    vpGaussRand noise(sigma, 0.0, seed);
    const app::ImagesAt imagesAt = [&](const vpColVector &q, std::vector<vpImagePoint> &left,
                                       std::vector<vpImagePoint> &right) {
      return world.rig.project(world.arm.getMarkers(q), left, right, sigma, noise);
    };
    const app::ImagesAt stillImagesAt = [&](const vpColVector &q, std::vector<vpImagePoint> &left,
                                            std::vector<vpImagePoint> &right) {
      bool visible = imagesAt(q, left, right);
      for (unsigned int k = 1; k < stillFrames; ++k) {
        std::vector<vpImagePoint> l, r;
        visible = imagesAt(q, l, r) && visible;
        for (size_t j = 0; j < l.size(); ++j) {
          left[j] += l[j];
          right[j] += r[j];
        }
      }
      for (size_t j = 0; j < left.size(); ++j) {
        left[j] /= stillFrames;
        right[j] /= stillFrames;
      }
      return visible;
    };
    const vpProjectiveRobot robot =
        app::acquireByTrials(world.trialDeg, stillImagesAt, std::max(1.0, 4.0 * sigma / std::sqrt(stillFrames)), true);
    std::cout << "Model acquired: bundle adjustment RMS " << robot.getAcquisition().getCalibrationResidual() << " px\n";

    // 2. The arm moves on its own; each frame's images give its joints.
    vpProjectiveMotionCapture capture(robot.getModel());
    capture.setVelocityWindow(12);
    capture.setInitialJoints(trajectory(0.0) + vpColVector(6, vpMath::rad(1.0))); // roughly where it starts
    const app::ImagesAt trueImages = app::trueMarkerImages(world.rig, world.arm);
    std::vector<Frame> captured;
    double seconds = 0.0;
    vpStereoServoDisplay view(world.rig.getWidth(), world.rig.getHeight(), display);
    for (unsigned int k = 0; k < frames; ++k) {
      Frame f;
      f.t = k / 25.0;
      f.q = trajectory(f.t);
      std::vector<vpImagePoint> left, right;
      if (!imagesAt(f.q, left, right)) {
        std::cerr << "frame " << k << ": a marker left the view\n";
        return 1;
      }
      std::vector<bool> visible(left.size(), true);
      if (k >= 100 && k < 130) {
        visible[5] = visible[6] = false; // two markers hidden for 1.2 s
      }
      const double start = vpTime::measureTimeMicros();
      capture.capture(f.t, left, right, visible);
      seconds += 1e-6 * (vpTime::measureTimeMicros() - start);
      f.qCaptured = capture.getJoints();
      f.qdotCaptured = k > 0 ? capture.getJointVelocities() : vpColVector(6, 0.0);
      // 3. The floor of this frame: the true Jacobian of the visible markers' images.
      vpMatrix J = app::imageJacobian(trueImages, f.q);
      for (unsigned int row = 0; row < J.getRows(); ++row) {
        for (unsigned int c = 0; !visible[row / 4] && c < J.getCols(); ++c) {
          J[row][c] = 0.0; // a hidden marker constrains nothing
        }
      }
      f.floor = app::noiseFloor(J, sigma);
      captured.push_back(f);
      if (view.isOpen()) { // measured (s) against the model's images at the captured joints (s*)
        view.display();
        vpColVector e;
        for (unsigned int j = 0; j < left.size(); ++j) {
          vpImagePoint l, r;
          robot.getModel().projectMarker(j, f.qCaptured, l, r);
          vpFeatureStereoPoint s, s_star;
          s.buildFrom(left[j], right[j]);
          s_star.buildFrom(l, r);
          view.displayFeature(j, s, s_star, visible[j]);
          e.stack(s.error(s_star));
        }
        view.displayText("frame " + std::to_string(k) + (k >= 100 && k < 130 ? ": markers 5 and 6 hidden" : ""));
        view.flush();
        view.plot(e, f.qCaptured);
        vpTime::wait(40.0); // about 25 Hz
      }
    }

    // Per joint: the error of each frame over that frame's floor, RMS and median of its magnitude over the frames: an
    // efficient estimator has 1 and 0.674; the model's own error (acquired at the same noise) adds to the floor, most
    // where the floor is far from linear, near the singular configuration.
    std::cout << "\n"
              << frames << " frames at " << sigma << " px, " << 1e6 * seconds / frames
              << " us per frame on average (the benchmark program times it)\n"
              << "| joint | RMS error (deg) | RMS floor (deg) | error / floor, RMS | median |error| / floor | RMS "
                 "velocity error (deg/s) |\n|---|---|---|---|---|---|\n";
    bool ok = true;
    for (unsigned int i = 0; i < 6; ++i) {
      double e2 = 0.0, f2 = 0.0, z2 = 0.0, v2 = 0.0;
      std::vector<double> z;
      for (size_t k = 0; k < captured.size(); ++k) {
        const Frame &f = captured[k];
        const double e = f.qCaptured[i] - f.q[i];
        e2 += e * e / captured.size();
        f2 += f.floor[i] * f.floor[i] / captured.size();
        z2 += std::pow(e / f.floor[i], 2) / captured.size();
        z.push_back(std::abs(e / f.floor[i]));
        const double h = 1e-6; // the true velocity, a central difference of the trajectory
        const double qdot = (trajectory(f.t + h)[i] - trajectory(f.t - h)[i]) / (2.0 * h);
        v2 += k >= 12 ? std::pow(f.qdotCaptured[i] - qdot, 2) / (captured.size() - 12) : 0.0;
      }
      ok = ok && app::median(z) <= 1.25 * 0.674;
      std::cout << "| " << i << " | " << vpMath::deg(std::sqrt(e2)) << " | " << vpMath::deg(std::sqrt(f2)) << " | "
                << std::sqrt(z2) << " | " << app::median(z) << " | " << vpMath::deg(std::sqrt(v2)) << " |\n";
    }
    writeFigures(captured, output);
    if (view.isOpen() && click) {
      std::cout << "Click in the window to quit" << std::endl;
      view.getClick();
    }
    return ok ? 0 : 1;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return 1;
  }
}
