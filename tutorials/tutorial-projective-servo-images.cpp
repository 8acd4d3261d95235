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

//! \example tutorial-projective-servo-images.cpp
/*!
  The paper's experiment of tutorial-projective-servo.cpp (Ruf & Horaud, ICCV'99, section 6) with the loop closed on
  images: the same PUMA-like arm, the same uncalibrated rig, the same trial motions and the same servo task, but every
  pixel the plugin gets is the centre of a blob that ViSP's vpDot2 tracker followed in rendered 8-bit images. No
  ground-truth projection enters the loop.

  1. Images. Each camera of the simulated rig renders a 640 x 480 8-bit image of the gripper's lit markers, 6 mm
     balls bright on a dark scene: the exact perspective silhouette of every ball (its size follows its depth; a
     nearer ball hides a farther one) sampled by 8 x 8 rays per pixel, blurred by the optics (Gaussian, 0.8 px), with
     Gaussian sensor noise (4 grey levels, seeded) and 8-bit quantisation.
  2. Tracking. vpDot2 follows every marker from frame to frame in both images (vpDot2::track(), vpDot2::getCog()).
     The ground truth gives image measurements once only: a simulated user click a little off each marker at the
     start, that vpDot2::initTracking() refines. From then on a marker is whatever its tracker followed. The cameras
     grab frames while the arm moves, often enough for the blobs to move by about 8 px between frames, and each
     tracker starts from its blob's previous position moved at constant image velocity.
  3. Acquisition from images: the 7 markers are tracked at the zero reference and through each trial motion (the
     paper's [30, 20, 30, 40, 60, 60] deg, each joint both ways); the fundamental matrix is estimated from the tracked
     centres, then vpProjectiveRobot::calibrate() runs as in the main tutorial. A trial ends early, at its last
     trustworthy frame, where two blobs are about to merge or a blob leaves the image (the main tutorial shortens the
     trials that leave the image too).
  4. Teaching and servoing from images: the arm is shown the target (s* = the tracked centres there), driven to the
     start, and servoed by vpServoProjective with vpFeatureStereoPoint built from the tracked centres, every joint
     step imaged frame by frame. The servo is the main tutorial's (lambda = 0.5, joint steps limited to 15 deg).
  5. Over several seeds, the main tutorial's table (convergence, iterations, final joint errors against the noise
     floor), the tracking accuracy (tracked centre minus true projection, measured for this report only) and the
     final joint errors against the main job's at 0.5 px noise.

  Every tracking problem is detected and reported, never hidden: vpDot2 losing a blob, a blob at the image border
  (leaving the image), a blob whose area jumps (merged with another one), a blob found away from its predicted
  position (the tracker jumped to another blob), two blobs a few pixels apart (about to merge). A tracking failure
  ends the run, which then counts as not converged.

  Which markers are seen. The simulator, and so the main job, sees every marker from every direction, as if the
  gripper were transparent. A renderer that hid the markers on the faces turned away from the rig (painted discs, or
  domes stuck on the faces) could not run this experiment at all: at the zero reference only markers 0-3 face both
  cameras (the program prints it), fewer than the 5 non-coplanar markers the acquisition needs in every one of its
  images, and at the target the face of the servo's markers 0-2 is turned away from the rig by more than 120 deg, so
  the main task could not even be taught. Hiding them would change the markers, the acquisition and the task, and
  leave nothing to compare with the main job, which is what this program is for. The markers are therefore active
  ones, as motion-capture systems use: infrared LEDs in diffusing balls standing off the gripper, each seen from all
  around and switched on or off at will. The acquisition lights all 7. Teaching and servoing light only the 3 they
  track: on its way from the start to the target the arm moves marker 6 (which a real gripper would hide) across
  marker 2 in both images, and a blob tracker cannot tell two crossing blobs apart. What a blob tracker really suffers
  from stays: sub-pixel rendering, blur, noise, blob size following depth, lit markers crossing each other (the
  acquisition shortens joint 4's trials for it) and the image border.

  Usage: tutorial-projective-servo-images [--seeds N] [--model FILE] [--output DIR] [--no-display] [--help]
  - --seeds N: number of seeds (default 20, as the main job; about 25 s of computation).
  - --model FILE: if FILE exists, the model is loaded from it and every seed servoes with it (no acquisition);
    otherwise seed 1 acquires the arm from images, saves the model to FILE and the other seeds servo with it.
    Without it, every seed acquires its own model.
  - --output DIR: writes the final left and right images of seed 1 with the feature trajectories as PNG.
  - --no-display: no window even if an X display is available (without one, none is opened).
  The exit code is 0 only if every seed converged.
*/

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/blob/vpDot2.h>
#include <visp3/core/vpColVector.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImageConvert.h>
#include <visp3/core/vpImageDraw.h>
#include <visp3/core/vpImageFilter.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTime.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/gui/vpDisplayX.h>
#include <visp3/io/vpImageIo.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorArm.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#include "tutorial-projective-common.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
//! [World]
//! What only the simulator knows: the metric rig, the arm, and the task in its joint values. All as in the main
//! tutorial (see there how the start and the target were chosen: the gripper translates by 82 cm, turns by 88 deg).
struct World {
  vpSimulatorStereoRig rig = vpSimulatorStereoRig::paperRig(vpColVector(3, 0.0), 1.0);
  vpSimulatorArm arm = vpSimulatorArm::puma(vpSimulatorArm::paperBasePose());
  std::vector<double> trialDeg = {30, 20, 30, 40, 60, 60}; // the paper's trial motions
  std::vector<unsigned int> tracked = {0, 1, 2};           // the servo's markers
  std::vector<double> startDeg = {15.4461, 54.9087, -48.3752, 62.3954, 29.0729, 1.7330};
  std::vector<double> targetDeg = {8.1330, 7.0830, -56.4826, 90.4984, 76.3260, 57.1987};
};
//! [World]

//! [Image model]
//! What the cameras see, and how the servo is judged on it.
struct ImageModel {
  double markerRadius = 0.003;       // m: 6 mm balls, 10 px wide at 1 m
  double background = 30.0;          // grey level of the scene, dark in the infrared
  double markerLevel = 220.0;        // grey level of a lit ball
  double blurSigma = 0.8;            // px: optics
  double noiseSigma = 4.0;           // grey levels: sensor noise
  unsigned int supersampling = 8;    // 8 x 8 rays per pixel: anti-aliasing to 1/64 of a pixel's area
  double pixelsPerFrame = 8.0;       // the frame rate: blobs move by about this much between frames
  double firstStepDeg = 0.05;        // joint step of a motion's first frame, before any image velocity is known
  double convergenceThreshold = 0.2; // px: RMS(s - s*) for convergence, the main job's 2 sigma at 0.1 px
};
//! [Image model]

using tutorial::degToRad;
using tutorial::maxOf;
using tutorial::mean;

//! Joint values (rad) as a line of degrees.
std::string degrees(const vpColVector &q)
{
  std::ostringstream os;
  os << std::fixed << std::setprecision(4);
  for (unsigned int i = 0; i < q.size(); ++i) {
    os << (i > 0 ? " " : "") << vpMath::deg(q[i]);
  }
  return os.str();
}

