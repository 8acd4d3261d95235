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
  \file vpProjectiveCellTeach.cpp
  \brief s* taught by showing: the user brings the arm to the target (its pendant, by hand, or typed moves), confirms,
  and the corners of a few frames at rest are averaged.
*/

#include <visp3/projective/vpProjectiveCell.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>

#include <visp3/projective/vpProjectiveException.h>

#include "cell/vpProjectiveCellInternal.h"

using namespace vpProjectiveInternal;
using vpProjectiveCellInternal::at;

void vpProjectiveCell::ask(std::istream &commands, std::ostream &prompt, const std::string &question)
{
  const unsigned int n = static_cast<unsigned int>(m_types.size());
  prompt << question << "\n  (jog the arm with its pendant or by hand, or type 'move Q0 ... Q" << n - 1
         << "' (rad, m) or 'jog JOINT DELTA'; Enter or 'ok' confirms, 'quit' stops)" << std::endl;
  std::string line;
  for (;;) {
    prompt << "> " << std::flush;
    if (!std::getline(commands, line)) {
      const int signal = vpProjectiveCellRobot::getSignal();
      m_robot->halt(signal != 0 ? "a signal received while waiting for a confirmation"
                                : "the commands ended before a confirmation");
      fail(vpProjectiveException::robotMotionError, at("teach()"),
           "no confirmation: " + m_robot->getHaltReason() + "; the arm was stopped");
    }
    std::istringstream words(line);
    std::string word;
    if (!(words >> word) || word == "ok") {
      return;
    }
    if (word == "quit") {
      m_robot->halt("the user asked to quit");
      fail(vpProjectiveException::robotMotionError, at("teach()"), "the user asked to quit; the arm was stopped");
    }
    vpColVector q;
    double t = 0.0;
    m_robot->getJoints(q, t);
    std::vector<double> values;
    for (double v = 0.0; words >> v;) {
      values.push_back(v);
    }
    const bool move = word == "move" && values.size() == n && words.eof();
    const bool jog = word == "jog" && values.size() == 2 && words.eof() && values[0] >= 0.0 && values[0] < n &&
                     values[0] == std::floor(values[0]);
    if (!move && !jog) {
      prompt << "not understood: '" << line << "': type Enter, ok, quit, move with " << n
             << " readings, or jog JOINT DELTA" << std::endl;
      continue;
    }
    if (move) {
      q = vpColVector(values);
    } else {
      q[static_cast<unsigned int>(values[0])] += values[1];
    }
    try {
      moveTo(q);
    } catch (const vpProjectiveException &e) {
      if (m_robot->isHalted()) {
        throw;
      }
      prompt << e.getStringMessage() << std::endl; // refused before moving (outside the safe range): ask again
    }
  }
}

void vpProjectiveCell::teach(std::istream &commands, std::ostream &prompt)
{
  vpStopGuard guard(*m_robot);
  ask(commands, prompt, "Bring the arm to the TARGET pose of the servo, the tags in view of both cameras.");
  teachHere();
  ask(commands, prompt, "Bring the arm to the START pose of the servo (keep the tags in view).");
}

void vpProjectiveCell::teachHere()
{
  vpStopGuard guard(*m_robot);
  m_robot->stop(); // at rest: the images from now on show the arm still
  std::map<int, std::pair<vpImagePoint, vpImagePoint>> sum;
  std::map<int, unsigned int> count;
  vpColVector q0, q;
  double t = 0.0;
  for (unsigned int k = 0; k < m_settings.targetFrames; ++k) {
    vpFrame frame;
    grab(true, frame);
    m_robot->getJoints(q, t);
    if (k == 0) {
      q0 = q;
    }
    record(vpProjectiveSession::TARGET, q, t);
    for (size_t j = 0; j < frame.ids.size(); ++j) {
      const int tag = frame.ids[j] / 4;
      if (!m_settings.tags.empty() &&
          std::find(m_settings.tags.begin(), m_settings.tags.end(), tag) == m_settings.tags.end()) {
        continue;
      }
      auto &s = sum[frame.ids[j]];
      s.first += frame.left[j];
      s.second += frame.right[j];
      ++count[frame.ids[j]];
    }
  }
  const vpColVector moved = q - q0;
  if (std::max(moved.getMaxValue(), -moved.getMinValue()) > 1e-3) {
    fail(vpProjectiveException::invalidValueError, at("teach()"),
         "the arm moved while s* was taught (by more than 1e-3 rad or m): hold it still, then confirm");
  }
  m_targetIds.clear();
  m_targetLeft.clear();
  m_targetRight.clear();
  for (const auto &c : count) {
    if (c.second == m_settings.targetFrames) { // seen in every frame
      m_targetIds.push_back(c.first);
      m_targetLeft.push_back(sum[c.first].first / static_cast<double>(c.second));
      m_targetRight.push_back(sum[c.first].second / static_cast<double>(c.second));
    }
  }
  if (m_targetIds.size() < 3) {
    fail(vpProjectiveException::notEnoughPointsError, at("teach()"),
         "only " + std::to_string(m_targetIds.size()) + " corners" +
             (m_settings.tags.empty() ? std::string() : " of the servo's tags") + " are seen in all " +
             std::to_string(m_settings.targetFrames) +
             " frames at the target: the servo needs 3 (a tag's 4 give a better task); bring the tags into view of "
             "both cameras");
  }
  std::ostringstream os;
  os << "s*: " << m_targetIds.size() << " corners averaged over " << m_settings.targetFrames << " frames";
  progress(os.str());
}
