"""KUKA KRL programs as controllers store them (docs/programs/krl.md).

The real programs of crates/stiffid/tests/data/programs/krl (SOURCES.md) are each refused naming
the line of the first motion an independent reading (the regular expressions below, not stiffid's
reader) finds stiffid cannot take: a target that is no literal aggregate nor a point the .src or
.dat declares with a value, or a sensor-guided motion (a motion to where the robot stands, `PTP
$AXIS_ACT`, moves nothing and is passed over). A program stored as a teach pendant stores
it (inline forms, points in the .dat, tool and base by number) is compensated with its .dat, and
krllint (pinned in requirements-test.txt) finds nothing in either file written that it does not
find in the file read."""

import re
import subprocess
import sys
import warnings

import pytest

import stiffid
from conftest import REPO

MILLING = REPO / "examples" / "milling"
CORPUS = REPO / "crates" / "stiffid" / "tests" / "data" / "programs" / "krl"
MOTION = re.compile(r"^\s*(PTP|LIN|CIRC|SPTP|SLIN|SCIRC|RSI_MOVECORR|ST_MOVECORR)\b\s*(.*)$", re.I)
DECLARED = re.compile(r"^\s*(?:DECL\s+)?(?:GLOBAL\s+)?(E6POS|E6AXIS|POS|AXIS|FRAME)\s+(\w+)\s*(=\s*\{)?", re.I)


def first_refused(src, dat):
    """The line of the first motion of `src` stiffid cannot take (module docs), 1-based."""
    code = [line.split(";")[0] for line in src.splitlines()]
    with_value = set()
    for line in code + [line.split(";")[0] for line in dat.splitlines()]:
        m = DECLARED.match(line)
        if m and m.group(3):
            with_value.add(m.group(2).upper())
    for number, line in enumerate(code, start=1):
        m = MOTION.match(line)
        if not m:
            continue
        word, target = m.group(1).upper(), m.group(2).strip()
        if word in ("PTP", "LIN") and target.upper() in ("$AXIS_ACT", "$POS_ACT"):
            continue
        if word in ("RSI_MOVECORR", "ST_MOVECORR"):
            return number
        name = re.match(r"[\w$]+", target)
        if not target.startswith("{") and (name is None or name.group(0).upper() not in with_value):
            return number
    return None


def compensate(program, setup):
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        return stiffid.compensate(
            setup, stiffness=MILLING / "kuka-stiffness.json", program=program, process=MILLING / "aluminium.toml"
        )


@pytest.fixture(scope="module")
def setup():
    """The KR 210 milling setup; the controller holds the pocket's tool and base as number 1."""
    text = (MILLING / "kuka-milling.toml").read_text()
    text += "\n[controller]\ntools = [{ number = 1, xyz_mm = [0, 0, 250] }]\nbases = [{ number = 1, xyz_mm = [2000, 0, 550] }]\n"
    return stiffid.Setup.from_toml(text, base_dir=MILLING)


@pytest.mark.parametrize("src", sorted(CORPUS.glob("*.src")), ids=lambda p: p.name)
def test_each_real_program_is_refused_at_the_line_an_independent_reading_finds(src, setup):
    dat = src.with_suffix(".dat")
    line = first_refused(src.read_text(), dat.read_text() if dat.exists() else "")
    assert line is not None, src.name
    with pytest.raises(stiffid.InputError) as e:
        compensate(src, setup)
    assert src.name in str(e.value) and f"line {line}:" in str(e.value), str(e.value)


def literal():
    """The example pocket as one file: the points its pocket.dat declares put back into the
    motions of its pocket.src by name (`LIN XP2 C_DIS` becomes `LIN {E6POS: ..} C_DIS`)."""
    points = dict(re.findall(r"^DECL E6POS (XP\d+)=\{([^}]*)\}$", (MILLING / "pocket.dat").read_text(), re.M))
    lines = []
    for line in (MILLING / "pocket.src").read_text().splitlines():
        if line.startswith(("PTP XP", "LIN XP", "CIRC XP")):
            line = re.sub(r"XP\d+", lambda m: "{E6POS: " + points[m.group(0)] + "}", line.replace(", XP", ",XP"))
        lines.append(line)
    return lines


def stored(n):
    """The pocket's first `n` motions as a teach pendant stores them: the .src and the .dat."""
    src, dat, speed = [], ["&ACCESS RVP", "DEFDAT  POCKET"], "0.03"
    motions = 0
    for line in literal():
        if line.startswith(("$TOOL", "$BASE")):
            continue
        speed = line.split("=")[1].strip() if line.startswith("$VEL.CP") else speed
        if line.startswith("CIRC"):
            motions += 1
            if motions <= n:
                src.append(line)
            continue
        m = re.match(r"(PTP|LIN) \{E6POS: ([^}]*)\}(.*)", line)
        if not m:
            src.append(line)
            continue
        motions += 1
        if motions > n:
            continue
        kind, point, rest = m.groups()
        data = f"PDAT_ACT=PPDAT{motions}" if kind == "PTP" else f"LDAT_ACT=LCPDAT{motions}"
        bas = "BAS(#PTP_PARAMS,20)" if kind == "PTP" else f"BAS(#CP_PARAMS,{speed})"
        src += [f";FOLD {kind} P{motions} Tool[1] Base[1];%{{PE}}", "$BWDSTART=FALSE", data, f"FDAT_ACT=FP{motions}", bas, f"{kind} XP{motions}{rest}", ";ENDFOLD"]
        dat += [f"DECL E6POS XP{motions}={{{point}}}", f'DECL FDAT FP{motions}={{TOOL_NO 1,BASE_NO 1,IPO_FRAME #BASE,POINT2[] " "}}']
    return "\n".join(src) + "\n", "\n".join(dat + ["ENDDAT"]) + "\n"


def findings(path):
    """krllint's findings in the file at `path`, without their line numbers' order."""
    out = subprocess.run([sys.executable, "-m", "krllint", str(path)], capture_output=True, text=True, check=False)
    return sorted(line.split(":", 1)[1] for line in out.stdout.splitlines() if re.match(r"^\d+:", line))


def test_a_stored_program_is_compensated_with_its_dat_and_lints_as_read(setup, tmp_path):
    pytest.importorskip("krllint")
    src, dat = stored(12)
    (tmp_path / "POCKET.src").write_text(src)
    (tmp_path / "POCKET.dat").write_text(dat)
    result = compensate(tmp_path / "POCKET.src", setup)
    out = tmp_path / "out"
    out.mkdir()
    (out / "POCKET.src").write_text(result["program"])
    (out / "POCKET.dat").write_text(result["data"])
    # The .dat's points moved, its other bytes did not; the .src keeps its lines (bounds aside).
    number = re.compile(r"-?\d+\.?\d*")
    assert result["data"] != dat and number.sub("#", result["data"]) == number.sub("#", dat)
    assert [line.split(" ; bound")[0] for line in result["program"].splitlines()] == src.splitlines()
    for name in ("POCKET.src", "POCKET.dat"):
        assert findings(out / name) == findings(tmp_path / name), name
    # krllint is not a formality: a keyword in lower case is a finding.
    (out / "BROKEN.src").write_text(result["program"].replace("LIN XP2", "lin XP2", 1))
    assert findings(out / "BROKEN.src") != findings(tmp_path / "POCKET.src")
