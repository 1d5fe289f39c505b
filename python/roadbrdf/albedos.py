"""Black-sky, white-sky and blue-sky albedo (``src/roadbrdf/albedo``)."""

from __future__ import annotations

import warnings


from . import _roadbrdf
from .core import InputError
from .fitting import read_fit
from typing import Sequence

from .model import Model, SpectralModel

__all__ = ["albedo"]


def albedo(model: Model | SpectralModel | str, params: dict | None = None,
           sun_zenith: float | str | Sequence[float] = 30.0, sun_azimuth: float | None = None,
           azimuth_mean: bool = False,
           diffuse_fraction: float | str | None = None, atmosphere: str | None = None,
           spectrum: str | None = None, wavelengths: float | str | Sequence[float] | None = None,
           illuminant: str | None = None, tolerance: float = 1e-5) -> dict:
    """Black-sky, white-sky and blue-sky albedo, as ``roadbrdf albedo --json`` computes them.

    ``model``: a :class:`Model` (with ``params``), a :class:`SpectralModel`, or a fit / MIX.json file.
    ``sun_zenith`` [deg]: a number, a list or a range string such as ``"0:60:30"`` (both ends included); ``diffuse_fraction``: a number in [0, 1] or a CSV file
    (wavelength_nm, diffuse_fraction); ``atmosphere``: e.g. ``"spectrl2:aod=0.2"`` (SPECTRL2 clear sky);
    ``spectrum``: broadband weighting ``"astm-g173-global"`` (default), ``"astm-g173-direct"`` or a CSV
    file; ``illuminant``: also the luminous albedo under "A", "D65" or a lamp file.

    Returns a dict: ``wavelengths`` [nm], ``sun_zenith_deg``, ``black_sky`` [zenith][wavelength],
    ``white_sky`` [wavelength], ``blue_sky``, ``diffuse_fraction``, their ``*_error`` estimates,
    ``broadband`` (solar-weighted values), ``luminous``, ``coverage`` (a fit's measured directions and
    the fractions of the black- and white-sky integrals outside them, ``None`` when unknown),
    ``uncertainty`` (standard uncertainties of the same albedos from the parameter covariance of a fit, or
    of a mixture from its end-members' fits; ``None`` when unknown), ``units`` and ``notes``. Mostly extrapolated or non-physical results are also reported as :class:`UserWarning`.
    """
    zeniths = _roadbrdf.values(sun_zenith, "sun_zenith")
    common = (zeniths, None if sun_azimuth is None else float(sun_azimuth), bool(azimuth_mean),
              "" if diffuse_fraction is None else str(diffuse_fraction), atmosphere or "", spectrum or "",
              _roadbrdf.values(wavelengths, "wavelengths", True), illuminant or "",
              float(tolerance))
    if isinstance(model, (str, bytes)) or hasattr(model, "__fspath__"):
        model = read_fit(model)
    if isinstance(model, SpectralModel):
        if params:
            raise InputError("params cannot be combined with a spectral model")
        return _warn_notes(_roadbrdf.albedo_spectral(model._spectral, *common))
    return _warn_notes(_roadbrdf.albedo_model(model._model, model.parameter_values(params), *common))


def _warn_notes(report: dict) -> dict:
    """The command line's warnings: notes on mostly extrapolated or non-physical results."""
    for note in report.get("notes", []):
        if note.startswith(("WARNING: mostly", "WARNING: non-physical")):
            warnings.warn(note[len("WARNING: "):], UserWarning, stacklevel=3)
    return report