//! [Visibility]
/*!
  Ground truth, only to explain the choice of marker model (see the header): the markers whose gripper face (as
  documented by vpSimulatorArm::gripperMarkers(): 0-2 on the front face -y, 3 on the finger tip +z, 4 on the left side
  -x, 5 and 6 on the back +y) is turned towards both cameras at configuration q.
*/
std::string markersFacingTheRig(const World &world, const vpColVector &q)
{
  const double normal[7][3] = {{0, -1, 0}, {0, -1, 0}, {0, -1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, 1, 0}, {0, 1, 0}};
  const vpHomogeneousMatrix wMt = world.arm.get_wMt(q);
  const vpHomogeneousMatrix wMl = world.rig.get_wMl(), wMr = wMl * world.rig.get_rMl().inverse();
  const std::vector<vpColVector> X = world.arm.getMarkers(q);
  std::ostringstream os;
  for (unsigned int k = 0; k < X.size() && k < 7; ++k) {
    bool facing = true;
    for (const vpHomogeneousMatrix *wMc : {&wMl, &wMr}) {
      double dot = 0.0;
      for (unsigned int a = 0; a < 3; ++a) {
        const double n = wMt[a][0] * normal[k][0] + wMt[a][1] * normal[k][1] + wMt[a][2] * normal[k][2];
        dot += n * ((*wMc)[a][3] - X[k][a]); // towards the camera centre
      }
      facing = facing && dot > 0.0;
    }
    if (facing) {
      os << k << " ";
    }
  }
  return os.str();
}
//! [Visibility]

//! [Noise]
/*!
  Sensor noise: independent Gaussian grey-level noise on every pixel, then 8-bit quantisation, seeded. 300 000
  vpGaussRand draws per image would dominate the run time, so 65536 of them are drawn once into a table, and each
  pixel takes one of them at random through a seeded vpUniRand: independent draws from a very fine sample of the
  Gaussian. Most of an image is the uniform background, whose noisy grey levels are tabulated too.
*/
class PixelNoise
{
public:
  PixelNoise(double sigma, double background, long seed)
      : m_table(65536), m_background(65536), m_uniform(static_cast<uint64_t>(seed), 1) // another stream
  {
    vpGaussRand gauss(sigma, 0.0, seed);
    for (unsigned int k = 0; k < m_table.size(); ++k) {
      m_table[k] = gauss();
      m_background[k] = quantise(background + m_table[k]);
    }
  }
  //! A noisy 8-bit image of the grey level \e level.
  unsigned char operator()(double level) { return quantise(level + m_table[index()]); }
  //! A noisy 8-bit image of the background.
  unsigned char background() { return m_background[index()]; }

private:
  static unsigned char quantise(double g)
  {
    return static_cast<unsigned char>(std::min(255.0, std::max(0.0, g)) + 0.5);
  }
  unsigned int index()
  {
    m_high = !m_high; // each 32-bit draw gives two 16-bit indices
    if (m_high) {
      m_bits = m_uniform.next();
      return m_bits & 0xFFFFu;
    }
    return m_bits >> 16;
  }
  std::vector<double> m_table;
  std::vector<unsigned char> m_background;
  vpUniRand m_uniform;
  uint32_t m_bits = 0;
  bool m_high = false;
};
//! [Noise]

//! [Renderer]
/*!
  One camera of the rig as an image sensor. Its metric model is the simulator's ground truth: the world is imaged
  through it, the plugin never sees it.
*/
class MarkerCamera
{
public:
  MarkerCamera(const vpCameraParameters &cam, const vpHomogeneousMatrix &cMw, unsigned int width, unsigned int height,
               const ImageModel &model)
      : m_cam(cam), m_cMw(cMw), m_model(model), m_ideal(height, width, model.background),
        m_horizontal(height, width, model.background), m_blurred(height, width, model.background),
        m_stamp(height, width, 0)
  {
    // Half of a normalised Gaussian kernel of 3 sigma on each side: m_kernel[0] is its centre.
    const unsigned int size = 2 * static_cast<unsigned int>(std::ceil(3.0 * model.blurSigma)) + 1;
    m_kernel.resize((size + 1) / 2);
    vpImageFilter::getGaussianKernel(m_kernel.data(), size, model.blurSigma, true);
  }

