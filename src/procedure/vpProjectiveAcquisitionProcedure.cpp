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
  vpProjectiveAcquisitionProcedure::run(), which moves each joint both ways, estimates the rig if needed and
  calibrates the arm model. The settings are in vpProjectiveAcquisitionSettings.cpp; the motions, the checks and the
  mounting's detection in vpProjectiveAcquisitionMotion.cpp, vpProjectiveAcquisitionChecks.cpp and
  vpProjectiveAcquisitionMounting.cpp.
*/

#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveNotices.h>
#include <visp3/projective/vpSimulatorRobotArm.h>

#include "core/vpImageWindow.h"
#include "acquisition/vpProjectiveAcquisitionInternal.h"
#include "procedure/vpRobotJointLimits.h"

using namespace vpProjectiveAcquisitionInternal;

bool vpProjectiveAcquisitionProcedure::acquire(std::vector<int> &ids, std::vector<vpImagePoint> &left,
                                               std::vector<vpImagePoint> &right) const
{
  if (!m_identified) {
    const bool ok = m_source(left, right);
    ids.resize(left.size());
    for (size_t j = 0; j < ids.size(); ++j) {
      ids[j] = static_cast<int>(j);
    }
    return ok;
  }
  std::vector<int> rawIds;
  std::vector<vpImagePoint> l, r;
  if (!m_idSource(rawIds, l, r)) {
    return false;
  }
  if (rawIds.size() != l.size() || l.size() != r.size()) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                at("run") + ": the image source gave " + std::to_string(rawIds.size()) + " ids, " +
                                    std::to_string(l.size()) + " left and " + std::to_string(r.size()) +
                                    " right images: give one id and both images of every marker.");
  }
  std::vector<size_t> order(rawIds.size());
  for (size_t j = 0; j < order.size(); ++j) {
    order[j] = j;
  }
  std::sort(order.begin(), order.end(), [&rawIds](size_t a, size_t b) { return rawIds[a] < rawIds[b]; });
  ids.resize(order.size());
  left.resize(order.size());
  right.resize(order.size());
  for (size_t k = 0; k < order.size(); ++k) {
    ids[k] = rawIds[order[k]];
    left[k] = l[order[k]];
    right[k] = r[order[k]];
    if (k > 0 && ids[k] == ids[k - 1]) {
      throw vpProjectiveException(vpProjectiveException::invalidValueError,
                                  at("run") + ": the image source gave marker id " + std::to_string(ids[k]) +
                                      " twice in one frame: each marker needs its own id.");
    }
  }
  return true;
}

unsigned int vpProjectiveAcquisitionProcedure::keepMarkers(const std::vector<int> &keep, std::vector<int> &ids,
                                                           std::vector<vpImagePoint> &left,
                                                           std::vector<vpImagePoint> &right)
{
  size_t m = 0;
  for (size_t k = 0; k < ids.size(); ++k) {
    if (std::binary_search(keep.begin(), keep.end(), ids[k])) {
      ids[m] = ids[k];
      left[m] = left[k];
      right[m] = right[k];
      ++m;
    }
  }
  ids.resize(m);
  left.resize(m);
  right.resize(m);
  return static_cast<unsigned int>(m);
}

bool vpProjectiveAcquisitionProcedure::inside(const std::vector<vpImagePoint> &left,
                                              const std::vector<vpImagePoint> &right) const
{
  for (const std::vector<vpImagePoint> *image : {&left, &right}) {
    for (const vpImagePoint &p : *image) {
      if (!vpProjectiveInternal::vpImageWindow(m_width, m_height, m_imageMargin).contains(p)) {
        return false;
      }
    }
  }
  return true;
}

double vpProjectiveAcquisitionProcedure::amountOf(const vpColVector &v, unsigned int i, double fallback) const
{
  return v.size() == 0 ? fallback : v[i];
}

