"""Virtual road surfaces and the virtual gonioreflectometer (``src/roadbrdf/surface``, docs/surface.md)."""

from __future__ import annotations

import os
from typing import Any, Optional, Sequence, Tuple, Union

import numpy as np

from . import _roadbrdf
from .core import ArrayLike, InputError, as_float, as_float_array, as_mapping, as_text, warn_at_caller
from .io import Dataset
from .model import Model

PathLike = Union[str, "os.PathLike[str]"]
#: Wavelengths [nm]: None (default), a number, a sequence or a range text such as "400:700:10".
Wavelengths = Union[None, float, Sequence[float], str]

__all__ = ["Surface", "surface", "read_surface", "flat_surface", "gaussian_slope_surface", "render", "render_albedo"]


def _is_path(value):
    return isinstance(value, (str, bytes)) or hasattr(value, "__fspath__")


class Surface:
    """A virtual road sample: a periodic height field with one material per cell (docs/surface.md,
    ``src/roadbrdf/surface/height_field.h``). Made by :func:`surface`, :func:`read_surface`,
    :func:`flat_surface` or :func:`gaussian_slope_surface`; rendered by :func:`render` and
    :func:`render_albedo`.

    Attributes
    ----------
    heights : ndarray (ny, nx)
        node heights [mm]; ``heights[j, i]`` is node (i, j) at x = i cell_mm, y = j cell_mm. The grid is
        periodic (node nx is node 0); each cell is two planar triangles split along (i, j)-(i+1, j+1).
    material_map : ndarray (ny, nx) of int
        material of cell (i, j) at ``[j, i]``: an index into ``materials``.
    materials : list of str
        material names (index 0 is the mastic of a generated sample, then one per coarse class).
    material_specs : list of dict
        each material's ``fit`` file (absolute path) and ``fit_model``, or ``model``, ``parameters``, ``options``.
    cell_mm : float
        grid spacing [mm]; ``size_mm`` = (nx cell_mm, ny cell_mm) is the period.
    statistics : dict
        texture statistics (computed once): ``mpd_mm`` mean profile depth [mm] (ISO 13473-1 style, the
        baseline being the sample period), ``etd_mm`` = 0.2 + 0.8 MPD [mm], ``rms_height_mm``,
        ``mean_height_mm``, ``min_height_mm``, ``max_height_mm`` [mm], ``surface_area_ratio`` (true /
        projected area, dimensionless), ``exposed_area_fraction`` and ``exposed_true_area_fraction``
        (per material, aligned with ``materials``: share of the projected / true area). The same
        numbers as ``roadbrdf surface`` prints; also as the properties ``mpd_mm``, ``etd_mm``,
        ``rms_height_mm``, ``area_ratio``, ``exposed_area_fraction``.
    generation : dict or None
        for a sample generated from a formulation: ``classes``, ``target_volume_fraction``,
        ``achieved_volume_fraction`` (of the slab), ``grain_count``, ``targets_reached``, ``deposition``,
        ``slab_thickness_mm``, ``matrix_level_mm``, ``notes``.
    """

    def __init__(self, handle: Any, generation: Optional[dict] = None) -> None:
        self._field = handle
        self.generation = generation
        self._statistics = None
        self._heights = None
        self._material_map = None

    @property
    def name(self) -> str:
        return self._field.name

    @property
    def description(self) -> str:
        """How the sample was made (free text, as written in the SURFACE file)."""
        return self._field.description

    @property
    def cell_mm(self) -> float:
        return self._field.cell_size_mm

    @property
    def shape(self) -> Tuple[int, int]:
        """(ny, nx) nodes (= cells: periodic)."""
        return (self._field.ny, self._field.nx)

    @property
    def size_mm(self) -> Tuple[float, float]:
        """Period (x, y) [mm]."""
        return (self._field.nx * self.cell_mm, self._field.ny * self.cell_mm)

    @property
    def heights(self) -> np.ndarray:
        if self._heights is None:
            self._heights = np.asarray(self._field.heights)
            self._heights.flags.writeable = False
        return self._heights

    @property
    def material_map(self) -> np.ndarray:
        if self._material_map is None:
            self._material_map = np.asarray(self._field.material)
            self._material_map.flags.writeable = False
        return self._material_map

    @property
    def material_specs(self) -> list:
        return list(self._field.materials)

    @property
    def materials(self) -> list:
        return [m["name"] for m in self._field.materials]

    @property
    def statistics(self) -> dict:
        if self._statistics is None:
            self._statistics = dict(self._field.statistics())
        return dict(self._statistics)

    @property
    def mpd_mm(self) -> float:
        """Mean profile depth [mm]."""
        return self.statistics["mpd_mm"]

    @property
    def etd_mm(self) -> float:
        """Estimated texture depth 0.2 + 0.8 MPD [mm]."""
        return self.statistics["etd_mm"]

    @property
    def rms_height_mm(self) -> float:
        return self.statistics["rms_height_mm"]

    @property
    def area_ratio(self) -> float:
        """True / projected area."""
        return self.statistics["surface_area_ratio"]

    @property
    def exposed_area_fraction(self) -> np.ndarray:
        """Projected area fraction of each material (aligned with ``materials``)."""
        return np.asarray(self.statistics["exposed_area_fraction"])

    def write(self, path: PathLike, preview: Optional[PathLike] = None) -> None:
        """Write the SURFACE file (JSON, atomically), with the statistics; fit paths are written relative
        to its folder. ``preview``: also a PNG of the height map coloured by material."""
        self._field.write(str(path))
        if preview is not None:
            self._field.write_preview(str(preview))

    def render(self, theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike, phi_r: ArrayLike,
               **options: Any) -> Dataset:
        """Same as :func:`render` (``render(self, ...)``)."""
        return render(self, theta_i, phi_i, theta_r, phi_r, **options)

    def render_albedo(self, sun_zenith: Union[float, Sequence[float], str], **options: Any) -> dict:
        """Same as :func:`render_albedo` (``render_albedo(self, ...)``)."""
        return render_albedo(self, sun_zenith, **options)

    def __repr__(self) -> str:
        ny, nx = self.shape
        return f"roadbrdf.Surface({self.name!r}: {nx} x {ny} cells of {self.cell_mm:g} mm, materials {self.materials})"


