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
  \file vpProjectiveRobot.h
  \brief A serial arm seen by an uncalibrated stereo rig: acquisition, projective kinematic model, inverse kinematics
  and model file behind one facade with ViSP types.
*/

#ifndef _vpProjectiveRobot_h_
#define _vpProjectiveRobot_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveRigUpdate.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveRobot
  \ingroup group_projective
  \brief A serial chain of \f$ n \f$ revolute or prismatic joints modelled only in the projective frame
  \f$ \mathcal{P} \f$ of an uncalibrated stereo rig (Ruf & Horaud, sections 5 and 6): the facade that a ViSP program
  uses, with ViSP types and checked arguments.

  It gathers the pieces that Pinocchio would call model, data and algorithms:
  - vpProjectiveArmAcquisition: the acquisition images and calibrate(), which computes
  - vpProjectiveArmModel: the model (generators, \f$ G \f$, markers) and its kinematics, eqs. (34)-(46), which the
    servo's control loop calls through the Eigen methods below (getModel());
  - vpProjectiveInverseKinematics: inverseKinematics();
  - vpProjectiveModelFile: saveModel() and loadModel() (JSON).
  See those classes for the mathematics. Joints are indexed \f$ 0 \ldots n-1 \f$ from base to tip; joint values are
  the joints' encoder readings, radians (revolute) or the encoder's length unit (prismatic), and the model moves by
  their difference to the zero reference's readings (zero unless setZeroReference() was given them).

  \code
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  robot.setStereoRig(rig);
  robot.setZeroReference(qRef, left0, right0);     // encoder readings and marker images at the zero reference
  robot.addTrialMotion(q_i, left_i, right_i);      // each joint alone moved (q_i its readings), both ways
  robot.calibrate();
  vpMatrix J = robot.getImageJacobian(q, M);       // 4 x n at the readings q
  robot.saveModel("arm.json");
  \endcode
*/
class VISP_EXPORT vpProjectiveRobot
{
public:
  //! Joint kinds: the one enumeration of vpProjectiveJoint.
  typedef vpProjectiveJoint::vpJointType vpJointType;
  //! A revolute joint.
  static constexpr vpJointType REVOLUTE = vpProjectiveJoint::REVOLUTE;
  //! A prismatic joint.
  static constexpr vpJointType PRISMATIC = vpProjectiveJoint::PRISMATIC;
  //! Where the rig is (see vpProjectiveArmModel::vpRigMounting).
  typedef vpProjectiveArmModel::vpRigMounting vpRigMounting;
  //! Rig fixed in the workspace, markers on the last link.
  static constexpr vpRigMounting EYE_TO_HAND = vpProjectiveArmModel::EYE_TO_HAND;
  //! Rig on the last link, markers static.
  static constexpr vpRigMounting EYE_IN_HAND = vpProjectiveArmModel::EYE_IN_HAND;
  //! Largest number of joints.
  static const unsigned int maxJoints = vpProjectiveArmModel::maxJoints;
  //! Joint values (n x 1) without heap allocation.
  typedef vpProjectiveArmModel::JointVector JointVector;
  //! A 4 x n Jacobian without heap allocation.
  typedef vpProjectiveArmModel::PointJacobian PointJacobian;

  //! An empty robot; use loadModel() or the other constructor.
  vpProjectiveRobot();
  /*!
    A chain of joints of the given types, base to tip.
    \exception vpProjectiveException if there are no joints, more than maxJoints, or a type is invalid.
  */
  explicit vpProjectiveRobot(const std::vector<vpJointType> &joints);
  /*!
    A chain of \e n joints whose types calibrate() (or vpProjectiveAcquisitionProcedure::run()) identifies from the
    trials: each joint the type that fits its trials better (vpProjectiveArmAcquisition(unsigned int),
    vpProjectiveModelCheck). getJointType() is known once calibrated.
    \exception vpProjectiveException (dimensionError) if \e n is 0 or more than maxJoints.
  */
  explicit vpProjectiveRobot(unsigned int n);

