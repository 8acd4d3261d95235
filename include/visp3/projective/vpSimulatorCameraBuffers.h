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
  \file vpSimulatorCameraBuffers.h
  \brief One camera of a simulated stereo rig as the image renderers see it: its parameters, its pose and the
  renderers' per-pixel work buffers.
*/

#ifndef _vpSimulatorCameraBuffers_h_
#define _vpSimulatorCameraBuffers_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <visp3/core/vpCameraParameters.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpSimulatorCameraBuffers
  \ingroup group_projective_simulator
  \brief The left or right camera of a vpSimulatorStereoRig with the buffers an image renderer works in, shared by
  vpSimulatorMarkerRenderer and vpSimulatorTagRenderer (users do not need it).

  A renderer writes the ideal (noise-free, unblurred) grey levels of the pixels it draws into \e ideal, blurs them
  separably through \e horizontal into \e blurred, and marks each pixel it has drawn in the current frame in \e stamp
  (a pixel is drawn in frame \e frame when its stamp is \e frame or more), so that only the pixels near what it draws
  are touched and the buffers are reset by region, not whole. All images are the rig's height x width.
*/
class VISP_EXPORT vpSimulatorCameraBuffers
{
public:
  //! No camera: empty buffers, identity pose, default parameters.
  vpSimulatorCameraBuffers() = default;
  /*!
    The left (\e right false) or right camera of \e rig: its parameters, its pose \f$ {}^c M_w \f$ (the inverse of
    the camera's pose in the world frame) and buffers of the rig's image size filled with \e background.
  */
  vpSimulatorCameraBuffers(const vpSimulatorStereoRig &rig, bool right, double background);

  //! Fills the ideal, horizontal and blurred images with \e background, the stamps with 0, and restarts the frames.
  void reset(double background);

  vpCameraParameters cam;      //!< Intrinsic parameters.
  vpHomogeneousMatrix cMw;     //!< World frame in the camera frame.
  vpImage<double> ideal;       //!< Ideal grey levels (before blur and noise).
  vpImage<double> horizontal;  //!< The ideal image blurred along the rows.
  vpImage<double> blurred;     //!< The ideal image blurred along the rows and the columns.
  vpImage<unsigned int> stamp; //!< The frame in which each pixel was last drawn.
  unsigned int frame = 0;      //!< The current frame.
};

END_VISP_NAMESPACE

#endif
