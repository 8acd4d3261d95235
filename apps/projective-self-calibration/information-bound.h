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
  \file information-bound.h
  \brief What the data allows: the Cramer-Rao bound of the metric self-calibration (vpProjectiveSelfCalibration's
  parameters: both cameras' 5 intrinsics, the rig's rotation and baseline, the joints' screw axes, the markers) at a
  world's true parameters, from a Jacobian of the pixels written independently of the library.

  With Gaussian pixel noise \f$ \sigma \f$ on every coordinate, the Fisher information of the parameters \f$ \theta
  \f$ is \f$ J^T J / \sigma^2 \f$ (J the pixels' Jacobian at the truth), and no unbiased estimator has a covariance
  smaller than its inverse: the bound's standard deviations are those an efficient estimator reaches, the floor of
  any other on these frames. Parameters known beforehand (the skew, the markers, the joint axes) are left out of
  \f$ \theta \f$: the bound with them known.
*/

#ifndef _selfcal_information_bound_h_
#define _selfcal_information_bound_h_

#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveJoint.h>
#include <visp3/projective/vpProjectiveSelfCalibration.h>

#include "calibration-world.h"
#include "rig-errors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
/*!
  A metric rig and arm in the self-calibration's model, in the left camera's frame at the zero reference: marker j at
  readings q is at \f$ T(q - q_{ref}) X_j \f$ (the joints' exponentials base to tip), imaged by \f$ K_l [I | 0] \f$ and
  \f$ K_r [{}^lR_r^T | -{}^lR_r^T b] \f$.
*/
struct MetricModel {
  Eigen::Matrix<double, 10, 1> k; //!< fx, fy, skew, u0, v0 of the left camera, then of the right one (px)
  Eigen::Matrix3d lRr;            //!< the right camera's orientation in the left camera's frame
  Eigen::Vector3d b;              //!< the right camera's centre in the left camera's frame
  std::vector<vpProjectiveJoint::vpJointType> types;
  std::vector<Eigen::Vector3d> axis, point; //!< per joint: unit direction; a point of a revolute axis
  std::vector<Eigen::Vector3d> X;           //!< the markers at the zero reference
  Eigen::VectorXd qRef;                     //!< the zero reference's readings
};

//! The true model of a study world (metres).
MetricModel trueModel(const StudyArm &arm, const SkewedRig &rig);

//! The pixels (u, v, u', v') of every observed marker of \e frames, frame after frame, predicted by \e model.
Eigen::VectorXd predict(const MetricModel &model, const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames);

/*!
  The minimal parameters around \e model, as vpProjectiveSelfCalibration adjusts them: 10 intrinsics, the rotation
  (3, left camera's axes), the baseline (3; 2 across it when \e unitBaseline: the scale's gauge), per joint its
  direction (2 across it) and, revolute, its point (2 in the plane across the axis), each marker (3).
*/
class MetricParameters
{
public:
  MetricParameters(const MetricModel &model, bool unitBaseline);
  //! The model moved by \e x (size() x 1).
  MetricModel moved(const Eigen::VectorXd &x) const;
  const MetricModel &model() const { return m_model; }
  bool unitBaseline() const { return m_unitBaseline; }
  int size() const { return m_size; }
  static const int kRotation = 10, kBaseline = 13; //!< the intrinsics first, then these
  int baselineSize() const { return m_unitBaseline ? 2 : 3; }
  int joint(size_t i) const { return m_joint[i]; } //!< the first of joint i's 2 or 4
  int marker(size_t j) const { return m_marker + 3 * static_cast<int>(j); }

private:
  MetricModel m_model;
  bool m_unitBaseline;
  std::vector<Eigen::Vector3d> m_e1, m_e2; //!< two unit normals to each joint's axis, then to the baseline
  std::vector<int> m_joint;
  int m_marker, m_size;
};

//! Central differences of predict() over the parameters \e p at their model.
Eigen::MatrixXd pixelJacobian(const MetricParameters &p,
                              const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames);

//! What is known beforehand, left out of the parameters.
enum Known { NOTHING_KNOWN = 0, SKEW_KNOWN = 1, MARKERS_KNOWN = 2, AXES_KNOWN = 4 };

/*!
  The deviations of the study's parameters (focal length: worst relative of both cameras; principal point and skew:
  worst px; rig rotation: rms angle, deg; baseline direction: along its least determined axis, deg; baseline length:
  relative, its unit the prismatic joint's or, for an all-revolute arm, the distance of markers 0 and 1) from the
  covariance \f$ \sigma^2 (J^T J)^{-1} \f$ of the parameters not \e known; all infinite if J lacks rank. Known markers
  or axes (lengths) fix the scale themselves: give them parameters without the unit baseline.
*/
void informationBound(const MetricParameters &p, const Eigen::MatrixXd &J, double sigma, unsigned int known,
                      double (&deviation)[PARAMETERS]);

/*!
  The probability that the errors of an efficient estimator (Gaussian with the bound's covariance, nothing known),
  measured as the study measures them (compare()), are within \e bounds (in the deviations' units), per parameter:
  the share of 4000 draws.
*/
void withinBounds(const MetricParameters &p, const Eigen::MatrixXd &J, double sigma, const double (&bounds)[PARAMETERS],
                  double (&probability)[PARAMETERS]);

//! The same deviations from the self-calibration's stated ones (\e t its translation).
void statedDeviations(const vpProjectiveSelfCalibration::vpUncertainty &u, const Eigen::Matrix3d &Kl,
                      const Eigen::Matrix3d &Kr, const Eigen::Vector3d &t, double (&deviation)[PARAMETERS]);

/*!
  The study "what the data allows": per arm of \e arms and seed, the errors and stated deviations of the
  self-calibration on the data (the acquisition and \e frames frames within +-\e range deg at \e sigma px,
  the worlds of projective-self-calibration's main study), and the Cramer-Rao bound on them, with parameters known,
  on more frames and wider spreads, and on frames suggested by suggestConfigurations(); median / worst over the
  seeds. Returns 1 if a bound's check fails (the true model does not predict the world's pixels).
*/
int whatTheDataAllows(const std::vector<std::string> &arms, unsigned int seeds, unsigned int first, double sigma,
                      unsigned int frames, double range);
} // namespace selfcal

#endif
