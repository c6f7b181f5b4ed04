"""Option combinations identify refuses: the command and Python give the same error, from the
library's one check (the command spells each option as its flag, Python as its keyword)."""

import re
import subprocess

import pytest

import stiffid
from conftest import FANUC_DATA, cli_path

# Each refused combination: the command's options, Python's keywords, and the error as Python
# words it (the library's text).
REFUSED = [
    (["--robust", "huber", "--nonnegative"], dict(robust="huber", nonnegative=True),
     "robust: not with nonnegative: choose one"),
    (["--offsets", "--robust", "tukey"], dict(offsets=True, robust="tukey"),
     "offsets: not with robust: the offsets are eliminated by centring"),
    (["--offsets", "--nonnegative"], dict(offsets=True, nonnegative=True),
     "offsets: not with nonnegative: the non-negative fit's standard errors"),
    (["--offsets", "--cross-validate"], dict(offsets=True, cross_validate=True),
     "offsets: not with cross_validate: a held-out posture's offsets"),
    (["--offsets", "--folds", "3"], dict(offsets=True, folds=3),
     "offsets: not with folds: a held-out posture's offsets"),
    (["--compare-models", "--robust", "huber"], dict(compare_models=True, robust="huber"),
     "compare_models: not with robust: the comparison holds out posture by posture"),
    (["--compare-models", "--nonnegative", "--folds", "4", "--offsets"],
     dict(compare_models=True, nonnegative=True, folds=4, offsets=True),
     "compare_models: not with nonnegative, folds, offsets: the comparison"),
    (["--compare-models", "--cross-validate"], dict(compare_models=True, cross_validate=True),
     "compare_models: not with cross_validate: the comparison"),
    (["--candidates", "tilt3_x"], dict(candidates=["tilt3_x"]),
     "candidates: only with compare_models"),
    (["--bootstrap", "5"], dict(bootstrap=5), "bootstrap: only with compare_models"),
    (["--compare-models", "--seed", "3"], dict(compare_models=True, seed=3),
     "seed: only with bootstrap"),
    (["--compare-models", "--bootstrap", "0"], dict(compare_models=True, bootstrap=0),
     "bootstrap: 0 resamples: expected 1 to 2000"),
]


def command_error(options):
    """The command's one-line error for `options`, its flags written as Python's keywords."""
    args = ["identify", "--setup", "fanuc-r2000ic-165f", "--data", str(FANUC_DATA), *options]
    out = subprocess.run([str(cli_path()), *args], capture_output=True, text=True)
    assert out.returncode == 2, out
    assert out.stdout == ""
    line = out.stderr.strip()
    assert line.startswith("error: ") and "\n" not in line, line
    return re.sub(r"--([a-z][a-z-]*)", lambda m: m.group(1).replace("-", "_"), line[len("error: "):])


@pytest.mark.parametrize("options,keywords,expected", REFUSED)
def test_the_command_and_python_refuse_the_same_combinations_alike(options, keywords, expected):
    fanuc = stiffid.Setup.builtin("fanuc-r2000ic-165f")
    with pytest.raises(stiffid.InputError) as raised:
        stiffid.identify(fanuc, str(FANUC_DATA), **keywords)
    python = str(raised.value)
    assert python.startswith(expected), python
    assert command_error(options) == python
