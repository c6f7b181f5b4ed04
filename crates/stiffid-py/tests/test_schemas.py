"""The JSON Schemas in docs/schemas validate the real output of every command that writes a document
(on the built-in setups, the FANUC measurements, the milling path, ...), and reject that output with
a required key missing or, for a closed schema, an unknown key added.

That the shipped schemas are the generated ones is checked by the command's own tests
(crates/stiffid-cli/tests/it/schemas.rs); here they meet the documents, through the reference
validator (the `jsonschema` package)."""

import json

import jsonschema
import pytest

import stiffid

from conftest import FANUC_DATA, REPO

SCHEMAS = REPO / "docs" / "schemas"
GROUP = """posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg
1,10,-20,-100,30,40,-60
2,-45,10,-70,-90,-30,120
3,60,-40,-130,150,60,10
4,-80,30,-50,-20,-70,-150
5,30,0,-160,100,20,80
6,-10,-55,-90,-160,80,-30
"""


def example(path: str) -> str:
    return str(REPO / "examples" / path)


def validator(name: str):
    schema = json.loads((SCHEMAS / f"{name}.schema.json").read_text())
    cls = jsonschema.validators.validator_for(schema)
    cls.check_schema(schema)
    return cls(schema), schema


def assert_valid(name: str, doc: dict, closed: bool = True):
    """`doc` is valid under the shipped schema `name`; invalid without any one of its required keys
    and, for a closed schema, with an unknown key (a schema that can fail)."""
    v, schema = validator(name)
    errors = [f"{e.message} at {list(e.absolute_path)}" for e in v.iter_errors(doc)]
    assert not errors, f"{name}: {errors}"
    # The stiffness file requires one of two keys, which its schema cannot say: no `required`.
    for key in schema.get("required", []):
        missing = {k: x for k, x in doc.items() if k != key}
        assert not v.is_valid(missing), f"{name}: valid without {key}"
    extra = dict(doc, an_unknown_key=None)
    assert v.is_valid(extra) != closed, f"{name}: an unknown key"


@pytest.fixture
def group(tmp_path):
    path = tmp_path / "group.csv"
    path.write_text(GROUP)
    return str(path)


def test_kinematics_and_predict(cli):
    # A wrist singularity: dexterity is null.
    k = cli("kinematics", "--robot", "comau-smart5-nj165-3.0", "--q-deg", "0,0,-90,0,0,0",
            "--characteristic-length-mm", "1200", "--json")
    assert k["dexterity"] is None
    assert_valid("kinematics", k)
    assert_valid("kinematics", stiffid.Robot.preset("comau-smart5-nj165-3.0").kinematics([10, 20, -100, 30, 40, 50]))
    # A stiffness file with the compliance covariance: every standard deviation is there.
    p = cli("predict", "--setup", "fanuc-r2000ic-165f", "--q-deg", "0,10,-20,0,30,0",
            "--wrench", "100,-50,200,1,2,3", "--stiffness", example("milling/stiffness.json"), "--json")
    assert isinstance(p["tcp_deflection_std_mm"], list)
    assert_valid("predict", p)
    mine = stiffid.predict(stiffid.Setup.builtin("fanuc-r2000ic-165f"), [0, 10, -20, 0, 30, 0],
                           [100, -50, 200, 1, 2, 3], stiffness_nm_per_rad=example("milling/stiffness.json"))
    assert_valid("predict", mine)


def test_evaluate_and_select(cli, tmp_path, group):
    cell = example("cell/zhang2021-tracker.toml")
    e = cli("evaluate", "--setup", cell, "--postures", group, "--json")
    assert isinstance(e["feasibility"][2]["violations"][0]["check"], str)
    assert_valid("evaluate", e)

    local = cli("select", "--setup", cell, "--start-random", "--max-evals", "20",
                "--out", tmp_path / "local.csv", "--json")
    assert isinstance(local["unconstrained"], dict)
    assert_valid("select", local)
    # The criterion is one of the names `--criterion` takes.
    v, _ = validator("select")
    assert not v.is_valid(dict(local, criterion="relative_a"))

    # A pool of the six postures, two more and one out of the bounds (skipped).
    pool = tmp_path / "pool.csv"
    pool.write_text(GROUP + "7,0,-30,-90,0,45,0\n8,20,-10,-120,60,-45,90\n9,0,-30,-90,0,45,359\n")
    chosen = cli("select", "--setup", "zhang2021-comau-nj165", "--pool", pool, "--target-pct", "50",
                 "--out", tmp_path / "pool-out.csv", "--json")
    assert chosen["pool"]["skipped"][0]["posture"] == 9
    assert isinstance(chosen["target"]["steps"], list)
    assert_valid("select", chosen)


