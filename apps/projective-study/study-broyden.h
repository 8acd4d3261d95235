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
  \file study-broyden.h
  \brief Uncalibrated servoing with a Broyden-estimated image Jacobian: the second baseline.
*/

#ifndef _study_study_broyden_h_
#define _study_study_broyden_h_

#include <cmath>
#include <functional>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>

#include "study-control.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace study
{
//! [Broyden]
/*!
  Uncalibrated servoing with a Broyden-estimated image Jacobian (Jagersand-style). prepare() initialises J by one
  small exploratory motion per joint at the start configuration (\e delta, tried the other way if the first one
  leaves an image or a joint range; the arm returns to the start after each): column i is the measured image motion
  divided by the joint motion. In the loop, each iteration's measured image change \f$ \Delta s \f$ and encoder
  change \f$ \Delta q \f$ give the rank-one update \f$ J \leftarrow J + (\Delta s - J \Delta q) \Delta q^T /
  (\Delta q^T \Delta q) \f$ on the rows tracked at both iterations. An update is made only if the step is measurable:
  the motion it predicts, \f$ \|J \Delta q\| \f$, must exceed 3 times the noise of \f$ \Delta s \f$ (\f$ \sqrt{2}
  \sigma \f$ per coordinate, so \f$ 3 \sqrt{2 m} \sigma \f$ for m rows); below it the update would only fit noise
  (its size grows as \f$ \sigma / \|\Delta q\| \f$ while the arm settles).
*/
class BroydenServo : public Controller
{
public:
  BroydenServo(unsigned int nbJoints, double delta, double sigma, const std::vector<vpImagePoint> &leftTarget,
               const std::vector<vpImagePoint> &rightTarget, const ControlSettings &settings)
      : m_n(nbJoints), m_delta(delta), m_sigma(sigma), m_target(targetVector(leftTarget, rightTarget)),
        m_settings(settings), m_J(), m_previousS(), m_previousQ(), m_previousTracked(), m_hasPrevious(false),
        m_updates(0), m_skipped(0)
  {
  }

  bool prepare(const vpColVector &q0,
               const std::function<bool(const vpColVector &, std::vector<vpImagePoint> &, std::vector<vpImagePoint> &)>
                   &moveAndMeasure,
               unsigned int &moves) override
  {
    moves = 0;
    std::vector<vpImagePoint> left0, right0;
    if (!moveAndMeasure(q0, left0, right0)) {
      return false;
    }
    const vpColVector s0 = targetVector(left0, right0);
    m_J.resize(s0.size(), m_n);
    for (unsigned int i = 0; i < m_n; ++i) {
      bool done = false;
      for (double sign : {1.0, -1.0}) {
        vpColVector q = q0;
        q[i] += sign * m_delta;
        std::vector<vpImagePoint> left, right;
        ++moves;
        if (moveAndMeasure(q, left, right)) {
          const vpColVector ds = targetVector(left, right) - s0;
          for (unsigned int r = 0; r < s0.size(); ++r) {
            m_J[r][i] = ds[r] / (sign * m_delta);
          }
          done = true;
          break;
        }
      }
      if (!done) {
        return false;
      }
    }
    return true;
  }

  vpColVector velocity(const vpColVector &q, const std::vector<vpImagePoint> &left,
                       const std::vector<vpImagePoint> &right, const std::vector<bool> &tracked) override
  {
    const vpColVector s = targetVector(left, right);
    if (m_hasPrevious) {
      update(q - m_previousQ, s - m_previousS, tracked);
    }
    m_previousS = s;
    m_previousQ = q;
    m_previousTracked = tracked;
    m_hasPrevious = true;

    unsigned int rows = 0;
    for (bool t : tracked) {
      rows += t ? 4 : 0;
    }
    vpMatrix J(rows, m_n);
    vpColVector e(rows);
    unsigned int r = 0;
    for (unsigned int row = 0; row < s.size(); ++row) {
      if (tracked[row / 4]) {
        for (unsigned int j = 0; j < m_n; ++j) {
          J[r][j] = m_J[row][j];
        }
        e[r++] = s[row] - m_target[row];
      }
    }
    return dampedLeastSquares(J, e, m_settings);
  }

  //! Numbers of rank-one updates made and skipped (step too small to be measured).
  unsigned int getUpdates() const { return m_updates; }
  unsigned int getSkippedUpdates() const { return m_skipped; }
  const vpMatrix &getJacobian() const { return m_J; }

  //! (u, v, u', v') of every point, stacked.
  static vpColVector targetVector(const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right)
  {
    vpColVector s(4 * static_cast<unsigned int>(left.size()));
    for (unsigned int k = 0; k < left.size(); ++k) {
      s[4 * k] = left[k].get_u();
      s[4 * k + 1] = left[k].get_v();
      s[4 * k + 2] = right[k].get_u();
      s[4 * k + 3] = right[k].get_v();
    }
    return s;
  }

private:
  void update(const vpColVector &dq, const vpColVector &ds, const std::vector<bool> &tracked)
  {
    const double dq2 = dq.sumSquare();
    std::vector<unsigned int> rows;
    for (unsigned int row = 0; row < ds.size(); ++row) {
      if (tracked[row / 4] && m_previousTracked[row / 4]) {
        rows.push_back(row);
      }
    }
    if (rows.empty() || !(dq2 > 0.0)) {
      ++m_skipped;
      return;
    }
    double predicted2 = 0.0;
    std::vector<double> residual(rows.size());
    for (size_t k = 0; k < rows.size(); ++k) {
      double Jdq = 0.0;
      for (unsigned int j = 0; j < m_n; ++j) {
        Jdq += m_J[rows[k]][j] * dq[j];
      }
      predicted2 += Jdq * Jdq;
      residual[k] = ds[rows[k]] - Jdq;
    }
    const double noise = 3.0 * std::sqrt(2.0 * rows.size()) * m_sigma;
    if (std::sqrt(predicted2) < noise) {
      ++m_skipped;
      return;
    }
    for (size_t k = 0; k < rows.size(); ++k) {
      for (unsigned int j = 0; j < m_n; ++j) {
        m_J[rows[k]][j] += residual[k] * dq[j] / dq2;
      }
    }
    ++m_updates;
  }

  unsigned int m_n;
  double m_delta;
  double m_sigma;
  vpColVector m_target;
  ControlSettings m_settings;
  vpMatrix m_J;
  vpColVector m_previousS, m_previousQ;
  std::vector<bool> m_previousTracked;
  bool m_hasPrevious;
  unsigned int m_updates, m_skipped;
};
//! [Broyden]
} // namespace study

#endif
