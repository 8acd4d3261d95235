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
  \file vpProjectiveArmAcquisition.h
  \brief The acquisition of an arm's projective kinematic model from images: trial motions, algebraic generators,
  affine and metric upgrade, bundle adjustment, outliers.
*/

#ifndef _vpProjectiveArmAcquisition_h_
#define _vpProjectiveArmAcquisition_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <functional>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveModelCheck.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveArmAcquisition
  \ingroup group_projective
  \brief The data of an arm's acquisition (Ruf & Horaud, section 6) and the calibration that turns it into a
  vpProjectiveArmModel.

  setZeroReference() takes the images of the markers at the zero reference; addTrialMotion() the images after one
  joint alone moved by a known amount (several per joint, ideally both ways: one chord per joint leaves the axis tilt
  of the base joints poorly determined, a second, opposite one fixes it). calibrate() then computes
  -# the algebraic generators from the trial homographies (logarithms (25), (31)), each trial's displacement by
     maximum likelihood (vpProjectiveDisplacement::estimateFromImages(), or estimateRobust() with an outlier
     threshold), each joint's generator the candidate that best predicts its trials;
  -# in a frame whitened by the zero-reference points, the plane \f$ \pi \f$ with \f$ \pi^T \hat H_i = 0 \f$ for all
     joints (affine step) and the symmetric \f$ W \f$ with \f$ A_i W + W A_i^T = 0 \f$ for the revolute blocks
     (metric step): a matrix \f$ G \f$ with \f$ \hat H_i = G^{-1} \hat T_i G \f$, \f$ \hat T_i \in se(3) \f$, tried with
     every joint and with one or two left out, each metric twist read off its generator or off the Kabsch rigid
     motions of its trials' markers;
  -# a Ceres bundle adjustment over \f$ G^{-1} \f$, the metric twists (revolute: unit axis and a point on it;
     prismatic: a direction vector) and the marker points, minimising the pixel error of every acquisition image in
     both cameras with \f$ P, P' \f$ fixed. All generators thereby share one \f$ G \f$, which is \f$ H_{PE} \f$ up to a
     similarity, and the final RMS residual (getCalibrationResidual()) sits at the image noise level: the self-check.

  <b>The model check.</b> calibrate() refuses a model whose residual is far above the image noise, names a declared
  joint type that the trials contradict, and with a joint count alone (vpProjectiveArmAcquisition(unsigned int))
  identifies the joint types from the trials; a refused model comes with its probable causes ranked by a diagnostic
  each (getModelCheck(), vpProjectiveModelCheck, \ref page_model_check).

  <b>Identified markers.</b> With ids (the setZeroReference() and addTrialMotion() overloads taking ids, such as
  AprilTag corners), the trials are matched to the zero reference by id and may miss some of its markers (occluded,
  turned away): every step above uses the observations there are, a trial's displacement those of its markers
  (at least 5).

  Joint amounts are radians (revolute) or the encoder's length unit (prismatic).
*/
class VISP_EXPORT vpProjectiveArmAcquisition
{
public:
  //! An acquisition without joints (construct with joint types to use it).
  vpProjectiveArmAcquisition();
  /*!
    The acquisition of a chain of joints of the given kinds, base to tip.
    \exception vpProjectiveException (dimensionError, invalidValueError) if there are no joints, more than
    vpProjectiveArmModel::maxJoints, or a kind is neither REVOLUTE nor PRISMATIC.
  */
  explicit vpProjectiveArmAcquisition(const std::vector<vpProjectiveJoint::vpJointType> &types);
  /*!
    The acquisition of a chain of \e n joints whose types calibrate() identifies from the trials (each joint the type
    that fits its trials better: vpProjectiveModelCheck). Trial amounts are then the joints' readings as they are
    (radians for a revolute joint, a length unit for a prismatic one).
    \exception vpProjectiveException (dimensionError) if \e n is 0 or above vpProjectiveArmModel::maxJoints.
  */
  explicit vpProjectiveArmAcquisition(unsigned int n);
  /*!
    The acquisition of a model computed elsewhere (read from a file): its joints, mounting, rig, zero-reference joints
    and markers (ids 0 to K-1), without images. Calibration frames can be added (addCalibrationFrame()); calibrate()
    needs a zero reference and trials.
  */
  explicit vpProjectiveArmAcquisition(const vpProjectiveArmModel &model);