def test_evaluate_without_a_characteristic_length(cli, tmp_path, group):
    text = cli("setups", "show", "zhang2021-comau-nj165", parse=False)
    setup = tmp_path / "no-length.toml"
    setup.write_text("".join(l + "\n" for l in text.splitlines() if not l.startswith("characteristic_length_mm")))
    e = cli("evaluate", "--setup", setup, "--postures", group, "--json")
    assert e["classical"] is None and e["zhang2021"] is None
    assert_valid("evaluate", e)


def identify(cli, *extra):
    return cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--json", *extra)


def test_identify_validate_and_compensate(cli, tmp_path):
    stiffness = tmp_path / "stiffness.json"
    plain = identify(cli, "--folds", "4", "--out", stiffness)
    assert isinstance(plain["cross_validation"], dict)
    assert_valid("identify", plain)
    robust = identify(cli, "--robust", "tukey")
    assert isinstance(robust["robust"], dict)
    assert_valid("identify", robust)
    bounded = identify(cli, "--nonnegative")
    assert isinstance(bounded["active_bounds"], list)
    assert_valid("identify", bounded)
    # What identify --out writes is a stiffness file; so is the milling example's.
    written = json.loads(stiffness.read_text())
    assert_valid("identify", written)
    assert_valid("stiffness", written, closed=False)
    assert_valid("stiffness", json.loads((REPO / "examples" / "milling" / "stiffness.json").read_text()), closed=False)

    v = cli("validate", "--setup", "fanuc-r2000ic-165f", "--stiffness", stiffness, "--data", FANUC_DATA, "--json")
    assert_valid("validate", v)

    c = cli("compensate", "--setup", example("milling/fanuc-milling.toml"), "--stiffness", stiffness,
            "--path", example("milling/path.csv"), "--out", tmp_path / "compensated.csv",
            "--free", "tool-rotation", "--json")
    assert isinstance(c["points"][0]["dx_std_mm"], float)
    assert_valid("compensate", c)


def test_compare_models(cli, tmp_path):
    # --compare-models: the document, and the [model] fragment of --out read back by a setup.
    fragment = tmp_path / "model.toml"
    m = identify(cli, "--compare-models", "--out", fragment)
    assert_valid("identify", m)
    assert_valid("identify", identify(cli, "--compare-models", "--candidates", "tilt3_x,tool_y",
                                            "--bootstrap", "5"))
    models = m["models"]
    assert models[0]["held_out_explained"] == pytest.approx(0.765, abs=5e-4)
    rec = next(r for r in models if r["recommended"])
    assert rec["held_out_explained"] >= 0.81 and rec["physical"] is True
    setup = tmp_path / "with-model.toml"
    setup.write_text(cli("setups", "show", "fanuc-r2000ic-165f", parse=False) + fragment.read_text())
    fit = cli("identify", "--setup", setup, "--data", FANUC_DATA, "--json")
    names = [p["name"] for p in fit["parameters"]]
    assert len(names) == rec["parameters"]
    assert names[:6] == ["k1", "k2", "k3", "k4", "k5", "k6"]
    assert_valid("identify", fit)
    assert_valid("stiffness", fit, closed=False)
    # Robust and cross-validated over every parameter of the model.
    robust = cli("identify", "--setup", setup, "--data", FANUC_DATA, "--json", "--robust", "tukey", "--folds", "5")
    assert isinstance(robust["robust"], dict) and isinstance(robust["cross_validation"], dict)
    assert [s["name"] for s in robust["cross_validation"]["spread"]] == names
    assert_valid("identify", robust)
    loo = cli("identify", "--setup", setup, "--data", FANUC_DATA, "--json", "--cross-validate")
    assert loo["cross_validation"]["explained"] == pytest.approx(rec["held_out_explained"], rel=1e-9)
    assert loo["cross_validation"]["explained_std_error"] == pytest.approx(
        rec["held_out_explained_std_error"], rel=1e-9
    )
    assert_valid("identify", loo)


def test_python_model_documents():
    # Python's compare_models=True: the command's document plus `table` and `fragment`; identify
    # over a model with virtual springs: the identify-model document plus its arrays.
    import stiffid
    from conftest import plain

    fanuc = stiffid.Setup.builtin("fanuc-r2000ic-165f")
    compared = stiffid.identify(fanuc, FANUC_DATA, compare_models=True, candidates=["tilt3_x", "tool_y"])
    assert_valid("identify", {k: v for k, v in compared.items() if k not in ("table", "fragment")})
    fit = stiffid.identify(fanuc.with_model(compared["fragment"]), FANUC_DATA, folds=5)
    assert_valid("identify", plain(fit))
    assert_valid("stiffness", plain(fit), closed=False)


def test_simulate_and_reproduce(cli, tmp_path, group):
    s = cli("simulate", "--setup", "zhang2021-comau-nj165", "--postures", group, "--runs", "5", "--json")
    assert_valid("simulate", s)
    report = tmp_path / "report"
    cli("reproduce", "--out", report, "--runs", "5", "--starts", "2", "--trials", "2", parse=False)
    assert_valid("reproduce", json.loads((report / "summary.json").read_text()))
