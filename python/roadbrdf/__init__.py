"""roadbrdf: spectral BRDF models, fitting, mixing, albedo and road photometry for road materials.

Conventions (the same as the ``roadbrdf`` command-line program):

* angles in degrees; theta is the zenith angle from the surface normal, phi the azimuth; both the
  incident direction (towards the source) and the reflected direction (towards the viewer) point
  away from the surface; phi_r - phi_i = 180 deg is the forward (specular) side;
* BRDF in sr^-1, wavelengths in nm;
* model names, parameter names, units and bounds are those of ``roadbrdf models``.

Errors in the input raise :class:`InputError` (a :class:`ValueError`) with the same message as the
command line.
"""

from __future__ import annotations

import numpy as np

from . import _roadbrdf

__all__ = ["InputError", "Model", "SpectralModel", "Dataset", "RTable", "models", "model_names", "read_fit",
           "read_dataset", "write_dataset", "read_curet", "read_alta", "rtable", "read_rtable",
           "fit", "spectral_model_from_fit", "mix", "albedo", "road_to_zenith_azimuth", "data_directory", "Surface", "surface",
           "read_surface", "flat_surface", "gaussian_slope_surface", "render", "render_albedo",
           "InstrumentSpectrum", "read_instrument", "instrument_dataset", "read_manifest", "calibrate_manifest"]

InputError = _roadbrdf.InputError
__version__ = _roadbrdf.__version__


def data_directory() -> str:
    """Folder of the bundled data tables (``share/roadbrdf/data`` of the build or install tree;
    ``$ROADBRDF_DATA`` overrides it)."""
    return _roadbrdf.data_directory()


def model_names():
    """Names of the single (non-composite) models, e.g. ``['lambert', 'oren-nayar', ...]``.

    Composites are written with ``+``: ``Model('oren-nayar+torrance-sparrow')``.
    """
    return list(_roadbrdf.model_names())


def models():
    """Metadata of every model: a list of dicts with ``name``, ``summary``, ``citation``,
    ``reciprocal``, ``energy_conserving``, ``non_negative``, ``has_delta``, ``parameters``
    (each a dict with ``name``, ``unit``, ``description``, ``default``, ``lower``, ``upper``,
    ``spectral``, ``linear``) and ``options`` (``name``, ``values``, ``default``, ``description``).
    This is the same metadata as ``roadbrdf models --json``."""
    return [_roadbrdf.make_model(name, {}).description for name in _roadbrdf.model_names()]


def road_to_zenith_azimuth(gamma, alpha, beta, delta):
    """Convert road-photometry angles (gamma, alpha, beta, delta) [deg] to
    (theta_i, phi_i, theta_r, phi_r) [deg]: gamma = theta_i, alpha = 90 - theta_r,
    beta = 180 - (phi_r - phi_i), delta = phi_r - 180."""
    g, a, b, d = np.broadcast_arrays(*(np.asarray(x, dtype=float) for x in (gamma, alpha, beta, delta)))
    theta_i = g
    theta_r = 90.0 - a
    phi_r = d + 180.0
    phi_i = phi_r - (180.0 - b)
    return theta_i, phi_i, theta_r, phi_r


def _as_float_or_array(values, shape):
    out = np.asarray(values, dtype=float).reshape(shape)
    return float(out) if out.ndim == 0 else out


