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
  \file command-line.h
  \brief The command line of the apps, written once: each program declares its options with
  their variables and help, and parse() fills them, prints the usage on --help or on a bad option, and says with
  which exit code to stop.

  \code
  unsigned int seeds = 20;
  bool display = vpStereoServoDisplay::hasDisplay(), click = true;
  app::CommandLine cmd;
  cmd.add("--seeds", seeds, "N", "number of noise seeds", 1).displayOptions(display, click); // -d, -c
  int exitCode;
  if (!cmd.parse(argc, argv, exitCode)) return exitCode;
  \endcode
*/

#ifndef _app_command_line_h_
#define _app_command_line_h_

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <iostream>
#include <limits>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpConfig.h>
#include <visp3/projective/vpStereoServoDisplay.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
//! Options of one program: declare them, then parse().
class CommandLine
{
public:
  //! An unsigned option "name VALUE": values below \e min are raised to it (as std::max(min, atoi(VALUE))).
  CommandLine &add(const std::string &name, unsigned int &value, const std::string &meta, const std::string &help,
                   unsigned int min = 0)
  {
    Option o = make(name, meta, help, UNSIGNED);
    o.u = &value;
    o.min = min;
    o.deflt = std::to_string(value);
    m_options.push_back(o);
    return *this;
  }
  //! A real option; a value below \e min or not finite is an error.
  CommandLine &add(const std::string &name, double &value, const std::string &meta, const std::string &help,
                   double min = -std::numeric_limits<double>::max())
  {
    Option o = make(name, meta, help, REAL);
    o.d = &value;
    o.min = min;
    std::ostringstream os;
    os << value;
    o.deflt = os.str();
    m_options.push_back(o);
    return *this;
  }
  //! A string option (a file or a directory).
  CommandLine &add(const std::string &name, std::string &value, const std::string &meta, const std::string &help)
  {
    Option o = make(name, meta, help, STRING);
    o.s = &value;
    o.deflt = value.empty() ? "none" : value;
    m_options.push_back(o);
    return *this;
  }
  //! An unsigned option whose value must be one of \e allowed.
  CommandLine &choice(const std::string &name, unsigned int &value, const std::vector<unsigned int> &allowed,
                      const std::string &help)
  {
    std::string meta;
    for (unsigned int a : allowed) {
      meta += (meta.empty() ? "" : "|") + std::to_string(a);
    }
    add(name, value, meta, help);
    m_options.back().allowed = allowed;
    return *this;
  }
  //! A flag without value: sets \e value to \e setTo.
  CommandLine &flag(const std::string &name, bool &value, bool setTo, const std::string &help)
  {
    Option o = make(name, "", help, FLAG);
    o.b = &value;
    o.setTo = setTo;
    m_options.push_back(o);
    return *this;
  }
  //! The display options of ViSP's examples: -d or --no-display sets \e display to false (no window even if a display
  //! is available), -c or --no-click sets \e click to false (no click awaited at the end).
  CommandLine &displayOptions(bool &display, bool &click)
  {
    flag("-d", display, false, "no window even if a display is available (or --no-display)");
    flag("--no-display", display, false, "the same as -d");
    flag("-c", click, false, "no click awaited at the end, with a window (or --no-click)");
    return flag("--no-click", click, false, "the same as -c");
  }
  //! A line printed after the options in the usage.
  CommandLine &note(const std::string &text)
  {
    m_notes.push_back(text);
    return *this;
  }

