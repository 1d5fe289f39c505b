"""Fit quality (``roadbrdf plot fit DATA.csv FIT.json``): measured against fitted BRDF per geometry at one
wavelength, the residuals, and - when the fit has more than one band - RMSE against wavelength for every
model of the fit file."""

from __future__ import annotations

import os

import numpy as np

from . import read_fit
from .core import read_json_file
from .plot_common import (as_dataset, finish, panels, plain, plain_title, readable_log_axis, sample_label,
                          stem, wavelength_index)
from .plot_common import brdf_scale, dataset_options, unit_label

__all__ = ["fit_quality"]


@dataset_options
def fit_quality(data, fit, model=None, wavelength=None, title=None, output=None, *, ax=None, fig=None, dpi=None):
    """Measured vs fitted BRDF per geometry (with residuals) at one wavelength, and RMSE against wavelength
    for every model of the fit file (that panel only when the file has several bands: no empty panels).

    ``data``: the dataset that was fitted; ``fit``: the fit file (JSON written by ``roadbrdf fit``);
    ``model``: which fit of the file (default: the best); ``wavelength`` [nm]: the band nearest to it
    (default 550 nm or the middle). ``ax``: the 2 or 3 axes to draw into, or ``fig``.

    ``fig.roadbrdf_data``: ``measured``, ``fitted`` (N,) [sr^-1] at ``wavelength`` [nm], ``angles`` (N x 4),
    ``rmse`` = {model: (wavelengths, RMSE)} from the file.
    """
    d = as_dataset(data)
    fits = read_json_file(fit)
    chosen = model or fits["best"]
    spectral_model = read_fit(fit, chosen)
    index, note = wavelength_index(d.wavelengths, wavelength)
    wl = float(d.wavelengths[index])
    a = d.angles
    predicted = brdf_scale() * np.asarray(spectral_model.evaluate(a[:, 0], a[:, 1], a[:, 2], a[:, 3], wl))
    measured = d.brdf[:, index]
    rmse = {}
    for f in fits["fits"]:
        if "rmse" not in f:  # a fit file written by hand
            continue
        group = "".join(f", {k}={v:g}" for k, v in (f.get("group") or {}).items())
        rmse[f["model"] + group] = (np.asarray(f["wavelengths"], dtype=float),
                                    brdf_scale() * np.asarray(f["rmse"], dtype=float))
    several_bands = any(x.size > 1 for x, _ in rmse.values())
    fig, axes = panels([None] * (3 if several_bands else 2), ax=ax, fig=fig, size=(4.6, 4.2),
                       what="panels (measured vs fitted, residuals" + (", RMSE)" if several_bands else ")"))
    name = sample_label(d, data, stem(fit))
    axis = axes[0]
    positive = (measured > 0) & (predicted > 0)
    axis.loglog(measured[positive], predicted[positive], "o", ms=4)
    if positive.any():
        lo = min(measured[positive].min(), predicted[positive].min()) * 0.8
        hi = max(measured[positive].max(), predicted[positive].max()) * 1.25
        axis.plot([lo, hi], [lo, hi], "k--", lw=0.8, label="1:1")
        axis.set_xlim(lo, hi)
        axis.set_ylim(lo, hi)
        axis.set_aspect("equal", adjustable="box")
        for which in (axis.xaxis, axis.yaxis):
            readable_log_axis(which, lo, hi)
        axis.legend(fontsize=8)
    axis.set_xlabel("measured " + unit_label())
    axis.set_ylabel("fitted " + unit_label())
    axis.set_title(f"{chosen} at {wl:g} nm" + (f" ({note})" if note else ""), fontsize=9)
    axis = axes[1]
    order = np.argsort(a[:, 0] * 1000 + a[:, 2])
    axis.bar(np.arange(len(order)), (predicted - measured)[order], width=0.8)
    axis.axhline(0, color="k", lw=0.8)
    axis.set_xlabel("geometry (sorted by $\\theta_i$, then $\\theta_r$)")
    axis.set_ylabel("fitted $-$ measured [sr$^{-1}$]")
    axis.set_title(f"residuals at {wl:g} nm", fontsize=9)
    if several_bands:
        axis = axes[2]
        for label, (x, y) in rmse.items():
            axis.plot(x, y, lw=1.2, label=label, marker="o" if x.size < 8 else None, ms=3)
        axis.set_xlabel("wavelength [nm]")
        axis.set_ylabel("RMSE [sr$^{-1}$]")
        axis.set_yscale("log")
        finite = np.concatenate([y[np.isfinite(y) & (y > 0)] for _, y in rmse.values()] or [np.array([])])
        if finite.size:
            low, high = finite.min() / 1.15, finite.max() * 1.15
            axis.set_ylim(low, high)
            readable_log_axis(axis.yaxis, low, high)
        axis.set_title("RMSE vs wavelength", fontsize=9)
        axis.legend(fontsize=7)
    fig.suptitle(plain_title(title) or f"Fit quality: {name}, {chosen} ({os.path.basename(os.fspath(fit))})")
    result = {"measured": measured, "fitted": predicted, "wavelength": wl, "angles": a, "rmse": rmse,
              "model": chosen}
    return finish(fig, output, result, axes, dpi)
