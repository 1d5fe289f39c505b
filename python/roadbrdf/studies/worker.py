"""What every study or campaign task runs on its worker around the task itself (:func:`guarded`): the build
check, the CPU time, and the failure policy.

- A task carries the build fingerprint of the process that made its key (``roadbrdf.core.build_fingerprint``).
  A worker whose own fingerprint differs (a Dask worker with another roadbrdf installed) refuses it with
  :class:`BuildMismatch`, which stops the study: its results would be stored under a key that promises the
  submitter's build.
- Any other exception of the task is the candidate's recorded failure, ``internal error: TYPE: MESSAGE``, with the
  traceback in the result (kept in the results store); the study goes on. ``--retry-failed`` runs it again.
"""

from __future__ import annotations

import socket
import time
import traceback
from typing import Any, Callable, Dict

from ..core import InputError, build_fingerprint


class BuildMismatch(InputError):
    """A task made by another roadbrdf build than this worker's (its results would not be the submitter's)."""


def check_build(task: Dict[str, Any]) -> None:
    """Raise :class:`BuildMismatch` when ``task["build"]`` is not this process's build fingerprint."""
    mine = build_fingerprint()
    theirs = task.get("build")
    if theirs != mine:
        from .. import _roadbrdf
        raise BuildMismatch(
            f"worker {socket.gethostname()}: its roadbrdf build (fingerprint {mine[:16]}, {_roadbrdf.__file__}) "
            f"differs from the build that submitted the task (fingerprint {str(theirs)[:16]}): results would not "
            "be the same bit for bit; install the same roadbrdf on every worker as on the submitting machine "
            "(docs/studies.md \"Execution\")")


def guarded(run: Callable[[Dict[str, Any], Any], Dict[str, Any]], task: Dict[str, Any], shared: Any) -> Dict[str, Any]:
    """``run(task, shared)`` (a dict with ``rows`` and ``error``) after :func:`check_build`, with its CPU time
    (``seconds``) and this worker's ``build``; an exception other than a build mismatch becomes the result
    ``{"rows": [], "error": "internal error: TYPE: MESSAGE", "traceback": ...}``."""
    check_build(task)
    start = time.process_time()
    try:
        result = run(task, shared)
    except Exception as e:  # noqa: BLE001 - the failure policy: a candidate's bug must not stop the others
        result = {"rows": [], "error": f"internal error: {type(e).__name__}: {e}",
                  "traceback": traceback.format_exc()}
    result["seconds"] = time.process_time() - start  # CPU time of the task (the store keeps it; not in the CSV)
    result["build"] = build_fingerprint()
    return result
