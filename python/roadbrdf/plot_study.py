"""Figures of a design study's results (``roadbrdf plot study RESULTS.csv -o FIG.png``).

* the trade-off plane: solar albedo against Q0 (or S1) for every candidate, coloured by R class, with the Pareto
  front (candidates no other candidate beats on both axes: higher albedo and higher Q0, or higher albedo and
  lower S1) and the R-class bands of S1 (R1 < 0.42 <= R2 < 0.85 <= R3 < 1.35 <= R4, CIE 144 / EN 13201);
* the urban-heat / lighting-energy plane (``axis="power"``, a study with ``predictions.lighting``): solar albedo
  against the lighting power per km of road [W/km] (the least power that meets the study's M class, else the
  installed power), with the Pareto front of higher albedo and lower power;
* sensitivity: each variable's effect on each output (the mean of the output over the candidates at each value
  of the variable, with the spread of the other variables as a band).

The rows of several prediction methods (a fast study's ``areal``, ``mastic``, ...) are predictions of the same
candidates by models that disagree, not more candidates: each method gets its own markers and Pareto front on the
plane and its own line in the sensitivity panels (``method`` keeps one).
"""

from __future__ import annotations

import csv
import math

import numpy as np

from .plot_common import finish as _finish, panels, plain, plain_title

_CLASS_COLOURS = {"R1": "tab:blue", "R2": "tab:green", "R3": "tab:orange", "R4": "tab:red"}
_S1_BANDS = [("R1", 0.0, 0.42), ("R2", 0.42, 0.85), ("R3", 0.85, 1.35), ("R4", 1.35, math.inf)]
_MARKERS = "osD^vP*X"
_FRONT_STYLES = ["-", "--", ":", "-."]


def _by_method(rows, method):
    """The rows of ``method`` (all when None) and the methods present, in order of appearance."""
    if method is not None:
        rows = [r for r in rows if r.get("method") == method]
    if not rows:
        raise ValueError("no successful candidates to draw" + (f" with method '{method}'" if method else ""))
    return rows, list(dict.fromkeys(r.get("method", "") for r in rows))


def read_results(path):
    """Rows of a results CSV (status ok only) as dicts, numbers converted, and the variable columns."""
    with open(path, newline="", encoding="utf-8") as f:
        reader = csv.DictReader(f)
        header = reader.fieldnames or []
        rows = [r for r in reader if r.get("status") == "ok"]
    if "status" not in header:
        raise ValueError(f"{path}: not a roadbrdf study results file (no 'status' column)")
    fixed = {"candidate", "replicate", "key", "status", "error", "method"}
    first_output = next((i for i, h in enumerate(header) if h.startswith("black_sky_")), len(header))
    variables = [h for h in header[:first_output] if h not in fixed]
    out = []
    for r in rows:
        item = {}
        for k, v in r.items():
            try:
                item[k] = float(v)
            except (TypeError, ValueError):
                item[k] = v
        out.append(item)
    return out, variables, header


def _albedo_column(header, albedo):
    if albedo is not None:
        if albedo not in header:
            raise ValueError(f"no column '{albedo}' (albedo columns: "
                             f"{', '.join(h for h in header if 'sky' in h and 'error' not in h)})")
        return albedo
    for prefix in ("blue_sky_", "black_sky_"):
        for h in header:
            if h.startswith(prefix) and "error" not in h:
                return h
    return "white_sky [1]"


def pareto(x, y, maximise_y=True):
    """Indices of the Pareto-optimal points (maximise x, and maximise or minimise y)."""
    x = np.asarray(x, dtype=float)
    y = np.asarray(y, dtype=float) * (1 if maximise_y else -1)
    keep = []
    for i in range(x.size):
        dominated = np.any((x >= x[i]) & (y >= y[i]) & ((x > x[i]) | (y > y[i])))
        if not dominated:
            keep.append(i)
    return sorted(keep, key=lambda i: x[i])


_POWER_COLUMNS = ("least_power_per_km_w [W/km]", "power_per_km_w [W/km]")


def _power_rows(rows, header):
    """The power column (the least power for the study's class when the study asked for one, else the installed
    power), its axis label, and the rows that have a value there (a class no flux meets leaves it empty)."""
    col = next((c for c in _POWER_COLUMNS if c in header and any(isinstance(r.get(c), float) for r in rows)), None)
    if col is None:
        raise ValueError("no lighting power column in the results (a study with predictions.lighting has "
                         "'least_power_per_km_w [W/km]' and 'power_per_km_w [W/km]')")
    kept = [r for r in rows if isinstance(r.get(col), float) and math.isfinite(r[col])]
    if not kept:
        raise ValueError(f"no candidate has a value in '{col}' (no flux meets the class)")
    if col == _POWER_COLUMNS[0]:
        names = sorted({r.get("least_class [class]") for r in kept if isinstance(r.get("least_class [class]"), str)})
        label = f"least lighting power for {'/'.join(names) or 'the class'} [W/km]"
    else:
        label = "installed lighting power [W/km]"
    return col, label, kept


