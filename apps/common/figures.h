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
  \file figures.h
  \brief What the servo apps show of a run: CSV data and PNG figures like the paper's Fig. 2, 4 and 5 (gnuplot,
  headless), and a live view of both camera images with the features' trajectories and targets.
*/

#ifndef _app_projective_figures_h_
#define _app_projective_figures_h_

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <functional>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#include "servo-report.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
/*!
  Writes the gnuplot \e commands to \e script and runs gnuplot on it (headless PNG terminals): says on \e log which
  figures (\e figures) were written, or, without gnuplot, that only the data \e data and the script were.
*/
inline void runGnuplot(const std::string &commands, const std::string &script, const std::string &figures,
                       const std::string &data, std::ostream &log = std::cout)
{
  std::ofstream(script.c_str()) << commands;
  if (std::system(("gnuplot '" + script + "' 2>/dev/null").c_str()) == 0) {
    log << "Figures written: " << figures << " (data " << data << ")\n";
  } else {
    log << "gnuplot is not available: only the data " << data << " and the script " << script << " were written\n";
  }
}

//! [Figures]
//! CSV of seed 1's trajectory, and PNG figures like the paper's Fig. 2, 4 and 5 through gnuplot (headless).
inline void writeFigures(const ServoRun &run, const std::string &dir)
{
  const std::string csv = dir + "/projective-servo-trajectory.csv";
  std::ofstream out(csv.c_str());
  out << "iteration";
  for (unsigned int i = 0; i < run.q.front().size(); ++i) {
    out << ",q" << i << "_deg";
  }
  for (unsigned int k = 0; k < run.left.front().size(); ++k) {
    out << ",u" << k << ",v" << k << ",up" << k << ",vp" << k;
  }
  out << ",error_rms_px";
  for (unsigned int r = 0; r < run.error.front().size(); ++r) {
    out << ",abs_e" << r;
  }
  out << "\n";
  for (size_t it = 0; it < run.q.size(); ++it) {
    out << it;
    for (unsigned int i = 0; i < run.q[it].size(); ++i) {
      out << "," << vpMath::deg(run.q[it][i]);
    }
    for (size_t k = 0; k < run.left[it].size(); ++k) {
      out << "," << run.left[it][k].get_u() << "," << run.left[it][k].get_v() << "," << run.right[it][k].get_u() << ","
          << run.right[it][k].get_v();
    }
    out << "," << std::sqrt(run.error[it].sumSquare() / run.error[it].size());
    for (unsigned int r = 0; r < run.error[it].size(); ++r) {
      out << "," << std::max(1e-6, std::abs(run.error[it][r]));
    }
    out << "\n";
  }
  out.close();
  const std::string targetCsv = dir + "/projective-servo-target.csv";
  std::ofstream target(targetCsv.c_str());
  target << "u,v,up,vp,u_initial,v_initial,up_initial,vp_initial\n";
  for (size_t k = 0; k < run.leftTarget.size(); ++k) {
    target << run.leftTarget[k].get_u() << "," << run.leftTarget[k].get_v() << "," << run.rightTarget[k].get_u() << ","
           << run.rightTarget[k].get_v() << "," << run.left.front()[k].get_u() << "," << run.left.front()[k].get_v()
           << "," << run.right.front()[k].get_u() << "," << run.right.front()[k].get_v() << "\n";
  }
  target.close();

  const unsigned int n = run.q.front().size(), nbPoints = static_cast<unsigned int>(run.left.front().size());
  std::ostringstream gp;
  gp << "set datafile separator ','\nset key outside\n";
  // Fig. 2: feature trajectories in both images (v axis downwards, as in the images).
  gp << "set terminal png size 1300,520\nset output '" << dir << "/projective-servo-fig2-features.png'\n"
     << "set multiplot layout 1,2\n";
  for (int camera = 0; camera < 2; ++camera) {
    gp << "set title '" << (camera == 0 ? "left" : "right") << " image'\nset xlabel 'u [px]'\nset ylabel 'v [px]'\n"
       << "set xrange [0:640]\nset yrange [480:0]\nset size ratio -1\nplot ";
    for (unsigned int k = 0; k < nbPoints; ++k) {
      const unsigned int c = 2 + n + 4 * k + 2 * camera;
      gp << "'" << csv << "' using " << c << ":" << c + 1 << " with linespoints pt 7 ps 0.5 title 'point " << k
         << "', ";
    }
    gp << "'" << targetCsv << "' using " << 5 + 2 * camera << ":" << 6 + 2 * camera
       << " with points pt 6 ps 2 lw 2 lc rgb 'black' title 'initial', '" << targetCsv << "' using " << 1 + 2 * camera
       << ":" << 2 + 2 * camera << " with points pt 2 ps 2 lw 2 lc rgb 'red' title 'target'\n";
  }
  gp << "unset multiplot\nset terminal png size 1000,480\nset autoscale\nset yrange [*:*]\nset xrange [*:*]\n"
     << "set size noratio\n";
  // Fig. 4: joint trajectories.
  gp << "set output '" << dir << "/projective-servo-fig4-joints.png'\nset title 'joint-space trajectory'\n"
     << "set xlabel 'iteration'\nset ylabel 'q [deg]'\nplot ";
  for (unsigned int i = 0; i < n; ++i) {
    gp << "'" << csv << "' using 1:" << 2 + i << " with linespoints title 'q" << i << "'" << (i + 1 < n ? ", " : "\n");
  }
  // Fig. 5: image error components, log scale.
  const unsigned int firstError = 2 + n + 4 * nbPoints + 1;
  gp << "set output '" << dir << "/projective-servo-fig5-error.png'\nset title 'image error |s - s*|'\n"
     << "set logscale y\nset ylabel '[px]'\nplot ";
  for (unsigned int r = 0; r < 4 * nbPoints; ++r) {
    gp << "'" << csv << "' using 1:" << firstError + r << " with lines notitle, ";
  }
  gp << "'" << csv << "' using 1:" << firstError - 1 << " with linespoints lw 2 title 'RMS'\n";
  runGnuplot(gp.str(), dir + "/projective-servo-figures.gp",
             dir + "/projective-servo-fig{2-features,4-joints,5-error}.png", csv);
}
//! [Figures]