class Model:
    """A BRDF model with its options fixed; parameters are given at evaluation.

    >>> m = Model("oren-nayar")
    >>> m.evaluate(30, 0, 45, 180, albedo=0.5, sigma=0.3)   # sr^-1
    >>> m = Model("lambert+torrance-sparrow", options={"distribution": "beckmann"})
    >>> m.evaluate(theta_i, 0, theta_r, 180, params={"lambert.albedo": 0.2, "torrance-sparrow.roughness": 0.3})

    Options are the model's discrete choices (``roadbrdf models``); for composites, use
    ``"component.option"`` names or plain names applied to every component that has them.
    """

    def __init__(self, name: str, options: dict | None = None, **more_options):
        opts = {str(k): str(v) for k, v in (options or {}).items()}
        opts.update({k: str(v) for k, v in more_options.items()})
        self._model = _roadbrdf.make_model(name, opts)

    @property
    def name(self) -> str:
        """Model name as the command line spells it."""
        return self._model.name

    @property
    def description(self) -> dict:
        """Metadata (see :func:`models`), with the resolved ``option_values``."""
        return self._model.description

    @property
    def parameters(self) -> list:
        """Parameter metadata: list of dicts (name, unit, description, default, lower, upper, ...)."""
        return self._model.description["parameters"]

    @property
    def parameter_names(self) -> list:
        return list(self._model.parameter_names)

    def default_parameters(self) -> dict:
        """``{name: default}`` for every parameter."""
        return {p["name"]: p["default"] for p in self.parameters}

    def evaluate(self, theta_i, phi_i, theta_r, phi_r, params: dict | None = None, **kwargs):
        """BRDF [sr^-1] at the given angles [deg].

        Angles and parameter values broadcast together with numpy rules; parameters not given
        take their defaults. Parameters may be passed as keywords (``albedo=0.3``) or in
        ``params`` (needed for composite names such as ``"oren-nayar.albedo"``). Values outside a
        parameter's bounds, unknown names and zenith angles outside [0, 90] raise InputError.
        Returns a float for scalar input, else an array of the broadcast shape. The ideal
        specular (delta) part of a model, if any, is not included (see :meth:`delta_reflectance`).
        """
        given = dict(params or {})
        given.update(kwargs)
        names = self.parameter_names
        unknown = [k for k in given if k not in names]
        if unknown:
            raise InputError(
                f"model '{self.name}' has no parameter '{unknown[0]}' (parameters: {' '.join(names)})")
        values = []
        for p in self.parameters:
            v = np.asarray(given.get(p["name"], p["default"]), dtype=float)
            bad = ~np.isfinite(v) | (v < p["lower"]) | (v > p["upper"])
            if np.any(bad):
                first = float(np.atleast_1d(v)[np.argmax(np.atleast_1d(bad))])
                raise InputError(f"parameter '{p['name']}' of model '{self.name}' = {first:g} is outside its "
                                 f"bounds [{p['lower']:g}, {p['upper']:g}]")
            values.append(v)
        arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (theta_i, phi_i, theta_r, phi_r)), *values)
        shape = arrays[0].shape
        flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
        pmatrix = np.ascontiguousarray(np.stack(flat[4:], axis=-1)) if values else np.zeros((flat[0].size, 0))
        out = self._model.evaluate_flat(flat[0], flat[1], flat[2], flat[3], pmatrix.reshape(-1))
        return _as_float_or_array(out, shape)

    __call__ = evaluate

    def delta_reflectance(self, theta_i, params: dict | None = None, **kwargs) -> float:
        """Reflectance R(theta_i) of the ideal specular part f = R delta(w_r - mirror(w_i))/cos(theta_r)
        (0 for models without one). theta_i in degrees."""
        given = dict(params or {})
        given.update(kwargs)
        p = [float(given.get(q["name"], q["default"])) for q in self.parameters]
        return self._model.delta_reflectance(p, float(np.cos(np.radians(theta_i))))

    def __repr__(self):
        return f"roadbrdf.Model({self.name!r})"


class SpectralModel:
    """A model with wavelength-dependent parameters, e.g. read from a fit file (:func:`read_fit`).

    Parameters at a wavelength are interpolated linearly between the tabulated wavelengths;
    wavelengths outside the tabulated range raise InputError (no extrapolation).
    """

    def __init__(self, handle):
        self._spectral = handle

    @property
    def model(self) -> Model:
        m = Model.__new__(Model)
        m._model = self._spectral.model
        return m

    @property
    def wavelengths(self) -> np.ndarray:
        """Tabulated wavelengths [nm]."""
        return np.asarray(self._spectral.wavelengths)

    def parameters_at(self, wavelength: float) -> dict:
        """``{name: value}`` at one wavelength [nm]."""
        values = self._spectral.parameters_at(float(wavelength))
        return dict(zip(self.model.parameter_names, values))

    def evaluate(self, theta_i, phi_i, theta_r, phi_r, wavelength):
        """BRDF [sr^-1] at angles [deg] and wavelengths [nm], broadcast together."""
        arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (theta_i, phi_i, theta_r, phi_r,
                                                                            wavelength)))
        shape = arrays[0].shape
        flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
        return _as_float_or_array(self._spectral.evaluate_flat(*flat), shape)

    __call__ = evaluate


