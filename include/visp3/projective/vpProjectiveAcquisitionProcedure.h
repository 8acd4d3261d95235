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
#include <type_traits>
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
  \brief Drives a vpRobot through the acquisition of Ruf & Horaud (section 6), calibrates the model and tells the
  rig's mounting.

  <b>Checks at the zero reference, before the arm moves.</b> run() reads the joints \f$ q_{ref} \f$
  (ARTICULAR_FRAME, rad or m) and the marker images there (the zero reference, recorded with \f$ q_{ref} \f$, so that
  the model takes absolute encoder readings), then checks, and throws before any motion, that
  - there are at least 5 markers (markers: the points the rig tracks, on the tool eye-to-hand, static in the scene
    eye-in-hand), every one tracked and inside the image margin in both images (the message names the marker);
  - 5 of them have no 4 coplanar. That is what the mathematics needs, and no more: a projective displacement of
    \f$ P^3 \f$ (15 degrees of freedom, 3 equations per point) is unique exactly when the points contain a projective
    basis, 5 points of which no 4 are coplanar; points on a plane and one more, or on two lines, are left fixed by a
    whole family of displacements. More markers may have 4 coplanar (the corners of a cube are fine). Numerically,
    4 markers count as coplanar when the plane that fits their triangulated points best leaves them within
    setCoplanarityThreshold() pixels RMS of plane parallax (a marker's plane parallax: the distance, in one image,
    between its image and that of the point where the other camera's line of sight through it meets the plane): a
    threshold on what the images show, above their noise, not on a metric size the rig does not know. With a known rig
  the check uses the triangulated markers; without one, the zero reference's single image pair cannot give the epipolar
  geometry, so run() then checks that the markers are not all on one plane (a homography maps the left images to the
  right ones within the threshold, RMS), and checks the rest with the rig it estimates, before the calibration.

  <b>Trial motions.</b> Then, for each joint \f$ i \f$ and each sign \f$ s = \pm 1 \f$, it moves joint \f$ i \f$ alone
  to \f$ q_{ref,i} + s\,k\,\delta_i \f$, \f$ k = 1, 2, \ldots \f$ (step \f$ \delta_i \f$, setSteps()), and stops at the
  first of: the amount \f$ a_i \f$ reached (setMaxAmounts()); a marker closer than the margin to the image border
  (setImageMargin(), setImageSize()) or lost; the next step beyond the joint limits minus a margin
  (setJointLimits()). The encoder readings (getPosition()) at the last position with all markers inside is a trial
  motion (addTrialMotion()). The robot goes back to \f$ q_{ref} \f$ after each joint. A joint whose larger amount is
  below its minimum (setMinAmounts()) makes run() throw. A marker that jumps between two steps to where another
  marker was makes run() throw too: the image source changed the markers' order. The model is then calibrated
  (vpProjectiveArmAcquisition::calibrate()); if that fails, the message lists the causes the run saw (small image
  motions, nearly coplanar markers).

  <b>Moving the robot.</b> By default (VELOCITY_CONTROL, setMotionControl()) every move is driven by joint velocities,
  the way ViSP's servo examples drive vpSimulatorViper850, vpSimulatorAfma6 and the real arms:
  vpRobot::setRobotState(STATE_VELOCITY_CONTROL), then vpRobot::setVelocity(ARTICULAR_FRAME, qdot) on the joints
  that must move, at most vpRobot::getMaxRotationVelocity() (revolute) or getMaxTranslationVelocity() (prismatic;
  see setSpeed()), \f$ \dot q = (q^* - q) / \Delta t \f$ near the target with \f$ \Delta t \f$ the time one command
  was seen to last (one step of a simulator in its constant sampling time mode: it lands on the target), until
  getPosition() reads the target within the tolerance, then a zero velocity and a reading that no longer changes.
  The arm stops at each step before the images are taken: images and encoder readings of a moving arm are not taken
  at the same instant (a camera's exposure and latency are tens of milliseconds, a degree at the speeds used), and a
  trial pairs the two. No call blocks without a bound: a move that does not arrive within setMoveTimeout() stops the
  robot and throws vpProjectiveException (robotMotionError) naming the joint, its commanded and its read value.
  POSITION_CONTROL uses vpRobot::setPosition(ARTICULAR_FRAME, q) instead: a blocking call that ViSP gives no timeout
  (in ViSP 3.5, vpSimulatorViper850::setPosition() sets a joint velocity that its own thread overwrites with the
  last setVelocity() command, and progresses only when it wins that race: 1.7 s per 1-degree step in one
  measurement, 45 s in another), for robots whose setPosition() is the better controller; setMotion() gives a function
  of the caller's. After either, getPosition() must read the target within a tenth of the step (the same error
  otherwise), unless the image source reports a marker lost there (a motion tracked frame by frame may stop short where
  tracking fails).

  <b>The rig's mounting.</b> The trials move one joint each, and one joint's motion looks the same whether the rig is
  on the hand or in the workspace: only the order of the product of exponentials (34) differs, which shows when two
  joints move together. After the calibration run() therefore builds the model for both mountings (the same
  generators, the two orders), picks the configuration within the explored joint ranges where their predicted
  images differ most with every marker inside the images, moves two joints there together, and keeps the mounting
  whose prediction matches the images (getMountingReport(): the residuals of both). The acquisition's mounting
  (vpProjectiveArmAcquisition::setRigMounting(), vpProjectiveRobot::setRigMounting()) is replaced by the one found,
  and the output says so. When the two orders predict the same images everywhere in the explored ranges
  (commuting joints, one joint) the mounting does not matter and is kept; when they differ but no check motion
  keeps the markers in view, run() throws: set the mounting and call setMountingDetection(false).

  <b>Identified markers.</b> With a vpIdentifiedImageSource (markers named by ids, such as AprilTag corners), the
  markers are matched by id instead of by their order, and a marker may be missing from a frame (occluded, turned
  away): the zero reference's markers are those the source gives there (the checks above use them; a marker not
  seen there is ignored in every later frame), a step counts as long as it shows at least 5 of them (fewer: the
  joint's motion stops, MARKER_LOST), every marker it shows inside the margins. The calibration uses the
  observations there are (vpProjectiveArmAcquisition's identified markers); a marker seen in fewer than
  setMinMarkerVisibility() of the trial motions is left out of the model (the output says so,
  getDroppedMarkers()), and the markers kept are checked again for general position. The model's marker j is then
  the acquisition's vpProjectiveArmAcquisition::getMarkerIds()[j]. The step callback receives the markers the step
  shows, in ascending id order.

  <b>Joint types.</b> The acquisition's joint types set the units and defaults (degrees or centimetres); an acquisition
  of a joint count alone (vpProjectiveArmAcquisition(unsigned int), vpProjectiveRobot(unsigned int)) has them
  identified by its calibration, and run() then moves every joint by steps of 0.02 (radians or metres: 1.1 deg or 2
  cm) up to 0.35 (20 deg or 35 cm) each way, at most the smaller of the robot's rotation and translation speeds.

  <b>The model check.</b> Before the first motion, run() images the markers twice at rest: the difference of the two
  frames gives the image noise (getImageNoise(); RMS per coordinate divided by sqrt(2)), which the calibration's check
  takes as a lower bound of the noise (vpProjectiveArmAcquisition::setImageNoise()). A model whose residual is far above
  it is refused with its probable causes ranked (vpProjectiveModelCheck): no model is returned then.

  <b>Units.</b> The plugin's joint values are radians and metres. A limit of a revolute joint outside
  \f$ [-2\pi, 2\pi] \f$, or of a prismatic joint beyond 10 m, is refused as probable degrees or millimetres, and so is a
  step or an amount of a revolute joint above \f$ 2\pi \f$ or of any joint above 10 (the setters refuse the values
  above 10 at once, run() the others once it knows the joint types).

  <b>Progress.</b> One line per step of the procedure on std::cout by default (the zero reference's checks, the
  noise at rest, the joint limits as given, each joint and direction, the rig, the calibration, the mounting), each
  flushed as it is written; setOutput() writes them elsewhere, setOutput(nullptr) silences them. The first time a run
  changes a setting of the user's (it replaces the mounting) or degrades the acquisition (it leaves out a marker or a
  trial), one line on std::cerr names it and the fix (vpProjectiveNotices; vpProjectiveNotices::setEnabled(false)
  silences it).

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
  /*!
    Gives identified markers: \e ids[j] names the marker whose images are left[j] and right[j] (distinct ids, in
    any order; vpStereoAprilTagDetector::getIds(), getLeftPoints(), getRightPoints()). Markers may be missing from
    some frames; returns false if the images could not be read at all.
  */
  typedef std::function<bool(std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)>
      vpIdentifiedImageSource;
  //! Called with the joint moved, the joints (rad or m) and the images after each step (live display).
  typedef std::function<void(unsigned int joint, const vpColVector &q, const std::vector<vpImagePoint> &left,
                             const std::vector<vpImagePoint> &right)>
      vpStepCallback;
  /*!
    Moves \e robot to the joints \e q (ARTICULAR_FRAME, rad or m) and returns once it is there (setMotion(): a
    motion of the caller's in place of setMotionControl()'s).
  */
  typedef std::function<void(vpRobot &robot, const vpColVector &q)> vpMotion;

  //! How run() moves the robot (see the class documentation).
  enum vpMotionControl {
    VELOCITY_CONTROL, //!< Joint velocities until getPosition() reads the target (default; bounded by a timeout).
    POSITION_CONTROL  //!< vpRobot::setPosition(ARTICULAR_FRAME, q): blocking, without a timeout.
  };

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

  //! What run() found about the rig's mounting.
  struct vpMountingReport {
    bool checked;                             //!< True if a check motion told the mounting.
    vpProjectiveArmModel::vpRigMounting set;  //!< The mounting the acquisition had when run() started.
    vpProjectiveArmModel::vpRigMounting kept; //!< The mounting of the model run() returned.
    double residual;                          //!< RMS (px) of the kept model's prediction of the check images.
    double otherResidual;                     //!< RMS (px) of the other mounting's prediction of them.
    double separation;                        //!< RMS (px) between the two models' predictions there.
    vpColVector q;                            //!< Joint readings of the check motion (empty if none).
  };

  /*!
    A procedure reading the marker images from \e source, in images of \e width x \e height pixels.
    \exception vpProjectiveException (invalidValueError) if \e source is empty or a size is 0.
  */
  vpProjectiveAcquisitionProcedure(const vpImageSource &source, unsigned int width, unsigned int height);
  /*!
    A procedure reading identified markers from \e source, a vpIdentifiedImageSource or any function callable as one
    (see the class documentation: <b>Identified markers</b>), in images of \e width x \e height pixels.
    \exception vpProjectiveException (invalidValueError) if \e source is empty or a size is 0.
  */
  template <typename Source, typename = typename std::enable_if<
                                 std::is_convertible<Source, vpIdentifiedImageSource>::value &&
                                 !std::is_convertible<Source, vpImageSource>::value &&
                                 !std::is_same<typename std::decay<Source>::type, std::nullptr_t>::value>::type>
  vpProjectiveAcquisitionProcedure(const Source &source, unsigned int width, unsigned int height)
      : vpProjectiveAcquisitionProcedure(vpIdentifiedImageSource(source), width, height, true)
  {
  }

  /*!
    Largest amount per joint and direction (n x 1, rad or m, > 0). Default: 30 deg for a revolute joint, 10 cm
    for a prismatic one.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) on a value <= 0, above 10 (probable
    degrees or millimetres) or not finite.
  */
  void setMaxAmounts(const vpColVector &amounts);
  /*!
    Step per joint (n x 1, rad or m, > 0): the arm stops and the markers are imaged every step. Default: 2 deg for a
    revolute joint, 1 cm for a prismatic one (a run of ViSP's vpSimulatorViper850 at its default speed: about 20 s;
    1 deg: about 30 s).
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) on a value <= 0, above 10 or not finite.
  */
  void setSteps(const vpColVector &steps);
  /*!
    Smallest acceptable amount per joint (n x 1, rad or m, >= 0): run() throws if a joint moves less, both ways.
    Default: 5 deg for a revolute joint, 1 cm for a prismatic one.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) on a negative, above 10 or non-finite
    value.
  */
  void setMinAmounts(const vpColVector &amounts);
  /*!
    Joint limits (n x 1 each, rad or m, \e qmin < \e qmax) and the margin kept from them (>= 0, rad or m). Default:
    the robot's own limits less 2 deg (revolute) or 1 cm (prismatic) when it knows them (vpViper: vpRobotViper650,
    vpRobotViper850, vpSimulatorViper850; vpAfma6: vpRobotAfma6, vpSimulatorAfma6; vpAfma4 before ViSP 3.7, which
    removed it; vpSimulatorRobotArm), otherwise none. run() prints the limits it uses, in the units they were given.
    \exception vpProjectiveException (dimensionError, invalidValueError, nonFiniteValueError) on mismatched sizes,
    qmin >= qmax, a negative margin, non-finite values, or a limit beyond 10 in absolute value (probable degrees or
    millimetres; run() refuses a revolute joint's limit outside [-2 pi, 2 pi] too).
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
    vpRobot::setMaxTranslationVelocity() (m/s); 0 keeps the robot's (ViSP's default: 0.7 rad/s, 0.2 m/s). The
    velocity moves never command more than these.
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setSpeed(double rotation, double translation);
  /*!
    How run() moves the robot (default VELOCITY_CONTROL; see the class documentation). setMotion() overrides both.
    \exception vpProjectiveException (invalidValueError) on another value.
  */
  void setMotionControl(vpMotionControl control);
  //! The motion control of setMotionControl().
  vpMotionControl getMotionControl() const { return m_control; }
  /*!
    Longest time (seconds, >= 0) a velocity move may take before run() stops the robot and throws; 0 (default): 2 s
    plus 4 times the move's duration at the speed (setSpeed()).
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setMoveTimeout(double seconds);
  /*!
    The smallest tolerance (rad or m, > 0; default 1e-5) of a velocity move back to the zero reference: the other
    joints stay there while one joint's trials are imaged, and an offset of \e tolerance moves the markers by about
    \e tolerance times their pixels per joint unit (1e-5 rad: about a hundredth of a pixel at 1,000 px per radian).
    A tolerance below the encoders' noise would make the moves time out, so run() first reads the joints 10 times at
    rest, 5 ms apart (getEncoderNoise()), and uses the larger of \e tolerance and 4 times the largest standard
    deviation it measured (the progress says which). The steps in between only need a reading: they stop within a
    twentieth of the step.
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setArrivalTolerance(double tolerance);
  /*!
    The standard deviation (n x 1, rad or m) of each joint's readings at rest, measured at the start of the last
    run() (see setArrivalTolerance()); empty before.
  */
  const vpColVector &getEncoderNoise() const { return m_encoderNoise; }
  /*!
    A motion of the caller's: empty (default) for setMotionControl()'s; otherwise \e motion moves the robot (and
    run() leaves the robot's state to it). getPosition() must then read the target within a tenth of the step.
  */
  void setMotion(const vpMotion &motion) { m_motion = motion; }
  /*!
    RMS plane parallax (pixels, > 0) below which 4 markers count as coplanar in the checks of the zero reference
    (see the class documentation), and RMS homography transfer error below which all of them do. Default 2 px:
    several times a tracker's noise (4 coplanar markers and 1 px of noise give about 1 px), below what markers that
    span a few centimetres in depth give (the paper's 7 gripper markers, 10 cm across at 1 m: 6.6 px; the corners
    of a 6 cm cube: 9 px).
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setCoplanarityThreshold(double pixels);
  /*!
    Whether run() tells the rig's mounting by a check motion of two joints together (default true; see the class
    documentation). With false the acquisition's mounting is used as set.
  */
  void setMountingDetection(bool detect) { m_detectMounting = detect; }
  /*!
    Epipolar inlier threshold (pixels, > 0) of the rig's estimation when the acquisition given to run() has no rig
    (vpProjectiveStereoRig::estimate()). Default 2 px, for noise up to about 0.5 px per coordinate: raise it in
    proportion to the noise.
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setEpipolarThreshold(double pixels);
  /*!
    With identified markers, the smallest fraction (0 to 1) of the trial motions a zero-reference marker must be seen
    in; a marker seen in fewer is left out of the model, and the progress output says so (getDroppedMarkers()).
    Default 0.5. No effect with a vpImageSource, whose markers are all in every frame.
    \exception vpProjectiveException (invalidValueError) outside [0, 1].
  */
  void setMinMarkerVisibility(double fraction);
  //! The ids of the markers the last run() left out for being seen in too few trials (identified markers).
  const std::vector<int> &getDroppedMarkers() const { return m_dropped; }
  //! Where to write the progress, a line per step of the procedure, flushed (null: nothing). Default &std::cout.
  void setOutput(std::ostream *os) { m_os = os; }
  //! Called after each step with the new images (live display); empty: nothing.
  void setStepCallback(const vpStepCallback &callback) { m_callback = callback; }

  /*!
    Runs the acquisition on \e robot (left at the zero reference: in velocity control at zero velocity by default)
    and calibrates \e acquisition (joint types set by the caller, and its stereo rig if the rig is known; without
    one, the rig is estimated from the images of the run; its zero reference and trials are replaced, its mounting
    set to the one found). Returns the model.
    \exception vpProjectiveException (dimensionError) if a per-joint setting or the acquisition does not have the
    robot's number of joints; (notEnoughPointsError) if there are fewer than 5 markers or the image source fails at
    the zero reference; (degenerateConfigurationError) if a marker is outside the margins at the zero reference, no 5
    markers have 4 non-coplanar ones, the markers change order, a joint cannot move its minimum amount without a
    marker leaving the images or reaching a limit, or the mounting cannot be told; (robotMotionError) if a move does
    not arrive: the message says which and what to change. Without a rig: (estimationFailedError) if the images of
    the run do not determine one (see vpProjectiveStereoRig::estimate()). On any error \e acquisition is unchanged
    and the robot is sent back to the zero reference (unless a move failed).
  */
  vpProjectiveArmModel run(vpRobot &robot, vpProjectiveArmAcquisition &acquisition);
  /*!
    The same for the facade: runs the acquisition on \e robot with the joint types, the rig mounting, the outlier
    threshold and, if it has one, the stereo rig of \e projectiveRobot, which is calibrated on success (as after
    vpProjectiveRobot::calibrate(); its model takes absolute encoder readings; its mounting is the one found) and
    unchanged on failure.
    \exception vpProjectiveException as run(vpRobot &, vpProjectiveArmAcquisition &).
  */
  void run(vpRobot &robot, vpProjectiveRobot &projectiveRobot);

  //! What the last run() did with each joint.
  const std::vector<vpJointReport> &getReports() const { return m_reports; }
  //! What the last run() found about the mounting.
  const vpMountingReport &getMountingReport() const { return m_mountingReport; }
  //! The model residual (RMS pixels) of the last run().
  double getCalibrationResidual() const { return m_residual; }
  //! The image noise (pixels per coordinate) measured at rest by the last run() (0: not measured).
  double getImageNoise() const { return m_restNoise; }
  /*!
    The general-position margin of the last run()'s markers (pixels): over the sets of 5 markers, the largest of the
    smallest RMS plane parallax of 4 of them to the plane that fits them best (see setCoplanarityThreshold()); -1 if
    not measured.
  */
  double getGeneralPositionParallax() const { return m_parallax; }
  //! A word for a stop reason ("amount", "image border", "marker lost", "joint limit").
  static std::string toString(vpStopReason reason);

private:
  vpProjectiveAcquisitionProcedure(const vpIdentifiedImageSource &source, unsigned int width, unsigned int height,
                                   bool identified);
  bool inside(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right) const;
  double amountOf(const vpColVector &v, unsigned int i, double fallback) const;
  //! \e revolute, \e prismatic or \e unknown after joint \e i's type (unknown: an acquisition of a joint count).
  double byType(unsigned int i, double revolute, double prismatic, double unknown) const;
  //! A joint value in its unit: degrees, metres, or as read for a joint of unknown type.
  std::string valueText(double v, unsigned int i) const;
  //! The image noise from a second frame at rest (the first: \e ids, \e left, \e right), 0 if not measured.
  double noiseAtRest(const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                     const std::vector<vpImagePoint> &right);
  //! Refuses joint values (limits, amounts, steps) outside the plugin's units, once the types are known.
  void checkUnits() const;
  double stepOf(unsigned int i) const;
  void moveTo(vpRobot &robot, const vpColVector &q, double tolerance, bool check = true);
  void moveByVelocity(vpRobot &robot, const vpColVector &q, double tolerance);
  void checkArrival(vpRobot &robot, const vpColVector &q, double tolerance, const char *how) const;
  void stopRobot(vpRobot &robot) const;
  void measureEncoderNoise(vpRobot &robot);
  void checkZeroReference(const vpProjectiveArmAcquisition &acquisition, const std::vector<vpImagePoint> &left,
                          const std::vector<vpImagePoint> &right);
  void checkGeneralPosition(const vpProjectiveStereoRig &rig, const std::vector<vpImagePoint> &left,
                            const std::vector<vpImagePoint> &right, const char *when);
  void moveJoint(vpRobot &robot, const vpColVector &qRef, unsigned int i, int sign, double &amount,
                 vpStopReason &reason, vpColVector &qReached, std::vector<int> &ids, std::vector<vpImagePoint> &left,
                 std::vector<vpImagePoint> &right, std::vector<vpImagePoint> &allLeft,
                 std::vector<vpImagePoint> &allRight);
  bool acquire(std::vector<int> &ids, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right) const;
  static unsigned int keepMarkers(const std::vector<int> &keep, std::vector<int> &ids, std::vector<vpImagePoint> &left,
                                  std::vector<vpImagePoint> &right);
  vpProjectiveArmModel tellMounting(vpRobot &robot, const vpColVector &qRef, const vpProjectiveArmModel &model,
                                    const std::vector<vpJointReport> &reports);
  void progress(const std::string &line) const;

  vpImageSource m_source;
  vpIdentifiedImageSource m_idSource;
  bool m_identified; // m_idSource is the source
  double m_minVisibility;
  std::vector<int> m_refIds;   // of the zero reference's markers in the last run(), ascending
  std::vector<int> m_modelIds; // of the model's markers
  std::vector<int> m_dropped;
  unsigned int m_width, m_height;
  vpColVector m_maxAmounts, m_steps, m_minAmounts, m_qmin, m_qmax;
  double m_limitMargin, m_imageMargin, m_rotationSpeed, m_translationSpeed, m_epipolarThreshold;
  vpMotionControl m_control;
  double m_moveTimeout;
  double m_minTolerance; // setArrivalTolerance()
  double m_tolerance;    // the run's: m_minTolerance, or more when the encoders are noisier
  double m_coplanarity;
  bool m_detectMounting;
  std::ostream *m_os;
  vpStepCallback m_callback;
  vpMotion m_motion;
  std::vector<vpJointReport> m_reports;
  vpMountingReport m_mountingReport;
  double m_residual;
  double m_parallax;
  double m_commandPeriod; // seconds of motion one velocity command was seen to make (0: not yet measured)
  double m_wallPeriod;    // wall-clock seconds from a velocity command to a new reading
  std::vector<vpProjectiveJoint::vpJointType> m_types; // of the acquisition being run
  bool m_typesKnown = true;                            // false: an acquisition of a joint count
  double m_restNoise = 0.0;                            // measured at rest by the last run()
  vpColVector m_lower, m_upper;                        // the joint range of the run (empty: no limits)
  vpColVector m_encoderNoise;                          // of the last run (getEncoderNoise())
};

END_VISP_NAMESPACE

#endif
