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
  \file vpProjectiveAcquisitionProcedure.h
  \brief Automatic acquisition of an arm's projective model on a ViSP robot (vpRobot): trial motions of each joint
  alone, bounded by the image border and the joint limits, then calibration.
*/

#ifndef _vpProjectiveAcquisitionProcedure_h_
#define _vpProjectiveAcquisitionProcedure_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/robot/vpRobot.h>

#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveRobot.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveAcquisitionProcedure
  \ingroup group_projective
  \brief Drives a vpRobot through the acquisition of Ruf & Horaud (section 6) and calibrates the model.

  run() reads the joints \f$ q_{ref} \f$ (ARTICULAR_FRAME, rad or m) and the marker images there (the zero
  reference, recorded with \f$ q_{ref} \f$, so that the model takes absolute encoder readings). Then, for each joint
  \f$ i \f$ and each sign \f$ s = \pm 1 \f$, it moves joint \f$ i \f$ alone (setPosition() in ARTICULAR_FRAME) to
  \f$ q_{ref,i} + s\,k\,\delta_i \f$, \f$ k = 1, 2, \ldots \f$ (step \f$ \delta_i \f$, setSteps()), and stops at the
  first of: the amount \f$ a_i \f$ reached (setMaxAmounts()); a marker closer than the margin to the image border
  (setImageMargin(), setImageSize()) or lost; the next step beyond the joint limits minus a margin
  (setJointLimits()). The encoder readings (getPosition()) at the last position with all markers inside is a trial
  motion (addTrialMotion()). The robot goes back to \f$ q_{ref} \f$ after each joint. A joint whose larger amount is
  below its minimum (setMinAmounts()) makes run() throw. The model is then calibrated
  (vpProjectiveArmAcquisition::calibrate()).

  Given an acquisition without a stereo rig, run() weakly calibrates the rig itself: the fundamental matrix from
  every stereo pair it saw with all markers inside the margins (the zero reference and every step: 7 markers and 100
  steps give 700 matches), by vpProjectiveStereoRig::estimate() with the threshold of setEpipolarThreshold(). The
  model then comes from pixels and encoder readings only, and the estimated rig is in the acquisition afterwards
  (vpProjectiveArmAcquisition::getStereoRig()) and in the model.
*/
class VISP_EXPORT vpProjectiveAcquisitionProcedure
{
public:
  /*!
    Gives the images (pixels) of the markers, left and right, always in the same order; returns false if a marker is
    not tracked.
  */
  typedef std::function<bool(std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)> vpImageSource;
  //! Called with the joint moved, the joints (rad or m) and the images after each step (live display).
  typedef std::function<void(unsigned int joint, const vpColVector &q, const std::vector<vpImagePoint> &left,
                             const std::vector<vpImagePoint> &right)>
      vpStepCallback;
  /*!
    Moves \e robot to the joints \e q (ARTICULAR_FRAME, rad or m) and returns once it is there; for a robot whose
    setPosition() cannot be used (ViSP 3.5's vpSimulatorViper850 does not finish its moves: drive it by velocity).
  */
  typedef std::function<void(vpRobot &robot, const vpColVector &q)> vpMotion;

  //! Why the motion of a joint in one direction stopped.
  enum vpStopReason {
    AMOUNT_REACHED, //!< The amount of setMaxAmounts() was reached.
    IMAGE_BORDER,   //!< One more step would bring a marker within the image margin.
    MARKER_LOST,    //!< One more step and the image source lost a marker.
    JOINT_LIMIT     //!< One more step would pass the joint limit minus its margin.
  };

  //! What run() did with one joint.
  struct vpJointReport {
    double amountNegative;     //!< Amount reached towards negative values (>= 0; rad or m).
    double amountPositive;     //!< Amount reached towards positive values (>= 0; rad or m).
    vpStopReason stopNegative; //!< Why the negative motion stopped.
    vpStopReason stopPositive; //!< Why the positive motion stopped.
    unsigned int trials;       //!< Trial motions recorded for this joint.
  };

  /*!
    A procedure reading the marker images from \e source, in images of \e width x \e height pixels.
    \exception vpProjectiveException (invalidValueError) if \e source is empty or a size is 0.
  */
  vpProjectiveAcquisitionProcedure(const vpImageSource &source, unsigned int width, unsigned int height);