  /*!
    Reads the command line. Returns false if the program must stop at once with \e exitCode: after --help (or -h),
    EXIT_SUCCESS; after an unknown option, a missing or bad value, EXIT_FAILURE; the usage is printed in both cases.
  */
  bool parse(int argc, char **argv, int &exitCode) const
  {
    for (int i = 1; i < argc; ++i) {
      const std::string arg = argv[i];
      const Option *o = find(arg);
      std::string error;
      if (o == nullptr || (o->kind != FLAG && i + 1 >= argc)) {
        error = (arg == "--help" || arg == "-h") ? "" : "unknown option or missing value: " + arg;
        return stop(argv[0], error, exitCode);
      }
      if (o->kind == FLAG) {
        *o->b = o->setTo;
        continue;
      }
      const std::string text = argv[++i];
      if (o->kind == STRING) {
        *o->s = text;
      } else if (o->kind == REAL) {
        const double v = std::atof(text.c_str());
        if (!std::isfinite(v) || v < o->min) {
          std::ostringstream os;
          os << arg << " needs a finite number of at least " << o->min << ", not " << text;
          return stop(argv[0], os.str(), exitCode);
        }
        *o->d = v;
      } else {
        const unsigned int v = static_cast<unsigned int>(std::max(static_cast<int>(o->min), std::atoi(text.c_str())));
        if (!o->allowed.empty() && std::find(o->allowed.begin(), o->allowed.end(), v) == o->allowed.end()) {
          return stop(argv[0], arg + " takes " + o->meta + ", not " + text, exitCode);
        }
        *o->u = v;
      }
    }
    return true;
  }

private:
  enum Kind { UNSIGNED, REAL, STRING, FLAG };
  struct Option {
    std::string name, meta, help, deflt;
    Kind kind;
    unsigned int *u = nullptr;
    double *d = nullptr;
    std::string *s = nullptr;
    bool *b = nullptr;
    bool setTo = false;
    double min = 0.0;
    std::vector<unsigned int> allowed;
  };

  static Option make(const std::string &name, const std::string &meta, const std::string &help, Kind kind)
  {
    Option o;
    o.name = name;
    o.meta = meta;
    o.help = help;
    o.kind = kind;
    return o;
  }
  const Option *find(const std::string &name) const
  {
    for (const Option &o : m_options) {
      if (o.name == name) {
        return &o;
      }
    }
    return nullptr;
  }
  bool stop(const char *program, const std::string &error, int &exitCode) const
  {
    if (!error.empty()) {
      std::cerr << "Error: " << error << "\n";
    }
    std::cout << "Usage: " << program;
    for (const Option &o : m_options) {
      std::cout << " [" << o.name << (o.meta.empty() ? "" : " " + o.meta) << "]";
    }
    std::cout << " [--help]\n";
    for (const Option &o : m_options) {
      const std::string left = o.name + (o.meta.empty() ? "" : " " + o.meta);
      std::cout << "  " << left << std::string(left.size() < 20 ? 20 - left.size() : 1, ' ') << o.help
                << (o.kind == FLAG ? "" : " (default " + o.deflt + ")") << "\n";
    }
    for (const std::string &n : m_notes) {
      std::cout << n << "\n";
    }
    exitCode = error.empty() ? EXIT_SUCCESS : EXIT_FAILURE;
    return false;
  }

  std::vector<Option> m_options;
  std::vector<std::string> m_notes;
};
//! The options of the servo apps.
struct ServoOptions {
  unsigned int seeds = 20; //!< noise seeds of the study
  std::string modelFile;   //!< model file (.json): acquired and saved once, loaded by later runs
  std::string output;      //!< where to write data and figures
  bool display = vpStereoServoDisplay::hasDisplay(); //!< windows, if a display is available (-d: not)
  bool click = true;                                 //!< with windows, wait for a click at the end (-c: not)
  double maxExcursionDeg = 20; //!< planned paths: a joint's largest motion beyond its start and target values
};

/*!
  Reads the options of a servo app: --seeds N, --model FILE, --output DIR (only if \e withOutput; the default is
  \e options.output as given), --max-excursion DEG (only if \e withPlanning), -d, -c. Returns false if the
  program must stop with \e exitCode (see CommandLine::parse()).
*/
inline bool parseServoOptions(int argc, char **argv, ServoOptions &options, int &exitCode, bool withOutput,
                              bool withPlanning = false)
{
  CommandLine cmd;
  cmd.add("--seeds", options.seeds, "N", "noise seeds of the study", 1)
      .add("--model", options.modelFile, "FILE",
           "model file (arm.json): acquired and saved once, loaded by later runs");
  if (withOutput) {
    cmd.add("--output", options.output, "DIR", "where to write the run's data and figures");
  }
  if (withPlanning) {
    cmd.add("--max-excursion", options.maxExcursionDeg, "DEG",
            "largest motion of a joint beyond its start and target values on the plan (40: straight image lines)", 0.0);
  }
  cmd.displayOptions(options.display, options.click);
  return cmd.parse(argc, argv, exitCode);
}
} // namespace app

#endif
