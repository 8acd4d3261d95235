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

#include "paper-record.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <sstream>

#include <nlohmann/json.hpp>

#include <visp3/core/vpException.h>
#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveSession.h>
#include <visp3/projective/vpServoProjective.h>

#include "paper-experiment.h"

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

namespace app
{
namespace
{
const char *const kSettingsFile = "/projective-paper.json";

std::vector<vpProjectiveJoint::vpJointType> jointTypes(const PaperWorld &world)
{
  std::vector<vpProjectiveJoint::vpJointType> types;
  for (unsigned int i = 0; i < world.arm.getNumberOfJoints(); ++i) {
    types.push_back(world.arm.getJointType(i) == vpProjectiveJoint::PRISMATIC ? vpProjectiveJoint::PRISMATIC
                                                                              : vpProjectiveJoint::REVOLUTE);
  }
  return types;
}

[[noreturn]] void notARecording(const std::string &folder, const std::string &why)
{
  throw vpException(vpException::fatalError, "'" + folder + "' is not a recording of projective-paper (" + why +
                                                 "); record one with projective-paper --record DIR");
}
} // namespace

PaperRecorder::PaperRecorder(const std::string &folder, const PaperWorld &world, const PaperRunSettings &settings)
    : m_world(world), m_writer(folder, jointTypes(world)), m_renderer(world.rig, 7)
{
  nlohmann::json file;
  file["sigma"] = settings.sigma;
  file["max_excursion_deg"] = settings.maxExcursionDeg;
  file["iterations"] = settings.iterations;
  std::ofstream out((folder + kSettingsFile).c_str());
  out << file.dump(1) << "\n";
  if (!out) {
    throw vpException(vpException::ioError, "cannot write '" + folder + kSettingsFile + "'");
  }
}

void PaperRecorder::add(vpProjectiveSession::vpFrameRole role, const vpColVector &q,
                        const std::vector<unsigned int> &indices, const std::vector<vpImagePoint> &left,
                        const std::vector<vpImagePoint> &right)
{
  vpImage<unsigned char> Il, Ir;
  m_renderer.render(m_world.arm.getMarkers(q), Il, Ir); // its own noise stream: the run's is untouched
  const std::vector<int> ids(indices.begin(), indices.end());
  m_writer.addFrame(role, q, static_cast<double>(getNumberOfFrames()), Il, Ir, ids, left, right);
}

void PaperRecorder::close()
{
  m_writer.close();
}

PaperReplay replay(const PaperWorld &world, const std::string &folder)
{
  PaperReplay out;
  const vpProjectiveSession session = vpProjectiveSession::read(folder, false);
  {
    std::ifstream in((folder + kSettingsFile).c_str());
    if (!in) {
      notARecording(folder, "no projective-paper.json");
    }
    std::stringstream text;
    text << in.rdbuf();
    const nlohmann::json file = nlohmann::json::parse(text.str(), nullptr, false);
    if (!file.is_object() || !file.contains("sigma") || !file.contains("max_excursion_deg") ||
        !file.contains("iterations")) {
      notARecording(folder, "projective-paper.json lacks sigma, max_excursion_deg or iterations");
    }
    out.settings.sigma = file["sigma"].get<double>();
    out.settings.maxExcursionDeg = file["max_excursion_deg"].get<double>();
    out.settings.iterations = file["iterations"].get<unsigned int>();
  }
  const unsigned int n = session.getNumberOfJoints();
  if (n != world.arm.getNumberOfJoints()) {
    notARecording(folder, "its arm has " + std::to_string(n) + " joints");
  }
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    if (session.getFrame(k).markerIds.empty()) {
      notARecording(folder, "frame " + std::to_string(k) + " has no recorded markers");
    }
  }