def plane(results, axis="Q0", albedo=None, method=None, title=None, output=None, *, ax=None, dpi=None):
    """Solar albedo against Q0 or S1 (or, ``axis="power"``, the lighting power per km) with the Pareto front of
    each method and the R-class regions (``ax``: draw into it; ``method``: only its rows).

    ``fig.roadbrdf_data``: ``albedo`` and ``lighting`` (N,) with their ``albedo_column``/``lighting_column``,
    ``classes`` and ``methods`` (N,), ``fronts`` ({method: indices of its front, by increasing albedo}) and
    ``pareto`` (the fronts' indices, method after method)."""
    rows, _, header = read_results(results) if isinstance(results, str) else results
    rows, methods = _by_method(rows, method)
    col = _albedo_column(header, albedo)
    left_out = 0
    if axis == "power":
        ycol, ylabel, kept = _power_rows(rows, header)
        left_out, rows = len(rows) - len(kept), kept
        methods = list(dict.fromkeys(r.get("method", "") for r in rows))
    else:
        ycol = {"Q0": "Q0 [sr^-1]", "S1": "S1 [1]"}[axis]
        ylabel = "Q0 [sr$^{-1}$]" if axis == "Q0" else "S1"
    for needed in (col, ycol):
        if needed not in header:
            raise ValueError(f"no column '{needed}' in the results (a study without it: choose another albedo or "
                             "axis, or an r-table in its predictions)")
    x = np.array([r[col] for r in rows], dtype=float)
    y = np.array([r[ycol] for r in rows], dtype=float)
    classes = [r.get("class [R]", "") for r in rows]
    fig, (ax,) = panels([None], ax=ax, size=(6.4, 4.8))
    if axis == "S1":
        top = max(1.5, float(np.nanmax(y)) * 1.1)
        for name, lo, hi in _S1_BANDS:
            ax.axhspan(lo, min(hi, top), color=_CLASS_COLOURS[name], alpha=0.08)
            ax.text(1.0, (lo + min(hi, top)) / 2, f" {name}", transform=ax.get_yaxis_transform(), va="center",
                    fontsize=8, color=_CLASS_COLOURS[name])
        ax.set_ylim(0, top)
    of = np.array([r.get("method", "") for r in rows])
    several = len(methods) > 1
    for name in sorted(set(classes)):  # colour = class, marker = method
        for k, meth in enumerate(methods):
            m = np.array([c == name for c in classes]) & (of == meth)
            if m.any():
                ax.scatter(x[m], y[m], s=14, marker=_MARKERS[k % len(_MARKERS)], alpha=0.8,
                           color=_CLASS_COLOURS.get(name, "grey"), label="_nolegend_" if several else plain(name) if name else "no class")
    if several:  # the legend's keys: a colour per class, a marker per method
        for name in sorted(set(classes)):
            ax.scatter([], [], s=14, color=_CLASS_COLOURS.get(name, "grey"), label=plain(name) if name else "no class")
        for k, meth in enumerate(methods):
            ax.scatter([], [], s=14, marker=_MARKERS[k % len(_MARKERS)], color="grey", label=plain(meth))
    fronts = {}
    for k, meth in enumerate(methods):
        where = np.flatnonzero(of == meth)
        front = [int(where[i]) for i in pareto(x[where], y[where], maximise_y=(axis == "Q0"))]  # S1, power: lower
        fronts[meth] = front
        ax.plot(x[front], y[front], color="k", ls=_FRONT_STYLES[k % len(_FRONT_STYLES)], lw=1.2,
                label=f"Pareto front, {meth}" if several else "Pareto front")
        ax.scatter(x[front], y[front], s=30, marker=_MARKERS[k % len(_MARKERS)], facecolors="none", edgecolors="k")
    ax.set_xlabel(f"solar albedo ({col.split(' [')[0]})")
    ax.set_ylabel(ylabel)
    ax.legend(fontsize=8)
    what = f"{len(rows)} candidates" if not several else f"{len(rows)} predictions by {len(methods)} methods"
    if left_out:
        what += f"; {left_out} without a power value left out"
    topic = "lighting power" if axis == "power" else axis
    ax.set_title(plain_title(title) or f"albedo - {topic} trade-off ({what})")
    data = {"albedo": x, "lighting": y, "albedo_column": col, "lighting_column": ycol, "classes": classes,
            "methods": list(of), "fronts": fronts, "pareto": [i for f in fronts.values() for i in f]}
    return _finish(fig, output, data, [ax], dpi)


