"""Every error in reading an argument names it.

PyO3 notes the argument on an error raised while converting it (``while processing 'seed'``);
the package's functions and methods put that name in front of the message
(``seed: True is a bool: expected a whole number``), as the library's own checks of an argument
do. Python 3.11 and later (earlier versions have no exception notes: the message is PyO3's alone).
"""

import functools
import re

_NOTE = re.compile(r"while processing '(\w+)'")


def naming(function):
    """``function``, whose errors in reading an argument begin with the argument's name."""

    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except Exception as error:
            _name(error)
            raise

    return call


def name_arguments_of(cls):
    """Wraps every public method of the class ``cls`` (instance and static) with ``naming``."""
    for key, attribute in list(vars(cls).items()):
        if key.startswith("_"):
            continue
        if isinstance(attribute, staticmethod):
            setattr(cls, key, staticmethod(naming(attribute.__func__)))
        elif type(attribute).__name__ == "method_descriptor":
            setattr(cls, key, naming(attribute))


def _name(error):
    notes = getattr(error, "__notes__", [])
    for note in notes:
        found = _NOTE.fullmatch(note)
        if found and error.args and isinstance(error.args[0], str):
            error.args = (f"{found[1]}: {error.args[0]}", *error.args[1:])
            notes.remove(note)
            return
