"""Fitted parameters with their standard errors (``roadbrdf plot params FIT.json -o FIG.png``).

One panel per parameter: against wavelength (a line per fit, the ± one standard error band shaded),
or, for a fit file of ``fit --group-by``, against a group column at one wavelength (the report's
per-incidence parameters: a line per model with error bars). The numbers are those of
:func:`roadbrdf.params` (the fit file's), in ``fig.roadbrdf_data``:
``{parameter: {label: (x, value, stderr)}}`` and ``bounds`` = {parameter: (lower, upper)}. A parameter fixed
in every fit that has it has no panel unless named; the ± bands are clipped to the physical bounds.
"""

from __future__ import annotations

import os

import numpy as np

from .plot_common import finish as _finish, panels, plain_title


def params(fit_file, parameters=None, models=None, against="wavelength", wavelength=None, ax=None, title=None,
           output=None, *, fig=None, dpi=None):
    """Plot fitted parameters ± standard error.

    Parameters
    ----------
    fit_file : path
        A fit file of ``roadbrdf fit``.
    parameters : list of str, optional
        Parameters to plot (default: every parameter of the fits shown).
    models : list of str, optional
        Only these models' fits.
    against : "wavelength" or a group column of the file (e.g. "theta_i")
    wavelength : float, optional
        With a group column: the wavelength [nm] (the nearest fitted band answers; default: the middle one).
    ax : matplotlib Axes or list of Axes, optional
        Draw into these (one per parameter) instead of a new figure.
    fig : matplotlib Figure or SubFigure, optional
        Add the panels to this figure.
    dpi : float, optional
        Resolution of the raster parts when saving ``output``.
    """
    table, units, fits = _table(fit_file, models)
    fixed, bounds = _fixed_and_bounds(fits)
    # A parameter fixed in every fit shown that has it (a composite's weights, say) is a constant, not a
    # result: no panel unless asked for.
    names = list(parameters) if parameters else [p for p in units if np.isfinite(table[p]).any() and p not in fixed]
    for p in names:
        if p not in units:
            from . import _roadbrdf
            raise ValueError(f"no parameter '{p}' in {fit_file}{_roadbrdf.did_you_mean(p, list(units))} "
                             f"(parameters: {', '.join(units)})")
    groups = [c[:-4] for c in table if c.endswith("_deg")]
    if against != "wavelength" and against not in groups:
        choices = ["wavelength"] + groups
        raise ValueError(f"against: '{against}' is not one of {', '.join(choices)}"
                         + ("" if groups else " (the fit file has no groups: fit with --group-by)"))
    note = ""
    if against != "wavelength":
        bands = np.unique(table["wavelength_nm"])
        wanted = float(bands[len(bands) // 2]) if wavelength is None else float(wavelength)
        band = float(bands[np.argmin(np.abs(bands - wanted))])
        if abs(band - wanted) > 1e-6:
            note = f" (nearest band to {wanted:g} nm)"
        at_band = table["wavelength_nm"] == band
        table = {c: v[at_band] for c, v in table.items()}
    columns = min(len(names), 3)
    fig, axes = panels([None] * len(names), ax=ax, fig=fig, ncols=columns, size=(4.2, 3.4), what="parameters")
    data = {}
    others = [g for g in groups if g != against]
    for axis, p in zip(axes, names):
        data[p] = {}
        keys = ["model", *(g + "_deg" for g in others)]
        for key, rows in _groups(table, keys):
            label = key[0] + "".join(f", {g}={v:g}" for g, v in zip(others, key[1:]))
            x = table["wavelength_nm" if against == "wavelength" else against + "_deg"][rows]
            y = table[p][rows]
            e = table[p + "_stderr"][rows]
            if not np.isfinite(y).any():
                continue
            data[p][label] = (x, y, e)
            # The band y +- e is clipped to the parameter's physical range: a standard error is a local
            # (linearised) figure and does not carry the parameter beyond its bounds.
            low, high = bounds.get((key[0], p), (-np.inf, np.inf))
            e = np.where(np.isfinite(e), e, 0.0)
            below, above = np.clip(y - e, low, high), np.clip(y + e, low, high)
            if against == "wavelength" and x.size > 1:
                line, = axis.plot(x, y, label=label)
                axis.fill_between(x, below, above, color=line.get_color(), alpha=0.25, linewidth=0)
            else:
                axis.errorbar(x, y, yerr=np.vstack([np.maximum(y - below, 0.0), np.maximum(above - y, 0.0)]),
                              marker="o", capsize=3, label=label)
        axis.set_xlabel("wavelength [nm]" if against == "wavelength" else f"{against} [deg]")
        axis.set_ylabel(f"{p} [{units[p]}]")
        axis.grid(True, alpha=0.3)
        if data[p]:
            axis.legend(fontsize="small")
    if against != "wavelength":
        data["wavelength_nm"] = band
    data["bounds"] = {p: bounds[k] for k in bounds for p in names if k[1] == p}
    heading = plain_title(title) or f"{os.path.basename(os.fspath(fit_file))}: fitted parameters ± 1 standard error"
    if against != "wavelength":
        heading += f" at {band:g} nm{note}"
    fig.suptitle(heading, fontsize="medium")
    return _finish(fig, output, data, axes, dpi)


def add_parser(sub, output):
    """The ``params`` kind of ``roadbrdf plot`` (its FIT.json argument is named ``fit_file`` so that the plot
    dispatcher's input/output check covers it)."""
    p = sub.add_parser("params", help="fitted parameters ± standard error against wavelength or a group column")
    p.add_argument("fit_file", metavar="FIT.json", help="fit file written by roadbrdf fit")
    p.add_argument("--parameter", action="append", help="parameter to plot (repeatable; default: all)")
    p.add_argument("--model", action="append", help="only this model's fits (repeatable; default: all)")
    p.add_argument("--against", default="wavelength",
                   help="x axis: wavelength (default) or a group column of a `fit --group-by` file, e.g. theta_i")
    p.add_argument("--wavelength", type=float, help="with a group column: the wavelength [nm] (default: the middle)")
    output(p)


def run(a):
    params(a.fit_file, a.parameter, a.model, a.against, a.wavelength, title=a.title, output=a.output, dpi=a.dpi)


def _table(fit_file, models):
    """The table of :func:`roadbrdf.params` (the same library call) as {column: array} (numbers as float, NaN
    where missing; text as object arrays), the parameters' units and the fits shown (model, options, fixed,
    bounds; the library reads them from the same parse), without building a DataFrame: the figure needs only
    the columns (and importing pandas would cost a command as much time and memory as drawing a panel)."""
    from . import _roadbrdf
    t = _roadbrdf.params_table(os.fspath(fit_file), models=[str(m) for m in models or ()])
    return dict(t["data"]), dict(t["units"]), list(t["fits"])


def _groups(table, keys):
    """(key tuple, row mask) of each distinct value of the ``keys`` columns, in the order they first appear
    (``DataFrame.groupby(keys, sort=False)``; rows with a missing group value belong to none)."""
    columns = [table[k] for k in keys]
    seen = {}
    for i, key in enumerate(zip(*columns)):
        if any(isinstance(v, float) and np.isnan(v) for v in key):
            continue
        seen.setdefault(key, []).append(i)
    n = len(columns[0]) if columns else 0
    for key, rows in seen.items():
        mask = np.zeros(n, dtype=bool)
        mask[rows] = True
        yield key, mask


def _fixed_and_bounds(fits):
    """The parameters fixed in every fit shown that has them ({name}; a composite's weights held at 1 in a file
    that also holds other models), and each (model, parameter)'s physical bounds (lower, upper) from the
    model's metadata, as the library gives them with the table."""
    held, free = set(), set()
    bounds = {}
    for f in fits:
        fixed = set(f["fixed"])
        for p, range_ in f["bounds"].items():
            (held if p in fixed else free).add(p)
            bounds[(f["model"], p)] = (float(range_[0]), float(range_[1]))
    return held - free, bounds
