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
  \file vpSimulatorArm.h
  \brief A metric serial arm with markers on its last link: the ground truth behind tutorials and tests.
*/

#ifndef _vpSimulatorArm_h_
#define _vpSimulatorArm_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/core/vpMatrix.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpSimulatorArm
  \ingroup group_projective_simulator
  \brief A serial chain of revolute and prismatic joints given by standard Denavit-Hartenberg parameters, carrying
  marker points on its last link.

  Frames: \c w the world, \c b the arm base (\c wMb), \c e the last link, \c t the tool carrying the markers
  (\c eMt). Joints are indexed from 0, base to tip; revolute values are radians, prismatic ones metres. The metric
  twists at the zero reference \f$ q = 0 \f$ (4x4 matrices of se(3) in the world frame, eq. (9)) give the product of
  exponentials used by the paper (eq. (35)):
  \f$ {}^wM_e(q) = \exp(q_0 \hat T_0) \cdots \exp(q_{n-1} \hat T_{n-1})\, {}^wM_e(0) \f$ (and likewise for
  \f$ {}^wM_t \f$). Joint \e i turns about (or slides along) the z axis of the frame reached after rows 0 to i-1,
  at q = 0: a revolute twist has \f$ \omega \f$ that unit axis and \f$ v = -\omega \times p \f$, p a point on it; a
  prismatic one has \f$ \omega = 0 \f$ and v the unit axis.
*/
class VISP_EXPORT vpSimulatorArm
{
public:
  //! One Denavit-Hartenberg row: \f$ T = R_z(\theta) T_z(d) T_x(a) R_x(\alpha) \f$, the joint adds to \f$ \theta \f$
  //! (revolute) or \f$ d \f$ (prismatic), which thus hold the joint's offset at q = 0.
  struct vpDHRow {
    //! Revolute or prismatic.
    vpProjectiveJoint::vpJointType type;
    double theta; //!< rad
    double d;     //!< m
    double a;     //!< m
    double alpha; //!< rad
  };

  /*!
    \param dh : one row per joint, base to tip.
    \param eMt : tool frame on the last link (where markers are attached).
    \param tMarkers : marker points (3x1) in the tool frame.
    \param wMb : base pose in the world.
  */
  vpSimulatorArm(const std::vector<vpDHRow> &dh, const vpHomogeneousMatrix &eMt,
                 const std::vector<vpColVector> &tMarkers, const vpHomogeneousMatrix &wMb);

  /*!
    A PUMA-like 6R arm with the paper's link lengths (section 6: "links of 36cm, 48cm, and 40cm"): base column
    d1 = 36 cm, upper arm a2 = 48 cm, forearm (elbow to wrist centre) d4 = 40 cm, a spherical wrist with a 5 cm
    flange offset d6, and a 10 cm gripper (gripperMount(), centre 10 cm from the wrist centre) carrying the 7 markers
    of gripperMarkers() (no 4 coplanar); the first 3 lie on the gripper face that looks at the rig and are the
    tracked ones. Standard DH rows \f$ R_z(\theta_i + q_i) T_z(d_i) T_x(a_i) R_x(\alpha_i) \f$ (PUMA 560 structure
    without shoulder and elbow offsets):

    | i | theta_i (q = 0) | d_i (m) | a_i (m) | alpha_i |
    |---|-----------------|---------|---------|---------|
    | 0 | 0               | 0.36    | 0       | 90 deg  |
    | 1 | 74 deg          | 0       | 0.48    | 0       |
    | 2 | -60 deg         | 0       | 0       | -90 deg |
    | 3 | 0               | 0.40    | 0       | 90 deg  |
    | 4 | -40 deg         | 0       | 0       | -90 deg |
    | 5 | 86 deg          | 0.05    | 0       | 0       |

    q = 0 is a raised "ready" pose: upper arm up, elbow bent by 30 deg, wrist bent by 40 deg, the gripper pointing up
    and its front face (markers 0-2) towards the rig; joint limits +-170 deg. With paperBasePose() and
    vpSimulatorStereoRig::paperRig((0, 0, 0), 1.0), all 7 markers stay at least 10 px inside both images (and off
    the lines of sight of the links) while one joint moves from q = 0: joints 0, 3 and 5 anywhere, joint 1 within
    [-21, 32.5] deg, joint 2 within [-45, 32] deg, joint 4 within [-73.5, 108.5] deg. The paper's trial motions
    [30, 20, 30, 40, 60, 60] deg thus fit both ways, with the least to spare for joint 1 negative (1 deg) and joint 2
    positive (2 deg).
  */
  static vpSimulatorArm puma(const vpHomogeneousMatrix &wMb);
  /*!
    ViSP's Viper850 geometry carrying the same 10 cm gripper (gripperMount(), gripperMarkers()): the DH parameters
    a1, d1, a2, a3, d4, d6 and the joint limits of vpViper850, with get_wMe(q) equal to
    \f$ {}^wM_b \f$ vpViper850::get_fMe(q). Like vpViper::get_fMe(), the model ignores the joint 5-6 coupling, which
    only relates motor to joint positions.
  */
  static vpSimulatorArm viper850(const vpHomogeneousMatrix &wMb);

