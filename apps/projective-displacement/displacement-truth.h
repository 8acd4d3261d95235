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
  \file displacement-truth.h
  \brief The ground truth of projective-displacement.cpp: the scene, the metric twist of the rotation, the
  projective-to-Euclidean link of a rig's frame, the errors of an estimate against them, and their tables.
*/

#ifndef _app_projective_displacement_truth_h_
#define _app_projective_displacement_truth_h_

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <iostream>
#include <vector>

#include <Eigen/Core>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpEigenConversion.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>

#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
/*!
  A 4x4 matrix of the projective groups (vpProjectiveDisplacement::matrix(), vpProjectiveRotation::generator(): Eigen)
  as a vpMatrix, by ViSP's own conversion, which ViSP 3.5 and 3.6 declare in namespace vp and ViSP 3.7 in visp.
*/
inline vpMatrix toVpMatrix(const Eigen::Matrix4d &E)
{
  vpMatrix M;
#ifdef VISP_NAMESPACE_NAME
  VISP_NAMESPACE_NAME::eigen2visp(Eigen::MatrixXd(E), M);
#else
  vp::eigen2visp(Eigen::MatrixXd(E), M);
#endif
  return M;
}

//! [Scene]
//! The metric world, known only to the simulator: markers, motion and the scene used for the weak calibration.
struct Scene {
  vpColVector fixation;             // world point (m) the rig verges on, 1 m in front of its midpoint
  std::vector<vpColVector> markers; // 7 markers on a ~10 cm rigid body, no 4 coplanar (world frame, m)
  vpColVector axisPoint;            // a point on the rotation axis (world frame, m)
  vpColVector axisDirection;        // unit direction of the rotation axis (world frame)
  double angle;                     // rotation angle (rad)
  unsigned int nbCalibrationPoints; // random scene points matched to estimate F
  double calibrationBox;            // side (m) of the cube around the fixation point they are drawn in
};

inline Scene buildScene()
{
  Scene scene;
  // The rig's midpoint is the world origin; it looks along the world +Z axis (X to the right, Y down in the images).
  scene.fixation = vpColVector({0.0, 0.0, 1.0});
  // Marker offsets (m) from the fixation point: any 4 of them are at least 1 cm away from a common plane.
  const double offsets[7][3] = {{0.05, 0.05, -0.01},  {-0.03, 0.00, 0.04}, {0.00, -0.02, 0.04},  {0.03, -0.04, -0.01},
                                {-0.02, 0.04, -0.03}, {0.04, 0.04, 0.03},  {-0.04, -0.04, -0.01}};
  for (unsigned int j = 0; j < 7; ++j) {
    scene.markers.push_back(vpColVector(
        {scene.fixation[0] + offsets[j][0], scene.fixation[1] + offsets[j][1], scene.fixation[2] + offsets[j][2]}));
  }
  // A general axis: 7 cm away from the body's centre, parallel to none of the camera axes.
  scene.axisPoint = vpColVector({0.06, -0.03, 1.02});
  scene.axisDirection = vpColVector({0.3, 0.8, 0.5});
  scene.axisDirection.normalize();
  scene.angle = vpMath::rad(30.0);
  scene.nbCalibrationPoints = 50;
  scene.calibrationBox = 0.40;
  return scene;
}
//! [Scene]

//! [Twist]
/*!
  Unit-speed metric twist (4x4 matrix of se(3)) of the rotation about the axis through \e p with unit direction
  \e w: d/dtheta (R(theta) (X - p) + p) = [w]x X - [w]x p at theta = 0.
*/
inline vpMatrix rotationTwist(const vpColVector &p, const vpColVector &w)
{
  const vpMatrix wx = vpColVector::skew(w);
  const vpColVector v = -(wx * p);
  vpMatrix T(4, 4, 0.0);
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int k = 0; k < 3; ++k) {
      T[i][k] = wx[i][k];
    }
    T[i][3] = v[i];
  }
  return T;
}
//! [Twist]

//! [Link]
/*!
  Ground-truth link H_PE (N ~ H_PE M) of the projective frame of \e rig, fitted over the workspace: the noise-free
  images of the world points \e wX are triangulated in the rig's frame (M) and matched with their metric left-camera
  coordinates (N); the 3D homography between them is the linear fit of vpProjectiveDisplacement (a DLT of any 3D
  homography; its scale and sign do not matter here). For the true F this is H_PE exactly; for an estimated F,
  whose frame no homography maps exactly onto the metric cameras, it is the homography that best explains the
  workspace.
*/
inline vpMatrix projectiveToEuclidean(const vpSimulatorStereoRig &sim, const vpProjectiveStereoRig &rig,
                                      const std::vector<vpColVector> &wX)
{
  const vpHomogeneousMatrix lMw = sim.get_wMl().inverse();
  std::vector<vpColVector> M, N;
  for (size_t k = 0; k < wX.size(); ++k) {
    vpImagePoint ipLeft, ipRight;
    sim.project(wX[k], ipLeft, ipRight); // no noise: only the simulator can do this
    M.push_back(rig.triangulate(ipLeft, ipRight));
    N.push_back(vpColVector(lMw * vpColVector({wX[k][0], wX[k][1], wX[k][2], 1.0})));
  }
  return toVpMatrix(vpProjectiveDisplacement::estimate(M, N).matrix());
}
//! [Link]

