"""Spectroradiometer files: ASD ``.asd`` (v6-v8), Spectral Evolution ``.sed`` and Spectra Vista
``.sig``, and manifests that turn a goniometric run of such files into one dataset.

The same readers as ``roadbrdf convert`` and ``roadbrdf calibrate``; docs/data.md
("Instrument files") describes the formats, the manifest, and what is certain or inferred.
Warnings (SVC detector overlaps, saturation flags) are :class:`UserWarning`; malformed files raise
:class:`roadbrdf.InputError` naming the file and the byte offset or line.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Optional, Union

import numpy as np

from . import _roadbrdf

if TYPE_CHECKING:
    from .io import Dataset

PathLike = Union[str, "os.PathLike[str]"]

__all__ = ["InstrumentSpectrum", "read_instrument", "instrument_dataset", "read_manifest", "calibrate_manifest",
           "read_usgs", "usgs_dataset", "calibrate"]

_ZENITH = ("theta_i", "phi_i", "theta_r", "phi_r")
_ROAD = ("gamma", "alpha", "beta", "delta")


class InstrumentSpectrum:
    """One instrument file.

    Attributes
    ----------
    path, format : str
        the file and ``"asd"``, ``"sed"`` or ``"sig"``.
    wavelengths : ndarray (M,)
        [nm], strictly increasing (SVC overlaps resolved by the overlap rule).
    target, reference, reflectance : ndarray (M,) or None
        the target signal, the reference-panel signal stored in the file, and the reflectance
        factor [1] (the file's column / 100, or ASD target / reference).
    quantity, units : str
        of target and reference: ``"DN"``, ``"normalized DN"``, ``"radiance"``, ``"irradiance"``.
    target_settings, reference_settings : dict
        integration times and gains on which raw counts depend.
    metadata : dict
        the header values (keys ``asd.*``, ``sed.*``, ``sig.*``).
    """

    def __init__(self, d: dict[str, Any]) -> None:
        self.__dict__.update(_arrays(d, "wavelengths", "target", "reference", "reflectance"))

    def __repr__(self) -> str:
        return (f"roadbrdf.InstrumentSpectrum({self.path!r}: {self.format}, {self.wavelengths.size} channels "
                f"{self.wavelengths[0]:g}-{self.wavelengths[-1]:g} nm, {self.quantity})")


def _arrays(d: dict[str, Any], *keys: str) -> dict[str, Any]:
    """The library's JSON lists of values as arrays (null values and missing signals stay None)."""
    return dict(d, **{key: None if d[key] is None else np.asarray(d[key], dtype=float) for key in keys})


def read_instrument(path: PathLike, overlap: str = "upper") -> InstrumentSpectrum:
    """Read an ``.asd``, ``.sed`` or ``.sig`` file. ``overlap`` (SVC): ``"upper"`` keeps the next
    detector's channels where detectors overlap, ``"lower"`` the previous detector's, ``"error"``
    refuses; nothing is averaged."""
    return InstrumentSpectrum(_roadbrdf.read_instrument(str(path), overlap))


def instrument_dataset(path: PathLike, quantity: str = "target", overlap: str = "upper",
                       **angles: float) -> Dataset:
    """A one-geometry :class:`roadbrdf.Dataset` from one instrument file (``roadbrdf convert FILE
    --geometry ...``, the same request). Give the angles [deg] as ``theta_i=, phi_i=, theta_r=, phi_r=`` or
    ``gamma=, alpha=, beta=, delta=``; ``quantity`` is ``"target"``, ``"reference"`` or
    ``"reflectance"``."""
    from .io import convert

    return convert(str(path), source="instrument", geometry=_geometry(angles), quantity=quantity, overlap=overlap)


def _geometry(angles: dict[str, float]) -> str:
    """The angles as the request's `geometry` field: "theta_i=D,phi_i=D,theta_r=D,phi_r=D"."""
    if set(angles) not in (set(_ZENITH), set(_ROAD)):
        raise _roadbrdf.InputError("give the angles theta_i, phi_i, theta_r, phi_r or gamma, alpha, beta, delta [deg]")
    return ",".join(f"{name}={float(value)!r}" for name, value in angles.items())


def read_usgs(path: PathLike, wavelengths: PathLike) -> dict[str, Any]:
    """A USGS Spectral Library v7 (splib07a) ASCII spectrum and its wavelength file (io/usgs.h):
    a dict with ``record``, ``title``, ``wavelengths`` [nm] and ``reflectance`` [1] (missing
    channels, -1.23e+34, left out; ``missing`` counts them). Malformed files raise
    :class:`roadbrdf.InputError` naming the file, line and column."""
    return _arrays(_roadbrdf.read_usgs(str(path), str(wavelengths)), "wavelengths", "reflectance")


def usgs_dataset(path: PathLike, wavelengths: PathLike, **angles: float) -> Dataset:
    """A one-geometry :class:`roadbrdf.Dataset` of BRDF = R/pi [sr^-1] from a splib07a spectrum
    (``roadbrdf convert FILE --from usgs --usgs-wavelengths W.txt --geometry ...``, the same request); the
    angles [deg] as in :func:`instrument_dataset`. The library does not record the lab geometry per file."""
    from .io import convert

    return convert(str(path), source="usgs", usgs_wavelengths=str(wavelengths), geometry=_geometry(angles))


def read_manifest(path: PathLike, quantity: str = "target", overlap: str = "upper") -> Dataset:
    """The sample rows of a run manifest as a :class:`roadbrdf.Dataset` of instrument signals
    (``roadbrdf convert RUN.csv --from manifest --quantity ...``, the same request), in the files' units."""
    from .io import convert

    return convert(str(path), source="manifest", quantity=quantity, overlap=overlap)


def calibrate(*args: Any, **kwargs: Any) -> Dataset:
    """The calibrated BRDF [sr^-1] against a reference panel, as ``roadbrdf calibrate`` computes it (one
    library request, the same rules): f = (S - dark)/(white - dark) x rho_panel/pi, with the uncertainty
    of the panel propagated; no extrapolation of the panel file. The radiances are the ``sample`` dataset
    (the one positional argument), ``reference`` and ``dark``, or a run ``manifest`` of instrument files;
    written to ``output`` (``format``) when given. ``None`` leaves a field at its default.
    """
    from . import Dataset

    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    return Dataset._from_dict(_roadbrdf.calibrate(*args, **kwargs))


def calibrate_manifest(manifest: PathLike, panel_reflectance: Optional[PathLike] = None, **kwargs: Any) -> Dataset:
    """The calibrated BRDF [sr^-1] of a run (``roadbrdf calibrate --manifest RUN.csv
    --panel-reflectance RHO.txt``): :func:`calibrate` with ``manifest`` given, the other fields by
    keyword (``panel_brf``, ``panel_brf_start``, ``panel_brf_step``, ``overlap``, ``output``, ...).
    """
    if panel_reflectance is not None:
        kwargs["panel_reflectance"] = panel_reflectance
    return calibrate(manifest=manifest, **kwargs)


_doc = _roadbrdf.calibrate.__doc__ or ""
if "Arguments" in _doc:
    # The keywords, from the request's field table (the same rows as `roadbrdf calibrate --help`).
    calibrate.__doc__ = (calibrate.__doc__ or "") + "\n    " + _doc[_doc.index("Arguments"):_doc.rindex(
        "Returns")].strip().replace("\n", "\n    ") + "\n"
