"""What every roadbrdf figure shares: the matplotlib set-up, saving (atomic, normal permissions), the panels
a figure draws into (``ax=`` / ``fig=``), the data behind a figure (``fig.roadbrdf_data``), labels and the
evaluation of a model, fit file or mixture at a wavelength."""

from __future__ import annotations

import copy
import functools
import math
import os

import numpy as np

import matplotlib

if os.environ.get("MPLBACKEND") is None and not os.environ.get("DISPLAY"):
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import Dataset, Model, SpectralModel, read_dataset, read_fit  # noqa: E402
from .core import write_figure_atomic  # noqa: E402
from . import _roadbrdf  # noqa: E402

__all__ = ["plt", "save", "finish", "panels", "UNIT", "DEFAULT_DPI", "OutputFolderError", "check_output_folder"]

#: The BRDF axis label.
UNIT = "BRDF [sr$^{-1}$]"
#: Resolution of the raster parts of a figure [dots per inch] when none is asked for.
DEFAULT_DPI = 150


#: The longest name (sample, file, label) shown in a figure; longer ones are shortened with an ellipsis.
MAX_NAME = 80
#: The longest title given by the caller.
MAX_TITLE = 160


def plain(text, limit: int = MAX_NAME) -> str:
    """A name as figure text: shortened to ``limit`` characters (its start and an ellipsis) and with ``$``
    escaped, so that matplotlib shows it as written instead of reading it as mathtext (a name is text, never
    a formula)."""
    text = str(text)
    if len(text) > limit:
        text = text[: limit - 1] + "…"
    return text.replace("$", r"\$")


def plain_title(title):
    """A caller's title as figure text (:func:`plain`), or None."""
    return plain(title, MAX_TITLE) if title else None


class OutputFolderError(ValueError):
    """The folder of a figure file does not exist (``roadbrdf plot`` exits with status 2)."""


def check_output_folder(output) -> None:
    """Raise :class:`OutputFolderError` when the folder ``output`` would be written into does not exist."""
    output = os.fspath(output)
    folder = os.path.dirname(output)
    if folder and not os.path.isdir(folder):
        raise OutputFolderError(f"output folder '{folder}' does not exist")


def save(fig, output, dpi=None, tight=True):
    """Save a figure as PNG, SVG or PDF (from the extension) atomically: a temporary file in the same folder,
    given the mode of the file it replaces (a new file: 0666 & ~umask, as any program's output), then renamed
    over it. A symbolic link is followed and kept. ``dpi``: resolution of the raster parts (default 150).
    ``tight``: cropped to what is drawn (an extra layout pass); False for a figure laid out with fixed margins.
    Returns the path."""
    output = os.fspath(output)
    check_output_folder(output)
    root = fig.figure  # a SubFigure saves its whole figure
    write_figure_atomic(root, output, dpi=dpi or DEFAULT_DPI, bbox_inches="tight" if tight else None)
    return output


def finish(fig, output, data=None, axes=(), dpi=None, tight=True):
    """Attach ``data`` as ``fig.roadbrdf_data`` (and to each axis drawn, for figures composed of several
    calls), save when ``output`` is given (``tight``: see :func:`save`), return the figure."""
    if data is not None:
        fig.roadbrdf_data = data
        for a in axes:
            a.roadbrdf_data = data
    if output is not None:
        save(fig, output, dpi, tight)
    return fig


_finish = finish  # the name plot_params and plot_study used before the split


def panels(projections, ax=None, fig=None, ncols=None, size=(5.0, 4.2), what="panels"):
    """The axes a figure draws into: ``projections`` lists each panel's projection (None, "polar", "3d").

    ``ax``: the caller's axes (one, or a sequence with one per panel, of the right projections);
    ``fig``: a Figure or SubFigure to add the panels to; neither: a new figure with constrained layout
    (labels and legends are not clipped). Returns (figure, list of axes)."""
    n = len(projections)
    if ax is not None:
        axes = list(np.ravel(np.array(ax, dtype=object)))
        if len(axes) != n:
            raise ValueError(f"ax: {len(axes)} axes given for {n} {what}")
        for a, p in zip(axes, projections):
            want = p or "rectilinear"
            if a.name != want:
                raise ValueError(f"ax: this figure needs {want} axes (projection='{want}'), got {a.name}")
        return axes[0].figure, axes
    ncols = min(ncols or n, n)
    nrows = math.ceil(n / ncols)
    if fig is None:
        fig = plt.figure(figsize=(size[0] * ncols, size[1] * nrows), layout="constrained")
    axes = [fig.add_subplot(nrows, ncols, k + 1, projection=p) for k, p in enumerate(projections)]
    return fig, axes


