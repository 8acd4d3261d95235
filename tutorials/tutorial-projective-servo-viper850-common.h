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
  \file tutorial-projective-servo-viper850-common.h
  \brief What tutorial-projective-servo-viper850.cpp (a fixed rig watches markers on the arm: eye-to-hand) and
  tutorial-projective-servo-eye-in-hand.cpp (the rig on the arm's hand watches a static object) share: driving ViSP's
  vpSimulatorViper850, the acquisition of the projective model, the servo loop, the multi-seed study and its table.

  Each tutorial describes its scene in a struct World, the template parameter of the functions below, with:
  - qRefDeg, startDeg, targetDeg (std::vector<double>, deg): the zero reference of the projective model, and the
    start and target of the servo task;
  - tracked (std::vector<unsigned int>): the markers the servo tracks;
  - predictionRangeDeg (double): the model is checked at random q within +-predictionRangeDeg of the zero reference;
  - mounting (vpProjectiveRobot::vpRigMounting): where the rig is;
  - damping (double, px/rad): the control law is damped when the smallest singular value of J falls below it
    (vpServoProjective::setDamping(damping, damping));
  - nbMarkers(): the number of markers;
  - rigAt(viper, q) and markersAt(viper, q): the metric rig and the markers (base frame) when the joints are at q;
    the one carried by the arm follows ViSP's kinematic model of the Viper850, the other stays where it is.
*/

#ifndef _tutorial_projective_servo_viper850_common_h_
#define _tutorial_projective_servo_viper850_common_h_

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>
#include <iomanip>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <visp3/core/vpColVector.h>
#include <visp3/core/vpConfig.h>
#include <visp3/core/vpDisplay.h>
#include <visp3/core/vpGaussRand.h>
#include <visp3/core/vpHomogeneousMatrix.h>
#include <visp3/core/vpImage.h>
#include <visp3/core/vpImagePoint.h>
#include <visp3/core/vpIoTools.h>
#include <visp3/core/vpMath.h>
#include <visp3/core/vpMatrix.h>
#include <visp3/core/vpRotationMatrix.h>
#include <visp3/core/vpRxyzVector.h>
#include <visp3/core/vpThetaUVector.h>
#include <visp3/core/vpTime.h>
#include <visp3/core/vpUniRand.h>
#include <visp3/gui/vpDisplayX.h>
#include <visp3/robot/vpSimulatorViper850.h>

#include <visp3/projective/vpFeatureStereoPoint.h>
#include <visp3/projective/vpProjectiveRobot.h>
#include <visp3/projective/vpProjectiveStereoRig.h>
#include <visp3/projective/vpServoProjective.h>
#include <visp3/projective/vpSimulatorStereoRig.h>

#ifdef ENABLE_VISP_NAMESPACE
using namespace VISP_NAMESPACE_NAME;
#endif

#if defined(VISP_HAVE_MODULE_GUI) && defined(VISP_HAVE_PTHREAD)

//! The machinery shared by the two tutorials on ViSP's simulated Viper850.
namespace viper850
{
inline vpColVector point3(double x, double y, double z)
{
  vpColVector p(3);
  p[0] = x;
  p[1] = y;
  p[2] = z;
  return p;
}

inline vpColVector degToRad(const std::vector<double> &deg)
{
  vpColVector q(static_cast<unsigned int>(deg.size()));
  for (unsigned int i = 0; i < q.size(); ++i) {
    q[i] = vpMath::rad(deg[i]);
  }
  return q;
}

//! End-effector pose in the robot's base frame from ViSP's kinematic model of the Viper850.
inline vpHomogeneousMatrix get_fMe(const vpViper850 &viper, const vpColVector &q)
{
  vpHomogeneousMatrix fMe;
  viper.get_fMe(q, fMe);
  return fMe;
}

//! [Robot]
const double samplingTime = 0.005;        //!< s, the simulator's sampling time, here the control period too
const double maxStep = vpMath::rad(15.0); //!< largest joint motion per period (rad), for positioning and servoing alike

/*!
  vpSimulatorViper850 integrates the joint velocities in a thread of its own, in real time by default. In the
  constant sampling time mode (vpRobotWireFrameSimulator::setConstantSamplingTimeMode()), it instead makes exactly
  one step of getSamplingTime() seconds for each setVelocity() call, when its thread next polls the command (it does
  so every 4 ms). Waiting for that step before the next image makes the run independent of the machine's load. The
  thread still waits getSamplingTime() in real time after each step: ViSP's default of 10 ms would lengthen the
  study by half, and it refuses less than 4 ms (vpTime::getMinTimeForUsleepCall()).

  With \e externalView (the robot built with its display), ViSP's external camera is placed to show the arm.
*/
inline void setupRobot(vpSimulatorViper850 &robot, bool externalView)
{
  robot.setConstantSamplingTimeMode(true);
  robot.setSamplingTime(samplingTime);
  // setVelocity() would scale down any command above this joint velocity (rad/s).
  robot.setMaxRotationVelocity(maxStep / robot.getSamplingTime());
  robot.setRobotState(vpRobot::STATE_VELOCITY_CONTROL);
  if (externalView) {
    // ViSP's external camera 2 m to the right of the arm, looking at it along +y of the base frame.
    const vpHomogeneousMatrix fMc(vpTranslationVector(0.4, -2.0, 0.5), vpRotationMatrix(vpRxyzVector(-M_PI / 2, 0, 0)));
    robot.setExternalCameraPosition(fMc.inverse());
  }
}

//! Sends qdot (rad/s) and returns the joint positions read once the simulator has integrated it over one period.
inline vpColVector applyVelocity(vpSimulatorViper850 &robot, const vpColVector &qdot)
{
  vpColVector q0, q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q0);
  robot.setVelocity(vpRobot::ARTICULAR_FRAME, qdot);
  // The simulator's step is q0 + Ts qdot; if that rounds to q0 there is no change to wait for.
  bool moves = false;
  for (unsigned int i = 0; i < q0.size(); ++i) {
    moves = moves || (q0[i] + robot.getSamplingTime() * qdot[i] != q0[i]);
  }
  q = q0;
  const double t0 = vpTime::measureTimeMs();
  while (moves) {
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    bool changed = false;
    for (unsigned int i = 0; i < q.size(); ++i) {
      changed = changed || q[i] != q0[i];
    }
    if (changed) {
      break;
    }
    if (vpTime::measureTimeMs() - t0 > 10000.0) {
      throw vpException(vpException::fatalError, "the simulated Viper850 did not move within 10 s of a command");
    }
    vpTime::sleepMs(0.2);
  }
  return q;
}

/*!
  Moves the arm along a straight line in joint space to qGoal, by steps of at most maxStep, and returns the joint
  positions reached (qGoal up to rounding). vpSimulatorViper850::setPosition() would be the natural call, but in
  ViSP 3.5 its thread overwrites the positioning velocity with the last setVelocity() command (zero after a stop), so
  that a 20 deg move did not finish within minutes; velocity steps are exact and repeatable.
*/
inline vpColVector moveTo(vpSimulatorViper850 &robot, const vpColVector &qGoal)
{
  vpColVector q;
  robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
  double largest = 0.0;
  for (unsigned int i = 0; i < q.size(); ++i) {
    largest = std::max(largest, std::abs(qGoal[i] - q[i]));
  }
  for (unsigned int k = static_cast<unsigned int>(std::ceil(largest / maxStep)); k > 0; --k) {
    q = applyVelocity(robot, (qGoal - q) / (k * robot.getSamplingTime())); // what remains, spread over k steps
  }
  return q;
}
//! [Robot]

//! [Images]
/*!
  Image processing stand-in: images (Gaussian noise sigma) of the markers \e which when the joints are at \e q, seen
  by the rig where it is then (World::rigAt()) at the markers where they are then (World::markersAt()). Returns true
  if they are all in both images.
*/
template <class World>
bool imagesAt(const World &world, const vpViper850 &viper, const vpColVector &q, const std::vector<unsigned int> &which,
              double sigma, vpGaussRand &noise, std::vector<vpImagePoint> &left, std::vector<vpImagePoint> &right)
{
  const vpSimulatorStereoRig &rig = world.rigAt(viper, q);
  const std::vector<vpColVector> &fMarkers = world.markersAt(viper, q);
  left.resize(which.size());
  right.resize(which.size());
  bool inView = true;
  for (size_t k = 0; k < which.size(); ++k) {
    inView = rig.project(fMarkers[which[k]], left[k], right[k], sigma, noise) && inView;
  }
  return inView;
}

template <class World> std::vector<unsigned int> allMarkers(const World &world)
{
  std::vector<unsigned int> all(world.nbMarkers());
  for (unsigned int j = 0; j < all.size(); ++j) {
    all[j] = j;
  }
  return all;
}
//! [Images]

//! [Acquisition]
//! The paper's trial motions (deg), halved until the markers stay in view.
const std::vector<double> trialDeg = {30, 20, 30, 40, 60, 60};

/*!
  Acquisition (paper section 6): marker images at the zero reference, then joint i alone moved by +-trial_i (halved
  until every marker is in view), the amounts read back from the encoders. The fundamental matrix is estimated from
  the same images, so nothing but pixels and encoder values enters the model.
*/
template <class World>
vpProjectiveRobot acquire(const World &world, vpSimulatorViper850 &robot, double sigma, vpGaussRand &noise,
                          bool verbose)
{
  const vpColVector qRef = degToRad(world.qRefDeg);
  const unsigned int n = qRef.size();
  const std::vector<unsigned int> all = allMarkers(world);
  std::vector<vpImagePoint> left0, right0, allLeft, allRight;
  imagesAt(world, robot, moveTo(robot, qRef), all, sigma, noise, left0, right0);
  allLeft = left0;
  allRight = right0;

  struct Trial {
    unsigned int joint;
    double amount;
    std::vector<vpImagePoint> left, right;
  };
  std::vector<Trial> trials;
  for (unsigned int i = 0; i < n; ++i) {
    for (double sign : {1.0, -1.0}) {
      Trial t{i, sign * vpMath::rad(trialDeg[i]), {}, {}};
      vpColVector q;
      for (;;) {
        vpColVector qTrial = qRef;
        qTrial[i] += t.amount;
        q = moveTo(robot, qTrial); // straight from the previous pose: only where the arm stops matters
        if (imagesAt(world, robot, q, all, sigma, noise, t.left, t.right)) {
          break;
        }
        t.amount /= 2.0; // a marker left the view: a smaller trial
      }
      t.amount = q[i] - qRef[i]; // as read by the encoder
      if (verbose && std::abs(t.amount) < vpMath::rad(trialDeg[i]) - 1e-9) {
        std::cout << "    joint " << i << ": trial reduced to " << vpMath::deg(t.amount) << " deg to stay in view\n";
      }
      allLeft.insert(allLeft.end(), t.left.begin(), t.left.end());
      allRight.insert(allRight.end(), t.right.begin(), t.right.end());
      trials.push_back(t);
    }
  }

  vpProjectiveStereoRig rig;
  rig.estimate(allLeft, allRight, std::max(1.0, 4.0 * sigma));

  vpProjectiveRobot model(std::vector<vpProjectiveRobot::vpJointType>(n, vpProjectiveRobot::REVOLUTE));
  model.setRigMounting(world.mounting); // with the rig on the hand, the hand is the base of the chain
  model.setStereoRig(rig);
  model.setZeroReference(left0, right0);
  for (const Trial &t : trials) {
    model.addTrialMotion(t.joint, t.amount, t.left, t.right);
  }
  model.calibrate();
  return model;
}
//! [Acquisition]

//! [Model accuracy]
//! RMS pixel error of the markers predicted by the model, rig.project(H(q) M(0)), at random q within
//! +-world.predictionRangeDeg of the zero reference where the markers are in view (ground truth from the kinematics:
//! the arm does not move).
template <class World>
double predictionError(const World &world, const vpViper850 &viper, const vpProjectiveRobot &model, unsigned int seed)
{
  const vpColVector qRef = degToRad(world.qRefDeg);
  const std::vector<vpColVector> M0 = model.getZeroReferencePoints();
  const std::vector<unsigned int> all = allMarkers(world);
  vpUniRand uniform(seed);
  vpGaussRand noNoise(1.0, 0.0, 1);
  double sum = 0.0;
  unsigned int count = 0;
  for (unsigned int k = 0; k < 100; ++k) {
    vpColVector q(qRef.size());
    for (unsigned int i = 0; i < q.size(); ++i) {
      q[i] = vpMath::rad(uniform.uniform(-world.predictionRangeDeg, world.predictionRangeDeg));
    }
    std::vector<vpImagePoint> left, right;
    if (!imagesAt(world, viper, qRef + q, all, 0.0, noNoise, left, right)) {
      continue;
    }
    const vpMatrix H = model.getDisplacement(q);
    for (size_t j = 0; j < M0.size(); ++j) {
      vpImagePoint l, r;
      model.getStereoRig().project(H * M0[j], l, r);
      sum += vpImagePoint::sqrDistance(l, left[j]) + vpImagePoint::sqrDistance(r, right[j]);
      count += 4;
    }
  }
  return count > 0 ? std::sqrt(sum / count) : 0.0;
}
//! [Model accuracy]

//! One servo run: the trajectory and its outcome.
struct ServoRun {
  std::vector<vpColVector> q;                         // joint positions per iteration (rad)
  std::vector<std::vector<vpImagePoint>> left, right; // tracked markers per iteration
  std::vector<vpColVector> error;                     // s - s* per iteration (px)
  std::vector<vpImagePoint> leftTarget, rightTarget;
  int convergedAt = -1; // first iteration with RMS(s - s*) < 2 sigma
  bool inView = true;
  vpColVector finalJointError;  // q - q_target at the end (rad)
  double finalImageError = 0.0; // RMS(s - s*) at the end (px)
};

//! [Servo]
/*!
  The servo loop, in the shape of ViSP's tutorial-ibvs-4pts-wireframe-robot-viper.cpp: read the robot, build the
  features, compute the control law, send the joint velocities. s* is taught by showing: the arm is brought to the
  target once and the noisy images of the tracked markers are recorded. \e show, if set, is called at every
  iteration (live display).
*/
template <class World>
ServoRun servo(const World &world, vpSimulatorViper850 &robot, const vpProjectiveRobot &model, double sigma,
               vpGaussRand &noise, unsigned int iterations,
               const std::function<void(const ServoRun &)> &show = std::function<void(const ServoRun &)>())
{
  ServoRun run;
  const vpColVector qRef = degToRad(world.qRefDeg), qTarget = degToRad(world.targetDeg);
  const unsigned int nbPoints = static_cast<unsigned int>(world.tracked.size());

  imagesAt(world, robot, moveTo(robot, qTarget), world.tracked, sigma, noise, run.leftTarget, run.rightTarget);
  std::vector<vpFeatureStereoPoint> s(nbPoints), s_star(nbPoints);
  vpServoProjective task;
  task.setRobot(model);
  // qdot is a velocity: lambda = 0.5 per control period, joint steps limited to maxStep per period, and damping when
  // the smallest singular value of J falls below world.damping (px/rad).
  task.setLambda(0.5 / robot.getSamplingTime());
  task.setMaxJointVelocity(maxStep / robot.getSamplingTime());
  task.setDamping(world.damping, world.damping);
  for (unsigned int k = 0; k < nbPoints; ++k) {
    s_star[k].buildFrom(run.leftTarget[k], run.rightTarget[k]);
    task.addFeature(s[k], s_star[k]);
  }

  vpColVector q = moveTo(robot, degToRad(world.startDeg));
  for (unsigned int it = 0; it <= iterations; ++it) {
    robot.getPosition(vpRobot::ARTICULAR_FRAME, q);
    std::vector<vpImagePoint> left, right;
    run.inView = imagesAt(world, robot, q, world.tracked, sigma, noise, left, right);
    if (!run.inView) {
      break;
    }
    for (unsigned int k = 0; k < nbPoints; ++k) {
      s[k].buildFrom(left[k], right[k]);
    }
    const vpColVector qdot = task.computeControlLaw(q - qRef); // the model's joints are relative to the reference
    const vpColVector e = task.getError();
    run.q.push_back(q);
    run.left.push_back(left);
    run.right.push_back(right);
    run.error.push_back(e);
    run.finalImageError = std::sqrt(e.sumSquare() / e.size());
    if (run.convergedAt < 0 && run.finalImageError < std::max(2.0 * sigma, 1e-6)) {
      run.convergedAt = static_cast<int>(it);
    }
    if (show) {
      show(run);
    }
    if (it < iterations) {
      applyVelocity(robot, qdot); // ViSP's tutorial sends it and waits one period with vpTime::wait()
    }
  }
  run.finalJointError = q - qTarget;
  return run;
}
//! [Servo]

//! [Noise floor]
//! sqrt(diag(sigma^2 (J^T J)^-1)), J the true stacked image Jacobian of the tracked markers at the target.
template <class World> vpColVector noiseFloor(const World &world, const vpViper850 &viper, double sigma)
{
  const vpColVector qTarget = degToRad(world.targetDeg);
  const unsigned int n = qTarget.size();
  vpMatrix J(4 * static_cast<unsigned int>(world.tracked.size()), n);
  vpGaussRand noNoise(1.0, 0.0, 1);
  const double h = 1e-6;
  for (unsigned int i = 0; i < n; ++i) {
    vpColVector qp = qTarget, qm = qTarget;
    qp[i] += h;
    qm[i] -= h;
    std::vector<vpImagePoint> lp, rp, lm, rm;
    imagesAt(world, viper, qp, world.tracked, 0.0, noNoise, lp, rp);
    imagesAt(world, viper, qm, world.tracked, 0.0, noNoise, lm, rm);
    for (unsigned int k = 0; k < world.tracked.size(); ++k) {
      J[4 * k][i] = (lp[k].get_u() - lm[k].get_u()) / (2 * h);
      J[4 * k + 1][i] = (lp[k].get_v() - lm[k].get_v()) / (2 * h);
      J[4 * k + 2][i] = (rp[k].get_u() - rm[k].get_u()) / (2 * h);
      J[4 * k + 3][i] = (rp[k].get_v() - rm[k].get_v()) / (2 * h);
    }
  }
  const vpMatrix covariance = (J.t() * J).inverseByLU() * (sigma * sigma);
  vpColVector floor(n);
  for (unsigned int i = 0; i < n; ++i) {
    floor[i] = std::sqrt(covariance[i][i]);
  }
  return floor;
}
//! [Noise floor]

//! Statistics of one noise level over all seeds.
struct Study {
  double sigma = 0.0;
  std::vector<int> iterations;
  std::vector<double> imageError, prediction, calibrationResidual;
  vpColVector meanAbsJointError; // rad
  vpColVector floor;             // rad
  unsigned int seeds = 0, lostView = 0, notConverged = 0;
  std::vector<std::string> failures;
};

//! [Monte Carlo]
template <class World>
Study study(const World &world, vpSimulatorViper850 &robot, double sigma, unsigned int seeds, unsigned int iterations)
{
  Study st;
  st.sigma = sigma;
  st.seeds = seeds;
  st.meanAbsJointError.resize(static_cast<unsigned int>(world.qRefDeg.size()), true);
  st.floor = noiseFloor(world, robot, sigma);
  for (unsigned int seed = 1; seed <= seeds; ++seed) {
    vpGaussRand noise(1.0, 0.0, static_cast<long>(seed));
    const vpProjectiveRobot model = acquire(world, robot, sigma, noise, false);
    st.prediction.push_back(predictionError(world, robot, model, seed));
    st.calibrationResidual.push_back(model.getCalibrationResidual());
    const ServoRun run = servo(world, robot, model, sigma, noise, iterations);
    if (!run.inView) {
      st.failures.push_back("seed " + std::to_string(seed) + ": a tracked marker left an image");
      ++st.lostView;
    } else if (run.convergedAt < 0) {
      std::ostringstream os;
      os << "seed " << seed << ": not converged, image error " << run.finalImageError << " px RMS after " << iterations
         << " iterations";
      st.failures.push_back(os.str());
      ++st.notConverged;
    } else {
      st.iterations.push_back(run.convergedAt);
      st.imageError.push_back(run.finalImageError);
      for (unsigned int i = 0; i < st.meanAbsJointError.size(); ++i) {
        st.meanAbsJointError[i] += std::abs(run.finalJointError[i]);
      }
    }
  }
  if (!st.iterations.empty()) {
    st.meanAbsJointError /= static_cast<double>(st.iterations.size());
  }
  return st;
}
//! [Monte Carlo]

//! True if the detailed run and every run of the studies converged: the tutorials' exit code.
inline bool allConverged(const ServoRun &run, const std::vector<Study> &studies)
{
  bool converged = run.inView && run.convergedAt >= 0;
  for (const Study &st : studies) {
    converged = converged && st.iterations.size() == st.seeds;
  }
  return converged;
}

inline double mean(const std::vector<double> &x)
{
  double m = 0.0;
  for (double v : x) {
    m += v;
  }
  return x.empty() ? 0.0 : m / static_cast<double>(x.size());
}

inline int median(std::vector<int> x)
{
  std::sort(x.begin(), x.end());
  return x.empty() ? 0 : x[x.size() / 2];
}

template <typename T> T maxOf(const std::vector<T> &x)
{
  return x.empty() ? T(0) : *std::max_element(x.begin(), x.end());
}

//! [Table]
template <class World> void printTable(const World &world, const std::vector<Study> &studies)
{
  std::cout << "\nFinal joint error |q - q*| (deg), mean over the converged runs, beside the noise floor "
               "sqrt(diag(sigma^2 (J^T J)^-1)):\n";
  std::cout << std::fixed << std::setprecision(3);
  for (const Study &st : studies) {
    std::cout << "\n  sigma = " << st.sigma << " px: converged " << st.iterations.size() << "/" << st.seeds
              << " (lost view " << st.lostView << ", not converged " << st.notConverged
              << "), iterations to converge: median " << median(st.iterations) << ", max " << maxOf(st.iterations)
              << "; final image error RMS " << mean(st.imageError) << " px\n";
    std::cout << "  acquired model: bundle-adjustment residual " << mean(st.calibrationResidual)
              << " px RMS, marker prediction error at random q within +-" << std::setprecision(0)
              << world.predictionRangeDeg << std::setprecision(3) << " deg: mean " << mean(st.prediction) << " px, max "
              << maxOf(st.prediction) << " px RMS\n";
    std::cout << "    joint       ours      floor  ours/floor\n";
    for (unsigned int i = 0; i < st.floor.size(); ++i) {
      const double ours = vpMath::deg(st.meanAbsJointError[i]), floor = vpMath::deg(st.floor[i]);
      std::cout << std::setw(9) << i << std::setw(11) << ours << std::setw(11) << floor << std::setw(12) << ours / floor
                << "\n";
    }
    for (const std::string &failure : st.failures) {
      std::cout << "    " << failure << "\n";
    }
  }
}
//! [Table]

//! [Live display]
/*!
  The two camera images of the servo run, if there is a display: tracked markers (green trajectories) and their
  targets (red crosses). Without a display (or without X11), it does nothing.
*/
class LiveView
{
public:
  LiveView(const vpSimulatorStereoRig &rig, bool display)
  {
#if defined(VISP_HAVE_X11)
    if (display) {
      m_left.resize(rig.getHeight(), rig.getWidth(), 255);
      m_right.resize(rig.getHeight(), rig.getWidth(), 255);
      m_displayLeft.reset(new vpDisplayX(m_left, 660, 0, "Left camera"));
      m_displayRight.reset(new vpDisplayX(m_right, 660, static_cast<int>(rig.getHeight()) + 40, "Right camera"));
    }
#else
    (void)rig;
    (void)display;
#endif
  }

  //! True if the windows are open.
  bool isOpen() const
  {
#if defined(VISP_HAVE_X11)
    return m_displayLeft != nullptr;
#else
    return false;
#endif
  }

  //! The function for servo() to call at every iteration: empty if the windows are not open.
  std::function<void(const ServoRun &)> callback()
  {
    if (!isOpen()) {
      return std::function<void(const ServoRun &)>();
    }
    return [this](const ServoRun &run) { show(run); };
  }

  //! Draws the run so far.
  void show(const ServoRun &run)
  {
    vpDisplay::display(m_left);
    vpDisplay::display(m_right);
    for (size_t k = 0; k < run.leftTarget.size(); ++k) {
      vpDisplay::displayCross(m_left, run.leftTarget[k], 12, vpColor::red, 2);
      vpDisplay::displayCross(m_right, run.rightTarget[k], 12, vpColor::red, 2);
      for (size_t it = 0; it < run.left.size(); ++it) {
        vpDisplay::displayPoint(m_left, run.left[it][k], vpColor::green, 2);
        vpDisplay::displayPoint(m_right, run.right[it][k], vpColor::green, 2);
      }
    }
    std::ostringstream os;
    os << "iteration " << run.q.size() - 1 << ", image error " << std::fixed << std::setprecision(2)
       << run.finalImageError << " px RMS";
    vpDisplay::displayText(m_left, 20, 20, os.str(), vpColor::blue);
    vpDisplay::flush(m_left);
    vpDisplay::flush(m_right);
  }

  //! If the windows are open, waits for a click in the left one.
  void waitForClick()
  {
    if (isOpen()) {
      std::cout << "Click in the left image to quit" << std::endl;
      vpDisplay::getClick(m_left);
    }
  }

private:
  vpImage<unsigned char> m_left, m_right;
#if defined(VISP_HAVE_X11)
  std::unique_ptr<vpDisplayX> m_displayLeft, m_displayRight;
#endif
};
//! [Live display]

//! The command line options of both tutorials.
struct Options {
  unsigned int seeds = 20; //!< noise seeds of the study, at each noise level
  std::string modelFile;   //!< where to save the acquired model, or to load it from if it exists
  bool display = false;    //!< external view of the arm and camera images
};

/*!
  Reads the command line: [--seeds N (default 20)] [--model FILE] [--no-display] [--help]. The display is on if the
  DISPLAY environment variable is set (and ViSP has X11), unless --no-display. Returns false if the program must stop
  at once with \e exitCode: after --help (EXIT_SUCCESS) or anything else (EXIT_FAILURE), the usage printed.
*/
inline bool parseOptions(int argc, char **argv, Options &options, int &exitCode)
{
  options.display = std::getenv("DISPLAY") != nullptr;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--seeds" && i + 1 < argc) {
      options.seeds = static_cast<unsigned int>(std::max(1, std::atoi(argv[++i])));
    } else if (arg == "--model" && i + 1 < argc) {
      options.modelFile = argv[++i];
    } else if (arg == "--no-display") {
      options.display = false;
    } else {
      std::cout << "Usage: " << argv[0] << " [--seeds N (default 20)] [--model FILE] [--no-display] [--help]\n";
      exitCode = arg == "--help" ? EXIT_SUCCESS : EXIT_FAILURE;
      return false;
    }
  }