  //! Number of joints \e n.
  unsigned int getNumberOfJoints() const { return static_cast<unsigned int>(m_types.size()); }
  /*!
    The kinds of the joints, base to tip: as declared, or as the last successful calibrate() identified them
    (REVOLUTE for every joint before, see hasDeclaredJointTypes()).
  */
  const std::vector<vpProjectiveJoint::vpJointType> &getJointTypes() const { return m_types; }
  //! True if the joint types were given to the constructor; false if calibrate() identifies them.
  bool hasDeclaredJointTypes() const { return m_declared; }
  /*!
    Sets where the rig is mounted (default EYE_TO_HAND). The trials are the same in both cases (one joint each):
    only motions of several joints tell the mountings apart, which vpProjectiveAcquisitionProcedure makes.
  */
  void setRigMounting(vpProjectiveArmModel::vpRigMounting mounting) { m_mounting = mounting; }
  //! Where the rig is mounted.
  vpProjectiveArmModel::vpRigMounting getRigMounting() const { return m_mounting; }

  /*!
    The weakly calibrated rig whose projective frame the model will live in. Clears the images of another rig.
    \exception vpProjectiveException (notInitializedError) if the rig has no fundamental matrix.
  */
  void setStereoRig(const vpProjectiveStereoRig &rig);
  //! The rig set by setStereoRig().
  const vpProjectiveStereoRig &getStereoRig() const { return m_rig; }

  /*!
    Images of the \f$ K \ge 5 \f$ markers at the zero reference (5 of them with no 4 coplanar: a projective basis;
    on the tool eye-to-hand, static in the scene eye-in-hand), in a fixed order: pixels, left[j] and right[j] of
    marker j. Clears the trials.
    \exception vpProjectiveException (notEnoughPointsError, dimensionError, nonFiniteValueError, notInitializedError)
    on fewer than 5 markers, a size mismatch, a non-finite coordinate, no rig.
  */
  void setZeroReference(const std::vector<vpImagePoint> &left0, const std::vector<vpImagePoint> &right0);
  /*!
    The same, with the joints' encoder readings \e qRef (n x 1: radians, or length units) at the zero reference: the
    model then takes absolute encoder readings (vpProjectiveArmModel::zeroReferenceJoints()), and so does
    addTrialMotion(const vpColVector &, ...).
    \exception vpProjectiveException as the other overload, and if \e qRef has not n finite entries.
  */
  void setZeroReference(const vpColVector &qRef, const std::vector<vpImagePoint> &left0,
                        const std::vector<vpImagePoint> &right0);
  /*!
    The same with identified markers (AprilTag corners: vpStereoAprilTagDetector::getIds()): \e ids[j] names the
    marker of left0[j] and right0[j]. The ids must be distinct, in any order; the markers are kept in ascending id
    order, so that the model's marker j is getMarkerIds()[j]. Trials then name their markers by id
    (addTrialMotion(const vpColVector &, const std::vector<int> &, ...)) and may miss some.
    \exception vpProjectiveException as the other overloads, and (dimensionError, invalidValueError) if \e ids has not
    one id per marker or repeats one.
  */
  void setZeroReference(const vpColVector &qRef, const std::vector<int> &ids, const std::vector<vpImagePoint> &left0,
                        const std::vector<vpImagePoint> &right0);
  //! The joint values at the zero reference (n x 1; zeros unless given to setZeroReference()).
  vpColVector getZeroReferenceJoints() const;
  /*!
    The ids of the zero reference's markers, ascending: the model's marker j is getMarkerIds()[j] (0, 1, ..., K-1
    when the zero reference was given without ids).
  */
  const std::vector<int> &getMarkerIds() const { return m_ids; }