//! Angle (deg) between two fundamental matrices seen as 9-vectors, up to scale and sign.
inline double angleBetween(const vpMatrix &F1, const vpMatrix &F2)
{
  double dot = 0.0;
  for (unsigned int i = 0; i < 3; ++i) {
    for (unsigned int j = 0; j < 3; ++j) {
      dot += F1[i][j] * F2[i][j];
    }
  }
  const double c = std::fabs(dot) / (F1.frobeniusNorm() * F2.frobeniusNorm());
  return vpMath::deg(std::acos(std::min(1.0, c)));
}

//! RMS distance (px) of the noise-free images of \e wX to the epipolar lines of \e F, in both images.
inline double epipolarError(const vpSimulatorStereoRig &sim, const vpMatrix &F, const std::vector<vpColVector> &wX)
{
  double sum = 0.0;
  for (size_t k = 0; k < wX.size(); ++k) {
    vpImagePoint ipLeft, ipRight;
    sim.project(wX[k], ipLeft, ipRight);
    const vpColVector m({ipLeft.get_u(), ipLeft.get_v(), 1.0});
    const vpColVector mp({ipRight.get_u(), ipRight.get_v(), 1.0});
    const vpColVector l = F * m;                  // epipolar line of m in the right image
    const vpColVector lp = F.transpose() * mp;    // epipolar line of m' in the left image
    const double r = vpColVector::dotProd(mp, l); // m'^T F m
    sum += r * r / (l[0] * l[0] + l[1] * l[1]) + r * r / (lp[0] * lp[0] + lp[1] * lp[1]);
  }
  return std::sqrt(sum / (2.0 * wX.size()));
}

//! One estimate of the motion and its errors against the ground truth of the same projective frame.
struct Estimate {
  double angle;          // eq. (21), deg
  double angleError;     // |angle - true angle|, deg
  double generatorError; // ||Hhat - Hhat_true||_F / ||Hhat_true||_F
  double axisError;      // angle (deg) between the true axis and the estimated one (fixed points of Hhat)
  double offsetError;    // distance (mm) from the true axis' point nearest the body to the estimated axis
};

//! Everything one experiment produces.
struct Result {
  double fResidual;     // RMS reprojection residual of the weak calibration (px)
  unsigned int inliers; // matches kept by the robust estimation of F
  double fEpipolar;     // RMS distance of noise-free matches to the estimated epipolar lines (px)
  double fAngle;        // angle between estimated and true F (deg)
  double frameDistance; // ||Hhat_true(estimated F frame) - Hhat_true(true F frame)||_F / ||Hhat_true(true F frame)||_F
  Estimate linearEst;   // linear, from triangulated points, in the frame of the estimated F
  Estimate refinedEst;  // refined from the images, in the frame of the estimated F
  Estimate linearTrue;  // linear, in the frame of the true F
  Estimate refinedTrue; // refined, in the frame of the true F
};

//! Errors of the generator \e Hhat (4x4) against the ground truth of its frame (link \e Hpe, generator \e HhatTrue).
inline void compare(const vpMatrix &Hhat, const vpMatrix &HhatTrue, const vpMatrix &Hpe, const Scene &scene,
                    const vpSimulatorStereoRig &sim, Estimate &e)
{
  e.generatorError = (Hhat - HhatTrue).frobeniusNorm() / HhatTrue.frobeniusNorm();

  // The axis is the line of fixed points of the motion, the kernel of Hhat (rank 2). Mapped to metric left-camera
  // coordinates by H_PE, then to the world, it is spanned by two homogeneous points: a direction (last entry 0) and
  // a finite point (last entry 1).
  vpMatrix kernel;
  (Hpe * Hhat * Hpe.inverseByLU()).nullSpace(kernel, 2);
  const vpMatrix wKernel = vpMatrix(sim.get_wMl()) * kernel;
  const double a0 = wKernel[3][0], a1 = wKernel[3][1];
  const vpColVector d = wKernel * vpColVector({a1, -a0});
  const vpColVector X = wKernel * vpColVector({a0, a1});
  const vpColVector w = vpColVector(d.extract(0, 3)).normalize();
  const vpColVector p = X.extract(0, 3) / X[3];
  e.axisError = vpMath::deg(std::acos(std::min(1.0, std::fabs(vpColVector::dotProd(w, scene.axisDirection)))));

  // Distance from the point of the true axis nearest the body's centre to the estimated axis.
  vpColVector centre(3, 0.0);
  for (size_t j = 0; j < scene.markers.size(); ++j) {
    centre += scene.markers[j] / static_cast<double>(scene.markers.size());
  }
  const vpColVector &a = scene.axisDirection;
  const vpColVector q = scene.axisPoint + vpColVector::dotProd(centre - scene.axisPoint, a) * a;
  e.offsetError = 1000.0 * vpColVector::cross(q - p, w).frobeniusNorm();
}

