"""register and calibrate_cell: a known tracker transform and shifted tool points come back, proposed registration postures read back register the tracker, the same documents as the command."""

import numpy as np
import pytest

import stiffid
from conftest import REPO
from test_schemas import assert_valid

HEADER = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,x_tracker_mm,y_tracker_mm,z_tracker_mm"
POSTURES = [
    [0.0, 0.0, -90.0, 0.0, 30.0, 0.0],
    [35.0, -20.0, -110.0, 40.0, -30.0, 60.0],
    [-40.0, 15.0, -70.0, -60.0, 45.0, -90.0],
    [10.0, -30.0, -120.0, 90.0, 60.0, 30.0],
]
# base_from_tracker: a turn of 90 deg about z and a translation, mm.
ROTATION = np.array([[0.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0]])
TRANSLATION_MM = np.array([3000.0, -2000.0, 1500.0])


def readings(setup, path, shift_mm=(0.0, 0.0, 0.0)):
    """Every measuring point (shifted in the flange frame) in every posture, as the tracker reads it."""
    lines = [HEADER]
    for i, q in enumerate(POSTURES):
        pose = setup.robot.flange_pose(q)
        for k, point in enumerate(setup.measuring_points_mm):
            base = (pose @ np.append(point + np.asarray(shift_mm), 1.0))[:3]
            tracker = ROTATION.T @ (base - TRANSLATION_MM)
            numbers = ",".join(repr(float(v)) for v in [*q, *tracker])
            lines.append(f"P{i + 1},{k + 1},{numbers}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_register_gives_the_transform_back_and_equals_the_command(paper, cli, tmp_path):
    path = readings(paper, tmp_path / "readings.csv")
    doc = stiffid.register(paper, path)
    np.testing.assert_allclose(doc["xyz_mm"], TRANSLATION_MM, atol=1e-6)
    np.testing.assert_allclose(doc["rpy_deg"], [0.0, 0.0, 90.0], atol=1e-9)
    assert doc["residual_rms_mm"] < 1e-6 and len(doc["points"]) == 16
    assert doc == cli("register", "--setup", "zhang2021-comau-nj165", "--data", path, "--json")
    assert_valid("register", doc)
    for key in ["seed", "candidates", "restarts"]:
        with pytest.raises(stiffid.InputError, match=rf"^{key}: only with count="):
            stiffid.register(paper, path, **{key: 5})


def test_calibrate_cell_finds_the_shift_and_equals_the_command(paper, cli, tmp_path):
    path = readings(paper, tmp_path / "shifted.csv", shift_mm=(2.0, 0.0, 0.0))
    doc = stiffid.calibrate_cell(paper, path)
    for p in doc["points"]:
        np.testing.assert_allclose(p["shift_mm"], [2.0, 0.0, 0.0], atol=1e-6)
    assert doc["absolute_error_rms_mm"] < 1e-6
    assert doc == cli("calibrate-cell", "--setup", "zhang2021-comau-nj165", "--data", path, "--json")
    assert_valid("calibrate-cell", doc)


def test_collinear_points_are_refused_naming_the_file(paper, tmp_path):
    path = tmp_path / "line.csv"
    rows = [f"P{i},1,0,0,-90,0,30,0,{100.0 * i},0,0" for i in range(1, 5)]
    path.write_text("\n".join([HEADER, *rows]) + "\n")
    with pytest.raises(stiffid.InputError, match=r"line.csv.*lie on one line"):
        stiffid.register(paper, path)


def test_mirrored_readings_are_refused_unless_forced(paper, tmp_path):
    path = readings(paper, tmp_path / "readings.csv")
    lines = path.read_text().splitlines()
    mirrored = [lines[0]]
    for line in lines[1:]:
        cells = line.split(",")
        cells[8] = repr(-float(cells[8]))
        mirrored.append(",".join(cells))
    path.write_text("\n".join(mirrored) + "\n")
    for job in (stiffid.register, stiffid.calibrate_cell):
        with pytest.raises(stiffid.InputError, match=r"readings.csv: readings: the tracker's readings are a mirror image"):
            job(paper, path)
        assert job(paper, path, force=True)["noise_std_mm"] > 10.0


def test_proposed_postures_equal_the_command_and_register_when_read(cli, tmp_path):
    cell = stiffid.Setup.from_file(REPO / "examples" / "cell" / "zhang2021-tracker.toml")
    doc = stiffid.register(cell, count=3, candidates=500)
    assert len(doc["postures"]) == 3
    assert doc["rotation_std_total_deg"] < doc["random_median_rotation_std_total_deg"]
    command = cli("register", "--setup", REPO / "examples" / "cell" / "zhang2021-tracker.toml",
                  "--count", "3", "--candidates", "500", "--json")
    assert {k: v for k, v in doc.items() if k != "setup"} == {k: v for k, v in command.items() if k != "setup"}
    assert_valid("register-postures", doc)
    # The template filled with what a tracker at the cell's position, turned by 90 deg, reads.
    lines = doc["readings_template"].splitlines()
    rows = [lines[0]]
    for line in lines[1:]:
        cells = line.split(",")
        q = [float(v) for v in cells[2:8]]
        point = np.asarray(cell.measuring_points_mm[int(cells[1]) - 1])
        base = (cell.robot.flange_pose(q) @ np.append(point, 1.0))[:3]
        tracker = ROTATION.T @ (base - TRANSLATION_MM)
        rows.append(",".join(cells[:8] + [repr(float(v)) for v in tracker]))
    path = tmp_path / "filled.csv"
    path.write_text("\n".join(rows) + "\n")
    fit = stiffid.register(cell, path)
    np.testing.assert_allclose(fit["xyz_mm"], TRANSLATION_MM, atol=1e-6)
    with pytest.raises(stiffid.InputError, match="not both"):
        stiffid.register(cell, path, count=3)
    # `postures` is a postures file everywhere else: the count's old keyword names the new one.
    with pytest.raises(stiffid.InputError, match="postures: renamed count"):
        stiffid.register(cell, postures=3)
