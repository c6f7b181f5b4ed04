"""calibrate: noise-free readings of a robot with known geometric errors give them back, the same
document and files as `stiffid calibrate`, and a setup pointing at the calibrated robot file
serves every function with the calibrated robot."""

import json
import re

import numpy as np
import pytest

import stiffid
from test_schemas import assert_valid

SETUP = "zhang2021-comau-nj165"
HEADER = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm"
# base_from_tracker: a turn of 90 deg about z and a translation, mm.
ROTATION = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
TRANSLATION_MM = np.array([3000.0, -2000.0, 1500.0])
# The true robot's errors: (joint, field of the robot file, nominal, true value).
ERRORS = [(3, "a_mm", 1175.0, 1175.5), (4, "d_mm", 1444.0, 1444.3), (5, "alpha_deg", 90.0, 90.02)]


def postures(n, seed):
    """Postures spread over the COMAU's range, deg."""
    u = np.random.default_rng(seed).random((n, 6)) - 0.5
    return u * [100, 60, 60, 200, 60, 200] + [0, 0, -90, 0, 60, 0]


def readings(robot, points_mm, qs, path):
    """Every measuring point in every posture of `robot`, as the tracker reads it."""
    lines = [HEADER]
    for i, q in enumerate(qs):
        pose = robot.flange_pose(q)
        for k, point in enumerate(points_mm):
            tracker = ROTATION.T @ ((pose @ np.append(point, 1.0))[:3] - TRANSLATION_MM)
            lines.append(f"P{i + 1},{k + 1}," + ",".join(repr(float(v)) for v in [*q, *tracker]))
    path.write_text("\n".join(lines) + "\n")
    return path


def joint_field(text, joint, field, value):
    """The robot file `text` with `field` of its `joint`-th [[joint]] table set to `value`."""
    tables = text.split("[[joint]]")
    tables[joint] = re.sub(rf"(?m)^{field} = .*$", f"{field} = {value!r}", tables[joint], count=1)
    return "[[joint]]".join(tables)


@pytest.fixture(scope="module")
def campaign(paper, tmp_path_factory):
    """The true robot (the paper's with ERRORS, from the robot file a cell-only calibration of the
    nominal robot writes) and its readings: 25 postures to fit, 10 held out."""
    d = tmp_path_factory.mktemp("calibrate")
    nominal_readings = readings(paper.robot, paper.measuring_points_mm, postures(12, 3), d / "nominal.csv")
    doc = stiffid.calibrate(paper, nominal_readings, geometry="none", out=d / "nominal.toml")
    assert doc["residual_rms_mm"] < 1e-6
    nominal = stiffid.Robot.from_file(d / "nominal.toml")
    q = postures(5, 4)
    # The written robot file is the nominal robot.
    np.testing.assert_allclose(nominal.flange_pose(q), paper.robot.flange_pose(q), rtol=0, atol=1e-9)
    text = (d / "nominal.toml").read_text()
    for joint, field, before, after in ERRORS:
        written = re.search(rf"(?m)^{field} = (.*)$", text.split("[[joint]]")[joint])
        assert written and abs(float(written.group(1)) - before) < 1e-9, (joint, field)
        text = joint_field(text, joint, field, after)
    (d / "true.toml").write_text(text)
    true = stiffid.Robot.from_file(d / "true.toml")
    points = paper.measuring_points_mm
    fit = readings(true, points, postures(25, 1), d / "fit.csv")
    held = readings(true, points, postures(10, 2), d / "held.csv")
    return d, true, fit, held


