"""roadbrdf: spectral BRDF models, fitting, mixing, albedo and road photometry for road materials.

Conventions (the same as the ``roadbrdf`` command-line program):

* angles in degrees; theta is the zenith angle from the surface normal, phi the azimuth; both the
  incident direction (towards the source) and the reflected direction (towards the viewer) point
  away from the surface; phi_r - phi_i = 180 deg is the forward (specular) side;
* BRDF in sr^-1, wavelengths in nm;
* model names, parameter names, units and bounds are those of ``roadbrdf models``.

Errors in the input raise :class:`InputError` (a :class:`ValueError`) with the same message as the
command line (naming the Python argument where the command line names its flag).

The package mirrors the library's folders: ``roadbrdf.core``, ``roadbrdf.model`` (models/),
``roadbrdf.io``, ``roadbrdf.fitting``, ``roadbrdf.photometry``, ``roadbrdf.mixing``,
``roadbrdf.albedos`` (albedo/), ``roadbrdf.surfaces`` (surface/) and ``roadbrdf.lightings`` (lighting/), plus
``roadbrdf.instruments`` and ``roadbrdf.plot``; four module names differ from their folder by a letter so that they do not hide
the functions ``roadbrdf.models()``, ``roadbrdf.albedo()``, ``roadbrdf.surface()`` and ``roadbrdf.lighting()``. Everything
public is also available from ``roadbrdf`` itself.
"""

from __future__ import annotations

from . import _roadbrdf
from .core import InputError, data_directory, road_to_zenith_azimuth
from .result import Diagnostic, Result, RoadbrdfWarning
from .model import Model, SpectralModel, model_aliases, model_names, models
from .io import Dataset, check, read_alta, read_curet, read_dataset, write_dataset
from .io import resample
from .io import evaluate, simulate
from .fitting import FitResult, ModelFit, fit, params, read_fit, spectral_model_from_fit
from .photometry import RTable, read_rtable, rtable
from .mixing import mix, mix_calibrate
from .albedos import AlbedoResult, albedo
from .surfaces import (Surface, flat_surface, gaussian_slope_surface, read_surface, render, render_albedo,
                      surface)
from .instruments import (InstrumentSpectrum, calibrate_manifest, instrument_dataset, read_instrument,
                          read_manifest, read_usgs, usgs_dataset)
from .instruments import calibrate
from .io import convert
# Road lighting (docs/lighting.md): roadbrdf.lighting(...) = `roadbrdf lighting`, a roadbrdf.Result.
from .lightings import lighting, luminaire
# Design studies (studies/, docs/studies.md): roadbrdf.study(...) = `roadbrdf study`.
from .studies import study
# Road markings (EN 1436) and model grids for other tools: request-contract functions returning a Result.
marking = _roadbrdf.marking
export = _roadbrdf.export

__all__ = ["InputError", "Result", "Diagnostic", "RoadbrdfWarning", "Model", "SpectralModel", "Dataset", "RTable", "FitResult", "ModelFit", "models",
           "model_names", "model_aliases", "read_fit", "read_dataset", "write_dataset", "read_curet", "read_alta",
           "rtable", "read_rtable", "check", "fit", "params", "spectral_model_from_fit", "mix", "mix_calibrate",
           "albedo", "AlbedoResult", "road_to_zenith_azimuth",
           "data_directory", "Surface", "surface", "read_surface", "flat_surface", "gaussian_slope_surface",
           "render", "render_albedo", "InstrumentSpectrum", "read_instrument", "instrument_dataset",
           "read_manifest", "calibrate_manifest", "read_usgs", "usgs_dataset", "study", "marking", "export",
           "luminaire", "lighting",
           "evaluate", "simulate",
           "calibrate", "convert"]
__all__ += ["resample"]

__version__ = _roadbrdf.__version__
