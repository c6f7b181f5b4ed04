"""plan: the measurement plan job, the same document as the `plan.json` of `stiffid select
--report`, with its rope, loading point and expected displacements those of the forward model."""

import json

import numpy as np
import pytest

import stiffid
from conftest import REPO
from test_schemas import assert_valid

POOL = REPO / "examples" / "pool" / "zhang2021-pool.csv"
# The paper's setup in a cell (floor, clearance, a table), without its tracker: 51 of the 100
# pool postures pass its checks.
CELL = (REPO / "examples" / "pool" / "zhang2021-cell.toml").read_text().split("[tracker]")[0]


def command_plan(cli, tmp_path, setup, *flags):
    """The postures `stiffid select --pool` chooses (as the pool file gives them) and the plan.json of its --report."""
    out, report = tmp_path / "chosen.csv", tmp_path / "plan"
    doc = cli("select", "--setup", setup, "--pool", POOL, "--out", out, "--report", report, *flags, "--json")
    rows = np.loadtxt(POOL, delimiter=",", skiprows=1)[:, 1:]
    chosen = rows[[i - 1 for i in doc["pool"]["chosen"]]]
    np.testing.assert_allclose(chosen, doc["postures_deg"], rtol=1e-14)
    return chosen, json.loads((report / "plan.json").read_text())


def test_the_plan_equals_the_commands_plan_json(cli, tmp_path):
    (tmp_path / "cell.toml").write_text(CELL)
    cell = stiffid.Setup.from_file(tmp_path / "cell.toml")
    chosen, theirs = command_plan(cli, tmp_path, tmp_path / "cell.toml", "--count", 6, "--criterion", "zhang2021")
    mine = stiffid.plan(cell, chosen, criterion="zhang2021")
    assert mine == theirs
    assert mine["bodies"]["link_radii_mm"] is not None and len(mine["postures"]) == 6
    assert all(p["failed_checks"] == [] and p["min_clearance_mm"] >= 50 for p in mine["postures"])
    assert_valid("plan", mine)
    # The rope runs from the loading point to the anchor; the measuring points move as predict says.
    q = chosen[0]
    loading = (cell.robot.flange_pose(q) @ np.append(cell.loading_point_mm, 1.0))[:3]
    rope = cell.anchor_mm - loading
    p = mine["postures"][0]
    np.testing.assert_allclose(p["rope_length_mm"], np.linalg.norm(rope), rtol=1e-12)
    np.testing.assert_allclose(p["rope_direction"], rope / np.linalg.norm(rope), atol=1e-12)
    np.testing.assert_allclose(p["loading_point_z_mm"], loading[2], rtol=1e-12)
    wrench = np.append(cell.load_n * rope / np.linalg.norm(rope), [0.0, 0.0, 0.0])
    predicted = stiffid.predict(cell, q, wrench)["measuring_points"]
    np.testing.assert_allclose(p["displacements_mm"], [m["displacement_mm"] for m in predicted], rtol=1e-9)


def test_a_target_is_named_and_a_plan_needs_the_nominal_stiffness(paper, cli, tmp_path):
    chosen, theirs = command_plan(cli, tmp_path, "zhang2021-comau-nj165", "--target-pct", 2)
    mine = stiffid.plan(paper, chosen, target_pct=2)
    assert mine == theirs and mine["target_pct"] == 2 and mine["bodies"] is None
    without = stiffid.Setup.from_toml(cli("setups", "show", "zhang2021-comau-nj165", parse=False)
                                      .replace("nominal_stiffness_nm_per_rad", "# nominal_stiffness_nm_per_rad"))
    with pytest.raises(stiffid.InputError, match="nominal_stiffness_nm_per_rad"):
        stiffid.plan(without, chosen)
    with pytest.raises(stiffid.InputError, match="criterion"):
        stiffid.plan(paper, chosen, criterion="best")
    with pytest.raises(stiffid.InputError, match=r"postures_deg: posture 0, q3_deg = 10 is outside the joint limits"):
        stiffid.plan(paper, [[0, 0, 10, 0, 0, 0]])


