"""Mixing: the BRDF of a road formulation from its components' fits (``src/roadbrdf/mixing``).

The request is validated and run by the library (``src/roadbrdf/mixing/mix_request.h``), exactly as
``roadbrdf mix`` runs it. With ``method="all"``, a method that cannot be applied is skipped with a
note: each note is issued as a :class:`UserWarning` and kept in :attr:`MixResult.notes` (the command
line prints the same notes as warnings).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Sequence, Union

from . import _roadbrdf
from .core import InputError, as_float, as_int, as_text, warn_at_caller
from .model import SpectralModel

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["mix", "MixResult", "MethodResult"]

PathLike = Union[str, "os.PathLike[str]"]


class MethodResult:
    """One mixing method's result: ``method``, ``description``, ``end_members``, ``weights``
    {end-member: weight}, ``formulation_weights``, ``settings``, ``notes``, ``comparison`` (held-out
    errors against the measured mixture: ``rmse`` [sr^-1], ``relative_rmse``, ``chi2_reduced``,
    ``albedo``, ...; None without data); :meth:`spectral_model` evaluates the mixture, with the parameter
    covariance from the end-members' fits where the method has one (areal, mastic, hapke: see ``notes``), so
    that :func:`roadbrdf.albedo` and :func:`roadbrdf.rtable` give its uncertainties."""

    def __init__(self, run: Any, index: int, content: dict) -> None:
        self._run = run
        self._index = index
        self.method: str = content["method"]
        self.description: str = content["description"]
        self.end_members: list = list(content["end_members"])
        self.weights: dict = dict(content["weights"])
        self.formulation_weights = content.get("formulation_weights")
        self.settings: dict = dict(content.get("settings") or {})
        self.notes: list = list(content.get("notes") or [])
        self.comparison = content.get("comparison")

    def spectral_model(self) -> SpectralModel:
        return SpectralModel(self._run.spectral_model(self._index))

    def __repr__(self) -> str:
        w = " ".join(f"{k}={v:.3f}" for k, v in self.weights.items())
        err = f", held-out RMSE {self.comparison['rmse']:.4g} sr^-1" if self.comparison else ""
        return f"roadbrdf.MethodResult({self.method!r}: {w}{err})"


class MixResult:
    """The result of :func:`mix`: one :class:`MethodResult` per method applied (``methods``),
    ``best`` (lowest held-out RMSE, with data), ``notes`` (methods skipped and why), ``summary`` (the
    report ``roadbrdf mix`` prints); :meth:`write` writes MIX.json with the command line's writer,
    :meth:`to_dict` gives its content (also as ``result["methods"]``, ``result["best"]``, ...)."""

    def __init__(self, run: Any) -> None:
        self._run = run
        content = run.content()
        self.methods: list = [MethodResult(run, i, m) for i, m in enumerate(content["methods"])]
        self.notes: list = list(run.notes)
        self._best = content.get("best")

    @property
    def best(self) -> MethodResult | None:
        return None if self._best is None else self.method(self._best)

    @property
    def summary(self) -> str:
        return self._run.table()

    def method(self, name: str) -> MethodResult:
        for m in self.methods:
            if m.method == name:
                return m
        names = [m.method for m in self.methods]
        raise InputError(f"method '{name}' is not in this result (methods: {', '.join(names)})"
                         f"{_roadbrdf.did_you_mean(name, names)}")

    def spectral_model(self, method: str | None = None) -> SpectralModel:
        """The mixture of ``method`` (default: the best, else the first) as a :class:`SpectralModel`."""
        chosen = self.method(method) if method else (self.best or self.methods[0])
        return chosen.spectral_model()

    def to_dict(self) -> dict:
        return self._run.content()

    def __getitem__(self, key: str) -> Any:
        content = self.to_dict()
        if key in content:
            return content[key]
        return self.method(key)

    def write(self, path: PathLike) -> None:
        """Write MIX.json (atomically), as ``roadbrdf mix -o`` does."""
        self._run.write(os.fspath(path))

    def write_residuals(self, path: PathLike) -> None:
        """Write the held-out residuals (CSV), as ``roadbrdf mix --residuals`` does (needs data)."""
        self._run.write_residuals(os.fspath(path))

    def to_dataframe(self) -> pd.DataFrame:
        """A pandas DataFrame, one row per method: ``method``, the weights ``weight.<end-member>`` and,
        with data, ``rmse``, ``relative_rmse``, ``chi2_reduced``, ``albedo``, ``albedo_difference``."""
        import pandas as pd
        rows = []
        for m in self.methods:
            row = {"method": m.method}
            row.update({f"weight.{k}": v for k, v in m.weights.items()})
            for key in ("rmse", "relative_rmse", "chi2_reduced", "albedo", "albedo_difference"):
                if m.comparison is not None:
                    row[key] = m.comparison.get(key)
            rows.append(row)
        return pd.DataFrame(rows)

    def __repr__(self) -> str:
        return "roadbrdf.MixResult(\n" + self.summary.rstrip("\n") + "\n)"


def mix(formulation: PathLike, data: PathLike | None = None, method: str = "all", folds: int = 5, seed: int = 1,
        per_wavelength: bool = False, sum_to_one: bool = False, binder_coverage: float | None = None,
        mastic_fraction: float | None = None, reference: PathLike | None = None, output: PathLike | None = None,
        use_sigma: bool = True, residuals: PathLike | None = None,
        cross_sections: PathLike | None = None, uncertainty: bool = False) -> MixResult:
    """Predict the BRDF of a road formulation from its components' fits, as ``roadbrdf mix`` does.

    ``formulation``: a formulation JSON file (see docs/mixing.md); ``data``: the measured mixture
    (CSV path) to compare the methods on held-out geometries (``folds``-fold); ``method``: areal,
    fitted, mastic, hapke, shadowed or all; ``reference``: the fit file of the measured mixture (for
    the albedo difference); ``use_sigma``: weight the fitted methods by 1/sigma^2 when the data have
    sigma (False = ``--no-sigma-weights``); ``output``: also write MIX.json; ``residuals``: CSV path for the
    held-out residuals (needs ``data``); ``cross_sections``: calibration file of :func:`mix_calibrate`
    (``--cross-sections``, hapke only); ``uncertainty``: carry the components' fit covariances into the
    areal, mastic and hapke mixtures (``--uncertainty``; their albedo is then much slower). Methods skipped with ``method="all"`` are reported as
    :class:`UserWarning` (and in ``notes``).
    """
    def path(value, name):
        return "" if value is None else as_text(value, name)

    run = _roadbrdf.mix(as_text(formulation, "formulation"), path(data, "data"), as_text(method, "method"),
                        as_int(folds, "folds"), as_int(seed, "seed"), bool(per_wavelength), bool(sum_to_one),
                        None if binder_coverage is None else as_float(binder_coverage, "binder_coverage"),
                        None if mastic_fraction is None else as_float(mastic_fraction, "mastic_fraction"),
                        path(reference, "reference"), path(output, "output"), bool(use_sigma),
                        path(residuals, "residuals"), path(cross_sections, "cross_sections"), bool(uncertainty))
    for note in run.notes:
        warn_at_caller(note)
    result = MixResult(run)
    if output is not None:
        result.write(output)
    if residuals is not None:
        result.write_residuals(residuals)
    return result


def mix_calibrate(mixtures: Sequence[tuple[PathLike, PathLike]], reference: str | None = None,
                  output: PathLike | None = None) -> dict:
    """Fit effective cross-section factors of the hapke method's end-members, as ``roadbrdf mix-calibrate``.

    ``mixtures``: pairs ``(formulation, data)`` of measured mixtures; ``reference``: the end-member whose
    factor is 1 (default: the first); ``output``: also write the calibration file (for ``mix(...,
    cross_sections=...)``). Returns ``reference``, ``factors`` and ``standard_errors`` ({end-member: value}),
    ``mixtures``, ``rms_uncalibrated``, ``rms_calibrated`` (per mixture, reflectance factor), ``notes`` and
    ``table`` (the report). See docs/mixing.md "Calibrated intimate mixing".
    """
    pairs = [(os.fspath(f), os.fspath(d)) for f, d in mixtures]
    return _roadbrdf.mix_calibrate([f for f, _ in pairs], [d for _, d in pairs],
                                   "" if reference is None else str(reference),
                                   "" if output is None else os.fspath(output))
