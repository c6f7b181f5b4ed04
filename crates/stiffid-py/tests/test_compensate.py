"""stiffid.compensate against `stiffid compensate` on the milling example (real identified stiffness)."""

import numpy as np
import pytest

import stiffid
from conftest import REPO

PATH = REPO / "examples" / "milling" / "path.csv"
STIFFNESS = REPO / "examples" / "milling" / "stiffness.json"
# The built-in FANUC setup with the tool centre point compensate requires ([tool] tcp_mm).
SETUP = REPO / "examples" / "milling" / "fanuc-milling.toml"


@pytest.fixture
def milling():
    return stiffid.Setup.from_file(SETUP)


def command(cli, tmp_path, *extra):
    out = tmp_path / "compensated.csv"
    args = ["compensate", "--setup", SETUP, "--stiffness", STIFFNESS, "--path", PATH]
    return cli(*args, "--out", out, "--json", *extra)["points"]


def column(points, *keys):
    return np.array([[p[k] for k in keys] for p in points])


@pytest.mark.parametrize("free", [False, True])
def test_compensate_equals_the_command(milling, cli, tmp_path, free):
    extra = ["--free", "tool-rotation"] if free else []
    theirs = command(cli, tmp_path, *extra)
    mine = stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation"] if free else None)
    assert mine["line"].dtype == np.int64 and mine["iterations"].dtype == np.int64
    assert mine["line"].tolist() == [p["line"] for p in theirs]
    assert mine["iterations"].tolist() == [p["iterations"] for p in theirs]
    qc = column(theirs, *[f"qc{i}_deg" for i in range(1, 7)])
    np.testing.assert_allclose(mine["q_compensated_deg"], qc, rtol=0, atol=1e-12)
    np.testing.assert_allclose(mine["q_deg"], column(theirs, *[f"q{i}_deg" for i in range(1, 7)]), atol=1e-12)
    np.testing.assert_allclose(mine["deflection_mm"], column(theirs, "dx_mm", "dy_mm", "dz_mm"), rtol=1e-12, atol=1e-15)
    np.testing.assert_allclose(mine["deflection_std_mm"], column(theirs, "dx_std_mm", "dy_std_mm", "dz_std_mm"), rtol=1e-12)
    np.testing.assert_allclose(mine["tool_rotation_deg"], [p["tool_rotation_deg"] for p in theirs], atol=1e-12)
    # Compensation is real: the compensated angles differ from the nominal, and the residual is tiny.
    assert np.abs(mine["q_compensated_deg"] - mine["q_deg"]).max() > 1e-3
    assert mine["residual_um"].max() < 0.1
    # Every point's Newton steps converged: the document says so, and nothing warns.
    summary = mine["document"]["summary"]
    assert (summary["stop_reason"], summary["not_converged"]) == ("converged", 0)


def test_stiffness_as_numbers_has_no_std(milling):
    numbers = [860896.0, 2719582.5, 1959759.6, 270828.3, 424693.0, 206019.8]
    out = stiffid.compensate(milling, PATH, numbers)
    assert "deflection_std_mm" not in out
    assert out["q_compensated_deg"].shape == (len(out["line"]), 6)


