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
  \file vpProjectiveCell.h
  \brief The program of a real cell: acquisition, s* taught by showing, the planned servo and the recording of the
  session, on any arm behind vpProjectiveCellArm and any two cameras behind vpStereoImageSource, the arm stopped on
  every exit path.
*/

#ifndef _vpProjectiveCell_h_
#define _vpProjectiveCell_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <deque>
#include <istream>
#include <memory>
#include <ostream>
#include <string>
#include <utility>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpProjectiveCellArm.h>
#include <visp3/projective/vpProjectiveCellRobot.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSessionCalibration.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>
#include <visp3/projective/vpStereoImageSource.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveCell
  \ingroup group_projective
  \brief Runs a real cell end to end: the acquisition of the arm's model (vpProjectiveAcquisitionProcedure), s*
  taught by showing, the planned servo (vpServoProjective with setPathPlanning()) and the recording of every frame
  used (vpProjectiveSessionWriter), on an arm behind vpProjectiveCellArm and two cameras behind vpStereoImageSource,
  markers from a vpProjectiveSessionCalibration::vpMarkerExtractor (AprilTag corners by default).

  <b>Safety.</b> Every command goes through a vpProjectiveCellRobot built from the settings (vpSettings): the joint
  limits (the user's, else the arm's; an arm that knows none is refused unless vpSettings::noJointLimits says so
  explicitly) less a margin, and speeds below the settings and the arm's own. Each public call stops the arm before
  it returns or throws, whatever happened (an exception of a camera, of the arm or of the computation, a lost tag,
  a status of the task to stop on, SIGINT or SIGTERM after vpProjectiveCellRobot::installSignalHandlers()), and so
  does the destructor; the robot's halt is latched (vpProjectiveCellRobot): once stopped for a fault or a signal,
  the arm is not moved again by this object.

  <b>Time stamps.</b> When the cameras stamp their images (vpStereoImageSource::getTimestamps(), on the clock of
  vpProjectiveCellArm::getJoints()), the acquisition uses only images taken vpSettings::settleTime after the arm
  stopped (without stamps: it drops vpSettings::discardFrames images first), and the servo predicts each image's
  features to the time of the joint readings it uses them with, by the model: a feature seen at \f$ t_l \f$ (left)
  and \f$ t_r \f$ (right) with the joints read at \f$ t \f$ becomes \f$ s + [J_l\,(q(t) - q(t_l));
  J_r\,(q(t) - q(t_r))] \f$, \f$ J \f$ the stereo image Jacobian at \f$ q(t) \f$ and \f$ q(\cdot) \f$ the joint
  readings interpolated (vpSettings::latencyCompensation). The control period of the task follows the time between
  two readings of the loop (vpServoProjective::setControlPeriod()). A frame whose timing is beyond the limits
  (vpSettings::maxSkew, maxLatency, minFrameRate) is not used: its features count as lost, so that cameras that stall
  or lag stop the arm after vpSettings::maxLostTime, with a message that says which limit. \ref page_cell_timing
  gives what skew, latency and frame rate the servo stands, and where these defaults come from.

  \code
  vpStereoGrabberSource cameras("/dev/video0", "/dev/video2");
  MyArm arm;                                   // a vpProjectiveCellArm, or vpProjectiveCellViSPArm of a vpRobot
  vpProjectiveCell::vpSettings settings;       // safe defaults: 15 deg/s, 15 deg trials, 5 deg from the limits
  vpProjectiveCellRobot::installSignalHandlers(); // Ctrl-C stops the arm
  vpProjectiveCell cell(arm, cameras, vpProjectiveSessionCalibration::aprilTagMarkers("36h11"), settings);
  cell.setRecording("session-2026-11-27");     // every frame used, for visp-projective calibrate / check
  cell.acquire();                              // the arm moves: a hand on the emergency stop
  cell.teach(std::cin, std::cout);             // jog the arm to the target, Enter; then to the start, Enter
  vpProjectiveCell::vpServoResult result = cell.servo();
  \endcode