def test_the_scene_is_the_plans_in_3d_and_the_commands_glb(cli, tmp_path):
    (tmp_path / "cell.toml").write_text(CELL)
    cell = stiffid.Setup.from_file(tmp_path / "cell.toml")
    chosen, plan = command_plan(cli, tmp_path, tmp_path / "cell.toml", "--count", 6)
    scene = stiffid.scene(cell, chosen)
    doc = scene.document()
    assert len(doc["postures"]) == 6
    # The flange and the arrows are the plan's: the forward kinematics and its displacements.
    for q, p, planned in zip(chosen, doc["postures"], plan["postures"]):
        flange = cell.robot.flange_pose(q)[:3, 3]
        np.testing.assert_allclose(np.array(p["flange_m"]) * 1e3, flange, atol=1e-9)
        predicted = np.array([a["predicted_m"] for a in p["arrows"]]) * 1e3
        np.testing.assert_allclose(predicted, planned["displacements_mm"], rtol=1e-12)
    # The same glTF binary as the command's plan.glb; a page without any address to fetch.
    assert scene.glb() == (tmp_path / "plan" / "plan.glb").read_bytes()
    assert scene.glb()[:4] == b"glTF"
    html = scene.html("plan")
    assert "<title>plan</title>" in html and "https://" not in html
    assert scene._repr_html_().startswith("<iframe srcdoc=")
    with pytest.raises(stiffid.InputError, match="postures_deg"):
        stiffid.scene(cell, np.zeros((501, 6)))


def test_a_plan_takes_at_most_1000_postures(paper):
    """The plan's leave-one-out is quadratic in the count: its maximum is 1000, refused beyond."""
    with pytest.raises(ValueError, match=r"postures_deg: expected 1 to 1000 postures, got 1001"):
        stiffid.plan(paper, np.zeros((1001, 6)))


def test_a_plan_at_external_values_works_each_posture_out_there():
    # The track cell: each posture read at its station and table angles, the rope from the
    # loading point of the arm on its carriage (the flange where kinematics puts it) to the anchor.
    setup = stiffid.Setup.from_file(REPO / "examples" / "track" / "track-cell.toml")
    q = [[0, 30, 0, 0, 60, 0], [10, 35, -5, 0, 55, 0]]
    external = [[3000, 0, 0], [3500, 10, 45]]
    plan = stiffid.plan(setup, q, external=external)
    for p, qi, e in zip(plan["postures"], q, external):
        assert [p["e1_mm"], p["e2_deg"], p["e3_deg"]] == e
        k = setup.robot.kinematics(qi, external=e)
        flange = np.eye(4)
        flange[:3, :3], flange[:3, 3] = k["flange_rotation"], k["flange_position_mm"]
        loading = (flange @ np.append(setup.loading_point_mm, 1.0))[:3]
        np.testing.assert_allclose(p["rope_length_mm"], np.linalg.norm(setup.anchor_mm - loading), rtol=1e-12)
    # The plan's scene stands the arm where the plan read it (SI: m, rad).
    scene = stiffid.scene(setup, document=plan).document()
    for shown, e in zip(scene["postures"], external):
        np.testing.assert_allclose(shown["external"], [e[0] / 1e3, np.radians(e[1]), np.radians(e[2])], rtol=1e-12)
    with pytest.raises(ValueError, match=r"external\[1\]: expected 3 values"):
        stiffid.plan(setup, q, external=[[3000, 0, 0], [3500, 10]])
    with pytest.raises(stiffid.InputError, match="external"):
        stiffid.plan(setup, q, external=[[3000, 0, 0], [9000, 0, 0]])
    # Without them it is refused, as the kinematics refuse it: every posture would stand at 0.
    with pytest.raises(stiffid.InputError, match=r"^external: none given: the robot has external axes"):
        stiffid.plan(setup, q)
