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
  \file study-control.h
  \brief The control settings every method of the study shares, its damped least-squares law, and the interface of a
  controller driven by the study's loop: only the Jacobian differs between the methods.
*/

#ifndef _study_study_control_h_
#define _study_study_control_h_

#include <algorithm>
#include <cmath>
#include <functional>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpServoDampedLeastSquares.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Control settings]
/*!
  The control settings every method shares, those of the main job's projective task: gain 0.5, joint steps
  limited to 15 deg per iteration (the whole velocity scaled down, keeping its direction), and damped least squares
  \f$ \dot q = -\lambda (J^T J + \mu^2 I)^{-1} J^T e \f$ with \f$ \mu^2 = \mu_{max}^2 (1 - (\sigma_{min} /
  \sigma_0)^2) \f$ when the smallest singular value \f$ \sigma_{min} \f$ of J (pixels per radian) is below
  \f$ \sigma_0 \f$, 0 otherwise (vpServoProjective::setDamping(30, 30)).
*/
struct ControlSettings {
  double lambda = 0.5;
  double qdotMax = vpMath::rad(15.0); // rad per iteration
  double sigmaThreshold = 30.0;       // sigma_0, px/rad
  double maxDamping = 30.0;           // mu_max, px/rad
};

//! The control law of vpServoProjective::computeControlLaw() on a given Jacobian J (px/rad) and error e (px): the
//! plugin's one damped least-squares law, with the study's settings.
inline vpColVector dampedLeastSquares(const vpMatrix &J, const vpColVector &e, const ControlSettings &settings)
{
  vpServoDampedLeastSquares law;
  law.setDamping(settings.sigmaThreshold, settings.maxDamping);
  law.setMaxJointVelocity(settings.qdotMax);
  return law.computeVelocity(J, e, settings.lambda);
}
//! [Control settings]

//! A controller driven by the study's loop: image measurements of the tracked stereo points in, joint velocity out.
class Controller
{
public:
  virtual ~Controller() {}
  /*!
    Called once at the start configuration \e q0 before the servo loop. \e moveAndMeasure(q, left, right) moves the
    arm to q and returns false if a tracked point is then out of an image or q is beyond a joint limit (the arm
    does not move then). Returns false if the controller cannot start; \e moves counts the extra configurations
    visited.
  */
  virtual bool prepare(const vpColVector &q0,
                       const std::function<bool(const vpColVector &, std::vector<vpImagePoint> &,
                                                std::vector<vpImagePoint> &)> &moveAndMeasure,
                       unsigned int &moves)
  {
    (void)q0;
    (void)moveAndMeasure;
    moves = 0;
    return true;
  }
  /*!
    Joint velocity (rad per iteration) at joint values \e q from the measured stereo points; \e tracked[k] is false
    for a point the tracker lost at this iteration (its measurement is then meaningless).
  */
  virtual vpColVector velocity(const vpColVector &q, const std::vector<vpImagePoint> &left,
                               const std::vector<vpImagePoint> &right, const std::vector<bool> &tracked) = 0;
  //! The points the controller itself rejected as outliers at the last velocity() (none by default).
  virtual void rejected(std::vector<bool> &flags) const { flags.clear(); }
};
} // namespace study

#endif