  //! The Denavit-Hartenberg table of puma() (its theta entries hold the zero-reference offsets).
  static std::vector<vpDHRow> pumaTable();
  /*!
    The Denavit-Hartenberg table of an R-R-P-R-R-R arm with the Stanford arm's structure (Scheinman's: a telescoping
    third joint, spherical wrist): d1 = 0.41 m, d2 = 0.15 m, the third joint's d its prismatic value (metres), 10 cm
    from the wrist to the flange; no zero-reference offsets. The evaluation's arm with a prismatic joint.
  */
  static std::vector<vpDHRow> stanfordTable();
  /*!
    The 7 gripper markers (3x1, metres) in the tool frame \c t: origin at the gripper's centre, z the approach
    direction; markers 0-2 lie on the face y = -2 cm.
  */
  static std::vector<vpColVector> gripperMarkers();
  //! The gripper's mount on the flange: \c eMt, a 5 cm translation along the last link's z axis.
  static vpHomogeneousMatrix gripperMount();
  /*!
    Base pose for puma() used by the tutorials and tests: at q = 0 the gripper's centre (the tool frame origin) is at
    the world origin, so that the rig to use is vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0), which looks
    along the world +Z axis with the world +Y axis pointing down in the images. The base's z axis (up) is the world
    -Y axis turned by 7 deg about the world X axis away from the rig (the rig, 12 cm below the gripper, looks up at
    it by 7 deg), and the arm's plane at q = 0 faces the rig (base turned by -86 deg about its z axis); the base stands
    1.30 m below the gripper and 8 cm nearer to the rig. See puma() for what stays in view.
  */
  static vpHomogeneousMatrix paperBasePose();

  //! Number of joints \e n.
  unsigned int getNumberOfJoints() const { return static_cast<unsigned int>(m_dh.size()); }
  //! Kind of joint \e i.
  vpProjectiveJoint::vpJointType getJointType(unsigned int i) const;
  //! Tip pose \f$ {}^wM_t(q) \f$.
  vpHomogeneousMatrix get_wMt(const vpColVector &q) const;
  //! Last-link pose \f$ {}^wM_e(q) = {}^wM_b\, T_0(q_0) \cdots T_{n-1}(q_{n-1}) \f$ (no tool).
  vpHomogeneousMatrix get_wMe(const vpColVector &q) const;
  //! Base pose.
  const vpHomogeneousMatrix &get_wMb() const { return m_wMb; }
  //! Tool mount on the last link.
  const vpHomogeneousMatrix &get_eMt() const { return m_eMt; }
  //! Denavit-Hartenberg table.
  const std::vector<vpDHRow> &getDHTable() const { return m_dh; }
  //! Marker positions in the world (3x1 each).
  std::vector<vpColVector> getMarkers(const vpColVector &q) const;
  //! Markers in the tool frame.
  const std::vector<vpColVector> &getToolMarkers() const { return m_tMarkers; }
  /*!
    Metric twist \f$ \hat T_i \f$ (4x4 se(3) matrix, world frame) of joint \e i at the zero reference:
    \f$ {}^wM_e(q) = \prod_i \exp(q_i \hat T_i)\, {}^wM_e(0) \f$.
  */
  vpMatrix getTwist(unsigned int i) const;
  //! The metric motion of the tool from q = 0 to q (world frame): \f$ {}^wM_t(q)\, {}^wM_t(0)^{-1} \f$.
  vpHomogeneousMatrix getDisplacement(const vpColVector &q) const;

  //! Joint limits (from vpViper850 for the Viper, +-170 deg otherwise).
  const vpColVector &getJointMin() const { return m_qmin; }
  //! Upper joint limits (n x 1).
  const vpColVector &getJointMax() const { return m_qmax; }
  //! Replaces the joint limits (n x 1 each, qmin <= qmax).
  void setJointLimits(const vpColVector &qmin, const vpColVector &qmax);
  //! Explicit Euler step \f$ q + \dot q\, dt \f$, clamped to the joint limits.
  vpColVector integrate(const vpColVector &q, const vpColVector &qdot, double dt) const;

private:
  void checkJointVector(const vpColVector &q, const char *where, const char *name) const;

  std::vector<vpDHRow> m_dh;
  vpHomogeneousMatrix m_eMt;
  std::vector<vpColVector> m_tMarkers;
  vpHomogeneousMatrix m_wMb;
  vpColVector m_qmin;
  vpColVector m_qmax;
};

END_VISP_NAMESPACE

#endif