def test_known_errors_come_back_with_the_commands_document_and_files(paper, cli, campaign):
    d, _, fit, held = campaign
    mine = stiffid.calibrate(paper, fit, validate=held, out=d / "py.toml")
    assert mine["residual_rms_mm"] < 1e-6 and mine["nominal_rms_mm"] > 0.1
    assert mine["stop_reason"] in ("converged", "stalled", "damping-exhausted")
    v = mine["validation"]
    assert v["rms_mm"] < 1e-6 and v["nominal_rms_mm"] > 0.1 and len(v["errors"]) == 10 * 4
    values = {p["name"]: p for p in mine["parameters"]}
    for (joint, field, before, after), unit in zip(ERRORS, ["mm", "mm", "deg"]):
        p = values[f"joint{joint}.{field.split('_')[0]}"]
        assert p["identified"] and p["unit"] == unit and p["nominal"] == 0.0
        assert abs(p["value"] - (after - before)) < 1e-7, p
    theirs = cli("calibrate", "--setup", SETUP, "--data", fit, "--validate", held,
                 "--out", d / "cli.toml", "--json")
    assert mine == theirs
    assert (d / "py.toml").read_bytes() == (d / "cli.toml").read_bytes()
    # The COMAU's axis map couples q2 and q3: no URDF joint can carry it, so none is written.
    with pytest.raises(stiffid.InputError, match="cannot be written as a URDF: its axis map"):
        stiffid.calibrate(paper, fit, urdf_out=d / "py.urdf")
    assert not (d / "py.urdf").exists()
    assert_valid("calibrate", mine)


@pytest.mark.parametrize(
    "kwargs, flags",
    [
        (dict(geometry="offsets", cross_validate=True), ["--geometry", "offsets", "--cross-validate"]),
        (dict(gravity="lumped"), ["--gravity", "lumped"]),
        (dict(tolerance_mm=0.5, tolerance_deg=0.05), ["--tolerance-mm", "0.5", "--tolerance-deg", "0.05"]),
        (dict(reregister=True), ["--reregister"]),
        (dict(level=0.9), ["--level", "0.9"]),
    ],
)
def test_every_option_equals_the_command(paper, cli, campaign, kwargs, flags):
    _, _, fit, held = campaign
    if kwargs.get("reregister") or kwargs.get("level"):
        kwargs, flags = dict(kwargs, validate=held), [*flags, "--validate", held]
    if "gravity" not in kwargs:
        kwargs, flags = dict(kwargs, gravity="none"), [*flags, "--gravity", "none"]
    with pytest.warns(UserWarning) if kwargs.get("geometry") == "offsets" else _nothing():
        mine = stiffid.calibrate(paper, fit, **kwargs)
    assert mine == cli("calibrate", "--setup", SETUP, "--data", fit, *flags, "--json")
    if kwargs.get("level"):
        intervals = mine["validation"]["intervals"]
        assert intervals["level"] == 0.9 and intervals["method"] == "jackknife+"
        assert mine["validation"]["coverage"] == intervals["coverage"]
        assert all(e["interval_mm"] is not None for e in mine["validation"]["errors"])


def test_a_setup_with_the_calibrated_robot_serves_every_function(paper, cli, campaign):
    d, true, fit, _ = campaign
    stiffid.calibrate(paper, fit, gravity="none", out=d / "calibrated.toml")
    text = cli("setups", "show", SETUP, parse=False)
    assert 'robot = "comau-smart5-nj165-3.0"' in text
    setup_file = d / "calibrated-setup.toml"
    setup_file.write_text(text.replace('robot = "comau-smart5-nj165-3.0"', 'robot = "calibrated.toml"'))
    calibrated = stiffid.Setup.from_file(setup_file)
    assert calibrated.robot.name.endswith("(calibrated)")
    # The tracker registers on the calibrated robot to the readings' rounding, not on the nominal.
    assert stiffid.register(calibrated, fit)["residual_rms_mm"] < 1e-6
    assert stiffid.register(paper, fit)["residual_rms_mm"] > 0.1
    # Its joints move as the true robot's: the flange's displacement between two postures.
    qs = postures(2, 5)
    poses = calibrated.robot.flange_pose(qs)
    truth = true.flange_pose(qs)
    moved = np.linalg.solve(poses[0], poses[1])
    np.testing.assert_allclose(moved, np.linalg.solve(truth[0], truth[1]), atol=1e-8)
    q, w = [10, 20, -90, 30, 20, 10], [100, -50, 200, 5, 0, 3]
    theirs = cli("predict", "--setup", setup_file, "--q-deg", ",".join(map(str, q)),
                 "--wrench", ",".join(map(str, w)), "--json")
    mine = stiffid.predict(calibrated, q, w)
    # A setup from a file is named by its path as given, from both front ends.
    assert mine == theirs and mine["setup"] == str(setup_file)
    assert mine != stiffid.predict(paper, q, w) | {"setup": mine["setup"]}
    again = stiffid.calibrate(calibrated, fit)
    assert again == cli("calibrate", "--setup", setup_file, "--data", fit, "--json")
    assert again["setup"] == str(setup_file)


