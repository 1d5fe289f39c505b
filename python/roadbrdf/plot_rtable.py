"""Road r-table figure (``roadbrdf plot rtable``): the r-table heat map (10^4 r over beta and tan gamma) and
the sample's (S1, Q0) among the CIE R classes, the class diagram's range following the sample's S1."""

from __future__ import annotations

import math
import os
import textwrap

import matplotlib.colors as mcolors
import numpy as np

from . import Model, RTable, SpectralModel, read_rtable
from . import rtable as _rtable
from .plot_common import finish, is_model_file, panels, plain_title, stem

__all__ = ["rtable", "CLASS_R"]

#: CIE R classes: name, S1 limits and the (S1, Q0) of the standard table of each class (van Bommel,
#: Road Lighting, Table 12.2; the bundled standard tables reproduce these S1 values).
CLASS_R = [("R1", 0.0, 0.42, 0.25, 0.10), ("R2", 0.42, 0.85, 0.58, 0.07), ("R3", 0.85, 1.35, 1.11, 0.07),
           ("R4", 1.35, np.inf, 1.55, 0.08)]


def class_diagram_range(s1, q0):
    """(S1 upper limit, Q0 upper limit) of the class diagram: the four classes, and the sample with room."""
    s1_top = max(2.5, 1.15 * float(s1)) if s1 is not None and np.isfinite(s1) else 2.5
    q0_top = max(0.15, 1.3 * float(q0)) if q0 is not None and np.isfinite(q0) else 0.15
    return s1_top, q0_top


def _pm(value, u, decimals):
    """``value ± u`` with u to two significant digits and the value to the same decimal place (GUM 7.2.6);
    ``decimals`` when u is zero or not finite."""
    if u is not None and math.isfinite(u) and u > 0:
        decimals = min(max(decimals, 1 - math.floor(math.log10(u))), 8)
    return f"{value:.{decimals}f} ± {u:.{decimals}f}"


def _error_bars(t):
    """The standard uncertainties of S1 and Q0 to draw, with the class probabilities; None when the table has
    none or they are undefined (null)."""
    u = t.get("uncertainty")
    if t.get("extrapolated") or not isinstance(u, dict) or u.get("S1") is None or u.get("Q0") is None:
        # A table all of whose standard-region cells are extrapolated: the fit's covariance does not describe
        # them (photometry/rtable_coverage.h), so no bars and no class probability.
        return None
    classes = [(c["class"], float(c["probability"])) for c in (u.get("class_probabilities") or [])]
    return {"S1": float(u["S1"]), "Q0": float(u["Q0"]), "class_probabilities": classes}


