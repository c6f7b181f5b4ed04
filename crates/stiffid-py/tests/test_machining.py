"""process_force, read_program and compensate(program=..., process=...) against the command: the
same jobs, so the same documents and the same compensated program."""

import re
import warnings

import numpy as np
import pytest

import stiffid
from conftest import REPO

MILLING = REPO / "examples" / "milling"
POCKET = MILLING / "pocket.nc"
PROCESS = MILLING / "aluminium.toml"
SETUP = MILLING / "fanuc-milling.toml"
STIFFNESS = MILLING / "stiffness.json"


def test_process_force_is_the_commands_document(cli):
    mine = stiffid.process_force(PROCESS, peak_resolution_deg=1.0)
    theirs = cli("force", "--process", PROCESS, "--peak-resolution-deg", "1", "--json")
    assert mine == theirs
    (op,) = mine["operations"]
    # Down milling: the normal force dominates, the feed force is smaller and positive.
    assert op["mean_force_n"][1] > 200 and 0 < op["mean_force_n"][0] < op["mean_force_n"][1]
    with pytest.raises(stiffid.InputError, match=r"peak_resolution_deg: 20: expected"):
        stiffid.process_force(PROCESS, peak_resolution_deg=20.0)


def test_read_program_reads_the_pocket_as_the_command_does(cli, tmp_path):
    read = stiffid.read_program(POCKET)
    assert read["language"] == "gcode"
    theirs = cli("compensate", "--setup", SETUP, "--stiffness", STIFFNESS, "--program", POCKET,
                 "--process", PROCESS, "--out", tmp_path / "p.nc", "--json")["points"]
    assert read["line"].tolist() == [p["line"] for p in theirs]
    # The corner arcs lie on their circles: the first corner's centre is (130, -80), radius 20.
    corner = read["position_mm"][(read["position_mm"][:, 0] > 130) & (read["position_mm"][:, 1] < -80)]
    radii = np.hypot(corner[:, 0] - 130, corner[:, 1] + 80)
    np.testing.assert_allclose(radii, 20, atol=1e-9)
    assert read["rapid"][0] and not read["rapid"][1:-1].any()
    with pytest.raises(stiffid.InputError, match=r"expected a program ending in"):
        stiffid.read_program(PROCESS)


KRL_TRACK = ("DEF track( )\nPTP {A1 10, A2 -80, A3 95, A4 0, A5 30, A6 -5, E1 1500.5, E2 0, E3 0, E4 0, E5 0, E6 0}\n"
             "DECL E6AXIS XP2={A1 11,A2 -79,A3 94,A4 0,A5 31,A6 -5,E1 1600,E2 45.25}\nLIN XP2 C_DIS\nEND\n")


def test_read_program_carries_each_targets_external_values(tmp_path):
    path = tmp_path / "track.src"
    path.write_text(KRL_TRACK)
    read = stiffid.read_program(path)
    assert read["external_axes"] == ["E1", "E2", "E3", "E4", "E5", "E6"]
    assert read["external"].shape == (2, 6)
    np.testing.assert_array_equal(read["external"][0], [1500.5, 0, 0, 0, 0, 0])
    # The aggregate leaves E3..E6 out: no value, NaN.
    np.testing.assert_array_equal(read["external"][1, :2], [1600.0, 45.25])
    assert np.isnan(read["external"][1, 2:]).all()
    np.testing.assert_array_equal(read["q_deg"][1], [11, -79, 94, 0, 31, -5])
    pocket = stiffid.read_program(POCKET)
    assert pocket["external_axes"] == [] and pocket["external"].shape == (len(pocket["line"]), 0)


def test_read_program_gives_the_programmed_speeds():
    # The LS pocket is written from pocket.nc: the G-code's feeds (its arcs circular motions
    # through two of their points), its rapids joint moves, a joint move first.
    gcode = stiffid.read_program(POCKET)
    ls = stiffid.read_program(MILLING / "pocket.ls")
    np.testing.assert_array_equal(np.isnan(gcode["feed_mm_s"]), gcode["rapid"])
    np.testing.assert_array_equal(np.isnan(ls["feed_mm_s"]), ls["joint"])
    assert ls["joint"][0] and ls["joint"].sum() == gcode["rapid"].sum()
    assert len(ls["line"]) < len(gcode["line"])
    np.testing.assert_allclose(np.unique(ls["feed_mm_s"][~ls["joint"]].round(9)), [5, 30])
    assert np.isnan(ls["time_s"]).all() and ls["speed_not_read"] == [None] * len(ls["line"])
    np.testing.assert_allclose(np.unique(gcode["feed_mm_s"][~gcode["rapid"]].round(9)), [5, 30])


