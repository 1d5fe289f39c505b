"""Fitting models to a measured spectral BRDF: :func:`fit` and its result objects.

The request is validated and run by the library (``src/roadbrdf/fitting/fit_request.h``), exactly
as ``roadbrdf fit`` runs it: the same option distribution over composites, the same checks and the
same error messages (naming the Python argument, e.g. ``options.distribution``, where the command
line names its flag, ``--option distribution``).
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING, Any, Sequence, Union

import numpy as np

from . import _roadbrdf
from .core import InputError, as_float, as_text
from .io import Dataset
from .model import SpectralModel

if TYPE_CHECKING:
    import pandas as pd

__all__ = ["fit", "FitResult", "ModelFit", "read_fit", "spectral_model_from_fit"]

PathLike = Union[str, "os.PathLike[str]"]


def read_fit(path: str, model: str | None = None) -> SpectralModel:
    """Read a fit file written by ``roadbrdf fit`` (or a MIX.json written by ``roadbrdf mix``) as a
    spectral model: the best-ranked fit, or the fit of ``model`` (its name as in the file, e.g.
    ``"oren-nayar+torrance-sparrow"``; for a MIX.json, the method, e.g. ``"shadowed"``). In a grouped
    fit file (``fit --group-by``) name the group too, as ``--fit`` does: ``"oren-nayar,theta_i=40"``."""
    return SpectralModel(_roadbrdf.read_spectral_model_file(str(path), model or ""))


def params(*args: Any, **kwargs: Any) -> pd.DataFrame | str:
    """The fitted parameters of a fit file, as ``roadbrdf params`` prints them (one library request, the
    same rules).

    One row per fit (model, and group in a grouped file) and wavelength: ``model``, the group columns
    ``<column>_deg``, ``wavelength_nm``, each parameter and its ``<name>_stderr``, ``rmse_per_sr``,
    ``relative_rmse_percent``, ``max_relative_error_percent``, ``aic``, ``bic``, ``converged``,
    ``at_bounds``. A wavelength that was not fitted is answered by the nearest fitted one; the notes
    saying so are in ``df.attrs["notes"]``, the parameter units in ``df.attrs["units"]``.

    The arguments are the request's fields (listed below, the command line's options; ``None`` leaves a
    field at its default). With ``format`` ("table", "csv", "markdown", "latex") the table's text is
    returned instead, byte for byte what the command prints. ``group_by`` (``"theta_i"``,
    ``"model,wavelength"`` or a list; the columns ``model``, ``wavelength`` and the file's group columns)
    makes one table per value, headed ``theta_i = 40 deg``, as ``params --group-by``; the DataFrame stays
    one table, its rows in that order. With ``output`` the text is also written there, as the command
    writes it.
    """
    kwargs = {key: value for key, value in kwargs.items() if value is not None}
    t = _roadbrdf.params_table(*args, **kwargs)
    if "format" in kwargs:
        return t["text"]
    import pandas as pd
    df = pd.DataFrame({c: t["data"][c] for c in t["columns"]}, columns=list(t["columns"]))
    df.attrs["notes"] = list(t["notes"])
    df.attrs["units"] = dict(t["units"])
    return df


# The keywords, from the request's field table (the same rows as `roadbrdf params --help`).
_doc = _roadbrdf.params_table.__doc__ or ""
if "Arguments" in _doc:
    params.__doc__ += "\n    " + _doc[_doc.index("Arguments"):_doc.rindex("Returns")].strip().replace("\n", "\n    ") + "\n"


class ModelFit:
    """The fit of one model: parameters and their uncertainties per wavelength, and statistics.

    Attributes
    ----------
    model : str
        Model name (as ``roadbrdf models`` spells it).
    options : dict
        Resolved model options.
    wavelengths : ndarray (M,)
        Fitted wavelengths [nm].
    parameter_names, parameter_units : list of str
    parameters : ndarray (P, M)
        Parameter values, one row per parameter (order of ``parameter_names``).
    standard_errors : ndarray (P, M)
        Standard errors (NaN for fixed parameters and where the covariance is undefined).
    correlation : ndarray (M, P, P)
    covariance : ndarray (M, P, P)
        correlation x standard errors (NaN where undefined).
    fixed, shared : list of str
    statistics : dict of arrays (M,)
        ``rmse`` [sr^-1], ``relative_rmse``, ``max_relative_error``, ``r_squared``, ``chi2``, ``aic``,
        ``bic``, ``cost``, ``iterations``, ``points``, ``free_parameters``, ``converged``, ``status``,
        ``covariance_ok``, ``covariance_message``, ``at_bounds``.
    totals : dict
        Over all wavelengths: ``rmse``, ``relative_rmse``, ``max_relative_error``, ``chi2``, ``aic``,
        ``bic``, ``points`` (measured values), ``missing_values``, ``free_parameters``,
        ``converged_count``, ``at_bound_count``, ``covariance_failures``, ``stayed_at_start_count``,
        ``worse_than_nested`` (fitted models this one contains that fit better: its fit missed the optimum),
        ``seconds``, ``joint``, and ``coverage``: the measured directions (``theta_i_deg`` and
        ``theta_r_deg`` [min, max], ``azimuth_planes_deg``, ``geometries``), as in the fit file.
    """

    def __init__(self, summary: Any, index: int) -> None:
        self._summary = summary
        self._index = index
        s = summary
        self.model: str = s.model_name(index)
        #: The geometry group of this fit (``fit(..., group_by=...)``): ``{column: degrees}``, empty without groups.
        self.group: dict = dict(s.group(index))
        self.options: dict = dict(s.options(index))
        self.wavelengths: np.ndarray = np.asarray(s.wavelengths, dtype=float)
        self.parameter_names: list = list(s.parameter_names(index))
        self.parameter_units: list = list(s.parameter_units(index))
        self.parameters: np.ndarray = np.asarray(s.parameters(index))
        self.standard_errors: np.ndarray = np.asarray(s.standard_errors(index))
        self.correlation: np.ndarray = np.asarray(s.correlation(index))
        se = self.standard_errors.T  # (M, P)
        self.covariance: np.ndarray = self.correlation * se[:, :, None] * se[:, None, :]
        self.fixed: list = list(s.fixed(index))
        self.shared: list = list(s.shared(index))
        self.statistics: dict = {k: (np.asarray(v) if k not in ("status", "covariance_message", "at_bounds") else list(v))
                                 for k, v in s.statistics(index).items()}
        self.totals: dict = dict(s.totals(index))

    def parameter(self, name: str) -> np.ndarray:
        """Values of one parameter per wavelength."""
        if name not in self.parameter_names:
            raise InputError(f"model '{self.model}' has no parameter '{name}'"
                             f"{_roadbrdf.did_you_mean(name, self.parameter_names)}")
        return self.parameters[self.parameter_names.index(name)]

    def spectral_model(self) -> SpectralModel:
        """The fitted model as a :class:`SpectralModel` (parameters interpolated in wavelength)."""
        return SpectralModel(self._summary.spectral_model(self._index))

    def to_dataframe(self) -> pd.DataFrame:
        """A pandas DataFrame with one row per wavelength: ``wavelength_nm``, then each parameter and
        its ``stderr_<name>``, then ``rmse``, ``aic``, ``bic``, ``converged``."""
        import pandas as pd
        columns: dict = {"wavelength_nm": self.wavelengths}
        for k, name in enumerate(self.parameter_names):
            columns[name] = self.parameters[k]
            columns["stderr_" + name] = self.standard_errors[k]
        for key in ("rmse", "aic", "bic", "converged"):
            columns[key] = self.statistics[key]
        return pd.DataFrame(columns)

    def __repr__(self) -> str:
        t = self.totals
        group = "".join(f", {k}={v:g}" for k, v in self.group.items())
        return (f"roadbrdf.ModelFit({self.model!r}{group}: {len(self.parameter_names)} parameters x "
                f"{self.wavelengths.size} "
                f"wavelengths, RMSE {t['rmse']:.4g} sr^-1, BIC {t['bic']:.2f}, "
                f"converged {t['converged_count']}/{self.wavelengths.size})")


class FitResult:
    """The result of :func:`fit`: one :class:`ModelFit` per model, ranked by total BIC.

    ``result.best`` is the best-ranked fit, ``result.fits`` all of them in the order asked for,
    ``result["model name"]`` one of them; ``summary`` is the ranking table ``roadbrdf fit`` prints,
    ``warnings`` its warnings. :meth:`write` writes the fit file with the command line's writer;
    :meth:`to_dict` gives its content (also reachable as ``result["fits"]``, ``result["best"]``).
    """

    def __init__(self, summary: Any) -> None:
        self._summary = summary
        self.fits: list = [ModelFit(summary, i) for i in range(summary.count)]
        self.ranking: list = list(summary.ranking)

    @property
    def best(self) -> ModelFit:
        return self.fits[self.ranking[0]]

    @property
    def wavelengths(self) -> np.ndarray:
        return np.asarray(self._summary.wavelengths, dtype=float)

    @property
    def notes(self) -> list:
        """Wavelengths asked for that are not on the data's grid, each answered by the nearest band
        (``"515 nm: nearest band 510 nm"``), as ``roadbrdf fit`` notes them on standard error."""
        return list(self._summary.notes)

    @property
    def summary(self) -> str:
        return self._summary.table()

    @property
    def missing_values(self) -> int:
        """Missing (NaN) values of the data, masked out of the fit at their wavelength."""
        return int(self._summary.missing_values)

    def warnings(self, where: str = "the fit result") -> list:
        return list(self._summary.warnings(where))

    def model_fit(self, model: str, **group: float) -> ModelFit:
        """The fit of ``model``; in a grouped result also name its group, e.g. ``model_fit("lambert", theta_i=40)``
        (or as ``--fit`` names it, ``model_fit("lambert,theta_i=40")``). The fit is chosen by the rule, and
        refused with the messages, of the fit file's readers."""
        model = as_text(model, "model")
        if not model.strip():
            raise InputError("model: expected a model name")
        items = [model] + [f"{as_text(k, 'group')}={as_float(v, k)!r}" for k, v in group.items()]
        return self.fits[self._summary.select(",".join(items))]

    def spectral_model(self, model: str | None = None) -> SpectralModel:
        """The best fit (or that of ``model``) as a :class:`SpectralModel`."""
        return (self.best if model is None else self.model_fit(model)).spectral_model()

    def to_dict(self) -> dict:
        """The fit file's content (``best``, ``fits`` with per-model ``parameters``, ``stderr``, ...)."""
        return self._summary.file_content()

    def __getitem__(self, key: str) -> Any:
        if key in ("best", "fits", "format", "version", "units", "best_criterion"):
            return self.to_dict()[key]
        return self.model_fit(key)

    def write(self, path: PathLike) -> None:
        """Write the fit file (JSON, atomically), byte for byte as ``roadbrdf fit -o`` writes it."""
        self._summary.write(os.fspath(path))

    def to_dataframe(self) -> pd.DataFrame:
        """A long pandas DataFrame: ``model``, the group columns when grouped (degrees), ``wavelength_nm``,
        ``parameter``, ``value``, ``stderr``."""
        import pandas as pd
        group_columns = list(self.fits[0].group) if self.fits else []
        rows = []
        for f in self.fits:
            key = tuple(f.group[c] for c in group_columns)
            for k, name in enumerate(f.parameter_names):
                for w, wl in enumerate(f.wavelengths):
                    rows.append((f.model, *key, float(wl), name, float(f.parameters[k, w]),
                                 float(f.standard_errors[k, w])))
        return pd.DataFrame(rows, columns=["model", *group_columns, "wavelength_nm", "parameter", "value", "stderr"])

    def __repr__(self) -> str:
        return "roadbrdf.FitResult(\n" + self.summary.rstrip("\n") + "\n)"


def fit(data: Dataset | PathLike, models: str | Sequence[str] | None = None, **request: Any) -> FitResult:
    """Fit one or more models to a dataset, exactly as ``roadbrdf fit`` does.

    ``data`` is a :class:`Dataset` or its file (read with ``delimiter``, ``decimal``,
    ``average_duplicates``); ``models`` a name or a list of names. Every other keyword is a field of
    the library's request, the same as the command's options (the list below is made from the one
    table both front ends use); ``fix`` is an alias of ``fixed``. With ``output`` the fit file is
    written, with ``residuals`` the residuals CSV. Returns a :class:`FitResult`.
    """
    if models is not None:
        request["models"] = models
    if "fix" in request:
        if "fixed" in request:
            raise InputError("fixed: give either fixed or its alias fix, not both")
        request["fixed"] = request.pop("fix")
    return FitResult(_roadbrdf.fit(data, **request))


fit.__doc__ = (fit.__doc__ or "") + "\n    " + "\n    ".join(
    (_roadbrdf.fit.__doc__ or "").split("\n\n", 2)[-1].splitlines())


def spectral_model_from_fit(fit_result: FitResult | dict, model: str | None = None) -> SpectralModel:
    """The spectral model of a fit result (the best fit, or that of ``model``): a :class:`FitResult`
    from :func:`fit`, or a fit file's content as a dict (read as the fit file itself is, errors naming
    its JSON keys under ``fit_result``)."""
    if isinstance(fit_result, FitResult):
        return fit_result.spectral_model(model)
    import json
    return SpectralModel(_roadbrdf.parse_fit_file(json.dumps(fit_result), "fit_result", model or ""))
