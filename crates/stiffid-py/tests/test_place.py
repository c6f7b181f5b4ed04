"""stiffid.place against `stiffid place` on the drilling panel of the milling example."""

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
    assert mine["gain_vs_own_percent"] > 25 and mine["gain_vs_reach_only_percent"] > 0
