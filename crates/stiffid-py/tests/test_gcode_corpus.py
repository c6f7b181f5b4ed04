"""The real G-code programs of crates/stiffid/tests/data/programs/gcode (SOURCES.md) as stiffid
reads them (`stiffid.read_program` with the setup and process a user would write beside them)
against an independent reading: pygcode (pinned in requirements-test.txt) splits each line into
its words, and the controller's modes are followed here as LinuxCNC's manual states them
(G20/G21, G90/G91, G91.1, G17-G19, G43 H / G49 with the tools' lengths, G28 to the setup's
position, G81 holes, an axis unknown until a block gives it). Every line where the independent
reading reaches a place with X, Y and Z known ends at that place in stiffid's path, stiffid has
points on no other line, an arc's points lie on its circle, and a hole reaches its bottom."""

import math

import numpy as np
import pytest

import stiffid
from conftest import REPO

pygcode = pytest.importorskip("pygcode")

CORPUS = REPO / "crates" / "stiffid" / "tests" / "data" / "programs" / "gcode"
MILLING = REPO / "examples" / "milling"
G28_MM = (0.0, 0.0, 150.0)  # workpiece-fusion360.toml
LENGTHS = {  # process-*.toml: tool number -> length_mm
    "process-fusion360.toml": {1: 50.0},
    "process-two-tools.toml": {13: 60.0, 18: 45.0},
    "aluminium.toml": {},
}
FILES = [
    ("fusion360-personal-contour.nc", "workpiece-fusion360.toml", "aluminium.toml"),
    ("fusion360-personal-arcs.nc", "workpiece-fusion360.toml", "aluminium.toml"),
    ("fusion360-generic-router.nc", "workpiece-fusion360.toml", "process-fusion360.toml"),
    ("fusion360-mpcnc-mill.gcode", "workpiece-fusion360.toml", "aluminium.toml"),
    ("fusion360-mpcnc-drill.gcode", "workpiece-fusion360.toml", "aluminium.toml"),
    ("linuxcnc-two-tools.ngc", "workpiece-linuxcnc.toml", "process-two-tools.toml"),
    ("pcb2gcode-drill.ngc", "workpiece-linuxcnc.toml", "aluminium.toml"),
    ("pcb2gcode-outline.ngc", "workpiece-linuxcnc.toml", "aluminium.toml"),
]


def setup_with(workpiece):
    text = (MILLING / "fanuc-milling.toml").read_text()
    text = text[: text.index("[workpiece]")] + (CORPUS / workpiece).read_text()
    return stiffid.Setup.from_toml(text, base_dir=MILLING)


class Reading:
    """The controller's state as the independent reading follows it, mm."""

    def __init__(self, lengths):
        self.pos = [None, None, None]  # programmed point, mm
        self.scale, self.absolute, self.plane, self.motion = 1.0, True, 17, None
        self.lengths, self.tool, self.h = lengths, None, 0.0
        self.cycle = {}

    def lift(self):
        if not self.lengths:
            return 0.0
        return None if self.tool not in self.lengths else self.h - self.lengths[self.tool]

    def tip(self):
        lift = self.lift()
        if None in self.pos or lift is None:
            return None
        return np.array([self.pos[0], self.pos[1], self.pos[2] + lift])

    def set_offset(self, h):
        """G43/G49: the machine stays, its programmed Z changes by the offset's change."""
        if self.pos[2] is not None:
            self.pos[2] += self.h - h
        self.h = h


def words_of(text):
    block = pygcode.Line(text).block
    return [(w.letter, float(w.value)) for w in block.words]


