"""Fitted parameters with their standard errors (``roadbrdf plot params FIT.json -o FIG.png``).

One panel per parameter: against wavelength (a line per fit, the ± one standard error band shaded),
or, for a fit file of ``fit --group-by``, against a group column at one wavelength (the report's
per-incidence parameters: a line per model with error bars). The numbers are those of
:func:`roadbrdf.params` (the fit file's), in ``fig.roadbrdf_data``:
``{parameter: {label: (x, value, stderr)}}`` and ``bounds`` = {parameter: (lower, upper)}. A parameter fixed
in every fit that has it has no panel unless named; the ± bands are clipped to the physical bounds.
"""

from __future__ import annotations

import math
import os
import textwrap

import numpy as np

from .plot_common import finish as _finish, panels, plain, plain_title, plt


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
    others = [g for g in groups if g != against]
    keys = ["model", *(g + "_deg" for g in others)]
    # The fits with a value of a parameter shown (the figure's key, one colour each).
    fit_rows = [(key, rows) for key, rows in _groups(table, keys)
                if any(np.isfinite(table[p][rows]).any() for p in names)]
    labels = [key[0] + "".join(f", {g}={v:g}" for g, v in zip(others, key[1:])) for key, _ in fit_rows]
    held_by = {}  # model -> the parameters its fits hold fixed
    for f in fits:
        held_by.setdefault(f["model"], set()).update(f["fixed"])
    heading = plain_title(title) or f"{os.path.basename(os.fspath(fit_file))}: fitted parameters ± 1 standard error"
    if against != "wavelength":
        heading += f" at {band:g} nm{note}"
    heading = "\n".join([heading, *_held_constants(table, held_by, fixed - set(names))])
    own = ax is None and fig is None
    if own:
        # The figure is not cropped to what is drawn when saved (fixed margins): a long heading is wrapped.
        wrap = max(int(_width(len(names), labels) / _CHAR), 20)
        heading = "\n".join(textwrap.fill(line, wrap) for line in heading.split("\n"))
        fig, axes, labelled, key_columns = _grid(len(names), heading.count("\n") + 1, labels)
    else:
        fig, axes = panels([None] * len(names), ax=ax, fig=fig, ncols=min(len(names), 3), size=(4.2, 3.4),
                           what="parameters")
        labelled = axes
    data = {}
    # One colour per fit across the panels (a model's parameters are found by their colour), one key for the
    # figure when it is this function's own.
    colours = {label: f"C{k % 10}" for k, label in enumerate(labels)}
    handles = {}
    for axis, p in zip(axes, names):
        data[p] = {}
        on_bound = []
        for (key, rows), label in zip(fit_rows, labels):
            x = table["wavelength_nm" if against == "wavelength" else against + "_deg"][rows]
            y = table[p][rows]
            e = table[p + "_stderr"][rows]
            if not np.isfinite(y).any():
                continue
            data[p][label] = (x, y, e)
            held = p in held_by.get(key[0], ())  # drawn dashed, without a band: a value given, not fitted
            # The band y +- e is clipped to the parameter's physical range: a standard error is a local
            # (linearised) figure and does not carry the parameter beyond its bounds.
            low, high = bounds.get((key[0], p), (-np.inf, np.inf))
            e = np.where(np.isfinite(e), e, 0.0)
            below, above = np.clip(y - e, low, high), np.clip(y + e, low, high)
            if against == "wavelength" and x.size > 1:
                line, = axis.plot(x, y, color=colours[label], linestyle="--" if held else "-",
                                  label=label + (" (fixed)" if held else ""))
                if not held:
                    axis.fill_between(x, below, above, color=colours[label], alpha=0.25, linewidth=0)
            else:
                line = axis.errorbar(x, y, yerr=np.vstack([np.maximum(y - below, 0.0), np.maximum(above - y, 0.0)]),
                                     color=colours[label], marker="o", capsize=3, label=label)
            handles.setdefault(label, line)
            # On a bound the standard error is undefined (no band there): the panel says where it sits.
            sides = [item.partition("=")[2] for cell in table["at_bounds"][rows] if isinstance(cell, str)
                     for item in cell.split(";") if item.partition("=")[0] == p] if "at_bounds" in table else []
            for side in sorted(set(sides)):
                where = "wavelengths" if against == "wavelength" else "points"
                who = f"{label}: " if len(labels) > 1 else ""
                on_bound.append(f"{who}at its {side} bound at {sides.count(side)} of {x.size} {where}")
        if on_bound:
            axis.text(0.02, 0.03, "\n".join(on_bound), transform=axis.transAxes, fontsize="small", va="bottom")
        axis.set_ylabel(f"{p} [{units[p]}]")
        axis.grid(True, alpha=0.3)
        if data[p] and not own:
            axis.legend(fontsize="small")
    x_label = "wavelength [nm]" if against == "wavelength" else f"{against} [deg]"
    for axis in labelled:
        axis.set_xlabel(x_label)
    if against != "wavelength":
        data["wavelength_nm"] = band
    data["bounds"] = {p: bounds[k] for k in bounds for p in names if k[1] == p}
    if own:
        _same_x(axes, labelled)
        height = fig.get_figheight()
        fig.suptitle(heading, fontsize="medium", y=1.0 - _EDGE / height, va="top")
        if handles:
            lines = heading.count("\n") + 1
            fig.legend(list(handles.values()), list(handles), loc="upper center", fontsize="small", frameon=False,
                       ncols=key_columns, borderaxespad=0.0,
                       bbox_to_anchor=(0.5, 1.0 - (_EDGE + lines * _TEXT_ROW + _GAP_Y) / height))
    else:
        fig.suptitle(heading, fontsize="medium")
    return _finish(fig, output, data, axes, dpi, tight=not own)


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


