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
  Python bindings of the projective geometry: the weakly calibrated rig (ProjectiveStereoRig) and the groups of
  p-displacements (ProjectiveDisplacement, ProjectiveRotation, ProjectiveTranslation). Output parameters of the C++
  methods become return values (project() returns the left and right pixels).
*/

#include "module.h"

#include <visp3/projective/vpProjectiveDisplacement.h>
#include <visp3/projective/vpProjectiveRotation.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpProjectiveTranslation.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace vpPython
{
namespace
{
void bindRig(py::module_ &m)
{
  py::class_<vpProjectiveStereoRig>(m, "ProjectiveStereoRig",
                                    "A stereo rig known only through its fundamental matrix F (m'^T F m = 0) and the "
                                    "projective frame of its canonical camera pair (vpProjectiveStereoRig).")
      .def(py::init<>())
      .def(py::init<const vpProjectiveStereoRig &>(), py::arg("other"), "A copy of another rig.")
      .def("estimate", &vpProjectiveStereoRig::estimate, py::arg("left"), py::arg("right"),
           py::arg("inlierThreshold") = 2.0, ReleaseGil(),
           "F from >= 8 matches: left[i] (u, v) seen as right[i], (N, 2) arrays; robust, then refined.")
      .def("setFundamentalMatrix", &vpProjectiveStereoRig::setFundamentalMatrix, py::arg("F"))
      .def("setProjections",
           py::overload_cast<const vpMatrix &, const vpMatrix &>(&vpProjectiveStereoRig::setProjections), py::arg("P"),
           py::arg("Pp"))
      .def("isCanonical", &vpProjectiveStereoRig::isCanonical)
      .def("isInitialized", &vpProjectiveStereoRig::isInitialized)
      .def("getFundamentalMatrix", py::overload_cast<>(&vpProjectiveStereoRig::getFundamentalMatrix, py::const_))
      .def("getLeftProjection", py::overload_cast<>(&vpProjectiveStereoRig::getLeftProjection, py::const_))
      .def("getRightProjection", py::overload_cast<>(&vpProjectiveStereoRig::getRightProjection, py::const_))
      .def("getLeftEpipole", &vpProjectiveStereoRig::getLeftEpipole)
      .def("getRightEpipole", &vpProjectiveStereoRig::getRightEpipole)
      .def("getInliers", &vpProjectiveStereoRig::getInliers, "Per match of the last estimate(): used or not.")
      .def("getEstimationResidual", &vpProjectiveStereoRig::getEstimationResidual)
      .def("triangulate",
           py::overload_cast<const vpImagePoint &, const vpImagePoint &>(&vpProjectiveStereoRig::triangulate,
                                                                         py::const_),
           py::arg("ipLeft"), py::arg("ipRight"), "The projective point M (4,) of one match (u, v), (u', v').")
      .def("triangulate",
           py::overload_cast<const std::vector<vpImagePoint> &, const std::vector<vpImagePoint> &>(
               &vpProjectiveStereoRig::triangulate, py::const_),
           py::arg("left"), py::arg("right"), "The points (N, 4) of N matches given as (N, 2) arrays.")
      .def(
          "project",
          [](const vpProjectiveStereoRig &rig, const vpColVector &M) {
            vpImagePoint left, right;
            rig.project(M, left, right);
            return py::make_tuple(left, right);
          },
          py::arg("M"), "The pixels (u, v) of M (4,) in the left and right images: a pair of (2,) arrays.");
}

void bindDisplacement(py::module_ &m)
{
  py::class_<vpProjectiveDisplacement> displacement(
      m, "ProjectiveDisplacement",
      "A p-displacement H = H_PE^-1 T H_PE (4x4, normalised by eq. (12)): how the points of a rigid body move "
      "(vpProjectiveDisplacement).");
  bindEnum<vpProjectiveDisplacement::vpMotionType>(displacement, "MotionType",
                                                   {{"IDENTITY", vpProjectiveDisplacement::IDENTITY},
                                                    {"TRANSLATION", vpProjectiveDisplacement::TRANSLATION},
                                                    {"ROTATION", vpProjectiveDisplacement::ROTATION},
                                                    {"GENERAL", vpProjectiveDisplacement::GENERAL}});
  displacement.def(py::init<>())
      .def(py::init<const vpMatrix &>(), py::arg("H"))
      .def_static("estimate",
                  py::overload_cast<const std::vector<vpColVector> &, const std::vector<vpColVector> &>(
                      &vpProjectiveDisplacement::estimate),
                  py::arg("M0"), py::arg("M1"), ReleaseGil(),
                  "H with M1[j] ~ H M0[j] from >= 5 pairs of projective points, (N, 4) arrays.")
      .def_static("estimate",
                  py::overload_cast<const vpProjectiveStereoRig &, const std::vector<vpImagePoint> &,
                                    const std::vector<vpImagePoint> &, const std::vector<vpImagePoint> &,
                                    const std::vector<vpImagePoint> &>(&vpProjectiveDisplacement::estimate),
                  py::arg("rig"), py::arg("left0"), py::arg("right0"), py::arg("left1"), py::arg("right1"),
                  ReleaseGil(), "The maximum-likelihood H from the images of >= 5 points before and after the motion.")
      .def_static(
          "estimate",
          [](const vpProjectiveStereoRig &rig, const std::vector<vpImagePoint> &left0,
             const std::vector<vpImagePoint> &right0, const std::vector<vpImagePoint> &left1,
             const std::vector<vpImagePoint> &right1, double inlierThreshold) {
            std::vector<bool> inliers;
            vpProjectiveDisplacement H;
            {
              py::gil_scoped_release release;
              H = vpProjectiveDisplacement::estimate(rig, left0, right0, left1, right1, inlierThreshold, inliers);
            }
            return py::make_tuple(H, inliers);
          },
          py::arg("rig"), py::arg("left0"), py::arg("right0"), py::arg("left1"), py::arg("right1"),
          py::arg("inlierThreshold"), "The robust estimate: (H, inliers), inliers[j] telling whether point j was used.")
      .def_static(
          "exp", [](const vpMatrix &Hhat) { return vpProjectiveDisplacement::exp(Hhat); }, py::arg("Hhat"),
          "exp(Hhat) of an element Hhat (4x4) of pse(3).")
      .def(
          "matrix", [](const vpProjectiveDisplacement &H) { return toArray(H.matrix()); }, "The normalised H (4x4).")
      .def("getRotationAngle", &vpProjectiveDisplacement::getRotationAngle)
      .def("classify", &vpProjectiveDisplacement::classify, py::arg("tolerance") = 1e-6)
      .def("log", py::overload_cast<>(&vpProjectiveDisplacement::log, py::const_),
           "The principal logarithm (4x4, in pse(3)).")
      .def(
          "act", [](const vpProjectiveDisplacement &H, const vpColVector &M) { return H.act(M); }, py::arg("M"),
          "H M (4,).")
      .def("inverse", &vpProjectiveDisplacement::inverse)
      .def("__mul__", &vpProjectiveDisplacement::operator*, py::is_operator());
}

//! The p-rotation or p-translation \e Subgroup as the Python class \e name; \e amount names its joint value.
template <typename Subgroup> void bindSubgroup(py::module_ &m, const char *name, const char *amount, const char *doc)
{
  py::class_<Subgroup>(m, name, doc)
      .def(py::init<>())
      .def(py::init<const vpMatrix &, double>(), py::arg("Hhat"), py::arg("tolerance") = 1e-6)
      .def_static("log", &Subgroup::log, py::arg("H"), py::arg("amount"))
      .def(
          "exp", [](const Subgroup &g, double q) { return g.exp(q); }, py::arg(amount))
      .def(
          "dexp", [](const Subgroup &g, double q) { return toArray(g.dexp(q)); }, py::arg(amount))
      .def(
          "generator", [](const Subgroup &g) { return toArray(g.generator()); }, "The generator Hhat (4x4).")
      .def_static(
          "project", [](const vpMatrix &Hhat) { return toArray(Subgroup::project(Subgroup(Hhat, 1e300).generator())); },
          py::arg("Hhat"), "The closest exact generator to Hhat (4x4).")
      .def_static(
          "generatorResidual",
          [](const vpMatrix &Hhat) { return Subgroup::generatorResidual(Subgroup(Hhat, 1e300).generator()); },
          py::arg("Hhat"));
}
} // namespace

void bindGeometry(py::module_ &m)
{
  bindRig(m);
  bindDisplacement(m);
  bindSubgroup<vpProjectiveRotation>(m, "ProjectiveRotation", "theta",
                                     "The subgroup exp(theta Hhat_R) of a revolute joint (vpProjectiveRotation).");
  bindSubgroup<vpProjectiveTranslation>(m, "ProjectiveTranslation", "tau",
                                        "The subgroup exp(tau Hhat_T) of a prismatic joint (vpProjectiveTranslation).");
}
} // namespace vpPython