def read_fit(path: str, model: str | None = None) -> SpectralModel:
    """Read a fit file written by ``roadbrdf fit`` (or a MIX.json written by ``roadbrdf mix``) as a
    spectral model: the best-ranked fit, or the fit of ``model`` (its name as in the file, e.g.
    ``"oren-nayar+torrance-sparrow"``; for a MIX.json, the method, e.g. ``"shadowed"``)."""
    return SpectralModel(_roadbrdf.read_spectral_model_file(str(path), model or ""))


class Dataset:
    """A spectral BRDF dataset: N geometries x M wavelengths.

    Attributes
    ----------
    angles : ndarray (N, 4)
        theta_i, phi_i, theta_r, phi_r [deg] of each geometry.
    wavelengths : ndarray (M,)
        [nm], strictly increasing.
    brdf : ndarray (N, M)
        [sr^-1].
    sigma : ndarray (N, M) or None
        standard uncertainty [sr^-1].
    metadata : dict
        "sample", "instrument", "units" and free keys (the "# key: value" lines of a CSV file).
    convention : "zenith" or "road"
        angle columns used when the dataset is written.
    """

    def __init__(self, angles, wavelengths, brdf, sigma=None, metadata=None, convention="zenith"):
        self.angles = np.asarray(angles, dtype=float).reshape(-1, 4)
        self.wavelengths = np.asarray(wavelengths, dtype=float).reshape(-1)
        self.brdf = np.asarray(brdf, dtype=float).reshape(self.angles.shape[0], self.wavelengths.size)
        self.sigma = None if sigma is None else np.asarray(sigma, dtype=float).reshape(self.brdf.shape)
        self.metadata = dict(metadata or {})
        self.convention = convention

    @classmethod
    def _from_dict(cls, d):
        return cls(d["angles"], d["wavelengths"], d["brdf"], d["sigma"], d["metadata"], d["convention"])

    @property
    def theta_i(self):
        return self.angles[:, 0]

    @property
    def phi_i(self):
        return self.angles[:, 1]

    @property
    def theta_r(self):
        return self.angles[:, 2]

    @property
    def phi_r(self):
        return self.angles[:, 3]

    def __len__(self):
        return self.angles.shape[0]

    def __repr__(self):
        name = self.metadata.get("sample", "")
        return (f"roadbrdf.Dataset({name!r}: {len(self)} geometries x {self.wavelengths.size} wavelengths "
                f"{self.wavelengths[0]:g}-{self.wavelengths[-1]:g} nm)") if self.wavelengths.size else "roadbrdf.Dataset()"

    def write(self, path, format="wide"):
        """Write as wide (default) or long CSV, atomically (see :func:`write_dataset`)."""
        write_dataset(self, path, format)


def read_dataset(path, average_duplicates=False, allow_missing=False, delimiter="auto", decimal="auto") -> Dataset:
    """Read a wide or long CSV dataset (the format is detected from the header).

    Duplicate geometries are an error unless ``average_duplicates``; missing values (empty, nan,
    NA) are an error unless ``allow_missing`` (then kept as NaN). Negative values are kept and
    reported with a :class:`UserWarning`. Malformed files raise InputError naming file:line:column.
    ``delimiter`` ("auto", ",", ";", "tab") and ``decimal`` ("auto", ".", ",") are the command line's
    ``--delimiter`` / ``--decimal``: by default the dialect is detected (docs/data.md).
    """
    return Dataset._from_dict(_roadbrdf.read_dataset(str(path), average_duplicates, allow_missing, str(delimiter),
                                                     str(decimal)))


