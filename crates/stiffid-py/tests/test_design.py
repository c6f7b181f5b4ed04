"""Setup, evaluate and select: the documents of the command's jobs, equal to its JSON."""

import numpy as np
import pytest

import stiffid
from conftest import plain, write_postures


def test_setup_fields(paper):
    assert paper.name == "zhang2021-comau-nj165"
    np.testing.assert_array_equal(
        paper.nominal_stiffness_nm_per_rad, [950000, 3000000, 900000, 250000, 200000, 150000]
    )
    np.testing.assert_allclose(paper.lower_deg, [-90, -60, -180, -180, -90, -180], atol=1e-12)
    np.testing.assert_allclose(paper.upper_deg, [90, 40, -40, 180, 90, 180], atol=1e-12)
    assert paper.load_n == 500.0
    assert paper.noise_variance_mm2 == pytest.approx(9.23e-5)
    np.testing.assert_array_equal(paper.level_multiples, [0.5, 1.0, 1.5, 2.0, 2.5, 3.0])
    assert paper.measuring_points_mm.shape == (4, 3)
    assert paper.test_postures_deg.shape == (3, 6)
    assert paper.springs == "axis"
    assert paper.robot.name == "COMAU SMART5 NJ 165-3.0"
    assert set(stiffid.Setup.builtins()) >= {"zhang2021-comau-nj165", "fanuc-r2000ic-165f"}


def timeless(document):
    """A select document without what differs between two runs of one call: the wall-clock time,
    the command's output paths and the pool's name (a file for the command, `arrays` here)."""
    document = {key: value for key, value in document.items() if key not in ("elapsed_s", "out", "report")}
    if "pool" in document:
        document["pool"] = {key: value for key, value in document["pool"].items() if key != "file"}
    return document


def test_the_evaluate_document_equals_the_command(paper, cli, tmp_path):
    """One job, two front ends: the same group gives the same document, key for key and bit for bit."""
    group = paper.random_group(6, 7)
    path = write_postures(tmp_path / "group.csv", group)
    mine = paper.evaluate(group)
    assert mine["predicted_deviation_pct"].shape == (6, 6) and mine["relative_std"].shape == (6,)
    assert plain(mine) == cli("evaluate", "--setup", "zhang2021-comau-nj165", "--postures", path, "--json")


def test_evaluate_prediction_is_the_formula(paper):
    e = paper.evaluate(paper.random_group(6, 1))
    factor = 100 * np.sqrt(2 / np.pi) * np.sqrt(paper.level_multiples)[:, None]
    np.testing.assert_allclose(e["predicted_deviation_pct"], factor * e["relative_std"][None, :], rtol=1e-12)
    assert e["relative_a"] == pytest.approx(np.sqrt(np.mean(e["relative_std"] ** 2)), rel=1e-12)
    assert [p["name"] for p in e["parameters"]] == ["k1", "k2", "k3", "k4", "k5", "k6"]
    assert all(p["identified"] and p["unit"] == "Nm/rad" for p in e["parameters"])
    assert e["unidentifiable"] == [] and len(e["feasibility"]) == 6


def test_the_select_documents_equal_the_command(paper, cli, tmp_path):
    """One job, two front ends: local, global, pool and target choices give the same document,
    with the same solver named (the default, auto, names the one it ran for the criterion)."""
    pool = paper.random_group(12, 5)
    pool_csv = write_postures(tmp_path / "pool.csv", pool)
    setup = ["--setup", "zhang2021-comau-nj165", "--out", tmp_path / "out.csv", "--json"]
    for flags, kwargs, solver in [
        (["--criterion", "zhang2021", "--start-random", "--seed", 1], dict(criterion="zhang2021", method="local", n=6),
         "slsqp"),
        (["--global", "--seed", 3, "--starts", 4, "--polished", 2, "--max-evals", 1000],
         dict(method="global", seed=3, starts=4, polished=2, max_evals=1000), "active-set"),
        (["--global", "--seed", 3, "--starts", 4, "--polished", 2, "--max-evals", 1000, "--solver", "slsqp"],
         dict(method="global", seed=3, starts=4, polished=2, max_evals=1000, solver="slsqp"), "slsqp"),
        (["--pool", pool_csv, "--count", 6], dict(pool=pool, n=6), None),
        (["--pool", pool_csv, "--target-pct", 6], dict(pool=pool, target_pct=6), None),
    ]:
        mine = paper.select(**kwargs)
        theirs = cli("select", *setup, *flags)
        assert timeless(plain(mine)) == timeless(theirs), flags
        assert mine.get("solver") == solver, flags
    assert mine["search"] == "pool" and mine["target"]["postures"] == len(mine["postures_deg"])
    assert "solver" not in mine and "gradient" not in mine


