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
 * visp_projective: a program built against the installed plugin (ctest case external_project).
 * A rectified rig given by its fundamental matrix: triangulate, reproject, and start a projective robot model.
 */

#include <cmath>
#include <iostream>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/projective/vpProjectiveException.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpStereoAprilTagDetector.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

int main()
{
  try {
    // Rectified pair: corresponding points share their row, m'^T F m = v - v' = 0.
    vpMatrix F(3, 3, 0.0);
    F[1][2] = -1.0;
    F[2][1] = 1.0;
    vpProjectiveStereoRig rig;
    rig.setFundamentalMatrix(F);

    // Markers seen with a disparity (u - u') that varies: a non-planar set of 6 points.
    const double uv[6][3] = {{320, 240, 20}, {400, 250, 25}, {280, 180, 18},
                             {350, 300, 30}, {300, 320, 22}, {420, 200, 27}};
    std::vector<vpImagePoint> left, right;
    double worst = 0.0;
    for (const auto &p : uv) {
      const vpImagePoint ipLeft(p[1], p[0]), ipRight(p[1], p[0] - p[2]);
      const vpColVector M = rig.triangulate(ipLeft, ipRight);
      vpImagePoint l, r;
      rig.project(M, l, r);
      worst = std::max(worst, std::max(vpImagePoint::distance(l, ipLeft), vpImagePoint::distance(r, ipRight)));
      left.push_back(ipLeft);
      right.push_back(ipRight);
    }
    std::cout << "triangulated " << left.size() << " points, worst reprojection error " << worst << " px" << std::endl;
    if (!(worst < 1e-6)) {
      std::cerr << "reprojection error too large" << std::endl;
      return 1;
    }

    // A 2-joint projective robot: the zero reference is accepted, calibrating without trial motions is refused.
    vpProjectiveRobot robot(std::vector<vpProjectiveRobot::vpJointType>(2, vpProjectiveRobot::REVOLUTE));
    robot.setStereoRig(rig);
    robot.setZeroReference(left, right);
    bool refused = false;
    try {
      robot.calibrate();
    } catch (const vpProjectiveException &e) {
      refused = true;
      std::cout << "calibrate() without trial motions refused as expected (code " << e.getCode() << ")" << std::endl;
    }
    if (robot.getNumberOfJoints() != 2 || robot.isCalibrated() || !refused) {
      std::cerr << "unexpected robot state" << std::endl;
      return 1;
    }

#if defined(VISP_HAVE_APRILTAG)
    // The tag detector (ViSP's detection module through the package): a blank pair has no corner.
    vpStereoAprilTagDetector tags(vpDetectorAprilTag::TAG_36h11);
    const vpImage<unsigned char> blank(48, 64, 128);
    if (tags.detect(blank, blank) != 0) {
      std::cerr << "corners found in blank images" << std::endl;
      return 1;
    }
#endif
  } catch (const vpException &e) {
    std::cerr << "error: " << e.getMessage() << std::endl;
    return 1;
  }
  std::cout << "OK" << std::endl;
  return 0;
}