  /*!
    Largest amount per joint and direction (n x 1, rad or m, > 0). Default: 30 deg for every joint.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) on a value <= 0 or not finite.
  */
  void setMaxAmounts(const vpColVector &amounts);
  /*!
    Step per joint (n x 1, rad or m, > 0). Default: 1 deg for every joint.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) on a value <= 0 or not finite.
  */
  void setSteps(const vpColVector &steps);
  /*!
    Smallest acceptable amount per joint (n x 1, rad or m, >= 0): run() throws if a joint moves less, both ways.
    Default: 5 deg for every joint.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) on a negative or non-finite value.
  */
  void setMinAmounts(const vpColVector &amounts);
  /*!
    Joint limits (n x 1 each, rad or m, \e qmin < \e qmax) and the margin kept from them (>= 0, rad or m). Default:
    no limits.
    \exception vpProjectiveException (dimensionError, invalidValueError, nonFiniteValueError) on mismatched sizes,
    qmin >= qmax, a negative margin or non-finite values.
  */
  void setJointLimits(const vpColVector &qmin, const vpColVector &qmax, double margin);
  /*!
    Margin (pixels, >= 0) kept from the image border. Default: 10 px.
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setImageMargin(double pixels);
  /*!
    Image size (pixels).
    \exception vpProjectiveException (invalidValueError) if a size is 0.
  */
  void setImageSize(unsigned int width, unsigned int height);
  /*!
    Speed given to the robot before the motions: vpRobot::setMaxRotationVelocity() (rad/s) and
    vpRobot::setMaxTranslationVelocity() (m/s); 0 keeps the robot's. Default 0.
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setSpeed(double rotation, double translation);
  /*!
    How to move the robot; empty (default): vpRobot::setRobotState(STATE_POSITION_CONTROL) at the start of run(),
    then vpRobot::setPosition(ARTICULAR_FRAME, q). With a motion, run() leaves the robot's state to it.
  */
  void setMotion(const vpMotion &motion) { m_motion = motion; }
  /*!
    Epipolar inlier threshold (pixels, > 0) of the rig's estimation when the acquisition given to run() has no rig
    (vpProjectiveStereoRig::estimate()). Default 2 px, for noise up to about 0.5 px per coordinate: raise it in
    proportion to the noise.
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setEpipolarThreshold(double pixels);
  //! Where to write a line per joint (null: nothing). Default null.
  void setOutput(std::ostream *os) { m_os = os; }
  //! Called after each step with the new images (live display); empty: nothing.
  void setStepCallback(const vpStepCallback &callback) { m_callback = callback; }

  /*!
    Runs the acquisition on \e robot (put in POSITION_CONTROL, left at the zero reference) and calibrates
    \e acquisition (joint types set by the caller, and its stereo rig if the rig is known; without one, the rig is
    estimated from the images of the run; its zero reference and trials are replaced). Returns the model.
    \exception vpProjectiveException (dimensionError) if a per-joint setting or the acquisition does not have the
    robot's number of joints; (notEnoughPointsError) if the image source fails at the zero reference;
    (degenerateConfigurationError) if a joint cannot move its minimum amount without a marker leaving the images
    or reaching a limit: the message says which and what to change. On any error \e acquisition is unchanged and the
    robot is sent back to the zero reference. Without a rig: (estimationFailedError) if the images of the run do not
    determine one (see vpProjectiveStereoRig::estimate()).
  */
  vpProjectiveArmModel run(vpRobot &robot, vpProjectiveArmAcquisition &acquisition);
  /*!
    The same for the facade: runs the acquisition on \e robot with the joint types, the rig mounting, the outlier
    threshold and, if it has one, the stereo rig of \e projectiveRobot, which is calibrated on success (as after
    vpProjectiveRobot::calibrate(); its model takes absolute encoder readings) and unchanged on failure.
    \exception vpProjectiveException as run(vpRobot &, vpProjectiveArmAcquisition &).
  */
  void run(vpRobot &robot, vpProjectiveRobot &projectiveRobot);

  //! What the last run() did with each joint.
  const std::vector<vpJointReport> &getReports() const { return m_reports; }
  //! The model residual (RMS pixels) of the last run().
  double getCalibrationResidual() const { return m_residual; }
  //! A word for a stop reason ("amount", "image border", "marker lost", "joint limit").
  static std::string toString(vpStopReason reason);

private:
  bool inside(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right) const;
  double amountOf(const vpColVector &v, unsigned int i, double fallback) const;
  void moveTo(vpRobot &robot, const vpColVector &q) const;
  void moveJoint(vpRobot &robot, const vpColVector &qRef, unsigned int i, int sign, double &amount,
                 vpStopReason &reason, vpColVector &qReached, std::vector<vpImagePoint> &left,
                 std::vector<vpImagePoint> &right, std::vector<vpImagePoint> &allLeft,
                 std::vector<vpImagePoint> &allRight);

  vpImageSource m_source;
  unsigned int m_width, m_height;
  vpColVector m_maxAmounts, m_steps, m_minAmounts, m_qmin, m_qmax;
  double m_limitMargin, m_imageMargin, m_rotationSpeed, m_translationSpeed, m_epipolarThreshold;
  std::ostream *m_os;
  vpStepCallback m_callback;
  vpMotion m_motion;
  std::vector<vpJointReport> m_reports;
  double m_residual;
};

END_VISP_NAMESPACE

#endif
