"""Figures of a design study's results (``roadbrdf plot study RESULTS.csv -o FIG.png``).

* the trade-off plane: solar albedo against Q0 (or S1) for every candidate, coloured by R class, with the Pareto
  front (candidates no other candidate beats on both axes: higher albedo and higher Q0, or higher albedo and
  lower S1) and the R-class bands of S1 (R1 < 0.42 <= R2 < 0.85 <= R3 < 1.35 <= R4, CIE 144 / EN 13201);
* sensitivity: each variable's effect on each output (the mean of the output over the candidates at each value
  of the variable, with the spread of the other variables as a band).
"""

from __future__ import annotations

import csv
import math

import numpy as np

from .plot_common import finish as _finish, panels

_CLASS_COLOURS = {"R1": "tab:blue", "R2": "tab:green", "R3": "tab:orange", "R4": "tab:red"}
_S1_BANDS = [("R1", 0.0, 0.42), ("R2", 0.42, 0.85), ("R3", 0.85, 1.35), ("R4", 1.35, math.inf)]


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


def plane(results, axis="Q0", albedo=None, method=None, title=None, output=None, *, ax=None, dpi=None):
    """Solar albedo against Q0 or S1 with the Pareto front and the R-class regions (``ax``: draw into it).

    ``fig.roadbrdf_data``: ``albedo`` and ``lighting`` (N,) with their ``albedo_column``/``lighting_column``,
    ``classes`` (N,), ``pareto`` (indices of the front, by increasing albedo)."""
    rows, _, header = read_results(results) if isinstance(results, str) else results
    if method is not None:
        rows = [r for r in rows if r.get("method") == method]
    if not rows:
        raise ValueError("no successful candidates to draw")
    col = _albedo_column(header, albedo)
    ycol = {"Q0": "Q0 [sr^-1]", "S1": "S1 [1]"}[axis]
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
    for name in sorted(set(classes)):
        m = np.array([c == name for c in classes])
        ax.scatter(x[m], y[m], s=14, color=_CLASS_COLOURS.get(name, "grey"), label=name or "no class", alpha=0.8)
    front = pareto(x, y, maximise_y=(axis == "Q0"))
    ax.plot(x[front], y[front], "k-", lw=1.2, label="Pareto front")
    ax.scatter(x[front], y[front], s=30, facecolors="none", edgecolors="k")
    ax.set_xlabel(f"solar albedo ({col.split(' [')[0]})")
    ax.set_ylabel("Q0 [sr$^{-1}$]" if axis == "Q0" else "S1")
    ax.legend(fontsize=8)
    ax.set_title(title or f"albedo - {axis} trade-off ({len(rows)} candidates)")
    data = {"albedo": x, "lighting": y, "albedo_column": col, "lighting_column": ycol, "classes": classes,
            "pareto": front}
    return _finish(fig, output, data, [ax], dpi)


def sensitivity(results, outputs=None, method=None, title=None, output=None, *, ax=None, fig=None, dpi=None):
    """One panel per (output, variable): the output's mean at each value of the variable, min-max band
    (``ax``: one axis per panel, row by row; ``fig``: a Figure / SubFigure to draw into).

    ``fig.roadbrdf_data``: {output: {variable: {"x", "mean", "min", "max"}}}."""
    rows, variables, header = read_results(results) if isinstance(results, str) else results
    if method is not None:
        rows = [r for r in rows if r.get("method") == method]
    if not rows:
        raise ValueError("no successful candidates to draw")
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
            data[out][var] = {"x": list(order) if not numeric else np.asarray(pos, dtype=float),
                              "mean": np.asarray(mean), "min": np.asarray(lo), "max": np.asarray(hi)}
            ax.fill_between(pos, lo, hi, alpha=0.2)
            ax.plot(pos, mean, "o-")
            if not numeric:
                ax.set_xticks(pos)
                ax.set_xticklabels(order, fontsize=7, rotation=30)
            if i == len(outputs) - 1:
                ax.set_xlabel(var)
            if j == 0:
                ax.set_ylabel(out.replace(" [1]", ""))
    fig.suptitle(title or "sensitivity: mean (line) and range (band) over the other variables")
    return _finish(fig, output, data, flat, dpi)


def add_parser(sub, output):
    """The ``study`` kind of ``roadbrdf plot`` (its RESULTS argument is named ``result`` so that the plot
    dispatcher's input/output check covers it)."""
    p = sub.add_parser("study", help="design-study results: albedo-Q0/S1 plane with the Pareto front and class "
                                     "regions, or sensitivity panels")
    p.add_argument("result", help="results CSV of `roadbrdf study`")
    p.add_argument("--figure", choices=["plane", "sensitivity"], default="plane")
    p.add_argument("--axis", choices=["Q0", "S1"], default="Q0", help="plane: the lighting axis")
    p.add_argument("--albedo", help="albedo column (default: the first blue-sky, else black-sky column)")
    p.add_argument("--method", help="only the rows of one prediction method (e.g. mastic)")
    output(p)


def run(a):
    draw(a.result, a.figure, a.axis, a.albedo, a.method, a.title, a.output, dpi=a.dpi)


def draw(results, kind="plane", axis="Q0", albedo=None, method=None, title=None, output=None, *, dpi=None):
    """``roadbrdf plot study``: the trade-off plane (``kind="plane"``) or the sensitivity panels."""
    data = read_results(results)
    if kind == "plane":
        return plane(data, axis, albedo, method, title, output, dpi=dpi)
    return sensitivity(data, None, method, title, output, dpi=dpi)
