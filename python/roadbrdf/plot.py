"""Publication figures for roadbrdf (matplotlib).

Every function returns the matplotlib Figure it drew and, when ``output`` is given, saves it
(PNG, SVG or PDF from the extension, written atomically). The same figures are available from the
command line as ``roadbrdf plot KIND ... -o FILE`` (``python3 -m roadbrdf.plot KIND ...``).

Kinds:

* :func:`spectral` - BRDF against wavelength at one geometry for several samples, with uncertainty bands;
* :func:`hemisphere` - BRDF over the viewing hemisphere for one incidence: polar heat map and 3-D lobe;
* :func:`plane` - BRDF in the plane of incidence (negative theta_r on the backward side), measured
  points against models;
* :func:`fit_quality` - measured vs fitted values per geometry with residuals, and RMSE vs wavelength;
* :func:`albedo` - black-sky albedo vs sun zenith, spectral albedo, blue-sky albedo for several aerosol loads;
* :func:`rtable` - r-table heat map, and the sample's (S1, Q0) among the standard classes;
* ``plot_params.params`` - fitted parameters ± standard error against wavelength or a group column.

Angles in degrees, BRDF in sr^-1, wavelengths in nm.
"""

from __future__ import annotations

import argparse
import os
import textwrap
import tempfile

import numpy as np

import matplotlib

if os.environ.get("MPLBACKEND") is None and not os.environ.get("DISPLAY"):
    matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

from . import Dataset, Model, SpectralModel, read_dataset, read_fit, read_rtable  # noqa: E402
from . import rtable as _rtable  # noqa: E402

__all__ = ["spectral", "hemisphere", "plane", "fit_quality", "albedo", "rtable", "save"]

_UNIT = "BRDF [sr$^{-1}$]"


def save(fig, output):
    """Save a figure atomically (temporary file in the same folder, then rename)."""
    output = os.fspath(output)
    folder = os.path.dirname(os.path.abspath(output))
    suffix = os.path.splitext(output)[1]
    fd, tmp = tempfile.mkstemp(prefix=".roadbrdf-plot-", suffix=suffix, dir=folder)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=150, bbox_inches="tight")
        os.replace(tmp, output)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return output


def _finish(fig, output):
    if output is not None:
        save(fig, output)
    return fig


def _as_dataset(x):
    return x if isinstance(x, Dataset) else read_dataset(x)


def _label(d: Dataset, fallback: str):
    return d.metadata.get("sample", fallback)


# ---- 1. spectral BRDF ------------------------------------------------------------------------
def spectral(samples, geometry=(30.0, 0.0, 30.0, 0.0), labels=None, title=None, output=None):
    """BRDF against wavelength at one geometry for several datasets (paths or :class:`Dataset`).

    ``geometry`` = (theta_i, phi_i, theta_r, phi_r) [deg] or text (plot_geometry.parse_geometry: also road
    angles); each dataset's nearest geometry (plot_geometry.nearest_geometry: up to a turn about the
    normal) is used and named in the legend, with its distance when above 1 deg (also on standard
    error). Uncertainty bands (+-1 sigma) are drawn when the data have sigma. Returns the figure; the
    plotted curves are in ``fig.roadbrdf_data`` (label -> (wavelengths, brdf)), the geometries used
    and their distances in ``fig.roadbrdf_geometries`` (label -> (angles, distance_deg)).
    """
    import sys
    from .plot_geometry import TOLERANCE_DEG, nearest_geometry, parse_geometry
    if isinstance(geometry, str):
        geometry = parse_geometry(geometry)
    datasets = [_as_dataset(s) for s in samples]
    labels = labels or [_label(d, f"sample {k + 1}") for k, d in enumerate(datasets)]
    fig, ax = plt.subplots(figsize=(8, 4.5))
    fig.roadbrdf_data, fig.roadbrdf_geometries = {}, {}
    for d, label in zip(datasets, labels):
        k, distance = nearest_geometry(d.angles, geometry)
        ti, pi, tr, pr = d.angles[k]
        y = d.brdf[k]
        far = ""
        if distance > TOLERANCE_DEG:
            far = f", {distance:.1f}° from the geometry asked for"
            print(f"roadbrdf: warning: {label}: the nearest measured geometry ({ti:g}, {pi:g}, {tr:g}, {pr:g}) is "
                  f"{distance:.1f} deg from the one asked for {tuple(float(x) for x in geometry)}", file=sys.stderr)
        fig.roadbrdf_geometries[label] = (tuple(float(x) for x in d.angles[k]), distance)
        line, = ax.plot(d.wavelengths, y, lw=1.4,
                        label=f"{label}  ($\\theta_i$={ti:.0f}°, $\\theta_r$={tr:.0f}°, "
                              f"$\\Delta\\phi$={(pr - pi) % 360:.0f}°{far})")
        if d.sigma is not None:
            ax.fill_between(d.wavelengths, y - d.sigma[k], y + d.sigma[k], color=line.get_color(), alpha=0.25, lw=0)
        fig.roadbrdf_data[label] = (d.wavelengths, y)
    ax.set_xlabel("wavelength [nm]")
    ax.set_ylabel(_UNIT)
    ax.set_xlim(min(d.wavelengths[0] for d in datasets), max(d.wavelengths[-1] for d in datasets))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="upper center", bbox_to_anchor=(0.5, -0.14), ncol=1, frameon=False)
    ax.set_title(title or "Spectral BRDF (bands: $\\pm1\\sigma$)")
    return _finish(fig, output)


