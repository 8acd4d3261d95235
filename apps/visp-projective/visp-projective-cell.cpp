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

#include "visp-projective-cell.h"

#include <iomanip>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
void printCell(const vpProjectiveCellFingerprint &cell, std::ostream &os)
{
  typedef vpProjectiveCellFingerprint FP;
  if (cell.getWidth() == 0 && cell.getCameraSide() == FP::SIDE_UNKNOWN && !FP::isKnown(cell.getLeftCamera())) {
    os << "cameras: not recorded (a model made before the cell's fingerprint, or not from a session)" << std::endl;
    return;
  }
  os << "cameras: ";
  if (cell.getWidth() > 0) {
    os << "left images " << cell.getWidth() << " x " << cell.getHeight() << ", ";
  }
  if (FP::isKnown(cell.getLeftCamera()) || FP::isKnown(cell.getRightCamera())) {
    os << "left " << FP::toString(cell.getLeftCamera()) << ", right " << FP::toString(cell.getRightCamera()) << ", ";
  }
  const Eigen::Vector3d &b = cell.getBaselineDirection();
  os << "the right camera " << FP::toString(cell.getCameraSide());
  if (cell.getCameraSide() != FP::SIDE_UNKNOWN) {
    os << std::fixed << std::setprecision(3) << " (the baseline's direction (" << b(0) << ", " << b(1) << ", " << b(2)
       << ") in the left camera's frame)";
    os.unsetf(std::ios::floatfield);
  }
  os << ", layout " << FP::toString(cell.getCameraLayout()) << std::endl;
}
} // namespace vispProjective
