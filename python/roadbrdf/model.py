"""BRDF models and spectral models (``src/roadbrdf/models``). The module is ``model`` because
``roadbrdf.models()`` is the function listing every model."""

from __future__ import annotations

import numpy as np

from . import _roadbrdf
from typing import Any, List

from .core import ArrayLike, InputError, as_float, as_float_array, as_mapping, as_options

__all__ = ["Model", "SpectralModel", "models", "model_names", "model_aliases"]


def model_names() -> List[str]:
    """Names of the single (non-composite) models, e.g. ``['lambert', 'oren-nayar', ...]``.

    Composites are written with ``+``: ``Model('oren-nayar+torrance-sparrow')``.
    """
    return list(_roadbrdf.model_names())


def model_aliases() -> List[dict]:
    """Other names of models with some options fixed, e.g. ``cook-torrance`` (torrance-sparrow with
    profile=v-cavity, distribution=beckmann, fresnel=exact-dielectric). Each a dict with ``name``,
    ``model``, ``description``, ``citation`` and ``options`` (the fixed ones). An alias is accepted
    wherever a model name is, composites included, as by ``roadbrdf models`` on the command line."""
    return list(_roadbrdf.model_aliases())


def models() -> List[dict]:
    """Metadata of every model: a list of dicts with ``name``, ``summary``, ``citation``,
    ``reciprocal``, ``energy_conserving``, ``non_negative``, ``has_delta``, ``mirror_lobe`` (whether the BRDF
    may have a lobe about the mirror direction that the albedo quadrature cross-checks at grazing sun),
    ``isotropic``,
    ``isotropic_when_equal`` (pairs of parameter names), ``grazing_zero`` (where the value at exactly
    90 deg is 0 because the BRDF diverges there; "" when it is the limit everywhere), ``reduces_to``
    (pairs [simpler model, parameter values]), ``parameters``
    (each a dict with ``name``, ``unit``, ``description``, ``default``, ``lower``, ``upper``,
    ``spectral``, ``linear``) and ``options`` (``name``, ``values``, ``default``, ``description``).
    This is the same metadata as ``roadbrdf models --json``."""
    return [_roadbrdf.make_model(name, {}).description for name in _roadbrdf.model_names()]



def _angle_arrays(theta_i, phi_i, theta_r, phi_r):
    return [as_float_array(a, name) for a, name in
            ((theta_i, "theta_i"), (phi_i, "phi_i"), (theta_r, "theta_r"), (phi_r, "phi_r"))]


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

    def __init__(self, name: str, options: dict | None = None, **more_options: Any) -> None:
        opts = as_options(options, "options")
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

    def _check_names(self, given: dict) -> None:
        names = self.parameter_names
        unknown = [k for k in given if k not in names]
        if unknown:
            raise InputError(f"model '{self.name}' has no parameter '{unknown[0]}' (parameters: {' '.join(names)})")

    def parameter_values(self, params: dict | None = None) -> list:
        """One parameter set in the model's order: ``params`` ({name: value}) with the defaults for the
        rest. Unknown names raise InputError; the library checks the values against the bounds."""
        given = as_mapping(params, "params")
        self._check_names(given)
        return [as_float(given.get(p["name"], p["default"]), f"params.{p['name']}") for p in self.parameters]

    def evaluate(self, theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike, phi_r: ArrayLike,
                 params: dict | None = None, **kwargs: ArrayLike) -> float | np.ndarray:
        """BRDF [sr^-1] at the given angles [deg].

        Angles and parameter values broadcast together with numpy rules; parameters not given
        take their defaults. Parameters may be passed as keywords (``albedo=0.3``) or in
        ``params`` (needed for composite names such as ``"oren-nayar.albedo"``). Values outside a
        parameter's bounds, unknown names and zenith angles outside [0, 90] raise InputError.
        Returns a float for scalar input, else an array of the broadcast shape. The ideal
        specular (delta) part of a model, if any, is not included (see :meth:`delta_reflectance`).
        """
        given = as_mapping(params, "params")
        given.update(kwargs)
        self._check_names(given)
        values = []
        for p in self.parameters:
            v = as_float_array(given.get(p["name"], p["default"]), p["name"])
            lower, upper = p.get("physical_bounds", (p["lower"], p["upper"]))  # as check_parameters
            bad = ~np.isfinite(v) | (v < lower) | (v > upper)
            if np.any(bad):
                first = float(np.atleast_1d(v)[np.argmax(np.atleast_1d(bad))])
                raise InputError(f"parameter '{p['name']}' of model '{self.name}' = {first:g} is outside its "
                                 f"bounds [{lower:g}, {upper:g}]")
            values.append(v)
        arrays = np.broadcast_arrays(*_angle_arrays(theta_i, phi_i, theta_r, phi_r), *values)
        shape = arrays[0].shape
        flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
        pmatrix = np.ascontiguousarray(np.stack(flat[4:], axis=-1)) if values else np.zeros((flat[0].size, 0))
        out = self._model.evaluate_flat(flat[0], flat[1], flat[2], flat[3], pmatrix.reshape(-1))
        return _as_float_or_array(out, shape)

    __call__ = evaluate

    def delta_reflectance(self, theta_i: float, params: dict | None = None, **kwargs: float) -> float:
        """Reflectance R(theta_i) of the ideal specular part f = R delta(w_r - mirror(w_i))/cos(theta_r)
        (0 for models without one). theta_i in degrees."""
        given = as_mapping(params, "params")
        given.update(kwargs)
        p = [as_float(given.get(q["name"], q["default"]), f"params.{q['name']}") for q in self.parameters]
        return self._model.delta_reflectance(p, float(np.cos(np.radians(as_float(theta_i, "theta_i")))))

    def __repr__(self):
        return f"roadbrdf.Model({self.name!r})"


class SpectralModel:
    """A model with wavelength-dependent parameters, e.g. read from a fit file (:func:`read_fit`).

    Parameters at a wavelength are interpolated linearly between the tabulated wavelengths;
    wavelengths outside the tabulated range raise InputError (no extrapolation).
    """

    def __init__(self, handle: Any) -> None:
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
        values = self._spectral.parameters_at(as_float(wavelength, "wavelength"))
        return dict(zip(self.model.parameter_names, values))

    def evaluate(self, theta_i: ArrayLike, phi_i: ArrayLike, theta_r: ArrayLike, phi_r: ArrayLike,
                 wavelength: ArrayLike) -> float | np.ndarray:
        """BRDF [sr^-1] at angles [deg] and wavelengths [nm], broadcast together."""
        arrays = np.broadcast_arrays(*_angle_arrays(theta_i, phi_i, theta_r, phi_r),
                                     as_float_array(wavelength, "wavelength"))
        shape = arrays[0].shape
        flat = [np.ascontiguousarray(a.reshape(-1)) for a in arrays]
        return _as_float_or_array(self._spectral.evaluate_flat(*flat), shape)

    __call__ = evaluate


def model_argument(value, name: str):
    """A model argument: a :class:`Model` or :class:`SpectralModel` as it is, a fit or MIX.json file (a path) read
    as a SpectralModel; anything else is a TypeError naming ``name``."""
    if isinstance(value, (Model, SpectralModel)):
        return value
    if isinstance(value, str) or hasattr(value, "__fspath__"):
        from .fitting import read_fit
        return read_fit(value)
    raise TypeError(f"{name}: expected a Model, a SpectralModel or a fit file, got {type(value).__name__}")