  /*!
    Images of the same markers, in the same order, after joint \e i alone moved from the zero reference by \e amount
    (radians or length units, signed, as read by the encoder). Call several times per joint, ideally both ways.
    \exception vpProjectiveException on a bad joint index (dimensionError), a zero, non-finite or whole-turn amount
    (invalidValueError, nonFiniteValueError), a size mismatch (dimensionError), no zero reference
    (notInitializedError).
  */
  void addTrialMotion(unsigned int i, double amount, const std::vector<vpImagePoint> &left,
                      const std::vector<vpImagePoint> &right);
  /*!
    The same from the encoder readings \e q (n x 1) after the trial: the joint i whose reading differs most from the
    zero reference's is the one that moved, by \f$ q_i - q_{ref,i} \f$; the others must not have moved by more than
    1 % of that (encoder noise), since the trial is one joint's motion alone.
    \exception vpProjectiveException as the other overload, and (dimensionError, nonFiniteValueError,
    invalidValueError) if \e q has not n finite entries, or no joint or several joints moved.
  */
  void addTrialMotion(const vpColVector &q, const std::vector<vpImagePoint> &left,
                      const std::vector<vpImagePoint> &right);
  /*!
    Identified markers after joint \e i alone moved by \e amount: \e ids[j] names the marker of left[j] and
    right[j], in any order. Markers are matched by id to the zero reference's: an id the zero reference does not have
    is ignored, a zero-reference marker the trial does not show is missing from it (calibrate() uses the
    observations there are; isObserved()).
    \exception vpProjectiveException as the other overloads, (dimensionError, invalidValueError) if \e ids has not one
    id per marker or repeats one, and (notEnoughPointsError) if the trial shows fewer than 5 of the zero
    reference's markers (a trial's displacement needs 5).
  */
  void addTrialMotion(unsigned int i, double amount, const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                      const std::vector<vpImagePoint> &right);
  /*!
    The same from the encoder readings \e q after the trial, as addTrialMotion(const vpColVector &, ...).
    \exception vpProjectiveException as both.
  */
  void addTrialMotion(const vpColVector &q, const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                      const std::vector<vpImagePoint> &right);
  /*!
    True if trial \e trial (in the order of addTrialMotion(), from 0) shows marker \e marker (the model's index: the
    zero reference's, see getMarkerIds()).
    \exception vpProjectiveException (dimensionError) if there is no such trial or marker.
  */
  bool isObserved(unsigned int trial, unsigned int marker) const;
  //! Number of trial motions added since the zero reference.
  unsigned int getNumberOfTrials() const { return static_cast<unsigned int>(m_trials.size()); }
  //! Number of markers of the zero reference.
  unsigned int getNumberOfMarkers() const { return static_cast<unsigned int>(m_zeroImages.size()); }

  /*! \name Frames for the metric self-calibration (vpProjectiveSelfCalibration) */
  //@{
  /*!
    Images of the zero reference's markers, in its order, at any configuration: the joints' encoder readings \e q
    (n x 1, as addTrialMotion(const vpColVector &, ...) takes them): a servo's or an observation's frame. calibrate()
    does not use them; the metric self-calibration adjusts the cameras and the arm over the zero reference, the trials
    and every such frame. They are kept until the zero reference or the rig is set again.
    \exception vpProjectiveException (notInitializedError) without a zero reference (or a model, see the constructor
    from a model); (dimensionError, nonFiniteValueError) if \e q has not n finite entries, or the images are not one
    finite pair per marker. Nothing is recorded on error.
  */
  void addCalibrationFrame(const vpColVector &q, const std::vector<vpImagePoint> &left,
                           const std::vector<vpImagePoint> &right);
  /*!
    The same with identified markers (\e ids[j] names left[j] and right[j], in any order, as the identified trials):
    the frame may miss some of the zero reference's markers.
    \exception vpProjectiveException as the other overload, (dimensionError, invalidValueError) if \e ids has not one
    id per marker or repeats one, and (notEnoughPointsError) if the frame shows none of the zero reference's markers.
  */
  void addCalibrationFrame(const vpColVector &q, const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                           const std::vector<vpImagePoint> &right);
  //! Number of calibration frames added since the zero reference.
  unsigned int getNumberOfCalibrationFrames() const { return static_cast<unsigned int>(m_frames.size()); }
  //! Forgets the calibration frames (the zero reference and the trials stay).
  void clearCalibrationFrames() { m_frames.clear(); }

