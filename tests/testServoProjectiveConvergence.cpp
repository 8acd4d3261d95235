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
  Tests of vpServoProjective's closed loop (settings in vpServoProjectiveTestTools.h): 10 random start/target pairs
  (target within +-20 deg of the zero reference, start within +-15 deg of the target, markers in view at both ends)
  for the PUMA and for the Viper850 with markers 0-2, and 10 small pairs (+-3 deg, +-2 deg) eye-in-hand with all 7
  markers, all reach an RMS image error below 1e-6 px within 200 iterations, and the joints reach the target's.
*/

#include <gtest/gtest.h>

#include "vpServoProjectiveTestTools.h"

using namespace vpProjectiveTest;

TEST(ServoProjective, ConvergesNoiseFreePuma)
{
  expectConvergence(pumaEyeToHand(), 1, 10, vpMath::rad(20.0), vpMath::rad(15.0));
}

TEST(ServoProjective, ConvergesNoiseFreeViper850)
{
  expectConvergence(viperEyeToHand(), 2, 10, vpMath::rad(20.0), vpMath::rad(15.0));
}

TEST(ServoProjective, ConvergesNoiseFreeEyeInHand)
{
  // The rig on the PUMA's tool, 7 static markers; the eye-in-hand view allows only a few degrees per joint. A camera
  // 1 m from an 8 cm object barely tells a sideways translation from a rotation: sigma_min / sigma_max ~ 4e-4 at the
  // zero reference (3 and 8100 px/rad with markers 0-2, 4.7 and 12300 with all 7) and lower on some paths. Measured
  // on these pairs: damping from sigma_0 = 1 stalls 3 of 10 pairs with markers 0-2 (2 of 10 with all 7); without any
  // damping one 3-marker pair wandered off near a singularity; all 7 markers with sigma_0 = 0.1 converge.
  expectConvergence(pumaEyeInHand(), 3, 10, vpMath::rad(3.0), vpMath::rad(2.0), 0.1, {0, 1, 2, 3, 4, 5, 6});
}
