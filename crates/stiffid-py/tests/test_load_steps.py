"""identify on raw tracker readings under load steps: noise-free recovery with offsets, the same document as the command; load steps in the setup scale the predicted rates."""

import numpy as np
import pytest

import stiffid
from conftest import REPO, plain as to_json

LOADS = [0.0, 100.0, 200.0, 300.0, 400.0, 500.0, 300.0, 100.0]
HEADER = "posture,point,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg,load_n,fx_n,fy_n,fz_n,x_mm,y_mm,z_mm"


def readings(setup, path, offset_mm):
    """Readings simulated from the forward model: tau = J_f^T W, dq = h tau, delta = J_m[:3] dq."""
    robot = setup.robot
    h = 1.0 / setup.nominal_stiffness_nm_per_rad
    direction = np.array([0.3, -0.2, -1.0]) / np.linalg.norm([0.3, -0.2, -1.0])
    lines = [HEADER]
    for i, q in enumerate(setup.random_group(6, seed=3)):
        pose = robot.flange_pose(q)
        jf = robot.jacobian(q, setup.loading_point_mm)
        for k, point in enumerate(setup.measuring_points_mm):
            rest = (pose @ np.append(point, 1.0))[:3]
            jm = robot.jacobian(q, point)
            for f in LOADS:
                wrench = np.concatenate([direction * f, np.zeros(3)])
                delta_mm = 1e3 * jm[:3] @ (h * (jf.T @ wrench))
                shift = direction * offset_mm if f > 0 else np.zeros(3)
                x = rest + delta_mm + shift
                numbers = ",".join(repr(float(v)) for v in [*q, f, *wrench[:3], *x])
                lines.append(f"P{i},{k + 1},{numbers}")
    path.write_text("\n".join(lines) + "\n")
    return path


def test_offsets_are_recovered_and_equal_the_command(paper, cli, tmp_path):
    path = readings(paper, tmp_path / "readings.csv", 0.02)
    result = stiffid.identify(paper, path, offsets=True)
    np.testing.assert_allclose(result["stiffness_nm_per_rad"], paper.nominal_stiffness_nm_per_rad, rtol=1e-7)
    doc = to_json(result)
    assert len(doc["offsets"]) == 6 * 4 and len(doc["load_steps"]) == 6
    for o in doc["offsets"]:
        assert np.linalg.norm(o["offset_mm"]) == pytest.approx(0.02, abs=1e-9)
    for step in doc["load_steps"]:
        assert step["levels"] == 5 and step["zero_load_offset_mm"] == pytest.approx(0.02, abs=1e-9)
        assert step["hysteresis_mm"] == pytest.approx(0.0, abs=1e-9)
    assert doc == cli("identify", "--setup", "zhang2021-comau-nj165", "--data", path, "--offsets", "--json")
    without = stiffid.identify(paper, path)
    assert without["offsets"] is None
    assert np.max(np.abs(without["stiffness_nm_per_rad"] / paper.nominal_stiffness_nm_per_rad - 1)) > 1e-3


def test_a_loaded_first_reading_is_named(paper, tmp_path):
    path = tmp_path / "bad.csv"
    path.write_text(HEADER + "\nA,1,0,0,-90,0,0,0,100,0,0,-100,2000,0,2000\n")
    with pytest.raises(stiffid.InputError, match=r"bad.csv.*line 2.*start with the unloaded one"):
        stiffid.identify(paper, path)



def test_load_steps_in_the_setup_scale_the_predicted_rates(paper):
    text = (REPO / "crates" / "stiffid-core" / "setups" / "zhang2021-comau-nj165.toml").read_text()
    stepped = stiffid.Setup.from_toml(text.replace("[loading]\n", "[loading]\nsteps_n = [100, 200, 300, 400, 500]\n"))
    assert paper.load_steps_n == [] and stepped.load_steps_n == [100.0, 200.0, 300.0, 400.0, 500.0]
    group = paper.random_group(6, 1)
    # F^2 (S2 + S1^2) / S2^2: the least squares over every step, the unloaded reading shared,
    # over the 2 of one loaded minus one unloaded reading.
    factor = 500.0**2 * (550_000.0 + 1500.0**2) / 550_000.0**2 / 2.0
    np.testing.assert_allclose(stepped.evaluate(group)["predicted_deviation_pct"],
                               np.sqrt(factor) * paper.evaluate(group)["predicted_deviation_pct"], rtol=1e-9)
