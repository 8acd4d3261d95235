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
  Private: the check that joint values given by a user (limits, amounts, steps) are in the plugin's units, radians and
  metres: used by vpProjectiveAcquisitionProcedure and vpServoProjective. Not installed.
*/

#ifndef _vpJointUnits_h_
#define _vpJointUnits_h_

#include <cmath>
#include <string>
#include <vector>

#include <visp3/core/vpArray2D.h>

#include "core/vpProjectiveErrors.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
/*!
  Joint values (limits, amounts, steps: n x 1) in the plugin's units: a revolute joint's within [-2 pi, 2 pi] radians,
  a prismatic joint's within 10 m, \e revolute[i] telling joint i's type (empty: types unknown, every joint within
  10). Otherwise throws invalidValueError naming the joint, \e what (e.g. "qmax") and the probable unit.
*/
inline void requireJointUnits(const vpArray2D<double> &values, const std::vector<bool> &revolute,
                              const std::string &where, const std::string &what)
{
  for (unsigned int i = 0; i < values.getRows(); ++i) {
    const double x = values[i][0];
    const bool known = i < revolute.size();
    const bool turns = known && revolute[i];
    if (std::abs(x) > (turns ? 2.0 * M_PI : 10.0)) {
      fail(vpProjectiveException::invalidValueError, where,
           "joint " + std::to_string(i) + "'s " + what + ", " + std::to_string(x) +
               (turns   ? ", is outside [-2 pi, 2 pi] for a revolute joint: probable degrees; give radians "
                          "(vpMath::rad())"
                : known ? ", exceeds 10 m for a prismatic joint: probable millimetres; give metres"
                        : ", exceeds 10: neither radians nor metres (probable degrees or millimetres); give radians "
                          "(vpMath::rad()) and metres"));
    }
  }
}
} // namespace vpProjectiveInternal

#endif
