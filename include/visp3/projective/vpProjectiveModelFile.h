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
  \file vpProjectiveModelFile.h
  \brief The model file: a projective arm model saved as versioned, checksummed JSON.
*/

#ifndef _vpProjectiveModelFile_h_
#define _vpProjectiveModelFile_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <string>
#include <vector>

#include <visp3/projective/vpProjectiveArmAcquisition.h>
#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpProjectiveModelCheck.h>
#include <visp3/projective/vpProjectiveCellFingerprint.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectiveModelFile
  \ingroup group_projective
  \brief Reads and writes a vpProjectiveArmModel as a JSON file (nlohmann-json), so that an arm is acquired once and
  servoed on later runs.

  The file is one JSON object:
  \code{.json}
  {
    "format": "visp_projective_robot_model",
    "version": 3,
    "model": {
      "mounting": "eye-to-hand",
      "joints": ["revolute", "revolute", "prismatic"],
      "zero_reference_joints": [0.0, 0.0, 0.0],
      "rig": { "camera_pair": "canonical", "fundamental_matrix": [[...], [...], [...]] },
      "G": [[...], [...], [...], [...]],
      "twists": [ { "axis": [x, y, z], "point": [x, y, z] }, ... ],
      "markers": [ [x, y, z, w], ... ],
      "calibration_residual": 0.41,
      "algebraic_residual": 20.9
    },
    "checksum": "fnv1a64:0123456789abcdef"
  }
  \endcode
  A rig re-registered by vpProjectiveRobot::updateRig() is a general camera pair: its "rig" entry is then
  <tt>{ "camera_pair": "general", "fundamental_matrix": ..., "left_projection": [3 rows of 4], "right_projection":
  [3 rows of 4] }</tt>, the projections being what the model uses. Version 2 files (no camera_pair: always the
  canonical pair of F) are still read.

  Matrices are arrays of rows, values in the units of vpProjectiveArmModel (G maps the projective frame to the
  metric one; axes and points in that metric frame; joint values in radians or encoder length units; residuals in
  pixels). The checksum is FNV-1a (64 bits) of the "model" member written compactly (<tt>dump()</tt> of
  nlohmann-json): a value edited or damaged on disk is detected on load. Doubles are written with 17 significant
  digits, so that a model read back is bit-identical to the one saved.

  Every failure to read is a vpProjectiveException (fileError) whose message names the file and what is wrong: missing
  or unreadable, not JSON or truncated, another format or version, a checksum that does not match, a missing, mistyped
  or non-finite entry, inconsistent sizes, or a model that vpProjectiveArmModel rejects.

  A model saved with what its calibration checked (vpProjectiveRobot::saveModel() after calibrate(), or save() given a
  vpProjectiveModelCheck) also carries, inside "model", <tt>"model_check": { "joint_types": "identified" or
  "declared", "image_noise": 0.31, "residual_limit": 0.93, "joints": [ { "turn": 0.52, "residual_revolute": 0.30,
  "residual_prismatic": 14.2 }, ... ] }</tt>: how the joint types were found, the image noise (pixels) and the limit
  of the check, and per joint the rotation angle (rad) of its trials' displacements and the RMS residual (pixels) of
  its trials with each type (null where not fitted). The entry is optional, as "marker_ids".

  A model calibrated from a recorded session (vpProjectiveSessionCalibration) also carries, inside "model" (hence
  under the checksum), <tt>"marker_ids": [ ... ]</tt>: the identifier of each marker (e.g. 4 * AprilTag id + corner),
  so that the markers are found again in new images by their identifiers. The entry is optional: a file without it
  reads as before, and a reader of this version that does not ask for it ignores it.

  Likewise optional, <tt>"frames": [ { "q": [...], "s": [ [u, v, u', v'] or null, ... ] }, ... ]</tt>: the stereo
  images the model's metric self-calibration adjusts over (vpProjectiveArmAcquisition::getFrames(): the encoder
  readings q, and per marker its pixels in both images, null where the frame does not show it), so that the
  self-calibration and its uncertainty (vpProjectiveSelfCalibration) can be computed again from the file.

  Such a model also carries, inside "model", the fingerprint of its cell (vpProjectiveCellFingerprint), optional as
  "marker_ids" (a file without it reads as an empty fingerprint):
  \code{.json}
  "cell": { "image_size": [640, 480], "camera_layout": "left-right", "right_camera": "right",
            "baseline_direction": [0.995, 0.0, 0.0997],
            "cameras": { "left": { "device": "/dev/video0", "name": "HD Webcam C920", "bus": "usb-0000:00:14.0-1",
                                   "serial": "8A3F1C2E" },
                         "right": { "device": "/dev/video2", ... } } }
  \endcode
  \c image_size is the left camera's (pixels; left out when not known), \c right_camera where the metric
  self-calibration put the right camera ("right", "left", "above-below" or "unknown"), \c baseline_direction its unit
  direction in the left camera's frame, \c cameras the identities of the cameras (left out when the session did not
  record them; an identity's empty fields are left out).