def sensitivity(results, outputs=None, method=None, title=None, output=None, *, ax=None, fig=None, dpi=None):
    """One panel per (output, variable): the output's mean at each value of the variable, min-max band, a line
    per method (``ax``: one axis per panel, row by row; ``fig``: a Figure / SubFigure to draw into; ``method``:
    only its rows).

    ``fig.roadbrdf_data``: {output: {variable: {method: {"x", "mean", "min", "max"}}}}."""
    rows, variables, header = read_results(results) if isinstance(results, str) else results
    every, methods = _by_method(rows, method)
    if not variables:
        raise ValueError("the study has no variables")
    outputs = outputs or [_albedo_column(header, None), "Q0 [sr^-1]", "S1 [1]"]
    outputs = [o for o in outputs if o in header]
    if not outputs:
        raise ValueError("none of the outputs asked for is a column of the results")
    fig, flat = panels([None] * (len(outputs) * len(variables)), ax=ax, fig=fig, ncols=len(variables),
                       size=(3.2, 2.6), what="panels (one per output and variable)")
    axes = [flat[i * len(variables):(i + 1) * len(variables)] for i in range(len(outputs))]
    data = {}
    for i, out in enumerate(outputs):
        data[out] = {}
        for j, var in enumerate(variables):
            ax = axes[i][j]
            data[out][var] = {}
            for meth in methods:
                rows = [r for r in every if r.get("method", "") == meth]
                data[out][var][meth] = _effect(ax, rows, var, out, meth if len(methods) > 1 else None)
            if i == len(outputs) - 1:
                ax.set_xlabel(plain(var))
            if j == 0:
                ax.set_ylabel(out.replace(" [1]", ""))
    if len(methods) > 1:
        axes[0][0].legend(fontsize=7, title="method", title_fontsize=7)
    fig.suptitle(plain_title(title) or "sensitivity: mean (line) and range (band) over the other variables")
    return _finish(fig, output, data, flat, dpi)


def _effect(ax, rows, var, out, label):
    """Draw one method's mean and range of ``out`` at each value of ``var`` (continuous designs binned in 8);
    return {"x", "mean", "min", "max"}."""
    values = [r[var] for r in rows]
    numeric = all(isinstance(v, float) for v in values)
    if numeric and len(set(values)) > 12:  # continuous designs: bin into 8 classes
        edges = np.linspace(min(values), max(values), 9)
        keys = [float(np.clip(np.searchsorted(edges, v, side="right") - 1, 0, 7)) for v in values]
        centres = {float(k): (edges[int(k)] + edges[int(k) + 1]) / 2 for k in range(8)}
    else:
        keys = values
        centres = None
    groups = {}
    for k, r in zip(keys, rows):
        groups.setdefault(k, []).append(r[out])
    order = sorted(groups)
    pos = [centres[k] for k in order] if centres else (order if numeric else list(range(len(order))))
    mean = [float(np.mean(groups[k])) for k in order]
    lo = [float(np.min(groups[k])) for k in order]
    hi = [float(np.max(groups[k])) for k in order]
    line, = ax.plot(pos, mean, "o-", label=plain(label) if label else None)
    ax.fill_between(pos, lo, hi, alpha=0.2, color=line.get_color())
    if not numeric:
        ax.set_xticks(pos)
        ax.set_xticklabels([plain(o) for o in order], fontsize=7, rotation=30)
    return {"x": list(order) if not numeric else np.asarray(pos, dtype=float), "mean": np.asarray(mean),
            "min": np.asarray(lo), "max": np.asarray(hi)}


def add_parser(sub, output):
    """The ``study`` kind of ``roadbrdf plot`` (its RESULTS argument is named ``result`` so that the plot
    dispatcher's input/output check covers it)."""
    p = sub.add_parser("study", help="design-study results: albedo-Q0/S1 plane with the Pareto front and class "
                                     "regions, or sensitivity panels")
    p.add_argument("result", help="results CSV of `roadbrdf study`")
    p.add_argument("--figure", choices=["plane", "sensitivity"], default="plane",
                   help="plane: solar albedo against Q0 or S1, Pareto fronts, R classes (default); sensitivity: "
                        "each output's mean and range at each value of each variable")
    p.add_argument("--axis", choices=["Q0", "S1", "power"], default="Q0",
                   help="plane: the lighting axis (power: lighting power per km of road [W/km], a study with "
                        "lighting predictions)")
    p.add_argument("--albedo", help="albedo column (default: the first blue-sky, else black-sky column)")
    p.add_argument("--method", help="only the rows of one prediction method (e.g. mastic; default: every method, "
                                    "each with its own front or line)")
    output(p)


def run(a):
    draw(a.result, a.figure, a.axis, a.albedo, a.method, a.title, a.output, dpi=a.dpi)


def draw(results, kind="plane", axis="Q0", albedo=None, method=None, title=None, output=None, *, dpi=None):
    """``roadbrdf plot study``: the trade-off plane (``kind="plane"``) or the sensitivity panels."""
    data = read_results(results)
    if kind == "plane":
        return plane(data, axis, albedo, method, title, output, dpi=dpi)
    return sensitivity(data, None, method, title, output, dpi=dpi)