# How the figure being drawn reads its datasets and scales its BRDF axes (set by dataset_options).
_READING = {"average_duplicates": False, "units": "brdf"}
#: The BRF axis label (reflectance factor, Nicodemus et al. 1977: pi x BRDF).
BRF_UNIT = "BRF (π·BRDF)"


def dataset_options(function):
    """A figure function's keywords ``average_duplicates`` (the readers' duplicate policy for the dataset
    files it reads) and ``units`` ("brdf", or "brf": the BRDF axes of datasets and models drawn as the
    reflectance factor pi x BRDF)."""
    @functools.wraps(function)
    def with_options(*args, average_duplicates=False, units="brdf", **kwargs):
        if units not in ("brdf", "brf"):
            raise ValueError(f"units: expected 'brdf' or 'brf', got {units!r}")
        if not isinstance(average_duplicates, (bool, np.bool_)):
            raise TypeError(f"average_duplicates: expected True or False, got {type(average_duplicates).__name__}")
        previous = dict(_READING)
        _READING.update(average_duplicates=bool(average_duplicates), units=units)
        try:
            return function(*args, **kwargs)
        finally:
            _READING.update(previous)
    return with_options


def brdf_scale() -> float:
    """The factor of the BRDF axes: pi when the figure shows BRF, else 1."""
    return math.pi if _READING["units"] == "brf" else 1.0


def unit_label() -> str:
    """The BRDF axis label of the figure being drawn (BRDF or BRF)."""
    return BRF_UNIT if _READING["units"] == "brf" else UNIT


def as_dataset(x):
    d = x if isinstance(x, Dataset) else read_dataset(x, average_duplicates=_READING["average_duplicates"])
    if brdf_scale() == 1.0:
        return d
    scaled = copy.copy(d)
    scaled.brdf = d.brdf * brdf_scale()
    scaled.sigma = None if d.sigma is None else d.sigma * brdf_scale()
    return scaled


def stem(path) -> str:
    """A file's name without its folder and its .csv/.json/.fit.json/.mix.json ending, as figure text
    (:func:`plain`)."""
    name = os.path.basename(os.fspath(path))
    for ending in (".fit.json", ".mix.json", ".albedo.json", ".json", ".csv"):
        if name.endswith(ending) and len(name) > len(ending):
            return plain(name[: -len(ending)])
    return plain(name)


def sample_label(d: Dataset, source=None, fallback="sample") -> str:
    """The sample's name as figure text (:func:`plain`): its metadata, else the file's stem."""
    return plain(d.metadata.get("sample") or (stem(source) if isinstance(source, (str, os.PathLike)) else fallback))