def write_dataset(dataset: Dataset, path, format="wide"):
    """Write a dataset as ``"wide"`` or ``"long"`` CSV, atomically (temporary file, then rename)."""
    _roadbrdf.write_dataset(np.ascontiguousarray(dataset.angles), np.ascontiguousarray(dataset.wavelengths),
                            np.ascontiguousarray(dataset.brdf),
                            None if dataset.sigma is None else np.ascontiguousarray(dataset.sigma),
                            {str(k): str(v) for k, v in dataset.metadata.items()}, dataset.convention,
                            str(path), format)


def read_curet(abrdf_path, table_path, sample: int) -> Dataset:
    """One sample of the CUReT BRDF database (``abrdf.dat`` + ``table.txt``), grey, stored at a
    nominal wavelength recorded in the metadata."""
    return Dataset._from_dict(_roadbrdf.read_curet(str(abrdf_path), str(table_path), int(sample)))


def read_alta(path, wavelength, assumed_output="", exclude_grazing=False) -> Dataset:
    """An ALTA text-format BRDF file (BRDF x cos theta_v output is divided by cos theta_v).
    ``wavelength`` [nm] is required (ALTA files carry none)."""
    return Dataset._from_dict(_roadbrdf.read_alta(str(path), float(wavelength), assumed_output, exclude_grazing))


class RTable(dict):
    """A road r-table: a dict with ``r`` (29 x 20 array of reduced luminance coefficients in sr^-1,
    NaN where the table is not defined; rows tan(gamma), columns beta), ``tan_gamma``,
    ``beta_deg``, ``alpha_deg``, ``name``, and the summary figures ``Q0``, ``S1``, ``S2``, ``Qd`` [sr^-1
    except S1, S2], ``class`` (R system) and ``classes`` (R, N, C). Files store 1e4 r."""

    def write(self, path, format="csv"):
        """Write as ``"csv"``, ``"rtb"`` (DIALux) or ``"radiance"``, atomically."""
        _roadbrdf.write_rtable(np.ascontiguousarray(self["r"]), self["name"], self["alpha_deg"], str(path), format)


def rtable(model, params: dict | None = None, alpha=1.0, illuminant="A", wavelength=None, band=None) -> RTable:
    """Standard r-table (29 tan(gamma) x 20 beta) of a model or a spectral model at observation angle
    ``alpha`` [deg] (CIE: 1).

    ``model`` is a :class:`Model` (with ``params``), a :class:`SpectralModel` (e.g. :func:`read_fit`),
    or a fit file path. A spectral model is reduced to one BRDF per geometry photometrically
    (V(lambda) x ``illuminant`` "A", "D65" or a lamp CSV file), or at one ``wavelength`` [nm], or
    averaged over ``band`` = (lo, hi) [nm]. A single-band fit is used at its band; ``note`` (else None)
    says so.
    """
    if isinstance(model, (str, bytes)) or hasattr(model, "__fspath__"):
        model = read_fit(model)
    if isinstance(model, SpectralModel):
        if params:
            raise InputError("params cannot be combined with a spectral model")
        return RTable(_roadbrdf.rtable_from_spectral(model._spectral, float(alpha), illuminant, wavelength,
                                                     None if band is None else (float(band[0]), float(band[1]))))
    given = dict(params or {})
    names = model.parameter_names
    unknown = [k for k in given if k not in names]
    if unknown:
        raise InputError(f"model '{model.name}' has no parameter '{unknown[0]}' (parameters: {' '.join(names)})")
    values = [float(given.get(p["name"], p["default"])) for p in model.parameters]
    return RTable(_roadbrdf.rtable_from_model(model._model, values, float(alpha)))


def read_rtable(path, format=None, alpha=1.0, scale=1e4) -> RTable:
    """Read an r-table file (csv, rtb or radiance; format from the extension unless given).
    Zero cells are read as missing (NaN), never as zero reflectance."""
    return RTable(_roadbrdf.read_rtable(str(path), format, float(alpha), float(scale)))