@pytest.mark.parametrize("output", [None, "ls"])
def test_compensate_a_program_equals_the_command(cli, tmp_path, output):
    setup = stiffid.Setup.from_file(SETUP)
    out = tmp_path / ("POCKET.ls" if output else "pocket.nc")
    theirs = cli("compensate", "--setup", SETUP, "--stiffness", STIFFNESS, "--program", POCKET,
                 "--process", PROCESS, "--out", out, "--json")
    with pytest.warns(UserWarning, match="plunge"):
        mine = stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET, process=PROCESS, output=output)
    assert mine["program"] == out.read_text()
    document = mine["document"]
    for key in ["setup", "stiffness", "path", "out"]:
        document.pop(key), theirs.pop(key)
    document["program"].pop("out"), theirs["program"].pop("out")
    document["program"].pop("process"), theirs["program"].pop("process")
    assert document == theirs
    force = np.linalg.norm(mine["force_n"], axis=1)
    assert (force > 200).sum() >= len(force) - 4
    with pytest.raises(stiffid.InputError, match=r"process"):
        stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET)
    # The output language by its name, as the command's by the extension of --out: one rule.
    with pytest.raises(stiffid.InputError, match=r"^output: unknown value 'cobol' \(known: gcode, krl, rapid, ls, inform\)"):
        stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET, process=PROCESS, output="cobol")


def test_an_inform_job_in_pulses_equals_the_command(cli, tmp_path):
    # The setup gives the controller's pulses; the job and its sub-jobs are the command's, byte
    # for byte (CR LF line ends), their targets the compensated axis angles to half a pulse.
    pulses = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7]
    path = tmp_path / "yaskawa.toml"
    path.write_text(SETUP.read_text() + f"\n[controller]\npulses_per_deg = {pulses}\n")
    out = tmp_path / "WALL.jbi"
    theirs = cli("compensate", "--setup", path, "--stiffness", STIFFNESS, "--program", POCKET, "--process",
                 PROCESS, "--out", out, "--moves-per-file", "100", "--json")
    setup = stiffid.Setup.from_file(path)
    # Nobody asked for Cartesian targets: no warning of them (asked for, one).
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mine = stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET, process=PROCESS, output="inform",
                                  program_name="wall", moves_per_file=100)
    assert not [w for w in caught if "joint targets" in str(w.message)]
    with pytest.warns(UserWarning, match="INFORM programs are written with joint targets"):
        asked = stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET, process=PROCESS, output="inform",
                                   program_name="wall", moves_per_file=100, targets="cartesian")
    assert asked["program"] == mine["program"]
    assert mine["program"] == out.read_bytes().decode()
    assert "CALL JOB:WALL_04\r\n" in mine["program"]
    positions = []
    for name, text in mine["subprograms"].items():
        assert (tmp_path / f"{name}.jbi").read_bytes().decode() == text
        positions += [[int(v) for v in line.split("=")[1].split(",")]
                      for line in text.split("\r\n") if line.startswith("C0")]
    compensated = np.array([[p[f"qc{k}_deg"] for k in range(1, 7)] for p in theirs["points"]])
    # Each position is a point's compensated angles to half a pulse, in path order: the arcs
    # written as MOVC leave their other chord points out, a taught arc start repeats the point
    # before it.
    positions = np.array(positions) / pulses
    assert len(positions) < len(compensated)
    at = 0
    for p in positions:
        close = np.abs(compensated[max(at - 1, 0):] - p).max(axis=1) <= 0.5 / min(pulses) + 1e-6
        assert close.any(), p
        at = max(at - 1, 0) + int(np.argmax(close)) + 1
    with pytest.raises(ValueError, match=r"controller.pulses_per_deg: missing"):
        stiffid.compensate(stiffid.Setup.from_file(SETUP), stiffness=STIFFNESS, program=POCKET, process=PROCESS,
                           output="inform")


def test_program_options_equal_the_command(cli, tmp_path):
    setup = stiffid.Setup.from_file(SETUP)
    out = tmp_path / "WALL.ls"
    cli("compensate", "--setup", SETUP, "--stiffness", STIFFNESS, "--program", POCKET, "--process", PROCESS,
        "--out", out, "--targets", "joint", "--moves-per-file", "100", "--name-length", "36", "--json")
    with pytest.warns(UserWarning, match="plunge"):
        mine = stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET, process=PROCESS, output="ls",
                                  program_name="wall", targets="joint", moves_per_file=100, name_length=36)
    assert mine["program"] == out.read_text()
    assert list(mine["subprograms"]) == ["WALL_01", "WALL_02", "WALL_03", "WALL_04"]
    for name, text in mine["subprograms"].items():
        assert (tmp_path / f"{name}.ls").read_text() == text
    assert "CALL WALL_04 ;" in mine["program"]
    with pytest.raises(ValueError, match=r"reserved word of FANUC LS"):
        stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET, process=PROCESS, output="ls",
                           program_name="call")
    with pytest.raises(ValueError, match=r"largest TCP speed, 10 mm/s"):
        stiffid.compensate(setup, stiffness=STIFFNESS, program=POCKET, process=PROCESS, output="ls",
                           max_tcp_speed_mm_s=10.0)


