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
  \file vpServoModelMismatch.h
  \brief Detection of a model that no longer predicts the features of a servo task (a moved camera, slipped markers).
*/

#ifndef _vpServoModelMismatch_h_
#define _vpServoModelMismatch_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <cmath>
#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoProjectiveData.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoModelMismatch
  \ingroup group_projective
  \brief Tells when most features of a servo task disagree with the model's prediction, consistently over
  consecutive iterations: the cameras moved (a bumped camera, a moved rig) or the markers slipped, so that the model
  no longer describes what the cameras see. It complements vpServoFeatureHealth, which sets single features aside.

  <b>Prediction.</b> Each feature \f$ i \f$ (current value \f$ s_i = (u, v, u', v') \f$, pixels) is a point of the
  moving end. The detector remembers it at the zero reference as the unit-norm mean
  \f[ \bar M_i \propto \sum_k \pm H(q_k)^{-1} M_{ik}, \f]
  \f$ M_{ik} \f$ the point linearly triangulated (vpProjectiveStereoRig::triangulateLinear()) at the iterations
  \f$ k \f$ where the feature agreed with the model, each term of unit norm with the sign of the sum (no coordinate is
  divided by); or, once the feature is recognised as one of the model's acquired markers
  (vpProjectiveArmModel::matchMarker(), tried at every iteration it agrees until then), that marker's point, which
  no averaging of stereo pairs would improve. Its prediction
  at joints \f$ q \f$ is the image \f$ \hat s_i \f$ of \f$ H(q) \bar M_i \f$ (4x1, model frame), and its distance
  (pixels) the larger over both images of \f$ \|\hat s_i - s_i\| \f$ per image.

  <b>Local prediction.</b> The model gets a control step right anywhere, but its absolute prediction drifts by
  several pixels far from the acquisition's configurations (a Viper850 turned 90 deg from its zero reference), which
  alone would stop a healthy task. So each feature also has a recent memory \f$ \tilde M_i \f$, the sign-aligned
  unit mean of the last memory and the point triangulated at the last iteration where the feature agreed (weights
  1/2, 1/2: a few iterations' average, following the drift), predicted as the image of \f$ H(q) \tilde M_i \f$ plus
  the offset of the feature from that image where it last agreed (the model's motion from there, not its absolute
  place: the half-weighted memory lags behind a feature that moves fast); that prediction disagrees beyond the
  threshold plus a tenth of the image motion it predicts since then (a model a few percent off in its local motion,
  times a path step that moves a feature by 100-200 px). A feature disagrees only when both predictions are farther
  than the threshold: the distance reported is the recent prediction's when it is within the threshold (the absolute
  one is then not computed), else the smaller of the two. A bump is sudden: both memories, frozen from the iteration
  before it, disagree at once and stay so.

  <b>Decision.</b> An iteration disagrees when at least two features have a prediction and more than half of them
  (both of two, 2 of 3, 4 of 7) are farther than the threshold (setThreshold(), default 5 px: well above the noise of
  a tracked feature and the prediction error of an acquired model, well below the image motion of a camera turned by
  1 degree or moved by 5 mm at 1 m with a 12.5 mm lens). Not all of them: a camera turned about the line of sight of
  one feature (about its optical axis, for a feature near the image centre) barely moves that feature; one feature
  alone off its prediction is a tracking fault (vpServoFeatureHealth). An iteration also disagrees by the tests
  against the noise below. The model mismatches when the last
  setConsecutiveIterations() iterations (default 2) all disagreed. Memories are updated only by the features that agree,
  never in an iteration that disagrees.

  <b>Noise.</b> The threshold is fixed, but a camera moved by a fraction of a degree shifts the features by 1-5 px,
  which features tracked at 0.5 px of noise show plainly when taken together. So the detector also learns the noise it
  works in and tests the features jointly against it. Let \f$ r_i = s_i - \hat s_i \f$ be feature \f$ i \f$'s
  residual against its recent prediction (4x1, offset included, no slack), \f$ r_{ic} \f$ its part in image
  \f$ c \f$ (left, right), and \f$ m_i \f$ the image motion that prediction gives since the feature last agreed. At
  every iteration that agrees, the features within the threshold give the estimate
  \f$ e = \mathrm{med}_{i,c} \|r_{ic}\|^2 / (2 \ln 2) \f$ (the median of \f$ \sigma^2 \chi^2_2 \f$ is
  \f$ 2 \ln 2 \, \sigma^2 \f$: one feature off by a tracking fault does not move it), averaged into
  \f$ \hat\sigma^2 \f$ (getNoise(): the mean of the estimates, then an exponential mean over 20 iterations, following a
  noise that changes; each estimate at most 4 times the current value, so that a change of the cameras that the tests
  below missed does not teach them that its residuals are noise). \f$ \hat\sigma \f$ is the residual's noise per
  coordinate, \f$ \sqrt 2 \f$ times the features' own: the residual is the difference of two measurements. Once 3
  iterations have given it, with \f$ \sigma^2 = \max(\hat\sigma^2, \sigma_{min}^2) \f$, \f$ \sigma_{min} = 0.5 \f$ px
  (features rounded to whole pixels have residuals of 0.41 px per coordinate, and most often 0: a noise-free or
  quantised simulation does not alarm on rounding), and \f$ \sigma_i^2 = \sigma^2 + (\kappa m_i)^2 \f$, the model's
  local motion error \f$ \kappa = 2 \% \f$ of the motion (4 times the 0.5 % of models acquired at 0.5 px: a fixed
  bound, as the threshold's slack, not learned), an iteration also disagrees when, over the features within the
  threshold that have a residual less the one of largest \f$ \|r_{ic}\|^2 / \sigma_i^2 \f$ (one feature's tracking
  fault is vpServoFeatureHealth's; a feature beyond the threshold votes above instead), \f$ K \geq 2 \f$ of them in
  both images:
  - (all of them) in an image \f$ c \f$, \f$ \sum_i \|r_{ic}\|^2 / \sigma_i^2 \f$ exceeds the value that
    \f$ \chi^2_{2K} \f$ exceeds with probability \f$ 10^{-5} \f$ (Wilson-Hilferty): each term is about
    \f$ \chi^2_2 \f$ while the cameras have not moved, and the sum of the \f$ K \f$ smallest of \f$ K + 1 \f$ is below
    \f$ \chi^2_{2K} \f$;
  - (their common motion) in an image, the mean \f$ \mu_c \f$ of their \f$ r_{ic} \f$ has
    \f$ Q_c = \|\mu_c\|^2 / v_c > 20 \f$, \f$ v_c = \sigma^2 / K + (\kappa \bar m)^2 \f$ (\f$ \bar m \f$ their mean
    motion; the model's error is common to the features, the noise is not): \f$ Q_c \f$ is then about
    \f$ \chi^2_2 \f$, beyond 20 with probability \f$ e^{-10} = 4.5 \cdot 10^{-5} \f$; or over both images (a moved
    rig shifts the features in both), \f$ Q_0 + Q_1 \f$ beyond the \f$ 10^{-5} \f$ value of \f$ \chi^2_4 \f$. A
    shift common to the features adds up over them: at 0.5 px of noise and 7 features, 2 px is 6 standard deviations
    of \f$ \mu_c \f$ (a 2 px shift of both images is seen within 2 calls in 1395 of 1400 seeded cases of the tests).

  Then the consecutive iterations' rule: a false alarm needs setConsecutiveIterations() improbable iterations in a row,
  and the residuals of consecutive iterations share a measurement with opposite signs (the features' values where they
  last agreed), which makes them less likely together. A disagreeing iteration updates neither the memories nor the
  noise, so the iteration after a bump is compared with the images before it too. setThreshold(0) turns these tests
  off with the rest.

  <b>Left and right images exchanged.</b> A program that gives the right camera's image as the left one (and the
  converse) after an acquisition that had them right: a feature that is an acquired marker is then recognised
  (vpProjectiveArmModel::matchMarker()) or predicted within the threshold only with its two images exchanged. An
  iteration is exchanged when a feature is so and none is recognised or predicted only as given (a feature whose two
  images nearly coincide, as near the fixation point of verged cameras, tells neither; nor does a feature that is no
  acquired marker); the model mismatches, isImagesExchanged() true, when the last setConsecutiveIterations()
  iterations all were, from the first call on: features triangulated from exchanged images would otherwise be
  remembered as points that no arm carries, and the disagreement would show only after the arm moved far enough.
  Memories are not updated in such an iteration. A task without acquired markers among its features does not tell
  it.

  Usage: startIteration(), observe() for every feature, endIteration(); reset() when the rig or the model changed.
  No allocation once the features are added.
*/
class VISP_EXPORT vpServoModelMismatch
{
public:
  //! No feature, threshold 5 px, 2 consecutive iterations.
  vpServoModelMismatch();

  /*!
    Distance (pixels) beyond which a feature disagrees with its prediction; 0 disables the detection.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if it is negative or not finite.
  */
  void setThreshold(double pixels);
  //! The threshold (pixels; 0: detection off).
  double getThreshold() const { return m_threshold; }
  /*!
    Number of consecutive disagreeing iterations that make a mismatch (default 2).
    \exception vpProjectiveException (invalidValueError) if it is 0.
  */
  void setConsecutiveIterations(unsigned int iterations);
  //! The number of setConsecutiveIterations().
  unsigned int getConsecutiveIterations() const { return m_iterations; }

  //! Sets the number of features; forgets every memory.
  void resize(unsigned int features);
  //! Forgets every memory (the model or its rig changed): the next iteration starts anew.
  void reset();
  //! Number of features.
  unsigned int getNumberOfFeatures() const { return static_cast<unsigned int>(m_records.size()); }

  /*!
    Starts an iteration on \e data (vpServoProjectiveData: \f$ H(q) \f$, its inverse, the features' values and points,
    computed once by the caller) of \e model; both must outlive the iteration.
  */
  void startIteration(const vpProjectiveArmModel &model, const vpServoProjectiveData &data);
  /*!
    Feature \e i (no index check) of current value vpServoProjectiveData::getFeature() (4x1, pixels); \e usable false
    for a feature that is not tracked, not finite or out of the image (it neither votes nor updates its memory).
  */
  void observe(unsigned int i, bool usable);
  //! Ends the iteration: true if the model mismatches (see the class documentation).
  bool endIteration();

  //! True if the last endIteration() found a mismatch.
  bool isMismatch() const { return m_mismatch; }
  /*!
    True if the mismatch of the last endIteration() is of left and right images exchanged (see the class
    documentation): give the left camera's image first.
  */
  bool isImagesExchanged() const { return m_mismatch && m_exchangedIterations >= m_iterations; }
  //! Prediction distance (pixels) of feature \e i at the last iteration, -1 if not evaluated (no check of \e i).
  double getDistance(unsigned int i) const { return m_records[i].distance; }
  /*!
    The point feature \e i is remembered as at the zero reference (4x1, unit norm, model frame; no check of \e i):
    the acquired marker's point once recognised, else the mean of its triangulations. False (and \e M untouched)
    without a memory.
  */
  bool getMemory(unsigned int i, Eigen::Vector4d &M) const
  {
    const vpRecord &r = m_records[i];
    if (!r.hasMemory || !(r.sum.norm() > 0.0)) {
      return false;
    }
    M = r.sum.normalized();
    return true;
  }
  /*!
    The unit-norm mean of feature \e i's triangulations at the zero reference, \f$ \propto \sum_k \pm H(q_k)^{-1}
    M_{ik} \f$ over the iterations where it agreed (4x1, no check of \e i), kept for a recognised marker too: the
    point in the frame of the rig that saw it (where a task's \f$ s^* \f$, triangulated through that rig, lies),
    which the acquired marker's point is not by the arm model's own error. What vpServoRigRefinement pairs with the
    images after a re-registration. False (and \e M untouched) without a memory.
  */
  bool getTriangulatedMemory(unsigned int i, Eigen::Vector4d &M) const
  {
    const vpRecord &r = m_records[i];
    if (!r.hasMemory || !(r.triangulated.norm() > 0.0)) {
      return false;
    }
    M = r.triangulated.normalized();
    return true;
  }
  //! True if feature \e i is remembered as an acquired marker's point (no check of \e i).
  bool isMemoryExact(unsigned int i) const { return m_records[i].hasMemory && m_records[i].exact; }
  //! Number of consecutive disagreeing iterations so far.
  unsigned int getDisagreeingIterations() const { return m_disagreeing; }
  /*!
    The noise learned from the iterations that agreed (\f$ \hat\sigma \f$ of the class documentation, before its
    floor: pixels per coordinate of a feature's residual against its recent prediction, \f$ \sqrt 2 \f$ times the
    features' own noise); 0 until an iteration agreed.
  */
  double getNoise() const { return std::sqrt(m_noise2); }

private:
  struct vpRecord {
    Eigen::Vector4d sum;          // sum of the sign-aligned unit points at the zero reference
    Eigen::Vector4d s;            // this iteration's value
    double distance;              // this iteration's distance, -1: not evaluated
    double exchangedDistance;     // the same with the two images exchanged (an acquired marker's prediction), or -1
    int marker;                   // this iteration's vpProjectiveArmModel::matchMarker() of a non-exact memory, or -1
    bool usable;                  // this iteration
    bool hasMemory;               // sum is set
    bool exact;                   // sum is an acquired marker's point (vpProjectiveArmModel::matchMarker())
    Eigen::Vector4d recent;       // the recent memory (unit, zero reference), set with hasMemory
    Eigen::Vector4d offset;       // the feature's value minus the recent memory's image where it last agreed
    Eigen::Vector4d last;         // the feature's value where it last agreed
    Eigen::Vector4d triangulated; // as sum, of the triangulations only (kept for a marker)
    Eigen::Vector4d residual;     // this iteration's value minus its recent prediction (offset, no slack)
    double motion;                // the image motion of that prediction since the feature last agreed (pixels)
    bool hasResidual;             // residual and motion are this iteration's
  };

  bool disagreesWithNoise(); // the tests against the learned noise (class documentation, "Noise")
  void learnNoise();         // from an iteration that agreed

  std::vector<vpRecord> m_records;
  double m_threshold;
  unsigned int m_iterations;
  unsigned int m_disagreeing;
  unsigned int m_exchangedIterations; // consecutive iterations seeing the left and right images exchanged
  bool m_mismatch;
  std::vector<double> m_work;      // 2 values per feature, sized by resize(): the medians without allocation
  std::vector<double> m_sumBounds; // [k]: the chi-square bound of the sum over k features of an image, by resize()
  double m_noise2;                 // the learned noise's square, 0: none yet
  unsigned int m_noiseIterations;  // the iterations that gave it
  const vpProjectiveArmModel *m_model;
  const vpServoProjectiveData *m_data;
};

END_VISP_NAMESPACE

#endif
