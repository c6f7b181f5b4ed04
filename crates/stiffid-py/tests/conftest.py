"""Shared fixtures: the built `stiffid` command (to compare with), the data and the setups."""

import json
import os
import subprocess
from pathlib import Path

import numpy as np
import pytest

import stiffid

REPO = Path(__file__).resolve().parents[3]
FANUC_DATA = REPO / "examples" / "data" / "fanuc-r2000ic-165f" / "measurements.csv"


def cli_path() -> Path:
    """The `stiffid` binary: $STIFFID_CLI, else target/ci/stiffid (of $CARGO_TARGET_DIR)."""
    if "STIFFID_CLI" in os.environ:
        return Path(os.environ["STIFFID_CLI"])
    target = Path(os.environ.get("CARGO_TARGET_DIR", REPO / "target"))
    return target / "ci" / "stiffid"


@pytest.fixture(scope="session")
def cli():
    """Runs the command with arguments and returns its stdout parsed as JSON (or the text)."""
    path = cli_path()
    assert path.exists(), f"{path}: build the command first (cargo build --release) or set STIFFID_CLI"

    def run(*args, parse=True):
        out = subprocess.run([str(path), *map(str, args)], check=True, capture_output=True, text=True)
        return json.loads(out.stdout) if parse else out.stdout

    return run


@pytest.fixture(scope="session")
def paper():
    return stiffid.Setup.builtin("zhang2021-comau-nj165")


@pytest.fixture(scope="session")
def fanuc():
    return stiffid.Setup.builtin("fanuc-r2000ic-165f")


def write_postures(path: Path, postures) -> Path:
    """A postures CSV (posture,q1_deg,...,q6_deg) with 17 significant digits (exact round trip)."""
    lines = ["posture,q1_deg,q2_deg,q3_deg,q4_deg,q5_deg,q6_deg"]
    lines += [f"{i + 1}," + ",".join(repr(float(v)) for v in q) for i, q in enumerate(postures)]
    path.write_text("\n".join(lines) + "\n")
    return path


def plain(document):
    """A document as its JSON holds it: arrays as lists, NaN as None."""
    if isinstance(document, dict):
        return {key: plain(value) for key, value in document.items()}
    if isinstance(document, (list, tuple)):
        return [plain(value) for value in document]
    if isinstance(document, np.ndarray):
        return plain(document.tolist())
    if isinstance(document, float) and document != document:
        return None
    return document


@pytest.fixture(scope="session")
def mesh_robot(tmp_path_factory):
    """The generated 6R robot with STL collision meshes (crates/stiffid/tests/support/mesh_robot.rs)
    and its cell setup, written by the library's `mesh_robot` example (which `cargo test` builds beside
    the command): the package directory (`mesh_robot/urdf/robot.urdf`,
    `mesh_robot/meshes/*.stl`, `cell.toml`)."""
    example = cli_path().parent / "examples" / "mesh_robot"
    assert example.exists(), f"{example}: build it first (cargo build --profile ci -p stiffid --example mesh_robot)"
    out = tmp_path_factory.mktemp("mesh")
    subprocess.run([str(example), str(out)], check=True, capture_output=True)
    return out
