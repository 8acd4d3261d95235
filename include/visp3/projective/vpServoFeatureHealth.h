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
  \file vpServoFeatureHealth.h
  \brief Which stereo point features a servo iteration may use: lost, non-finite, out-of-image and outlying
  features, with the per-feature memory of the last acceptance.
*/

#ifndef _vpServoFeatureHealth_h_
#define _vpServoFeatureHealth_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <vector>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoProjectiveData.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpServoFeatureHealth
  \ingroup group_projective
  \brief The health of the stereo point features of a servo task: at each iteration, each feature \f$ i \f$, of
  current value \f$ s_i = (u, v, u', v') \f$ and desired value \f$ s^*_i \f$ (pixels, left then right image), gets a
  state, tested in this order:
  -# FEATURE_NOT_TRACKED: the tracker said so with setFeatureTracked(i, false);
  -# FEATURE_NOT_FINITE: \f$ s_i \f$ or \f$ s^*_i \f$ holds a NaN or an infinity (a tracker that lost the point);
  -# FEATURE_OUT_OF_IMAGE: outside the image window of setImageSize() in either image;
  -# FEATURE_OUTLIER: with setOutlierThreshold(), too far from its epipolar line or from the model's prediction;
  -# FEATURE_ACTIVE otherwise.

  <b>Distances.</b> With \f$ m = (u, v, 1)^T \f$, \f$ m' = (u', v', 1)^T \f$ and \f$ F \f$ the fundamental matrix of
  the rig (pixels), the epipolar distance (pixels) is the larger of the distances of \f$ m \f$ to the line
  \f$ F^T m' \f$ and of \f$ m' \f$ to the line \f$ F m \f$,
  \f[ d_F = \max\left( \frac{|m'^T F m|}{\|(F^T m')_{1,2}\|}, \frac{|m'^T F m|}{\|(F m)_{1,2}\|} \right); \f]
  the prediction distance (pixels) is the larger over both images of the pixel distance between \f$ s_i \f$ and the
  projection of
  \f[ \hat M_i = H(q)\, H(q_l)^{-1} M_l, \f]
  \f$ M_l \f$ the projective point (4x1, projective frame of the rig) triangulated when the feature was last
  accepted (found FEATURE_ACTIVE), at joints \f$ q_l \f$, moved by the model's displacement (34) \f$ H(q) \f$
  (4x4) since then.

  <b>Memory.</b> The class keeps, per feature, \f$ M_0 = H(q_l)^{-1} M_l \f$ (unit norm, never divided by its last
  coordinate; getMemory()), so that each iteration needs one \f$ H(q) \f$. The prediction is tested once the feature
  has been accepted at least once with the outlier rejection on. It is the task's only memory of where a feature was
  last accepted: vpServoProjective's open loop predicts from it too (vpProjectivePathFollowing::predict()).

  <b>One iteration.</b> startIteration() on the iteration's data (vpServoProjectiveData: \f$ H(q) \f$ and the
  triangulated points, computed once by the servo), classify() for every feature, then endIteration(): only then do the
  states, distances and memories of the iteration become those that the getters report and the next iteration predicts
  from. An iteration interrupted between startIteration() and endIteration() (an exception of the caller) leaves the
  previous outcome as it was. endIteration() sees every feature's state and distances before they become the outcome: a
  check over the whole iteration or over consecutive ones (a model that no longer predicts any feature) belongs there.

  vpServoProjective drives this class; its documentation tells what the servo does with each state.
*/
class VISP_EXPORT vpServoFeatureHealth
{
public:
  //! What happened to feature i at the last iteration.
  enum vpFeatureState {
    FEATURE_ACTIVE,       //!< Used by the control law.
    FEATURE_NOT_TRACKED,  //!< Set aside: setFeatureTracked(i, false).
    FEATURE_OUT_OF_IMAGE, //!< Set aside: outside the image window of setImageSize() in the left or right image.
    FEATURE_NOT_FINITE,   //!< Set aside: a coordinate of \f$ s_i \f$ or \f$ s^*_i \f$ is NaN or infinite.
    FEATURE_OUTLIER       //!< Set aside: farther than setOutlierThreshold() from its epipolar line or its prediction.
  };

  //! No feature, every check off.
  vpServoFeatureHealth();

  /*! \name Features */
  //@{
  //! One more feature (index getNumberOfFeatures() - 1): tracked, FEATURE_ACTIVE, no memory.
  void addFeature();
  //! Removes every feature and its memory.
  void clearFeatures();
  //! Number of features.
  unsigned int getNumberOfFeatures() const { return static_cast<unsigned int>(m_tracked.size()); }
  /*!
    The tracker's verdict on feature \e i: false sets it aside as FEATURE_NOT_TRACKED from the next iteration on,
    until it is set back to true. Default: true.
    \exception vpProjectiveException (dimensionError) if \e i is not the index of a feature.
  */
  void setFeatureTracked(unsigned int i, bool tracked);
  //! The value given by setFeatureTracked() for feature \e i. \exception vpProjectiveException on a bad index.
  bool isFeatureTracked(unsigned int i) const;
  //@}

  /*! \name Settings */
  //@{
  /*!
    Image size (pixels), for the detection of features that left the view. A feature is FEATURE_OUT_OF_IMAGE when
    \f$ (u, v) \f$ or \f$ (u', v') \f$ lies outside
    \f[ [b, w - 1 - b] \times [b, h - 1 - b] \f]
    (\f$ u \f$ the column, \f$ v \f$ the row, \f$ b \f$ = \e border pixels, bounds included). 0 x 0 (the default)
    disables the check.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if only one of \e width and \e height
    is 0, or \e border is negative, not finite or leaves no pixel (\f$ 2b > w - 1 \f$ or \f$ 2b > h - 1 \f$); nothing
    is changed then.
  */
  void setImageSize(unsigned int width, unsigned int height, double border = 0.0);
  /*!
    Outlier rejection (pixels): feature \e i is FEATURE_OUTLIER when its epipolar distance or, once it has been
    accepted, its prediction distance exceeds \e pixels (see the class documentation). 0 (the default) disables it.
    Choose it well above the noise: at \f$ \sigma \f$ px per coordinate the epipolar distance has a standard
    deviation of about \f$ \sqrt 2 \sigma \f$, and the prediction distance includes the model's own prediction error.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if \e pixels is negative or not finite;
    nothing is changed then.
  */
  void setOutlierThreshold(double pixels);
  //! Image width (pixels) of setImageSize() (0: no image check).
  unsigned int getImageWidth() const { return m_width; }
  //! Image height (pixels) of setImageSize().
  unsigned int getImageHeight() const { return m_height; }
  //! Border (pixels) of setImageSize().
  double getImageBorder() const { return m_border; }
  //! Threshold (pixels) of setOutlierThreshold() (0: no outlier rejection).
  double getOutlierThreshold() const { return m_outlierThreshold; }
  /*!
    Tolerance \f$ \tau \in (0, 1) \f$ (default \f$ 10^{-6} \f$, above \f$ 4 \cdot 10^{-8} \f$) of the test that
    vpServoProjective runs on a reduced task (features set aside): the active features still constrain every joint
    when the scale-aware singular value ratio of \f$ D^{-1} J^T J D^{-1} \f$ is at least \f$ \tau \f$
    (vpServoProjectiveReport::getSingularValueRatio()); otherwise SERVO_STOPPED.
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if not in (0, 1); nothing is changed.
  */
  void setRankTolerance(double tolerance);
  //! The tolerance of setRankTolerance().
  double getRankTolerance() const { return m_rankTolerance; }
  //@}

  /*! \name One iteration (see the class documentation) */
  //@{
  /*!
    Starts an iteration on \e data (vpServoProjectiveData: \f$ H(q) \f$, its inverse, the features' values and points,
    computed once by the caller) of \e model, an acquired model whose rig's \f$ F \f$ is read here, once for the
    iteration. No allocation. The data must outlive the iteration. Sizes are not checked.
  */
  void startIteration(const vpProjectiveArmModel &model, const vpServoProjectiveData &data);
  /*!
    State of feature \e i in this iteration, of current value \f$ s_i \f$ (vpServoProjectiveData::getFeature()) and
    desired value \e sStar (4x1, pixels \f$ (u, v, u', v') \f$); records its distances. An active feature's point
    (vpServoProjectiveData::getPoint(), linearly triangulated) is remembered as \f$ M_0 = H(q)^{-1} M \f$
    (vpServoProjectiveData::getZeroPoint()) for the next predictions. Classifying a feature twice in an iteration
    keeps the second outcome.
    \exception vpProjectiveException (dimensionError, notInitializedError) on a bad index or outside an iteration.
  */
  vpFeatureState classify(unsigned int i, const Eigen::Vector4d &sStar);
  /*!
    Ends the iteration: its states, distances and memories become the outcome reported by the getters.
    \exception vpProjectiveException (notInitializedError) outside an iteration, or if a feature was not classified
    in it (the iteration then stays open).
  */
  void endIteration();
  //@}

  /*! \name Outcome of the last completed iteration */
  //@{
  /*!
    State of feature \e i (FEATURE_ACTIVE before the first iteration).
    \exception vpProjectiveException (dimensionError) on a bad index.
  */
  vpFeatureState getFeatureState(unsigned int i) const { return outcome(i, "getFeatureState()").state; }
  /*!
    Epipolar distance \f$ d_F \f$ (pixels) of feature \e i; -1 if it was not evaluated (outlier rejection off, or the
    feature set aside before the test).
    \exception vpProjectiveException (dimensionError) on a bad index.
  */
  double getEpipolarDistance(unsigned int i) const { return outcome(i, "getEpipolarDistance()").epipolarDistance; }
  /*!
    Prediction distance (pixels) of feature \e i; -1 if it was not evaluated (outlier rejection off, no earlier
    acceptance, the feature set aside before the test, or the prediction on a camera's focal plane).
    \exception vpProjectiveException (dimensionError) on a bad index.
  */
  double getPredictionDistance(unsigned int i) const
  {
    return outcome(i, "getPredictionDistance()").predictionDistance;
  }
  //! Number of features found active.
  unsigned int getNumberOfActiveFeatures() const { return m_nbActive; }
  /*!
    True if feature \e i, at its classify() in the iteration in progress (else in the last completed iteration), was
    tracked, finite and inside the image window of setImageSize(), whatever its desired value and the outlier tests:
    a feature the model can be checked against (vpServoModelMismatch::observe()). The window is tested here only,
    once per feature and iteration. \exception vpProjectiveException (dimensionError) on a bad index.
  */
  bool isInView(unsigned int i) const;
  /*!
    The point \e M0 (4x1, unit norm, projective frame of the rig at the zero reference) of feature \e i at the last
    completed iteration where it was accepted (FEATURE_ACTIVE): \f$ H(q_l)^{-1} M_l \f$. False (\e M0 untouched) if it
    never was. \exception vpProjectiveException (dimensionError) on a bad index.
  */
  bool getMemory(unsigned int i, Eigen::Vector4d &M0) const
  {
    const vpRecord &r = outcome(i, "getMemory()");
    if (r.hasM0) {
      M0 = r.M0;
    }
    return r.hasM0;
  }
  //@}

private:
  //! The outcome of one feature in one iteration, and its memory.
  struct vpRecord {
    vpFeatureState state;
    double epipolarDistance;   // -1: not evaluated
    double predictionDistance; // -1: not evaluated
    Eigen::Vector4d M0;        // H(q_l)^-1 M_l at the last acceptance, unit norm
    bool hasM0;                // M0 is set
    bool predicts;             // accepted with the outlier rejection on: the prediction is tested
    bool inView;               // tracked, finite and inside the image window (isInView())
    unsigned long iteration;   // the iteration that classified it (0: none)
  };

  void checkIndex(unsigned int i, const char *method) const;
  //! The outcome of feature \e i in the last completed iteration; throws as checkIndex(), naming \e method.
  const vpRecord &outcome(unsigned int i, const char *method) const;
  void checkIteration(const char *method) const;
  vpFeatureState outlierTest(const Eigen::Vector4d &s, vpRecord &record) const;

  std::vector<char> m_tracked;
  std::vector<vpRecord> m_records; // outcome of the last completed iteration
  std::vector<vpRecord> m_work;    // the iteration in progress
  unsigned int m_nbActive;
  unsigned int m_width;
  unsigned int m_height;
  double m_border;
  double m_outlierThreshold;
  double m_rankTolerance;

  // The iteration in progress.
  unsigned long m_iteration; // its number, from 1
  unsigned int m_classified; // features classified in it
  unsigned int m_workActive; // of which active
  bool m_inIteration;
  bool m_predict;
  Eigen::Matrix3d m_F; // the rig's fundamental matrix, for the epipolar test
  const vpServoProjectiveData *m_data;
};

END_VISP_NAMESPACE

#endif
