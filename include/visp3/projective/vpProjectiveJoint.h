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
  \file vpProjectiveJoint.h
  \brief The joints of a serial chain: their kinds, and the one-parameter group of each kind.
*/

#ifndef _vpProjectiveJoint_h_
#define _vpProjectiveJoint_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <Eigen/Core>

#include <visp3/projective/vpMetricTwist.h>
#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveTranslation.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveJoint
  \ingroup group_projective
  \brief Kinds of joints, and what each kind's one-parameter group gives: its exponential, logarithm and metric twist.

  A revolute joint moves by a p-rotation (vpProjectiveRotation), a prismatic one by a p-translation
  (vpProjectiveTranslation). The functions here dispatch on the kind, so that the robot model, its acquisition, the
  Ceres cost functors and the simulator all use the same exponential for the same joint. The names and signatures are
  those of the group API (\ref page_groups), with the joint's type first. Joint values are radians
  (revolute) or the encoder's length unit (prismatic).
*/
class VISP_EXPORT vpProjectiveJoint
{
public:
  //! Kinds of joints.
  enum vpJointType {
    REVOLUTE, //!< Rotation about a fixed axis: a p-rotation, \f$ \hat H^3 = -\hat H \f$.
    PRISMATIC //!< Translation along a fixed direction: a p-translation, \f$ \hat H^2 = 0 \f$.
  };

  //! \f$ \exp(q \hat H) \f$ (4x4) of a joint of kind \e type: eq. (26) or (31).
  template <typename T>
  static Eigen::Matrix<T, 4, 4> exp(vpJointType type, const Eigen::Matrix<T, 4, 4> &Hhat, const T &q)
  {
    return type == REVOLUTE ? vpProjectiveRotation::exp(Hhat, q) : vpProjectiveTranslation::exp(Hhat, q);
  }
  //! \f$ \exp(q \hat H) M \f$ (4x1) of a joint of kind \e type, without forming the 4x4 exponential.
  template <typename T>
  static Eigen::Matrix<T, 4, 1> act(vpJointType type, const Eigen::Matrix<T, 4, 4> &Hhat, const T &q,
                                    const Eigen::Matrix<T, 4, 1> &M)
  {
    return type == REVOLUTE ? vpProjectiveRotation::act(Hhat, q, M) : vpProjectiveTranslation::act(Hhat, q, M);
  }
  /*!
    Generator (4x4) of a joint of kind \e type from a displacement \e H of the joint by \e amount (its encoder
    reading): vpProjectiveRotation::log() or vpProjectiveTranslation::log().
  */
  static Eigen::Matrix4d log(vpJointType type, const vpProjectiveDisplacement &H, double amount);
  //! The closest exact generator of kind \e type: vpProjectiveRotation::project() or
  //! vpProjectiveTranslation::project().
  static Eigen::Matrix4d project(vpJointType type, const Eigen::Matrix4d &Hhat);
  /*!
    Metric twist (4x4) of a joint of kind \e type: vpMetricTwist::revolute(axis, point) (unit \e axis through
    \e point) or vpMetricTwist::prismatic(axis) (\e axis the motion per unit of joint value; \e point unused).
  */
  template <typename T>
  static Eigen::Matrix<T, 4, 4> twist(vpJointType type, const Eigen::Matrix<T, 3, 1> &axis,
                                      const Eigen::Matrix<T, 3, 1> &point)
  {
    return type == REVOLUTE ? vpMetricTwist::revolute(axis, point) : vpMetricTwist::prismatic(axis);
  }
  //! "revolute" or "prismatic".
  static const char *name(vpJointType type);
};

END_VISP_NAMESPACE

#endif
