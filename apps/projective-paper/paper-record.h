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
  \file paper-record.h
  \brief The main job's recording (projective-paper --record DIR) and its offline replay (--replay DIR).

  What is recorded: the detailed run of seed 1, whose trajectories are the figures (Fig. 2, 4, 5 and their CSV), as a
  session (vpProjectiveSession):
  - the acquisition: the zero frame (q = 0) and every trial the acquisition used (joint i alone, both ways, as
    reduced to stay in view), with the 7 markers;
  - the target frames that taught s* (role "target", the 3 tracked markers);
  - every servo iteration (role "servo": q and the 3 tracked markers).
  The experiment's markers are projected points with Gaussian noise, not image features: each frame carries the
  pixels the program used in its "recorded_markers" entry (identifiers = marker indices, bit-exact doubles), and its
  images are those points rendered as lit balls by vpSimulatorMarkerRenderer (seeded apart from the experiment's
  noise, so recording changes nothing), for viewing or for a dot tracker. A file projective-paper.json beside
  session.json keeps the run's settings (noise, planning excursion, iterations).

  Offline:
  - projective-paper --replay DIR --output OUT calibrates the model from the recorded acquisition (the same function
    on the same pixels: the same model, bit for bit), then runs the servo law on the recorded frames: at each frame
    the control law of the replayed task gives the joint velocity, and the next recorded frame's q must be its
    integration (checked); the figures are written from the replay and equal the recorded run's.
  - visp-projective calibrate DIR --recorded-markers --output MODEL.json and visp-projective check MODEL.json DIR
    --recorded-markers calibrate and check the session with the tool's own pipeline.
*/

#ifndef _app_paper_record_h_
#define _app_paper_record_h_

#include <memory>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpImagePoint.h>

#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveSessionWriter.h>
#include <visp3/projective/vpSimulatorMarkerRenderer.h>

#include "paper-world.h"
#include "servo-report.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
//! The settings of a recorded run, saved as projective-paper.json in the session folder.
struct PaperRunSettings {
  double sigma = 0.5;           //!< image noise of the run (px)
  double maxExcursionDeg = 20;  //!< the planner's largest joint excursion (deg)
  unsigned int iterations = 40; //!< servo iterations
};

//! Records the frames of a run as a session (see the file's documentation).
class PaperRecorder
{
public:
  //! A recording in the new folder \e folder of \e world's run with \e settings.
  PaperRecorder(const std::string &folder, const PaperWorld &world, const PaperRunSettings &settings);
  /*!
    Records a frame of \e role at joints \e q: the markers \e indices of the arm (their identifiers) measured at
    \e left and \e right (one per index), and the images of all the arm's markers at \e q.
  */
  void add(vpProjectiveSession::vpFrameRole role, const vpColVector &q, const std::vector<unsigned int> &indices,
           const std::vector<vpImagePoint> &left, const std::vector<vpImagePoint> &right);
  //! Writes session.json with every frame.
  void close();
  //! Number of frames recorded.
  unsigned int getNumberOfFrames() const { return m_writer.getSession().getNumberOfFrames(); }

private:
  const PaperWorld &m_world;
  vpProjectiveSessionWriter m_writer;
  vpSimulatorMarkerRenderer m_renderer;
};

//! What a replay found.
struct PaperReplay {
  vpProjectiveRobot robot;    //!< the model calibrated from the recorded acquisition
  ServoRun run;               //!< the servo run replayed on the recorded frames
  double maxStepMismatch = 0; //!< largest |q_{k+1} - integrate(q_k, qdot_k)| over the frames (rad)
  PaperRunSettings settings;  //!< the recorded run's settings
};

/*!
  Replays the recording in \e folder (see the file's documentation).
  \exception vpException if the folder is not a recording of projective-paper (a frame without recorded markers, no
  trial, no target or servo frame, no projective-paper.json).
*/
PaperReplay replay(const PaperWorld &world, const std::string &folder);
} // namespace app

#endif
