"""The robot's mass from Python: the same frequencies, effective masses and surge as the command,
placeholder masses a UserWarning."""

from pathlib import Path

import numpy as np
import pytest

import stiffid

ROOT = Path(__file__).resolve().parents[3]
COMAU = (ROOT / "crates/stiffid-core/presets/comau-smart5-nj165-3.0.toml").read_text()
SETUP = (ROOT / "crates/stiffid-core/setups/zhang2021-comau-nj165.toml").read_text()
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


def test_masses_known_to_a_percentage_widen_the_surge_as_the_command_says(tmp_path, cli):
    path = files(tmp_path)
    path.write_text(path.read_text() + "\n[masses]\nsd_pct = 10\n")
    setup = stiffid.Setup.from_file(path)
    doc = stiffid.predict(setup, Q, [200, -100, -1500, 0, 0, 0])
    command = cli("predict", "--setup", path, "--q-deg", ",".join(map(str, Q)), "--wrench", "200,-100,-1500", "--json")
    for key in ["effective_mass_std_kg", "surge_std_mm_s"]:
        assert doc[key] == command[key], key
    m, sd = doc["effective_mass_kg"], doc["effective_mass_std_kg"]
    assert 0 < sd < 0.1 * m
    # The nominal stiffness has no covariance: the surge's uncertainty is the mass's alone.
    expected = doc["surge_mm_s"] * sd / (2 * m)
    assert abs(doc["surge_std_mm_s"] - expected) < 1e-12 * expected


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


DRILL = (
    'kind = "drilling"\n[tool]\ndiameter_mm = 10\n[cut]\nfeed_per_rev_mm = 0.2\n'
    "[coefficients]\nspecific_energy_n_per_mm2 = 800\nspecific_thrust_n_per_mm2 = 1000\n"
)


def drilling(tmp_path, tcp_mm):
    """The setup (its path) with the tool point `tcp_mm` and a workpiece, two G81 holes, the
    drilling process and the stiffness file."""
    path = files(tmp_path)
    text = path.read_text().replace("[tool]\n", f"[tool]\ntcp_mm = {tcp_mm}\n", 1)
    text += "\n[workpiece]\nbase_from_part = { xyz_mm = [1500, 0, 300], rpy_deg = [0, 0, 0] }\n"
    path.write_text(text)
    program = tmp_path / "holes.nc"
    program.write_text("(stiffid: tool_rpy_deg = 180 0 0)\nG0 X0 Y0 Z10\nG81 X20 Y10 Z-8 R2 F120\nX40\nG80\n")
    process = tmp_path / "drill.toml"
    process.write_text(DRILL)
    stiffness = tmp_path / "k.json"
    stiffness.write_text('{"stiffness_nm_per_rad": [950000, 3000000, 900000, 250000, 200000, 150000]}')
    return path, program, process, stiffness


def test_compensate_gives_the_commands_surge_at_each_drilling_exit(tmp_path, cli):
    path, program, process, stiffness = drilling(tmp_path, [0, 0, 250])
    setup = stiffid.Setup.from_file(path)
    mine = stiffid.compensate(setup, stiffness=stiffness, program=program, process=process)
    surge = mine["surge_mm_s"]
    exits = ~np.isnan(surge)
    assert exits.sum() == 2
    assert np.all(np.isnan(mine["first_frequency_hz"]))
    command = cli("compensate", "--setup", path, "--stiffness", stiffness, "--program", program, "--process", process,
                  "--out", tmp_path / "out.nc", "--json")
    rows = command["points"]
    assert [r["surge_mm_s"] for r in rows if r["surge_mm_s"] is not None] == list(surge[exits])
    assert mine["document"]["program"]["dynamics"] == command["program"]["dynamics"]
    # The held mass and the surge give back the energy F^2 c / 2 of a positive compliance.
    m = mine["effective_mass_kg"][exits]
    assert np.all(m > 0) and np.all(surge[exits] > 0)


def test_the_free_tool_axis_minimises_the_surge_as_the_command_does(tmp_path, cli):
    # A spindle 120 mm off the flange axis: a turn about the drill moves the whole arm.
    path, program, process, stiffness = drilling(tmp_path, [120, 0, 250])
    setup = stiffid.Setup.from_file(path)
    # Written as KRL: a G-code program has no word for the rotation chosen.
    free = dict(free=["tool-rotation=-90..90/20"], output="krl")
    mine = stiffid.compensate(setup, stiffness=stiffness, program=program, process=process,
                              minimise="surge", **free)
    assert mine["document"]["minimise"] == "surge"
    assert [f["variable"] for f in mine["document"]["free"]] == ["tool-rotation"]
    exits = ~np.isnan(mine["surge_mm_s"])
    assert exits.sum() == 2
    assert np.all(mine["surge_mm_s"][exits] <= mine["surge_before_mm_s"][exits])
    command = cli("compensate", "--setup", path, "--stiffness", stiffness, "--program", program, "--process", process,
                  "--free", "tool-rotation=-90..90/20", "--minimise", "surge", "--out", tmp_path / "out.src", "--json")
    rows = command["points"]
    for key in ["tool_rotation_deg", "surge_mm_s", "surge_before_mm_s"]:
        theirs = np.array([np.nan if r[key] is None else r[key] for r in rows])
        np.testing.assert_array_equal(mine[key], theirs)
    assert mine["document"]["program"]["dynamics"] == command["program"]["dynamics"]
    # The default objective is the bound the document reports; the objective means nothing
    # without a free variable.
    bound = stiffid.compensate(setup, stiffness=stiffness, program=program, process=process, **free)
    assert bound["document"]["minimise"] == "bound"
    with pytest.raises(ValueError, match=r"minimise: only with free"):
        stiffid.compensate(setup, stiffness=stiffness, program=program, process=process,
                           minimise="surge")
    with pytest.raises(ValueError, match=r"minimise: unknown value 'speed'"):
        stiffid.compensate(setup, stiffness=stiffness, program=program, process=process,
                           minimise="speed", **free)