*/
class VISP_EXPORT vpProjectiveCell
{
public:
  //! Every limit, speed and amount of a run, with the defaults of a first session on a real arm.
  struct vpSettings {
    /*! \name Safety */
    //@{
    vpColVector qmin;                     //!< Lower joint limits (n x 1, encoder readings); empty: the arm's own.
    vpColVector qmax;                     //!< Upper joint limits (n x 1); empty: the arm's own.
    bool noJointLimits = false;           //!< True: move an arm whose limits are unknown (only if it has none).
    double limitMarginRotation;           //!< Kept from a revolute joint's limits (rad). Default 5 deg.
    double limitMarginTranslation = 0.02; //!< Kept from a prismatic joint's limits (m).
    double maxRotationSpeed;           //!< Largest speed of a revolute joint, every motion (rad/s). Default 15 deg/s.
    double maxTranslationSpeed = 0.03; //!< Largest speed of a prismatic joint (m/s).
    //@}
    /*! \name Acquisition (vpProjectiveAcquisitionProcedure) */
    //@{
    double amountRotation;           //!< Largest trial of a revolute joint, each way (rad). Default 15 deg.
    double amountTranslation = 0.05; //!< Largest trial of a prismatic joint, each way (m).
    double stepRotation;             //!< Step of a revolute joint's trials (rad). Default 2 deg.
    double stepTranslation = 0.01;   //!< Step of a prismatic joint's trials (m).
    double imageMargin = 20.0;       //!< Margin (px) a marker keeps from the image border during the trials.
    double arrivalTolerance = 1e-5;  //!< Smallest arrival tolerance (rad or m; raised to 4 times the encoders' noise).
    double moveTimeout = 0.0;        //!< Longest move (s); 0: 2 s plus 4 times the move's duration.
    double settleTime = 0.1;         //!< Stamped images: taken at least this long (s) after the arm stopped.
    unsigned int discardFrames = 3;  //!< Images without stamps: dropped after the arm stopped, before one is used.
    //@}
    /*! \name Teaching and servo */
    //@{
    unsigned int targetFrames = 10;    //!< Frames averaged into s*.
    std::vector<int> tags;             //!< Tag ids whose corners the servo uses (corner id / 4); empty: all seen at s*.
    double gain = 0.5;                 //!< Gain \f$ \lambda \f$ of the task (1/s).
    double imageBorder = 10.0;         //!< Features this close to the border (px) are set aside; the plan keeps off.
    bool planning = true;              //!< Path planning (vpServoProjective::setPathPlanning()).
    bool latencyCompensation = true;   //!< Features predicted to the joint readings' time (stamped images).
    double period = 0.04;              //!< Control period (s) until the loop has measured its own.
    double timeout = 60.0;             //!< Longest servo (s, the arm's clock).
    double convergedError = 0.5;       //!< Image error (px RMS) under which the task has converged...
    unsigned int convergedFrames = 10; //!< ... for this many frames in a row.
    double maxLostTime = 0.5;  //!< Longest time (s) with too few features seen (SERVO_OPEN_LOOP, SERVO_STOPPED).
    double maxSkew = 0.04;     //!< Stamped images: a frame whose two images are further apart (s) is not used.
    double maxLatency = 0.2;   //!< Stamped images: a frame older than this (s) at the readings is not used.
    double minFrameRate = 4.0; //!< A frame that comes later than 1 / minFrameRate (s) after the last is not used.
    //@}
    //! The defaults (those of the members in degrees are set here, in radians).
    vpSettings();
    /*! A copy made by assignment: ViSP 3.5's vpArray2D copy constructor passes a null pointer to memcpy for an
        empty vector (qmin and qmax by default), which UBSan reports; its assignment does not. */
    vpSettings(const vpSettings &other);
    //! Every member of \e other copied (the vectors by assignment, which ViSP 3.5 does safely when empty).
    vpSettings &operator=(const vpSettings &other) = default;
  };

  //! How a servo ended (the arm stopped in every case).
  enum vpServoEnd {
    SERVO_CONVERGED, //!< The image error stayed under vpSettings::convergedError.
    SERVO_TIMEOUT,   //!< vpSettings::timeout passed.
    SERVO_TAGS_LOST, //!< Too few features for longer than vpSettings::maxLostTime.
    SERVO_STATUS     //!< The task stopped: SERVO_MODEL_MISMATCH, SERVO_NO_PLAN or SERVO_ARM_NOT_FOLLOWING (the
                     //!< message says which and why).
  };
  //! What servo() did.
  struct vpServoResult {
    vpServoEnd end;      //!< How it ended.
    std::string message; //!< One line: why, and what to do.
    double error;        //!< Image error at the end (px RMS over the features seen).
    double seconds;      //!< Duration (the arm's clock).
    unsigned int frames; //!< Frames used.
    vpColVector q;       //!< Joint readings at the end.
  };

  /*!
    A cell of \e arm and \e cameras (both outlive it), markers from \e markers, run with \e settings. Nothing moves.
    \exception vpProjectiveException (invalidValueError) if the arm knows no joint limits and the settings give none
    nor vpSettings::noJointLimits; (dimensionError, invalidValueError, nonFiniteValueError) on settings of the wrong
    size or value (the message names the setting).
  */
  vpProjectiveCell(vpProjectiveCellArm &arm, vpStereoImageSource &cameras,
                   const vpProjectiveSessionCalibration::vpMarkerExtractor &markers, const vpSettings &settings);
  //! Stops the arm and closes the recording.
  ~vpProjectiveCell();

  //! Where the progress goes, one flushed line per step (null: nowhere). Default: null.
  void setOutput(std::ostream *os) { m_os = os; }
  /*!
    Records every frame used from now on in the new session \e folder (vpProjectiveSessionWriter: acquisition frames,
    TARGET, SERVO), closed by servo() and the destructor, with which camera is left when the cameras tell
    (vpStereoImageSource::getCameraIdentities()).
    \exception vpProjectiveException (fileError) as vpProjectiveSessionWriter().
  */
  void setRecording(const std::string &folder);

