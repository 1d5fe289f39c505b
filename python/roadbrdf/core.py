"""Core helpers: the error type, the data folder and the angle conventions (``src/roadbrdf/core``)."""

from __future__ import annotations

import hashlib
import os
import sys
import tempfile
from typing import Any, Tuple

import numpy as np

#: Numbers or arrays (anything numpy.asarray accepts).
ArrayLike = Any

from . import _roadbrdf

__all__ = ["InputError", "data_directory", "road_to_zenith_azimuth", "build_fingerprint"]

#: Errors in the input: a ValueError with the same message as the command line.
InputError = _roadbrdf.InputError


def as_float_array(value: ArrayLike, name: str) -> np.ndarray:
    """``value`` as a float64 array; text, objects and complex numbers are an :class:`InputError`
    naming the argument ``name`` (never a TypeError, never a silently dropped imaginary part)."""
    if np.iscomplexobj(value):
        raise InputError(f"{name}: expected real numbers, got complex numbers")
    try:
        return np.asarray(value, dtype=float)
    except (TypeError, ValueError) as error:
        raise InputError(f"{name}: expected numbers, got {type(value).__name__} ({error})") from None


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


def umask() -> int:
    """The process's umask, read without changing it where /proc tells it."""
    try:
        with open("/proc/self/status", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        pass
    mask = os.umask(0)
    os.umask(mask)
    return mask


def write_atomic(path, write, suffix: str = "") -> str:
    """Write an output file as the library's AtomicFile does: ``write(temporary_path)`` fills a temporary
    file in the target's folder, which is synced, given the mode of the file it replaces (a new file:
    0666 & ~umask, as any program's output) and renamed over the target; the folder is synced. A symbolic
    link is followed and kept. On any error the temporary file is removed and the target is untouched.
    Returns ``path``."""
    target = os.path.realpath(os.fspath(path))
    folder = os.path.dirname(target)
    try:
        mode = os.stat(target).st_mode & 0o7777
    except FileNotFoundError:
        mode = 0o666 & ~umask()
    fd, tmp = tempfile.mkstemp(prefix=".roadbrdf-", suffix=suffix, dir=folder)
    os.close(fd)
    try:
        write(tmp)
        with open(tmp, "rb") as fh:
            os.fsync(fh.fileno())
        os.chmod(tmp, mode)
        os.replace(tmp, target)
        dir_fd = os.open(folder, os.O_RDONLY)
        try:
            os.fsync(dir_fd)
        finally:
            os.close(dir_fd)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def write_text_atomic(path, text: str, suffix: str = "") -> None:
    """``text`` (UTF-8) to ``path`` by :func:`write_atomic`, or to standard output for ``-``."""
    if os.fspath(path) == "-":
        sys.stdout.write(text)
        sys.stdout.flush()
        return

    def fill(tmp):
        with open(tmp, "w", encoding="utf-8") as fh:
            fh.write(text)

    write_atomic(path, fill, suffix)
