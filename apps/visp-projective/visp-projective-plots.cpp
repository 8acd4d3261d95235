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
  \file visp-projective-plots.cpp
  \brief The predicted marker paths of `visp-projective report --plots`, over the zero frame's images.
*/

#include "visp-projective-plots.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <fstream>
#include <iomanip>
#include <limits>
#include <sstream>

#include <visp3/core/vpException.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/io/vpImageIo.h>
#include <visp3/projective/vpProjectiveJoint.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
const char *const kColours[] = {"#d62728", "#2ca02c", "#1f77b4", "#ff7f0e", "#9467bd", "#17becf", "#8c564b", "#e377c2"};

//! A joint value as the legend writes it: degrees for a revolute joint, metres for a prismatic one.
std::string amount(double v, bool revolute)
{
  std::ostringstream os;
  os << std::showpos << std::fixed << std::setprecision(revolute ? 1 : 3) << (revolute ? vpMath::deg(v) : v)
     << (revolute ? " deg" : " m");
  return os.str();
}

//! The joint a trial frame moves: the one farthest from the zero frame's readings.
unsigned int movedJoint(const vpColVector &q, const vpColVector &q0)
{
  unsigned int joint = 0;
  for (unsigned int i = 1; i < q.size(); ++i) {
    joint = std::abs(q[i] - q0[i]) > std::abs(q[joint] - q0[joint]) ? i : joint;
  }
  return joint;
}
} // namespace

