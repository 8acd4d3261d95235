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

#include <visp3/projective/vpProjectiveNotices.h>

#include <atomic>
#include <cstdint>
#include <iostream>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace
{
std::atomic<bool> g_enabled(true);
std::atomic<std::uint64_t> g_told(0); // bit k: kind k was told

std::uint64_t bitOf(unsigned int kind)
{
  return std::uint64_t(1) << kind;
}
} // namespace

void vpProjectiveNotices::setEnabled(bool enabled)
{
  g_enabled.store(enabled);
}

bool vpProjectiveNotices::isEnabled()
{
  return g_enabled.load();
}

void vpProjectiveNotices::reset()
{
  g_told.store(0);
}

bool vpProjectiveNotices::isPending(unsigned int kind)
{
  return kind < maxKinds && g_enabled.load(std::memory_order_relaxed) &&
         (g_told.load(std::memory_order_relaxed) & bitOf(kind)) == 0;
}

bool vpProjectiveNotices::tell(unsigned int kind, const std::string &line)
{
  if (!isPending(kind)) {
    return false;
  }
  if ((g_told.fetch_or(bitOf(kind)) & bitOf(kind)) != 0) {
    return false; // another thread told it first
  }
  std::cerr << "Warning: " << line << " (vpProjectiveNotices::setEnabled(false) silences these lines)" << std::endl;
  return true;
}
