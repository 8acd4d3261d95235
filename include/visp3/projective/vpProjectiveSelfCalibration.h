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
  \file vpProjectiveSelfCalibration.h
  \brief Metric self-calibration of a stereo rig and an arm from the projective model acquired with them.
*/

#ifndef _vpProjectiveSelfCalibration_h_
#define _vpProjectiveSelfCalibration_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <ostream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveArmModel.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveSelfCalibration
  \ingroup group_projective
  \brief The metric stereo rig and the arm's joint axes that a vpProjectiveArmModel holds without anybody having
  calibrated anything.

  The acquisition's bundle adjustment shares one \f$ G \f$ between all generators, \f$ \hat H_i = G^{-1} \hat T_i G
  \f$ with metric twists \f$ \hat T_i \f$: \f$ G \f$ is \f$ H_{PE} \f$ up to a similarity, so it maps the projective
  frame to a metric frame \f$ E' \f$ that differs from the left camera's frame by a rotation, a translation and a
  scale. In that frame the two cameras are
  \f[ P G^{-1} \simeq K_l [R_l \,|\, t_l], \qquad P' G^{-1} \simeq K_r [R_r \,|\, t_r], \f]
  and an RQ decomposition of each left 3x3 block gives the intrinsics \f$ K \f$ (upper triangular with the skew,
  \f$ K_{33} = 1 \f$, positive focal lengths) and the rotations; the sign of each camera matrix is the one that puts
  the markers in front of it, and a mirrored \f$ E' \f$ (an improper \f$ R \f$) is turned into a right-handed one. The
  right camera's pose in the left one is then
  \f[ {}^l M_r = \begin{bmatrix} R_l R_r^T & t_l - R_l R_r^T t_r \\ 0 & 1 \end{bmatrix}, \qquad X_l = {}^l M_r X_r,
  \f]
  its translation known up to the scale of \f$ E' \f$, which a prismatic joint's encoder fixes (its twist is the
  motion per encoder unit: the translation comes out in encoder units, least squares over the prismatic joints), or
  a known distance between two markers, or else the baseline is given unit length.

  That read-out (the static functions) is only as accurate as the acquisition. An object of this class goes further:
  a metric bundle adjustment over every stereo image of the markers at known joint readings (the acquisition's and
  any number of frames at other configurations, vpProjectiveArmAcquisition::addCalibrationFrame()), started from the
  read-out. Its parameters, all in the left camera's frame at the zero reference:
  - both cameras' intrinsics \f$ (f_x, f_y, s, u_0, v_0) \f$, skew included: \f$ K = [f_x\ s\ u_0; 0\ f_y\ v_0;
    0\ 0\ 1] \f$;
  - the right camera's orientation \f$ {}^lR_r \f$ and centre \f$ b \f$ (\f$ {}^lM_r = [{}^lR_r\ b; 0\ 1] \f$);
  - each joint's screw axis: a unit direction and, revolute, a point of the axis (2 coordinates in a plane across
    it: a line has 4 degrees of freedom);
  - each marker's point \f$ X_j \f$ at the zero reference.
  Marker j seen at readings q is at \f$ T(q - q_{ref}) X_j \f$, \f$ T \f$ the product of the joints'
  exponentials (vpProjectiveArmModel's order), and images at \f$ K_l [I | 0] \f$ and \f$ K_r\, {}^rM_l \f$;
  the adjustment minimises the pixel errors of every observation (Ceres, Levenberg-Marquardt). Gauge: the left
  camera's frame is the reference, so nothing but the scale is free; it is fixed by the prismatic joints (their
  motion per encoder unit has unit length: lengths come out in the encoders' unit) or, when the arm has none, by a
  unit baseline. setScale() then expresses the lengths in another unit.

  Each parameter comes with its standard deviation: the covariance \f$ \hat\sigma^2 (J^T J)^{-1} \f$ at the
  solution (ceres::Covariance), with the noise level \f$ \hat\sigma^2 = \sum r^2 / (m - p) \f$ estimated from the m
  residuals and p free parameters. A rank-deficient Jacobian (a joint that never moved, frames that leave a
  parameter free) gives no covariance: isObservable() is then false and every standard deviation infinite.

  What makes the intrinsics, the principal point above all, observable: views of the markers spread over the images
  and turned about several axes (the arm's joints at several configurations each), not many views of the same
  configuration. suggestConfigurations() ranks random configurations by how much their images would shrink the
  largest uncertainty (getLargestUncertainty()), using the covariance. See the page \ref page_self_calibration.
*/
class VISP_EXPORT vpProjectiveSelfCalibration
{
public:
  //! How the metric scale of the translations is fixed.
  enum vpScale {
    SCALE_FROM_PRISMATIC_JOINTS, //!< Encoder units of the prismatic joints (least squares over them).
    SCALE_UNIT_BASELINE,         //!< The baseline has length 1.
    SCALE_MARKER_DISTANCE        //!< Two markers a known distance apart.
  };

  /*!
    The metric rig of \e model.
    \param model : an acquired model.
    \param Kl, Kr : intrinsics of the left and right cameras (3x3, pixels, skew included, \f$ K_{33} = 1 \f$).
    \param lMr : pose of the right camera in the left camera's frame (4x4 rigid, \f$ X_l = {}^l M_r X_r \f$).
    \param scale : how the translation's unit is fixed; SCALE_FROM_PRISMATIC_JOINTS falls back to a unit baseline
    when the arm has no prismatic joint.
    \param markerA, markerB, distance : with SCALE_MARKER_DISTANCE, two marker indices of the model and their
    distance (any positive length unit, which the translation then takes).
    \return the scale applied: lengths of the metric frame of \e model (vpProjectiveArmModel::projectiveToMetric())
    times this value are in the unit of \e lMr.
    \exception vpProjectiveException (notInitializedError) for an empty model; (invalidValueError, dimensionError)
    for a bad marker index or distance; (degenerateConfigurationError) if a camera matrix is singular in the metric
    frame or the baseline is zero.
  */
  static double metricStereoRig(const vpProjectiveArmModel &model, Eigen::Matrix3d &Kl, Eigen::Matrix3d &Kr,
                                Eigen::Matrix4d &lMr, vpScale scale = SCALE_FROM_PRISMATIC_JOINTS,
                                unsigned int markerA = 0, unsigned int markerB = 1, double distance = 0.0);

  /*!
    The joints' axes in the left camera's frame: for each joint a unit direction (3x1: a revolute joint's axis, or a
    prismatic joint's direction of motion) and a point (3x1: on a revolute joint's axis, in the unit of
    metricStereoRig() with the same scale arguments; the origin for a prismatic joint).
    \exception vpProjectiveException as metricStereoRig().
  */
  static void jointAxes(const vpProjectiveArmModel &model, std::vector<Eigen::Vector3d> &direction,
                        std::vector<Eigen::Vector3d> &point, vpScale scale = SCALE_FROM_PRISMATIC_JOINTS,
                        unsigned int markerA = 0, unsigned int markerB = 1, double distance = 0.0);

  /*! \name The metric bundle adjustment */
  //@{
  //! The standard deviations of the estimates (1 sigma), in the units of the getters.
  struct vpUncertainty {
    Eigen::Matrix<double, 5, 1> left;   //!< Left camera: fx, fy, skew, u0, v0 (px).
    Eigen::Matrix<double, 5, 1> right;  //!< Right camera: fx, fy, skew, u0, v0 (px).
    Eigen::Vector3d rotation;           //!< The rotation of lMr, a rotation vector in the left camera's axes (rad).
    Eigen::Vector3d translation;        //!< The translation of lMr (the length unit).
    double baselineDirection;           //!< The baseline's direction (rad, along its least determined axis).
    double baselineLength;              //!< The baseline's length (the length unit; 0 when the unit is the baseline).
    std::vector<double> jointDirection; //!< Per joint, its direction (rad, least determined axis).
    std::vector<double> jointPoint;     //!< Per revolute joint, its axis' position (the length unit; 0 prismatic).
  };

  //! No calibration (isCalibrated() false).
  vpProjectiveSelfCalibration();
  /*!
    The metric bundle adjustment of \e model's cameras and arm over the stereo images \e frames (each at the joints'
    encoder readings, markers in the model's order: vpProjectiveArmAcquisition::getFrames()), started from the
    read-out of \e model's \f$ G \f$ (metricStereoRig()). Without any observation in \e frames (a model read from
    an old file), the result is that read-out, without uncertainty.
    \exception vpProjectiveException (notInitializedError) for an empty model; (dimensionError) if a frame has not n
    readings or not one image per marker; (degenerateConfigurationError) as metricStereoRig();
    (estimationFailedError) if the adjustment fails (a frame's markers on a camera's focal plane).
  */
  vpProjectiveSelfCalibration(const vpProjectiveArmModel &model,
                              const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames);
  //! True once computed by the constructor from a model.
  bool isCalibrated() const { return m_calibrated; }
  /*!
    The unit of the lengths the getters give (default SCALE_FROM_PRISMATIC_JOINTS: the encoders' unit, or a unit
    baseline without a prismatic joint); with SCALE_MARKER_DISTANCE the distance \e distance between the markers
    \e markerA and \e markerB (the scale's own uncertainty then enters the baseline's, not the joints').
    \exception vpProjectiveException (notInitializedError) before a calibration; (dimensionError, invalidValueError)
    for a bad marker index or distance. The scale is unchanged on error.
  */
  void setScale(vpScale scale, unsigned int markerA = 0, unsigned int markerB = 1, double distance = 0.0);
  /*!
    The metric rig: both cameras' intrinsics \e Kl, \e Kr (3x3, skew included, \f$ K_{33} = 1 \f$) and the right
    camera's pose in the left camera's frame \e lMr (\f$ X_l = {}^lM_r X_r \f$).
    \exception vpProjectiveException (notInitializedError) before a calibration.
  */
  void getMetricStereoRig(Eigen::Matrix3d &Kl, Eigen::Matrix3d &Kr, Eigen::Matrix4d &lMr) const;
  /*!
    The joints' screw axes in the left camera's frame at the zero reference: per joint a unit direction, and a point
    of a revolute joint's axis (the origin for a prismatic joint). \exception vpProjectiveException as above.
  */
  void getJointAxes(std::vector<Eigen::Vector3d> &direction, std::vector<Eigen::Vector3d> &point) const;
  //! The markers' points at the zero reference, left camera's frame. \exception vpProjectiveException as above.
  std::vector<Eigen::Vector3d> getMarkers() const;
  //! The standard deviations of every estimate. \exception vpProjectiveException as above.
  const vpUncertainty &getUncertainty() const;
  //! True if the covariance exists (every parameter determined by the frames); false: infinite deviations.
  bool isObservable() const { return m_observable; }
  //! The image noise estimated from the residuals, \f$ \hat\sigma \f$ (px per coordinate).
  double getNoiseLevel() const { return m_noise; }
  //! RMS residual per coordinate (px).
  double getResidual() const { return m_residual; }
  //! Number of frames with an observation.
  unsigned int getNumberOfFrames() const { return m_frameCount; }
  //! Number of marker observations (each 4 pixel coordinates).
  unsigned int getNumberOfObservations() const { return m_observations; }
  /*!
    The largest uncertainty, made dimensionless so that focal lengths, principal points and angles compare: each
    camera's \f$ \sigma_{f_x}/f_x \f$, \f$ \sigma_{f_y}/f_y \f$, \f$ \sigma_s/f_x \f$, \f$ \sigma_{u_0}/f_x
    \f$, \f$ \sigma_{v_0}/f_y \f$ (the angles they subtend), the rotation's and the baseline direction's (rad) and
    the baseline length's relative deviation; \e what, if not null, receives its name (e.g. "left v0").
    \exception vpProjectiveException as above.
  */
  double getLargestUncertainty(std::string *what = nullptr) const;
  /*!
    The next configurations to show the markers at: among \e candidates random readings within [\e qmin, \e qmax]
    (n x 1 each, seeded by \e seed) whose predicted markers are all 10 px inside both \e width x \e height images,
    the \e count chosen one after the other, each the one whose images would shrink the largest uncertainty
    (getLargestUncertainty()) most given the frames and those chosen before: the covariance updated with the
    candidate's information at the estimated noise level, \f$ \Sigma - \Sigma J^T (\hat\sigma^2 I + J \Sigma
    J^T)^{-1} J \Sigma \f$ (J its pixels' Jacobian). \e largest, if not null, receives the predicted largest
    uncertainty after each choice.
    \exception vpProjectiveException as above; (dimensionError, invalidValueError) on bad bounds;
    (degenerateConfigurationError) if no covariance (isObservable() false) or no candidate keeps the markers in view.
  */
  std::vector<vpColVector> suggestConfigurations(unsigned int count, const vpColVector &qmin, const vpColVector &qmax,
                                                 unsigned int width, unsigned int height,
                                                 std::vector<double> *largest = nullptr, unsigned int candidates = 200,
                                                 unsigned int seed = 1) const;
  //! Writes every estimate with its standard deviation, a line each (the report of `visp-projective report`).
  void print(std::ostream &os) const;
  //@}

private:
  void derive();

  bool m_calibrated;
  std::vector<vpProjectiveJoint::vpJointType> m_types;
  vpProjectiveArmModel::vpRigMounting m_mounting;
  vpProjectiveArmModel::JointVector m_qRef;
  std::vector<vpProjectiveArmAcquisition::vpFrame> m_frames;
  // The estimate in the adjustment's unit, and the covariance of its parameters (see the source's layout).
  Eigen::Matrix<double, 5, 1> m_left, m_right;
  Eigen::Matrix3d m_lRr;
  Eigen::Vector3d m_b;
  std::vector<Eigen::Vector3d> m_axis, m_point, m_markers;
  Eigen::MatrixXd m_covariance;
  bool m_observable;
  double m_noise, m_residual;
  unsigned int m_frameCount, m_observations;
  // The scale of the getters: lengths of the adjustment times m_unit.
  vpScale m_scale;
  unsigned int m_markerA, m_markerB;
  double m_distance, m_unit;
  vpUncertainty m_uncertainty;
};

END_VISP_NAMESPACE

#endif
