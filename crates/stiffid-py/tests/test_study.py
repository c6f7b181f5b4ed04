"""reproduce and simulate: equal to the command's summary.json for seed 1."""

import json

import numpy as np
import pytest

import stiffid
from conftest import plain, write_postures

RATES = ["mean_deviation_pct", "std_deviation_pct", "predicted_deviation_pct", "mean_stiffness_nm_per_rad"]


@pytest.fixture(scope="module")
def study():
    """The paper's study with the command's defaults: 200 runs, seed 1, 16 starts, 20 trials."""
    return stiffid.reproduce()


@pytest.fixture(scope="module")
def summary(cli, tmp_path_factory):
    out = tmp_path_factory.mktemp("reproduce") / "report"
    cli("reproduce", "--out", out, parse=False)
    return json.loads((out / "summary.json").read_text())


def test_the_reproduce_document_equals_summary_json(study, summary):
    """One job, two front ends: the study's document is the command's summary.json, bit for bit
    (the wall-clock time aside), and its groups are the study's groups."""
    drop = lambda d: {key: value for key, value in d.items() if key != "elapsed_s"}
    assert drop(plain(study)) == drop(summary)
    assert isinstance(study["levels"], np.ndarray) and study["groups"][0]["mean_deviation_pct"].ndim == 2
    np.testing.assert_array_equal(study["levels"], summary["levels"])
    assert study["findings"] == summary["findings"]
    assert study["findings"]["sentences"] and study["findings"]["start_groups"] == 20


def test_reproduce_with_our_solver_equals_the_command(cli, tmp_path):
    """The solver reaches the study from both front ends: the same small study with our SQP gives
    the command's summary.json, and its paper searches differ from SLSQP's; the default (auto)
    takes the paper searches from SLSQP and the global ones from ours."""
    small = dict(runs=5, starts=1, trials=2)
    flags = ["--runs", 5, "--starts", 1, "--trials", 2, "--solver", "active-set"]
    cli("reproduce", "--out", tmp_path / "report", *flags, parse=False)
    summary = json.loads((tmp_path / "report" / "summary.json").read_text())
    ours = stiffid.reproduce(solver="active-set", **small)
    drop = lambda d: {key: value for key, value in d.items() if key != "elapsed_s"}
    assert drop(plain(ours)) == drop(summary)
    slsqp = plain(stiffid.reproduce(solver="slsqp", **small))
    assert plain(ours)["groups"][2]["postures_deg"] != slsqp["groups"][2]["postures_deg"]
    auto = plain(stiffid.reproduce(**small))
    assert auto["groups"][2]["postures_deg"] == slsqp["groups"][2]["postures_deg"]
    assert auto["groups"][3]["postures_deg"] == plain(ours)["groups"][3]["postures_deg"]


def test_study_arrays(study):
    groups = study["groups"]
    levels = len(study["levels"])
    mean = np.array([g["mean_deviation_pct"] for g in groups])
    assert mean.shape == (len(groups), levels, 6)
    assert all(g["predicted_deviation_pct"].shape == (levels, 6) for g in groups)
    np.testing.assert_allclose([g["average_deviation_pct"] for g in groups], mean.mean(axis=(1, 2)), rtol=1e-12)
    assert groups[2]["name"] == "group3-zhang2021"
    # The paper's claim (Fig. 8) and the first-order prediction within 10% on average.
    assert study["findings"]["group3_beats_groups_1_and_2"]
    assert study["findings"]["prediction_mean_abs_relative_error"] < 0.1


def test_simulate_equals_the_study(study, paper):
    """The study simulates its groups with the same seed: the same groups in the same order give
    the same numbers."""
    groups = [g["postures_deg"] for g in study["groups"]]
    sims = stiffid.simulate(paper, groups, runs=study["runs"], seed=study["seed"])
    assert len(sims) == 5
    for sim, g in zip(sims, study["groups"]):
        for key in RATES:
            np.testing.assert_allclose(sim[key], g[key], rtol=1e-9, err_msg=key)


def test_the_simulate_document_equals_the_command(paper, cli, tmp_path):
    """One job, two front ends: the same groups give the same simulation, bit for bit (the
    groups' names aside: the command names them by file)."""
    groups = [paper.random_group(6, 1), paper.random_group(8, 2)]
    paths = [write_postures(tmp_path / f"g{i}.csv", g) for i, g in enumerate(groups)]
    theirs = cli("simulate", "--setup", "zhang2021-comau-nj165", "--postures", *paths, "--runs", 20, "--seed", 3, "--json")
    mine = stiffid.simulate(paper, groups, runs=20, seed=3)
    assert [m["name"] for m in mine] == ["groups[0]", "groups[1]"]
    assert [dict(plain(m), name="") for m in mine] == [dict(t, name="") for t in theirs["groups"]]
    assert [p["name"] for p in theirs["parameters"]] == ["k1", "k2", "k3", "k4", "k5", "k6"]


def test_simulate_is_deterministic_and_seeded(paper):
    group = [paper.random_group(6, 1)]
    a = stiffid.simulate(paper, group, runs=10, seed=4)[0]
    b = stiffid.simulate(paper, group, runs=10, seed=4)[0]
    c = stiffid.simulate(paper, group, runs=10, seed=5)[0]
    np.testing.assert_array_equal(a["mean_deviation_pct"], b["mean_deviation_pct"])
    assert not np.array_equal(a["mean_deviation_pct"], c["mean_deviation_pct"])


@pytest.mark.parametrize(
    "kwargs, message",
    [
        (dict(runs=0), "runs"),
        (dict(starts=0), "starts"),
        (dict(runs=100001), "runs"),
        (dict(solver="newton"), "solver: unknown value 'newton'"),
    ],
)
def test_bad_reproduce_arguments(kwargs, message):
    with pytest.raises(ValueError, match=message):
        stiffid.reproduce(**kwargs)


def test_bad_simulate_arguments(paper):
    with pytest.raises(ValueError, match="groups: expected a list"):
        stiffid.simulate(paper, 3)
    with pytest.raises(ValueError, match=r"groups\[0\]: expected an array of shape"):
        stiffid.simulate(paper, [np.zeros((6, 5))])
    with pytest.raises(ValueError, match="runs"):
        stiffid.simulate(paper, [paper.random_group(6, 1)], runs=0)
