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
  The numpy face of ViSP's types in the Python module visp_projective (DESIGN.md section 3, fourth round): pybind11
  type casters, so that every bound method takes and returns numpy arrays where the C++ API has
  - vpColVector: a 1-D float array (n,) (an (n, 1) array is accepted too);
  - vpMatrix: a 2-D float array;
  - vpHomogeneousMatrix: a (4, 4) float array, checked to be a rigid transform;
  - vpImagePoint: (u, v), 2 floats (u = get_u() the column, v = get_v() the row);
  - std::vector<vpImagePoint>: an (N, 2) float array of (u, v) rows;
  - std::vector<vpColVector>: an (N, k) float array, one vector per row;
  - vpImage<unsigned char>: a 2-D uint8 array (height, width).
  Every conversion copies (the C++ objects own their data), so a call may release the GIL once its arguments are
  converted. An argument of the right kind but the wrong shape raises ValueError naming the expected shape; one of
  another kind (another number of dimensions) lets pybind11 try the method's other overloads.
  Included by every translation unit of the module, before any binding (one definition of each caster).
*/

#ifndef _visp_projective_python_conversions_h_
#define _visp_projective_python_conversions_h_

#include <string>
#include <vector>

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpMatrix.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace py = pybind11;
typedef py::array_t<double, py::array::c_style | py::array::forcecast> DoubleArray;

//! \e src as a C-contiguous float64 array, or an invalid handle (and no Python error) if it does not convert.
inline DoubleArray toDoubleArray(py::handle src)
{
  if (!src || src.is_none()) {
    return DoubleArray();
  }
  DoubleArray a = DoubleArray::ensure(src);
  if (!a) {
    PyErr_Clear();
  }
  return a;
}

//! "(5, 3)": the shape of \e a for a message.
inline std::string shapeOf(const py::array &a)
{
  std::string s = "(";
  for (py::ssize_t k = 0; k < a.ndim(); ++k) {
    s += (k > 0 ? ", " : "") + std::to_string(a.shape(k));
  }
  return s + (a.ndim() == 1 ? ",)" : ")");
}

//! A new float64 array of \e shape filled from \e data (row-major).
inline py::array_t<double> newArray(std::vector<py::ssize_t> shape, const double *data)
{
  py::array_t<double> a(shape);
  if (a.size() > 0) {
    std::copy(data, data + a.size(), a.mutable_data());
  }
  return a;
}
} // namespace vpPython

