"""BRDF in the plane of incidence (``roadbrdf plot plane``): theta_r signed, negative on the backward (source)
side, positive on the forward (specular) side; models, fit files and mixtures as curves, measured points
of datasets as markers. Polar (radius = BRDF from 0, or an explicit logarithmic radius with ``log``) or
cartesian; one panel per incidence."""

from __future__ import annotations

import matplotlib.ticker as mticker
import numpy as np

from . import SpectralModel
from .plot_common import (as_dataset, decade_floor, evaluate, finish, incidences, is_model_file,
                          label_log_radius, log_radius, measured_at_incidence, model_file, panels, plain, plain_title,
                          sample_label, wavelength_index)
from .plot_common import dataset_options, unit_label

__all__ = ["plane", "in_plane_points"]

_SIGNED = np.linspace(-89.5, 89.5, 359)


def in_plane_points(d, theta_i, wavelength_index_, label="dataset"):
    """The measured points of ``d`` at incidence ``theta_i`` in its plane of incidence: (signed theta_r [deg],
    BRDF [sr^-1]), theta_r negative where phi_r = phi_i (backward), positive where phi_r = phi_i + 180."""
    a = d.angles
    dphi = (a[:, 3] - a[:, 1]) % 360.0
    forward = np.abs(dphi - 180.0) < 0.5
    backward = (dphi < 0.5) | (dphi > 359.5)
    sel = measured_at_incidence(d, theta_i, label) & (forward | backward)
    signed = np.where(forward, a[:, 2], -a[:, 2])[sel]
    order = np.argsort(signed, kind="stable")
    return signed[order], d.brdf[sel, wavelength_index_][order]


def _curves(models, params, wavelength, labels, fit, theta_i):
    out = []
    for k, m in enumerate(models):
        label = None
        if is_model_file(m):
            m, label, _ = model_file(m, fit)
        p = params[k] if isinstance(params, (list, tuple)) else params
        phi_r = np.where(_SIGNED >= 0, 180.0, 0.0)
        f, wl, name = evaluate(m, p, wavelength, theta_i, 0.0, np.abs(_SIGNED), phi_r)
        label = labels[k] if k < len(labels) else (label or name)
        out.append((label + (f" ({wl:g} nm)" if wl and isinstance(m, SpectralModel) else ""), (_SIGNED, np.asarray(f))))
    return out


