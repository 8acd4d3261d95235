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
  vpProjectiveAcquisitionProcedure::tellMounting(): which rig mounting (eye-to-hand or eye-in-hand) the images
  say, from a check motion of two joints where the two mountings' models predict different images.
*/

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveNotices.h>

#include "core/vpImageWindow.h"
#include "acquisition/vpProjectiveAcquisitionInternal.h"

using namespace vpProjectiveAcquisitionInternal;

namespace
{
const char *mountingName(vpProjectiveArmModel::vpRigMounting m)
{
  return m == vpProjectiveArmModel::EYE_TO_HAND ? "EYE_TO_HAND" : "EYE_IN_HAND";
}
} // namespace

vpProjectiveArmModel vpProjectiveAcquisitionProcedure::tellMounting(vpRobot &robot, const vpColVector &qRef,
                                                                    const vpProjectiveArmModel &model,
                                                                    const std::vector<vpJointReport> &reports)
{
  vpMountingReport report;
  report.checked = false;
  report.set = report.kept = model.getRigMounting();
  report.residual = report.otherResidual = -1.0;
  report.separation = 0.0;
  const unsigned int n = model.getNumberOfJoints();
  const vpProjectiveArmModel::vpRigMounting otherMounting = model.getRigMounting() == vpProjectiveArmModel::EYE_TO_HAND
                                                                ? vpProjectiveArmModel::EYE_IN_HAND
                                                                : vpProjectiveArmModel::EYE_TO_HAND;
  if (!m_detectMounting || n < 2) {
    m_mountingReport = report;
    progress(std::string("rig mounting: ") + mountingName(report.set) +
             (n < 2 ? " (one joint: the mounting makes no difference)" : " (as set; detection off)"));
    return model;
  }
  // The other mounting's model: the same generators, the product of exponentials (34) in the other order.
  std::vector<Eigen::Vector3d> axis, point;
  for (unsigned int i = 0; i < n; ++i) {
    axis.push_back(model.axis(i));
    point.push_back(model.point(i));
  }
  const vpProjectiveArmModel other(model.jointTypes(), otherMounting, model.getStereoRig(), model.projectiveToMetric(),
                                   axis, point, model.markers(), model.zeroReferenceJoints());
  const size_t K = model.markers().size();
  auto predict = [K](const vpProjectiveArmModel &m, const vpProjectiveArmModel::JointVector &q,
                     std::vector<Eigen::Vector4d> &s) {
    const Eigen::Matrix4d H = m.displacement(q);
    s.resize(K);
    for (size_t j = 0; j < K; ++j) {
      if (!m.predictMarker(static_cast<unsigned int>(j), H, s[j])) {
        return false;
      }
    }
    return true;
  };
  auto insideS = [this](const std::vector<Eigen::Vector4d> &s) {
    for (const Eigen::Vector4d &p : s) {
      if (!vpProjectiveInternal::vpImageWindow(m_width, m_height, m_imageMargin).containsStereo(p)) {
        return false;
      }
    }
    return true;
  };
  std::vector<bool> shown(K, true); // the markers the check images show (identified markers may be missing)
  auto rms = [K, &shown](const std::vector<Eigen::Vector4d> &a, const std::vector<Eigen::Vector4d> &b) {
    double sum = 0.0;
    size_t count = 0;
    for (size_t j = 0; j < K; ++j) {
      if (shown[j]) {
        sum += (a[j] - b[j]).squaredNorm();
        ++count;
      }
    }
    return std::sqrt(sum / (4.0 * static_cast<double>(std::max<size_t>(count, 1))));
  };
  // The check configuration: two joints moved together within the explored ranges, every marker inside the margin
  // in both predictions, where the predictions differ most.
  double bestVisible = 0.0, bestAnywhere = 0.0;
  vpColVector qCheck;
  std::vector<Eigen::Vector4d> sA, sB;
  for (unsigned int i = 0; i < n; ++i) {
    for (unsigned int j = i + 1; j < n; ++j) {
      for (int si = -1; si <= 1; si += 2) {
        for (int sj = -1; sj <= 1; sj += 2) {
          for (double f : {1.0, 0.75, 0.5}) {
            const double ai = f * (si < 0 ? reports[i].amountNegative : reports[i].amountPositive);
            const double aj = f * (sj < 0 ? reports[j].amountNegative : reports[j].amountPositive);
            if (ai <= 0.0 || aj <= 0.0) {
              continue;
            }
            vpColVector q = qRef;
            q[i] += si * ai;
            q[j] += sj * aj;
            vpProjectiveArmModel::JointVector qe(n);
            for (unsigned int k = 0; k < n; ++k) {
              qe(k) = q[k];
            }
            if (!predict(model, qe, sA) || !predict(other, qe, sB)) {
              continue;
            }
            const double d = rms(sA, sB);
            bestAnywhere = std::max(bestAnywhere, d);
            if (d > bestVisible && insideS(sA) && insideS(sB)) {
              bestVisible = d;
              qCheck = q;
            }
          }
        }
      }
    }
  }
  // Two models whose predictions differ by 5 times the noise are told apart by one check at better than 1 in 1000.
  const double needed = std::max(1.0, 5.0 * m_residual);
  std::ostringstream os;
  if (bestVisible < needed) {
    if (bestAnywhere < needed) {
      report.separation = bestAnywhere;
      m_mountingReport = report;
      os << "rig mounting: " << mountingName(report.set) << " as set (both mountings predict the same images within "
         << bestAnywhere << " px in the explored joint ranges: the joints' motions commute there)";
      progress(os.str());
      return model;
    }
    os << at("run") << ": the rig mounting cannot be told from the images: the two mountings predict images up to "
       << bestAnywhere << " px apart in the explored joint ranges, but at most " << bestVisible
       << " px apart where every marker stays in view (needed: " << needed
       << " px). Set the mounting with setRigMounting() (EYE_IN_HAND: the cameras ride on the arm and the markers "
          "are static; EYE_TO_HAND: the rig is fixed and the markers are on the tool) and call "
          "setMountingDetection(false).";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  double smallestStep = std::numeric_limits<double>::infinity();
  for (unsigned int k = 0; k < n; ++k) {
    smallestStep = std::min(smallestStep, stepOf(k));
  }
  moveTo(robot, qCheck, std::max(m_tolerance, 0.05 * smallestStep), false);
  vpColVector reading;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, reading);
  std::vector<int> ids;
  std::vector<vpImagePoint> l, r;
  bool seen = false;
  // A detector can miss a marker in one frame (blur, a reflection): up to 3 frames at the check pose.
  for (int frame = 0; frame < 3 && !seen; ++frame) {
    seen = acquire(ids, l, r);
    if (seen && m_identified) {
      // The model's markers the images show, in the model's order (ascending ids); at least 5.
      std::vector<vpImagePoint> ml(K), mr(K);
      shown.assign(K, false);
      unsigned int count = 0;
      for (size_t k = 0; k < ids.size(); ++k) {
        const std::vector<int>::const_iterator it = std::lower_bound(m_modelIds.begin(), m_modelIds.end(), ids[k]);
        if (it != m_modelIds.end() && *it == ids[k] && static_cast<size_t>(it - m_modelIds.begin()) < K) {
          const size_t j = static_cast<size_t>(it - m_modelIds.begin());
          ml[j] = l[k];
          mr[j] = r[k];
          shown[j] = true;
          ++count;
        }
      }
      l = ml;
      r = mr;
      seen = count >= 5;
    }
    seen = seen && l.size() == K && r.size() == K;
  }
  if (seen && (m_motion || m_control == POSITION_CONTROL)) {
    checkArrival(robot, qCheck, std::max(m_tolerance, 0.05 * smallestStep),
                 m_motion ? "the motion of setMotion()" : "setPosition()");
  }
  moveTo(robot, qRef, m_tolerance);
  if (!seen) {
    os << at("run") << ": the image source lost a marker at the mounting's check motion, where both mountings "
       << "predicted every marker inside the images: the markers changed order, or the rig or the markers moved "
          "during the acquisition; run again.";
    throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
  }
  vpProjectiveArmModel::JointVector qe(n);
  for (unsigned int k = 0; k < n; ++k) {
    qe(k) = reading[k];
  }
  std::vector<Eigen::Vector4d> measured(K);
  for (size_t j = 0; j < K; ++j) {
    measured[j] = Eigen::Vector4d(l[j].get_u(), l[j].get_v(), r[j].get_u(), r[j].get_v());
  }
  const bool okA = predict(model, qe, sA), okB = predict(other, qe, sB);
  const double rA = okA ? rms(sA, measured) : std::numeric_limits<double>::infinity();
  const double rB = okB ? rms(sB, measured) : std::numeric_limits<double>::infinity();
  report.checked = true;
  report.q = reading;
  shown.assign(K, true);
  report.separation = okA && okB ? rms(sA, sB) : bestVisible;
  report.kept = rB < rA ? otherMounting : model.getRigMounting();
  report.residual = std::min(rA, rB);
  report.otherResidual = std::max(rA, rB);
  if (!(report.residual < 0.5 * report.separation)) {
    os << at("run") << ": neither mounting predicts the check motion (two joints moved together): "
       << mountingName(model.getRigMounting()) << " is off by " << rA << " px, " << mountingName(otherMounting)
       << " by " << rB << " px, for predictions " << report.separation
       << " px apart. The markers changed order, the rig or the markers moved during the acquisition, or a joint "
          "moved other than its reading says; run again.";
    throw vpProjectiveException(vpProjectiveException::estimationFailedError, os.str());
  }
  m_mountingReport = report;
  os << "rig mounting: " << mountingName(report.kept) << " (its model predicts a check motion of two joints within "
     << report.residual << " px; " << mountingName(report.kept == report.set ? otherMounting : report.set)
     << " would be off by " << report.otherResidual << " px)";
  if (report.kept != report.set) {
    os << "; the acquisition was set to " << mountingName(report.set) << ": the model uses "
       << mountingName(report.kept) << " (call setRigMounting(" << mountingName(report.kept) << ") to say so)";
    vpProjectiveNotices::tell(NOTICE_MOUNTING_REPLACED,
                              at("run") + ": the rig's mounting was set to " + mountingName(report.set) +
                                  ", but a motion of two joints shows " + mountingName(report.kept) +
                                  ": the model uses " + mountingName(report.kept) + "; call setRigMounting(" +
                                  mountingName(report.kept) + ") to say so");
  }
  progress(os.str());
  return report.kept == model.getRigMounting() ? model : other;
}
