"""Robot kinematics: known flange positions, Jacobians against finite differences, shapes."""

import numpy as np
import pytest

import stiffid

COMAU = "comau-smart5-nj165-3.0"


@pytest.fixture(scope="module")
def robot():
    return stiffid.Robot.preset(COMAU)


# docs/model.md section 4: flange positions (mm) of the COMAU SMART5 NJ 165-3.0, checked against
# independent public kinematics.
KNOWN = [
    ([0, 0, -90, 0, 0, 0], [2074.0, 0.0, 2255.0]),
    ([0, 10, -90, 0, 0, 0], [2278.04, 0.0, 2237.15]),
    ([0, 0, -80, 0, 0, 0], [2005.16, 0.0, 2541.89]),
    ([10, 20, -90, 30, 20, 10], [2417.77, -466.26, 2116.01]),
]


def test_flange_positions_match_the_reference(robot):
    for q, p in KNOWN:
        pose = robot.flange_pose(q)
        assert pose.shape == (4, 4)
        np.testing.assert_allclose(pose[:3, 3], p, atol=0.01)
        np.testing.assert_allclose(pose[3], [0, 0, 0, 1])
        r = pose[:3, :3]
        np.testing.assert_allclose(r @ r.T, np.eye(3), atol=1e-12)


def test_vectorised_equals_one_by_one(robot):
    q = np.array([k[0] for k in KNOWN], dtype=float)
    poses = robot.flange_pose(q)
    jacobians = robot.jacobian(q, point_mm=[150, 0, 200])
    dexterity = robot.dexterity(q)
    assert poses.shape == (4, 4, 4) and jacobians.shape == (4, 6, 6) and dexterity.shape == (4,)
    for i, qi in enumerate(q):
        np.testing.assert_array_equal(poses[i], robot.flange_pose(qi))
        np.testing.assert_array_equal(jacobians[i], robot.jacobian(qi, point_mm=[150, 0, 200]))
        assert dexterity[i] == robot.dexterity(qi)


def point_position(robot, q_deg, point_mm):
    pose = robot.flange_pose(q_deg)
    return (pose[:3, :3] @ np.asarray(point_mm) + pose[:3, 3]) * 1e-3  # m


def rotation(robot, q_deg):
    return robot.flange_pose(q_deg)[:3, :3]


@pytest.mark.parametrize("q", [[10, 20, -90, 30, 20, 10], [-35, -12, -120, 70, -40, 100]])
def test_jacobian_matches_central_differences(robot, q):
    """Column j: d(point)/dq_j (m/rad) and the angular velocity of the flange per rad of q_j."""
    point = [80, 80, 260]
    jac = robot.jacobian(q, point_mm=point)
    h = 1e-6  # rad
    for j in range(6):
        dq = np.zeros(6)
        dq[j] = np.degrees(h)
        qp, qm = np.add(q, dq), np.subtract(q, dq)
        v = (point_position(robot, qp, point) - point_position(robot, qm, point)) / (2 * h)
        dr = (rotation(robot, qp) - rotation(robot, qm)) / (2 * h)
        w_hat = dr @ rotation(robot, q).T
        w = [w_hat[2, 1], w_hat[0, 2], w_hat[1, 0]]
        np.testing.assert_allclose(jac[:3, j], v, atol=1e-7)
        np.testing.assert_allclose(jac[3:, j], w, atol=1e-7)


def test_axis_jacobian_is_kinematic_times_axis_map(robot):
    """J_q = J_theta M: for the COMAU, theta = [-q1, q2 - 90, -q3 - q2 - 90, -q4, q5, 180 - q6]."""
    q = [10, 20, -90, 30, 20, 10]
    m = np.diag([-1.0, 1, -1, -1, 1, -1])
    m[2, 1] = -1
    ja = robot.jacobian(q, coordinates="axis")
    jk = robot.jacobian(q, coordinates="kinematic")
    np.testing.assert_allclose(ja, jk @ m, atol=1e-12)


def test_dexterity_is_equation_21(robot):
    q = [10, 20, -90, 30, 20, 10]
    length = 1.2
    jn = robot.jacobian(q, point_mm=[80, 80, 260]).copy()
    jn[:3] /= length
    a = jn @ jn.T
    expected = np.sqrt(np.trace(a) * np.trace(np.linalg.inv(a))) / 6
    k = robot.dexterity(q, point_mm=[80, 80, 260], characteristic_length_mm=1200)
    assert k == pytest.approx(expected, rel=1e-10)
    assert k >= 1