def fit(data, models, options: dict | None = None, shared=(), fix: dict | None = None, start: dict | None = None,
        loss="plain", robust="none", use_sigma=True, solid_angle_weights=False, multistart=1, seed=1,
        wavelengths="", threads=1, output=None) -> dict:
    """Fit one or more models to a dataset, exactly as ``roadbrdf fit`` does.

    Parameters
    ----------
    data : Dataset or path
        The measured spectral BRDF.
    models : str or list of str
        Model names, e.g. ``["oren-nayar", "oren-nayar+torrance-sparrow"]``.
    options : dict
        Model options, applied to every model that declares them (e.g. ``{"distribution": "beckmann"}``).
    shared : list of str, or "auto"
        Joint spectral mode: parameters shared by all wavelengths (Schur-complement solve).
    fix, start : dict
        Parameters held at a value / starting values, ``{name: value}``.
    loss : "plain" | "relative" | "log" | "cosine"
    robust : "none" | "huber:SCALE" | "cauchy:SCALE"
    use_sigma : bool
        Weights 1/sigma^2 when the data have uncertainties.
    multistart : int
        Starting points (Latin hypercube over the nonlinear parameters, seeded by ``seed``).
    wavelengths : str
        Subset, ``"400:1000:10"`` or a comma list [nm].
    output : path, optional
        Also write the fit file (JSON).

    Returns
    -------
    dict
        The fit file's content: ``best`` and ``fits`` (per model: ``model``, ``options``, ``wavelengths``,
        ``parameters`` {name: list per wavelength}, ``stderr``, ``rmse``, ``rmse_total``, AIC/BIC, ...).
        Use :func:`spectral_model_from_fit` (or :func:`read_fit` on ``output``) to evaluate it.
    """
    import json
    d = data if isinstance(data, Dataset) else read_dataset(data)
    if isinstance(models, str):
        models = [models]
    if isinstance(shared, str):
        shared = [s for s in shared.split(",") if s]
    text = _roadbrdf.fit(np.ascontiguousarray(d.angles), np.ascontiguousarray(d.wavelengths),
                         np.ascontiguousarray(d.brdf), None if d.sigma is None else np.ascontiguousarray(d.sigma),
                         {str(k): str(v) for k, v in d.metadata.items()}, d.convention, list(models),
                         {str(k): str(v) for k, v in (options or {}).items()}, list(shared),
                         {k: float(v) for k, v in (fix or {}).items()}, {k: float(v) for k, v in (start or {}).items()},
                         loss, robust, bool(use_sigma), bool(solid_angle_weights), int(multistart), int(seed),
                         str(wavelengths), int(threads), "" if output is None else str(output))
    return json.loads(text)


def spectral_model_from_fit(fit_result: dict, model: str | None = None) -> SpectralModel:
    """The spectral model of a fit result returned by :func:`fit` (the best fit, or ``model``)."""
    import json
    import os
    import tempfile
    fd, path = tempfile.mkstemp(suffix=".json")
    try:
        with os.fdopen(fd, "w") as fh:
            json.dump(fit_result, fh)
        return read_fit(path, model)
    finally:
        os.remove(path)


def mix(formulation, data=None, method="all", folds=5, seed=1, per_wavelength=False, sum_to_one=False,
        binder_coverage=None, mastic_fraction=None, reference=None, output=None, use_sigma=True,
        residuals=None) -> dict:
    """Predict the BRDF of a road formulation from its components' fits, as ``roadbrdf mix`` does.

    ``formulation``: a formulation JSON file (see docs/mixing.md); ``data``: the measured mixture
    (CSV path) to compare the methods on held-out geometries (``folds``-fold); ``method``: areal,
    fitted, mastic, hapke, shadowed or all; ``reference``: the fit file of the measured mixture (for
    the albedo difference); ``use_sigma``: weight the fitted methods by 1/sigma^2 when the data have
    sigma (False = ``--no-sigma``); ``residuals``: CSV path for the held-out residuals (``--residuals``,
    needs ``data``). Returns the MIX.json content (per method: weights, parameters, and the
    comparison when ``data`` is given); ``read_fit(output, method)`` evaluates a method's mixture.
    """
    import json
    text = _roadbrdf.mix(str(formulation), "" if data is None else str(data), method, int(folds), int(seed),
                         bool(per_wavelength), bool(sum_to_one), binder_coverage, mastic_fraction,
                         "" if reference is None else str(reference), "" if output is None else str(output),
                         bool(use_sigma), "" if residuals is None else str(residuals))
    return json.loads(text)


