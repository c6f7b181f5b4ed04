"""The robot's mass from Python: the same frequencies, effective masses and surge as the command,
placeholder masses a UserWarning."""

from pathlib import Path

import numpy as np
import pytest

import stiffid

ROOT = Path(__file__).resolve().parents[3]
COMAU = (ROOT / "crates/stiffid/presets/comau-smart5-nj165-3.0.toml").read_text()
SETUP = (ROOT / "crates/stiffid/setups/zhang2021-comau-nj165.toml").read_text()
Q = [10, -20, -100, 30, 40, 50]
K = [950000, 3000000, 900000, 250000, 200000, 150000]


def robot_text(equal):
    """The COMAU preset with a mass, centre and inertia tensor on each joint."""
    masses = [420.0, 260.0, 180.0, 45.0, 25.0, 12.0]
    head, *parts = COMAU.split("[[joint]]\n")
    text = head
    for i, part in enumerate(parts):
        m = 1.0 if equal else masses[i]
        j = m * 0.01
        text += (
            f"[[joint]]\nmass_kg = {m}\ncom_mm = [{50.0 * i}, 20.0, -30.0]\n"
            f"inertia_kg_m2 = [{j}, {j * 1.2}, {j * 0.8}, 0, 0, 0]\n{part}"
        )
    return text


def files(tmp_path, equal=False):
    (tmp_path / "robot.toml").write_text(robot_text(equal))
    setup = SETUP.replace('robot = "comau-smart5-nj165-3.0"', 'robot = "robot.toml"')
    path = tmp_path / "setup.toml"
    path.write_text(setup)
    return path


def test_predict_gives_the_commands_modes_and_surge(tmp_path, cli):
    path = files(tmp_path)
    setup = stiffid.Setup.from_file(path)
    doc = stiffid.predict(setup, Q, [200, -100, -1500, 0, 0, 0])
    command = cli("predict", "--setup", path, "--q-deg", ",".join(map(str, Q)), "--wrench", "200,-100,-1500", "--json")
    for key in ["natural_frequencies_hz", "mode_shapes", "effective_mass_kg", "effective_mass_free_kg", "surge_mm_s"]:
        assert doc[key] == command[key], key
    m, v = doc["effective_mass_kg"], doc["surge_mm_s"] * 1e-3
    c = doc["compliance_along_force_mm_per_n"] * 1e-3
    f2 = 200.0**2 + 100.0**2 + 1500.0**2
    assert abs(0.5 * m * v * v - 0.5 * f2 * c) < 1e-12 * f2 * c


def test_kinematics_gives_the_commands_frequencies(tmp_path, cli):
    files(tmp_path)
    robot = stiffid.Robot.from_file(tmp_path / "robot.toml")
    doc = robot.kinematics(Q, stiffness_nm_per_rad=K)
    command = cli("kinematics", "--robot", tmp_path / "robot.toml", "--q-deg", ",".join(map(str, Q)), "--stiffness-nm-per-rad", ",".join(map(str, K)), "--json")
    assert doc["natural_frequencies_hz"] == command["natural_frequencies_hz"]
    assert np.all(np.diff(doc["natural_frequencies_hz"]) >= 0)


def test_placeholder_masses_warn(tmp_path):
    setup = stiffid.Setup.from_file(files(tmp_path, equal=True))
    with pytest.warns(UserWarning, match="placeholders"):
        doc = stiffid.predict(setup, Q, [0, 0, -1000, 0, 0, 0])
    assert doc["natural_frequencies_hz"] is None and doc["warnings"][0]["kind"] == "masses"
