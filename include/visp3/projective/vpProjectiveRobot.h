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
  \brief Projective kinematics of a serial arm: acquisition, forward kinematics, velocities and Jacobians in the
  projective frame of a weakly calibrated stereo rig.
*/

#ifndef _vpProjectiveRobot_h_
#define _vpProjectiveRobot_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveRobot
  \ingroup group_projective
  \brief A serial chain of \f$ n \f$ revolute or prismatic joints modelled only in the projective frame
  \f$ \mathcal{P} \f$ of an uncalibrated stereo rig (Ruf & Horaud, sections 5 and 6).

  Joints are indexed \f$ 0 \ldots n-1 \f$ from base to tip; revolute values are radians, prismatic ones are the
  encoder's length unit. The same model covers the eye-to-hand case (rig fixed, the base is the robot base) and the
  eye-in-hand case (rig on the hand, which is then the base of the chain).

  <b>Model.</b> Each joint has a generator \f$ \hat H_i \f$ (4x4): a p-rotation generator
  (\f$ \hat H^3 = -\hat H \f$) or a p-translation generator (\f$ \hat H^2 = 0 \f$). Relative to the zero reference
  \f$ q = 0 \f$, the last link moves by the product of exponentials (34)
  \f[ H(q) = \exp(q_0 \hat H_0) \cdots \exp(q_{n-1} \hat H_{n-1}), \qquad M(q) = H(q) M(0). \f]
  With \f$ A_k = \exp(q_0 \hat H_0) \cdots \exp(q_k \hat H_k) \f$ (\f$ A_{-1} = I \f$), joint \f$ k \f$ moves at
  configuration \f$ q \f$ with \f$ \hat H_{k,q} = A_{k-1} \hat H_k A_{k-1}^{-1} \f$ (39), and a point \f$ M \f$ of
  the last link has the point Jacobian (42)-(44), 4 x n,
  \f[ J_H(q, M) = [\hat H_{0,q} M \;\cdots\; \hat H_{n-1,q} M]. \f]
  Its image Jacobian (45)-(46), 4 x n with rows \f$ (u, v, u', v') \f$, is
  \f[ J(q, M) = \begin{bmatrix} J_C(P M)\, P \\ J_C(P' M)\, P' \end{bmatrix} J_H(q, M), \qquad
      J_C(m) = \begin{bmatrix} 1/m_3 & 0 & -m_1/m_3^2 \\ 0 & 1/m_3 & -m_2/m_3^2 \end{bmatrix}, \f]
  invariant to the scale and sign of \f$ M \f$.

  <b>Acquisition (section 6).</b> setZeroReference() takes the images of the markers of the last link at
  \f$ q = 0 \f$; addTrialMotion() the images after joint \e i alone moved by a known amount (several per joint,
  ideally both ways). calibrate() then computes
  -# the algebraic generators from the trial homographies (logarithms (25), (31));
  -# a whitened frame, the plane \f$ \pi \f$ with \f$ \pi^T \hat H_i = 0 \f$ for all joints (affine step), and the
     symmetric \f$ W \f$ with \f$ A_i W + W A_i^T = 0 \f$ for the revolute blocks (metric step): a matrix \f$ G \f$
     with \f$ \hat H_i = G^{-1} \hat T_i G \f$, \f$ \hat T_i \in se(3) \f$;
  -# a Ceres bundle adjustment over \f$ G^{-1} \f$, the metric twists (revolute: unit axis and a point on it;
     prismatic: a direction vector) and the marker points, minimising the pixel error of every acquisition image in
     both cameras. All generators thereby share one \f$ G \f$, which is \f$ H_{PE} \f$ up to a similarity.

  \code
  vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(6, vpProjectiveRobot::REVOLUTE));
  robot.setStereoRig(rig);
  robot.setZeroReference(left0, right0);
  robot.addTrialMotion(i, amount, left_i, right_i); // for every joint, both ways
  robot.calibrate();
  vpMatrix J = robot.getImageJacobian(q, M);       // 4 x n
  \endcode
*/
class VISP_EXPORT vpProjectiveRobot
{
public:
  //! Joint kinds.
  enum vpJointType { REVOLUTE, PRISMATIC };

  /*!
    Where the rig is. The joints keep the robot's own numbering (0 at the robot base) in both cases; only the order
    of the product of exponentials (34) changes, since the base of the chain is the end that holds the rig.
  */
  enum vpRigMounting {
    EYE_TO_HAND, //!< Rig fixed in the workspace, markers on the last link: \f$ H(q) = \exp(q_0 \hat H_0) \cdots
                 //!< \exp(q_{n-1} \hat H_{n-1}) \f$.
    EYE_IN_HAND  //!< Rig on the last link, markers static: the hand is the base, \f$ H(q) = \exp(q_{n-1}
                 //!< \hat H_{n-1}) \cdots \exp(q_0 \hat H_0) \f$.
  };