namespace vispProjective
{
std::vector<std::string> writeJointPathPlots(const vpProjectiveArmModel &model, const std::vector<int> &ids,
                                             double range, double travel, const std::string &folder,
                                             const vpProjectiveSession *session,
                                             const vpProjectiveSessionCalibration::vpMarkerExtractor &extractor)
{
  const unsigned int n = model.getNumberOfJoints(), m = static_cast<unsigned int>(model.markers().size());
  const vpProjectiveArmModel::JointVector qRef = model.zeroReferenceJoints();
  vpIoTools::makeDirectory(folder);
  // The acquired range of each joint (relative to the zero reference): its trials in the session.
  std::vector<double> lo(n, 0.0), hi(n, 0.0);
  unsigned int width = 0, height = 0, zero = 0;
  std::vector<unsigned int> trials;
  if (session != nullptr) {
    for (unsigned int k = 0; k < session->getNumberOfFrames(); ++k) {
      zero = session->getFrame(k).role == vpProjectiveSession::ZERO ? k : zero;
    }
    const vpColVector &q0 = session->getFrame(zero).q;
    for (unsigned int k = 0; k < session->getNumberOfFrames(); ++k) {
      const vpProjectiveSession::vpFrame &f = session->getFrame(k);
      if (f.role == vpProjectiveSession::TRIAL && f.q.size() == n) {
        const unsigned int i = movedJoint(f.q, q0);
        lo[i] = std::min(lo[i], f.q[i] - qRef(i));
        hi[i] = std::max(hi[i], f.q[i] - qRef(i));
        trials.push_back(k);
      }
    }
    vpImage<unsigned char> Il, Ir;
    session->getImages(zero, Il, Ir);
    width = Il.getWidth();
    height = Il.getHeight();
    for (int c = 0; c < 2; ++c) { // RGB: gnuplot's rgbimage reads it as it is
      vpImage<vpRGBa> I;
      vpImageConvert::convert(c == 0 ? Il : Ir, I);
      vpImageIo::write(I, folder + (c == 0 ? "/zero-left.png" : "/zero-right.png"));
    }
  }
  // The paths: 201 samples either way, solid (acquired) and dashed (extrapolated) files per camera and joint.
  std::vector<std::vector<std::ostringstream>> solid(2), dashed(2), measured(2), predicted(2);
  for (int c = 0; c < 2; ++c) {
    solid[c].resize(n);
    dashed[c].resize(n);
    measured[c].resize(n);
    predicted[c].resize(n);
  }
  Eigen::Vector4d low = Eigen::Vector4d::Constant(std::numeric_limits<double>::infinity()), high = -low;
  std::vector<double> extent(n);
  const int samples = 201;
  for (unsigned int i = 0; i < n; ++i) {
    const bool revolute = model.jointType(i) == vpProjectiveJoint::REVOLUTE;
    const double given = revolute ? vpMath::rad(range) : travel;
    const double acquired = std::max(-lo[i], hi[i]);
    extent[i] = given > 0.0 ? given : (acquired > 0.0 ? 1.5 * acquired : (revolute ? vpMath::rad(30.0) : 0.05));
    for (unsigned int j = 0; j < m; ++j) {
      int previous = -1; // the kind of the previous sample: 0 acquired, 1 extrapolated
      for (int k = 0; k < samples; ++k) {
        vpProjectiveArmModel::JointVector q = qRef;
        const double delta = extent[i] * (2.0 * k / (samples - 1) - 1.0);
        q(i) += delta;
        Eigen::Vector4d s;
        if (!model.predictMarker(j, model.displacement(q), s) || !s.allFinite()) {
          previous = -1;
          continue;
        }
        low = low.cwiseMin(s);
        high = high.cwiseMax(s);
        const int kind = session != nullptr && delta >= lo[i] - 1e-12 && delta <= hi[i] + 1e-12 ? 0 : 1;
        for (int c = 0; c < 2; ++c) {
          std::ostringstream &os = (kind == 0 ? solid : dashed)[c][i];
          if (kind != previous) {
            os << "\n"; // a new polyline (the last point of the other kind repeated: the line does not break)
          }
          os << s(2 * c) << " " << s(2 * c + 1) << "\n";
          if (kind != previous && previous >= 0) {
            (previous == 0 ? solid : dashed)[c][i] << s(2 * c) << " " << s(2 * c + 1) << "\n";
          }
        }
        previous = kind;
      }
      for (int c = 0; c < 2; ++c) {
        solid[c][i] << "\n";
        dashed[c][i] << "\n";
      }
    }
  }
  // The measurements: each trial's markers, beside the model's prediction at its readings.
  for (unsigned int k : trials) {
    const vpProjectiveSession::vpFrame &f = session->getFrame(k);
    const unsigned int i = movedJoint(f.q, session->getFrame(zero).q);
    std::vector<int> seen = f.markerIds;
    std::vector<vpImagePoint> l = f.markerLeft, r = f.markerRight;
    if (seen.empty() && extractor) {
      vpImage<unsigned char> Il, Ir;
      session->getImages(k, Il, Ir);
      extractor(Il, Ir, seen, l, r);
    }
    vpProjectiveArmModel::JointVector q(n);
    for (unsigned int a = 0; a < n; ++a) {
      q(a) = f.q[a];
    }
    const Eigen::Matrix4d H = model.displacement(q);
    for (size_t p = 0; p < seen.size(); ++p) {
      const auto it = std::find(ids.begin(), ids.end(), seen[p]);
      Eigen::Vector4d s;
      if (it != ids.end() && model.predictMarker(static_cast<unsigned int>(it - ids.begin()), H, s)) {
        for (int c = 0; c < 2; ++c) {
          const vpImagePoint &ip = c == 0 ? l[p] : r[p];
          measured[c][i] << ip.get_u() << " " << ip.get_v() << "\n";
          predicted[c][i] << s(2 * c) << " " << s(2 * c + 1) << "\n";
        }
      }
    }
  }

  std::vector<std::string> figures;
  for (int c = 0; c < 2; ++c) {
    const std::string side = c == 0 ? "left" : "right";
    std::ostringstream script, plots;
    double u0 = 0, u1 = width, v0 = 0, v1 = height;
    if (session == nullptr) { // the paths' bounding box with a margin
      const double mu = 0.05 * (high(2 * c) - low(2 * c)) + 1.0, mv = 0.05 * (high(2 * c + 1) - low(2 * c + 1)) + 1.0;
      u0 = low(2 * c) - mu;
      u1 = high(2 * c) + mu;
      v0 = low(2 * c + 1) - mv;
      v1 = high(2 * c + 1) + mv;
    }
    script << "set terminal pngcairo size 1200,800 font ',10'\nset output '" << folder << "/joint-paths-" << side
           << ".png'\nset title \"" << (c == 0 ? "Left" : "Right")
           << " camera: the marker paths the model predicts, each joint moving alone\\n"
           << (session != nullptr ? "over the zero frame; solid: the acquired range, dashed: extrapolated; o: measured "
                                    "in a trial, x: the model at its readings"
                                  : "(give the model's session: its images, acquired ranges and measurements)")
           << "\"\nset key font ',9'\nset xlabel 'u (pixels)'\nset ylabel 'v (pixels)'\nset size ratio -1\nset key "
              "outside right top\n"
           << "set xrange [" << u0 << ":" << u1 << "]\nset yrange [" << v1 << ":" << v0 << "]\n";
    if (session != nullptr) {
      script << "set object 1 rect from 0,0 to " << width << "," << height
             << " front fillstyle empty border lc rgb 'black' lw 2\n";
      plots << "'" << folder << "/zero-" << side << ".png' binary filetype=png flipy with rgbimage notitle";
    }
    for (unsigned int i = 0; i < n; ++i) {
      const bool revolute = model.jointType(i) == vpProjectiveJoint::REVOLUTE;
      const std::string base = folder + "/" + side + "-joint" + std::to_string(i);
      const std::string colour = kColours[i % 8];
      const std::pair<std::ostringstream *, std::string> files[] = {{&solid[c][i], base + "-acquired.dat"},
                                                                    {&dashed[c][i], base + "-extrapolated.dat"},
                                                                    {&measured[c][i], base + "-measured.dat"},
                                                                    {&predicted[c][i], base + "-predicted.dat"}};
      for (int f = 0; f < 4; ++f) {
        const std::string data = files[f].first->str();
        if (data.find_first_not_of("\n") == std::string::npos) {
          continue; // gnuplot refuses an empty file
        }
        std::ofstream(files[f].second.c_str()) << data;
        std::ostringstream title;
        title << "joint " << i << ": ";
        if (f == 0) {
          title << "acquired " << amount(lo[i], revolute) << " to " << amount(hi[i], revolute);
        } else if (f == 1) {
          title << (session != nullptr ? "extrapolated to " : "predicted, ") << amount(-extent[i], revolute) << " to "
                << amount(extent[i], revolute);
        } else {
          title << (f == 2 ? "measured (o)" : "model (x)");
        }
        plots << (plots.str().empty() ? "" : ", \\\n     ") << "'" << files[f].second << "' with "
              << (f == 0   ? "lines lw 2"
                  : f == 1 ? (session != nullptr ? "lines dt 2 lw 1" : "lines lw 2")
                  : f == 2 ? "points pt 6 ps 1.2"
                           : "points pt 2 ps 0.8")
              << " lc rgb '" << colour << "' title '" << title.str() << "'";
      }
    }
    script << "plot " << plots.str() << "\n";
    const std::string scriptFile = folder + "/joint-paths-" + side + ".gnuplot";
    std::ofstream(scriptFile.c_str()) << script.str();
    if (std::system(("gnuplot '" + scriptFile + "' 2>'" + scriptFile + ".log'").c_str()) != 0) {
      throw vpException(vpException::ioError, "gnuplot failed on '" + scriptFile + "' (see '" + scriptFile +
                                                  ".log'): install gnuplot (Debian: gnuplot-nox); the data and the "
                                                  "script are in '" +
                                                  folder + "'");
    }
    figures.push_back(folder + "/joint-paths-" + side + ".png");
  }
  return figures;
}
} // namespace vispProjective
