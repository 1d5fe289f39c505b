"""The figures of the sample report, drawn by the public functions of :mod:`roadbrdf.plot` (and
``roadbrdf.plot_params.params``), each returned as a matplotlib Figure and embedded as PNG.

``draw_all(r)`` (or :class:`Drawing`, started before the albedo and finished after the r-table) fills
``r.figures`` (key -> (PNG bytes, caption)) and ``r.spectral_keys``; a figure that cannot be drawn is named
in ``r.figure_errors`` (shown in the page, and on standard error) rather than losing the whole report.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
import warnings

from .report_html import esc, figure_png

__all__ = ["draw_all", "Drawing"]


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


#: The jobs drawn by the worker processes, inherited when they are forked (closures cannot be sent to a
#: process; a forked worker has them already and is sent only their index).
_JOBS: list = []


def _run_index(index):
    return _run(_JOBS[index])


def _worker_signals():
    """A worker leaves Ctrl-C to the report (which stops the pool) and dies at once on SIGTERM."""
    import signal
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _cores() -> int:
    """Cores for the figures: ``ROADBRDF_REPORT_PROCESSES`` when set (1: everything drawn in this process, in
    order), else the cores this process may run on; 1 where processes cannot be forked."""
    import multiprocessing
    from .report import default_threads
    if "fork" not in multiprocessing.get_all_start_methods():
        return 1
    asked = os.environ.get("ROADBRDF_REPORT_PROCESSES", "").strip()
    return int(asked) if asked.isdigit() and int(asked) > 0 else default_threads()


class Drawing:
    """The figures of the page, drawn while the report computes the rest.

    Matplotlib draws on one thread, so the figures are spread over processes: creating a Drawing forks
    workers (one core is left to the report, which goes on with the albedo and the r-table) that draw the
    figures needing neither; :meth:`finish` draws the albedo and r-table figures here, then those no worker
    has started yet, collects the workers' and keeps every result in the page's order. Forking keeps the
    data already read (dataset, fit models) without copying; with one core everything is drawn here, in
    order (``ROADBRDF_REPORT_PROCESSES=1`` asks for that)."""

    def __init__(self, r):
        self.jobs = _early_jobs(r)
        self.futures, self.pool, self.order = None, None, []
        workers = min(_cores() - 1, len(self.jobs))
        if workers < 1:
            return
        global _JOBS
        import multiprocessing
        from concurrent.futures import ProcessPoolExecutor
        from . import plot  # noqa: F401 - imported once here, not in each worker
        for stream in (sys.stdout, sys.stderr):  # a forked worker must not write the parent's buffered text again
            stream.flush()
        _JOBS = self.jobs
        self.pool = ProcessPoolExecutor(workers, mp_context=multiprocessing.get_context("fork"),
                                        initializer=_worker_signals)
        # The costliest figures (many panels) first, so that the workers finish together.
        self.order = sorted(range(len(self.jobs)), key=lambda k: -self.jobs[k].cost)
        self.futures = {k: self.pool.submit(_run_index, k) for k in self.order}

    def finish(self, r) -> None:
        """Draw the rest, collect the workers' figures and fill ``r.figures``, ``r.figure_errors`` and
        ``r.spectral_keys``."""
        from concurrent.futures.process import BrokenProcessPool
        late = _late_jobs(r)
        results = [_run(job) for job in late]
        early = None
        if self.futures is not None:
            # Then this process takes the figures no worker has started, the last ones queued first.
            drawn = {}
            for k in reversed(self.order):
                if self.futures[k].cancel():
                    drawn[k] = _run(self.jobs[k])
            try:
                early = [drawn[k] if k in drawn else self.futures[k].result() for k in range(len(self.jobs))]
            except BrokenProcessPool:  # a worker died (out of memory, say): draw its figures here
                early = None
            self.stop(at_once=early is None)
        if early is None:
            early = [_run(job) for job in self.jobs]
        _keep(r, self.jobs + late, early + results)

    def stop(self, at_once: bool = True) -> None:
        """End the workers: at once (Ctrl-C, SIGTERM or an error of the report), or, ``at_once=False``
        after :meth:`finish`, when they are idle, by letting them exit."""
        global _JOBS
        if self.pool is None:
            return
        if at_once:
            for process in list((getattr(self.pool, "_processes", None) or {}).values()):
                process.terminate()
            self.pool.shutdown(wait=False, cancel_futures=True)
        else:
            self.pool.shutdown(wait=True)
        self.pool, _JOBS = None, []


def _keep(r, jobs, results) -> None:
    """Each figure's PNG and caption in ``r.figures``, or its error in ``r.figure_errors``, in the page's
    order (``results`` are those of ``jobs``)."""
    r.figures, r.figure_errors, r.spectral_keys = {}, {}, []
    order = {key: k for k, key in enumerate(_PAGE_ORDER)}
    pairs = sorted(zip(jobs, results), key=lambda p: order.get(p[0].key, len(order)))
    seen = set()
    for job, (png, error, lines, extra) in pairs:
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


#: The order the figures are kept in (and their stderr lines among the caveats of the spectral section).
_PAGE_ORDER = ["spectral-mirror", "spectral-retro", "spectral-nadir", "hemisphere", "plane", "fit-quality",
               "params-by-wavelength", "params-by-incidence", "albedo", "rtable", "mixing"]


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


def _early_jobs(r) -> list:
    """The figures that need neither the albedo nor the r-table (drawn while those are computed)."""
    from . import plot
    from .report import fit_model
    params_plot = _params_function()
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
                                              title=f"{r.sample}: fit quality",
                                              average_duplicates=r.average_duplicates), cost=2))
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
    if r.mix is not None and r.mix.methods:
        chosen = r.mix.best or r.mix.methods[0]
        jobs.append(_Job("mixing", esc(f"Plane of incidence at θ_i = {ti:g}°, {band:g} nm: the measured sample, its "
                                       f"fit ({best}) and the mixing prediction of the best method "
                                       f"({chosen.method}) (plot.plane)."),
                         lambda: plot.plane([chosen.spectral_model(), fit_model(r, best)], [r.dataset],
                                            theta_i=ti, wavelength=band,
                                            labels=[f"mixing prediction ({chosen.method})", f"fit ({best})"],
                                            title=f"{r.sample}: mixing prediction, θ_i = {ti:g}°")))
    return jobs


def _late_jobs(r) -> list:
    """The albedo and r-table figures."""
    from . import plot
    best = r.best.model
    jobs = []
    if r.albedo is not None:
        jobs.append(_Job("albedo", esc(f"Albedo of {best}: spectral black-, white- and blue-sky, and the "
                                       "solar-weighted values (plot.albedo)."),
                         lambda: plot.albedo(r.albedo, title=f"{r.sample}: albedo ({best})")))
    if r.rtable is not None:
        jobs.append(_Job("rtable", esc(f"r-table of {best} and its (S1, Q0) among the CIE R classes (plot.rtable)."),
                         lambda: plot.rtable(r.rtable, title=f"{r.sample}: r-table ({best})")))
    return jobs


def draw_all(r) -> None:
    """Every figure of the page (:class:`Drawing` started and finished at once)."""
    drawing = Drawing(r)
    try:
        drawing.finish(r)
    finally:
        drawing.stop()
