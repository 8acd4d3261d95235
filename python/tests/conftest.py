"""What the tests of the Python module share: the simulated worlds (the paper's PUMA, ViSP's Viper850 and a
revolute-prismatic-revolute chain, each with its tool markers facing the paper's rig), a Python robot implementing
the vpRobot calls the acquisition procedure makes, and an arm acquired by trial motions (the C++ counterpart:
tests/vpProjectiveArmTestTools.h). Every random number comes from a seeded numpy generator."""
import os

import numpy as np
import pytest
import visp_projective as vpp

TUTORIALS = os.path.join(os.path.dirname(__file__), os.pardir, os.pardir, "tutorials", "python")


class World:
    """An arm at its zero-reference joints q_ref, its 7 gripper markers seen by the paper's rig, pixel noise sigma."""

    def __init__(self, name, arm, q_ref, amounts):
        self.name, self.arm, self.q_ref, self.amounts = name, arm, np.array(q_ref, float), np.array(amounts, float)
        self.rig = vpp.SimulatorStereoRig.paperRig([0.0, 0.0, 0.0], 1.0)
        self.types = [arm.getJointType(i) for i in range(arm.getNumberOfJoints())]

    def images(self, q, rng=None, sigma=0.0, markers=None):
        """(visible, left, right): the markers' pixels at the joints q, with Gaussian noise sigma (px) from rng."""
        points = self.arm.getMarkers(q)
        visible, left, right = self.rig.project(points if markers is None else points[markers])
        if sigma > 0.0:
            left, right = left + rng.normal(0.0, sigma, left.shape), right + rng.normal(0.0, sigma, right.shape)
        return visible, left, right


def base_pose(table, q_ref):
    """The base pose of the arm of the DH table with the gripper that puts its tool where the PUMA's is at its zero
    reference (at the world origin, the markers facing the paper's rig) when the joints are q_ref."""
    tool = vpp.SimulatorArm.puma(vpp.SimulatorArm.paperBasePose()).get_wMt(np.zeros(6))
    unplaced = vpp.SimulatorArm(table, vpp.SimulatorArm.gripperMount(), vpp.SimulatorArm.gripperMarkers(), np.eye(4))
    return tool @ np.linalg.inv(unplaced.get_wMt(q_ref))


def puma():
    return World("PUMA", vpp.SimulatorArm.puma(vpp.SimulatorArm.paperBasePose()), np.zeros(6),
                 np.radians([30, 20, 30, 40, 60, 60]))


def viper850():
    q_ref = np.radians([0, -150, 190, 0, -75, 0])  # tests/vpProjectiveArmTestTools.h, viperZeroReference()
    wMb = base_pose(vpp.SimulatorArm.viper850(np.eye(4)).getDHTable(), q_ref)
    return World("Viper850", vpp.SimulatorArm.viper850(wMb), q_ref, np.radians([30, 8, 12, 30, 30, 60]))


def rpr():
    R, P = vpp.ProjectiveRobot.REVOLUTE, vpp.ProjectiveRobot.PRISMATIC
    Row = vpp.SimulatorArm.DHRow
    table = [Row(R, 0.0, 0.30, 0.25, np.pi / 2), Row(P, np.pi / 2, 0.20, 0.0, np.pi / 2), Row(R, 0.3, 0.10, 0.0, 0.0)]
    q_ref = np.array([np.radians(10.0), 0.05, np.radians(-20.0)])  # tests/vpProjectiveArmTestTools.h, mixedTable()
    arm = vpp.SimulatorArm(table, vpp.SimulatorArm.gripperMount(), vpp.SimulatorArm.gripperMarkers(),
                           base_pose(table, q_ref))
    return World("RPR", arm, q_ref, [np.radians(12.0), 0.04, np.radians(40.0)])


class PythonArm:
    """A robot written in Python: vpRobot's calls that ProjectiveAcquisitionProcedure makes, on a SimulatorArm whose
    joints move for one sampling period dt at each setVelocity() (as SimulatorRobotArm's constant sampling mode)."""

    def __init__(self, arm, q0, dt=0.04):
        self.arm, self.q, self.dt, self.states = arm, np.array(q0, float), dt, []

    def getPosition(self, frame):
        assert frame == vpp.Robot.ARTICULAR_FRAME
        return self.q.copy()

    def setVelocity(self, frame, qdot):
        assert frame == vpp.Robot.ARTICULAR_FRAME
        self.q = self.arm.integrate(self.q, qdot, self.dt)

    def setRobotState(self, state):
        self.states.append(state)

    def getMaxRotationVelocity(self):
        return 1.0

    def getMaxTranslationVelocity(self):
        return 0.2


def acquire_by_trials(world, sigma, seed):
    """The acquisition of the tutorials: marker images at q_ref, then each joint alone moved both ways by its amount
    (halved until the markers stay in view); the rig from the same images; then calibrate()."""
    rng = np.random.default_rng(seed)
    _, left0, right0 = world.images(world.q_ref, rng, sigma)
    trials = []
    for i, amount in enumerate(world.amounts):
        for sign in (1.0, -1.0):
            q = world.q_ref.copy()
            q[i] += sign * amount
            while not (seen := world.images(q, rng, sigma))[0]:
                q[i] = world.q_ref[i] + (q[i] - world.q_ref[i]) / 2.0
            trials.append((q, seen[1], seen[2]))
    rig = vpp.ProjectiveStereoRig()
    rig.estimate(np.vstack([left0] + [t[1] for t in trials]), np.vstack([right0] + [t[2] for t in trials]),
                 max(1.0, 4.0 * sigma))
    robot = vpp.ProjectiveRobot(world.types)
    robot.setStereoRig(rig)
    robot.setZeroReference(world.q_ref, left0, right0)
    for q, left, right in trials:
        robot.addTrialMotion(q, left, right)
    robot.calibrate()
    return robot


def prediction_error(robot, world, rng, spread):
    """RMS (px per coordinate) of the model's marker predictions against the truth at 20 random joint values within
    +-spread of the zero reference (only where the truth is in view)."""
    squares, model = [], robot.getModel()
    for k in range(20):
        q = world.q_ref + rng.uniform(-1.0, 1.0, len(world.q_ref)) * spread
        visible, left, right = world.images(q)
        if visible:
            for j in range(len(left)):
                predicted = model.projectMarker(j, q)
                squares += [np.sum((predicted[0] - left[j]) ** 2), np.sum((predicted[1] - right[j]) ** 2)]
    assert len(squares) > 40, "too few configurations with the markers in view"
    return np.sqrt(np.sum(squares) / (2 * len(squares)))


@pytest.fixture(scope="session")
def paper_robot():
    """The paper's PUMA acquired at 0.1 px of noise (seed 1)."""
    return acquire_by_trials(puma(), 0.1, 1)
