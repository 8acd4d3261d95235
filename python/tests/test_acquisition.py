"""The acquisition procedure on a robot written in Python (conftest.PythonArm: vpRobot's getPosition, setVelocity,
setRobotState, getMaxRotationVelocity, getMaxTranslationVelocity) and marker images from a Python callable: the model
it calibrates predicts the markers, on three arms (PUMA, Viper850 with a non-zero zero reference, a chain with a
prismatic joint); a Python error or a bad image source stops the run with its own message."""
import io

import numpy as np
import pytest
import visp_projective as vpp
from conftest import PythonArm, prediction_error, puma, rpr, viper850


def procedure_on(world, robot, rng, sigma):
    """A quick procedure (joints moved by steps of a third of the world's amounts, at most 2/3 of them) on the noisy
    images of all the markers at the Python robot's joints."""
    def source():
        visible, left, right = world.images(robot.q, rng, sigma)
        return (left, right) if visible else None

    procedure = vpp.ProjectiveAcquisitionProcedure(source, world.rig.getWidth(), world.rig.getHeight())
    procedure.setMaxAmounts(world.amounts * 2 / 3)
    procedure.setSteps(world.amounts / 3)
    procedure.setMinAmounts(world.amounts / 4)
    procedure.setJointLimits(world.arm.getJointMin(), world.arm.getJointMax(), 0.0)
    return procedure


@pytest.mark.parametrize("make_world", [puma, viper850, rpr])
def test_python_robot_acquisition(make_world):
    world = make_world()
    rng = np.random.default_rng(1)
    robot = PythonArm(world.arm, world.q_ref)
    procedure = procedure_on(world, robot, rng, 0.1)
    output = io.StringIO()
    procedure.setOutput(output)
    steps = []
    procedure.setStepCallback(lambda joint, q, left, right: steps.append((joint, q, left.shape)))
    model = vpp.ProjectiveRobot(world.types)
    procedure.run(robot, model)
    assert model.isCalibrated(), world.name
    assert procedure.getCalibrationResidual() < 0.2, world.name  # about the noise, 0.1 px
    assert model.getRigMounting() == vpp.ProjectiveRobot.EYE_TO_HAND
    assert np.abs(model.getAcquisition().getZeroReferenceJoints() - world.q_ref).max() < 1e-4  # absolute encoder readings
    assert np.abs(robot.q - world.q_ref).max() < 1e-4  # the arm back at the zero reference
    assert vpp.Robot.STATE_VELOCITY_CONTROL in robot.states
    assert prediction_error(model, world, rng, world.amounts / 2) < 1.0, world.name
    reports = procedure.getReports()
    assert len(reports) == len(world.types) and all(r.trials >= 2 for r in reports)
    assert {s[0] for s in steps} == set(range(len(world.types))) and steps[0][2] == (7, 2)
    assert "calibrated:" in output.getvalue() and "acquisition done" in output.getvalue()


def test_python_errors_stop_the_run():
    world = puma()
    rng = np.random.default_rng(2)

    class Broken(PythonArm):
        def setVelocity(self, frame, qdot):
            if self.q[2] > 0.1:
                raise RuntimeError("emergency stop pressed")
            super().setVelocity(frame, qdot)

    robot = Broken(world.arm, world.q_ref)
    model = vpp.ProjectiveRobot(world.types)
    with pytest.raises(RuntimeError, match="emergency stop pressed") as error:
        procedure_on(world, robot, rng, 0.0).run(robot, model)
    assert not isinstance(error.value, vpp.ViSPException)  # the robot's own exception, not the library's
    assert not model.isCalibrated()

    robot = PythonArm(world.arm, world.q_ref)
    procedure = vpp.ProjectiveAcquisitionProcedure(lambda: (np.zeros((7, 3)), np.zeros((7, 3))), 640, 480)
    with pytest.raises(ValueError, match=r"\(N, 2\) array"):
        procedure.run(robot, model)
    procedure = vpp.ProjectiveAcquisitionProcedure(lambda: 42, 640, 480)
    with pytest.raises(TypeError, match="must return \\(left, right\\)"):
        procedure.run(robot, model)
    with pytest.raises(TypeError, match="getPosition"):
        procedure.run(object(), model)

    markers = world.images(world.q_ref)[1:]
    procedure = vpp.ProjectiveAcquisitionProcedure(lambda: (markers[0][:4], markers[1][:4]), 640, 480)
    with pytest.raises(vpp.ProjectiveException) as error:  # the library's own check, before any motion
        procedure.run(robot, model)
    assert error.value.code == vpp.ProjectiveException.notEnoughPointsError and "5" in str(error.value)
    assert np.array_equal(robot.q, world.q_ref)
