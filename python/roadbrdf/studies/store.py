"""The results store and the results CSV.

The store is an append-only JSON-lines file: a header line, then one line per finished task (its key, its rows
or its error and, for an internal error, its traceback; the build fingerprint of the worker that computed it, the
one in the key). A line is written with one ``write`` on an ``O_APPEND`` descriptor and synced before the next
task's result is taken, so a killed study leaves complete lines plus at most one torn last line; that line is
reported and removed when the store is opened again (its task runs again). Lines of tasks that no longer belong to
the study (an edited study file) stay in the store.

The store is locked (``flock``) while a study uses it, by the study process alone: a process forked from it (a
local worker) closes its copy of the locked descriptor at once (``os.register_at_fork``), so that the lock ends
with the study however it ends, even by ``kill -9``. A lock held by processes left over from a study that no
longer runs (a stale lock) is recognised: the message names them.

The CSV is written once the study is complete, atomically (temporary file in the same folder, fsync, rename,
fsync of the folder), or to standard output for ``-``.
"""

from __future__ import annotations

import errno
import fcntl
import json
import os
import stat
import sys
import weakref

from ..core import write_text_atomic
from .spec import LIGHTING_OUTPUTS, InputError, check_json_depth

_HEADER = {"format": "roadbrdf-study-store", "version": 1}

# Descriptors of the stores this process holds locked: a forked child closes them (it must not keep the lock).
_LOCKED = weakref.WeakSet()


def _close_locked_in_child():
    for store in list(_LOCKED):
        if store._fd is not None:
            try:
                os.close(store._fd)
            except OSError:
                pass
            store._fd = None


os.register_at_fork(after_in_child=_close_locked_in_child)


def _lock_holders(path):
    """The processes that hold an open descriptor of ``path`` (from /proc; empty where it cannot be read)."""
    try:
        st = os.stat(path)
    except OSError:
        return []
    holders = []
    for entry in os.listdir("/proc"):
        if not entry.isdigit() or int(entry) == os.getpid():
            continue
        folder = f"/proc/{entry}/fd"
        try:
            fds = os.listdir(folder)
        except OSError:
            continue
        for fd in fds:
            try:
                other = os.stat(os.path.join(folder, fd))
            except OSError:
                continue
            if (other.st_dev, other.st_ino) == (st.st_dev, st.st_ino):
                holders.append(int(entry))
                break
    return holders


def _parent(pid):
    """The parent process id and the parent's command name (from /proc), or (None, "")."""
    try:
        with open(f"/proc/{pid}/stat", encoding="ascii", errors="replace") as f:
            parent = int(f.read().rsplit(")", 1)[1].split()[1])
        with open(f"/proc/{parent}/comm", encoding="utf-8", errors="replace") as f:
            return parent, f.read().strip()
    except (OSError, ValueError, IndexError):
        return None, ""


def _in_use_message(path):
    """Why the lock of ``path`` is taken: another running study, or processes left over from a study that was
    killed (adopted by init or a service manager: a stale lock, the processes named so that they can be ended)."""
    holders = _lock_holders(path)
    orphans = []
    for pid in holders:
        parent, name = _parent(pid)
        if parent in holders:
            continue  # a child of another holder: the holder decides
        if parent == 1 or name in ("systemd", "init"):
            orphans.append(pid)
    roots = [p for p in holders if _parent(p)[0] not in holders]
    if roots and len(orphans) == len(roots):
        listed = " ".join(str(p) for p in holders)
        return (f"{path}: the results store is locked by processes left over from a study that no longer runs "
                f"(a stale lock: processes {listed}); end them (kill {listed}) and run again")
    where = f" (process {', '.join(str(p) for p in holders)})" if holders else ""
    return f"{path}: the results store is in use by another running study{where}"


def _check_record(record, where):
    """A result line's fields, as the study reads them (a line edited by hand or by another program is refused
    with its line number rather than failing later)."""
    if not isinstance(record, dict):
        raise InputError(f"{where}:1: a results-store line must be a JSON object")
    key = record.get("key")
    if not isinstance(key, str) or not key:
        raise InputError(f"{where}:1: key: expected the task's key (a string)")
    if "error" not in record or not (record["error"] is None or isinstance(record["error"], str)):
        raise InputError(f"{where}:1: error: expected null or a message")
    rows = record.get("rows")
    if not isinstance(rows, list) or not all(isinstance(r, dict) for r in rows):
        raise InputError(f"{where}:1: rows: expected an array of objects")
    for name, kind in (("build", str), ("traceback", str), ("units", dict), ("fit_file", str)):
        if name in record and not isinstance(record[name], kind):
            raise InputError(f"{where}:1: {name}: expected {'a string' if kind is str else 'an object'}")
    if record["error"] is None and any(not isinstance(r.get("method", ""), str) for r in rows):
        raise InputError(f"{where}:1: rows: a row's method must be a string")
    for i, r in enumerate(rows):
        for name, _, kind in LIGHTING_OUTPUTS:
            value = r.get(name)
            if value is None:
                continue
            ok = (isinstance(value, str) if kind == "text" else
                  isinstance(value, (int, float)) and not isinstance(value, bool))
            if not ok:
                raise InputError(f"{where}:1: rows[{i}].{name}: expected {'text' if kind == 'text' else 'a number'} "
                                 f"or null, got {json.dumps(value)[:40]}")