  //! Largest number of joints: fixed-size storage keeps the control loop free of allocations.
  static const unsigned int maxJoints = 16;

  //! Joint values (n x 1) without heap allocation.
  typedef Eigen::Matrix<double, Eigen::Dynamic, 1, 0, maxJoints, 1> JointVector;
  //! A 4 x n Jacobian without heap allocation.
  typedef Eigen::Matrix<double, 4, Eigen::Dynamic, 0, 4, maxJoints> PointJacobian;

  //! An empty model; use loadModel() or the other constructor.
  vpProjectiveRobot();
  /*!
    A chain of joints of the given types, base to tip.
    \exception vpProjectiveException if there are no joints or more than maxJoints.
  */
  explicit vpProjectiveRobot(const std::vector<vpJointType> &joints);

  //! Number of joints \e n.
  unsigned int getNumberOfJoints() const { return static_cast<unsigned int>(m_types.size()); }
  //! Type of joint \e i. \exception vpProjectiveException on a bad index.
  vpJointType getJointType(unsigned int i) const;
  //! Sets where the rig is mounted (default EYE_TO_HAND); the acquisition is the same in both cases.
  void setRigMounting(vpRigMounting mounting) { m_mounting = mounting; }
  //! Where the rig is mounted.
  vpRigMounting getRigMounting() const { return m_mounting; }

  /*! \name Acquisition */
  //@{
  //! The weakly calibrated rig whose projective frame the model lives in. Clears acquired data of another rig.
  void setStereoRig(const vpProjectiveStereoRig &rig);
  //! The rig set by setStereoRig() (or read by loadModel()).
  const vpProjectiveStereoRig &getStereoRig() const { return m_rig; }
  /*!
    Images of the \f$ K \ge 5 \f$ markers of the last link at \f$ q = 0 \f$, in a fixed order (no 4 coplanar).
    \exception vpProjectiveException on fewer than 5 markers, a size mismatch, a non-finite coordinate, a missing rig.
  */
  void setZeroReference(const std::vector<vpImagePoint> &left0, const std::vector<vpImagePoint> &right0);
  /*!
    Images of the same markers, in the same order, after joint \e i alone moved from the zero reference by \e amount
    (radians or length units, signed, read by the encoder). Call several times per joint, ideally both ways.
    \exception vpProjectiveException on a bad joint index, a zero or non-finite amount, a size mismatch, a missing
    zero reference.
  */
  void addTrialMotion(unsigned int i, double amount, const std::vector<vpImagePoint> &left,
                      const std::vector<vpImagePoint> &right);
  /*!
    Computes the generators: algebraic estimate, metric upgrade, then Ceres bundle adjustment (see the class
    documentation).
    \exception vpProjectiveException if a joint has no trial motion, the zero reference is missing, or the data is
    degenerate.
  */
  void calibrate();
  //! True once calibrate() or loadModel() succeeded.
  bool isCalibrated() const { return m_calibrated; }
  //! RMS pixel residual of the final bundle adjustment over all acquisition images (the self-check: ~ noise level).
  double getCalibrationResidual() const { return m_residual; }
  //! RMS pixel residual of the algebraic generators alone (before refinement), for comparison.
  double getAlgebraicResidual() const { return m_algebraicResidual; }
  /*!
    Mismatched markers in the acquisition images (a wrong blob tracked, two markers swapped): with \e pixels > 0,
    calibrate() finds them in each trial by the 5-point consensus of vpProjectiveDisplacement::estimateRobust(),
    leaves them out of the initial model and of the bundle adjustment, then keeps out exactly the trial observations
    the final model places more than \e pixels away (RMS over the two images), with one more adjustment if that
    changed. A zero-reference marker whose left and right images match no 3D point within \e pixels makes
    calibrate() throw (the zero reference defines the markers). About 3 sigma of the pixel noise is a good value (1.5
    px at 0.5 px); 0, the default, uses every observation.
    \exception vpProjectiveException (invalidValueError) if \e pixels is negative or not finite.
  */
  void setOutlierThreshold(double pixels);
  //! The outlier threshold in pixels (0: no rejection).
  double getOutlierThreshold() const { return m_outlierThreshold; }
  //! Number of trial observations (marker in a trial's pair of images) the last calibrate() left out.
  unsigned int getNumberOfOutliers() const;
  /*!
    True if the last calibrate() left out marker \e marker of trial \e trial (trials numbered in the order of
    addTrialMotion(), from 0).
    \exception vpProjectiveException (dimensionError) if there is no such observation.
  */
  bool isOutlier(unsigned int trial, unsigned int marker) const;
  //@}

