"""Core helpers: the error type, the data folder and the angle conventions (``src/roadbrdf/core``)."""

from __future__ import annotations

import hashlib
import json
import os
import re
import sys
import warnings
from typing import Any, Tuple

import numpy as np

#: Numbers or arrays (anything numpy.asarray accepts).
ArrayLike = Any

from . import _roadbrdf

__all__ = ["InputError", "data_directory", "road_to_zenith_azimuth", "build_fingerprint"]
# Argument conversion for the wrappers (as_int, as_float, as_mapping, as_options, as_text): errors name the
# argument and are InputError (a ValueError) or TypeError, never AttributeError or OverflowError.

#: Errors in the input: a ValueError with the same message as the command line.
InputError = _roadbrdf.InputError


_PACKAGE_DIRECTORY = os.path.dirname(os.path.abspath(__file__)) + os.sep


def warn_at_caller(message: str, category: type = UserWarning) -> None:
    """Issue a warning at the line of the user's code that called into roadbrdf: the first frame
    outward that is not a file of this package (the C++ module's frames are not Python frames). When
    every frame is the package's (``python -m roadbrdf.plot_cli``), at the outermost of them."""
    frame = sys._getframe(0)
    level = 1
    while frame.f_back is not None and os.path.abspath(frame.f_code.co_filename).startswith(_PACKAGE_DIRECTORY):
        frame = frame.f_back
        level += 1
    warnings.warn(message, category, stacklevel=level)


def as_float_array(value: ArrayLike, name: str) -> np.ndarray:
    """``value`` as a float64 array; text, objects and complex numbers are an :class:`InputError`
    naming the argument ``name`` (never a TypeError, never a silently dropped imaginary part)."""
    if np.iscomplexobj(value):
        raise InputError(f"{name}: expected real numbers, got complex numbers")
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError) as error:
        raise InputError(f"{name}: expected numbers, got {type(value).__name__} ({error})") from None


def _type_name(value) -> str:
    return type(value).__name__


def as_int(value, name: str, low: int | None = None, high: int | None = None) -> int:
    """``value`` as an integer: an int, a numpy integer or an integral finite float (``1e3``); anything else
    (inf, nan, 2.5, text, None) is an :class:`InputError` naming the argument ``name``, as is a value outside
    [``low``, ``high``]. Never an OverflowError or a silently truncated value."""
    if isinstance(value, (bool, np.bool_)):
        raise InputError(f"{name}: expected an integer, got {value!r}")
    if isinstance(value, (int, np.integer)):
        out = int(value)
    elif isinstance(value, (float, np.floating)):
        if not np.isfinite(value) or float(value) != np.floor(value):
            raise InputError(f"{name}: expected an integer, got {value!r}")
        out = int(value)
    else:
        raise InputError(f"{name}: expected an integer, got {_type_name(value)} {value!r:.60}")
    if (low is not None and out < low) or (high is not None and out > high):
        bounds = f"[{low if low is not None else '-inf'}, {high if high is not None else 'inf'}]"
        raise InputError(f"{name}: {out} is outside {bounds}")
    return out


def as_float(value, name: str) -> float:
    """``value`` as a float (a real number; inf and nan are passed on for the library to judge); text, None,
    containers and complex numbers are an :class:`InputError` naming the argument ``name``."""
    if isinstance(value, (bool, np.bool_)) or not isinstance(value, (int, float, np.integer, np.floating)):
        if isinstance(value, np.ndarray) and value.ndim == 0 and value.dtype.kind in "iuf":
            return float(value)
        if isinstance(value, str):
            try:
                return float(value)  # a number written as text, as float() reads it
            except ValueError:
                pass
        raise InputError(f"{name}: expected a number, got {_type_name(value)} {value!r:.60}")
    return float(value)


def as_mapping(value, name: str) -> dict:
    """``value`` (a dict, or None for none) as a dict; anything else is a TypeError naming ``name``."""
    if value is None:
        return {}
    if not hasattr(value, "keys") or not hasattr(value, "__getitem__"):
        raise TypeError(f"{name}: expected a dict, got {_type_name(value)} {value!r:.60}")
    try:
        return {k: value[k] for k in value.keys()}
    except (TypeError, KeyError, AttributeError) as e:
        raise TypeError(f"{name}: expected a dict, got {_type_name(value)} ({e})") from None


def as_options(value, name: str) -> dict:
    """Model options {name: choice} as text ({str: str}) from a dict or None (:func:`as_mapping`)."""
    return {str(k): str(v) for k, v in as_mapping(value, name).items()}


def as_text(value, name: str) -> str:
    """``value`` (a str, or an os.PathLike where a path is meant) as text; anything else is a TypeError."""
    if isinstance(value, str):
        return value
    if isinstance(value, os.PathLike):
        return os.fspath(value)
    raise TypeError(f"{name}: expected a string, got {_type_name(value)} {value!r:.60}")


# The nesting depth of the JSON files read (as core/json_input.h bounds the library's).
MAX_JSON_DEPTH = 64


# A JSON string (its brackets are text), and a run of characters that are no bracket.
_JSON_STRING = re.compile(r'"(?:[^"\\]|\\.)*"')
_NOT_BRACKET = re.compile(r'[^\[\]{}]+')


