"""Hostile arguments through Python: each an InputError naming the argument, and what is
accepted is what the command accepts."""

from pathlib import Path

import numpy as np
import pytest

import stiffid
from conftest import REPO

MILLING = REPO / "examples" / "milling"
TRACK = {"name": "track", "role": "carrier", "direction": [0, 1, 0], "limits_mm": [0, 4000]}


def test_external_axes_take_numpy_arrays_and_refuse_nan_naming_the_argument():
    robot = stiffid.Robot.preset("kuka-kr210-robond")
    as_arrays = dict(TRACK, direction=np.array([0.0, 1.0, 0.0]), limits_mm=np.array([0, 4000]))
    assert robot.with_external_axes([as_arrays]).external_axes == robot.with_external_axes(
        [TRACK]
    ).external_axes
    with pytest.raises(stiffid.InputError, match=r"^axes: expected tables of names, numbers"):
        robot.with_external_axes([dict(TRACK, direction=np.array([0.0, np.nan, 1.0]))])
    with pytest.raises(stiffid.InputError, match=r"^axes: .*\{1, 2\}|^axes: .*set"):
        robot.with_external_axes([dict(TRACK, direction={1, 2})])


def test_external_axes_of_the_wrong_shape_name_the_argument_and_the_table():
    robot = stiffid.Robot.preset("kuka-kr210-robond")
    with pytest.raises(stiffid.InputError, match=r'^axes: external_axis\[2\]: invalid type: string "x"'):
        robot.with_external_axes([TRACK, dict(TRACK, name="t2", direction="x")])
    with pytest.raises(stiffid.InputError, match=r"^axes: external_axis\[1\]: missing field `role`$"):
        robot.with_external_axes([{k: v for k, v in TRACK.items() if k != "role"}])
    with pytest.raises(stiffid.InputError, match=r"^axes: expected a list of tables, one per external axis"):
        robot.with_external_axes(TRACK)


def test_a_wrench_frame_with_a_program_is_refused_as_by_the_command():
    common = dict(program=MILLING / "pocket.nc", process=MILLING / "aluminium.toml", frame="tool")
    expected = r"^frame: only with path= .*process file's"
    with pytest.raises(stiffid.InputError, match=expected):
        stiffid.compensate(stiffid.Setup.from_file(MILLING / "fanuc-milling.toml"), stiffness=MILLING / "stiffness.json", **common)
    with pytest.raises(stiffid.InputError, match=expected):
        stiffid.place(MILLING / "fanuc-milling.toml", MILLING / "stiffness.json", region_mm=(500, 2000, -1500, 500), **common)


def test_a_negative_seed_of_place_names_the_argument():
    with pytest.raises(stiffid.InputError, match=r"^seed: -1 is negative"):
        stiffid.place(
            MILLING / "fanuc-milling.toml",
            MILLING / "stiffness.json",
            program=MILLING / "pocket.nc",
            process=MILLING / "aluminium.toml",
            region_mm=(500, 2000, -1500, 500),
            seed=-1,
        )


def test_program_settings_without_a_generated_program_are_refused_as_by_the_command(tmp_path):
    setup = stiffid.Setup.from_file(MILLING / "fanuc-milling.toml")
    common = dict(stiffness=MILLING / "stiffness.json", process=MILLING / "aluminium.toml")
    with pytest.raises(stiffid.InputError, match=r"^targets: only for a G-code program written as a robot program"):
        stiffid.compensate(setup, program=MILLING / "pocket.nc", targets="joint", **common)
    with pytest.raises(stiffid.InputError, match=r"^moves_per_file: only for a G-code program written as a robot program: a robot program is written back"):
        stiffid.compensate(setup, program=MILLING / "pocket.ls", moves_per_file=100, **common)
    with pytest.raises(stiffid.InputError, match=r"^max_tcp_speed_mm_s: only for a G-code program written as a robot program"):
        stiffid.compensate(setup, program=MILLING / "pocket.nc", max_tcp_speed_mm_s=100.0, **common)


def test_a_bool_is_no_number(paper, tmp_path):
    with pytest.raises(stiffid.InputError, match=r"^tolerance_mm: True is a bool: expected a number"):
        stiffid.calibrate(paper, tmp_path / "readings.csv", tolerance_mm=True, tolerance_deg=0.1)
    with pytest.raises(stiffid.InputError, match=r"^tolerance_deg: expected a number, got <class 'str'>"):
        stiffid.calibrate(paper, tmp_path / "readings.csv", tolerance_mm=0.1, tolerance_deg="0.1")
    with pytest.raises(stiffid.InputError, match=r"^payload_kg: False is a bool"):
        stiffid.setups_new(tmp_path / "robot.urdf", payload_kg=False)