def test_bad_arguments_are_refused_and_nothing_is_written(paper, campaign, tmp_path):
    d, _, fit, held = campaign
    before = fit.read_bytes()
    with pytest.raises(stiffid.InputError, match=r"^out .*fit.csv: refusing to write over the input file"):
        stiffid.calibrate(paper, fit, out=fit)
    assert fit.read_bytes() == before
    with pytest.raises(stiffid.InputError, match=r"^urdf_out .*: refusing to write over the input file .*held.csv"):
        stiffid.calibrate(paper, fit, validate=held, urdf_out=held)
    with pytest.raises(stiffid.InputError, match=r"^urdf_out .*same.toml: the same file as out"):
        stiffid.calibrate(paper, fit, out=tmp_path / "same.toml", urdf_out=tmp_path / "same.toml")
    with pytest.raises(stiffid.InputError, match=r"^out .*: exists and is not a regular file"):
        stiffid.calibrate(paper, fit, out=tmp_path)
    with pytest.raises(stiffid.InputError, match=r"^out .*nowhere/x.toml: no directory"):
        stiffid.calibrate(paper, fit, out=tmp_path / "nowhere" / "x.toml")
    with pytest.raises(stiffid.InputError, match=r"^tolerance_mm, tolerance_deg: give both or neither"):
        stiffid.calibrate(paper, fit, tolerance_mm=0.5)
    with pytest.raises(stiffid.InputError, match=r"^tolerance_mm, tolerance_deg: expected \[1e-6, 1000\] mm and \[1e-6, 90\] deg, got -1 and 0.1"):
        stiffid.calibrate(paper, fit, tolerance_mm=-1, tolerance_deg=0.1)
    with pytest.raises(stiffid.InputError, match=r"^reregister: only with validate="):
        stiffid.calibrate(paper, fit, reregister=True)
    with pytest.raises(stiffid.InputError, match=r"geometry.*'everything'.*none, offsets, full"):
        stiffid.calibrate(paper, fit, geometry="everything")
    with pytest.raises(stiffid.InputError, match=r"gravity.*masses"):
        stiffid.calibrate(paper, fit, gravity="masses")
    assert list(tmp_path.iterdir()) == []


class _nothing:
    """No warning expected (a context that checks nothing)."""

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False


def test_stiffness_out_writes_the_commands_stiffness_file(paper, cli, campaign):
    d, _, fit, _ = campaign
    mine = stiffid.calibrate(paper, fit, gravity="lumped", stiffness_out=d / "py-k.json")
    cli("calibrate", "--setup", SETUP, "--data", fit, "--gravity", "lumped",
        "--stiffness-out", d / "cli-k.json", "--json")
    assert (d / "py-k.json").read_bytes() == (d / "cli-k.json").read_bytes()
    written = json.loads((d / "py-k.json").read_text())
    assert written == mine["stiffness_file"]
    # Without loads or a gravity model no compliance is fitted: refused, nothing written.
    with pytest.raises(stiffid.InputError, match=r"stiffness_out: no compliance is fitted.*gravity=\"masses\""):
        stiffid.calibrate(paper, fit, gravity="none", stiffness_out=d / "none.json")
    assert not (d / "none.json").exists()