  /*!
    The image of the balls of radius R centred at the world points \e wX. A ray through a pixel hits the ball of
    camera-frame centre C when its angle to C is below asin(R / |C|): with the ray d = ((u - u0) / px, (v - v0) / py,
    1), when d.C > 0 and (d.C)^2 >= |d|^2 (|C|^2 - R^2). Each pixel near a ball averages 8 x 8 such rays (all balls
    look alike, so a nearer ball hiding a farther one is the union of their silhouettes); the image is then blurred
    and noise is added everywhere. Only the neighbourhood of the balls is rendered and blurred: elsewhere the image
    is the uniform background, which blurring leaves unchanged.
  */
  void render(const std::vector<vpColVector> &wX, PixelNoise &noise, vpImage<unsigned char> &I)
  {
    const int width = static_cast<int>(m_ideal.getWidth()), height = static_cast<int>(m_ideal.getHeight());
    const int h = static_cast<int>(m_kernel.size()) - 1;
    const double R = m_model.markerRadius;
    const double px = m_cam.get_px(), py = m_cam.get_py(), u0 = m_cam.get_u0(), v0 = m_cam.get_v0();

    // Where each ball is: its centre in the camera frame and a pixel box holding its silhouette.
    m_balls.clear();
    for (const vpColVector &X : wX) {
      Ball b;
      b.x = m_cMw[0][0] * X[0] + m_cMw[0][1] * X[1] + m_cMw[0][2] * X[2] + m_cMw[0][3];
      b.y = m_cMw[1][0] * X[0] + m_cMw[1][1] * X[1] + m_cMw[1][2] * X[2] + m_cMw[1][3];
      b.z = m_cMw[2][0] * X[0] + m_cMw[2][1] * X[1] + m_cMw[2][2] * X[2] + m_cMw[2][3];
      if (b.z <= 2.0 * R) {
        continue; // behind the camera: not imaged
      }
      b.c2 = b.x * b.x + b.y * b.y + b.z * b.z - R * R;
      // The silhouette is an ellipse of semi-axes rho and rho / cos(angle off the optical axis), 3% longer at the
      // image corners, centred within 0.01 px of the image of the ball's centre: pixels whose centre is farther than
      // 1.2 rho + 0.75 px (half a pixel diagonal) from there do not see the ball.
      const double rho = px * R / std::sqrt(b.z * b.z - R * R);
      b.u = u0 + px * b.x / b.z;
      b.v = v0 + py * b.y / b.z;
      b.reach = 1.2 * rho + 0.75;
      b.jmin = std::max(0, static_cast<int>(std::floor(b.u - b.reach)));
      b.jmax = std::min(width - 1, static_cast<int>(std::ceil(b.u + b.reach)));
      b.imin = std::max(0, static_cast<int>(std::floor(b.v - b.reach)));
      b.imax = std::min(height - 1, static_cast<int>(std::ceil(b.v + b.reach)));
      if (b.jmin <= b.jmax && b.imin <= b.imax) {
        m_balls.push_back(b);
      }
    }

    // Supersampled silhouettes: the fraction of a pixel's rays that hit a ball. A silhouette is convex, so a pixel
    // whose four corners see the same ball is covered: only the pixels on a silhouette's edge need the 8 x 8 rays.
    const unsigned int S = m_model.supersampling;
    const double contrast = m_model.markerLevel - m_model.background;
    const auto hit = [&](const Ball &b, double u, double v) {
      const double dx = (u - u0) / px, dy = (v - v0) / py, dc = dx * b.x + dy * b.y + b.z;
      return dc > 0.0 && dc * dc >= (dx * dx + dy * dy + 1.0) * b.c2;
    };
    ++m_frame;
    std::vector<const Ball *> near;
    for (const Ball &box : m_balls) {
      for (int i = box.imin; i <= box.imax; ++i) {
        for (int j = box.jmin; j <= box.jmax; ++j) {
          if (m_stamp[i][j] == m_frame) {
            continue; // already done for an overlapping box
          }
          m_stamp[i][j] = m_frame;
          near.clear();
          for (const Ball &b : m_balls) {
            if ((j - b.u) * (j - b.u) + (i - b.v) * (i - b.v) < b.reach * b.reach) {
              near.push_back(&b);
            }
          }
          unsigned int hits = 0;
          for (const Ball *b : near) {
            if (hit(*b, j - 0.5, i - 0.5) && hit(*b, j + 0.5, i - 0.5) && hit(*b, j - 0.5, i + 0.5) &&
                hit(*b, j + 0.5, i + 0.5)) {
              hits = S * S;
              break;
            }
          }
          for (unsigned int a = 0; a < S && hits < S * S && !near.empty(); ++a) {
            for (unsigned int c = 0; c < S; ++c) {
              for (const Ball *b : near) {
                if (hit(*b, j - 0.5 + (c + 0.5) / S, i - 0.5 + (a + 0.5) / S)) {
                  ++hits;
                  break;
                }
              }
            }
          }
          m_ideal[i][j] = m_model.background + contrast * hits / (S * S);
        }
      }
    }

    // Separable Gaussian blur (vpImageFilter's kernel) around the balls, edges replicated.
    for (const Ball &b : m_balls) {
      const int j0 = std::max(0, b.jmin - h), j1 = std::min(width - 1, b.jmax + h);
      for (int i = std::max(0, b.imin - 2 * h); i <= std::min(height - 1, b.imax + 2 * h); ++i) {
        for (int j = j0; j <= j1; ++j) {
          double sum = m_kernel[0] * m_ideal[i][j];
          for (int k = 1; k <= h; ++k) {
            sum += m_kernel[k] * (m_ideal[i][std::max(0, j - k)] + m_ideal[i][std::min(width - 1, j + k)]);
          }
          m_horizontal[i][j] = sum;
        }
      }
    }
    for (const Ball &b : m_balls) {
      const int j0 = std::max(0, b.jmin - h), j1 = std::min(width - 1, b.jmax + h);
      for (int i = std::max(0, b.imin - h); i <= std::min(height - 1, b.imax + h); ++i) {
        for (int j = j0; j <= j1; ++j) {
          double sum = m_kernel[0] * m_horizontal[i][j];
          for (int k = 1; k <= h; ++k) {
            sum += m_kernel[k] * (m_horizontal[std::max(0, i - k)][j] + m_horizontal[std::min(height - 1, i + k)][j]);
          }
          m_blurred[i][j] = sum;
        }
      }
    }

    // Sensor noise on every pixel, and 8-bit quantisation: the background, then again around the balls.
    I.resize(static_cast<unsigned int>(height), static_cast<unsigned int>(width));
    for (unsigned int k = 0; k < I.getSize(); ++k) {
      I.bitmap[k] = noise.background();
    }
    for (const Ball &b : m_balls) {
      for (int i = std::max(0, b.imin - h); i <= std::min(height - 1, b.imax + h); ++i) {
        for (int j = std::max(0, b.jmin - h); j <= std::min(width - 1, b.jmax + h); ++j) {
          I[i][j] = noise(m_blurred[i][j]);
        }
      }
    }

    // Back to the uniform background for the next image.
    for (const Ball &b : m_balls) {
      for (int i = std::max(0, b.imin - 2 * h); i <= std::min(height - 1, b.imax + 2 * h); ++i) {
        for (int j = std::max(0, b.jmin - h); j <= std::min(width - 1, b.jmax + h); ++j) {
          m_ideal[i][j] = m_horizontal[i][j] = m_blurred[i][j] = m_model.background;
        }
      }
    }
  }

private:
  struct Ball {
    double x, y, z, c2;         // centre in the camera frame (m), |C|^2 - R^2
    double u, v, reach;         // image of the centre, radius (px) beyond which no pixel sees the ball
    int imin, imax, jmin, jmax; // pixel box of the silhouette
  };
  vpCameraParameters m_cam;
  vpHomogeneousMatrix m_cMw;
  ImageModel m_model;
  std::vector<double> m_kernel;
  std::vector<Ball> m_balls;
  vpImage<double> m_ideal, m_horizontal, m_blurred; // uniform background outside the balls' boxes
  vpImage<unsigned int> m_stamp;
  unsigned int m_frame = 0;
};
//! [Renderer]

//! [Tracker]
/*!
  vpDot2 trackers of a set of markers in both images. A marker's identity is that of the tracker that followed it
  since the click. Each frame is checked with the tracked blobs alone (no ground truth) for what makes a centre
  wrong; the first problem found is reported.
*/
class StereoMarkerTracker
{
public:
  /*!
    Starts tracking the markers \e indices from clicks in both images: vpDot2::initTracking() takes the grey level
    under the click, finds the blob around it and its centre.
    \exception vpException if a click is not on a blob, or two blobs are less than minimumGap apart.
  */
  void initialise(const std::vector<unsigned int> &indices, const vpImage<unsigned char> &Il,
                  const vpImage<unsigned char> &Ir, const std::vector<vpImagePoint> &clickLeft,
                  const std::vector<vpImagePoint> &clickRight)
  {
    m_indices = indices;
    for (unsigned int c = 0; c < 2; ++c) {
      m_blobs[c].assign(indices.size(), Blob());
      for (size_t k = 0; k < indices.size(); ++k) {
        Blob &b = m_blobs[c][k];
        b.dot.setGraphics(false);
        b.dot.initTracking(c == 0 ? Il : Ir, c == 0 ? clickLeft[k] : clickRight[k]);
        b.previous = b.dot.getCog();
        b.area = b.dot.getArea();
      }
      std::string failure;
      if (!separated(c, getCogs(c), "", c == 0 ? " in the left image" : " in the right image", failure)) {
        throw vpException(vpException::fatalError, "the clicked markers are not separate blobs: " + failure);
      }
    }
    m_motion = 0.0;
  }

  //! The trackers of the markers \e which (a subset of getIndices()).
  StereoMarkerTracker subset(const std::vector<unsigned int> &which) const
  {
    StereoMarkerTracker t;
    for (unsigned int marker : which) {
      const size_t k = std::find(m_indices.begin(), m_indices.end(), marker) - m_indices.begin();
      t.m_indices.push_back(marker);
      t.m_blobs[0].push_back(m_blobs[0].at(k));
      t.m_blobs[1].push_back(m_blobs[1].at(k));
    }
    return t;
  }

