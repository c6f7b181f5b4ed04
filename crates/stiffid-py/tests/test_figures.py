"""figures: the SVG figures of a calibration and an identification, drawn from their documents,
are byte for byte the figures the command's reports write for the same call."""

import numpy as np
import pytest

import stiffid
from conftest import FANUC_DATA, plain
from test_calibrate import SETUP, campaign  # noqa: F401 (the fixture)


def test_calibration_figures_are_the_reports(paper, cli, campaign, tmp_path):  # noqa: F811
    _, _, fit, held = campaign
    doc = stiffid.calibrate(paper, fit, validate=held)
    figures = stiffid.figures(doc)
    assert list(figures)[:2] == ["errors", "residuals"]
    assert "parameters_mm" in figures and "parameters_deg" in figures
    cli("calibrate", "--setup", SETUP, "--data", fit, "--validate", held, "--report", tmp_path / "r", "--json")
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
    with pytest.raises(stiffid.InputError, match="document: not an identify document"):
        stiffid.figures({"setup": "x"})
    with pytest.raises(stiffid.InputError, match="is not part of a document"):
        stiffid.figures({"errors": [object()], "geometry": "full"})
