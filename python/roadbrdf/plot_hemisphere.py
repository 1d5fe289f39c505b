"""BRDF over the viewing hemisphere (``roadbrdf plot hemisphere``): for each incidence a polar heat map
(radius theta_r, angle phi_r - phi_i) of a model, fit file or mixture, with the measured points of a
dataset drawn on it as marked dots, and a 3-D lobe (radius = BRDF) drawn with equal axes so that its
shape is not distorted. The mesh is rasterized inside vector files (SVG, PDF) to keep them small."""

from __future__ import annotations

import os

import matplotlib.colors as mcolors
import numpy as np

from . import Dataset
from .plot_common import (as_dataset, evaluate, finish, incidences, is_model_file, measured_at_incidence,
                          model_file, model_name, panels, plain, plain_title, plt, sample_label, wavelength_index)
from .plot_common import dataset_options, unit_label

__all__ = ["hemisphere"]


def _is_dataset(x):
    return isinstance(x, Dataset) or (isinstance(x, (str, os.PathLike)) and not is_model_file(x)
                                      and os.path.isfile(os.fspath(x)))


def _equal_box(ax3, x, y, z):
    """Limits at the extent of the points and a box of the same proportions: a lobe keeps its shape."""
    spans = []
    for setter, v in ((ax3.set_xlim, x), (ax3.set_ylim, y), (ax3.set_zlim, z)):
        v = np.asarray(v, dtype=float)
        v = v[np.isfinite(v)]
        lo, hi = (float(v.min()), float(v.max())) if v.size else (0.0, 1.0)
        if hi - lo <= 0:
            lo, hi = lo - 0.5, hi + 0.5
        setter(lo, hi)
        spans.append(hi - lo)
    ax3.set_box_aspect(spans, zoom=0.85)  # room for the axis labels


def _lobe_xyz(theta_r, dphi, f):
    t, p = np.radians(theta_r), np.radians(dphi)
    return f * np.sin(t) * np.cos(p), f * np.sin(t) * np.sin(p), f * np.cos(t)