  /*!
    Tracks a new stereo frame. Each blob is first predicted at constant image velocity, its last displacement scaled
    by \e stepRatio (this frame's joint step over the previous one; 0 before any motion), then vpDot2::track() finds
    it from there. Returns false, with the reason in \e failure, if two tracked blobs are (predicted, or found) less
    than minimumGap apart (about to merge), if a blob is predicted less than minimumGap from the image border
    (leaving the image), or if a blob
    - is lost (vpDot2 throws);
    - touches the image border (leaving the image);
    - changed its area A since the last frame by more than 15% + 1.5 sqrt(A) px, the pixel quantisation of a small
      blob's contour (a merge at least doubles it);
    - was found farther than its radius r plus minimumGap / 2 from the prediction: a tracker that jumped to another
      blob lands at least 2 r + minimumGap from the right place, while the prediction errs by less than r.
  */
  bool track(const vpImage<unsigned char> &Il, const vpImage<unsigned char> &Ir, double stepRatio, std::string &failure)
  {
    m_motion = 0.0;
    for (unsigned int c = 0; c < 2; ++c) {
      const vpImage<unsigned char> &I = c == 0 ? Il : Ir;
      const std::string image = c == 0 ? " in the left image" : " in the right image";
      std::vector<vpImagePoint> predicted;
      for (const Blob &b : m_blobs[c]) {
        predicted.push_back(b.dot.getCog() + (b.dot.getCog() - b.previous) * stepRatio);
      }
      if (!separated(c, predicted, "predicted ", image, failure) || !inside(c, I, predicted, image, failure)) {
        return false;
      }
      for (size_t k = 0; k < m_blobs[c].size(); ++k) {
        Blob &b = m_blobs[c][k];
        const vpImagePoint last = b.dot.getCog();
        const std::string name = "marker " + std::to_string(m_indices[k]);
        b.dot.setCog(predicted[k]);
        try {
          b.dot.track(I);
        } catch (const vpException &e) {
          failure = name + " lost by vpDot2" + image + " (" + e.getStringMessage() + ")";
          return false;
        }
        const vpImagePoint cog = b.dot.getCog();
        const vpRect box = b.dot.getBBox();
        const double area = b.dot.getArea(), miss = vpImagePoint::distance(cog, predicted[k]);
        std::ostringstream os;
        os << std::fixed << std::setprecision(1);
        if (box.getLeft() < 2 || box.getTop() < 2 || box.getRight() > I.getWidth() - 3 ||
            box.getBottom() > I.getHeight() - 3) {
          os << name << " at the image border" << image << " (leaving the image)";
        } else if (std::abs(area - b.area) > 0.15 * b.area + 1.5 * std::sqrt(b.area)) {
          os << name << "'s blob area jumped from " << b.area << " to " << area << " px" << image
             << " (merged with another blob, or hidden by it)";
        } else if (miss > std::sqrt(area / M_PI) + 0.5 * minimumGap) {
          os << name << " found " << miss << " px from its predicted position" << image
             << " (the tracker may have jumped to another blob)";
        }
        if (!os.str().empty()) {
          failure = os.str();
          return false;
        }
        m_motion = std::max(m_motion, vpImagePoint::distance(cog, last));
        b.previous = last;
        b.area = area;
      }
      if (!separated(c, getCogs(c), "", image, failure)) {
        return false;
      }
    }
    return true;
  }

  /*!
    Blobs closer than this (px, edge to edge) are about to merge. Until then the blur (0.8 px) leaves less than 1% of
    the contrast between them: their binarised regions, hence their centres, are untouched.
  */
  static constexpr double minimumGap = 3.0;

  //! Tracked markers (indices of the simulator's markers, in the order of the trackers).
  const std::vector<unsigned int> &getIndices() const { return m_indices; }
  //! Blob centres in the left (\e camera 0) or right (1) image, vpDot2::getCog().
  std::vector<vpImagePoint> getCogs(unsigned int camera) const
  {
    std::vector<vpImagePoint> cogs;
    for (const Blob &b : m_blobs[camera]) {
      cogs.push_back(b.dot.getCog());
    }
    return cogs;
  }
  //! Largest blob displacement of the last frame (px).
  double getLargestMotion() const { return m_motion; }
  //! Draws the blobs (contour and centre).
  void display(const vpImage<unsigned char> &Il, const vpImage<unsigned char> &Ir) const
  {
    for (size_t k = 0; k < m_blobs[0].size(); ++k) {
      m_blobs[0][k].dot.display(Il, vpColor::green);
      m_blobs[1][k].dot.display(Ir, vpColor::green);
    }
  }

private:
  //! False, with the reason in \e failure, if two of the blob centres \e cogs of image \e c are less than minimumGap
  //! apart, edge to edge (radii from the blobs' areas).
  bool separated(unsigned int c, const std::vector<vpImagePoint> &cogs, const std::string &what,
                 const std::string &image, std::string &failure) const
  {
    for (size_t k = 0; k < cogs.size(); ++k) {
      for (size_t l = k + 1; l < cogs.size(); ++l) {
        const double gap = vpImagePoint::distance(cogs[k], cogs[l]) - std::sqrt(m_blobs[c][k].area / M_PI) -
                           std::sqrt(m_blobs[c][l].area / M_PI);
        if (gap < minimumGap) {
          std::ostringstream os;
          os << std::fixed << std::setprecision(1) << "markers " << m_indices[k] << " and " << m_indices[l] << " "
             << what << gap << " px apart" << image << " (about to merge)";
          failure = os.str();
          return false;
        }
      }
    }
    return true;
  }

  //! False, with the reason in \e failure, if a blob predicted at \e cogs in image \e c would reach the border.
  bool inside(unsigned int c, const vpImage<unsigned char> &I, const std::vector<vpImagePoint> &cogs,
              const std::string &image, std::string &failure) const
  {
    for (size_t k = 0; k < cogs.size(); ++k) {
      const double margin = std::sqrt(m_blobs[c][k].area / M_PI) + minimumGap;
      if (cogs[k].get_u() < margin || cogs[k].get_v() < margin || cogs[k].get_u() > I.getWidth() - 1 - margin ||
          cogs[k].get_v() > I.getHeight() - 1 - margin) {
        failure = "marker " + std::to_string(m_indices[k]) + " predicted at the image border" + image +
                  " (leaving the image)";
        return false;
      }
    }
    return true;
  }

  struct Blob {
    vpDot2 dot;
    vpImagePoint previous; // centre one frame earlier, for the constant-velocity prediction
    double area = 0.0;     // px, last frame
  };
  std::vector<unsigned int> m_indices;
  std::vector<Blob> m_blobs[2];
  double m_motion = 0.0;
};
//! [Tracker]

//! RMS of the tracked centres minus the true projections (px per coordinate): only reported, never used.
struct TrackingAccuracy {
  double sumSquares = 0.0, largest = 0.0;
  unsigned int coordinates = 0;
  //! Accounts one stereo frame; returns its errors (u, v, u', v' of each tracked marker).
  vpColVector add(const World &world, const vpColVector &q, const StereoMarkerTracker &tracker)
  {
    const std::vector<vpColVector> X = world.arm.getMarkers(q);
    const std::vector<vpImagePoint> left = tracker.getCogs(0), right = tracker.getCogs(1);
    vpColVector errors(4 * static_cast<unsigned int>(left.size()));
    for (unsigned int k = 0; k < left.size(); ++k) {
      vpImagePoint l, r;
      world.rig.project(X[tracker.getIndices()[k]], l, r);
      errors[4 * k] = left[k].get_u() - l.get_u();
      errors[4 * k + 1] = left[k].get_v() - l.get_v();
      errors[4 * k + 2] = right[k].get_u() - r.get_u();
      errors[4 * k + 3] = right[k].get_v() - r.get_v();
    }
    sumSquares += errors.sumSquare();
    coordinates += errors.size();
    largest = std::max(largest, std::max(errors.getMaxValue(), -errors.getMinValue()));
    return errors;
  }
  void add(const TrackingAccuracy &other)
  {
    sumSquares += other.sumSquares;
    coordinates += other.coordinates;
    largest = std::max(largest, other.largest);
  }
  double rms() const { return coordinates > 0 ? std::sqrt(sumSquares / coordinates) : 0.0; }
};

class Viewer;

//! [Session]
/*!
  One seed's run of the experiment: the arm at joint values q, the two cameras with the seed's noise, the seed's
  simulated clicks, the lit markers, the last images and the trackers.
*/
struct Session {
  Session(const World &w, const ImageModel &m, unsigned int seed)
      : world(w), model(m),
        left(w.rig.getLeftCameraParameters(), w.rig.get_wMl().inverse(), w.rig.getWidth(), w.rig.getHeight(), m),
        right(w.rig.getRightCameraParameters(), w.rig.get_rMl() * w.rig.get_wMl().inverse(), w.rig.getWidth(),
              w.rig.getHeight(), m),
        noise(m.noiseSigma, m.background, static_cast<long>(seed)), clicks(static_cast<uint64_t>(seed), 2),
        Ileft(w.rig.getHeight(), w.rig.getWidth(), 0), Iright(w.rig.getHeight(), w.rig.getWidth(), 0),
        q(w.arm.getNumberOfJoints(), 0.0)
  {
  }
  //! Grabs a stereo frame of the arm at q: the images of its lit markers.
  void grab()
  {
    const std::vector<vpColVector> markers = world.arm.getMarkers(q);
    std::vector<vpColVector> X;
    for (unsigned int k : lit) {
      X.push_back(markers[k]);
    }
    left.render(X, noise, Ileft);
    right.render(X, noise, Iright);
    ++frames;
  }

