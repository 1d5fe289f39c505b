"""The figures of the sample report, drawn by the public functions of :mod:`roadbrdf.plot` (and
``roadbrdf.plot_params.params``), each returned as a matplotlib Figure and embedded as PNG.

``draw_all(r)`` fills ``r.figures`` (key -> (PNG bytes, caption)) and ``r.spectral_keys``; a figure that
cannot be drawn is named in ``r.figure_errors`` (shown in the page, and on standard error) rather than
losing the whole report.
"""

from __future__ import annotations

import contextlib
import io
import sys
import warnings

from .report_html import esc, figure_png

__all__ = ["draw_all"]


def _params_function():
    """``params`` of the plotting package: roadbrdf.plot_params today, roadbrdf.plot.params if it moves."""
    try:
        from .plot_params import params
    except ImportError:  # pragma: no cover - the plot package refactored
        from .plot import params
    return params


def _draw(r, key, caption, make):
    """Run ``make()`` (returning a Figure) and keep its PNG; stderr lines of the plot functions (e.g. a
    geometry far from the one asked for) become caveats of the spectral section."""
    stderr = io.StringIO()
    try:
        with contextlib.redirect_stderr(stderr), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fig = make()
        r.figures[key] = (figure_png(fig), caption)
    except Exception as e:  # noqa: BLE001 - one figure must not lose the report
        r.figure_errors[key] = f"{type(e).__name__}: {e}"
        print(f"roadbrdf report: warning: figure '{key}' not drawn: {e}", file=sys.stderr)
        return None
    for line in stderr.getvalue().splitlines():
        if line.strip():
            r.warnings.setdefault("spectra", []).append(line.replace("roadbrdf: warning: ", ""))
    return fig


def _spectral(r):
    """BRDF against wavelength at the mirror, retro and nadir-viewing geometries of the figures' incidence."""
    from . import plot
    from .plot_common import plain
    ti = r.theta_i_figures
    requests = [("mirror", (ti, 0.0, ti, 180.0), f"mirror (specular) direction, θ_i = θ_r = {ti:g}°"),
                ("retro", (ti, 0.0, ti, 0.0), f"retro direction (towards the source), θ_i = θ_r = {ti:g}°"),
                ("nadir", (ti, 0.0, 0.0, 0.0), f"viewed along the normal, θ_i = {ti:g}°")]
    r.spectral_keys, seen = [], set()
    for name, geometry, text in requests:
        key = f"spectral-{name}"
        fig = _draw(r, key, "", lambda g=geometry, t=text: plot.spectral([r.dataset], g, labels=[r.sample],
                                                                          title=f"Spectral BRDF: {t}"))
        if fig is None:
            r.spectral_keys.append(key)
            continue
        angles, distance = fig.roadbrdf_geometries[plain(r.sample)]  # the label as the figure shows it
        if angles in seen:  # the same measured geometry answers two requests (e.g. theta_i = 0)
            del r.figures[key]
            continue
        seen.add(angles)
        far = f", {distance:.1f}° from the request" if distance > 1.0 else ""
        png, _ = r.figures[key]
        r.figures[key] = (png, esc(f"{text}: measured geometry θ_i {angles[0]:g}°, φ_i {angles[1]:g}°, θ_r "
                                   f"{angles[2]:g}°, φ_r {angles[3]:g}°{far} (plot.spectral)."))
        r.spectral_keys.append(key)


def draw_all(r) -> None:
    from . import plot, read_fit
    params_plot = _params_function()
    r.figures, r.figure_errors = {}, {}
    _spectral(r)
    ti, band, best = r.theta_i_figures, r.band, r.best.model
    _draw(r, "hemisphere", esc(f"The best-ranked fit ({best}) over the viewing hemisphere at θ_i = {ti:g}°, "
                               f"{band:g} nm, with the measured points on the same colour scale (plot.hemisphere)."),
          lambda: plot.hemisphere(read_fit(r.fit_all_path, best), theta_i=ti, wavelength=band, data=r.dataset,
                                  title=f"{r.sample}: {best} at {band:g} nm, θ_i = {ti:g}°"))
    _draw(r, "plane", esc(f"Plane of incidence at θ_i = {ti:g}°, {band:g} nm: the measured points and every "
                          "model fitted to all configurations (plot.plane)."),
          lambda: plot.plane([read_fit(r.fit_all_path, m) for m in r.models], [r.dataset], theta_i=ti,
                             wavelength=band, labels=list(r.models), title=f"{r.sample}: plane of incidence, "
                             f"θ_i = {ti:g}°"))
    _draw(r, "fit-quality", esc(f"Fit quality of {best} (all configurations): fitted against measured at {band:g} "
                                "nm, residuals, and the RMSE of every model against wavelength (plot.fit_quality)."),
          lambda: plot.fit_quality(r.path, r.fit_all_path, best, wavelength=band,
                                   title=f"{r.sample}: fit quality", average_duplicates=r.average_duplicates))
    if r.fit_all.wavelengths.size > 1:
        free = [p for p in r.best.parameter_names if p not in r.fixed]
        _draw(r, "params-by-wavelength", esc(f"Parameters of {best} against wavelength, ± one standard error "
                                             "(plot_params.params)."),
              lambda: params_plot(r.fit_all_path, parameters=free, models=[best],
                                  title=f"{r.sample}: {best}, parameters ± 1 standard error"))
    if r.fit_groups is not None:
        units = r.group_params.attrs["units"]
        free = [p for p in units if p not in r.fixed and r.group_params[p].notna().any()]
        _draw(r, "params-by-incidence", esc(f"Parameters of the per-incidence fits at {band:g} nm against θ_i, ± one "
                                            "standard error (plot_params.params)."),
              lambda: params_plot(r.fit_groups_path, parameters=free, against="theta_i", wavelength=band,
                                  title=f"{r.sample}: per-incidence fits"))  # params() adds the band
    if r.albedo is not None:
        _draw(r, "albedo", esc(f"Albedo of {best}: spectral black-, white- and blue-sky, and the solar-weighted "
                               "values (plot.albedo)."),
              lambda: plot.albedo(r.albedo, title=f"{r.sample}: albedo ({best})"))
    if r.rtable is not None:
        _draw(r, "rtable", esc(f"r-table of {best} and its (S1, Q0) among the CIE R classes (plot.rtable)."),
              lambda: plot.rtable(r.rtable, title=f"{r.sample}: r-table ({best})"))
    if r.mix is not None and r.mix.methods:
        chosen = r.mix.best or r.mix.methods[0]
        _draw(r, "mixing", esc(f"Plane of incidence at θ_i = {ti:g}°, {band:g} nm: the measured sample, its fit "
                               f"({best}) and the mixing prediction of the best method ({chosen.method}) (plot.plane)."),
              lambda: plot.plane([chosen.spectral_model(), read_fit(r.fit_all_path, best)], [r.dataset], theta_i=ti,
                                 wavelength=band, labels=[f"mixing prediction ({chosen.method})", f"fit ({best})"],
                                 title=f"{r.sample}: mixing prediction, θ_i = {ti:g}°"))
