"""identify and validate: the FANUC data equal to the command's, noise-free recovery, bad data."""

import subprocess
from pathlib import Path

import numpy as np
import pytest

import stiffid
from conftest import FANUC_DATA, cli_path, plain


@pytest.fixture(scope="module")
def fanuc_cli(cli):
    return cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--json")


def test_the_documents_equal_the_command(fanuc, cli, fanuc_cli):
    """One job, two front ends: the same call gives the same document, key for key and bit for bit."""
    assert plain(stiffid.identify(fanuc, FANUC_DATA)) == fanuc_cli
    for flags, kwargs in [
        (["--robust"], dict(robust="huber")),
        (["--robust", "tukey"], dict(robust="tukey")),
        (["--nonnegative"], dict(nonnegative=True)),
        (["--cross-validate"], dict(cross_validate=True)),
        (["--folds", "5", "--nonnegative"], dict(folds=5, nonnegative=True)),
    ]:
        theirs = cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, *flags, "--json")
        assert plain(stiffid.identify(fanuc, FANUC_DATA, **kwargs)) == theirs, flags


def test_the_result_is_the_document_with_arrays(fanuc, fanuc_cli):
    """A dict with the command's keys; the stiffness, compliance, their errors, intervals and
    covariance as NumPy arrays."""
    mine = stiffid.identify(fanuc, FANUC_DATA)
    assert isinstance(mine, dict) and mine.keys() == fanuc_cli.keys()
    assert mine["method"] == "least-squares" and mine["stiffness_nm_per_rad"].shape == (6,)
    assert mine["ci95_nm_per_rad"].shape == (6, 2)
    assert mine["compliance_covariance_rad2_per_nm2"].shape == (6, 6)
    np.testing.assert_array_equal(mine["stiffness_nm_per_rad"], fanuc_cli["stiffness_nm_per_rad"])
    assert mine["residuals"] == fanuc_cli["residuals"] and len(mine["residuals"]) == 43
    assert mine["cross_validation"] is None
    assert mine["region"]["postures"] == 43


def test_displacements_in_metres_warn_as_the_command(fanuc, tmp_path):
    """The FANUC data with its displacements written in m instead of mm: the stiffness comes out
    about 1000 times the nominal, and Python warns with the command's words."""
    lines = FANUC_DATA.read_text().splitlines()
    header = lines[0].split(",")
    d = [header.index(c) for c in ("dx_mm", "dy_mm", "dz_mm")]
    out = [lines[0]]
    for line in lines[1:]:
        fields = line.split(",")
        for c in d:
            fields[c] = repr(float(fields[c]) / 1000)
        out.append(",".join(fields))
    metres = tmp_path / "metres.csv"
    metres.write_text("\n".join(out) + "\n")
    with pytest.warns(UserWarning) as caught:
        mine = stiffid.identify(fanuc, metres)
    messages = [str(w.message) for w in caught]
    assert any("in m instead of mm" in m for m in messages), messages
    assert mine["unit_warning"] in messages
    run = subprocess.run([str(cli_path()), "identify", "--setup", "fanuc-r2000ic-165f", "--data", str(metres)],
                         capture_output=True, text=True, check=True)
    assert [l.removeprefix("warning: ") for l in run.stderr.splitlines()] == messages


def test_cross_validation_from_arrays(paper):
    k = np.array([900000.0, 2500000, 1000000, 300000, 180000, 120000])
    q, wrench, d = synthetic(paper, k)
    mine = stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d, cross_validate=True)
    cv = mine["cross_validation"]
    assert cv["folds"] == len(q) and len(cv["per_fold"]) == len(q)
    np.testing.assert_allclose(cv["stiffness_mean_nm_per_rad"], k, rtol=1e-8)
    assert cv["rms_delta_b_mm"] < 1e-9 and cv["explained"] == pytest.approx(1.0)
    assert [f["postures"] for f in cv["per_fold"]][:2] == [["1"], ["2"]]
    assert "line" not in mine["residuals"][0]
    with pytest.raises(ValueError, match="folds: expected 2 to 9"):
        stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d, folds=10)