*/
class VISP_EXPORT vpProjectiveModelFile
{
public:
  //! The format version this build writes and reads.
  static constexpr int version = 3;

  /*!
    Writes \e model and its calibration residuals (pixels; see vpProjectiveArmAcquisition) to \e filename.
    \exception vpProjectiveException (fileError) if the file cannot be written.
  */
  static void save(const std::string &filename, const vpProjectiveArmModel &model, double calibrationResidual,
                   double algebraicResidual);
  /*!
    The same with the markers' identifiers \e markerIds (one per marker of \e model, distinct; empty: none written),
    the self-calibration's \e frames (each with n readings and one image per marker; empty: none written) and what the
    model's calibration checked (\e check, if not null and checked: the "model_check" entry), and the fingerprint of
    its cell (\e cell, if not null: the "cell" entry).
    \exception vpProjectiveException (dimensionError, invalidValueError) if the identifiers or the frames do not
    match the model; (fileError) if the file cannot be written.
  */
  static void save(const std::string &filename, const vpProjectiveArmModel &model, double calibrationResidual,
                   double algebraicResidual, const std::vector<int> &markerIds,
                   const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames =
                       std::vector<vpProjectiveArmAcquisition::vpFrame>(),
                   const vpProjectiveModelCheck *check = nullptr, const vpProjectiveCellFingerprint *cell = nullptr);
  /*!
    Reads a model written by save(); \e calibrationResidual and \e algebraicResidual, if not null, receive the
    residuals it was saved with, \e markerIds the markers' identifiers (empty if the file has none), \e frames the
    self-calibration's frames (empty if the file has none), \e cell the fingerprint of its cell (empty if the file has
    none).
    \exception vpProjectiveException (fileError) as described in the class documentation.
  */
  static vpProjectiveArmModel load(const std::string &filename, double *calibrationResidual = nullptr,
                                   double *algebraicResidual = nullptr, std::vector<int> *markerIds = nullptr,
                                   std::vector<vpProjectiveArmAcquisition::vpFrame> *frames = nullptr,
                                   vpProjectiveCellFingerprint *cell = nullptr);

  /*!
    The JSON text that save() writes; with \e cell (not null), the fingerprint of the model's cell in its "cell" entry.
  */
  static std::string toString(const vpProjectiveArmModel &model, double calibrationResidual, double algebraicResidual,
                              const std::vector<int> &markerIds = std::vector<int>(),
                              const std::vector<vpProjectiveArmAcquisition::vpFrame> &frames =
                                  std::vector<vpProjectiveArmAcquisition::vpFrame>(),
                              const vpProjectiveModelCheck *check = nullptr,
                              const vpProjectiveCellFingerprint *cell = nullptr);
  /*!
    The model of a JSON text as written by save(); \e name (a file name) is quoted in the error messages. \e markerIds,
    \e frames and \e cell, if not null, receive the markers' identifiers, the frames and the fingerprint of its cell
    (empty if the file has none).
    \exception vpProjectiveException (fileError) as load().
  */
  static vpProjectiveArmModel fromString(const std::string &text, const std::string &name,
                                         double *calibrationResidual = nullptr, double *algebraicResidual = nullptr,
                                         std::vector<int> *markerIds = nullptr,
                                         std::vector<vpProjectiveArmAcquisition::vpFrame> *frames = nullptr,
                                         vpProjectiveCellFingerprint *cell = nullptr);
};

END_VISP_NAMESPACE

#endif