  const World &world;
  ImageModel model;
  MarkerCamera left, right;
  PixelNoise noise;
  vpUniRand clicks;
  vpImage<unsigned char> Ileft, Iright;
  vpColVector q;
  std::vector<unsigned int> lit; // the markers switched on
  StereoMarkerTracker tracker;
  TrackingAccuracy *accuracy = nullptr; // where to account the frames, if anywhere
  Viewer *viewer = nullptr;
  std::string caption;
  unsigned int frames = 0;
};
//! [Session]

//! [Viewer]
//! Both images live (seed 1, with an X display): the tracked blobs, the taught target and the servo's trajectory.
class Viewer
{
public:
  explicit Viewer(Session &session)
#if defined(VISP_HAVE_X11)
      : m_left(session.Ileft, 0, 0, "Left camera"),
        m_right(session.Iright, static_cast<int>(session.Ileft.getWidth()) + 20, 0, "Right camera")
#endif
  {
    (void)session;
  }
  void show(const Session &session)
  {
    for (unsigned int c = 0; c < 2; ++c) {
      const vpImage<unsigned char> &I = c == 0 ? session.Ileft : session.Iright;
      vpDisplay::display(I);
      vpDisplay::displayText(I, 20, 20, session.caption, vpColor::yellow);
      for (const vpImagePoint &ip : target[c]) {
        vpDisplay::displayCross(I, ip, 14, vpColor::red, 2);
      }
      for (const std::vector<vpImagePoint> &points : trail[c]) {
        for (const vpImagePoint &ip : points) {
          vpDisplay::displayPoint(I, ip, vpColor::cyan, 2);
        }
      }
    }
    session.tracker.display(session.Ileft, session.Iright);
    vpDisplay::flush(session.Ileft);
    vpDisplay::flush(session.Iright);
  }
  std::vector<vpImagePoint> target[2];
  std::vector<std::vector<vpImagePoint>> trail[2];

private:
#if defined(VISP_HAVE_X11)
  vpDisplayX m_left, m_right;
#endif
};
//! [Viewer]

//! [Click]
/*!
  The one use of the ground truth for image measurements, standing for a user who clicks each marker once in both
  images at the start: a click up to 2 px off the marker's true image (seeded), inside the blob, that
  vpDot2::initTracking() refines. From then on each marker is known only through its tracker.
*/
void clickMarkers(Session &session, const std::vector<unsigned int> &indices)
{
  const std::vector<vpColVector> X = session.world.arm.getMarkers(session.q);
  std::vector<vpImagePoint> clickLeft, clickRight;
  for (unsigned int k : indices) {
    vpImagePoint l, r;
    session.world.rig.project(X[k], l, r);
    clickLeft.push_back(l + vpImagePoint(session.clicks.uniform(-2.0, 2.0), session.clicks.uniform(-2.0, 2.0)));
    clickRight.push_back(r + vpImagePoint(session.clicks.uniform(-2.0, 2.0), session.clicks.uniform(-2.0, 2.0)));
  }
  session.tracker.initialise(indices, session.Ileft, session.Iright, clickLeft, clickRight);
}
//! [Click]

//! [Move]
//! How a motion imaged frame by frame ended.
struct MoveResult {
  bool complete = true; // reached the end of the segment
  std::string failure;  // otherwise, why the tracking stopped
  unsigned int frames = 0;
};

/*!
  Drives the arm along the joint-space segment from session.q to \e qTo while the cameras grab frames and the
  trackers follow the blobs. The joint step starts at ImageModel::firstStepDeg and adapts so that the blobs move by
  about ImageModel::pixelsPerFrame between frames (measured on the tracked blobs). The last frame is at \e qTo, so a
  motion always ends with a fresh stereo frame. If a frame fails the tracker's checks, the arm stops at the last good
  frame: session.q and the trackers are those of that frame.
*/
MoveResult move(Session &session, const vpColVector &qTo)
{
  MoveResult result;
  const vpColVector qFrom = session.q, dq = qTo - qFrom;
  double span = 0.0;
  for (unsigned int i = 0; i < dq.size(); ++i) {
    span = std::max(span, std::abs(dq[i]));
  }
  double s = 0.0, step = span > 0.0 ? std::min(1.0, vpMath::rad(session.model.firstStepDeg) / span) : 1.0;
  double previousStep = 0.0;
  while (s < 1.0) {
    const double next = std::min(1.0, s + step);
    const StereoMarkerTracker lastGood = session.tracker;
    session.q = qFrom + dq * next;
    session.grab();
    ++result.frames;
    if (!session.tracker.track(session.Ileft, session.Iright, previousStep > 0.0 ? (next - s) / previousStep : 0.0,
                               result.failure)) {
      session.tracker = lastGood;
      session.q = qFrom + dq * s;
      result.complete = false;
      return result;
    }
    if (session.accuracy != nullptr) {
      session.accuracy->add(session.world, session.q, session.tracker);
    }
    if (session.viewer != nullptr) {
      session.viewer->show(session);
    }
    previousStep = next - s;
    s = next;
    // Next step: as large as keeps the blobs within pixelsPerFrame, growing at most twofold.
    const double motion = session.tracker.getLargestMotion();
    step = previousStep * std::min(2.0, session.model.pixelsPerFrame / std::max(motion, 1e-3));
  }
  return result;
}
//! [Move]

//! [Acquisition]
/*!
  Acquisition from images: the user clicks the 7 markers at the zero reference; each trial motion is then tracked
  from there. Between trials the arm drives back to the zero reference, where the trackers restart from their
  zero-reference state. A trial that cannot be tracked to its end (blobs about to merge, a blob leaving the image)
  ends at its last good frame, whose encoder value is the trial's amount. The fundamental matrix comes from the
  tracked centres of all these images.
  \param zeroState : receives the trackers at the zero reference, for the servo's markers to start from.
*/
vpProjectiveRobot acquire(Session &session, TrackingAccuracy &accuracy, StereoMarkerTracker &zeroState, bool verbose)
{
  const World &world = session.world;
  const unsigned int n = world.arm.getNumberOfJoints();
  std::vector<unsigned int> all(world.arm.getToolMarkers().size());
  for (unsigned int k = 0; k < all.size(); ++k) {
    all[k] = k;
  }
  session.q = vpColVector(n, 0.0);
  session.lit = all;
  session.caption = "acquisition: zero reference";
  session.grab();
  clickMarkers(session, all);
  accuracy.add(world, session.q, session.tracker);
  zeroState = session.tracker;
  const std::vector<vpImagePoint> left0 = zeroState.getCogs(0), right0 = zeroState.getCogs(1);
  if (verbose) {
    std::cout << "    markers 0-6 clicked once at the zero reference (simulated clicks, refined by vpDot2)\n";
  }

  std::vector<tutorial::TrialMotion> trials;
  session.accuracy = &accuracy;
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      const double planned = sign * vpMath::rad(world.trialDeg[i]);
      std::ostringstream caption;
      caption << "acquisition: joint " << i << " by " << vpMath::deg(planned) << " deg";
      session.caption = caption.str();
      // Back at the zero reference: a new frame, tracked from the zero-reference state.
      session.q = vpColVector(n, 0.0);
      session.tracker = zeroState;
      session.grab();
      std::string failure;
      if (!session.tracker.track(session.Ileft, session.Iright, 0.0, failure)) {
        throw vpException(vpException::fatalError, "acquisition: tracking failed at the zero reference: " + failure);
      }
      vpColVector qTrial(n, 0.0);
      qTrial[i] = planned;
      const MoveResult r = move(session, qTrial);
      const double amount = session.q[i];
      if (amount == 0.0) {
        throw vpException(vpException::fatalError,
                          "acquisition: joint " + std::to_string(i) + " could not move at all: " + r.failure);
      }
      if (verbose) {
        std::ostringstream os;
        os << std::fixed << std::setprecision(1) << std::showpos << "    joint " << i << ": " << vpMath::deg(amount)
           << " deg in " << std::noshowpos << r.frames << " frames";
        if (!r.complete) {
          os << ", reduced from " << std::showpos << vpMath::deg(planned) << " deg: " << r.failure;
        }
        std::cout << os.str() << "\n";
      }
      trials.push_back({i, amount, session.tracker.getCogs(0), session.tracker.getCogs(1)});
    }
  }
  session.accuracy = nullptr;

  // From here on, as in the main tutorial, with tracked centres instead of noisy projections: F with inliers within
  // 1 px of their epipolar line, then the calibration.
  return tutorial::calibrateFromTrials(n, left0, right0, trials, 1.0);
}
//! [Acquisition]

