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
  \file vpProjectiveModelCheck.h
  \brief What an acquisition's calibration checked: the model's residual against the image noise, the joint types
  the trials show, and, for a refused model, its probable causes ranked by a diagnostic each.
*/

#ifndef _vpProjectiveModelCheck_h_
#define _vpProjectiveModelCheck_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <visp3/projective/vpProjectiveJoint.h>

BEGIN_VISP_NAMESPACE

class vpProjectiveArmAcquisition;

/*!
  \class vpProjectiveModelCheck
  \ingroup group_projective
  \brief The model-quality gate of vpProjectiveArmAcquisition::calibrate() and its findings (\ref page_model_check).

  <b>The gate.</b> A model is accepted when its RMS residual per pixel coordinate over every acquisition image
  (getResidual()), and that of each joint's own trials (vpJointTypeFit::residual), stay within the limit
  \f[ T = \max(k\,\sigma, 0.5\ \mathrm{px}) \f]
  where \f$ k \f$ is vpProjectiveArmAcquisition::setResidualTolerance() (default 3) and \f$ \sigma \f$ the image
  noise (getNoise(): pixels per coordinate), the larger of
  - the noise measured on the acquisition's own images (getEpipolarNoise()): every marker's left and right images
    must meet the rig's epipolar geometry, and the gap (the reprojection error of its optimal triangulation, one
    degree of freedom per pair: \f$ \sigma^2 \chi^2_1 \f$ under Gaussian noise) is measured on the zero reference and
    every trial; \f$ \sigma^2 \f$ is the mean of the smallest 90 % of those squared gaps divided by 0.6233 (the mean
    of \f$ \chi^2_1 \f$ below its 90th percentile), a mean that a few mismatched pairs do not move;
  - the noise given by vpProjectiveArmAcquisition::setImageNoise(), e.g. measured on frames at rest (what
    vpProjectiveAcquisitionProcedure does).
  A model that fits its images at the noise level has a residual of about \f$ 0.85\,\sigma \f$ to \f$ \sigma \f$ (the
  fitted parameters take the rest); the 0.5 px floor keeps noise-free images and a tracker whose frames repeat the
  same pixels from refusing a model that fits within half a pixel.

  <b>Joint types.</b> Each joint's trials show whether it turns or slides: the rotation angle of their projective
  displacements (vpJointTypeFit::turn, the argument of the displacement's complex eigenvalues: a p-rotation by
  \f$ \theta \f$ has eigenvalues \f$ 1, 1, e^{\pm i\theta} \f$, a p-translation only 1) is the reading of a revolute
  joint and zero for a prismatic one, and the model fits the trials better with the right type. The check refits the
  model with a joint's type changed (a bundle adjustment started from the same motion of the markers' centroid) and
  compares the squared errors \f$ S \f$ of all the observations: vpJointTypeFit::evidence \f$ = (S_{other} - S_{model})
  / \sigma^2 \f$. A joint is refitted when its type is in doubt: its turn does not match its reading as a revolute
  joint, its trials' residual exceeds 1.25 times the noise or the other joints' residual, or the model is refused;
  joints whose trials clearly turn (by their reading and over 0.2 rad, or
  by over 0.3 rad whatever the reading) are not. A declared type is contradicted when the other type lowers
  \f$ S \f$ by more than \f$ 16 \sigma^2 \f$ and at least 10 %: the model is then refused and the joint named. With
  unknown types (vpProjectiveArmAcquisition(unsigned int)), each joint takes the type with the lower \f$ S \f$.

  <b>Causes.</b> A refused model comes with every cause the check can test, ranked likeliest first (getCauses()), each
  with its diagnostic: the residual of the model with the cause fixed when the images allow the fix to be tried
  (joint types changed, revolute readings taken as degrees, a trial predicted with a second joint's motion, two
  markers exchanged), or a ratio that shows it (the epipolar gap of a marker's two images, the epipolar noise against
  the noise at rest). getMessage() says it in one line, with what to do.

  <b>Left and right exchanged.</b> Before any fit, the epipolar noise is measured again with every observation's left
  and right images exchanged: below half of it as given, the images were given right first against the rig's
  \f$ F \f$, and the model is refused with CAUSE_IMAGES_EXCHANGED alone (a model of the exchanged cameras would fit
  them). In the rig's order the gaps are the noise alone and exchanging can only add to them; a rig whose \f$ F \f$ is
  nearly skew-symmetric (nearly parallel cameras) cannot tell the order (vpServoModelMismatch tells it in the servo).
*/
class VISP_EXPORT vpProjectiveModelCheck
{
public:
  //! The probable causes of a refused model.
  enum vpCause {
    CAUSE_JOINT_TYPE,      //!< A joint of the other type than declared (a prismatic joint declared revolute, ...).
    CAUSE_SECOND_JOINT,    //!< A second joint moved during a trial (or it was not the joint the trial names).
    CAUSE_READING_UNITS,   //!< Joint readings in other units (a revolute joint's in degrees).
    CAUSE_MARKERS_SWAPPED, //!< Markers swapped between the left and right images of a frame, or between frames.
    CAUSE_MOUNTING,        //!< The rig's mounting (trials of one joint look the same in both: only a motion of
                           //!< several joints tells, as vpProjectiveAcquisitionProcedure makes).
    CAUSE_IMAGE_ERRORS,    //!< Errors the model has no part for: lens distortion, a tracker's bias, a rig that moved.
    CAUSE_IMAGES_EXCHANGED //!< Left and right images exchanged against the rig's F (the acquisition's images meet it
                           //!< only so): refused before any fit, the only cause then.
  };

