"""The setup's elastostatic model seen from Python: parameters, nominal stiffness, a model given
as a `[model]` fragment and written back."""

import numpy as np
import pytest

import stiffid
from test_cartesian import SPRINGS


def test_the_drives_alone(paper):
    params = paper.parameters
    assert [p["name"] for p in params] == ["k1", "k2", "k3", "k4", "k5", "k6"]
    assert {p["kind"] for p in params} == {"drive"} and {p["unit"] for p in params} == {"Nm/rad"}
    np.testing.assert_allclose([p["stiffness"] for p in params], paper.nominal_stiffness_nm_per_rad, rtol=1e-15)
    assert paper.model_toml == ""


def test_a_model_with_virtual_springs(paper):
    setup = paper.with_model(SPRINGS)
    params = setup.parameters
    assert [(p["name"], p["kind"], p["unit"]) for p in params[6:]] == [
        ("base_tx", "translation", "N/mm"),
        ("base_rz", "rotation", "Nm/rad"),
    ]
    assert [p["stiffness"] for p in params[6:]] == pytest.approx([2e4, 5e6], rel=1e-15)
    # Written back and read again: the same model; the original setup is unchanged.
    again = paper.with_model(setup.model_toml)
    assert again.parameters == params and again.model_toml == setup.model_toml
    assert len(paper.parameters) == 6
    assert len(setup.with_model("").parameters) == 6


def test_a_family_and_a_spring_without_nominal_stiffness(paper):
    setup = paper.with_model('[[model.family]]\nfamily = "tool"\n')
    names = [p["name"] for p in setup.parameters]
    assert names[6:] == ["tool_x", "tool_y", "tool_z"]
    assert [p["stiffness"] for p in setup.parameters[6:]] == [None, None, None]


def test_a_setup_file_with_a_model(tmp_path, paper):
    from test_cell import PAPER_TOML

    setup = stiffid.Setup.from_toml(PAPER_TOML + SPRINGS, "model.toml")
    assert setup.parameters == paper.with_model(SPRINGS).parameters


@pytest.mark.parametrize(
    "fragment, message",
    [
        ('[[model.spring]]\nname = "a"\nkind = "rotation"\nlink = 3\naxis = [0, 0, 0]\n', r"model.spring\[1\].axis"),
        ('[[model.family]]\nfamily = "nope"\n', r"model.family\[1\].family"),
        ("[tool]\nx = 1\n", r"<model>: .*unknown field"),
        ('[[model.spring]]\nname = "a"\nkind = "translation"\nlink = 9\naxis = [1, 0, 0]\n', r"link"),
    ],
)
def test_bad_models_name_the_field(paper, fragment, message):
    with pytest.raises(stiffid.InputError, match=message):
        paper.with_model(fragment)