def albedo(model, params: dict | None = None, sun_zenith=30.0, sun_azimuth=None, azimuth_mean=False,
           diffuse_fraction=None, atmosphere=None, spectrum=None, wavelengths=None, illuminant=None,
           tolerance=1e-5) -> dict:
    """Black-sky, white-sky and blue-sky albedo, as ``roadbrdf albedo --json`` computes them.

    ``model``: a :class:`Model` (with ``params``), a :class:`SpectralModel`, or a fit / MIX.json file.
    ``sun_zenith`` [deg]: a number or a list; ``diffuse_fraction``: a number in [0, 1] or a CSV file
    (wavelength_nm, diffuse_fraction); ``atmosphere``: e.g. ``"spectrl2:aod=0.2"`` (SPECTRL2 clear sky);
    ``spectrum``: broadband weighting ``"astm-g173-global"`` (default), ``"astm-g173-direct"`` or a CSV
    file; ``illuminant``: also the luminous albedo under "A", "D65" or a lamp file.

    Returns a dict: ``wavelengths`` [nm], ``sun_zenith_deg``, ``black_sky`` [zenith][wavelength],
    ``white_sky`` [wavelength], ``blue_sky``, ``diffuse_fraction``, their ``*_error`` estimates,
    ``broadband`` (solar-weighted values), ``luminous``, ``units`` and ``notes``.
    """
    import json
    zeniths = [float(z) for z in np.atleast_1d(sun_zenith)]
    common = (zeniths, None if sun_azimuth is None else float(sun_azimuth), bool(azimuth_mean),
              "" if diffuse_fraction is None else str(diffuse_fraction), atmosphere or "", spectrum or "",
              [] if wavelengths is None else [float(w) for w in np.atleast_1d(wavelengths)], illuminant or "",
              float(tolerance))
    if isinstance(model, (str, bytes)) or hasattr(model, "__fspath__"):
        model = read_fit(model)
    if isinstance(model, SpectralModel):
        if params:
            raise InputError("params cannot be combined with a spectral model")
        return json.loads(_roadbrdf.albedo_spectral(model._spectral, *common))
    given = dict(params or {})
    names = model.parameter_names
    unknown = [k for k in given if k not in names]
    if unknown:
        raise InputError(f"model '{model.name}' has no parameter '{unknown[0]}' (parameters: {' '.join(names)})")
    values = [float(given.get(p["name"], p["default"])) for p in model.parameters]
    return json.loads(_roadbrdf.albedo_model(model._model, values, *common))


# ---- virtual road surfaces and the virtual gonioreflectometer (docs/surface.md) ----------------

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

    def __init__(self, handle, generation=None):
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
    def shape(self):
        """(ny, nx) nodes (= cells: periodic)."""
        return (self._field.ny, self._field.nx)

    @property
    def size_mm(self):
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

    def write(self, path, preview=None):
        """Write the SURFACE file (JSON, atomically), with the statistics; fit paths are written relative
        to its folder. ``preview``: also a PNG of the height map coloured by material."""
        self._field.write(str(path))
        if preview is not None:
            self._field.write_preview(str(preview))

    def render(self, theta_i, phi_i, theta_r, phi_r, **options):
        """Same as :func:`render` (``render(self, ...)``)."""
        return render(self, theta_i, phi_i, theta_r, phi_r, **options)

    def render_albedo(self, sun_zenith, **options):
        """Same as :func:`render_albedo` (``render_albedo(self, ...)``)."""
        return render_albedo(self, sun_zenith, **options)

    def __repr__(self):
        ny, nx = self.shape
        return f"roadbrdf.Surface({self.name!r}: {nx} x {ny} cells of {self.cell_mm:g} mm, materials {self.materials})"