def test_fanuc_stiffness_is_the_numpy_reference(fanuc):
    """The independent NumPy fit of examples/data/fanuc-r2000ic-165f/numpy_reference.py (also the
    reference of crates/stiffid-cli/tests/it/identify_cli.rs): k1 of about 8.6e5 Nm/rad."""
    k = stiffid.identify(fanuc, FANUC_DATA)["stiffness_nm_per_rad"]
    assert k.shape == (6,)
    assert k[0] == pytest.approx(8.609e5, rel=1e-3)


def synthetic(setup, stiffness):
    """Noise-free displacements of the setup's measuring points in its test postures under the
    rope load, from the library's forward model (validate's prediction)."""
    q = np.vstack([setup.test_postures_deg, setup.random_group(6, 3)])
    wrench = np.tile([300.0, -200.0, -400.0, 20.0, -10.0, 5.0], (len(q), 1))
    p = len(setup.measuring_points_mm)
    zero = np.zeros((len(q) * p, 3))
    v = stiffid.validate(setup, stiffness, q_deg=q, wrench=wrench, displacement_mm=zero)
    return q, wrench, v["predicted_mm"]


def test_noise_free_recovery_from_arrays(paper):
    k = np.array([900000.0, 2500000, 1000000, 300000, 180000, 120000])
    q, wrench, d = synthetic(paper, k)
    mine = stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d)
    np.testing.assert_allclose(mine["stiffness_nm_per_rad"], k, rtol=1e-9)
    assert mine["residual_rms_mm"] < 1e-12
    assert mine["data"] == "arrays" and mine["postures"] == len(q)
    checked = stiffid.validate(paper, k, q_deg=q, wrench=wrench, displacement_mm=d)
    assert checked["max_delta_b_mm"] < 1e-12 and checked["explained"] == pytest.approx(1.0)


def test_force_only_wrench_is_a_zero_moment(paper):
    k = paper.nominal_stiffness_nm_per_rad
    q, wrench, _ = synthetic(paper, k)
    force = wrench[:, :3]
    zero = np.zeros((len(q) * 4, 3))
    a = stiffid.validate(paper, k, q_deg=q, wrench=force, displacement_mm=zero)
    six = np.hstack([force, np.zeros_like(force)])
    b = stiffid.validate(paper, k, q_deg=q, wrench=six, displacement_mm=zero)
    np.testing.assert_array_equal(a["predicted_mm"], b["predicted_mm"])


def test_the_validate_document_equals_the_command(fanuc, cli, fanuc_cli, tmp_path):
    """One job, two front ends: the same stiffness on the same data gives the same document."""
    path = tmp_path / "k.json"
    path.write_text('{"stiffness_nm_per_rad": %s}' % list(fanuc_cli["stiffness_nm_per_rad"]))
    theirs = cli("validate", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--stiffness", path, "--json")
    mine = stiffid.validate(fanuc, fanuc_cli["stiffness_nm_per_rad"], FANUC_DATA)
    arrays = ["delta_b_mm", "measured_mm", "predicted_mm"]
    assert {key: value for key, value in mine.items() if key not in arrays} == theirs
    from_file = stiffid.validate(fanuc, path, FANUC_DATA)
    np.testing.assert_array_equal(from_file["delta_b_mm"], mine["delta_b_mm"])
    np.testing.assert_array_equal(mine["delta_b_mm"], [c["delta_b_mm"] for c in theirs["checks"]])
    np.testing.assert_array_equal(mine["predicted_mm"], [c["predicted_mm"] for c in theirs["checks"]])


def fanuc_with(tmp_path, line, column, value):
    """The FANUC data with one field replaced (line and column 1-based), as bad.csv."""
    lines = FANUC_DATA.read_text().splitlines()
    fields = lines[line - 1].split(",")
    fields[column - 1] = value
    lines[line - 1] = ",".join(fields)
    bad = tmp_path / "bad.csv"
    bad.write_text("\n".join(lines) + "\n")
    return bad


def test_bad_csv_names_file_line_and_column(fanuc, tmp_path):
    with pytest.raises(ValueError, match=r"bad.csv: line 4, column 9 \(fx_n\).*heavy"):
        stiffid.identify(fanuc, fanuc_with(tmp_path, 4, 9, "heavy"))


def test_measurement_outside_the_limits_names_its_line(fanuc, tmp_path):
    with pytest.raises(ValueError, match=r"bad.csv: line 3, column 3 \(q1_deg\)"):
        stiffid.identify(fanuc, fanuc_with(tmp_path, 3, 3, "400"))


def test_missing_file(fanuc, tmp_path):
    with pytest.raises(FileNotFoundError, match="none.csv: no such file"):
        stiffid.identify(fanuc, tmp_path / "none.csv")
    with pytest.raises(ValueError, match="is a directory, expected a file"):
        stiffid.identify(fanuc, tmp_path)
    for robust in [None, "huber"]:  # read whole, or in pieces: a device is no input file
        with pytest.raises(ValueError, match="/dev/zero: is a device, not a regular file; give a file"):
            stiffid.identify(fanuc, "/dev/zero", robust=robust)


def test_wrong_shapes_are_refused(paper):
    q, wrench, d = synthetic(paper, paper.nominal_stiffness_nm_per_rad)
    with pytest.raises(ValueError, match=r"wrench: expected 9 rows \(one per posture\), got 8"):
        stiffid.identify(paper, q_deg=q, wrench=wrench[:8], displacement_mm=d)
    with pytest.raises(ValueError, match=r"wrench: expected an array of shape \(n, 3\) or \(n, 6\)"):
        stiffid.identify(paper, q_deg=q, wrench=wrench[:, :4], displacement_mm=d)
    with pytest.raises(ValueError, match=r"displacement_mm: expected 36 rows, one per posture and measuring point .* got 35"):
        stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d[:-1])
    with pytest.raises(ValueError, match="displacement_mm: expected an array of shape"):
        stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d[:, :2])
    with pytest.raises(ValueError, match="give either a measurements CSV path"):
        stiffid.identify(paper, q_deg=q, wrench=wrench)
    with pytest.raises(ValueError, match="robust: unknown value 'cauchy'"):
        stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d, robust="cauchy")


