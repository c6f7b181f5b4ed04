"""figures: the SVG figures of a calibration, an identification and a plan, drawn from their
documents, and those a compensation and the study return, are byte for byte the figures the
command's reports write for the same call."""

import numpy as np
import pytest

import stiffid
from conftest import FANUC_DATA, REPO, plain
from test_calibrate import SETUP, campaign  # noqa: F401 (the fixture)
from test_plan import CELL, command_plan

MILLING = REPO / "examples" / "milling" / "fanuc-milling.toml"
MILLING_PATH = REPO / "examples" / "milling" / "path.csv"
MILLING_STIFFNESS = REPO / "examples" / "milling" / "stiffness.json"
POCKET = REPO / "examples" / "milling" / "pocket.nc"
PROCESS = REPO / "examples" / "milling" / "aluminium.toml"


def test_calibration_figures_are_the_reports(paper, cli, campaign, tmp_path):  # noqa: F811
    _, _, fit, held = campaign
    # The geometry alone: the figures, not the model's choice, are compared.
    doc = stiffid.calibrate(paper, fit, validate=held, gravity="none")
    figures = stiffid.figures(doc)
    assert list(figures)[:2] == ["errors", "residuals"]
    assert "parameters_mm" in figures and "parameters_deg" in figures
    cli("calibrate", "--setup", SETUP, "--data", fit, "--validate", held, "--gravity", "none",
        "--report", tmp_path / "r", "--json")
    for name, svg in figures.items():
        assert svg.startswith("<svg") and svg == (tmp_path / "r" / "figures" / f"{name}.svg").read_text(), name
    # The errors figure draws every reading before and after (a circle each) on a log scale: an
    # error of round-off after the fit may fall below the axis.
    tiny = sum(1 for e in doc["errors"] if e["after_norm_mm"] < 1e-9)
    assert 2 * len(doc["errors"]) - tiny <= figures["errors"].count("<circle") <= 2 * len(doc["errors"])


def test_identification_figures_are_the_reports(fanuc, cli, tmp_path):
    ident = stiffid.identify(fanuc, FANUC_DATA, cross_validate=True)
    figures = stiffid.figures(ident)
    assert list(figures) == ["measured", "parameters", "qq", "folds", "prediction"]
    # Measured against predicted: one point per displacement coordinate of the document.
    residuals = ident["residuals"]
    assert figures["measured"].count("<circle") == 3 * len(residuals)
    for r in residuals:
        np.testing.assert_allclose(np.add(r["predicted_mm"], r["residual_mm"]), r["measured_mm"], rtol=0, atol=1e-12)
    assert figures == stiffid.figures(plain(ident))
    cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--cross-validate",
        "--report", tmp_path / "r", "--json")
    for name, svg in figures.items():
        assert svg == (tmp_path / "r" / "figures" / f"{name}.svg").read_text(), name
    models = stiffid.identify(fanuc, FANUC_DATA, compare_models=True)
    assert list(stiffid.figures(models)) == ["models"]


def test_other_documents_are_refused():
    # Which document it is, its `kind` says: no guess from its keys.
    with pytest.raises(stiffid.InputError, match="document: its `kind` is \"\""):
        stiffid.figures({"setup": "x", "errors": [], "geometry": "full"})
    with pytest.raises(stiffid.InputError, match="document: its `kind` is \"predict\""):
        stiffid.figures({"kind": "predict", "residuals": []})
    with pytest.raises(stiffid.InputError, match="is not part of a document"):
        stiffid.figures({"kind": "calibrate", "errors": [object()], "geometry": "full"})


def report_figures(directory):
    """Every figures/<name>.svg of a report directory, keyed by name."""
    return {p.stem: p.read_text() for p in sorted((directory / "figures").glob("*.svg"))}


def test_plan_figures_are_the_reports(cli, tmp_path):
    """A plan's figures from its document and setup are select --report's, byte for byte; the
    postures drawn are the document's (one numbered label per posture)."""
    (tmp_path / "cell.toml").write_text(CELL)
    cell = stiffid.Setup.from_file(tmp_path / "cell.toml")
    chosen, plan = command_plan(cli, tmp_path, tmp_path / "cell.toml", "--count", 6)
    figures = stiffid.figures(plan, setup=cell)
    assert list(figures) == ["postures"] + [f"posture_{i:02}" for i in range(1, 7)]
    assert figures == report_figures(tmp_path / "plan")
    assert stiffid.figures(stiffid.plan(cell, chosen), setup=cell) == figures
    with pytest.raises(stiffid.InputError, match="setup: a plan's figures"):
        stiffid.figures(plan)


@pytest.mark.filterwarnings("ignore::UserWarning")
def test_compensation_figures_are_the_reports(cli, tmp_path):
    """compensate(..., figures=True) returns compensate --report's figures, byte for byte: on a
    path with the free tool axis and its map, and on a program with its process."""
    milling = stiffid.Setup.from_file(MILLING)
    cli("compensate", "--setup", MILLING, "--stiffness", MILLING_STIFFNESS, "--path", MILLING_PATH,
        "--free", "tool-rotation", "--map", "--out", tmp_path / "c.csv", "--report", tmp_path / "r", parse=False)
    mine = stiffid.compensate(milling, MILLING_PATH, MILLING_STIFFNESS, free=["tool-rotation"], map=True, figures=True)
    assert list(mine["figures"]) == ["deflection", "path", "map"]
    assert mine["figures"] == report_figures(tmp_path / "r")
    assert "figures" not in stiffid.compensate(milling, MILLING_PATH, MILLING_STIFFNESS)
    setup = stiffid.Setup.from_file(MILLING)
    cli("compensate", "--setup", MILLING, "--stiffness", MILLING_STIFFNESS, "--program", POCKET,
        "--process", PROCESS, "--out", tmp_path / "p.nc", "--report", tmp_path / "p", parse=False)
    mine = stiffid.compensate(setup, stiffness=MILLING_STIFFNESS, program=POCKET, process=PROCESS, figures=True)
    assert list(mine["figures"]) == ["deflection", "path", "force", "segments"]
    assert mine["figures"] == report_figures(tmp_path / "p")


def test_study_figures_are_the_reports(cli, tmp_path):
    """reproduce(..., figures=True) returns the report's figures of the same small study."""
    cli("reproduce", "--out", tmp_path / "r", "--runs", 5, "--starts", 1, "--trials", 2, parse=False)
    mine = stiffid.reproduce(runs=5, starts=1, trials=2, figures=True)
    names = ["deviation_vs_noise", "table4_level2", "criteria_vs_deviation"]
    assert list(mine["figures"]) == names + [f"postures_{g['name']}" for g in mine["groups"]]
    assert mine["figures"] == report_figures(tmp_path / "r")
