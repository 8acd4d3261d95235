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
  \file vpProjectivePathPlanner.h
  \brief Global servoing: the joint target of a servo task found by the projective model, and a path to it that keeps
  the features in view and the joints within their limits.
*/

#ifndef _vpProjectivePathPlanner_h_
#define _vpProjectivePathPlanner_h_

#include <visp3/projective/vpProjectiveConfig.h>

#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <visp3/core/vpMath.h>

#include <Eigen/Core>

#include <visp3/projective/vpProjectiveArmModel.h>
#include <visp3/projective/vpServoControlLaw.h>

BEGIN_VISP_NAMESPACE

/*!
  \class vpProjectivePathPlanner
  \ingroup group_projective
  \brief Plans a servo task with the acquired model: the model is global (Ruf & Horaud: the Jacobian is "an analytic
  expression in q, sound over the robot's entire configuration space"), so the task's target can be solved for and a
  path to it chosen before moving, where the local law (47) alone meets local minima, joint limits and lost features.

  The task: points \f$ M_k(0) \f$ of the moving end (4x1 projective points at the zero reference, e.g. a servo
  task's features triangulated at the current joints \f$ q \f$ and carried there by \f$ H(q)^{-1} \f$, which needs no
  marker identity) and their desired pixels \f$ s^*_k = (u, v, u', v') \f$. plan()
  -# solves the inverse kinematics of \f$ s^* \f$ from many starts (vpProjectiveInverseKinematics::solveAll():
     \f$ q \f$, the end of the inverse kinematics tracked along straight image lines from the features at \f$ q \f$
     to \f$ s^* \f$, the branch that the motion meets first, then random configurations within the limits), each
     minimum refined together with the points by their two views (the points' images at \f$ q \f$, where they were
     triangulated, and \f$ s^* \f$ at the target: vpProjectiveInverseKinematics::solveWithPoints()): every branch
     it finds whose residual is within 1.5 times the best one (the branches of one gripper pose tie; another pose
     that three points nearly explain does not), none if the best leaves more than setMaxResidual() pixels;
  -# chooses the target \f$ q^* \f$: among the branches, the representative (revolute joints modulo a turn) nearest
     to \f$ q \f$ in joint space that is inside the joint limits with the features in view (inside the image window,
     and in front of both cameras: their depths keep the signs they have at \f$ q \f$, where they are seen), out of
     the margins of setJointLimitMargin() if one is; the other branches inside the limits, nearest first, when no
     path leads there;
  -# plans the joint path from \f$ q \f$ to \f$ q^* \f$, sampled so that no joint moves more than setMaxJointStep()
     between samples, and keeps it only if at every sample the joints are inside their limits and the features in
     view. Candidates, in this order:
     - straight image lines \f$ s_k(t) = (1 - t) s_k(q) + t s_k(q^*) \f$ (which stay inside a window that holds both
       ends), tracked by the inverse kinematics in steps four times finer, warm-started at the previous sample and
       with the joint-space line as a weak prior (30 px per radian: it settles the joints the pixels hardly see near a
       singular configuration); kept if it ends at \f$ q^* \f$, no fine step moves a joint by more than
       setMaxJointStep() (a jump to another branch; a fine step is tracked again in up to 8 sub-steps first, so that a
       joint turning fast is followed) and no joint goes beyond its [start, target] interval by more than
       setMaxExcursion() (no wrist spin);
     - the straight line in joint space;
     - two straight lines through a waypoint, drawn (with a fixed seed) among the configurations inside the limits
       with the features in view, about the middle of the joint-space line in a box growing to the whole of the
       limits: the shortest feasible;
  -# never does worse than law (47) alone: given the task's control law (setControlLaw()), plan() rehearses it on
     the model from \f$ q \f$ (the features predicted by \f$ H(q) \f$, the same gain, damping, saturation and
     joint-limit avoidance, steps guarded as guardStep() does, one model step per iteration as the loop's
     \f$ q \leftarrow q + \dot q \f$). The rehearsal solves the task if it stays inside the joint limits with the
     features in view and reaches the global minimum (a residual within 1.5 times that of the best branch plus
     0.05 px, where a local minimum of three points leaves pixels) within setRehearsalBudget() iterations. The plan
     is then law (47) itself (PATH_LAW, its target the branch it reached), unless a path exists that is faster (its
     samples and 3 iterations of the law after them, fewer than the rehearsed iterations); and law (47) whenever no
     path exists. Without a successful rehearsal (a joint limit, a lost feature, a local minimum, a slow law) the
     task follows the path;
  -# fails with a status (vpPlanStatus) when no branch explains \f$ s^* \f$, none is inside the limits, none
     inside them has the features in view, or no path keeps them in view.

  The straight line of the projective motion group, \f$ H(t) = \exp(t \log(H^* H^{-1})) H \f$ (a screw motion of the
  gripper), is not a candidate: its image paths are helices, not lines (\ref servo_meas_planning says what was
  measured with it).

  Joint values are encoder readings (radians for revolute joints, the encoder's length unit for prismatic ones) as
  everywhere in the model. vpServoProjective::setPathPlanning() runs it once per target and follows the path.
*/
class VISP_EXPORT vpProjectivePathPlanner
{
public:
  //! Joint values without heap allocation.
  typedef vpProjectiveArmModel::JointVector JointVector;

