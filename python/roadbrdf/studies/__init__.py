"""Design studies: sweep a formulation space, predict every candidate, collect the table (docs/studies.md);
and campaign fitting: fit every measured sample of a folder or list and collect their parameters (campaign.py).

``roadbrdf.study(STUDY, output=...)`` and ``roadbrdf study STUDY.json -o RESULTS.csv`` are the same code: the
command line runs :func:`main` (``python3 -m roadbrdf.studies``). The file's ``format`` says which it is.
"""

from __future__ import annotations

import json
import os
import sys

from .spec import InputError, read_study

__all__ = ["study", "read_study", "main"]


def _inputs(study):
    files = [("STUDY", study.path), ("base", study.base_path)]
    files += [("fit", path) for path in sorted(study.fit_hash)]
    return [(role, path) for role, path in files if os.path.exists(path)]


def _is_campaign(source):
    from .campaign import is_campaign
    if isinstance(source, dict):
        return is_campaign(source)
    try:
        with open(os.fspath(source), encoding="utf-8") as f:
            return is_campaign(json.load(f))
    except (OSError, ValueError, RecursionError):
        return False  # read_study reports what is wrong with the file


def study(source, output=None, store=None, scheduler=None, workers=None, progress=True, retry_failed=False,
          worker_wait=30.0):
    """Run a design study (or a campaign fit) and return its table as a list of dicts (CSV header -> value).

    ``source``: a study file (``"format": "roadbrdf-study"``) or its content as a dict. ``output``: the results
    CSV (``-`` = standard output), written once every candidate is done. ``store``: the results store (JSON
    lines, appended as tasks finish; default ``OUTPUT.store.jsonl``, none without ``output``): a re-run computes
    only what it lacks. ``scheduler``: a Dask scheduler address (``tcp://HOST:PORT``; default
    ``$ROADBRDF_SCHEDULER``), else ``workers`` local processes (default: all cores). ``worker_wait``: seconds to
    wait for the scheduler's first worker before giving up (default 30). ``progress``: report on
    standard error. ``retry_failed``: run failed candidates again. Errors in the study raise InputError naming
    the file and the JSON key.

    A ``"format": "roadbrdf-campaign"`` file fits every sample it lists with the same models and settings instead
    (one task per sample; the table has one row per sample, model and wavelength: docs/studies.md "Campaign
    fitting").
    """
    from .. import _roadbrdf
    from .run import execute, run_pending, table
    from .store import Store, check_output, write_csv
    campaign = _is_campaign(source)
    if campaign:
        from .campaign import read_campaign
        s = read_campaign(source)
        inputs = [("CAMPAIGN", s.path)] + [("samples", sample["path"]) for sample in s.samples]
    else:
        s = read_study(source)
        inputs = _inputs(s)
    if scheduler is None:
        scheduler = os.environ.get("ROADBRDF_SCHEDULER") or None
    if workers is not None and (isinstance(workers, bool) or not isinstance(workers, int) or workers < 1):
        raise InputError(f"workers: expected a positive integer, got {workers!r}")
    if scheduler is not None and workers is not None:
        raise InputError("give workers (local processes) or a scheduler (Dask), not both")
    if isinstance(worker_wait, bool) or not isinstance(worker_wait, (int, float)) or not 0 < worker_wait < 1e6:
        raise InputError(f"worker_wait: expected seconds in (0, 1e6), got {worker_wait!r}")
    if store is None and output is not None and os.fspath(output) != "-" and (
            not os.path.exists(os.fspath(output)) or os.path.isfile(os.fspath(output))):
        store = os.fspath(output) + ".store.jsonl"  # not next to a device or FIFO (/dev/stdout): no store then
    outputs = [("-o", os.fspath(output))] if output is not None else []
    if store is not None:
        outputs.append(("--store", os.fspath(store)))
    _roadbrdf.check_distinct_files([(role, p) for role, p in inputs if os.path.exists(p)], outputs)
    for role, path in outputs:
        check_output(path, role)
    if not campaign:
        from .run import check_size
        check_size(s, progress)
    results = Store(store)
    try:
        if campaign:
            from . import campaign as c
            tasks = c.make_tasks(s, _roadbrdf.__version__)
            remote = c.texts_of(s) if scheduler else None
            run_pending(f"campaign '{s.name}'", tasks, None, c.fit_sample, results, scheduler, workers, progress,
                        retry_failed, shared_remote=remote, noun="samples", worker_wait=worker_wait)
        else:
            tasks, _ = execute(s, results, scheduler, workers, progress, retry_failed, _roadbrdf.__version__,
                               worker_wait)
    finally:
        results.close()
    if campaign:
        header, rows = c.table(s, tasks, results)
        c.write_fit_files(s, tasks, results)
        failures = {results.results[key]["error"] for *_, key, _ in tasks}
        if None not in failures and len(failures) == 1:
            # The same error for every sample is the campaign's settings', not the samples'.
            raise InputError(f"every sample failed: {failures.pop()}")
    else:
        if progress and len(tasks) >= 100000:
            print(f"study '{s.name}': collecting the table of {len(tasks)} candidates", file=sys.stderr, flush=True)
        header, rows = table(s, tasks, results)
    if output is not None:
        write_csv(os.fspath(output), header, rows)
    return [dict(zip(header, row)) for row in rows]


def main(argv=None):
    """``roadbrdf study STUDY.json -o RESULTS.csv ...`` (``python3 -m roadbrdf.studies``)."""
    import argparse
    parser = argparse.ArgumentParser(prog="roadbrdf study",
                                     description="Design study: predict every candidate formulation of STUDY.json; "
                                                 "or campaign fitting: fit every sample of CAMPAIGN.json "
                                                 "(docs/studies.md).")
    parser.add_argument("study", help="study file (\"format\": \"roadbrdf-study\" or \"roadbrdf-campaign\")")
    parser.add_argument("-o", "--output", required=True, help="results CSV (- = standard output)")
    parser.add_argument("--store", help="results store (default: OUTPUT.store.jsonl)")
    parser.add_argument("--scheduler", help="Dask scheduler tcp://HOST:PORT (default: $ROADBRDF_SCHEDULER)")
    parser.add_argument("--workers", type=int, help="local worker processes (default: all cores)")
    parser.add_argument("--worker-wait", type=float, default=30.0, metavar="SECONDS",
                        help="with --scheduler: how long to wait for a first Dask worker (default 30 s)")
    parser.add_argument("--retry-failed", action="store_true", help="run failed candidates again")
    parser.add_argument("--quiet", action="store_true", help="no progress on standard error")
    a = parser.parse_args(argv)
    rows = study(a.study, a.output, a.store, a.scheduler, a.workers, not a.quiet, a.retry_failed, a.worker_wait)
    if a.output != "-" and not a.quiet:
        failed = sum(1 for r in rows if r["status"] == "failed")
        print(f"{a.output}: {len(rows)} rows, {failed} failed", file=sys.stderr)
    return 0