def surface(formulation_path: PathLike, size_mm: float = 60.0, cell_mm: float = 0.1, seed: int = 1,
            matrix_level: Optional[float] = None, target_mpd: Optional[float] = None,
            output: Optional[PathLike] = None, mastic_fraction: Optional[float] = None,
            preview: Optional[PathLike] = None) -> Surface:
    """A virtual sample of a formulation, as ``roadbrdf surface FORMULATION`` builds it: coarse aggregate
    classes as packed ellipsoidal grains in a mastic (docs/surface.md "Virtual sample").

    ``size_mm``: side of the periodic sample [mm]; ``cell_mm``: grid spacing [mm]; ``matrix_level``: mastic
    level as a fraction of the slab thickness (default 0.7), or ``target_mpd`` [mm], or ``mastic_fraction`` (the
    exposed, projected area fraction of the mastic, in (0, 1), met within max(0.001, 1/cells); an unreachable
    value raises ValueError naming the reachable range) to choose it (the three exclude each other).
    Fit files are resolved relative to the formulation's folder (they are needed only to render).
    ``output``: also write the SURFACE file (and ``preview``, a PNG of the height map), as the command does;
    ``formulation_path`` may also be the formulation itself (a dict). Generator notes (e.g. jamming) are issued as UserWarning.
    """
    handle, report = _roadbrdf.surface(formulation_path, size_mm=size_mm, cell_mm=cell_mm, seed=seed,
                                       matrix_level=matrix_level, target_mpd=target_mpd,
                                       mastic_fraction=mastic_fraction, output=output, preview=preview)
    for note in report["notes"]:
        warn_at_caller(note)
    return Surface(handle, dict(report))


def read_surface(path: PathLike) -> Surface:
    """Read a SURFACE file (written by ``roadbrdf surface`` or :meth:`Surface.write`); fit files of its
    materials are resolved relative to the file's folder."""
    return Surface(_roadbrdf.read_surface(as_text(path, "path")))


