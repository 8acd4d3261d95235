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

/*
  Private: the metric bundle adjustment of vpProjectiveSelfCalibration: both cameras (intrinsics with skew), the rig,
  the joints' screw axes and the markers, in the left camera's frame at the zero reference, over every stereo image of
  the markers at known joint readings; its covariance (Ceres), and the information a new frame would add. Not
  installed.
*/

#ifndef _vpMetricAdjustment_h_
#define _vpMetricAdjustment_h_

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*
  The self-calibration's products of dynamic matrices (covariances, Jacobians) are lazyProduct()s: Eigen's blocked
  product would spread these small ones over OpenMP threads (the library is built with OpenMP), which cost more than
  they save and belong to the caller's loop.
*/

//! An undetermined deviation.
const double kInfinity = std::numeric_limits<double>::infinity();

/*!
  The metric cameras and arm, in the left camera's frame at the zero reference (lengths in the prismatic joints'
  unit, or with a unit baseline when the arm has none). The markers seen at joint readings q are at
  \f$ T(q - q_{ref}) X_j \f$, \f$ T \f$ the product of the joints' exponentials (vpProjectiveArmModel's order), and
  image at \f$ K_l [I | 0] \f$ and \f$ K_r\, {}^rM_l \f$.
*/
struct MetricArm {
  Eigen::Matrix<double, 5, 1> left, right;  // intrinsics: fx, fy, skew, u0, v0 (px)
  Eigen::Matrix3d lRr;                      // the right camera's orientation in the left camera's frame
  Eigen::Vector3d b;                        // the right camera's centre in the left camera's frame
  std::vector<Eigen::Vector3d> axis, point; // per joint: unit direction, a point of a revolute axis
  std::vector<Eigen::Vector3d> X;           // the markers at the zero reference
};

//! What the chain is: the joints' kinds, the mounting (the order of the product) and the zero reference's readings.
struct MetricChain {
  std::vector<vpProjectiveJoint::vpJointType> types;
  vpProjectiveArmModel::vpRigMounting mounting;
  vpProjectiveArmModel::JointVector qRef;
  bool hasPrismatic() const;
};

//! One stereo image: readings q, pixels (u, v, u', v') of each marker, and which markers it observes.
struct MetricFrame {
  vpProjectiveArmModel::JointVector q;
  std::vector<Eigen::Vector4d> s;
  std::vector<bool> seen;
};

/*!
  The start of the adjustment: the metric rig and arm read off \e model's \f$ G \f$ (vpProjectiveSelfCalibration's
  static read-out), scaled by the prismatic joints or to a unit baseline.
  \exception vpProjectiveException as vpProjectiveSelfCalibration::metricStereoRig().
*/
MetricArm metricStart(const vpProjectiveArmModel &model);

//! Predicted pixels of every marker of \e arm at readings \e q; false if one is not in front of both cameras.
bool predictFrame(const MetricChain &chain, const MetricArm &arm, const vpProjectiveArmModel::JointVector &q,
                  std::vector<Eigen::Vector4d> &s);

/*!
  Checks the scale of SCALE_MARKER_DISTANCE (vpProjectiveSelfCalibration's constructor and setScale()): \e markerA
  and \e markerB two distinct markers of the \e markers the model has, \e distance positive and finite.
  \exception vpProjectiveException (dimensionError, invalidValueError) otherwise, at \e where.
*/
void checkMarkerDistance(unsigned int markerA, unsigned int markerB, double distance, size_t markers,
                         const std::string &where);

//! Square root of the largest eigenvalue of the symmetric \e S: the deviation along its least determined axis.
double largestDeviation(const Eigen::Matrix3d &S);

//! The deviation (rad, least determined axis) of the unit direction \e d of a vector of covariance \e S and length
//! \e length.
double directionDeviation(const Eigen::Vector3d &d, const Eigen::Matrix3d &S, double length);

/*!
  The adjustment's parameters in one ambient vector: left (5), right (5), the rotation's perturbation phi (3, left
  camera axes: lRr = exp(phi) lRr_0), b (3), per joint its direction (3) and point (3, zero for a prismatic joint),
  per marker its point (3). Its covariance describes each estimate's uncertainty.
*/
struct MetricLayout {
  static const int kLeft = 0, kRight = 5, kRotation = 10, kBaseline = 13, kJoints = 16;
  static int joint(unsigned int i) { return kJoints + 6 * static_cast<int>(i); }
  static int marker(unsigned int n, unsigned int j)
  {
    return kJoints + 6 * static_cast<int>(n) + 3 * static_cast<int>(j);
  }
  static int size(unsigned int n, unsigned int K) { return marker(n, K); }
};

/*!
  The adjustment itself: Levenberg-Marquardt (Ceres) from \e start over \e frames, each a residual block of its
  observed markers (4 pixel residuals each). The scale is the prismatic joints' (their twists of unit length) or, with
  none, the baseline's (unit length). Nothing is fixed but that: the left camera's frame is the gauge.
*/
class MetricProblem
{
public:
  MetricProblem(const MetricChain &chain, const MetricArm &start);
  ~MetricProblem();
  MetricProblem(const MetricProblem &) = delete;
  MetricProblem &operator=(const MetricProblem &) = delete;

  //! Adds the observed markers of \e frame (none: nothing).
  void addFrame(const MetricFrame &frame);
  //! Solves; false if Ceres gives no usable solution.
  bool solve();
  //! The current estimate.
  MetricArm estimate() const;
  //! Sum of squared residuals, and the number of residuals (4 per observation) and of free parameters.
  void cost(double &sum, unsigned int &residuals, unsigned int &parameters) const;
  /*!
    \f$ (J^T J)^{-1} \f$ in the tangent space of the parameters (ceres::Covariance), \e L the map from it to the ambient
    layout (MetricLayout); false if the Jacobian is rank deficient (a parameter the frames do not determine).
  */
  bool covariance(Eigen::MatrixXd &tangent, Eigen::MatrixXd &L);
  //! The Jacobian (4 K x tangent dimension) of the pixels of every marker at readings \e q.
  Eigen::MatrixXd frameJacobian(const vpProjectiveArmModel::JointVector &q);

private:
  struct Data;
  std::unique_ptr<Data> m;
};
} // namespace vpProjectiveInternal

#endif
