"""Core helpers: the error type, the data folder and the angle conventions (``src/roadbrdf/core``)."""

from __future__ import annotations

from typing import Any, Tuple

import numpy as np

#: Numbers or arrays (anything numpy.asarray accepts).
ArrayLike = Any

from . import _roadbrdf

__all__ = ["InputError", "data_directory", "road_to_zenith_azimuth"]

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