def test_a_distinct_pool_choice_equals_the_command(paper, cli, tmp_path):
    """distinct=True keeps the first of every near pair of the pool, as --distinct does: a pool
    with two postures 1 deg from others gives the command's document, those two left out."""
    pool = paper.random_group(10, 5)
    near = pool[[2, 6]] + 1.0
    pool = np.vstack([pool, near])
    pool_csv = write_postures(tmp_path / "pool.csv", pool)
    mine = paper.select(pool=pool, n=6, distinct=True, distinct_deg=3, distinct_mm=20)
    theirs = cli("select", "--setup", "zhang2021-comau-nj165", "--out", tmp_path / "out.csv", "--json",
                 "--pool", pool_csv, "--count", 6, "--distinct", "--distinct-deg", 3, "--distinct-mm", 20)
    assert timeless(plain(mine)) == timeless(theirs)
    assert mine["pool"]["not_distinct"] == [[11, 3], [12, 7]]
    with pytest.raises(ValueError, match="distinct_deg: 1e9 is outside"):
        paper.select(pool=pool, n=6, distinct=True, distinct_deg=1e9)


def test_local_select_from_a_start(paper):
    start = paper.random_group(6, 2)
    found = paper.select("relative-a", start=start)
    assert found["search"] == "local"
    assert found["start_value"] == pytest.approx(paper.evaluate(start)["relative_a"], rel=1e-12)
    assert found["value"] == pytest.approx(found["criteria"]["relative_a"], rel=1e-12)
    assert found["value"] < found["start_value"]
    # Why it stopped, and the one search counted under its reason.
    counts = {c["termination"]: c["searches"] for c in found["terminations"]}
    assert counts[found["termination"]] == 1 and sum(counts.values()) == 1


def test_a_pool_choice_names_the_pool_rows(paper):
    pool = paper.random_group(12, 5)
    found = paper.select("relative-a", pool=pool, n=6, seed=1)
    p = found["pool"]
    assert p["method"] == "enumeration" and p["skipped"] == [] and p["file"] == "arrays"
    np.testing.assert_array_equal(found["postures_deg"], pool[[i - 1 for i in p["chosen"]]])
    assert "termination" not in found and found["start_value"] is None


def test_same_seed_same_group(paper):
    a = paper.select("d-optimal", method="global", seed=2, starts=2, polished=1, max_evals=300)
    b = paper.select("d-optimal", method="global", seed=2, starts=2, polished=1, max_evals=300)
    np.testing.assert_array_equal(a["postures_deg"], b["postures_deg"])


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(criterion="best"), r"unknown criterion 'best' \(known: classical, zhang2021"),
        (dict(method="annealing"), "method: unknown value 'annealing'"),
        (dict(n=1), "n"),
        (dict(n=101), "n"),
        (dict(starts=0), "starts"),
        (dict(gradient="numeric"), "gradient: unknown value 'numeric'"),
        (dict(solver="newton"), "solver: unknown value 'newton' \\(known: auto, slsqp, active-set\\)"),
        (dict(method="global", start=np.zeros((6, 6))), "start"),
        (dict(method="pool"), "pool"),
        (dict(restarts=3), "restarts: only for a pool choice"),
        (dict(method="local", target_pct=5), "target_pct: needs a pool or the global search"),
        (dict(method="global", target_pct=0.0), "target_pct"),
        (dict(method="global", distinct=True), "distinct"),
        (dict(distinct_deg=3.0), "distinct_deg, distinct_mm: only with distinct=True"),
    ],
)
def test_bad_select_arguments(paper, kwargs, message):
    with pytest.raises(ValueError, match=message):
        paper.select(**kwargs)


def test_start_outside_the_bounds_is_refused(paper):
    start = paper.random_group(6, 1)
    start[2, 1] = 45.0  # q2 bound: [-60, 40]
    with pytest.raises(ValueError, match=r"start: posture 2, q2_deg = 45 is outside the setup's bounds \[-60.0, 40.0\]"):
        paper.select(start=start)


