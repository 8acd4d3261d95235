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
  vpProjectiveSessionCalibration::check()'s diagnosis: the probable causes of frames that a model does not fit, each
  tried by a fix (the images exchanged, the rig re-registered, the markers refitted, a free motion per frame) or shown
  by the fingerprint of the cell, ranked likeliest first.
*/

#include <visp3/projective/vpProjectiveSessionCalibration.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <set>
#include <sstream>

#include <visp3/core/vpException.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveRigRegistration.h>

#include "rig/vpStereoRigGeometry.h"
#include "session/vpProjectiveSessionInternal.h"

using namespace vpProjectiveInternal;
using namespace vpProjectiveSessionInternal;

namespace
{
typedef vpProjectiveSessionCalibration Calibration;
typedef std::vector<std::pair<unsigned int, Eigen::Vector4d>> Pairs;

const double kNaN = std::numeric_limits<double>::quiet_NaN();

//! At most this many frames, evenly spread, are refitted (the fixes are least-squares fits: a few dozen frames tell).
const size_t kMaxFittedFrames = 40;

//! The frames the fixes are tried on: all, or kMaxFittedFrames evenly spread.
std::vector<const CheckedFrame *> fittedFrames(const std::vector<CheckedFrame> &frames)
{
  std::vector<const CheckedFrame *> kept;
  const size_t n = frames.size();
  for (size_t i = 0; i < std::min(n, kMaxFittedFrames); ++i) {
    kept.push_back(&frames[n <= kMaxFittedFrames ? i : i * (n - 1) / (kMaxFittedFrames - 1)]);
  }
  return kept;
}

//! True if the frames hold two configurations or more (else the markers' motion tells nothing about the readings).
bool severalConfigurations(const std::vector<const CheckedFrame *> &frames)
{
  for (const CheckedFrame *f : frames) {
    if ((f->joints - frames.front()->joints).norm() > 1e-9) {
      return true;
    }
  }
  return false;
}

//! \e s with its left and right images exchanged.
Eigen::Vector4d exchanged(const Eigen::Vector4d &s)
{
  return Eigen::Vector4d(s(2), s(3), s(0), s(1));
}

//! RMS per coordinate of the model's prediction with the session's images exchanged.
double exchangedResidual(const vpProjectiveArmModel &model, const std::vector<const CheckedFrame *> &frames)
{
  double l = 0.0, r = 0.0;
  unsigned int count = 0;
  for (const CheckedFrame *f : frames) {
    Pairs pairs = f->pairs;
    for (auto &pair : pairs) {
      pair.second = exchanged(pair.second);
    }
    predictionError(model, f->q, pairs, l, r, count);
  }
  return rms(l + r, 4 * count);
}

//! RMS epipolar distance (px) of the matches under the model's F, as they are (\e asIs) and exchanged.
void epipolarResiduals(const vpProjectiveArmModel &model, const std::vector<CheckedFrame> &frames, double &asIs,
                       double &exchangedImages)
{
  Eigen::Matrix3d F;
  model.getStereoRig().getFundamentalMatrix(F);
  double a = 0.0, e = 0.0;
  unsigned int count = 0;
  for (const CheckedFrame &f : frames) {
    for (const auto &pair : f.pairs) {
      const Eigen::Vector2d m = pair.second.head<2>(), mp = pair.second.tail<2>();
      a += std::pow(epipolarDistance(F, m, mp), 2);
      e += std::pow(epipolarDistance(F, mp, m), 2);
      ++count;
    }
  }
  asIs = rms(a, count);
  exchangedImages = rms(e, count);
}

//! RMS per coordinate of the session under the model's rig re-registered on it (the arm and markers kept); NaN if
//! the registration fails (too few points, or a camera farther than vpProjectiveRigRegistration::maxResidual).
double reRegisteredResidual(const vpProjectiveArmModel &model, const std::vector<const CheckedFrame *> &frames)
{
  std::vector<Eigen::Vector4d> points, images;
  for (const CheckedFrame *f : frames) {
    const Eigen::Matrix4d H = model.displacement(f->joints);
    for (const auto &pair : f->pairs) {
      points.push_back(H * model.markers()[pair.first]);
      images.push_back(pair.second);
    }
  }
  try {
    double residual = kNaN;
    vpProjectiveRigRegistration::registerRig(model.getStereoRig(), model.projectiveToMetric(), points, images,
                                             vpProjectiveRigRegistration::FIXED_INTRINSICS, &residual);
    return residual;
  } catch (const vpException &) {
    return kNaN;
  }
}

//! The DLT rows of pixel \e uv seen by the camera \e C (3x4) added to the normal matrix \e A (rows of unit norm).
void addView(const Eigen::Matrix<double, 3, 4> &C, const Eigen::Vector2d &uv, Eigen::Matrix4d &A)
{
  for (int i = 0; i < 2; ++i) {
    Eigen::Matrix<double, 1, 4> row = uv(i) * C.row(2) - C.row(i);
    if (row.norm() > 0.0) {
      row.normalize();
      A += row.transpose() * row;
    }
  }
}

/*!
  RMS per coordinate of the session with each model marker refitted on it (triangulated over every frame through the
  model's cameras moved by H(q): the markers moved on the tool, the rig and the arm as in the model); NaN with fewer
  than two configurations.
*/
double refittedMarkersResidual(const vpProjectiveArmModel &model, const std::vector<const CheckedFrame *> &frames)
{
  if (!severalConfigurations(frames)) {
    return kNaN;
  }
  const vpProjectiveStereoRig &rig = model.getStereoRig();
  vpProjectiveStereoRig::Projection P, Pp;
  rig.getLeftProjection(P);
  rig.getRightProjection(Pp);
  const size_t m = model.markers().size();
  std::vector<Eigen::Matrix4d> normal(m, Eigen::Matrix4d::Zero());
  std::vector<Eigen::Matrix4d> H;
  for (const CheckedFrame *f : frames) {
    H.push_back(model.displacement(f->joints));
    for (const auto &pair : f->pairs) {
      addView(P * H.back(), pair.second.head<2>(), normal[pair.first]);
      addView(Pp * H.back(), pair.second.tail<2>(), normal[pair.first]);
    }
  }
  std::vector<Eigen::Vector4d> refitted(m, Eigen::Vector4d::Zero());
  for (size_t j = 0; j < m; ++j) {
    if (!normal[j].isZero() && !smallestSingularVector(normal[j], refitted[j])) {
      return kNaN;
    }
  }
  double sum = 0.0;
  unsigned int count = 0;
  for (size_t k = 0; k < frames.size(); ++k) {
    for (const auto &pair : frames[k]->pairs) {
      Eigen::Vector4d s;
      sum += rig.project(H[k] * refitted[pair.first], s) ? (s - pair.second).squaredNorm() : 4e12;
      count += 4;
    }
  }
  return rms(sum, count);
}

/*!
  RMS per coordinate of the session with the model's markers moved by a free projective displacement per frame
  (vpProjectiveDisplacement::estimateFromImages() from their images at the zero reference): what fits when the
  markers are the model's but the readings do not say their motion; NaN with fewer than two configurations. Frames
  with fewer than 5 markers are left out.
*/
double freeMotionResidual(const vpProjectiveArmModel &model, const std::vector<const CheckedFrame *> &frames)
{
  if (!severalConfigurations(frames)) {
    return kNaN;
  }
  double sum = 0.0;
  unsigned int count = 0;
  for (const CheckedFrame *f : frames) {
    if (f->pairs.size() < 5) {
      continue;
    }
    std::vector<Eigen::Vector4d> s0, s1;
    for (const auto &pair : f->pairs) {
      Eigen::Vector4d s;
      if (model.predictMarker(pair.first, Eigen::Matrix4d::Identity(), s)) {
        s0.push_back(s);
        s1.push_back(pair.second);
      }
    }
    if (s0.size() < 5) {
      continue;
    }
    try {
      const Eigen::Matrix4d H = vpProjectiveDisplacement::estimateFromImages(model.getStereoRig(), s0, s1, 50);
      for (const auto &pair : f->pairs) {
        Eigen::Vector4d s;
        sum += model.predictMarker(pair.first, H, s) ? (s - pair.second).squaredNorm() : 4e12;
        count += 4;
      }
    } catch (const vpException &) {
      return kNaN;
    }
  }
  return count > 0 ? rms(sum, count) : kNaN;
}

/*!
  The residual (px) under which a fix fits: three times the session's own image noise, measured as the residual of
  its matches under the fundamental matrix estimated from them (vpProjectiveStereoRig::estimate(), inliers within the
  mismatch threshold \e m), between 0.5 px and \e m; \e m when it cannot be estimated (fewer than 8 matches).
*/
double fitLimit(const std::vector<CheckedFrame> &frames, double m)
{
  std::vector<vpImagePoint> left, right;
  for (const CheckedFrame &f : frames) {
    for (const auto &pair : f.pairs) {
      left.push_back(vpImagePoint(pair.second(1), pair.second(0)));
      right.push_back(vpImagePoint(pair.second(3), pair.second(2)));
    }
  }
  try {
    vpProjectiveStereoRig own;
    own.estimate(left, right, m);
    return std::min(m, std::max(0.5, 3.0 * own.getEstimationResidual()));
  } catch (const vpException &) {
    return m;
  }
}

//! "1.23 px", or "not tried" for NaN.
std::string residualText(double px)
{
  return std::isfinite(px) ? pixels(px) : std::string("not tried");
}

//! Rank of a cause among the likely ones: the fewest things changed first.
int rankOf(Calibration::vpRigState cause)
{
  switch (cause) {
  case Calibration::CAMERAS_SWAPPED:
    return 0;
  case Calibration::LEFT_CAMERA_MOVED:
  case Calibration::RIGHT_CAMERA_MOVED:
    return 2;
  case Calibration::MARKERS_MOVED:
    return 3;
  case Calibration::BOTH_CAMERAS_MOVED:
    return 4;
  case Calibration::OTHER_READINGS:
    return 5;
  default:
    return 6;
  }
}
} // namespace