@dataset_options
def plane(models=(), samples=(), theta_i=45.0, params=None, wavelength=None, labels=None, title=None, output=None,
          *, log=False, cartesian=False, fit=None, ax=None, fig=None, dpi=None):
    """BRDF in the plane of incidence for an incidence theta_i [deg] or several (one panel each): theta_r from
    -90 (backward, source side) to +90 (forward, specular side), report section 4.1.2 style.

    ``models``: model names, :class:`Model`, :class:`SpectralModel` or fit / MIX.json files (``fit``: which
    member; ``params`` apply to plain models, one dict or one per model); ``samples``: datasets whose in-plane
    points are drawn as markers, at their band nearest to ``wavelength`` (default 550 nm or the middle); the
    spectral models are evaluated at that band (without datasets: at ``wavelength``). ``log``: logarithmic
    radius (or y axis) with labelled decades; otherwise the radius starts at 0. ``cartesian``: BRDF against
    signed theta_r. ``ax``: one axis per incidence (polar unless ``cartesian``), or ``fig`` to draw into.

    ``fig.roadbrdf_data``: {label: (signed theta_r [deg], BRDF [sr^-1])}; several incidences:
    {theta_i: {label: ...}}.
    """
    angles = incidences(theta_i)
    models = list(models)
    datasets = []
    for s in ([samples] if isinstance(samples, str) else list(samples)):
        if is_model_file(s):
            models.append(s)
        else:
            datasets.append((as_dataset(s), s))
    if not models and not datasets:
        raise ValueError("plane: give a model, a fit file, a mixture or a dataset")
    labels = [plain(x) for x in labels or []]
    if datasets:
        d0 = datasets[0][0]
        wavelength = float(d0.wavelengths[wavelength_index(d0.wavelengths, wavelength)[0]])
    per_incidence = []
    for t in angles:
        curves = _curves(models, params, wavelength, labels, fit, t)
        for k, (d, src) in enumerate(datasets):
            band, _ = wavelength_index(d.wavelengths, wavelength)
            name = sample_label(d, src, f"sample {k + 1}")
            x, y = in_plane_points(d, t, band, name)
            curves.append((f"{name} measured ({d.wavelengths[band]:g} nm)", (x, y)))
        per_incidence.append((t, curves))
    every = np.concatenate([y for _, curves in per_incidence for _, (_, y) in curves])
    floor = decade_floor(every)  # a logarithmic radius is shared by the panels; a linear one is each panel's
    n = len(angles)
    fig, axes = panels([None if cartesian else "polar"] * n, ax=ax, fig=fig, ncols=min(n, 4) if cartesian else (n if n <= 3 else -(-n // 2)),
                       size=(5.6, 4.6) if not cartesian else (5.0, 4.0), what="incidences")
    measured_labels = {lab for _, curves in per_incidence for lab, _ in curves if " measured (" in lab}
    for axis, (t, curves) in zip(axes, per_incidence):
        values = np.concatenate([y for _, (_, y) in curves])
        top = float(np.nanmax(values)) if values.size and np.isfinite(values).any() else 1.0
        for j, (label, (x, y)) in enumerate(curves):
            style = dict(ls="none", marker="o", ms=5) if label in measured_labels else dict(lw=1.5)
            if cartesian:
                axis.plot(x, y, color=f"C{j}", label=label, **style)
            else:
                axis.plot(np.radians(x), log_radius(y, floor) if log else y, color=f"C{j}", label=label, **style)
        if cartesian:
            axis.set_xlim(-90, 90)
            if log:
                axis.set_yscale("log")
                axis.set_ylabel(unit_label() + ", logarithmic")
            else:
                axis.set_ylim(0, top * 1.05)
                axis.set_ylabel(unit_label())
            for where, text in ((-t, "retro"), (t, "specular")):
                axis.axvline(where, color="gray", lw=0.8, ls=":")
                axis.text(where, 0.98, f" {text}", transform=axis.get_xaxis_transform(), fontsize=7, color="gray",
                          va="top")
            axis.set_xlabel("signed $\\theta_r$ [deg]  (− backward, source side; + forward, specular side)",
                            fontsize=8)
            axis.grid(alpha=0.3)
        else:
            axis.set_thetamin(-90)
            axis.set_thetamax(90)
            axis.set_theta_zero_location("N")
            axis.set_theta_direction(-1)
            if log:
                label_log_radius(axis, floor, float(np.nanmax(log_radius(every, floor))))
                axis.set_xlabel(f"radius: {unit_label()}, logarithmic (centre {floor:g})", fontsize=8)
            else:
                axis.set_rlim(0, top * 1.05)
                axis.yaxis.set_major_locator(mticker.MaxNLocator(4))
                axis.tick_params(axis="y", labelsize=7)
                axis.set_xlabel("radius: " + unit_label() + " (from 0)", fontsize=8)
            axis.set_rlabel_position(0)
            axis.text(0.02, 0.98, "backward\n(source side)", transform=axis.transAxes, ha="left", va="top",
                      fontsize=8)
            axis.text(0.98, 0.98, "forward\n(specular side)", transform=axis.transAxes, ha="right", va="top",
                      fontsize=8)
        axis.set_title(f"$\\theta_i$ = {t:g}°" + ("" if cartesian else " (angle: $\\theta_r$)"), fontsize=10)
    axes[-1].legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.2 if cartesian else -0.05),
                    frameon=False)
    fig.suptitle(plain_title(title) or "BRDF in the plane of incidence" + (f", {wavelength:g} nm" if wavelength else ""))
    if n == 1:
        data = dict(per_incidence[0][1])
    else:
        data = {t: dict(curves) for t, curves in per_incidence}
    return finish(fig, output, data, axes, dpi)