# ---- helpers for models --------------------------------------------------------------------------
def _default_wavelength_index(wavelengths, wavelength):
    """Index of ``wavelength`` [nm], or of 550 nm (else the middle) when not given."""
    wavelengths = np.asarray(wavelengths)
    if wavelength is None:
        wavelength = 550.0 if wavelengths[0] <= 550.0 <= wavelengths[-1] else wavelengths[wavelengths.size // 2]
    return int(np.argmin(np.abs(wavelengths - wavelength)))


def _evaluate(model, params, wavelength, ti, pi, tr, pr):
    if isinstance(model, (str, os.PathLike)) and str(model).endswith(".json"):
        model = read_fit(model)
    if isinstance(model, SpectralModel):
        if wavelength is None:
            wavelength = float(model.wavelengths[_default_wavelength_index(model.wavelengths, None)])
        return model.evaluate(ti, pi, tr, pr, wavelength), wavelength
    if isinstance(model, str):
        model = Model(model)
    return model.evaluate(ti, pi, tr, pr, params=params or {}), None


# ---- 2. hemisphere -------------------------------------------------------------------------------
def hemisphere(model, params=None, theta_i=45.0, wavelength=None, log=False, resolution=90, title=None, output=None):
    """BRDF over the viewing hemisphere for an incidence theta_i [deg] (source at phi_i = 0):
    a polar heat map (radius = theta_r, angle = phi_r) and a 3-D lobe (radius = BRDF).

    ``model``: a :class:`Model` (with ``params``), a model name, a :class:`SpectralModel` or a fit file
    (then at ``wavelength`` [nm], default the middle of its range).
    """
    tr = np.linspace(0.0, 89.5, resolution)
    pr = np.linspace(0.0, 360.0, 4 * resolution + 1)
    TR, PR = np.meshgrid(tr, pr, indexing="ij")
    f, wavelength = _evaluate(model, params, wavelength, theta_i, 0.0, TR, PR)
    fig = plt.figure(figsize=(11, 4.8))
    ax = fig.add_subplot(1, 2, 1, projection="polar")
    values = np.log10(np.maximum(f, 1e-6)) if log else f
    ax.grid(False)
    mesh = ax.pcolormesh(np.radians(PR), TR, values, shading="auto", cmap="viridis")
    ax.set_rlim(0, 90)
    ax.set_rticks([30, 60, 90])
    ax.grid(True, alpha=0.3)
    ax.set_yticklabels(["30°", "60°", "90°"], fontsize=7)
    ax.plot([np.pi], [theta_i], marker="*", color="w", ms=10, mec="k")  # specular direction
    ax.plot([0.0], [theta_i], marker="o", color="r", ms=6, mec="k")       # retro direction (source)
    cbar = fig.colorbar(mesh, ax=ax, pad=0.1)
    cbar.set_label("log$_{10}$ " + _UNIT if log else _UNIT)
    ax.set_title(f"viewing hemisphere, $\\theta_i$ = {theta_i:g}°\n(radius $\\theta_r$, angle $\\phi_r$; "
                 "● source side, ★ mirror)", fontsize=9)
    ax3 = fig.add_subplot(1, 2, 2, projection="3d")
    t, p = np.radians(TR), np.radians(PR)
    x, y, z = f * np.sin(t) * np.cos(p), f * np.sin(t) * np.sin(p), f * np.cos(t)
    norm = plt.Normalize(np.nanmin(f), np.nanmax(f))
    ax3.plot_surface(x, y, z, facecolors=plt.cm.viridis(norm(f)), rstride=2, cstride=4, linewidth=0,
                     antialiased=False, shade=False)
    ax3.set_xlabel("x [sr$^{-1}$]")
    ax3.set_ylabel("y [sr$^{-1}$]")
    ax3.set_zlabel("z [sr$^{-1}$]")
    ax3.set_title("BRDF lobe (radius = BRDF)", fontsize=9)
    name = getattr(model, "name", None) or str(model)
    fig.suptitle(title or (name + (f" at {wavelength:g} nm" if wavelength else "")))
    fig.roadbrdf_data = {"theta_r": tr, "phi_r": pr, "brdf": f}
    return _finish(fig, output)


# ---- 3. plane of incidence -----------------------------------------------------------------------
def plane(models=(), samples=(), theta_i=45.0, params=None, wavelength=None, labels=None, title=None, output=None):
    """BRDF in the plane of incidence for incidence theta_i [deg]: theta_r from -90 (backward,
    source side) to +90 (forward, specular side), report section 4.1.2 style, as a polar plot.

    ``models``: model names, :class:`Model`, :class:`SpectralModel` or fit files (``params`` apply to
    plain models, ``wavelength`` [nm] to spectral ones); ``samples``: datasets whose in-plane points
    at this incidence are drawn as markers (at ``wavelength``, default their middle wavelength).
    """
    fig = plt.figure(figsize=(7, 5.5))
    ax = fig.add_subplot(1, 1, 1, projection="polar")
    ax.set_thetamin(-90)
    ax.set_thetamax(90)
    ax.set_theta_zero_location("N")
    ax.set_theta_direction(-1)
    angles = np.linspace(-89.5, 89.5, 359)
    fig.roadbrdf_data = {}
    labels = list(labels or [])
    for k, m in enumerate(models):
        phi_r = np.where(angles >= 0, 180.0, 0.0)
        f, wl = _evaluate(m, params if not isinstance(params, list) else params[k], wavelength, theta_i, 0.0,
                          np.abs(angles), phi_r)
        label = labels[k] if k < len(labels) else (getattr(m, "name", None) or os.path.basename(str(m)))
        ax.plot(np.radians(angles), f, lw=1.5, label=label + (f" ({wl:g} nm)" if wl else ""))
        fig.roadbrdf_data[label] = (angles, f)
    for k, s in enumerate(samples):
        d = _as_dataset(s)
        wl_index = _default_wavelength_index(d.wavelengths, wavelength)
        a = d.angles
        dphi = (a[:, 3] - a[:, 1]) % 360.0
        forward = np.abs(dphi - 180.0) < 0.5
        backward = (dphi < 0.5) | (dphi > 359.5)
        sel = (np.abs(a[:, 0] - theta_i) < 0.5) & (forward | backward)
        signed = np.where(forward, a[:, 2], -a[:, 2])[sel]  # negative theta_r on the source side
        y = d.brdf[sel, wl_index]
        label = _label(d, f"sample {k + 1}") + f" (measured, {d.wavelengths[wl_index]:g} nm)"
        ax.plot(np.radians(signed), y, "o", ms=5, label=label)
        fig.roadbrdf_data[label] = (signed, y)
    ax.yaxis.set_major_locator(matplotlib.ticker.MaxNLocator(4))
    ax.tick_params(axis="y", labelsize=7)
    ax.set_rlabel_position(0)
    ax.set_xlabel("radius: " + _UNIT)
    ax.text(np.radians(-60), ax.get_rmax() * 1.25, "backward\n(source side)", ha="center", fontsize=8)
    ax.text(np.radians(60), ax.get_rmax() * 1.25, "forward\n(specular side)", ha="center", fontsize=8)
    ax.legend(fontsize=8, loc="lower center", bbox_to_anchor=(0.5, -0.32))
    ax.set_title(title or f"Plane of incidence, $\\theta_i$ = {theta_i:g}° (angle: $\\theta_r$)")
    return _finish(fig, output)


# ---- 4. fit quality ------------------------------------------------------------------------------
def fit_quality(data, fit, model=None, wavelength=None, title=None, output=None):
    """Measured vs fitted BRDF per geometry (with residuals) at one wavelength, and RMSE against
    wavelength for every model of the fit file.

    ``data``: the dataset that was fitted; ``fit``: the fit file (JSON written by ``roadbrdf fit``);
    ``model``: which fit of the file (default: the best).
    """
    import json
    d = _as_dataset(data)
    with open(fit) as fh:
        fits = json.load(fh)
    chosen = model or fits["best"]
    spectral_model = read_fit(fit, chosen)
    wl_index = _default_wavelength_index(d.wavelengths, wavelength)
    wl = float(d.wavelengths[wl_index])
    a = d.angles
    predicted = spectral_model.evaluate(a[:, 0], a[:, 1], a[:, 2], a[:, 3], wl)
    measured = d.brdf[:, wl_index]
    fig, axes = plt.subplots(1, 3, figsize=(14, 4.3))
    ax = axes[0]
    positive = (measured > 0) & (predicted > 0)
    ax.loglog(measured[positive], predicted[positive], "o", ms=4)
    lo = min(measured[positive].min(), predicted[positive].min()) * 0.8
    hi = max(measured[positive].max(), predicted[positive].max()) * 1.25
    ax.plot([lo, hi], [lo, hi], "k--", lw=0.8, label="1:1")
    ax.set_xlabel("measured " + _UNIT)
    ax.set_ylabel("fitted " + _UNIT)
    ax.set_title(f"{chosen} at {wl:g} nm")
    ax.legend(fontsize=8)
    ax = axes[1]
    order = np.argsort(a[:, 0] * 1000 + a[:, 2])
    ax.bar(np.arange(len(order)), (predicted - measured)[order], width=0.8)
    ax.axhline(0, color="k", lw=0.8)
    ax.set_xlabel("geometry (sorted by $\\theta_i$, then $\\theta_r$)")
    ax.set_ylabel("fitted $-$ measured [sr$^{-1}$]")
    ax.set_title("residuals")
    ax = axes[2]
    for f in fits["fits"]:
        ax.plot(f["wavelengths"], f["rmse"], lw=1.2, label=f["model"])
    ax.set_xlabel("wavelength [nm]")
    ax.set_ylabel("RMSE [sr$^{-1}$]")
    ax.set_yscale("log")
    ax.set_title("RMSE vs wavelength")
    ax.legend(fontsize=7)
    fig.suptitle(title or f"Fit quality: {_label(d, os.path.basename(str(data)))}")
    fig.tight_layout()
    fig.roadbrdf_data = {"measured": measured, "fitted": predicted, "wavelength": wl}
    return _finish(fig, output)


# ---- 5. albedo -----------------------------------------------------------------------------------
def albedo(result, title=None, output=None):
    """Albedo figure from the JSON of ``roadbrdf albedo --json`` (a dict or a path): spectral
    black-, white- and blue-sky albedo, and black-sky albedo against sun zenith when tabulated."""
    import json
    if not isinstance(result, dict):
        with open(result) as fh:
            result = json.load(fh)
    wl = np.asarray(result["wavelengths"], dtype=float)
    fig, axes = plt.subplots(1, 2, figsize=(12, 4.3))
    ax = axes[0]
    bs = np.asarray(result["black_sky"], dtype=float)
    zen = np.atleast_1d(np.asarray(result.get("sun_zenith_deg", result.get("sun_zenith", [np.nan])), dtype=float))
    if bs.ndim == 1:
        bs = bs[None, :]
    # A few bands (or one) are drawn as points: a line through them would suggest a spectrum.
    marker = "o" if wl.size < 8 else None
    for k in range(bs.shape[0]):
        ax.plot(wl, bs[k], lw=1.2, marker=marker, label=f"black-sky, sun zenith {zen[min(k, zen.size - 1)]:g}°")
    ax.plot(wl, np.asarray(result["white_sky"], dtype=float), "k", lw=1.6, marker=marker, label="white-sky")
    if result.get("blue_sky") is not None:
        blue = np.asarray(result["blue_sky"], dtype=float)
        blue = blue[0] if blue.ndim > 1 else blue
        ax.plot(wl, blue, "b--", lw=1.4, marker=marker, label=f"blue-sky, sun zenith {zen[0]:g}°")
    if wl.size == 1:
        ax.set_xlim(wl[0] - 50.0, wl[0] + 50.0)
    ax.set_xlabel("wavelength [nm]")
    ax.set_ylabel("albedo [1]")
    ax.legend(fontsize=7)
    ax.grid(alpha=0.3)
    ax.set_title("spectral albedo")
    ax = axes[1]
    broadband = result.get("broadband")
    bb = np.atleast_1d(np.asarray((broadband or {}).get("black_sky", []), dtype=float))
    if broadband is None:
        # Not formed (e.g. a single-band fit): say why, from the report's notes.
        ax.axis("off")
        notes = [n for n in result.get("notes", []) if "omitted" in n] or ["no broadband values"]
        ax.text(0.05, 0.5, "broadband albedo omitted:\n" + "\n".join(textwrap.fill(n, 60) for n in notes),
                fontsize=9, va="center")
    elif bb.size == zen.size and bb.size > 1:
        ax.plot(zen, bb, "o-", label="black-sky (broadband)")
        ax.axhline(float(np.atleast_1d(broadband.get("white_sky"))[0]), color="k", lw=1.2, label="white-sky")
        ax.set_xlabel("sun zenith angle [deg]")
        ax.set_ylabel("solar-weighted albedo [1]")
        ax.legend(fontsize=8)
        ax.grid(alpha=0.3)
        ax.set_title("broadband albedo vs sun zenith")
    else:
        ax.axis("off")
        text = "\n".join(f"{k}: {np.atleast_1d(v)[0]:.4f}" for k, v in broadband.items()
                         if isinstance(v, (int, float, list)))
        ax.text(0.05, 0.5, "broadband albedo\n" + text, fontsize=11, va="center")
    fig.suptitle(title or "Albedo")
    fig.roadbrdf_data = result
    return _finish(fig, output)


# ---- 6. r-table ------------------------------------------------------------------------------
# CIE R classes: S1 limits and the (S1, Q0) of the standard table of each class (van Bommel,
# Road Lighting, Table 12.2; the bundled standard tables reproduce these S1 values).
_CLASS_R = [("R1", 0.0, 0.42, 0.25, 0.10), ("R2", 0.42, 0.85, 0.58, 0.07), ("R3", 0.85, 1.35, 1.11, 0.07),
            ("R4", 1.35, 2.5, 1.55, 0.08)]


def rtable(table, params=None, title=None, output=None, wavelength=None, band=None, illuminant=""):
    """r-table heat map (10^4 r over beta and tan gamma, missing cells blank) and the sample's
    (S1, Q0) among the CIE R classes with the standard tables' points.

    ``table``: an :class:`roadbrdf.RTable`, an r-table file, a fit or MIX.json file, a
    :class:`SpectralModel`, or a :class:`Model` (with ``params``). A spectral model is reduced as
    :func:`roadbrdf.rtable` does: photometrically under ``illuminant``, at one ``wavelength`` [nm], or
    averaged over ``band`` = (lo, hi) [nm]; a single-band fit is taken at its band.
    """
    spectral_choice = wavelength is not None or band is not None
    if isinstance(table, dict):
        t = table
    elif isinstance(table, Model):
        if spectral_choice:
            raise ValueError("wavelength/band need a fit file: a model with constant parameters has no spectrum")
        t = _rtable(table, params)
    elif isinstance(table, SpectralModel) or str(table).endswith(".json"):
        t = _rtable(table, illuminant=illuminant, wavelength=wavelength, band=band)
    else:
        if spectral_choice:
            raise ValueError("wavelength/band apply to a fit file, not to an r-table file")
        t = read_rtable(table)
    r = np.asarray(t["r"], dtype=float) * 1e4
    fig, axes = plt.subplots(1, 2, figsize=(13, 4.8), gridspec_kw={"width_ratios": [1.4, 1]})
    ax = axes[0]
    masked = np.ma.masked_invalid(r)
    positive = r[np.isfinite(r) & (r > 0)]
    norm = matplotlib.colors.LogNorm(vmin=positive.min(), vmax=positive.max()) if positive.size else None
    im = ax.imshow(masked, aspect="auto", cmap="magma", origin="lower", norm=norm)
    ax.set_xticks(range(len(t["beta_deg"])))
    ax.set_xticklabels([f"{b:g}" for b in t["beta_deg"]], fontsize=7, rotation=90)
    ax.set_yticks(range(0, len(t["tan_gamma"]), 2))
    ax.set_yticklabels([f"{x:g}" for x in t["tan_gamma"][::2]], fontsize=7)
    ax.set_xlabel("$\\beta$ [deg]")
    ax.set_ylabel("tan $\\gamma$")
    fig.colorbar(im, ax=ax).set_label("$10^4\\,r$ [sr$^{-1}$]")
    ax.set_title(f"{os.path.basename(str(t.get('name', '')))}  ($\\alpha$ = {t['alpha_deg']:g}°; blank = not defined)", fontsize=10)
    ax = axes[1]
    for k, (name, lo, hi, s1_standard, q0_standard) in enumerate(_CLASS_R):
        ax.axvspan(lo, hi, alpha=0.12, color=f"C{k}")
        ax.text((lo + hi) / 2, 0.005, name, ha="center", fontsize=9)
        ax.plot([s1_standard], [q0_standard], "s", color="gray", ms=6)
        ax.annotate(f"standard {name}", (s1_standard, q0_standard), textcoords="offset points", xytext=(0, 7),
                    ha="center", fontsize=7, color="gray")
    if t.get("S1") is not None and t.get("Q0") is not None:
        ax.plot([t["S1"]], [t["Q0"]], "r*", ms=14, label=f"this surface: S1 = {t['S1']:.2f}, Q0 = {t['Q0']:.3f}")
    ax.set_xlim(0, 2.5)
    ax.set_ylim(0, max(0.15, (t.get("Q0") or 0) * 1.3))
    ax.set_xlabel("S1 = r(0, 2) / r(0, 0)")
    ax.set_ylabel("Q0 [sr$^{-1}$]")
    ax.legend(fontsize=8, loc="upper right")
    ax.set_title("CIE R classes (■ the standard tables)", fontsize=10)
    fig.suptitle(title or "Road r-table")
    if t.get("note"):
        fig.text(0.5, 0.005, t["note"], ha="center", va="bottom", fontsize=8, color="gray")
    fig.tight_layout()
    fig.roadbrdf_data = t
    return _finish(fig, output)


# ---- command line ----------------------------------------------------------------------------
class _Parser(argparse.ArgumentParser):
    """argparse with the errors of the roadbrdf program: ``roadbrdf: error: ...`` naming the nearest
    valid sub-command or option (the same edit-distance helper as the C++ program)."""

    def error(self, message):
        import re
        from . import _roadbrdf
        hint = ""
        unknown = re.search(r"unrecognized arguments: (\S+)", message)
        choice = re.search(r"invalid choice: '([^']*)' \(choose from (.*)\)", message)
        if unknown:
            word = unknown.group(1).split("=")[0]
            names = [o for a in self._all_actions() for o in a.option_strings]
            message = f"unknown option '{word}' of '{self.prog}'"
            hint = _roadbrdf.did_you_mean(word, names)
        elif choice:
            word = choice.group(1)
            names = re.findall(r"'([^']*)'", choice.group(2))
            message = f"unknown kind of figure '{word}' (one of {', '.join(names)})"
            hint = _roadbrdf.did_you_mean(word, names)
        self.exit(2, f"roadbrdf: error: {message}{hint}; see '{self.prog} --help'\n")

    def _all_actions(self):
        actions = list(self._actions)
        for a in self._actions:
            if isinstance(a, argparse._SubParsersAction):
                for parser in a.choices.values():
                    actions += parser._actions
        return actions


def _assignments(items, what, number):
    """``NAME=VALUE`` items of a repeatable option; ``number``: values are finite floats."""
    out = {}
    for item in items or []:
        name, eq, value = item.partition("=")
        if not eq or not name:
            raise ValueError(f"{what} expects NAME=VALUE, got '{item}'")
        if name in out:
            raise ValueError(f"{what} {name} is given twice")
        if number:
            try:
                v = float(value)
            except ValueError:
                v = float("nan")
            if not np.isfinite(v):
                raise ValueError(f"{what} {name}: '{value}' is not a finite number")
            value = v
        out[name] = value
    return out


def _model_argument(text, a):
    """A model name (with -p/--option) or a fit file (with --fit) as the object the figures take."""
    params = _assignments(getattr(a, "parameter", None), "-p", True)
    options = _assignments(getattr(a, "option", None), "--option", False)
    if str(text).endswith(".json"):
        if params or options:
            raise ValueError(f"-p/--option cannot be combined with a fit file ('{text}')")
        return read_fit(text, a.fit), {}
    if a.fit:
        raise ValueError(f"--fit selects a fit of a fit file; '{text}' is a model name")
    return Model(text, options), params


def _renamed(new):
    """An old option spelling, refused with a message naming the new one."""
    class Renamed(argparse.Action):
        def __call__(self, parser, namespace, values, option_string=None):
            raise ValueError(f"{option_string}: renamed: use {new}")
    return Renamed


def main(argv=None):
    """``python3 -m roadbrdf.plot KIND ... -o FILE`` (also ``roadbrdf plot``)."""
    parser = _Parser(prog="roadbrdf plot", description="roadbrdf figures (PNG, SVG or PDF).")
    sub = parser.add_subparsers(dest="kind", required=True, parser_class=_Parser)

    def output(p):
        p.add_argument("-o", "--output", required=True, help="figure file (.png, .svg, .pdf)")
        p.add_argument("--title", help="figure title (default: from the inputs)")

    def model_flags(p, options=True):
        p.add_argument("-p", "--parameter", action="append", metavar="NAME=VALUE",
                       help="model parameter (repeatable); defaults otherwise")
        if options:
            p.add_argument("--option", action="append", metavar="NAME=VALUE",
                           help="model option (repeatable), e.g. distribution=ggx")
        p.add_argument("--fit", metavar="NAME", help="which fit of FIT.json (its model name) or which method of a "
                       "MIX.json (default: the best-ranked)")

    def geometry(text):
        from .plot_geometry import parse_geometry
        try:
            return parse_geometry(text)
        except ValueError as e:
            raise argparse.ArgumentTypeError(str(e)) from None

    p = sub.add_parser("spectral", help="BRDF vs wavelength at one geometry for several datasets")
    p.add_argument("data", nargs="+", help="dataset CSV files")
    p.add_argument("--geometry", type=geometry, default=(30.0, 0.0, 30.0, 0.0),
                   help="theta_i,phi_i,theta_r,phi_r [deg] or gamma=G,alpha=A,beta=B,delta=D (road angles): the "
                        "nearest measured geometry, up to a turn about the normal (default 30,0,30,0)")
    output(p)
    p = sub.add_parser("hemisphere", help="BRDF over the viewing hemisphere (heat map and lobe)")
    p.add_argument("model", help="model name (with -p/--option) or fit file (with --fit)")
    model_flags(p)
    p.add_argument("--theta-i", type=float, default=45.0, help="incidence zenith angle [deg] (default 45)")
    p.add_argument("--wavelength", type=float, help="wavelength [nm] of a fit file (default: 550 or the middle)")
    p.add_argument("--log", action="store_true", help="logarithmic colour scale")
    output(p)
    p = sub.add_parser("plane", help="BRDF in the plane of incidence")
    p.add_argument("--model", action="append", default=[], help="model name or fit file (repeatable)")
    p.add_argument("--data", action="append", default=[], help="dataset (repeatable)")
    model_flags(p)
    p.add_argument("--theta-i", type=float, default=45.0, help="incidence zenith angle [deg] (default 45)")
    p.add_argument("--wavelength", type=float, help="wavelength [nm] of fit files and datasets (default: 550 or the middle)")
    output(p)
    p = sub.add_parser("fit", help="fit quality: measured vs fitted, residuals, RMSE vs wavelength")
    p.add_argument("data", help="the dataset CSV that was fitted")
    p.add_argument("fit_file", metavar="FIT.json", help="fit file written by roadbrdf fit")
    p.add_argument("--fit", metavar="NAME", help="which fit of FIT.json (its model name; default: the best-ranked)")
    p.add_argument("--model", action=_renamed("--fit NAME"), help=argparse.SUPPRESS)
    p.add_argument("--wavelength", type=float, help="wavelength [nm] of the left panels (default: 550 or the middle)")
    output(p)
    p = sub.add_parser("albedo", help="albedo figure from `roadbrdf albedo --json` output")
    p.add_argument("result", help="JSON written by roadbrdf albedo --json")
    output(p)
    p = sub.add_parser("rtable", help="r-table heat map and class diagram")
    p.add_argument("table", help="r-table file, fit file (with --fit) or model name (with -p/--option)")
    model_flags(p)
    p.add_argument("--wavelength", type=float, help="fit file: the r-table at one wavelength [nm]")
    p.add_argument("--band", help="fit file: unweighted mean over a band A:B [nm]")
    p.add_argument("--illuminant", default="", help="fit file: photometric weighting V(lambda) x A (default)|D65|FILE")
    output(p)
    from .plot_study import add_parser as _add_study_parser, run as _run_study  # design studies (plot_study.py)
    from .plot_params import add_parser as _add_params_parser, run as _run_params  # plot_params.py
    _add_study_parser(sub, output)
    _add_params_parser(sub, output)
    a = parser.parse_args(argv)
    # As every roadbrdf command: the figure must not replace one of the files it is drawn from.
    inputs = []
    for role in ("data", "model", "fit_file", "result", "table"):
        value = getattr(a, role, None)
        for path in (value if isinstance(value, list) else [value]):
            if isinstance(path, str):
                inputs.append(("FIT.json" if role == "fit_file" else role.upper(), path))
    from . import _roadbrdf
    _roadbrdf.check_distinct_files(inputs, [("-o", a.output)])
    if a.kind == "spectral":
        spectral(a.data, a.geometry, title=a.title, output=a.output)
    elif a.kind == "hemisphere":
        model, params = _model_argument(a.model, a)
        hemisphere(model, params, a.theta_i, a.wavelength, a.log, title=a.title, output=a.output)
    elif a.kind == "plane":
        chosen = [_model_argument(m, a) for m in a.model]
        params = _assignments(a.parameter, "-p", True)
        plane([m for m, _ in chosen], a.data, a.theta_i, params, a.wavelength,
              labels=[os.path.basename(m) for m in a.model], title=a.title, output=a.output)
    elif a.kind == "fit":
        fit_quality(a.data, a.fit_file, a.fit, a.wavelength, title=a.title, output=a.output)
    elif a.kind == "albedo":
        albedo(a.result, title=a.title, output=a.output)
    elif a.kind == "rtable":
        table = a.table
        if table.endswith(".json") or not os.path.exists(table):
            table, params = _model_argument(table, a)
        else:
            if a.parameter or a.option or a.fit:
                raise ValueError(f"-p/--option/--fit cannot be combined with an r-table file ('{table}')")
            params = {}
        band = None
        if a.band is not None:
            lo, sep, hi = a.band.partition(":")
            if not sep:
                raise ValueError(f"--band expects A:B in nm, got '{a.band}'")
            band = (float(lo), float(hi))
        rtable(table, params, title=a.title, output=a.output, wavelength=a.wavelength, band=band,
               illuminant=a.illuminant)
    elif a.kind == "study":
        _run_study(a)
    elif a.kind == "params":
        _run_params(a)
    print(a.output)
    return 0


if __name__ == "__main__":
    import sys
    try:
        sys.exit(main())
    except ValueError as e:
        print(f"roadbrdf: error: {e}", file=sys.stderr)
        sys.exit(2)