//! Mean and maximum of a series.
struct Stats {
  double sum = 0.0, max = 0.0;
  unsigned int n = 0;
  void add(double x)
  {
    sum += x;
    max = std::max(max, x);
    ++n;
  }
  double mean() const { return n > 0 ? sum / n : 0.0; }
};

static const char *const kMethods[4] = {"linear (triangulated)", "refined (images, Ceres)", "linear (triangulated)",
                                        "refined (images, Ceres)"};
static const char *const kFrames[4] = {"estimated F", "estimated F", "true F", "true F"};

inline void printHeader(const char *const columns[], int n)
{
  std::cout << "    " << std::left << std::setw(25) << "method" << std::setw(13) << "frame" << std::right;
  for (int c = 0; c < n; ++c) {
    std::cout << std::setw(11) << columns[c];
  }
  std::cout << std::endl;
}

//! Prints the errors of one run next to the ground truth.
inline void printResult(const Scene &scene, const Result &r)
{
  const char *const columns[6] = {"angle", "angle err", "gen. err", "axis err", "offset err"};
  std::cout << "5. Results next to the ground truth" << std::endl
            << "   angle (deg): eq. (21); gen. err: ||Hhat - Hhat_true||_F / ||Hhat_true||_F in the same frame;"
            << std::endl
            << "   axis err (deg), offset err (mm): axis of fixed points of Hhat, mapped to metric by H_PE, against the"
            << std::endl
            << "   true axis (offset: distance between the two axes at the body)" << std::endl;
  printHeader(columns, 5);
  std::cout << "    " << std::left << std::setw(25) << "ground truth" << std::setw(13) << "-" << std::right
            << std::fixed << std::setprecision(4) << std::setw(11) << vpMath::deg(scene.angle) << std::setw(11) << 0.0
            << std::setw(11) << 0.0 << std::setw(11) << 0.0 << std::setw(11) << 0.0 << std::endl;
  const Estimate *e[4] = {&r.linearEst, &r.refinedEst, &r.linearTrue, &r.refinedTrue};
  for (int k = 0; k < 4; ++k) {
    std::cout << "    " << std::left << std::setw(25) << kMethods[k] << std::setw(13) << kFrames[k] << std::right
              << std::setw(11) << e[k]->angle << std::setw(11) << e[k]->angleError << std::setw(11)
              << e[k]->generatorError << std::setw(11) << e[k]->axisError << std::setw(11) << e[k]->offsetError
              << std::endl;
  }
  std::cout.unsetf(std::ios::floatfield);
  std::cout << std::setprecision(6);
}

//! Mean and maximum errors over many runs of the experiment, before and after the refinement.
struct Summary {
  Stats fAngle, fEpipolar, angle[4], generator[4], axis[4], offset[4];
  //! Accounts one run.
  void add(const Result &r)
  {
    const Estimate *e[4] = {&r.linearEst, &r.refinedEst, &r.linearTrue, &r.refinedTrue};
    fAngle.add(r.fAngle);
    fEpipolar.add(r.fEpipolar);
    for (int k = 0; k < 4; ++k) {
      angle[k].add(e[k]->angleError);
      generator[k].add(e[k]->generatorError);
      axis[k].add(e[k]->axisError);
      offset[k].add(e[k]->offsetError);
    }
  }
  //! Prints the summary of seeds 1..\e seeds at \e sigma px, computed in \e seconds.
  void print(unsigned int seeds, double sigma, double seconds) const
  {
    std::cout << "Summary over seeds 1.." << seeds << " at " << sigma << " px (" << std::setprecision(3) << seconds
              << " s)" << std::endl
              << "    weak calibration: RMS epipolar error of the noise-free matches, mean " << fEpipolar.mean()
              << " px, max " << fEpipolar.max << " px" << std::endl
              << "    angle between the estimated and the true F: mean " << fAngle.mean() << " deg, max " << fAngle.max
              << " deg" << std::endl;
    const char *const columns[8] = {"angle mean", "angle max", "gen. mean", "gen. max", "axis mean", "offs. mean"};
    printHeader(columns, 6);
    std::cout << std::fixed << std::setprecision(4);
    for (int k = 0; k < 4; ++k) {
      std::cout << "    " << std::left << std::setw(25) << kMethods[k] << std::setw(13) << kFrames[k] << std::right
                << std::setw(11) << angle[k].mean() << std::setw(11) << angle[k].max << std::setw(11)
                << generator[k].mean() << std::setw(11) << generator[k].max << std::setw(11) << axis[k].mean()
                << std::setw(11) << offset[k].mean() << std::endl;
    }
    std::cout.unsetf(std::ios::floatfield);
    std::cout << std::setprecision(6);
  }
};
} // namespace app

#endif