@dataset_options
def hemisphere(model=None, params=None, theta_i=45.0, wavelength=None, log=False, resolution=90, title=None,
               output=None, *, data=None, lobe=True, fit=None, label=None, ax=None, fig=None, dpi=None):
    """BRDF over the viewing hemisphere for one incidence theta_i [deg] or several (one column of panels each;
    the source at phi_i = 0): a polar heat map (radius theta_r, angle phi_r) and, with ``lobe``, a 3-D lobe.

    ``model``: a :class:`Model` (with ``params``), a model name, a :class:`SpectralModel` or a fit / MIX.json
    file (``fit``: which member; at ``wavelength`` [nm], default 550 or the middle of its range); or a dataset (path or
    :class:`Dataset`), whose measured points are drawn alone. ``data``: a dataset whose points at each
    incidence are drawn over the model (its band nearest to ``wavelength``; the model is evaluated at that
    band). ``log``: logarithmic colour scale. ``ax``: the panels' axes (polar, and 3-D with ``lobe``), or
    ``fig``: a Figure / SubFigure to draw into.

    ``fig.roadbrdf_data`` (one incidence): ``theta_i``, ``wavelength``, and for a model ``theta_r`` (R,),
    ``phi_r`` (P,), ``brdf`` (R x P) [deg, sr^-1]; for data ``measured`` = {``theta_r``, ``phi_r`` (relative
    to phi_i), ``brdf``, ``wavelength``}. Several incidences: {theta_i: that dict}.
    """
    if model is not None and data is None and _is_dataset(model):
        model, data = None, model
    if model is None and data is None:
        raise ValueError("hemisphere: give a model, a fit file, a mixture or a dataset")
    angles = incidences(theta_i)
    model_label = None
    if model is not None and is_model_file(model):
        model, model_label, _ = model_file(model, fit)
    d = as_dataset(data) if data is not None else None
    data_label = sample_label(d, data) if d is not None else None
    note = ""
    if d is not None:
        band, note = wavelength_index(d.wavelengths, wavelength)
        wavelength = float(d.wavelengths[band])
    tr = np.linspace(0.0, 89.5, resolution)
    pr = np.linspace(0.0, 360.0, 4 * resolution + 1)
    TR, PR = np.meshgrid(tr, pr, indexing="ij")
    per_incidence = []
    name = None
    for t in angles:
        item = {"theta_i": t}
        if model is not None:
            f, wl, name = evaluate(model, params, wavelength, t, 0.0, TR, PR)
            item.update(theta_r=tr, phi_r=pr, brdf=np.asarray(f))
            wavelength = wl if wl is not None else wavelength
        if d is not None:
            rows = measured_at_incidence(d, t, data_label)
            a = d.angles[rows]
            item["measured"] = {"theta_r": a[:, 2], "phi_r": (a[:, 3] - a[:, 1]) % 360.0,
                                "brdf": d.brdf[rows, band], "wavelength": wavelength}
        item["wavelength"] = wavelength
        per_incidence.append(item)
    every = np.concatenate([np.ravel(v) for item in per_incidence
                            for v in ([item["brdf"]] if "brdf" in item else []) +
                            ([item["measured"]["brdf"]] if "measured" in item else [])])
    positive = every[np.isfinite(every) & (every > 0)]
    if log:
        lo = float(positive.min()) if positive.size else 1e-6
        norm = mcolors.LogNorm(lo, max(float(np.nanmax(every)), lo * 10))
    else:
        norm = plt.Normalize(float(np.nanmin(every)), float(np.nanmax(every)))
    n = len(angles)
    kinds = ["polar"] * n + (["3d"] * n if lobe else [])
    size = (5.2, 4.4)
    fig, axes = panels(kinds, ax=ax, fig=fig, ncols=2 if (n == 1 and lobe) else n, size=size,
                       what="panels (a polar map per incidence, then a 3-D lobe per incidence)")
    maps, lobes = axes[:n], axes[n:]
    mappable = None
    for k, item in enumerate(per_incidence):
        t, axis = item["theta_i"], maps[k]
        axis.grid(False)
        if "brdf" in item:
            mappable = axis.pcolormesh(np.radians(PR), TR, item["brdf"], shading="auto", cmap="viridis", norm=norm,
                                       rasterized=True)
        if "measured" in item:
            m = item["measured"]
            points = axis.scatter(np.radians(m["phi_r"]), m["theta_r"], c=m["brdf"], cmap="viridis", norm=norm,
                                  s=28, edgecolors="k", linewidths=0.8, zorder=3,
                                  label=f"measured ({m['brdf'].size} points)")
            mappable = mappable or points
            axis.legend(loc="lower left", bbox_to_anchor=(-0.1, -0.12), fontsize=7, frameon=False)
        axis.set_rlim(0, 90)
        axis.set_rticks([30, 60, 90])
        axis.grid(True, alpha=0.3)
        axis.set_yticklabels(["30°", "60°", "90°"], fontsize=7)
        axis.plot([np.pi], [t], marker="*", color="w", ms=10, mec="k", zorder=4)  # specular direction
        axis.plot([0.0], [t], marker="o", color="r", ms=6, mec="k", zorder=4)       # retro direction (source)
        axis.set_title(f"$\\theta_i$ = {t:g}°  (radius $\\theta_r$, angle $\\phi_r-\\phi_i$;\n"
                       "● source side, ★ mirror)", fontsize=9)
    colourbar = fig.colorbar(mappable, ax=maps, shrink=0.85, pad=0.08)
    colourbar.set_label(unit_label() + (" (logarithmic colours)" if log else ""))
    for k, item in enumerate(per_incidence):
        if not lobes:
            break
        ax3 = lobes[k]
        xs, ys, zs = [], [], []
        if "brdf" in item:
            f = item["brdf"]
            x, y, z = _lobe_xyz(TR, PR, f)
            ax3.plot_surface(x, y, z, facecolors=plt.cm.viridis(norm(f)), rstride=2, cstride=4, linewidth=0,
                             antialiased=False, shade=False, rasterized=True)
            xs, ys, zs = [x], [y], [z]
        if "measured" in item:
            m = item["measured"]
            x, y, z = _lobe_xyz(m["theta_r"], m["phi_r"], m["brdf"])
            ax3.scatter(x, y, z, c=m["brdf"], cmap="viridis", norm=norm, s=16, edgecolors="k", linewidths=0.5,
                        depthshade=False)
            xs, ys, zs = xs + [x], ys + [y], zs + [z]
        _equal_box(ax3, *(np.concatenate([np.ravel(v) for v in vs]) for vs in (xs, ys, zs)))
        for setter, axis_name in ((ax3.set_xlabel, "x"), (ax3.set_ylabel, "y"), (ax3.set_zlabel, "z")):
            setter(f"{axis_name} [sr$^{{-1}}$]", fontsize=8)
        ax3.tick_params(labelsize=6)
        ax3.set_title(f"lobe at $\\theta_i$ = {item['theta_i']:g}° (radius = BRDF, equal axes)", fontsize=9)
    if label is not None:
        label = plain(label)
    else:
        if model is not None:
            label = model_label or name or model_name(model)
        if data_label:
            label = f"{label}, measured {data_label}" if label else f"{data_label} (measured)"
    at = f" at {wavelength:g} nm" if wavelength is not None else ""
    fig.suptitle(plain_title(title) or f"BRDF over the viewing hemisphere: {label}{at}" + (f" ({note})" if note else ""))
    result = per_incidence[0] if n == 1 else {item["theta_i"]: item for item in per_incidence}
    return finish(fig, output, result, axes, dpi)
