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
  Private: what the sources of vpProjectiveAcquisitionProcedure share (the procedure, its motions, its checks, the
  mounting's detection). Not installed.
*/

#ifndef _vpProjectiveAcquisitionInternal_h_
#define _vpProjectiveAcquisitionInternal_h_

#include <chrono>
#include <iomanip>
#include <sstream>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveAcquisitionInternal
{
//! The kinds of the procedure's notices (vpProjectiveNotices: 32 to 39 are the acquisition procedure's).
enum vpAcquisitionNotice {
  NOTICE_MOUNTING_REPLACED = 32, //!< The mounting found replaced the one set.
  NOTICE_MARKER_DROPPED = 33,    //!< An identified marker seen in too few trials was left out of the model.
  NOTICE_TRIAL_DROPPED = 34      //!< A trial that shows fewer than 5 of the markers kept was left out.
};

inline std::string at(const char *method)
{
  return std::string("vpProjectiveAcquisitionProcedure::") + method;
}

inline double seconds()
{
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}

inline std::string jointValue(double v, bool revolute)
{
  std::ostringstream os;
  os << std::setprecision(6) << (revolute ? vpMath::deg(v) : v) << (revolute ? " deg" : " m");
  return os.str();
}

/*!
  The general-position margin of the points \e X (unit 4-vectors in \e rig's frame; pixels): over the sets of 5
  points, the largest of the smallest RMS plane parallax of 4 points of the set to the plane that fits them best;
  \e best receives that set. At most the first 24 points are examined (a lower bound for more). Also used by
  vpProjectiveSessionCalibration.
*/
double generalPositionParallax(const vpProjectiveStereoRig &rig, const std::vector<Eigen::Vector4d> &X,
                               std::vector<unsigned int> &best);

/*!
  RMS distance (pixels) between the right images and the left ones mapped by the least-squares homography of all
  the pairs: at the noise level when the markers are all on one plane. Also used by vpProjectiveSessionCalibration.
*/
double homographyTransferError(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right);
} // namespace vpProjectiveAcquisitionInternal

#endif
