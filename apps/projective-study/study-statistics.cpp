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
  \file study-statistics.cpp
  \brief Percentiles and number formatting of the study.
*/

#include "study-statistics.h"

#include <algorithm>
#include <iomanip>
#include <limits>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
double percentile(std::vector<double> x, double p)
{
  if (x.empty()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  std::sort(x.begin(), x.end());
  const size_t rank = static_cast<size_t>(std::ceil(p * x.size()));
  return x[std::min(x.size() - 1, rank > 0 ? rank - 1 : 0)];
}

std::string fixed(double x, int digits)
{
  if (!std::isfinite(x)) {
    return "-";
  }
  std::ostringstream os;
  os << std::fixed << std::setprecision(digits) << x;
  return os.str();
}

std::string seedList(const std::vector<unsigned int> &seeds)
{
  std::ostringstream os;
  for (size_t i = 0; i < seeds.size(); ++i) {
    os << (i ? ", " : "") << seeds[i];
  }
  return os.str();
}
} // namespace study
