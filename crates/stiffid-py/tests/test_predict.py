"""predict: the document equals the command's, with every option; bad input is refused by name."""

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
    """Each measuring point's displacement is the forward model's (`deflection`, Eq. 3-7), and
    C_x times the wrench is the loaded point's displacement and rotation."""
    w = np.array([100.0, -50, 200, 5, 0, 3])
    doc = stiffid.predict(paper, Q, w)
    for p, point in zip(doc["measuring_points"], paper.measuring_points_mm):
        d = stiffid.deflection(paper, Q, w, observed_mm=point)
        np.testing.assert_allclose(p["displacement_mm"], d["displacement_mm"][0], rtol=1e-12)
    loaded = stiffid.deflection(paper, Q, w)
    c = np.array(doc["cartesian_compliance"]["matrix_si"])
    np.testing.assert_allclose((c @ w)[:3] * 1e3, loaded["displacement_mm"][0], rtol=1e-9)
    np.testing.assert_allclose((c @ w)[3:], loaded["rotation_rad"][0], rtol=1e-9)


def test_bad_input_is_refused_by_name(paper):
    with pytest.raises(ValueError, match=r"q_deg\[3\]"):
        stiffid.predict(paper, [0, 0, -300, 0, 0, 0], [0, 0, -500, 0, 0, 0])
    with pytest.raises(ValueError, match="wrench"):
        stiffid.predict(paper, Q, [0, 0, -500])
    with pytest.raises(ValueError, match="compliance_covariance_rad2_per_nm2"):
        stiffid.predict(paper, Q, [0, 0, -500, 0, 0, 0], compliance_covariance_rad2_per_nm2=np.eye(6))