//! [Model accuracy]
//! RMS pixel error of the markers predicted by the model, rig.project(H(q) M(0)), at random q within +-30 deg.
double predictionError(const World &world, const vpProjectiveRobot &robot, unsigned int seed)
{
  return tutorial::predictionError(robot, tutorial::trueMarkerImages(world.rig, world.arm), seed);
}
//! [Model accuracy]

//! One servo run: the trajectory and its outcome.
struct ServoRun {
  std::vector<vpColVector> q;                         // joint values per iteration (rad)
  std::vector<std::vector<vpImagePoint>> left, right; // tracked centres per iteration
  std::vector<vpColVector> error;                     // s - s* per iteration (px)
  std::vector<vpImagePoint> leftTarget, rightTarget;
  std::vector<vpColVector> trackingError; // tracked centres minus true projections per iteration (px), for the report
  std::vector<unsigned int> frames;       // frames grabbed during each control period
  int convergedAt = -1;                   // first iteration with RMS(s - s*) under the threshold
  std::string failure;                    // a tracking failure, if any
  vpColVector finalJointError;            // q - q_target at the end (rad)
  double finalImageError = 0.0;           // RMS(s - s*) at the end (px)
};

//! [Servo]
/*!
  Teaching by showing, then the servo loop of the main tutorial on tracked centres. The arm, at the zero reference
  with its servo markers tracked, is driven by the start to the target, where s* is the tracked centres, then back
  to the start. At every iteration the features are the centres tracked in the last frame; the arm executes the
  control law's joint step in one control period while the cameras grab frames (as many as the tracker needs), the
  last one at the new joint values.
*/
ServoRun servo(Session &session, const vpProjectiveRobot &robot, TrackingAccuracy &accuracy, unsigned int iterations)
{
  const World &world = session.world;
  ServoRun run;
  const vpColVector qTarget = degToRad(world.targetDeg);
  const unsigned int nbPoints = static_cast<unsigned int>(world.tracked.size());

  // The direct joint-space line from the zero reference to the target turns the face of markers 0-2 edge-on, and
  // markers 1 and 2 would cross in both images (the tracker would report it): the arm goes by the start.
  session.caption = "teaching: to the start";
  MoveResult r = move(session, degToRad(world.startDeg));
  if (r.complete) {
    session.caption = "teaching: the arm is shown the target";
    r = move(session, qTarget);
  }
  if (!r.complete) {
    run.failure = "while showing the target: " + r.failure;
    return run;
  }
  run.leftTarget = session.tracker.getCogs(0);
  run.rightTarget = session.tracker.getCogs(1);
  if (session.viewer != nullptr) {
    session.viewer->target[0] = run.leftTarget;
    session.viewer->target[1] = run.rightTarget;
  }
  session.caption = "to the start";
  r = move(session, degToRad(world.startDeg));
  if (!r.complete) {
    run.failure = "while moving to the start: " + r.failure;
    return run;
  }

  std::vector<vpFeatureStereoPoint> s(nbPoints), s_star(nbPoints);
  vpServoProjective task;
  task.setRobot(robot);
  task.setLambda(0.5);
  task.setMaxJointVelocity(vpMath::rad(15.0)); // as in the main tutorial
  task.setDamping(30.0, 30.0);
  for (unsigned int k = 0; k < nbPoints; ++k) {
    s_star[k].buildFrom(run.leftTarget[k], run.rightTarget[k]);
    task.addFeature(s[k], s_star[k]);
  }

  unsigned int framesThisPeriod = r.frames;
  for (unsigned int it = 0; it <= iterations; ++it) {
    // The features: centres tracked by vpDot2 in the last frame (getCog()).
    const std::vector<vpImagePoint> left = session.tracker.getCogs(0), right = session.tracker.getCogs(1);
    for (unsigned int k = 0; k < nbPoints; ++k) {
      s[k].buildFrom(left[k], right[k]);
    }
    run.trackingError.push_back(accuracy.add(world, session.q, session.tracker));
    const vpColVector qdot = task.computeControlLaw(session.q); // eq. (47), J from the model at q
    const vpColVector e = task.getError();
    run.q.push_back(session.q);
    run.left.push_back(left);
    run.right.push_back(right);
    run.error.push_back(e);
    run.frames.push_back(framesThisPeriod);
    run.finalImageError = std::sqrt(e.sumSquare() / e.size());
    if (run.convergedAt < 0 && run.finalImageError < session.model.convergenceThreshold) {
      run.convergedAt = static_cast<int>(it);
    }
    if (session.viewer != nullptr) {
      session.viewer->trail[0].push_back(left);
      session.viewer->trail[1].push_back(right);
    }
    if (it < iterations) {
      std::ostringstream caption;
      caption << "servo: iteration " << it + 1 << ", image error " << std::fixed << std::setprecision(2)
              << run.finalImageError << " px RMS";
      session.caption = caption.str();
      r = move(session, world.arm.integrate(session.q, qdot, 1.0)); // one control period
      framesThisPeriod = r.frames;
      if (!r.complete) {
        run.failure = "servo iteration " + std::to_string(it + 1) + ": " + r.failure;
        break;
      }
    }
  }
  run.finalJointError = session.q - qTarget;
  return run;
}
//! [Servo]

//! [Noise floor]
//! sqrt(diag(sigma^2 (J^T J)^-1)) with J the true stacked image Jacobian of the tracked markers at the target.
vpColVector noiseFloor(const World &world, double sigma)
{
  const tutorial::ImagesAt trueImages = tutorial::trueMarkerImages(world.rig, world.arm, world.tracked);
  return tutorial::noiseFloor(tutorial::imageJacobian(trueImages, degToRad(world.targetDeg)), sigma);
}
//! [Noise floor]

//! [Images]
//! The final left and right images of a run with the features' trajectories (cyan), start (blue) and target (red).
void writeImages(const Session &session, const ServoRun &run, const std::string &dir)
{
  for (unsigned int c = 0; c < 2; ++c) {
    vpImage<vpRGBa> I;
    vpImageConvert::convert(c == 0 ? session.Ileft : session.Iright, I);
    const std::vector<std::vector<vpImagePoint>> &trajectory = c == 0 ? run.left : run.right;
    const std::vector<vpImagePoint> &target = c == 0 ? run.leftTarget : run.rightTarget;
    for (size_t k = 0; k < target.size(); ++k) {
      for (size_t it = 1; it < trajectory.size(); ++it) {
        vpImageDraw::drawLine(I, trajectory[it - 1][k], trajectory[it][k], vpColor::cyan);
      }
      if (!trajectory.empty()) {
        vpImageDraw::drawCircle(I, trajectory.front()[k], 8, vpColor::blue, 2);
      }
      vpImageDraw::drawCross(I, target[k], 16, vpColor::red, 1);
    }
    const std::string file =
        dir + (c == 0 ? "/projective-servo-images-left.png" : "/projective-servo-images-right.png");
    vpImageIo::write(I, file);
    std::cout << "Image written: " << file << "\n";
  }
}
//! [Images]

