"""The rig and the groups from Python (DESIGN.md section 3, fourth round): numpy in and out, (u, v) pixel order, the
same results as the C++ library on the same numbers, bad input refused with the plugin's message."""
import os
import subprocess

import numpy as np
import pytest
import visp_projective as vpp

SIM = vpp.SimulatorStereoRig.paperRig([0.0, 0.0, 0.0], 1.0)


def matches(rng, n, sigma=0.0, outliers=0):
    """n matches of random world points in front of the paper's rig (pixels with noise sigma), the first `outliers`
    of them with their right pixel moved 30 to 60 px away."""
    left, right = [], []
    while len(left) < n:
        visible, l, r = SIM.project(rng.uniform([-0.15, -0.12, -0.1], [0.15, 0.12, 0.1]))
        if visible:
            left.append(l)
            right.append(r)
    left, right = np.array(left), np.array(right)
    left += rng.normal(0.0, sigma, left.shape)
    right += rng.normal(0.0, sigma, right.shape)
    angle = rng.uniform(0.0, 2.0 * np.pi, outliers)
    right[:outliers] += rng.uniform(30.0, 60.0, (outliers, 1)) * np.column_stack([np.cos(angle), np.sin(angle)])
    return left, right


def test_rig_from_numpy_equals_the_cpp_rig(tmp_path):
    reference = os.environ.get("VISP_PROJECTIVE_RIG_REFERENCE")
    if not reference:
        pytest.skip("VISP_PROJECTIVE_RIG_REFERENCE (the C++ program rig-reference) is set by ctest")
    for seed, (n, outliers) in enumerate([(40, 4), (12, 0)]):  # robust (RANSAC) and below 15 matches
        left, right = matches(np.random.default_rng(seed), n, 0.3, outliers)
        path = tmp_path / f"matches{seed}.txt"
        path.write_text(f"{n} 2.0\n" + "".join(f"{a!r} {b!r} {c!r} {d!r}\n" for a, b, c, d in np.hstack([left, right])))
        cpp = subprocess.run([reference, str(path)], capture_output=True, text=True, check=True).stdout.split()
        rig = vpp.ProjectiveStereoRig()
        rig.estimate(left, right, 2.0)
        F = rig.getFundamentalMatrix()
        assert F.shape == (3, 3) and F.dtype == np.float64
        assert np.array_equal(F.ravel(), np.array(cpp[:9], float))  # bit for bit
        assert rig.getEstimationResidual() == float(cpp[9])
        assert rig.getInliers() == [c == "1" for c in cpp[10:]]
        assert not any(rig.getInliers()[:outliers]) and all(rig.getInliers()[outliers:])
        # The same geometry as the simulator's true F (both of unit norm, up to sign).
        F_true = SIM.getFundamentalMatrix() / np.linalg.norm(SIM.getFundamentalMatrix())
        assert min(np.linalg.norm(F - F_true), np.linalg.norm(F + F_true)) < 0.05


def test_pixels_are_u_v_and_round_trip():
    rng = np.random.default_rng(7)
    left, right = matches(rng, 20)
    rig = vpp.ProjectiveStereoRig()
    rig.estimate(left, right)
    F = rig.getFundamentalMatrix()
    ml, mr = np.column_stack([left, np.ones(20)]), np.column_stack([right, np.ones(20)])
    assert np.max(np.abs(np.einsum("ij,jk,ik->i", mr, F, ml)) / np.linalg.norm(F @ ml.T, axis=0)) < 1e-6
    assert np.linalg.norm(F @ rig.getLeftEpipole()) < 1e-9 and rig.getRightProjection().shape == (3, 4)
    M = rig.triangulate(left, right)
    assert M.shape == (20, 4) and np.allclose(np.linalg.norm(M, axis=1), 1.0)
    for k in range(20):
        assert np.array_equal(rig.triangulate(left[k], right[k]), M[k])  # the list is the single matches
        l, r = rig.project(M[k])
        assert np.abs(l - left[k]).max() < 1e-6 and np.abs(r - right[k]).max() < 1e-6
        assert np.allclose(rig.project(-3.0 * M[k])[0], l)  # any scale and sign
    assert np.array_equal(rig.project(list(M[0]))[0], rig.project(tuple(M[0]))[0])  # any sequence of 4 floats


