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
  The C++ side of test_geometry.py's comparison: vpProjectiveStereoRig::estimate() on the matches of a text file, its
  results printed with every digit, so that the test compares them with the Python module's on the same numbers.
    rig-reference MATCHES
  MATCHES: "N threshold", then N lines "u v u' v'". Prints F (9 values, row-major), the residual, then one 0/1 per
  match (inlier). Exit status 0, or 1 with the exception's message on stderr.
*/

#include <cstdio>
#include <fstream>
#include <iostream>
#include <vector>

#include <visp3/core/vpException.h>
#include <visp3/projective/vpProjectiveStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main(int argc, char **argv)
{
  if (argc != 2) {
    std::cerr << "Usage: " << argv[0] << " MATCHES" << std::endl;
    return 1;
  }
  std::ifstream in(argv[1]);
  size_t n = 0;
  double threshold = 0.0;
  in >> n >> threshold;
  std::vector<vpImagePoint> left(n), right(n);
  for (size_t k = 0; k < n; ++k) {
    double u, v, up, vp;
    in >> u >> v >> up >> vp;
    left[k].set_uv(u, v);
    right[k].set_uv(up, vp);
  }
  if (!in) {
    std::cerr << "cannot read " << argv[1] << std::endl;
    return 1;
  }
  try {
    vpProjectiveStereoRig rig;
    rig.estimate(left, right, threshold);
    const vpMatrix F = rig.getFundamentalMatrix();
    for (unsigned int k = 0; k < 9; ++k) {
      std::printf("%.17g\n", F.data[k]);
    }
    std::printf("%.17g\n", rig.getEstimationResidual());
    for (bool inlier : rig.getInliers()) {
      std::printf("%d\n", inlier ? 1 : 0);
    }
  } catch (const vpException &e) {
    std::cerr << e.getStringMessage() << std::endl;
    return 1;
  }
  return 0;
}