def test_rows_of_numbers_refuse_text_and_bools_naming_the_element(paper):
    with pytest.raises(stiffid.InputError, match=r"^stations: expected rows of numbers"):
        paper.select(stations="1000")
    track = stiffid.Setup.from_file(REPO / "examples" / "track" / "track-cell.toml")
    with pytest.raises(stiffid.InputError, match=r"^stations\[0\]\[0\]: True is a bool"):
        track.select(stations=[[True, 0, 0]])
    with pytest.raises(stiffid.InputError, match=r"^external\[1\]\[2\]: expected a number"):
        stiffid.plan(track, [[0, 0, 0, 0, 0, 0], [0, 10, 0, 0, 0, 0]], external=[[0, 0, 0], [0, 0, "x"]])


@pytest.mark.parametrize(
    "name, call",
    [
        ("characteristic_length_mm", lambda r, s: r.kinematics([0, 0, 0, 0, 0, 0], characteristic_length_mm=True)),
        ("characteristic_length_mm", lambda r, s: r.dexterity([0, 0, 0, 0, 0, 0], characteristic_length_mm=False)),
        ("position_tolerance_mm", lambda r, s: r.inverse_kinematics(np.eye(4), [0] * 6, position_tolerance_mm=True)),
        ("target_pct", lambda r, s: s.select(target_pct=True)),
        ("margin_mm", lambda r, s: s.select(margin_mm=True)),
        ("level", lambda r, s: stiffid.predict(s, [0, 0, 0, 0, 0, 0], [0, 0, 100, 0, 0, 0], level=True)),
        ("target_pct", lambda r, s: stiffid.plan(s, [[0, 0, 0, 0, 0, 0]] * 2, target_pct=True)),
        ("peak_resolution_deg", lambda r, s: stiffid.process_force(MILLING / "aluminium.toml", peak_resolution_deg=True)),
    ],
)
def test_a_bool_is_no_number_for_any_optional_number(paper, name, call):
    robot = stiffid.Robot.preset("kuka-kr210-robond")
    with pytest.raises(stiffid.InputError, match=rf"^{name}: (True|False) is a bool: expected a number"):
        call(robot, paper)


def _pocket(**options):
    common = dict(program=MILLING / "pocket.nc", process=MILLING / "aluminium.toml")
    return stiffid.compensate(
        stiffid.Setup.from_file(MILLING / "fanuc-milling.toml"), MILLING / "stiffness.json", **common, **options
    )


@pytest.mark.parametrize(
    "name, expected, call",
    [
        ("level", "a number", lambda r, s: _pocket(level=True)),
        ("moves_per_file", "a whole number", lambda r, s: _pocket(moves_per_file=False)),
        ("seed", "a whole number", lambda r, s: stiffid.simulate(s, [[0, 0, 0, 0, 0, 0]] * 7, runs=10, seed=True)),
        ("runs", "a whole number", lambda r, s: stiffid.reproduce(runs=True)),
        ("seed", "a whole number", lambda r, s: s.select(seed=True)),
        ("n", "a whole number", lambda r, s: s.random_group(True)),
        ("restarts", "a whole number", lambda r, s: r.inverse_kinematics(np.eye(4), [0] * 6, restarts=True)),
        ("count", "a whole number", lambda r, s: stiffid.register(s, count=True)),
    ],
)
def test_a_bool_is_no_number_for_any_number_argument(paper, name, expected, call):
    robot = stiffid.Robot.preset("kuka-kr210-robond")
    with pytest.raises(stiffid.InputError, match=rf"^{name}: (True|False) is a bool: expected {expected}$"):
        call(robot, paper)


def test_every_argument_of_the_wrong_type_is_an_input_error_naming_it(paper, tmp_path):
    with pytest.raises(stiffid.InputError, match=r"^update: .int. object is not an instance of .bool."):
        stiffid.calibrate(paper, tmp_path / "readings.csv", update=1)
    with pytest.raises(stiffid.InputError, match=r"^setup: .*Setup"):
        stiffid.plan("paper", [[0, 0, 0, 0, 0, 0]])
    with pytest.raises(stiffid.InputError, match=r"^distinct: "):
        paper.select(distinct="yes")
    with pytest.raises(stiffid.InputError, match=r"^name: "):
        stiffid.Robot.preset(7)