  //! Outcome of plan().
  enum vpPlanStatus {
    PLAN_NONE,                  //!< plan() not called yet.
    PLAN_FOUND,                 //!< A path to a target inside the limits, the features in view all along.
    PLAN_NO_INVERSE_KINEMATICS, //!< No joint values explain the desired features.
    PLAN_OUTSIDE_JOINT_LIMITS,  //!< Every branch of the inverse kinematics is outside the joint limits.
    PLAN_NO_VISIBLE_PATH        //!< No target inside the limits has the features in view, or no path keeps them there.
  };
  //! The kind of path of a plan.
  enum vpPathKind {
    PATH_IMAGE_LINE, //!< Straight image lines from the current to the desired pixels.
    PATH_JOINT_LINE, //!< The straight line in joint space.
    PATH_WAYPOINT,   //!< Two straight joint-space lines through a waypoint.
    PATH_LAW         //!< Law (47) alone: its rehearsal on the model solves the task, no faster path (setControlLaw()).
  };

  vpProjectivePathPlanner();

  /*!
    Joint limits (n x 1 each, encoder readings): the target and the path stay within \f$ [q_{min}, q_{max}] \f$, and
    the inverse kinematics starts from configurations drawn there. Empty vectors remove them (then the starts are
    drawn within a turn of the current revolute joints and 0.5 encoder units of the prismatic ones).
    \exception vpProjectiveException if the sizes differ, a value is not finite or some \f$ q_{min} \ge q_{max} \f$.
  */
  void setJointLimits(const JointVector &qmin, const JointVector &qmax);
  /*!
    The image window \f$ [b, w - 1 - b] \times [b, h - 1 - b] \f$ (pixels, \f$ u \f$ the column) the features' predicted
    images must stay in along the path, as vpServoProjective::setImageSize(); 0 x 0 disables the check.
    \exception vpProjectiveException on a border that leaves no pixel or is negative, or one zero side.
  */
  void setImageSize(unsigned int width, unsigned int height, double border = 0.0);
  /*!
    The largest motion of a joint between two samples of the path (radians for revolute joints, encoder units for
    prismatic ones; default 5 deg): the follower moves by one sample per iteration at most. With a control law whose
    velocity is saturated (setControlLaw(), vpServoControlLaw::setMaxJointVelocity()), the step is at most
    two thirds of that saturation: the follower adds its image feedback to the path's step, and a step that the
    saturation cuts would leave the arm behind its plan.
    \exception vpProjectiveException if it is not positive and finite.
  */
  void setMaxJointStep(double step);
  //! The step of the path's samples: setMaxJointStep(), at most two thirds of the control law's saturation.
  double getMaxJointStep() const;
  /*!
    The largest motion of a joint beyond the interval of its start and target values along a path of straight image
    lines (radians for revolute joints, encoder units for prismatic ones; default: twice setMaxJointStep()). Straight
    image lines can ask for it: on the main tutorial's task (a gripper motion of 82 cm and 88 deg) they need joint 2
    to fold 31 deg past its target, and the default keeps the joint-space line, whose joints move monotonically and
    whose images are arcs; \ref servo_meas_planning measures both.
    \exception vpProjectiveException (invalidValueError) if it is negative or not finite.
  */
  void setMaxExcursion(double excursion);
  //! The bound of setMaxExcursion(), or twice setMaxJointStep() when it was not set.
  double getMaxExcursion() const;
  /*!
    A margin kept from the joint limits at the target when a branch allows it: a branch whose target has a joint
    within \e fraction of that joint's range \f$ q_{max} - q_{min} \f$ from a limit is chosen only if no branch
    inside the limits keeps every joint out of the margins (default 0: the nearest branch inside the limits).
    vpServoProjective leaves it at 0: its joint-limit avoidance lets the arm reach a planned target inside the
    activation band, and a branch out of the band can be half a turn away (the taught configuration is the nearest).
    \exception vpProjectiveException (invalidValueError) if it is not in [0, 1/2].
  */
  void setJointLimitMargin(double fraction);
  //! The margin of setJointLimitMargin() (fraction of each joint's range).
  double getJointLimitMargin() const { return m_limitMargin; }
  /*!
    The control law that the task runs when it follows no path (vpServoControlLaw: gain, damped least squares with
    saturation, joint-limit avoidance in the joint values of plan()'s \e q), rehearsed on the model by plan() before
    any path is planned (see the class documentation): the same implementation of law (47) as the task's.
    vpServoProjective passes its own. Without a call, no rehearsal: a path is always planned.
  */
  void setControlLaw(const vpServoControlLaw &law)
  {
    m_law = law;
    m_hasLaw = true;
  }
  //! No control law: plan() rehearses nothing and always plans a path (its step no longer capped by a saturation).
  void clearControlLaw() { m_hasLaw = false; }
  /*!
    Joint values \e q where law (47) was seen to stall, pixels from s*, in the images (not in the model, which is off by
    a few pixels and cannot tell that minimum from the solution): the next plan() leaves out the inverse-kinematic
    branch nearest to \e q if it is within \e radius (rad or m per joint), as a target that the images refuse. An empty
    \e q (the default) leaves none out. vpServoProjective sets it when it re-plans from such a stall.
  */
  void setRefusedTarget(const JointVector &q, double radius = vpMath::rad(20.0))
  {
    m_refused = q;
    m_refusedRadius = radius;
  }
  /*!
    The largest number of iterations of the rehearsal of law (47) (default 50; 0: no rehearsal). A law that needs
    more in the model is slow in the loop too, where the noise slows it further: a path is planned instead.
  */
  void setRehearsalBudget(unsigned int iterations) { m_rehearsalBudget = iterations; }
  //! The budget of setRehearsalBudget().
  unsigned int getRehearsalBudget() const { return m_rehearsalBudget; }
  /*!
    Planar feature groups: each group lists the indices (in plan()'s \e points order) of points that lie on one
    planar marker, in order around it, such as the 4 corners of an AprilTag (corner 0 to 3, ids \f$ 4\,id + k \f$ of
    vpStereoAprilTagDetector). A detector finds such a marker only while it faces the cameras: besides the features'
    being in view, the target and every sample of the path (and of the rehearsal of law (47)) keep each group facing
    both cameras, its image polygon's signed area \f$ A = \frac{1}{2} \sum_k (u_k v_{k+1} - u_{k+1} v_k) \f$ in each
    image keeping the sign it has at the planning joints and at least setMinGroupArea() times the smaller of its
    areas there and at \f$ s^* \f$ (a tag turning edge-on shrinks to a segment, then flips). When no plan keeps every
    group facing the cameras, plan() plans without this check and says so in getDescription(): the task's open loop
    (vpServoProjective::setMaxOpenLoopTime()) then carries the arm past where a marker is lost. An empty list (the
    default) disables the check; a group in which the sign differs between the planning joints and \f$ s^* \f$ is not
    checked in that image.
    \exception vpProjectiveException (invalidValueError) if a group has fewer than 3 points or a point twice; the
    groups are then unchanged. plan() throws (dimensionError) if an index is not one of its points.
  */
  void setPlanarGroups(const std::vector<std::vector<unsigned int>> &groups);
  //! The groups of setPlanarGroups().
  const std::vector<std::vector<unsigned int>> &getPlanarGroups() const { return m_groups; }
  /*!
    The smallest image area of a planar group along a plan (setPlanarGroups()), as a fraction of the smaller of its
    areas at the planning joints and at \f$ s^* \f$ (default 0.3: a tag seen up to about 70 deg more obliquely than at
    the ends of the motion; 0 keeps only the sign).
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if it is not in [0, 1].
  */
  void setMinGroupArea(double fraction);
  //! The fraction of setMinGroupArea().
  double getMinGroupArea() const { return m_minGroupArea; }
  /*!
    The number of random starts of the inverse kinematics (default 24), besides the current joint values.
    \exception vpProjectiveException (invalidValueError) if 0.
  */
  void setNumberOfStarts(unsigned int starts);
  /*!
    The largest RMS pixel residual per coordinate of the best inverse-kinematic solution for the target to exist
    (default 5 px); above it plan() reports PLAN_NO_INVERSE_KINEMATICS. The residual is that of both views of the
    points after their refinement (vpProjectiveInverseKinematics::solveWithPoints()): at the image noise for the true
    target, the model's prediction error included (\ref servo_meas_planning gives measured values); a desired
    feature 150 px off its place in both images leaves about 6 px, the refined points absorbing part of it.
    \exception vpProjectiveException if it is not positive and finite.
  */
  void setMaxResidual(double pixels);
  //! Gain of the path following's feedback (default 1): the fraction of the error to the sample's predicted
  //! features that vpServoProjective corrects per call. \exception vpProjectiveException if it is not in (0, 1].
  void setPathFollowingGain(double gain);
  //! The gain of setPathFollowingGain().
  double getPathFollowingGain() const { return m_followGain; }
  /*!
    Open loop on the model (default 2 s; 0: off): while a plan is under way and the active features no longer
    constrain every joint (a tag turned edge-on, an occlusion), vpServoProjective replaces each feature set aside that
    was active before by its prediction \f$ \hat s_i = (P, P')\, H(q)\, H(q_l)^{-1} M_l \f$ at the measured joints
    (\f$ M_l \f$ its point at the last call \f$ q_l \f$ where it was active): SERVO_OPEN_LOOP for at most \e seconds
    of consecutive calls (vpServoProjective::setControlPeriod()), then SERVO_STOPPED until the features return
    (\ref servo_task_open_loop).
    \exception vpProjectiveException (invalidValueError, nonFiniteValueError) if \e seconds is negative or not
    finite; the setting is then unchanged.
  */
  void setMaxOpenLoopTime(double seconds);
  //! The bound of setMaxOpenLoopTime() (seconds; 0: off).
  double getMaxOpenLoopTime() const { return m_maxOpenLoopTime; }