//! What the seeds give, for the table.
struct Study {
  std::vector<double> iterations, imageError, prediction, calibrationResidual, frames;
  vpColVector meanAbsJointError; // rad, sum over the converged seeds until finish()
  TrackingAccuracy acquisitionAccuracy, servoAccuracy;
  unsigned int seeds = 0, trackingFailures = 0, notConverged = 0, converged = 0;
  std::vector<std::string> failures;
  double jitterSumSquares = 0.0;
  unsigned int jitterDof = 0;

  /*!
    Jitter of the tracked centres once converged: the spread of their errors about their mean over the iterations
    while the arm stays at the target. The rest of the tracking error is a fixed function of where a blob falls on
    the pixel grid, the same when s* was taught and at the end: it cancels, the jitter does not.
  */
  void addJitter(const ServoRun &run)
  {
    const size_t first = static_cast<size_t>(run.convergedAt), m = run.trackingError.size() - first;
    if (run.convergedAt < 0 || m < 2) {
      return;
    }
    for (unsigned int r = 0; r < run.trackingError[first].size(); ++r) {
      double mean = 0.0;
      for (size_t it = first; it < run.trackingError.size(); ++it) {
        mean += run.trackingError[it][r] / m;
      }
      for (size_t it = first; it < run.trackingError.size(); ++it) {
        jitterSumSquares += (run.trackingError[it][r] - mean) * (run.trackingError[it][r] - mean);
      }
      jitterDof += static_cast<unsigned int>(m - 1);
    }
  }
  double jitter() const { return jitterDof > 0 ? std::sqrt(jitterSumSquares / jitterDof) : 0.0; }
};

//! [Seed]
/*!
  One seed: its own cameras' noise and clicks, the model (acquired from its images if \e acquireModel, else \e robot
  as given), teaching and servoing, all accounted in \e st.
*/
void runSeed(Session &session, unsigned int seed, vpProjectiveRobot &robot, bool acquireModel, bool verbose,
             const std::string &output, Study &st)
{
  const World &world = session.world;
  const unsigned int n = world.arm.getNumberOfJoints();
  const double t0 = vpTime::measureTimeMs();
  ++st.seeds;
  std::cout << std::fixed << std::setprecision(3);

  // The model, and the servo's markers tracked at the zero reference.
  StereoMarkerTracker zeroState;
  TrackingAccuracy acquisitionAccuracy;
  try {
    if (acquireModel) {
      if (verbose) {
        std::cout << "\nSeed 1: acquisition from images\n";
      }
      robot = acquire(session, acquisitionAccuracy, zeroState, verbose);
      st.prediction.push_back(predictionError(world, robot, seed));
      st.calibrationResidual.push_back(robot.getCalibrationResidual());
      st.acquisitionAccuracy.add(acquisitionAccuracy);
      if (verbose) {
        std::cout << "    epipolar geometry from the tracked centres: RMS residual "
                  << robot.getStereoRig().getEstimationResidual() << " px\n"
                  << "    algebraic generators: RMS error on the acquisition images " << robot.getAlgebraicResidual()
                  << " px; after the bundle adjustment " << robot.getCalibrationResidual() << " px\n"
                  << "    tracking accuracy (tracked centre - true projection): " << acquisitionAccuracy.rms()
                  << " px RMS, largest " << acquisitionAccuracy.largest << " px, over "
                  << acquisitionAccuracy.coordinates << " coordinates\n"
                  << "    marker prediction at random q within +-30 deg: " << st.prediction.back() << " px RMS\n";
      }
    } else {
      session.q = vpColVector(n, 0.0);
      session.lit = world.tracked;
      session.caption = "zero reference";
      session.grab();
      clickMarkers(session, world.tracked); // only the servo's markers are needed
      zeroState = session.tracker;
      if (verbose) {
        std::cout << "\nSeed 1: the model file's model; markers 0-2 clicked once at the zero reference\n";
      }
    }
  } catch (const vpException &e) {
    st.failures.push_back("seed " + std::to_string(seed) + ": " + e.getStringMessage());
    ++st.trackingFailures;
    return;
  }

  // Back at the zero reference with only the servo's markers lit, which keep their trackers: teach, then servo.
  session.q = vpColVector(n, 0.0);
  session.lit = world.tracked;
  session.tracker = zeroState.subset(world.tracked);
  session.grab();
  std::string failure;
  TrackingAccuracy servoAccuracy;
  ServoRun run;
  if (!session.tracker.track(session.Ileft, session.Iright, 0.0, failure)) {
    run.failure = "at the zero reference: " + failure;
  } else {
    run = servo(session, robot, servoAccuracy, 40);
  }
  st.servoAccuracy.add(servoAccuracy);

  if (verbose) {
    std::cout << "Seed 1: teaching and servo from images (" << session.frames << " stereo frames in all, "
              << std::setprecision(1) << (vpTime::measureTimeMs() - t0) / 1000.0 << " s)\n"
              << std::setprecision(3);
    if (!run.failure.empty()) {
      std::cout << "    TRACKING FAILURE " << run.failure << "\n";
    } else {
      std::cout << "    converged after " << run.convergedAt << " iterations, final image error " << run.finalImageError
                << " px RMS; tracking accuracy " << servoAccuracy.rms() << " px RMS\n"
                << "    final joint error (deg) " << degrees(run.finalJointError) << "\n";
      const vpHomogeneousMatrix d =
          world.arm.get_wMt(session.q).inverse() * world.arm.get_wMt(degToRad(world.targetDeg));
      std::cout << "    final tool pose error: " << 1000 * d.getTranslationVector().frobeniusNorm() << " mm, "
                << vpMath::deg(vpThetaUVector(d.getRotationMatrix()).getTheta()) << " deg\n";
      std::cout << "    iteration  image error RMS (px)  frames (to reach it; iteration 0: from the zero reference, "
                   "teaching included)\n";
      for (size_t it = 0; it < run.error.size() && it <= 25; ++it) {
        std::cout << std::setw(13) << it << std::setw(22) << std::sqrt(run.error[it].sumSquare() / run.error[it].size())
                  << std::setw(8) << run.frames[it] << "\n";
      }
    }
    if (!output.empty() && !run.q.empty()) {
      vpIoTools::makeDirectory(output);
      writeImages(session, run, output);
    }
  }

  if (!run.failure.empty()) {
    st.failures.push_back("seed " + std::to_string(seed) + ": tracking failure " + run.failure);
    ++st.trackingFailures;
  } else if (run.convergedAt < 0) {
    std::ostringstream os;
    os << "seed " << seed << ": not converged, image error " << run.finalImageError
       << " px RMS after 40 iterations, joint error (deg) " << degrees(run.finalJointError);
    st.failures.push_back(os.str());
    ++st.notConverged;
  } else {
    ++st.converged;
    st.addJitter(run);
    st.iterations.push_back(run.convergedAt);
    st.imageError.push_back(run.finalImageError);
    st.frames.push_back(session.frames);
    if (st.meanAbsJointError.size() != n) {
      st.meanAbsJointError.resize(n, true);
    }
    for (unsigned int i = 0; i < n; ++i) {
      st.meanAbsJointError[i] += std::abs(run.finalJointError[i]);
    }
  }
}
//! [Seed]

