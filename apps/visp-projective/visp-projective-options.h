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
  \file visp-projective-options.h
  \brief The command line of visp-projective: positional arguments and "--name VALUE" (or "--name=VALUE") options,
  with the usage of each subcommand.
*/

#ifndef _visp_projective_options_h_
#define _visp_projective_options_h_

#include <map>
#include <string>
#include <vector>

namespace vispProjective
{
//! One subcommand's command line: its positional arguments and options, and its usage text.
class Arguments
{
public:
  /*!
    A command line \e command (e.g. "calibrate") with the \e positional argument names (e.g. "SESSION"), the
    options that take a value (\e valued: "--output") and those that do not (\e flags: "--quiet").
  */
  Arguments(const std::string &command, const std::vector<std::string> &positional,
            const std::vector<std::string> &valued, const std::vector<std::string> &flags);
  /*!
    Reads argv[first..argc-1]. Returns false on --help or -h (\e help set) or on a mistake (\e error set to a
    one-line message).
  */
  bool parse(int argc, char **argv, int first, bool &help, std::string &error);
  //! Positional argument \e i.
  const std::string &positional(size_t i) const { return m_values[i]; }
  //! The option's value, or \e fallback if not given.
  std::string value(const std::string &name, const std::string &fallback = std::string()) const;
  //! True if the option was given.
  bool has(const std::string &name) const { return m_options.count(name) != 0; }
  /*!
    The option's value as a finite number >= \e min (\e fallback if not given); false with \e error set otherwise.
  */
  bool number(const std::string &name, double fallback, double min, double &value, std::string &error) const;

private:
  std::string m_command;
  std::vector<std::string> m_positional, m_valued, m_flags, m_values;
  std::map<std::string, std::string> m_options;
};
} // namespace vispProjective

#endif