  //! Number of joints \e n.
  unsigned int getNumberOfJoints() const { return m_acquisition.getNumberOfJoints(); }
  /*!
    Type of joint \e i.
    \exception vpProjectiveException (dimensionError) on a bad index; (notInitializedError) for a robot of a joint
    count alone before calibrate() identified the types.
  */
  vpJointType getJointType(unsigned int i) const;
  /*!
    Sets where the rig is mounted (default EYE_TO_HAND). The trial motions look the same in both cases (one joint
    each); vpProjectiveAcquisitionProcedure tells the mounting by a motion of two joints and sets the one it finds.
  */
  void setRigMounting(vpRigMounting mounting);
  //! Where the rig is mounted.
  vpRigMounting getRigMounting() const { return m_acquisition.getRigMounting(); }

  /*! \name Acquisition (see vpProjectiveArmAcquisition) */
  //@{
  //! The weakly calibrated rig whose projective frame the model lives in. Clears acquired data of another rig.
  void setStereoRig(const vpProjectiveStereoRig &rig);
  //! The rig of the model (or, before calibrate(), the one set by setStereoRig()).
  const vpProjectiveStereoRig &getStereoRig() const;
  /*!
    Images of the \f$ K \ge 5 \f$ markers at the zero reference (pixels; on the last link eye-to-hand, static in the
    scene eye-in-hand), in a fixed order, 5 of them with no 4 coplanar; the zero reference's joint values are then 0.
    \exception vpProjectiveException on fewer than 5 markers, a size mismatch, a non-finite coordinate, a missing rig.
  */
  void setZeroReference(const std::vector<vpImagePoint> &left0, const std::vector<vpImagePoint> &right0);
  /*!
    The same with the joints' encoder readings \e qRef (n x 1) at the zero reference: every joint value given to the
    robot and its servo task afterwards is an encoder reading, and the trial motions can be given by their readings.
    \exception vpProjectiveException as the other overload, and if \e qRef has not n finite entries.
  */
  void setZeroReference(const vpColVector &qRef, const std::vector<vpImagePoint> &left0,
                        const std::vector<vpImagePoint> &right0);
  /*!
    Images of the same markers, in the same order, after joint \e i alone moved from the zero reference by \e amount
    (radians or length units, signed). Call several times per joint, ideally both ways.
    \exception vpProjectiveException on a bad joint index, a zero or non-finite amount, a size mismatch, a missing
    zero reference.
  */
  void addTrialMotion(unsigned int i, double amount, const std::vector<vpImagePoint> &left,
                      const std::vector<vpImagePoint> &right);
  /*!
    The same from the encoder readings \e q (n x 1) after the trial: the joint that moved and its amount are read
    off the difference to the zero reference's readings (see vpProjectiveArmAcquisition::addTrialMotion()).
    \exception vpProjectiveException as the other overload, and if no joint or several joints moved.
  */
  void addTrialMotion(const vpColVector &q, const std::vector<vpImagePoint> &left,
                      const std::vector<vpImagePoint> &right);
  /*!
    A frame for the metric self-calibration: the images of the zero reference's markers, in its order, at any
    configuration, \e q the encoder readings (n x 1, as addTrialMotion() takes them); a servo's or an observation's
    frame. getMetricStereoRig() and vpProjectiveSelfCalibration adjust the cameras and the arm over the acquisition and
    every such frame (vpProjectiveSelfCalibration, which also gives each estimate's uncertainty:
    <tt>vpProjectiveSelfCalibration(robot.getModel(), robot.getAcquisition().getFrames())</tt>; after updateRig(),
    only the last getNumberOfCalibrationFrames() of them show the current rig). Before or after calibrate() or
    loadModel(); the model is not changed. updateRig() (a moved camera) forgets them.
    \exception vpProjectiveException as vpProjectiveArmAcquisition::addCalibrationFrame(): no zero reference, \e q not
    n finite readings, not one finite image pair per marker. Nothing is recorded on error.
  */
  void addCalibrationFrame(const vpColVector &q, const std::vector<vpImagePoint> &left,
                           const std::vector<vpImagePoint> &right);
  /*!
    Computes the model: algebraic generators, metric upgrade, then Ceres bundle adjustment (see
    vpProjectiveArmAcquisition), and checks it against the image noise and the joint types the trials show
    (getAcquisition().getModelCheck(), vpProjectiveModelCheck). On failure the robot keeps the model it had.
    \exception vpProjectiveException if a joint has no trial motion, the zero reference is missing, or the data is
    degenerate; (modelRejectedError) if the check refuses the model: the message ranks its probable causes.
  */
  void calibrate();
  //! True once calibrate() or loadModel() succeeded.
  bool isCalibrated() const { return m_calibrated; }
  /*!
    Outlier threshold of the acquisition in pixels (see vpProjectiveArmAcquisition::setOutlierThreshold()); 0, the
    default, uses every observation.
    \exception vpProjectiveException (invalidValueError) if \e pixels is negative or not finite.
  */
  void setOutlierThreshold(double pixels);
  /*!
    The acquisition: its images, the outlier threshold and the observations the last calibrate() left out
    (getOutlierThreshold(), getNumberOfOutliers(), isOutlier(trial, marker)), the residuals of the model
    (getCalibrationResidual(), getAlgebraicResidual(): of calibrate(), or those given to setCalibration() or read by
    loadModel()), the zero reference's joint values, and the rig as it was estimated or set (getStereoRig() returns the
    model's, refined by the bundle adjustment, once calibrated). After loadModel(): no images, the model's rig.
  */
  const vpProjectiveArmAcquisition &getAcquisition() const { return m_acquisition; }
  /*!
    Takes \e model, computed from \e acquisition outside the robot (vpProjectiveAcquisitionProcedure::run() does),
    with the RMS residual \e residual (pixels) of its final refinement, as calibrate() would: the rig observations
    and re-registration are forgotten and the tasks on the robot are told (vpListener).
    \exception vpProjectiveException (dimensionError) if the joint types of \e model, \e acquisition and the robot
    differ; (invalidValueError) if \e residual is negative or not finite. The robot is then unchanged.
  */
  void setCalibration(const vpProjectiveArmAcquisition &acquisition, const vpProjectiveArmModel &model,
                      double residual);
  //@}

