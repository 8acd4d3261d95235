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

#include <visp3/projective/vpServoModelMismatch.h>

#include <algorithm>
#include <cmath>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
//! The relative error of the model's local motion that the recent prediction tolerates (a tenth of the motion).
const double kMotionTolerance = 0.1;
//! The standard deviation of the model's local motion error in the noise tests, relative to the motion: 4 times the
//! 0.5 % measured on the acquired models of the tests (the threshold's slack, a tenth, bounds it instead).
const double kMotionNoise = 0.02;
//! The floor of the learned noise (pixels per coordinate of a residual): whole-pixel rounding gives 0.41.
const double kNoiseFloor = 0.5;
//! The variance the noise tests use: the learned one \e noise2, at least the floor's.
double flooredVariance(double noise2)
{
  return std::max(noise2, kNoiseFloor * kNoiseFloor);
}
//! The iterations that must have given the noise before it is used; then its exponential mean's length.
const unsigned int kNoiseIterations = 3, kNoiseMemory = 20;
//! The bound of the common motion's statistic (chi-square, 2 degrees of freedom: exceeded with probability e^-10).
const double kCommonBound = 20.0;
//! The chi-square value with \e k degrees of freedom exceeded with probability 1e-5 (Wilson-Hilferty: the cube root
//! of chi^2_k / k is nearly normal, of mean 1 - 2 / (9k) and variance 2 / (9k); 4.265 the normal's 1e-5 quantile).
double chiSquareBound(size_t k)
{
  const double a = 2.0 / (9.0 * static_cast<double>(k));
  const double c = 1.0 - a + 4.265 * std::sqrt(a);
  return static_cast<double>(k) * c * c * c;
}

//! The median of the first \e n values of \e x (reordered; \e n > 0), without allocation.
double medianOf(std::vector<double> &x, size_t n)
{
  const auto mid = x.begin() + static_cast<std::ptrdiff_t>(n / 2);
  std::nth_element(x.begin(), mid, x.begin() + static_cast<std::ptrdiff_t>(n));
  return n % 2 == 1 ? *mid : 0.5 * (*mid + *std::max_element(x.begin(), mid));
}

//! \e M or \f$ -M \f$, whichever agrees in sign with \e reference: a projective point's sign is arbitrary, so the
//! points summed into one memory are aligned first.
Eigen::Vector4d alignedWith(const Eigen::Vector4d &reference, const Eigen::Vector4d &M)
{
  return reference.dot(M) < 0.0 ? Eigen::Vector4d(-M) : M;
}

//! The stereo point \e s = (u, v, u', v') with its left and right images exchanged.
Eigen::Vector4d exchanged(const Eigen::Vector4d &s)
{
  return Eigen::Vector4d(s(2), s(3), s(0), s(1));
}

//! The larger over both images of the distance between the stereo points \e a and \e b (pixels).
double stereoDistance(const Eigen::Vector4d &a, const Eigen::Vector4d &b)
{
  // max(sqrt x, sqrt y) = sqrt(max(x, y)): one square root.
  return std::sqrt(std::max((a.head<2>() - b.head<2>()).squaredNorm(), (a.tail<2>() - b.tail<2>()).squaredNorm()));
}
} // namespace

vpServoModelMismatch::vpServoModelMismatch()
    : m_records(), m_threshold(5.0), m_iterations(2), m_disagreeing(0), m_exchangedIterations(0), m_mismatch(false),
      m_work(), m_sumBounds(), m_noise2(0.0), m_noiseIterations(0), m_model(nullptr), m_data(nullptr)
{
}

void vpServoModelMismatch::setThreshold(double pixels)
{
  m_threshold = nonNegative(pixels, vpErrorSite("vpServoModelMismatch")("setThreshold()"),
                            "the model-mismatch threshold", "a distance in pixels, e.g. 5; 0 disables the detection");
}

void vpServoModelMismatch::setConsecutiveIterations(unsigned int iterations)
{
  m_iterations = atLeastOne(iterations, "vpServoModelMismatch::setConsecutiveIterations()",
                            "a mismatch needs at least one disagreeing iteration; pass 1 or more (default 2)");
}

void vpServoModelMismatch::resize(unsigned int features)
{
  m_records.resize(features);
  m_work.assign(2 * static_cast<size_t>(features), 0.0);
  m_sumBounds.resize(features);
  for (size_t k = 1; k < m_sumBounds.size(); ++k) {
    m_sumBounds[k] = chiSquareBound(2 * k); // the sum's bound over k features of an image: once, not per call
  }
  reset();
}

