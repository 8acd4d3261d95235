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
  Private: the Gaussian kernel of the renderers' optical blur. Not installed.
*/

#ifndef _vpGaussianKernel_h_
#define _vpGaussianKernel_h_

#include <cmath>
#include <vector>

#include <visp3/core/vpConfig.h>
#include <visp3/core/vpImageFilter.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpProjectiveInternal
{
//! Half of a normalised Gaussian kernel of 3 sigma on each side (its centre first); {1} for no blur (sigma <= 0).
inline std::vector<double> halfKernel(double sigma)
{
  if (sigma <= 0.0) {
    return std::vector<double>(1, 1.0);
  }
  const unsigned int size = 2 * static_cast<unsigned int>(std::ceil(3.0 * sigma)) + 1;
  std::vector<double> kernel((size + 1) / 2);
  vpImageFilter::getGaussianKernel(kernel.data(), size, sigma, true);
  return kernel;
}
} // namespace vpProjectiveInternal

#endif
