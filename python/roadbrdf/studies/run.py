"""Running a study: tasks keyed by content, executors (local processes or a Dask cluster), progress, the table.

A task's key is the SHA-256 of the canonical JSON of (the candidate's formulation with every fit file replaced by
the SHA-256 of its bytes, its mastic exposure, the prediction settings, the replicate, the roadbrdf version and
the build fingerprint: roadbrdf.core.build_fingerprint). The same key means the same computation by the same code,
so a result in the store is reused whatever study, order, executor or machine produced it, and never one of
another build. The random seed of the physical path is taken from the same hash without the build. The task
carries the fingerprint, and a worker of another build refuses it (worker.py).
"""

from __future__ import annotations

import hashlib
import json
import os
import sys
import time

from ..core import build_fingerprint
from .design import apply, candidates
from .evaluate import run_task
from .spec import InputError


def _fit_ref(study, path):
    return "sha256:" + study.fit_hash[os.path.abspath(path)]


def _sha256(entry):
    return hashlib.sha256(json.dumps(entry, sort_keys=True, separators=(",", ":")).encode()).hexdigest()


def make_tasks(study, version, build=None):
    """(index, point, replicate, key, task) for every candidate; ``build``: the build fingerprint in the keys
    (default: this process's, roadbrdf.core.build_fingerprint)."""
    build = build or build_fingerprint()
    out = []
    for index, point, replicate in candidates(study):
        error = None
        try:
            formulation, mastic_fraction = apply(study, point)
        except InputError as e:
            formulation, mastic_fraction, error = None, None, str(e)
        if formulation is not None:
            for c in formulation["components"]:
                if isinstance(c.get("fit"), str):
                    c["fit"] = _fit_ref(study, c["fit"])
            if isinstance(formulation.get("mastic"), dict) and isinstance(formulation["mastic"].get("fit"), str):
                formulation["mastic"]["fit"] = _fit_ref(study, formulation["mastic"]["fit"])
        entry = {"formulation": formulation, "mastic_fraction": mastic_fraction, "predictions": study.predictions,
                 "replicate": replicate, "error": error, "roadbrdf": version}
        # The seed comes from the candidate without the build, so that another build draws the same virtual
        # samples (and a build that changes nothing in the physical path gives the same numbers).
        seed = int(_sha256(entry)[:12], 16) % 2147483647 + 1
        entry["build"] = build
        key = _sha256(entry)
        task = dict(entry)
        task["key"] = key
        task["seed"] = seed
        out.append((index, point, replicate, key, task))
    return out


class Progress:
    """Done, in flight, failed and the estimated time left, on standard error (at most once a second)."""

    def __init__(self, total, cached, enabled, running="running", label="study"):
        self.total, self.cached, self.enabled, self.running, self.label = total, cached, enabled, running, label
        self.done = self.failed = 0
        self.bug_reported = False
        self.start = time.monotonic()
        self.last = 0.0

    def update(self, running, force=False):
        now = time.monotonic()
        if not self.enabled or (not force and now - self.last < 1.0):
            return
        self.last = now
        left = self.total - self.cached - self.done
        if self.done:
            eta = (now - self.start) / self.done * left
            eta_text = f"{int(eta) // 3600}:{int(eta) % 3600 // 60:02d}:{int(eta) % 60:02d}"
        else:
            eta_text = "?"
        print(f"{self.label}: {self.cached + self.done}/{self.total} done ({self.cached} from the store), {running} {self.running}, "
              f"{self.failed} failed, about {eta_text} left", file=sys.stderr, flush=True)


def _finished(key, result, store, progress):
    """A task's result arrived: stored, counted; the first internal error's traceback on standard error (the
    store keeps every one)."""
    store.add(key, result)
    progress.done += 1
    if result["error"] is not None:
        progress.failed += 1
        if result.get("traceback") and not progress.bug_reported:
            progress.bug_reported = True
            where = f"; every one's traceback is in {store.path}" if store.path else ""
            print(f"roadbrdf: warning: task {key[:12]} failed with an internal error (a bug in roadbrdf: please "
                  f"report it); the study goes on, the candidate is recorded as failed{where}:\n"
                  f"{result['traceback'].rstrip()}", file=sys.stderr, flush=True)


def _local(pending, shared, workers, store, progress, function):
    import concurrent.futures as cf
    import multiprocessing
    ctx = multiprocessing.get_context(_start_method())
    with cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_init_worker,
                                initargs=(function, shared)) as pool:
        futures = {}
        for key, task in pending:
            futures[pool.submit(_run_cached, task)] = key
        try:
            for future in cf.as_completed(futures):
                _finished(futures[future], future.result(), store, progress)
                progress.update(min(workers, len(futures) - progress.done))
        except BaseException:
            for f in futures:
                f.cancel()
            raise


_FUNCTION = None
_SHARED = None


def _start_method():
    """'fork' when the caller runs a single thread (the usual script or the command line: the workers start at
    once and the caller's main script is not run again), else 'forkserver' (forking a process with other threads
    running can deadlock; the workers then import the caller's main module, which needs the usual
    ``if __name__ == "__main__":`` guard)."""
    try:
        threads = len(os.listdir("/proc/self/task"))
    except OSError:
        threads = 2
    return "fork" if threads == 1 else "forkserver"


