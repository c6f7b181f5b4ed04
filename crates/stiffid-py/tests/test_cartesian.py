"""The Cartesian compliance and stiffness of a tool point: J K^-1 J^T built in NumPy, with and
without virtual springs, and the deflection it predicts."""

import numpy as np
import pytest

import stiffid

Q = [[10, 20, -90, 30, 20, 10], [-35, -12, -120, 70, -40, 100]]

# Two virtual springs in the base (link 0) frame, whose Jacobian columns are known by hand: a
# translation along base x, [1, 0, 0, 0, 0, 0], and a rotation about base z through (100, 0, 0) mm,
# [z x (p - o); z].
SPRINGS = """
[[model.spring]]
name = "base_tx"
kind = "translation"
link = 0
axis = [1, 0, 0]
nominal_stiffness_n_per_mm = 20000.0

[[model.spring]]
name = "base_rz"
kind = "rotation"
link = 0
axis = [0, 0, 1]
point_mm = [100, 0, 0]
nominal_stiffness_nm_per_rad = 5000000.0
"""


def point_position_m(robot, q, point_mm):
    pose = robot.flange_pose(q)
    return (pose[:3, :3] @ np.asarray(point_mm, float) + pose[:3, 3]) * 1e-3


def test_drives_alone_is_j_k_inverse_j_transpose(paper):
    point = paper.loading_point_mm
    k = paper.nominal_stiffness_nm_per_rad
    c = stiffid.cartesian_compliance(paper, Q)
    assert c.shape == (2, 6, 6)
    for i, q in enumerate(Q):
        j = paper.robot.jacobian(q, point_mm=point, coordinates=paper.springs)
        expected = j @ np.diag(1 / k) @ j.T
        np.testing.assert_allclose(c[i], expected, rtol=1e-12, atol=1e-12 * np.abs(expected).max())
        np.testing.assert_array_equal(stiffid.cartesian_compliance(paper, q), c[i])
    # K_x = C_x^-1, computed from J^-1 (not by inverting C_x).
    kx = stiffid.cartesian_stiffness(paper, Q[0])
    np.testing.assert_allclose(kx @ c[0], np.eye(6), atol=1e-8)


def test_virtual_springs_add_their_columns(paper):
    setup = paper.with_model(SPRINGS)
    q, point = Q[0], [80, 80, 260]
    k = np.concatenate([paper.nominal_stiffness_nm_per_rad, [2e4, 5e6]])
    c = stiffid.cartesian_compliance(setup, q, point_mm=point, stiffness_nm_per_rad=k)
    j = paper.robot.jacobian(q, point_mm=point, coordinates=paper.springs)
    p = point_position_m(paper.robot, q, point)
    j_tx = np.array([1.0, 0, 0, 0, 0, 0])
    z, o = np.array([0.0, 0, 1]), np.array([0.1, 0, 0])
    j_rz = np.concatenate([np.cross(z, p - o), z])
    expected = j @ np.diag(1 / k[:6]) @ j.T
    expected += np.outer(j_tx, j_tx) / (2e4 * 1e3) + np.outer(j_rz, j_rz) / 5e6
    np.testing.assert_allclose(c, expected, rtol=1e-10, atol=1e-12 * np.abs(expected).max())
    # The nominal stiffness of the setup's model is the default; the springs matter.
    np.testing.assert_array_equal(stiffid.cartesian_compliance(setup, q, point_mm=point), c)
    drives = stiffid.cartesian_compliance(paper, q, point_mm=point)
    assert np.abs(c - drives).max() > 0.01 * np.abs(drives).max()
    kx = stiffid.cartesian_stiffness(setup, q, point_mm=point)
    np.testing.assert_allclose(kx @ c, np.eye(6), atol=1e-7)


def test_the_compliance_predicts_the_deflection(paper):
    """[dp; dphi] = C_x W: the same displacement as `deflection` under a wrench at the point."""
    w = np.array([300.0, -200, 500, 20, -10, 30])
    c = stiffid.cartesian_compliance(paper, Q[1], point_mm=paper.tcp_mm)
    d = stiffid.deflection(paper, Q[1], w, at_mm=paper.tcp_mm)[0]
    np.testing.assert_allclose((c @ w)[:3] * 1e3, d["tcp_deflection_mm"], rtol=1e-10)
    np.testing.assert_allclose((c @ w)[3:] * 1e3, d["tcp_rotation_mrad"], rtol=1e-10)


def test_a_wrist_singularity_has_no_stiffness(paper):
    c = stiffid.cartesian_compliance(paper, [0, 0, -90, 0, 0, 0])
    assert np.linalg.matrix_rank(c) < 6
    assert np.isnan(stiffid.cartesian_stiffness(paper, [0, 0, -90, 0, 0, 0])).all()


def test_bad_arguments(paper):
    with pytest.raises(stiffid.InputError, match=r"stiffness_nm_per_rad: expected an array of shape \(6,\)"):
        stiffid.cartesian_compliance(paper, Q[0], stiffness_nm_per_rad=[1e6] * 5)
    with pytest.raises(stiffid.InputError, match=r"point_mm"):
        stiffid.cartesian_compliance(paper, Q[0], point_mm=[1, 2])
    with pytest.raises(stiffid.InputError, match=r"q_deg: posture 0, q5_deg = 130"):
        stiffid.cartesian_stiffness(paper, [0, 0, -90, 0, 130, 0])