def test_bad_input_refused_with_the_plugins_message():
    rng = np.random.default_rng(3)
    left, right = matches(rng, 20)
    rig = vpp.ProjectiveStereoRig()
    with pytest.raises(vpp.ProjectiveException) as error:
        rig.triangulate(left[0], right[0])
    assert error.value.code == vpp.ProjectiveException.notInitializedError
    rig.estimate(left, right)
    F = rig.getFundamentalMatrix()
    cases = [((left[:5], right[:5]), vpp.ProjectiveException.notEnoughPointsError, "at least 8 matches"),
             ((left, right[:19]), vpp.ProjectiveException.dimensionError, "20"),
             ((np.where(np.arange(40).reshape(20, 2) == 7, np.nan, left), right),
              vpp.ProjectiveException.nonFiniteValueError, "finite")]
    for args, code, words in cases:
        with pytest.raises(vpp.ProjectiveException) as error:
            rig.estimate(*args)
        assert error.value.code == code and words in str(error.value)
        assert str(error.value).startswith("vpProjectiveStereoRig::estimate()")  # the C++ message, as it is
        assert isinstance(error.value, vpp.ViSPException) and isinstance(error.value, RuntimeError)
        assert np.array_equal(rig.getFundamentalMatrix(), F)  # a failed estimate leaves the rig as it was
    with pytest.raises(vpp.ProjectiveException, match="focal plane"):
        rig.project(np.array([0.0, 0.0, 0.0, 1.0]))  # the left camera's centre
    with pytest.raises(ValueError, match=r"\(N, 2\) array of \(u, v\) pixels"):
        rig.estimate(np.zeros((10, 3)), np.zeros((10, 3)))
    with pytest.raises(TypeError):
        rig.estimate("left", "right")


def test_displacements_and_joint_groups():
    rng = np.random.default_rng(11)
    G = np.eye(4) + 0.3 * rng.normal(size=(4, 4))  # a projective frame (H_PE)
    axis = rng.normal(size=3)
    axis /= np.linalg.norm(axis)
    twist = np.zeros((4, 4))  # a unit rotation twist about axis through the point p
    twist[:3, :3] = [[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]]
    twist[:3, 3] = -twist[:3, :3] @ np.array([0.1, -0.2, 0.3])
    Hhat = np.linalg.inv(G) @ twist @ G
    theta = 0.7
    rotation = vpp.ProjectiveRotation(Hhat)
    H = rotation.exp(theta)
    assert H.classify(1e-6) == vpp.ProjectiveDisplacement.ROTATION
    assert abs(H.getRotationAngle() - theta) < 1e-9
    M0 = rng.normal(size=(8, 4))
    M1 = np.array([H.act(M) for M in M0])
    estimated = vpp.ProjectiveDisplacement.estimate(M0, -2.0 * M1)  # any scale per point set
    assert np.abs(estimated.matrix() - H.matrix()).max() < 1e-9
    assert np.abs(H.log() - theta * Hhat).max() < 1e-9
    assert np.abs(vpp.ProjectiveDisplacement.exp(H.log()).matrix() - H.matrix()).max() < 1e-12
    assert np.abs((H * H.inverse()).matrix() - np.eye(4)).max() < 1e-12
    assert np.abs(vpp.ProjectiveRotation.log(H, theta).generator() - Hhat).max() < 1e-9
    assert vpp.ProjectiveRotation.generatorResidual(Hhat) < 1e-12
    h = 1e-6  # dexp against central differences
    numeric = (rotation.exp(theta + h).matrix() - rotation.exp(theta - h).matrix()) / (2 * h)
    assert np.abs(rotation.dexp(theta) - numeric).max() < 1e-7 * np.abs(numeric).max()
    slide = np.zeros((4, 4))
    slide[:3, 3] = axis
    T = vpp.ProjectiveTranslation(np.linalg.inv(G) @ slide @ G)
    assert T.exp(0.05).classify(1e-6) == vpp.ProjectiveDisplacement.TRANSLATION
    with pytest.raises(vpp.ProjectiveException) as error:
        vpp.ProjectiveRotation(np.linalg.inv(G) @ slide @ G)  # not a p-rotation's generator
    assert error.value.code == vpp.ProjectiveException.invalidValueError and "Hhat^3 = -Hhat" in str(error.value)
    with pytest.raises(vpp.ProjectiveException) as error:
        vpp.ProjectiveDisplacement(np.eye(3))
    assert error.value.code == vpp.ProjectiveException.dimensionError
