"""Road photometry: r-tables and their classes (``src/roadbrdf/photometry``)."""

from __future__ import annotations

import os
from typing import Any, Union

import numpy as np

from . import _roadbrdf
from .core import InputError, as_float, as_text
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


def rtable(model: Model | SpectralModel | PathLike | None = None, params: dict | None = None, **kwargs: Any) -> RTable:
    """Standard r-table (29 tan(gamma) x 20 beta) of a model, a spectral model or an r-table file at
    observation angle ``alpha`` [deg] (CIE: 1), as ``roadbrdf rtable`` computes it (one library request, the
    same rules).

    ``model`` is a :class:`Model` (with ``params``, a dict NAME: VALUE), a :class:`SpectralModel` (e.g.
    :func:`read_fit`), or a fit file, a MIX.json or a model name (resolved as the command line resolves it;
    ``params`` then become its ``parameters``); or None with ``import_file`` (an r-table file). The other
    arguments are keywords, one per field of the request (listed below, the command line's options); ``None``
    leaves a field at its default. A spectral model is reduced to one BRDF per geometry photometrically
    (V(lambda) x ``illuminant`` "A" (default), "D65" or a lamp CSV file), or at one ``wavelength`` [nm], or
    averaged over ``band`` = (lo, hi) [nm]. A single-band fit is used at its band. ``Q0`` is averaged over
    ``q0_region`` ("standard" CIE cells or the whole "table"); ``class`` is in ``class_system`` (R, N or C).
    ``notes`` (the first also as ``note``, else None) and ``warnings`` hold the command line's one-line
    messages; the warnings are also raised as :class:`UserWarning`. With ``output`` the table is written
    there (``format``), with ``compare`` compared with another r-table file (``comparison``).
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    if model is None:
        if params:
            raise InputError("params: need a model")
        return RTable(_roadbrdf.rtable(**kwargs))
    if isinstance(model, str) or hasattr(model, "__fspath__"):
        if params:
            kwargs["parameters"] = [f"{name}={as_float(value, name)!r}" for name, value in _params(params).items()]
        return RTable(_roadbrdf.rtable(os.fspath(model), **kwargs))
    model = model_argument(model, "model")
    if isinstance(model, SpectralModel):
        if params:
            raise InputError("params cannot be combined with a spectral model")
        spectral = model._spectral
    else:
        spectral = _roadbrdf.constant_spectral_model(model._model, model.parameter_values(params))
    return RTable(_roadbrdf.rtable_spectral(spectral, **kwargs))


# The keywords, from the request's field table (the same rows as `roadbrdf rtable --help`).
_doc = _roadbrdf.rtable.__doc__ or ""
if "Arguments" in _doc:
    rtable.__doc__ += "\n    " + _doc[_doc.index("Arguments"):_doc.rindex("Returns")].strip().replace("\n", "\n    ") + "\n"


def _params(params) -> dict:
    """``params`` as a dict; anything else is an InputError naming it."""
    if not isinstance(params, dict):
        raise InputError(f"params: expected a dict NAME: VALUE, got {type(params).__name__}")
    return params


def read_rtable(path: PathLike, format: str | None = None, alpha: float = 1.0, scale: float = 1e4) -> RTable:
    """Read an r-table file (csv, rtb or radiance; format from the extension unless given).
    Zero cells are read as missing (NaN), never as zero reflectance."""
    return RTable(_roadbrdf.read_rtable(as_text(path, "path"), format, as_float(alpha, "alpha"),
                                        as_float(scale, "scale")))