@pytest.mark.parametrize(
    "name, call",
    [
        ("max_error_mm", lambda s: _pocket(max_error_mm=10**400)),
        ("level", lambda s: stiffid.calibrate(s, MILLING / "path.csv", level=10**400)),
    ],
)
def test_an_int_beyond_a_float_is_refused_as_too_large_not_as_no_number(paper, name, call):
    """An int too large for a float is a number: the refusal names the argument and says it is too
    large, not that an int is no number."""
    with pytest.raises(stiffid.InputError, match=rf"^{name}: an int too large for a float \(at most about 1.8e308\): expected a number$"):
        call(paper)


@pytest.mark.parametrize("given", ["/tmp", b"/tmp", Path("/tmp")])
@pytest.mark.parametrize(
    "call",
    [
        lambda p: stiffid.Setup.from_file(MILLING / "kuka-milling.toml", package_paths=p),
        lambda p: stiffid.Setup.from_toml((MILLING / "kuka-milling.toml").read_text(), package_paths=p),
        lambda p: stiffid.Robot.from_file(MILLING / "kuka-milling.toml", package_paths=p),
    ],
)
def test_one_path_for_package_paths_is_refused_saying_to_give_a_list(given, call):
    """``package_paths`` is a list of directories: one path given alone is refused naming the
    argument and saying to give a list (not "Can't extract `str` to `Vec`")."""
    with pytest.raises(stiffid.InputError, match=r"^package_paths: .* is one path: expected a list of directories \(package_paths=\["):
        call(given)


def test_a_document_that_holds_itself_is_refused_not_a_crash():
    setup = stiffid.Setup.builtin("zhang2021-comau-nj165")
    looped = {"kind": "plan"}
    looped["self"] = looped
    with pytest.raises(stiffid.InputError, match=r"^document: nested more than 64 deep"):
        stiffid.figures(looped, setup)
    deep = {"kind": "plan"}
    for _ in range(10000):
        deep = {"kind": "plan", "a": deep}
    with pytest.raises(stiffid.InputError, match=r"^document: nested more than 64 deep"):
        stiffid.figures(deep, setup)


def test_every_seed_the_command_takes_python_takes():
    setup = stiffid.Setup.builtin("zhang2021-comau-nj165")
    top = 2**64 - 1
    assert setup.random_group(6, top).shape == (6, 6)
    assert not np.array_equal(setup.random_group(6, top), setup.random_group(6, top - 1))
    with pytest.raises(stiffid.InputError, match=r"^seed: 18446744073709551616 is more than"):
        setup.random_group(6, 2**64)
    with pytest.raises(stiffid.InputError, match=r"^seed: -1 is negative"):
        setup.random_group(6, -1)


def test_a_paths_compensation_refuses_the_options_of_a_program():
    setup = stiffid.Setup.from_file(MILLING / "fanuc-milling.toml")
    common = dict(path=MILLING / "path.csv", stiffness=MILLING / "stiffness.json")
    for key, given in [("targets", "joint"), ("program_name", "X"), ("chord_tolerance_mm", 0.5), ("moves_per_file", 500)]:
        with pytest.raises(stiffid.InputError, match=rf"^{key}: only with program="):
            stiffid.compensate(setup, **common, **{key: given})


def test_a_plans_target_outside_its_range_is_refused():
    setup = stiffid.Setup.builtin("zhang2021-comau-nj165")
    group = setup.random_group(6, 1)
    for bad in [float("nan"), float("inf"), 0.0, -3.0]:
        with pytest.raises(stiffid.InputError, match=r"^target_pct: "):
            stiffid.plan(setup, group, target_pct=bad)


def test_the_cartesian_stiffness_at_a_wrist_singularity_is_nan():
    setup = stiffid.Setup.builtin("fanuc-r2000ic-165f")
    assert np.isnan(stiffid.cartesian_stiffness(setup, [0, 10, -10, 0, 0, 0])).all()
    assert np.isfinite(stiffid.cartesian_stiffness(setup, [0, 10, -10, 0, 3, 0])).all()


def test_a_plan_is_drawn_with_its_own_robot_and_its_postures():
    paper = stiffid.Setup.builtin("zhang2021-comau-nj165")
    fanuc = stiffid.Setup.builtin("fanuc-r2000ic-165f")
    plan = stiffid.plan(paper, paper.random_group(6, 1))
    assert len(stiffid.figures(plan, paper)) == 7
    with pytest.raises(stiffid.InputError, match=r"^setup: the plan is of the robot 'COMAU"):
        stiffid.figures(plan, fanuc)
    with pytest.raises(stiffid.InputError, match=r"^setup: the plan is of the robot 'COMAU"):
        stiffid.scene(fanuc, document=plan)
    with pytest.raises(stiffid.InputError, match=r"^document: a plan without postures"):
        stiffid.figures({"kind": "plan"}, paper)