//! [Prediction figure]
/*!
  The model's prediction error over a servo run whose rig was bumped (projective-bumped-camera.cpp): CSV
  \e dir/projective-bumped-prediction.csv (iteration, error in px, phase) and the PNG
  \e dir/projective-bumped-prediction.png through gnuplot (log scale), one colour per phase: \e phase[it] is 0 before
  the bump, 1 with the bumped camera and the old rig, 2 after the rig was re-registered.
*/
inline void writePredictionFigure(const std::vector<double> &error, const std::vector<int> &phase,
                                  const std::string &dir)
{
  const std::string csv = dir + "/projective-bumped-prediction.csv", png = dir + "/projective-bumped-prediction.png";
  std::ofstream out(csv.c_str());
  out << "iteration,prediction_error_px,phase\n";
  for (size_t it = 0; it < error.size(); ++it) {
    out << it << "," << error[it] << "," << phase[it] << "\n";
  }
  out.close();
  std::ostringstream gp;
  gp << "set datafile separator ','\nset terminal png size 1000,480\nset output '" << png << "'\n"
     << "set title 'model prediction error of the tracked markers (RMS per coordinate)'\n"
     << "set xlabel 'servo iteration'\nset ylabel '[px]'\nset logscale y\nset key top right\nplot ";
  const char *names[3] = {"before the bump", "camera bumped, old rig", "rig re-registered"};
  const char *colours[3] = {"#1a9850", "#d73027", "#4575b4"};
  for (int p = 0; p < 3; ++p) {
    gp << "'" << csv << "' every ::1 using 1:($3 == " << p << " ? $2 : 1/0) with linespoints pt 7 ps 0.7 lc rgb '"
       << colours[p] << "' title '" << names[p] << "'" << (p < 2 ? ", " : "\n");
  }
  runGnuplot(gp.str(), dir + "/projective-bumped-prediction.gp", png, csv);
}
//! [Prediction figure]

//! [Live display]
/*!
  The two camera images of a servo run, if there is a display (vpStereoServoDisplay on white images: the simulated
  cameras give pixels): the measured markers (green) and their paths, their targets (red crosses), and a vpPlot of
  the image error and the joints. Without a display it draws nothing.
*/
class LiveView
{
public:
  //! A window for \e width x \e height images at (\e x, \e y) on the screen, if \e display and there is a display;
  //! waitForClick() waits only if \e click.
  LiveView(unsigned int width, unsigned int height, bool display, bool click, int x = 0, int y = 0)
      : m_display(width, height, display && vpStereoServoDisplay::hasDisplay(), x, y), m_click(click)
  {
  }

  //! True if the windows are open.
  bool isOpen() const { return m_display.isOpen(); }

  //! The function for a servo loop to call at every iteration: empty if the windows are not open.
  std::function<void(const ServoRun &)> callback()
  {
    if (!isOpen()) {
      return std::function<void(const ServoRun &)>();
    }
    return [this](const ServoRun &run) { show(run); };
  }

  //! Draws iteration \e iterations - 1 of the run (its last one by default): call it once per iteration, in order.
  void show(const ServoRun &run, size_t iterations = 0)
  {
    if (!isOpen() || run.q.empty()) {
      return;
    }
    const size_t n = iterations > 0 ? std::min(iterations, run.q.size()) : run.q.size();
    m_display.display();
    for (unsigned int k = 0; k < run.leftTarget.size(); ++k) {
      vpFeatureStereoPoint s, s_star;
      s.buildFrom(run.left[n - 1][k], run.right[n - 1][k]);
      s_star.buildFrom(run.leftTarget[k], run.rightTarget[k]);
      m_display.displayFeature(k, s, s_star);
    }
    const double rms = std::sqrt(run.error[n - 1].sumSquare() / run.error[n - 1].size());
    std::ostringstream os;
    os << "iteration " << n - 1 << ", image error " << std::fixed << std::setprecision(2) << rms << " px RMS";
    m_display.displayText(os.str());
    m_display.flush();
    m_display.plot(run.error[n - 1], run.q[n - 1]);
  }

  //! Shows the marker images \e left, \e right (e.g. an acquisition step) with \e caption, if the windows are open.
  void showMarkers(const std::string &caption, const std::vector<vpImagePoint> &left,
                   const std::vector<vpImagePoint> &right)
  {
    if (!isOpen()) {
      return;
    }
    m_display.display();
    m_display.displayMarkers(left, right, vpColor::blue);
    m_display.displayText(caption);
    m_display.flush();
  }

  //! If the windows are open and clicks are allowed, waits for a click in the images' window.
  void waitForClick()
  {
    if (isOpen() && m_click) {
      std::cout << "Click in the window to quit" << std::endl;
      m_display.getClick();
    }
  }

private:
  vpStereoServoDisplay m_display;
  bool m_click;
};
//! [Live display]
} // namespace app

#endif
