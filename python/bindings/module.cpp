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
  The Python module visp_projective (DESIGN.md section 3, fourth round): ViSP's class names without the vp prefix,
  their methods' names, numpy arrays for ViSP's types (conversions.h), and every vpException raised as a Python
  exception with the same message: ProjectiveException for the plugin's vpProjectiveException, ViSPException (its base)
  for ViSP's others, both RuntimeError, with the ViSP error code in their attribute `code`.
*/

#include "module.h"

#include <visp3/core/vpException.h>
#include <visp3/projective/vpProjectiveException.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
// The exception types, created once with the module and kept for the process's lifetime (never destroyed: the
// interpreter may be gone when static objects are).
PyObject *g_vispException = nullptr;
PyObject *g_projectiveException = nullptr;

void raise(PyObject *type, const vpException &e)
{
  py::object exception = py::reinterpret_borrow<py::object>(type)(e.getStringMessage());
  exception.attr("code") = e.getCode();
  PyErr_SetObject(type, exception.ptr());
}
} // namespace

void bindErrors(py::module_ &m)
{
  g_vispException = py::exception<vpException>(m, "ViSPException", PyExc_RuntimeError).release().ptr();
  g_projectiveException =
      py::exception<vpProjectiveException>(m, "ProjectiveException", g_vispException).release().ptr();
  py::object projective = m.attr("ProjectiveException");
  m.attr("ViSPException").attr("__doc__") =
      "A ViSP error (vpException): str(e) is ViSP's message, e.code ViSP's error code.";
  projective.attr("__doc__") = "An error of the plugin (vpProjectiveException): str(e) says what was wrong and what to "
                               "do, e.code is one of the class's codes (notEnoughPointsError, ...).";
  const std::pair<const char *, vpProjectiveException::errorProjectiveCodeEnum> codes[] = {
      {"notEnoughPointsError", vpProjectiveException::notEnoughPointsError},
      {"degenerateConfigurationError", vpProjectiveException::degenerateConfigurationError},
      {"nonFiniteValueError", vpProjectiveException::nonFiniteValueError},
      {"dimensionError", vpProjectiveException::dimensionError},
      {"notInitializedError", vpProjectiveException::notInitializedError},
      {"invalidValueError", vpProjectiveException::invalidValueError},
      {"pointAtInfinityError", vpProjectiveException::pointAtInfinityError},
      {"fileError", vpProjectiveException::fileError},
      {"estimationFailedError", vpProjectiveException::estimationFailedError},
      {"robotMotionError", vpProjectiveException::robotMotionError},
      {"modelRejectedError", vpProjectiveException::modelRejectedError}};
  for (const auto &code : codes) {
    projective.attr(code.first) = static_cast<int>(code.second);
  }
  py::register_exception_translator([](std::exception_ptr p) {
    try {
      if (p) {
        std::rethrow_exception(p);
      }
    } catch (const vpProjectiveException &e) {
      raise(g_projectiveException, e);
    } catch (const vpException &e) {
      raise(g_vispException, e);
    }
  });
}
} // namespace vpPython

PYBIND11_MODULE(visp_projective, m)
{
  m.doc() = "visp_projective: non-metric stereo visual servoing for ViSP (Ruf & Horaud, ICCV'99) from Python. "
            "Classes as in C++ without the vp prefix, numpy arrays for matrices, vectors, (N, 2) pixel lists of "
            "(u, v) rows and uint8 images.";
  vpPython::bindErrors(m);
  vpPython::bindGeometry(m);
  vpPython::bindRobot(m);
  vpPython::bindServo(m);
  vpPython::bindSimulation(m);
  vpPython::bindAcquisition(m);
  vpPython::bindSessions(m);
}
