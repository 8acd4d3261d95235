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
  \file vpServoRigRefinement.h
  \brief The refinement of a re-registered rig with a servo task's own frames.
*/

#ifndef _vpServoRigRefinement_h_
#define _vpServoRigRefinement_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpServoFeatureHealth.h>
#include <visp3/projective/vpServoModelMismatch.h>
#include <visp3/projective/vpServoProjectiveData.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoRigRefinement
  \ingroup group_projective
  \brief A part of vpServoProjective (vpServoProjective::getRigRefinement()): after the
  robot's rig was re-registered (vpProjectiveRobot::updateRig(), from as few as 3 observation poses), the task
  records, at each call that moves the arm, the images of its active features (pixels, 4x1 each) with their points at
  the zero reference (4x1, the model's projective frame) as the model-mismatch check triangulated them through the rig
  before the re-registration (the frame of the task's \f$ s^* \f$ point; for a feature recognised as an acquired
  marker, the mean of that and the marker's point), moved by \f$ H(q) \f$ (34). Every \e period
  such calls it re-registers the rig from the update's observations and all the frames recorded so far
  (vpProjectiveRobot::refineRig()), \e count times, then stops recording (\ref servo_meas_mismatch).

  Outliers and features set aside are never recorded. Nothing is recorded and nothing allocated until start(); the
  recording uses memory reserved there. A refinement that fails leaves the robot as it was and counts as one of the
  \e count.
*/
class VISP_EXPORT vpServoRigRefinement
{
public:
  //! On, every 40 calls, 3 times; not recording.
  vpServoRigRefinement();

  /*!
    The settings (vpServoProjective::getRigRefinement().setRefinement()).
    \param refine : true to refine after a re-registration, false never (a refinement under way stops).
    \param period : calls that move the arm between two refinements (> 0).
    \param count : refinements per re-registration (> 0).
    \exception vpProjectiveException (invalidValueError) if \e period or \e count is 0 or their product above 100000
    (frames to keep); the settings are then unchanged.
  */
  void setRefinement(bool refine, unsigned int period = 40, unsigned int count = 3);
  //! True if a re-registration starts a refinement.
  bool isEnabled() const { return m_enabled; }
  //! Calls that move the arm between two refinements.
  unsigned int getPeriod() const { return m_period; }
  //! Refinements per re-registration.
  unsigned int getCount() const { return m_count; }

  /*!
    Starts recording after a re-registration, if enabled: the zero-reference points of the \e nbFeatures features are
    \e mismatch's means of their triangulations through the rig before the move
    (vpServoModelMismatch::getTriangulatedMemory(): that rig's frame, as the task's re-expressed \f$ s^* \f$), for a
    feature recognised as an acquired marker (vpServoModelMismatch::isMemoryExact()) the unit mean of that and the
    marker's point, taken before it forgets them. Without any memory (the mismatch check off, or no feature ever
    agreed), nothing is recorded.
  */
  void start(const vpServoModelMismatch &mismatch, unsigned int nbFeatures);
  //! Stops recording and forgets the recorded frames and the features' points (another model or set of features).
  void stop();
  /*!
    Records the active features of one call that moved the arm (\e data at its joints, \e health its features'
    states); true when a refinement is due (every getPeriod() calls).
  */
  bool record(const vpServoProjectiveData &data, const vpServoFeatureHealth &health);
  //! Refines \e robot's rig with the frames recorded so far (vpProjectiveRobot::refineRig()); never throws: a
  //! failure leaves the robot as it was and is counted. After getCount() refinements, stops recording.
  void refine(vpProjectiveRobot &robot);

  //! True while recording frames since a re-registration.
  bool isActive() const { return m_active; }
  //! Successful refinements since the last re-registration.
  unsigned int getNumberOfRefinements() const { return m_done; }
  //! Refinements that failed since the last re-registration (the rig was left as it was).
  unsigned int getNumberOfFailures() const { return m_failed; }
  //! Frames' points (a feature seen at a call) recorded since the last re-registration.
  unsigned int getNumberOfPoints() const { return static_cast<unsigned int>(m_X.size()); }

private:
  bool m_enabled;
  unsigned int m_period;
  unsigned int m_count;
  bool m_active;                         // recording since a re-registration
  unsigned int m_calls;                  // calls recorded since then
  unsigned int m_done, m_failed;         // refinements since then
  std::vector<Eigen::Vector4d> m_zero;   // per feature: its point at the zero reference
  std::vector<char> m_hasZero;           // per feature: m_zero is set
  std::vector<Eigen::Vector4d> m_X, m_s; // the frames' points H(q) M(0) and their images, reserved by start()
};

END_VISP_NAMESPACE

#endif
