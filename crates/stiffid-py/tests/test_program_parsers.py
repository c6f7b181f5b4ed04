"""Every RAPID program stiffid writes parses with an independent parser of the language: PyPI's
rapidchecker (a pyparsing grammar of ABB RAPID, pinned in requirements-test.txt) finds no grammar
or format error in a program generated from G-code, with Cartesian or joint targets, nor in a RAPID
program compensated in place. The milling pocket's first wall (straight moves and an arc, its
process and tool) keeps the parser's seconds few; the whole pocket's program has the same lines."""

import re
import subprocess
import sys
import warnings

import pytest

import stiffid
from conftest import REPO

check = pytest.importorskip("rapidchecker.check")

MILLING = REPO / "examples" / "milling"
STIFFNESS = MILLING / "stiffness.json"
PROCESS = MILLING / "aluminium.toml"


@pytest.fixture(scope="module")
def wall(tmp_path_factory):
    """The pocket's header and first wall (down to its first arc) with its program end."""
    lines = (MILLING / "pocket.nc").read_text().splitlines()
    arc = next(i for i, line in enumerate(lines) if line.startswith("G3"))
    path = tmp_path_factory.mktemp("rapid") / "wall.nc"
    path.write_text("\n".join(lines[: arc + 3] + ["G0 Z5", "M05", "M30"]) + "\n")
    return path


@pytest.fixture(scope="module")
def setup():
    """The milling setup with the spindle's mass, which a RAPID tooldata needs."""
    text = (MILLING / "fanuc-milling.toml").read_text()
    spindle = "[tool]\nmass_kg = 15.0\ncentre_of_mass_mm = [0.0, 0.0, 120.0]\n"
    return stiffid.Setup.from_toml(text.replace("[tool]\n", spindle, 1), base_dir=MILLING)


def generate(setup, program, **kwargs):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return stiffid.compensate(setup, stiffness=STIFFNESS, program=program, process=PROCESS, **kwargs)["program"]


@pytest.mark.parametrize(
    "targets, move, tolerance",
    [("cartesian", "MoveL [", 0.01), ("cartesian", "MoveC [", 0.05), ("joint", "MoveAbsJ", 0.01)],
)
def test_generated_rapid_programs_parse(setup, wall, targets, move, tolerance):
    """The wall's arc, compensated, stays within 0.024 mm of a circle: a MoveC at a chord
    tolerance of 0.05 mm, its chords at 0.01 mm (with a warning); with joint targets its chord
    points."""
    generated = generate(setup, wall, output="rapid", targets=targets, chord_tolerance_mm=tolerance)
    assert move in generated
    assert check.check_format(generated) == []


def test_a_rapid_program_compensated_in_place_parses(setup, wall, tmp_path):
    module = tmp_path / "WALL.mod"
    module.write_text(generate(setup, wall, output="rapid", targets="joint"))
    compensated = generate(setup, module)
    assert compensated != module.read_text()
    assert check.check_format(compensated) == []
    # The parser is not a formality: a statement without its ';' is an error.
    broken = compensated.replace("ConfL \\On;", "ConfL \\On", 1)
    assert broken != compensated and check.check_format(broken) != []


def test_a_rapid_module_with_offs_reltool_and_movec_compensated_in_place_parses(setup, wall, tmp_path):
    """A stored module's forms stiffid reads (declared targets moved by Offs and RelTool of
    numbers, a circle as MoveC) stay valid RAPID once compensated in place."""
    generated = generate(setup, wall, output="rapid", targets="cartesian")
    lines = generated.splitlines()
    moves = [i for i, line in enumerate(lines) if line.lstrip().startswith("MoveL [")]
    assert len(moves) >= 4

    def target(i):
        line = lines[i]
        start = line.index("[")
        end = line.index("]], ") + 2
        return line[:start], line[start:end], line[end:]

    head, first, rest = target(moves[0])
    lines[moves[0]] = f"{head}Offs({first},0,0,0){rest}"
    head, second, rest = target(moves[1])
    lines[moves[1]] = f"{head}RelTool({second},0,0,0\\Rz:=0){rest}"
    _, circle, _ = target(moves[2])
    head, end, rest = target(moves[3])
    lines[moves[2]] = ""
    lines[moves[3]] = f"{head.replace('MoveL', 'MoveC')}{circle}, {end}{rest}"
    module = tmp_path / "CELL.mod"
    module.write_text("\n".join(lines) + "\n")
    compensated = generate(setup, module)
    assert compensated != module.read_text()
    for form in ("Offs([[", "RelTool([[", "MoveC [["):
        assert form in compensated
    assert check.check_format(compensated) == []


def test_generated_krl_programs_with_circ_lint_clean(setup, wall, tmp_path):
    """A KRL program written from the wall (its arc a CIRC at a chord tolerance of 0.05 mm, the
    KSS header lines before DEF) lints clean with krllint (pinned in requirements-test.txt), as the whole pocket does."""
    pytest.importorskip("krllint")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        generated = stiffid.compensate(setup, stiffness=STIFFNESS, program=wall, process=PROCESS, output="krl", targets="cartesian", chord_tolerance_mm=0.05)
    assert generated["program"].startswith("&ACCESS RVP\n&REL 1\n") and "\nCIRC XP" in generated["program"]
    # Its points in the .dat written beside it (DEFDAT of the program's name): both files lint.
    assert generated["data"].startswith("&ACCESS RVP\n&REL 1\nDEFDAT WALL\nDECL E6POS XP1={")
    for name, text in (("WALL.src", generated["program"]), ("WALL.dat", generated["data"])):
        path = tmp_path / name
        path.write_text(text)
        out = subprocess.run([sys.executable, "-m", "krllint", str(path)], capture_output=True, text=True, check=False)
        assert "0 found errors" in out.stdout and "0 fatal errors" in out.stdout, out.stdout
        assert not [line for line in out.stdout.splitlines() if re.match(r"^\d+:", line)], out.stdout
