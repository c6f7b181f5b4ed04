"""Every RAPID program stiffid writes parses with an independent parser of the language: PyPI's
rapidchecker (a pyparsing grammar of ABB RAPID, pinned in requirements-test.txt) finds no grammar
or format error in a program generated from G-code nor in a RAPID program compensated in place."""

import warnings

import pytest

import stiffid
from conftest import REPO

check = pytest.importorskip("rapidchecker.check")

MILLING = REPO / "examples" / "milling"
SETUP = MILLING / "fanuc-milling.toml"
STIFFNESS = MILLING / "stiffness.json"
PROCESS = MILLING / "aluminium.toml"


def test_generated_and_compensated_rapid_programs_parse(tmp_path):
    setup = stiffid.Setup.from_file(SETUP)
    with pytest.warns(UserWarning, match="plunge"):
        generated = stiffid.compensate(setup, stiffness=STIFFNESS, program=MILLING / "pocket.nc",
                                       process=PROCESS, output="rapid", targets="joint")["program"]
    assert "MoveAbsJ" in generated
    assert check.check_format(generated) == []
    module = tmp_path / "POCKET.mod"
    module.write_text(generated)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        compensated = stiffid.compensate(setup, stiffness=STIFFNESS, program=module, process=PROCESS)["program"]
    assert compensated != generated
    assert check.check_format(compensated) == []
    # The parser is not a formality: a statement without its ';' is an error.
    broken = compensated.replace("tool0;", "tool0", 1)
    assert check.check_format(broken) != []