  //! One probable cause of a refused model and its diagnostic.
  struct vpDiagnosis {
    vpCause cause;          //!< The cause.
    bool likely;            //!< The diagnostic points at it (the fix brings the residual within the limit, or the
                            //!< ratio shows it).
    double residualIfFixed; //!< RMS residual (px) of the model with the fix tried; NaN if the images do not allow it.
    double evidence;        //!< The diagnostic's value (see finding): a ratio, pixels, or \f$ \Delta S / \sigma^2 \f$.
    int joint;              //!< The joint it names (-1: none).
    int trial;              //!< The trial it names, in the order of addTrialMotion() (-1: none; -2: the zero ref.).
    int marker;             //!< The marker it names (-1: none).
    int other;              //!< The second joint or marker it names (-1: none).
    std::string finding;    //!< What the images show, with the diagnostic's value.
    std::string fix;        //!< What to do.
  };

  //! What the check found about one joint.
  struct vpJointTypeFit {
    vpProjectiveJoint::vpJointType type; //!< The model's type: declared, or identified from the trials.
    bool declared;                       //!< The type was given to the acquisition (false: identified).
    bool contradicted;                   //!< Declared, and the trials fit the other type decisively better.
    double turn;                         //!< Mean rotation angle (rad) of the displacements of the joint's trials.
    double reading;                      //!< Mean absolute reading change of its trials (rad, or length unit).
    double residual;                     //!< RMS residual (px) of the joint's own trials under the model.
    double residualRevolute;  //!< RMS residual (px) of its trials with the joint revolute, the others as in the model
                              //!< (NaN: not fitted).
    double residualPrismatic; //!< The same with the joint prismatic.
    double evidence; //!< \f$ (S_{other} - S_{model}) / \sigma^2 \f$: > 0 when the model's type fits better (NaN: the
                     //!< other type was not fitted).
  };

  //! Nothing checked yet.
  vpProjectiveModelCheck();

  //! True once a calibrate() reached a model (accepted or refused).
  bool isChecked() const { return m_checked; }
  //! True if the model passed the gate.
  bool isAccepted() const { return m_accepted; }
  //! RMS residual (px per coordinate) of the model over every acquisition image.
  double getResidual() const { return m_residual; }
  //! The image noise (px per coordinate) the gate used: the larger of getEpipolarNoise() and getGivenNoise().
  double getNoise() const { return m_noise; }
  //! The noise measured on the acquisition's images against the rig's epipolar geometry (px per coordinate).
  double getEpipolarNoise() const { return m_epipolarNoise; }
  //! The noise given by vpProjectiveArmAcquisition::setImageNoise() (0: none).
  double getGivenNoise() const { return m_givenNoise; }
  //! The limit (px) on the model's residual and on each joint's: max(tolerance x noise, 0.5 px); infinite when the
  //! gate is off.
  double getLimit() const { return m_limit; }
  //! What the check found about each joint, base to tip.
  const std::vector<vpJointTypeFit> &getJoints() const { return m_joints; }
  //! The probable causes of a refused model, likeliest first (empty for an accepted model).
  const std::vector<vpDiagnosis> &getCauses() const { return m_causes; }
  //! One line: the verdict, the numbers, and for a refused model its causes ranked with their diagnostics and fixes.
  const std::string &getMessage() const { return m_message; }
  //! A short name of a cause ("joint types", "a second joint moved", ...).
  static std::string toString(vpCause cause);

private:
  friend class vpProjectiveArmAcquisition;
  bool m_checked;
  bool m_accepted;
  double m_residual;
  double m_noise;
  double m_epipolarNoise;
  double m_givenNoise;
  double m_limit;
  std::vector<vpJointTypeFit> m_joints;
  std::vector<vpDiagnosis> m_causes;
  std::string m_message;
};

END_VISP_NAMESPACE

#endif