def independent(path, lengths):
    """Per line: ("move", end tip) / ("arc", start, end, centre, plane) / ("hole", xy, bottom)."""
    r, out = Reading(lengths), {}
    for n, text in enumerate(path.read_text().splitlines(), 1):
        words = words_of(text)
        gs = [v for letter, v in words if letter == "G"]
        axes = {letter: v for letter, v in words if letter in "XYZ"}
        centre = {letter: v for letter, v in words if letter in "IJK"}
        for letter, v in words:
            if letter == "T":
                r.tool = int(v)
        for g in gs:
            if g in (20, 21):
                r.scale = 25.4 if g == 20 else 1.0
            elif g in (90, 91):
                r.absolute = g == 90
            elif g in (17, 18, 19):
                r.plane = int(g)
            elif g in (0, 1, 2, 3, 81):
                r.motion = int(g)
            elif g == 80:
                r.motion = None
        if 43 in gs:
            h = next((v for letter, v in words if letter == "H"), r.tool)
            r.set_offset(r.lengths[int(h)])
        if 49 in gs:
            r.set_offset(0.0)
        if 28 in gs:
            reached = home(r, axes)
            if reached is not None:
                out[n] = reached
            continue
        if r.motion == 81 and (axes or 81 in gs):
            out[n] = hole(r, words, axes)
            continue
        if not axes and not (r.motion in (2, 3) and centre):
            continue
        start = r.tip()
        for k, letter in enumerate("XYZ"):
            if letter in axes:
                v = axes[letter] * r.scale
                r.pos[k] = v if r.absolute else (None if r.pos[k] is None else r.pos[k] + v)
        end = r.tip()
        if end is None:
            continue
        if r.motion in (2, 3):
            c = start.copy()
            for k, letter in enumerate("IJK"):
                c[k] += centre.get(letter, 0.0) * r.scale
            out[n] = ("arc", start, end, c, r.plane)
        else:
            out[n] = ("move", end)
    return out


def home(r, axes):
    """G28: the axes named (all when none) to the setup's position (the tip's)."""
    lift = r.lift()
    for k, letter in enumerate("XYZ"):
        if not axes or letter in axes:
            r.pos[k] = None if lift is None else G28_MM[k] - (lift if k == 2 else 0.0)
    return None if r.tip() is None else ("move", r.tip())


def hole(r, words, axes):
    """G81 (G98): over the hole, down to R, feed to Z, back to the higher of R and the start."""
    c = r.cycle
    if 81 in [v for letter, v in words if letter == "G"] and "start" not in c:
        c["start"] = r.pos[2]
    for letter, v in words:
        if letter in "RZ":
            c[letter] = v * r.scale
    x = axes["X"] * r.scale if "X" in axes else r.pos[0]
    y = axes["Y"] * r.scale if "Y" in axes else r.pos[1]
    top = max(c["R"], c["start"])
    r.pos = [x, y, top]
    return ("hole", np.array([x, y, c["Z"]]), np.array([x, y, top]))


@pytest.mark.parametrize("name,workpiece,process", FILES)
def test_corpus_paths_match_an_independent_reading(name, workpiece, process):
    process_path = (MILLING if process == "aluminium.toml" else CORPUS) / process
    read = stiffid.read_program(
        CORPUS / name, chord_tolerance_mm=0.001, setup=setup_with(workpiece), process=process_path
    )
    lines, positions = read["line"], read["position_mm"]
    expected = independent(CORPUS / name, LENGTHS[process])
    assert set(expected) == set(lines.tolist()), name
    for n, what in expected.items():
        points = positions[lines == n]
        if what[0] == "move":
            np.testing.assert_allclose(points[-1], what[1], atol=1e-9, err_msg=f"{name}:{n}")
        elif what[0] == "hole":
            assert np.min(np.linalg.norm(points - what[1], axis=1)) < 1e-9, f"{name}:{n}"
            np.testing.assert_allclose(points[-1], what[2], atol=1e-9, err_msg=f"{name}:{n}")
        else:
            _, start, end, centre, plane = what
            u, v = {17: (0, 1), 18: (2, 0), 19: (1, 2)}[plane]
            r0 = math.hypot(start[u] - centre[u], start[v] - centre[v])
            r1 = math.hypot(end[u] - centre[u], end[v] - centre[v])
            radii = np.hypot(points[:, u] - centre[u], points[:, v] - centre[v])
            assert np.all(np.abs(radii - r0) <= abs(r1 - r0) + 1e-9), f"{name}:{n}"
            np.testing.assert_allclose(points[-1], end, atol=1e-9, err_msg=f"{name}:{n}")
    assert len(positions) > 3
