"""The package's checks of its arguments: each value as the library takes it (a real number,
a whole number, a flag, text, a path), refused with a message naming the keyword it was
given as. Ranges are the library's (``_core._check_number``, the registry's declarations)."""

import numbers
import os

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


def _whole(name: str, value, lo: float, hi: float) -> int:
    """value as an int, when it is a whole number in [lo, hi] (the library's check)."""
    v = _real(name, value)
    _core._check_number(name, v, lo, hi, True)
    return int(v)


def _observer(name: str, value) -> int:
    v = _whole(name, value, 2, 10)
    if v not in (2, 10):
        raise Error("%s: %r is not 2 or 10" % (name, value))
    return v


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
    if columns is None:
        return ""
    if isinstance(columns, str):
        return columns
    parts = [str(c) for c in columns]
    if len(parts) != 2:
        raise Error("columns: give two columns (n and k), not %r" % (columns,))
    return ",".join(parts)


def _render_args(shape, size, lighting, roughness, background, illuminant, observer, direct,
                 linear) -> tuple:
    """The compiled renderer's arguments after the material's own."""
    return (_text("shape", shape), _whole("size", size, 1, _core._max_tile_size),
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