void vpServoModelMismatch::reset()
{
  for (vpRecord &r : m_records) {
    r.sum.setZero();
    r.recent.setZero();
    r.offset.setZero();
    r.last.setZero();
    r.triangulated.setZero();
    r.s.setZero();
    r.residual.setZero();
    r.motion = 0.0;
    r.hasResidual = false;
    r.distance = -1.0;
    r.exchangedDistance = -1.0;
    r.marker = -1;
    r.usable = false;
    r.hasMemory = false;
    r.exact = false;
  }
  m_disagreeing = 0;
  m_exchangedIterations = 0;
  m_mismatch = false;
  m_noise2 = 0.0;
  m_noiseIterations = 0;
}

void vpServoModelMismatch::startIteration(const vpProjectiveArmModel &model, const vpServoProjectiveData &data)
{
  m_model = &model;
  m_data = &data; // H(q) and the features' points at the zero reference: computed once for the whole servo
  for (vpRecord &r : m_records) {
    r.hasResidual = false; // a feature not observed this iteration has no residual in it
  }
}

void vpServoModelMismatch::observe(unsigned int i, bool usable)
{
  vpRecord &r = m_records[i];
  const Eigen::Vector4d &s = m_data->getFeature(i);
  r.s = s;
  r.usable = usable && s.allFinite();
  r.distance = -1.0;
  r.exchangedDistance = -1.0;
  r.hasResidual = false;
  if (!r.usable || !r.hasMemory || m_model == nullptr) {
    return;
  }
  // The recent prediction first (it follows the model's drift, offset to where the feature last agreed): within the
  // threshold plus a tenth of the motion it predicts since then, the feature agrees and the absolute prediction is not
  // needed; otherwise the smaller of both distances (each the larger over both images). The absolute memory is
  // normalised only when the recent prediction does not settle it.
  for (int k = 0; k < 2; ++k) {
    Eigen::Vector4d sHat;
    if (m_data->predict(k == 0 ? r.recent : Eigen::Vector4d(r.sum.normalized()), sHat)) {
      double slack = 0.0;
      if (k == 0) {
        sHat += r.offset; // the model's motion from where the feature last agreed
        r.motion = stereoDistance(sHat, r.last);
        r.residual = s - sHat;
        r.hasResidual = true;
        slack = kMotionTolerance * r.motion;
      }
      const double d = std::max(0.0, stereoDistance(sHat, s) - slack);
      r.distance = r.distance < 0.0 ? d : std::min(r.distance, d);
      if (r.exact) { // an acquired marker's images, exchanged, against the same prediction
        const double dx = std::max(0.0, stereoDistance(sHat, exchanged(s)) - slack);
        r.exchangedDistance = r.exchangedDistance < 0.0 ? dx : std::min(r.exchangedDistance, dx);
      }
    }
    if (r.distance >= 0.0 && r.distance <= m_threshold) {
      break;
    }
  }
}

bool vpServoModelMismatch::endIteration()
{
  unsigned int evaluated = 0, disagreeing = 0, exchangedOnly = 0, givenOnly = 0;
  for (vpRecord &r : m_records) {
    if (r.distance >= 0.0) {
      ++evaluated;
      if (r.distance > m_threshold) {
        ++disagreeing;
      }
    }
    // Left and right exchanged: an acquired marker predicted, or recognised, only with its images exchanged.
    r.marker = -1;
    if (!r.usable || m_model == nullptr) {
      continue;
    }
    bool given = false, other = false;
    if (r.exact) {
      given = r.distance >= 0.0 && r.distance <= m_threshold;
      other = r.exchangedDistance >= 0.0 && r.exchangedDistance <= m_threshold;
    } else {
      r.marker = m_model->matchMarker(m_data->getDisplacement(), r.s);
      given = r.marker >= 0;
      other = m_model->matchMarker(m_data->getDisplacement(), exchanged(r.s)) >= 0;
    }
    exchangedOnly += other && !given ? 1 : 0;
    givenOnly += given && !other ? 1 : 0;
  }
  // Most features, not all: a camera turned about the line of sight of one feature leaves that feature where it was
  // (a 2.9 deg turn about the optical axis moves a marker near the image centre by 4 px, the others by 7-13 px). A
  // single feature off its prediction is vpServoFeatureHealth's, not a moved camera. Or, below the threshold, the
  // features together against the noise learned (a bump of 1-5 px at 0.5 px of noise).
  const bool disagrees = m_threshold > 0.0 && ((evaluated >= 2 && 2 * disagreeing > evaluated) || disagreesWithNoise());
  const bool exchangedImages = m_threshold > 0.0 && exchangedOnly >= 1 && givenOnly == 0;
  m_disagreeing = disagrees ? m_disagreeing + 1 : 0;
  m_exchangedIterations = exchangedImages ? m_exchangedIterations + 1 : 0;
  m_mismatch = m_disagreeing >= m_iterations || m_exchangedIterations >= m_iterations;
  if (!disagrees && !exchangedImages && m_model != nullptr) {
    learnNoise();
    for (size_t i = 0; i < m_records.size(); ++i) {
      vpRecord &r = m_records[i];
      if (!r.usable || (r.hasMemory && (r.distance < 0.0 || r.distance > m_threshold))) {
        continue;
      }
      const Eigen::Vector4d &M = m_data->getZeroPoint(static_cast<unsigned int>(i)); // H(q)^-1 M, unit norm
      if (!M.allFinite()) {
        continue;
      }
      r.recent = r.hasMemory ? Eigen::Vector4d((r.recent + alignedWith(r.recent, M)).normalized()) : M;
      Eigen::Vector4d sHat;
      r.offset = m_data->predict(r.recent, sHat) ? Eigen::Vector4d(r.s - sHat) : Eigen::Vector4d::Zero();
      r.last = r.s;
      r.triangulated += alignedWith(r.triangulated, M);
      if (r.exact) {
        continue;
      }
      // A feature that is an acquired marker is remembered as that marker's point: one stereo pair's depth error,
      // turned sideways by a large motion, would otherwise exceed the threshold for every feature of a 3-point task.
      if (r.marker >= 0) { // recognised above
        r.sum = m_model->markers()[static_cast<size_t>(r.marker)].normalized();
        r.hasMemory = r.exact = true;
        continue;
      }
      r.sum += r.hasMemory ? alignedWith(r.sum, M) : M;
      r.hasMemory = true;
    }
  }
  m_model = nullptr;
  m_data = nullptr;
  return m_mismatch;
}

