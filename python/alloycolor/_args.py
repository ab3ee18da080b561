"""The package's checks of its arguments: each value as the library takes it (a real number,
a whole number, a flag, text, a path), refused with a message naming the keyword it was
given as. Ranges and their words are the library's, as the program's options have them: the
registry's declarations (fit), the settings' ranges (``_setting``: match, tolerance,
suggest), the library's checks of angles, colour tables, pictures, exports and pages; a
number is given to them as Python spells it (``_spelled``), so that the words are those
the program prints for the same text."""

import numbers
import os
from typing import Iterable

import numpy as np

from . import _alloycolor as _core
from ._alloycolor import Error


def _real(name: str, value) -> float:
    """value as a float, when it is a real number (not a bool, complex or string)."""
    if isinstance(value, (bool, np.bool_)):
        raise Error("%s: %r is a boolean, not a number" % (name, value))
    if isinstance(value, (complex, np.complexfloating)):
        raise Error("%s: %r is complex; give a real number" % (name, value))
    if not isinstance(value, numbers.Real):
        raise Error("%s: %r is not a number" % (name, value))
    return float(value)


def _whole(name: str, value, lo: float = -2**31, hi: float = 2**31 - 1) -> int:
    """value as an int, when it is a whole number in [lo, hi] (the library's check; by
    default the range of the program's whole-number options, whose own ranges the library
    checks after)."""
    v = _real(name, value)
    _core._check_number(name, v, lo, hi, True)
    return int(v)


def _spelled(value) -> str:
    """A real number as Python spells it: the text a user would give the program for it."""
    return repr(float(value)) if isinstance(value, (float, np.floating)) else str(int(value))


def _setting(name: str, value) -> float:
    """A number checked against the range every face takes for the setting ``name`` (the
    library's: match's target_sigma and margin, tolerance's de, suggest's count), refused in
    the words the program uses for the same value."""
    v = _real(name, value)
    _core._check_setting(name, _spelled(value))
    return v


def _observer(name: str, value) -> int:
    """A CIE observer, as the program takes --observer: a whole number, which the library's
    colour tables accept when it is 2 or 10 ("unknown observer 5 deg; valid observers: ...")."""
    return _whole(name, value)


def _texts(name: str, value) -> list:
    """One string or a sequence of strings, as a list."""
    if isinstance(value, str):
        return [value]
    if isinstance(value, (bytes, dict)) or not isinstance(value, Iterable):
        raise Error("%s: %r is not a string or a sequence of strings" % (name, value))
    return [_text(name, v) for v in value]


def _path(name: str, value) -> str:
    if not isinstance(value, (str, os.PathLike)):
        raise Error("%s: %r is not a file path" % (name, value))
    path = os.fspath(value)
    if not isinstance(path, str):
        raise Error("%s: give the path as a str, not %r" % (name, value))
    return path


def _callable(name: str, value):
    if value is not None and not callable(value):
        raise Error("%s: %r is not callable" % (name, value))
    return value


def _flag(name: str, value) -> bool:
    if not isinstance(value, (bool, np.bool_)):
        raise Error("%s: %r is not True or False" % (name, value))
    return bool(value)


def _text(name: str, value) -> str:
    if not isinstance(value, str):
        raise Error("%s: %r is not a string" % (name, value))
    return value


def _holds_bool(value) -> bool:
    """True for a bool, or a (nested) list or tuple holding one (numpy turns [0.5, False]
    into floats)."""
    if isinstance(value, (list, tuple)):
        return any(_holds_bool(v) for v in value)
    return isinstance(value, (bool, np.bool_))


def _real_array(name: str, value) -> np.ndarray:
    arr = np.asarray(value)
    if arr.dtype.kind == "b" or _holds_bool(value):
        raise Error("%s: booleans are not numbers" % name)
    if arr.dtype.kind == "c":
        raise Error("%s: complex values; give real numbers" % name)
    if arr.dtype.kind not in "iuf":
        raise Error("%s: %r is not a number or an array of numbers" % (name, value))
    return np.asarray(arr, dtype=float)


def _columns_text(columns) -> str:
    """columns as the program's --columns N,K: "n6,k6", or two names or 1-based numbers."""
    if columns is None:
        return ""
    if isinstance(columns, str):
        return columns
    if isinstance(columns, (bool, bytes, dict)) or not isinstance(columns, Iterable):
        raise Error("columns: give \"N,K\" or two columns (n and k), not %r" % (columns,))
    parts = list(columns)
    for c in parts:
        if isinstance(c, (bool, np.bool_)) or not isinstance(c, (str, numbers.Integral)):
            raise Error("columns: %r is not a column's name or 1-based number" % (c,))
    if len(parts) != 2:
        raise Error("columns: give two columns (n and k), not %r" % (columns,))
    return ",".join(str(c) for c in parts)


def _render_args(shape, size, lighting, roughness, background, illuminant, observer, direct,
                 linear) -> tuple:
    """The compiled renderer's arguments after the material's own."""
    return (_text("shape", shape), _whole("size", size),
            _text("lighting", lighting), _real("roughness", roughness),
            "" if background is None else _text("background", background),
            _text("illuminant", illuminant), _observer("observer", observer),
            _flag("direct", direct), _flag("linear", linear))


def _export_args(prefix, format, scene_dir, roughness) -> tuple:
    """The compiled export's arguments after the material's own."""
    return (_path("prefix", prefix), _text("format", format),
            "" if scene_dir is None else _path("scene_dir", scene_dir), _real("roughness", roughness))


def _broadcast_x(model, x) -> np.ndarray:
    if isinstance(x, str):
        return np.asarray(model.parse_composition(x), dtype=float)
    arr = np.asarray(x)
    if arr.dtype.kind in "US":
        return np.vectorize(model.parse_composition, otypes=[float])(arr)
    if arr.dtype.kind == "b" or _holds_bool(x):
        raise Error("x: a composition is an atomic fraction (a real number or a string such "
                    "as \"75wt%\"), not a boolean")
    if arr.dtype.kind == "c":
        raise Error("x: a composition is an atomic fraction, a real number, not complex")
    if arr.dtype.kind not in "iuf":
        raise Error("x: %r is not a composition (a number in [0, 1] or a string such as "
                    "\"75wt%%\")" % (x,))
    return np.asarray(arr, dtype=float)


def _output_guard(*sources, guard=None):
    """The inputs of a call that writes, noted as the program notes a command's (core/output.h
    OutputGuard: no output may replace one): the colour tables, and each source's files: a
    path, a Dataset's manifest and samples, a Spectrum's file, a Model's inputs (the file it
    was loaded from; the data set it was fitted to and the model it refitted)."""
    guard = _core._OutputGuard() if guard is None else guard
    for source in sources:
        if isinstance(source, str):
            guard.note(source)
        elif source is not None:
            source._note_inputs(guard)
    return guard
