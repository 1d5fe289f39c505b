"""Albedo figure (``roadbrdf plot albedo``): black-sky albedo against sun zenith with the white-sky value and
the blue-sky albedo of each atmosphere given, and the spectral albedo when there are several bands.

The input is what ``roadbrdf albedo --json`` writes (one result per atmosphere, or several files), or a fit
file / MIX.json / model from which the albedo is computed for each atmosphere (``atmospheres``, e.g.
``spectrl2:aod=0.05`` and ``spectrl2:aod=0.4``)."""

from __future__ import annotations

import os
import re

import numpy as np

from . import Model, SpectralModel, read_fit
from .albedos import albedo as compute_albedo
from .core import read_json_file
from .plot_common import finish, panels, plain, plain_title, stem

__all__ = ["albedo"]

# The quadrature tolerance of an albedo the figure computes itself (from a fit file, a mixture or a model),
# absolute. A figure resolves about 1e-3 of albedo (a pixel of the default albedo axis is ~8e-4 for a
# sand's 0.07-0.35), so 1e-4 draws the same picture as the command line's 1e-5 at a fraction of the cost
# (on the 2151-band Hapke fit of bench/report_bench.sh: values within 1.2e-5 and standard uncertainties within
# 6e-5 of those at 1e-5, the solar-weighted ones within 0.4 %); ``tolerance`` asks for another, and
# ``roadbrdf albedo`` gives the numbers at its own default.
FIGURE_TOLERANCE = 1e-4

# A fit file or MIX.json says so in its top-level "format" (an albedo result has none); unescaped quotes
# occur in JSON only around keys and string values, so the pair cannot hide inside another value.
_MODEL_FILE = re.compile(rb'"format"\s*:\s*"roadbrdf-(?:fit|mix)"')


def _is_model_file(path) -> bool:
    try:
        with open(path, "rb") as f:
            return _MODEL_FILE.search(f.read()) is not None
    except OSError:
        return False  # read_json_file names the file and the reason


def _results(result, labels, atmospheres, sun_zenith, wavelengths, fit, params, tolerance):
    items = result if isinstance(result, (list, tuple)) else [result]
    out = []
    for k, item in enumerate(items):
        # A result given as a value has no name: numbered only when there are several to tell apart.
        name = stem(item) if isinstance(item, (str, os.PathLike)) else (f"result {k + 1}" if len(items) > 1 else "")
        if isinstance(item, (str, os.PathLike)):
            # A fit file or MIX.json is read once, by the albedo request itself (a 2151-band fit file is
            # 8 MB of JSON).
            if _is_model_file(item):
                item = os.fspath(item)
            else:
                content = read_json_file(item)
                item = content if "black_sky" in content else read_fit(item, fit)
        if isinstance(item, dict):
            if atmospheres:
                raise ValueError(f"atmospheres apply to a fit file or a model, not to an albedo result ('{name}')")
            out.append((name, item))
            continue
        if not isinstance(item, (SpectralModel, Model, str)):
            raise ValueError(f"albedo: expected an albedo result, a fit file, a mixture or a model, got {item!r}")
        for atmosphere in atmospheres or [None]:
            r = compute_albedo(item, params if isinstance(item, Model) else None, sun_zenith=sun_zenith,
                               atmosphere=atmosphere, wavelengths=wavelengths, tolerance=tolerance,
                               fit=fit if isinstance(item, str) else None)
            out.append((", ".join(x for x in (name, atmosphere) if x), r))
    labels = [plain(x) for x in labels or []]
    return [(labels[k] if k < len(labels) else name, r) for k, (name, r) in enumerate(out)]


def _u(values, shape=None):
    """Standard uncertainties of the JSON "uncertainty" as floats (null -> NaN), or None when absent."""
    if values is None:
        return None
    a = np.array(values, dtype=float)  # None entries become NaN
    return a if shape is None else a.reshape(shape)


