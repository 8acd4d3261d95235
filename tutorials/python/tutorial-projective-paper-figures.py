#!/usr/bin/env python3
"""The paper's experiment from Python, with its figures made by matplotlib (as apps/projective-paper makes them with
gnuplot): a PUMA-like arm seen by an uncalibrated stereo rig (Ruf & Horaud, ICCV'99, section 6) is acquired by trial
motions of one joint at a time, then servoed by the control law (47) with path planning from a start 82 cm and
88 deg away from its target, at 0.5 px of image noise. Figures like the paper's Fig. 2 (the features' image
trajectories), Fig. 4 (the joint trajectories) and Fig. 5 (the image error) are written headless (Agg).
Usage: tutorial-projective-paper-figures.py [--output DIR] [--seed N]
The exit code is 0 if the task converged (the image error of the last 10 iterations below twice the noise, RMS)
with the markers in view."""
import argparse
import os
import sys

import matplotlib
matplotlib.use("Agg")  # headless: PNG files, no window
import matplotlib.pyplot as plt
import numpy as np
import visp_projective as vpp

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", default=".", help="where the figures go (default: the current folder)")
parser.add_argument("--seed", type=int, default=1, help="seed of the image noise (default 1)")
args = parser.parse_args()
os.makedirs(args.output, exist_ok=True)

# The paper's world, which only the simulator knows (apps/common/paper-world.h), and 0.5 px of image noise.
rig = vpp.SimulatorStereoRig.paperRig([0.0, 0.0, 0.0], 1.0)
arm = vpp.SimulatorArm.puma(vpp.SimulatorArm.paperBasePose())
trial_deg = [30, 20, 30, 40, 60, 60]  # the paper's trial motions
tracked = [0, 1, 2]  # the markers on the gripper's face that looks at the rig
q_start = np.radians([15.4461, 54.9087, -48.3752, 62.3954, 29.0729, 1.7330])
q_target = np.radians([8.1330, 7.0830, -56.4826, 90.4984, 76.3260, 57.1987])
sigma, noise = 0.5, np.random.default_rng(args.seed)


def images(q, markers=None):
    """The noisy images (left, right) of the markers at the joints q, and whether all are in view."""
    points = arm.getMarkers(q) if markers is None else arm.getMarkers(q)[markers]
    visible, left, right = rig.project(points)
    return visible, left + noise.normal(0.0, sigma, left.shape), right + noise.normal(0.0, sigma, right.shape)


# 1. Acquisition: the markers at q = 0, then each joint alone moved both ways (halved until the markers stay in view);
# the fundamental matrix from these very images: nothing but pixels and encoder readings enters the model.
_, left0, right0 = images(np.zeros(6))
trials = []
for i, amount in enumerate(np.radians(trial_deg)):
    for sign in (1.0, -1.0):
        q = np.zeros(6)
        q[i] = sign * amount
        while not (seen := images(q))[0]:
            q[i] /= 2.0
        trials.append((i, q[i], seen[1], seen[2]))
stereo = vpp.ProjectiveStereoRig()
stereo.estimate(np.vstack([left0] + [t[2] for t in trials]), np.vstack([right0] + [t[3] for t in trials]),
                max(1.0, 4.0 * sigma))
robot = vpp.ProjectiveRobot([vpp.ProjectiveRobot.REVOLUTE] * 6)
robot.setStereoRig(stereo)
robot.setZeroReference(left0, right0)
for i, amount, left, right in trials:
    robot.addTrialMotion(i, amount, left, right)
robot.calibrate()
print(f"Acquisition: {len(trials)} trials, model residual {robot.getAcquisition().getCalibrationResidual():.3f} px RMS")

# 2. The servo task (apps/projective-paper/paper-experiment.cpp, configureTask()): law (47), path planning.
task = vpp.ServoProjective()
task.setRobot(robot)
task.setLambda(0.5)
task.setMaxJointVelocity(np.radians(15.0))
task.setDamping(30.0, 30.0)
task.setJointLimits(arm.getJointMin(), arm.getJointMax())
task.setImageSize(rig.getWidth(), rig.getHeight(), 10.0)
task.setPathPlanning(True)
task.getPathPlanner().setMaxJointStep(np.radians(10.0))
task.getPathPlanner().setMaxExcursion(np.radians(20.0))
s = [vpp.FeatureStereoPoint() for k in tracked]
s_star = [vpp.FeatureStereoPoint() for k in tracked]
_, left_star, right_star = images(q_target, tracked)  # s*: taught by showing the target once
for k in range(len(tracked)):
    s_star[k].buildFrom(left_star[k], right_star[k])
    task.addFeature(s[k], s_star[k])

# 3. The servo loop, one control period per iteration.
q, joints, features, errors, in_view = q_start.copy(), [], [], [], True
for it in range(41):
    visible, left, right = images(q, tracked)
    in_view = in_view and visible
    for k in range(len(tracked)):
        s[k].buildFrom(left[k], right[k])
    qdot = task.computeControlLaw(q)
    joints.append(np.degrees(q))
    features.append((left, right))
    errors.append(np.concatenate([s[k].error(s_star[k]) for k in range(len(tracked))]))
    q = arm.integrate(q, qdot, 1.0)
rms = np.sqrt(np.mean(np.square(errors), axis=1))
print(f"Servo: image error {rms[0]:.1f} px RMS at the start, {rms[-1]:.2f} px at the end; joint error "
      f"{np.abs(np.degrees(q - q_target)).max():.2f} deg at most (the simulator's truth)")

# 4. The figures: Fig. 2 (image trajectories), Fig. 4 (joints), Fig. 5 (image error).
figure, axes = plt.subplots(1, 2, figsize=(13, 5.2))
for camera, (ax, star) in enumerate(zip(axes, (left_star, right_star))):
    for k in range(len(tracked)):
        path = np.array([f[camera][k] for f in features])
        ax.plot(path[:, 0], path[:, 1], ".-", markersize=3, label=f"point {k}")
        ax.plot(*path[0], "ko", fillstyle="none", markersize=10)
    ax.plot(star[:, 0], star[:, 1], "rx", markersize=10, label="target")
    ax.set(title=("left", "right")[camera] + " image", xlabel="u [px]", ylabel="v [px]", xlim=(0, rig.getWidth()),
           ylim=(rig.getHeight(), 0), aspect="equal")
    ax.legend()
figure.savefig(os.path.join(args.output, "projective-servo-fig2-features.png"))
figure, ax = plt.subplots(figsize=(10, 4.8))
ax.plot(np.array(joints), ".-")
ax.set(title="joint-space trajectory", xlabel="iteration", ylabel="q [deg]")
ax.legend([f"q{i}" for i in range(6)])
figure.savefig(os.path.join(args.output, "projective-servo-fig4-joints.png"))
figure, ax = plt.subplots(figsize=(10, 4.8))
ax.semilogy(np.maximum(np.abs(np.array(errors)), 1e-6), linewidth=0.5)
ax.semilogy(rms, "k.-", linewidth=2, label="RMS")
ax.set(title="image error |s - s*|", xlabel="iteration", ylabel="[px]")
ax.legend()
figure.savefig(os.path.join(args.output, "projective-servo-fig5-error.png"))
print(f"Figures: {args.output}/projective-servo-fig{{2-features,4-joints,5-error}}.png")
sys.exit(0 if in_view and np.sqrt(np.mean(np.square(rms[-10:]))) < 2.0 * sigma else 1)
