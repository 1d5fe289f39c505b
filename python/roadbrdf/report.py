"""The report of one sample: ``roadbrdf report DATA.csv [--model M ...] [--formulation F.json] -o REPORT.html``
(also ``python3 -m roadbrdf.report``, and :func:`write_report` from Python).

One self-contained HTML page (inline style, figures as embedded PNG, no script, nothing fetched) that a
lab files with a sample: provenance of the data file, the quality check of ``roadbrdf check``, the
geometry coverage, spectral and angular figures, the fits of each model per incidence angle at one
wavelength with their parameter tables, the ranking of the models over all configurations, the albedo
and the r-table of the best model with the coverage caveats, and, with a formulation, the mixing
predictions compared with the sample. Every number comes from the library's public Python API
(:func:`roadbrdf.check`, :func:`roadbrdf.fit`, :func:`roadbrdf.params`, :func:`roadbrdf.albedo`,
:func:`roadbrdf.rtable`, :func:`roadbrdf.mix`) and every figure from :mod:`roadbrdf.plot`; what the page
shows is described in docs/report.md.
"""

from __future__ import annotations

import argparse
import contextlib
import datetime
import hashlib
import io
import math
import os
import sys
import tempfile
import time
import warnings
from types import SimpleNamespace

import numpy as np

from . import __version__, _roadbrdf
from .core import InputError, read_json_file, write_text_atomic

__all__ = ["write_report", "render_report", "gather", "main", "DEFAULT_MODELS"]

#: The models fitted when none is given (``--model``).
DEFAULT_MODELS = ("oren-nayar", "lambert+torrance-sparrow")


# ---- inputs --------------------------------------------------------------------------------------
def _file_info(path: str) -> dict:
    """Name, size, SHA-256, modification time and data rows (lines after the header that are neither
    empty nor comments) of the data file."""
    with open(path, "rb") as fh:
        content = fh.read()
    lines = [line.strip() for line in content.decode("utf-8-sig", errors="replace").splitlines()]
    data_lines = [line for line in lines if line and not line.startswith("#")]
    modified = datetime.datetime.fromtimestamp(os.stat(path).st_mtime, datetime.timezone.utc)
    return {"name": os.path.basename(path), "path": path, "size": len(content),
            "sha256": hashlib.sha256(content).hexdigest(), "rows": max(len(data_lines) - 1, 0),
            "modified": modified.strftime("%Y-%m-%d %H:%M:%S")}


def _composite_weights(models) -> dict:
    """``{component.weight: 1}`` for every composite: a composite's weights are degenerate with its
    components' amplitudes (albedo, ks, ...), so they are held at 1, as the demo does."""
    fixed = {}
    for m in models:
        parts = m.split("+")
        if len(parts) > 1:
            fixed.update({f"{p}.weight": 1.0 for p in parts})
    return fixed


def _free_parameters(model: str, fixed: dict, catalogue: dict) -> int:
    """An upper bound of the free parameters of ``model`` (a name fixed by a plain name may not count)."""
    parts = model.split("+")
    if len(parts) == 1:
        return sum(1 for p in catalogue[model] if p not in fixed)
    return sum(1 for c in parts for p in [*catalogue[c], "weight"] if f"{c}.{p}" not in fixed)


def _incidence_groups(dataset, band_index: int, needed: int, needed_by: str):
    """The geometries of each measured incidence (theta_i to 1e-6 deg, as fit --group-by groups them):
    count, viewing angles, azimuth planes, and whether it has enough values at the band to be fitted."""
    ti = np.round(dataset.theta_i, 6)
    groups = []
    for value in np.unique(ti):
        sel = ti == value
        a = dataset.angles[sel]
        points = int(np.isfinite(dataset.brdf[sel, band_index]).sum())
        beta = np.round(180.0 - np.degrees(np.arccos(np.clip(np.cos(np.radians(a[:, 3] - a[:, 1])), -1, 1))), 3)
        planes = np.unique(beta[(a[:, 0] > 0) & (a[:, 2] > 0)])
        fitted = points > needed
        groups.append({"theta_i": float(value), "geometries": int(sel.sum()), "points": points,
                       "theta_r": np.unique(np.round(a[:, 2], 3)), "planes": int(planes.size), "fitted": fitted,
                       "reason": "" if fitted else f"{points} values for up to {needed} free parameters of {needed_by}"})
    return groups


