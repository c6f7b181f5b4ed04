"""The `stiffid` command that the wheel installs (its console script, and `python -m stiffid`) is
the Rust binary's program: the same output for the same call, the same exit codes."""

import subprocess
import sys
from pathlib import Path

import pytest

from conftest import cli_path

SCRIPT = Path(sys.executable).with_name("stiffid")


def run(command, *args):
    return subprocess.run([*command, *map(str, args)], capture_output=True, text=True)


@pytest.fixture(params=["script", "module"])
def installed(request):
    """The command as the wheel installs it: the console script beside this Python, or -m."""
    if request.param == "script":
        assert SCRIPT.exists(), f"{SCRIPT}: the wheel's console script is missing"
        return [str(SCRIPT)]
    return [sys.executable, "-m", "stiffid"]


def test_same_output_as_the_binary(installed):
    args = ["kinematics", "--robot", "comau-smart5-nj165-3.0", "--q-deg", "10,20,-90,30,20,10", "--json"]
    ours = run(installed, *args)
    binary = run([str(cli_path())], *args)
    assert ours.returncode == 0, ours.stderr
    assert ours.stdout == binary.stdout
    # The reference robot's flange at this posture (DESIGN: (2417.77, -466.26, 2116.01) mm).
    assert "2417.7" in ours.stdout


def test_version_and_bad_input(installed):
    version = run(installed, "--version")
    assert version.returncode == 0
    assert version.stdout == run([str(cli_path())], "--version").stdout
    bad = run(installed, "kinematics", "--robot", "no-such-robot", "--q-deg", "0,0,0,0,0,0")
    assert bad.returncode == 2
    assert bad.stderr.startswith("error: ")
    assert bad.stdout == ""