  /*! \name Model */
  //@{
  //! Generator \f$ \hat H_i \f$ (4x4) of joint \e i in the zero reference.
  vpMatrix getGenerator(unsigned int i) const;
  /*!
    \f$ G \f$ (4x4): maps projective points to a metric frame, \f$ \hat H_i = G^{-1} \hat T_i G \f$. It equals
    \f$ H_{PE} \f$ up to a similarity (the metric upgrade obtained as a by-product of calibrate()).
  */
  vpMatrix getProjectiveToMetric() const;
  //! Metric twist \f$ \hat T_i = G \hat H_i G^{-1} \f$ (4x4 se(3) matrix) of joint \e i.
  vpMatrix getTwist(unsigned int i) const;
  //! Refined projective points \f$ M_j(0) \f$ (4x1, unit norm) of the markers at the zero reference.
  std::vector<vpColVector> getZeroReferencePoints() const;
  //@}

  /*! \name Kinematics */
  //@{
  //! \f$ H(q) \f$ (4x4) of the last link, eq. (34).
  vpMatrix getDisplacement(const vpColVector &q) const;
  //! \f$ \hat H_{k,q} \f$ (4x4), the projective motion of joint \e k at configuration \e q, eq. (39).
  vpMatrix getJointMotion(unsigned int k, const vpColVector &q) const;
  //! \f$ J_H(q, M) \f$ (4 x n), eqs. (42)-(44); \e M is the current projective point (4x1) on the last link.
  vpMatrix getPointJacobian(const vpColVector &q, const vpColVector &M) const;
  //! Stereo image Jacobian (4 x n, rows \f$ (u, v, u', v') \f$) of eqs. (45)-(46) at \e q for the current point M.
  vpMatrix getImageJacobian(const vpColVector &q, const vpColVector &M) const;
  //! Predicted images of marker \e j at configuration q: \f$ P H(q) M_j(0) \f$ and \f$ P' H(q) M_j(0) \f$.
  void projectMarker(unsigned int j, const vpColVector &q, vpImagePoint &ipLeft, vpImagePoint &ipRight) const;
  /*!
    Inverse kinematics (the paper's motion-capture use): the joint values that best explain the observed images of
    the markers, by Ceres minimisation of the pixel error started at \e q0 (zeros if empty).
    \param left, right : images of the markers \e indices (all markers if \e indices is empty).
    \param q0 : starting joint values (n x 1); zeros if empty.
    \param indices : which markers \e left and \e right show, as indices of the zero-reference markers.
    \param residual : if not null, receives the final RMS pixel error.
  */
  vpColVector inverseKinematics(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right,
                                const vpColVector &q0 = vpColVector(),
                                const std::vector<unsigned int> &indices = std::vector<unsigned int>(),
                                double *residual = nullptr) const;
  //@}

  /*! \name Model file */
  //@{
  /*!
    Writes the acquired model (rig, joint types, G, twists, generators, zero-reference points) to a versioned text
    file with a checksum.
  */
  void saveModel(const std::string &filename) const;
  /*!
    Reads a model written by saveModel().
    \exception vpProjectiveException (fileError) if the file is missing, truncated, corrupted, of another version, or
    inconsistent.
  */
  void loadModel(const std::string &filename);
  //@}

  /*! \name Eigen access for hot paths (no allocation) */
  //@{
  //! Generator \f$ \hat H_i \f$ of joint \e i (no index check).
  const Eigen::Matrix4d &generator(unsigned int i) const { return m_Hhat[i]; }
  //! \f$ \exp(q \hat H_i) \f$ by Rodrigues' form (26) or (31).
  Eigen::Matrix4d jointExp(unsigned int i, double q) const;
  //! \f$ H(q) \f$, eq. (34).
  Eigen::Matrix4d displacement(const JointVector &q) const;
  //! \f$ \hat H_{k,q} \f$ for every joint k (in joint numbering), eq. (39).
  void jointMotions(const JointVector &q, Eigen::Matrix4d *HhatKq) const;
  //! \f$ J_H(q, M) \f$ from precomputed jointMotions().
  void pointJacobian(const Eigen::Matrix4d *HhatKq, const Eigen::Vector4d &M, PointJacobian &JH) const;
  //! Stereo image Jacobian (4 x n) from precomputed jointMotions(); false if M is on a camera's focal plane.
  bool imageJacobian(const Eigen::Matrix4d *HhatKq, const Eigen::Vector4d &M, PointJacobian &J) const;
  //@}

private:
  struct vpTrial {
    unsigned int joint;
    double amount;
    std::vector<Eigen::Vector4d> s; // (u, v, u', v') of each marker
  };

