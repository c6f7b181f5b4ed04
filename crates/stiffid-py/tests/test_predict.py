"""predict: the document equals the command's, with every option; bad input is refused by name."""

import os

import numpy as np
import pytest

import stiffid
from conftest import REPO

Q = [10, 20, -90, 30, 20, 10]
MILLING_STIFFNESS = REPO / "examples" / "milling" / "stiffness.json"


@pytest.mark.parametrize(
    "flags, kwargs",
    [
        ([], {}),
        (["--frame", "tool", "--at-mm", "0,0,300"], dict(frame="tool", at_mm=[0, 0, 300])),
    ],
)
def test_the_document_equals_the_command(paper, cli, flags, kwargs):
    theirs = cli("predict", "--setup", "zhang2021-comau-nj165", "--q-deg", ",".join(map(str, Q)),
                 "--wrench", "100,-50,200,5,0,3", *flags, "--json")
    assert stiffid.predict(paper, Q, [100, -50, 200, 5, 0, 3], **kwargs) == theirs


def test_a_stiffness_file_with_its_covariance_equals_the_command(fanuc, cli):
    q = [0, 10, -20, 0, 30, 0]
    theirs = cli("predict", "--setup", "fanuc-r2000ic-165f", "--q-deg", "0,10,-20,0,30,0",
                 "--wrench", "100,-50,200,1,2,3", "--stiffness", MILLING_STIFFNESS, "--json")
    mine = stiffid.predict(fanuc, q, [100, -50, 200, 1, 2, 3], stiffness_nm_per_rad=MILLING_STIFFNESS)
    assert mine == theirs
    assert all(s > 0 for s in mine["tcp_deflection_std_mm"])


def test_it_is_the_deflection_of_the_measuring_points(paper):
    """C_x times the wrench is the loaded point's displacement and rotation (the TCP's, with the
    wrench at the TCP)."""
    w = np.array([100.0, -50, 200, 5, 0, 3])
    tcp = paper.tcp_mm
    doc = stiffid.predict(paper, Q, w, at_mm=tcp)
    c = np.array(doc["cartesian_compliance"]["matrix_si"])
    np.testing.assert_allclose((c @ w)[:3] * 1e3, doc["tcp_deflection_mm"], rtol=1e-9)
    np.testing.assert_allclose((c @ w)[3:] * 1e3, doc["tcp_rotation_mrad"], rtol=1e-9)
    # The text's units are the document's: C_x in mm, mrad per kN, kNm; K_x in N, Nm per um, urad.
    np.testing.assert_allclose(doc["cartesian_compliance"]["matrix_mm_mrad_per_kn_knm"], c * 1e6, rtol=1e-15)
    k = np.array(doc["cartesian_stiffness"]["matrix_si"])
    np.testing.assert_allclose(doc["cartesian_stiffness"]["matrix_n_nm_per_um_urad"], k * 1e-6, rtol=1e-15)
    np.testing.assert_allclose(doc["tcp_deflection_norm_mm"], np.linalg.norm(doc["tcp_deflection_mm"]), rtol=1e-15)


def test_deflection_is_predict_for_each_posture(paper, fanuc, cli):
    """deflection over (n, 6) postures is the list of the command's predict documents, equal as
    parsed JSON (every number to the last bit), with a wrench per posture and every option."""
    qs = [Q, [0, 10, -20, 0, 30, 0], [-30, 5, -100, 40, -20, 90]]
    ws = [[100, -50, 200, 5, 0, 3], [0, 0, -1000, 0, 0, 0], [300, 20, -40, 0, 10, 0]]
    for setup, name, stiffness in [(paper, "zhang2021-comau-nj165", None),
                                   (fanuc, "fanuc-r2000ic-165f", MILLING_STIFFNESS)]:
        extra = ["--stiffness", str(stiffness)] if stiffness else []
        theirs = [cli("predict", "--setup", name, "--q-deg", ",".join(map(str, q)),
                      "--wrench", ",".join(map(str, w)), "--frame", "tool", "--at-mm", "10,0,250",
                      *extra, "--json")
                  for q, w in zip(qs, ws)]
        mine = stiffid.deflection(setup, qs, ws, frame="tool", at_mm=[10, 0, 250],
                                  stiffness_nm_per_rad=stiffness)
        assert mine == theirs
    one = stiffid.deflection(paper, Q, ws[0])
    assert one == [stiffid.predict(paper, Q, ws[0])]
    # One wrench for every posture.
    assert stiffid.deflection(paper, qs, ws[0])[1] == stiffid.predict(paper, qs[1], ws[0])