def rtable(table, params=None, title=None, output=None, wavelength=None, band=None, illuminant="", *, fit=None,
           ax=None, fig=None, dpi=None):
    """r-table heat map (10^4 r over beta and tan gamma, missing cells blank) and the sample's (S1, Q0) among
    the CIE R classes with the standard tables' points.

    ``table``: an :class:`roadbrdf.RTable` (dict), an r-table file, a fit or MIX.json file (``fit``: which
    member), a :class:`SpectralModel`, or a :class:`Model` (with ``params``). A spectral model is reduced as
    :func:`roadbrdf.rtable` does: photometrically under ``illuminant``, at one ``wavelength`` [nm], or averaged
    over ``band`` = (lo, hi) [nm]; a single-band fit is taken at its band. ``ax``: two axes, or ``fig``.

    When the table has standard uncertainties (from the covariance of a fit, or of a mixture from its
    end-members' fits: ``uncertainty``), the sample's point carries error bars u(S1), u(Q0) (k = 1, wavelengths
    independent) and the legend the class probabilities; a table whose standard region is all extrapolated
    (``extrapolated``) has neither, and its legend says "extrapolated".

    ``fig.roadbrdf_data``: the r-table (``r``, ``beta_deg``, ``tan_gamma``, ``Q0``, ``S1``, ``class``,
    ``uncertainty``, ...), ``diagram_range`` = (S1 upper limit, Q0 upper limit) and ``error_bars`` = {``S1``,
    ``Q0``: the standard uncertainties drawn, ``class_probabilities``: [(class, probability)]} or None.
    """
    spectral_choice = wavelength is not None or band is not None
    name = None
    if isinstance(table, dict):
        t = table
    elif isinstance(table, Model):
        if spectral_choice:
            raise ValueError("wavelength/band need a fit file: a model with constant parameters has no spectrum")
        t = _rtable(table, params)
    elif isinstance(table, SpectralModel) or is_model_file(table):
        if is_model_file(table):
            name = stem(table)
            if fit:
                from . import read_fit
                table = read_fit(table, fit)
        t = _rtable(table, illuminant=illuminant, wavelength=wavelength, band=band)
    else:
        if spectral_choice:
            raise ValueError("wavelength/band apply to a fit file, not to an r-table file")
        name = stem(table)
        t = read_rtable(table)
    t = RTable(t)  # a copy: the caller's table is not changed
    r = np.asarray(t["r"], dtype=float) * 1e4
    fig, axes = panels([None, None], ax=ax, fig=fig, size=(6.2, 4.8), what="panels (r-table, class diagram)")
    axis = axes[0]
    masked = np.ma.masked_invalid(r)
    positive = r[np.isfinite(r) & (r > 0)]
    norm = mcolors.LogNorm(vmin=positive.min(), vmax=positive.max()) if positive.size else None
    im = axis.imshow(masked, aspect="auto", cmap="magma", origin="lower", norm=norm)
    axis.set_xticks(range(len(t["beta_deg"])))
    axis.set_xticklabels([f"{b:g}" for b in t["beta_deg"]], fontsize=7, rotation=90)
    axis.set_yticks(range(0, len(t["tan_gamma"]), 2))
    axis.set_yticklabels([f"{x:g}" for x in t["tan_gamma"][::2]], fontsize=7)
    axis.set_xlabel("$\\beta$ [deg]")
    axis.set_ylabel("tan $\\gamma$")
    fig.colorbar(im, ax=axis).set_label("$10^4\\,r$ [sr$^{-1}$]")
    model = os.path.basename(str(t.get("name", "")))
    weighting = (t.get("weighting") or {}) if isinstance(t.get("weighting"), dict) else {}
    how = ""
    if wavelength is not None:
        how = f", at {wavelength:g} nm"
    elif band is not None:
        how = f", mean over {band[0]:g}-{band[1]:g} nm"
    elif weighting.get("illuminant"):
        how = f", V($\\lambda$) x illuminant {weighting['illuminant']}"
    axis.set_title(f"{model}  ($\\alpha$ = {t['alpha_deg']:g}°{how}; blank = not defined)", fontsize=9)
    axis = axes[1]
    s1, q0 = t.get("S1"), t.get("Q0")
    s1_top, q0_top = class_diagram_range(s1, q0)
    for k, (cls, lo, hi, s1_standard, q0_standard) in enumerate(CLASS_R):
        hi = min(hi, s1_top)
        axis.axvspan(lo, hi, alpha=0.12, color=f"C{k}")
        axis.text((lo + hi) / 2, 0.03 * q0_top, cls, ha="center", fontsize=9)
        axis.plot([s1_standard], [q0_standard], "s", color="gray", ms=6)
        axis.annotate(f"standard {cls}", (s1_standard, q0_standard), textcoords="offset points", xytext=(0, 7),
                      ha="center", fontsize=7, color="gray")
    bars = _error_bars(t)
    if s1 is not None and q0 is not None:
        label = f"this surface: S1 = {s1:.2f}, Q0 = {q0:.3f} sr$^{{-1}}$" + (
            f", class {t['class']}" if t.get("class") else "")
        if t.get("extrapolated"):
            label += "\nextrapolated (no standard-region cell measured)"
        if bars:
            label = (f"this surface: S1 = {_pm(s1, bars['S1'], 2)}, Q0 = {_pm(q0, bars['Q0'], 3)} sr$^{{-1}}$"
                     + (f", class {t['class']}" if t.get("class") else ""))
            axis.errorbar([s1], [q0], xerr=[bars["S1"]], yerr=[bars["Q0"]], fmt="none", ecolor="red", capsize=3,
                          elinewidth=1.0)
            if bars["class_probabilities"]:
                label += "\nP(class): " + ", ".join(f"{c} {p:.2f}" for c, p in bars["class_probabilities"])
        axis.plot([s1], [q0], "r*", ms=14, label=label)
        axis.legend(fontsize=8, loc="upper right")
    axis.set_xlim(0, s1_top)
    axis.set_ylim(0, q0_top)
    axis.set_xlabel("S1 = r(0, 2) / r(0, 0) [1]")
    axis.set_ylabel("Q0 [sr$^{-1}$]")
    axis.set_title("CIE R classes (■ the standard tables)", fontsize=10)
    label = name if name and name != model else None
    fig.suptitle(plain_title(title) or "Road r-table: " + (f"{label} ({model})" if label else model or "table"))
    if t.get("note"):
        fig.supxlabel(textwrap.fill(t["note"], 150), fontsize=8, color="gray")
    t["diagram_range"] = (s1_top, q0_top)
    t["error_bars"] = bars
    return finish(fig, output, t, axes, dpi)