def test_unphysical_data_names_the_measurement(paper):
    q, wrench, d = synthetic(paper, paper.nominal_stiffness_nm_per_rad)
    d = d.copy()
    d[5, 1] = 5000.0  # 5 m: a unit error
    with pytest.raises(ValueError, match="measurement 6"):
        stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d)


def test_validate_refuses_a_bad_stiffness(paper):
    q, wrench, d = synthetic(paper, paper.nominal_stiffness_nm_per_rad)
    with pytest.raises(ValueError, match="stiffness_nm_per_rad"):
        stiffid.validate(paper, [1, 2, 3], q_deg=q, wrench=wrench, displacement_mm=d)
    with pytest.raises(ValueError, match="stiffness_nm_per_rad"):
        stiffid.validate(paper, [-1, 2, 3, 4, 5, 6], q_deg=q, wrench=wrench, displacement_mm=d)


def test_bad_stiffness_file_names_it(fanuc, tmp_path):
    path = tmp_path / "k.json"
    path.write_text('{"stiffness_nm_per_rad": [1, 2]}')
    with pytest.raises(ValueError, match="k.json: "):
        stiffid.validate(fanuc, path, FANUC_DATA)


def test_deflection_is_the_measurement_model(paper):
    """The displacement of measuring point i under the rope wrench is what validate predicts."""
    k = np.array([900000.0, 2500000, 1000000, 300000, 180000, 120000])
    q, wrench, d = synthetic(paper, k)
    docs = stiffid.deflection(paper, q, wrench, stiffness_nm_per_rad=k)
    for i in range(len(paper.measuring_points_mm)):
        mine = [doc["measuring_points"][i]["displacement_mm"] for doc in docs]
        np.testing.assert_allclose(mine, d[i::4], rtol=1e-10, atol=1e-15)


def test_deflection_uncertainty(fanuc):
    result = stiffid.identify(fanuc, FANUC_DATA)
    q = fanuc.random_group(3, 1)
    out = stiffid.deflection(fanuc, q, [0, 0, -1000, 0, 0, 0], stiffness_nm_per_rad=result["stiffness_nm_per_rad"],
                             compliance_covariance_rad2_per_nm2=result["compliance_covariance_rad2_per_nm2"])
    assert len(out) == 3 and all(s > 0 for doc in out for s in doc["tcp_deflection_std_mm"])
    with pytest.raises(ValueError, match="compliance_covariance_rad2_per_nm2: expected a covariance"):
        stiffid.deflection(fanuc, q, [0, 0, -1000, 0, 0, 0], stiffness_nm_per_rad=result["stiffness_nm_per_rad"],
                           compliance_covariance_rad2_per_nm2=-np.eye(6))
    with pytest.raises(ValueError, match=r"wrench: expected shape \(6,\) or \(3, 6\)"):
        stiffid.deflection(fanuc, q, np.zeros((2, 6)))


