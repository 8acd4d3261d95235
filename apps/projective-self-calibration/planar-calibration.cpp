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
  \file planar-calibration.cpp
  \brief ViSP's calibration of a stereo rig from views of a planar grid.
*/

#include "planar-calibration.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <Eigen/Geometry>

#include <visp3/core/vpException.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/vision/vpCalibration.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace selfcal
{
void planarCalibration(const SkewedRig &rig, unsigned int views, unsigned int points, double width, double sigma,
                       vpGaussRand &noise, vpUniRand &rng, Eigen::Matrix3d &Kl, Eigen::Matrix3d &Kr,
                       Eigen::Matrix4d &lMr, double &usedWidth)
{
  // The rig's vergence point in the left camera's frame: where both optical axes meet (vergingRig()).
  const vpHomogeneousMatrix lMr0 = rig.lMr();
  const Eigen::Vector3d cl = Eigen::Vector3d::Zero(), cr(lMr0[0][3], lMr0[1][3], lMr0[2][3]);
  const Eigen::Vector3d zl = Eigen::Vector3d::UnitZ(), zr(lMr0[0][2], lMr0[1][2], lMr0[2][2]);
  // Closest points of the two axes: cl + a zl and cr + b zr.
  const Eigen::Vector3d w = cl - cr;
  const double zz = zl.dot(zr), den = 1.0 - zz * zz;
  const double a = (zz * zr.dot(w) - zl.dot(w)) / den, b = (zr.dot(w) - zz * zl.dot(w)) / den;
  const Eigen::Vector3d fixation = 0.5 * (cl + a * zl + cr + b * zr);
  const double distance = fixation.norm();
  // At the vergence point, where both views overlap most (beyond it a verged pair's views part); a grid wider than
  // 60 % of the view's height there is replaced by one that wide, which both cameras see whole.
  const double fieldHeight = rig.height * distance / rig.Kl(1, 1);
  usedWidth = std::min(width, 0.6 * fieldHeight);
  double depth = distance;
  const Eigen::Vector3d along = fixation.normalized();

  std::vector<vpCalibration> calibrations[2];
  std::vector<vpHomogeneousMatrix> lMo;
  for (unsigned int attempt = 0; lMo.size() < views; ++attempt) {
    if (attempt > 100000) {
      throw vpException(vpException::fatalError, "no grid pose keeps the grid in view of both cameras");
    }
    if (attempt % 1000 == 999) {
      usedWidth *= 0.9; // the grid does not fit the views' overlap: a smaller one
    }
    // The grid facing the rig, moved across the view, tilted and turned (drawn one by one: the order of the
    // arguments of one call is unspecified).
    const double dx = rng.uniform(-0.15, 0.15), dy = rng.uniform(-0.15, 0.15), dz = rng.uniform(0.9, 1.2);
    const double tiltX = rng.uniform(-30, 30), tiltY = rng.uniform(-30, 30), turn = rng.uniform(-15, 15);
    const Eigen::Vector3d centre = along * depth * dz + Eigen::Vector3d(dx * rig.width * depth / rig.Kl(0, 0),
                                                                        dy * rig.height * depth / rig.Kl(1, 1), 0.0);
    const Eigen::Matrix3d facing = Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitZ(), along).matrix();
    const Eigen::Matrix3d R = facing * Eigen::AngleAxisd(vpMath::rad(tiltX), Eigen::Vector3d::UnitX()).matrix() *
                              Eigen::AngleAxisd(vpMath::rad(tiltY), Eigen::Vector3d::UnitY()).matrix() *
                              Eigen::AngleAxisd(vpMath::rad(turn), Eigen::Vector3d::UnitZ()).matrix();
    vpHomogeneousMatrix pose;
    for (unsigned int i = 0; i < 3; ++i) {
      for (unsigned int j = 0; j < 3; ++j) {
        pose[i][j] = R(i, j);
      }
      pose[i][3] = centre(i);
    }
    const vpHomogeneousMatrix wMo = rig.wMl * pose;
    vpCalibration view[2];
    std::vector<vpColVector> grid;
    std::vector<double> X, Y;
    for (unsigned int i = 0; i < points; ++i) {
      for (unsigned int j = 0; j < points; ++j) {
        X.push_back(usedWidth * (i / (points - 1.0) - 0.5));
        Y.push_back(usedWidth * (j / (points - 1.0) - 0.5));
        const vpColVector wX = wMo * vpColVector({X.back(), Y.back(), 0.0, 1.0});
        grid.push_back(vpColVector({wX[0], wX[1], wX[2]}));
      }
    }
    std::vector<vpImagePoint> left, right;
    if (!rig.images(grid, sigma, noise, left, right, 5.0)) {
      continue;
    }
    for (size_t k = 0; k < grid.size(); ++k) {
      view[0].addPoint(X[k], Y[k], 0.0, left[k]);
      view[1].addPoint(X[k], Y[k], 0.0, right[k]);
    }
    lMo.push_back(pose);
    calibrations[0].push_back(view[0]);
    calibrations[1].push_back(view[1]);
  }
  Eigen::Matrix3d *K[2] = {&Kl, &Kr};
  const Eigen::Matrix3d *Ktrue[2] = {&rig.Kl, &rig.Kr};
  for (int c = 0; c < 2; ++c) {
    // The virtual visual servoing starts from what a user knows from the lens and the sensor.
    vpCameraParameters cam;
    const Eigen::Matrix3d &T = *Ktrue[c];
    cam.initPersProjWithoutDistortion(0.85 * T(0, 0), 0.85 * T(0, 0), rig.width / 2.0 + 20.0, rig.height / 2.0 - 20.0);
    double residual = 0.0;
    // Gauss-Newton steps (gain 1 instead of ViSP's 0.25): the same minimum, reached in a few iterations instead of
    // thousands (its stopping test is an absolute change of the squared error below 1e-10 px^2).
    vpCalibration::setLambda(1.0);
    vpCalibration::computeCalibrationMulti(vpCalibration::CALIB_VIRTUAL_VS, calibrations[c], cam, residual);
    *K[c] << cam.get_px(), 0.0, cam.get_u0(), 0.0, cam.get_py(), cam.get_v0(), 0.0, 0.0, 1.0;
  }
  // The rig from the grid's poses in both cameras, lMr = lMo rMo^-1, averaged over the views.
  vpColVector t(3, 0.0), thetaU(3, 0.0);
  for (size_t k = 0; k < lMo.size(); ++k) {
    const vpHomogeneousMatrix M = calibrations[0][k].cMo * calibrations[1][k].cMo.inverse();
    t += M.getTranslationVector() / static_cast<double>(lMo.size());
    thetaU += vpColVector(vpThetaUVector(M.getRotationMatrix())) / static_cast<double>(lMo.size());
  }
  const vpHomogeneousMatrix M(vpTranslationVector(t[0], t[1], t[2]), vpThetaUVector(thetaU[0], thetaU[1], thetaU[2]));
  for (unsigned int i = 0; i < 4; ++i) {
    for (unsigned int j = 0; j < 4; ++j) {
      lMr(i, j) = M[i][j];
    }
  }
}
} // namespace selfcal
