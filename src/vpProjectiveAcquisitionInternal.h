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

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpMath.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveAcquisitionInternal
{
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
} // namespace vpProjectiveAcquisitionInternal

#endif