def _init_worker(function, shared):
    global _FUNCTION, _SHARED
    _FUNCTION, _SHARED = function, shared


def _run_cached(task):
    return _FUNCTION(task, _SHARED)


def _dask(pending, shared, scheduler, store, progress, function):
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise InputError(f"--scheduler {scheduler}: the Python package 'distributed' is not installed "
                         "(Debian: apt-get install python3-distributed)") from None
    try:
        client = Client(scheduler, timeout=30)
    except (OSError, TimeoutError) as e:
        raise InputError(f"--scheduler {scheduler}: cannot connect: {e}") from None
    try:
        scattered = client.scatter(shared, broadcast=True)
        futures = {}
        for key, task in pending:
            futures[client.submit(function, task, scattered, key=f"roadbrdf-study-{key}", pure=False)] = key
        for future in as_completed(list(futures)):
            _finished(futures[future], future.result(), store, progress)
            progress.update(len(futures) - progress.done)
    finally:
        client.close()


def columns(study):
    """The CSV header: identification, the variables (with units), the outputs (with units)."""
    p = study.predictions
    head = ["candidate", "replicate", "key", "status", "error", "method"]
    for v in study.variables:
        unit = {"%": "%", "1": "1", "": "library"}[v["unit"]]
        head.append(f"{v['name']} [{unit}]")
    out = []
    for z in p["sun_zenith_deg"]:
        out += [f"black_sky_{z:g}deg", f"black_sky_{z:g}deg_error"]
    out += ["white_sky", "white_sky_error"]
    if p["diffuse_fraction"] is not None or p["atmosphere"] is not None:
        for z in p["sun_zenith_deg"]:
            out += [f"blue_sky_{z:g}deg", f"blue_sky_{z:g}deg_error"]
    units = {name: "1" for name in out}
    rt = ["Q0", "Q0_error", "S1", "S1_error", "Qd", "Qd_error", "class"]
    if p["path"] == "physical" and not p["physical"]["rtable"]:
        rt = []
    units.update({"Q0": "sr^-1", "Q0_error": "sr^-1", "Qd": "sr^-1", "Qd_error": "sr^-1", "S1": "1",
                  "S1_error": "1", "class": "R"})
    out += rt
    if p["path"] == "physical":
        out += ["mpd_mm", "exposed_mastic_fraction"]
        units.update({"mpd_mm": "mm", "exposed_mastic_fraction": "1"})
    return head, out, units


def table(study, tasks, store):
    """Header and rows of the results CSV, in candidate order (one row per candidate and method)."""
    head, out, units = columns(study)
    header = head + [f"{name} [{units[name]}]" for name in out]
    rows = []
    for index, point, replicate, key, _ in tasks:
        record = store.results[key]
        ident = [index + 1, replicate, key]
        values = [point[v["name"]] for v in study.variables]
        if record["error"] is not None:
            rows.append(ident + ["failed", record["error"], ""] + values + [None] * len(out))
            continue
        for r in record["rows"]:
            rows.append(ident + ["ok", "", r["method"]] + values + [r.get(name) for name in out])
    return header, rows


def execute(study, store, scheduler=None, workers=None, progress=True, retry_failed=False, version=""):
    """Run the study's tasks that the store lacks; return (tasks, number computed)."""
    tasks = make_tasks(study, version)
    computed = run_pending(f"study '{study.name}'", tasks, study.fits, run_task, store, scheduler, workers, progress,
                           retry_failed)
    return tasks, computed


def run_pending(title, tasks, shared, function, store, scheduler, workers, progress, retry_failed, shared_remote=None,
                noun="candidates"):
    """Run function(task, shared) for every distinct task key the store lacks (or failed, with retry_failed), on
    local processes or the Dask scheduler, adding each result to the store as it arrives; return how many ran.
    ``tasks``: (..., key, task) tuples, the key in the last but one place. ``shared_remote``: what the Dask
    workers get instead of ``shared`` (data the local processes read from disk), when it differs."""
    todo = []
    seen = set()
    for *_, key, task in tasks:
        if key in seen:
            continue  # the same candidate twice in a design (e.g. a grid with repeated choices) runs once
        seen.add(key)
        record = store.results.get(key)
        if record is None or (retry_failed and record["error"] is not None):
            todo.append((key, task))
    cached = len(seen) - len(todo)
    bar = Progress(len(seen), cached, progress, "running or queued" if scheduler else "running", title.split()[0])
    if progress:
        build = tasks[0][-1]["build"] if tasks else None
        other = sum(1 for r in store.results.values() if r.get("build") != build)
        print(f"{title}: {len(tasks)} {noun}, {cached} already in the store, {len(todo)} to compute"
              f"{' on ' + scheduler if scheduler else ''}"
              f"{f' ({other} results of other roadbrdf builds in the store are not used)' if other else ''}",
              file=sys.stderr, flush=True)
    if todo:
        if scheduler:
            _dask(todo, shared if shared_remote is None else shared_remote, scheduler, store, bar, function)
        else:
            n = workers or os.cpu_count() or 1
            _local(todo, shared, min(n, len(todo)), store, bar, function)
        bar.update(0, force=True)
    return len(todo)