def test_without_a_length_the_robots_own_is_used(robot):
    q, point = [10, 20, -90, 30, 20, 10], [80, 80, 260]
    length = robot.characteristic_length_mm(point_mm=point)
    # The paper's COMAU and tool: about the paper's 1.2 m, and not a copy of it.
    assert 1000 < length < 1400 and length != 1200
    assert robot.dexterity(q, point_mm=point) == robot.dexterity(
        q, point_mm=point, characteristic_length_mm=length
    )
    assert robot.dexterity(q, point_mm=point) != robot.dexterity(
        q, point_mm=point, characteristic_length_mm=1200
    )


def test_wrist_singularity_is_infinite(robot):
    assert robot.dexterity([0, 0, -90, 0, 0, 0]) == float("inf")


def test_limits_and_names(robot):
    assert robot.name == "COMAU SMART5 NJ 165-3.0"
    assert COMAU in stiffid.Robot.presets()
    assert robot.lower_limit_deg.shape == (6,) and np.all(robot.lower_limit_deg < robot.upper_limit_deg)


@pytest.mark.parametrize(
    "q, message",
    [
        (np.zeros(5), r"q_deg: expected an array of shape \(6,\) or \(n, 6\), got shape \(5,\)"),
        (np.zeros((2, 7)), r"got shape \(2, 7\)"),
        (np.zeros((2, 2, 6)), r"got shape \(2, 2, 6\)"),
        ([0, 0, float("nan"), 0, 0, 0], r"q_deg\[0, 2\] = NaN is not a finite number"),
        ([0, 0, -90, 0, 130, 0], r"q_deg: posture 0, q5_deg = 130 is outside the joint limits \[-125.0, 125.0\]"),
        ("abc", r"q_deg: expected an array"),
    ],
)
def test_bad_postures_are_refused(robot, q, message):
    with pytest.raises(ValueError, match=message):
        robot.flange_pose(q)


def test_bad_options_are_refused(robot):
    with pytest.raises(ValueError, match="coordinates: unknown value 'joint' .known: axis, kinematic."):
        robot.jacobian([0, 0, -90, 0, 30, 0], coordinates="joint")
    with pytest.raises(ValueError, match="point_mm"):
        robot.jacobian([0, 0, -90, 0, 30, 0], point_mm=[1, 2])
    with pytest.raises(ValueError, match="characteristic_length_mm"):
        robot.dexterity([0, 0, -90, 0, 30, 0], characteristic_length_mm=0)


def test_unknown_preset_names_the_known_ones():
    with pytest.raises(ValueError, match=r"unknown robot preset 'nope' \(known: .*comau-smart5-nj165-3.0"):
        stiffid.Robot.preset("nope")


