"""The simulated AprilTag cell, the detector on numpy images, and sessions from Python: the corners found in rendered
uint8 arrays are the renderer's true corners; a session recorded by ProjectiveSessionWriter during an acquisition
reads back frame by frame and image by image, and calibrates offline into a model that fits it."""
import numpy as np
import pytest
import visp_projective as vpp


def make_cell():
    cell = vpp.SimulatorStereoCell(vpp.SimulatorArm.puma(vpp.SimulatorArm.paperBasePose()),
                                   vpp.SimulatorStereoRig.paperRig([0.0, 0.0, 0.0], 1.0))
    cell.addToolTags(0.03)
    return cell


def test_detector_finds_the_true_corners():
    cell = make_cell()
    cell.getRenderer().setNoise(1.0)
    robot = cell.getRobot()
    robot.setPosition(vpp.Robot.ARTICULAR_FRAME, np.radians([5, -5, 8, 10, -10, 15]))
    left_image, right_image = cell.acquire()
    assert left_image.dtype == np.uint8 and left_image.shape == (cell.getHeight(), cell.getWidth())
    tags = vpp.StereoAprilTagDetector()
    n = tags.detect(left_image, right_image)
    ids, left, right = cell.getTrueCorners()
    assert n == len(ids) >= 8 and tags.getIds() == ids  # 2 or 3 tags seen, ascending 4 * id + corner
    assert np.abs(tags.getLeftPoints() - left).max() < 0.3 and np.abs(tags.getRightPoints() - right).max() < 0.3
    assert tags.detect(np.zeros((480, 640), np.uint8), np.zeros((480, 640), np.uint8)) == 0
    with pytest.raises(TypeError):  # floats are not an 8-bit image
        tags.detect(left_image.astype(float), right_image)
    with pytest.raises(ValueError, match="2-D uint8 image"):
        tags.detect(np.zeros((4, 4, 3), np.uint8), right_image)


def test_session_recorded_read_back_and_calibrated(tmp_path):
    cell = make_cell()
    robot = cell.getRobot()
    robot.setConstantSamplingTimeMode(True)
    robot.setSamplingTime(0.04)
    types = [vpp.ProjectiveRobot.REVOLUTE] * 6
    folder = str(tmp_path / "session")
    tags = vpp.StereoAprilTagDetector()
    recorded = []
    with vpp.ProjectiveSessionWriter(folder, types) as writer:
        def source():  # the tag corners, each frame with 5 corners or more recorded with the encoders
            images = cell.acquire()
            tags.detect(*images)
            if len(tags.getIds()) >= 5:
                q = robot.getPosition(vpp.Robot.ARTICULAR_FRAME)
                recorded.append((writer.addAcquisitionFrame(q, robot.getTime(), *images), q, images))
            return tags.getIds(), tags.getLeftPoints(), tags.getRightPoints()

        procedure = vpp.ProjectiveAcquisitionProcedure(source, cell.getWidth(), cell.getHeight(), identified=True)
        procedure.setMaxAmounts(np.radians([12.0] * 6))
        procedure.setSteps(np.radians([6.0] * 6))
        model = vpp.ProjectiveRobot(types)
        procedure.run(robot, model)
    assert writer.isClosed()

    session = vpp.ProjectiveSession.read(folder)
    assert session.getNumberOfFrames() == len(recorded) and session.getJointTypes() == types
    assert session.getNumberOfFrames(vpp.ProjectiveSession.ZERO) == 1
    assert session.getNumberOfFrames(vpp.ProjectiveSession.TRIAL) >= 12
    for k in (0, len(recorded) // 2, len(recorded) - 1):
        role, q, images = recorded[k]
        frame = session.getFrame(k)
        assert frame.role == role and np.array_equal(frame.q, q)
        left, right = session.getImages(k)
        assert np.array_equal(left, images[0]) and np.array_equal(right, images[1])  # PNG: lossless
    replay = vpp.ProjectiveSessionSource(session, [vpp.ProjectiveSession.TRIAL])
    first = replay.acquire()
    assert session.getFrame(replay.getFrameIndex()).role == vpp.ProjectiveSession.TRIAL
    assert np.array_equal(first[0], session.getImages(replay.getFrameIndex())[0])

    calibration = vpp.ProjectiveSessionCalibration("36h11")
    arm = calibration.calibrate(session)
    assert arm.getNumberOfJoints() == 6 and calibration.getCalibrationResidual() < 0.5
    assert len(calibration.getJointSummaries()) == 6
    checks = calibration.check(arm, calibration.getMarkerIds(), session)
    assert len(checks) == session.getNumberOfFrames() and all(c.fits for c in checks)
    assert calibration.getRigState() == vpp.ProjectiveSessionCalibration.RIG_UNCHANGED
    path = str(tmp_path / "arm.json")
    calibration.saveModel(path)
    loaded = vpp.ProjectiveRobot()
    loaded.loadModel(path)
    _, q, images = recorded[-1]  # the file's model predicts the corners of the last frame
    tags.detect(*images)
    ids = calibration.getMarkerIds()
    seen = [(ids.index(i), k) for k, i in enumerate(tags.getIds()) if i in ids]
    assert len(seen) >= 5
    model = loaded.getModel()
    for j, k in seen:
        left, right = model.projectMarker(j, q)
        assert np.abs(left - tags.getLeftPoints()[k]).max() < 0.5
        assert np.abs(right - tags.getRightPoints()[k]).max() < 0.5

    with pytest.raises(vpp.ProjectiveException) as error:  # a recording is never overwritten
        vpp.ProjectiveSessionWriter(folder, types)
    assert error.value.code == vpp.ProjectiveException.fileError and "session.json" in str(error.value)
    with pytest.raises(vpp.ProjectiveException) as error:
        vpp.ProjectiveSession.read(str(tmp_path / "missing"))
    assert error.value.code == vpp.ProjectiveException.fileError
