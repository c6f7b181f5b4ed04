"""Models beyond the six drives from Python: identify over a setup with virtual springs, and
`identify(..., compare_models=True)`, each the same document as the command's."""

import json

import numpy as np
import pytest

import stiffid
from conftest import FANUC_DATA, plain
from test_identify import synthetic

ELBOW = '[[model.family]]\nfamily = "tilt"\nlinks = [3]\nnominal_stiffness_nm_per_rad = 5e6\n'


@pytest.fixture(scope="module")
def compared(fanuc):
    return stiffid.identify(fanuc, FANUC_DATA, compare_models=True)


@pytest.fixture(scope="module")
def compared_cli(cli):
    return cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--compare-models", "--json")


def test_compare_models_is_the_commands_document(compared, compared_cli):
    """One job, two front ends: the same comparison, key for key and bit for bit."""
    assert {k: v for k, v in compared.items() if k not in ("table", "fragment")} == compared_cli


def test_compare_models_table_is_the_path_as_arrays_and_names(compared, compared_cli):
    t, models = compared["table"], compared_cli["models"]
    assert t["added"] == [m["added"] for m in models] and t["added"][0] is None
    assert t["springs"] == [m["springs"] for m in models]
    assert t["parameters"].dtype == np.int64
    np.testing.assert_array_equal(t["parameters"], [m["parameters"] for m in models])
    np.testing.assert_array_equal(t["held_out_explained"], [m["held_out_explained"] for m in models])
    np.testing.assert_array_equal(
        t["held_out_explained_std_error"], [m["held_out_explained_std_error"] for m in models]
    )
    np.testing.assert_array_equal(t["physical"], [m["physical"] for m in models])
    np.testing.assert_array_equal(t["recommended"], [m["recommended"] for m in models])
    # The FANUC data: 76.5% held out for the drives, at least 81% for the recommended model.
    assert t["held_out_explained"][0] == pytest.approx(0.765, abs=5e-4)
    rec = int(np.flatnonzero(t["recommended"])[0])
    assert t["held_out_explained"][rec] >= 0.81 and t["physical"][rec] and t["parameters"][rec] > 6
    # The fragment gives the recommended model to a setup.
    chosen = stiffid.Setup.builtin("fanuc-r2000ic-165f").with_model(compared["fragment"])
    assert [p["name"] for p in chosen.parameters][6:] == t["springs"][rec]


def test_compare_models_candidates_and_refusals(fanuc):
    c = stiffid.identify(fanuc, FANUC_DATA, compare_models=True, candidates=["tilt3_x", "tool_y"])
    assert {m["added"] for m in c["models"][1:]} <= {"tilt3_x", "tool_y"}
    assert {r["added"] for r in c["steps"][0]["candidates"]} == {"tilt3_x", "tool_y"}
    with pytest.raises(ValueError, match="candidates: 'nope' is not a candidate"):
        stiffid.identify(fanuc, FANUC_DATA, compare_models=True, candidates=["nope"])
    with pytest.raises(ValueError, match="compare_models: not with robust"):
        stiffid.identify(fanuc, FANUC_DATA, compare_models=True, robust="huber")
    with pytest.raises(ValueError, match="candidates: only with compare_models"):
        stiffid.identify(fanuc, FANUC_DATA, candidates=["tilt"])


def test_compare_models_bootstrap_is_the_commands_document(fanuc, cli):
    """The bootstrap from both front ends: the same document, bootstrap section included."""
    ours = stiffid.identify(fanuc, FANUC_DATA, compare_models=True, bootstrap=8, seed=5)
    theirs = cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA,
                 "--compare-models", "--bootstrap", "8", "--seed", "5", "--json")
    assert {k: v for k, v in ours.items() if k not in ("table", "fragment")} == theirs
    b = theirs["bootstrap"]
    assert (b["resamples"], b["seed"]) == (8, 5)
    # The drives are in every model; every share is a multiple of one usable resample.
    usable = 8 - b["unidentified"]
    assert [p["name"] for p in b["parameters"][:6]] == ["k1", "k2", "k3", "k4", "k5", "k6"]
    assert all(p["chosen_share"] == 1.0 for p in b["parameters"][:6])
    for p in b["parameters"]:
        assert round(p["chosen_share"] * usable) == pytest.approx(p["chosen_share"] * usable)
        assert p["percentile_2_5"] <= p["median"] <= p["percentile_97_5"]
    assert "bootstrap" not in stiffid.identify(fanuc, FANUC_DATA, compare_models=True,
                                               candidates=["tool_y"])