def test_robot_file_errors(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.urdf: no such file"):
        stiffid.Robot.from_file(tmp_path / "missing.urdf")
    bad = tmp_path / "robot.toml"
    bad.write_text("name = 3\n")
    with pytest.raises(ValueError, match="robot.toml"):
        stiffid.Robot.from_file(bad)


def test_input_files_have_the_commands_limits(robot, tmp_path):
    with pytest.raises(ValueError, match=r"^/dev/zero: is a device, not a regular file; give a file$"):
        robot.read_postures("/dev/zero")
    with pytest.raises(ValueError, match=r"is a directory, expected a file"):
        stiffid.Setup.from_file(tmp_path)
    (tmp_path / "bin.csv").write_bytes(b"posture\xff\xfe")
    with pytest.raises(ValueError, match=r"bin.csv: not UTF-8 text \(invalid byte 0xFF at offset 7, line 1, column 8\); Latin-1"):
        robot.read_postures(tmp_path / "bin.csv")


def test_postures_file_round_trip(robot, tmp_path):
    from conftest import write_postures

    q = np.array([k[0] for k in KNOWN], dtype=float)
    np.testing.assert_allclose(robot.read_postures(write_postures(tmp_path / "p.csv", q)), q, atol=1e-12)
    bad = tmp_path / "bad.csv"
    bad.write_text("posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg\n1,0,0,-90,0,0,x\n")
    with pytest.raises(ValueError, match="bad.csv: line 2"):
        robot.read_postures(bad)


def tool_pose(robot, q, point_mm):
    """The pose inverse_kinematics reaches: the point's position (mm) and the flange's rotation."""
    pose = robot.flange_pose(q).copy()
    pose[:3, 3] += pose[:3, :3] @ np.asarray(point_mm, float)
    return pose


@pytest.mark.parametrize("point", [None, [150, 0, 200]])
def test_inverse_kinematics_round_trip(robot, point):
    """flange_pose of the solution is the target, from a start 5 deg away on every axis."""
    q = np.array([10, 20, -90, 30, 20, 10], float)
    target = tool_pose(robot, q, point or [0, 0, 0])
    kwargs = {} if point is None else dict(point_mm=point)
    s = robot.inverse_kinematics(target, q + 5, **kwargs)
    assert s["q_deg"].shape == (6,) and s["iterations"] >= 1
    np.testing.assert_allclose(s["q_deg"], q, atol=1e-8)
    np.testing.assert_allclose(tool_pose(robot, s["q_deg"], point or [0, 0, 0]), target, atol=1e-7)
    assert s["position_error_mm"] <= 1e-7 and s["rotation_error_deg"] <= np.degrees(1e-10)


def test_inverse_kinematics_along_a_path_stays_on_one_branch(robot):
    qs = np.array([[10, 20, -90, 30, 20, 10 + i] for i in range(5)], float)
    s = robot.inverse_kinematics(robot.flange_pose(qs), qs[0], restarts=0)
    assert s["q_deg"].shape == (5, 6) and s["iterations"].shape == (5,)
    np.testing.assert_allclose(s["q_deg"], qs, atol=1e-8)


def test_inverse_kinematics_of_an_unreachable_pose(robot):
    target = robot.flange_pose([0, 0, -90, 0, 30, 0]).copy()
    target[:3, 3] = [9000, 0, 0]
    with pytest.raises(stiffid.InfeasibleError, match="the closest of 3 starts stopped at iteration-limit"):
        robot.inverse_kinematics(target, [0, 0, -90, 0, 30, 0], restarts=2)
    # One step from a reachable pose 10 deg away is cut short, and the message says so.
    near = robot.flange_pose([10, 10, -80, 10, 40, 10])
    with pytest.raises(stiffid.InfeasibleError, match=r"1 start stopped at iteration-limit.*max_iterations"):
        robot.inverse_kinematics(near, [0, 0, -90, 0, 30, 0], restarts=0, max_iterations=1)


def test_inverse_kinematics_arguments(robot):
    q0 = [0, 0, -90, 0, 30, 0]
    pose = robot.flange_pose(q0)
    bent = pose.copy()
    bent[0, 0] = 2
    with pytest.raises(stiffid.InputError, match=r"pose_mm: the upper-left 3x3 block is not a rotation"):
        robot.inverse_kinematics(bent, q0)
    with pytest.raises(stiffid.InputError, match=r"pose_mm: expected an array of shape \(4, 4\)"):
        robot.inverse_kinematics(pose[:3], q0)
    with pytest.raises(stiffid.InputError, match=r"position_tolerance_mm"):
        robot.inverse_kinematics(pose, q0, position_tolerance_mm=0)
    with pytest.raises(stiffid.InputError, match=r"restarts"):
        robot.inverse_kinematics(pose, q0, restarts=10**6)
    with pytest.raises(stiffid.InputError, match=r"q0_deg: posture 0, q5_deg = 130"):
        robot.inverse_kinematics(pose, [0, 0, -90, 0, 130, 0])


@pytest.mark.parametrize(
    "flags, kwargs",
    [
        (["--characteristic-length-mm", "1234.5", "--point-mm", "100,-50,300"],
         dict(characteristic_length_mm=1234.5, point_mm=[100, -50, 300])),
        (["--coordinates", "kinematic"], dict(coordinates="kinematic")),
        # A wrist singularity: the dexterity is null in both.
        (["--characteristic-length-mm", "1200"], dict(characteristic_length_mm=1200)),
    ],
)
def test_the_kinematics_document_equals_the_command(robot, cli, flags, kwargs):
    q = [0, 0, -90, 0, 0, 0] if kwargs.get("characteristic_length_mm") == 1200 else [10, 20, -100, 30, 40, 50]
    theirs = cli("kinematics", "--robot", COMAU, "--q-deg", ",".join(map(str, q)), *flags, "--json")
    mine = robot.kinematics(q, **kwargs)
    assert mine == theirs
    assert mine["characteristic_length_source"] == ("derived" if "characteristic_length_mm" not in kwargs else "given")
    point, coordinates = kwargs.get("point_mm"), kwargs.get("coordinates", "axis")
    np.testing.assert_allclose(mine["jacobian"], robot.jacobian(q, point_mm=point, coordinates=coordinates), rtol=1e-12)
    length = kwargs.get("characteristic_length_mm")
    k = robot.dexterity(q, point_mm=point, characteristic_length_mm=length, coordinates=coordinates)
    assert mine["dexterity"] == (None if np.isinf(k) else pytest.approx(k, rel=1e-12))


# A robot on a track and a part on a positioner, from the example cell and built in code,
# against a NumPy model of the same cell written here.
TRACK_CELL = "examples/track/track-cell.toml"


def _rotation(axis, angle):
    """Rodrigues' formula."""
    axis = np.asarray(axis, float) / np.linalg.norm(axis)
    k = np.array([[0, -axis[2], axis[1]], [axis[2], 0, -axis[0]], [-axis[1], axis[0], 0]])
    return np.eye(3) + np.sin(angle) * k + (1 - np.cos(angle)) * k @ k


def _turn(point, axis, angle):
    t = np.eye(4)
    r = _rotation(axis, angle)
    t[:3, :3] = r
    t[:3, 3] = np.asarray(point) - r @ np.asarray(point)
    return t


def test_a_robot_on_a_track_with_a_positioner_matches_numpy():
    from pathlib import Path

    root = Path(__file__).resolve().parents[3]
    setup = stiffid.Setup.from_file(root / TRACK_CELL)
    robot = setup.robot
    axes = robot.external_axes
    assert [a["column"] for a in axes] == ["e1_mm", "e2_deg", "e3_deg"]
    assert [a["name"] for a in axes] == ["track", "tilt", "rotate"]
    fixed = stiffid.Robot.preset("kuka-kr210-robond")
    q = [10, 30, -20, 40, 60, -30]
    e = [2500.0, -30.0, 70.0]
    doc = robot.kinematics(q, point_mm=[0, 0, 250], external=e)
    flange = fixed.flange_pose(q)
    np.testing.assert_allclose(
        doc["flange_position_mm"], flange[:3, 3] + [2500.0, 0, 0], atol=1e-9
    )
    jacobian = np.array(doc["external_jacobian"])
    assert jacobian.shape == (6, 3)
    np.testing.assert_allclose(jacobian[:, 0], [1, 0, 0, 0, 0, 0], atol=1e-15)
    # The positioner's columns: minus the part's twist at the tool point, from NumPy matrices.
    x = np.array(doc["point_position_mm"]) * 1e-3
    p1, d1 = np.array([3.0, 1.8, 0.7]), np.array([1.0, 0, 0])
    p2, d2 = np.array([3.0, 1.8, 0.9]), np.array([0, 0, 1.0])
    a1 = np.radians(e[1])
    d2_now = _rotation(d1, a1) @ d2
    o2_now = (_turn(p1, d1, a1) @ np.append(p2, 1))[:3]
    for column, (d, o) in zip(jacobian[:, 1:].T, [(d1, p1), (d2_now, o2_now)]):
        np.testing.assert_allclose(column[:3], -np.cross(d, x - o), atol=1e-9)
        np.testing.assert_allclose(column[3:], -d, atol=1e-12)
    part = _turn(p1, d1, a1) @ _turn(p2, d2, np.radians(e[2]))
    part[:3, 3] += part[:3, :3] @ [3.0, 1.8, 0.9]
    # The example's [workpiece] reaches the document through --setup only: here the part's
    # frame is the positioner's own (identity at e = 0).
    np.testing.assert_allclose(
        doc["part_position_mm"],
        (_turn(p1, d1, a1) @ _turn(p2, d2, np.radians(e[2])))[:3, 3] * 1e3,
        atol=1e-9,
    )
    with pytest.raises(stiffid.InputError, match="e1_mm track"):
        robot.kinematics(q)
    with pytest.raises(stiffid.InputError, match="no external axes"):
        fixed.kinematics(q, external=[100.0])


def test_a_robot_on_a_track_built_in_code():
    robot = stiffid.Robot.preset("kuka-kr210-robond").with_external_axes(
        [{"name": "track", "role": "carrier", "direction": [0, 1, 0], "limits_mm": [0, 4000]}]
    )
    assert robot.external_axes[0]["limits"] == [0.0, 4000.0]
    q = [0, 30, 0, 0, 60, 0]
    moved = robot.kinematics(q, external=[1500])["flange_position_mm"]
    here = stiffid.Robot.preset("kuka-kr210-robond").flange_pose(q)[:3, 3]
    np.testing.assert_allclose(moved, here + [0, 1500, 0], atol=1e-9)
    with pytest.raises(stiffid.InputError, match=r"external_axis\[1\] \(track\).limits_mm"):
        stiffid.Robot.preset("kuka-kr210-robond").with_external_axes(
            [{"name": "track", "role": "carrier", "direction": [0, 1, 0]}]
        )
    assert robot.with_external_axes(None).external_axes == []