def test_setup_from_toml_and_file(tmp_path, paper):
    text = (
        'name = "mine"\nrobot = "comau-smart5-nj165-3.0"\ncharacteristic_length_mm = 1200.0\n'
        "nominal_stiffness_nm_per_rad = [950000, 3000000, 900000, 250000, 200000, 150000]\n"
        "[tool]\nloading_point_mm = [150, 0, 200]\nmeasuring_points_mm = [[80, 80, 260], [-80, 80, 260]]\n"
        "[loading]\nload_n = 500.0\nanchor_mm = [1500, 1500, 0]\n"
        "[noise]\nreading_sd_mm = 0.0068\nlevel_multiples = [1.0]\n"
        "[bounds]\nlower_deg = [-90, -60, -180, -180, -90, -180]\nupper_deg = [90, 40, -40, 180, 90, 180]\n"
    )
    s = stiffid.Setup.from_toml(text)
    assert s.name == "mine" and s.measuring_points_mm.shape == (2, 3)
    path = tmp_path / "mine.toml"
    path.write_text(text)
    assert stiffid.Setup.from_file(path).name == "mine"
    with pytest.raises(ValueError, match=r"bad.toml: nominal_stiffness_nm_per_rad"):
        stiffid.Setup.from_toml(text.replace("950000,", "-1,"), source_name="bad.toml")
    with pytest.raises(ValueError, match="unknown field|unknown"):
        stiffid.Setup.from_toml(text + "colour = 1\n")
    one_point = stiffid.Setup.from_toml(text.replace(", [-80, 80, 260]]", "]"))
    with pytest.raises(ValueError, match="3 observation rows cannot identify 6 compliances"):
        one_point.evaluate(one_point.random_group(2, 1)[:1])
    with pytest.raises(ValueError, match=r"unknown setup 'nope' \(known: "):
        stiffid.Setup.builtin("nope")


def test_fields_only_some_criteria_use_may_be_left_out(paper, cli, tmp_path):
    text = cli("setups", "show", "zhang2021-comau-nj165", parse=False)
    without = {
        field: stiffid.Setup.from_toml("\n".join(l for l in text.splitlines() if not l.startswith(field)))
        for field in ["characteristic_length_mm", "nominal_stiffness_nm_per_rad"]
    }
    no_length, no_stiffness = without["characteristic_length_mm"], without["nominal_stiffness_nm_per_rad"]
    assert no_length.characteristic_length_mm is None and no_stiffness.nominal_stiffness_nm_per_rad is None
    assert no_length.nominal_stiffness_nm_per_rad.tolist() == paper.nominal_stiffness_nm_per_rad.tolist()
    group = paper.random_group(6, 1)
    full, e_length, e_stiffness = paper.evaluate(group), no_length.evaluate(group), no_stiffness.evaluate(group)
    assert e_length["classical"] is None and e_length["zhang2021"] is None
    assert e_length["relative_a"] == full["relative_a"]
    np.testing.assert_array_equal(e_length["predicted_deviation_pct"], full["predicted_deviation_pct"])
    for key in ["scaled_cond", "d_optimal", "relative_a", "relative_std", "predicted_deviation_pct"]:
        assert e_stiffness[key] is None, key
    assert e_stiffness["zhang2021"] == full["zhang2021"]
    with pytest.raises(ValueError, match=r"^the setup has no characteristic_length_mm: criterion classical needs it"):
        no_length.select("classical", method="local", start=group, max_evals=50)
    with pytest.raises(ValueError, match=r"^the setup has no nominal_stiffness_nm_per_rad: criterion relative-a needs it \(a rough prior"):
        no_stiffness.select(method="local", start=group, max_evals=50)
    assert no_stiffness.select("zhang2021", method="local", start=group, max_evals=50)["value"] > 0
    with pytest.raises(ValueError, match=r"nominal_stiffness_nm_per_rad: the simulation"):
        stiffid.simulate(no_stiffness, [group], runs=5)
    with pytest.raises(ValueError, match=r"nominal_stiffness_nm_per_rad: predict without a stiffness"):
        stiffid.deflection(no_stiffness, group[0], [0, 0, -500, 0, 0, 0])


