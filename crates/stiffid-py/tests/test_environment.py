"""What the command checks in its invocation, Python checks too: angles that look like radians
under a `q_deg` argument warn as `--q-deg` does, and `RAYON_NUM_THREADS` is capped as the command
caps it (the import fails with the command's message)."""

import subprocess
import sys
import warnings

import pytest

import stiffid
from conftest import REPO, cli_path

MILLING_SETUP = REPO / "examples" / "milling" / "fanuc-milling.toml"
MILLING_STIFFNESS = REPO / "examples" / "milling" / "stiffness.json"
MILLING_PATH = REPO / "examples" / "milling" / "path.csv"

RADIANS = [0.1, 0.5, -1.2, 0.3, 0.2, 0.1]
WRENCH = [100, -50, 200, 5, 0, 3]


def command_warning(*args):
    out = subprocess.run([str(cli_path()), *map(str, args)], capture_output=True, text=True)
    assert out.returncode == 0, out.stderr
    return out.stderr


@pytest.mark.parametrize("call, args", [
    ("predict", ["predict", "--setup", "fanuc-r2000ic-165f", "--wrench", ",".join(map(str, WRENCH)), "--q-deg"]),
    ("kinematics", ["kinematics", "--robot", "fanuc-r2000ic-165f", "--q-deg"]),
])
def test_radians_under_q_deg_warn_as_the_command(fanuc, call, args):
    theirs = command_warning(*args, ",".join(map(str, RADIANS)))
    assert "--q-deg: every axis angle lies within +-1.200 deg: radians given as degrees?" in theirs
    with pytest.warns(UserWarning, match=r"^q_deg: every axis angle lies within \+-1\.200 deg: radians given as degrees\?$"):
        if call == "predict":
            stiffid.predict(fanuc, RADIANS, WRENCH)
        else:
            fanuc.robot.kinematics(RADIANS)
    # compensate's start posture warns before the job (which refuses this start's configuration).
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        with pytest.raises(stiffid.InputError, match="configuration"):
            stiffid.compensate(stiffid.Setup.from_file(MILLING_SETUP), MILLING_PATH, MILLING_STIFFNESS, q0_deg=RADIANS)
    assert [str(w.message)[:45] for w in caught] == ["q0_deg: every axis angle lies within +-1.200 "]


def test_degrees_do_not_warn(paper, recwarn):
    stiffid.predict(paper, [10, 20, -90, 30, 20, 10], WRENCH)
    paper.robot.kinematics([10.5, 20, -90, 30, 20, 10])
    assert not [w for w in recwarn if "radians" in str(w.message)]


def imported(threads):
    code = "import stiffid; print(stiffid.predict(stiffid.Setup.builtin('zhang2021-comau-nj165'), [10, 20, -90, 30, 20, 10], [0, 0, -500, 0, 0, 0])['tcp_deflection_mm'][2])"
    env = {"RAYON_NUM_THREADS": threads, "PATH": "/usr/bin:/bin"}
    return subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env)


def test_the_thread_count_is_capped_as_the_command_caps_it():
    for threads in ["5000", "many"]:
        out = imported(threads)
        assert out.returncode != 0
        message = f"RAYON_NUM_THREADS = '{threads}': expected a number of threads from 0 (one per core) to 256"
        assert f"stiffid.InputError: {message}" in out.stderr, out.stderr
        theirs = subprocess.run([str(cli_path()), "robots"], capture_output=True, text=True,
                                env={"RAYON_NUM_THREADS": threads})
        assert theirs.returncode == 2 and message in theirs.stderr
    for threads in ["0", "2"]:
        out = imported(threads)
        assert out.returncode == 0 and float(out.stdout) < 0, out.stderr