  void checkCalibrated(const char *where) const;
  JointVector toJointVector(const vpColVector &q, const std::string &where) const;
  std::vector<Eigen::Vector4d> triangulateZeroReference() const;
  //! Generator of each joint from its trials' displacements (the best-predicting candidate), M0 the zero reference.
  void algebraicGenerators(const std::vector<Eigen::Vector4d> &M0, std::vector<Eigen::Matrix4d> &Hhat);
  //! Flags the trial observations farther than the outlier threshold from the model; true if a flag changed.
  bool classifyTrialObservations();
  /*!
    Affine and metric upgrade from the generators of the joints flagged in \e use: G (4x4) maps the projective frame
    to a metric one centred and scaled on the markers M0. False when the data do not give a finite, invertible G.
  */
  bool metricUpgrade(const std::vector<Eigen::Matrix4d> &Hhat, const std::vector<bool> &use,
                     const std::vector<Eigen::Vector4d> &M0, Eigen::Matrix4d &G) const;
  //! Metric axes and points of every joint in the frame of G, from its generator or its trials' rigid motions.
  bool initialTwists(const Eigen::Matrix4d &G, const std::vector<Eigen::Matrix4d> &Hhat,
                     const std::vector<Eigen::Vector4d> &M0,
                     const std::vector<std::vector<Eigen::Vector4d>> &trialPoints, std::vector<Eigen::Vector3d> &axis,
                     std::vector<Eigen::Vector3d> &point) const;
  //! The start of the bundle adjustment: the best-predicting of the upgrades with every joint and all but one.
  void initialMetricModel(const std::vector<Eigen::Matrix4d> &Hhat, const std::vector<Eigen::Vector4d> &M0,
                          Eigen::Matrix4d &G, std::vector<Eigen::Vector3d> &axis,
                          std::vector<Eigen::Vector3d> &point) const;
  /*!
    Bundle adjustment over G^-1, the twists and the markers, on the pixel error of the acquisition images: the inlier
    observations, or with \e robustLoss every observation under a Cauchy loss at the outlier threshold.
  */
  void bundleAdjust(const std::vector<Eigen::Vector4d> &M0, const Eigen::Matrix4d &G, std::vector<Eigen::Vector3d> axis,
                    std::vector<Eigen::Vector3d> point, bool robustLoss);
  //! RMS pixel error of all trials predicted by the generators Hhat from the zero-reference points M0.
  double predictionResidual(const std::vector<Eigen::Matrix4d> &Hhat, const std::vector<Eigen::Vector4d> &M0) const;
  //! Adds the squared pixel errors of joint i's trials predicted by Hhat, and their number of coordinates.
  void accumulateTrialError(unsigned int i, const Eigen::Matrix4d &Hhat, const std::vector<Eigen::Vector4d> &M0,
                            double &sum, size_t &count) const;
  void setModelFromTwists();

  //! Joint index at position k of the product of exponentials, base of the chain (the rig's end) first.
  unsigned int chainJoint(unsigned int k) const
  {
    return m_mounting == EYE_TO_HAND ? k : static_cast<unsigned int>(m_types.size()) - 1 - k;
  }

  std::vector<vpJointType> m_types;
  vpRigMounting m_mounting;
  vpProjectiveStereoRig m_rig;
  std::vector<Eigen::Vector4d> m_zeroImages; // (u, v, u', v') of each marker at q = 0
  std::vector<vpTrial> m_trials;

  // The model: Hhat_i = G^-1 That_i G, with That_i built from (w_i, p_i) (revolute) or d_i (prismatic).
  Eigen::Matrix4d m_G;
  Eigen::Matrix4d m_Ginv;
  std::vector<Eigen::Vector3d> m_axis;  // unit axis w (revolute) or direction d (prismatic)
  std::vector<Eigen::Vector3d> m_point; // a point on the axis (revolute), unused for prismatic
  std::vector<Eigen::Matrix4d> m_Hhat;
  std::vector<Eigen::Vector4d> m_M0; // refined zero-reference markers, unit norm
  double m_residual;
  double m_algebraicResidual;
  double m_outlierThreshold;               // pixels, 0: every observation is used
  std::vector<std::vector<bool>> m_inlier; // [trial][marker]: used by the last calibrate()
  bool m_calibrated;
};

END_VISP_NAMESPACE

#endif