def _figure_incidence(groups, theta_i):
    """The incidence of the angular figures: the one asked for, else the middle measured one (not 0 when
    there are others)."""
    values = [g["theta_i"] for g in groups]
    if theta_i is not None:
        return float(values[int(np.argmin(np.abs(np.asarray(values) - theta_i)))])
    middle = values[len(values) // 2]
    return float(max(values) if middle == 0.0 else middle)


class _Steps:
    """Progress on standard error (unless quiet): a line as each step starts, the steps done as the library's
    progress lines (roadbrdf.heartbeat: a bar on a terminal, a line every 10 s in a log), and the time of each
    step. ``total``: the steps planned; :meth:`close` ends the progress."""

    def __init__(self, quiet: bool, total: int = 1):
        from .heartbeat import Heartbeat
        self.quiet, self.start, self.times = quiet, time.monotonic(), {}
        self.beat = Heartbeat("roadbrdf report", total, enabled=not quiet).__enter__()

    @contextlib.contextmanager
    def step(self, name: str, text: str):
        self.say(f"{text} ...")
        t0 = time.monotonic()
        yield
        self.times[name] = time.monotonic() - t0
        self.beat.advance()

    def say(self, text: str):
        if not self.quiet:
            self.beat.say(f"roadbrdf report: {text}")

    def close(self, failed: bool = False):
        self.beat.__exit__(RuntimeError if failed else None, None, None)


@contextlib.contextmanager
def _collect(r, key):
    """UserWarnings of the library inside the block, kept in ``r.warnings[key]`` (they are caveats of the report)."""
    with warnings.catch_warnings(record=True) as caught:
        warnings.simplefilter("always")
        yield
    r.warnings.setdefault(key, []).extend(dict.fromkeys(str(w.message) for w in caught))


# ---- gathering the results -----------------------------------------------------------------------
def gather(data, models=DEFAULT_MODELS, formulation=None, wavelength=600.0, theta_i=None, sun_zenith="0:60:30",
           atmosphere="spectrl2", illuminant="A", multistart=8, fix=None, free_weights=False, folds=5, threads=None,
           quiet=True, workdir=None, installation=None, lighting_class=None, average_duplicates=False, _steps=None):
    """Every result of the report (a namespace), computed with the public API; ``workdir`` holds the fit
    files the figures and tables read (a temporary folder when None, removed afterwards). ``threads``: of
    the fit over all wavelengths (None: every core; the fit does not depend on it, bit for bit);
    ``installation``: a road-lighting installation file for the lighting section (report_lighting.py),
    ``lighting_class`` its M class; ``average_duplicates``: the duplicate policy of every command (else
    repeated geometries are an error)."""
    from . import Model, SpectralModel, check, fit, mix, models as model_catalogue, params, read_dataset, read_fit
    from . import albedo as albedo_of, rtable as rtable_of
    models = list(dict.fromkeys(models or DEFAULT_MODELS))
    for m in models:
        try:
            Model(m)  # an unknown name is an InputError naming the known ones
        except InputError as e:
            known = _roadbrdf.model_names()
            unknown = [c for c in m.split("+") if c not in known]
            raise InputError(f"--model: {e}{_roadbrdf.did_you_mean(unknown[0], known) if unknown else ''}") from None
    zeniths = _roadbrdf.values(sun_zenith, "--sun-zenith")
    if formulation is not None and not os.path.isfile(formulation):
        raise InputError(f"--formulation: '{formulation}': no such file")
    threads = default_threads() if threads is None else int(threads)
    from . import report_lighting
    report_lighting.check_arguments(installation, lighting_class)
    # The steps: read, fit-all, fit-groups, albedo, r-table and figures; mix and its r-table with a formulation;
    # lighting with an installation.
    steps = _steps or _Steps(quiet, 6 + 2 * (formulation is not None) + (installation is not None))
    r = SimpleNamespace(path=os.fspath(data), models=models, wavelength_asked=float(wavelength),
                        multistart=int(multistart), warnings={}, figures={}, figure_errors={}, folds=int(folds),
                        illuminant=illuminant, steps=steps, mix=None, formulation=None, lighting=None,
                        average_duplicates=bool(average_duplicates))
    try:
        with steps.step("read", f"reading and checking {r.path}"), _collect(r, "read"):
            r.file = _file_info(r.path)
            r.dataset = read_dataset(r.path, average_duplicates=r.average_duplicates)
            r.check = check(r.path, average_duplicates=r.average_duplicates)
    except BaseException:
        if _steps is None:
            steps.close(failed=True)
        raise
    d = r.dataset
    r.sample = d.metadata.get("sample") or os.path.splitext(r.file["name"])[0]
    r.fixed = {} if free_weights else _composite_weights(models)
    r.fixed.update({str(k): float(v) for k, v in (fix or {}).items()})
    own = tempfile.TemporaryDirectory(prefix="roadbrdf-report-") if workdir is None else None
    folder = own.name if own else workdir
    drawing = None
    try:
        r.fit_all_path = os.path.join(folder, "all-configurations.fit.json")
        with steps.step("fit-all", f"fitting {', '.join(models)} to every geometry ({len(d)}) at "
                                   f"{d.wavelengths.size} wavelengths"), _collect(r, "fit-all"):
            r.fit_all = fit(d, models, fixed=r.fixed, multistart=r.multistart, threads=threads)
            r.fit_all.write(r.fit_all_path)
        r.warnings["fit-all"].extend(r.fit_all.warnings("the fit of all configurations"))
        r.best = r.fit_all.best
        if formulation is not None:  # early: a formulation whose component fits are missing fails at once
            import json
            r.formulation = read_json_file(formulation)
            r.formulation_name = os.path.basename(formulation)
            with steps.step("mix", f"mixing predictions of {r.formulation_name}"), _collect(r, "mix"):
                # With the end-members' covariances (cheap for the mixing itself; the r-table of one method is
                # propagated below, the albedo's propagation would take minutes and is left to the commands).
                r.mix = mix(formulation, data=r.path, method="all", folds=r.folds, reference=r.fit_all_path,
                            uncertainty=True, average_duplicates=r.average_duplicates)
        band_index = int(np.argmin(np.abs(d.wavelengths - r.wavelength_asked)))
        r.band = float(d.wavelengths[band_index])
        r.all_params = params(r.fit_all_path, wavelengths=[r.band])
        _fit_groups(r, folder, band_index, fit, params, model_catalogue)
        r.theta_i_figures = _figure_incidence(r.groups, theta_i)
        r.atmosphere_text = (f"diffuse fraction and solar weights from {atmosphere}" if atmosphere
                             else "ASTM G173 global solar weights, no sky (blue-sky not formed)")
        # From the fit file, as `roadbrdf albedo FIT.json` reads it: the file records the measured directions
        # (the coverage the albedo and r-table report), which a FitResult's in-memory model does not carry.
        # Every model the figures draw, from one parse of the file (parsing it takes longer than reading a model
        # out of it); a name the file does not hold is left to fit_model, which reads one model at a time.
        names = list(dict.fromkeys([r.best.model, *r.models]))
        try:
            r.fit_models = {name: SpectralModel(m) for name, m in
                            zip(names, _roadbrdf.read_fit_file_models(r.fit_all_path, names))}
        except ValueError:
            r.fit_models = {r.best.model: read_fit(r.fit_all_path, r.best.model)}
        best_model = r.fit_models[r.best.model]
        # A section whose quantity the data cannot give (an r-table is weighted by V(lambda), so data outside the
        # visible range have none) is absent with its reason; the other sections are shown.
        r.albedo = r.rtable = None
        r.albedo_note = r.rtable_note = ""
        # The figures that need neither the albedo nor the r-table are drawn by other processes meanwhile.
        from .report_figures import Drawing
        drawing = Drawing(r)
        with steps.step("albedo", f"albedo of {r.best.model}"), _collect(r, "albedo"):
            try:
                r.albedo = albedo_of(best_model, sun_zenith=zeniths, atmosphere=atmosphere or None)
            except InputError as e:
                r.albedo_note = f"No albedo: {e}"
                steps.say(f"warning: no albedo: {e}")
        with steps.step("rtable", f"r-table of {r.best.model}"), _collect(r, "rtable"):
            try:
                r.rtable = rtable_of(best_model, illuminant=illuminant)
            except InputError as e:
                r.rtable_note = f"No r-table: {e}"
                steps.say(f"warning: no r-table: {e}")
        if r.mix is not None and r.rtable is not None:
            with steps.step("mix-rtable", "r-table of the mixing prediction with its uncertainty"), \
                    _collect(r, "mix-rtable"):
                _mixture_uncertainty(r, rtable_of)
        if installation is not None:
            with steps.step("lighting", f"road lighting of {os.path.basename(installation)}"), _collect(r, "lighting"):
                report_lighting.gather(r, installation, lighting_class, r.fit_all_path)
        r.all_caveats = list(dict.fromkeys(
            [w["message"] for w in (r.albedo or {}).get("warnings", [])] +
            [n for n in (r.albedo or {}).get("notes", []) if n.startswith("coverage")] +
            list((r.rtable or {}).get("warnings") or []) +
            [n for n in (r.rtable or {}).get("notes") or [] if n.startswith("coverage")]))
        with steps.step("figures", "drawing the figures"):
            drawing.finish(r)
    finally:
        if drawing is not None:
            drawing.stop()
        if own:
            own.cleanup()
        if _steps is None:
            steps.close(failed=sys.exc_info()[0] is not None)
    return r


def default_threads() -> int:
    """The threads of the report's fit when none is asked for: the cores this process may run on."""
    try:
        return max(len(os.sched_getaffinity(0)), 1)
    except AttributeError:  # pragma: no cover - not Linux
        return max(os.cpu_count() or 1, 1)


def fit_model(r, model: str):
    """The spectral model of ``model`` from the fit file of all configurations, read once per report (a
    2151-band fit file takes a noticeable fraction of a second to read)."""
    from . import read_fit
    if model not in r.fit_models:
        r.fit_models[model] = read_fit(r.fit_all_path, model)
    return r.fit_models[model]


#: The mixing methods whose prediction carries the end-members' parameter covariance (docs/mixing.md,
#: "Uncertainty of a mixture"); ``fitted`` and ``shadowed`` fit weights to the measured sample and carry none.
COVARIANCE_METHODS = ("areal", "mastic", "hapke")


def _mixture_uncertainty(r, rtable_of):
    """The r-table (Q0, S1, S2, Qd, class probabilities with their standard uncertainties) of one mixing
    prediction: the method with the lowest held-out RMSE among those that carry a covariance, skipping one
    whose uncertainty is undefined (an end-member fit without a covariance at a wavelength the weighting
    uses). Sets ``r.mix_u_method`` (None when no method has one), ``r.mix_rtable`` and ``r.mix_u_skipped``
    {method: reason}. Only the r-table: a mixture's albedo uncertainty differentiates the black-sky integrals
    by every end-member parameter (minutes of CPU), too slow for a report."""
    r.mix_u_method, r.mix_rtable, r.mix_u_skipped = None, None, {}
    candidates = sorted((m for m in r.mix.methods if m.method in COVARIANCE_METHODS),
                        key=lambda m: (m.comparison or {}).get("rmse", math.inf))
    for m in candidates:
        t = rtable_of(m.spectral_model(), illuminant=r.illuminant)
        u = t.get("uncertainty")
        if u is None:
            r.mix_u_skipped[m.method] = "no parameter covariance" + "".join(f" ({n})" for n in m.notes[:1])
        elif u.get("Q0") is None or u.get("S1") is None:
            r.mix_u_skipped[m.method] = ("undefined: an end-member's fit has no covariance at a wavelength the "
                                         "r-table's weighting uses")
        else:
            r.mix_u_method, r.mix_rtable = m.method, t
            return
    missing = [m for m in COVARIANCE_METHODS if m not in {c.method for c in candidates}]
    for m in missing:
        r.mix_u_skipped[m] = "not applied to this formulation"


def _fit_groups(r, folder, band_index, fit, params, model_catalogue):
    """The per-incidence fits at the band (fit --group-by theta_i), leaving out the incidences with too
    few values for the models' free parameters (named in ``r.group_note``)."""
    catalogue = {m["name"]: [p["name"] for p in m["parameters"]] for m in model_catalogue()}
    counts = {m: _free_parameters(m, r.fixed, catalogue) for m in r.models}
    needed_by = max(counts, key=counts.get)
    r.groups = _incidence_groups(r.dataset, band_index, counts[needed_by], needed_by)
    left_out = [g for g in r.groups if not g["fitted"]]
    r.where = " and ".join(f"theta_i!={g['theta_i']!r}" for g in left_out)
    r.where_note = f" --where '{r.where}'" if r.where else ""
    r.group_note = "; ".join(f"θ_i = {g['theta_i']:g}° not fitted per incidence: {g['reason']}" for g in left_out)
    r.fit_groups, r.group_params = None, None
    if len(left_out) == len(r.groups):
        return
    r.fit_groups_path = os.path.join(folder, "per-incidence.fit.json")
    with r.steps.step("fit-groups", f"fitting per incidence at {r.band:g} nm"), _collect(r, "fit-groups"):
        r.fit_groups = fit(r.dataset, r.models, fixed=r.fixed, multistart=r.multistart, wavelengths=[r.band],
                           group_by="theta_i", where=r.where)
        r.fit_groups.write(r.fit_groups_path)
        r.group_params = params(r.fit_groups_path)
    r.warnings["fit-groups"].extend(r.fit_groups.warnings("the per-incidence fits"))


# ---- the page ------------------------------------------------------------------------------------
def render_report(r, command: str = "") -> str:
    """The HTML page of the gathered results ``r``."""
    from . import report_sections as s
    from .report_html import esc, page
    import matplotlib
    sections = [s.provenance(r), s.quality(r), s.coverage(r), s.spectra(r), s.per_incidence(r), s.ranking(r),
                s.albedo(r), s.rtable(r), s.mixing(r)]
    if getattr(r, "lighting_installation", None) is not None:  # only when an installation was given
        from .report_lighting import section as lighting_section
        sections.append(lighting_section(r))
    now = datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%d %H:%M UTC")
    times = ", ".join(f"{k} {v:.1f} s" for k, v in r.steps.times.items())
    footer = (f"roadbrdf {esc(__version__)} · generated {esc(now)} · Python {esc(sys.version.split()[0])}, numpy "
              f"{esc(np.__version__)}, matplotlib {esc(matplotlib.__version__)}"
              + (f"<br>command: <code>{esc(command)}</code>" if command else "") + f"<br>times: {esc(times)}")
    subtitle = (f"Sample report of <strong>{esc(r.file['name'])}</strong> · models: {esc(', '.join(r.models))}"
                f" · per-incidence fits at {r.band:g} nm")
    return page(f"roadbrdf report: {r.sample}", subtitle, s.summary(r), sections, footer)


def _check_output(output: str, inputs) -> None:
    if output != "-":
        folder = os.path.dirname(os.path.abspath(output))
        if not os.path.isdir(folder):
            raise InputError(f"-o: folder '{folder}' does not exist")
        if os.path.isdir(output):
            raise InputError(f"-o: '{output}' is a folder")
    _roadbrdf.check_distinct_files([(role, p) for role, p in inputs if p], [("-o", output)])


def write_report(data, output, models=DEFAULT_MODELS, formulation=None, wavelength=600.0, theta_i=None,
                 sun_zenith="0:60:30", atmosphere="spectrl2", illuminant="A", multistart=8, fix=None,
                 free_weights=False, folds=5, threads=None, quiet=True, command="", installation=None,
                 lighting_class=None, average_duplicates=False):
    """Write the report of the dataset ``data`` to ``output`` (HTML, atomically; ``"-"``: standard output)
    and return the gathered results. Arguments as ``roadbrdf report``'s options; ``atmosphere=None``: no
    sky model (no blue-sky). Errors in the input are :class:`roadbrdf.InputError`, raised before the
    long steps where they can be seen at once (missing file or folder, unknown model)."""
    data, output = os.fspath(data), os.fspath(output)
    if not os.path.isfile(data):
        raise InputError(f"DATA: '{data}': no such file")
    installation = None if installation is None else os.fspath(installation)
    inputs = [("DATA", data), ("--formulation", formulation), ("--installation", installation)]
    if formulation is not None and os.path.isfile(formulation):  # its component fits are inputs too
        inputs += _roadbrdf.formulation_input_files(os.fspath(formulation))
    _check_output(output, inputs)
    steps = _Steps(quiet, 6 + 2 * (formulation is not None) + (installation is not None))
    try:
        r = gather(data, models, formulation, wavelength, theta_i, sun_zenith, atmosphere, illuminant, multistart,
                   fix, free_weights, folds, threads, quiet, installation=installation, lighting_class=lighting_class,
                   average_duplicates=average_duplicates, _steps=steps)
        text = render_report(r, command)
        write_text_atomic(output, text)
    except BaseException:
        steps.close(failed=True)
        raise
    steps.close()
    r.html = text
    total = time.monotonic() - r.steps.start
    r.steps.say(f"wrote {output} ({len(text.encode()) / 1024:.0f} KiB, {total:.1f} s)")
    return r


# ---- command line ----------------------------------------------------------------------------------
class _Parser(argparse.ArgumentParser):
    """argparse with the program's errors: ``roadbrdf report: error: ...``, status 2, nearest option named."""

    def error(self, message):
        import re
        unknown = re.search(r"unrecognized arguments: (\S+)", message)
        if unknown:
            word = unknown.group(1).split("=")[0]
            names = [o for a in self._actions for o in a.option_strings]
            message = f"unknown option '{word}'{_roadbrdf.did_you_mean(word, names)}"
        self.exit(2, f"roadbrdf report: error: {message}; see 'roadbrdf report --help'\n")


def _fix_items(items):
    out = {}
    for item in items or []:
        name, eq, value = item.partition("=")
        try:
            out[name] = float(value) if eq and name else None
        except ValueError:
            out[name] = None
        if out[name] is None or not np.isfinite(out[name]):
            raise InputError(f"--fix expects NAME=VALUE (a number), got '{item}'")
    return out


def main(argv=None) -> int:
    """``python3 -m roadbrdf.report DATA.csv -o REPORT.html`` (also ``roadbrdf report``)."""
    p = _Parser(prog="roadbrdf report", description="The report of one sample: one self-contained HTML page "
                "(provenance, quality check, coverage, figures, per-incidence fits, model ranking, albedo, "
                "r-table, mixing prediction). See docs/report.md.")
    p.add_argument("data", metavar="DATA.csv", help="the sample's dataset (wide or long CSV)")
    p.add_argument("-o", "--output", required=True, metavar="REPORT.html", help="the page to write ('-': standard output)")
    p.add_argument("--model", action="append", metavar="M",
                   help=f"model to fit (repeatable; default: {' and '.join(DEFAULT_MODELS)}; see `roadbrdf models`)")
    p.add_argument("--formulation", metavar="F.json", help="the sample's formulation: add the mixing predictions "
                   "(its components' fit files must exist; docs/mixing.md)")
    p.add_argument("--wavelength", type=float, default=600.0,
                   help="wavelength [nm] of the per-incidence fits, tables and figures (nearest band; default 600)")
    p.add_argument("--theta-i", type=float, help="incidence [deg] of the angular figures (default: the middle one measured)")
    p.add_argument("--sun-zenith", default="0:60:30", help="sun zenith angles [deg] of the albedo (default 0:60:30)")
    p.add_argument("--atmosphere", default="spectrl2",
                   help="sky of the blue-sky albedo and solar weights: spectrl2[:aod=...] (default) or none")
    p.add_argument("--illuminant", default="A", help="photometric weighting of the r-table: A (default), D65 or FILE")
    p.add_argument("--multistart", type=int, default=8, help="starting points per fit (default 8)")
    p.add_argument("--fix", action="append", metavar="NAME=VALUE", help="hold a parameter (repeatable)")
    p.add_argument("--free-weights", action="store_true",
                   help="fit the component weights of composites too (default: held at 1)")
    p.add_argument("--folds", type=int, default=5, help="cross-validation folds of the mixing comparison (default 5)")
    p.add_argument("--threads", type=int, default=None,
                   help="threads of the fit over all wavelengths (default: every core; the result does not depend on it)")
    p.add_argument("--quiet", action="store_true", help="no progress lines on standard error")
    p.add_argument("--installation", metavar="INSTALLATION.json",
                   help="add a road-lighting section: this installation with the sample's best fit as its pavement "
                        "(docs/lighting.md)")
    p.add_argument("--lighting-class", metavar="M", help="with --installation: the M class (M1-M6) whose least "
                   "flux and power per km the section gives")
    p.add_argument("--average-duplicates", action="store_true",
                   help="average dataset rows with the same geometry (else an error), as every command does")
    a = p.parse_args(argv)
    command = "roadbrdf report " + " ".join(argv if argv is not None else sys.argv[1:])
    atmosphere = None if a.atmosphere.lower() == "none" else a.atmosphere
    write_report(a.data, a.output, a.model or DEFAULT_MODELS, a.formulation, a.wavelength, a.theta_i, a.sun_zenith,
                 atmosphere, a.illuminant, a.multistart, _fix_items(a.fix), a.free_weights, a.folds, a.threads,
                 a.quiet, command, installation=a.installation, lighting_class=a.lighting_class,
                 average_duplicates=a.average_duplicates)
    return 0


class _Terminated(KeyboardInterrupt):
    """SIGTERM: the report stops as on Ctrl-C (its temporary folder removed), with the status of SIGTERM."""


def _terminate(signum, frame):
    raise _Terminated()


def _run() -> int:
    import signal
    signal.signal(signal.SIGTERM, _terminate)
    try:
        return main()
    except (ValueError, OSError) as e:  # InputError is a ValueError
        text = str(e) if not isinstance(e, OSError) or not e.filename else f"{e.filename}: {e.strerror}"
        text = text.replace("`average_duplicates`", "--average-duplicates")  # the library's field, as a flag
        print(f"roadbrdf report: error: {text}", file=sys.stderr)
        return 2
    except Exception as e:  # noqa: BLE001 - a bug: its traceback, and the program's status for internal errors
        import traceback
        traceback.print_exc()
        print(f"roadbrdf report: internal error: {type(e).__name__}: {e}", file=sys.stderr)
        return 3
    except KeyboardInterrupt as e:
        print("roadbrdf report: interrupted", file=sys.stderr)
        return 143 if isinstance(e, _Terminated) else 130


if __name__ == "__main__":
    sys.exit(_run())
