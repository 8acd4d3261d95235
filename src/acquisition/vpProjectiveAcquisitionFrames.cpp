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
  vpProjectiveArmAcquisition's frames for the metric self-calibration: views of the markers at any configuration, and
  every stereo image of the acquisition with its joint readings.
*/

#include <visp3/projective/vpProjectiveArmAcquisition.h>

#include <sstream>

#include "core/vpProjectiveConversions.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveArmAcquisition");
} // namespace

vpProjectiveArmAcquisition::vpProjectiveArmAcquisition(const vpProjectiveArmModel &model)
    : vpProjectiveArmAcquisition(model.jointTypes())
{
  setRigMounting(model.getRigMounting());
  setStereoRig(model.getStereoRig());
  m_qRef = model.zeroReferenceJoints();
  for (size_t j = 0; j < model.markers().size(); ++j) {
    m_ids.push_back(static_cast<int>(j));
  }
}

void vpProjectiveArmAcquisition::addCalibrationFrame(const vpColVector &q, const std::vector<vpImagePoint> &left,
                                                     const std::vector<vpImagePoint> &right)
{
  if (!m_ids.empty() && left.size() == right.size() && left.size() != m_ids.size()) {
    std::ostringstream os;
    os << "the frame shows " << left.size() << " markers but the zero reference " << m_ids.size()
       << "; pass the same markers in the same order";
    fail(vpProjectiveException::dimensionError, at("addCalibrationFrame()"), os.str());
  }
  addCalibrationFrame(q, m_ids, left, right); // every marker, in the zero reference's order
}

void vpProjectiveArmAcquisition::addCalibrationFrame(const vpColVector &q, const std::vector<int> &ids,
                                                     const std::vector<vpImagePoint> &left,
                                                     const std::vector<vpImagePoint> &right)
{
  const std::string where = at("addCalibrationFrame()");
  if (m_ids.empty()) {
    fail(vpProjectiveException::notInitializedError, where,
         "call setZeroReference() before adding calibration frames: their markers are the zero reference's");
  }
  vpFrame frame;
  frame.q = toEigenVector<vpProjectiveArmModel::JointVector>(q, m_types.size(), where, "the joint readings");
  unsigned int shown = 0;
  frame.s = matchByIds(ids, left, right, where, frame.seen, shown);
  if (shown == 0) {
    fail(vpProjectiveException::notEnoughPointsError, where,
         "the frame shows none of the zero reference's markers (matched by id); leave it out");
  }
  m_frames.push_back(std::move(frame));
}

std::vector<vpProjectiveArmAcquisition::vpFrame> vpProjectiveArmAcquisition::getFrames() const
{
  std::vector<vpFrame> frames;
  if (!m_zeroImages.empty()) {
    frames.push_back(vpFrame{m_qRef, m_zeroImages, std::vector<bool>(m_zeroImages.size(), true)});
  }
  for (size_t k = 0; k < m_trials.size(); ++k) {
    vpFrame frame{m_qRef, m_trials[k].s, m_trials[k].seen};
    frame.q(m_trials[k].joint) += m_trials[k].amount;
    if (m_inlier.size() == m_trials.size()) {
      frame.seen = m_inlier[k]; // the last calibrate()'s: false where not shown or an outlier
    }
    frames.push_back(std::move(frame));
  }
  frames.insert(frames.end(), m_frames.begin(), m_frames.end());
  return frames;
}