  /*! \name Model */
  //@{
  /*!
    The model itself (Eigen types, const and thread-safe kinematics): \f$ G \f$ (projectiveToMetric()), the twists,
    the markers' points \f$ M_j(0) \f$ (markers()), the zero reference's joint values, the joints' motions and point
    Jacobians, and the markers' predicted images (projectMarker()).
    \exception vpProjectiveException (notInitializedError) before calibrate() or loadModel().
  */
  const vpProjectiveArmModel &getModel() const;
  //! Generator \f$ \hat H_i \f$ (4x4) of joint \e i at the zero reference.
  vpMatrix getGenerator(unsigned int i) const;
  //@}

  /*! \name Metric self-calibration (see vpProjectiveSelfCalibration) */
  //@{
  /*!
    The metric stereo rig hidden in the model: the intrinsics of both cameras (3x3, pixels, skew included) and the
    right camera's pose in the left camera's frame (\f$ X_l = {}^l M_r X_r \f$), its translation in the prismatic
    joints' encoder unit, or of unit length when the arm has no prismatic joint. The metric bundle adjustment of
    vpProjectiveSelfCalibration over the acquisition's images and every calibration frame (addCalibrationFrame();
    after updateRig() only the frames added since), started from the model's metric upgrade. The joints' axes, another
    scale and each estimate's uncertainty: vpProjectiveSelfCalibration (see addCalibrationFrame()). \exception
    vpProjectiveException (notInitializedError) before calibrate() or loadModel(); (degenerateConfigurationError) if the
    model gives no metric upgrade.
  */
  void getMetricStereoRig(vpMatrix &Kl, vpMatrix &Kr, vpHomogeneousMatrix &lMr) const;
  //@}