def surface(formulation_path, size_mm=60.0, cell_mm=0.1, seed=1, matrix_level=None, target_mpd=None,
            output=None, mastic_fraction=None) -> Surface:
    """A virtual sample of a formulation, as ``roadbrdf surface FORMULATION`` builds it: coarse aggregate
    classes as packed ellipsoidal grains in a mastic (docs/surface.md "Virtual sample").

    ``size_mm``: side of the periodic sample [mm]; ``cell_mm``: grid spacing [mm]; ``matrix_level``: mastic
    level as a fraction of the slab thickness (default 0.7), or ``target_mpd`` [mm], or ``mastic_fraction`` (the
    exposed, projected area fraction of the mastic, in (0, 1), met within max(0.001, 1/cells); an unreachable
    value raises ValueError naming the reachable range) to choose it (the three exclude each other).
    Fit files are resolved relative to the formulation's folder (they are needed only to render).
    ``output``: also write the SURFACE file. Generator notes (e.g. jamming) are issued as UserWarning.
    """
    import warnings
    handle, report = _roadbrdf.surface_from_formulation(
        str(formulation_path), float(size_mm), float(cell_mm), int(seed),
        None if matrix_level is None else float(matrix_level), None if target_mpd is None else float(target_mpd),
        None if mastic_fraction is None else float(mastic_fraction))
    for note in report["notes"]:
        warnings.warn(note, UserWarning, stacklevel=2)
    s = Surface(handle, dict(report))
    if output is not None:
        s.write(output)
    return s


def read_surface(path) -> Surface:
    """Read a SURFACE file (written by ``roadbrdf surface`` or :meth:`Surface.write`); fit files of its
    materials are resolved relative to the file's folder."""
    return Surface(_roadbrdf.read_surface(str(path)))


def _material_arguments(model_or_fit, params, fit_model):
    """(fit, fit_model, model, parameters, options) for the binding: a fit file path, a :class:`Model`
    or a model name."""
    if isinstance(model_or_fit, Model):
        options = {str(k): str(v) for k, v in model_or_fit.description.get("option_values", {}).items()}
        return "", "", model_or_fit.name, {str(k): float(v) for k, v in (params or {}).items()}, options
    if not _is_path(model_or_fit):
        raise InputError("expected a roadbrdf.Model, a model name or a fit file path")
    text = str(model_or_fit)
    if text.endswith(".json"):
        if params:
            raise InputError("params cannot be combined with a fit file")
        return text, fit_model or "", "", {}, {}
    return "", "", text, {str(k): float(v) for k, v in (params or {}).items()}, {}


def flat_surface(model_or_fit, params: dict | None = None, cells=16, cell_mm=0.1, fit_model=None) -> Surface:
    """A flat sample z = 0 of one material (validation; ``roadbrdf surface MATERIAL --flat``).

    ``model_or_fit``: a :class:`Model` (with ``params``), a model name, or a fit file (``*.json``, its
    best fit or ``fit_model``). Its rendered BRDF is the material's BRDF averaged over the detector cone.
    """
    return Surface(_roadbrdf.flat_surface(*_material_arguments(model_or_fit, params, fit_model), int(cells),
                                          float(cell_mm)))


def gaussian_slope_surface(model_or_fit, sigma_rad, params: dict | None = None, cells=128, cell_mm=0.1, seed=1,
                           fit_model=None) -> Surface:
    """An isotropic random rough surface of one material with facet slope angle standard deviation
    ``sigma_rad`` [rad] (the Oren-Nayar roughness; ``roadbrdf surface MATERIAL --gaussian-slopes``)."""
    return Surface(_roadbrdf.gaussian_slope_surface(*_material_arguments(model_or_fit, params, fit_model),
                                                    float(sigma_rad), int(cells), float(cell_mm), int(seed)))


def _as_surface(value):
    if isinstance(value, Surface):
        return value
    if _is_path(value):
        return read_surface(value)
    raise InputError("expected a roadbrdf.Surface or a SURFACE file path")


def _render_options(samples, target_error, max_samples, error_floor, acceptance_deg, sampling, seed, threads,
                    max_bounces):
    return (None if samples is None else int(samples), None if target_error is None else float(target_error),
            int(max_samples), float(error_floor), float(acceptance_deg), str(sampling), int(seed), int(threads),
            int(max_bounces))


def _wavelength_list(wavelengths):
    return [] if wavelengths is None else [float(w) for w in np.atleast_1d(wavelengths)]