def test_a_file_of_many_chunks_equals_the_arrays_and_the_command(fanuc, cli, tmp_path):
    """A file of 25 000 rows (the FANUC rows cycled, each its own posture: more than one chunk of
    the streamed reader, 2 MiB of text) identified from its path (read once in chunks) equals the same rows given
    as arrays (in memory) to 1e-12 and the command's JSON."""
    lines = [l for l in FANUC_DATA.read_text().splitlines() if l and not l.startswith("#")]
    header, rows = lines[0], [l.split(",") for l in lines[1:]]
    assert header.startswith("posture,point,q1_deg") and header.endswith("fx_n,fy_n,fz_n,dx_mm,dy_mm,dz_mm")
    n = 25_000
    q = np.array([[float(v) + 1e-4 * (i // len(rows)) for v in rows[i % len(rows)][2:8]] for i in range(n)])
    wrench = np.array([[float(v) for v in rows[i % len(rows)][8:11]] for i in range(n)])
    d = np.array([[float(v) for v in rows[i % len(rows)][11:14]] for i in range(n)])
    path = tmp_path / "large.csv"
    with path.open("w") as f:
        f.write(header + "\n")
        for i in range(n):
            src = rows[i % len(rows)]
            f.write(",".join([f"p{i}", src[1], *(repr(float(v)) for v in q[i]), *src[8:]]) + "\n")
    assert path.stat().st_size > 2 * 2**20
    from_file = stiffid.identify(fanuc, path)
    from_arrays = stiffid.identify(fanuc, q_deg=q, wrench=wrench, displacement_mm=d)
    assert (from_file["rows"], from_file["postures"]) == (3 * n, n)
    np.testing.assert_allclose(from_file["stiffness_nm_per_rad"], from_arrays["stiffness_nm_per_rad"], rtol=1e-12)
    residuals = [[r["residual_mm"] for r in x["residuals"]] for x in (from_file, from_arrays)]
    np.testing.assert_allclose(residuals[0], residuals[1], rtol=0, atol=1e-12)
    assert from_file["residuals"][n - 1]["posture"] == f"p{n - 1}" and len(from_file["residuals"]) == n
    theirs = cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", path, "--json")
    np.testing.assert_array_equal(from_file["stiffness_nm_per_rad"], theirs["stiffness_nm_per_rad"])
    assert theirs["residuals"][n - 1]["line"] == n + 1


def test_errors_are_stiffid_errors_by_kind(paper):
    assert issubclass(stiffid.Error, ValueError)
    for kind in (stiffid.InputError, stiffid.InfeasibleError, stiffid.UnidentifiableError):
        assert issubclass(kind, stiffid.Error)
    q, wrench, d = synthetic(paper, paper.nominal_stiffness_nm_per_rad)
    with pytest.raises(stiffid.InputError, match="robust: unknown value"):
        stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d, robust="cauchy")
    vertical = np.zeros_like(wrench)
    vertical[:, 2] = -500.0  # a vertical force alone has no moment about joint 1's vertical axis
    with pytest.raises(stiffid.UnidentifiableError, match="arrays: joint 1 cannot be identified"):
        stiffid.identify(paper, q_deg=q, wrench=vertical, displacement_mm=d)


def test_rows_are_postures_times_the_measuring_points_or_point_says_which(paper):
    k = paper.nominal_stiffness_nm_per_rad
    q, wrench, d = synthetic(paper, k)
    per_posture = d.reshape(len(q), 4, 3)
    three = per_posture[:, [0, 1, 3]].reshape(-1, 3)
    # Three rows per posture for a four-point setup: refused, not read as points 1-3.
    with pytest.raises(ValueError, match="displacement_mm"):
        stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=three)
    with pytest.raises(ValueError, match="displacement_mm"):
        stiffid.validate(paper, k, q_deg=q, wrench=wrench, displacement_mm=three)
    fit = stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=three, point=[1, 2, 4])
    np.testing.assert_allclose(fit["stiffness_nm_per_rad"], k, rtol=1e-9)
    for bad in ([1, 2, 5], [1, 1, 2], [0, 1, 2], []):
        with pytest.raises(ValueError, match="point"):
            stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=three, point=bad)


