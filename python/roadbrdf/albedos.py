"""Black-sky, white-sky and blue-sky albedo (``src/roadbrdf/albedo``)."""

from __future__ import annotations

import numbers
import os
from typing import TYPE_CHECKING, Any, Union

import numpy as np

from . import _roadbrdf
from .core import InputError, as_float, warn_at_caller
from .model import Model, SpectralModel, model_argument
from .result import RoadbrdfWarning

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["albedo", "AlbedoResult"]

PathLike = Union[str, "os.PathLike[str]"]


def _array_of(key: str, doc: str) -> property:
    """A read-only attribute giving the report's ``key`` as a float array (None where it is null)."""
    def get(self) -> np.ndarray | None:
        value = self.get(key)
        return None if value is None else np.asarray(value, dtype=float)
    return property(get, doc=doc)


class AlbedoResult(dict):
    """The result of :func:`albedo`: the report ``roadbrdf albedo --json`` prints, as a dict (keys below),
    with its numbers also as NumPy arrays (``wavelengths`` [nm], ``sun_zenith_deg``, ``black_sky``
    [zenith, wavelength], ``white_sky`` [wavelength], ``blue_sky`` [zenith, wavelength] or None, and their
    ``*_error`` estimates), :attr:`summary` (the table ``roadbrdf albedo`` prints), :meth:`write` (the
    command line's writer) and :meth:`to_dataframe`. Albedos are dimensionless reflectances."""

    def __init__(self, report: Any) -> None:
        super().__init__(report.content())
        self._report = report

    wavelengths = _array_of("wavelengths", "[nm] (empty for a model with constant parameters)")
    sun_zenith_deg = _array_of("sun_zenith_deg", "[deg]")
    black_sky = _array_of("black_sky", "[sun zenith, wavelength]")
    black_sky_error = _array_of("black_sky_error", "quadrature error estimates of black_sky")
    white_sky = _array_of("white_sky", "[wavelength]")
    white_sky_error = _array_of("white_sky_error", "quadrature error estimates of white_sky")
    blue_sky = _array_of("blue_sky", "[sun zenith, wavelength]; None without a diffuse fraction or atmosphere")
    blue_sky_error = _array_of("blue_sky_error", "error estimates of blue_sky; None with it")

    @property
    def notes(self) -> list:
        return list(self["notes"])

    @property
    def summary(self) -> str:
        """The table ``roadbrdf albedo`` prints without ``--json``."""
        return self._report.table()

    def write(self, path: PathLike, format: str = "json") -> None:
        """Write as ``roadbrdf albedo -o PATH`` does (``format`` "json": with ``--json``; "table": the
        table), atomically."""
        if format not in ("json", "table"):
            raise InputError(f"format must be 'json' or 'table', not '{format}'")
        self._report.write(os.fspath(path), format == "json")

    def to_dataframe(self) -> pd.DataFrame:
        """A pandas DataFrame, one row per wavelength (one row without wavelengths for a non-spectral
        model): ``wavelength_nm``, ``black_sky_<zenith>deg`` (and ``_error``) per sun zenith, ``white_sky``
        (and ``_error``), ``blue_sky_<zenith>deg`` where defined."""
        import pandas as pd
        columns = {}
        if len(self["wavelengths"]):
            columns["wavelength_nm"] = self.wavelengths
        for k, zenith in enumerate(self.sun_zenith_deg):
            columns[f"black_sky_{zenith:g}deg"] = self.black_sky[k]
            columns[f"black_sky_{zenith:g}deg_error"] = self.black_sky_error[k]
        columns["white_sky"] = self.white_sky
        columns["white_sky_error"] = self.white_sky_error
        if self.blue_sky is not None:
            for k, zenith in enumerate(self.sun_zenith_deg):
                columns[f"blue_sky_{zenith:g}deg"] = self.blue_sky[k]
        return pd.DataFrame(columns)

    def __repr__(self) -> str:
        return "roadbrdf.AlbedoResult(\n" + self.summary.rstrip("\n") + "\n)"


def albedo(model: Model | SpectralModel | str | os.PathLike, params: dict | None = None, **kwargs: Any) -> AlbedoResult:
    """Black-sky, white-sky and blue-sky albedo, as ``roadbrdf albedo --json`` computes them.

    ``model``: a :class:`Model` (with ``params``, a dict NAME: VALUE), a :class:`SpectralModel`, or a fit file,
    a MIX.json or a model name (resolved as the command line resolves it; ``params`` then become its
    ``parameters``). The other arguments are keywords, one per field of the request (listed below, the
    command line's options); ``None`` leaves a field at its default, and ``diffuse_fraction`` may be a number.

    Returns an :class:`AlbedoResult`, a dict: ``wavelengths`` [nm], ``sun_zenith_deg``, ``black_sky`` [zenith][wavelength],
    ``white_sky`` [wavelength], ``blue_sky``, ``diffuse_fraction``, their ``*_error`` estimates,
    ``broadband`` (solar-weighted values), ``luminous``, ``coverage`` (a fit's measured directions and
    the fractions of the black- and white-sky integrals outside them, ``None`` when unknown),
    ``uncertainty`` (standard uncertainties of the same albedos from the parameter covariance of a fit, or
    of a mixture from its end-members' fits; ``None`` when unknown or with ``uncertainty=False``, which skips
    their computation), ``units``, ``notes`` and ``warnings`` (each a dict ``kind``, ``message``: mostly
    extrapolated, non-physical or implausible results), which are also issued as :class:`RoadbrdfWarning`.
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    fraction = kwargs.get("diffuse_fraction")
    if isinstance(fraction, numbers.Real) and not isinstance(fraction, (bool, np.bool_)):
        kwargs["diffuse_fraction"] = str(fraction)
    if isinstance(model, str) or hasattr(model, "__fspath__"):
        if params:
            kwargs["parameters"] = [f"{name}={as_float(value, name)!r}" for name, value in params.items()]
        return _warn_notes(AlbedoResult(_roadbrdf.albedo(os.fspath(model), **kwargs)))
    model = model_argument(model, "model")
    if isinstance(model, SpectralModel):
        if params:
            raise InputError("params cannot be combined with a spectral model")
        return _warn_notes(AlbedoResult(_roadbrdf.albedo_spectral(model._spectral, **kwargs)))
    return _warn_notes(AlbedoResult(_roadbrdf.albedo_model(model._model, model.parameter_values(params), **kwargs)))


# The keywords, from the request's field table (the same rows as `roadbrdf albedo --help`).
_doc = _roadbrdf.albedo.__doc__ or ""
if "Arguments" in _doc:
    albedo.__doc__ += "\n    " + _doc[_doc.index("Arguments"):_doc.rindex("Returns")].strip().replace("\n", "\n    ") + "\n"


def _warn_notes(report: AlbedoResult) -> AlbedoResult:
    """The result's warnings (mostly extrapolated, non-physical or implausible results), issued at the caller."""
    for warning in report.get("warnings", []):
        warn_at_caller(warning["message"], RoadbrdfWarning)
    return report
