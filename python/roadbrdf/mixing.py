"""Mixing: the BRDF of a road formulation from its components' fits (``src/roadbrdf/mixing``).

The request is validated and run by the library (``src/roadbrdf/mixing/mix_request.h``), exactly as
``roadbrdf mix`` runs it. With ``method="all"``, a method that cannot be applied is skipped with a
note: each note is issued as a :class:`UserWarning` and kept in :attr:`MixResult.notes` (the command
line prints the same notes as warnings).
"""

from __future__ import annotations

import json
import os
from typing import TYPE_CHECKING, Any, Sequence, Union

from . import _roadbrdf
from .core import InputError, warn_at_caller
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


def mix(formulation: PathLike, **request: Any) -> MixResult:
    """Predict the BRDF of a road formulation from its components' fits, as ``roadbrdf mix`` does.

    ``formulation``: a formulation JSON file (see docs/mixing.md) or its content as a dict; ``fits``: fit
    files given as values ({reference: fit file content, a FitResult or its dict}), used for the
    formulation's ``fit`` references of the same name instead of files. Every other keyword is a field of the
    library's request, the same as the command's options (the list below is made from the one table
    both front ends use): ``data`` compares the methods on a measured mixture's held-out geometries,
    ``output`` writes MIX.json, ``residuals`` the held-out residuals. Methods skipped with
    ``method="all"`` are reported as :class:`UserWarning` (and in ``notes``).
    """
    fits = request.get("fits")
    if fits is not None:  # fit contents by reference: texts, dicts or FitResults
        request["fits"] = {str(k): v if isinstance(v, str) else json.dumps(v.to_dict() if hasattr(v, "to_dict") else v)
                           for k, v in fits.items()}
    run = _roadbrdf.mix(formulation, **request)
    for note in run.notes:
        warn_at_caller(note)
    return MixResult(run)


mix.__doc__ = (mix.__doc__ or "") + "\n    " + "\n    ".join(
    (_roadbrdf.mix.__doc__ or "").split("\n\n", 2)[-1].splitlines())


def mix_calibrate(mixtures: Sequence[tuple[PathLike, PathLike]], **kwargs: Any) -> dict:
    """Fit effective cross-section factors of the hapke method's end-members, as ``roadbrdf mix-calibrate``
    (one library request, the same rules).

    ``mixtures``: pairs ``(formulation, data)`` of measured mixtures (the command's ``MIXTURES`` pairs). The
    other arguments are keywords, one per field of the request (listed below, the command line's options;
    ``None`` leaves a field at its default): ``reference``, the end-member whose factor is 1 (default: the
    first); ``output``, also write the calibration file (for ``mix(..., cross_sections=...)``); the
    dataset-reading fields of the measured files. Returns ``reference``, ``factors`` and ``standard_errors``
    ({end-member: value}), ``mixtures``, ``rms_uncalibrated``, ``rms_calibrated`` (per mixture, reflectance
    factor), ``notes`` and ``table`` (the report). See docs/mixing.md "Calibrated intimate mixing".
    """
    files = []
    for pair in mixtures:
        formulation, data = pair
        files += [os.fspath(formulation), os.fspath(data)]
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    return _roadbrdf.mix_calibrate(files, **kwargs)


# The keywords, from the request's field table (the same rows as `roadbrdf mix-calibrate --help`).
_doc = _roadbrdf.mix_calibrate.__doc__ or ""
if "Arguments" in _doc:
    mix_calibrate.__doc__ += ("\n    " + _doc[_doc.index("Arguments"):_doc.rindex("Returns")].strip()
                              .replace("\n", "\n    ") + "\n")
