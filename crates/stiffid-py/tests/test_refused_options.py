"""Every option combination the library refuses with a typed option error, through Python: the
same combinations as the command's test (crates/stiffid-cli/tests/it/refused_options.rs), from
one table (crates/stiffid/tests/data/refused_options.json): an InputError (a ValueError) with
the library's message, each option spelled as its keyword, where the command spells it as its
flag."""

import json
import re

import numpy as np
import pytest

import stiffid
from conftest import FANUC_DATA, REPO

TABLE = json.loads((REPO / "crates" / "stiffid" / "tests" / "data" / "refused_options.json").read_text())
PLACES = {
    "{fanuc_data}": str(FANUC_DATA),
    "{milling_stiffness}": str(REPO / "examples" / "milling" / "stiffness.json"),
    "{group}": np.array(TABLE["group"], dtype=float),
}


def render(template, spell):
    return re.sub(r"\{([a-z_]+)\}", lambda m: spell(m.group(1)), template)


def value(v):
    return PLACES.get(v, v) if isinstance(v, str) else v


def call(spec):
    setup = stiffid.Setup.builtin(spec["setup"])
    args = [value(a) for a in spec["args"]]
    kwargs = {k: value(v) for k, v in spec["kwargs"].items()}
    name = spec["call"]
    if name.startswith("Setup."):
        return getattr(setup, name[len("Setup."):])(*args, **kwargs)
    return getattr(stiffid, name)(setup, *args, **kwargs)


def test_the_table_holds_every_combination():
    assert len(TABLE["refused"]) >= 30


@pytest.mark.parametrize("case", TABLE["refused"], ids=lambda c: " ".join(c["cli"][:1] + c["cli"][4:]))
def test_every_refused_option_combination_is_the_librarys_typed_error(case):
    with pytest.raises(stiffid.InputError) as raised:
        call(case["python"])
    assert type(raised.value) is stiffid.InputError
    assert str(raised.value) == render(case["error"], lambda name: name)