  /*!
    The acquisition: the arm, at rest where the markers are seen, is its zero reference; each joint moves alone
    within the settings, and the model is calibrated. The arm is stopped at the end.
    \exception vpProjectiveException as vpProjectiveAcquisitionProcedure::run(), (robotMotionError) if the robot was
    halted (a signal, a limit, an error of the arm), or any exception of the cameras or the arm.
  */
  void acquire();
  /*!
    The model of a previous acquisition (vpProjectiveRobot::loadModel()) in place of acquire().
    \exception vpProjectiveException (dimensionError) if the model's joints are not as many as the arm's;
    (invalidValueError) if the fingerprint of the model's cell (vpProjectiveCellFingerprint) is not this cell's, the
    likeliest first: the model's file recorded its cameras and the cameras' identities
    (vpStereoImageSource::getCameraIdentities()) are not them (exchanged, named first, or others:
    vpProjectiveCellFingerprint::cameraMismatch()), a joint of the arm is of another kind than the model's
    (vpProjectiveCellFingerprint::jointTypesMismatch()), the cameras' images are not of the model's size. The cell is
    left as it was.
  */
  void loadModel(const std::string &file);
  /*!
    Writes the model with its markers' ids and the fingerprint of the cell (the image size, the cameras' identities
    when the source gives them, the side of the right camera: vpProjectiveCellFingerprint) (vpProjectiveModelFile::
    save()): vpProjectiveRobot::loadModel() reads it, loadModel() compares the cameras, and
    `visp-projective check MODEL SESSION` checks it against a recorded session.
  */
  void saveModel(const std::string &file) const;
  //! The model (calibrated after acquire() or loadModel()).
  const vpProjectiveRobot &getModel() const { return m_model; }

  /*!
    s* taught by showing. Asks on \e prompt to bring the arm to the target pose and confirm, reads \e commands one
    line at a time: an empty line or "ok" confirms; "move Q0 ... Qn-1" moves the arm to those joint readings (rad,
    m) and "jog J DELTA" moves joint J by DELTA, both by velocity within the settings; the arm may also be jogged with
    its own pendant or moved by hand meanwhile. At the confirmation, the arm must be at rest: vpSettings::targetFrames
    frames are averaged into s*, each corner seen in all of them. Then the same for the start pose of the servo.
    \exception vpProjectiveException (notEnoughPointsError) if fewer than 3 corners are seen at the target,
    (invalidValueError) on a line it does not understand... it then asks again; (robotMotionError) on "quit", the
    end of \e commands or a signal.
  */
  void teach(std::istream &commands, std::ostream &prompt);
  //! s* taught from the arm where it is (no question asked): what teach() does at its first confirmation.
  void teachHere();
  //! The corner ids of s* and their pixels.
  const std::vector<int> &getTargetIds() const { return m_targetIds; }

  /*!
    Moves the arm by velocity to the joint readings \e q (n x 1) within the settings, and stops it there.
    \exception vpProjectiveException (robotMotionError) if it does not arrive within the move timeout, or is halted.
  */
  void moveTo(const vpColVector &q);

  /*!
    The planned servo to s*, until it converges, times out, loses its tags or stops on a status; the arm is stopped
    in every case, and the recording closed.
    \exception vpProjectiveException (notInitializedError) without a model or s*; any exception of the cameras or the
    arm, or (robotMotionError) on a signal, after the arm stopped.
  */
  vpServoResult servo();
  //! A line for \e end ("converged", "timeout", "tags lost", "status").
  static std::string toString(vpServoEnd end);

  //! The safety layer every command goes through (its halt, its last command, its stops).
  vpProjectiveCellRobot &getRobot() { return *m_robot; }

private:
  struct vpFrame {
    std::vector<int> ids;
    std::vector<vpImagePoint> left, right;
    double tLeft, tRight; // when the images were taken (the arm's clock); those of the readings without stamps
    bool stamped;
  };
  void grab(bool atRest, vpFrame &frame);
  void record(int role, const vpColVector &q, double t);
  void progress(const std::string &line) const;
  vpColVector jointsAt(double t) const;
  void remember(double t, const vpColVector &q);
  void ask(std::istream &commands, std::ostream &prompt, const std::string &question);

  vpProjectiveCellArm &m_arm;
  vpStereoImageSource &m_cameras;
  vpProjectiveSessionCalibration::vpMarkerExtractor m_markers;
  vpSettings m_settings;
  std::vector<vpProjectiveJoint::vpJointType> m_types;
  vpColVector m_lower, m_upper; // the safe range (empty: none)
  std::unique_ptr<vpProjectiveCellRobot> m_robot;
  vpProjectiveRobot m_model;
  std::vector<int> m_markerIds; // of the model's markers (corner ids)
  std::vector<int> m_targetIds;
  std::vector<vpImagePoint> m_targetLeft, m_targetRight;
  std::unique_ptr<vpProjectiveSessionWriter> m_writer;
  std::string m_recording;
  std::ostream *m_os;
  vpImage<unsigned char> m_Ileft, m_Iright;
  std::deque<std::pair<double, vpColVector>> m_history; // joint readings of the last seconds, with their times
};

END_VISP_NAMESPACE

#endif
