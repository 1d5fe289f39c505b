"""The figures of the sample report, drawn by the public functions of :mod:`roadbrdf.plot` (and
``roadbrdf.plot_params.params``), each returned as a matplotlib Figure and embedded as PNG.

``draw_all(r)`` fills ``r.figures`` (key -> (PNG bytes, caption)) and ``r.spectral_keys``; a figure that
cannot be drawn is named in ``r.figure_errors`` (shown in the page, and on standard error) rather than
losing the whole report.
"""

from __future__ import annotations

import contextlib
import io
import os
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


class _Job:
    """One figure of the page: ``make()`` returns the matplotlib Figure; ``caption`` (HTML) is shown under it
    and ``spectral`` marks the spectral figures (their caption names the measured geometry drawn)."""

    def __init__(self, key, caption, make, spectral=None, cost=1):
        self.key, self.caption, self.make, self.spectral, self.cost = key, caption, make, spectral, cost


def _run(job):
    """Draw one figure: (PNG or None, error or None, stderr lines, extra), all plain data so that a
    worker process can return them. The plot functions' stderr lines (e.g. a geometry far from the one asked
    for) become caveats of the spectral section; ``extra`` holds the measured geometries a spectral figure
    drew (``fig.roadbrdf_geometries``)."""
    stderr = io.StringIO()
    extra = None
    try:
        with contextlib.redirect_stderr(stderr), warnings.catch_warnings():
            warnings.simplefilter("ignore")
            fig = job.make()
        extra = getattr(fig, "roadbrdf_geometries", None)
        png, error = figure_png(fig), None
    except Exception as e:  # noqa: BLE001 - one figure must not lose the report
        png, error = None, (type(e).__name__, str(e))
    return png, error, [line for line in stderr.getvalue().splitlines() if line.strip()], extra


#: The jobs of the report being drawn, inherited by the forked worker processes (closures cannot be sent
#: to a process; a forked worker has them already and is sent only their index).
_JOBS: list = []


def _run_index(index):
    return _run(_JOBS[index])


def _worker_signals():
    """A worker leaves Ctrl-C to the report (which stops the pool) and dies at once on SIGTERM."""
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _processes(jobs) -> int:
    """Processes drawing the figures: one per core (at most one per figure); ``ROADBRDF_REPORT_PROCESSES``
    overrides (1: drawn in this process, in order). Drawing is single-threaded matplotlib, so the figures
    are spread over processes; forking keeps the data already read (datasets, fit models) without copying."""
    import multiprocessing
    from .report import default_threads
    asked = os.environ.get("ROADBRDF_REPORT_PROCESSES", "")
    n = int(asked) if asked.strip().isdigit() and int(asked) > 0 else default_threads()
    if "fork" not in multiprocessing.get_all_start_methods():
        return 1
    return max(1, min(n, len(jobs)))


def _draw_parallel(jobs, n):
    """The results of ``jobs`` (in their order) drawn by ``n`` forked processes, the costliest figures first
    so that the processes finish together; None when a worker died (the caller draws them itself)."""
    global _JOBS
    import multiprocessing
    from concurrent.futures import ProcessPoolExecutor
    from concurrent.futures.process import BrokenProcessPool
    order = sorted(range(len(jobs)), key=lambda k: -jobs[k].cost)
    _JOBS = jobs
    for stream in (sys.stdout, sys.stderr):  # a forked worker must not write the parent's buffered text again
        stream.flush()
    pool = ProcessPoolExecutor(n, mp_context=multiprocessing.get_context("fork"), initializer=_worker_signals)
    try:
        drawn = dict(zip(order, pool.map(_run_index, order)))
        pool.shutdown()
        return [drawn[k] for k in range(len(jobs))]
    except BrokenProcessPool:
        pool.shutdown()
        return None
    except BaseException:  # Ctrl-C or SIGTERM: stop the workers at once, not after the figures left
        for process in list(getattr(pool, "_processes", {}).values()):
            process.terminate()
        pool.shutdown(wait=False, cancel_futures=True)
        raise
    finally:
        _JOBS = []


def _draw_jobs(r, jobs) -> None:
    """Draw ``jobs`` (over several processes when there are cores for it) and keep each result in the
    page's order: ``r.figures[key]`` = (PNG, caption), or the error in ``r.figure_errors``."""
    n = _processes(jobs)
    results = _draw_parallel(jobs, n) if n > 1 else None
    if results is None:
        results = [_run(job) for job in jobs]
    seen = set()
    for job, (png, error, lines, extra) in zip(jobs, results):
        if error is not None:
            r.figure_errors[job.key] = f"{error[0]}: {error[1]}"
            print(f"roadbrdf report: warning: figure '{job.key}' not drawn: {error[1]}", file=sys.stderr)
            if job.spectral is not None:
                r.spectral_keys.append(job.key)
            continue
        r.warnings.setdefault("spectra", []).extend(line.replace("roadbrdf: warning: ", "") for line in lines)
        caption = job.caption
        if job.spectral is not None:
            from .plot_common import plain
            angles, distance = extra[plain(r.sample)]  # the label as the figure shows it
            if angles in seen:  # the same measured geometry answers two requests (e.g. theta_i = 0)
                continue
            seen.add(angles)
            far = f", {distance:.1f}° from the request" if distance > 1.0 else ""
            caption = esc(f"{job.spectral}: measured geometry θ_i {angles[0]:g}°, φ_i {angles[1]:g}°, θ_r "
                          f"{angles[2]:g}°, φ_r {angles[3]:g}°{far} (plot.spectral).")
            r.spectral_keys.append(job.key)
        r.figures[job.key] = (png, caption)