namespace vpProjectiveSessionInternal
{
std::string causeName(Calibration::vpRigState cause)
{
  const char *const names[] = {
      "no change",        "the left camera moved",     "the right camera moved",     "both cameras moved",
      "exchanged images", "markers moved on the tool", "readings of other encoders", "another cell"};
  return names[static_cast<int>(cause)];
}

std::vector<Calibration::vpCheckDiagnosis> diagnoseMismatch(const MismatchInput &in)
{
  const vpProjectiveArmModel &model = in.model;
  const double m = fitLimit(in.frames, in.threshold);
  const std::vector<const CheckedFrame *> fitted = fittedFrames(in.frames);
  double epipolar = 0.0, epipolarExchanged = 0.0;
  epipolarResiduals(model, in.frames, epipolar, epipolarExchanged);
  // The matches meet the model's epipolar geometry, and not markedly better exchanged: its rig did not change (a
  // symmetric rig of like cameras has F close to F^T: exchanged images then meet F within a pixel, F^T much closer).
  const bool rigKept = epipolar <= m && !(4.0 * epipolarExchanged < epipolar);

  // The fingerprint of the cell: image size, cameras, marker identifiers.
  const vpProjectiveCellFingerprint &cell = in.cell;
  const vpProjectiveSession &session = in.session;
  std::vector<std::string> otherCell;
  const std::string otherSize = cell.imageSizeMismatch(session.getWidth(), session.getHeight());
  if (!otherSize.empty()) {
    otherCell.push_back(otherSize);
  }
  typedef vpProjectiveCellFingerprint FP;
  const int sameLeft = FP::sameCamera(session.getLeftCamera(), cell.getLeftCamera());
  const int sameRight = FP::sameCamera(session.getRightCamera(), cell.getRightCamera());
  const bool camerasExchanged = FP::sameCamera(session.getLeftCamera(), cell.getRightCamera()) == 1 &&
                                FP::sameCamera(session.getRightCamera(), cell.getLeftCamera()) == 1;
  if (!camerasExchanged && (sameLeft == 0 || sameRight == 0)) {
    otherCell.push_back("its cameras are " + FP::toString(session.getLeftCamera()) + " and " +
                        FP::toString(session.getRightCamera()) + ", the model's " + FP::toString(cell.getLeftCamera()) +
                        " and " + FP::toString(cell.getRightCamera()));
  }
  if (2 * in.modelIdsSeen < in.ids.size()) {
    otherCell.push_back(
        "it shows " + std::to_string(in.modelIdsSeen) + " of the model's " + std::to_string(in.ids.size()) +
        " markers" +
        (in.otherIds > 0 ? " and " + std::to_string(in.otherIds) + " markers the model does not have" : std::string()));
  }

  std::vector<Calibration::vpCheckDiagnosis> causes;
  auto add = [&causes](Calibration::vpRigState cause, bool likely, double residual, const std::string &finding,
                       const std::string &fix) {
    causes.push_back({cause, likely, residual, finding, fix});
  };
  const std::string reRegister = "re-register the rig (vpProjectiveRobot::updateRig() from 3 observation poses) or "
                                 "calibrate again";
  const double swapResidual = exchangedResidual(model, fitted);
  {
    const double residual = swapResidual;
    std::ostringstream os;
    os << "the left and right images are exchanged: with them exchanged the model fits the session within "
       << residualText(residual) << " RMS; its matches are " << pixels(epipolarExchanged)
       << " from the model's epipolar lines exchanged, " << pixels(epipolar) << " as they are";
    if (camerasExchanged) {
      os << "; its left camera is the model's right one (" << FP::toString(session.getLeftCamera()) << ")";
    }
    add(Calibration::CAMERAS_SWAPPED, camerasExchanged || residual <= m || (epipolarExchanged <= m && !rigKept),
        residual, os.str(),
        "exchange the left and right cameras (their devices or cables, or the session's left and right images) and "
        "record again");
  }
  const double reRegistered = in.leftOff > 0 || in.rightOff > 0 ? reRegisteredResidual(model, fitted) : kNaN;
  const std::string registered = "; a rig re-registered on the session fits it within " + residualText(reRegistered);
  if (in.rightOff == 0) {
    add(Calibration::LEFT_CAMERA_MOVED, true, reRegistered,
        "the left camera moved: its images are off by " + pixels(in.leftResidual) + " RMS, the right ones fit (" +
            pixels(in.rightResidual) + ")" + registered,
        reRegister);
  } else if (in.leftOff == 0) {
    add(Calibration::RIGHT_CAMERA_MOVED, true, reRegistered,
        "the right camera moved: its images are off by " + pixels(in.rightResidual) + " RMS, the left ones fit (" +
            pixels(in.leftResidual) + ")" + registered,
        reRegister);
  } else {
    // Exchanged images that fit with nothing refitted explain a pair of like cameras that seem to have moved.
    add(Calibration::BOTH_CAMERAS_MOVED, reRegistered <= m && !(swapResidual <= m), reRegistered,
        "both cameras moved (or the arm is seen by another rig): both images are off (left " + pixels(in.leftResidual) +
            ", right " + pixels(in.rightResidual) + " RMS)" + registered,
        reRegister);
  }
  const double refitted = refittedMarkersResidual(model, fitted);
  add(Calibration::MARKERS_MOVED, rigKept && refitted <= m, refitted,
      "the markers moved on the tool: the matches meet the model's epipolar geometry (" + pixels(epipolar) +
          ": the rig did not change) and the markers refitted on the session fit it within " + residualText(refitted),
      "fix the markers on the tool and calibrate again");
  // A free motion per frame also fits a rig that changed along its epipolar lines, and moved markers: the readings
  // are the cause left when neither the re-registered rig nor the refitted markers fit.
  const double freeMotion = freeMotionResidual(model, fitted);
  add(Calibration::OTHER_READINGS, freeMotion <= m && !(refitted <= m) && !(reRegistered <= m), freeMotion,
      "the readings are not the model's encoders: the model's rig and markers fit each frame within " +
          residualText(freeMotion) +
          " when moved freely, not by the motion its readings give (another arm, the "
          "joints in another order, other units or another zero)",
      "record the readings of the encoders the model was calibrated with, or calibrate this arm");
  bool anyLikely = false;
  for (const Calibration::vpCheckDiagnosis &c : causes) {
    anyLikely = anyLikely || c.likely;
  }
  std::string facts;
  for (const std::string &f : otherCell) {
    facts += (facts.empty() ? "" : "; ") + f;
  }
  add(Calibration::OTHER_CELL, !otherCell.empty() || !anyLikely, kNaN,
      "the session is of another cell: " + (facts.empty() ? std::string("no fix fits it") : facts),
      "check the session against the model of its own cell, or calibrate this cell");

  // Likely causes first, the fewest things changed first; a cell whose fingerprint differs right after exchanged
  // images that fit (which explain cameras that seem other), before the rest.
  auto rank = [&](const Calibration::vpCheckDiagnosis &c) {
    const int r = rankOf(c.cause);
    return c.cause == Calibration::OTHER_CELL && !otherCell.empty() ? 1 : r;
  };
  std::stable_sort(causes.begin(), causes.end(),
                   [&](const Calibration::vpCheckDiagnosis &a, const Calibration::vpCheckDiagnosis &b) {
                     return a.likely != b.likely ? a.likely : rank(a) < rank(b);
                   });
  return causes;
}
} // namespace vpProjectiveSessionInternal
