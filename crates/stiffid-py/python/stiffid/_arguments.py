"""Every error in reading an argument names it.

PyO3 notes the argument on an error raised while converting it (``while processing 'seed'``).
The package's functions and methods put that name in front of the message, and raise a wrong
type as an ``InputError``, as the library's own checks of an argument do
(``update: 'int' object is not an instance of 'bool'``). Python 3.11 and later (earlier
versions have no exception notes: the error is PyO3's own there).
"""

import errno
import functools
import inspect
import os
import re

from ._stiffid import Error, InputError

_NOTE = re.compile(r"while processing '(\w+)'")


def naming(function):
    """``function``, whose errors in reading an argument begin with the argument's name."""

    @functools.wraps(function)
    def call(*args, **kwargs):
        try:
            return function(*args, **kwargs)
        except Exception as error:
            named = _missing(error, function, args, kwargs)
            named = _named(named) if named is error else named
            if named is error:
                raise
            raise named from error

    return call


class MissingFileError(InputError, FileNotFoundError):
    """A file that does not exist: an ``InputError`` whose message begins with the argument that
    names it (``setup: cell.toml: no such file``; a file another file names: its path alone), and
    a ``FileNotFoundError`` (``except FileNotFoundError`` catches it), ``filename`` the path."""

    def __str__(self):
        return str(self.args[0]) if self.args else ""


_MISSING = re.compile(r"(.*): no such file", re.S)


def _missing(error, function, args, kwargs):
    """``error`` as a ``MissingFileError`` naming the argument whose path it is, when it is the
    module's ``FileNotFoundError``; else ``error`` itself."""
    if type(error) is not FileNotFoundError or len(error.args) != 1:
        return error
    found = _MISSING.fullmatch(str(error.args[0]))
    if not found:
        return error
    path = found[1]
    name = _argument_of(function, args, kwargs, path)
    missing = MissingFileError(f"{name}: {error.args[0]}" if name else error.args[0])
    missing.errno, missing.strerror, missing.filename = errno.ENOENT, "no such file", path
    return missing


def _argument_of(function, args, kwargs, path):
    """The name of the argument of the call ``function(*args, **kwargs)`` that gives ``path`` (a
    path, or a list of them), or None."""
    try:
        given = inspect.signature(function).bind_partial(*args, **kwargs).arguments
    except (TypeError, ValueError):
        given = kwargs
    for name, value in given.items():
        values = value if isinstance(value, (list, tuple)) else [value]
        for v in values:
            if isinstance(v, (str, os.PathLike)) and _same(v, path):
                return name
    return None


def _same(value, path):
    try:
        return os.fspath(value) == path or os.path.normpath(os.fspath(value)) == os.path.normpath(path)
    except TypeError:
        return False


def name_arguments_of(cls):
    """Wraps every public method of the class ``cls`` (instance and static) with ``naming``."""
    for key, attribute in list(vars(cls).items()):
        if key.startswith("_"):
            continue
        if isinstance(attribute, staticmethod):
            setattr(cls, key, staticmethod(naming(attribute.__func__)))
        elif type(attribute).__name__ == "method_descriptor":
            setattr(cls, key, naming(attribute))


# Python's own words for a call that does not fit the signature: the argument named first.
_CALL = [
    (re.compile(r"(\w+)\(\) got an unexpected keyword argument '(\w+)'"),
     lambda m: f"{m[2]}: not an argument of {m[1]}() (see help(stiffid.{m[1]}) for its arguments)"),
    (re.compile(r"(\w+)\(\) missing \d+ required (?:positional|keyword-only) arguments?: '(\w+)'.*"),
     lambda m: f"{m[2]}: missing: {m[1]}() needs it"),
    (re.compile(r"(\w+)\(\) got multiple values for (?:keyword )?argument '(\w+)'"),
     lambda m: f"{m[2]}: given twice, by position and by keyword"),
    (re.compile(r"(\w+)\(\) takes (.*) positional arguments? but (\d+) (?:were|was) given"),
     lambda m: f"{m[1]}: takes {m[2]} positional arguments, {m[3]} given: pass the others by keyword"),
    (re.compile(r"argument '(\w+)': (.*)", re.S), lambda m: f"{m[1]}: {m[2]}"),
]


def _named(error):
    """``error`` with its argument's name in front (an ``InputError`` unless it is one of the
    package's errors), or ``error`` itself when no argument is noted on it."""
    if type(error) is TypeError and error.args and isinstance(error.args[0], str):
        for pattern, words in _CALL:
            found = pattern.fullmatch(error.args[0])
            if found:
                return InputError(words(found))
    notes = getattr(error, "__notes__", [])
    for note in notes:
        found = _NOTE.fullmatch(note)
        if found and error.args and isinstance(error.args[0], str):
            message = f"{found[1]}: {error.args[0]}"
            if not isinstance(error, Error):
                return InputError(message)
            error.args = (message, *error.args[1:])
            notes.remove(note)
            return error
    return error