  // The acquisition: the zero frame and the trials in their order, as acquireByTrials() passed them on.
  const vpProjectiveSession::vpFrame &zero = session.getFrame(session.getZeroFrame());
  std::vector<TrialMotion> trials;
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    const int joint = session.getTrialJoint(k);
    if (joint >= 0) {
      const vpProjectiveSession::vpFrame &f = session.getFrame(k);
      const unsigned int i = static_cast<unsigned int>(joint);
      trials.push_back(TrialMotion{i, f.q[i] - zero.q[i], f.markerLeft, f.markerRight});
    }
  }
  if (trials.empty()) {
    notARecording(folder, "no trial frame");
  }
  out.robot =
      calibrateFromTrials(n, zero.markerLeft, zero.markerRight, trials, acquisitionThreshold(out.settings.sigma));

  // The servo run: s* from the target frames, then the law on each recorded servo frame.
  std::vector<unsigned int> servoFrames;
  std::vector<std::vector<vpImagePoint>> leftFrames, rightFrames;
  for (unsigned int k = 0; k < session.getNumberOfFrames(); ++k) {
    const vpProjectiveSession::vpFrame &f = session.getFrame(k);
    if (f.role == vpProjectiveSession::SERVO) {
      servoFrames.push_back(k);
    } else if (f.role == vpProjectiveSession::TARGET) {
      leftFrames.resize(f.markerLeft.size());
      rightFrames.resize(f.markerRight.size());
      for (size_t j = 0; j < f.markerLeft.size() && j < leftFrames.size(); ++j) {
        leftFrames[j].push_back(f.markerLeft[j]);
        rightFrames[j].push_back(f.markerRight[j]);
      }
    }
  }
  const size_t nbPoints = leftFrames.size();
  if (servoFrames.empty() || nbPoints == 0) {
    notARecording(folder, "no target or servo frame");
  }
  std::vector<vpFeatureStereoPoint> s(nbPoints), s_star(nbPoints);
  vpServoProjective task;
  configureTask(task, world, out.robot, out.settings.maxExcursionDeg, false);
  for (size_t k = 0; k < nbPoints; ++k) {
    s_star[k].buildFrom(leftFrames[k], rightFrames[k]); // the mean of the target frames
    out.run.leftTarget.push_back(s_star[k].getLeft());
    out.run.rightTarget.push_back(s_star[k].getRight());
    task.addFeature(s[k], s_star[k]);
  }
  ServoRun &run = out.run;
  for (size_t it = 0; it < servoFrames.size(); ++it) {
    const vpProjectiveSession::vpFrame &f = session.getFrame(servoFrames[it]);
    if (f.markerLeft.size() != nbPoints) {
      notARecording(folder, "servo frame " + std::to_string(servoFrames[it]) + " does not have the target's markers");
    }
    for (size_t k = 0; k < nbPoints; ++k) {
      s[k].buildFrom(f.markerLeft[k], f.markerRight[k]);
    }
    const vpColVector qdot = task.computeControlLaw(f.q);
    if (it == 0) {
      run.plan = task.getPathPlanner().getDescription();
    }
    vpColVector e;
    for (size_t k = 0; k < nbPoints; ++k) {
      e.stack(s[k].error(s_star[k]));
    }
    run.record(static_cast<unsigned int>(it), f.q, f.markerLeft, f.markerRight, e,
               std::max(2.0 * out.settings.sigma, 1e-6));
    if (it + 1 < servoFrames.size()) { // the next frame is where this law's step took the arm
      const vpColVector step = world.arm.integrate(f.q, qdot, 1.0) - session.getFrame(servoFrames[it + 1]).q;
      out.maxStepMismatch = std::max(out.maxStepMismatch, step.getMaxValue());
      out.maxStepMismatch = std::max(out.maxStepMismatch, -step.getMinValue());
    }
  }
  run.inView = servoFrames.size() == out.settings.iterations + 1;
  run.finalJointError = run.q.back() - degToRad(world.targetDeg);
  return out;
}
} // namespace app
