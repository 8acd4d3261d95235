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
  \file vpProjectiveRigUpdate.h
  \brief What a vpProjectiveRobot keeps of the re-registrations of its rig: observations, mode, residual, counters.
*/

#ifndef _vpProjectiveRigUpdate_h_
#define _vpProjectiveRigUpdate_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveRigRegistration.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveRigUpdate
  \ingroup group_projective
  \brief The rig-registration state of a vpProjectiveRobot (vpProjectiveRobot::getRigUpdate()): the observations
  recorded by vpProjectiveRobot::addRigObservation() since the last vpProjectiveRobot::updateRig() (joints
  \f$ q_k \f$, n x 1, and the images \f$ (u, v, u', v') \f$ of every zero-reference marker, pixels), the registration
  mode (vpProjectiveRigRegistration), the RMS error of the last update, and the counters that the servo tasks on the
  robot read. A new model (calibrate(), loadModel(), setCalibration()) starts it anew but for its mode.
*/
class VISP_EXPORT vpProjectiveRigUpdate
{
public:
  /*! \name Settings and observations */
  //@{
  //! Which cameras vpProjectiveRobot::updateRig() estimates (default vpProjectiveRigRegistration::FIXED_INTRINSICS).
  void setRegistrationMode(vpProjectiveRigRegistration::vpRegistrationMode mode) { m_mode = mode; }
  //! The mode of setRegistrationMode().
  vpProjectiveRigRegistration::vpRegistrationMode getRegistrationMode() const { return m_mode; }
  //! Number of observations recorded since the last vpProjectiveRobot::updateRig().
  unsigned int getNumberOfObservations() const { return static_cast<unsigned int>(m_joints.size()); }
  //! Forgets the observations recorded since the last vpProjectiveRobot::updateRig().
  void clearObservations();
  //@}

  /*! \name What the updates did */
  //@{
  /*!
    True after a successful vpProjectiveRobot::updateRig() since the model was computed or loaded:
    vpProjectiveRobot::refineRig() has something to refine.
  */
  bool hasRegistration() const { return m_registration.valid; }
  //! RMS reprojection error per coordinate (pixels) of the last successful updateRig() or refineRig().
  double getResidual() const { return m_residual; }
  /*!
    Counts the successful updateRig() and refineRig() calls since the model was computed or loaded (the tasks on the
    robot are told of each, see vpServoProjective).
  */
  unsigned long getGeneration() const { return m_generation; }
  /*!
    Counts the successful updateRig() calls since the model was computed or loaded, without the refineRig() calls
    (which getGeneration() counts too): a task tells a re-registration from a refinement by it.
  */
  unsigned long getUpdateCount() const { return m_updates; }
  /*!
    Counts the models computed or loaded (calibrate(), loadModel(), setCalibration()): the projective frame changes
    with each, and a task's points of another model are meaningless.
  */
  unsigned long getModelGeneration() const { return m_modelGeneration; }
  //@}

private:
  friend class vpProjectiveRobot; // records the observations and the updates

  typedef vpProjectiveArmModel::JointVector JointVector;

  //! A new model: no observation, no registration, the rig's counters at 0, one more model; the mode and the last
  //! residual stay.
  void restart();

  std::vector<JointVector> m_joints;                  // observations since the last updateRig()
  std::vector<std::vector<Eigen::Vector4d>> m_images; // their marker images (u, v, u', v')
  //! The last successful updateRig(): the rig before it and its observations, which refineRig() starts from.
  struct vpRegistration {
    vpProjectiveStereoRig rigBefore;
    std::vector<JointVector> joints;
    std::vector<std::vector<Eigen::Vector4d>> images;
    bool valid = false;
  };
  vpRegistration m_registration;
  vpProjectiveRigRegistration::vpRegistrationMode m_mode = vpProjectiveRigRegistration::FIXED_INTRINSICS;
  double m_residual = 0.0;
  unsigned long m_generation = 0;
  unsigned long m_updates = 0;
  unsigned long m_modelGeneration = 0;
};

END_VISP_NAMESPACE

#endif
