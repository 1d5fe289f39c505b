"""BRDF against wavelength at one geometry (``roadbrdf plot spectral``): measured datasets with their
uncertainty bands, and the curves predicted by fit files and mixtures (MIX.json) in the same figure."""

from __future__ import annotations

import os
import sys

import numpy as np

from . import SpectralModel
from .plot_common import (as_dataset, finish, is_model_file, model_file, panels, plain, plain_title,
                          sample_label, stem)
from .plot_common import brdf_scale, dataset_options, unit_label
from .plot_geometry import TOLERANCE_DEG, nearest_geometry, parse_geometry

__all__ = ["spectral"]


def _geometry_text(ti, pi, tr, pr):
    return f"$\\theta_i$={ti:.0f}°, $\\theta_r$={tr:.0f}°, $\\Delta\\phi$={(pr - pi) % 360:.0f}°"


@dataset_options
def spectral(samples=(), geometry=(30.0, 0.0, 30.0, 0.0), labels=None, title=None, output=None, *, models=(),
             fit=None, model_labels=None, ax=None, dpi=None):
    """BRDF against wavelength at one geometry: measured datasets and predicted (fitted or mixed) curves.

    ``samples``: datasets (paths or :class:`Dataset`); a fit file or MIX.json among them counts as a model.
    ``models``: fit files, MIX.json files or :class:`SpectralModel` (``fit``: which fit or mixing method of
    each file, default its best). ``geometry`` = (theta_i, phi_i, theta_r, phi_r) [deg] or text
    (plot_geometry.parse_geometry: also road angles). Each dataset is drawn at its nearest geometry
    (plot_geometry.nearest_geometry: up to a turn about the normal), named in the legend with its distance
    when above 1 deg (also on standard error), with +-1 sigma bands when the data have sigma; each model
    is evaluated at ``geometry`` over its tabulated wavelengths and drawn dashed, in the colour of the
    dataset of the same name (``F1.mix.json`` with ``F1.csv``). ``ax``: draw into this axis.

    Returns the figure: ``fig.roadbrdf_data`` = {label: (wavelengths [nm], BRDF [sr^-1])},
    ``fig.roadbrdf_geometries`` = {label: (angles used, distance [deg])}, ``fig.roadbrdf_kinds`` =
    {label: "measured" | "fit" | "mix"}.
    """
    if isinstance(geometry, str):
        geometry = parse_geometry(geometry)
    geometry = tuple(float(x) for x in geometry)
    datasets, sources, wanted = [], [], list(models)
    for s in ([samples] if isinstance(samples, (str, os.PathLike)) else list(samples)):
        if is_model_file(s) or isinstance(s, SpectralModel):
            wanted.append(s)
        else:
            datasets.append(as_dataset(s))
            sources.append(s)
    if not datasets and not wanted:
        raise ValueError("spectral: give at least one dataset, fit file or mixture")
    labels = [plain(x) for x in labels] if labels else [sample_label(d, src, f"sample {k + 1}") for k, (d, src) in
                                                        enumerate(zip(datasets, sources))]
    fig, (ax,) = panels([None], ax=ax, size=(8.0, 5.0))
    data, geometries, kinds, colours = {}, {}, {}, {}
    for d, src, label in zip(datasets, sources, labels):
        k, distance = nearest_geometry(d.angles, geometry)
        ti, pi, tr, pr = d.angles[k]
        y = d.brdf[k]
        far = ""
        if distance > TOLERANCE_DEG:
            far = f", {distance:.1f}° from the geometry asked for"
            print(f"roadbrdf: warning: {label}: the nearest measured geometry ({ti:g}, {pi:g}, {tr:g}, {pr:g}) is "
                  f"{distance:.1f} deg from the one asked for {geometry}", file=sys.stderr)
        style = {"marker": "o", "ms": 4} if d.wavelengths.size < 8 else {}
        line, = ax.plot(d.wavelengths, y, lw=1.4, label=f"{label} measured  ({_geometry_text(ti, pi, tr, pr)}{far})",
                        **style)
        if d.sigma is not None:
            ax.fill_between(d.wavelengths, y - d.sigma[k], y + d.sigma[k], color=line.get_color(), alpha=0.25, lw=0)
        data[label] = (np.asarray(d.wavelengths), np.asarray(y))
        geometries[label] = (tuple(float(x) for x in d.angles[k]), distance)
        kinds[label] = "measured"
        colours[label] = line.get_color()
        if isinstance(src, (str, os.PathLike)):
            colours.setdefault(stem(src), line.get_color())
    model_labels = [plain(x) for x in model_labels or []]
    for k, m in enumerate(wanted):
        if isinstance(m, SpectralModel):
            spectral_model, label, kind = m, f"{m.model.name} model", "fit"
            key = None
        else:
            spectral_model, label, kind = model_file(m, fit)
            key = stem(m)
        if k < len(model_labels):
            label = model_labels[k]
        wl = np.asarray(spectral_model.wavelengths, dtype=float)
        y = brdf_scale() * np.asarray(spectral_model.evaluate(*geometry, wl), dtype=float).reshape(-1)
        colour = colours.get(key) or colours.get(label.split(" (")[0])
        ax.plot(wl, y, "--" if kind == "mix" else ":", lw=1.6, color=colour, marker="s" if wl.size < 8 else None,
                ms=4, label=f"{label}  (at {_geometry_text(*geometry)})")
        data[label] = (wl, y)
        geometries[label] = (geometry, 0.0)
        kinds[label] = kind
    lo = min(float(x[0]) for x, _ in data.values())
    hi = max(float(x[-1]) for x, _ in data.values())
    ax.set_xlim(lo - 50.0, hi + 50.0) if hi - lo < 1.0 else ax.set_xlim(lo, hi)
    ax.set_xlabel("wavelength [nm]")
    ax.set_ylabel(unit_label())
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1, frameon=False)
    measured_stems = {stem(s) for s in sources if isinstance(s, (str, os.PathLike))}
    others = [lab.split(" (")[0] for lab in data if kinds[lab] != "measured"]
    names = ", ".join(dict.fromkeys(list(labels) + [o for o in others if o not in measured_stems]))
    with_sigma = any(d.sigma is not None for d in datasets)  # the bands are promised only when drawn
    ax.set_title(plain_title(title) or f"Spectral BRDF of {names}" + (" (bands: $\\pm1\\sigma$)" if with_sigma else ""),
                 fontsize=10)
    fig.roadbrdf_geometries = geometries
    fig.roadbrdf_kinds = kinds
    return finish(fig, output, data, [ax], dpi)
