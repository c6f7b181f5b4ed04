"""Feasibility in the cell: a posture known to hit the floor, the evaluate document's checks,
and a URDF robot's own meshes through package paths."""

import numpy as np
import pytest

import stiffid
from conftest import REPO, plain, write_postures

PAPER_TOML = (REPO / "crates" / "stiffid-core" / "setups" / "zhang2021-comau-nj165.toml").read_text()
FLOOR = "\n[cell]\nfloor_z_mm = 0.0\nclearance_mm = 50.0\n"
# Upper arm tilted 40 deg forward, forearm pointing 100 deg down: the tool is in the floor.
IN_THE_FLOOR = [0, 40, -170, 0, 0, 0]
UPRIGHT = [0, 0, -90, 0, 30, 0]


@pytest.fixture(scope="module")
def cell():
    return stiffid.Setup.from_toml(PAPER_TOML + FLOOR, "cell.toml")


def test_a_posture_in_the_floor_fails_the_floor_check(cell):
    down, up = cell.feasibility([IN_THE_FLOOR, UPRIGHT])
    assert down["posture"] == 1 and not down["feasible"]
    floor = [v for v in down["violations"] if v["check"] == "floor"]
    assert floor and floor[0]["margin_mm"] < 0 and "floor" in floor[0]["between"]
    assert up == dict(up, posture=2, feasible=True, violations=[]) and up["min_clearance_mm"] > 50
    assert cell.feasibility(UPRIGHT) == [dict(up, posture=1)]


def test_feasibility_is_the_evaluate_documents(cell, cli, tmp_path):
    """The same checks as `Setup.evaluate` and `stiffid evaluate --json`."""
    setup = tmp_path / "cell.toml"
    setup.write_text(PAPER_TOML + FLOOR)
    group = cell.random_group(6, 3)
    theirs = cli("evaluate", "--setup", setup, "--postures", write_postures(tmp_path / "g.csv", group), "--json")
    assert cell.feasibility(group) == cell.evaluate(group)["feasibility"] == theirs["feasibility"]


def test_without_a_cell_only_the_bounds_are_checked(paper):
    (f,) = paper.feasibility(UPRIGHT)
    assert f["feasible"] and f["min_clearance_mm"] is None
    (f,) = paper.feasibility([0, 50, -90, 0, 30, 0])  # q2 beyond the setup's bound of 40 deg
    assert [v["check"] for v in f["violations"]] == ["bounds"]
    assert f["violations"][0]["margin_deg"] == pytest.approx(-10)


def test_a_urdf_robots_meshes_resolve_in_the_package_paths(mesh_robot):
    urdf = mesh_robot / "mesh_robot" / "urdf" / "robot.urdf"
    robot = stiffid.Robot.from_file(urdf, package_paths=[mesh_robot])
    assert robot.name == "mesh_robot"
    # Meshes not found: the robot loads for kinematics with a warning naming the package.
    with pytest.warns(UserWarning, match=r"package.*mesh_robot.*--package-path"):
        bare = stiffid.Robot.from_file(urdf)
    assert bare.name == "mesh_robot"
    with pytest.warns(UserWarning, match=r"package.*mesh_robot"):
        stiffid.Robot.from_file(urdf, package_paths=[mesh_robot / "nowhere"])
    # The setup's own package_paths (relative to the setup file) resolve them too.
    setup = stiffid.Setup.from_file(mesh_robot / "cell.toml")
    text = (mesh_robot / "cell.toml").read_text().replace('package_paths = ["."]\n', "")
    with pytest.warns(UserWarning, match=r"package.*mesh_robot"):
        without = stiffid.Setup.from_toml(text, "cell.toml", mesh_robot)
    # Only the cell's body checks need the meshes.
    with pytest.raises(stiffid.InputError, match=r"\[cell\].*--package-path"):
        without.feasibility([[0, 0, -90, 0, 30, 0]])
    given = stiffid.Setup.from_toml(text, "cell.toml", mesh_robot, package_paths=[mesh_robot])
    # The meshes are the robot's bodies: the cell's checks see them (not the capsules).
    q = [[0, 0, -90, 0, 30, 0], [0, 60, -60, 0, 0, 0]]
    assert given.feasibility(q) == setup.feasibility(q)


def test_too_many_package_paths_are_refused(mesh_robot):
    with pytest.raises(stiffid.InputError, match=r"package_paths"):
        stiffid.Robot.from_file(mesh_robot / "mesh_robot" / "urdf" / "robot.urdf", package_paths=[mesh_robot] * 65)