  /*!
    Plans the task (see the class documentation) from the joint values \e q (n x 1) for the points \e points (4x1
    each, zero reference) and their desired pixels \e sStar (same size, at least 2 points, finite).
    \return the status, PLAN_FOUND when the path exists; the plan is then given by the getters.
    \exception vpProjectiveException (dimensionError, nonFiniteValueError, notEnoughPointsError) on bad sizes or values.
  */
  vpPlanStatus plan(const vpProjectiveArmModel &model, const JointVector &q, const std::vector<Eigen::Vector4d> &points,
                    const std::vector<Eigen::Vector4d> &sStar);

  //! Outcome of the last plan().
  vpPlanStatus getStatus() const { return m_status; }
  //! Every branch of the inverse kinematics found by the last plan() (joint values as found).
  const std::vector<JointVector> &getBranches() const { return m_branches; }
  //! The RMS pixel residual per coordinate of each branch of getBranches() (same order, the best first).
  const std::vector<double> &getBranchResiduals() const { return m_residuals; }
  //! Index in getBranches() of the branch the target belongs to (meaningful with PLAN_FOUND).
  unsigned int getChosenBranch() const { return m_branch; }
  //! The target \f$ q^* \f$ (n x 1) the path ends at (meaningful with PLAN_FOUND).
  const JointVector &getTarget() const { return m_target; }
  //! The joint values of the path's samples, from \e q (first) to the target (last).
  const std::vector<JointVector> &getPath() const { return m_path; }
  //! The points' predicted pixels (u, v, u', v') at every sample of the path: getPredictedFeatures()[sample][point].
  const std::vector<std::vector<Eigen::Vector4d>> &getPredictedFeatures() const { return m_features; }
  //! The kind of the planned path.
  vpPathKind getPathKind() const { return m_kind; }
  /*!
    Guards a step of law (47) toward the planned task (after the path, or along PATH_LAW; the rehearsal guards its
    steps the same way): while the model predicts that the joint step \e qdot (n x 1, changed in place) from \e q
    raises the RMS pixel error of the planned points to \f$ s^* \f$ by more than 0.5 px (well above the noise and the
    model's error, so that the end of the motion is the law's), the step is halved, at most 5 times. Near a singular
    configuration law (47)'s full step overshoots by tens of pixels and the arm chatters about the target; the guard
    damps that without touching a step that the model predicts to descend. Returns the number of halvings. No
    allocation. Needs a plan (PLAN_FOUND) of this model; does nothing otherwise.
  */
  unsigned int guardStep(const vpProjectiveArmModel &model, const JointVector &q, JointVector &qdot) const;
  /*!
    The outcome of the last rehearsal of law (47): true if it solved the task (then getPathKind() is PATH_LAW unless a
    faster path was found).
    getRehearsalIterations() and getRehearsalResidual() say how far it got.
  */
  bool getRehearsalSucceeded() const { return m_rehearsalOk; }
  //! Iterations of the last rehearsal of law (47) (0 if none ran).
  unsigned int getRehearsalIterations() const { return m_rehearsalIterations; }
  //! RMS pixel residual per coordinate at the end of the last rehearsal of law (47) (negative if none ran).
  double getRehearsalResidual() const { return m_rehearsalResidual; }
  //! A sentence describing the last plan (branches, target, path kind) or why there is none.
  const std::string &getDescription() const { return m_description; }

private:
  vpPlanStatus planOnce(const vpProjectiveArmModel &model, const JointVector &q,
                        const std::vector<Eigen::Vector4d> &points, const std::vector<Eigen::Vector4d> &sStar);
  bool inside(const JointVector &q) const;
  std::vector<std::pair<JointVector, unsigned int>> targetCandidates(const vpProjectiveArmModel &model,
                                                                     const JointVector &q,
                                                                     const std::vector<Eigen::Vector4d> &points,
                                                                     bool &anyInside) const;
  bool planPath(const vpProjectiveArmModel &model, const JointVector &q, const JointVector &target,
                const std::vector<JointVector> &rehearsed, const std::vector<Eigen::Vector4d> &points,
                const JointVector &qmin, const JointVector &qmax, std::vector<JointVector> &path,
                std::vector<std::vector<Eigen::Vector4d>> &features, vpPathKind &kind, bool corners) const;
  bool connectPath(const vpProjectiveArmModel &model, const JointVector &q, const JointVector &target,
                   const std::vector<Eigen::Vector4d> &points, const JointVector &qmin, const JointVector &qmax,
                   std::vector<JointVector> &path, std::vector<std::vector<Eigen::Vector4d>> &features) const;
  bool visible(const vpProjectiveArmModel &model, const JointVector &q, const std::vector<Eigen::Vector4d> &points,
               std::vector<Eigen::Vector4d> &s) const;
  bool feasible(const vpProjectiveArmModel &model, const std::vector<JointVector> &path,
                const std::vector<Eigen::Vector4d> &points, std::vector<std::vector<Eigen::Vector4d>> &features) const;
  std::vector<JointVector> jointLine(const JointVector &from, const JointVector &to) const;
  bool imagePath(const vpProjectiveArmModel &model, const JointVector &q, const JointVector &target,
                 const std::vector<Eigen::Vector4d> &points, std::vector<JointVector> &path) const;
  bool rehearseLaw(const vpProjectiveArmModel &model, const JointVector &q, const std::vector<Eigen::Vector4d> &points,
                   const std::vector<Eigen::Vector4d> &sStar, std::vector<JointVector> &path,
                   std::vector<std::vector<Eigen::Vector4d>> &features);
  unsigned int halveWhileRising(const vpProjectiveArmModel &model, const JointVector &q, JointVector &qdot) const;
  //! \e branch's representative nearest to \e q: each revolute joint within half a turn of q's.
  static JointVector nearestRepresentative(const vpProjectiveArmModel &model, const JointVector &branch,
                                           const JointVector &q);
  vpPlanStatus failWith(vpPlanStatus status, std::ostringstream &os);
  vpPlanStatus adoptLaw(const vpProjectiveArmModel &model, const std::vector<JointVector> &path,
                        const std::vector<std::vector<Eigen::Vector4d>> &features, std::ostringstream &os);
  static double residual(const vpProjectiveArmModel &model, const JointVector &q,
                         const std::vector<Eigen::Vector4d> &points, const std::vector<Eigen::Vector4d> &sStar);