  /*! \name Kinematics (ViSP types, checked; q holds encoder readings, n x 1) */
  //@{
  //! \f$ H(q) \f$ (4x4) of the last link, eq. (34).
  vpMatrix getDisplacement(const vpColVector &q) const;
  //! Stereo image Jacobian (4 x n, pixels per joint unit, rows \f$ (u, v, u', v') \f$) of eqs. (45)-(46) at q for M.
  vpMatrix getImageJacobian(const vpColVector &q, const vpColVector &M) const;
  /*!
    Inverse kinematics (the paper's motion-capture use; see vpProjectiveInverseKinematics): the joint values that
    best explain the observed images of the markers, started at \e q0.
    \param left, right : images of the markers \e indices (all markers if \e indices is empty).
    \param q0 : starting joint values (n x 1); the zero reference's if empty.
    \param indices : which markers \e left and \e right show, as indices of the zero-reference markers.
    \param residual : if not null, receives the final RMS pixel error.
    \exception vpProjectiveException on sizes that disagree, a bad index, non-finite values, fewer markers than
    needed (each constrains at most 2 joints' worth of equations), or a minimisation that fails.
  */
  vpColVector inverseKinematics(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                const vpColVector &q0 = vpColVector(),
                                const std::vector<unsigned int> &indices = std::vector<unsigned int>(),
                                double *residual = nullptr) const;
  //@}

  /*! \name The rig moved: prediction error and re-registration (see vpProjectiveRigRegistration) */
  //@{
  /*!
    RMS per coordinate (pixels) of the difference between the measured images \e left, \e right of every marker
    (in the zero reference's order) and the model's predictions at joints \e q (n x 1):
    \f$ \sqrt{\frac{1}{4K} \sum_j \|s_j - \hat s_j(q)\|^2} \f$ over the K markers and their 4 coordinates
    \f$ (u, v, u', v') \f$.
    \exception vpProjectiveException (notInitializedError) before calibrate() or loadModel(); (dimensionError) if a
    marker is missing or the sizes differ; (nonFiniteValueError) on a non-finite value; (pointAtInfinityError) if a
    marker's prediction is on a camera's focal plane.
  */
  double getPredictionError(const vpColVector &q, const std::vector<vpImagePoint> &left,
                            const std::vector<vpImagePoint> &right) const;
  /*!
    Records the images of all zero-reference markers (same order) at joints \e q (n x 1) for the next updateRig().
    Nothing is recorded on error.
    \exception vpProjectiveException (notInitializedError) before calibrate() or loadModel(); (dimensionError) if a
    marker is missing or the sizes differ; (nonFiniteValueError) on a non-finite value; (degenerateConfigurationError)
    if \e q equals (within 1e-6 joint units) the joints of an observation already recorded: move the arm between
    observations.
  */
  void addRigObservation(const vpColVector &q, const std::vector<vpImagePoint> &left,
                         const std::vector<vpImagePoint> &right);
  /*!
    Re-estimates both cameras in the model's projective frame from the observations recorded since the last
    update (at least 3; vpProjectiveRigRegistration::registerRig() with getRigUpdate().getRegistrationMode()), then
    forgets them.
    The arm model (generators, \f$ G \f$, markers) is kept; the rig becomes a general camera pair
    (vpProjectiveStereoRig::isCanonical() false) that saveModel() writes. getRigUpdate().getGeneration() increases by
    one: the servo tasks on this robot then re-express their desired features in the new images. \exception
    vpProjectiveException (notInitializedError) before calibrate() or loadModel(); (notEnoughPointsError) with fewer
    than 3 observations; and those of registerRig(). On failure the model, the rig and the observations are left as they
    were.
  */
  void updateRig();
  /*!
    Refines the last re-registration with more views (the frames of a servo task, see
    vpServoProjective::getRigRefinement(), which calls it): both cameras re-estimated as updateRig() did, from the
    rig before that update, from its observations together with the projective points \e points (4x1 each, model
    frame, where they were seen: \f$ H(q_k) M_i(0) \f$ for a point \f$ M_i(0) \f$ of the last link at the zero
    reference seen at joints \f$ q_k \f$) and their images \e images \f$ (u, v, u', v') \f$ (pixels), same order.
    The observations of that update are kept for the next refinement: each refinement replaces the previous one.
    getRigUpdate().getGeneration() increases by one and the tasks on this robot are told, as by updateRig().
    \exception vpProjectiveException (notInitializedError) before calibrate() or loadModel() or without a successful
    updateRig() since; (dimensionError) if the sizes differ; and those of vpProjectiveRigRegistration::registerRig()
    (a non-finite value, points that do not fit the model). On failure the model, the rig and every observation are
    left as they were.
  */
  void refineRig(const std::vector<Eigen::Vector4d> &points, const std::vector<Eigen::Vector4d> &images);