def _spectral(r):
    """BRDF against wavelength at the mirror, retro and nadir-viewing geometries of the figures' incidence."""
    from . import plot
    ti = r.theta_i_figures
    requests = [("mirror", (ti, 0.0, ti, 180.0), f"mirror (specular) direction, θ_i = θ_r = {ti:g}°"),
                ("retro", (ti, 0.0, ti, 0.0), f"retro direction (towards the source), θ_i = θ_r = {ti:g}°"),
                ("nadir", (ti, 0.0, 0.0, 0.0), f"viewed along the normal, θ_i = {ti:g}°")]
    return [_Job(f"spectral-{name}", "", lambda g=geometry, t=text: plot.spectral(
        [r.dataset], g, labels=[r.sample], title=f"Spectral BRDF: {t}"), spectral=text)
        for name, geometry, text in requests]


def draw_all(r) -> None:
    from . import plot
    from .report import fit_model
    params_plot = _params_function()
    r.figures, r.figure_errors, r.spectral_keys = {}, {}, []
    ti, band, best = r.theta_i_figures, r.band, r.best.model
    jobs = _spectral(r)
    jobs.append(_Job("hemisphere", esc(f"The best-ranked fit ({best}) over the viewing hemisphere at θ_i = {ti:g}°, "
                                       f"{band:g} nm, with the measured points on the same colour scale "
                                       "(plot.hemisphere)."),
                     lambda: plot.hemisphere(fit_model(r, best), theta_i=ti, wavelength=band, data=r.dataset,
                                             title=f"{r.sample}: {best} at {band:g} nm, θ_i = {ti:g}°"),
                     cost=3))
    jobs.append(_Job("plane", esc(f"Plane of incidence at θ_i = {ti:g}°, {band:g} nm: the measured points and every "
                                  "model fitted to all configurations (plot.plane)."),
                     lambda: plot.plane([fit_model(r, m) for m in r.models], [r.dataset], theta_i=ti,
                                        wavelength=band, labels=list(r.models), title=f"{r.sample}: plane of "
                                        f"incidence, θ_i = {ti:g}°"), cost=2))
    jobs.append(_Job("fit-quality", esc(f"Fit quality of {best} (all configurations): fitted against measured at "
                                        f"{band:g} nm, residuals, and the RMSE of every model against wavelength "
                                        "(plot.fit_quality)."),
                     lambda: plot.fit_quality(r.path, r.fit_all_path, best, wavelength=band,
                                              title=f"{r.sample}: fit quality"), cost=2))
    if r.fit_all.wavelengths.size > 1:
        free = [p for p in r.best.parameter_names if p not in r.fixed]
        jobs.append(_Job("params-by-wavelength", esc(f"Parameters of {best} against wavelength, ± one standard "
                                                     "error (plot_params.params)."),
                         lambda: params_plot(r.fit_all_path, parameters=free, models=[best],
                                             title=f"{r.sample}: {best}, parameters ± 1 standard error"),
                         cost=3))
    if r.fit_groups is not None:
        units = r.group_params.attrs["units"]
        free_g = [p for p in units if p not in r.fixed and r.group_params[p].notna().any()]
        jobs.append(_Job("params-by-incidence", esc(f"Parameters of the per-incidence fits at {band:g} nm against "
                                                    "θ_i, ± one standard error (plot_params.params)."),
                         lambda: params_plot(r.fit_groups_path, parameters=free_g, against="theta_i",
                                             wavelength=band, title=f"{r.sample}: per-incidence fits")))
    if r.albedo is not None:
        jobs.append(_Job("albedo", esc(f"Albedo of {best}: spectral black-, white- and blue-sky, and the "
                                       "solar-weighted values (plot.albedo)."),
                         lambda: plot.albedo(r.albedo, title=f"{r.sample}: albedo ({best})")))
    if r.rtable is not None:
        jobs.append(_Job("rtable", esc(f"r-table of {best} and its (S1, Q0) among the CIE R classes (plot.rtable)."),
                         lambda: plot.rtable(r.rtable, title=f"{r.sample}: r-table ({best})")))
    if r.mix is not None and r.mix.methods:
        chosen = r.mix.best or r.mix.methods[0]
        jobs.append(_Job("mixing", esc(f"Plane of incidence at θ_i = {ti:g}°, {band:g} nm: the measured sample, its "
                                       f"fit ({best}) and the mixing prediction of the best method "
                                       f"({chosen.method}) (plot.plane)."),
                         lambda: plot.plane([chosen.spectral_model(), fit_model(r, best)], [r.dataset],
                                            theta_i=ti, wavelength=band,
                                            labels=[f"mixing prediction ({chosen.method})", f"fit ({best})"],
                                            title=f"{r.sample}: mixing prediction, θ_i = {ti:g}°")))
    _draw_jobs(r, jobs)