def _material_fields(model_or_fit, params, fit_model):
    """The request fields of a validation surface's material: ``input`` (a model name or a fit file path),
    ``parameters``, ``options`` and ``fit``, from a :class:`Model`, a model name or a fit file."""
    fields = dict(parameters={str(k): as_float(v, f"params.{k}") for k, v in as_mapping(params, "params").items()},
                  fit=None if fit_model is None else as_text(fit_model, "fit_model"))
    if isinstance(model_or_fit, Model):
        options = {str(k): str(v) for k, v in model_or_fit.description.get("option_values", {}).items()}
        return dict(fields, input=model_or_fit.name, options=options)
    if not _is_path(model_or_fit):
        raise InputError("model_or_fit: expected a roadbrdf.Model, a model name or a fit file path")
    return dict(fields, input=os.fsdecode(model_or_fit))


def flat_surface(model_or_fit: Union[Model, str, PathLike], params: dict | None = None, cells: int = 16,
                 cell_mm: float = 0.1, fit_model: Optional[str] = None) -> Surface:
    """A flat sample z = 0 of one material (validation; ``roadbrdf surface MATERIAL --flat``).

    ``model_or_fit``: a :class:`Model` (with ``params``), a model name, or a fit file (``*.json``, its
    best fit or ``fit_model``). Its rendered BRDF is the material's BRDF averaged over the detector cone.
    """
    handle, _ = _roadbrdf.surface(flat=True, cells=cells, cell_mm=cell_mm,
                                  **_material_fields(model_or_fit, params, fit_model))
    return Surface(handle)


def gaussian_slope_surface(model_or_fit: Union[Model, str, PathLike], sigma_rad: float, params: dict | None = None,
                           cells: int = 128, cell_mm: float = 0.1, seed: int = 1,
                           fit_model: Optional[str] = None) -> Surface:
    """An isotropic random rough surface of one material with facet slope angle standard deviation
    ``sigma_rad`` [rad] (the Oren-Nayar roughness; ``roadbrdf surface MATERIAL --gaussian-slopes``)."""
    if sigma_rad is None:
        raise InputError("sigma_rad: expected a number, got NoneType")
    handle, _ = _roadbrdf.surface(sigma_rad=sigma_rad, cells=cells, cell_mm=cell_mm, seed=seed,
                                  **_material_fields(model_or_fit, params, fit_model))
    return Surface(handle)


def _as_surface(value):
    if isinstance(value, Surface):
        return value
    if _is_path(value):
        return read_surface(value)
    raise InputError("surface: expected a roadbrdf.Surface or a SURFACE file path")


def render(surface: Union[Surface, PathLike], theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike,
           phi_r: ArrayLike, **settings: Any) -> Dataset:
    """The virtual gonioreflectometer: path-trace a :class:`Surface` (or a SURFACE file path) at the
    given geometries, as ``roadbrdf render SURFACE --grid`` does (docs/surface.md "Estimator").

    Angles [deg] broadcast together (flattened to the dataset's geometries). The settings are keywords, one
    per field of the render request (listed below, the command line's options; ``None`` leaves a field at
    its default): ``wavelengths`` [nm], increasing (default: those of the materials' fits, or 550). Paths
    per geometry: ``samples`` (default 4096) or adaptive ``target_error`` (relative standard error, with
    ``max_samples`` and ``error_floor`` [sr^-1] for values near 0); not both. ``acceptance_deg``: detector
    cone half-angle [deg] (0 = ideal direction); ``sampling``: ``"brdf"`` or ``"cosine"``; ``max_bounces``:
    0 = unlimited. Results depend on ``seed`` only, not on ``threads``.

    Returns a :class:`Dataset` of the cone-averaged BRDF [sr^-1] with ``sigma`` = the Monte Carlo standard
    error; ``metadata`` describes the virtual instrument, plus ``dataset.paths`` (paths per geometry) and
    ``dataset.converged`` (adaptive runs: the target was reached). The GIL is released while rendering.
    """
    s = _as_surface(surface)
    arrays = np.broadcast_arrays(*(as_float_array(a, name) for a, name in
                                   ((theta_i, "theta_i"), (phi_i, "phi_i"), (theta_r, "theta_r"), (phi_r, "phi_r"))))
    flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
    r = _roadbrdf.render_surface(s._field, *flat, **_settings(settings))
    metadata = dict(r["metadata"])
    metadata.setdefault("units", "sr^-1")  # as the dataset readers set it
    d = Dataset(np.stack(flat, axis=-1), np.asarray(r["wavelengths"], dtype=float), np.asarray(r["brdf"], dtype=float),
                np.asarray(r["sigma"], dtype=float), metadata, "zenith")
    d.paths = np.asarray(r["paths"])
    d.converged = np.asarray(r["converged"], dtype=bool)
    return d


