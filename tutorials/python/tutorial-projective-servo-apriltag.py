#!/usr/bin/env python3
"""The simulated AprilTag cell servoed end to end from Python (tutorial-projective-servo-apriltag.cpp's steps): a
PUMA-like arm with three tags on its tool, two uncalibrated cameras, the acquisition by trial motions, s* taught by
showing, then the planned servo. Replace the cell by your robot and grabbers and keep the rest.
Usage: tutorial-projective-servo-apriltag.py [--output PNG]; exit code 0 if the image error ends below 1 px RMS."""
import argparse
import sys

import numpy as np
import visp_projective as vpp

parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
parser.add_argument("--output", help="write the left image at the end with the corners' paths (PNG, matplotlib)")
args = parser.parse_args()

# The cell: the arm (a vpRobot, 25 Hz joint velocity control) and two cameras rendering its tags with noise and blur.
cell = vpp.SimulatorStereoCell(vpp.SimulatorArm.puma(vpp.SimulatorArm.paperBasePose()),
                               vpp.SimulatorStereoRig.paperRig([0.0, 0.0, 0.0], 1.0))
cell.addToolTags(0.03)  # tags 0, 1, 2 on a holder on the tool
cell.getRenderer().setNoise(1.0)
cell.getRenderer().setBlur(0.5)
robot = cell.getRobot()
robot.setConstantSamplingTimeMode(True)  # each setVelocity() moves the arm for one period
robot.setSamplingTime(0.04)
robot.setMaxRotationVelocity(np.radians(30.0))
n = robot.getNumberOfJoints()
tags = vpp.StereoAprilTagDetector(vpp.StereoAprilTagDetector.TAG_36h11)


def see():  # a stereo frame: the tag corners found in both images, ids 4 * tag + corner
    tags.detect(*cell.acquire())
    return tags.getIds(), tags.getLeftPoints(), tags.getRightPoints()


# The acquisition: each joint moved alone by velocity; the rig and the arm's model from the same images.
model = vpp.ProjectiveRobot([vpp.ProjectiveRobot.REVOLUTE] * n)
acquisition = vpp.ProjectiveAcquisitionProcedure(see, cell.getWidth(), cell.getHeight(), identified=True)
acquisition.setOutput(sys.stdout)
acquisition.run(robot, model)  # moves the arm: keep a hand on the emergency stop of a real one
print(f"Model: residual {acquisition.getCalibrationResidual():.3f} px RMS")

# s*: the arm shown the target, the 4 corners of tag 1 (ids 4 to 7) averaged over 16 frames.
q_target, q_start = np.radians([10, -8, 12, 15, -12, 20]), np.radians([-25, 20, -25, 40, 30, -35])
robot.setPosition(vpp.Robot.ARTICULAR_FRAME, q_target)
frames = [see() for frame in range(16)]

task = vpp.ServoProjective()
task.setRobot(model)
task.setControlPeriod(robot.getSamplingTime())  # one call per camera frame: qdot is sent as a velocity
task.setLambda(1.0)
task.setMaxJointVelocity(np.radians(30.0))
task.setJointLimits(robot.getJointMin(), robot.getJointMax())
task.setImageSize(cell.getWidth(), cell.getHeight(), 10.0)
task.setPathPlanning(True)  # rehearse law (47) on the model, plan a path if it would fail
task.getPathPlanner().setPlanarGroups([[0, 1, 2, 3]])  # one tag's corners: the path keeps it facing the cameras
task.setSettling(True)  # once converged, average rather than chase each frame's noise
s, s_star = [vpp.FeatureStereoPoint() for k in range(4)], [vpp.FeatureStereoPoint() for k in range(4)]
for k in range(4):  # s*: the mean of the frames where corner k was seen
    seen = [(l[ids.index(4 + k)], r[ids.index(4 + k)]) for ids, l, r in frames if 4 + k in ids]
    s_star[k].buildFrom(*map(np.array, zip(*seen)))
    task.addFeature(s[k], s_star[k])

# The servo loop: detect, update s, compute qdot, send it.
robot.setPosition(vpp.Robot.ARTICULAR_FRAME, q_start)
robot.setRobotState(vpp.Robot.STATE_VELOCITY_CONTROL)
paths, error = [[] for k in range(4)], np.inf
for it in range(300):
    ids, left, right = see()
    e = []
    for k in range(4):
        if 4 + k in ids:
            s[k].buildFrom(left[ids.index(4 + k)], right[ids.index(4 + k)])
            paths[k].append(left[ids.index(4 + k)])
        task.setFeatureTracked(k, 4 + k in ids)  # a corner out of view is set aside for this iteration
        e.append(s[k].error(s_star[k]))
    if all(4 + k in ids for k in range(4)):
        tags.setPredictedRegions(ids, left, right)  # next frame: search near these corners
    qdot = task.computeControlLaw(robot.getPosition(vpp.Robot.ARTICULAR_FRAME))
    if task.getStatus() in (vpp.ServoProjective.SERVO_MODEL_MISMATCH, vpp.ServoProjective.SERVO_NO_PLAN):
        print(f"Stopped at call {it}: {vpp.ServoProjective.toString(task.getStatus())}")
        break
    robot.setVelocity(vpp.Robot.ARTICULAR_FRAME, qdot)
    error = np.sqrt(np.mean(np.concatenate(e) ** 2))
    if it % 20 == 0:
        print(f"iteration {it}: image error {error:.3f} px RMS, {len(ids)} corners seen")
    if it > 20 and error < 0.3 and np.linalg.norm(qdot) < np.radians(0.05):
        break  # settled
robot.setRobotState(vpp.Robot.STATE_STOP)
print(f"After {it} iterations: image error {error:.4f} px RMS")

if args.output:  # the left image at the end, the corners' paths in green and s* in red
    import matplotlib.pyplot as plt
    plt.imshow(cell.acquire()[0], cmap="gray")
    for k in range(4):
        plt.plot(*np.array(paths[k]).T, "g-", linewidth=1)
        plt.plot(s_star[k].get_u(), s_star[k].get_v(), "r+", markersize=12)
    plt.savefig(args.output, dpi=100)
sys.exit(0 if error < 1.0 else 1)