class Store:
    """Finished task results by key, backed by a file (or only in memory when ``path`` is None)."""

    def __init__(self, path):
        self.path = None if path is None else os.path.abspath(path)
        self.results = {}
        self._fd = None
        if self.path is None:
            return
        try:
            fd = os.open(self.path, os.O_RDWR | os.O_CREAT | os.O_APPEND | os.O_CLOEXEC, 0o644)
        except OSError as e:
            raise InputError(f"{self.path}: cannot open the results store: {e.strerror}") from None
        if not stat.S_ISREG(os.fstat(fd).st_mode):
            os.close(fd)
            raise InputError(f"{self.path}: the results store must be a regular file")
        try:
            fcntl.flock(fd, fcntl.LOCK_EX | fcntl.LOCK_NB)
        except BlockingIOError:
            os.close(fd)
            raise InputError(_in_use_message(self.path)) from None
        self._fd = fd
        _LOCKED.add(self)
        try:
            self._load()
        except BaseException:
            self.close()
            raise

    def _load(self):
        with open(self._fd, "rb", closefd=False) as f:
            f.seek(0)
            data = f.read()
        # Nothing is removed from a file that is not a store (its first line must be the header, or a torn start
        # of it).
        first = data.split(b"\n", 1)[0]
        header_text = json.dumps(_HEADER, separators=(",", ":")).encode()
        if b"\n" not in data and not header_text.startswith(data):
            raise InputError(f"{self.path}:1:1: not a roadbrdf study results store")
        if b"\n" in data:
            try:
                is_header = json.loads(first) == _HEADER
            except (ValueError, RecursionError):
                is_header = False
            if not is_header:
                raise InputError(f"{self.path}:1:1: not a roadbrdf study results store")
        end = data.rfind(b"\n") + 1
        if end < len(data):
            print(f"roadbrdf: warning: {self.path}: removed a torn last line of {len(data) - end} bytes (a study "
                  "was killed while writing it); its task runs again", file=sys.stderr)
            try:
                os.ftruncate(self._fd, end)
                os.fsync(self._fd)
            except OSError as e:
                raise InputError(f"{self.path}: cannot remove the torn last line: {e.strerror}") from None
            data = data[:end]
        if not data:
            self._append(_HEADER)
            return
        for number, line in enumerate(data.splitlines(), start=1):
            where = f"{self.path}:{number}"
            try:
                text = line.decode("utf-8")
                check_json_depth(text, where)
                record = json.loads(text)
            except UnicodeDecodeError as e:
                raise InputError(f"{where}:{e.start + 1}: not a results-store line: not UTF-8 text") from None
            except json.JSONDecodeError as e:
                raise InputError(f"{where}:{e.colno}: not a results-store line: {e.msg}") from None
            except RecursionError:
                raise InputError(f"{where}:1: not a results-store line: JSON nested too deeply") from None
            if number == 1:
                if record != _HEADER:
                    raise InputError(f"{self.path}:1:1: not a roadbrdf study results store")
                continue
            _check_record(record, where)
            # A key appears once unless a failed task was retried; the later line wins (it is the newer result).
            self.results[record["key"]] = record

    def _append(self, record):
        line = (json.dumps(record, separators=(",", ":"), allow_nan=True) + "\n").encode()
        try:
            written = os.write(self._fd, line)
            if written != len(line):
                raise OSError(errno.ENOSPC, f"short write ({written} of {len(line)} bytes)")
            os.fsync(self._fd)
        except OSError as e:
            raise InputError(f"{self.path}: cannot write the results store: {e.strerror or e}; it keeps every "
                             "result written before") from None

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


def check_output(path, role):
    """Refuse, before any work, an output that cannot be written: its folder missing or not writable, or a
    folder in its place (``role`` names the argument)."""
    path = os.fspath(path)
    if path == "-":
        return
    target = os.path.realpath(path)
    folder = os.path.dirname(target) or "."
    if os.path.isdir(target):
        raise InputError(f"{role}: {path} is a folder")
    if not os.path.isdir(folder):
        raise InputError(f"{role}: {path}: the folder {folder} does not exist")
    if not os.access(folder, os.W_OK | os.X_OK):
        raise InputError(f"{role}: {path}: the folder {folder} is not writable")


def write_csv(path, header, rows):
    """The results CSV, atomically (or to standard output for ``-``)."""
    body = "".join(",".join(_text(v) for v in row) + "\n" for row in [header] + rows)
    try:
        write_text_atomic(path, body, ".csv")
    except OSError as e:
        raise InputError(f"{path}: cannot write the results table: {e.strerror or e} (the results store keeps "
                         "every result: run again to write it)") from None
