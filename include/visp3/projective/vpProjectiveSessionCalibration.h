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
  \file vpProjectiveSessionCalibration.h
  \brief Calibrating an arm from a recorded session, and checking a model against another session.
*/

#ifndef _vpProjectiveSessionCalibration_h_
#define _vpProjectiveSessionCalibration_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <functional>
#include <ostream>
#include <string>
#include <vector>

#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpProjectiveAcquisitionProcedure.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveCellFingerprint.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>
#include <visp3/projective/vpStereoImageSource.h>
#include <visp3/robot/vpRobot.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveSessionCalibration
  \ingroup group_projective
  \brief What the command-line tool's \c calibrate and \c check do (visp-projective): the markers extracted from every
  frame of a session, the rig estimated, the arm acquired and bundle-adjusted into a model; and a model's prediction
  error on every frame of another session, which tells whether a camera moved since the model was made.

  The markers come from a marker extraction function (vpMarkerExtractor): given a stereo pair, it gives the markers
  found in both images, each with an identifier (e.g. 4 * AprilTag id + corner index), in ascending identifier order,
  and their pixels (ViSP's convention: the centre of pixel (i, j) is (u, v) = (j, i)). The AprilTag detector of the
  plugin is such a function; tests give one of their own.

  <b>calibrate()</b> reads the zero, trial and observation frames (and, for the metric self-calibration, the target
  and servo frames), then
  - extracts the markers of each, one progress line per frame; a frame without any marker is an error;
  - keeps the markers of the zero frame (at least 5), in identifier order; a trial frame may miss some of them
    (occluded, turned away), matched by identifier (vpProjectiveArmAcquisition's identified markers), as long as it
    shows 5;
  - refuses markers that are all on one plane (a homography maps their left images onto the right ones within the
    coplanarity threshold, RMS), since a rigid motion needs 5 markers of which no 4 are coplanar;
  - estimates the rig's fundamental matrix from every marker match of those frames
    (vpProjectiveStereoRig::estimate(), setEpipolarThreshold()), then checks that 5 markers have no 4 within the
    coplanarity threshold of a plane (plane parallax, as vpProjectiveAcquisitionProcedure does);
  - acquires the arm (vpProjectiveArmAcquisition: the zero frame's readings as the zero reference, each trial with
    its readings: the model takes absolute encoder readings), algebraic generators, metric upgrade and bundle
    adjustment;
  - tells the rig's mounting from the observation frames when there are some (the model of each mounting predicts
    them; the better one is kept), else keeps setMounting()'s (eye-to-hand by default);
  - tells which camera is left (vpProjectiveCellFingerprint::cameraSide(): the metric self-calibration's baseline in
    the left camera's frame) and refuses a session whose right camera sits to the left of its left one, i.e. whose
    left and right images are exchanged, unless the cameras' layout is LAYOUT_ANY (setCameraLayout(), or the
    session's \c camera_layout);
  - adds the observation, target and servo frames as calibration frames (vpProjectiveArmAcquisition::
    addCalibrationFrame(); a frame that shows none of the model's markers is left out, with a progress line) and
    says what the metric self-calibration over all of them determines (vpProjectiveSelfCalibration: the noise, the
    largest uncertainty);
  - summarises each joint: its trials, their range and the model's RMS prediction error on them.
  saveModel() then writes the model with the markers' identifiers, the self-calibration's frames and the fingerprint
  of the cell (getFingerprint(): the image size, the cameras the session recorded, their layout and side)
  (vpProjectiveModelFile), to a temporary file that is renamed: the model file is complete or absent.

  <b>check()</b> predicts, for each frame of a session, the markers of the model seen in it at the frame's encoder
  readings, and compares with the extracted ones: RMS per coordinate in the left image, in the right image, and both.
  A frame fits when both are within setMismatchThreshold(). When some do not, the probable causes are ranked, each
  by a diagnostic (getDiagnosis(), likeliest first; \ref page_sessions_checks):
  - the left and right images exchanged: the model's prediction with the session's images exchanged, the matches'
    distance to the model's epipolar lines with \f$ F \f$ and with \f$ F^T \f$, the cameras' identities;
  - a camera moved (left, right, or both): the error in each image (a camera moved alone leaves the other image
    fitting), and the residual of the rig re-registered on the session (vpProjectiveRigRegistration);
  - the markers moved on the tool: the residual of the markers refitted on the session (the matches meet the model's
    epipolar geometry: the rig did not change);
  - readings that are not the model's encoders (another arm, joints in another order, other units or zero): the
    residual of a free projective displacement per frame, which fits when the markers are the model's but their
    motion is not the one the readings say;
  - a session of another cell: what its fingerprint says against the model's (image size, cameras, marker
    identifiers), or no fix fitting.
  A cause is likely when its fix brings the residual within the threshold or a fact shows it; the likely ones come
  first, those that change least first (exchanged images, one camera, the markers, both cameras, the readings), then
  the others.

  Every error is a vpProjectiveException with a one-line message naming the frame and what to do.
*/
class VISP_EXPORT vpProjectiveSessionCalibration
{
public:
  /*!
    Extracts the markers of a stereo pair: fills \e ids (ascending, distinct), \e left and \e right (the same size,
    pixels) with the markers found in both images and returns their number.
  */
  typedef std::function<unsigned int(const vpImage<unsigned char> &Ileft, const vpImage<unsigned char> &Iright,
                                     std::vector<int> &ids, std::vector<vpImagePoint> &left,
                                     std::vector<vpImagePoint> &right)>
      vpMarkerExtractor;

  //! The rig's mounting for calibrate().
  enum vpMountingChoice {
    MOUNTING_AUTO,        //!< From the observation frames if any, else eye-to-hand (default).
    MOUNTING_EYE_TO_HAND, //!< The rig is fixed, the markers on the tool.
    MOUNTING_EYE_IN_HAND  //!< The rig rides on the hand, the markers are static.
  };

  //! What calibrate() found about one joint.
  struct vpJointSummary {
    vpProjectiveJoint::vpJointType type; //!< Revolute or prismatic.
    unsigned int trials;                 //!< Trial frames of the joint.
    double smallest;                     //!< Smallest signed trial amount (rad or m).
    double largest;                      //!< Largest signed trial amount (rad or m).
    double residual;                     //!< RMS prediction error (px per coordinate) of the model on its trials.
  };

  //! What check() found about one frame.
  struct vpFrameCheck {
    unsigned int frame;                    //!< Index in the session.
    vpProjectiveSession::vpFrameRole role; //!< The frame's role.
    unsigned int markers;                  //!< Markers of the model seen in the frame.
    double left;                           //!< RMS per coordinate of the left image (px).
    double right;                          //!< RMS per coordinate of the right image (px).
    double rms;                            //!< RMS per coordinate of both (px).
    bool fits;                             //!< True if left and right are within the mismatch threshold.
  };

  //! What check() concludes: every frame fits, or the likeliest cause of those that do not.
  enum vpRigState {
    RIG_UNCHANGED,      //!< Every frame fits.
    LEFT_CAMERA_MOVED,  //!< The left images are off, the right ones fit.
    RIGHT_CAMERA_MOVED, //!< The right images are off, the left ones fit.
    BOTH_CAMERAS_MOVED, //!< Both are off and a re-registered rig fits them: both cameras moved (or another rig).
    CAMERAS_SWAPPED,    //!< The session's left images are the model's right camera's and the other way round.
    MARKERS_MOVED,      //!< The rig is the model's, the markers moved on the tool (or in the scene, eye-in-hand).
    OTHER_READINGS,     //!< The readings are not the model's encoders (another arm, joint order, units or zero).
    OTHER_CELL          //!< A session of another cell: its fingerprint differs, or no fix fits.
  };

  //! A probable cause of frames that do not fit (check()), with its diagnostic.
  struct vpCheckDiagnosis {
    vpRigState cause;       //!< The cause (never RIG_UNCHANGED).
    bool likely;            //!< The diagnostic points at it (its fix fits within the threshold, or a fact shows it).
    double residualIfFixed; //!< RMS per coordinate (px) with the cause fixed; NaN where no fix is tried.
    std::string finding;    //!< What the session shows, with the diagnostic's value.
    std::string fix;        //!< What to do.
  };

  /*!
    A calibration whose markers come from \e extractor; empty: aprilTagMarkers("36h11").
  */
  explicit vpProjectiveSessionCalibration(const vpMarkerExtractor &extractor = vpMarkerExtractor());

  /*!
    The marker extraction of the AprilTag family \e family, as the tool's --family spells it: "36h11", "25h9",
    "16h5", "Circle21h7" (and "Circle49h12", "Custom48h12", "Standard41h12", "Standard52h13" when ViSP has its big
    families): vpStereoAprilTagDetector at its defaults on each stereo pair, a tag's 4 corners identified by
    4 * tag id + corner index.
    \exception vpProjectiveException (invalidValueError) on another family; with a ViSP built without AprilTag,
    (notImplementedError) when the function is called.
  */
  static vpMarkerExtractor aprilTagMarkers(const std::string &family);

  /*!
    The image source of vpProjectiveAcquisitionProcedure on a cell: each call takes a stereo pair from \e images,
    reads the joints of \e robot (vpRobot::getPosition(ARTICULAR_FRAME)), extracts the markers with \e extractor and
    gives those of the first call's identifiers (the zero reference), in that order; false if \e images has no more
    pairs or one of those markers is missing. A pair whose markers are all found is recorded with the readings if
    \e writer is not null (vpProjectiveSessionWriter::addAcquisitionFrame(): the zero frame, trials and the mounting
    check's observations; time in seconds from the first call): the session holds the frames the procedure used, and
    calibrates offline as the run did (visp-projective calibrate). \e images, \e robot and \e writer must outlive the
    function. \code vpStereoGrabberSource cameras("/dev/video0", "/dev/video2"); vpProjectiveSessionWriter
    writer("cell-2026-11-27", types); vpProjectiveAcquisitionProcedure procedure(
        vpProjectiveSessionCalibration::markerSource(cameras, extractor, robot, &writer), width, height);
    procedure.run(robot, projectiveRobot);
    \endcode
  */
  static vpProjectiveAcquisitionProcedure::vpImageSource markerSource(vpStereoImageSource &images,
                                                                      const vpMarkerExtractor &extractor,
                                                                      vpRobot &robot,
                                                                      vpProjectiveSessionWriter *writer = nullptr);

  //! The marker extraction function.
  void setMarkerExtractor(const vpMarkerExtractor &extractor);
  /*!
    With true, calibrate() and check() take each frame's recorded markers (its \c recorded_markers entry, see
    vpProjectiveSession) instead of extracting them from its images: for sessions recorded by a program whose markers
    are not found in images by this plugin (the paper's experiment), which then calibrate from exactly the pixels
    the program used. A frame without recorded markers is then an error. Default false.
  */
  void setRecordedMarkers(bool recorded) { m_recorded = recorded; }
  //! True if the recorded markers are used (setRecordedMarkers()).
  bool getRecordedMarkers() const { return m_recorded; }
  //! Where to write the progress, a line per frame and a summary (null: nothing). Default null.
  void setOutput(std::ostream *os) { m_os = os; }
  //! The mounting (default MOUNTING_AUTO).
  void setMounting(vpMountingChoice mounting) { m_mounting = mounting; }
  /*!
    The cameras' layout that calibrate() assumes (default LAYOUT_LEFT_RIGHT): with LAYOUT_ANY here or in the
    session (its \c camera_layout), a session whose right camera sits to the left of its left one is calibrated
    rather than refused as one with exchanged images (a camera mounted upside down, a mirror).
  */
  void setCameraLayout(vpProjectiveCellFingerprint::vpCameraLayout layout) { m_layout = layout; }
  /*!
    Epipolar inlier threshold of the rig's estimation (pixels, > 0; default 2).
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setEpipolarThreshold(double pixels);
  /*!
    Outlier threshold of the acquisition (pixels, >= 0; 0, the default, keeps every observation; see
    vpProjectiveArmAcquisition::setOutlierThreshold()).
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setOutlierThreshold(double pixels);
  /*!
    Coplanarity threshold (pixels RMS, > 0; default 2; see vpProjectiveAcquisitionProcedure::setCoplanarityThreshold()).
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setCoplanarityThreshold(double pixels);
  /*!
    RMS per coordinate (pixels, > 0; default 2) above which check() says that a frame does not fit the model.
    \exception vpProjectiveException (invalidValueError) if not positive or not finite.
  */
  void setMismatchThreshold(double pixels);

  /*!
    Calibrates the arm of \e session (see the class documentation) and returns the model.
    \exception vpProjectiveException with a one-line message naming the frame: no marker in a frame, fewer than 5
    markers in the zero frame or of them in a trial, coplanar markers, a joint without a trial, a rig or a
    calibration that cannot be estimated; and the extraction function's errors.
  */
  vpProjectiveArmModel calibrate(const vpProjectiveSession &session);
  //! The identifiers of the model's markers, in the model's order (after calibrate()).
  const std::vector<int> &getMarkerIds() const { return m_ids; }
  //! RMS pixel residual of the last calibrate()'s bundle adjustment.
  double getCalibrationResidual() const { return m_residual; }
  //! RMS pixel residual of the last calibrate()'s algebraic generators.
  double getAlgebraicResidual() const { return m_algebraicResidual; }
  //! What the last calibrate() found about each joint.
  const std::vector<vpJointSummary> &getJointSummaries() const { return m_joints; }
  //! The fingerprint of the last calibrate()'s cell (saved with the model).
  const vpProjectiveCellFingerprint &getFingerprint() const { return m_fingerprint; }
  /*!
    Writes the last calibrate()'s model with its residuals and marker identifiers to \e filename, atomically.
    \exception vpProjectiveException (notInitializedError) before calibrate(); (fileError) if the file cannot be
    written (no file is left then).
  */
  void saveModel(const std::string &filename) const;
  /*!
    Checks that \e filename can be written (a temporary file is created beside it and removed), so that a tool fails
    before a long calibration rather than after.
    \exception vpProjectiveException (fileError) naming the path.
  */
  static void checkWritable(const std::string &filename);

  /*!
    The prediction error of \e model (whose markers have the identifiers \e ids, its cell the fingerprint \e cell:
    vpProjectiveModelFile::load() gives it, empty if not known) on every frame of \e session, one progress line per
    frame, then the probable causes of the frames that do not fit (see the class documentation).
    \exception vpProjectiveException (dimensionError) if the session's joints are not the model's or \e ids does not
    have one identifier per marker (a session of another cell); (fileError) if a frame shows no marker of the model
    (naming it, and the markers it shows instead); and the extraction function's errors.
  */
  std::vector<vpFrameCheck> check(const vpProjectiveArmModel &model, const std::vector<int> &ids,
                                  const vpProjectiveSession &session,
                                  const vpProjectiveCellFingerprint &cell = vpProjectiveCellFingerprint());
  //! What the last check() concludes: RIG_UNCHANGED, or the likeliest cause (getDiagnosis()'s first).
  vpRigState getRigState() const { return m_state; }
  //! The probable causes of the last check()'s frames that do not fit, likeliest first (empty if every frame fits).
  const std::vector<vpCheckDiagnosis> &getDiagnosis() const { return m_diagnosis; }
  /*!
    The last check()'s conclusion in one line: toString(getRigState()) when every frame fits, else the likeliest
    cause with its finding and fix, then the other likely causes, then those the diagnostics rule out.
  */
  std::string getDiagnosisMessage() const;
  //! RMS per coordinate of the left images over the frames of the last check() (px).
  double getLeftResidual() const { return m_leftResidual; }
  //! RMS per coordinate of the right images over the frames of the last check() (px).
  double getRightResidual() const { return m_rightResidual; }
  //! A sentence for a rig state (a cause's finding in general words, and what to do).
  static std::string toString(vpRigState state);

private:
  void progress(const std::string &line) const;
  /*!
    The fingerprint of the cell of \e session calibrated into \e model; refuses (invalidValueError) a model whose
    right camera sits to the left of its left one unless the layout is LAYOUT_ANY.
  */
  vpProjectiveCellFingerprint cellOf(const vpProjectiveArmModel &model, const vpProjectiveSession &session) const;

  vpMarkerExtractor m_extractor;
  std::ostream *m_os;
  vpMountingChoice m_mounting;
  double m_epipolar, m_outlier, m_coplanarity, m_mismatch;
  bool m_calibrated;
  vpProjectiveArmModel m_model;
  std::vector<int> m_ids;
  std::vector<vpProjectiveArmAcquisition::vpFrame> m_frames; // of the metric self-calibration
  double m_residual, m_algebraicResidual;
  std::vector<vpJointSummary> m_joints;
  vpRigState m_state;
  double m_leftResidual, m_rightResidual;
  bool m_recorded;
  vpProjectiveCellFingerprint::vpCameraLayout m_layout;
  vpProjectiveCellFingerprint m_fingerprint;
  std::vector<vpCheckDiagnosis> m_diagnosis;
};

END_VISP_NAMESPACE

#endif
