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
from .design import apply, candidate_count, candidates
from .evaluate import run_task
from .spec import LIGHTING_OUTPUTS, InputError


def _fit_ref(study, path):
    return "sha256:" + study.fit_hash[os.path.abspath(path)]


def _sha256(entry):
    return hashlib.sha256(json.dumps(entry, sort_keys=True, separators=(",", ":")).encode()).hexdigest()


class Tasks:
    """The study's tasks, (index, point, replicate, key, task) in candidate order, made again at each iteration
    (a design of millions of candidates is never held in memory: only the keys are, while it runs)."""

    def __init__(self, study, version, build=None):
        self.study, self.version, self.build = study, version, build or build_fingerprint()

    def __len__(self):
        return candidate_count(self.study)

    def __iter__(self):
        return iter_tasks(self.study, self.version, self.build)


def make_tasks(study, version, build=None):
    """(index, point, replicate, key, task) for every candidate, as a list; ``build``: the build fingerprint in
    the keys (default: this process's, roadbrdf.core.build_fingerprint)."""
    return list(iter_tasks(study, version, build or build_fingerprint()))


def iter_tasks(study, version, build):
    """The tasks of :func:`make_tasks`, one at a time."""
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
        yield index, point, replicate, key, task


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


def _in_flight_limit(workers):
    """Tasks handed to the executor at a time: enough to keep every worker busy, few enough that a design of
    millions of candidates is submitted as it runs (memory stays flat, an interruption is seen at once)."""
    return 4 * workers + 16


def _local(pending, shared, workers, store, progress, function):
    import concurrent.futures as cf
    import multiprocessing
    import shutil
    import signal
    from ..scratch import make_scratch
    method = _start_method()
    ctx = multiprocessing.get_context(method)
    # The workers' temporary files go to one folder that this process removes however the pool ends (a worker
    # killed at an interruption cannot remove its own); one left by a study killed with SIGKILL is removed by
    # the next study (roadbrdf/scratch.py).
    scratch = make_scratch("roadbrdf-study-")
    # A forked worker's parent is this process; a fork-server worker's is the fork server.
    pool = cf.ProcessPoolExecutor(max_workers=workers, mp_context=ctx, initializer=_init_worker,
                                  initargs=(function, shared, os.getpid() if method == "fork" else None, scratch))
    # The workers are born with SIGINT blocked: a Ctrl-C reaches the whole process group, and one arriving
    # while a worker starts would kill it before _init_worker ignores SIGINT (the pool then breaks and the
    # study reports a dead worker instead of the interruption). The pool starts its workers (or its fork
    # server, whose children inherit its mask) at the first submission; this process's own SIGINT stays
    # pending until then and is delivered when the mask is restored.
    blocked = signal.pthread_sigmask(signal.SIG_BLOCK, {signal.SIGINT})

    def started():
        signal.pthread_sigmask(signal.SIG_SETMASK, blocked)

    try:
        _submit_and_collect(pool, pending, workers, store, progress, started)
    except BaseException:
        _stop(pool)
        raise
    finally:
        started()
        shutil.rmtree(scratch, ignore_errors=True)


def _submit_and_collect(pool, pending, workers, store, progress, started=lambda: None):
    """Hand the pending tasks to the pool a few at a time, store each result as it arrives; ``started`` is
    called once the first tasks are submitted (the pool's workers exist)."""
    import concurrent.futures as cf
    in_flight = {}
    pending = iter(pending)
    more = True
    while True:
        while more and len(in_flight) < _in_flight_limit(workers):
            item = next(pending, None)
            if item is None:
                more = False
            else:
                in_flight[pool.submit(_run_cached, item[1])] = item[0]
        started()
        if not in_flight:
            break
        done, _ = cf.wait(in_flight, timeout=1.0, return_when=cf.FIRST_COMPLETED)
        for future in done:
            try:
                result = future.result()
            except cf.process.BrokenProcessPool:
                raise InputError("a worker process ended abruptly (killed, or out of memory); the results store "
                                 "keeps every finished candidate: run again to resume") from None
            _finished(in_flight.pop(future), result, store, progress)
        progress.update(min(workers, len(in_flight)))
    pool.shutdown(wait=True)


def _stop(pool):
    """End a pool at once (an interruption or an error): queued tasks cancelled, running workers killed (their
    results are lost; the store keeps every finished one)."""
    processes = list((getattr(pool, "_processes", None) or {}).values())
    pool.shutdown(wait=False, cancel_futures=True)
    for process in processes:
        try:
            process.kill()
        except (OSError, AttributeError, ValueError):
            pass
    for process in processes:
        try:
            process.join(5)
        except (OSError, AttributeError, ValueError, AssertionError):
            pass


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