  bool groupsFacing(const std::vector<Eigen::Vector4d> &s) const;
  void computeGroupAreas(const std::vector<Eigen::Vector4d> &atStart, const std::vector<Eigen::Vector4d> &sStar);

  std::vector<std::vector<unsigned int>> m_groups; // setPlanarGroups()
  double m_minGroupArea;
  std::vector<Eigen::Vector2d> m_groupArea; // per group: the signed reference area in each image (0: not checked)
  bool m_groupsOn;                          // plan() checks the groups (off for its fallback)
  bool m_hasLimits;
  JointVector m_qmin, m_qmax;
  unsigned int m_width, m_height;
  double m_border;
  double m_maxStep;
  double m_maxExcursion; // negative: twice m_maxStep
  unsigned int m_starts;
  double m_maxResidual;
  double m_followGain;      // setPathFollowingGain()
  double m_maxOpenLoopTime; // setMaxOpenLoopTime(), seconds
  JointVector m_refused;    // setRefusedTarget(): empty, or where the law stalled in the images
  double m_refusedRadius;   // how near a branch must be to m_refused to be left out
  double m_limitMargin;
  std::vector<Eigen::Vector2d> m_front;  // per point: its depths in both cameras at the planning q
  std::vector<Eigen::Vector4d> m_points; // the planned points (zero reference) and their desired pixels
  std::vector<Eigen::Vector4d> m_sStar;
  bool m_hasLaw;
  vpServoControlLaw m_law;
  unsigned int m_rehearsalBudget;
  bool m_rehearsalOk;
  unsigned int m_rehearsalIterations;
  double m_rehearsalResidual;
  bool m_rehearsalSlow; // the last rehearsal ran out of budget inside the limits, in view, still moving

  vpPlanStatus m_status;
  std::vector<JointVector> m_branches;
  std::vector<double> m_residuals;
  unsigned int m_branch;
  JointVector m_target;
  std::vector<JointVector> m_path;
  std::vector<std::vector<Eigen::Vector4d>> m_features;
  vpPathKind m_kind;
  std::string m_description;
};

END_VISP_NAMESPACE

#endif