  //! One stereo image of the markers at known joint readings.
  struct vpFrame {
    vpProjectiveArmModel::JointVector q; //!< The joints' encoder readings (n x 1).
    std::vector<Eigen::Vector4d> s;      //!< (u, v, u', v') of each zero-reference marker, pixels (NaN if not seen).
    std::vector<bool> seen;              //!< Marker j is observed (shown, and not an outlier of calibrate()).
  };
  /*!
    Every stereo image of the acquisition at its readings: the zero reference, each trial (the zero reference's
    readings with the trial's amount added; the observations the last calibrate() left out as outliers not seen),
    then the calibration frames. Empty without a zero reference but for the calibration frames.
  */
  std::vector<vpFrame> getFrames() const;
  //@}

  /*!
    Mismatched markers in the acquisition images (a wrong blob tracked, two markers swapped): with \e pixels > 0,
    calibrate() finds them in each trial by the 5-point consensus of vpProjectiveDisplacement::estimateRobust(),
    leaves them out of the initial model and of the bundle adjustment, then keeps out exactly the trial observations
    the final model places more than \e pixels away (RMS over the two images), with one more adjustment if that
    changed. A zero-reference marker whose left and right images match no 3D point within \e pixels makes
    calibrate() throw (the zero reference defines the markers). About 3 sigma of the pixel noise is a good value;
    0, the default, uses every observation.
    \exception vpProjectiveException (invalidValueError) if \e pixels is negative or not finite.
  */
  void setOutlierThreshold(double pixels);
  //! The outlier threshold in pixels (0: no rejection).
  double getOutlierThreshold() const { return m_outlierThreshold; }

  /*!
    Computes the model (see the class documentation) and checks it (getModelCheck()). On success the outlier flags,
    the residuals and, without declared types, the joint types describe this calibration; on failure nothing changes
    but getModelCheck().
    \exception vpProjectiveException (notInitializedError) if a joint has no trial motion or the zero reference is
    missing; (degenerateConfigurationError) if a trial did not move the markers (a blocked joint, a too small trial) or
    a zero-reference marker's left and right images disagree beyond the outlier threshold; (estimationFailedError) if
    the upgrade or the bundle adjustment fails; (modelRejectedError) if the check refuses the model: the message
    ranks the probable causes (vpProjectiveModelCheck::getMessage()).
  */
  vpProjectiveArmModel calibrate();
  /*!
    The image noise (pixels per coordinate, >= 0) that the model check takes as a lower bound of its own estimate from
    the acquisition's images (vpProjectiveModelCheck::getNoise()): measured on frames at rest (the differences of two
    images of the markers without motion, divided by sqrt(2)), or known. Default 0: the estimate alone.
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setImageNoise(double pixels);
  //! The noise of setImageNoise().
  double getImageNoise() const { return m_imageNoise; }
  /*!
    calibrate() refuses a model whose residual, or a joint's trials' residual, exceeds \e factor times the image noise
    (and 0.5 px): see vpProjectiveModelCheck. Default 3; 0 accepts any model (the joint types are still identified or
    checked, and getModelCheck() still says what it found).
    \exception vpProjectiveException (invalidValueError) if negative or not finite.
  */
  void setResidualTolerance(double factor);
  //! The factor of setResidualTolerance().
  double getResidualTolerance() const { return m_tolerance; }
  /*!
    What the last calibrate() that reached a model checked: the residual against the image noise, the joint types,
    and for a refused model its probable causes, ranked (calibrate() then threw vpProjectiveException
    (modelRejectedError) with getMessage()).
  */
  const vpProjectiveModelCheck &getModelCheck() const { return m_check; }

