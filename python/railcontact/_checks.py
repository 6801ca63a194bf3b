"""The argument checks of the package railcontact, in one place (docs/PYTHON.md "Arguments").

Every public call checks its arguments here before it reaches the library:
  - a wrong type is a TypeError naming the argument: a bool, a string, None or a complex number
    where a number is expected, an array of bools, strings or complex numbers;
  - a non-finite number (NaN, infinity) is an InvalidInputError (a ValueError) naming it;
  - an array of the wrong shape is an InvalidInputError stating the shape expected;
  - two arguments that contradict each other are an InvalidInputError naming both;
  - a value outside its range is the library's InvalidInputError (its message: the value and the
    range), with the argument's name put in front (library_names).
"""
import math
import numbers
import os
import re

import numpy as np

from ._errors import InvalidInputError


def _got(value):
    return f"got {type(value).__name__} {value!r}"


def number(name, value):
    """A finite real number (float); an int or a NumPy number is fine, a bool is not."""
    if type(value) is not float and type(value) is not int:  # the common cases first: a simulation's step
        if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Real):
            raise TypeError(f"{name} must be a real number ({_got(value)})")
    value = float(value)
    if not math.isfinite(value):
        raise InvalidInputError(f"{name} = {value} must be finite")
    return value


def optional_number(name, value):
    return None if value is None else number(name, value)


def integer(name, value, minimum=None):
    """An integer (int or NumPy integer; not a bool, not a float), at least `minimum`."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, numbers.Integral):
        if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)) and not math.isfinite(value):
            raise InvalidInputError(f"{name} = {value} must be a finite integer")
        raise TypeError(f"{name} must be an integer ({_got(value)})")
    value = int(value)
    if minimum is not None and value < minimum:
        raise InvalidInputError(f"{name} = {value} must be at least {minimum}")
    return value


def flag(name, value):
    """True or False (a bool or a NumPy bool; not 0 or 1)."""
    if not isinstance(value, (bool, np.bool_)):
        raise TypeError(f"{name} must be True or False ({_got(value)})")
    return bool(value)


def choice(name, value, allowed):
    """One of the strings `allowed` (a dict or a sequence)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, one of {', '.join(allowed)} ({_got(value)})")
    if value not in allowed:
        raise InvalidInputError(f"{name} = {value!r} is not one of {', '.join(allowed)}")
    return value


def path(name, value):
    """A file path: a str or an os.PathLike (pathlib.Path)."""
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name} must be a path (str or pathlib.Path; {_got(value)})")
    value = os.fspath(value)
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a path as text, not bytes")
    if value == "" or "\0" in value:
        raise InvalidInputError(f"{name} = {value!r} is not a file path")
    return value


def callback(name, value):
    """None or a callable."""
    if value is not None and not callable(value):
        raise TypeError(f"{name} must be a function or None ({_got(value)})")
    return value


def array(name, value, shape, *, finite=True):
    """A real array (float64, C order) of the shape `shape`: a tuple of ints and None (any length),
    e.g. (None, 3). The message states the shape expected. finite=False lets NaN through (a
    failed state of a batch, a column meaning "not given")."""
    if value is None or isinstance(value, (str, bytes)):
        raise TypeError(f"{name} must be an array of shape {_shape_text(shape)} ({_got(value)})")
    a = np.asarray(value)
    if a.dtype.kind not in "iuf":
        what = {"b": "bools", "c": "complex numbers"}.get(a.dtype.kind, f"{a.dtype} values")
        raise TypeError(f"{name} must be an array of real numbers of shape {_shape_text(shape)} (got {what})")
    if a.ndim != len(shape) or any(want is not None and got != want for got, want in zip(a.shape, shape)):
        raise InvalidInputError(f"{name} must be an array of shape {_shape_text(shape)} (got shape {a.shape})")
    a = np.ascontiguousarray(a, dtype=float)
    if finite and not np.all(np.isfinite(a)):
        raise InvalidInputError(f"{name} must be finite (it holds NaN or infinity)")
    return a


def grid(name, value):
    """A non-empty 1-D list of finite numbers, or one number (a grid of one value)."""
    if isinstance(value, numbers.Real) and not isinstance(value, (bool, np.bool_)):
        value = [value]
    a = array(name, value, (None,))
    if a.size == 0:
        raise InvalidInputError(f"{name} must hold at least one value")
    return a


def _shape_text(shape):
    names = iter("NMK")
    dims = [str(d) if d is not None else next(names) for d in shape]
    return "(" + ", ".join(dims) + ("," if len(dims) == 1 else "") + ")"


def at_most_one(**given):
    """Refuses two arguments given together that exclude each other (None: not given)."""
    names = [name for name, value in given.items() if value is not None]
    if len(names) > 1:
        raise InvalidInputError(f"{' and '.join(names)} contradict each other: give one of {', '.join(given)}")


def exactly_one(**given):
    at_most_one(**given)
    if all(value is None for value in given.values()):
        raise InvalidInputError(f"give one of {', '.join(given)}")


class library_names:
    """with library_names(names): puts the argument's name in front of the library's
    InvalidInputError. names maps the library's names of the fields (friction_coefficient,
    "Young's modulus") to the arguments (mu, youngs_modulus)."""

    __slots__ = ("names",)

    def __init__(self, names):
        self.names = names

    def __enter__(self):
        return self

    def __exit__(self, kind, error, traceback):
        if kind is None or not issubclass(kind, InvalidInputError):
            return False
        message = str(error)
        found = [arg for field, arg in self.names.items() if re.search(rf"\b{re.escape(field)}\b", message)]
        found = [arg for arg in dict.fromkeys(found) if not re.search(rf"\b{re.escape(arg)}\b", message)]
        if found:
            raise InvalidInputError(f"{', '.join(found)}: {message}") from None
        return False
