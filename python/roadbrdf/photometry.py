"""Road photometry: r-tables and their classes (``src/roadbrdf/photometry``)."""

from __future__ import annotations

import os
from typing import Tuple, Union

import numpy as np

from . import _roadbrdf
from .core import InputError, as_float, as_text
from .fitting import read_fit
from .model import Model, SpectralModel, model_argument

PathLike = Union[str, "os.PathLike[str]"]

__all__ = ["RTable", "rtable", "read_rtable"]


class RTable(dict):
    """A road r-table: a dict with ``r`` (29 x 20 array of reduced luminance coefficients in sr^-1,
    NaN where the table is not defined; rows tan(gamma), columns beta), ``tan_gamma``,
    ``beta_deg``, ``alpha_deg``, ``name``, and the summary figures ``Q0``, ``S1``, ``S2``, ``Qd`` [sr^-1
    except S1, S2], ``class`` (R system) and ``classes`` (R, N, C). Files store 1e4 r. Tables computed
    from a fit also have ``coverage``: the fit's measured directions and the cells outside them, and the
    negative cells (``roadbrdf rtable --json``'s "coverage"; its warnings are :class:`UserWarning`), and
    ``uncertainty``: the standard uncertainties ``Q0``, ``S1``, ``S2``, ``Qd`` propagated from the fit's
    parameter covariance, or a mixture's from its end-members' fits (wavelengths independent; None where
    undefined) and ``class_probabilities``, a list of ``{"class", "probability"}`` for the classes of
    ``class_system`` of probability >= 1 % with S1 normal; ``uncertainty`` is None for a model given by its
    parameters, a mixture fitted to measured data (methods fitted, shadowed) or a file."""

    def write(self, path: PathLike, format: str = "csv") -> None:
        """Write as ``"csv"``, ``"rtb"`` (DIALux) or ``"radiance"``, atomically."""
        _roadbrdf.write_rtable(np.ascontiguousarray(self["r"]), self["name"], self["alpha_deg"], str(path), format)


def rtable(model: Model | SpectralModel | PathLike, params: dict | None = None, alpha: float = 1.0,
           illuminant: str = "", wavelength: float | None = None,
           band: Tuple[float, float] | None = None, q0_region: str = "standard", class_system: str = "R") -> RTable:
    """Standard r-table (29 tan(gamma) x 20 beta) of a model or a spectral model at observation angle
    ``alpha`` [deg] (CIE: 1), as ``roadbrdf rtable`` computes it (one library request, the same rules).

    ``model`` is a :class:`Model` (with ``params``), a :class:`SpectralModel` (e.g. :func:`read_fit`),
    or a fit file path. A spectral model is reduced to one BRDF per geometry photometrically
    (V(lambda) x ``illuminant`` "A" (default), "D65" or a lamp CSV file), or at one ``wavelength``
    [nm], or averaged over ``band`` = (lo, hi) [nm]. A single-band fit is used at its band. ``Q0`` is
    averaged over ``q0_region`` ("standard" CIE cells or the whole "table"); ``class`` is in
    ``class_system`` (R, N or C). ``notes`` (the first also as ``note``, else None) and ``warnings`` hold
    the command line's one-line messages; the warnings are also raised as :class:`UserWarning`.
    """
    model = model_argument(model, "model")
    if isinstance(model, SpectralModel):
        if params:
            raise InputError("params cannot be combined with a spectral model")
        spectral = model._spectral
    else:
        spectral = _roadbrdf.constant_spectral_model(model._model, model.parameter_values(params))
    return RTable(_roadbrdf.rtable_report(spectral, as_float(alpha, "alpha"), illuminant,
                                          None if wavelength is None else as_float(wavelength, "wavelength"),
                                          None if band is None else _band(band), q0_region, class_system))


def _band(band) -> Tuple[float, float]:
    """(lo, hi) [nm] from a pair of numbers; anything else is an InputError naming ``band``."""
    if isinstance(band, (str, bytes)) or not hasattr(band, "__len__") or len(band) != 2:
        raise InputError(f"band: expected a (lower, upper) pair of wavelengths [nm], got {band!r:.60}")
    return as_float(band[0], "band"), as_float(band[1], "band")


def read_rtable(path: PathLike, format: str | None = None, alpha: float = 1.0, scale: float = 1e4) -> RTable:
    """Read an r-table file (csv, rtb or radiance; format from the extension unless given).
    Zero cells are read as missing (NaN), never as zero reflectance."""
    return RTable(_roadbrdf.read_rtable(as_text(path, "path"), format, as_float(alpha, "alpha"),
                                        as_float(scale, "scale")))