def test_the_scene_of_a_calibration_document_is_the_reports(paper, cli, campaign):
    """stiffid.scene of the calibrate document: each fitted posture at its axis angles with its
    errors before and after, the same glTF binary as `calibrate --report`'s errors.glb."""
    d, _, fit, _ = campaign
    doc = stiffid.calibrate(paper, fit, gravity="none")
    scene = stiffid.scene(paper, document=doc)
    drawn = scene.document()
    assert {p["label"] for p in doc["postures"]} == {e["posture"] for e in doc["errors"] if e["set"] == "fitted"}
    for posture, p in zip(doc["postures"], drawn["postures"]):
        np.testing.assert_allclose(p["q_deg"], posture["q_deg"], atol=1e-12)
        flange = paper.robot.flange_pose(posture["q_deg"])[:3, 3]
        np.testing.assert_allclose(np.array(p["flange_m"]) * 1e3, flange, atol=1e-9)
    first = next(e for e in doc["errors"] if e["posture"] == doc["postures"][0]["label"] and e["point"] == 1)
    arrow = drawn["postures"][0]["arrows"][0]
    np.testing.assert_allclose(np.array(arrow["measured_m"]) * 1e3, first["before_mm"], rtol=1e-12)
    np.testing.assert_allclose(np.array(arrow["predicted_m"]) * 1e3, first["after_mm"], rtol=1e-12)
    cli("calibrate", "--setup", SETUP, "--data", fit, "--gravity", "none", "--report", d / "report", parse=False)
    assert scene.glb() == (d / "report" / "errors.glb").read_bytes()
    assert scene._repr_html_().startswith("<iframe srcdoc=")
    with pytest.raises(stiffid.InputError, match="postures_deg"):
        stiffid.scene(paper, [[0, 0, 0, 0, 0, 0]], document=doc)


def test_an_update_with_a_list_and_the_stiffness_file_equals_the_command(paper, cli, campaign):
    d, _, fit, held = campaign
    stiffid.calibrate(paper, fit, gravity="lumped", validate=held, out=d / "sag.toml",
                      stiffness_out=d / "sag-k.json")
    text = cli("setups", "show", SETUP, parse=False)
    setup_file = d / "sag-setup.toml"
    setup_file.write_text(text.replace('robot = "comau-smart5-nj165-3.0"', 'robot = "sag.toml"'))
    calibrated = stiffid.Setup.from_file(setup_file)
    mine = stiffid.calibrate(calibrated, held, update=True, update_parameters="offsets,base",
                             stiffness=d / "sag-k.json")
    theirs = cli("calibrate", "--setup", setup_file, "--data", held, "--update", "offsets,base",
                 "--stiffness", d / "sag-k.json", "--json")
    assert mine == theirs
    # The tool and the gravity terms held at the calibration's values.
    assert "point1.x" in mine["held"] and any(n.startswith("gravity.") for n in mine["held"])
    with pytest.raises(stiffid.InputError, match=r"^update_parameters, stiffness: only with update=True"):
        stiffid.calibrate(calibrated, held, update_parameters="offsets,base")
    with pytest.raises(stiffid.InputError, match=r"needs base"):
        stiffid.calibrate(calibrated, held, update=True, update_parameters="offsets,tool")


def test_a_refusal_names_the_keywords_python_spells_as_the_command_its_flags(paper, cli, campaign, tmp_path):
    """A calibration's refusal that tells what to give or leave out names the keyword beside the
    command's flag, the same message from both: ``level`` without held-out readings, and readings
    that are a mirror image of the robot's points (two tracker columns swapped) that ``force``
    fits anyway."""
    import subprocess

    from conftest import cli_path

    d, _, fit, _ = campaign
    setup = tmp_path / "setup.toml"
    setup.write_text(cli("setups", "show", SETUP, parse=False))
    lines = fit.read_text().splitlines()
    swapped = [lines[0]] + [",".join(v[:-3] + [v[-2], v[-3], v[-1]]) for v in (line.split(",") for line in lines[1:])]
    mirrored = tmp_path / "mirrored.csv"
    mirrored.write_text("\n".join(swapped) + "\n")
    for kwargs, flags, keyword in [
        ({"level": 0.9}, ["--level", "0.9"], "(Python validate= or update=True)"),
        ({}, [], "--force (Python force=True) fits"),
    ]:
        readings = fit if kwargs else mirrored
        with pytest.raises(stiffid.InputError) as mine:
            stiffid.calibrate(paper, readings, **kwargs)
        out = subprocess.run([str(cli_path()), "calibrate", "--setup", setup, "--data", readings, *flags],
                             capture_output=True, text=True)
        assert out.returncode == 2 and keyword in str(mine.value), str(mine.value)
        theirs = out.stderr.strip().removeprefix("error: ")
        assert theirs.split(": ", 1)[1] == str(mine.value).split(": ", 1)[1], (theirs, str(mine.value))
