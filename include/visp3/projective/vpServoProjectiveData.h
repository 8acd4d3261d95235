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
  \file vpServoProjectiveData.h
  \brief What one control iteration of vpServoProjective computes at one configuration, computed once and read by
  every part of the servo.
*/

#ifndef _vpServoProjectiveData_h_
#define _vpServoProjectiveData_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmData.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoNormalEquations.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoProjectiveData
  \ingroup group_projective
  \brief The per-configuration data of a servo iteration, as Pinocchio separates a robot's data from its model: the
  model (vpProjectiveArmModel, its rig included) is constant and shared, this object holds what one configuration
  \f$ q \f$ and one set of measured features give, computed once per iteration and read by every part of the servo
  (the control law, vpServoDampedLeastSquares, vpServoFeatureHealth, vpServoModelMismatch,
  vpServoJointLimitAvoidance, vpServoSettling, the path following). No part computes \f$ H(q) \f$ or triangulates a
  feature on its own.

  - computeKinematics(): the arm's data at \f$ q \f$ (vpProjectiveArmData, filled by
    vpProjectiveKinematics::forwardKinematics() in one pass: the joint motions that the image Jacobian (46) needs,
    \f$ H(q) \f$ and \f$ H(q)^{-1} \f$);
  - computeFeature(): the feature's value \f$ s_i = (u, v, u', v') \f$ (pixels), and when it is finite its point
    \f$ M_i \f$ (4x1, projective frame of the rig, linear triangulation) and that point at the zero reference
    \f$ M_{0,i} = H(q)^{-1} M_i \f$ (4x1, unit norm);
  - the task: \f$ J \f$ (4N x n, pixels per joint unit; zero rows for features set aside), \f$ e = s - s^* \f$
    (4N, pixels), the normal equations \f$ J^T J \f$, \f$ J^T e \f$ and their factorisations
    (vpServoNormalEquations: each computed once, read by the law's parts), filled by
    vpServoProjective::computeControlLaw().

  vpServoProjectiveReport::getData() (vpServoProjective::getReport()) gives the data of the last successful iteration.
  No allocation once the sizes are known. getDisplacementCount() counts the \f$ H(q) \f$ computed since the last
  computeKinematics() (1 after an iteration), so that a test can check that none is computed twice.
*/
class VISP_EXPORT vpServoProjectiveData
{
public:
  typedef vpProjectiveArmModel::JointVector JointVector; //!< Joint values (n x 1: rad or m per joint).
  typedef vpProjectiveArmModel::JointMatrix JointMatrix; //!< Matrices over the joints (n x n at most).

  vpServoProjectiveData();

  /*! \name Computation (the servo's order: kinematics, then each feature) */
  //@{
  /*!
    The joint motions, \f$ H(q) \f$ and \f$ H(q)^{-1} \f$ at \e q (n x 1, the model's joint values: radians or the
    encoder's length unit) of \e model, for \e features features (their values are then unset until computeFeature()).
    Sizes are not checked.
  */
  void computeKinematics(const vpProjectiveArmModel &model, const JointVector &q, unsigned int features);
  /*!
    Feature \e i of value \e s (4x1, pixels): its point \f$ M_i \f$ and \f$ M_{0,i} = H(q)^{-1} M_i \f$ when \e s is
    finite (hasPoint()). Call after computeKinematics(); \e i is not checked.
  */
  void computeFeature(const vpProjectiveArmModel &model, unsigned int i, const Eigen::Vector4d &s);
  //@}

  /*! \name Kinematics */
  //@{
  //! The arm's data at the q of the last computeKinematics(): \f$ H(q) \f$, \f$ H(q)^{-1} \f$, the joint motions.
  const vpProjectiveArmData &getArmData() const { return m_arm; }
  //! The joint values (n x 1) of the last computeKinematics().
  const JointVector &getJoints() const { return m_arm.getJoints(); }
  //! \f$ H(q) \f$ (4x4, eq. (34)).
  const Eigen::Matrix4d &getDisplacement() const { return m_arm.getDisplacement(); }
  //! \f$ H(q)^{-1} \f$ (4x4), the product of the joint exponentials of \f$ -q \f$.
  const Eigen::Matrix4d &getDisplacementInverse() const { return m_arm.getDisplacementInverse(); }
  //! Number of \f$ H(q) \f$ computed since the last computeKinematics() began (1 after it).
  unsigned int getDisplacementCount() const { return static_cast<unsigned int>(m_arm.getPassCount() - m_passesBefore); }
  /*!
    The images \f$ \hat s = (u, v, u', v') \f$ (4x1, pixels) of \f$ H(q) X \f$, \e X (4x1, any scale and sign) a point
    at the zero reference: vpProjectiveStereoRig::project(getDisplacement() * X, s) by the rig of the model given to
    the last computeKinematics() (which must still exist). The predictions of the feature health and of the
    model-mismatch check. False, \e s unspecified, on a camera's focal plane, for a non-finite image or before any
    computeKinematics().
  */
  bool predict(const Eigen::Vector4d &X, Eigen::Vector4d &s) const;
  //@}

  /*! \name Features (index i in addFeature() order) */
  //@{
  //! Number of features of the last computeKinematics().
  unsigned int getNumberOfFeatures() const { return m_nbFeatures; }
  //! \f$ s_i \f$ (4x1, pixels).
  const Eigen::Vector4d &getFeature(unsigned int i) const { return m_s[i]; }
  //! True if \f$ s_i \f$ is finite: getPoint() and getZeroPoint() are set.
  bool hasPoint(unsigned int i) const { return m_hasPoint[i] != 0; }
  //! \f$ M_i \f$ (4x1, projective frame of the rig): vpProjectiveStereoRig::triangulateLinear() of \f$ s_i \f$.
  const Eigen::Vector4d &getPoint(unsigned int i) const { return m_M[i]; }
  //! \f$ M_{0,i} = H(q)^{-1} M_i \f$ (4x1, unit norm): the point at the zero reference.
  const Eigen::Vector4d &getZeroPoint(unsigned int i) const { return m_M0[i]; }
  //@}

  /*! \name Task (filled by vpServoProjective) */
  //@{
  //! \f$ J \f$ (4N x n, pixels per joint unit), zero rows for the features set aside.
  const Eigen::MatrixXd &getTaskJacobian() const { return m_J; }
  //! \f$ e = s - s^* \f$ (4N, pixels), zero rows for the features set aside.
  const Eigen::VectorXd &getError() const { return m_e; }
  //! \f$ J^T J \f$ (n x n), \f$ J^T e \f$ (n x 1) and their factorisations, shared by the parts of the law.
  const vpServoNormalEquations &getNormalEquations() const { return m_normal; }
  //! Number of features used by the task.
  unsigned int getNumberOfActiveFeatures() const { return m_nbActive; }
  //@}

private:
  friend class vpServoProjective; // fills the task part

  vpProjectiveArmData m_arm;
  const vpProjectiveStereoRig *m_rig; // the model's rig of the last computeKinematics(), for predict()
  unsigned long m_passesBefore;       // m_arm's pass count when the last computeKinematics() began
  unsigned int m_nbFeatures;
  std::vector<Eigen::Vector4d> m_s, m_M, m_M0;
  std::vector<char> m_hasPoint;
  Eigen::MatrixXd m_J;
  Eigen::VectorXd m_e;
  vpServoNormalEquations m_normal;
  double m_errorNorm; // ||e|| in the unit of vpServoProjective::setErrorUnit()
  unsigned int m_nbActive;
};

END_VISP_NAMESPACE

#endif