#if !defined(VISP_HAVE_X11)
  options.display = false;
#endif
  return true;
}

/*!
  Prints the task: \e motion, the pose of the servoed frame (named \e what) at the target relative to the start, and
  the joint distance.
*/
inline void printTask(const std::string &what, const vpHomogeneousMatrix &motion, const vpColVector &qStart,
                      const vpColVector &qTarget)
{
  std::cout << "Task: " << what << " translates by " << 100.0 * motion.getTranslationVector().frobeniusNorm()
            << " cm and rotates by " << vpMath::deg(vpThetaUVector(motion.getRotationMatrix()).getTheta())
            << " deg; joint distance (deg) " << ((qTarget - qStart) * (180.0 / M_PI)).t() << "\n";
}

/*!
  The model of the detailed run: loaded from \e modelFile if it exists, otherwise acquired (and saved to \e modelFile
  if given). Prints how well it fits the acquisition images and predicts the markers.
*/
template <class World>
vpProjectiveRobot acquireOrLoad(const World &world, vpSimulatorViper850 &robot, double sigma, vpGaussRand &noise,
                                const std::string &modelFile)
{
  vpProjectiveRobot model;
  if (!modelFile.empty() && vpIoTools::checkFilename(modelFile)) {
    model.loadModel(modelFile); // acquired by an earlier run: no trial motion now
    std::cout << "    model loaded from " << modelFile << "\n";
  } else {
    model = acquire(world, robot, sigma, noise, true);
    std::cout << "    epipolar geometry from the " << model.getStereoRig().getInliers().size()
              << " marker matches of the acquisition images: RMS residual "
              << model.getStereoRig().getEstimationResidual() << " px\n";
    if (!modelFile.empty()) {
      model.saveModel(modelFile);
      std::cout << "    model saved to " << modelFile << "\n";
    }
  }
  std::cout << "    algebraic generators: RMS error on the acquisition images " << model.getAlgebraicResidual()
            << " px; after the bundle adjustment " << model.getCalibrationResidual() << " px\n";
  std::cout << "    marker prediction at random q within +-" << world.predictionRangeDeg
            << " deg: " << predictionError(world, robot, model, 1) << " px RMS\n";
  return model;
}

/*!
  Prints the outcome of the detailed run: convergence, final joint error, \e poseError (the final pose error of the
  servoed frame, named \e what) and the image error at every iteration.
*/
inline void printDetailedRun(const ServoRun &run, const std::string &what, const vpHomogeneousMatrix &poseError)
{
  std::cout << "Seed 1 servo: " << (run.inView ? "markers kept in view" : "markers LOST") << ", converged after "
            << run.convergedAt << " iterations, final image error " << run.finalImageError << " px RMS\n";
  std::cout << "    final joint error (deg) " << (run.finalJointError * (180.0 / M_PI)).t() << "\n";
  std::cout << "    final " << what << " pose error: " << 1000 * poseError.getTranslationVector().frobeniusNorm()
            << " mm, " << vpMath::deg(vpThetaUVector(poseError.getRotationMatrix()).getTheta()) << " deg\n";
  std::cout << "    iteration  image error RMS (px)\n";
  for (size_t it = 0; it < run.error.size(); ++it) {
    std::cout << std::setw(13) << it << std::setw(22) << std::sqrt(run.error[it].sumSquare() / run.error[it].size())
              << "\n";
  }
}
} // namespace viper850

#endif
#endif
