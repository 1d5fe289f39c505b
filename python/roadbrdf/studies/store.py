"""The results store and the results CSV.

The store is an append-only JSON-lines file: a header line, then one line per finished task (its key, its rows
or its error and, for an internal error, its traceback; the build fingerprint of the worker that computed it, the
one in the key). A line is written with one ``write`` on an ``O_APPEND`` descriptor and synced before the next
task's result is taken, so a killed study leaves complete lines plus at most one torn last line; that line is
reported and removed when the store is opened again (its task runs again). The store is locked while a study
uses it. Lines of tasks that no longer belong to the study (an edited study file) stay in the store.

The CSV is written once the study is complete, atomically (temporary file in the same folder, fsync, rename,
fsync of the folder), or to standard output for ``-``.
"""

from __future__ import annotations

import fcntl
import json
import os
import sys

from ..core import write_text_atomic
from .spec import InputError

_HEADER = {"format": "roadbrdf-study-store", "version": 1}


class Store:
    """Finished task results by key, backed by a file (or only in memory when ``path`` is None)."""

    def __init__(self, path):
        self.path = None if path is None else os.path.abspath(path)
        self.results = {}
        self._fd = None
        if self.path is None:
            return
        fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_CLOEXEC, 0o644)
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise InputError(f"{self.path}: the results store is in use by another running study") from None
        self._fd = fd
        self._load()

    def _load(self):
        with open(self._fd, "rb", closefd=False) as f:
            f.seek(0)
            data = f.read()
        if not data:
            self._append(_HEADER)
            return
        end = data.rfind(b"\n") + 1
        if end < len(data):
            print(f"roadbrdf: warning: {self.path}: removed a torn last line of {len(data) - end} bytes (a study "
                  "was killed while writing it); its task runs again", file=sys.stderr)
            os.ftruncate(self._fd, end)
            os.fsync(self._fd)
            data = data[:end]
        for number, line in enumerate(data.splitlines(), start=1):
            try:
                record = json.loads(line)
            except json.JSONDecodeError as e:
                raise InputError(f"{self.path}:{number}:{e.colno}: not a results-store line: {e.msg}") from None
            if number == 1:
                if record != _HEADER:
                    raise InputError(f"{self.path}:1:1: not a roadbrdf study results store")
                continue
            if not isinstance(record, dict) or "key" not in record:
                raise InputError(f"{self.path}:{number}:1: a results-store line needs a \"key\"")
            # A key appears once unless a failed task was retried; the later line wins (it is the newer result).
            self.results[record["key"]] = record

    def _append(self, record):
        line = (json.dumps(record, separators=(",", ":"), allow_nan=True) + "\n").encode()
        written = os.write(self._fd, line)
        if written != len(line):
            raise OSError(f"{self.path}: short write ({written} of {len(line)} bytes)")
        os.fsync(self._fd)

    def add(self, key, result):
        record = {"key": key, "error": result["error"], "rows": result["rows"],
                  "cpu_seconds": round(result.get("seconds", 0.0), 6)}
        # The worker's build fingerprint (worker.py); an internal error's traceback; campaign fitting: parameter
        # units, the fit file's text (campaign.py).
        for extra in ("build", "traceback", "units", "fit_file"):
            if extra in result:
                record[extra] = result[extra]
        if self._fd is not None:
            self._append(record)
        self.results[key] = record

    def close(self):
        if self._fd is not None:
            os.close(self._fd)
            self._fd = None


def _text(value):
    if value is None:
        return ""
    if isinstance(value, float):
        return repr(value)  # shortest text that reads back to the same double
    text = str(value)
    if any(ch in text for ch in ',"\n\r'):
        text = '"' + text.replace('"', '""') + '"'
    return text


def write_csv(path, header, rows):
    """The results CSV, atomically (or to standard output for ``-``)."""
    body = "".join(",".join(_text(v) for v in row) + "\n" for row in [header] + rows)
    write_text_atomic(path, body, ".csv")