  /*!
    The rig-registration state: the observations since the last updateRig(), the registration mode, the residual
    of the last update and the generation counters (vpProjectiveRigUpdate).
  */
  const vpProjectiveRigUpdate &getRigUpdate() const { return m_rigUpdate; }
  //! The same, to set the registration mode or forget the observations.
  vpProjectiveRigUpdate &getRigUpdate() { return m_rigUpdate; }

  /*!
    What is told to the tasks on this robot (vpServoProjective::setRobot() attaches its task): the model was replaced
    (calibrate(), loadModel(), an assignment to the robot: \e rigOnly false) or its rig re-registered (updateRig():
    \e rigOnly true), or the robot is destroyed. The robot calls them from the call that changed it; a listener must
    not call back into the robot from them. A new model or rig thus reaches a task through this explicit call, not by
    a task polling the counters of getRigUpdate(). A listener attaches itself (attachTo(), detachFrom()), which
    changes the robot's list of listeners: not from several threads at once.
  */
  class VISP_EXPORT vpListener
  {
  public:
    virtual ~vpListener() = default;
    //! The model (\e rigOnly false) or only its rig (\e rigOnly true) changed.
    virtual void robotModelChanged(bool rigOnly) = 0;
    //! The robot is being destroyed: forget it.
    virtual void robotDestroyed() = 0;

  protected:
    //! Be told of every change of \e robot's model or rig until detachFrom() (attaching twice attaches once).
    void attachTo(const vpProjectiveRobot &robot) { robot.attach(*this); }
    //! Stop being told (nothing if this listener was not attached to \e robot).
    void detachFrom(const vpProjectiveRobot &robot) { robot.detach(*this); }
  };
  //@}

  /*! \name Model file (see vpProjectiveModelFile) */
  //@{
  /*!
    Writes the acquired model to a versioned, checksummed JSON file (e.g. "arm.json"), with the frames of its metric
    self-calibration (see getMetricStereoRig()).
  */
  void saveModel(const std::string &filename) const;
  /*!
    Reads a model written by saveModel(); the frames it holds become calibration frames. On failure the robot keeps
    the model it had.
    \exception vpProjectiveException (fileError) if the file is missing, truncated, corrupted, of another version, or
    inconsistent.
  */
  void loadModel(const std::string &filename);
  //@}

private:
  //! Tells \e listener of every change of the model or rig until detach() (attaching twice attaches once).
  void attach(vpListener &listener) const;
  //! Stops telling \e listener (nothing if it was not attached).
  void detach(vpListener &listener) const;
  //! The frames of the metric self-calibration: those that show the current rig (see getMetricStereoRig()).
  std::vector<vpProjectiveArmAcquisition::vpFrame> selfCalibrationFrames() const;
  //! Takes \e model, calibrated from \e acquisition with these residuals (given to the acquisition), as the robot's
  //! model.
  void adopt(const vpProjectiveArmAcquisition &acquisition, const vpProjectiveArmModel &model, double residual,
             double algebraicResidual);
  //! The model with the rig \e rig (re-registered, RMS error \e rms): a new rig generation; tells no one.
  void adoptRig(const vpProjectiveStereoRig &rig, double rms);
  void checkJoint(unsigned int i, const char *method) const;
  JointVector toJointVector(const vpColVector &q, const char *method) const;

  vpProjectiveArmAcquisition m_acquisition;
  vpProjectiveArmModel m_model;
  bool m_calibrated;
  vpProjectiveRigUpdate m_rigUpdate;

  //! The listeners of attach(): a copy of the robot starts with none; an assignment to the robot tells them (it is
  //! the last member, assigned after the model); the destructor tells them the robot is gone.
  struct vpListeners {
    std::vector<vpListener *> list;
    vpListeners() = default;
    vpListeners(const vpListeners &) : list() {}
    vpListeners &operator=(const vpListeners &)
    {
      notify(false);
      return *this;
    }
    ~vpListeners();
    void notify(bool rigOnly) const;
  };
  mutable vpListeners m_listeners;
};

END_VISP_NAMESPACE

#endif