def check_json_depth(text, where):
    """Refuse JSON nested deeper than MAX_JSON_DEPTH (before Python's parser recurses into it), naming the line and
    column where the limit is passed."""
    # The running depth over the brackets outside strings, found by the regular-expression engine and summed by
    # NumPy (an 8 MB fit file in a few hundredths of a second); only a document that passes the limit is scanned
    # token by token below, for the line and column.
    brackets = _NOT_BRACKET.sub("", _JSON_STRING.sub("", text)).encode("ascii")
    if not brackets:
        return
    steps = np.frombuffer(brackets, dtype=np.uint8)
    if int(np.cumsum(np.where((steps == ord("[")) | (steps == ord("{")), 1, -1)).max()) <= MAX_JSON_DEPTH:
        return
    depth = 0
    for m in re.finditer(r'"(?:[^"\\]|\\.)*"|[\[\]{}]', text):
        token = m.group()
        if token in "[{":
            depth += 1
            if depth > MAX_JSON_DEPTH:
                line = text.count("\n", 0, m.start()) + 1
                column = m.start() - (text.rfind("\n", 0, m.start()) + 1) + 1
                raise InputError(f"{where}:{line}:{column}: JSON nested deeper than {MAX_JSON_DEPTH} levels")
        elif token in "]}":
            depth -= 1


def parse_json_text(text, where):
    """JSON text as Python values: depth-checked, errors located (``where:LINE:COLUMN: ...``), as an
    :class:`InputError`."""
    check_json_depth(text, where)
    try:
        return json.loads(text)
    except json.JSONDecodeError as e:
        raise InputError(f"{where}:{e.lineno}:{e.colno}: invalid JSON: {e.msg}") from None
    except RecursionError:
        raise InputError(f"{where}: JSON nested too deeply") from None


def read_json_file(path):
    """A JSON file (UTF-8) as Python values through :func:`parse_json_text`; an unreadable file is an
    :class:`InputError` naming it."""
    where = os.fspath(path)
    try:
        with open(where, "rb") as f:
            data = f.read()
    except OSError as e:
        raise InputError(f"{where}: cannot read: {e.strerror}") from None
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        raise InputError(f"{where}: byte {e.start + 1}: not UTF-8 text") from None
    return parse_json_text(text, where)


def data_directory() -> str:
    """Folder of the bundled data tables (``share/roadbrdf/data`` of the build or install tree;
    ``$ROADBRDF_DATA`` overrides it)."""
    return _roadbrdf.data_directory()


_FINGERPRINT = None


def build_fingerprint() -> str:
    """SHA-256 (hex) of what this process computes with: the loaded ``_roadbrdf`` extension's bytes, the
    package's Python sources (every ``*.py`` under the package folder, by relative path) and the bundled
    tables that the library reads (``data_directory()/third-party``). Two processes with the same fingerprint
    give the same numbers, bit for bit; any rebuild, edit or reinstall changes it (``__version__`` does not).
    Computed once per process (about 30 ms)."""
    global _FINGERPRINT
    if _FINGERPRINT is None:
        h = hashlib.sha256()

        def add(label, path):
            with open(path, "rb") as fh:
                data = fh.read()
            h.update(f"{label}\0{len(data)}\0".encode())
            h.update(data)

        add("_roadbrdf", _roadbrdf.__file__)
        try:
            data = os.path.join(data_directory(), "third-party")
        except InputError:
            data = ""  # no bundled tables: what needs them fails with this error anyway
        for label, top in (("python", os.path.dirname(os.path.abspath(__file__))), ("data", data)):
            files = []
            for folder, dirs, names in os.walk(top, followlinks=True):
                dirs[:] = [d for d in dirs if d != "__pycache__"]
                files += [os.path.join(folder, n) for n in names if label == "data" or n.endswith(".py")]
            for path in sorted(files, key=lambda f: os.path.relpath(f, top)):
                add(f"{label}/{os.path.relpath(path, top)}", path)
        _FINGERPRINT = h.hexdigest()
    return _FINGERPRINT


def road_to_zenith_azimuth(gamma: ArrayLike, alpha: ArrayLike, beta: ArrayLike,
                           delta: ArrayLike) -> Tuple[np.ndarray, np.ndarray, np.ndarray, np.ndarray]:
    """Convert road-photometry angles (gamma, alpha, beta, delta) [deg] to
    (theta_i, phi_i, theta_r, phi_r) [deg]: gamma = theta_i, alpha = 90 - theta_r,
    beta = 180 - (phi_r - phi_i), delta = phi_r - 180."""
    g, a, b, d = np.broadcast_arrays(*(as_float_array(x, name) for x, name in
                                       ((gamma, "gamma"), (alpha, "alpha"), (beta, "beta"), (delta, "delta"))))
    theta_i = g
    theta_r = 90.0 - a
    phi_r = d + 180.0
    phi_i = phi_r - (180.0 - b)
    return theta_i, phi_i, theta_r, phi_r


def write_text_atomic(path, text: str, suffix: str = "") -> None:
    """``text`` (UTF-8) to ``path`` by the library's AtomicFile (core/atomic_file.h: a temporary file in the
    target's folder, synced, given the mode of the file it replaces and renamed over it; links followed,
    devices written directly, the target untouched on any error), or to standard output for ``-``.
    ``suffix`` is not needed any more and kept for callers."""
    if os.fspath(path) == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return
    _roadbrdf.write_text_atomic(os.fspath(path), text)


def write_figure_atomic(figure, path, **savefig) -> None:
    """A matplotlib figure saved to ``path`` by the library's AtomicFile (the format from the extension)."""
    import io
    buffer = io.BytesIO()
    figure.savefig(buffer, format=os.path.splitext(os.fspath(path))[1].lstrip(".") or None, **savefig)
    _roadbrdf.write_bytes_atomic(os.fspath(path), buffer.getvalue())