# The panels' layout when the figure is this function's own: fixed sizes in inches instead of a constrained
# layout (which measures every label and tick of every panel at each draw, the most part of saving a figure
# of many panels), one x range, labelled under the lowest panel of each column.
_PANEL = (3.5, 2.3)  # panel width, height [in]
_LEFT, _RIGHT, _GAP_X = 0.85, 0.2, 0.9  # left margin (y tick labels and label), right margin, column gap [in]
_BOTTOM, _GAP_Y = 0.55, 0.2  # bottom margin (x tick labels and label), row gap [in]
_EDGE, _TEXT_ROW = 0.1, 0.2  # the figure's top margin, a line of the heading or a row of the key [in]
_CHAR = 0.09  # the width of a character of the heading (medium size) [in], at most


def _grid(n, heading_lines, labels):
    """A new figure of ``n`` panels, three to a row at most, under a heading of ``heading_lines`` lines and the
    key of ``labels``: (figure, axes, the axes that show the x tick labels, the key's columns)."""
    import matplotlib.ticker as mticker
    ncols = max(min(n, 3), 1)
    nrows = max(math.ceil(n / ncols), 1)
    width = _width(n, labels)
    key_columns = _key_columns(labels, width)
    key_rows = math.ceil(len(labels) / key_columns) if labels else 0
    top = _EDGE + heading_lines * _TEXT_ROW + _GAP_Y + key_rows * _TEXT_ROW + _GAP_Y
    height = top + nrows * _PANEL[1] + (nrows - 1) * _GAP_Y + _BOTTOM
    fig = plt.figure(figsize=(width, height))
    grid = fig.add_gridspec(nrows, ncols, left=_LEFT / width, right=1 - _RIGHT / width, bottom=_BOTTOM / height,
                            top=1 - top / height, wspace=_GAP_X / _PANEL[0], hspace=_GAP_Y / _PANEL[1])
    axes = [fig.add_subplot(grid[k // ncols, k % ncols]) for k in range(n)]
    for axis in axes:
        # The grid marks the ticks: no tick marks (each is drawn as a marker of its own), and at most five
        # intervals on either axis, which a panel of this size shows without crowding.
        axis.tick_params(length=0)
        axis.xaxis.set_major_locator(mticker.MaxNLocator(nbins=5, steps=[1, 2, 2.5, 5, 10]))
        axis.yaxis.set_major_locator(mticker.MaxNLocator(nbins=5, steps=[1, 2, 2.5, 5, 10]))
    # A panel with one below it in the same column leaves the x tick labels to that one.
    return fig, axes, [axis for k, axis in enumerate(axes) if k + ncols >= n], key_columns


def _same_x(axes, labelled):
    """One x range for every panel (the union of theirs), tick labels only on the ``labelled`` panels. Not
    matplotlib's shared axes: hiding shared tick labels makes each panel measure its tick labels again to place
    its (empty) titles; empty labels cost nothing."""
    import matplotlib.ticker as mticker
    low = min(a.get_xlim()[0] for a in axes)
    high = max(a.get_xlim()[1] for a in axes)
    for a in axes:
        a.set_xlim(low, high)
        if a not in labelled:
            a.xaxis.set_major_formatter(mticker.NullFormatter())


def _width(n, labels):
    """The width [in] of a figure of ``n`` panels, three to a row, and at least that of its key's longest label."""
    ncols = max(min(n, 3), 1)
    panels_width = _LEFT + ncols * _PANEL[0] + (ncols - 1) * _GAP_X + _RIGHT
    return max(panels_width, _key_entry(labels) + 0.4)


def _key_entry(labels):
    """The width [in] of a column of the figure's key: the longest label (about 0.075 in a character at small
    size) and the line's handle."""
    return 0.075 * max((len(label) for label in labels), default=0) + 0.7


def _key_columns(labels, width):
    """Columns of the figure's key: as many as fit across ``width`` [in]."""
    return max(1, min(len(labels), int(width // _key_entry(labels))))


def _held_constants(table, held_by, hidden):
    """Heading lines "held fixed in MODEL: name = value, ..." for the parameters held fixed that have no panel
    (``hidden``)."""
    out = []
    for model, held in held_by.items():
        rows = table["model"] == model
        items = []
        for p in sorted(held & hidden):
            values = table[p][rows] if p in table else np.array([])
            values = np.unique(values[np.isfinite(values)])
            if values.size:
                items.append(f"{p} = {values[0]:.4g}" if values.size == 1
                             else f"{p} = {values.min():.4g} to {values.max():.4g}")
        if items:
            out.append(plain(f"held fixed in {model}: " + ", ".join(items), 160))
    return out


def _groups(table, keys):
    """(key tuple, row mask) of each distinct value of the ``keys`` columns, in the order they first appear
    (``DataFrame.groupby(keys, sort=False)``; rows with a missing group value belong to none)."""
    columns = [table[k] for k in keys]
    n = len(columns[0]) if columns else 0
    # Consecutive rows of one fit share their key (the table lists each fit's wavelengths together): the key is
    # read at the start of each run.
    change = np.zeros(max(n - 1, 0), dtype=bool)
    for c in columns:
        differ = np.asarray(c[1:] != c[:-1], dtype=bool)
        if c.dtype.kind == "f":
            differ &= ~(np.isnan(c[1:]) & np.isnan(c[:-1]))
        change |= differ
    starts = [0, *(int(i) + 1 for i in np.flatnonzero(change))] if n else []
    seen = {}
    for begin, end in zip(starts, starts[1:] + [n]):
        key = tuple(c[begin] for c in columns)
        if any(isinstance(v, float) and np.isnan(v) for v in key):
            continue
        seen.setdefault(key, []).append((begin, end))
    for key, runs in seen.items():
        mask = np.zeros(n, dtype=bool)
        for begin, end in runs:
            mask[begin:end] = True
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