def test_deflection_refuses_as_predict_does(paper, fanuc):
    qs = [Q, [0, 0, -300, 0, 0, 0]]
    with pytest.raises(stiffid.InputError, match=r"^posture 1: q_deg\[3\]"):
        stiffid.deflection(paper, qs, [0, 0, -500, 0, 0, 0])
    with pytest.raises(ValueError, match="compliance_covariance_rad2_per_nm2: needs stiffness_nm_per_rad"):
        stiffid.deflection(paper, Q, [0, 0, -500, 0, 0, 0], compliance_covariance_rad2_per_nm2=np.eye(6))
    with pytest.raises(ValueError, match=r"wrench: expected shape \(6,\) or \(2, 6\)"):
        stiffid.deflection(paper, qs, np.zeros((3, 6)))
    with pytest.raises(stiffid.InputError, match=r"^observed_mm: not an argument of deflection\(\)"):
        stiffid.deflection(paper, Q, [0, 0, -500, 0, 0, 0], observed_mm=[0, 0, 0])
    with pytest.warns(UserWarning, match="q_deg posture 0: every axis angle lies within"):
        stiffid.deflection(fanuc, [0.1, 0.2, -0.3, 0.4, 0.5, 0.6], [0, 0, -500, 0, 0, 0])


def test_a_level_without_prediction_data_is_refused(paper, tmp_path):
    """The job's own option check: no prediction interval, no level (as --level)."""
    with pytest.raises(stiffid.InputError, match=r"^level: only with a stiffness file that holds prediction data"):
        stiffid.predict(paper, Q, [0, 0, -500, 0, 0, 0], level=0.9)
    assert "tcp_deflection_mm" in stiffid.predict(paper, Q, [0, 0, -500, 0, 0, 0])


def test_a_fifo_is_refused_at_once_as_an_input_file(paper, tmp_path):
    """A named pipe with no writer: refused, never waited on."""
    fifo = tmp_path / "readings.csv"
    os.mkfifo(fifo)
    with pytest.raises(stiffid.InputError, match=r"readings.csv: is a FIFO, not a regular file"):
        stiffid.register(paper, fifo)


def test_bad_input_is_refused_by_name(paper):
    with pytest.raises(ValueError, match=r"q_deg\[3\]"):
        stiffid.predict(paper, [0, 0, -300, 0, 0, 0], [0, 0, -500, 0, 0, 0])
    with pytest.raises(ValueError, match="wrench"):
        stiffid.predict(paper, Q, [0, 0, -500])
    with pytest.raises(ValueError, match="compliance_covariance_rad2_per_nm2"):
        stiffid.predict(paper, Q, [0, 0, -500, 0, 0, 0], compliance_covariance_rad2_per_nm2=np.eye(6))


FANUC_POSTURE = [-59.991, -16.693, -28.93, 3.788, -62.93, 144.919]


def test_a_posture_beyond_the_identification_range_is_flagged_and_warned(fanuc, cli, tmp_path):
    """identify's stiffness file records the region of its postures (each axis' range widened by
    5 deg); predict and validate flag a posture with an axis beyond it, as the command does."""
    import warnings
    from conftest import FANUC_DATA

    k = tmp_path / "k.json"
    cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--out", k, parse=False)
    wrench = [0, 0, -1000, 0, 0, 0]
    for q2 in [-16.693, 42.5]:  # a measured posture; 4 deg past axis 2's largest angle
        q = list(FANUC_POSTURE)
        q[1] = q2
        with warnings.catch_warnings():
            warnings.simplefilter("error")
            doc = stiffid.predict(fanuc, q, wrench, stiffness_nm_per_rad=k)
        assert doc["extrapolates"] is False and doc["outside_region"] == []
    q = list(FANUC_POSTURE)
    q[1] = 48.5
    with pytest.warns(UserWarning, match=r"^the posture lies outside the region the stiffness was identified from "
                      r".*axis 2 at 48\.50 deg \(identified over -52\.03 \.\. 38\.50\)"):
        doc = stiffid.predict(fanuc, q, wrench, stiffness_nm_per_rad=k)
    assert doc["extrapolates"] is True
    assert doc["outside_region"][0]["axis"] == 2
    assert doc["region"]["postures"] == 43
    assert doc == cli("predict", "--setup", "fanuc-r2000ic-165f", "--q-deg", ",".join(map(str, q)),
                      "--wrench", "0,0,-1000", "--stiffness", k, "--json")
    # Over many postures, each flagged posture is warned about.
    with pytest.warns(UserWarning, match="axis 2 at 48.50 deg"):
        docs = stiffid.deflection(fanuc, [FANUC_POSTURE, q], wrench, stiffness_nm_per_rad=k)
    assert [d["extrapolates"] for d in docs] == [False, True]
    # validate: the identification data are inside.
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        v = stiffid.validate(fanuc, k, FANUC_DATA)
    assert v["extrapolated_postures"] == 0
    assert all(c["extrapolates"] is False for c in v["checks"])


def test_a_stiffness_file_without_its_region_is_read_with_one_warning(fanuc, cli, tmp_path):
    import json
    from conftest import FANUC_DATA

    k = tmp_path / "k.json"
    cli("identify", "--setup", "fanuc-r2000ic-165f", "--data", FANUC_DATA, "--out", k, parse=False)
    old = json.loads(k.read_text())
    del old["region"]
    k.write_text(json.dumps(old))
    with pytest.warns(UserWarning, match="does not record the postures it was identified from") as caught:
        doc = stiffid.predict(fanuc, FANUC_POSTURE, [0, 0, -1000, 0, 0, 0], stiffness_nm_per_rad=k)
    assert len([w for w in caught if "region" in str(w.message)]) == 1
    assert doc["extrapolates"] is None and doc["region"] is None