def _die_with_parent(parent_pid):
    """Make this worker end when the process that started it ends, however it ends (``kill -9`` too): Linux's
    parent-death signal (prctl PR_SET_PDEATHSIG), checked once against a parent that ended before it was set
    (``parent_pid``: the expected parent, None when unknown). A fork-server worker's parent is the fork server,
    which ends when the study does."""
    import ctypes
    import signal
    pr_set_pdeathsig = 1
    try:
        libc = ctypes.CDLL(None, use_errno=True)
        libc.prctl(pr_set_pdeathsig, signal.SIGKILL, 0, 0, 0)
    except (OSError, AttributeError):
        return
    parent = os.getppid()
    if parent == 1 or (parent_pid is not None and parent != parent_pid):
        os._exit(1)  # the study is already gone


def _init_worker(function, shared, parent_pid, scratch):
    global _FUNCTION, _SHARED
    import signal
    import tempfile
    _die_with_parent(parent_pid)
    tempfile.tempdir = scratch
    # Ctrl-C reaches the whole foreground process group: the study ends its workers itself (_stop), and a worker
    # must not report a KeyboardInterrupt as the candidate's failure.
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, {signal.SIGINT})  # blocked at birth (_local)
    _FUNCTION, _SHARED = function, shared


def _run_cached(task):
    return _FUNCTION(task, _SHARED)


def _dask(pending, shared, scheduler, store, progress, function, worker_wait=30.0):
    try:
        from distributed import Client, as_completed
    except ImportError:
        raise InputError(f"--scheduler {scheduler}: the Python package 'distributed' is not installed "
                         "(Debian: apt-get install python3-distributed)") from None
    import asyncio
    import concurrent.futures as cf
    import logging
    # distributed logs each failed reconnection to a scheduler that went away with its traceback; the study reports
    # the failure itself, in one line.
    for name in [n for n in logging.root.manager.loggerDict if n.split(".")[0] == "distributed"] + ["distributed"]:
        logging.getLogger(name).setLevel(logging.CRITICAL)
    try:
        client = Client(scheduler, timeout=30)
    except (OSError, TimeoutError, cf.TimeoutError) as e:
        raise InputError(f"--scheduler {scheduler}: cannot connect: {e}") from None
    try:
        try:
            client.wait_for_workers(1, timeout=worker_wait)
        except (TimeoutError, cf.TimeoutError):
            raise InputError(f"--scheduler {scheduler}: the scheduler has no workers (none joined within {worker_wait:g} s); "
                             f"start some (dask-worker {scheduler}) and run again") from None
        limit = _in_flight_limit(max(1, len(client.scheduler_info().get("workers", {}))))
        scattered = client.scatter(shared, broadcast=True)
        futures = {}
        pending = iter(pending)

        def submit():
            item = next(pending, None)
            if item is not None:
                key, task = item
                future = client.submit(function, task, scattered, key=f"roadbrdf-study-{key}", pure=False)
                futures[future] = key
            return item is not None

        while len(futures) < limit and submit():
            pass
        running = as_completed(list(futures))
        for future in running:
            _finished(futures.pop(future), future.result(), store, progress)
            if submit():
                running.add(list(futures)[-1])
            progress.update(len(futures))
    except (cf.CancelledError, asyncio.CancelledError, cf.TimeoutError, TimeoutError, OSError) as e:
        # A scheduler that went away (its futures are cancelled) or has no workers (scatter times out).
        what = type(e).__name__ + (f": {e}" if str(e) else "")
        raise InputError(f"--scheduler {scheduler}: the Dask cluster stopped working ({what}); the results store "
                         "keeps every finished candidate: run again to resume") from None
    except Exception as e:  # noqa: BLE001 - distributed's own errors (CommClosedError...) have no common base
        if type(e).__module__.split(".")[0] != "distributed":
            raise
        raise InputError(f"--scheduler {scheduler}: the Dask cluster stopped working ({type(e).__name__}: {e}); "
                         "the results store keeps every finished candidate: run again to resume") from None
    finally:
        try:
            client.close(timeout=10)
        except Exception:  # noqa: BLE001 - closing a client of a dead scheduler may fail in many ways
            pass


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
    if p.get("lighting") is not None:
        for name, unit, _ in LIGHTING_OUTPUTS:
            out.append(name)
            units[name] = unit
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


