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
  Private: the codes of the AprilTag family that the tag renderer prints. Not installed.
*/

#ifndef _vpAprilTag36h11_h_
#define _vpAprilTag36h11_h_

#include <cstdint>

namespace vpProjectiveInternal
{
/*
  Data of the tag36h11 family of AprilTag 3 (https://github.com/AprilRobotics/apriltag, tag36h11.c; ViSP 3.5 ships
  it in 3rdparty/apriltag), under the BSD 2-clause licence below: the first 32 of its 587 codes and the position of
  each of its 36 bits in the 8 x 8 grid inside the white quiet zone (the black border is rows and columns 0 and 7).
  Bit i of a code (the most significant first, 1 = white) is the cell (kBitX[i], kBitY[i]), x the column.

  The licence of that data:
  Copyright (C) 2013-2016, The Regents of The University of Michigan.
  All rights reserved.
  This software was developed in the APRIL Robotics Lab under the
  direction of Edwin Olson, ebolson@umich.edu. This software may be
  available under alternative licensing terms; contact the address above.
  Redistribution and use in source and binary forms, with or without
  modification, are permitted provided that the following conditions are met:
  1. Redistributions of source code must retain the above copyright notice, this
     list of conditions and the following disclaimer.
  2. Redistributions in binary form must reproduce the above copyright notice,
     this list of conditions and the following disclaimer in the documentation
     and/or other materials provided with the distribution.
  THIS SOFTWARE IS PROVIDED BY THE COPYRIGHT HOLDERS AND CONTRIBUTORS "AS IS" AND
  ANY EXPRESS OR IMPLIED WARRANTIES, INCLUDING, BUT NOT LIMITED TO, THE IMPLIED
  WARRANTIES OF MERCHANTABILITY AND FITNESS FOR A PARTICULAR PURPOSE ARE
  DISCLAIMED. IN NO EVENT SHALL THE COPYRIGHT OWNER OR CONTRIBUTORS BE LIABLE FOR
  ANY DIRECT, INDIRECT, INCIDENTAL, SPECIAL, EXEMPLARY, OR CONSEQUENTIAL DAMAGES
  (INCLUDING, BUT NOT LIMITED TO, PROCUREMENT OF SUBSTITUTE GOODS OR SERVICES;
  LOSS OF USE, DATA, OR PROFITS; OR BUSINESS INTERRUPTION) HOWEVER CAUSED AND
  ON ANY THEORY OF LIABILITY, WHETHER IN CONTRACT, STRICT LIABILITY, OR TORT
  (INCLUDING NEGLIGENCE OR OTHERWISE) ARISING IN ANY WAY OUT OF THE USE OF THIS
  SOFTWARE, EVEN IF ADVISED OF THE POSSIBILITY OF SUCH DAMAGE.
  The views and conclusions contained in the software and documentation are those
  of the authors and should not be interpreted as representing official policies,
  either expressed or implied, of the Regents of The University of Michigan.
*/
inline constexpr uint64_t kCodes36h11[32] = {
    0xd7e00984bULL, 0xdda664ca7ULL, 0xdc4a1c821ULL, 0xe17b470e9ULL, 0xef91d01b1ULL, 0xf429cdd73ULL, 0x05da29225ULL,
    0x1106cba43ULL, 0x223bed79dULL, 0x21f51213cULL, 0x33eb19ca6ULL, 0x3f76eb0f8ULL, 0x469a97414ULL, 0x45dcfe0b0ULL,
    0x4a6465f72ULL, 0x51801db96ULL, 0x5eb946b4eULL, 0x68a7cc2ecULL, 0x6f0ba2652ULL, 0x78765559dULL, 0x87b83d129ULL,
    0x86cc4a5c5ULL, 0x8b64df90fULL, 0x9c577b611ULL, 0xa3810f2f5ULL, 0xaf4d75b83ULL, 0xb59a03fefULL, 0xbb1096f85ULL,
    0xd1b92fc76ULL, 0xd0dd509d2ULL, 0xe2cfda160ULL, 0x2ff497c63ULL};
inline constexpr unsigned char kBitX[36] = {1, 2, 3, 4, 5, 2, 3, 4, 3, 6, 6, 6, 6, 6, 5, 5, 5, 4,
                                            6, 5, 4, 3, 2, 5, 4, 3, 4, 1, 1, 1, 1, 1, 2, 2, 2, 3};
inline constexpr unsigned char kBitY[36] = {1, 1, 1, 1, 1, 2, 2, 2, 3, 1, 2, 3, 4, 5, 2, 3, 4, 3,
                                            6, 6, 6, 6, 6, 5, 5, 5, 4, 6, 5, 4, 3, 2, 5, 4, 3, 4};
} // namespace vpProjectiveInternal

#endif
