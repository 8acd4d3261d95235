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
  \file study-projective.h
  \brief The projective servo in the study: its acquisition and its controller (plain, or with vpServoProjective's
  robustness API).
*/

#ifndef _study_study_projective_h_
#define _study_study_projective_h_

#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpImagePoint.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoProjective.h>

#include "study-control.h"
#include "study-world.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Acquisition]
//! The main job's acquisition (app::acquireByTrials(), any joint kinds): q = 0, then each joint alone both
//! ways by the world's trials (halved until in view); F from the same images with the inlier threshold
//! max(1, 4 sigma); calibrate(). Throws a vpException on failure.
vpProjectiveRobot acquire(const World &world, double sigma, vpGaussRand &noise);
//! [Acquisition]

//! RMS pixel error of the acquired model's prediction of the tracked markers at q (a diagnostic of failures).
double modelPredictionError(const World &world, const vpProjectiveRobot &robot, const vpColVector &q);

//! [Projective servo]
/*!
  The projective servo as in the main job (vpServoProjective, gain 0.5, 15 deg, damping (30, 30)).
  - Plain: when the tracker loses a point the task is rebuilt on the tracked ones (their rows only), as the
    baselines do, and nothing else.
  - Robust: the robustness API of vpServoProjective: the tracker's verdict through setFeatureTracked(), the image
    window (setImageSize()), outlier rejection against the epipolar geometry and the model's prediction
    (setOutlierThreshold()), and joint-limit avoidance (setJointLimits()).
  - Planned (setPlanned()): global servoing as in the main job: setPathPlanning(true) with the world's joint
    limits (setJointLimits()) and image window (setImageSize() with a border); the first computeControlLaw() plans
    the task from the model (inverse kinematics of s*, a path in the limits and in view), the task follows it and law
    (47) finishes. getNoPlan() and getPlannedTarget() tell what the planner did.
*/
class ProjectiveServo : public Controller
{
public:
  ProjectiveServo(const vpProjectiveRobot &robot, const std::vector<vpImagePoint> &leftTarget,
                  const std::vector<vpImagePoint> &rightTarget, const ControlSettings &settings)
      : m_task(), m_s(leftTarget.size()), m_sStar(leftTarget.size()), m_tracked(leftTarget.size(), true),
        m_robust(false), m_rejected(leftTarget.size(), false)
  {
    m_task.setRobot(robot);
    m_task.setLambda(settings.lambda);
    m_task.getControlLaw().setMaxJointVelocity(settings.qdotMax);
    m_task.getControlLaw().setDamping(settings.sigmaThreshold, settings.maxDamping);
    for (size_t k = 0; k < m_s.size(); ++k) {
      m_sStar[k].buildFrom(leftTarget[k], rightTarget[k]);
      m_task.addFeature(m_s[k], m_sStar[k]);
    }
  }
  ProjectiveServo(const ProjectiveServo &) = delete;
  ProjectiveServo &operator=(const ProjectiveServo &) = delete;

  //! Turns the robustness API on.
  void setRobust(unsigned int width, unsigned int height, double outlierThreshold, const vpColVector &qmin,
                 const vpColVector &qmax)
  {
    m_robust = true;
    m_task.setImageSize(width, height);
    m_task.getFeatureHealth().setOutlierThreshold(outlierThreshold);
    m_task.setJointLimits(qmin, qmax);
  }

  //! Turns path planning on (global servoing), inside the joint limits and the image window with \e border px, the
  //! path sampled every \e step rad at most; \e rehearsal, if not negative, is the planner's law rehearsal budget
  //! (0: always a path).
  void setPlanned(unsigned int width, unsigned int height, double border, double step, const vpColVector &qmin,
                  const vpColVector &qmax, int rehearsal = -1)
  {
    m_task.getPathPlanner().setMaxJointStep(step);
    if (rehearsal >= 0) {
      m_task.getPathPlanner().setRehearsalBudget(static_cast<unsigned int>(rehearsal));
    }
    m_task.setJointLimits(qmin, qmax);
    m_task.setImageSize(width, height, border);
    m_task.setPathPlanning(true);
    m_planned = true;
  }
  //! Planned servo: the first computeControlLaw() found no plan.
  bool getNoPlan() const { return m_noPlan; }
  //! Planned servo: the joint values the planner chose for the target (empty if none).
  const vpColVector &getPlannedTarget() const { return m_plannedTarget; }

  vpColVector velocity(const vpColVector &q, const std::vector<vpImagePoint> &left,
                       const std::vector<vpImagePoint> &right, const std::vector<bool> &tracked) override
  {
    if (m_robust) {
      for (unsigned int k = 0; k < m_s.size(); ++k) {
        m_task.setFeatureTracked(k, tracked[k]);
      }
    } else if (tracked != m_tracked) {
      m_task.clearFeatures();
      for (size_t k = 0; k < m_s.size(); ++k) {
        if (tracked[k]) {
          m_task.addFeature(m_s[k], m_sStar[k]);
        }
      }
      m_tracked = tracked;
    }
    for (size_t k = 0; k < m_s.size(); ++k) {
      if (tracked[k]) {
        m_s[k].buildFrom(left[k], right[k]);
      }
    }
    const vpColVector qdot = m_task.computeControlLaw(q);
    m_mismatch += m_task.getStatus() == vpServoProjective::SERVO_MODEL_MISMATCH; // a false alarm: no camera moves
    if (m_planned && m_first) {
      m_first = false;
      m_noPlan = m_task.getStatus() == vpServoProjective::SERVO_NO_PLAN;
      if (!m_noPlan) {
        m_plannedTarget = m_task.getPlannedTarget();
      }
    }
    if (m_robust) {
      for (unsigned int k = 0; k < m_s.size(); ++k) {
        m_rejected[k] = m_task.getReport().getFeatureState(k) == vpServoProjective::FEATURE_OUTLIER;
      }
      m_stopped += m_task.getStatus() == vpServoProjective::SERVO_STOPPED;
    }
    return qdot;
  }
  void rejected(std::vector<bool> &flags) const override { flags = m_rejected; }
  unsigned int getStoppedIterations() const { return m_stopped; }
  //! Iterations that reported SERVO_MODEL_MISMATCH.
  unsigned int getMismatchIterations() const { return m_mismatch; }

private:
  vpServoProjective m_task;
  std::vector<vpFeatureStereoPoint> m_s, m_sStar; // sized once: the task keeps references
  std::vector<bool> m_tracked;
  bool m_robust;
  std::vector<bool> m_rejected;
  unsigned int m_stopped = 0, m_mismatch = 0;
  bool m_planned = false, m_first = true, m_noPlan = false;
  vpColVector m_plannedTarget;
};
//! [Projective servo]
} // namespace study

#endif
