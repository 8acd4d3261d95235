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
  What the translation units of the Python module visp_projective share: the binding function of each part (one
  translation unit each, so that a parallel build compiles them side by side), the GIL policy of long calls, Python
  callables given to C++ code that runs without the GIL, and C++ progress output written to a Python file.

  GIL. A call that may take long (estimation, calibration, acquisition, planning, rendering, detection) releases the
  GIL once its arguments are converted (ReleaseGil); C++ code that then calls back into Python (an image source, a
  Python robot, a progress stream) takes the GIL for the duration of that call only.
*/

#ifndef _visp_projective_python_module_h_
#define _visp_projective_python_module_h_

#include "conversions.h"

#include <initializer_list>
#include <memory>
#include <ostream>
#include <utility>
#include <vector>

#include <Eigen/Core>
#include <pybind11/iostream.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
//! The pixels (u, v) of a list of image points: an (N, 2) array in Python (conversions.h).
typedef std::vector<vpImagePoint> Pixels;

//! The call guard of the long calls: the GIL is released while the C++ function runs.
typedef py::call_guard<py::gil_scoped_release> ReleaseGil;

//! The parts of the module, in the order the module defines them (a part may use the enumerations of earlier ones).
void bindErrors(py::module_ &m);
void bindGeometry(py::module_ &m);
void bindRobot(py::module_ &m);
void bindServo(py::module_ &m);
void bindSimulation(py::module_ &m);
void bindAcquisition(py::module_ &m);
void bindSessions(py::module_ &m);

/*!
  Binds the C++ enumeration \e E as the Python enum \e name of \e scope (a class or the module) from the table of its
  \e values, each a (Python name, C++ value) pair, and exports the values into \e scope as C++ has them in the class
  (ProjectiveRobot.REVOLUTE beside ProjectiveRobot.JointType.REVOLUTE): one way of binding every enumeration.
*/
template <typename E, typename Scope>
void bindEnum(Scope &scope, const char *name, std::initializer_list<std::pair<const char *, E>> values)
{
  py::enum_<E> binding(scope, name);
  for (const std::pair<const char *, E> &value : values) {
    binding.value(value.first, value.second);
  }
  binding.export_values();
}

//! A 4x4 Eigen matrix as a (4, 4) numpy array.
inline py::array_t<double> toArray(const Eigen::Matrix4d &M)
{
  const Eigen::Matrix<double, 4, 4, Eigen::RowMajor> rows = M;
  return newArray({4, 4}, rows.data());
}

/*!
  The images of a stereo pair that \e fill(left, right) gives, computed with the GIL released (rendering, reading
  files): a (left, right) tuple of 2-D uint8 arrays, or None when \e fill returns false (no more images).
*/
template <typename Fill> py::object stereoPair(Fill fill)
{
  vpImage<unsigned char> left, right;
  bool filled = false;
  {
    py::gil_scoped_release release;
    filled = fill(left, right);
  }
  return filled ? py::object(py::make_tuple(left, right)) : py::object(py::none());
}

/*!
  A Python callable held by C++ code that may copy or destroy it without the GIL (a std::function in a C++ object
  whose method runs with the GIL released): the Python object is only touched with the GIL held, by call() and by
  the last owner's destruction.
*/
class Callable
{
public:
  explicit Callable(py::object f)
      : m_f(new py::object(std::move(f)), [](py::object *o) {
          py::gil_scoped_acquire gil;
          delete o;
        })
  {
  }
  //! Calls the callable with \e args under the GIL and gives the result to \e use, still under the GIL.
  template <typename Use, typename... Args> auto call(Use use, Args &&...args) const
  {
    py::gil_scoped_acquire gil;
    return use((*m_f)(std::forward<Args>(args)...));
  }

private:
  std::shared_ptr<py::object> m_f;
};

/*!
  An std::ostream that writes to a Python file object (sys.stdout by default) with the GIL taken at each flush, for
  the C++ classes' progress output (setOutput()); each line the classes write is flushed.
*/
class Output
{
public:
  explicit Output(const py::object &file) : m_buffer(file), m_stream(&m_buffer) {}
  std::ostream *stream() { return &m_stream; }

private:
  py::detail::pythonbuf m_buffer;
  std::ostream m_stream;
};

/*!
  A C++ object with the progress output of its setOutput(std::ostream *) given in Python: setOutput(file) writes to
  the Python file \e file (e.g. sys.stdout), setOutput(None) to nothing. The Python object keeps the stream alive.
*/
template <typename Base> class WithOutput : public Base
{
public:
  using Base::Base;
  void setPythonOutput(const py::object &file)
  {
    if (file.is_none()) {
      Base::setOutput(nullptr);
      m_output.reset();
    } else {
      std::unique_ptr<Output> output(new Output(file));
      Base::setOutput(output->stream());
      m_output = std::move(output);
    }
  }

private:
  std::unique_ptr<Output> m_output;
};
} // namespace vpPython

#endif
