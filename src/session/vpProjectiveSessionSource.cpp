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

#include <visp3/projective/vpProjectiveSessionSource.h>

#include <algorithm>

#include "core/vpProjectiveErrors.h"

using namespace vpProjectiveInternal;

namespace
{
const vpErrorSite at("vpProjectiveSessionSource");
}

vpProjectiveSessionSource::vpProjectiveSessionSource(const vpProjectiveSession &session,
                                                     const std::vector<vpProjectiveSession::vpFrameRole> &roles)
    : m_session(session), m_order(), m_next(0), m_current(-1)
{
  if (session.getFolder().empty()) {
    fail(vpProjectiveException::notInitializedError, at("vpProjectiveSessionSource()"),
         "the session has no folder (no images to replay); read it with vpProjectiveSession::read(folder)");
  }
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    if (roles.empty() || std::find(roles.begin(), roles.end(), session.getFrame(k).role) != roles.end()) {
      m_order.push_back(k);
    }
  }
}

bool vpProjectiveSessionSource::acquire(vpImage<unsigned char> &Ileft, vpImage<unsigned char> &Iright)
{
  if (m_next >= m_order.size()) {
    return false;
  }
  const unsigned int k = m_order[m_next];
  m_session.getImages(k, Ileft, Iright);
  ++m_next;
  m_current = static_cast<int>(k);
  return true;
}

const vpProjectiveSession::vpFrame &vpProjectiveSessionSource::getFrame() const
{
  if (m_current < 0) {
    fail(vpProjectiveException::notInitializedError, at("getFrame()"), "no frame acquired yet; call acquire() first");
  }
  return m_session.getFrame(static_cast<unsigned int>(m_current));
}

const vpColVector &vpProjectiveSessionSource::getJoints() const
{
  return getFrame().q;
}

void vpProjectiveSessionSource::rewind()
{
  m_next = 0;
  m_current = -1;
}