# Memory a result row takes while the study writes its table (the store's record, the table row and the returned
# dict): a fixed part and a part per column, in bytes. Measured with tracemalloc: 3.9 kB per row of 24 columns
# (a fast study of 2000 candidates, one method), taken as 1 kB + 120 B per column.
_BYTES_PER_ROW = 1000
_BYTES_PER_COLUMN = 120


def memory_available():
    """Bytes of memory available to a new allocation (MemAvailable of /proc/meminfo), or None when unknown."""
    try:
        with open("/proc/meminfo", encoding="ascii") as f:
            for line in f:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    return None


def check_size(study, progress=True, available=None):
    """Refuse, before any work, a study whose results do not fit in memory (the store's records, the table and the
    returned rows are held in memory); ``available``: bytes (default: :func:`memory_available`). The error names
    what sets the count: ``design.count``, the grid's levels, ``replicates``."""
    count = candidate_count(study)
    head, out, _ = columns(study)
    rows = 1 if study.predictions["path"] == "physical" else len(study.predictions["methods"])
    need = count * rows * (_BYTES_PER_ROW + _BYTES_PER_COLUMN * (len(head) + len(study.variables) + len(out)))
    available = memory_available() if available is None else available
    if available is not None and need > 0.8 * available:
        what = "design.count" if study.design["type"] != "grid" else "the grid's levels (variables[].values, levels)"
        raise InputError(f"{count} candidates ({what} x replicates) need about {need / 1e9:.1f} GB of memory for "
                         f"their results, more than the {available / 1e9:.1f} GB available: split the study into "
                         "smaller ones (they can share one results store)")
    if progress and count >= 100000:
        print(f"study '{study.name}': {count} candidates, about {need / 1e9:.1f} GB of memory for their results",
              file=sys.stderr, flush=True)


def execute(study, store, scheduler=None, workers=None, progress=True, retry_failed=False, version="",
            worker_wait=30.0):
    """Run the study's tasks that the store lacks; return (tasks, number computed). ``tasks`` is a :class:`Tasks`:
    iterating it makes the tasks again (they are never all in memory)."""
    tasks = Tasks(study, version)
    computed = run_pending(f"study '{study.name}'", tasks, study.fits, run_task, store, scheduler, workers, progress,
                           retry_failed, worker_wait=worker_wait)
    return tasks, computed


def run_pending(title, tasks, shared, function, store, scheduler, workers, progress, retry_failed, shared_remote=None,
                noun="candidates", worker_wait=30.0):
    """Run function(task, shared) for every distinct task key the store lacks (or failed, with retry_failed), on
    local processes or the Dask scheduler, adding each result to the store as it arrives; return how many ran.
    ``tasks``: (..., key, task) tuples, the key in the last but one place; iterated twice (first for the keys,
    then for the tasks to run, handed to the executor a few at a time). ``shared_remote``: what the Dask workers
    get instead of ``shared`` (data the local processes read from disk), when it differs."""
    todo = set()
    seen = set()
    total = build = None
    prepared = time.monotonic()
    try:
        total = len(tasks)
    except TypeError:
        pass
    for count, (*_, key, task) in enumerate(tasks, start=1):
        build = task.get("build") if build is None else build
        if progress and time.monotonic() - prepared >= 1.0:
            prepared = time.monotonic()
            print(f"{title.split()[0]}: preparing: {count}/{total if total is not None else '?'} {noun}",
                  file=sys.stderr, flush=True)
        if key in seen:
            continue  # the same candidate twice in a design (e.g. a grid with repeated choices) runs once
        seen.add(key)
        record = store.results.get(key)
        if record is None or (retry_failed and record["error"] is not None):
            todo.add(key)
    count = len(todo)
    cached = len(seen) - count
    del seen
    bar = Progress(cached + count, cached, progress, "running or queued" if scheduler else "running",
                   title.split()[0])
    if progress:
        other = sum(1 for r in store.results.values() if r.get("build") != build)
        print(f"{title}: {total if total is not None else cached + count} {noun}, {cached} already in the store, "
              f"{count} to compute{' on ' + scheduler if scheduler else ''}"
              f"{f' ({other} results of other roadbrdf builds in the store are not used)' if other else ''}",
              file=sys.stderr, flush=True)

    def pending():
        for *_, key, task in tasks:
            if key in todo:
                todo.discard(key)  # once, in candidate order
                yield key, task

    if count:
        if scheduler:
            _dask(pending(), shared if shared_remote is None else shared_remote, scheduler, store, bar, function,
                  worker_wait)
        else:
            n = workers or os.cpu_count() or 1
            _local(pending(), shared, min(n, count), store, bar, function)
        bar.update(0, force=True)
    return count