//! [Table]
//! The main tutorial's table for the loop closed on images, against the noise floor and the main job at 0.5 px.
//! Returns true if the final joint errors are within 2 times the main job's.
bool printTable(const World &world, const ImageModel &model, const Study &st)
{
  const unsigned int n = world.arm.getNumberOfJoints(), seeds = st.seeds;
  vpColVector meanAbs(n, 0.0);
  if (st.converged > 0) {
    meanAbs = st.meanAbsJointError / st.converged;
  }
  const vpColVector floorAccuracy = noiseFloor(world, st.servoAccuracy.rms()),
                    floorJitter = noiseFloor(world, st.jitter());
  const std::vector<double> mainJob = {0.051, 0.081, 0.119, 0.486, 0.151, 0.501}; // main job, 0.5 px, 20 seeds
  std::vector<double> it = st.iterations;
  std::sort(it.begin(), it.end());
  std::cout << std::fixed << std::setprecision(3) << "\nClosed on images, " << seeds << " seeds: converged "
            << st.converged << "/" << seeds << " (tracking failures " << st.trackingFailures << ", not converged "
            << st.notConverged << "), iterations to converge (RMS(s - s*) < " << model.convergenceThreshold
            << " px): median " << std::setprecision(0) << (it.empty() ? 0.0 : it[it.size() / 2]) << ", max "
            << maxOf(it) << std::setprecision(3) << "; final image error RMS " << mean(st.imageError) << " px; "
            << std::setprecision(0) << mean(st.frames) << " stereo frames per seed\n"
            << std::setprecision(3);
  std::cout << "  tracking accuracy, vpDot2 centre - true projection, px per coordinate (the main job's noise: 0.5 "
               "and 0.1 px):\n    ";
  if (st.acquisitionAccuracy.coordinates > 0) {
    std::cout << "acquisition " << st.acquisitionAccuracy.rms() << " RMS (largest " << st.acquisitionAccuracy.largest
              << "), ";
  }
  std::cout << "servo " << st.servoAccuracy.rms() << " RMS (largest " << st.servoAccuracy.largest
            << "), jitter once converged " << st.jitter() << " RMS\n";
  if (!st.prediction.empty()) {
    std::cout << "  acquired models: bundle-adjustment residual " << mean(st.calibrationResidual)
              << " px RMS, marker prediction error at random q within +-30 deg: mean " << mean(st.prediction)
              << " px, max " << maxOf(st.prediction) << " px RMS\n";
  }
  if (st.converged == 0) {
    std::cout << "  no seed converged:\n";
    for (const std::string &failure : st.failures) {
      std::cout << "    " << failure << "\n";
    }
    return false;
  }
  std::cout << "  Final joint error |q - q*| (deg), mean over the converged seeds; the noise floor\n"
            << "  sqrt(diag(sigma^2 (J^T J)^-1)) with sigma the servo's tracking accuracy and with sigma the jitter;\n"
            << "  the main job at 0.5 px:\n";
  std::cout << "    joint   images  floor(accuracy)  floor(jitter)  images/floor(jitter)  main 0.5 px  images/main\n";
  bool within = st.converged > 0;
  for (unsigned int i = 0; i < n; ++i) {
    const double ours = vpMath::deg(meanAbs[i]), ratio = ours / mainJob[i];
    within = within && ratio <= 2.0;
    std::cout << std::setw(9) << i << std::setw(9) << ours << std::setw(17) << vpMath::deg(floorAccuracy[i])
              << std::setw(15) << vpMath::deg(floorJitter[i]) << std::setw(22) << ours / vpMath::deg(floorJitter[i])
              << std::setw(13) << mainJob[i] << std::setw(13) << ratio << "\n";
  }
  for (const std::string &failure : st.failures) {
    std::cout << "    " << failure << "\n";
  }
  return within;
}
//! [Table]

} // namespace

int main(int argc, char **argv)
{
  unsigned int seeds = 20;
  std::string output, modelFile;
  bool display = std::getenv("DISPLAY") != nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seeds" && i + 1 < argc) {
      seeds = static_cast<unsigned int>(std::max(1, std::atoi(argv[++i])));
    } else if (arg == "--output" && i + 1 < argc) {
      output = argv[++i];
    } else if (arg == "--model" && i + 1 < argc) {
      modelFile = argv[++i];
    } else if (arg == "--no-display") {
      display = false;
    } else {
      std::cout << "Usage: " << argv[0]
                << " [--seeds N (default 20)] [--model FILE] [--output DIR] [--no-display] [--help]\n";
      return arg == "--help" ? EXIT_SUCCESS : EXIT_FAILURE;
    }
  }
#if !defined(VISP_HAVE_X11)
  display = false;
#endif

  try {
    const World world;
    const ImageModel model;
    const double t0 = vpTime::measureTimeMs();
    const unsigned int n = world.arm.getNumberOfJoints();
    const vpColVector qStart = degToRad(world.startDeg), qTarget = degToRad(world.targetDeg);

    std::cout << "Non-metric visual servoing of a PUMA-like arm from an uncalibrated stereo rig (Ruf & Horaud),\n"
              << "closed on rendered images tracked by vpDot2\n";
    std::cout << "If the markers were painted on the gripper's faces, those turned to both cameras would be\n"
              << "  at the zero reference: " << markersFacingTheRig(world, vpColVector(n, 0.0))
              << "\n  at the start:          " << markersFacingTheRig(world, qStart)
              << "\n  at the target:         " << markersFacingTheRig(world, qTarget)
              << "\n  so the markers are lit balls seen from all around, as the main job's are (see the header)\n";

    //! [Seeds]
    vpProjectiveRobot model0; // the model of the model file, if any
    bool haveModel = !modelFile.empty() && vpIoTools::checkFilename(modelFile);
    if (haveModel) {
      model0.loadModel(modelFile); // acquired from images by an earlier run
      std::cout << "Model loaded from " << modelFile << ": every seed servoes with it, no acquisition\n";
    }
    Study st;
    std::unique_ptr<Session> firstSession; // seed 1's, kept with its windows until the end
    std::unique_ptr<Viewer> viewer;
    for (unsigned int seed = 1; seed <= seeds; ++seed) {
      std::unique_ptr<Session> session(new Session(world, model, seed));
      if (seed == 1 && display) {
        viewer.reset(new Viewer(*session));
        session->viewer = viewer.get();
      }
      vpProjectiveRobot robot = model0;
      runSeed(*session, seed, robot, !haveModel, seed == 1, output, st);
      if (!haveModel && !modelFile.empty() && robot.isCalibrated()) {
        robot.saveModel(modelFile); // acquired once: the other seeds, and later runs, servo with it
        std::cout << "    model saved to " << modelFile << ": the other seeds servo with it\n";
        model0 = robot;
        haveModel = true;
      }
      if (seed == 1) {
        firstSession = std::move(session);
      }
    }
    //! [Seeds]

    const bool within = printTable(world, model, st);
    std::cout << "The loop closed on images " << (within ? "ends within" : "does NOT end within")
              << " 2 times the main job's final joint errors at 0.5 px; run time " << std::setprecision(1)
              << (vpTime::measureTimeMs() - t0) / 1000.0 << " s\n";

    if (viewer) {
      std::cout << "Click in the left image to quit" << std::endl;
      vpDisplay::getClick(firstSession->Ileft);
    }
    return st.converged == seeds ? EXIT_SUCCESS : EXIT_FAILURE;
  } catch (const vpException &e) {
    std::cerr << "Error: " << e.getStringMessage() << std::endl;
    return EXIT_FAILURE;
  }
}
