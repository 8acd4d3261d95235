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
  \file vpProjectiveArmModel.h
  \brief The projective kinematic model of a serial arm: generators, forward kinematics, joint motions and Jacobians
  in the projective frame of a weakly calibrated stereo rig.
*/

#ifndef _vpProjectiveArmModel_h_
#define _vpProjectiveArmModel_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>

#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveArmModel
  \ingroup group_projective
  \brief The acquired model of a serial chain of \f$ n \f$ revolute or prismatic joints, expressed only in the
  projective frame \f$ \mathcal{P} \f$ of an uncalibrated stereo rig (Ruf & Horaud, sections 5 and 6), and the
  kinematics it gives.

  As Pinocchio separates a robot's model from the algorithms that use it, this class holds the model and nothing of
  how it was obtained: vpProjectiveArmAcquisition computes it from images, vpProjectiveModelFile reads and writes it,
  vpProjectiveInverseKinematics inverts it, and vpProjectiveRobot gathers them behind one facade. Every method is
  const and writes only into its arguments: one model may serve several threads.

  <b>Parametrisation.</b> A 4x4 matrix \f$ G \f$ maps the projective frame to a metric one (it is \f$ H_{PE} \f$ up
  to a similarity). Joint \f$ i \f$ has the metric twist \f$ \hat T_i \f$ (vpProjectiveJoint::twist(): a unit axis
  \f$ \omega_i \f$ through a point \f$ p_i \f$ for a revolute joint, the motion \f$ d_i \f$ per unit of joint value
  for a prismatic one), and its projective generator is
  \f[ \hat H_i = G^{-1} \hat T_i G \quad (4 \times 4), \f]
  a p-rotation (\f$ \hat H^3 = -\hat H \f$) or a p-translation (\f$ \hat H^2 = 0 \f$) generator. The markers of the
  last link (eye-to-hand) or of the static object (eye-in-hand) are the projective points \f$ M_j(0) \f$ (4x1, unit
  norm from the acquisition) at the zero reference.

  <b>Joint values.</b> \f$ q \f$ (n x 1) holds the joints' encoder readings: radians for a revolute joint, the
  encoder's length unit for a prismatic one, joints indexed \f$ 0 \ldots n-1 \f$ from the robot's base. The zero
  reference is at \f$ q_{ref} \f$ (zeroReferenceJoints(), 0 unless the acquisition recorded it), and the model's
  motions are those of \f$ \delta q = q - q_{ref} \f$.

  <b>Kinematics.</b> The last link (eye-to-hand) moves relative to the zero reference by the product of exponentials
  (34),
  \f[ H(q) = \exp(\delta q_0 \hat H_0) \cdots \exp(\delta q_{n-1} \hat H_{n-1}), \qquad M(q) = H(q)\, M(0), \f]
  the chain's base being the end that holds the rig (eye-in-hand: the hand, so the product runs from joint \f$ n-1
  \f$ down to joint 0). With \f$ A_k \f$ the product of the first \f$ k+1 \f$ factors of the chain (\f$ A_{-1} = I
  \f$), the joint at position \f$ k \f$ of the chain moves with \f$ \hat H_{k,q} = A_{k-1} \hat H_k A_{k-1}^{-1} \f$
  (39), and a point \f$ M \f$ of the moving end has the point Jacobian (42)-(44), 4 x n,
  \f[ J_H(q, M) = [\hat H_{0,q} M \;\cdots\; \hat H_{n-1,q} M], \f]
  and the stereo image Jacobian (45)-(46), 4 x n with rows \f$ (u, v, u', v') \f$ in pixels,
  \f[ J(q, M) = \begin{bmatrix} J_C(P M)\, P \\ J_C(P' M)\, P' \end{bmatrix} J_H(q, M), \qquad
      J_C(m) = \begin{bmatrix} 1/m_3 & 0 & -m_1/m_3^2 \\ 0 & 1/m_3 & -m_2/m_3^2 \end{bmatrix}, \f]
  invariant to the scale and sign of \f$ M \f$. The joint motions and both Jacobians at a configuration are computed by
  the free functions of vpProjectiveKinematics into a vpProjectiveArmData (model / data / algorithms, as in
  Pinocchio). The methods take Eigen types and allocate nothing: they serve the control loop. vpProjectiveRobot
  offers the same with ViSP types and checked arguments.
*/
class VISP_EXPORT vpProjectiveArmModel
{
public:
  /*!
    Where the rig is. The joints keep the robot's own numbering (0 at the robot base) in both cases; only the order
    of the product of exponentials (34) changes, since the base of the chain is the end that holds the rig.
  */
  enum vpRigMounting {
    EYE_TO_HAND, //!< Rig fixed in the workspace, markers on the last link: \f$ H(q) = \exp(\delta q_0 \hat H_0)
                 //!< \cdots \exp(\delta q_{n-1} \hat H_{n-1}) \f$.
    EYE_IN_HAND  //!< Rig on the last link, markers static: the hand is the base, \f$ H(q) = \exp(\delta q_{n-1}
                 //!< \hat H_{n-1}) \cdots \exp(\delta q_0 \hat H_0) \f$.
  };

  //! Largest number of joints: fixed-size storage keeps the control loop free of allocations.
  static const unsigned int maxJoints = 16;
  //! Joint values (n x 1) without heap allocation.
  typedef Eigen::Matrix<double, Eigen::Dynamic, 1, 0, maxJoints, 1> JointVector;
  //! An n x n matrix without heap allocation.
  typedef Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, 0, maxJoints, maxJoints> JointMatrix;
  //! A 4 x n Jacobian without heap allocation.
  typedef Eigen::Matrix<double, 4, Eigen::Dynamic, 0, 4, maxJoints> PointJacobian;

  //! An empty model (no joint).
  vpProjectiveArmModel();
  /*!
    A model from its metric parametrisation (see the class documentation).
    \param types : the kinds of the \f$ n \f$ joints, base to tip (1 to maxJoints).
    \param mounting : where the rig is.
    \param rig : the weakly calibrated rig whose projective frame the model lives in.
    \param G : \f$ G \f$ (4x4, invertible), projective frame to metric frame.
    \param axis : per joint, the unit axis \f$ \omega_i \f$ (revolute) or the motion \f$ d_i \f$ per joint unit
    (prismatic), metric frame of \e G (3x1).
    \param point : per joint, a point \f$ p_i \f$ of the axis (revolute; unused for prismatic), metric frame (3x1).
    \param markers : the markers' projective points \f$ M_j(0) \f$ at the zero reference (4x1, any non-zero scale:
    the acquisition gives them unit norm).
    \param qRef : the joint values at the zero reference (n x 1); empty for zeros.
    \exception vpProjectiveException (dimensionError, invalidValueError, nonFiniteValueError,
    degenerateConfigurationError, notInitializedError) if the sizes disagree, a value is not finite, a revolute axis
    is not of unit norm, G is singular, a marker is the zero vector or the rig has no fundamental matrix.
  */
  vpProjectiveArmModel(const std::vector<vpProjectiveJoint::vpJointType> &types, vpRigMounting mounting,
                       const vpProjectiveStereoRig &rig, const Eigen::Matrix4d &G,
                       const std::vector<Eigen::Vector3d> &axis, const std::vector<Eigen::Vector3d> &point,
                       const std::vector<Eigen::Vector4d> &markers, const JointVector &qRef = JointVector());

  /*! \name The model */
  //@{
  //! Number of joints \e n.
  unsigned int getNumberOfJoints() const { return static_cast<unsigned int>(m_types.size()); }
  //! Kind of joint \e i (no index check).
  vpProjectiveJoint::vpJointType jointType(unsigned int i) const { return m_types[i]; }
  //! The kinds of all joints, base to tip.
  const std::vector<vpProjectiveJoint::vpJointType> &jointTypes() const { return m_types; }
  //! Where the rig is mounted.
  vpRigMounting getRigMounting() const { return m_mounting; }
  //! The rig whose projective frame the model lives in.
  const vpProjectiveStereoRig &getStereoRig() const { return m_rig; }
  //! \f$ G \f$ (4x4): projective frame to metric frame, \f$ H_{PE} \f$ up to a similarity.
  const Eigen::Matrix4d &projectiveToMetric() const { return m_G; }
  //! \f$ G^{-1} \f$ (4x4).
  const Eigen::Matrix4d &metricToProjective() const { return m_Ginv; }
  //! Axis \f$ \omega_i \f$ (revolute, unit) or motion \f$ d_i \f$ (prismatic) of joint \e i, metric frame (no check).
  const Eigen::Vector3d &axis(unsigned int i) const { return m_axis[i]; }
  //! A point \f$ p_i \f$ of the axis of revolute joint \e i, metric frame (no check; unused for prismatic joints).
  const Eigen::Vector3d &point(unsigned int i) const { return m_point[i]; }
  //! Metric twist \f$ \hat T_i \f$ (4x4 se(3)) of joint \e i (no index check).
  Eigen::Matrix4d twist(unsigned int i) const;
  //! Generator \f$ \hat H_i = G^{-1} \hat T_i G \f$ (4x4) of joint \e i (no index check).
  const Eigen::Matrix4d &generator(unsigned int i) const { return m_Hhat[i]; }
  //! The markers' projective points \f$ M_j(0) \f$ (4x1) at the zero reference.
  const std::vector<Eigen::Vector4d> &markers() const { return m_M0; }
  /*!
    The marker a feature is, if any: the index \f$ j \f$ of the marker whose predicted pixels
    \f$ \pi(H M_j(0)) \f$ at the displacement \e H (4x4, e.g. displacement(q)) are within \e pixels (RMS over
    \f$ (u, v, u', v') \f$) of the feature's pixels \e s, every other marker being more than twice as far; -1 if
    none. A feature that is a marker gets that marker's point, which the acquisition placed from all its images, in
    place of one stereo pair's triangulation (vpProjectivePathPlanner, vpServoModelMismatch). The default 2 px is
    several times a tracker's noise and the model's prediction error, a fraction of the markers' spacing in the image.
  */
  int matchMarker(const Eigen::Matrix4d &H, const Eigen::Vector4d &s, double pixels = 2.0) const;
  //! Joint values \f$ q_{ref} \f$ (n x 1) at the zero reference.
  const JointVector &zeroReferenceJoints() const { return m_qRef; }
  /*!
    The plane at infinity \f$ \pi \f$ (4x1) of the projective frame, the last row of \f$ G \f$: \f$ \pi^T M = 0 \f$
    for the points at infinity, and \f$ \pi^T H = \pi^T \f$ for every p-displacement \f$ H = G^{-1} T G \f$.
  */
  Eigen::Vector4d planeAtInfinity() const { return m_G.row(3).transpose(); }
  /*!
    Orbit height (15)-(16) \f$ \rho = \pi^T M \f$ of a projective point \e M (4x1): \f$ \rho N = G M \f$ with
    \f$ N \f$ of last coordinate 1. It does not change when the point moves rigidly (\f$ \rho(H M) = \rho(M) \f$),
    and relates its projective velocity to its metric one: \f$ \dot M = \rho\, G^{-1} \dot N \f$.
  */
  double orbitHeight(const Eigen::Vector4d &M) const { return m_G.row(3).dot(M); }
  //@}

  /*! \name Kinematics (Eigen types, no allocation, no argument check) */
  //@{
  //! \f$ \exp(\delta \hat H_i) \f$ (4x4), joint \e i moved by \e delta from any position: eq. (26) or (31).
  Eigen::Matrix4d jointExp(unsigned int i, double delta) const;
  /*!
    \f$ H(q) \f$ (4x4), the displacement of the moving end from the zero reference, eq. (34). For the joint motions
    (39) and the Jacobians (42)-(46) at q as well, vpProjectiveKinematics::forwardKinematics() fills a
    vpProjectiveArmData with all of them in one pass.
  */
  Eigen::Matrix4d displacement(const JointVector &q) const;
  /*!
    Predicted pixels \f$ s = (u, v, u', v') \f$ of marker \e j after the displacement \e H (4x4, from displacement()):
    the images of \f$ H M_j(0) \f$. False if the marker is then on a camera's focal plane.
  */
  bool predictMarker(unsigned int j, const Eigen::Matrix4d &H, Eigen::Vector4d &s) const;
  /*!
    Predicted images of marker \e j at the joint values \e q (n x 1; ViSP types, checked): predictMarker() at
    displacement(q), \f$ P H(q) M_j(0) \f$ and \f$ P' H(q) M_j(0) \f$.
    \exception vpProjectiveException (dimensionError) on a bad marker index or a \e q of another size;
    (nonFiniteValueError) on a non-finite \e q; (pointAtInfinityError) if the marker lies on a camera's focal plane
    at \e q.
  */
  void projectMarker(unsigned int j, const vpColVector &q, vpImagePoint &ipLeft, vpImagePoint &ipRight) const;
  //@}

private:
  //! Joint index at position k of the product of exponentials, base of the chain (the rig's end) first.
  unsigned int chainJoint(unsigned int k) const
  {
    return m_mounting == EYE_TO_HAND ? k : static_cast<unsigned int>(m_types.size()) - 1 - k;
  }

  std::vector<vpProjectiveJoint::vpJointType> m_types;
  vpRigMounting m_mounting;
  vpProjectiveStereoRig m_rig;
  Eigen::Matrix4d m_G;
  Eigen::Matrix4d m_Ginv;
  std::vector<Eigen::Vector3d> m_axis;
  std::vector<Eigen::Vector3d> m_point;
  std::vector<Eigen::Matrix4d> m_Hhat;
  std::vector<Eigen::Vector4d> m_M0;
  JointVector m_qRef;
};

END_VISP_NAMESPACE

#endif
