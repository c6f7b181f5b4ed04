"""The G-code's process words in the robot programs stiffid writes, checked by independent
parsers: the milling pocket's first wall (with its `T1 M06`, `S6000 M03`, `M05`, `M30`) written
as RAPID and KRL on a setup whose `[controller.io]` maps the tool change and the spindle (calls
with the tool number and speed, an output), with a home posture: rapidchecker (a pyparsing
grammar of ABB RAPID) finds no error, krllint finds nothing it does not find in the same program
written without them, and every process word is in the program as mapped or named in the one
warning; the G-code's comments of lines of their own are in both, and the parsers accept them."""

import re
import subprocess
import sys
import warnings

import pytest

import stiffid
from conftest import REPO

MILLING = REPO / "examples" / "milling"
STIFFNESS = MILLING / "stiffness.json"
PROCESS = MILLING / "aluminium.toml"

IO = """
[controller]
home_deg = [0, 10, -20, 0, -60, 0]
[controller.io]
tool_change = "TOOL_CHANGE({tool})"
spindle_cw = ["SPINDLE_ON({rpm})", "%s"]
"""


@pytest.fixture(scope="module")
def wall(tmp_path_factory):
    """The pocket's header and first wall (down to its first arc) with its program end."""
    lines = (MILLING / "pocket.nc").read_text().splitlines()
    arc = next(i for i, line in enumerate(lines) if line.startswith("G3"))
    path = tmp_path_factory.mktemp("process") / "wall.nc"
    path.write_text("\n".join(lines[: arc + 3] + ["G0 Z5", "M05", "M30"]) + "\n")
    return path


def setup(output=None):
    """The milling setup with the spindle's mass (a RAPID tooldata needs it) and, with `output`
    (the language's form of the spindle's output), the io and home posture."""
    text = (MILLING / "fanuc-milling.toml").read_text()
    spindle = "[tool]\nmass_kg = 15.0\ncentre_of_mass_mm = [0.0, 0.0, 120.0]\n"
    text = text.replace("[tool]\n", spindle, 1)
    if output:
        text += IO % output
    return stiffid.Setup.from_toml(text, base_dir=MILLING)


def generate(setup, program, **kwargs):
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        out = stiffid.compensate(setup, stiffness=STIFFNESS, program=program, process=PROCESS, **kwargs)
    return out["program"], [str(w.message) for w in caught]


def kept(text, warned, comment, wall):
    """Every process word of the wall kept: the mapped ones as their calls, the others (M05 and
    M30, on the wall's last two lines) named in one warning and written as comments."""
    n = len(wall.read_text().splitlines())
    left = [w for w in warned if "process word" in w]
    assert len(left) == 1, warned
    assert left[0].endswith(f"spindle_off: M5 (line {n - 1}); program_end: M30 (line {n})"), left[0]
    for word in (f"M5 (line {n - 1})", f"M30 (line {n})"):
        assert f"{comment}{word}" in text, word


def test_rapid_programs_with_process_words_parse(wall):
    """The process words' lines are the same whatever the targets (the joint form's moves parse
    in test_program_parsers.py): the parser's seconds are spent once, on Cartesian targets."""
    check = pytest.importorskip("rapidchecker.check")
    text, warned = generate(setup("out[doSpindle] = on"), wall, output="rapid", targets="cartesian")
    assert "    TOOL_CHANGE 1;\n    SPINDLE_ON 6000;\n    SetDO doSpindle, 1;\n" in text
    # The G-code's comments of lines of their own, at their place: rapidchecker reads them too.
    assert "    ! pocket wall: 300 x 200 mm, corner radius 20 mm, two passes of 4 mm\n    ! operation: wall\n" in text
    kept(text, warned, "! ", wall)
    assert check.check_format(text) == []


def findings(path):
    """krllint's findings in the file at `path`, without their line numbers."""
    out = subprocess.run([sys.executable, "-m", "krllint", str(path)], capture_output=True, text=True, check=False)
    return sorted({line.split(":", 1)[1] for line in out.stdout.splitlines() if re.match(r"^\d+:", line)})


@pytest.mark.parametrize("targets", ["cartesian", "joint"])
def test_krl_programs_with_process_words_lint_as_without(wall, tmp_path, targets):
    pytest.importorskip("krllint")
    text, warned = generate(setup("out[12] = on"), wall, output="krl", targets=targets)
    assert "TOOL_CHANGE(1)\nSPINDLE_ON(6000)\n$OUT[12]=TRUE\n" in text
    assert "; pocket wall: 300 x 200 mm, corner radius 20 mm, two passes of 4 mm\n; operation: wall\n" in text
    kept(text, warned, "; ", wall)
    plain, _ = generate(setup(), wall, output="krl", targets=targets)
    (tmp_path / "WITH.src").write_text(text.replace("DEF WALL", "DEF WITH"))
    (tmp_path / "PLAIN.src").write_text(plain.replace("DEF WALL", "DEF PLAIN"))
    assert set(findings(tmp_path / "WITH.src")) <= set(findings(tmp_path / "PLAIN.src"))