def render_albedo(surface: Union[Surface, PathLike], sun_zenith: Union[float, Sequence[float], str],
                  **settings: Any) -> dict:
    """Albedo of a virtual sample, as ``roadbrdf render SURFACE --albedo`` computes it: black-sky
    (directional-hemispherical reflectance) at the sun zenith angles [deg, 0 <= theta < 90] and white-sky by a
    ``white_sky_nodes``-point Gauss-Legendre rule in cos(theta) (0 = none). Same settings as :func:`render`
    (``acceptance_deg`` is not used: the detector covers the hemisphere).

    Returns a dict: ``wavelengths`` [nm], ``sun_zenith`` [deg], ``black_sky`` and ``black_sky_error``
    [angle, wavelength], ``white_sky`` and ``white_sky_error`` [wavelength] (None when white_sky_nodes = 0),
    dimensionless, errors = Monte Carlo standard errors; ``white_sky_nodes``, ``paths`` (total) and
    ``converged`` (per black-sky angle, then per white-sky node). ``output``: also write the albedo table
    (CSV) the command writes with ``-o``.
    """
    s = _as_surface(surface)
    name = os.fspath(surface) if _is_path(surface) else s.name
    zeniths = _roadbrdf.values(sun_zenith, "sun_zenith")
    r = _roadbrdf.render_surface_albedo(s._field, name, sun_zenith=zeniths, **_settings(settings))
    m = len(r["wavelengths"])
    out = {"wavelengths": np.asarray(r["wavelengths"], dtype=float),
           "sun_zenith": np.asarray(r["sun_zenith"], dtype=float),
           "black_sky": np.asarray(r["black_sky"], dtype=float).reshape(len(zeniths), m),
           "black_sky_error": np.asarray(r["black_sky_error"], dtype=float).reshape(len(zeniths), m),
           "white_sky": np.asarray(r["white_sky"], dtype=float) if r["white_sky_nodes"] > 0 else None,
           "white_sky_error": np.asarray(r["white_sky_error"], dtype=float) if r["white_sky_nodes"] > 0 else None,
           "white_sky_nodes": int(r["white_sky_nodes"]), "paths": int(r["paths"]),
           "converged": np.asarray(r["converged"], dtype=bool)}
    return out


def _settings(settings: dict) -> dict:
    """The render keywords given (None: the field's default)."""
    return {key: value for key, value in settings.items() if value is not None}


def _settings_doc(*own: str) -> str:
    """The render request's rows (the same as `roadbrdf render --help`) but for the command's files."""
    rows = [row for row in _roadbrdf.request_fields("render")
            if row["name"] not in ("surface", "grid", "sun_zenith", "format", "output") or row["name"] in own]
    return "\n    Settings (keywords):\n" + "".join(
        f"        {row['name']}{' [' + row['unit'] + ']' if row['unit'] else ''}: {row['help']}\n" for row in rows)


def _surface_doc() -> str:
    """The surface request's rows (the same as `roadbrdf surface --help`)."""
    return "\n    Fields (keywords; the material functions set input, flat, sigma_rad, parameters, options, fit):\n" + "".join(
        f"        {row['name']}{' [' + row['unit'] + ']' if row['unit'] else ''}: {row['help']}\n"
        for row in _roadbrdf.request_fields("surface"))


surface.__doc__ += _surface_doc()
render.__doc__ += _settings_doc()
render_albedo.__doc__ += _settings_doc("output")


# Spectroradiometer files and run manifests (instruments.py).
