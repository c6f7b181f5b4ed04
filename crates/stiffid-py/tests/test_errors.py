"""stiffid.Error (a ValueError) and its subclasses, one per kind of failure."""

import numpy as np
import pytest

import stiffid


def test_the_hierarchy():
    assert issubclass(stiffid.Error, ValueError)
    for kind in (stiffid.InputError, stiffid.InfeasibleError, stiffid.UnidentifiableError, stiffid.GateError):
        assert issubclass(kind, stiffid.Error)
    assert not issubclass(stiffid.InfeasibleError, stiffid.InputError)
    # A failed gate is no bad input (the command's exit code 1, not 2).
    assert not issubclass(stiffid.GateError, stiffid.InputError)


def test_bad_input_is_an_input_error(paper):
    with pytest.raises(stiffid.InputError, match=r"unknown setup 'nope'"):
        stiffid.Setup.builtin("nope")
    with pytest.raises(stiffid.InputError, match=r"criterion"):
        paper.select(criterion="nope")
    with pytest.raises(stiffid.InputError, match=r"q_deg\[0, 2\] = NaN"):
        paper.robot.flange_pose([0, 0, np.nan, 0, 0, 0])


def test_an_impossible_design_is_infeasible(paper):
    """A floor at the height of the robot's shoulder (700 mm): no posture within the bounds is
    feasible."""
    from test_cell import PAPER_TOML

    cell = stiffid.Setup.from_toml(PAPER_TOML + "\n[cell]\nfloor_z_mm = 700.0\nclearance_mm = 50.0\n", "cell.toml")
    with pytest.raises(stiffid.InfeasibleError, match="no feasible group found: the floor check failed"):
        cell.select(n=6, starts=2, screen_steps=5, polished=1)


def test_an_unreachable_pose_is_infeasible(paper):
    pose = np.eye(4)
    pose[:3, 3] = [10000, 0, 0]
    with pytest.raises(stiffid.InfeasibleError, match="mm"):
        paper.robot.inverse_kinematics(pose, [0, 0, -90, 0, 30, 0], restarts=1)


def test_data_that_cannot_identify_is_unidentifiable(paper):
    """One posture under a vertical force: no torque about joint 1's vertical axis."""
    q = np.array([[10, 20, -90, 30, 20, 10]])
    with pytest.raises(stiffid.UnidentifiableError, match="joint 1 cannot be identified"):
        stiffid.identify(paper, q_deg=q, wrench=[[0, 0, -500.0]], displacement_mm=np.ones((4, 3)))


def test_a_model_no_group_can_separate_is_unidentifiable(paper):
    """A rotation spring about the base z axis through the origin is joint 1's own axis: no
    group of postures separates the two; the search's group is refused as unidentifiable."""
    setup = paper.with_model(
        '[[model.spring]]\nname = "base_rz"\nkind = "rotation"\nlink = 0\naxis = [0, 0, 1]\n'
        "nominal_stiffness_nm_per_rad = 5e6\n"
    )
    group = paper.random_group(6, 1)
    assert setup.evaluate(group)["unidentifiable"] == ["0.71 base_rz - 0.71 k1"]
    with pytest.raises(stiffid.UnidentifiableError, match=r"the group cannot separate 0.71 base_rz - 0.71 k1"):
        setup.select(method="local", start=group, max_evals=20)


@pytest.mark.parametrize(
    "name, call",
    [
        ("n", lambda s: s.select(n=-1)),
        ("seed", lambda s: s.select(seed=-1)),
        ("starts", lambda s: s.select(starts=-2)),
        ("max_evals", lambda s: s.select(max_evals=-5)),
        ("n", lambda s: s.random_group(n=-6)),
        ("restarts", lambda s: s.robot.inverse_kinematics(s.robot.flange_pose([0, 0, -90, 0, 30, 0]),
                                                          [0, 0, -90, 0, 30, 0], restarts=-1)),
        ("max_iterations", lambda s: s.robot.inverse_kinematics(s.robot.flange_pose([0, 0, -90, 0, 30, 0]),
                                                                [0, 0, -90, 0, 30, 0], max_iterations=-1)),
        ("runs", lambda s: stiffid.simulate(s, [s.random_group()], runs=-1)),
        ("seed", lambda s: stiffid.simulate(s, [s.random_group()], seed=-1)),
        ("trials", lambda s: stiffid.reproduce(s, trials=-1)),
        ("count", lambda s: stiffid.register(s, count=-3)),
        ("folds", lambda s: stiffid.identify(s, q_deg=np.zeros((6, 6)), wrench=np.zeros((6, 6)),
                                             displacement_mm=np.zeros((6, 3)), folds=-1)),
    ],
)
def test_a_negative_count_is_a_value_error_naming_the_argument(paper, name, call):
    with pytest.raises(stiffid.InputError, match=rf"^{name}: -\d+ is negative: expected a whole number, 0 or more$"):
        call(paper)




def test_an_argument_of_the_wrong_type_or_value_is_an_input_error_naming_it(paper):
    """Every argument given wrong, by type, value, position or name, is an ``InputError`` whose
    message begins with the argument's name (never Python's own ``TypeError`` or a Rust path)."""
    from conftest import REPO

    milling = stiffid.Setup.from_file(REPO / "examples" / "milling" / "fanuc-milling.toml")
    path = REPO / "examples" / "milling" / "path.csv"
    stiffness = REPO / "examples" / "milling" / "stiffness.json"
    cases = [
        (lambda: stiffid.identify(paper, 5), r"^measurements: expected the path of a measurements CSV file"),
        (lambda: stiffid.compensate(milling, path, stiffness, level=95), r"^level: 95: expected a level in \[0\.5, 0\.999\]"),
        (lambda: stiffid.compensate(milling, stiffness), r"^stiffness: missing: .*the second positional argument is path"),
        (lambda: stiffid.compensate(milling, path, stiffness, confidence=0.95), r"^confidence: not an argument of compensate\(\)"),
        (lambda: stiffid.compensate(milling, path, stiffness, path=path), r"^path: given twice"),
        (lambda: stiffid.identify(), r"^setup: missing: identify\(\) needs it"),
        (lambda: stiffid.identify(paper, None, None), r"^identify: takes from 1 to 2 positional arguments, 3 given"),
    ]
    for call, message in cases:
        with pytest.raises(stiffid.InputError, match=message):
            call()


def test_a_missing_file_is_an_input_error_naming_the_argument_and_a_file_not_found_error(tmp_path):
    from test_compensate import PATH, SETUP, STIFFNESS

    setup, missing = stiffid.Setup.from_file(SETUP), tmp_path / "nope.json"
    for call, name in [
        (lambda: stiffid.compensate(setup, PATH, missing), "stiffness"),
        (lambda: stiffid.compensate(setup, tmp_path / "nope.csv", STIFFNESS), "path"),
        (lambda: stiffid.Setup.from_file(str(missing)), "path"),
    ]:
        with pytest.raises(stiffid.MissingFileError) as caught:
            call()
        error = caught.value
        assert isinstance(error, stiffid.InputError) and isinstance(error, FileNotFoundError)
        assert str(error).startswith(f"{name}: {tmp_path}"), str(error)
        assert error.filename.endswith(("nope.json", "nope.csv")) and error.errno == 2
    # `except FileNotFoundError` still catches it.
    try:
        stiffid.compensate(setup, PATH, missing)
    except FileNotFoundError as error:
        assert "stiffness: " in str(error)