def render(surface, theta_i, phi_i, theta_r, phi_r, wavelengths=None, samples=None, target_error=None,
           max_samples=1 << 20, acceptance_deg=1.0, sampling="brdf", seed=1, threads=0, max_bounces=0,
           error_floor=1e-5) -> Dataset:
    """The virtual gonioreflectometer: path-trace a :class:`Surface` (or a SURFACE file path) at the
    given geometries, as ``roadbrdf render SURFACE --grid`` does (docs/surface.md "Estimator").

    Angles [deg] broadcast together (flattened to the dataset's geometries). ``wavelengths`` [nm],
    increasing (default: those of the materials' fits, or 550). Paths per geometry: ``samples`` (default
    4096) or adaptive ``target_error`` (relative standard error, with ``max_samples`` and ``error_floor``
    [sr^-1] for values near 0); not both. ``acceptance_deg``: detector cone half-angle [deg] (0 = ideal
    direction); ``sampling``: ``"brdf"`` or ``"cosine"``; ``max_bounces``: 0 = unlimited. Results depend
    on ``seed`` only, not on ``threads``.

    Returns a :class:`Dataset` of the cone-averaged BRDF [sr^-1] with ``sigma`` = the Monte Carlo standard
    error; ``metadata`` describes the virtual instrument, plus ``dataset.paths`` (paths per geometry) and
    ``dataset.converged`` (adaptive runs: the target was reached). The GIL is released while rendering.
    """
    s = _as_surface(surface)
    arrays = np.broadcast_arrays(*(np.asarray(a, dtype=float) for a in (theta_i, phi_i, theta_r, phi_r)))
    flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
    r = _roadbrdf.render_surface(s._field, *flat, _wavelength_list(wavelengths),
                                 *_render_options(samples, target_error, max_samples, error_floor, acceptance_deg,
                                                  sampling, seed, threads, max_bounces))
    metadata = dict(r["metadata"])
    metadata.setdefault("units", "sr^-1")  # as the dataset readers set it
    d = Dataset(np.stack(flat, axis=-1), r["wavelengths"], r["brdf"], r["sigma"], metadata, "zenith")
    d.paths = np.asarray(r["paths"])
    d.converged = np.asarray(r["converged"], dtype=bool)
    return d


def render_albedo(surface, sun_zenith, wavelengths=None, white_sky_nodes=8, samples=None, target_error=None,
                  max_samples=1 << 20, acceptance_deg=1.0, sampling="brdf", seed=1, threads=0, max_bounces=0,
                  error_floor=1e-5) -> dict:
    """Albedo of a virtual sample, as ``roadbrdf render SURFACE --albedo`` computes it: black-sky
    (directional-hemispherical reflectance) at the sun zenith angles [deg, 0 <= theta < 90] and white-sky by a
    ``white_sky_nodes``-point Gauss-Legendre rule in cos(theta) (0 = none). Same sampling options as
    :func:`render` (``acceptance_deg`` is not used: the detector covers the hemisphere).

    Returns a dict: ``wavelengths`` [nm], ``sun_zenith`` [deg], ``black_sky`` and ``black_sky_error``
    [angle, wavelength], ``white_sky`` and ``white_sky_error`` [wavelength] (None when white_sky_nodes = 0),
    dimensionless, errors = Monte Carlo standard errors; ``white_sky_nodes``, ``paths`` (total) and
    ``converged`` (per black-sky angle, then per white-sky node).
    """
    s = _as_surface(surface)
    zeniths = [float(z) for z in np.atleast_1d(sun_zenith)]
    r = _roadbrdf.render_surface_albedo(s._field, zeniths, _wavelength_list(wavelengths), int(white_sky_nodes),
                                        *_render_options(samples, target_error, max_samples, error_floor,
                                                         acceptance_deg, sampling, seed, threads, max_bounces))
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


# Spectroradiometer files and run manifests (instruments.py).
from .instruments import (InstrumentSpectrum, read_instrument, instrument_dataset, read_manifest,  # noqa: E402
                          calibrate_manifest)

# Design studies (studies/, docs/studies.md): roadbrdf.study(...) = `roadbrdf study`.
from .studies import study  # noqa: E402