bool vpServoModelMismatch::disagreesWithNoise()
{
  if (m_noiseIterations < kNoiseIterations) {
    return false;
  }
  const double sigma2 = flooredVariance(m_noise2);
  double both = 0.0; // the common motion's statistic over both images (a moved rig shifts the features in both)
  for (int image = 0; image < 2; ++image) {
    // Over the features within the threshold, less the one of largest normalised residual in this image (a tracking
    // fault): the sum of their squared residuals over their variances, and their mean residual.
    double sum = 0.0, largest = -1.0, motion = 0.0, largestMotion = 0.0;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero(), largestResidual = Eigen::Vector2d::Zero();
    size_t within = 0;
    for (const vpRecord &r : m_records) {
      if (r.hasResidual && r.distance <= m_threshold) {
        const double m = kMotionNoise * r.motion;
        const Eigen::Vector2d ri = r.residual.segment<2>(2 * image);
        const double z = ri.squaredNorm() / (sigma2 + m * m);
        sum += z;
        mean += ri;
        motion += r.motion;
        if (z > largest) {
          largest = z;
          largestResidual = ri;
          largestMotion = r.motion;
        }
        ++within;
      }
    }
    if (within < 3) {
      return false;
    }
    const double kept = static_cast<double>(within - 1);
    if (sum - largest > m_sumBounds[within - 1]) {
      return true;
    }
    mean = (mean - largestResidual) / kept;
    const double common = kMotionNoise * (motion - largestMotion) / kept; // the model's error is common: no 1/n
    const double q = mean.squaredNorm() / (sigma2 / kept + common * common);
    if (q > kCommonBound) {
      return true;
    }
    both += q;
  }
  static const double bothBound = chiSquareBound(4);
  return both > bothBound;
}

void vpServoModelMismatch::learnNoise()
{
  // The squared residuals per image of the features that agree (those the tests read); their median over 2 ln 2
  // estimates the variance of a coordinate (the median of sigma^2 chi^2_2).
  size_t n = 0;
  for (const vpRecord &r : m_records) {
    if (r.hasResidual && r.distance <= m_threshold) { // a residual comes with its distance (observe())
      m_work[n++] = r.residual.head<2>().squaredNorm();
      m_work[n++] = r.residual.tail<2>().squaredNorm();
    }
  }
  if (n == 0) {
    return;
  }
  // Winsorised at 4 times the noise learned so far: a change of the cameras that the tests missed (during a large
  // motion) moves the median too, and must not teach the next iterations that its residuals are noise.
  double estimate = medianOf(m_work, n) / (2.0 * std::log(2.0));
  if (m_noiseIterations >= kNoiseIterations) {
    estimate = std::min(estimate, 4.0 * flooredVariance(m_noise2));
  }
  m_noiseIterations = std::min(m_noiseIterations + 1, kNoiseMemory);
  m_noise2 += (estimate - m_noise2) / static_cast<double>(m_noiseIterations);
}