def test_unit_slips_in_setups_and_angles_warn_as_the_command(fanuc, tmp_path):
    """Tool points in metres and axis angles in radians pass every range check; Python raises the
    command's plausibility warnings for both."""
    cell = (Path(__file__).parents[3] / "examples" / "cell" / "zhang2021-tracker.toml").read_text()
    metres = cell.replace("[150.0, 0.0, 200.0]", "[0.15, 0.0, 0.2]")
    for x, y in [("80.0", "80.0"), ("-80.0", "80.0"), ("-80.0", "-80.0"), ("80.0", "-80.0")]:
        metres = metres.replace(f"[{x}, {y}, 260.0]", f"[{float(x) / 1e3}, {float(y) / 1e3}, 0.26]")
    assert metres.count("0.26]") == 4
    with pytest.warns(UserWarning, match="given in metres instead of mm"):
        stiffid.Setup.from_toml(metres)
    lines = FANUC_DATA.read_text().splitlines()
    header = lines[0].split(",")
    q = [header.index(f"q{a}_deg") for a in range(1, 7)]
    out = [lines[0]]
    for line in lines[1:]:
        fields = line.split(",")
        for i in q:
            fields[i] = repr(float(np.radians(float(fields[i]))))
        out.append(",".join(fields))
    radians = tmp_path / "radians.csv"
    radians.write_text("\n".join(out) + "\n")
    with pytest.warns(UserWarning, match="radians under _deg names") as caught:
        stiffid.identify(fanuc, radians)
    run = subprocess.run([str(cli_path()), "identify", "--setup", "fanuc-r2000ic-165f", "--data", str(radians)],
                         capture_output=True, text=True, check=True)
    assert [l.removeprefix("warning: ") for l in run.stderr.splitlines()] == [str(w.message) for w in caught]


def test_the_scene_of_an_identification_draws_its_displacements(paper):
    """stiffid.scene(setup, q_deg, document=identify(...)): each arrow the document's measured and
    predicted displacement of its posture and point, the ellipsoid's semi-axes the identified
    compliance's eigenvalues times the load; a plan document gives the plan's postures; another
    document, or postures that are not the document's, are refused."""
    k = np.array([900000.0, 2500000, 1000000, 300000, 180000, 120000])
    q, wrench, d = synthetic(paper, k)
    doc = stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d)
    scene = stiffid.scene(paper, q, document=doc).document()
    assert len(scene["postures"]) == len(q)
    for r in doc["residuals"]:
        a = scene["postures"][int(r["posture"]) - 1]["arrows"][r["point"] - 1]
        np.testing.assert_allclose(np.array(a["measured_m"]) * 1e3, r["measured_mm"], rtol=1e-12)
        np.testing.assert_allclose(np.array(a["predicted_m"]) * 1e3, r["predicted_mm"], rtol=1e-12)
    for p in scene["postures"]:
        e = p["ellipsoid"]
        np.testing.assert_allclose(e["semi_axes_m"], scene["ellipsoid_force_n"] * np.array(e["compliance_m_per_n"]))
    plan = stiffid.plan(paper, q[:3])
    by_plan = stiffid.scene(paper, document=plan).document()
    np.testing.assert_allclose([p["q_deg"] for p in by_plan["postures"]], q[:3], atol=1e-9)
    with pytest.raises(stiffid.InputError, match="postures"):
        stiffid.scene(paper, q[:3], document=doc)
    with pytest.raises(stiffid.InputError, match="document"):
        stiffid.scene(paper, q, document={"setup": "x"})
    # Which document it is, its `kind` says: the residuals alone make no identification.
    with pytest.raises(stiffid.InputError, match='document: its `kind` is ""'):
        stiffid.scene(paper, q, document={k: v for k, v in doc.items() if k != "kind"})