def test_bad_free_axis_and_start_are_refused(milling):
    with pytest.raises(ValueError, match=r"free tool-rotation step: 0: expected a number > 0 and <= 90"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation=-90..90/0"])
    with pytest.raises(ValueError, match=r"^free tool-rotation range: 1e308: expected a number > 0 and <= 180 \(deg\)$"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=[{"variable": "tool-rotation", "range": 1e308}])
    with pytest.raises(ValueError, match=r"^free: tool-rotation=-90..80: `-90..80`: expected a range -R..R"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation=-90..80"])
    with pytest.raises(ValueError, match=r"^free: spindle: unknown variable: expected tool-rotation"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["spindle"])
    with pytest.raises(ValueError, match=r"^free: expected a list"):
        stiffid.compensate(milling, PATH, STIFFNESS, free="tool-rotation")
    with pytest.raises(ValueError, match=r"^free: `ranges`: expected the keys"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=[{"variable": "station", "ranges": 5}])
    with pytest.raises(ValueError, match=r"^free: tool-rotation: given twice"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation", "tool-rotation=-10..10"])
    # The keywords free= replaced are refused saying how to write them; the options of the free
    # variables mean nothing without one.
    with pytest.raises(ValueError, match=r'^free_tool_axis: removed; write free=\["tool-rotation=-90..90/2"\]$'):
        stiffid.compensate(milling, PATH, STIFFNESS, free_tool_axis=True)
    with pytest.raises(ValueError, match=r'^free_tool_axis_objective: removed; write minimise='):
        stiffid.compensate(milling, PATH, STIFFNESS, free_tool_axis_objective="bound")
    with pytest.raises(stiffid.InputError, match=r"^free_axis: not an argument of compensate\(\)"):
        stiffid.compensate(milling, PATH, STIFFNESS, free_axis=True)
    for option in [dict(minimise="bound"), dict(objective="max"), dict(margin_deg=3.0),
                   dict(max_condition=100.0), dict(refine=1)]:
        with pytest.raises(ValueError, match=rf"^{next(iter(option))}: only with free"):
            stiffid.compensate(milling, PATH, STIFFNESS, **option)
    with pytest.raises(ValueError, match=r"q0_deg"):
        stiffid.compensate(milling, PATH, STIFFNESS, q0_deg=[0, 0, 0, 0, 0, 0, 0])
    with pytest.raises(FileNotFoundError, match=r"nope.csv"):
        stiffid.compensate(milling, REPO / "nope.csv", STIFFNESS)


def test_the_feasibility_checks_are_the_commands(milling, cli, tmp_path):
    with pytest.raises(ValueError, match=r"^margin_deg: 91: expected 0 to 90$"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation"], margin_deg=91.0)
    with pytest.raises(ValueError, match=r"^max_condition: 0.5: expected a finite number >= 1$"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation"], max_condition=0.5)
    extra = ["--free", "tool-rotation", "--margin-deg", "15", "--max-condition", "500"]
    args = ["compensate", "--setup", SETUP, "--stiffness", STIFFNESS, "--path", PATH]
    theirs = cli(*args, "--out", tmp_path / "c.csv", "--json", *extra)
    mine = stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation"], margin_deg=15.0, max_condition=500.0)
    assert mine["document"]["feasibility"] == theirs["feasibility"]
    assert theirs["feasibility"]["max_condition"] == 500.0
    assert mine["tool_rotation_deg"].tolist() == [p["tool_rotation_deg"] for p in theirs["points"]]


def test_the_tool_centre_point_is_required(fanuc):
    # A measuring setup's measuring point is no tool.
    with pytest.raises(ValueError, match=r"tool.tcp_mm"):
        stiffid.compensate(fanuc, PATH, STIFFNESS)


def test_the_error_budget_equals_the_command_and_refuses_above_the_largest_error(milling, cli, tmp_path):
    theirs = command(cli, tmp_path)
    mine = stiffid.compensate(milling, PATH, STIFFNESS)
    np.testing.assert_allclose(mine["bound_mm"], [p["bound_mm"] for p in theirs], rtol=1e-12)
    # The example's robot is not a calibrated one and no stiffness file carries a model comparison.
    assert np.isnan(mine["bound_calibration_mm"]).all() and np.isnan(mine["bound_model_form_mm"]).all()
    parts = mine["bound_left_mm"] + mine["bound_force_mm"] + mine["bound_compensation_mm"]
    np.testing.assert_allclose(mine["bound_mm"], parts, rtol=1e-12)
    np.testing.assert_allclose(mine["bound_force_mm"], 0.2 * np.linalg.norm(mine["deflection_mm"], axis=1), rtol=1e-12)
    worst = mine["document"]["summary"]["budget"]["max_bound_mm"]
    assert worst == pytest.approx(mine["bound_mm"].max(), rel=1e-12)
    with pytest.raises(stiffid.GateError, match=r"max_error_mm: .*the worst points: line \d+: .* mostly \w+"):
        stiffid.compensate(milling, PATH, STIFFNESS, max_error_mm=worst / 2)
    assert stiffid.compensate(milling, PATH, STIFFNESS, max_error_mm=worst * 2)["bound_mm"].max() == pytest.approx(worst)


def test_the_map_holds_every_point_at_every_rotation_and_the_line_chosen(milling):
    out = stiffid.compensate(milling, PATH, STIFFNESS, free=["tool-rotation=-30..30/10"], objective="max", map=True)
    m = out["map"]
    n, g = len(out["line"]), len(m["tool_rotation_deg"])
    np.testing.assert_allclose(m["tool_rotation_deg"], np.linspace(-30, 30, g))
    for key in ["bound_mm", "deflection_mm", "condition", "limit_distance_deg"]:
        assert m[key].shape == (n, g) and m[key].dtype == np.float64
    np.testing.assert_allclose(m["chosen_deg"], out["tool_rotation_deg"], atol=1e-12)
    # The column of the path's own rotation is the path's own bound; the chosen cells are what
    # each point got, never above it.
    own = int(np.argmin(np.abs(m["tool_rotation_deg"])))
    before = [p["bound_before_mm"] for p in out["document"]["points"]]
    np.testing.assert_allclose(m["bound_mm"][:, own], before, rtol=1e-6)
    picked = m["bound_mm"][np.arange(n), [int(np.argmin(np.abs(m["tool_rotation_deg"] - c))) for c in m["chosen_deg"]]]
    assert (picked <= m["bound_mm"][:, own] * (1 + 1e-9)).all()
    assert out["bound_mm"].max() <= m["bound_mm"][:, own].max() * (1 + 1e-9)
    assert (m["condition"][np.isfinite(m["condition"])] >= 1).all()


def test_the_scene_of_a_compensation_document_is_the_reports(milling, cli, tmp_path):
    """stiffid.scene of the compensate document: the robot at the first point and at the largest
    deflection, the sampled path with its error, the same glTF binary as `compensate --report`'s
    path.glb."""
    mine = stiffid.compensate(milling, PATH, STIFFNESS)
    scene = stiffid.scene(milling, document=mine["document"])
    drawn = scene.document()
    largest = int(np.argmax(np.linalg.norm(mine["deflection_mm"], axis=1)))
    for p, i in zip(drawn["postures"], [0, largest]):
        np.testing.assert_allclose(p["q_deg"], mine["q_deg"][i], atol=1e-12)
    path = np.array([p["at_m"] for p in drawn["path"]]) * 1e3
    rows = mine["document"]["points"]
    np.testing.assert_allclose(path, [[r["x_mm"], r["y_mm"], r["z_mm"]] for r in rows], atol=1e-9)
    cli("compensate", "--setup", SETUP, "--stiffness", STIFFNESS, "--path", PATH,
        "--out", tmp_path / "c.csv", "--report", tmp_path / "report", parse=False)
    assert scene.glb() == (tmp_path / "report" / "path.glb").read_bytes()
    assert "error remaining after compensation" in drawn["path_error"]


def test_a_free_track_station_equals_the_command(cli, tmp_path):
    """The trim line along the rail of the track example: the station free within +-1500 mm in
    50 mm steps, the worst bound minimised, as `compensate --free-station-mm` chooses it."""
    setup = REPO / "examples" / "track" / "track-cell.toml"
    stiffness = REPO / "examples" / "milling" / "kuka-stiffness.json"
    path = REPO / "examples" / "track" / "trim.csv"
    options = ["--free", "station=-1500..1500/50", "--objective", "max"]
    out = tmp_path / "trim.csv"
    theirs = cli("compensate", "--setup", setup, "--stiffness", stiffness, "--path", path,
                 "--out", out, "--json", *options)["points"]
    cell = stiffid.Setup.from_file(setup)
    mine = stiffid.compensate(cell, path, stiffness, free=[{"variable": "station", "range": 1500, "step": 50}],
                              objective="max")
    np.testing.assert_allclose(mine["bound_mm"], [p["bound_mm"] for p in theirs], rtol=1e-12)
    np.testing.assert_allclose(mine["q_compensated_deg"],
                               column(theirs, *[f"qc{i}_deg" for i in range(1, 7)]), atol=1e-12)
    own = stiffid.compensate(cell, path, stiffness)
    assert mine["bound_mm"].max() < 0.7 * own["bound_mm"].max()
    with pytest.raises(ValueError, match="free station step"):
        stiffid.compensate(cell, path, stiffness, free=["station=-100..100/0"])


def test_a_free_table_angle_equals_the_command(cli, tmp_path):
    """The cut across the table's far side of the track example: the table's angle free within
    +-180 deg in 5 deg steps, the worst bound minimised, as `compensate --free positioner=-180..180/5`
    chooses it: the same bounds and angles, none worse than at the table at rest."""
    setup = REPO / "examples" / "track" / "track-cell.toml"
    stiffness = REPO / "examples" / "milling" / "kuka-stiffness.json"
    path = REPO / "examples" / "track" / "table.csv"
    options = ["--free", "positioner=-180..180/5", "--objective", "max"]
    theirs = cli("compensate", "--setup", setup, "--stiffness", stiffness, "--path", path,
                 "--out", tmp_path / "table.csv", "--json", *options)["points"]
    cell = stiffid.Setup.from_file(setup)
    mine = stiffid.compensate(cell, path, stiffness, free=["positioner=-180..180/5"], objective="max")
    np.testing.assert_allclose(mine["bound_mm"], [p["bound_mm"] for p in theirs], rtol=1e-12)
    [table] = mine["document"]["free"]
    assert (table["variable"], table["unit"]) == ("positioner", "deg")
    assert (table["range"], table["step"]) == (pytest.approx(180.0), pytest.approx(5.0))
    # The document's free variables pass back as they are: the same compensation.
    again = stiffid.compensate(cell, path, stiffness, free=mine["document"]["free"], objective="max")
    np.testing.assert_array_equal(again["bound_mm"], mine["bound_mm"])
    with pytest.raises(ValueError, match=r"^free: unit mm: positioner is in deg"):
        stiffid.compensate(cell, path, stiffness, free=[dict(table, unit="mm")])
    with pytest.raises(ValueError, match=r"^free: per: only for the configuration"):
        stiffid.compensate(cell, path, stiffness, free=[dict(table, per="run")])
    own = stiffid.compensate(cell, path, stiffness)
    assert (mine["bound_mm"] <= own["bound_mm"] * (1 + 1e-9)).all()
    assert mine["bound_mm"].max() < 0.6 * own["bound_mm"].max()
    with pytest.raises(ValueError, match="free positioner step"):
        stiffid.compensate(cell, path, stiffness, free=["positioner=-10..10/20"])


def test_the_track_map_holds_every_station_and_the_one_chosen():
    """map="track" on the trim line along the rail: every point at every station of the free
    station's grid, the station chosen the one each point got, its cell the point's bound."""
    setup = stiffid.Setup.from_file(REPO / "examples" / "track" / "track-cell.toml")
    stiffness = REPO / "examples" / "milling" / "kuka-stiffness.json"
    path = REPO / "examples" / "track" / "trim.csv"
    out = stiffid.compensate(setup, path, stiffness, free=["station=-200..200/100"], objective="max", map="track")
    m = out["map"]
    np.testing.assert_allclose(m["station_offset_mm"], [-200, -100, 0, 100, 200], atol=1e-9)
    n = len(out["line"])
    assert m["bound_mm"].shape == (n, 5) and "tool_rotation_deg" not in m
    assert np.isin(np.round(m["chosen_mm"], 6), m["station_offset_mm"]).all()
    assert (m["chosen_mm"] != 0).any()
    picked = m["bound_mm"][np.arange(n), [int(np.argmin(np.abs(m["station_offset_mm"] - c))) for c in m["chosen_mm"]]]
    np.testing.assert_allclose(picked, out["bound_mm"], rtol=1e-6)
    with pytest.raises(ValueError, match="map"):
        stiffid.compensate(setup, path, stiffness, map="station")


def test_lead_and_tilt_equal_the_command(milling, cli, tmp_path):
    extra = ["--free", "lead-tilt=-6..6/3", "--objective", "max"]
    theirs = command(cli, tmp_path, *extra)
    mine = stiffid.compensate(milling, PATH, STIFFNESS, free=["lead-tilt=-6..6/3"], objective="max")
    for key in ["lead_deg", "tilt_deg", "bound_mm"]:
        np.testing.assert_allclose(mine[key], [p[key] for p in theirs], rtol=1e-12, atol=1e-12)
    assert np.hypot(mine["lead_deg"], mine["tilt_deg"]).max() <= 6 + 1e-9
    assert np.abs(mine["lead_deg"]).max() > 0
    [lean] = mine["document"]["free"]
    assert (lean["variable"], lean["step"]) == ("lead-tilt", pytest.approx(3))
    with pytest.raises(ValueError, match="free lead-tilt range"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["lead-tilt=-45..45"])
    with pytest.raises(ValueError, match="cone_deg: removed"):
        stiffid.compensate(milling, PATH, STIFFNESS, cone_deg=5)


def test_one_configuration_per_run_equals_the_command(milling, cli, tmp_path):
    milling_dir = REPO / "examples" / "milling"
    program, process = milling_dir / "panel.nc", milling_dir / "drilling.toml"
    out = tmp_path / "panel.ls"
    args = ["compensate", "--setup", SETUP, "--stiffness", STIFFNESS, "--program", program, "--process", process]
    theirs = cli(*args, "--out", out, "--json", "--free", "configuration=run")["configurations"]
    mine = stiffid.compensate(milling, stiffness=STIFFNESS, program=program, process=process, output="ls",
                              free=["configuration=run"])["document"]["configurations"]
    assert mine == theirs
    # 20 holes, 20 runs; on the FANUC's own limits each keeps the program's own configuration.
    assert (mine["per"], len(mine["runs"])) == ("run", 20)
    assert all(r["chosen_own"] for r in mine["runs"])
    with pytest.raises(ValueError, match="configuration_per: removed"):
        stiffid.compensate(milling, PATH, STIFFNESS, configuration_per="run")
    with pytest.raises(ValueError, match="free: configuration=hole: `hole`: expected program or run"):
        stiffid.compensate(milling, PATH, STIFFNESS, free=["configuration=hole"])


def test_refine_never_rises_and_bad_values_are_refused(milling):
    free = dict(free=["tool-rotation=-90..90/5"], objective="max")
    grid = stiffid.compensate(milling, PATH, STIFFNESS, **free)
    refined = stiffid.compensate(milling, PATH, STIFFNESS, refine=1, **free)
    assert (grid["document"]["refine"], refined["document"]["refine"]) == (0, 1)
    assert refined["bound_mm"].max() <= grid["bound_mm"].max() * (1 + 1e-9)
    assert refined["bound_mm"].sum() < grid["bound_mm"].sum()
    assert np.all(np.abs(np.diff(refined["tool_rotation_deg"])) <= 5 + 1e-9)
    with pytest.raises(ValueError, match="refine: only with free: .*none is free"):
        stiffid.compensate(milling, PATH, STIFFNESS, refine=1)
    with pytest.raises(ValueError, match="refine: 5: expected 0 to 4"):
        stiffid.compensate(milling, PATH, STIFFNESS, refine=5, **free)
