"""setups_new: the same commented setup as `stiffid setups new`, which loads as written, paths
relative to the file it is written to, never over an existing file."""

import re
import subprocess

import pytest

import stiffid
from conftest import cli_path


def command(*args, cwd=None):
    out = subprocess.run([str(cli_path()), "setups", "new", *map(str, args)], check=True,
                         capture_output=True, text=True, cwd=cwd)
    return out.stdout


def test_a_presets_setup_equals_the_command_and_loads():
    text = stiffid.setups_new("kuka-kr210-robond", payload_kg=330)
    assert text == command("--robot", "kuka-kr210-robond", "--payload-kg", 330)
    setup = stiffid.Setup.from_toml(text)
    assert setup.robot_ref == "kuka-kr210-robond"
    # The payload scales the stiffness prior: twice the paper's 165 kg, twice its k1.
    assert setup.nominal_stiffness_nm_per_rad[0] == pytest.approx(2 * 950_000.0, rel=1e-6)
    # Bounds 5 deg inside the joint limits.
    assert setup.lower_deg[1] == pytest.approx(setup.robot.lower_limit_deg[1] + 5, abs=0.051)


def test_a_urdf_setup_written_to_a_file_names_its_robot_and_packages_relative_to_it(mesh_robot, tmp_path):
    urdf = mesh_robot / "mesh_robot" / "urdf" / "robot.urdf"
    out = tmp_path / "cells" / "new.toml"
    out.parent.mkdir()
    text = stiffid.setups_new(urdf, out=out, package_paths=[mesh_robot])
    assert out.read_text() == text
    theirs = tmp_path / "cells" / "cli.toml"
    command("--robot", urdf, "--out", theirs, "--package-path", mesh_robot)
    assert theirs.read_text() == text.replace("new.toml", "cli.toml")
    robot_line = re.search(r'(?m)^robot = "(.*)"$', text).group(1)
    assert not robot_line.startswith("/") and (out.parent / robot_line).resolve() == urdf.resolve()
    assert re.search(r'(?m)^package_paths = \["\.\./\.\./', text)
    # It loads as written, meshes found through its own package paths (no warning).
    setup = stiffid.Setup.from_file(out)
    assert setup.robot.name == "mesh_robot"
    with pytest.raises(stiffid.InputError, match=r"^out .*new.toml: exists; setups_new writes a new file only"):
        stiffid.setups_new(urdf, out=out, package_paths=[mesh_robot])


def test_bad_arguments_are_refused_by_name(tmp_path):
    with pytest.raises(stiffid.InputError, match=r"payload_kg"):
        stiffid.setups_new("kuka-kr210-robond", payload_kg=5000)
    with pytest.raises(stiffid.Error, match=r"no-such-robot"):
        stiffid.setups_new("no-such-robot")
    with pytest.raises(stiffid.InputError, match=r"^out .*nowhere.*: no directory"):
        stiffid.setups_new("kuka-kr210-robond", out=tmp_path / "nowhere" / "x.toml")
    assert list(tmp_path.iterdir()) == []