double vpProjectiveAcquisitionProcedure::stepOf(unsigned int i) const
{
  return amountOf(m_steps, i, byType(i, vpMath::rad(2.0), 0.01, 0.02));
}

void vpProjectiveAcquisitionProcedure::progress(const std::string &line) const
{
  if (m_os) {
    *m_os << line << std::endl; // flushed: a run whose output goes to a file shows where it is
  }
}

vpProjectiveArmModel vpProjectiveAcquisitionProcedure::run(vpRobot &robot, vpProjectiveArmAcquisition &acquisition)
{
  const double tStart = seconds();
  const double previousResidual = m_residual;
  m_types = acquisition.getJointTypes();
  m_typesKnown = acquisition.hasDeclaredJointTypes();
  m_parallax = -1.0;
  m_restNoise = 0.0;
  vpColVector qRef;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, qRef);
  const unsigned int n = qRef.size();
  for (const vpColVector *v : {&m_maxAmounts, &m_steps, &m_minAmounts, &m_qmin}) {
    if (v->size() != 0 && v->size() != n) {
      throw vpProjectiveException(vpProjectiveException::dimensionError,
                                  at("run") + ": a per-joint setting has " + std::to_string(v->size()) +
                                      " values, the robot has " + std::to_string(n) + " joints: give one per joint.");
    }
  }
  if (acquisition.getNumberOfJoints() != n) {
    throw vpProjectiveException(vpProjectiveException::dimensionError,
                                at("run") + ": the acquisition has " + std::to_string(acquisition.getNumberOfJoints()) +
                                    " joints, the robot " + std::to_string(n) + ": give the robot's joint types.");
  }
  checkUnits();
  // The joint range the trials stay in: the limits given, else those of ViSP's arms that know theirs (Viper650/850,
  // Afma4/6, real or simulated, and vpSimulatorRobotArm) less 2 deg or 1 cm, else none.
  m_lower = vpColVector();
  m_upper = vpColVector();
  std::string limitsFrom = "none";
  if (m_qmin.size() != 0) {
    m_lower = m_qmin + vpColVector(n, m_limitMargin);
    m_upper = m_qmax - vpColVector(n, m_limitMargin);
    limitsFrom = "setJointLimits()";
  } else {
    vpColVector qmin, qmax;
    if (vpProjectiveInternal::robotJointLimits(robot, qmin, qmax) && qmin.size() == n && qmax.size() == n) {
      m_lower = qmin;
      m_upper = qmax;
      for (unsigned int k = 0; k < n; ++k) {
        const double margin = byType(k, vpMath::rad(2.0), 0.01, 0.01);
        m_lower[k] += margin;
        m_upper[k] -= margin;
      }
      limitsFrom = "the robot's own, less " + std::string(m_typesKnown ? "2 deg or 1 cm" : "0.01 (rad or m)");
    }
  }
  measureEncoderNoise(robot);
  if (m_lower.size() != 0) { // the limits used, in the units they were given (radians, metres)
    std::ostringstream os;
    os << ", with the margin:";
    for (unsigned int k = 0; k < n; ++k) {
      os << " joint " << k << " [" << m_lower[k] << ", " << m_upper[k] << "]"
         << (!m_typesKnown                               ? " (rad or m)"
             : m_types[k] == vpProjectiveJoint::REVOLUTE ? " rad"
                                                         : " m")
         << (k + 1 < n ? "," : "");
    }
    limitsFrom += os.str();
  }
  std::vector<int> ids;
  std::vector<vpImagePoint> left, right;
  m_dropped.clear();
  if (!acquire(ids, left, right)) {
    throw vpProjectiveException(vpProjectiveException::notEnoughPointsError,
                                at("run") + ": the image source lost a marker at the zero reference: place the arm so "
                                            "that every marker is tracked in both images, then run again. Nothing "
                                            "moved.");
  }
  checkZeroReference(acquisition, left, right); // before the arm moves
  m_restNoise = noiseAtRest(ids, left, right);
  m_refIds = ids;
  m_modelIds = ids;
  progress("joint limits: " + limitsFrom);
  if (!m_motion) {
    robot.setRobotState(m_control == VELOCITY_CONTROL ? vpRobot::STATE_VELOCITY_CONTROL
                                                      : vpRobot::STATE_POSITION_CONTROL);
  }
  if (m_rotationSpeed > 0.0) {
    robot.setMaxRotationVelocity(m_rotationSpeed);
  }
  if (m_translationSpeed > 0.0) {
    robot.setMaxTranslationVelocity(m_translationSpeed);
  }
  // With a known rig the zero reference is checked before the arm moves; without one, once the rig is estimated.
  const bool rigKnown = acquisition.getStereoRig().isInitialized();
  vpProjectiveArmAcquisition work = acquisition;
  work.setImageNoise(std::max(acquisition.getImageNoise(), m_restNoise));
  if (rigKnown) {
    work.setZeroReference(qRef, left, right);
  }
  struct Trial {
    vpColVector q;
    std::vector<int> ids;
    std::vector<vpImagePoint> left, right;
  };
  std::vector<Trial> trials;
  std::vector<vpImagePoint> allLeft = left, allRight = right; // every pair seen inside the margins, for the rig
  std::vector<vpJointReport> reports(n);
  try {
    for (unsigned int i = 0; i < n; ++i) {
      vpJointReport &report = reports[i];
      report.trials = 0;
      for (int sign = -1; sign <= 1; sign += 2) {
        double amount = 0.0;
        vpStopReason reason = AMOUNT_REACHED;
        Trial trial;
        trial.ids = ids;
        trial.left = left;
        trial.right = right;
        moveJoint(robot, qRef, i, sign, amount, reason, trial.q, trial.ids, trial.left, trial.right, allLeft, allRight);
        (sign < 0 ? report.amountNegative : report.amountPositive) = amount;
        (sign < 0 ? report.stopNegative : report.stopPositive) = reason;
        if (amount > 0.0) {
          trials.push_back(trial); // the encoders' readings, as the model will take them
          ++report.trials;
        }
        if (sign > 0) {
          moveTo(robot, qRef, m_tolerance); // from the negative side, the positive steps pass through it anyway
        }
        std::ostringstream os;
        os << "joint " << i << (sign < 0 ? " -" : " +") << ": " << valueText(amount, i) << " (" << toString(reason)
           << ")" << (sign > 0 ? ", back at the zero reference" : "") << "; " << std::fixed << std::setprecision(1)
           << seconds() - tStart << " s";
        progress(os.str());
      }
      const double minAmount = amountOf(m_minAmounts, i, byType(i, vpMath::rad(5.0), 0.01, 0.01));
      if (std::max(report.amountNegative, report.amountPositive) < minAmount) {
        std::ostringstream os;
        os << at("run") << ": joint " << i << " moved only -" << valueText(report.amountNegative, i) << " ("
           << toString(report.stopNegative) << ") and +" << valueText(report.amountPositive, i) << " ("
           << toString(report.stopPositive) << "), less than the minimum " << valueText(minAmount, i)
           << ": too small a motion to observe; move the arm so that the markers are nearer the image centre and "
           << "the joint away from its limits, or lower the image margin or the minimum amount.";
        if (m_identified && (report.stopNegative == MARKER_LOST || report.stopPositive == MARKER_LOST)) {
          os << " With identified markers a step is lost when it shows fewer than 5 of the zero reference's markers "
                "(too few common markers): put markers where the cameras see them whatever the joint's motion.";
        }
        throw vpProjectiveException(vpProjectiveException::degenerateConfigurationError, os.str());
      }
    }
    if (m_identified) {
      // Markers seen in too few trials are left out of the model (and of the trials' images).
      std::vector<unsigned int> seenIn(m_refIds.size(), 0);
      for (const Trial &trial : trials) {
        for (int id : trial.ids) {
          ++seenIn[static_cast<size_t>(std::lower_bound(m_refIds.begin(), m_refIds.end(), id) - m_refIds.begin())];
        }
      }
      std::vector<int> kept;
      for (size_t j = 0; j < m_refIds.size(); ++j) {
        if (static_cast<double>(seenIn[j]) >= m_minVisibility * static_cast<double>(trials.size())) {
          kept.push_back(m_refIds[j]);
        } else {
          m_dropped.push_back(m_refIds[j]);
          std::ostringstream os;
          os << "marker " << m_refIds[j] << " left out: seen in " << seenIn[j] << " of " << trials.size()
             << " trial motions (setMinMarkerVisibility(): " << m_minVisibility << ")";
          progress(os.str());
          vpProjectiveNotices::tell(vpProjectiveAcquisitionInternal::NOTICE_MARKER_DROPPED,
                                    at("run") + ": " + os.str() +
                                        " (getDroppedMarkers()); keep every marker in view of both cameras during "
                                        "the trials, or lower setMinMarkerVisibility()");
        }
      }
      if (kept.size() < 5) {
        std::ostringstream os;
        os << at("run") << ": only " << kept.size() << " of the zero reference's " << m_refIds.size()
           << " markers are seen in at least " << m_minVisibility * 100.0
           << " % of the trial motions (too few common markers; the model needs 5, of which no 4 coplanar): put "
              "markers where the cameras see them whatever the joint's motion, or lower setMinMarkerVisibility().";
        throw vpProjectiveException(vpProjectiveException::notEnoughPointsError, os.str());
      }
      if (!m_dropped.empty()) {
        keepMarkers(kept, ids, left, right);
        std::vector<Trial> usable;
        for (Trial &trial : trials) {
          if (keepMarkers(kept, trial.ids, trial.left, trial.right) >= 5) {
            usable.push_back(trial);
          } else {
            progress("a trial motion left out: it shows fewer than 5 of the markers kept");
            vpProjectiveNotices::tell(vpProjectiveAcquisitionInternal::NOTICE_TRIAL_DROPPED,
                                      at("run") + ": a trial motion was left out: it shows fewer than 5 of the "
                                                  "markers kept; keep more markers in view during the trials");
          }
        }
        trials = usable;
        if (rigKnown) {
          checkGeneralPosition(acquisition.getStereoRig(), left, right, "zero reference, the markers kept");
        }
      }
      m_modelIds = kept;
      if (rigKnown) {
        work.setZeroReference(qRef, ids, left, right);
      }
    }
    if (!rigKnown) {
      vpProjectiveStereoRig rig;
      rig.estimate(allLeft, allRight, m_epipolarThreshold);
      work.setStereoRig(rig);
      if (m_identified) {
        work.setZeroReference(qRef, ids, left, right);
      } else {
        work.setZeroReference(qRef, left, right);
      }
      std::ostringstream os;
      os << "rig estimated from " << allLeft.size() << " matches, epipolar residual " << rig.getEstimationResidual()
         << " px";
      progress(os.str());
      checkGeneralPosition(rig, left, right, "zero reference, estimated rig");
    }
    for (const Trial &trial : trials) {
      if (m_identified) {
        work.addTrialMotion(trial.q, trial.ids, trial.left, trial.right);
      } else {
        work.addTrialMotion(trial.q, trial.left, trial.right);
      }
    }
    vpProjectiveArmModel model;
    try {
      model = work.calibrate();
    } catch (const vpProjectiveException &e) {
      if (e.getCode() == vpProjectiveException::modelRejectedError) {
        throw; // its message ranks the causes
      }
      // Say what the run saw that makes a calibration fail: small image motions, markers nearly coplanar.
      std::ostringstream os;
      os << e.getStringMessage() << ". What the procedure saw:";
      double smallest = std::numeric_limits<double>::infinity();
      unsigned int which = 0;
      for (size_t k = 0; k < trials.size(); ++k) {
        double sum = 0.0;
        size_t common = 0;
        for (size_t j = 0, m = 0; j < left.size(); ++j) {
          while (m < trials[k].ids.size() && trials[k].ids[m] < ids[j]) {
            ++m; // ids ascending in both (0, 1, ... without identified markers)
          }
          if (m < trials[k].ids.size() && trials[k].ids[m] == ids[j]) {
            sum += vpImagePoint::sqrDistance(left[j], trials[k].left[m]) +
                   vpImagePoint::sqrDistance(right[j], trials[k].right[m]);
            ++common;
          }
        }
        const double motion = std::sqrt(sum / (2.0 * static_cast<double>(std::max<size_t>(common, 1))));
        if (motion < smallest) {
          smallest = motion;
          which = static_cast<unsigned int>(k);
        }
      }
      if (!trials.empty()) {
        unsigned int joint = 0;
        vpColVector d = trials[which].q - qRef;
        for (unsigned int k = 1; k < n; ++k) {
          joint = std::abs(d[k]) > std::abs(d[joint]) ? k : joint;
        }
        os << " the smallest trial (joint " << joint << ") moved the markers by " << smallest << " px RMS"
           << (smallest < 20.0 ? ": too small a motion, raise setMaxAmounts() or start where the markers can move "
                                 "further"
                               : "");
      }
      os << "; markers' general-position margin " << m_parallax << " px of plane parallax"
         << (m_parallax >= 0.0 && m_parallax < 5.0 * m_coplanarity
                 ? ": nearly coplanar markers, add markers off their plane"
                 : "")
         << "; a marker order change would have stopped the run at the step where it happened.";
      throw vpProjectiveException(e.getCode(), os.str());
    }
    {
      std::ostringstream os;
      os << "calibrated: " << trials.size() << " trials, residual " << work.getCalibrationResidual()
         << " px RMS (limit " << work.getModelCheck().getLimit() << " px)";
      if (!m_typesKnown) {
        os << "; joint types identified from the images:";
        for (unsigned int i = 0; i < n; ++i) {
          os << " " << vpProjectiveJoint::name(work.getJointTypes()[i]);
        }
      }
      progress(os.str());
    }
    m_residual = work.getCalibrationResidual();
    m_types = work.getJointTypes(); // identified, for an acquisition of a joint count
    m_typesKnown = true;
    model = tellMounting(robot, qRef, model, reports);
    work.setRigMounting(model.getRigMounting());
    stopRobot(robot);
    acquisition = work;
    m_reports = reports;
    std::ostringstream os;
    os << "acquisition done in " << std::fixed << std::setprecision(1) << seconds() - tStart << " s";
    progress(os.str());
    return model;
  } catch (const vpProjectiveException &e) {
    m_residual = previousResidual;
    if (e.getCode() != vpProjectiveException::robotMotionError) {
      try {
        moveTo(robot, qRef, m_tolerance);
      } catch (...) {
      }
    }
    try {
      stopRobot(robot);
    } catch (...) {
    }
    throw;
  } catch (...) {
    m_residual = previousResidual;
    try {
      moveTo(robot, qRef, m_tolerance);
      stopRobot(robot);
    } catch (...) {
    }
    throw;
  }
}

void vpProjectiveAcquisitionProcedure::run(vpRobot &robot, vpProjectiveRobot &projectiveRobot)
{
  vpProjectiveArmAcquisition acquisition = projectiveRobot.getAcquisition();
  const vpProjectiveStereoRig &rig = projectiveRobot.getStereoRig(); // once calibrated, the model's (updateRig())
  if (rig.isInitialized()) {
    acquisition.setStereoRig(rig);
  }
  const vpProjectiveArmModel model = run(robot, acquisition);
  projectiveRobot.setCalibration(acquisition, model, m_residual);
}
