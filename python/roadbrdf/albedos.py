"""Black-sky, white-sky and blue-sky albedo (``src/roadbrdf/albedo``)."""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Sequence, Union

import numpy as np

from . import _roadbrdf
from .core import InputError, as_float, warn_at_caller
from .fitting import read_fit
from .model import Model, SpectralModel, model_argument

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


def albedo(model: Model | SpectralModel | str, params: dict | None = None,
           sun_zenith: float | str | Sequence[float] = 30.0, sun_azimuth: float | None = None,
           azimuth_mean: bool = False,
           diffuse_fraction: float | str | None = None, atmosphere: str | None = None,
           spectrum: str | None = None, wavelengths: float | str | Sequence[float] | None = None,
           illuminant: str | None = None, tolerance: float = 1e-5,
           uncertainty: bool = True) -> AlbedoResult:
    """Black-sky, white-sky and blue-sky albedo, as ``roadbrdf albedo --json`` computes them.

    ``model``: a :class:`Model` (with ``params``), a :class:`SpectralModel`, or a fit / MIX.json file.
    ``sun_zenith`` [deg]: a number, a list or a range string such as ``"0:60:30"`` (both ends included); ``diffuse_fraction``: a number in [0, 1] or a CSV file
    (wavelength_nm, diffuse_fraction); ``atmosphere``: e.g. ``"spectrl2:aod=0.2"`` (SPECTRL2 clear sky);
    ``spectrum``: broadband weighting ``"astm-g173-global"`` (default), ``"astm-g173-direct"`` or a CSV
    file; ``illuminant``: also the luminous albedo under "A", "D65" or a lamp file.

    Returns an :class:`AlbedoResult`, a dict: ``wavelengths`` [nm], ``sun_zenith_deg``, ``black_sky`` [zenith][wavelength],
    ``white_sky`` [wavelength], ``blue_sky``, ``diffuse_fraction``, their ``*_error`` estimates,
    ``broadband`` (solar-weighted values), ``luminous``, ``coverage`` (a fit's measured directions and
    the fractions of the black- and white-sky integrals outside them, ``None`` when unknown),
    ``uncertainty`` (standard uncertainties of the same albedos from the parameter covariance of a fit, or
    of a mixture from its end-members' fits; ``None`` when unknown or with ``uncertainty=False``, which skips
    their computation), ``units`` and ``notes``. Mostly extrapolated or non-physical results are also reported as :class:`UserWarning`.
    """
    zeniths = _roadbrdf.values(sun_zenith, "sun_zenith")
    common = (zeniths, None if sun_azimuth is None else as_float(sun_azimuth, "sun_azimuth"), bool(azimuth_mean),
              "" if diffuse_fraction is None else str(diffuse_fraction), atmosphere or "", spectrum or "",
              _roadbrdf.values(wavelengths, "wavelengths", True), illuminant or "",
              as_float(tolerance, "tolerance"), _flag(uncertainty, "uncertainty"))
    model = model_argument(model, "model")
    if isinstance(model, SpectralModel):
        if params:
            raise InputError("params cannot be combined with a spectral model")
        return _warn_notes(AlbedoResult(_roadbrdf.albedo_spectral(model._spectral, *common)))
    return _warn_notes(AlbedoResult(_roadbrdf.albedo_model(model._model, model.parameter_values(params), *common)))


def _flag(value, name: str) -> bool:
    """A True/False argument; anything else is a TypeError naming it (not silently truthy)."""
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    raise TypeError(f"{name}: expected True or False, got {type(value).__name__}")


def _warn_notes(report: AlbedoResult) -> AlbedoResult:
    """The command line's warnings: notes on mostly extrapolated or non-physical results."""
    for note in report.get("notes", []):
        if note.startswith(("WARNING: mostly", "WARNING: non-physical")):
            warn_at_caller(note[len("WARNING: "):])
    return report