def _versus_zenith(r, which="correlated"):
    """Black-, blue- and white-sky values against sun zenith: solar-weighted, else at the single band; with
    their standard uncertainties from the fit's covariance (``*_u``; the broadband ones ``which``: "correlated",
    the bound for errors correlated across wavelengths, or "independent"; None when the result has none)."""
    zen = np.atleast_1d(np.asarray(r["sun_zenith_deg"], dtype=float))
    bb = r.get("broadband")
    u = r.get("uncertainty") or {}
    if bb is not None:
        black = np.atleast_1d(np.asarray(bb["black_sky"], dtype=float))
        blue = None if bb.get("blue_sky") is None else np.atleast_1d(np.asarray(bb["blue_sky"], dtype=float))
        white = float(np.atleast_1d(bb["white_sky"])[0])
        how = "solar-weighted"
        ub = u.get("broadband") or {}
        chosen = lambda items: None if items is None else [i[which] for i in items]  # noqa: E731
        black_u = _u(chosen(ub.get("black_sky")))
        blue_u = _u(chosen(ub.get("blue_sky")))
        white_u = None if ub.get("white_sky") is None else _u(ub["white_sky"][which])
    else:
        wl = np.atleast_1d(np.asarray(r["wavelengths"], dtype=float))
        j = int(np.argmin(np.abs(wl - 550.0)))
        black = np.asarray(r["black_sky"], dtype=float).reshape(zen.size, -1)[:, j]
        blue = None if r.get("blue_sky") is None else np.asarray(r["blue_sky"], dtype=float).reshape(zen.size, -1)[:, j]
        white = float(np.atleast_1d(r["white_sky"])[j])
        how = f"at {wl[j]:g} nm"
        black_u = None if u.get("black_sky") is None else _u(u["black_sky"], (zen.size, -1))[:, j]
        blue_u = None if u.get("blue_sky") is None else _u(u["blue_sky"], (zen.size, -1))[:, j]
        white_u = None if u.get("white_sky") is None else _u(u["white_sky"])[j]
    return {"sun_zenith_deg": zen, "black_sky": black, "blue_sky": blue, "white_sky": white, "weighting": how,
            "black_sky_u": black_u, "blue_sky_u": blue_u, "white_sky_u": None if white_u is None else float(white_u)}


def albedo_range(curves):
    """(bottom, top) of the albedo axis: every value and its bar, with a margin each side of at least 5 % of the
    largest value (and 10 % of the data's spread), never below 0: a 1 % change stays a small change."""
    values = []
    for c in curves:
        for key in ("black_sky", "blue_sky", "white_sky"):
            if c[key] is None:
                continue
            v = np.atleast_1d(np.asarray(c[key], dtype=float))
            u = c.get(key + "_u")
            u = np.zeros_like(v) if u is None else np.nan_to_num(np.atleast_1d(np.asarray(u, dtype=float)))
            values += [v - u, v + u]
    v = np.concatenate(values)
    v = v[np.isfinite(v)]
    if v.size == 0:
        return 0.0, 1.0
    low, high = float(v.min()), float(v.max())
    margin = max(0.05 * max(abs(low), abs(high)), 0.1 * (high - low), 1e-6)
    return max(0.0, low - margin) if low >= 0 else low - margin, high + margin


def _named(what, label):
    """A legend entry: ``what``, then the result's name when it has one."""
    return f"{what}, {label}" if label else what


def _line(axis, x, y, u, fmt, **kw):
    """A curve with its standard uncertainty as error bars (k = 1) when known."""
    if u is None:
        axis.plot(x, y, fmt, **kw)
    else:
        axis.errorbar(x, y, yerr=u, fmt=fmt, capsize=2, elinewidth=0.8, **kw)


