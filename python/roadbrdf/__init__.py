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
           "fit", "spectral_model_from_fit", "mix", "albedo", "road_to_zenith_azimuth"]

InputError = _roadbrdf.InputError


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


def read_dataset(path, average_duplicates=False, allow_missing=False) -> Dataset:
    """Read a wide or long CSV dataset (the format is detected from the header).

    Duplicate geometries are an error unless ``average_duplicates``; missing values (empty, nan,
    NA) are an error unless ``allow_missing`` (then kept as NaN). Negative values are kept and
    reported with a :class:`UserWarning`. Malformed files raise InputError naming file:line:column.
    """
    return Dataset._from_dict(_roadbrdf.read_dataset(str(path), average_duplicates, allow_missing))


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
    averaged over ``band`` = (lo, hi) [nm].
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