def test_compare_models_bootstrap_refusals(fanuc):
    with pytest.raises(ValueError, match="bootstrap: 0 resamples: expected 1 to 2000"):
        stiffid.identify(fanuc, FANUC_DATA, compare_models=True, bootstrap=0)
    with pytest.raises(ValueError, match="bootstrap: 2001 resamples: expected 1 to 2000"):
        stiffid.identify(fanuc, FANUC_DATA, compare_models=True, bootstrap=2001)
    with pytest.raises(ValueError, match="bootstrap: only with compare_models"):
        stiffid.identify(fanuc, FANUC_DATA, bootstrap=10)
    with pytest.raises(ValueError, match="seed: only with bootstrap"):
        stiffid.identify(fanuc, FANUC_DATA, compare_models=True, seed=3)


def test_identify_over_a_model_is_the_commands_document(compared, cli, tmp_path):
    setup_file = tmp_path / "with-model.toml"
    setup_file.write_text(cli("setups", "show", "fanuc-r2000ic-165f", parse=False) + compared["fragment"])
    setup = stiffid.Setup.from_file(setup_file)
    for flags, kwargs in [([], {}), (["--robust", "tukey", "--folds", "5"], dict(robust="tukey", folds=5))]:
        theirs = cli("identify", "--setup", setup_file, "--data", FANUC_DATA, "--json", *flags)
        mine = stiffid.identify(setup, FANUC_DATA, **kwargs)
        assert plain(mine) == {**theirs, "setup": mine["setup"]}, flags
    units = [p["unit"] for p in mine["parameters"]]
    assert units[:6] == ["Nm/rad"] * 6 and mine["compliance_covariance_si"].shape == (len(units), len(units))


def test_noise_free_recovery_of_an_elbow_tilt_spring_from_arrays(paper):
    """Drives plus the elbow's two tilt springs: noise-free data from the library's forward model
    (validate's prediction over the model) give every stiffness back."""
    setup = paper.with_model(ELBOW)
    assert [p["name"] for p in setup.parameters][6:] == ["tilt3_x", "tilt3_y"]
    k = np.array([900000.0, 2500000, 1000000, 300000, 180000, 120000, 4e6, 7e6])
    q, wrench, d = synthetic(setup, k)
    mine = stiffid.identify(setup, q_deg=q, wrench=wrench, displacement_mm=d)
    parameters = mine["parameters"]
    np.testing.assert_allclose([p["stiffness"] for p in parameters], k, rtol=1e-8)
    assert [p["unit"] for p in parameters] == ["Nm/rad"] * 8 and mine["data"] == "arrays"
    assert mine["residual_rms_mm"] < 1e-10 and mine["unidentifiable"] == []
    # The drives alone on the same data leave residuals far above the tracker noise.
    drives = stiffid.identify(paper, q_deg=q, wrench=wrench, displacement_mm=d)
    assert drives["noise_ratio"] > 3 and drives["model_error_dominates"]


def test_compare_models_bootstrap_writes_the_commands_stiffness_file(fanuc, cli, tmp_path):
    """stiffness_out= writes the model-form file of `--stiffness-out`, byte for byte (one library
    function builds it for both)."""
    theirs, mine = tmp_path / "cli.json", tmp_path / "py.json"
    cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--compare-models",
        "--bootstrap", "4", "--seed", "3", "--stiffness-out", theirs, "--json")
    stiffid.identify(fanuc, FANUC_DATA, compare_models=True, bootstrap=4, seed=3,
                     stiffness_out=mine)
    assert mine.read_bytes() == theirs.read_bytes()
    form = json.loads(mine.read_text())["model_form"]
    assert (form["resamples"], form["seed"]) == (4, 3) and form["models"]
    with pytest.raises(ValueError, match="stiffness_out: only with compare_models=True and bootstrap"):
        stiffid.identify(fanuc, FANUC_DATA, compare_models=True, stiffness_out=tmp_path / "x.json")
    with pytest.raises(ValueError, match="stiffness_out"):
        stiffid.identify(fanuc, FANUC_DATA, compare_models=True, bootstrap=2, stiffness_out=FANUC_DATA)
    assert not (tmp_path / "x.json").exists()