def albedo(result, title=None, output=None, *, labels=None, atmospheres=None, sun_zenith="0:80:10",
           wavelengths=None, fit=None, params=None, uncertainty="correlated", tolerance=FIGURE_TOLERANCE, ax=None,
           fig=None, dpi=None):
    """Albedo figure: black-sky against sun zenith (solar-weighted, or at the single band) with white-sky and
    the blue-sky albedo of every atmosphere, and the spectral black-, white- and blue-sky albedo when there are
    several bands (a single sun zenith and a single band: the values as bars).

    ``result``: the dict or JSON file of ``roadbrdf albedo --json``, a list of them (one per atmosphere,
    ``labels`` naming them, default the file stems), or a fit / MIX.json file, :class:`SpectralModel` or
    :class:`Model` (with ``params``), whose albedo is computed at ``sun_zenith`` [deg] and ``wavelengths``
    for each of ``atmospheres`` (e.g. ``["spectrl2:aod=0.05", "spectrl2:aod=0.4"]``; ``fit``: which fit of
    the file), to the absolute quadrature ``tolerance`` (default :data:`FIGURE_TOLERANCE`, 1e-4: a tenth of a
    pixel; ``roadbrdf albedo`` computes to 1e-5). ``ax``: the panels' axes, or ``fig``.

    Where the result has standard uncertainties (a fit file with its covariance: ``uncertainty``), they are drawn
    as error bars (k = 1) and shaded bands; the solar-weighted ones are ``uncertainty``: "correlated" (the
    default: the bound for errors correlated across wavelengths, which a per-wavelength covariance cannot
    exclude) or "independent" (smaller by about the square root of the number of bands). Either comes from the
    fit's covariance alone: calibration, sample non-uniformity and repeatability between scans are not in it.
    The albedo axis contains the data with a margin proportional to their size (at least 5 % of the largest
    value each side), so a small change with sun zenith is not drawn as a cliff.

    ``fig.roadbrdf_data``: the first result's keys, and ``zenith_panel`` = {label: {sun_zenith_deg,
    black_sky, blue_sky, white_sky, weighting, black_sky_u, blue_sky_u, white_sky_u}}, ``spectral_panel`` =
    {wavelengths, black_sky {zenith: (M,)}, white_sky, blue_sky {label: (M,)}, blue_sky_zenith_deg, black_sky_u,
    white_sky_u} (None without several bands), ``results``.
    """
    results = _results(result, labels, atmospheres, sun_zenith, wavelengths, fit, params, tolerance)
    if not results:
        raise ValueError("albedo: nothing to draw")
    first = results[0][1]
    wl = np.atleast_1d(np.asarray(first["wavelengths"], dtype=float))
    zen = np.atleast_1d(np.asarray(first["sun_zenith_deg"], dtype=float))
    if uncertainty not in ("correlated", "independent"):
        raise ValueError(f"albedo: uncertainty must be 'correlated' or 'independent', got {uncertainty!r}")
    curves = {label: _versus_zenith(r, uncertainty) for label, r in results}
    several_zeniths = any(c["sun_zenith_deg"].size > 1 for c in curves.values())
    kinds = (["zenith"] if several_zeniths else []) + (["spectral"] if wl.size > 1 else [])
    kinds = kinds or ["values"]
    fig, axes = panels([None] * len(kinds), ax=ax, fig=fig, size=(6.0, 4.4), what=f"panels ({', '.join(kinds)})")
    spectral_panel = None
    for axis, kind in zip(axes, kinds):
        if kind == "zenith":
            for k, (label, c) in enumerate(curves.items()):
                colour = f"C{k}"
                _line(axis, c["sun_zenith_deg"], c["black_sky"], c["black_sky_u"], "o-", color=colour, ms=3,
                      label=_named(f"black-sky ({c['weighting']})", label))
                if c["blue_sky"] is not None:
                    _line(axis, c["sun_zenith_deg"], c["blue_sky"], c["blue_sky_u"], "s--", color=colour, ms=3,
                          label=_named("blue-sky", label))
                axis.axhline(c["white_sky"], color=colour, ls=":", lw=1.4, label=_named("white-sky", label))
                if c["white_sky_u"] is not None and np.isfinite(c["white_sky_u"]):
                    axis.axhspan(c["white_sky"] - c["white_sky_u"], c["white_sky"] + c["white_sky_u"], color=colour,
                                 alpha=0.12, lw=0)
            if any(c["black_sky_u"] is not None for c in curves.values()):
                # The largest bar is named: a well-determined albedo's bars hide behind the markers.
                largest = np.nanmax([np.nanmax(np.r_[c[k]]) for c in curves.values()
                                     for k in ("black_sky_u", "blue_sky_u") if c[k] is not None] or [np.nan])
                axis.text(0.01, 0.01, f"bars: k = 1 from the parameter covariance, {uncertainty}"
                          + (" across wavelengths" if uncertainty == "correlated" else " wavelengths")
                          + (f"; largest {largest:.2g}" if np.isfinite(largest) else "")
                          + "\n(calibration and repeatability between scans not included)",
                          transform=axis.transAxes, fontsize=6, va="bottom")
            axis.set_ylim(*albedo_range(curves.values()))
            axis.set_xlabel("sun zenith angle [deg]")
            axis.set_ylabel("albedo [1]")
            axis.set_title("albedo vs sun zenith", fontsize=10)
        elif kind == "spectral":
            black = np.asarray(first["black_sky"], dtype=float).reshape(zen.size, -1)
            shown = sorted(set(np.linspace(0, zen.size - 1, min(zen.size, 4)).round().astype(int)))
            u = first.get("uncertainty") or {}
            black_u = None if u.get("black_sky") is None else _u(u["black_sky"], black.shape)
            for k, j in enumerate(shown):
                axis.plot(wl, black[j], lw=1.2, color=f"C{k}", label=f"black-sky, sun zenith {zen[j]:g}°")
                if black_u is not None:
                    axis.fill_between(wl, black[j] - black_u[j], black[j] + black_u[j], color=f"C{k}", alpha=0.2, lw=0)
            white = np.asarray(first["white_sky"], dtype=float)
            axis.plot(wl, white, "k", lw=1.6, label="white-sky")
            white_u = None if u.get("white_sky") is None else _u(u["white_sky"])
            if white_u is not None:
                axis.fill_between(wl, white - white_u, white + white_u, color="k", alpha=0.15, lw=0,
                                  label="± standard uncertainty (parameter covariance)")
            blues = {}
            for k, (label, r) in enumerate(results):
                if r.get("blue_sky") is not None:
                    blue = np.asarray(r["blue_sky"], dtype=float).reshape(len(r["sun_zenith_deg"]), -1)[0]
                    blues[label] = blue
                    axis.plot(r["wavelengths"], blue, "--", lw=1.3, color=f"C{k + len(shown)}",
                              label=_named(f"blue-sky, sun zenith {r['sun_zenith_deg'][0]:g}°", label))
            spectral_panel = {"wavelengths": wl, "black_sky": {float(zen[j]): black[j] for j in shown},
                              "white_sky": white, "blue_sky": blues, "blue_sky_zenith_deg": float(zen[0]),
                              "black_sky_u": None if black_u is None else {float(zen[j]): black_u[j] for j in shown},
                              "white_sky_u": white_u}
            axis.set_xlabel("wavelength [nm]")
            axis.set_ylabel("albedo [1]")
            axis.set_title("spectral albedo", fontsize=10)
        else:
            names, values = [], []
            for label, c in curves.items():
                for what in ("black_sky", "blue_sky", "white_sky"):
                    if c[what] is not None:
                        names.append(f"{what.replace('_', '-')}\n{label}")
                        values.append(float(np.atleast_1d(c[what])[0]))
            axis.bar(range(len(values)), values, color=["C0", "C2", "k"] * len(curves))
            axis.set_xticks(range(len(values)))
            axis.set_xticklabels(names, fontsize=7)
            axis.set_ylabel("albedo [1]")
            c = next(iter(curves.values()))
            axis.set_title(f"albedo {c['weighting']}, sun zenith {c['sun_zenith_deg'][0]:g}°", fontsize=10)
        axis.grid(alpha=0.3)
        if kind != "values":
            axis.legend(fontsize=7)
    model = first.get("model")
    names = ", ".join(dict.fromkeys(label.split(",")[0] for label, _ in results if label))
    if not names:
        heading = f"Albedo of {model}" if model else "Albedo"
    else:
        heading = f"Albedo of {names}" + (f" ({model})" if model and model not in names else "")
    fig.suptitle(plain_title(title) or heading)
    data = dict(first)
    data.update(zenith_panel=curves, spectral_panel=spectral_panel, results=dict(results))
    return finish(fig, output, data, axes, dpi)