def test_the_candidates_documents_equal_the_command(paper, cli, tmp_path):
    """Evaluate with candidates and select for the candidates: the same documents from Python and
    the command; the group designed for the candidates identifies every designable one together."""
    group = paper.random_group(6, 7)
    path = write_postures(tmp_path / "group.csv", group)
    mine = paper.evaluate(group, candidates=["tilt", "lost2"])
    theirs = cli("evaluate", "--setup", "zhang2021-comau-nj165", "--postures", path,
                 "--candidates", "tilt,lost2", "--json")
    assert plain(mine) == theirs
    assert {c["family"] for c in mine["candidates"]["candidates"]} == {"tilt", "lost"}
    assert mine["candidates"]["candidates"][-1]["needs_load_steps"]
    chosen = paper.select(method="global", n=8, starts=4, for_candidates=True, candidates=["tilt", "bend"])
    theirs = cli("select", "--setup", "zhang2021-comau-nj165", "--out", tmp_path / "out.csv", "--json",
                 "--global", "--count", 8, "--starts", 4, "--for-candidates", "--candidates", "tilt,bend")
    assert timeless(plain(chosen)) == timeless(theirs)
    c = chosen["candidates"]
    assert c["together"] and c["designed"] == c["designable"] and c["nonlinear"] == []
    assert all(k["identified"] for k in c["candidates"] if k["name"] in c["designable"])


def test_a_design_for_the_candidates_refuses(paper):
    with pytest.raises(ValueError, match=r"for_candidates: .* at least 5 postures"):
        paper.select(method="global", n=3, starts=2, for_candidates=True)
    with pytest.raises(ValueError, match=r"candidates: only with for_candidates"):
        paper.select(method="global", n=6, starts=2, candidates=["tilt"])
    with pytest.raises(ValueError, match=r"candidates: 'elbow' is not a candidate"):
        paper.evaluate(paper.random_group(6, 1), candidates=["elbow"])


def test_evaluate_and_select_for_the_calibration_equal_the_command(paper, cli, tmp_path):
    """purpose= is the command's --for, with the calibration's options: the same documents."""
    group = paper.random_group(8, 7)
    path = write_postures(tmp_path / "group.csv", group)
    setup = ["--setup", "zhang2021-comau-nj165"]
    for kwargs, flags in [
        (dict(purpose="calibration"), ["--for", "calibration"]),
        (dict(purpose="calibration", calibration_criterion="o1", geometry="offsets"),
         ["--for", "calibration", "--calibration-criterion", "o1", "--geometry", "offsets"]),
        (dict(purpose="both", weight=0.25), ["--for", "both", "--weight", 0.25]),
        (dict(purpose="check"), ["--for", "check"]),
    ]:
        mine = paper.evaluate(group, **kwargs)
        assert plain(mine) == cli("evaluate", *setup, "--postures", path, "--json", *flags), flags
        assert mine["calibration"]["predicted_rms_mm"] > 0
    chosen = paper.select(method="global", n=8, starts=2, polished=1, max_evals=300, purpose="both")
    theirs = cli("select", *setup, "--out", tmp_path / "out.csv", "--json", "--global", "--count", 8,
                 "--starts", 2, "--polished", 1, "--max-evals", 300, "--for", "both")
    assert timeless(plain(chosen)) == timeless(theirs)
    # A check campaign: 10 postures by default, designed for the update's offsets.
    check = paper.select(method="global", starts=2, polished=1, max_evals=300, purpose="check")
    assert len(check["postures_deg"]) == 10 and check["calibration"]["geometry"] == "offsets"


def test_calibration_options_need_their_purpose(paper):
    group = paper.random_group(8, 7)
    with pytest.raises(ValueError, match=r"^geometry: a calibration option: only with for = calibration or both"):
        paper.evaluate(group, geometry="full")
    with pytest.raises(ValueError, match=r"^weight: "):
        paper.select(method="global", n=8, starts=2, purpose="calibration", weight=0.5)
    with pytest.raises(ValueError, match=r"^purpose: 'geometry' is not a purpose \(known: stiffness, calibration, both, check\)"):
        paper.evaluate(group, purpose="geometry")
    with pytest.raises(ValueError, match=r"calibration_criterion"):
        paper.evaluate(group, purpose="calibration", calibration_criterion="o2")
