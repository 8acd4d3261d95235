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

#include "core/vpProjectiveConversions.h"

#include <sstream>

namespace vpProjectiveInternal
{
std::vector<Eigen::Vector4d> stackStereoImages(const std::vector<vpImagePoint> &left,
                                               const std::vector<vpImagePoint> &right, const std::string &where)
{
  if (left.size() != right.size()) {
    std::ostringstream os;
    os << "got " << left.size() << " left and " << right.size() << " right marker images; pass matched pairs";
    fail(vpProjectiveException::dimensionError, where, os.str());
  }
  std::vector<Eigen::Vector4d> s(left.size());
  for (size_t j = 0; j < left.size(); ++j) {
    // Both pixels converted (and checked) before the comma initialiser starts: a throw inside it would leave it
    // unfinished, which Eigen asserts on when assertions are on (the sanitizer build).
    const Eigen::Vector2d l = toEigen(left[j], where, "a left marker image");
    const Eigen::Vector2d r = toEigen(right[j], where, "a right marker image");
    s[j] << l, r;
  }
  return s;
}
} // namespace vpProjectiveInternal
