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
  \file study-calibration.cpp
  \brief Believed calibrations of the calibrated baseline.
*/

#include "study-calibration.h"

#include <visp3/core/vpThetaUVector.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
unsigned int countLinkLengths(const std::vector<vpSimulatorArm::vpDHRow> &dh)
{
  unsigned int count = 0;
  for (const vpSimulatorArm::vpDHRow &row : dh) {
    count += (row.d != 0.0) + (row.a != 0.0);
  }
  return count;
}

BelievedCalibration believedCalibration(const vpSimulatorStereoRig &rig, const vpSimulatorArm &arm,
                                        const CalibrationErrorDirection &dir, double factor,
                                        const CalibrationErrorMagnitude &magnitude)
{
  const vpCameraParameters &cl = rig.getLeftCameraParameters(), &cr = rig.getRightCameraParameters();
  const double k = factor * magnitude.intrinsics;
  const std::vector<double> &s = dir.intrinsicSigns;
  vpCameraParameters camLeft, camRight;
  camLeft.initPersProjWithoutDistortion(cl.get_px() * (1 + k * s[0]), cl.get_py() * (1 + k * s[1]),
                                        cl.get_u0() * (1 + k * s[2]), cl.get_v0() * (1 + k * s[3]));
  camRight.initPersProjWithoutDistortion(cr.get_px() * (1 + k * s[4]), cr.get_py() * (1 + k * s[5]),
                                         cr.get_u0() * (1 + k * s[6]), cr.get_v0() * (1 + k * s[7]));

  const vpThetaUVector rigTu(dir.rigAxis[0] * factor * magnitude.rigRotation,
                             dir.rigAxis[1] * factor * magnitude.rigRotation,
                             dir.rigAxis[2] * factor * magnitude.rigRotation);
  const vpHomogeneousMatrix rigDelta(vpTranslationVector(0, 0, 0), rigTu);
  const vpThetaUVector baseTu(dir.baseAxis[0] * factor * magnitude.baseRotation,
                              dir.baseAxis[1] * factor * magnitude.baseRotation,
                              dir.baseAxis[2] * factor * magnitude.baseRotation);
  const double t = factor * magnitude.baseTranslation;
  const vpHomogeneousMatrix baseDelta(
      vpTranslationVector(dir.baseDirection[0] * t, dir.baseDirection[1] * t, dir.baseDirection[2] * t), baseTu);

  std::vector<vpSimulatorArm::vpDHRow> dh = arm.getDHTable();
  unsigned int j = 0;
  const double l = factor * magnitude.linkLengths;
  for (vpSimulatorArm::vpDHRow &row : dh) {
    if (row.d != 0.0) {
      row.d *= 1 + l * dir.linkSigns[j++];
    }
    if (row.a != 0.0) {
      row.a *= 1 + l * dir.linkSigns[j++];
    }
  }
  vpHomogeneousMatrix eMt = arm.get_eMt();
  for (unsigned int i = 0; i < 3; ++i) {
    eMt[i][3] *= 1 + l * dir.linkSigns[j];
  }
  return BelievedCalibration{camLeft, camRight, rigDelta * rig.get_rMl(), baseDelta * rig.get_wMl().inverse(),
                             vpSimulatorArm(dh, eMt, arm.getToolMarkers(), arm.get_wMb())};
}
} // namespace study