namespace pybind11
{
namespace detail
{
template <> struct type_caster<vpColVector> {
  PYBIND11_TYPE_CASTER(vpColVector, const_name("numpy.ndarray[float64[n]]"));
  bool load(handle src, bool)
  {
    vpPython::DoubleArray a = vpPython::toDoubleArray(src);
    if (!a || a.ndim() < 1 || a.ndim() > 2 || (a.ndim() == 2 && a.shape(1) != 1)) {
      return false; // a matrix may be another overload's (a list of vectors)
    }
    value.resize(static_cast<unsigned int>(a.shape(0)), false);
    std::copy(a.data(), a.data() + a.shape(0), value.data);
    return true;
  }
  static handle cast(const vpColVector &v, return_value_policy, handle)
  {
    return vpPython::newArray({static_cast<ssize_t>(v.size())}, v.data).release();
  }
};

template <> struct type_caster<vpMatrix> {
  PYBIND11_TYPE_CASTER(vpMatrix, const_name("numpy.ndarray[float64[m, n]]"));
  bool load(handle src, bool)
  {
    vpPython::DoubleArray a = vpPython::toDoubleArray(src);
    if (!a || a.ndim() != 2) {
      return false;
    }
    value.resize(static_cast<unsigned int>(a.shape(0)), static_cast<unsigned int>(a.shape(1)), false);
    std::copy(a.data(), a.data() + a.size(), value.data);
    return true;
  }
  static handle cast(const vpMatrix &M, return_value_policy, handle)
  {
    return vpPython::newArray({static_cast<ssize_t>(M.getRows()), static_cast<ssize_t>(M.getCols())}, M.data).release();
  }
};

template <> struct type_caster<vpHomogeneousMatrix> {
  PYBIND11_TYPE_CASTER(vpHomogeneousMatrix, const_name("numpy.ndarray[float64[4, 4]]"));
  bool load(handle src, bool)
  {
    vpPython::DoubleArray a = vpPython::toDoubleArray(src);
    if (!a || a.ndim() != 2) {
      return false;
    }
    if (a.shape(0) != 4 || a.shape(1) != 4) {
      throw value_error("a (4, 4) homogeneous matrix was expected, got shape " + vpPython::shapeOf(a));
    }
    for (unsigned int k = 0; k < 16; ++k) {
      value.data[k] = a.data()[k];
    }
    if (!value.isAnHomogeneousMatrix()) {
      throw value_error("a (4, 4) homogeneous matrix [R t; 0 0 0 1] with R a rotation (orthonormal, determinant 1) "
                        "was expected");
    }
    return true;
  }
  static handle cast(const vpHomogeneousMatrix &M, return_value_policy, handle)
  {
    return vpPython::newArray({4, 4}, M.data).release();
  }
};

template <> struct type_caster<vpImagePoint> {
  PYBIND11_TYPE_CASTER(vpImagePoint, const_name("numpy.ndarray[float64[2]] (u, v)"));
  bool load(handle src, bool)
  {
    vpPython::DoubleArray a = vpPython::toDoubleArray(src);
    if (!a || a.ndim() != 1) {
      return false;
    }
    if (a.shape(0) != 2) {
      throw value_error("a pixel (u, v) of 2 floats was expected, got shape " + vpPython::shapeOf(a));
    }
    value.set_uv(a.data()[0], a.data()[1]);
    return true;
  }
  static handle cast(const vpImagePoint &ip, return_value_policy, handle)
  {
    const double uv[2] = {ip.get_u(), ip.get_v()};
    return vpPython::newArray({2}, uv).release();
  }
};

template <> struct type_caster<std::vector<vpImagePoint>> {
  PYBIND11_TYPE_CASTER(std::vector<vpImagePoint>, const_name("numpy.ndarray[float64[N, 2]] (u, v) rows"));
  bool load(handle src, bool)
  {
    vpPython::DoubleArray a = vpPython::toDoubleArray(src);
    if (!a || a.ndim() < 1 || a.ndim() > 2 || (a.ndim() == 1 && a.size() != 0)) {
      return false; // an empty list is an empty set of pixels; a single pixel (2,) is another overload's
    }
    if (a.ndim() == 2 && a.shape(1) != 2) {
      throw value_error("an (N, 2) array of (u, v) pixels was expected, got shape " + vpPython::shapeOf(a));
    }
    const size_t n = a.ndim() == 2 ? static_cast<size_t>(a.shape(0)) : 0;
    value.resize(n);
    for (size_t k = 0; k < n; ++k) {
      value[k].set_uv(a.data()[2 * k], a.data()[2 * k + 1]);
    }
    return true;
  }
  static handle cast(const std::vector<vpImagePoint> &points, return_value_policy, handle)
  {
    array_t<double> a({static_cast<ssize_t>(points.size()), static_cast<ssize_t>(2)});
    double *d = a.mutable_data();
    for (size_t k = 0; k < points.size(); ++k) {
      d[2 * k] = points[k].get_u();
      d[2 * k + 1] = points[k].get_v();
    }
    return a.release();
  }
};

template <> struct type_caster<std::vector<vpColVector>> {
  PYBIND11_TYPE_CASTER(std::vector<vpColVector>, const_name("numpy.ndarray[float64[N, k]] (one vector per row)"));
  bool load(handle src, bool)
  {
    vpPython::DoubleArray a = vpPython::toDoubleArray(src);
    if (!a || a.ndim() < 1 || a.ndim() > 2 || (a.ndim() == 1 && a.size() != 0)) {
      return false;
    }
    const size_t n = a.ndim() == 2 ? static_cast<size_t>(a.shape(0)) : 0;
    const unsigned int k = a.ndim() == 2 ? static_cast<unsigned int>(a.shape(1)) : 0;
    value.assign(n, vpColVector(k));
    for (size_t r = 0; r < n; ++r) {
      std::copy(a.data() + r * k, a.data() + (r + 1) * k, value[r].data);
    }
    return true;
  }
  static handle cast(const std::vector<vpColVector> &vectors, return_value_policy, handle)
  {
    const ssize_t k = vectors.empty() ? 0 : static_cast<ssize_t>(vectors[0].size());
    for (const vpColVector &v : vectors) {
      if (static_cast<ssize_t>(v.size()) != k) { // vectors of different sizes: a list of arrays
        list l;
        for (const vpColVector &w : vectors) {
          l.append(reinterpret_steal<object>(type_caster<vpColVector>::cast(w, return_value_policy::copy, {})));
        }
        return l.release();
      }
    }
    array_t<double> a({static_cast<ssize_t>(vectors.size()), k});
    for (size_t r = 0; r < vectors.size(); ++r) {
      std::copy(vectors[r].data, vectors[r].data + k, a.mutable_data() + r * k);
    }
    return a.release();
  }
};

template <> struct type_caster<vpImage<unsigned char>> {
  PYBIND11_TYPE_CASTER(vpImage<unsigned char>, const_name("numpy.ndarray[uint8[height, width]]"));
  bool load(handle src, bool)
  {
    if (!src || src.is_none()) {
      return false;
    }
    // No forcecast: numpy converts only what converts safely (bool), not floats that would wrap around.
    array_t<unsigned char, array::c_style> a = array_t<unsigned char, array::c_style>::ensure(src);
    if (!a) {
      PyErr_Clear();
      return false;
    }
    if (a.ndim() != 2) {
      throw value_error("a 2-D uint8 image (height, width) was expected, got shape " + vpPython::shapeOf(a));
    }
    value.resize(static_cast<unsigned int>(a.shape(0)), static_cast<unsigned int>(a.shape(1)));
    std::copy(a.data(), a.data() + a.size(), value.bitmap);
    return true;
  }
  static handle cast(const vpImage<unsigned char> &I, return_value_policy, handle)
  {
    array_t<unsigned char> a({static_cast<ssize_t>(I.getHeight()), static_cast<ssize_t>(I.getWidth())});
    if (a.size() > 0) {
      std::copy(I.bitmap, I.bitmap + a.size(), a.mutable_data());
    }
    return a.release();
  }
};
} // namespace detail
} // namespace pybind11

#endif
