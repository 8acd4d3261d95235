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
  \file vpProjectiveException.h
  \brief Error raised by every class of the visp_projective plugin.
*/

#ifndef _vpProjectiveException_h_
#define _vpProjectiveException_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>

#include <visp3/core/vpException.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveException
  \ingroup group_projective
  \brief Error raised by the visp_projective classes when an input is invalid or degenerate.

  It derives from vpException, so existing ViSP applications that catch vpException also catch it. The code tells the
  kind of problem; the message says what was wrong and what to do.
*/
class VISP_EXPORT vpProjectiveException : public vpException
{
public:
  //! Kinds of error.
  enum errorProjectiveCodeEnum {
    notEnoughPointsError = 100,   //!< Fewer points or matches than the estimator needs.
    degenerateConfigurationError, //!< Coplanar, collinear or repeated points, or another critical configuration.
    nonFiniteValueError,          //!< An input contains NaN or infinity.
    dimensionError,               //!< Sizes of matrices or vectors do not match.
    notInitializedError,          //!< A method was called before the data it needs was set.
    invalidValueError,            //!< A value is out of its domain (zero trial motion, negative gain, ...).
    pointAtInfinityError,         //!< A point cannot be projected: it lies on a camera's focal plane or behind it.
    fileError,                    //!< A model file is missing, truncated, corrupted or of another version.
    estimationFailedError,        //!< An estimator did not converge to a usable result.
    robotMotionError,             //!< A robot did not reach a commanded position within its timeout.
    modelRejectedError            //!< A calibrated model fits its images far worse than their noise: refused, with
                                  //!< its probable causes (vpProjectiveModelCheck).
  };

  //! An error of kind \e code (errorProjectiveCodeEnum) with a message saying what was wrong and what to do.
  vpProjectiveException(int code, const std::string &message) : vpException(code, message) {}
};

END_VISP_NAMESPACE

#endif
