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

#include "visp-projective-options.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>

#include <visp3/core/vpConfig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vispProjective
{
Arguments::Arguments(const std::string &command, const std::vector<std::string> &positional,
                     const std::vector<std::string> &valued, const std::vector<std::string> &flags)
    : m_command(command), m_positional(positional), m_valued(valued), m_flags(flags), m_values(), m_options()
{
}

bool Arguments::parse(int argc, char **argv, int first, bool &help, std::string &error)
{
  help = false;
  for (int i = first; i < argc; ++i) {
    std::string arg = argv[i];
    if (arg == "--help" || arg == "-h") {
      help = true;
      return false;
    }
    if (arg.size() > 1 && arg[0] == '-' && arg != "--") {
      std::string name = arg, text;
      const size_t equal = arg.find('=');
      const bool inline_value = equal != std::string::npos;
      if (inline_value) {
        name = arg.substr(0, equal);
        text = arg.substr(equal + 1);
      }
      if (std::find(m_flags.begin(), m_flags.end(), name) != m_flags.end() && !inline_value) {
        m_options[name] = "";
        continue;
      }
      if (std::find(m_valued.begin(), m_valued.end(), name) == m_valued.end()) {
        error = "unknown option '" + name + "'; see '" + m_command + " --help'";
        return false;
      }
      if (!inline_value) {
        if (i + 1 >= argc) {
          error = "the option " + name + " needs a value; see '" + m_command + " --help'";
          return false;
        }
        text = argv[++i];
      }
      m_options[name] = text;
      continue;
    }
    if (arg == "--") {
      for (++i; i < argc; ++i) {
        m_values.push_back(argv[i]);
      }
      break;
    }
    m_values.push_back(arg);
  }
  if (m_values.size() != m_positional.size()) {
    std::string expected;
    for (const std::string &p : m_positional) {
      expected += " " + p;
    }
    error = "takes" + expected + " (" + std::to_string(m_positional.size()) + " argument" +
            (m_positional.size() == 1 ? "" : "s") + "), got " + std::to_string(m_values.size()) + "; see '" +
            m_command + " --help'";
    return false;
  }
  return true;
}

std::string Arguments::value(const std::string &name, const std::string &fallback) const
{
  const auto it = m_options.find(name);
  return it == m_options.end() ? fallback : it->second;
}

bool Arguments::number(const std::string &name, double fallback, double min, double &value, std::string &error) const
{
  value = fallback;
  if (!has(name)) {
    return true;
  }
  const std::string text = this->value(name);
  char *end = nullptr;
  const double v = std::strtod(text.c_str(), &end);
  if (text.empty() || end == nullptr || *end != '\0' || !std::isfinite(v) || v < min) {
    error = "the option " + name + " needs a finite number of at least " + std::to_string(min) + ", not '" + text + "'";
    return false;
  }
  value = v;
  return true;
}
} // namespace vispProjective
