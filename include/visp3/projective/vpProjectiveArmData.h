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
  \file vpProjectiveArmData.h
  \brief The kinematics of an arm model at one configuration (vpProjectiveArmData), and the free functions of
  vpProjectiveKinematics that fill and read it.
*/

#ifndef _vpProjectiveArmData_h_
#define _vpProjectiveArmData_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>

BEGIN_VISP_NAMESPACE

class vpProjectiveArmData;

/*!
  The algorithms of the arm floor, as Pinocchio's free functions of (model, data, q): the model
  (vpProjectiveArmModel) is constant and may be shared, the data (vpProjectiveArmData) holds what one configuration
  gives, and every reader of the arm's kinematics (the servo's data, inverse kinematics and hence motion capture, the
  path planner's rehearsal of law (47), vpProjectiveRobot::getImageJacobian()) fills it with forwardKinematics()
  and reads it, instead of computing \f$ H(q) \f$ and the joint motions in passes of its own.
*/
namespace vpProjectiveKinematics
{
/*!
  Fills \e data at the joint values \e q (n x 1, the model's units: radians or the encoder's length unit) of
  \e model in one pass over the joint exponentials (26), (31): the joint motions \f$ \hat H_{k,q} = A_{k-1} \hat H_k
  A_{k-1}^{-1} \f$ (eq. (39)), \f$ H(q) = A_{n-1} \f$ (eq. (34)) and \f$ H(q)^{-1} \f$ (the exponentials of the
  opposite joint values: no matrix inverse). No allocation; sizes are not checked.
*/
VISP_EXPORT void forwardKinematics(const vpProjectiveArmModel &model, vpProjectiveArmData &data,
                                   const vpProjectiveArmModel::JointVector &q);
/*!
  The point Jacobian \f$ J_H(q, M) = [\hat H_{0,q} M \;\cdots\; \hat H_{n-1,q} M] \f$ (4 x n, eqs. (42)-(44)) of the
  point \e M (4x1, its position at the data's q) from the joint motions of the last forwardKinematics():
  \f$ \dot M = J_H \dot q \f$.
*/
VISP_EXPORT void pointJacobian(const vpProjectiveArmModel &model, const vpProjectiveArmData &data,
                               const Eigen::Vector4d &M, vpProjectiveArmModel::PointJacobian &JH);
/*!
  The stereo image Jacobian \f$ J(q, M) \f$ (4 x n, pixels per joint unit, rows \f$ (u, v, u', v') \f$, eqs.
  (45)-(46)) of the point \e M (4x1, its position at the data's q, projective frame of the rig, any scale and sign)
  from the joint motions of the last forwardKinematics(). False if \e M is on a camera's focal plane.
*/
VISP_EXPORT bool imageJacobian(const vpProjectiveArmModel &model, const vpProjectiveArmData &data,
                               const Eigen::Vector4d &M, vpProjectiveArmModel::PointJacobian &J);
/*!
  The images of a point of the moving end given at the zero reference: \f$ M = H(q) X \f$ (4x1) of \e X (4x1, e.g.
  a marker's \f$ M_j(0) \f$), its pixels \e s (4x1, \f$ (u, v, u', v') \f$) and, when \e J is not null, its image
  Jacobian \f$ J(q, M) \f$ (4 x n). False if \e M is on a camera's focal plane (\e s, \e J unspecified).
*/
VISP_EXPORT bool pointImages(const vpProjectiveArmModel &model, const vpProjectiveArmData &data,
                             const Eigen::Vector4d &X, Eigen::Vector4d &s,
                             vpProjectiveArmModel::PointJacobian *J = nullptr);
} // namespace vpProjectiveKinematics

/*!
  \class vpProjectiveArmData
  \ingroup group_projective
  \brief What an arm model gives at one configuration \f$ q \f$, as Pinocchio separates a robot's data from its
  model: \f$ H(q) \f$ and \f$ H(q)^{-1} \f$ (4x4, eq. (34)) and the n joint motions \f$ \hat H_{k,q} \f$ (4x4 each,
  eq. (39), joint numbering), filled by vpProjectiveKinematics::forwardKinematics() in one pass and read by
  vpProjectiveKinematics::imageJacobian() and pointImages().

  The squares \f$ \hat H_i^2 \f$ of the model's generators, constants of the model, are kept between calls and
  recomputed only for a generator that differs from the one they were computed from (another model, a model that
  changed), so one data object may follow a model that is re-acquired. Fixed-size storage: nothing is allocated.
  getPassCount() counts the forwardKinematics() calls, so that a test can check that a reader computes the
  kinematics once per configuration.

  \code
  vpProjectiveArmData data;
  vpProjectiveKinematics::forwardKinematics(model, data, q);
  Eigen::Vector4d s;
  vpProjectiveArmModel::PointJacobian J;
  vpProjectiveKinematics::pointImages(model, data, model.markers()[0], s, &J); // marker 0's pixels and J(q, M)
  \endcode
*/
class VISP_EXPORT vpProjectiveArmData
{
public:
  typedef vpProjectiveArmModel::JointVector JointVector; //!< Joint values (n x 1: rad or length unit per joint).

  //! No configuration yet: \f$ H = I \f$, no joint.
  vpProjectiveArmData();

  //! The joint values \f$ q \f$ (n x 1) of the last forwardKinematics().
  const JointVector &getJoints() const { return m_q; }
  //! \f$ H(q) \f$ (4x4, eq. (34)): the displacement of the moving end from the zero reference.
  const Eigen::Matrix4d &getDisplacement() const { return m_H; }
  //! \f$ H(q)^{-1} \f$ (4x4), the product of the joint exponentials of \f$ -(q - q_{ref}) \f$.
  const Eigen::Matrix4d &getDisplacementInverse() const { return m_Hinv; }
  //! The joint motions \f$ \hat H_{k,q} \f$ (4x4), n of them in joint numbering.
  const Eigen::Matrix4d *getJointMotions() const { return m_HhatKq; }
  //! Number of forwardKinematics() calls on this object.
  unsigned long getPassCount() const { return m_passCount; }

private:
  friend void vpProjectiveKinematics::forwardKinematics(const vpProjectiveArmModel &model, vpProjectiveArmData &data,
                                                        const vpProjectiveArmModel::JointVector &q);

  JointVector m_q;
  Eigen::Matrix4d m_H;
  Eigen::Matrix4d m_Hinv;
  Eigen::Matrix4d m_HhatKq[vpProjectiveArmModel::maxJoints];
  Eigen::Matrix4d m_Hhat[vpProjectiveArmModel::maxJoints];  // the generators that m_Hhat2 was computed from
  Eigen::Matrix4d m_Hhat2[vpProjectiveArmModel::maxJoints]; // their squares
  unsigned int m_nbGenerators;
  unsigned long m_passCount;
};

END_VISP_NAMESPACE

#endif