  /*!
    RMS pixel residual per coordinate of the last calibrate()'s bundle adjustment (the self-check: ~ noise level);
    in a vpProjectiveRobot's acquisition (vpProjectiveRobot::getAcquisition()), that of the robot's model, as given to
    vpProjectiveRobot::setCalibration() or read by vpProjectiveRobot::loadModel().
  */
  double getCalibrationResidual() const { return m_residual; }
  //! RMS pixel residual of the algebraic generators alone (before the upgrade and the adjustment), for comparison;
  //! in a vpProjectiveRobot's acquisition, that of the robot's model.
  double getAlgebraicResidual() const { return m_algebraicResidual; }
  //! Number of trial observations (marker in a trial's pair of images) the last calibrate() left out as outliers
  //! (missing markers are not observations).
  unsigned int getNumberOfOutliers() const;
  /*!
    True if the last calibrate() left out marker \e marker of trial \e trial (trials numbered in the order of
    addTrialMotion(), from 0) as an outlier; false for a marker the trial does not show.
    \exception vpProjectiveException (dimensionError) if there is no such observation.
  */
  bool isOutlier(unsigned int trial, unsigned int marker) const;

private:
  friend class vpProjectiveRobot; // records the residuals of the model it takes (setCalibration(), loadModel())

  std::vector<vpProjectiveJoint::vpJointType> m_types;
  vpProjectiveArmModel::vpRigMounting m_mounting;
  vpProjectiveStereoRig m_rig;
  std::vector<Eigen::Vector4d> m_zeroImages; // (u, v, u', v') of each marker at the zero reference
  vpProjectiveArmModel::JointVector m_qRef;
  struct vpTrial {
    unsigned int joint;
    double amount;
    std::vector<Eigen::Vector4d> s; // (u, v, u', v') of each marker (NaN where not seen)
    std::vector<bool> seen;         // [marker]: the trial shows it
  };
  // The images of the zero reference's markers among identified ones (NaN where not shown, seen[j] false), and how
  // many are shown.
  std::vector<Eigen::Vector4d> matchByIds(const std::vector<int> &ids, const std::vector<vpImagePoint> &left,
                                          const std::vector<vpImagePoint> &right, const std::string &where,
                                          std::vector<bool> &seen, unsigned int &shown) const;
  // The trial of identified markers: the plain overload \e addPlainTrial checks the joint and the amount on the zero
  // reference's images, then this trial's matched images replace them.
  void addIdentifiedTrial(
      const std::vector<int> &ids, const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
      const std::function<void(const std::vector<vpImagePoint> &, const std::vector<vpImagePoint> &)> &addPlainTrial);
  std::vector<vpTrial> m_trials;
  std::vector<int> m_ids;        // of the zero reference's markers, ascending
  std::vector<vpFrame> m_frames; // calibration frames
  double m_outlierThreshold;
  std::vector<std::vector<bool>> m_inlier; // [trial][marker]: used by the last calibrate() (false where not seen)
  double m_residual;
  double m_algebraicResidual;
  bool m_declared = true;    // the types were given (false: calibrate() identifies them)
  double m_imageNoise = 0.0; // setImageNoise()
  double m_tolerance = 3.0;  // setResidualTolerance()
  vpProjectiveModelCheck m_check;
};

END_VISP_NAMESPACE

#endif