def wavelength_index(wavelengths, wavelength):
    """(index, note) of the band nearest to ``wavelength`` [nm] (default 550, else the middle band);
    ``note`` says when the band is not the one asked for."""
    wavelengths = np.asarray(wavelengths, dtype=float)
    asked = wavelength
    if wavelength is None:
        wavelength = 550.0 if wavelengths[0] <= 550.0 <= wavelengths[-1] else wavelengths[wavelengths.size // 2]
    k = int(np.argmin(np.abs(wavelengths - wavelength)))
    note = ""
    if asked is not None and abs(wavelengths[k] - asked) > 1e-9:
        note = f"nearest band to {asked:g} nm"
    return k, note


def is_model_file(x) -> bool:
    return isinstance(x, (str, os.PathLike)) and os.fspath(x).endswith(".json")


def model_file(path, member=None):
    """A fit file or MIX.json: (SpectralModel, label, kind) with kind "fit" or "mix"; ``member``: the
    fit (model name) or mixing method, default the file's best."""
    path = os.fspath(path)
    # The library's one resolver says which entry it chose (the file's best by default).
    spectral, kind, chosen = _roadbrdf.resolve_model(path, fit=member or "")
    what = f"{chosen} mixing prediction" if kind == "mix" else f"{chosen} fit"
    return SpectralModel(spectral), f"{stem(path)} ({what})", kind


def model_name(model) -> str:
    if isinstance(model, SpectralModel):
        return model.model.name
    if isinstance(model, Model):
        return model.name
    return os.path.basename(os.fspath(model)) if isinstance(model, os.PathLike) else str(model)


def evaluate(model, params, wavelength, ti, pi, tr, pr):
    """BRDF [sr^-1] of a :class:`Model` (with ``params``), a model name, a :class:`SpectralModel` or a fit /
    MIX.json file (at ``wavelength`` [nm], default 550 nm or the middle of its range). Returns
    (values, wavelength or None, label)."""
    label = None
    if is_model_file(model):
        model, label, _ = model_file(model)
    if isinstance(model, SpectralModel):
        if wavelength is None:
            wavelength = float(model.wavelengths[wavelength_index(model.wavelengths, None)[0]])
        return brdf_scale() * model.evaluate(ti, pi, tr, pr, wavelength), wavelength, label or model.model.name
    if isinstance(model, str):
        model = Model(model)
    return brdf_scale() * model.evaluate(ti, pi, tr, pr, params=params or {}), None, label or model.name


def incidences(theta_i) -> list:
    """One incidence or several: ``40``, ``[0, 20, 40]`` or ``"0,20,40"`` as a list of floats [deg]."""
    if isinstance(theta_i, str):
        items = [t.strip() for t in theta_i.split(",") if t.strip()]
        try:
            values = [float(t) for t in items]
        except ValueError:
            raise ValueError(f"theta_i: expected a number or a comma-separated list in degrees, got '{theta_i}'") \
                from None
    else:
        values = [float(t) for t in np.atleast_1d(theta_i)]
    if not values:
        raise ValueError("theta_i: no incidence angle given")
    for t in values:
        if not (np.isfinite(t) and 0.0 <= t < 90.0):
            raise ValueError(f"theta_i: {t:g} deg is outside [0, 90)")
    return values


def measured_at_incidence(d: Dataset, theta_i: float, label: str, tolerance=0.5):
    """Boolean mask of the rows of ``d`` measured at the incidence ``theta_i`` [deg] (within ``tolerance``);
    none is an error naming the incidences the file has."""
    rows = np.abs(d.angles[:, 0] - theta_i) <= tolerance
    if not rows.any():
        have = ", ".join(f"{t:g}" for t in np.unique(np.round(d.angles[:, 0], 3)))
        raise ValueError(f"{label}: no measured geometry at theta_i = {theta_i:g} deg (measured incidences: {have})")
    return rows


def decade_floor(values) -> float:
    """The centre of a logarithmic radius: the power of ten a decade below the smallest positive value (so
    that the smallest values stay visible away from the centre)."""
    v = np.asarray(values, dtype=float)
    v = v[np.isfinite(v) & (v > 0)]
    return 10.0 ** (math.floor(math.log10(v.min())) - 1) if v.size else 1e-3


def log_radius(values, floor):
    """Radius of a logarithmic polar axis: decades above ``floor`` (0 at the centre, values below it at 0)."""
    v = np.asarray(values, dtype=float)
    with np.errstate(divide="ignore", invalid="ignore"):
        return np.maximum(np.log10(np.where(v > 0, v, floor) / floor), 0.0)


def label_log_radius(ax, floor, top):
    """Decade ticks of a logarithmic radius, labelled with the BRDF they stand for; the centre is ``floor``."""
    decades = np.arange(0, math.ceil(top) + 1)
    ax.set_rlim(0, max(float(decades[-1]), 1.0))
    ax.set_yticks(decades)
    ax.set_yticklabels([f"{floor * 10.0 ** k:g}" for k in decades], fontsize=7)


def readable_log_axis(axis_obj, low, high) -> None:
    """Ticks for a logarithmic axis (``ax.xaxis`` / ``ax.yaxis``) over [low, high]: powers of ten when the
    range holds at least two, else 1-2-5 (or every digit) of each decade, labelled in plain numbers, so that a
    range inside one decade is not left with a single tick label."""
    import matplotlib.ticker as mticker
    if not (np.isfinite(low) and np.isfinite(high) and 0 < low < high):
        return
    first, last = math.ceil(math.log10(low) - 1e-9), math.floor(math.log10(high) + 1e-9)
    for subs in ((1.0,), (1.0, 2.0, 5.0), tuple(float(k) for k in range(1, 10))):
        ticks = [m * 10.0 ** e for e in range(first - 1, last + 1) for m in subs if low <= m * 10.0 ** e <= high]
        if len(ticks) >= 2:
            break
    axis_obj.set_major_locator(mticker.FixedLocator(ticks))
    axis_obj.set_major_formatter(mticker.FuncFormatter(lambda v, _: f"{v:.3g}"))
    axis_obj.set_minor_formatter(mticker.NullFormatter())