def test_read_program_reads_a_stored_inform_job_with_the_setups_pulses(tmp_path):
    # A job as a YRC1000 stores it: no ///POSTYPE line, tool file 1, no 'stiffid: comment, a circle.
    job = ("/JOB\r\n//NAME WELD\r\n//POS\r\n///NPOS 3,0,0,0,0,0\r\n///TOOL 1\r\n"
           "C00000=-48629,112084,69901,4161,-52375,-4796\r\nC00001=-46969,105372,61036,4871,-50464,-5567\r\n"
           "C00002=-45969,104372,60036,4871,-50464,-5567\r\n//INST\r\n///DATE 2023/02/07 09:03\r\n"
           "///ATTR SC,RW\r\n///GROUP1 RB1\r\nNOP\r\nTIMER T=0.50\r\nMOVJ C00000 VJ=25.00\r\n"
           "MOVC C00001 V=10.0\r\nMOVC C00002 V=10.0 PL=0\r\nEND\r\n")
    path = tmp_path / "WELD.JBI"
    path.write_bytes(job.encode())
    pulses = [1341.25, 1341.25, 1150.5, 873.4, 873.4, 532.7]
    setup_path = tmp_path / "yaskawa.toml"
    setup_path.write_text(SETUP.read_text() + f"\n[controller]\npulses_per_deg = {pulses}\n")
    with pytest.raises(stiffid.InputError, match=r"line 15: .*\[controller\] pulses_per_deg"):
        stiffid.read_program(path)
    read = stiffid.read_program(path, setup=stiffid.Setup.from_file(setup_path))
    assert read["language"] == "inform"
    # An independent reading: each C line's whole pulses over the setup's pulses per degree.
    positions = [[int(v) for v in m.group(1).split(",")] for m in re.finditer(r"^C\d{5}=(.*)\r$", job, re.M)]
    np.testing.assert_allclose(read["q_deg"], np.array(positions) / pulses, rtol=0, atol=1e-12)
    np.testing.assert_array_equal(read["line"], [15, 16, 17])
    np.testing.assert_allclose(read["feed_mm_s"][1:], [10.0, 10.0])


def test_krl_subprograms_data_equal_the_command(cli, tmp_path):
    """A KRL program split into sub-programs: each one's .dat (its points) is the file the command
    writes beside it, and the main program's is ``data``."""
    setup, stiffness = MILLING / "kuka-milling.toml", MILLING / "kuka-stiffness.json"
    out = tmp_path / "WALL.src"
    cli("compensate", "--setup", setup, "--stiffness", stiffness, "--program", POCKET, "--process", PROCESS,
        "--out", out, "--moves-per-file", "100", "--json")
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        mine = stiffid.compensate(stiffid.Setup.from_file(setup), stiffness=stiffness, program=POCKET,
                                  process=PROCESS, output="krl", program_name="wall", moves_per_file=100)
    assert mine["program"] == out.read_text() and mine["data"] == out.with_suffix(".dat").read_text()
    assert len(mine["subprograms"]) > 1 and list(mine["subprogram_data"]) == list(mine["subprograms"])
    for name, data in mine["subprogram_data"].items():
        assert data.startswith(f"&ACCESS RVP\n&REL 1\nDEFDAT {name}\n")
        assert (tmp_path / f"{name}.dat").read_text() == data


def test_a_latin1_program_gives_its_encoding_and_the_commands_bytes(cli, tmp_path):
    """A KRL program with a Latin-1 remark, its file beginning with a UTF-8 byte order mark (an
    editor's): ``encoding`` is ``latin-1``, the warning of kind ``encoding`` is the command's,
    and the program written in it is the command's file byte for byte, the mark included."""
    setup, stiffness = MILLING / "kuka-milling.toml", MILLING / "kuka-stiffness.json"
    src = (MILLING / "pocket.src").read_bytes().replace(b"DEF POCKET( )\n", b"DEF POCKET( )\n; Fr\xe4sen\n")
    src = b"\xef\xbb\xbf" + src
    (tmp_path / "pocket.src").write_bytes(src)
    (tmp_path / "pocket.dat").write_bytes((MILLING / "pocket.dat").read_bytes())
    out = tmp_path / "out.src"
    theirs = cli("compensate", "--setup", setup, "--stiffness", stiffness, "--program", tmp_path / "pocket.src",
                 "--process", PROCESS, "--out", out, "--json")
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        mine = stiffid.compensate(stiffid.Setup.from_file(setup), stiffness=stiffness,
                                  program=tmp_path / "pocket.src", process=PROCESS, program_name="out")
    assert mine["encoding"] == "latin-1"
    encoding = [w["message"] for w in theirs["warnings"] if w["kind"] == "encoding"]
    assert len(encoding) == 1 and encoding[0] in [str(w.message) for w in caught]
    assert mine["program"].encode("latin-1") == out.read_bytes()
    assert out.read_bytes().startswith(b"\xef\xbb\xbf") and b"; Fr\xe4sen\n" in out.read_bytes()
