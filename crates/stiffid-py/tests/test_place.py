"""stiffid.place against `stiffid place` on the drilling panel of the milling example."""

import pytest

import stiffid
from conftest import REPO

MILLING = REPO / "examples" / "milling"
SETUP = MILLING / "fanuc-milling.toml"


def test_place_equals_the_command(cli, tmp_path):
    out = tmp_path / "placed.toml"
    args = ["--stiffness", MILLING / "stiffness.json", "--program", MILLING / "panel.nc"]
    args += ["--process", MILLING / "drilling.toml", "--region-mm", "500,2000,-1500,500"]
    theirs = cli("place", "--setup", SETUP, *args, "--out", out, "--json")
    mine = stiffid.place(
        SETUP,
        MILLING / "stiffness.json",
        program=MILLING / "panel.nc",
        process=MILLING / "drilling.toml",
        region_mm=(500, 2000, -1500, 500),
    )
    assert mine["setup_text"] == out.read_text()
    del mine["setup_text"]
    assert mine == theirs
    assert mine["gain_vs_own_pct"] > 25 and mine["gain_vs_reach_only_pct"] > 0


def test_place_a_path_file_equals_the_command(cli, tmp_path):
    """The example's path file with its poses in the part frame: the same placement and document
    from both front ends; a robot program refused naming why."""
    lines = (MILLING / "path.csv").read_text().splitlines()
    rows = [lines[0]]
    for line in lines[1:]:
        fields = line.split(",")
        for k, own in enumerate((1300.0, -700.0, 400.0)):
            fields[k] = f"{float(fields[k]) - own:.9f}"
        rows.append(",".join(fields))
    part, out = tmp_path / "part.csv", tmp_path / "placed.toml"
    part.write_text("\n".join(rows) + "\n")
    stiffness = MILLING / "stiffness.json"
    theirs = cli("place", "--setup", SETUP, "--stiffness", stiffness, "--path", part,
                 "--region-mm", "500,2000,-1500,500", "--grid", "3", "--samples", "8",
                 "--starts", "1", "--out", out, "--json")
    mine = stiffid.place(SETUP, stiffness, path=part, region_mm=(500, 2000, -1500, 500),
                         grid=3, samples=8, starts=1)
    assert mine.pop("setup_text") == out.read_text()
    assert mine == theirs and mine["gain_vs_own_pct"] > 0
    with pytest.raises(ValueError, match="line 17: the program's tool .* is not the setup's"):
        stiffid.place(SETUP, stiffness, program=MILLING / "pocket.src",
                      process=MILLING / "aluminium.toml", region_mm=(500, 2000, -1500, 500))
    with pytest.raises(ValueError, match="expected program= and process="):
        stiffid.place(SETUP, stiffness, path=part, program=MILLING / "pocket.nc",
                      region_mm=(500, 2000, -1500, 500))


def test_the_free_height_and_tilt_are_the_commands_texts(cli, tmp_path):
    """free= takes the texts of `stiffid place --free`: the same placement; the old keywords and
    free=True refused saying the new form."""
    lines = (MILLING / "path.csv").read_text().splitlines()
    rows = [lines[0]]
    for line in lines[1:]:
        fields = line.split(",")
        for k, own in enumerate((1300.0, -700.0, 400.0)):
            fields[k] = f"{float(fields[k]) - own:.9f}"
        rows.append(",".join(fields))
    part, out = tmp_path / "part.csv", tmp_path / "placed.toml"
    part.write_text("\n".join(rows) + "\n")
    stiffness = MILLING / "stiffness.json"
    effort = dict(region_mm=(500, 2000, -1500, 500), rotation_deg=(0, 0), grid=3, samples=8, starts=1)
    theirs = cli("place", "--setup", SETUP, "--stiffness", stiffness, "--path", part,
                 "--region-mm", "500,2000,-1500,500", "--rotation-deg", "0,0", "--grid", "3",
                 "--samples", "8", "--starts", "1", "--free", "z=-30..60", "--free", "tilt=-4..4",
                 "--out", out, "--json")
    mine = stiffid.place(SETUP, stiffness, path=part, free=["z=-30..60", "tilt=-4..4"], **effort)
    assert mine.pop("setup_text") == out.read_text()
    assert mine == theirs
    assert 370 - 1e-9 <= mine["placed"]["xyz_mm"][2] <= 460 + 1e-9
    with pytest.raises(ValueError, match=r'^z_mm: removed; write free=\["z=LO..HI"\]'):
        stiffid.place(SETUP, stiffness, path=part, z_mm=(0, 10), **effort)
    with pytest.raises(ValueError, match=r'^tilt_deg: removed; write free=\["tilt=-T..T"\]'):
        stiffid.place(SETUP, stiffness, path=part, tilt_deg=5, **effort)
    with pytest.raises(ValueError, match=r"^free: expected a list of str"):
        stiffid.place(SETUP, stiffness, path=part, free=True, **effort)
    with pytest.raises(ValueError, match=r"tilt=-2..5: .*-T..T"):
        stiffid.place(SETUP, stiffness, path=part, free=["tilt=-2..5"], **effort)
